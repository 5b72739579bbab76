"""The type II condition of a Gough-Stewart platform at constant orientation.

Six legs from the ground to the output, each a U or S joint on the ground, an
actuated P joint and an S joint on the output (a 6-UPS or 6-SPS): the actuation
wrenches are the forces along the leg lines, with the Plücker coordinates
``(u_i, b_i x u_i)`` where ``u_i = b_i - a_i`` runs from the base pivot ``a_i``
to the platform pivot ``b_i``.  With the platform kept at the orientation the
file draws and its reference point at ``(x, y, z)`` (m, ground frame), each
``b_i`` is ``(x, y, z) + (b_i0 - c0)``; the determinant of the six lines is
then a polynomial of degree 3 in ``(x, y, z)`` (B. Mayer St-Onge, C. Gosselin,
"Singularity analysis and representation of the general Gough-Stewart
platform", IJRR 19(3), 2000): the leg lines are dependent on a cubic surface.
"""

from __future__ import annotations

import sympy

from mechsing.conditions.results import Condition, Factor
from mechsing.model import Mechanism

__all__ = ["DIGITS", "gough_stewart"]

#: exact coefficients longer than this (digits) are shown as 15-digit decimals
DIGITS = 40


def gough_stewart(mech: Mechanism) -> tuple[list[Condition], list[str]] | None:
    """The conditions of a 6-UPS / 6-SPS platform, or None when ``mech`` is not one."""
    out = mech.output
    if out is None or len(mech.joints) != 18:
        return None
    legs = mech.legs
    inputs = {n for n, _ in mech.input_coordinates()}
    if len(legs) != 6:
        return None
    lines = []
    for leg in legs:
        joints = [mech.joint(n) for n in leg.joints]
        if len(joints) != 3 or [j.type for j in joints][1] != "P":
            return None
        first, slide, last = joints
        if first.type not in ("U", "S") or last.type != "S" or slide.name not in inputs:
            return None
        if mech.ground not in first.between or out.body not in last.between:
            return None
        lines.append((sympy.Matrix(first.params["point"]), sympy.Matrix(last.params["point"])))
    x, y, z = (sympy.Symbol(n, real=True) for n in ("x", "y", "z"))
    c0 = sympy.Matrix(mech.output_reference_point())
    t = sympy.Matrix([x, y, z])
    rows = []
    for a, b0 in lines:
        b = t + b0 - c0
        u = b - a
        rows.append([*u, *b.cross(u)])
    det = sympy.expand(sympy.Matrix(rows).det(method="berkowitz"))
    if det == 0:
        const, factors = sympy.Integer(0), []
    else:
        const, factors = sympy.factor_list(det)
    shown = []
    for f, p in factors:
        number, rest = f.as_independent(x, y, z, as_Add=False)
        const *= number**p
        poly = sympy.Poly(rest, x, y, z)
        if poly.LC() < 0:
            rest, const = -rest, const * (-1) ** p
        lc = sympy.Poly(rest, x, y, z).LC()
        if any(len(str(abs(c.p)) + str(c.q)) > DIGITS for c in sympy.Poly(rest, x, y, z).coeffs()):
            # decimals of the file give huge exact integers: show the factor divided by its
            # leading coefficient, to 15 significant digits
            rest, const = sympy.expand(rest / lc).evalf(15), const * lc**p
        shown.append(Factor(rest, int(p), "the six leg lines are linearly dependent"))
    if const.is_Rational and len(str(abs(const.p)) + str(const.q)) > DIGITS:
        const = const.evalf(15)
    degree = sympy.Poly(det, x, y, z).total_degree() if det != 0 else 0
    note = (
        "the determinant of the six leg lines (Plücker coordinates, forces along the legs) "
        f"with the platform at the drawn orientation: a polynomial of total degree {degree} "
        "in its position"
    )
    cond = Condition("output (type II)", "determinant", ("x", "y", "z"), const, tuple(shown), note)
    notes = [
        "pose variables: x, y, z = the position of the output's reference point (m, ground "
        "frame), the platform kept at the orientation the file draws (a constant-orientation "
        "section of the singularity locus)"
    ]
    return [cond], notes
