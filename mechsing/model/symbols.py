"""A file's parameter kept as a sympy symbol that knows its value (symbolic conditions).

:mod:`mechsing.model.parameters` hands it out as ``ParameterSymbol`` when a caller asks
for symbols; it lives here so that reading a file imports sympy only when a symbol is
asked for.
"""

from __future__ import annotations

from typing import Any

import sympy

__all__ = ["ParameterSymbol", "prec_to_dps"]


class ParameterSymbol(sympy.Dummy):
    """A parameter kept as a symbol that still knows its value.

    It evaluates (``sympy.N``, ``float``) to the value, so the loader's checks
    of directions and scales work unchanged; it is real, and positive or
    negative as its value is.  :func:`symbolic_values` lists the symbols of an
    expression with their values; ``sympy.Symbol(s.name)`` is its printable
    twin.
    """

    def __new__(cls, name: str, value: Any) -> ParameterSymbol:
        sign = sympy.sign(sympy.N(value, 30))
        assumptions: dict[str, bool] = {"real": True}
        if sign > 0:
            assumptions["positive"] = True
        elif sign < 0:
            assumptions["negative"] = True
        obj = super().__new__(cls, name, **assumptions)
        obj.parameter_value = value
        return obj

    def _eval_evalf(self, prec: int) -> Any:
        return sympy.sympify(self.parameter_value).evalf(prec_to_dps(prec))


def prec_to_dps(prec: int) -> int:
    """Decimal digits of a binary precision (sympy's evalf speaks bits)."""
    return max(1, int(prec * 0.30103))
