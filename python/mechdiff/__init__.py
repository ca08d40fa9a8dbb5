"""mechdiff: kinematics and dynamics of planar mechanisms with exact derivatives.

Read a scene file (a mechanism described by its geometry, in TOML), set its parameters, run
its sweep, and get every column as a NumPy array, in the units the column names::

    import mechdiff

    scene = mechdiff.load("scenes/norton_four_bar.toml").with_parameters(b=1.9)
    run = scene.run()                        # the sweep of the file: 0 to 100 deg by 10
    run["psi"], run.units["psi"]             # array of ψ, "deg"
    sens = scene.sensitivity(of="psi", wrt="b")
    sens["d(psi)/d(b)"], sens.methods        # exact dψ/db (dual numbers), per position

Every run releases the GIL, so threads run scenes in parallel, and Ctrl-C interrupts it;
`mechdiff.study` spreads many variants over a Dask cluster. Failures raise the classes of
`mechdiff.errors`, whose messages keep the file, line and column, or the drive position in
the scene's units. Beside linkages: cams (`mechdiff.Cam`), rotors (`mechdiff.Rotor`),
formula derivatives (`mechdiff.derive`), generated Rust (`mechdiff.codegen`) and the
accuracy report (`mechdiff.accuracy`). In Jupyter a run shows its mechanism and diagram.
"""

from __future__ import annotations

import html
import json
import os
from dataclasses import dataclass
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import errors
from ._mechdiff import MAX_PICTURED_ROWS, MAX_VALUES, MAX_VARIANTS
from ._mechdiff import Scene as _RustScene
from ._mechdiff import __version__
from .errors import *  # noqa: F401,F403 (the exception classes at the package's top)
from .accuracy_report import accuracy
from .balancing import Rotor
from .cams import Cam
from .formulas import Derivatives, codegen, derive

__all__ = [
    "Scene",
    "Run",
    "Column",
    "Sensitivity",
    "DerivativeMethod",
    "Variants",
    "Limit",
    "Counterweight",
    "Cam",
    "Rotor",
    "Derivatives",
    "derive",
    "codegen",
    "accuracy",
    "MAX_PICTURED_ROWS",
    "load",
    "parse",
    "errors",
    "MAX_VARIANTS",
    "MAX_VALUES",
    "__version__",
] + errors.__all__

#: A parameter's value: a number, or a formula of the other parameters (``"2*a"``).
ParameterValue = Union[float, int, str]


def _setting_text(name: str, value: ParameterValue) -> str:
    """The text of a setting's value: a formula as given, a number as the shortest text that
    reads back as the same float."""
    if isinstance(value, str):
        return value
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.number)):
        raise errors.ArgumentError(
            f"parameter {name}={value!r}: expected a number or a formula in a string"
        )
    return repr(float(value))


def _settings(parameters: Mapping[str, ParameterValue]) -> List[Tuple[str, str]]:
    return [(name, _setting_text(name, value)) for name, value in parameters.items()]


@dataclass(frozen=True)
class Column:
    """A column of a run: its name, its unit, and its unit's size in SI (``si = value *
    factor``)."""

    name: str
    unit: str
    factor: float

    @property
    def header(self) -> str:
        """``name [unit]``, as the table's header writes it."""
        return f"{self.name} [{self.unit}]" if self.unit else self.name


@dataclass(frozen=True)
class Limit:
    """A limit position, change point or toggle the sweep reaches: the drive position (in
    the drive's unit), what it is (``"limit position"``, ``"change point"``, ``"toggle"``,
    ...) and the joints of the loop that stops the drive."""

    position: float
    kind: str
    joints: List[str]


@dataclass(frozen=True)
class Counterweight:
    """A counterweight ``[balancing]`` sized: its link, mass (kg), mass-radius ``m r`` (kg m),
    angle from the link's line (the scene's angle unit, counter-clockwise) and centre at the
    sketch pose (``[x, y]``, the scene's length unit)."""

    link: str
    mass: float
    mass_radius: float
    angle: float
    center: np.ndarray


class Run(Mapping[str, np.ndarray]):
    """A run's columns, each a NumPy array in its column's unit (the drive first), and what
    the run found: ``plan``, ``warnings``, ``dead_positions``, ``summary``.

    A mapping from column name to array: ``run["psi"]``, ``list(run)``, ``dict(run)``.
    """

    def __init__(self, raw: Dict[str, Any], scene: Optional["Scene"] = None):
        self._scene = scene
        #: The run's drawing and diagram (kept for runs of at most ``MAX_PICTURED_ROWS``
        #: positions), for ``_repr_html_``.
        self._pictures = raw.get("pictures")
        self.columns: List[Column] = [
            Column(n, u, f) for n, u, f in zip(raw["names"], raw["units"], raw["factors"])
        ]
        self._values: Dict[str, np.ndarray] = dict(zip(raw["names"], raw["values"]))
        #: The plan line: positions, derivative order, drive state, in the scene's units.
        self.plan: str = raw["plan"]
        #: Warnings about the results (ill-conditioned positions with their estimated error).
        self.warnings: List[str] = list(raw["warnings"])
        #: Per output searched: ``{output: [(drive position, value), ...]}`` in the scene's
        #: units (the drive's unit, the output's unit).
        self.dead_positions: Dict[str, List[Tuple[float, float]]] = {
            name: list(found) for name, found in raw["dead_positions"]
        }
        #: What the table prints after its rows: dead positions, limits, dynamics summaries.
        self.summary: str = raw["after_rows"]
        #: The limit positions, change points and toggles the sweep reaches: ``[Limit]``, the
        #: drive position in the drive's unit.
        self.limits: List[Limit] = [Limit(phi, kind, list(joints)) for phi, kind, joints in raw["limits"]]
        #: The lines ``[balancing]`` prints after the table (empty without it).
        self.balancing: List[str] = list(raw["balancing"])
        #: The counterweights ``[balancing]`` sized: ``[Counterweight]``, in the scene's units.
        self.counterweights: List[Counterweight] = [
            Counterweight(link, mass, mass_radius, angle, np.array(center))
            for link, mass, mass_radius, angle, center in raw["counterweights"]
        ]

    @property
    def metrics(self) -> Optional[Dict[str, Any]]:
        """The scene's linkage metrics (Grashof class, the input's range, transmission angle,
        quick return; as ``mechdiff check --json`` writes them, in the scene's units), or
        ``None`` when it has none. Computed when first asked for."""
        if self._scene is None:
            return None
        if not hasattr(self, "_metrics"):
            found = self._scene._rust.metrics()
            self._metrics = None if found is None else json.loads(found[1])
            self._metrics_lines = [] if found is None else list(found[0])
        return self._metrics

    @property
    def metrics_lines(self) -> List[str]:
        """The linkage metrics in words, as ``mechdiff check`` prints them (empty without)."""
        if self.metrics is None:
            return []
        return self._metrics_lines

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self._values[name]
        except KeyError:
            raise KeyError(
                f"no column {name!r}; the columns are: {', '.join(self._values)}"
            ) from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    @property
    def units(self) -> Dict[str, str]:
        """Each column's unit, by name."""
        return {c.name: c.unit for c in self.columns}

    @property
    def positions(self) -> int:
        """The number of drive positions (rows)."""
        return len(next(iter(self._values.values()))) if self._values else 0

    def si(self, name: str) -> np.ndarray:
        """The column ``name`` in SI units (a new array)."""
        factor = next(c.factor for c in self.columns if c.name == name) if name in self else 0
        return self[name] * factor

    def to_dict(self) -> Dict[str, np.ndarray]:
        """The columns as a plain dict of arrays (the arrays themselves, not copies)."""
        return dict(self._values)

    def to_numpy(self) -> np.ndarray:
        """The table as one array, ``[position, column]``, in the columns' units."""
        return np.column_stack(list(self._values.values()))

    def to_pandas(self, headers: bool = False):
        """The table as a pandas DataFrame (pandas must be installed; the arrays are handed
        over, not copied where pandas can keep them): columns named as the run names them
        (``headers=True``: ``name [unit]``), units in ``df.attrs["units"]`` (by column) and
        the plan in ``df.attrs["plan"]``."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("to_pandas() needs pandas: pip install pandas") from e
        names = [c.header if headers else c.name for c in self.columns]
        frame = pd.DataFrame(dict(zip(names, self._values.values())), copy=False)
        frame.attrs["units"] = {n: c.unit for n, c in zip(names, self.columns)}
        frame.attrs["plan"] = self.plan
        return frame

    def to_polars(self):
        """The table as a polars DataFrame (polars must be installed), each column named
        ``name [unit]`` (polars keeps no other metadata per column)."""
        try:
            import polars as pl
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("to_polars() needs polars: pip install polars") from e
        return pl.DataFrame({c.header: self._values[c.name] for c in self.columns})

    def __repr__(self) -> str:
        columns = ", ".join(c.header for c in self.columns)
        return f"<mechdiff.Run: {self.positions} positions; {columns}>"

    def _repr_html_(self) -> str:
        """The plan, the first and last rows, the findings: for Jupyter."""
        n = self.positions
        shown = list(range(n)) if n <= 20 else list(range(10)) + [-1] + list(range(n - 10, n))
        head = "".join(f"<th>{html.escape(c.header)}</th>" for c in self.columns)
        body = []
        for i in shown:
            if i < 0:
                body.append(f"<tr><td colspan={len(self.columns)}>…</td></tr>")
                continue
            cells = "".join(f"<td>{self._values[c.name][i]:.10g}</td>" for c in self.columns)
            body.append(f"<tr>{cells}</tr>")
        notes = "".join(f"<li>{html.escape(w)}</li>" for w in self.warnings)
        summary = f"<pre>{html.escape(self.summary)}</pre>" if self.summary.strip() else ""
        return (
            f"<p>{html.escape(self.plan)}</p>{self._pictures_html()}"
            f"<table><thead><tr>{head}</tr></thead>"
            f"<tbody>{''.join(body)}</tbody></table>{summary}"
            + (f"<ul>{notes}</ul>" if notes else "")
        )

    def drawing_svg(self) -> str:
        """The mechanism drawn at the run's first drawn position with its traced paths, as
        the HTML report draws it (SVG text); raises ``ArgumentError`` for a run of more than
        ``MAX_PICTURED_ROWS`` positions (draw a run at fewer)."""
        return self._kept_pictures().drawing_svg()

    def diagram_svg(self) -> str:
        """The run's diagram (its columns against the drive position, dead positions and
        limits marked; polar panels for forces), as the HTML report draws it (SVG text)."""
        return self._kept_pictures().diagram_svg()

    def _kept_pictures(self):
        if self._pictures is None and self.positions > MAX_PICTURED_ROWS:
            raise errors.ArgumentError(
                f"this run has {self.positions} positions; its pictures are kept for runs of at "
                f"most {MAX_PICTURED_ROWS} (run the scene at fewer positions to draw it)"
            )
        if self._pictures is None:
            raise errors.ArgumentError(
                "a sensitivity run keeps no pictures; draw the scene's own run (scene.run())"
            )
        return self._pictures

    def _pictures_html(self) -> str:
        """The drawing and the diagram side by side, inline SVG (no network), or a note."""
        if self._pictures is None and self.positions > MAX_PICTURED_ROWS:
            return (
                f"<p>(pictures are drawn for runs of at most {MAX_PICTURED_ROWS} positions)</p>"
            )
        if self._pictures is None:
            return ""
        try:
            drawing, diagram = self._pictures.drawing_svg(), self._pictures.diagram_svg()
        except errors.MechdiffError as e:
            return f"<p>(no pictures: {html.escape(str(e))})</p>"
        box = "display:inline-block;vertical-align:top;max-width:49%"
        return f'<div><div style="{box}">{drawing}</div><div style="{box}">{diagram}</div></div>'



@dataclass(frozen=True)
class DerivativeMethod:
    """How a derivative column was computed: ``"exact"`` (dual numbers through the pose's
    implicit differentiation) or ``"richardson"`` (extrapolated central differences of whole
    runs, where the exact route does not reach; ``why`` says why), with its estimated error
    relative to the column's largest value (0 for an exact column: its error is rounding)."""

    method: str
    estimated_error: float
    why: str

    @property
    def is_exact(self) -> bool:
        """Whether the column is exact."""
        return self.method == "exact"


class Sensitivity(Run):
    """A run with derivative columns ``d(COLUMN)/d(PARAMETER)`` after the others, per unit
    of the parameter as ``[parameters]`` writes it, and how each was computed
    (``methods``)."""

    def __init__(
        self,
        raw: Dict[str, Any],
        methods: Sequence[Tuple[str, str, float, str]],
        scene: Optional["Scene"] = None,
    ):
        super().__init__(raw, scene)
        #: Per derivative column: how it was computed.
        self.methods: Dict[str, DerivativeMethod] = {
            name: DerivativeMethod(method, error, why) for name, method, error, why in methods
        }


@dataclass
class Variants:
    """The runs of many variants of a scene: ``values[variant, position, column]`` in the
    columns' units (NaN for a variant that failed), and ``failures``: ``[(variant, kind,
    message), ...]``."""

    columns: List[str]
    values: np.ndarray
    failures: List[Tuple[int, str, str]]


class Scene:
    """A scene file read and checked, with the parameters it was read with.

    Read one with :func:`load` or :func:`parse` (or ``Scene.load`` / ``Scene.from_toml``);
    ``with_parameters`` gives a variant; ``run``, ``sensitivity`` and ``run_variants`` run
    it without holding the GIL. A scene pickles as its text and settings (Dask ships it to
    its workers and reads it there again).
    """

    def __init__(self, rust: _RustScene):
        self._rust = rust

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"], **parameters: ParameterValue) -> "Scene":
        """Reads the scene file at ``path``, with ``parameters`` replacing values of its
        ``[parameters]`` (numbers, or formulas of the other parameters, in each parameter's
        unit)."""
        return cls(_RustScene.load(os.fspath(path), _settings(parameters)))

    @classmethod
    def from_toml(cls, text: str, file: str = "<text>", **parameters: ParameterValue) -> "Scene":
        """Reads a scene given as TOML ``text``; ``file`` names it in messages."""
        return cls(_RustScene.parse(text, file, _settings(parameters)))

    parse = from_toml

    def with_parameters(self, **parameters: ParameterValue) -> "Scene":
        """The scene read again with ``parameters`` set (as the command line's ``--set``:
        every formula that uses them follows)."""
        return Scene(self._rust.with_settings(_settings(parameters)))

    @property
    def file(self) -> str:
        """The file's name as messages give it."""
        return self._rust.file

    @property
    def text(self) -> str:
        """The scene's TOML text as read."""
        return self._rust.text

    @property
    def title(self) -> Optional[str]:
        """The scene's title, if it has one."""
        return self._rust.title

    @property
    def parameters(self) -> Dict[str, float]:
        """The values of ``[parameters]`` after the settings, in the units of the fields that
        use them, in the order they are evaluated."""
        return dict(self._rust.parameters)

    @property
    def settings(self) -> Dict[str, str]:
        """The parameters set (``with_parameters``, ``load(**p)``), as text."""
        return dict(self._rust.settings)

    @property
    def positions(self) -> int:
        """The number of drive positions of the scene's sweep."""
        return self._rust.positions

    def check(self) -> Dict[str, Any]:
        """Checks the scene without running its sweep (``mechdiff check``): ``{"plan": str,
        "columns": [(name, unit), ...], "degrees_of_freedom": int, "loops": [(joints,
        branch sign), ...], "closed_form": [bool, ...], "motion_range": (lower, upper)}``,
        each end of the drive's motion range ``(position in the drive's unit, kind,
        joints)`` or ``None`` where it turns fully (a string saying why when it could not be
        walked); raises what a run would raise before solving."""
        return self._rust.check()

    def run(self, positions: Optional[Any] = None, *, evaluator: Optional[str] = None) -> Run:
        """Runs the scene's sweep, or the drive ``positions`` given (in the scene's unit of
        the sweep: the drive's, or the ``[sweep] of`` output's; at most 10⁶), in memory.

        ``evaluator``: ``"auto"`` (default), ``"solver"``, ``"program"``, ``"interpreter"``
        or ``"jit"``, as ``mechdiff run --evaluator``.

        The run releases the GIL and looks for Ctrl-C every 1024 positions
        (``KeyboardInterrupt``). In Jupyter the result shows the mechanism and the diagram
        (``_repr_html_``, runs of at most ``MAX_PICTURED_ROWS`` positions).
        """
        if positions is not None:
            positions = np.ascontiguousarray(positions, dtype=np.float64).reshape(-1)
        return Run(self._rust.run(positions, evaluator), self)

    def sensitivity(
        self,
        of: Union[str, Sequence[str], None] = None,
        wrt: Union[str, Sequence[str], None] = None,
        *,
        columns: Optional[Sequence[str]] = None,
    ) -> Sensitivity:
        """The derivatives of columns ``of`` with respect to parameters ``wrt`` at every
        drive position (``d(psi)/d(b)``), exact (dual numbers) where the exact route
        reaches and labelled otherwise (``.methods``). ``columns`` names them directly
        (``["d(psi')/d(a)"]``); with neither, the scene's own ``[sensitivity]`` and
        ``[tolerances]`` tables are run."""
        wanted = list(columns or [])
        if (of is None) != (wrt is None):
            raise errors.ArgumentError("sensitivity(): give both `of` and `wrt`, or neither")
        if of is not None and wrt is not None:
            ofs = [of] if isinstance(of, str) else list(of)
            wrts = [wrt] if isinstance(wrt, str) else list(wrt)
            wanted += [f"d({c})/d({p})" for c in ofs for p in wrts]
        raw, methods = self._rust.sensitivity(wanted)
        return Sensitivity(raw, methods, self)

    def run_variants(
        self,
        parameters: Mapping[str, Any],
        columns: Optional[Sequence[str]] = None,
    ) -> Variants:
        """Runs one variant per index of the equal-length arrays ``parameters`` (``{"a":
        array, "b": array}``, each value in the parameter's unit), each over the scene's
        sweep, in one call into Rust without the GIL. Returns the ``columns`` asked for
        (all without) of every variant; a variant that fails has NaN rows and a line in
        ``failures``; at most ``MAX_VARIANTS`` variants and ``MAX_VALUES`` numbers."""
        names = list(parameters)
        if names:
            table = np.column_stack(
                [np.asarray(parameters[n], dtype=np.float64).reshape(-1) for n in names]
            )
        else:
            table = np.zeros((0, 0))
        table = np.ascontiguousarray(table)
        asked = None if columns is None else list(columns)
        values, picked, failures = self._rust.run_variants(names, table, asked)
        return Variants(picked, values, failures)

    def codegen(self) -> str:
        """The Rust module computing the scene's outputs and their derivatives, as ``mechdiff
        codegen SCENE`` prints it (every loop must have a closed form)."""
        return self._rust.codegen()

    def __reduce__(self):
        return (_restore, (self.text, self.file, self._rust.settings))

    def __repr__(self) -> str:
        name = f" {self.title!r}" if self.title else ""
        return f"<mechdiff.Scene{name} from {self.file}: {self.positions} positions>"


def _restore(text: str, file: str, settings: List[Tuple[str, str]]) -> Scene:
    return Scene(_RustScene.parse(text, file, settings))


def load(path: Union[str, "os.PathLike[str]"], **parameters: ParameterValue) -> Scene:
    """Reads a scene file (see :meth:`Scene.load`)."""
    return Scene.load(path, **parameters)


def parse(text: str, file: str = "<text>", **parameters: ParameterValue) -> Scene:
    """Reads a scene from TOML text (see :meth:`Scene.from_toml`)."""
    return Scene.from_toml(text, file, **parameters)
