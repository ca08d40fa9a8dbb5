"""Studies of many variants of a scene, spread over a Dask cluster.

A tolerance Monte Carlo draws every toleranced parameter uniformly from its ± box, runs each
variant over the scene's sweep, and summarises the outputs per drive position: mean, standard
deviation, smallest and largest value, largest deviation from the nominal run. The variants
are run in chunks (each a task of ≥ 100 ms); a worker runs its chunk in one call into Rust
(without the GIL) and returns only the chunk's summary, so the memory a worker needs is one
chunk's, whatever the number of variants, and what comes back is a few arrays per chunk.

The samples are a function of the seed and the variant's index alone (drawn in blocks of
``BLOCK`` variants, each block from its own ``SeedSequence([seed, block])``), so a study
gives the same samples on one machine or a cluster; the chunks' summaries are merged in
chunk order, so a study on a cluster equals the same study run serially bit for bit.

>>> import mechdiff, mechdiff.study
>>> scene = mechdiff.load("scenes/norton_four_bar.toml")
>>> mc = mechdiff.study.monte_carlo(scene, {"a": 5e-4, "b": 5e-4}, samples=2048,
...                                 client="serial")
>>> mc.mean["psi"].shape, mc.failed
((11,), 0)

With ``client=None`` a ``LocalCluster`` of ``workers`` processes is started for the study
and closed after it (nothing to set up); pass a ``distributed.Client`` to use any cluster.
"""

from __future__ import annotations

import os
import resource
import socket
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import Scene, errors

__all__ = ["monte_carlo", "MonteCarlo", "draw", "BLOCK", "MAX_SAMPLES", "MAX_CHUNK"]

#: Variants drawn from one seed sequence; a chunk holds a whole number of blocks.
BLOCK = 1024

#: The most variants of one study.
MAX_SAMPLES = 100_000_000

#: The most variants of one chunk (one task's memory: variants × positions × columns).
MAX_CHUNK = 1_048_576

#: Failures kept with their reasons (all are counted).
KEPT_FAILURES = 100


def draw(seed: int, start: int, count: int, halfwidths: Sequence[float]) -> np.ndarray:
    """The uniform deviates in [-1, 1] of variants ``start .. start + count`` (``start`` a
    multiple of :data:`BLOCK`), one column per parameter: a function of the seed and the
    variants' indices only."""
    if start % BLOCK:
        raise errors.ArgumentError(f"start={start} is not a multiple of BLOCK={BLOCK}")
    width = len(halfwidths)
    out = np.empty((count, width))
    for offset in range(0, count, BLOCK):
        block = (start + offset) // BLOCK
        rng = np.random.default_rng(np.random.SeedSequence([seed, block]))
        n = min(BLOCK, count - offset)
        out[offset : offset + n] = rng.uniform(-1.0, 1.0, size=(BLOCK, width))[:n]
    return out


@dataclass
class _Summary:
    """One chunk's (or the merged study's) sums, in the columns' units."""

    count: int
    sum: np.ndarray  # Σ (y − y_nominal), [position, column]
    sum_squares: np.ndarray  # Σ (y − y_nominal)²
    low: np.ndarray
    high: np.ndarray
    failed: int = 0
    failures: List[Tuple[int, str, str, Dict[str, float]]] = field(default_factory=list)
    peak_rss: Dict[str, int] = field(default_factory=dict)  # worker → bytes
    cpu: Dict[str, float] = field(default_factory=dict)  # worker → CPU seconds so far

    def merge(self, other: "_Summary") -> None:
        """Adds ``other`` (the next chunk in order) into this summary."""
        self.count += other.count
        self.sum = self.sum + other.sum
        self.sum_squares = self.sum_squares + other.sum_squares
        self.low = np.fmin(self.low, other.low)
        self.high = np.fmax(self.high, other.high)
        self.failed += other.failed
        room = KEPT_FAILURES - len(self.failures)
        self.failures.extend(other.failures[: max(room, 0)])
        for worker, peak in other.peak_rss.items():
            self.peak_rss[worker] = max(self.peak_rss.get(worker, 0), peak)
        for worker, seconds in other.cpu.items():
            self.cpu[worker] = max(self.cpu.get(worker, 0.0), seconds)


def _peak_rss() -> int:
    """This process's peak resident memory, in bytes (Linux reports kB, macOS bytes)."""
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return peak if os.uname().sysname == "Darwin" else peak * 1024


def _cpu_seconds() -> float:
    """The CPU time this process has used (user and system), in seconds."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def _chunk(
    scene: Scene,
    names: List[str],
    nominal_values: np.ndarray,
    halfwidths: np.ndarray,
    seed: int,
    start: int,
    count: int,
    columns: List[str],
    nominal: np.ndarray,
) -> _Summary:
    """Runs variants ``start .. start + count`` and returns their summary (on a worker)."""
    values = nominal_values + draw(seed, start, count, halfwidths) * halfwidths
    variants = scene.run_variants(dict(zip(names, values.T)), columns)
    ok = np.ones(count, dtype=bool)
    failures = []
    for index, kind, message in variants.failures:
        ok[index] = False
        if len(failures) < KEPT_FAILURES:
            moved = dict(zip(names, map(float, values[index])))
            failures.append((start + index, kind, message, moved))
    good = variants.values[ok]
    deviation = good - nominal
    worker = f"{socket.gethostname()}:{os.getpid()}"
    return _Summary(
        count=int(ok.sum()),
        sum=deviation.sum(axis=0),
        sum_squares=(deviation * deviation).sum(axis=0),
        low=good.min(axis=0, initial=np.inf),
        high=good.max(axis=0, initial=-np.inf),
        failed=int(count - ok.sum()),
        failures=failures,
        peak_rss={worker: _peak_rss()},
        cpu={worker: _cpu_seconds()},
    )


@dataclass
class MonteCarlo:
    """A tolerance Monte Carlo's summary, per studied column, each an array over the drive
    positions in the column's unit."""

    #: The columns studied.
    columns: List[str]
    #: The drive positions (the scene's unit of the drive).
    drive: np.ndarray
    #: The nominal run of each column.
    nominal: Dict[str, np.ndarray]
    #: Mean over the variants that ran.
    mean: Dict[str, np.ndarray]
    #: Sample standard deviation.
    std: Dict[str, np.ndarray]
    #: Smallest and largest value sampled.
    low: Dict[str, np.ndarray]
    high: Dict[str, np.ndarray]
    #: Largest |y − y_nominal| sampled.
    max_deviation: Dict[str, np.ndarray]
    #: Variants run, and variants that failed (their reasons in ``failures``, the first
    #: ``KEPT_FAILURES``: ``(variant, kind, message, parameters)``).
    samples: int
    failed: int
    failures: List[Tuple[int, str, str, Dict[str, float]]]
    #: Chunks, and variants per chunk.
    chunks: int
    chunk: int
    #: Peak resident memory (bytes) of each process that ran chunks.
    peak_rss: Dict[str, int]
    #: CPU seconds of each process that ran chunks, at its last chunk (for a fresh
    #: LocalCluster: the study's cost, independent of other work on the machine).
    cpu_seconds: Dict[str, float]

    def to_pandas(self):
        """The summary as a DataFrame, one row per drive position (pandas needed)."""
        import pandas as pd

        table: Dict[str, np.ndarray] = {"drive": self.drive}
        for name in self.mean:
            for what in ("nominal", "mean", "std", "low", "high", "max_deviation"):
                table[f"{what}({name})"] = getattr(self, what)[name]
        return pd.DataFrame(table)


def _merge_in_order(results) -> _Summary:
    """Merges ``(index, summary)`` pairs arriving in any order, in chunk order."""
    waiting: Dict[int, _Summary] = {}
    merged: Optional[_Summary] = None
    following = 0
    for index, summary in results:
        waiting[index] = summary
        while following in waiting:
            part = waiting.pop(following)
            if merged is None:
                merged = part
            else:
                merged.merge(part)
            following += 1
    assert merged is not None and not waiting
    return merged


def monte_carlo(
    scene: Scene,
    tolerances: Mapping[str, float],
    samples: int,
    *,
    columns: Optional[Sequence[str]] = None,
    seed: int = 0,
    chunk: Optional[int] = None,
    client: Union[None, str, Any] = None,
    workers: int = 2,
) -> MonteCarlo:
    """A tolerance Monte Carlo of ``scene``: ``samples`` variants with each parameter of
    ``tolerances`` (``{name: ± half-width}`` in the parameter's unit) drawn uniformly from
    its box around its value, the others as they are.

    ``columns``: the columns studied (all but the drive without); ``chunk``: variants per
    task, a multiple of :data:`BLOCK` (default: 4 blocks, about 0.2 s of the Norton
    four-bar); ``client``: ``None`` for a ``LocalCluster`` of ``workers`` single-threaded
    processes started and closed here, a ``distributed.Client`` for any cluster, or
    ``"serial"`` to run the same chunks in this process.
    """
    if not 0 < samples <= MAX_SAMPLES:
        raise errors.LimitError(f"samples={samples}: expected 1 to {MAX_SAMPLES}")
    chunk = chunk or 4 * BLOCK
    if chunk % BLOCK or not 0 < chunk <= MAX_CHUNK:
        raise errors.ArgumentError(
            f"chunk={chunk}: expected a multiple of {BLOCK} up to {MAX_CHUNK}"
        )
    parameters = scene.parameters
    unknown = [n for n in tolerances if n not in parameters]
    if unknown:
        raise errors.SettingError(
            f"{scene.file}: no parameter {', '.join(map(repr, unknown))}; its parameters are: "
            f"{', '.join(parameters)}"
        )
    names = list(tolerances)
    halfwidths = np.array([float(tolerances[n]) for n in names])
    if not np.all(np.isfinite(halfwidths)) or np.any(halfwidths < 0):
        raise errors.ArgumentError(f"tolerances {dict(tolerances)}: expected finite ± half-widths ≥ 0")
    nominal_values = np.array([parameters[n] for n in names])
    # A parameter set by a formula of another moves with it unless set itself: the study
    # sets every toleranced one, as `--set` would.
    run = scene.run()
    drive = next(iter(run))
    studied = list(columns) if columns is not None else [c for c in run if c != drive]
    nominal = np.column_stack([run[c] for c in studied])
    starts = list(range(0, samples, chunk))
    tasks = [
        (scene, names, nominal_values, halfwidths, seed, s, min(chunk, samples - s), studied, nominal)
        for s in starts
    ]
    if isinstance(client, str):
        if client != "serial":
            raise errors.ArgumentError(f"client={client!r}: expected None, \"serial\" or a Client")
        merged = _merge_in_order((i, _chunk(*t)) for i, t in enumerate(tasks))
    elif client is None:
        from distributed import Client, LocalCluster

        with LocalCluster(
            n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster, Client(cluster) as local:
            merged = _on_cluster(local, tasks)
    else:
        merged = _on_cluster(client, tasks)
    n = merged.count
    mean = nominal + merged.sum / max(n, 1)
    spread = np.sqrt(np.maximum(merged.sum_squares - merged.sum**2 / max(n, 1), 0.0) / max(n - 1, 1))
    deviation = np.fmax(np.abs(merged.high - nominal), np.abs(nominal - merged.low))
    by_column = lambda a: {c: a[:, k] for k, c in enumerate(studied)}  # noqa: E731
    return MonteCarlo(
        columns=studied,
        drive=run[drive],
        nominal=by_column(nominal),
        mean=by_column(mean),
        std=by_column(spread),
        low=by_column(merged.low),
        high=by_column(merged.high),
        max_deviation=by_column(deviation),
        samples=samples,
        failed=merged.failed,
        failures=merged.failures,
        chunks=len(tasks),
        chunk=chunk,
        peak_rss=merged.peak_rss,
        cpu_seconds=merged.cpu,
    )


def _on_cluster(client: Any, tasks: List[tuple]) -> _Summary:
    """Runs the chunks as tasks of ``client``, merging their summaries as they arrive (in
    chunk order)."""
    from distributed import as_completed

    scene = client.scatter(tasks[0][0], broadcast=True)
    futures = {client.submit(_chunk, scene, *task[1:], pure=False): i for i, task in enumerate(tasks)}

    def arriving():
        for future in as_completed(list(futures)):
            index = futures.pop(future)
            summary = future.result()
            future.release()  # the worker forgets the summary once it is here
            yield index, summary

    return _merge_in_order(arriving())
