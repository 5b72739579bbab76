"""Planning a sweep: what it holds, what it solves, where it starts, what it measures.

Owns :func:`plan_sweep` (the :class:`Plan` of one sweep, built once: its float model,
the coordinates it holds and solves, the start's configuration, the closing problem),
:func:`generic_ranks` (each test's generic rank, from the full analysis of the start) and
:func:`check_determined` (a sweep whose path is not a curve is refused before it starts).

Which coordinates a sweep holds: a sweep of joint coordinates that are all inputs holds
the other inputs at their ``--from`` values and solves the passive joints; a sweep of a
joint that is not an input lets it drive the mechanism alone (the inputs are solved
with the passive joints); a sweep of the output's pose holds the other pose coordinates
and solves every joint (the inverse kinematics of a parallel robot).  A mechanism
without loops solves nothing: every other coordinate keeps its ``--from`` value.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from mechsing.analysis import analyze
from mechsing.errors import UserError
from mechsing.kinematics import Closer, KinematicModel
from mechsing.kinematics.batch_newton import BatchClosure
from mechsing.kinematics.newton import scaled_jacobian
from mechsing.kinematics.paths.problem import Problem
from mechsing.kinematics.pose import PoseModel
from mechsing.lie import log_so3
from mechsing.model import Mechanism
from mechsing.model.couplings import describe_coupling
from mechsing.numeric import to_float
from mechsing.sweeps.limits import LimitedCoordinate, limited_coordinates
from mechsing.sweeps.settings import SWEEP_DETERMINED_RTOL
from mechsing.sweeps.spec import Variable

__all__ = ["GenericRanks", "Plan", "check_determined", "generic_ranks", "plan_sweep"]


@dataclass
class Plan:
    """One sweep's plan: the start configuration's name, the float model, the
    coordinates with limits, whether the output's pose is swept, the swept columns of the
    sweep's coordinates (joints, then the pose's for a pose sweep), the start's
    coordinates, the closing problem, each test's generic rank and the generic mobility."""

    from_config: str
    model: KinematicModel
    limited: list[LimitedCoordinate]
    pose: bool
    cols: list[int]
    z0: np.ndarray
    problem: Problem
    generic: dict[str, int | None]
    generic_mobility: int | None


class GenericRanks(NamedTuple):
    """Each test's generic rank at the start (a test the file cannot run is absent) and
    the mechanism's generic mobility there (None where not decided)."""

    ranks: dict[str, int | None]
    mobility: int | None


def plan_sweep(mech: Mechanism, variables: list[Variable], from_config: str | None) -> Plan:
    """The plan of a sweep of ``variables`` from the configuration ``from_config``
    (default ``reference``); :class:`~mechsing.errors.UserError` for a configuration the
    file lacks or a coupled pair swept together."""
    from_config = from_config or "reference"
    if from_config not in mech.configurations:
        raise UserError(
            f"{mech.path or mech.name}: --from {from_config!r}: no such configuration; "
            f"the file has: {', '.join(mech.configurations)}"
        )
    model = KinematicModel(mech, "float")
    limited = limited_coordinates(mech)
    closer = Closer(model)
    q0 = np.asarray(to_float(closer.solve(from_config).q), dtype=float)
    pose = variables[0].kind == "pose"
    n = model.n
    if pose:
        c0 = [float(x) for x in to_float(np.array(mech.output_reference_point(), dtype=object))]
        cm: Any = PoseModel(model, c0, np.eye(3))
        g = cm.output_pose(np.concatenate([q0, np.zeros(6)]))
        r0 = log_so3(g[:3, :3])
        x0 = g[:3, :3] @ np.array(c0) + g[:3, 3]
        z0 = np.concatenate([q0, r0, x0])
        given = np.zeros(cm.n, dtype=bool)
        given[n:] = True
        cols = [n + v.column for v in variables]
        if mech.output is not None and mech.output.point is not None:
            # a point output has no rotation: the point's coordinates are held, its body's
            # rotation follows (unless swept)
            given[n : n + 3] = False
            given[[c for c in cols if c < n + 3]] = True
    else:
        cm = model
        z0 = q0
        cols = [v.column for v in variables]
        inputs = {model.joint(j).columns.start + i for j, i in mech.input_coordinates()}
        given = np.zeros(n, dtype=bool)
        if not mech.loops:
            given[:] = True
        elif set(cols) <= inputs:
            given[list(inputs)] = True
        given[cols] = True
        for ck in model.couplings:
            # a coupled joint follows its swept partner (never held against it)
            swept = {ck.follower, ck.leader} & set(cols)
            if len(swept) == 2:
                c = ck.coupling
                raise UserError(
                    f"--vary: joint {c.joint!r} is coupled to {c.leader!r} "
                    f"({describe_coupling(c)}): sweep one of them, the other follows"
                )
            for k in {ck.follower, ck.leader} - swept if swept else ():
                given[k] = False
    periodic = np.zeros(cm.n, dtype=bool)
    for v, c in zip(variables, cols, strict=True):
        periodic[c] = v.periodic
    problem = Problem(
        model,
        cm,
        given,
        closer,
        BatchClosure(cm),
        model.precision.closure_tolerance(model.length_scale),
        periodic,
    )
    generic = generic_ranks(mech, from_config, model.n)
    return Plan(
        from_config,
        model,
        limited,
        pose,
        cols,
        z0,
        problem,
        generic.ranks,
        generic.mobility,
    )


def check_determined(plan: Plan, mech: Mechanism, variables: list[Variable]) -> None:
    """A sweep whose path is not a curve is refused before it starts: holding the
    given coordinates must leave one degree of freedom to the swept one (a joint
    sweep), and the output must be able to move along a swept pose coordinate with
    the rest of its pose held (:class:`~mechsing.errors.UserError` otherwise)."""

    pb = plan.problem
    names = ", ".join(v.name for v in variables)
    M = plan.generic_mobility
    if not mech.loops or M is None:
        return
    if not plan.pose:
        g = int(np.sum(pb.given))
        inputs = ", ".join(mech.coordinate_label(j, i) for j, i in mech.input_coordinates())
        if g < M:
            raise UserError(
                f"--vary {names}: with the other coordinates solved, the mechanism keeps "
                f"{M - g} more degree(s) of freedom (its mobility is {M}), so the sweep's path "
                "is not determined; sweep an input of the file"
                + (f" ({inputs}): the others are then held" if inputs else "")
                + ", or declare inputs (inputs: [...]) so that the sweep holds them"
            )
        if g > M:
            coords = list(mech.coordinates())
            fixed = [
                mech.coordinate_label(j, i)
                for (j, i), given in zip(coords, pb.given, strict=True)
                if given
            ]
            swept = {v.name for v in variables}
            held = [c for c in fixed if c not in swept]
            what = f"swept ({names})" + (f" and held ({', '.join(held)})" if held else "")
            raise UserError(
                f"--vary {names}: the coordinates {what} are {g} for a mechanism of "
                f"mobility {M}: they cannot all move independently, so the path is "
                f"over-determined; sweep at most {M} independent coordinate(s)"
                + (f", such as the file's inputs ({inputs})" if inputs else "")
            )
        return
    Js = scaled_jacobian(pb.cm, plan.z0)
    free = ~pb.given
    A = Js[:, free]
    for v, c in zip(variables, plan.cols, strict=True):
        B = np.concatenate([A, Js[:, [c]]], axis=1)
        sa = np.linalg.svd(A, compute_uv=False)
        sb = np.linalg.svd(B, compute_uv=False)
        ra = int(np.sum(sa > SWEEP_DETERMINED_RTOL * sb[0]))
        rb = int(np.sum(sb > SWEEP_DETERMINED_RTOL * sb[0]))
        if rb > ra:
            raise UserError(
                f"--vary {v.name}: the output {mech.output.body!r} cannot move along "
                f"{v.name} with the rest of its pose held (its motion at {plan.from_config!r} "
                "does not contain that direction: the mechanism moves its output in a "
                "smaller set of displacements); sweep a pose coordinate the output can "
                "move along, or a joint"
            )


def generic_ranks(mech: Mechanism, from_config: str, n: int) -> GenericRanks:
    """Each test's generic rank, from the full float analysis of the start (and the
    mechanism's generic mobility there); ``n``: the model's number of coordinates."""
    res = analyze(mech, [from_config], "float").configurations[0]
    dec = {d.test: d for d in res.decisions}
    out: dict[str, int | None] = {}
    mobility = res.mobility.generic if res.mobility is not None else None
    if mech.loops and res.mobility is not None and res.mobility.generic is not None:
        out["closure"] = n - res.mobility.generic
    for test, name in (("input", "impossible-output"), ("output", "impossible-input")):
        if name in dec:
            out[test] = dec[name].generic
    if "output chain" in dec:  # no loop: T N is the output chain's matrix
        out["input"] = dec["output chain"].generic
        out["output"] = len(mech.input_coordinates()) or None
    if "constraint" in dec:
        out["constraint"] = dec["constraint"].generic
    return GenericRanks(out, mobility)
