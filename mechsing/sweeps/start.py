"""Where a path of a sweep starts: the first sample, reached from the start configuration.

Owns :func:`mode_start` (the start on an assembly mode that ``mechsing modes`` found,
instead of the one continuation reaches from the start configuration) and :func:`start_of`: the sample nearest the ``--from`` configuration's value of the
swept coordinate that can be reached from it on its assembly mode (the start may be at a
limit of travel, its nearest samples beyond it), stepping off a singular start along the
path's curve (:func:`off_singular`) or onto one of the branches that cross there
(:func:`onto_branch`, said in the sweep's notes).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechsing.errors import ClosureError, UserError
from mechsing.kinematics.closed import FLOAT_DIGITS, ClosedValue
from mechsing.kinematics.paths.arc import curve_tangent, off_singular
from mechsing.kinematics.paths.arc import onto_branch as branch_of
from mechsing.kinematics.paths.problem import Problem
from mechsing.kinematics.settings import CONTINUATION_SINGULAR_RTOL
from mechsing.model import Mechanism
from mechsing.numeric.tolerances import SWEEP_SAME_MODE_DISTANCE
from mechsing.sweeps.spec import Variable

if TYPE_CHECKING:
    from mechsing.assembly.result import ModesResult

__all__ = ["mode_out_of_range", "mode_start", "off_singular", "onto_branch", "start_of"]


def mode_out_of_range(k: int, config: str, count: int) -> UserError:
    """The error of ``--mode k`` when configuration ``config`` has ``count`` modes."""
    see = f"(mechsing modes FILE --config {config})"
    if count == 0:
        return UserError(f"--mode {k}: configuration {config!r} has no real assembly mode {see}")
    if count == 1:
        return UserError(
            f"--mode {k}: configuration {config!r} has 1 assembly mode {see}; give --mode 1 "
            "or leave --mode out"
        )
    return UserError(
        f"--mode {k}: configuration {config!r} has {count} assembly modes {see}; give "
        f"--mode 1 to {count}"
    )


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
        tangent = curve_tangent(pb, np.asarray(z, dtype=float), col)
        if tangent is not None:
            if abs(tangent[col]) <= CONTINUATION_SINGULAR_RTOL:
                # a start at a fold of the swept value (a dead centre: the curve's tangent
                # has no swept part, both its ways go to one side): left along the curve
                # to the nearest sample on that side
                for k in (k0 - 1, k0 + 1):
                    if 0 <= k < len(values):
                        off = off_singular(pb, z, col, float(values[k]))
                        if off is not None:
                            return k, off
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


def mode_start(
    mech: Mechanism, eng: Any, start: Any, found: ModesResult | None = None
) -> tuple[int, np.ndarray, ClosedValue]:
    """The number (its index plus 1, as ``mechsing modes`` numbers them), the coordinates
    and the frozen value (:class:`~mechsing.kinematics.closed.ClosedValue`, handed on
    unchanged) of the assembly mode a sweep starts on: ``start`` is an item of
    ``mechsing.modes(mech, from_config).modes``, its ``point`` or its index there
    (``found``: that result when it is already computed).  A sweep of the output's pose
    holds the pose, not the inputs, so it has no modes of the inputs to start on
    (UserError)."""
    from mechsing.assembly.api import modes
    from mechsing.assembly.result import Mode, joint_distance

    if eng.pose:
        raise UserError(
            "--mode/--modes: a sweep of the output's pose solves every joint for the pose; "
            "the assembly modes are those of the inputs: sweep joint coordinates (the inputs)"
        )
    if found is None:
        found = modes(mech, eng.from_config, "float")
    listed = found.modes
    given = start.point if isinstance(start, Mode) and start.point is not None else start
    if isinstance(given, ClosedValue) and given.source != "mode":
        raise UserError(
            f"start: the value given comes from a {given.source} configuration, not an "
            "assembly mode; give an item of mechsing.modes(...).modes, its point, or its index"
        )
    if isinstance(start, bool) or not isinstance(start, int | np.integer | Mode | ClosedValue):
        raise UserError(
            f"start={start!r}: give an assembly mode (an item of mechsing.modes(...).modes) "
            "or its index"
        )
    coords = mech.coordinates()
    L = float(eng.model.length_scale)
    if isinstance(start, Mode | ClosedValue):
        q = (
            list(given.floats())
            if isinstance(given, ClosedValue)
            else [float(start.joints[j][i]) for j, i in coords]
        )
        near = [
            k
            for k, m in enumerate(listed)
            if joint_distance(mech, q, [float(m.joints[j][i]) for j, i in coords], L)
            <= SWEEP_SAME_MODE_DISTANCE
        ]
        if not near:
            raise UserError(
                f"the mode given is not one of the {len(listed)} assembly modes of "
                f"{eng.from_config!r}; give one of mechsing.modes(mechanism, "
                f"{eng.from_config!r}).modes, or --from the configuration it was found at"
            )
        index = near[0]
    else:
        index = int(start)
        if not 0 <= index < len(listed):
            raise mode_out_of_range(index + 1, eng.from_config, len(listed))
    mode = listed[index]
    value = given if isinstance(given, ClosedValue) else mode.point
    if value is None:  # a Mode built by hand, without its value
        value = ClosedValue(
            [float(mode.joints[j][i]) for j, i in coords],
            FLOAT_DIGITS,
            "mode",
            f"{eng.from_config}#mode{index + 1}",
            mode.certified,
        )
    q = np.array([float(mode.joints[j][i]) for j, i in coords])
    z = np.array(eng.z0, dtype=float)
    z[: len(q)] = q
    return index + 1, z, value
