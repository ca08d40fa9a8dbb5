"""Rotor scenes (a ``[rotor]`` section): static, two-plane and couple-plane balance, as
NumPy arrays in kg m and kg m².

::

    rotor = mechdiff.Rotor.load("scenes/rotor_balancing.toml")
    rotor.static_correction        # array [m r x, m r y] (kg m) cancelling Σ m r
    rotor.two_plane                # array [[m r x, m r y], [...]] in the two planes
    rotor.table()                  # every mass and answer, as `mechdiff run --csv` writes it
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Optional, Union

import numpy as np

from ._mechdiff import Rotor as _RustRotor

#: The columns of the table that are text, not numbers.
_TEXT = ("row",)


class Rotor:
    """A rotor scene read, checked and balanced (``Rotor.load(path)`` /
    ``Rotor.from_toml(text)``). Every answer is in kg m (force polygon, ``m r``) or kg m²
    (couple polygon about the reference plane, ``m r d``) along the scene's x and y axes;
    planes and radii in the scene's length unit, angles in its angle unit."""

    def __init__(self, rust: _RustRotor):
        self._rust = rust
        answers = json.loads(rust.answers_json())
        #: The title, if the scene has one.
        self.title: Optional[str] = answers.get("title")
        #: One dict per row of ``mechdiff run --csv``: the masses, the polygons' gap
        #: (``resultant``), ``static``, ``two_plane`` (two rows), ``couple_plane`` (and its
        #: ``couple_plane_gap``), keyed by the CSV's headers (``None`` where a cell is empty).
        self.rows: List[Dict[str, Any]] = answers["rows"]

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "Rotor":
        """Reads and checks the rotor scene file at ``path`` and balances it."""
        return cls(_RustRotor.load(os.fspath(path)))

    @classmethod
    def from_toml(cls, text: str, file: str = "<text>") -> "Rotor":
        """Reads and checks a rotor scene given as TOML ``text`` and balances it."""
        return cls(_RustRotor.parse(text, file))

    @property
    def file(self) -> str:
        """The file's name as messages give it."""
        return self._rust.file

    def _vectors(self, row: str, key: str = "m r") -> np.ndarray:
        """The ``key`` vectors (``"m r"`` in kg m, ``"m r d"`` in kg m²) of the rows named
        ``row``, ``[row, (x, y)]``."""
        unit = "kg m^2" if key == "m r d" else "kg m"
        found = [
            [r[f"{key} x [{unit}]"], r[f"{key} y [{unit}]"]] for r in self.rows if r["row"] == row
        ]
        return np.array(found, dtype=np.float64).reshape(-1, 2)

    @property
    def masses(self) -> np.ndarray:
        """The masses' ``m r`` vectors (kg m), ``[mass, (x, y)]``, in file order."""
        return self._vectors("mass")

    @property
    def resultant(self) -> np.ndarray:
        """The polygons' gaps: ``[Σ m r (kg m), Σ m r d (kg m²)]``, each ``(x, y)``."""
        return np.vstack([self._vectors("resultant"), self._vectors("resultant", "m r d")])

    @property
    def static_correction(self) -> np.ndarray:
        """The static correction ``−Σ m r`` in the reference plane (kg m), ``(x, y)``."""
        return self._vectors("static")[0]

    @property
    def two_plane(self) -> Optional[np.ndarray]:
        """The corrections in the two ``planes`` (kg m), ``[plane, (x, y)]``; ``None`` when
        the scene gives no planes."""
        found = self._vectors("two_plane")
        return found if len(found) else None

    @property
    def couple_plane(self) -> Optional[Dict[str, Any]]:
        """The one mass of ``couple_mass_radius`` that cancels the couple: its row (plane,
        ``m r`` vector and angle), or ``None`` when not asked for."""
        return next((r for r in self.rows if r["row"] == "couple_plane"), None)

    def table(self):
        """Every row as ``mechdiff run --csv`` writes it: a pandas DataFrame when pandas is
        installed, else a dict of arrays (numbers as float, NaN where a cell is empty)."""
        headers = list(self.rows[0]) if self.rows else []
        columns: Dict[str, np.ndarray] = {}
        for h in headers:
            cells = [r[h] for r in self.rows]
            if h in _TEXT:
                columns[h] = np.array(cells, dtype=str)
            else:
                columns[h] = np.array([np.nan if c is None else c for c in cells], dtype=np.float64)
        try:
            import pandas as pd
        except ImportError:
            return columns
        return pd.DataFrame(columns)

    @property
    def report(self) -> str:
        """The report ``mechdiff run`` prints."""
        return "\n".join(self._rust.lines()) + "\n"

    def __repr__(self) -> str:
        name = f" {self.title!r}" if self.title else ""
        return f"<mechdiff.Rotor{name} from {self.file}: {len(self.masses)} masses>"

    def _repr_html_(self) -> str:
        import html

        return f"<pre>{html.escape(self.report)}</pre>"


__all__ = ["Rotor"]
