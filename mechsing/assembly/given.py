"""What a ``modes`` call is given, read once: the mechanism, the configuration, its given
joint values (the inputs), the output's pose (a serial arm's target, or a parallel
mechanism's: its working modes), the start
continuation marks a mode from, and the family of the mechanism; and the contract of a
formulation (:class:`Formulation`: ``applies(given)``, ``find(given)``).

Owns :class:`Given`, :func:`read_given`, :func:`closure_from_start`,
:func:`travel_of_start` and :class:`Formulation`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import sympy

from mechsing.assembly.settings import REACHED_DIGITS
from mechsing.errors import UserError
from mechsing.model import Mechanism
from mechsing.numeric import Precision

__all__ = [
    "NO_INPUTS",
    "Formulation",
    "Given",
    "closure_from_start",
    "read_given",
    "travel_of_start",
]

#: why a formulation of given joint values does not apply to a configuration that gives
#: the output's pose (a serial arm's, or a mechanism with loops at a pose)
NO_INPUTS = "the configuration gives the output's pose, not inputs"


@dataclass
class Given:
    """One ``modes`` call's data: ``values`` the given joint values (exact; None for a
    mechanism without loops, whose configuration gives the output's pose or every joint,
    read by the serial formulations, and for a mechanism with loops whose configuration
    gives the output's pose, read by the general formulation), ``refusal`` why the
    configuration's values are not inputs (None: they are), ``dps`` the digits the modes
    are found at, ``atol`` how far from orthonormal a given rotation may be; ``cache`` what one formulation's
    ``applies`` built for its ``find``."""

    mech: Mechanism
    config: str
    prec: Precision
    dps: int
    atol: Any
    values: dict[str, tuple[Any, ...]] | None
    refusal: str | None = None
    cache: dict[str, Any] = field(default_factory=dict)

    @property
    def where(self) -> str:
        return f"{self.mech.path or self.mech.name}: configuration {self.config!r}"

    @property
    def family(self) -> Any:
        """The mechanism's family (:func:`mechsing.kinematics.family.family`), decided once."""
        if "family" not in self.cache:
            from mechsing.kinematics.family import family

            self.cache["family"] = family(self.mech)
        return self.cache["family"]

    @property
    def closure(self) -> tuple[Any, str | None]:
        """Continuation's closure from the configuration's start, computed once
        (:func:`closure_from_start`)."""
        if "closure" not in self.cache:
            self.cache["closure"] = closure_from_start(self.mech, self.config)
        return self.cache["closure"]


@dataclass(frozen=True)
class Formulation:
    """One problem's formulation: its ``name``, ``applies(given)`` (None when it applies,
    else the reason it does not, in words) and ``find(given)`` (a
    :class:`~mechsing.assembly.chains.Found`)."""

    name: str
    applies: Callable[[Given], str | None]
    find: Callable[[Given], Any]


def read_given(
    mech: Mechanism, config: str, prec: Precision, dps: int, atol: Any, start: str | None = None
) -> Given:
    """The record of one call (``start``: the configuration continuation starts from, None
    for the configuration's own)."""
    if start is not None:
        mech = _started_from(mech, config, start)
    if not mech.loops or mech.configurations[config].pose is not None:
        # a serial arm: the output's pose (given, or reached) is what is given; loops and
        # the output's pose: the legs' postures reaching it (working modes)
        return Given(mech, config, prec, dps, atol, None, _values(mech, config)[1])
    values, refusal = _values(mech, config)
    if refusal is not None:
        raise UserError(f"{mech.path or mech.name}: {refusal}")
    return Given(mech, config, prec, dps, atol, values)


def _values(mech: Mechanism, config: str) -> tuple[dict[str, tuple[Any, ...]], str | None]:
    """The configuration's given joint values (exact), and why they are not the inputs
    of a set of modes (None: they are)."""
    from mechsing.model.mechanism import Displacement

    cfg = mech.configurations[config]
    if cfg.pose is not None:
        return {}, (
            f"configuration {config!r} gives the output's pose: modes takes given joint "
            "values (the inputs); give them with --set JOINT=VALUE"
        )
    out = {}
    for name, v in cfg.values.items():
        if isinstance(v, Displacement):
            return {}, (
                f"configuration {config!r}: joint {name} is given as a displacement; "
                "modes takes joint values"
            )
        out[name] = tuple(
            sympy.nsimplify(x) if isinstance(x, float) else sympy.sympify(x) for x in v
        )
    inputs = {ref.joint for ref in mech.inputs}
    if inputs and inputs <= set(out) and set(out) - inputs:
        # every value given: the modes share the inputs' values (the rest is one of them)
        out = {name: v for name, v in out.items() if name in inputs}
    if not out:
        return {}, (
            f"configuration {config!r} gives no joint value: the closed configurations form "
            "the whole configuration space, not a finite set of modes; give the inputs "
            "(--set JOINT=VALUE)"
        )
    return out, None


def _started_from(mech: Mechanism, config: str, start: str) -> Mechanism:
    """``mech`` with configuration ``config`` continued from ``start``."""
    where = mech.path or mech.name
    if start not in mech.configurations:
        raise UserError(
            f"{where}: --from {start!r}: no such configuration; the file has: "
            f"{', '.join(mech.configurations)}"
        )
    cur: str | None = start
    while cur is not None:
        if cur == config:
            raise UserError(
                f"{where}: --from {start!r}: it starts from {config!r} itself (a cycle); "
                "choose a configuration that does not"
            )
        cur = mech.configurations[cur].start
    cfg = dataclasses.replace(mech.configurations[config], start=start)
    return dataclasses.replace(mech, configurations={**mech.configurations, config: cfg})


def closure_from_start(
    mech: Mechanism, config: str, precision: str = "float"
) -> tuple[Any, str | None]:
    """Where continuation from the configuration's start closes it (``solve`` in float,
    or at ``precision``), or why it does not: (the SolveResult or None, the reason or
    None).  Computed once per ``modes``: the formulations test it as a posture, the result
    marks the mode it is."""
    from mechsing.analysis.solve import solve
    from mechsing.errors import ConfigurationError, UserError

    try:
        return solve(mech, config, precision), None
    except (ConfigurationError, UserError) as exc:
        return None, str(exc)


def travel_of_start(mech: Mechanism, config: str) -> str | None:
    """Where the start's assembly mode ends, when the configuration's given values lie
    beyond it: the sentence that says which value, by how much, and where its limit is
    (continuation from the start in float stops at that limit of travel; far beyond it,
    the value continuation reached, past which the limit lies); None otherwise.  What
    ``modes`` says with a count of 0."""
    from mechsing.analysis.solve import solve
    from mechsing.errors import BeyondTravelError, ConfigurationError, UserError

    # float closes values a hair beyond a fold (1e-13 rad) to its tolerance: more digits
    # tell that they are beyond
    for precision in ("float", f"mp:{REACHED_DIGITS}"):
        try:
            solve(mech, config, precision)
        except BeyondTravelError as exc:
            return exc.travel
        except (ConfigurationError, UserError):
            return None
    return None
