"""Formulas through the symbolic engine: ``derive`` gives a formula's derivatives as
expressions and as a function of NumPy arrays; ``codegen`` gives the Rust source of a
scene's outputs and their derivatives.

::

    d = mechdiff.derive("atan2(l*sin(phi), 1-l*cos(phi))", wrt="phi", order=3)
    d.expressions[1]                           # dψ/dφ as an s-expression
    value, d1, d2, d3 = d(phi=np.linspace(0, 6, 100), l=0.375)
"""

from __future__ import annotations

import os
from typing import Any, List, Union

import numpy as np

from ._mechdiff import Formula as _RustFormula


class Derivatives:
    """A formula and its derivatives 1 to ``order`` with respect to ``wrt``, made by the
    symbolic engine (the engine of ``mechdiff codegen``): exact, simplified, common
    subexpressions shared. Call it with every parameter as a keyword (numbers or arrays that
    broadcast together) to evaluate them."""

    def __init__(self, expression: str, wrt: str, order: int = 1):
        if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
            from .errors import ArgumentError

            raise ArgumentError(f"order={order!r}: expected a whole number from 0")
        self._rust = _RustFormula(expression, wrt, int(order))
        #: The formula as given.
        self.expression: str = expression
        #: The variable of differentiation.
        self.wrt: str = wrt
        #: The highest derivative.
        self.order: int = int(order)

    @property
    def parameters(self) -> List[str]:
        """The names a call needs: ``wrt``, then the formula's other symbols in alphabetical
        order (named constants such as ``pi`` are not parameters)."""
        return list(self._rust.parameters)

    @property
    def expressions(self) -> List[str]:
        """The value and each derivative (``[f, f′, f″, ...]``) as s-expressions:
        ``(* l (cos phi))``."""
        return list(self._rust.expressions())

    def __call__(self, **values: Any) -> np.ndarray:
        """The value and the derivatives at the points given by ``values`` (one keyword per
        parameter; numbers or arrays, broadcast together): an array whose first axis is the
        order (``result[k]`` the k-th derivative) and whose other axes are the points'
        shape. A point where the formula is 0/0 or a derivative is infinite raises
        ``FormulaError`` naming it."""
        names = list(values)
        arrays = np.broadcast_arrays(*[np.asarray(values[n], dtype=np.float64) for n in names])
        shape = arrays[0].shape if arrays else ()
        flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrays]
        table = self._rust.evaluate(names, flat)  # [point, order + 1]
        return np.moveaxis(table, 1, 0).reshape((self.order + 1,) + shape)

    def __repr__(self) -> str:
        return f"<mechdiff.Derivatives of {self.expression!r} to order {self.order} in {self.wrt}>"


def derive(expression: str, wrt: str, order: int = 1) -> Derivatives:
    """The derivatives 1 to ``order`` of the infix formula ``expression`` with respect to
    ``wrt`` (``+ - * / ^``, ``sqrt exp ln sin cos tan asin acos atan atan2 hypot ...``,
    ``pi``, ``if(a < b, then, otherwise)``): see :class:`Derivatives`."""
    return Derivatives(expression, wrt, order)


def codegen(scene: Union[Any, str, "os.PathLike[str]"]) -> str:
    """The Rust module computing a scene's outputs and their derivatives, as ``mechdiff
    codegen SCENE`` prints it: ``scene`` a :class:`mechdiff.Scene` (with its parameters as
    set) or the path of a scene file."""
    if isinstance(scene, (str, os.PathLike)):
        from . import Scene

        scene = Scene.load(scene)
    return scene.codegen()


__all__ = ["Derivatives", "derive", "codegen"]
