"""The constraint and actuation conditions of a translational 3-UPU, in the pose variables.

Three legs from the ground to the output, each a U joint on the ground, an
actuated P joint and a U joint on the output, with Tsai's axis conditions (L.-W.
Tsai, ARK 1996): the ground U's first axis ``s1`` is fixed in the ground, its
second axis ``s2`` is perpendicular to the leg, the output U's first axis is
parallel to ``s2`` and its second axis to ``s1``.  The output then translates;
its reference point is at ``(x, y, z)`` (m, ground frame), each platform pivot at
``b_i = b_i0 + (x, y, z) - c0``, and the leg runs along ``u_i = b_i - a_i``.

* Each leg's twists (rotations about ``s1`` and ``s2`` through both pivots, the
  slide along ``u_i``) leave one reciprocal wrench: the couple
  ``n_i = s1 x s2``, with ``s2`` along ``s1 x u_i``:
  ``n_i = (s1 . u_i) s1 - |s1|**2 u_i`` (the leg projected on the plane normal to
  ``s1``), linear in the pose.  The **constraint singularity** is
  ``det[n_1 n_2 n_3] = 0`` (Zlatanov, Bonev, Gosselin, ICRA 2002): the couples are
  dependent and the platform gains a rotation.
* The actuation wrench of leg i is the force along its line, ``(u_i, a_i x u_i)``
  (reciprocal to the four rotations, whose axes pass through a pivot).  The
  **actuation (type II) singularity** is the vanishing of the 6x6 determinant of the
  three forces and the three couples, which is ``det[u_1 u_2 u_3] * det[n_1 n_2 n_3]``
  (block triangular: a couple has no force part): the legs' directions parallel to
  one plane (the platform moves with the P joints locked), or a constraint
  singularity.

Both are exact polynomials in ``x, y, z`` with the file's numbers (and the named
parameters kept as symbols), factored.
"""

from __future__ import annotations

from typing import Any

import sympy

from mechsing.conditions.results import Condition, Factor
from mechsing.model import Mechanism

__all__ = ["translational_3upu"]

#: the meaning of the factors of det[u_1 u_2 u_3]
ACTUATION = "the three legs' directions are parallel to one plane (actuation forces dependent)"
#: the meaning of the factors of det[n_1 n_2 n_3]
CONSTRAINT = "the three legs' constraint couples are linearly dependent (the platform can rotate)"


def _legs(mech: Mechanism) -> list[tuple[Any, Any, Any]] | None:
    """Per leg: the ground pivot, the platform pivot and the fixed axis ``s1``; None when
    ``mech`` is not a 3-UPU with Tsai's axis conditions."""
    out = mech.output
    if out is None or len(mech.joints) != 9 or out.relative_to != mech.ground:
        return None
    legs = mech.legs
    inputs = {n for n, _ in mech.input_coordinates()}
    if len(legs) != 3 or len(inputs) != 3:
        return None
    found = []
    for leg in legs:
        joints = [mech.joint(n) for n in leg.joints]
        if [j.type for j in joints] != ["U", "P", "U"] or joints[1].name not in inputs:
            return None
        first, slide, last = joints
        if first.between[0] != mech.ground or last.between[1] != out.body:
            return None
        s1, s2 = (sympy.Matrix(a) for a in first.params["axes"])
        s3, s4 = (sympy.Matrix(a) for a in last.params["axes"])
        u = sympy.Matrix(slide.params["axis"])
        parallel = [(s3, s2), (s4, s1)]
        perpendicular = [(s1, s2), (s2, u)]
        if any(sympy.simplify(v.cross(w).norm()) != 0 for v, w in parallel) or any(
            sympy.simplify(v.dot(w)) != 0 for v, w in perpendicular
        ):
            return None
        found.append((sympy.Matrix(first.params["point"]), sympy.Matrix(last.params["point"]), s1))
    return found


def _factored(det: Any, xyz: tuple[Any, ...], meaning: str) -> tuple[Any, list[Factor]]:
    """``det`` as a constant and its factors in ``x, y, z`` (with the square roots of its
    coefficients as an extension of the rationals, where the factors live)."""
    if det == 0:
        return sympy.Integer(0), []
    roots = sorted(
        {a for a in det.atoms(sympy.Pow) if a.exp.is_Rational and not a.exp.is_Integer},
        key=str,
    )
    params = sorted(det.free_symbols - set(xyz), key=str)
    const, factors = sympy.factor_list(det, *xyz, *params, extension=roots or None)
    shown = []
    for f, p in factors:
        if not f.free_symbols & set(xyz):
            const *= f**p
            continue
        number, rest = f.as_independent(*xyz, as_Add=False)
        const *= number**p
        if sympy.Poly(rest, *xyz).LC().could_extract_minus_sign():
            rest, const = sympy.expand(-rest), const * (-1) ** p
        shown.append(Factor(rest, int(p), meaning))
    return sympy.simplify(const), shown


def _merged(factors: list[Factor]) -> tuple[Factor, ...]:
    """Equal factors once, their powers added and their meanings joined."""
    out: dict[Any, Factor] = {}
    for f in factors:
        if f.expression in out:
            g = out[f.expression]
            out[f.expression] = Factor(
                f.expression, g.power + f.power, f"{g.meaning}; and {f.meaning}"
            )
        else:
            out[f.expression] = f
    return tuple(out.values())


def translational_3upu(mech: Mechanism) -> tuple[list[Condition], list[str]] | None:
    """The constraint and actuation conditions of a translational 3-UPU, or None when
    ``mech`` is not one."""
    legs = _legs(mech)
    if legs is None:
        return None
    xyz = tuple(sympy.Symbol(n, real=True) for n in ("x", "y", "z"))
    t = sympy.Matrix(xyz)
    c0 = sympy.Matrix(mech.output_reference_point())
    U, N = [], []
    for a, b0, s1 in legs:
        u = (t + b0 - c0 - a).applyfunc(sympy.expand)
        U.append(list(u))
        N.append(list((s1.dot(u) * s1 - s1.dot(s1) * u).applyfunc(sympy.expand)))
    det_u = sympy.expand(sympy.Matrix(U).det(method="berkowitz"))
    det_n = sympy.expand(sympy.Matrix(N).det(method="berkowitz"))
    cu, fu = _factored(det_u, xyz, ACTUATION)
    cn, fn = _factored(det_n, xyz, CONSTRAINT)
    constraint = Condition(
        "constraint",
        "determinant",
        ("x", "y", "z"),
        cn,
        tuple(fn),
        "the determinant det[n_1 n_2 n_3] of the legs' constraint couples n_i = (s1 . u_i) s1 - |s1|^2 u_i "
        "(s1: the ground U's fixed axis, u_i: the leg from its ground pivot to its platform "
        "pivot)",
    )
    actuation = Condition(
        "output (type II)",
        "determinant",
        ("x", "y", "z"),
        sympy.simplify(cu * cn),
        _merged([*fu, *fn]),
        "the 6x6 determinant of the three actuation forces (u_i, a_i x u_i) and the three "
        "constraint couples (0, n_i): det[u_1 u_2 u_3] * det[n_1 n_2 n_3]",
    )
    notes = [
        "pose variables: x, y, z = the position of the output's reference point (m, ground "
        "frame); the platform of a 3-UPU with Tsai's axis conditions translates, so its "
        "orientation is the drawn one"
    ]
    return [constraint, actuation], notes
