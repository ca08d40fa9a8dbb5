#!/usr/bin/env bash
# Opens a run's HTML report in headless Chromium, scrubs it to three drive positions, takes a
# screenshot at each, and checks that the joint drawn by the page is where the solver puts it.
#
#   scripts/check_report_in_chromium.sh [SCENE] [POINT] [PHI ...]
#   (defaults: scenes/four_bar.toml P 30 90 200)
#
# POINT must be a `[[output]] point` of the scene (its solver position is read from the run's
# JSON output, columns x_POINT and y_POINT), and each PHI a drive position of the sweep (in the
# scene's unit). The page is opened at `report.html#phi=PHI&mark=POINT`, which scrubs the
# slider there and paints that joint red; the centre of the red pixels in the screenshot must
# lie within 1.5 px of the solver's position mapped through the drawing's frame.
#
# Needs: cargo, python3, and Chromium (`apt-get install chromium` on a Debian dev machine; the
# script is for developers, CI does not run it). Screenshots and the report stay in the printed
# folder for a look.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/four_bar.toml}
point=${2:-P}
if [ $# -ge 3 ]; then shift 2; positions=("$@"); else positions=(30 90 200); fi
browser=$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)
if [ -z "$browser" ]; then
    echo "no Chromium found: apt-get install chromium" >&2
    exit 2
fi
out=$(mktemp -d /tmp/mechdiff-report-check.XXXXXX)
cargo run --quiet --bin mechdiff -- run "$scene" --report "$out/report.html" --json "$out/run.json" > /dev/null
shots=()
for phi in "${positions[@]}"; do
    shot="$out/phi_$phi.png"
    "$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars \
        --force-device-scale-factor=1 --window-size=820,620 \
        --screenshot="$shot" "file://$out/report.html#phi=$phi&mark=$point" > /dev/null 2>&1
    shots+=("$phi=$shot")
done
python3 scripts/check_report_screenshot.py "$out/report.html" "$out/run.json" "$point" "${shots[@]}"
echo "screenshots and report in $out"
