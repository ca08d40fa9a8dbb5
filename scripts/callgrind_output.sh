#!/usr/bin/env bash
# The output side of `mechdiff run`, measured two ways.
#
#   cargo build --release --bin mechdiff
#   scripts/callgrind_output.sh [BINARY] [N]               # instructions (callgrind)
#   scripts/callgrind_output.sh --throughput [BINARY] [N]  # CPU time, MB/s, peak RSS
#
# BINARY defaults to target/release/mechdiff. Every run is on one worker (`--threads 1`).
#
# Instructions per drive position (load-independent; N defaults to 200000 positions). Each
# count is taken at N and at N/2 positions (both above the 65 536 positions from which the
# table is streamed, so both runs take the same path) and the start-up removed: (count(N) −
# count(N/2)) / (N − N/2). `callgrind_annotate --inclusive=yes` gives the split.
#  1. `mechdiff run --csv` of the slider-crank (scenes/slider_crank.toml swept finely), the
#     table to /dev/null (where the run formats no table) and to a file: end to end,
#     `RowFormat::row` (the numbers turned into text), of it Żmij's shortest digits
#     (`write_to_zmij_buffer`), `Output::batch` (the text made and written: `RowFormat::row`
#     and the writing, where `write_texts` is inlined), `write_texts` (the text written) and
#     `Sweep::walk` (the rows solved). With GENERATED=<instructions per position of the scene's generated code>
#     (scripts/callgrind_rows.sh, `code:`), end to end is also given as a multiple of it.
#  2. The Whitworth forces (scenes/whitworth_forces.toml swept finely, dynamics columns), its
#     table written to a file against the same run with the table discarded (stdout
#     /dev/null: the rows computed and checked, nothing formatted or written): the CLI's
#     cost over the run in process, as a ratio.
#
# --throughput (N defaults to 10000000 positions): CPU time (user + sys, /usr/bin/time) of
#  1. the slider-crank's CSV at N positions, the table to /dev/null: MB of CSV per CPU second
#     and the CSV's md5 (the bytes, to compare before and after a change);
#  2. the Whitworth forces at N/10 positions, table to a file and to /dev/null: the CPU
#     ratio; peak RSS of each run (constant memory: the same at N/100 and N/10).
set -euo pipefail
mode=instructions
if [ "${1:-}" = --throughput ]; then
    mode=throughput
    shift
fi
bin=${1:-target/release/mechdiff}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# A scene swept from 0 to 360 degrees (less one step) at n positions: `$1` with its
# `[sweep]` replaced, into `$3`.
sweep() {
    local scene=$1 count=$2 out=$3 step
    step=$(python3 -c "print(repr(360 / $count))")
    python3 - "$scene" "$count" "$step" "$out" <<'EOF'
import re, sys
scene, count, step, out = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
text = open(scene).read()
body = f"from = 0\nto = {360 - 360 / count!r}\nstep = {step}\n"
text = re.sub(r"(?ms)^\[sweep\]\n.*?(?=^\[)", "[sweep]\n" + body + "\n", text)
open(out, "w").write(text)
EOF
}

# The slider-crank as it has always been swept here: 0..360 at 360/n (n + 1 positions).
slider_crank() {
    local count=$1 step
    step=$(python3 -c "print(repr(360 / $count))")
    sed "s/^step = 5$/step = $step/" scenes/slider_crank.toml > "$dir/sc_$count.toml"
}

if [ "$mode" = throughput ]; then
    n=${2:-10000000}
    slider_crank "$n"
    timed() {
        /usr/bin/time -f "%U %S %M" -o "$dir/time" "$@"
        read -r user sys rss < "$dir/time"
        cpu=$(python3 -c "print($user + $sys)")
    }
    timed "$bin" run "$dir/sc_$n.toml" --csv "$dir/out.csv" --threads 1 > /dev/null
    bytes=$(stat -c %s "$dir/out.csv")
    echo "slider-crank CSV, $n positions, table to /dev/null:"
    echo "  $bytes bytes in $cpu s of CPU ($user user, $sys sys):" \
        "$(python3 -c "print(f'{$bytes / 1e6 / $cpu:.0f}')") MB/s; peak RSS $((rss / 1024)) MB"
    echo "  md5 $(md5sum < "$dir/out.csv" | cut -d' ' -f1)"
    rm -f "$dir/out.csv"
    for count in $((n / 100)) $((n / 10)); do
        sweep scenes/whitworth_forces.toml "$count" "$dir/wf_$count.toml"
        timed "$bin" run "$dir/wf_$count.toml" --threads 1 > "$dir/table.txt"
        written=$cpu
        written_rss=$rss
        rm -f "$dir/table.txt"
        timed "$bin" run "$dir/wf_$count.toml" --threads 1 > /dev/null
        echo "Whitworth forces, $count positions: table to a file $written s," \
            "discarded $cpu s of CPU: $(python3 -c "print(f'{$written / $cpu:.3f}')")×;" \
            "peak RSS $((written_rss / 1024)) MB / $((rss / 1024)) MB"
    done
    exit 0
fi

n=${2:-200000}
# callgrind's output of one run: total instructions, and the inclusive counts.
count() {
    local out=$1 toml=$2 table=$3
    shift 3
    valgrind --tool=callgrind --callgrind-out-file="$out" "$bin" run "$toml" "$@" \
        --threads 1 > "$table" 2> "$out.log"
    callgrind_annotate --inclusive=yes "$out" > "$out.txt"
}

# The inclusive count of the first function whose name matches `$2` in annotation `$1`.
inclusive() {
    { grep -E "$2" "$1" || true; } | head -1 | awk '{gsub(",", "", $1); print $1 + 0}'
}

total() {
    grep -E "PROGRAM TOTALS" "$1" | awk '{gsub(",", "", $1); print $1}'
}

per() {
    if [ -z "$1" ] || [ -z "$2" ]; then echo "n/a"; return; fi
    python3 -c "print(f'{($1 - $2) / ($n - $n // 2):.1f}')"
}

for count in "$n" $((n / 2)); do
    slider_crank "$count"
done
for target in null file; do
    for count in "$n" $((n / 2)); do
        table=/dev/null
        [ "$target" = file ] && table="$dir/table.txt"
        count "$dir/cg.$target.$count" "$dir/sc_$count.toml" "$table" --csv "$dir/out.csv"
    done
    big="$dir/cg.$target.$n.txt"
    small="$dir/cg.$target.$((n / 2)).txt"
    end=$(per "$(total "$big")" "$(total "$small")")
    echo "slider-crank --csv, table to $target ($n and $((n / 2)) positions):"
    if [ -n "${GENERATED:-}" ]; then
        echo "  end to end        $end instructions/position" \
            "($(python3 -c "print(f'{$end / $GENERATED:.1f}')")× the generated code's $GENERATED)"
    else
        echo "  end to end        $end instructions/position"
    fi
    for what in "RowFormat::row" "write_to_zmij_buffer" "Output::batch" "write_texts" \
        "Sweep.*::walk"; do
        printf '  %-20s %s\n' "$what" \
            "$(per "$(inclusive "$big" "$what")" "$(inclusive "$small" "$what")")"
    done
done

for count in "$n" $((n / 2)); do
    sweep scenes/whitworth_forces.toml "$count" "$dir/wf_$count.toml"
    count "$dir/wf.file.$count" "$dir/wf_$count.toml" "$dir/table.txt"
    count "$dir/wf.null.$count" "$dir/wf_$count.toml" /dev/null
done
file=$(per "$(total "$dir/wf.file.$n.txt")" "$(total "$dir/wf.file.$((n / 2)).txt")")
null=$(per "$(total "$dir/wf.null.$n.txt")" "$(total "$dir/wf.null.$((n / 2)).txt")")
echo "Whitworth forces, table to a file against discarded ($n and $((n / 2)) positions):"
echo "  table to a file   $file instructions/position"
echo "  table discarded   $null"
echo "  ratio             $(python3 -c "print(f'{$file / $null:.3f}')")"
for what in "RowFormat::row" "write_texts"; do
    printf '  %-17s %s\n' "$what" "$(per "$(inclusive "$dir/wf.file.$n.txt" "$what")" \
        "$(inclusive "$dir/wf.file.$((n / 2)).txt" "$what")")"
done
