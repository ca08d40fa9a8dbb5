#!/usr/bin/env bash
# Regenerates the pictures of the README (docs/pictures/) from the scenes:
#   whitworth_acceleration.svg/png   scenes/whitworth.toml, [plot] panels psi_ddot and x_C_ddot
#   rack_slotted_link_paths.svg/png  scenes/rack_slotted_link_travel.toml at the reference
#                                    instant ρ4 = 0.41916... m, paths of C, D and G1 traced
#   four_bar_coupler_curve.svg/png   scenes/four_bar.toml, the path of the coupler point P
#                                    to scale with φ marked along it and the dead positions
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d /tmp/mechdiff-readme-pictures.XXXXXX)
cargo run --quiet --release --bin mechdiff -- run scenes/whitworth.toml --plot "$out/whitworth" > /dev/null
cargo run --quiet --release --bin mechdiff -- run scenes/rack_slotted_link_travel.toml --plot "$out/rack" > /dev/null
cargo run --quiet --release --bin mechdiff -- run scenes/four_bar.toml --plot "$out/four_bar" > /dev/null
mkdir -p docs/pictures
for ext in svg png; do
    cp "$out/whitworth/diagram.$ext" "docs/pictures/whitworth_acceleration.$ext"
    cp "$out/rack/mechanism_at_0.41916244923215_m.$ext" "docs/pictures/rack_slotted_link_paths.$ext"
    cp "$out/four_bar/path_P.$ext" "docs/pictures/four_bar_coupler_curve.$ext"
done
rm -r "$out"
ls -l docs/pictures
