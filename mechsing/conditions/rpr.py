"""The conditions of a planar parallel robot, in the pose variables.

The pose is ``x``, ``y`` (the output's reference point, m) and ``phi`` (its rotation
about the plane's normal from the file's pose, rad).  Each leg is three one-dof joints
(R or P, in the plane) from the ground to the output with one of them actuated (a 3-RPR,
3-RRR, 3-PRR ...).  With the actuators locked a leg transmits one wrench, the one its two
passive joints do no work on (a force through each passive revolute's pivot, across each
passive slide): type II is the determinant of the three legs' transmission wrenches
(rows: force and moment about the origin; zero when their lines are concurrent or all
parallel), type I for a leg the vanishing of that wrench's work on its actuated joint
(its line through the actuated pivot, or across the actuated slide: a 3-RRR's leg
stretched or folded).

The pivots of the platform's joints are functions of the pose; a middle joint's pivot is
placed from the ground through the leg's first joint, whose variable (an input angle of
a 3-RRR, a slide of a 3-PRR) the conditions then also hold.  R-P-R legs whose P joints
are actuated (a 3-RPR) keep their classic form in the pose alone: type I the vanishing
of a leg's length."""

from __future__ import annotations

from typing import Any

import sympy

from mechsing.conditions.jacobians import condition_from, is_planar, parameter_symbols
from mechsing.conditions.results import Condition
from mechsing.conditions.symbolic import JointSymbols
from mechsing.errors import UserError
from mechsing.model import Mechanism

__all__ = ["planar_parallel"]


def planar_parallel(
    mech: Mechanism, S: dict[str, JointSymbols], source: str
) -> tuple[list[Condition], list[str]]:
    out = mech.output
    assert out is not None
    inputs = {n for n, _ in mech.input_coordinates()}
    legs = mech.legs
    refuse = UserError(
        f"{source}: a mechanism of {mech.graph.num_loops} loops with {len(inputs)} inputs: "
        "symbolic conditions of mechanisms with several inputs cover planar parallel robots "
        "(joints about or along the plane's normal z) with three legs of three R or P joints "
        "from the ground to the output, one of them actuated (3-RPR, 3-RRR, 3-PRR ...); this "
        "one is not; use 'mechsing analyze' or 'mechsing sweep' with pose configurations"
    )
    if not is_planar(mech, list(mech.joint_names)):
        raise refuse
    revolutes = [j for j in mech.joints if j.type == "R"]
    normal = sympy.Matrix(revolutes[0].params["axis"]) if revolutes else None
    # about z either way: a joint turning about -z turns by minus its value about z
    if normal is None or list(normal) not in ([0, 0, 1], [0, 0, -1]):
        raise refuse
    clash = [p.name for p in parameter_symbols(mech) if p.name in ("x", "y", "phi")]
    if clash:
        raise UserError(
            f"{source}: parameter {clash[0]!r} has the name of a pose variable (x, y, phi); "
            "rename it to keep it symbolic"
        )
    x, y, phi = (sympy.Symbol(n, real=True) for n in ("x", "y", "phi"))
    cphi, sphi = sympy.Symbol("c_phi", real=True), sympy.Symbol("s_phi", real=True)
    pose = JointSymbols(phi, cphi, sphi)
    c0 = sympy.Matrix(mech.output_reference_point())
    Rz = sympy.Matrix([[cphi, -sphi, 0], [sphi, cphi, 0], [0, 0, 1]])
    rpr = all(_is_rpr(mech, leg.joints, inputs) for leg in legs)
    if not rpr:
        chains = [_chain(mech, leg.joints) for leg in legs]
        ok = all(c is not None and len(c) == 3 and sum(n in inputs for n in c) == 1 for c in chains)
        if not ok or any(mech.joint(n).type not in ("R", "P") for c in chains for n in c or ()):
            raise refuse
        return _transmission(mech, S, chains, inputs, (x, y, c0, Rz), pose)
    rows = []
    lengths = []
    leg_names = []
    for leg in legs:
        types = [mech.joint(n).type for n in leg.joints]
        acts = [n for n in leg.joints if n in inputs]
        if sorted(types) != ["P", "R", "R"] or len(acts) != 1 or mech.joint(acts[0]).type != "P":
            raise refuse
        rs = [mech.joint(n) for n in leg.joints if mech.joint(n).type == "R"]
        base = [j for j in rs if mech.ground in j.between]
        top = [j for j in rs if out.body in j.between]
        if len(base) != 1 or len(top) != 1:
            raise refuse
        A = sympy.Matrix(base[0].params["point"])
        B0 = sympy.Matrix(top[0].params["point"])
        B = sympy.Matrix([x, y, c0[2]]) + Rz * (B0 - c0)
        f = B - A
        rows.append([f[0], f[1], A[0] * f[1] - A[1] * f[0]])
        lengths.append(sympy.expand(f[0] ** 2 + f[1] ** 2))
        leg_names.append(acts[0])
    params = set(parameter_symbols(mech))
    W = sympy.Matrix(rows)
    det = sympy.expand(W.det(method="berkowitz"))
    conds = [
        condition_from(
            "output (type II)",
            "determinant",
            det,
            [pose],
            params,
            "the determinant of the legs' actuation wrenches (rows: force along each leg line "
            "and its moment about the origin); it vanishes when the leg lines are concurrent or "
            "all parallel",
            lambda f: _concurrent("leg lines", f, x, y),
        )
    ]
    for name, L in zip(leg_names, lengths, strict=True):
        c = condition_from(
            f"input (type I), leg {name}",
            "determinant",
            L,
            [pose],
            params,
            f"the squared length of leg {name} (pivot to pivot); it vanishes only when the two "
            "pivots meet",
            lambda f, n=name: f"leg {n} has zero length",
        )
        conds.append(c)
    notes = [
        "pose variables: x, y = the position of the output's reference point (m), phi = its "
        "rotation about z from the file's pose (rad)"
    ]
    return conds, notes


def _concurrent(lines: str, f: Any, x: Any, y: Any) -> str:
    """The meaning of a factor of the type II determinant."""
    if sympy.sympify(f).has(x, y):
        return f"the {lines} are concurrent or all parallel"
    return (
        f"an orientation at which the {lines} are concurrent or all parallel wherever the "
        "platform is (as when its pivots' triangle is similar to the base's and turned "
        "parallel to it: the lines meet at the centre of similitude)"
    )


def _is_rpr(mech: Mechanism, joints: tuple[str, ...], inputs: set[str]) -> bool:
    """An R-P-R leg (in order from the ground) whose P joint is actuated."""
    chain = _chain(mech, joints)
    if chain is None or [mech.joint(n).type for n in chain] != ["R", "P", "R"]:
        return False
    return [n for n in chain if n in inputs] == [chain[1]]


def _chain(mech: Mechanism, joints: tuple[str, ...]) -> list[str] | None:
    """A leg's joints in order from the ground (None when they are not a chain)."""
    out: list[str] = []
    body, left = mech.ground, set(joints)
    while left:
        nxt = [n for n in left if body in mech.joint(n).between]
        if len(nxt) != 1:
            return None
        out.append(nxt[0])
        left.discard(nxt[0])
        body = mech.joint(nxt[0]).other(body)
    return out


def _cross(a: Any, b: Any) -> Any:
    return a[0] * b[1] - a[1] * b[0]


def _transmission(
    mech: Mechanism,
    S: dict[str, JointSymbols],
    chains: list[list[str]],
    inputs: set[str],
    pose_map: tuple[Any, Any, Any, Any],
    pose: JointSymbols,
) -> tuple[list[Condition], list[str]]:
    """The conditions of legs of three one-dof joints each (see the module's docstring)."""
    x, y, c0, Rz = pose_map
    ground = mech.ground
    rows, type1, used = [], [], [pose]

    def rot(js: JointSymbols, sign: int, v: Any) -> Any:
        c, s_ = js.c, sign * js.s
        return sympy.Matrix([c * v[0] - s_ * v[1], s_ * v[0] + c * v[1]])

    for chain in chains:
        j1, j2, j3 = (mech.joint(n) for n in chain)
        sign = 1 if j1.between[0] == ground else -1
        if j1.type == "R" and sympy.sympify(j1.params["axis"][2]) < 0:
            sign = -sign  # its value turns the leg about -z
        q1 = S[j1.name]
        used.append(q1)
        lines: list[tuple[str, Any]] = []  # ("R", pivot) or ("P", direction), 2-vectors
        if j1.type == "R":
            a = sympy.Matrix(j1.params["point"][:2])
            lines.append(("R", a))
        else:
            lines.append(("P", sympy.Matrix(j1.params["axis"][:2])))
        if j2.type == "R":
            p0 = sympy.Matrix(j2.params["point"][:2])
            if j1.type == "R":
                p = lines[0][1] + rot(q1, sign, p0 - lines[0][1])
            else:
                p = p0 + sign * q1.q * lines[0][1]
            lines.append(("R", p.applyfunc(sympy.expand)))
        else:
            u0 = sympy.Matrix(j2.params["axis"][:2])
            lines.append(("P", rot(q1, sign, u0) if j1.type == "R" else u0))
        if j3.type == "R":
            b = sympy.Matrix([x, y, c0[2]]) + Rz * (sympy.Matrix(j3.params["point"]) - c0)
            lines.append(("R", b[:2, :]))
        else:
            lines.append(("P", (Rz * sympy.Matrix(j3.params["axis"]))[:2, :]))
        act = [i for i, n in enumerate(chain) if n in inputs][0]
        passive = [lines[i] for i in range(3) if i != act]
        f, m = _wrench(*passive)
        rows.append([f[0], f[1], m])
        kind, at = lines[act]
        work = sympy.expand(m - _cross(at, f) if kind == "R" else f[0] * at[0] + f[1] * at[1])
        type1.append((chain[act], [chain[i] for i in range(3) if i != act], work))
    params = set(parameter_symbols(mech))
    det = sympy.expand(sympy.Matrix(rows).det(method="berkowitz"))
    conds = [
        condition_from(
            "output (type II)",
            "determinant",
            det,
            used,
            params,
            "the determinant of the legs' transmission wrenches (rows: the force each leg "
            "transmits with its actuator locked, through its passive pivots, and its moment "
            "about the origin); it vanishes when their lines are concurrent or all parallel",
            lambda f: _concurrent("legs' transmission lines", f, x, y),
        )
    ]
    for name, others, work in type1:
        conds.append(
            condition_from(
                f"input (type I), leg {name}",
                "determinant",
                work,
                used,
                params,
                f"the work of leg {name}'s transmission wrench (through {' and '.join(others)}) "
                f"on its actuated joint {name}: it vanishes when the actuator cannot move the "
                "leg's end across that line",
                lambda f, n=name, o=others: (
                    f"the transmission line of leg {n} (through {' and '.join(o)}) passes "
                    f"through {n}'s pivot, or runs across its slide"
                ),
            )
        )
    notes = [
        "pose variables: x, y = the position of the output's reference point (m), phi = its "
        "rotation about z from the file's pose (rad); the middle pivots are placed through "
        "each leg's first joint, whose variable the conditions also hold"
    ]
    return conds, notes


def _wrench(a: tuple[str, Any], b: tuple[str, Any]) -> tuple[Any, Any]:
    """The planar wrench (force, moment about the origin) that two joints (``("R",
    pivot)`` or ``("P", direction)``) do no work on: a force through each pivot, across
    each slide; a couple when both slide."""
    (ka, va), (kb, vb) = a, b
    if ka == "R" and kb == "R":
        f = vb - va
        return f, _cross(va, f)
    if ka == "P" and kb == "P":
        return sympy.Matrix([0, 0]), sympy.Integer(1)
    p, u = (va, vb) if ka == "R" else (vb, va)
    f = sympy.Matrix([-u[1], u[0]])
    return f, _cross(p, f)
