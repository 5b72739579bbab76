"""Six unknown joints in one chain: a serial arm for the output's pose, or a single loop
for its given joint values, both solved by the half-angle formulation (:mod:`.serial`).

A single loop (every joint of the file on it, each R or P) closes when the product of its
joints' displacements around it is the identity, ``prod_i exp(q_i xi_i)^(sign_i) = 1``
(the reference configuration, all values 0, closes it).  A given joint's factor is a
constant ``C``; moved past the joints after it (``X C = C (C* X C)``: each later joint's
line conjugated), the constants gather at the end, and with exactly six joints unknown
the loop is a six-joint chain reaching ``T = C*``: a general 7R with one input is the
general 6R arm (H.-Y. Lee and C.-G. Liang, Mech. Mach. Theory 23(3), 1988: at most 16).

The chains the general formulation closes on a target are defined here too: a serial
arm's (:func:`arm_chain`), and those of a mechanism with loops whose configuration
gives the output's pose (:func:`pose_chains`: each serial leg to the pose).

Owns :class:`Found` (what a formulation found),
:func:`serial_found`, :func:`loop_found`, the two registered problems
:data:`SERIAL_ARM` and :data:`SINGLE_LOOP`, and the chains above.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import mpmath

from mechsing.assembly.given import NO_INPUTS, Formulation, Given, closure_from_start
from mechsing.assembly.settings import MODE_CERTIFY_RADIUS
from mechsing.model import Mechanism
from mechsing.model.mechanism import Displacement

__all__ = [
    "SERIAL_ARM",
    "SINGLE_LOOP",
    "Found",
    "arm_chain",
    "loop_found",
    "pose_chains",
    "serial_found",
]


@dataclass(frozen=True)
class Found:
    """What a formulation and its method found: the formulation's JSON, the modes' joint
    coordinates (the file's order) with their certification, what the count claims, the
    paths' account, notes, how many joint-space solutions each mode stands for, and
    continuation's closure from the start when the formulation already has it."""

    formulation: dict[str, Any]
    rows: list[tuple[list[Any], bool]]
    count: int | None
    complete: str
    paths: dict[str, Any] | None
    notes: tuple[str, ...]
    equivalent: int = 1
    #: continuation's closure from the start, when the formulation computed it
    #: (:func:`~mechsing.assembly.given.closure_from_start`: the result or None, the reason it failed or None)
    closure: tuple[Any, str | None] | None = None


def _length(mech: Mechanism) -> float:
    from mechsing.kinematics import KinematicModel

    return float(KinematicModel(mech, "float").length_scale)


def serial_found(mech: Mechanism, config: str, dps: int, atol: Any, closure: Any = None) -> Found:
    """The postures of a serial arm for the pose configuration ``config`` gives (with, for
    an arm of more than six joints, the values of all but six), or for a six-joint arm the
    pose its joints reach (then they are tested as one of the modes); ``atol``: how far
    from orthonormal a given rotation matrix may be."""
    from mechsing.assembly.serial import (
        arm_chain,
        given_solution,
        pose_target,
        serial_arm,
        serial_target,
        six_joint_chain,
    )

    cfg = mech.configurations[config]
    L = _length(mech)
    names, signs = arm_chain(mech)
    notes = []
    if cfg.pose is not None and len(names) > 6:
        given = {n: cfg.values[n] for n in names if n in cfg.values}
        target = pose_target(mech, config, L, atol)
        arm, target = six_joint_chain(mech, names, signs, given, target, L)
        values = {n: v[0] for n, v in given.items()}
        return _found(
            mech,
            config,
            arm,
            target,
            values,
            dps,
            None,
            notes,
            "serial arm",
            "output's pose",
            closure,
        )
    arm = serial_arm(mech, L)
    target, from_joints = serial_target(mech, config, arm, atol)
    if from_joints:
        notes.append(
            f"configuration {config!r} gives joint values, not the output's pose: its modes "
            "are the arm's postures that reach the pose of its joints (given, or its start's)"
        )
    own = (lambda system: given_solution(mech, config, system)) if from_joints else None
    return _found(
        mech, config, arm, target, {}, dps, own, notes, "serial arm", "output's pose", closure
    )


def loop_found(
    mech: Mechanism,
    config: str,
    given: dict[str, tuple[Any, ...]],
    dps: int,
    closure: Any = None,
) -> Found:
    """The assembly modes of a single loop with six joints left unknown by ``given``."""
    from mechsing.assembly.serial import loop_arm

    arm, target = loop_arm(mech, given, _length(mech))
    values = {n: v[0] for n, v in given.items()}
    return _found(
        mech, config, arm, target, values, dps, None, [], "single loop", "given values", closure
    )


def _found(
    mech: Mechanism,
    config: str,
    arm: Any,
    target: list[Any],
    given: dict[str, Any],
    dps: int,
    own: Any,
    notes: list[str],
    what: str,
    fixed: str,
    closure: Any = None,
) -> Found:
    """Solve, test the configuration's own joints (``own``: their pairs and values, for
    an arm given by its joints), certify, and say what the count claims."""
    from mechsing.assembly.certify import krawczyk, newton, regular, singular_root
    from mechsing.assembly.serial import (
        already_found,
        joint_values_serial,
        serial_system,
        solve_serial,
    )

    system = serial_system(arm, target)
    found, paths, curve, solutions = solve_serial(system, dps)
    # the configuration's own joints (given) and continuation's closure from its start
    # are modes too: where one is a singular root, the local dimension test decides there
    # (continuation's endpoints on a curve of solutions are complex, so they cannot); one
    # the homotopy missed makes the count not proven
    missed = False
    closure = closure or closure_from_start(mech, config)
    for pairs, exact in _candidates(arm, system, own, closure[0]):
        if curve is not None:
            break
        root = pairs if exact else newton(system.square, system.gens, pairs, dps)
        if root is not None and regular(system.square, system.gens, root):
            q = joint_values_serial(system, root)
            if not already_found(arm, q, found):
                found, missed = [*found, (root, q, True)], True
            continue
        root, on_curve = singular_root(system.square, system.gens, pairs, dps)
        if root is None:
            continue
        q = joint_values_serial(system, root)
        if on_curve:
            curve = ", ".join(f"{n} = {float(v):.6g}" for n, v in zip(arm.joints, q, strict=True))
        elif not already_found(arm, q, found):
            found = [*found, (root, q, False)]
    if missed:
        notes.append(
            "continuation from the configuration's start closes at a regular mode the "
            "homotopy's paths missed (added): the count is not proven"
        )
    unknowns = []
    for i in system.outer:
        n = arm.joints[i]
        unknowns += (
            [f"cos({n}/2)", f"sin({n}/2)"] if arm.kinds[i] == "R" else [f"1 ({n})", f"{n}/(2L)"]
        )
    formulation = {
        "name": f"half-angle pairs of a {what}",
        "method": "homotopy continuation (Bertini 2, multihomogeneous start), Newton refinement",
        "unknowns": unknowns,
        "joints": list(arm.joints),
        "pair": [arm.joints[i] for i in system.middle],
        "polynomial_degree": 4,
        "bezout": paths["tracked"],
        "generic_count": arm.generic_count,
        "generic_count_reason": arm.pieper
        or "six unknown joints in a chain have at most 16 (Lee & Liang 1988, Raghavan & Roth 1993)",
    }
    if curve is not None:
        notes.append(
            f"the {fixed} is reached along a curve of joint values (a self-motion at a "
            f"singularity, through {curve}): the modes are not finitely many"
        )
        return Found(formulation, [], None, "infinite", paths, tuple(notes), 1, closure)
    radius = mpmath.mpf(MODE_CERTIFY_RADIUS)
    rows = []
    for pairs, q, is_regular in found:
        ok = is_regular and krawczyk(system.square, system.gens, pairs, radius)
        values = {**given, **dict(zip(arm.joints, q, strict=True))}
        rows.append(([values[name] for name, _ in mech.coordinates()], ok))
    complete = _claim(arm, system, paths, rows, solutions, dps, notes)
    if missed:
        complete = "not proven"
    return Found(formulation, rows, len(rows), complete, paths, tuple(notes), 1, closure)


def _candidates(arm: Any, system: Any, own: Any, closed: Any) -> list[tuple[list[Any], bool]]:
    """Postures known before the homotopy: the configuration's own joints (``own``:
    exact) and where continuation from its start closes (``closed``: float), as outer
    pairs."""
    from mechsing.assembly.serial import pairs_of

    out = []
    if own is not None:
        out.append((own(system)[0], True))
    if closed is not None:
        values = dict(closed.joints)
        out.append((pairs_of(system, [mpmath.mpf(values[n][0]) for n in arm.joints]), False))
    return out


def _claim(
    arm: Any,
    system: Any,
    paths: dict[str, Any],
    rows: list[tuple[list[Any], bool]],
    solutions: list[Any],
    dps: int,
    notes: list[str],
) -> str:
    """``maximal`` when the real modes, all certified, are the most the chain can have,
    or when every solution, real and complex, is certified distinct and they are that
    many (then none is missing); else ``not proven``, with the notes that say why."""
    from mechsing.assembly.serial import all_certified

    most = arm.generic_count
    certified = all(ok for _, ok in rows) and not paths["singular"]
    complete = "not proven"
    if certified and len(rows) == most:
        complete = "maximal"
    elif certified and paths["solutions"] == most and system.skew:
        # (with a pair that is not skew the rank-one condition's real and imaginary parts
        # are too large an interval system to certify in reasonable time)
        if all_certified(system, solutions, dps) == len(rows):
            complete = "maximal"
            notes.append(
                f"all {most} solutions, real and complex, are certified and distinct: the "
                f"most this chain has, so no real mode is missing ({len(rows)} are real)"
            )
    if complete != "maximal" and paths["solutions"] == most:
        notes.append(
            f"continuation found {most} solutions in all (real and complex), the most this "
            "chain can have: only the real ones are modes"
        )
    if paths["singular"]:
        notes.append(
            f"{paths['singular']} of continuation's endpoints are singular (multiple roots, "
            "or points of a curve of solutions): the count is not proven"
        )
    return complete


def _serial_applies(given: Given) -> str | None:
    from mechsing.assembly.serial import arm_chain
    from mechsing.errors import FormulationError

    try:
        names, _ = arm_chain(given.mech)
    except FormulationError as reason:
        return str(reason)
    cfg = given.mech.configurations[given.config]
    if len(names) > 6 and cfg.pose is None:
        return (
            f"the arm has {len(names)} joints: give the output's pose and {len(names) - 6} "
            "joint values (a redundant arm reaches a pose alone along a curve)"
        )
    return None


def _serial_find(given: Given) -> Found:
    return serial_found(given.mech, given.config, given.dps, given.atol, given.closure)


def _loop_applies(given: Given) -> str | None:
    from mechsing.assembly.serial import loop_arm
    from mechsing.errors import FormulationError

    if given.values is None:
        return NO_INPUTS
    try:
        given.cache["loop"] = loop_arm(given.mech, given.values, _length(given.mech))
    except FormulationError as reason:
        return str(reason)
    return None


def _loop_find(given: Given) -> Found:
    return loop_found(given.mech, given.config, given.values, given.dps, given.closure)


#: a serial arm of six R or P joints (or more, with all but six given) for the output's pose
SERIAL_ARM = Formulation("half-angle pairs of a serial arm", _serial_applies, _serial_find)
#: a single loop of R and P joints whose given values leave six unknown
SINGLE_LOOP = Formulation("half-angle pairs of a single loop", _loop_applies, _loop_find)


def arm_chain(given: Given) -> tuple[list[tuple[list[str], list[int], Any]], dict[str, list[Any]]]:
    """A serial arm's chain to its output, its given joints and what its target is (the
    configuration's pose, or the joint values whose pose it is)."""
    from mechsing.assembly.serial import chain_to_output

    mech, config = given.mech, given.config
    names, signs = chain_to_output(mech)
    cfg = mech.configurations[config]
    if cfg.pose is not None:
        values = {n: _written(cfg.values[n]) for n in names if n in cfg.values}
        return [(names, signs, "pose")], values
    return [(names, signs, {n: arm_values(mech, config, n) for n in names})], {}


def pose_chains(
    given: Given,
) -> tuple[list[tuple[list[str], list[int], Any]], dict[str, list[Any]]]:
    """A mechanism with loops whose configuration gives the output's pose: each of its
    legs, a serial chain from the output's ``relative_to`` body to the output body,
    closed on the pose (as ``solve`` adds the pose: a rigid chord between the two; the
    loops between legs then close), with the joint values the configuration also gives.
    A leg that is not one chain (a loop of its own), or a joint on no leg: refused."""
    from mechsing.errors import FormulationError

    mech, config = given.mech, given.config
    out = mech.output
    if out is None:
        raise FormulationError("the file has no output: the pose is nobody's")
    cfg = mech.configurations[config]
    values = {n: _written(v) for n, v in cfg.values.items()}
    chains: list[tuple[list[str], list[int], Any]] = []
    for i, leg in enumerate(mech.legs):
        path = _leg_path(mech, leg.joints)
        if path is None:
            raise FormulationError(
                f"the output's pose is reached leg by leg, and leg {i + 1} "
                f"({', '.join(leg.joints)}) is not one chain of joints from "
                f"{out.relative_to} to {out.body} (it branches, or holds a loop of its own "
                "as a Delta's parallelogram does): give the inputs instead"
            )
        chains.append((path[0], path[1], "pose"))
    on_legs = {n for names, _, _ in chains for n in names}
    off = [j.name for j in mech.joints if j.name not in on_legs]
    if not chains:
        raise FormulationError(f"no leg joins {out.relative_to} to {out.body}")
    if off:
        raise FormulationError(
            f"the output's pose is reached leg by leg, and joint {off[0]} is on no leg from "
            f"{out.relative_to} to {out.body}: give the inputs instead"
        )
    return chains, values


def _leg_path(mech: Mechanism, joints: tuple[str, ...]) -> tuple[list[str], list[int]] | None:
    """A leg's joints in order from the output's ``relative_to`` body to the output body,
    each with its direction (+1 from ``between[0]`` to ``between[1]``), when they form
    one chain between the two (None: they branch or close a loop of their own)."""
    out = mech.output
    assert out is not None
    left = {n: mech.joint(n).between for n in joints}
    at, names, signs = out.relative_to, [], []
    while left:
        step = [(n, 1 if b[0] == at else -1) for n, b in left.items() if at in b]
        if len(step) != 1:
            return None
        name, sign = step[0]
        names.append(name)
        signs.append(sign)
        a, b = left.pop(name)
        at = b if sign > 0 else a
    return (names, signs) if at == out.body else None


def arm_values(mech: Mechanism, config: str, name: str) -> list[Any]:
    """A joint's values in a configuration of an arm without loops: given there, else in
    its start's (the chain of starts), else the reference's zeros."""
    cur: str | None = config
    while cur is not None:
        cfg = mech.configurations[cur]
        if name in cfg.values:
            return _written(cfg.values[name])
        cur = cfg.start
    return [0] * mech.joint(name).dof


def _written(value: Any) -> Any:
    """A configuration's value of a joint as the chains hold it: its coordinates (a list),
    or a displacement as it is, which :class:`~mechsing.assembly.displacements.Joints`
    refuses where it writes the joint (modes takes joint values)."""
    return value if isinstance(value, Displacement) else list(value)
