"""Type stubs of the Rust extension `mechdiff._mechdiff` (see python/src/)."""

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

__version__: str
#: The most variants of one `Scene.run_variants` call.
MAX_VARIANTS: int
#: The most numbers (variants × positions × columns) one `run_variants` call returns.
MAX_VALUES: int

class Scene:
    """A scene read and checked, with its text and settings (wrapped by `mechdiff.Scene`)."""

    @staticmethod
    def load(path: str, settings: Sequence[Tuple[str, str]] = ...) -> "Scene": ...
    @staticmethod
    def parse(
        text: str, file: str = "<text>", settings: Sequence[Tuple[str, str]] = ...
    ) -> "Scene": ...
    def with_settings(self, settings: Sequence[Tuple[str, str]]) -> "Scene": ...
    @property
    def file(self) -> str: ...
    @property
    def text(self) -> str: ...
    @property
    def title(self) -> Optional[str]: ...
    @property
    def settings(self) -> List[Tuple[str, str]]: ...
    @property
    def parameters(self) -> List[Tuple[str, float]]: ...
    @property
    def positions(self) -> int: ...
    def check(self) -> Dict[str, Any]: ...
    def run(
        self,
        positions: Optional[npt.NDArray[np.float64]] = None,
        evaluator: Optional[str] = None,
    ) -> Dict[str, Any]: ...
    def sensitivity(
        self, columns: Sequence[str]
    ) -> Tuple[Dict[str, Any], List[Tuple[str, str, float, str]]]: ...
    def run_variants(
        self,
        names: Sequence[str],
        values: npt.NDArray[np.float64],
        columns: Optional[Sequence[str]] = None,
    ) -> Tuple[npt.NDArray[np.float64], List[str], List[Tuple[int, str, str]]]: ...
    def metrics(self) -> Optional[Tuple[List[str], str]]: ...
    def codegen(self) -> str: ...

#: The most drive positions of a run whose drawing and diagram are kept (`Run._repr_html_`).
MAX_PICTURED_ROWS: int
#: The most cam angles of one `Cam.svaj_at` call.
MAX_CAM_ANGLES: int
#: The most points of one `Formula.evaluate` call.
MAX_POINTS: int

class Pictures:
    """A run's scene and report, kept for its pictures (runs of at most MAX_PICTURED_ROWS)."""

    def diagram_svg(self) -> str: ...
    def drawing_svg(self) -> str: ...

class Cam:
    """A cam scene read and checked (wrapped by `mechdiff.Cam`)."""

    @staticmethod
    def load(path: str) -> "Cam": ...
    @staticmethod
    def parse(text: str, file: str = "<text>") -> "Cam": ...
    @property
    def file(self) -> str: ...
    @property
    def title(self) -> Optional[str]: ...
    def svaj(self) -> Dict[str, Any]: ...
    def svaj_at(
        self, theta: npt.NDArray[np.float64], side: str = "right"
    ) -> npt.NDArray[np.float64]: ...
    def profile_csv(self) -> str: ...
    def summary_json(self) -> str: ...
    def report(self) -> str: ...

class Rotor:
    """A rotor scene read, checked and balanced (wrapped by `mechdiff.Rotor`)."""

    @staticmethod
    def load(path: str) -> "Rotor": ...
    @staticmethod
    def parse(text: str, file: str = "<text>") -> "Rotor": ...
    @property
    def file(self) -> str: ...
    def answers_json(self) -> str: ...
    def lines(self) -> List[str]: ...

class Formula:
    """A formula and its derivatives by the symbolic engine (wrapped by
    `mechdiff.Derivatives`)."""

    def __init__(self, expression: str, wrt: str, order: int) -> None: ...
    @property
    def parameters(self) -> List[str]: ...
    def expressions(self) -> List[str]: ...
    def evaluate(
        self, names: Sequence[str], values: Sequence[npt.NDArray[np.float64]]
    ) -> npt.NDArray[np.float64]: ...

def accuracy_csv(
    file: str,
    text: Optional[str] = None,
    repeats: int = 15,
    positions: Optional[int] = None,
    crank_ratio: Optional[float] = None,
) -> str: ...

class SynthesisProblem:
    """A synthesis problem of the core engine (wrapped by `mechdiff.synthesis.Problem`)."""

    def __init__(
        self,
        linkage: str,
        task: str,
        targets: Sequence[Sequence[float]],
        *,
        name: Optional[str] = None,
        timing: str = "absolute",
        drive: Optional[Sequence[float]] = None,
        bounds: Sequence[Tuple[str, float, float]] = ...,
        branch: Optional[Sequence[float]] = None,
        crank_rotates: bool = False,
        min_transmission: float = 0.0,
        checks_between_targets: int = 8,
        angle_weight: float = 1.0,
        weights: Optional[Sequence[float]] = None,
        grashof: str = "any",
    ) -> None: ...
    @property
    def variable_names(self) -> List[str]: ...
    @property
    def bounds(self) -> List[Tuple[float, float]]: ...
    @property
    def weights(self) -> List[float]: ...
    @property
    def grashof(self) -> str: ...
    def residuals(self, x: Sequence[float]) -> Optional[List[float]]: ...
    def solve(
        self,
        seed: int = 0,
        samples: int = 1000,
        local_searches: int = 100,
        iterations: int = 200,
        stop_objective: float = 1e-24,
        max_evaluations: int = 10_000_000,
        time_limit: Optional[float] = None,
        exact: bool = True,
    ) -> Dict[str, Any]: ...
