"""Where a path of a sweep starts: the first sample, reached from the start configuration.

Owns :func:`start_of`: the sample nearest the ``--from`` configuration's value of the
swept coordinate that can be reached from it on its assembly mode (the start may be at a
limit of travel, its nearest samples beyond it), stepping off a singular start along the
path's curve (:func:`off_singular`) or onto one of the branches that cross there
(:func:`onto_branch`, said in the sweep's notes).
"""

from __future__ import annotations

import numpy as np

from mechsing.errors import ClosureError
from mechsing.kinematics.paths.arc import curve_tangent, off_singular
from mechsing.kinematics.paths.arc import onto_branch as branch_of
from mechsing.kinematics.paths.problem import Problem
from mechsing.sweeps.spec import Variable

__all__ = ["off_singular", "onto_branch", "start_of"]

#: the samples nearest the start's value tried as the sweep's first (the start may be at a
#: limit of travel, with its nearest samples beyond it)
_START_TRIES = 4


def start_of(
    pb: Problem,
    col: int,
    values: np.ndarray,
    z: np.ndarray,
    variable: Variable,
    from_config: str,
    notes: list[str],
) -> tuple[int, np.ndarray]:
    """The sample nearest z's value of ``col`` that can be reached from z (the start
    may be at a limit of travel, its nearest sample beyond it), and its configuration."""
    order = np.argsort(np.abs(values - z[col]), kind="stable")
    k0 = int(order[0])
    if z[col] == values[k0]:
        if curve_tangent(pb, np.asarray(z, dtype=float), col) is not None:
            return k0, np.array(z, dtype=float)
        # a start where branches cross (a bifurcation): onto one of them
        for k in (k0 + 1, k0 - 1):
            if 0 <= k < len(values):
                off = onto_branch(pb, z, col, float(values[k]), variable, from_config, notes)
                if off is not None:
                    return k, off
        return k0, np.array(z, dtype=float)
    first: ClosureError | None = None
    for k in order[:_START_TRIES]:
        try:
            return int(k), pb.reach(z, col, values[k])
        except ClosureError as exc:
            first = first or exc
        # a start at a fold or another singular point: step off it along the curve
        off = off_singular(pb, z, col, float(values[k]))
        if off is None:
            off = onto_branch(pb, z, col, float(values[k]), variable, from_config, notes)
        if off is not None:
            return int(k), off
    assert first is not None
    why = str(first).split(": ", 1)[-1]
    raise ClosureError(
        f"the sweep cannot start: none of the {min(_START_TRIES, len(values))} samples of "
        f"{variable.name} nearest its value at {from_config!r} ({variable.shown(z[col])}) can be "
        f"reached from that configuration on its assembly mode ({why}); start from another "
        "configuration (--from) or sweep a range that contains the start's value",
        from_config,
        first.residual,
    ) from None


def onto_branch(
    pb: Problem,
    z: np.ndarray,
    col: int,
    value: float,
    variable: Variable,
    from_config: str,
    notes: list[str],
) -> np.ndarray | None:
    """From a start where branches cross, onto one of them towards ``value``
    (:func:`~mechsing.kinematics.paths.arc.onto_branch`); the branch taken is said in
    the sweep's notes."""
    out = branch_of(pb, z, col, value)
    if out is None:
        return None
    notes.append(
        f"the start {from_config!r} is a singular point where branches of the path "
        f"cross ({variable.name} = {variable.shown(float(z[col]))}): the path follows one of them; "
        "start from a configuration on a branch (--from) to choose"
    )
    return out
