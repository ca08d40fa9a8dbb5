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

A design grid runs every combination of the values given (or the rows given) and returns
one row per variant and drive position; a failed variant is one row with its reason:

>>> grid = mechdiff.study.grid(scene, {"b": [1.8, 1.9, 5.0]}, client="serial")
>>> grid[grid.reason.notna()][["variant", "b", "kind"]].values.tolist()
[[2, 5.0, 'Unconstructible']]

A list of synthesis starts runs the core engine's search once per seed
(:mod:`mechdiff.synthesis`), one row per start with its objective and dimensions.

With ``client=None`` a ``LocalCluster`` of ``workers`` processes is started for the study
and closed after it (nothing to set up); pass a ``distributed.Client`` to use any cluster.
Tasks are chunks of variants (or starts) of at least ``TASK_SECONDS`` each, measured on a
first variant; each chunk comes back as it finishes, and the chunks are put together in
their order, so the result equals the serial study's (``client="serial"``) bit for bit.
With ``out="folder/"`` each chunk is written as one Parquet file as it arrives (the study's
memory is one chunk), and :func:`read_parquet` reads the folder back as one DataFrame.
"""

from __future__ import annotations

import json
import math
import os
import resource
import socket
import time
from pathlib import Path
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import Scene, errors

__all__ = [
    "monte_carlo",
    "MonteCarlo",
    "grid",
    "synthesis",
    "read_parquet",
    "draw",
    "BLOCK",
    "MAX_SAMPLES",
    "MAX_CHUNK",
    "TASK_SECONDS",
]

#: Variants drawn from one seed sequence; a chunk holds a whole number of blocks.
BLOCK = 1024

#: The most variants of one study.
MAX_SAMPLES = 100_000_000

#: The most variants of one chunk (one task's memory: variants × positions × columns).
MAX_CHUNK = 1_048_576

#: Failures kept with their reasons (all are counted).
KEPT_FAILURES = 100

#: The least time one task (a chunk of a grid or of synthesis starts) should take (s): the
#: cost of a variant is measured first and the chunk sized to it, so that Dask's overhead
#: per task (about a millisecond) stays small.
TASK_SECONDS = 0.1


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


# ---------------------------------------------------------------------------------------
# Chunked tasks on a cluster: the common part of a design grid and of synthesis starts.


def _chunk_size(seconds_per_item: float, most: int, seconds: float = TASK_SECONDS) -> int:
    """Items per task so that the items take at least ``seconds``, from 1 to ``most``."""
    per = max(seconds_per_item, 1e-9)
    return max(1, min(most, math.ceil(max(seconds, 0.0) / per)))


def _in_order(client: Union[None, str, Any], workers: int, function, tasks: List[tuple]):
    """Yields ``(index, result)`` of ``function(*task)`` for every task: in this process
    (``client="serial"``), on a fresh ``LocalCluster`` of ``workers`` processes (``None``),
    or on ``client``; on a cluster the results arrive as the tasks finish, each task's result
    released on its worker once it is here."""
    if isinstance(client, str):
        if client != "serial":
            raise errors.ArgumentError(f"client={client!r}: expected None, \"serial\" or a Client")
        for i, task in enumerate(tasks):
            yield i, function(*task)
        return
    if client is None:
        if not 0 < workers <= 1024:
            raise errors.ArgumentError(f"workers={workers}: expected 1 to 1024 processes")
        from distributed import Client, LocalCluster

        with LocalCluster(
            n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster, Client(cluster) as local:
            yield from _in_order(local, workers, function, tasks)
        return
    from distributed import as_completed

    shared = client.scatter(tasks[0][0], broadcast=True)  # the scene or problem, once
    futures = {
        client.submit(function, shared, *task[1:], pure=False): i for i, task in enumerate(tasks)
    }
    for future in as_completed(list(futures)):
        index = futures.pop(future)
        result = future.result()
        future.release()
        yield index, result


class _Collect:
    """Chunks' DataFrames put together in chunk order: in memory, or each written to a
    Parquet file of ``out`` as it arrives (then the memory is one chunk's)."""

    def __init__(self, out: Union[None, str, "os.PathLike[str]"], attrs: Dict[str, Any]):
        self.attrs = attrs
        self.frames: Dict[int, Any] = {}
        self.paths: Dict[int, Path] = {}
        self.folder: Optional[Path] = None
        if out is not None:
            folder = Path(out)
            if folder.exists() and not folder.is_dir():
                raise errors.ArgumentError(f"out={str(out)!r} is a file; expected a folder")
            if folder.is_dir() and any(folder.glob("part-*.parquet")):
                raise errors.ArgumentError(
                    f"out={str(out)!r} already holds a study's Parquet files; choose an empty "
                    "or new folder (a study never overwrites one)"
                )
            folder.mkdir(parents=True, exist_ok=True)
            self.folder = folder

    def add(self, index: int, frame) -> None:
        if self.folder is None:
            self.frames[index] = frame
            return
        import pyarrow as pa
        import pyarrow.parquet as pq

        table = pa.Table.from_pandas(frame, preserve_index=False)
        metadata = dict(table.schema.metadata or {})
        metadata[b"mechdiff"] = json.dumps(self.attrs).encode()
        table = table.replace_schema_metadata(metadata)
        path = self.folder / f"part-{index:06d}.parquet"
        partial = path.with_suffix(".parquet.partial")
        pq.write_table(table, partial)
        os.replace(partial, path)  # complete files only under the final name
        self.paths[index] = path

    def result(self):
        if self.folder is not None:
            return [self.paths[i] for i in sorted(self.paths)]
        import pandas as pd

        frame = pd.concat([self.frames[i] for i in sorted(self.frames)], ignore_index=True)
        frame.attrs.update(self.attrs)
        return frame


def read_parquet(folder: Union[str, "os.PathLike[str]"]):
    """The study written to ``folder`` (``out=``) as one DataFrame, its chunks in order,
    with the study's ``attrs`` (units, parameters, scene) as :func:`grid` returns them."""
    import pandas as pd
    import pyarrow.parquet as pq

    paths = sorted(Path(folder).glob("part-*.parquet"))
    if not paths:
        raise errors.ArgumentError(f"{str(folder)!r} holds no part-*.parquet files of a study")
    tables = [pq.read_table(p) for p in paths]
    frame = pd.concat([t.to_pandas() for t in tables], ignore_index=True)
    frame.attrs.update(json.loads(tables[0].schema.metadata[b"mechdiff"]))
    return frame


# ---------------------------------------------------------------------------------------
# A design grid.


def _grid_chunk(
    scene: Scene,
    names: List[str],
    values: np.ndarray,
    start: int,
    asked: List[str],
):
    """Runs the variants ``values`` (rows; the first is variant ``start``) and returns their
    long table: one row per variant and drive position, or one row with the reason of a
    variant that failed (on a worker)."""
    import pandas as pd

    count = len(values)
    variants = scene.run_variants(dict(zip(names, values.T)), asked)
    positions = variants.values.shape[1]
    failed = {index: (kind, message) for index, kind, message in variants.failures}
    ok = np.array([i not in failed for i in range(count)], dtype=bool)
    # Rows: each good variant's positions, each failed variant once, in variant order.
    per = np.where(ok, positions, 1)
    variant = np.repeat(np.arange(count), per)
    first = np.concatenate([[0], np.cumsum(per)[:-1]])
    position = np.arange(len(variant)) - np.repeat(first, per)
    good_row = np.repeat(ok, per)
    table: Dict[str, Any] = {"variant": start + variant}
    for k, name in enumerate(names):
        table[name] = values[variant, k]
    table["position"] = pd.array(position, dtype="Int64")
    table["position"][~good_row] = pd.NA  # a failed variant's one row is at no position
    table_values = np.full((len(variant), len(asked)), np.nan)
    table_values[good_row] = variants.values[ok].reshape(-1, len(asked))
    for k, name in enumerate(asked):
        table[name] = table_values[:, k]
    kinds = [failed[i][0] if i in failed else None for i in variant]
    reasons = [failed[i][1] if i in failed else None for i in variant]
    table["kind"] = pd.array(kinds, dtype="string")
    table["reason"] = pd.array(reasons, dtype="string")
    return pd.DataFrame(table)


def _design(
    scene: Scene, values: Optional[Mapping[str, Sequence[float]]], rows: Any
) -> Tuple[List[str], np.ndarray]:
    """The parameters' names and the variants' values (rows), from a full factorial of
    ``values`` or from ``rows``, checked."""
    if (values is None) == (rows is None):
        raise errors.ArgumentError("grid(): give `values` (a full factorial) or `rows`, not both")
    if values is not None:
        names = list(values)
        axes = [np.asarray(values[n], dtype=np.float64).reshape(-1) for n in names]
        count = math.prod(len(a) for a in axes) if axes else 0
        if not 0 < count <= MAX_SAMPLES:
            raise errors.LimitError(
                f"a grid of {' × '.join(str(len(a)) for a in axes)} = {count} variants: "
                f"expected 1 to {MAX_SAMPLES}"
            )
        mesh = np.meshgrid(*axes, indexing="ij")  # the last parameter varies fastest
        table = np.column_stack([m.reshape(-1) for m in mesh])
    else:
        names = [str(n) for n in rows]
        columns = [np.asarray(rows[n], dtype=np.float64).reshape(-1) for n in names]
        lengths = {len(c) for c in columns}
        if len(lengths) != 1:
            raise errors.ArgumentError(
                f"rows: the parameters have {sorted(lengths)} values; expected one per variant each"
            )
        count = lengths.pop()
        if not 0 < count <= MAX_SAMPLES:
            raise errors.LimitError(f"{count} rows: expected 1 to {MAX_SAMPLES} variants")
        table = np.column_stack(columns)
    unknown = [n for n in names if n not in scene.parameters]
    if unknown:
        raise errors.SettingError(
            f"{scene.file}: no parameter {', '.join(map(repr, unknown))}; its parameters are: "
            f"{', '.join(scene.parameters)}"
        )
    bad = np.argwhere(~np.isfinite(table))
    if len(bad):
        variant, k = bad[0]
        raise errors.ArgumentError(
            f"parameter {names[k]} of variant {variant} is {table[variant, k]}; expected a "
            "finite number"
        )
    return names, np.ascontiguousarray(table)


def grid(
    scene: Scene,
    values: Optional[Mapping[str, Sequence[float]]] = None,
    *,
    rows: Any = None,
    columns: Optional[Sequence[str]] = None,
    chunk: Optional[int] = None,
    client: Union[None, str, Any] = None,
    workers: int = 2,
    out: Union[None, str, "os.PathLike[str]"] = None,
):
    """A design study of ``scene``: every combination of ``values`` (``{name: [values]}``,
    a full factorial, the last name varying fastest) or the variants ``rows`` (``{name:
    array}`` of equal lengths, or a DataFrame), each value in the parameter's unit as
    ``[parameters]`` writes it, each variant run over the scene's sweep.

    Returns a pandas DataFrame, one row per variant and drive position: ``variant``, the
    parameters, ``position`` (the index in the sweep), the drive and the ``columns`` asked
    for (all without) in their units (``df.attrs["units"]``), and ``kind`` and ``reason``:
    a variant that cannot run (it does not assemble, a formula fails) is one row with NaN
    values and its reason, never lost. With ``out="folder/"`` each chunk is written as a
    Parquet file as it arrives and the files' paths are returned (:func:`read_parquet`).

    ``chunk``: variants per task (default: as many as take :data:`TASK_SECONDS`, from the
    measured cost of the first variant); ``client``: as for :func:`monte_carlo`.
    """
    names, table = _design(scene, values, rows)
    run = scene.run()
    drive = next(iter(run))
    studied = list(columns) if columns is not None else [c for c in run if c != drive]
    asked = [drive] + [c for c in studied if c != drive]
    clash = [n for n in names if n in asked or n in ("variant", "position", "kind", "reason")]
    if clash:
        raise errors.ArgumentError(
            f"parameter {', '.join(map(repr, clash))} has the name of a column of the study; "
            "leave that column out with `columns=`"
        )
    overhead = per_variant = None  # measured only when the chunk is not given
    if chunk is None:
        # Enough variants that a task takes TASK_SECONDS with the call's overhead.
        overhead, per_variant = _variant_cost(scene, names, table[0], asked)
        chunk = _chunk_size(per_variant, MAX_CHUNK, TASK_SECONDS - overhead)
    if not 0 < chunk <= MAX_CHUNK:
        raise errors.ArgumentError(f"chunk={chunk}: expected 1 to {MAX_CHUNK} variants")
    units = {c.name: c.unit for c in run.columns if c.name in asked}
    attrs = {
        "scene": scene.file,
        "parameters": names,
        "units": units,
        "positions": run.positions,
        "chunk": chunk,
        "seconds_per_variant": per_variant,
        "seconds_per_call": overhead,
    }
    tasks = [
        (scene, names, table[s : s + chunk], s, asked) for s in range(0, len(table), chunk)
    ]
    collect = _Collect(out, attrs)
    for index, frame in _in_order(client, workers, _grid_chunk, tasks):
        collect.add(index, frame)
    return collect.result()


def _variant_cost(
    scene: Scene, names: List[str], row: np.ndarray, asked: List[str]
) -> Tuple[float, float]:
    """What a call of ``run_variants`` costs here: its overhead (the nominal run that names
    the columns) and the time of each variant, from calls of 1 and of n copies of the
    variant ``row`` (n grown until the variants alone take ≥ 20 ms)."""

    def seconds(n: int) -> float:
        copies = {name: np.full(n, value) for name, value in zip(names, row)}
        start = time.perf_counter()
        scene.run_variants(copies, asked)
        return time.perf_counter() - start

    one, n = seconds(1), 4
    while True:
        many = seconds(n)
        if many - one >= 0.02 or n >= 4096:
            break
        n *= 4
    per_variant = max((many - one) / (n - 1), 1e-9)
    return max(one - per_variant, 0.0), per_variant


# ---------------------------------------------------------------------------------------
# Synthesis starts.


def _starts_chunk(problem, seeds: List[int], settings: Dict[str, Any]):
    """Runs one search per seed and returns one row per start (on a worker)."""
    import pandas as pd

    frame = pd.DataFrame([problem.solve_row(seed, **settings) for seed in seeds])
    # Text or missing, the same type in every chunk.
    for text in ("grashof_class", "stop", "kind", "reason"):
        frame[text] = frame[text].astype("string")
    return frame


def synthesis(
    problem,
    starts: Union[int, Sequence[int]],
    *,
    samples: int = 50,
    local_searches: int = 3,
    iterations: int = 200,
    stop_objective: float = 1e-24,
    time_limit: Optional[float] = None,
    exact: bool = True,
    chunk: Optional[int] = None,
    client: Union[None, str, Any] = None,
    workers: int = 2,
    out: Union[None, str, "os.PathLike[str]"] = None,
):
    """Synthesis from many starts: one search of the core engine per seed (``starts``: a
    count, seeds 0, 1, …, or the seeds), each sampling ``samples`` points of the bounds and
    polishing the best ``local_searches`` by Levenberg–Marquardt with the exact Jacobian
    (``exact=False``: central differences), on a Dask cluster as :func:`grid`.

    ``problem`` is a :class:`mechdiff.synthesis.Problem`. Returns a DataFrame, one row per
    start in order: ``start`` (the seed), ``objective`` (m², rad²), the design variables
    (m, rad), ``grashof_class`` (the answer's four-bar loop; missing for the slider-crank),
    ``evaluations``, ``successes``, ``stop``, ``certificate_deviation`` (m),
    ``seconds``, and ``kind``/``reason`` for a start that finds no usable mechanism (its
    values NaN); sort by ``objective`` for the best. ``chunk``: starts per task (default:
    from the measured time of the first start, which is kept).
    """
    seeds = list(range(starts)) if isinstance(starts, (int, np.integer)) else [int(s) for s in starts]
    if not 0 < len(seeds) <= 1_000_000:
        raise errors.LimitError(f"{len(seeds)} starts: expected 1 to 1000000")
    settings = dict(
        samples=samples,
        local_searches=local_searches,
        iterations=iterations,
        stop_objective=stop_objective,
        time_limit=time_limit,
        exact=exact,
    )
    attrs = {"variables": problem.variable_names, "units": problem.units}
    collect = _Collect(out, attrs)
    done = 0
    if chunk is None:
        started = time.perf_counter()
        collect.add(0, _starts_chunk(problem, seeds[:1], settings))
        chunk = _chunk_size(time.perf_counter() - started, 10_000)
        done = 1
    if not 0 < chunk <= 10_000:
        raise errors.ArgumentError(f"chunk={chunk}: expected 1 to 10000 starts")
    tasks = [(problem, seeds[s : s + chunk], settings) for s in range(done, len(seeds), chunk)]
    if tasks:
        for index, frame in _in_order(client, workers, _starts_chunk, tasks):
            collect.add(done + index, frame)
    return collect.result()
