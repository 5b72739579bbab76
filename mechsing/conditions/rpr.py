"""The conditions of a planar parallel robot of R-P-R legs, in the pose variables.

The P joints actuated (a 3-RPR), the pose is ``x``, ``y`` (the output's reference
point, m) and ``phi`` (its rotation about the plane's normal from the file's pose,
rad): type II is the determinant of the legs' actuation wrenches (the lines through
each leg's two pivots: zero when they are concurrent or parallel), type I the
vanishing of a leg's length."""

from __future__ import annotations

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
        "whose legs are R-P-R (revolute pivots with parallel axes, the P joint actuated: a "
        "3-RPR); this one is not; use 'mechsing analyze' or 'mechsing sweep' with pose "
        "configurations"
    )
    if not is_planar(mech, list(mech.joint_names)):
        raise refuse
    normal = sympy.Matrix(mech.joints[0].params["axis"]) if mech.joints[0].type == "R" else None
    if normal is None or list(normal) != [0, 0, 1]:
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
            lambda f: "the leg lines are concurrent or all parallel",
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
