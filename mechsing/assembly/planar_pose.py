"""The planar formulation as a registered problem: a planar mechanism (its joints generate
the planar motions G, :mod:`mechsing.kinematics.family`) whose unknown part is one body on
legs, by exact elimination (:mod:`.planar`, :mod:`.exact`).

A mechanism drawn in another plane than xy is turned first (an exact rotation taking
its plane's normal to z; joint values do not change with the frame), so a four-bar in
the xz plane has the modes it has in the xy plane.

Owns :data:`FORMULATION`.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.assembly.chains import Found
from mechsing.assembly.given import NO_INPUTS, Formulation, Given
from mechsing.assembly.settings import MODE_CERTIFY_RADIUS
from mechsing.errors import FormulationError
from mechsing.model import Mechanism
from mechsing.numeric import PARALLEL_AXES_ATOL

__all__ = ["FORMULATION", "turned_to_xy"]


def turned_to_xy(mech: Mechanism, normal: np.ndarray) -> Mechanism:
    """``mech`` turned so that its plane's ``normal`` (a unit vector) becomes z: each
    joint's directions and points rotated, exactly when the normal is rational (the
    rotation ``I + K + K^2 / (1 + c)``, ``K`` the cross-product matrix of ``n x z``).
    The normal is taken exactly from the file (:func:`_exact_normal`): the float one the
    subgroup test gives carries rounding (1e-15 off z on a slider-crank drawn in xy)."""
    n = _exact_normal(mech, normal)
    if n == [0, 0, 1]:
        return mech
    if n == [0, 0, -1]:
        R = sympy.diag(1, -1, -1)
    else:
        k = sympy.Matrix(n).cross(sympy.Matrix([0, 0, 1]))
        K = sympy.Matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        R = sympy.eye(3) + K + K * K / (1 + n[2])
    R = R.applyfunc(sympy.simplify)

    def turn(v: Any) -> Any:
        if isinstance(v, (tuple, list)) and len(v) == 3 and not isinstance(v[0], (tuple, list)):
            w = R * sympy.Matrix([sympy.sympify(x) for x in v])
            return tuple(sympy.simplify(x) for x in w)
        if isinstance(v, (tuple, list)) and v and isinstance(v[0], (tuple, list)):
            return tuple(turn(x) for x in v)
        return v

    joints = tuple(
        dataclasses.replace(j, params={k: turn(v) for k, v in j.params.items()})
        for j in mech.joints
    )
    return dataclasses.replace(mech, joints=joints)


def _exact_normal(mech: Mechanism, normal: np.ndarray) -> list[Any]:
    """The plane's unit normal from the file's exact directions: a revolute's axis, else
    the cross product of two slides' axes, whichever lies along ``normal`` (the float
    normal, which chooses the sign); rounded from ``normal`` where none does."""
    approx = np.asarray(normal, dtype=float)

    def unit(v: Any) -> list[Any] | None:
        w = sympy.Matrix([sympy.sympify(x) for x in v])
        size = sympy.sqrt(w.dot(w))
        if size == 0:
            return None
        w = w / size
        dot = float(sum(float(a) * b for a, b in zip(w, approx, strict=True)))
        return [sympy.nsimplify(x) if dot > 0 else -sympy.nsimplify(x) for x in w]

    axes = [j.params["axis"] for j in mech.joints if j.type == "R"]
    slides = [sympy.Matrix(j.params["axis"]) for j in mech.joints if j.type == "P"]
    axes += [a.cross(b) for i, a in enumerate(slides) for b in slides[i + 1 :]]
    for v in axes:
        n = unit(v)
        along = float(sum(float(a) * b for a, b in zip(n or [0, 0, 0], approx, strict=True)))
        if n is not None and abs(abs(along) - 1) <= PARALLEL_AXES_ATOL:
            return n
    n = [sympy.nsimplify(float(x), rational=True, tolerance=1e-15) for x in approx]
    size = sympy.sqrt(sum(x * x for x in n))
    return [x / size for x in n]


def _applies(given: Given) -> str | None:
    from mechsing.assembly.planar import planar_stages

    if given.values is None:
        return NO_INPUTS
    fam = given.family
    if fam.kind != "planar":
        return (
            f"its joints generate {fam.symbol or 'no decided subgroup'}, not the planar motions G"
        )
    mech = turned_to_xy(given.mech, fam.params["normal"])
    try:
        stages = planar_stages(mech, given.values)
    except FormulationError as reason:
        return str(reason)
    given.cache["planar"] = (mech, stages)
    return None


def _find(given: Given) -> Found:
    from mechsing.assembly.certify import krawczyk
    from mechsing.assembly.exact import eliminate_stages
    from mechsing.assembly.planar import joint_values, stages_system

    mech, stages = given.cache["planar"]
    found = eliminate_stages(stages, given.dps)
    square, unknowns = stages_system(stages)
    rows = []
    for platforms in found.branches:
        coords = joint_values(mech, stages, given.values, list(platforms))
        z = [v for c, s, x, y in platforms for v in (x, y, mpmath.atan2(s, c))]
        rows.append((coords, krawczyk(square, unknowns, z, mpmath.mpf(MODE_CERTIFY_RADIUS))))
    system = stages[0]
    formulation = {
        "name": "planar platform pose",
        "method": "exact elimination",
        "platform": system.platform,
        "unknowns": ["x", "y", "theta"],
        "legs": [{"kind": leg.kind, "joints": list(leg.joints)} for leg in system.legs],
        "polynomial_degree": found.degrees[0],
        "offset": str(2 * sympy.atan(found.offset)),
    }
    if len(stages) > 1:
        formulation["stages"] = [
            {
                "platform": st.platform,
                "legs": [{"kind": leg.kind, "joints": list(leg.joints)} for leg in st.legs],
                "polynomial_degree": degree,
            }
            for st, degree in zip(stages, found.degrees, strict=True)
        ]
    if not found.finite:
        return Found(formulation, [], None, "infinite", None, found.notes)
    complete = "proven" if found.proven else "not proven"
    return Found(formulation, rows, len(rows), complete, None, found.notes)


FORMULATION = Formulation("the planar platform pose (exact elimination)", _applies, _find)
