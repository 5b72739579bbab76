"""Idle spins in the general formulation: a body held by exactly two ball joints (a
coupler rod between S joints, an RSSR's, an S-S leg's) turns freely about the line
through their points, so with every other value given its closed configurations form a
curve however many assembly modes the mechanism has.  The spin moves nothing else (the
analysis calls it an idle motion), so a mode is taken with the rod free of spin: the
rotation of its first ball joint has no component about the rod's line, ``vec(r) . d =
0`` with ``d`` the line's direction at the reference, the least rotation turning the rod
to where it points (as the leg formulation lists a rod, :mod:`.legs`).  One linear
equation in that joint's quaternion per rod: the system is square again.

The equation fixes the spin except where the rod is turned half about an axis normal to
it relative to its neighbour (``r = (0, v)`` with ``v . d = 0``: the whole spin circle
satisfies it); there the local dimension test finds the circle and no count is claimed.

Owns :func:`idle_rods` and :func:`spin_equation`.
"""

from __future__ import annotations

from typing import Any

import mpmath
import sympy

from mechsing.model import Mechanism

__all__ = ["idle_rods", "spin_equation"]


def idle_rods(mech: Mechanism, given: dict[str, Any]) -> list[tuple[str, str, str]]:
    """Each body (not ground, not the output) joined by exactly two joints, both S and
    neither given: ``(body, first S, second S)`` in file order."""
    out_body = mech.output.body if mech.output is not None else None
    on: dict[str, list[str]] = {}
    for j in mech.joints:
        for b in j.between:
            on.setdefault(b, []).append(j.name)
    rods = []
    for body, names in on.items():
        if body in (mech.ground, out_body) or len(names) != 2:
            continue
        if all(mech.joint(n).type == "S" and n not in given for n in names):
            if _direction(mech, names[0], names[1]) is not None:
                rods.append((body, names[0], names[1]))
    return rods


def spin_equation(mech: Mechanism, rod: tuple[str, str, str], gens: Any) -> sympy.Expr:
    """``vec(r) . d = 0`` for the rod's first ball joint, whose quaternion ``r`` is
    ``gens`` (its variable group, scalar first); ``d`` runs from its point to the other
    joint's (exact, from the file)."""
    d = _direction(mech, rod[1], rod[2])
    assert d is not None
    return sympy.expand(sum(d[i] * gens[i + 1] for i in range(3)))


def _direction(mech: Mechanism, first: str, second: str) -> list[Any] | None:
    """The unit direction from one joint's point to the other's (sympy Floats at the
    working digits plus guard digits; None where the points coincide)."""
    a = sympy.Matrix(mech.joint(first).params["point"])
    b = sympy.Matrix(mech.joint(second).params["point"])
    d = b - a
    digits = mpmath.mp.dps + 10
    norm = sympy.N(sympy.sqrt(d.dot(d)), digits)
    if norm == 0:
        return None
    return [sympy.Float(sympy.N(x / norm, digits), digits) for x in d]
