"""A tolerance Monte Carlo of Norton's four-bar over a 2-worker LocalCluster: 10⁶ variants,
the scaling from 1 to 2 workers, and the peak memory of each worker (BENCHMARKS.md).

    python python/examples/norton_monte_carlo.py [SAMPLES [WORKERS ...]]

(default: 10⁶ variants on 1 and then 2 workers; e.g. `100000 1 2`, `1000000 2`).

Each of the four lengths a, b, c, d is drawn uniformly within ±0.5 mm of its value; every
variant is run over the scene's sweep (φ = 0° to 100° by 10°) and ψ, ψ′ and ψ̇ are
summarised per position. The workers return only their chunks' summaries, so their memory
does not grow with the number of variants: compare the peaks at 10⁵ and 10⁶.
"""

import os
import sys
import time
from pathlib import Path

import numpy as np

import mechdiff
import mechdiff.study as study

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "norton_four_bar.toml"
TOLERANCES = {"a": 5e-4, "b": 5e-4, "c": 5e-4, "d": 5e-4}


def main() -> None:
    samples = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    worker_counts = [int(w) for w in sys.argv[2:]] or [1, 2]
    scene = mechdiff.load(SCENE)
    print(f"{'variants':>9} {'workers':>7} {'chunks':>6} {'wall s':>8} {'worker CPU s':>13} "
          f"{'CPU µs/variant':>14} {'peak MB per worker':>19}  load")
    last = None
    seconds = {}
    for workers in worker_counts:
        start = time.perf_counter()
        mc = study.monte_carlo(scene, TOLERANCES, samples, workers=workers, chunk=8192)
        seconds[workers] = time.perf_counter() - start
        cpu = sum(mc.cpu_seconds.values())
        peaks = " ".join(f"{p / 2**20:.0f}" for p in sorted(mc.peak_rss.values()))
        print(f"{samples:9d} {workers:7d} {mc.chunks:6d} {seconds[workers]:8.1f} {cpu:13.1f} "
              f"{cpu / samples * 1e6:14.1f} {peaks:>19}  {os.getloadavg()[0]:.1f}", flush=True)
        if last is not None:
            # The same study on another number of workers: the same numbers, bit for bit.
            assert all(np.array_equal(mc.mean[c], last.mean[c]) for c in mc.columns)
        last = mc
    if 1 in seconds and 2 in seconds:
        print(f"scaling 1 → 2 workers (wall): {seconds[1] / seconds[2]:.2f}×")
    print("\nψ at φ = 50°: nominal {:.9f}°, mean {:.9f}°, σ {:.3e}°, max |Δ| {:.3e}° ({} failed)"
          .format(last.nominal["psi"][5], last.mean["psi"][5], last.std["psi"][5],
                  last.max_deviation["psi"][5], last.failed))


if __name__ == "__main__":
    main()
