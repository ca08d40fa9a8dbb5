"""A tolerance Monte Carlo of Norton's four-bar over a 2-worker LocalCluster: 10⁶ variants,
the scaling from 1 to 2 workers, and the peak memory of each worker (BENCHMARKS.md).

    python python/examples/norton_monte_carlo.py [SAMPLES ...]

Each of the four lengths a, b, c, d is drawn uniformly within ±0.5 mm of its value; every
variant is run over the scene's sweep (φ = 0° to 100° by 10°) and ψ, ψ′ and ψ̇ are
summarised per position. The workers return only their chunks' summaries, so their memory
does not grow with the number of variants: compare the peaks at 10⁵ and 10⁶.
"""

import sys
import time
from pathlib import Path

import numpy as np

import mechdiff
import mechdiff.study as study

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "norton_four_bar.toml"
TOLERANCES = {"a": 5e-4, "b": 5e-4, "c": 5e-4, "d": 5e-4}


def main() -> None:
    runs = [int(s) for s in sys.argv[1:]] or [100_000, 1_000_000]
    scene = mechdiff.load(SCENE)
    print(f"{'variants':>9} {'workers':>7} {'chunks':>6} {'seconds':>8} {'µs/variant':>10} "
          f"{'peak MB per worker':>20}")
    last = None
    for samples in runs:
        seconds = {}
        for workers in (1, 2):
            start = time.perf_counter()
            mc = study.monte_carlo(scene, TOLERANCES, samples, workers=workers, chunk=8192)
            seconds[workers] = time.perf_counter() - start
            peaks = " ".join(f"{p / 2**20:.0f}" for p in sorted(mc.peak_rss.values()))
            print(f"{samples:9d} {workers:7d} {mc.chunks:6d} {seconds[workers]:8.1f} "
                  f"{seconds[workers] / samples * 1e6:10.1f} {peaks:>20}")
            if last is not None and last.samples == samples:
                # The same study on 1 and 2 workers: the same numbers, bit for bit.
                assert all(np.array_equal(mc.mean[c], last.mean[c]) for c in mc.columns)
            last = mc
        print(f"{'':9} scaling 1 → 2 workers: {seconds[1] / seconds[2]:.2f}×")
    print("\nψ at φ = 50°: nominal {:.9f}°, mean {:.9f}°, σ {:.3e}°, max |Δ| {:.3e}° ({} failed)"
          .format(last.nominal["psi"][5], last.mean["psi"][5], last.std["psi"][5],
                  last.max_deviation["psi"][5], last.failed))


if __name__ == "__main__":
    main()
