"""The record of a closed configuration (:class:`ClosedConfiguration`), the frozen value
one is handed on as (:class:`ClosedValue`), and how a closure's residuals and tolerances
are shown in its messages."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing.numeric import Precision

__all__ = [
    "FLOAT_DIGITS",
    "SOURCES",
    "ClosedConfiguration",
    "ClosedValue",
    "digits_of",
    "shown_residual",
]

#: where a closed value came from: a configuration of the file closed (``given``), a
#: singular point a sweep located (``located``), an assembly mode ``modes`` found
#: (``mode``; ``certified`` when the Krawczyk test proved it)
SOURCES = ("given", "located", "mode")
#: the significant digits of a float64 number (its rounding, 2^-52, is 2.2e-16)
FLOAT_DIGITS = 15


@dataclass
class ClosedConfiguration:
    """A closed configuration: all coordinates ``q`` (model backend), its residual (m)."""

    name: str
    q: np.ndarray
    residual: float
    underdetermined: bool = False
    steps: int = 0
    given: tuple[int, ...] = ()
    notes: list[str] = field(default_factory=list)
    #: reached by landing on a fold of the given values (float locates it to ~1e-8 only)
    at_fold: bool = False


@dataclass(frozen=True)
class ClosedValue:
    """A closed configuration as a value: what :func:`mechsing.analyze` (each
    configuration's ``point``), :func:`mechsing.modes` (each mode's ``point``),
    :func:`mechsing.sweep` (``start=``, and each located point's ``point``) hand on.

    ``q``: every coordinate, in the mechanism's coordinate order (SI, radians), as the
    numbers they were found in (floats, ``mpmath.mpf`` carrying more digits, exact
    numbers); ``digits``: the significant digits those numbers carry
    (:func:`digits_of` the precision they were found at: 15 for float64, N for a point
    placed at mp:N, None for exact numbers); ``source``: where it came from (:data:`SOURCES`); ``name``:
    the configuration's (``located-3``, ``reference#mode2``); ``certified``: a mode the
    Krawczyk test proved.  Frozen, its coordinates a tuple: a value handed on is never
    changed on the way (:meth:`at` makes a new one)."""

    q: tuple[Any, ...]
    digits: int | None
    source: str
    name: str = ""
    certified: bool = False

    def __post_init__(self) -> None:
        if self.source not in SOURCES:
            raise ValueError(f"ClosedValue: source {self.source!r} is not one of {SOURCES}")
        if self.digits is not None and (not isinstance(self.digits, int) or self.digits < 1):
            raise ValueError(f"ClosedValue: digits {self.digits!r} is not a positive integer")
        if self.certified and self.source != "mode":
            raise ValueError("ClosedValue: only an assembly mode is certified")
        # any sequence (a numpy row) is kept as a tuple of its numbers: nothing shared
        q = tuple(float(x) if isinstance(x, np.floating) else x for x in self.q)
        object.__setattr__(self, "q", q)

    def floats(self) -> np.ndarray:
        """The coordinates in float (a new array: the value is not changed through it)."""
        return np.array([float(x) for x in self.q], dtype=float)

    def at(self, q: Any, digits: int | None, name: str | None = None) -> ClosedValue:
        """The same configuration, from the same source, found again as ``q`` at
        ``digits`` (a located point placed again at mp:N, a mode analysed at N digits)."""
        return ClosedValue(
            tuple(q), digits, self.source, self.name if name is None else name, self.certified
        )


def digits_of(precision: Precision) -> int | None:
    """The significant digits of numbers found at ``precision``: float64's 15 (its
    rounding is 2.2e-16), N at mp:N, None in exact mode (no rounding)."""
    if precision.mode == "exact":
        return None
    if precision.mode == "mp":
        return int(precision.digits or 50)
    return FLOAT_DIGITS


def shown_residual(x: Any, digits: int) -> str:
    """A residual or tolerance (float or mpf) in %g style, also below float's range."""
    f = float(x)
    if f != 0 or x == 0:
        return f"{f:.{digits}g}"
    import mpmath

    return mpmath.nstr(x, digits)
