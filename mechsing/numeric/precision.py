"""The precision policy: :class:`Precision` (a mode and its digits), its parsing, the
precision the numerical tests of an analysis run at, and the tolerances that follow
from a precision (rank thresholds, rotation and subspace tolerances; their constants
are in :mod:`mechsing.numeric.tolerances`).
"""

from __future__ import annotations

import math
from contextlib import AbstractContextManager, nullcontext
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from mechsing.numeric.backend import FLOAT, Backend, _exact_backend, _mp_backend, screw_zero_rtol
from mechsing.numeric.lazy import mpmath
from mechsing.numeric.tolerances import (
    CLOSURE_RTOL_FLOAT,
    EXACT_TEST_DIGITS,
    MP_MIN_DIGITS,
    ORDER3_RESIDUAL_FACTOR,
    ROTATION_ORTHONORMAL_ATOL,
    SUBSPACE_CONTAINMENT_FACTOR,
    SUBSPACE_RANK_FACTOR,
    Tolerances,
)

#: the context of a precision that sets nothing (float, exact, auto)
_UNCHANGED: AbstractContextManager[Any] = nullcontext()


@dataclass(frozen=True)
class Precision:
    """A precision mode: ``float``, ``mp`` with ``digits`` N, ``exact`` or ``auto``.

    ``auto`` decides in float and re-decides undecided verdicts at mp:50.
    """

    mode: str
    digits: int | None = None

    @classmethod
    def of(cls, bk: Backend) -> Precision:
        """The precision of a backend's numbers (mp: at the working precision)."""
        return cls(bk.name, int(mpmath.mp.dps) if bk.name == "mp" else None)

    def __str__(self) -> str:
        return f"mp:{self.digits}" if self.mode == "mp" else self.mode

    @property
    def tolerances(self) -> Tolerances:
        if self.mode in ("float", "auto"):
            return Tolerances(1e-12, 1e-9)
        if self.mode == "mp":
            # mpf: as floats, 10^(10-N) underflows to 0 beyond N = 333 and 10^(-N/2)
            # beyond N = 646, and every decision with them was wrong there
            n = self.digits or 50
            return Tolerances(mpmath.mpf(10) ** (10 - n), mpmath.mpf(10) ** (-n / 2))
        return Tolerances(0.0, 0.0)

    @property
    def backend(self) -> Backend:
        if self.mode == "mp":
            with self.context():
                return _mp_backend()
        if self.mode == "exact":
            return _exact_backend()
        return FLOAT

    def context(self) -> AbstractContextManager[Any]:
        """Set mpmath's working precision to N digits for the block (no-op otherwise: one
        shared empty context, as every analysis step enters it)."""
        if self.mode == "mp":
            return cast(AbstractContextManager[Any], mpmath.workdps(self.digits or 50))
        return _UNCHANGED

    def asarray(self, x: Any) -> np.ndarray:
        """Numbers of this mode from numbers, decimal strings or sympy numbers."""
        with self.context():
            return self.backend.asarray(x)

    def closure_tolerance(self, length_scale: float) -> Any:
        """Closure acceptance: 1e-12 L in float, 10^(15-N) L at mp:N, 0 exact.

        At mp:N an ``mpf`` (10^(15-N) underflows float beyond N = 323); compare it with
        residuals in the model's numbers (``KinematicModel.residual_norm(native=True)``).
        """
        if self.mode in ("float", "auto"):
            return CLOSURE_RTOL_FLOAT * length_scale
        if self.mode == "mp":
            # never looser than float's: more digits must not accept what float refuses
            n = self.digits or 50
            if 15 - n >= math.log10(CLOSURE_RTOL_FLOAT):
                return CLOSURE_RTOL_FLOAT * length_scale
            with mpmath.workdps(max(n, 15)):
                return mpmath.mpf(10) ** (15 - n) * length_scale
        return 0.0


def display_floor(precision: Precision | str, length_scale: float) -> float:
    """The display floor: a length below it is round-off and is shown as 0 (an angle below
    ``display_floor / L``): the closure tolerance of the precision, 1e-12 L in float,
    min(10^(15-N), 10^-12) L at mp:N, 0 in exact mode.  Text and reports show values
    through :func:`floored`; the JSON keeps the numbers."""
    p = parse_precision(precision) if isinstance(precision, str) else precision
    return float(p.closure_tolerance(float(length_scale)))


def floored(x: float, floor: float) -> float:
    """``x`` as it is displayed: 0 below the display ``floor`` (never -0)."""
    return 0.0 if abs(x) < floor else float(x) + 0.0


def parse_precision(text: str) -> Precision:
    """Parse ``float``, ``mp:N`` (20 <= N <= 10000), ``exact`` or ``auto``.

    N starts at 20: below it the two thresholds cross (``tau_lo = 10^(10-N)``
    exceeds ``tau_hi = 10^(-N/2)``), so no rank could be decided consistently.

    Raises
    ------
    ValueError
        with a message that says what is accepted.
    """
    t = text.strip().lower()
    if t in ("float", "exact", "auto"):
        return Precision(t)
    if t.startswith("mp:"):
        try:
            n = int(t[3:])
        except ValueError:
            n = -1
        if MP_MIN_DIGITS <= n <= 10000:
            return Precision("mp", n)
    raise ValueError(
        f"precision {text!r} is not one of auto, float, mp:N ({MP_MIN_DIGITS} <= N <= 10000) "
        "or exact (below 20 digits the two rank thresholds of mp:N cross)"
    )


def numeric_precision(prec: Precision) -> Precision:
    """The precision at which the numerical tests of an analysis run.

    The higher-order forms of the tangent cone and the input/output ranks are
    computed and decided at the analysis precision when it is numerical
    (``float``, ``mp:N``; an ``auto`` stage is float, or mp:50 after
    escalation); an ``exact`` analysis evaluates them at
    mp::data:`EXACT_TEST_DIGITS` from its exact configuration.
    """
    if prec.mode == "exact":
        return Precision("mp", EXACT_TEST_DIGITS)
    if prec.mode == "auto":
        return Precision("float")
    return prec


def subspace_rank_rtol(prec: Precision) -> float:
    """Relative singular value below which a direction is dropped from a basis of
    a cone piece: :data:`SUBSPACE_RANK_FACTOR` tau_hi (1e-10 in float)."""
    return SUBSPACE_RANK_FACTOR * prec.tolerances.tau_hi


def subspace_containment_atol(prec: Precision) -> float:
    """Projection residual below which an orthonormal basis lies in another's span:
    :data:`SUBSPACE_CONTAINMENT_FACTOR` tau_hi (1e-8 in float)."""
    return SUBSPACE_CONTAINMENT_FACTOR * prec.tolerances.tau_hi


def order3_residual_rtol(prec: Precision) -> float:
    """Relative residual below which a direction extends to third order:
    :data:`ORDER3_RESIDUAL_FACTOR` tau_hi (1e-9 in float)."""
    return ORDER3_RESIDUAL_FACTOR * prec.tolerances.tau_hi


def rotation_orthonormal_atol(prec: Precision) -> Any:
    """Largest entry of ``R^T R - I`` for which a given 3x3 matrix is a rotation.

    :data:`ROTATION_ORTHONORMAL_ATOL` (1e-9) in float and auto, 10^(-N/2) at
    mp:N (the mode's ``tau_hi``, as for subgroup membership), 0 in exact mode.
    """
    if prec.mode == "mp":
        with prec.context():
            return screw_zero_rtol(prec.backend)
    if prec.mode == "exact":
        return 0
    return ROTATION_ORTHONORMAL_ATOL
