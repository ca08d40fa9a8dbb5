"""Cam scenes (a file with a ``[cam]`` section): the SVAJ table, s, s′, s″, s‴ at any cam
angles, the profile and the summary, as NumPy arrays with their units.

::

    cam = mechdiff.Cam.load("scenes/cams/reference_002_simple_harmonic.toml")
    table = cam.svaj()                        # every `step` of the file, in its units
    table["s''"], table.units["s''"]          # array, "mm/rad^2"
    cam.svaj_at(np.linspace(0, 2 * np.pi, 1000))   # [angle, (s, s', s'', s''')], SI
"""

from __future__ import annotations

import csv
import io
import json
import os
import re
from typing import Any, Dict, Iterator, List, Mapping, Optional, Union

import numpy as np

from ._mechdiff import Cam as _RustCam

#: ``name [unit]``.
_HEADER = re.compile(r"^(.*) \[(.*)\]$")

#: The table's primes as ASCII (the run's columns write ``psi''``).
_PRIMES = {"′": "'", "″": "''", "‴": "'''"}


def _split(header: str):
    """``("s''", "mm/rad^2")`` from ``"s″ [mm/rad^2]"`` (primes as ASCII)."""
    match = _HEADER.match(header)
    name, unit = (match.group(1), match.group(2)) if match else (header, "")
    for prime, ascii in _PRIMES.items():
        name = name.replace(prime, ascii)
    return name, unit


class CamTable(Mapping[str, np.ndarray]):
    """A table of a cam: a mapping from column name to array (``"theta"`` first), each in
    the unit ``units[name]``; ``headers`` as the report prints them (``s″ [mm/rad^2]``)."""

    def __init__(self, headers: List[str], columns: List[np.ndarray], side: Optional[List[str]] = None):
        self.headers: List[str] = list(headers)
        split = [_split(h) for h in headers]
        self._values: Dict[str, np.ndarray] = {n: c for (n, _), c in zip(split, columns)}
        #: Each column's unit, by name.
        self.units: Dict[str, str] = {n: u for n, u in split}
        #: Per row: ``"left"`` or ``"right"`` for the two rows of a boundary where a
        #: derivative jumps (the one-sided limits), else ``""``.
        self.side: List[str] = list(side) if side is not None else [""] * len(columns[0])

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self._values[name]
        except KeyError:
            raise KeyError(f"no column {name!r}; the columns are: {', '.join(self._values)}") from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    def to_pandas(self):
        """The table as a pandas DataFrame (pandas must be installed), units in
        ``df.attrs["units"]``, the boundary side as a column ``side``."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("to_pandas() needs pandas: pip install pandas") from e
        frame = pd.DataFrame(dict(self._values))
        frame.insert(1, "side", self.side)
        frame.attrs["units"] = dict(self.units)
        return frame

    def __repr__(self) -> str:
        return f"<mechdiff.CamTable: {len(self.side)} rows; {', '.join(self.headers)}>"


class Cam:
    """A cam scene read and checked: its cam program (segments of motion laws or formulas),
    follower and base circle. Read with ``Cam.load(path)`` or ``Cam.from_toml(text)``."""

    def __init__(self, rust: _RustCam):
        self._rust = rust

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "Cam":
        """Reads and checks the cam scene file at ``path``."""
        return cls(_RustCam.load(os.fspath(path)))

    @classmethod
    def from_toml(cls, text: str, file: str = "<text>") -> "Cam":
        """Reads and checks a cam scene given as TOML ``text``; ``file`` names it in
        messages."""
        return cls(_RustCam.parse(text, file))

    @property
    def file(self) -> str:
        """The file's name as messages give it."""
        return self._rust.file

    @property
    def title(self) -> Optional[str]:
        """The scene's title, if it has one."""
        return self._rust.title

    def svaj(self) -> CamTable:
        """The SVAJ table as ``mechdiff run`` prints it, every ``step`` of the file from 0 to
        one turn: ``theta``, ``s``, ``s'``, ``s''``, ``s'''`` (and ``v``, ``a``, ``j`` when the
        cam turns), ``pressure angle``, ``ρ profile``, each in the file's units (the
        derivatives per rad of cam angle); two rows at a boundary where a derivative jumps
        (``side``)."""
        raw = self._rust.svaj()
        values = raw["values"]
        columns = [raw["theta"]] + [np.ascontiguousarray(values[:, k]) for k in range(values.shape[1])]
        headers = list(raw["headers"])
        headers[0] = headers[0].replace("θ", "theta", 1)
        return CamTable(headers, columns, raw["side"])

    def svaj_at(self, theta: Any, side: str = "right") -> np.ndarray:
        """s, s′, s″, s‴ at the cam angles ``theta`` (rad, any shape) in SI (m, or rad for an
        oscillating follower; per rad of cam angle), exact (dual numbers): an array of
        ``theta``'s shape with a last axis of 4. At a segment boundary, the limit from
        ``side``: ``"right"`` (the segment starting there) or ``"left"``."""
        angles = np.asarray(theta, dtype=np.float64)
        flat = np.ascontiguousarray(angles.reshape(-1))
        return self._rust.svaj_at(flat, side).reshape(angles.shape + (4,))

    def profile(self) -> CamTable:
        """The profile for CAD/CNC, every 0.5°: cam angle, pitch point, profile point and
        outward normal in the cam's frame (its centre at the origin), in the file's units."""
        rows = list(csv.reader(io.StringIO(self._rust.profile_csv())))
        headers, body = rows[0], np.array(rows[1:], dtype=np.float64)
        columns = [np.ascontiguousarray(body[:, k]) for k in range(len(headers))]
        headers[0] = headers[0].replace("θ", "theta", 1)
        return CamTable(headers, columns)

    @property
    def summary(self) -> Dict[str, Any]:
        """The summary as ``mechdiff run --json`` writes it: follower, base circle, largest
        pressure angle, smallest radii of curvature, undercut, the boundaries' continuity,
        sizing and warnings, in the file's units (named under ``"units"``)."""
        return json.loads(self._rust.summary_json())

    @property
    def report(self) -> str:
        """The report ``mechdiff run`` prints."""
        return self._rust.report()

    def __repr__(self) -> str:
        name = f" {self.title!r}" if self.title else ""
        return f"<mechdiff.Cam{name} from {self.file}>"

    def _repr_html_(self) -> str:
        import html

        return f"<pre>{html.escape(self.report)}</pre>"


__all__ = ["Cam", "CamTable"]
