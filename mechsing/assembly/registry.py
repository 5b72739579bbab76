"""The registry of formulations: each problem ``modes`` solves, in the order tried (the
special formulations first, where they are faster or prove more; the general one last).

Owns :data:`FORMULATIONS` and :func:`choose`.
"""

from __future__ import annotations

from mechsing.assembly import chains, general, planar_pose, platform
from mechsing.assembly.given import Formulation, Given
from mechsing.errors import UserError

__all__ = ["FORMULATIONS", "choose"]

#: every formulation, the first that applies is used
FORMULATIONS: tuple[Formulation, ...] = (
    planar_pose.FORMULATION,
    platform.FORMULATION,
    chains.SINGLE_LOOP,
    chains.SERIAL_ARM,
    general.FORMULATION,
)


def choose(given: Given) -> Formulation:
    """The first formulation that applies to ``given``; none: a UserError with each one's
    reason."""
    reasons = []
    for f in FORMULATIONS:
        reason = f.applies(given)
        if reason is None:
            return f
        reasons.append(f"{f.name} does not apply: {reason}")
    raise UserError(f"{given.where}: no method applies ({'; '.join(reasons)})")
