"""Dimensional synthesis: the dimensions of a linkage from what it must do, by the core
engine's search (a Latin hypercube of the bounds, the best samples polished by
Levenberg–Marquardt with the exact Jacobian of the residuals).

A problem names the linkage (``"four_bar"``, ``"slider_crank"``, ``"stephenson_six"``), the
task (``"path"``: points x, y in m; ``"function"``: pairs of drive angle and output, rad or
m; ``"motion"``: poses x, y in m and angle in rad), when the targets are met (``timing``
and ``drive``, rad) and bounds on every design variable (``Problem(...).variable_names``);
lengths in m and angles in rad, the engine's units. Targets generated from a known
four-bar are met exactly::

    import mechdiff.synthesis as synthesis

    problem = synthesis.Problem(
        "four_bar", "path", targets, drive=angles,               # rad
        bounds={"o2x": 0, "o2y": 0, "o4x": 0.4, "o4y": 0,        # fixed
                "crank": (0.05, 0.2), "coupler": (0.2, 0.8), "rocker": (0.1, 0.6),
                "px": (0, 0.8), "py": (-0.5, 0.5)})
    found = problem.solve(seed=1)
    found.objective, found.values["crank"]

``mechdiff.study.synthesis(problem, starts=100)`` runs many seeds on a Dask cluster.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import errors
from ._mechdiff import SynthesisProblem as _RustProblem

__all__ = ["Problem", "Solution"]

#: A bound: a value (the variable fixed) or ``(lower, upper)``.
Bound = Union[float, Tuple[float, float]]


@dataclass
class Solution:
    """What one search found: the design variables (``values``, m and rad), the objective
    (the sum of squared residuals), the residuals, and what the search cost and how it
    ended (see ``SynthesisProblem.solve`` in the stubs for every field)."""

    values: Dict[str, float]
    objective: float
    residuals: List[float]
    report: Dict[str, Any]

    @property
    def grashof_class(self) -> Optional[str]:
        """The Grashof class of the answer's four-bar loop (``"crank-rocker"``,
        ``"double-crank"``, ``"rocker-crank"``, ``"double-rocker"``, ``"triple-rocker"``),
        ``None`` for the slider-crank, which has none."""
        return self.report["grashof_class"]

    @property
    def why_not_better(self) -> Optional[str]:
        """``None`` when the objective reached the level asked for; otherwise why not."""
        return self.report["why_not_better"]


class Problem:
    """A synthesis problem (see the module's doc); pickles as its arguments, so Dask ships
    it to its workers."""

    def __init__(
        self,
        linkage: str,
        task: str,
        targets: Sequence[Sequence[float]],
        *,
        bounds: Mapping[str, Bound],
        name: Optional[str] = None,
        timing: str = "absolute",
        drive: Optional[Sequence[float]] = None,
        branch: Optional[Sequence[float]] = None,
        crank_rotates: bool = False,
        min_transmission: float = 0.0,
        checks_between_targets: int = 8,
        angle_weight: float = 1.0,
        weights: Optional[Sequence[float]] = None,
        grashof: str = "any",
    ):
        pairs = []
        for variable, bound in bounds.items():
            if isinstance(bound, (tuple, list)) and len(bound) == 2:
                pairs.append((str(variable), float(bound[0]), float(bound[1])))
            elif isinstance(bound, (int, float)) and not isinstance(bound, bool):
                pairs.append((str(variable), float(bound), float(bound)))
            else:
                raise errors.ArgumentError(
                    f"bounds[{variable!r}] = {bound!r}: expected a value or (lower, upper)"
                )
        self._args = dict(
            linkage=linkage,
            task=task,
            targets=[[float(v) for v in row] for row in targets],
            name=name,
            timing=timing,
            drive=None if drive is None else [float(a) for a in drive],
            bounds=pairs,
            branch=None if branch is None else [float(b) for b in branch],
            crank_rotates=bool(crank_rotates),
            min_transmission=float(min_transmission),
            checks_between_targets=int(checks_between_targets),
            angle_weight=float(angle_weight),
            weights=None if weights is None else [float(w) for w in weights],
            grashof=str(grashof),
        )
        args = dict(self._args)
        self._rust = _RustProblem(args.pop("linkage"), args.pop("task"), args.pop("targets"), **args)

    @property
    def variable_names(self) -> List[str]:
        """The design variables, in order: the linkage's, then the task's (``pose_angle``,
        ``drive0``, ``drive1``, …)."""
        return self._rust.variable_names

    @property
    def units(self) -> Dict[str, str]:
        """Each design variable's unit: ``rad`` for angles, ``m`` for lengths and places."""
        angles = {"guide", "pose_angle"}
        return {
            n: "rad" if n in angles or n.startswith("drive") else "m" for n in self.variable_names
        }

    @property
    def bounds(self) -> Dict[str, Tuple[float, float]]:
        """The bounds of every design variable (equal for a fixed one)."""
        return dict(zip(self.variable_names, self._rust.bounds))

    @property
    def weights(self) -> List[float]:
        """Each target's weight, in order (1 where none was given): it multiplies the
        target's squared error in the objective."""
        return self._rust.weights

    @property
    def grashof(self) -> str:
        """The Grashof class the four-bar loop must have (``"any"``: none required)."""
        return self._rust.grashof

    def residuals(self, values: Mapping[str, float]) -> Optional[List[float]]:
        """The residuals (m, rad) of the mechanism ``values`` (every design variable), or
        ``None`` where it does not assemble at a target."""
        missing = [n for n in self.variable_names if n not in values]
        if missing:
            raise errors.ArgumentError(f"values: missing {', '.join(missing)}")
        return self._rust.residuals([float(values[n]) for n in self.variable_names])

    def solve(
        self,
        seed: int = 0,
        *,
        samples: int = 1000,
        local_searches: int = 100,
        iterations: int = 200,
        stop_objective: float = 1e-24,
        max_evaluations: int = 10_000_000,
        time_limit: Optional[float] = None,
        exact: bool = True,
    ) -> Solution:
        """One search from the bounds alone (the same seed gives the same answer), without
        the GIL; raises :class:`mechdiff.StudyError` when no sample is a usable mechanism."""
        report = self._rust.solve(
            seed, samples, local_searches, iterations, stop_objective, max_evaluations,
            time_limit, exact,
        )
        return Solution(dict(report["variables"]), report["objective"], report["residuals"], report)

    def solve_row(self, seed: int, **settings: Any) -> Dict[str, Any]:
        """One search as a row of a study: ``start``, ``objective``, the variables, the
        answer's ``grashof_class``, what it cost and how it ended; a start without a usable
        mechanism has NaN values, no class, and its ``kind`` and ``reason``."""
        row: Dict[str, Any] = {"start": seed}
        try:
            found = self.solve(seed, **settings)
        except errors.StudyError as failure:
            row["objective"] = math.nan
            row.update({n: math.nan for n in self.variable_names})
            row.update(grashof_class=None, evaluations=0, successes=0, stop=None, certificate_deviation=math.nan,
                       seconds=math.nan, kind=failure.kind, reason=str(failure))
            return row
        report = found.report
        row["objective"] = found.objective
        row.update(found.values)
        row.update(
            grashof_class=found.grashof_class,
            evaluations=report["evaluations"],
            successes=report["successes"],
            stop=report["stop"],
            certificate_deviation=report["certificate_deviation"],
            seconds=report["seconds"],
            kind=None,
            reason=report["why_not_better"],
        )
        return row

    def __reduce__(self):
        return (_restore, (self._args,))

    def __repr__(self) -> str:
        a = self._args
        return f"<mechdiff.synthesis.Problem: {a['linkage']} {a['task']}, {len(a['targets'])} targets>"


def _restore(args: Dict[str, Any]) -> Problem:
    args = dict(args)
    bounds = {n: (lo, hi) for n, lo, hi in args.pop("bounds")}
    return Problem(args.pop("linkage"), args.pop("task"), args.pop("targets"), bounds=bounds, **args)
