"""The closed joint values of one configuration (the API behind ``mechsing solve``).

Owns :class:`SolveResult` (typed, immutable, with its JSON in :meth:`SolveResult.to_json`)
and :func:`solve`.  Conventions: joint values in SI units and radians, in the
mechanism's joint order; ``joints`` are floats (the numeric JSON every mode keeps), and
``joints_text`` the same values as text at the precision they were solved to: the
shortest decimal that reads back to the float in float mode, N significant digits at
mp:N (correctly rounded from the N-digit solution: data a file can give to mp and exact
modes), and the exact expression in exact mode.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from mechsing.errors import ConfigurationError, TimeLimitExceeded
from mechsing.model import Mechanism
from mechsing.numeric import Precision, parse_precision
from mechsing.timelimit import EXACT_TIME_LIMIT, TimeLimit

__all__ = ["SolveResult", "solve", "value_text"]


@dataclass(frozen=True)
class SolveResult:
    """One configuration closed at ``precision``: every joint's values (``joints``,
    floats; ``joints_text``, text at the solution's precision), the closure residual
    (m), whether the closure was underdetermined (minimum-norm steps) and the Newton
    steps it took."""

    mechanism: str
    configuration: str
    precision: str
    joints: tuple[tuple[str, tuple[float, ...]], ...]
    joints_text: tuple[tuple[str, tuple[str, ...]], ...]
    closure_residual: float
    underdetermined: bool
    steps: int
    #: what the closure says of the values it closed at (a given value moved onto the
    #: limit of travel it lies on to within its resolution, a start at a fold ...)
    notes: tuple[str, ...] = ()

    def to_json(self) -> dict[str, Any]:
        """The JSON of ``mechsing solve --format json`` (keys in this order; added keys
        come last)."""
        return {
            "mechanism": self.mechanism,
            "configuration": self.configuration,
            "precision": self.precision,
            "joints": {k: list(v) for k, v in self.joints},
            "closure_residual": self.closure_residual,
            "underdetermined": self.underdetermined,
            "steps": self.steps,
            "joints_text": {k: list(v) for k, v in self.joints_text},
            "notes": list(self.notes),
        }


def value_text(x: Any, precision: Precision) -> str:
    """A joint value as text at ``precision``: float ``repr`` (round-trips), N significant
    digits at mp:N, the exact expression in exact mode."""
    if precision.mode == "mp":
        import mpmath

        with precision.context():
            return str(mpmath.nstr(mpmath.mpf(x), precision.digits, strip_zeros=False))
    if precision.mode == "exact":
        import sympy

        return sympy.sstr(sympy.sympify(x))
    return repr(float(x))


def solve(
    mech: Mechanism,
    name: str,
    precision: Precision | str = "float",
    time_limit: float | None = None,
) -> SolveResult:
    """Close configuration ``name`` of ``mech`` at ``precision`` (float, mp:N or exact).

    The joints the configuration does not give are solved by continuation from its
    ``start`` (what ``mechsing solve`` prints).

    Parameters
    ----------
    mech : Mechanism
        The mechanism (:func:`mechsing.load`).
    name : str
        One of its configurations.
    precision : Precision or str
        ``"float"``, ``"mp:N"`` or ``"exact"`` (``"auto"`` solves in float).
    time_limit : float or None
        The most seconds the closure may take (None:
        :data:`~mechsing.timelimit.EXACT_TIME_LIMIT` in exact mode, no limit in the
        others); stopped there: a ConfigurationError (exit status 3).

    Returns
    -------
    SolveResult
        Every joint value, as numbers and as text to the precision's digits.
    """
    from mechsing.kinematics import solve_configuration

    prec = parse_precision(precision) if isinstance(precision, str) else precision
    if time_limit is None and prec.mode == "exact":
        time_limit = EXACT_TIME_LIMIT
    try:
        with TimeLimit(time_limit):
            model, closed = solve_configuration(mech, name, prec)
    except TimeLimitExceeded:
        if time_limit is None:  # a caller's limit (modes'): the caller reports it
            raise
        raise ConfigurationError(
            f"configuration {name!r}: stopped by the time limit after {time_limit:g} s before "
            f"it closed at {prec}; allow more time with --time-limit S, or use a lower precision",
            name,
        ) from None
    values = model.values(closed.q)
    mode = model.precision  # auto solves in float
    texts = []
    for jk in model.joints:
        texts.append((jk.name, tuple(value_text(x, mode) for x in closed.q[jk.columns])))
    return SolveResult(
        mechanism=mech.name,
        configuration=name,
        precision=str(model.precision),
        joints=tuple((k, tuple(v)) for k, v in values.items()),
        joints_text=tuple(texts),
        closure_residual=float(closed.residual),
        underdetermined=bool(closed.underdetermined),
        steps=int(closed.steps),
        notes=tuple(closed.notes),
    )
