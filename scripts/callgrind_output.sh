#!/usr/bin/env bash
# Instructions per drive position of `mechdiff run --csv` of the slider-crank
# (scenes/slider_crank.toml swept finely), end to end and split into the rows (the sweep's
# walk) and their text (formatting and writing), counted by callgrind (load-independent).
#
#   cargo build --release --bin mechdiff
#   scripts/callgrind_output.sh [BINARY] [N]
#
# BINARY defaults to target/release/mechdiff, N to 200000 positions. Each count is taken at
# N and at N/2 positions (both above the 65 536 positions from which the table is streamed,
# so both runs take the same path) and the start-up removed: (count(N) − count(N/2)) /
# (N − N/2). Two runs per size: the table to /dev/null (where the run formats no table) and
# to a file. `callgrind_annotate --inclusive=yes` gives the split: `RowFormat::row` (the
# numbers turned into text) and `write_texts` (the text written) against `Sweep::walk` (the
# rows solved).
set -euo pipefail
bin=${1:-target/release/mechdiff}
n=${2:-200000}
scene=scenes/slider_crank.toml
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# The sweep 0..360 at a step of 360/n degrees: n + 1 positions.
for count in "$n" $((n / 2)); do
    step=$(python3 -c "print(repr(360 / $count))")
    sed "s/^step = 5$/step = $step/" "$scene" > "$dir/sc_$count.toml"
done

# callgrind's output of one run: total instructions, and the inclusive counts of the text
# and the rows.
count() {
    local out=$1 toml=$2 table=$3
    valgrind --tool=callgrind --callgrind-out-file="$out" "$bin" run "$toml" \
        --csv "$dir/out.csv" --threads 1 > "$table" 2> "$out.log"
    callgrind_annotate --inclusive=yes "$out" > "$out.txt"
}

# The inclusive count of the first function whose name matches `$2` in annotation `$1`.
inclusive() {
    { grep -E "$2" "$1" || true; } | head -1 | awk '{gsub(",", "", $1); print $1 + 0}'
}

total() {
    grep -E "PROGRAM TOTALS" "$1" | awk '{gsub(",", "", $1); print $1}'
}

for target in null file; do
    for count in "$n" $((n / 2)); do
        table=/dev/null
        [ "$target" = file ] && table="$dir/table.txt"
        count "$dir/cg.$target.$count" "$dir/sc_$count.toml" "$table"
    done
    big="$dir/cg.$target.$n.txt"
    small="$dir/cg.$target.$((n / 2)).txt"
    per() {
        if [ -z "$1" ] || [ -z "$2" ]; then echo "n/a"; return; fi
        python3 -c "print(f'{($1 - $2) / ($n - $n // 2):.1f}')"
    }
    echo "table to $target ($n and $((n / 2)) positions):"
    echo "  end to end        $(per "$(total "$big")" "$(total "$small")") instructions/position"
    for what in "RowFormat::row" "write_texts" "Sweep.*::walk"; do
        printf '  %-17s %s\n' "$what" \
            "$(per "$(inclusive "$big" "$what")" "$(inclusive "$small" "$what")")"
    done
done
