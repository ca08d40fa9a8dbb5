"""Per-position cost of a sweep through Python against the Rust library's run, same machine,
same scene and positions, in one run (BENCHMARKS.md).

    python python/examples/sweep_cost.py [COUNT]

Builds and runs the Rust baseline (``cargo run --release -p mechdiff-python --example
sweep_cost``), then times ``Scene.run(positions=...)`` (the best of three), which includes
handing the columns to NumPy. Both in CPU time of the process (the machine may be shared).
"""

import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import mechdiff

ROOT = Path(__file__).resolve().parents[2]
CASES = [("scenes/norton_four_bar.toml", -100.0, 100.0), ("scenes/whitworth.toml", 0.0, 360.0)]


def rust_seconds(scene: str, lo: float, hi: float, count: int) -> float:
    command = ["cargo", "run", "-q", "--release", "-p", "mechdiff-python", "--example",
               "sweep_cost", "--", scene, str(lo), str(hi), str(count)]
    return float(subprocess.run(command, cwd=ROOT, check=True, capture_output=True, text=True).stdout)


def python_seconds(scene: str, lo: float, hi: float, count: int) -> float:
    loaded = mechdiff.load(ROOT / scene)
    positions = lo + (hi - lo) * np.arange(count) / (count - 1)
    best = float("inf")
    for _ in range(3):
        start = time.process_time()  # CPU time, as the Rust side measures it
        run = loaded.run(positions=positions)
        best = min(best, time.process_time() - start)
        assert run.positions == count
        del run
    return best


def main() -> None:
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    print(f"{'scene':32} {'Rust µs/pos':>12} {'Python µs/pos':>14} {'ratio':>6}")
    for scene, lo, hi in CASES:
        rust = rust_seconds(scene, lo, hi, count)
        python = python_seconds(scene, lo, hi, count)
        print(f"{scene:32} {rust / count * 1e6:12.3f} {python / count * 1e6:14.3f} {python / rust:6.3f}")


if __name__ == "__main__":
    main()
