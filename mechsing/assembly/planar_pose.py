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
from mechsing.errors import FormulationError
from mechsing.model import Mechanism
from mechsing.numeric import MODE_CERTIFY_RADIUS

__all__ = ["FORMULATION", "turned_to_xy"]


def turned_to_xy(mech: Mechanism, normal: np.ndarray) -> Mechanism:
    """``mech`` turned so that its plane's ``normal`` (a unit vector) becomes z: each
    joint's directions and points rotated, exactly when the normal is rational (the
    rotation ``I + K + K^2 / (1 + c)``, ``K`` the cross-product matrix of ``n x z``)."""
    n = [sympy.nsimplify(float(x), rational=True, tolerance=1e-15) for x in normal]
    size = sympy.sqrt(sum(x * x for x in n))
    n = [x / size for x in n]
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


def _applies(given: Given) -> str | None:
    from mechsing.assembly.planar import planar_system

    if given.values is None:
        return NO_INPUTS
    fam = given.family
    if fam.kind != "planar":
        return (
            f"its joints generate {fam.symbol or 'no decided subgroup'}, not the planar motions G"
        )
    mech = turned_to_xy(given.mech, fam.params["normal"])
    try:
        system = planar_system(mech, given.values)
    except FormulationError as reason:
        return str(reason)
    given.cache["planar"] = (mech, system)
    return None


def _find(given: Given) -> Found:
    from mechsing.assembly.certify import krawczyk
    from mechsing.assembly.exact import eliminate_planar
    from mechsing.assembly.planar import C, S, X, Y, joint_values

    mech, system = given.cache["planar"]
    found = eliminate_planar(system, given.dps)
    theta = sympy.Symbol("theta", real=True)
    square = [e.subs({C: sympy.cos(theta), S: sympy.sin(theta)}) for e in system.equations]
    rows = []
    for c, s, x, y in found.poses:
        coords = joint_values(mech, system, given.values, (c, s, x, y))
        ok = krawczyk(
            square, [X, Y, theta], [x, y, mpmath.atan2(s, c)], mpmath.mpf(MODE_CERTIFY_RADIUS)
        )
        rows.append((coords, ok))
    formulation = {
        "name": "planar platform pose",
        "method": "exact elimination",
        "platform": system.platform,
        "unknowns": ["x", "y", "theta"],
        "legs": [{"kind": leg.kind, "joints": list(leg.joints)} for leg in system.legs],
        "polynomial_degree": found.degree,
        "offset": str(2 * sympy.atan(found.offset)),
    }
    if not found.finite:
        return Found(formulation, [], None, "infinite", None, found.notes)
    complete = "proven" if found.proven else "not proven"
    return Found(formulation, rows, len(rows), complete, None, found.notes)


FORMULATION = Formulation("the planar platform pose (exact elimination)", _applies, _find)
