"""The record of a closed configuration (:class:`ClosedConfiguration`), and how a
closure's residuals and tolerances are shown in its messages."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["ClosedConfiguration", "shown_residual"]


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


def shown_residual(x: Any, digits: int) -> str:
    """A residual or tolerance (float or mpf) in %g style, also below float's range."""
    f = float(x)
    if f != 0 or x == 0:
        return f"{f:.{digits}g}"
    import mpmath

    return mpmath.nstr(x, digits)
