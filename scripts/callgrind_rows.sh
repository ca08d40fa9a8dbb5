#!/usr/bin/env bash
# Instructions per drive position (callgrind: independent of the machine's load) of every way
# mechdiff computes a row, for the four shipped scenes of issue 28 and for Dual2 on the
# Whitworth's ψ. Builds `examples/instructions_per_position.rs` once in release, then for each
# loop counts the instructions with R repetitions and with none; per position is
#   (count at R − count at 0) / (R × positions per repetition),
# the set-up (reading the scene, tracing, compiling) cancelling out.
#
#   scripts/callgrind_rows.sh                 # every loop below
#   scripts/callgrind_rows.sh row:whitworth   # only the loops named
#
# Loops (see the example's documentation):
#   code:<scene>         the scene's generated module (`mechdiff codegen`, `mechdiff_scene!`)
#   row:<scene>          `mechdiff run`'s row (`Sweeper::row`) on the default evaluator, auto
#   long:<scene>         the same over the scene's sweep refined to ≥ 20 000 positions, where
#                        auto compiles the program (the Done-when row of issue 28)
#   solver:<scene>       the same row on `--evaluator solver`
#   jit:<scene>          the same row on `--evaluator jit`
#   interpreter:<scene>  the same row on `--evaluator interpreter`
#   geometry, four_bar, rack, slider_crank   the solver's tracker alone: move_to + one output
#                        with ′ and ″ (Whitworth ψ, four-bar ψ, rack θ3, slider-crank s)
#   hand, generated, jit, program            Whitworth ψ, ψ′, ψ″: hand-derived, generated,
#                        the run-time evaluator compiled and interpreted
#   psi, dual2_64        Whitworth ψ by `Dual2.jets` and by num-dual's `Dual2_64` alone
# with <scene> one of whitworth, four_bar, rack (rack_slotted_link_travel.toml), slider_crank.
# Prints one line per loop: name, instructions per position, and the two counts; then, for
# every scene whose `code:` loop ran, each of its other loops' ratio to the generated code, the
# JIT's set-up (the `jit:` count at no repetition minus the `solver:`'s) and the measured
# break-even (set-up ÷ (solver row − JIT row): the positions from which compiling pays; compare
# the cost model's in src/evaluator/cost.rs). Each `<what>:<scene>` loop says on stderr which
# evaluator ran it. Issue 28's Done-when line for the default row reads the `long:` ratios (at
# ≥ 20 000 positions the harness's one clone of the sweeper per repetition costs < 2
# instructions per position; at a scene's own sweep of 73–721 positions it costs ~30–460).
#
#   scripts/callgrind_rows.sh code:whitworth long:whitworth solver:whitworth jit:whitworth
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_INCREMENTAL=0
cargo build --quiet --release --example instructions_per_position
bin=target/release/examples/instructions_per_position

loops=("$@")
if [ ${#loops[@]} -eq 0 ]; then
    for scene in whitworth four_bar rack slider_crank; do
        for what in code row long solver jit interpreter; do
            loops+=("$what:$scene")
        done
    done
    loops+=(geometry four_bar rack slider_crank hand generated jit program psi dual2_64)
fi

# The instructions callgrind counts for one run of `$bin $1 $2`.
count() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$1" "$2" 2>&1 \
        | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}

printf '%-22s %12s %16s %16s\n' loop per_position at_R at_0
declare -A per_position at_zero
for loop in "${loops[@]}"; do
    # Positions per repetition: the scene's sweep, or the 720 of the fixed loops.
    n=$("$bin" "$loop" 0 | sed -n 's/^positions per repetition: //p')
    n=${n:-720}
    # About 7 200 positions in all, as the fixed loops (10 × 720).
    reps=$(( (7200 + n - 1) / n ))
    zero=$(count "$loop" 0)
    full=$(count "$loop" "$reps")
    per=$(awk -v a="$full" -v b="$zero" -v r="$reps" -v n="$n" \
        'BEGIN { printf "%.1f", (a - b) / (r * n) }')
    printf '%-22s %12s %16s %16s\n' "$loop" "$per" "$full" "$zero"
    per_position[$loop]=$per
    at_zero[$loop]=$zero
done

for scene in whitworth four_bar rack slider_crank; do
    code=${per_position[code:$scene]:-}
    [ -n "$code" ] || continue
    for what in row long solver jit interpreter; do
        per=${per_position[$what:$scene]:-}
        [ -n "$per" ] || continue
        awk -v w="$what:$scene" -v p="$per" -v c="$code" \
            'BEGIN { printf "%-22s %8.1f x code\n", w, p / c }'
    done
    if [ -n "${at_zero[jit:$scene]:-}" ] && [ -n "${at_zero[solver:$scene]:-}" ]; then
        awk -v s="$scene" -v j="${at_zero[jit:$scene]}" -v o="${at_zero[solver:$scene]}" \
            'BEGIN { printf "%-22s %8.2f M instructions of JIT set-up\n", s, (j - o) / 1e6 }'
        # The measured break-even: set-up ÷ (solver row − JIT row).
        if [ -n "${per_position[jit:$scene]:-}" ] && [ -n "${per_position[solver:$scene]:-}" ]; then
            awk -v s="$scene" -v j="${at_zero[jit:$scene]}" -v o="${at_zero[solver:$scene]}" \
                -v pj="${per_position[jit:$scene]}" -v ps="${per_position[solver:$scene]}" \
                'BEGIN { printf "%-22s %8.0f positions: measured break-even of the JIT\n", s, (j - o) / (ps - pj) }'
        fi
    fi
done
