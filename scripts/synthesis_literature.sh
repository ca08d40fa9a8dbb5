#!/usr/bin/env bash
# Runs each literature synthesis scene (scenes/synthesis_literature_*.toml) through the
# release `mechdiff synthesize` over seeds 0–9, each run limited to 10 s, and prints the
# table of issue 26: problem, published best, best and median objective, successes of 10,
# median evaluations and median CPU time per run (user + system, from bash's `time`).
#
# A run succeeds when its objective reaches the scene's `objective` (the published best, or
# 1e-20 for the straight line, whose exact solutions exist), core's geometry solver moves
# the answer through every target ("checked: …"), the scene's own solver draws it ("the
# scene with these parameters … places …"), and its ground link |O4 − O2| is within the
# paper's bound (50 for the five points and the closed curve, 60 for the straight line).
#
#   scripts/synthesis_literature.sh [SECONDS]      (default 10 s per run)
set -euo pipefail
cd "$(dirname "$0")/.."
limit=${1:-10}
cargo build --quiet --release --bin mechdiff
bin=target/release/mechdiff
out=$(mktemp -d /tmp/mechdiff-synthesis-literature.XXXXXX)
trap 'rm -r "$out"' EXIT

# scene, problem as the table names it, published best as printed, the paper's ground bound
problems=(
    "five_points|5 timed points (Kunjur & Krishnamurty 1997, as in Cabrera et al. 2002)|1.2840e-6 (MUMSA)|50"
    "straight_line|6-point straight line, untimed (Cabrera et al. 2002)|4.0672e-12 (Lin & Hsiao; success ≤ 1e-20)|60"
    "closed_curve|18-point closed curve, timed (Kunjur & Krishnamurty 1997)|1.6078e-2 (HCDJ)|50"
    "log10|y = log10 x, 1 ≤ x ≤ 10, 21 pairs (Freudenstein 1955)|6.1317e-3 rad² (3-point design)|"
)

# The median of the numbers on standard input (the upper one of an even count).
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int(NR / 2) + 1] }'; }

echo "Seeds 0–9, ${limit} s limit per run, release build, $(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg)."
echo
echo "| Problem (source) | Published best | mechdiff best | Median | Successes / 10 | Median evaluations | Median CPU time (s) |"
echo "|---|---|---|---|---|---|---|"
for entry in "${problems[@]}"; do
    IFS='|' read -r name problem published ground_bound <<< "$entry"
    scene="scenes/synthesis_literature_${name}.toml"
    level=$(awk -F'[= #]+' '/^objective =/ { print $2; exit }' "$scene")
    : > "$out/$name.rows"
    for seed in 0 1 2 3 4 5 6 7 8 9; do
        log="$out/$name.$seed"
        TIMEFORMAT='%U %S'
        { time "$bin" synthesize "$scene" --seed "$seed" --time-limit "$limit" > "$log" 2>&1; } 2> "$log.time"
        cpu=$(awk '{ print $1 + $2 }' "$log.time")
        objective=$(awk '/^objective: / { print $2 }' "$log")
        evaluations=$(awk '/^search: / { print $2 }' "$log")
        ground=$(awk '$1 ~ /^o[24][xy]$/ && $2 == "=" { v[$1] = $3 }
            END { printf "%.17g", sqrt((v["o4x"] - v["o2x"])^2 + (v["o4y"] - v["o2y"])^2) }' "$log")
        ok=$(awk -v f="$objective" -v l="$level" -v g="$ground" -v b="$ground_bound" \
            'BEGIN { print (f <= l && (b == "" || g <= b)) ? 1 : 0 }')
        grep -q '^checked: core' "$log" || ok=0
        grep -q '^the scene with these parameters, moved through the targets' "$log" || ok=0
        echo "$objective $evaluations $cpu $ok" >> "$out/$name.rows"
    done
    best=$(awk '{ print $1 }' "$out/$name.rows" | sort -g | head -1)
    med=$(awk '{ print $1 }' "$out/$name.rows" | median)
    successes=$(awk '{ s += $4 } END { print s }' "$out/$name.rows")
    evals=$(awk '{ print $2 }' "$out/$name.rows" | median)
    cpu=$(awk '{ print $3 }' "$out/$name.rows" | median)
    printf '| %s | %s | %.4e | %.4e | %s | %s | %.2f |\n' \
        "$problem" "$published" "$best" "$med" "$successes" "$evals" "$cpu"
done
