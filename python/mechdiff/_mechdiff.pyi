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
