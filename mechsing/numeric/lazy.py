"""sympy and mpmath imported when first used: the one place that defers them.

A float analysis of a file whose numbers are plain decimals, degrees and ``pi/6``-like
values (:class:`~mechsing.numeric.pirational.PiRational`) needs neither library, and sympy
alone costs about as much as the rest of the start-up.  A module that uses them writes
``from mechsing.numeric.lazy import sympy`` (or ``mpmath``) and calls ``sympy.Rational``
as before: the first attribute asked for imports the library.  :func:`is_sympy` and
:func:`is_mp` ask whether a value is one of theirs without importing them (no value can
be while the library is not imported).
"""

from __future__ import annotations

import importlib
import sys
from typing import Any

__all__ = ["LazyModule", "is_mp", "is_sympy", "mpmath", "sympy"]


class LazyModule:
    """A module imported on its first attribute access; its names are then copied here,
    so later look-ups cost what a module's do (a name the module gains later, a
    submodule imported afterwards, is still found through the module)."""

    def __init__(self, name: str) -> None:
        self.__dict__["_lazy_name"] = name

    def __getattr__(self, attr: str) -> Any:
        module = importlib.import_module(self.__dict__["_lazy_name"])
        self.__dict__.update(vars(module))
        return getattr(module, attr)

    def __repr__(self) -> str:
        return f"<lazy module {self.__dict__['_lazy_name']!r}>"


sympy: Any = LazyModule("sympy")
mpmath: Any = LazyModule("mpmath")


def is_sympy(x: Any) -> bool:
    """Is ``x`` a sympy value (``sympy.Basic``)?  False at once while sympy is not
    imported."""
    module = sys.modules.get("sympy")
    return module is not None and isinstance(x, module.Basic)


def is_mp(x: Any) -> bool:
    """Is ``x`` an mpmath number (``mpf`` or ``mpc``)?  False at once while mpmath is not
    imported."""
    module = sys.modules.get("mpmath")
    return module is not None and isinstance(x, module.mpf | module.mpc)
