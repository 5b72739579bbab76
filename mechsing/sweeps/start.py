"""Where a path of a sweep starts: the first sample, reached from the start configuration.

Owns :func:`start_of`: the sample nearest the ``--from`` configuration's value of the
swept coordinate that can be reached from it on its assembly mode (the start may be at a
limit of travel, its nearest samples beyond it), stepping off a singular start along the
path's curve (:func:`off_singular`) or onto one of the branches that cross there
(:func:`onto_branch`, said in the sweep's notes).
"""

from __future__ import annotations

import math

import numpy as np

from mechsing.errors import ClosureError
from mechsing.kinematics.newton import scaled_system
from mechsing.sweeps.arc import Arc, curve_tangent
from mechsing.sweeps.problem import Problem
from mechsing.sweeps.settings import SWEEP_BRANCH_MIN_SWEPT, SWEEP_CURVE_RANK_RTOL
from mechsing.sweeps.spec import Variable

__all__ = ["off_singular", "onto_branch", "start_of"]

#: the samples nearest the start's value tried as the sweep's first (the start may be at a
#: limit of travel, with its nearest samples beyond it)
_START_TRIES = 4
#: the step (commensurate arclength) that leaves a singular start along its curve
_OFF_SINGULAR_STEP = 1e-3
#: a start where branches cross: directions tried over the kernel
_BRANCH_DIRECTIONS = 24


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


def off_singular(pb: Problem, z: np.ndarray, col: int, value: float) -> np.ndarray | None:
    """From a singular start (a fold: continuation has no direction there), a short
    step along the path's curve towards ``value``, then continuation to it."""
    d = 1 if value > z[col] else -1
    arc = Arc(pb, col, d)
    tau = arc.tangent(np.asarray(z, dtype=float))
    if tau is None:
        return None
    for sign in (1.0, -1.0):
        zn = arc.step(np.asarray(z, dtype=float), sign * tau, _OFF_SINGULAR_STEP)
        if zn is None or (zn[col] - z[col]) * d <= 0:
            continue
        # along the curve (near a fold the joints move like the square root of the
        # swept value: continuation in the swept value cannot leave it)
        out = Arc(pb, col, d).to_fold_or(zn, value)
        if out is not None and out[0] == "passed":
            return np.asarray(out[1], dtype=float)
    return None


def onto_branch(
    pb: Problem,
    z: np.ndarray,
    col: int,
    value: float,
    variable: Variable,
    from_config: str,
    notes: list[str],
) -> np.ndarray | None:
    """From a start where branches cross (the curve of the path has a kernel of more
    than one direction there, as at a change-point four-bar's flat position): the
    branches leave along some directions of that kernel.  A short pseudo-arclength
    step is tried along directions spread over it (towards ``value``); the step whose
    corrector moves least lies on a branch, and the path goes on from there to
    ``value`` along the curve.  The branch taken is said in the sweep's notes."""
    d = 1 if value > z[col] else -1
    arc = Arc(pb, col, d)
    z = np.asarray(z, dtype=float)
    Js, _ = scaled_system(pb.cm, z)
    _, s, Vt = np.linalg.svd(Js[:, arc.free], full_matrices=True)
    K = Vt[int(np.sum(s > SWEEP_CURVE_RANK_RTOL * (s[0] if len(s) else 1.0))) :]
    if K.shape[0] < 2:
        return None
    fr = pb.cm.float_frame
    best: tuple[float, np.ndarray] | None = None
    for th in np.linspace(0.0, math.pi, _BRANCH_DIRECTIONS, endpoint=False):
        tau = math.cos(th) * K[0] + math.sin(th) * K[1]
        if abs(tau[arc.cidx]) < SWEEP_BRANCH_MIN_SWEPT:
            continue  # hardly moves the swept value
        tau = tau if tau[arc.cidx] * d > 0 else -tau
        zn = arc.step(z, tau, _OFF_SINGULAR_STEP)
        if zn is None or (zn[col] - z[col]) * d <= 0 or arc.tangent(zn) is None:
            continue
        moved = np.zeros(pb.cm.n)
        moved[arc.free] = _OFF_SINGULAR_STEP * tau
        off = float(np.linalg.norm(fr.rates(pb.cm.difference(zn, z)) - moved))
        if best is None or off < best[0]:
            best = (off, zn)
    if best is None:
        return None
    out = Arc(pb, col, d).to_fold_or(best[1], value)
    if out is None or out[0] != "passed":
        return None
    notes.append(
        f"the start {from_config!r} is a singular point where branches of the path "
        f"cross ({variable.name} = {variable.shown(float(z[col]))}): the path follows one of them; "
        "start from a configuration on a branch (--from) to choose"
    )
    return np.asarray(out[1], dtype=float)
