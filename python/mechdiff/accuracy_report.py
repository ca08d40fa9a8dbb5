"""The accuracy report: every derivative method of a scene against an extended-precision
reference, timed side by side (``mechdiff accuracy``), as a DataFrame."""

from __future__ import annotations

import csv
import io
import os
from typing import Any, Dict, Optional, Union

import numpy as np

from ._mechdiff import accuracy_csv

#: Columns of the report that are text.
_TEXT = ("method", "kind")


def _table(text: str) -> Dict[str, np.ndarray]:
    rows = list(csv.reader(io.StringIO(text)))
    headers, body = rows[0], rows[1:]
    columns: Dict[str, np.ndarray] = {}
    for k, h in enumerate(headers):
        cells = [r[k] for r in body]
        if h in _TEXT:
            columns[h] = np.array(cells, dtype=str)
        else:
            columns[h] = np.array([float(c) if c else np.nan for c in cells], dtype=np.float64)
    return columns


def accuracy(
    subject: Union[Any, str, "os.PathLike[str]"] = "whitworth",
    *,
    repeats: int = 15,
    positions: Optional[int] = None,
    lam: Optional[float] = None,
    frame: Optional[bool] = None,
):
    """The accuracy report of ``subject``: a :class:`mechdiff.Scene` (read without parameter
    settings), the path of a scene file of any kind (linkage, cam, formulas, rotor), or
    ``"whitworth"`` (the reference machine, crank ratio ``lam``). Each method is timed
    ``repeats`` times (at most 1000) over at most ``positions`` drive positions.

    One row per method (``kind`` ``exact`` or ``difference`` with its ``step``), then one
    per scanned finite-difference step (``scan``): ``method, kind, step, order,
    time_median_s, time_min_s, time_max_s, ratio`` (to the fastest exact method),
    ``max_value, max_d1, max_d2, max_d3`` (the largest scaled error per derivative order),
    ``rms_*`` and ``digits_lost``, as ``mechdiff accuracy --csv`` writes them (a rotor scene:
    its own columns). A pandas DataFrame when pandas is installed (``frame=False``: always
    a dict of arrays), NaN where a cell does not apply."""
    if hasattr(subject, "text") and hasattr(subject, "settings"):
        if subject.settings:
            from .errors import ArgumentError

            raise ArgumentError(
                "accuracy() measures a scene as its file writes it; this one has parameters "
                f"set ({', '.join(subject.settings)}): write them into the file's "
                "[parameters] instead"
            )
        text = accuracy_csv(subject.file, subject.text, repeats, positions, lam)
    else:
        text = accuracy_csv(os.fspath(subject), None, repeats, positions, lam)
    columns = _table(text)
    if frame is False:
        return columns
    try:
        import pandas as pd
    except ImportError:
        if frame:
            raise ImportError("accuracy(frame=True) needs pandas: pip install pandas") from None
        return columns
    return pd.DataFrame(columns)


__all__ = ["accuracy"]
