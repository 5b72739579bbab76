"""A positional 3R arm's inverse kinematics as one polynomial: the section of
:func:`~mechsing.assembly.cusps.cusps` for a serial arm of three revolute joints whose
output is a point.

The first joint turns the arm about its axis, so a target is given by ``(rho, z)``: its
distance from the first axis and its height along it (the workspace half-plane,
Wenger 1992).  With the axes ``w_i`` through ``o_i`` and the point ``p0`` (all at the
reference, the ground frame), joint 3 puts the point at ``q3 = o3 + Rot(w3, q3)(p0 -
o3)`` and joint 2 at ``r = o2 + Rot(w2, q2)(q3 - o2)``; then

* ``w1 . (r - o1) = z`` and
* ``|o2 - o1|^2 + |q3 - o2|^2 + 2 (o2 - o1) . Rot(w2, q2)(q3 - o2) = rho^2 + z^2``

are linear in ``(cos q2, sin q2)`` with coefficients in ``(cos q3, sin q3)``: the shape
of the planar formulation (:func:`~mechsing.assembly.exact.eliminant_of`: Cramer's rule
and ``cos^2 + sin^2 = 1``), which leaves one polynomial in ``t = tan((q3 - q30)/2)``, the
arm's inverse-kinematics polynomial (a quartic for a general arm, after the factor free
of the target is divided out).  An arm whose first two axes meet (a PUMA's shoulder)
has ``|r - o1|`` free of ``q2``: the polynomial is a square (its inverse kinematics
decouples) and the arm is not cuspidal.

Owns :func:`arm_family`.
"""

from __future__ import annotations

from typing import Any

import mpmath
import sympy

from mechsing.errors import UserError
from mechsing.model import Mechanism

__all__ = ["arm_family"]


def _vec(v: Any) -> sympy.Matrix:
    return sympy.Matrix(
        [sympy.nsimplify(x) if isinstance(x, float) else sympy.sympify(x) for x in v]
    )


def _rot(w: sympy.Matrix, c: sympy.Expr, s: sympy.Expr, v: sympy.Matrix) -> sympy.Matrix:
    """Rot(w, q) v for the unit vector w (Rodrigues), c = cos q, s = sin q."""
    along = w.dot(v) * w
    return along + c * (v - along) + s * w.cross(v)


def _chain(mech: Mechanism) -> list[Any]:
    """The three R joints from ground to the output body, in order."""
    where = mech.path or mech.name
    if mech.output is None or mech.output.point is None:
        raise UserError(
            f"{where}: cusps of an arm need a positional task: give the output a point "
            "(output: {body: ..., point: [x, y, z]})"
        )
    joints = list(mech.joints)
    if len(joints) != 3 or any(j.type != "R" for j in joints):
        raise UserError(
            f"{where}: cusps of an arm take three revolute joints (a positional 3R arm); "
            f"it has {', '.join(f'{j.name} ({j.type})' for j in joints)}"
        )
    order, at = [], mech.ground
    for _ in range(3):
        nxt = [j for j in joints if at in j.between and j not in order]
        if len(nxt) != 1:
            raise UserError(f"{where}: the joints do not form one chain from {at}")
        order.append(nxt[0])
        at = nxt[0].other(at)
    if at != mech.output.body:
        raise UserError(f"{where}: the output body {mech.output.body} is not the chain's end")
    return order


def arm_family(mech: Mechanism, ranges: dict[str, tuple[float, float]]) -> dict[str, Any]:
    """The section's polynomial of a positional 3R arm (see the module)."""
    from mechsing.assembly.discriminant import Family, decoupled_evidence, without_free_factor
    from mechsing.assembly.exact import T, eliminant_of
    from mechsing.assembly.planar import OFFSETS, C, S, X, Y

    where = mech.path or mech.name
    j1, j2, j3 = _chain(mech)  # first: a 2R arm is told it is not a 3R arm
    if set(ranges) != {"rho", "z"}:
        raise UserError(
            f"{where}: a 3R arm's section is its workspace half-plane: --vary rho=lo:hi,z=lo:hi "
            "(rho: the distance from the first axis, z: the height along it)"
        )
    if ranges["rho"][0] < 0:
        raise UserError(f"{where}: --vary rho={ranges['rho'][0]:g}:...: rho is a distance (>= 0)")
    w = [_vec(j.params["axis"]) for j in (j1, j2, j3)]
    w = [v / sympy.sqrt(v.dot(v)) for v in w]
    o = [_vec(j.params["point"]) for j in (j1, j2, j3)]
    p0 = _vec(mech.output.point)
    RHO, Z = sympy.symbols("rho z", real=True)
    q3 = o[2] + _rot(w[2], C, S, p0 - o[2])
    u = q3 - o[1]
    ru = _rot(w[1], X, Y, u)
    d21 = o[1] - o[0]
    eq_z = sympy.expand(w[0].dot(d21 + ru) - Z)
    eq_r = sympy.expand(d21.dot(d21) + u.dot(u) + 2 * d21.dot(ru) - RHO**2 - Z**2)
    F, (D, Dx, Dy) = eliminant_of([eq_r, eq_z], X**2 + Y**2 - 1, 2)
    P = without_free_factor(F, T, RHO, Z)
    formulation = {
        "name": "positional 3R arm",
        "joints": [j1.name, j2.name, j3.name],
        "t": f"tan(({j3.name} - theta0) / 2)",
    }
    base = {
        "problem": "inverse kinematics",
        "varied": ("rho", "z"),
        "fixed": {},
        "formulation": formulation,
    }
    decoupled = decoupled_evidence(
        P,
        T,
        RHO,
        Z,
        f"the inverse kinematics decouples ({j3.name} from it, {j2.name} from one more "
        f"equation: the axes of {j1.name} and {j2.name} meet, or are parallel)",
    )
    if decoupled is not None:
        return {**base, "decoupled": decoupled}
    formulation["eliminant_degree"] = int(sympy.Poly(P, T).degree())
    r = OFFSETS[0]
    theta0 = 2 * mpmath.atan(mpmath.mpf(r.p) / r.q)
    formulation["theta0"] = float(theta0)
    cramer = sympy.lambdify([C, S, RHO, Z], [D, Dx, Dy], "mpmath")

    def mode_at(a: Any, b: Any, t: Any) -> dict[str, Any]:
        with mpmath.workdps(30):
            q3v = theta0 + 2 * mpmath.atan(t)
            d, dx, dy = cramer(mpmath.cos(q3v), mpmath.sin(q3v), a, b)
            q2v = mpmath.atan2(dy / d, dx / d)
        return {"joints": {j2.name: float(q2v), j3.name: float(q3v)}}

    return {**base, "family": Family.of(P, T, RHO, Z), "mode_at": mode_at}
