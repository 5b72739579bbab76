"""The registry of formulations: each problem ``modes`` solves, in the order tried (the
special formulations first, where they are faster or prove more; the general one last).

Owns :data:`FORMULATIONS` and :func:`find`.
"""

from __future__ import annotations

from typing import Any

from mechsing.assembly import axis, chains, general, legs, planar_pose, platform, rod
from mechsing.assembly.given import Formulation, Given
from mechsing.errors import FormulationError, UserError

__all__ = ["FORMULATIONS", "find"]

#: every formulation, the first that applies is used
FORMULATIONS: tuple[Formulation, ...] = (
    planar_pose.FORMULATION,
    platform.FORMULATION,
    legs.FORMULATION,
    chains.SINGLE_LOOP,
    chains.SERIAL_ARM,
    rod.FORMULATION,
    axis.FORMULATION,
    general.FORMULATION,
)


def find(given: Given) -> Any:
    """What the first formulation that applies to ``given`` finds (a
    :class:`~mechsing.assembly.chains.Found`).  A formulation whose ``find`` refuses the
    problem after ``applies`` accepted it (a FormulationError: the planar elimination's
    equations without a common quadratic part, say) hands it to the next one that
    applies; none: a UserError with each one's reason."""
    reasons = []
    for f in FORMULATIONS:
        reason = f.applies(given)
        if reason is None:
            try:
                return f.find(given)
            except FormulationError as exc:
                reason = str(exc)
        reasons.append(f"{f.name} does not apply: {reason}")
    raise UserError(f"{given.where}: no method applies ({'; '.join(reasons)})")
