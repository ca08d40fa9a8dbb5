#!/usr/bin/env bash
# Regenerates the README's pictures of the HTML report (docs/pictures/) with headless Chromium:
#   report_400.png    scenes/four_bar.toml's report at a phone's width (400 × 860 px)
#   report_1920.png   the same report at a desktop's width (1920 × 1080 px)
# both at φ = 120° with the velocity and acceleration arrows shown.
#
# Needs Chromium (`apt-get install chromium`).
set -euo pipefail
cd "$(dirname "$0")/.."
browser=$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)
if [ -z "$browser" ]; then
    echo "no Chromium found: apt-get install chromium" >&2
    exit 2
fi
out=$(mktemp -d /tmp/mechdiff-report-screenshots.XXXXXX)
trap 'rm -rf "$out"' EXIT
cargo run --quiet --bin mechdiff -- run scenes/four_bar.toml --report "$out/report.html" > /dev/null
mkdir -p docs/pictures
for size in 400,860 1920,1080; do
    "$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync \
        --user-data-dir="$out/profile" --hide-scrollbars --force-device-scale-factor=1 \
        --window-size="$size" --screenshot="docs/pictures/report_${size%,*}.png" \
        "file://$out/report.html#phi=120&vectors=1" > /dev/null 2>&1
done
ls -l docs/pictures/report_*.png
