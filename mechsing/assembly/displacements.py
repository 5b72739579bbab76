"""Each joint's displacement in Study coordinates, as the general formulation writes it:
unknown (a dual quaternion linear in its own homogeneous coordinates) or given (the
constant its values make), lengths over the characteristic length L.

A revolute's half-angle pair ``(c, s)`` ~ ``(cos(q/2), sin(q/2))`` gives ``c + s A`` with
``A`` its line; a slide's ``(1, q/(2L))`` gives ``c + s eps u``; a C joint the two, a U
joint its two revolutes'; an S joint the quaternion ``r`` of its rotation, ``r + eps (p x
r)`` about its point ``p``.

Owns :class:`Group` (one variable group), :class:`Joints` (the displacements of one
problem's joints) and the numbers they are written in (:func:`study_number`,
:func:`working_mpf`, :func:`quaternion_of_vector`, :func:`expanded`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import mpmath
import sympy

from mechsing.errors import FormulationError
from mechsing.lie.dual import study_multiply
from mechsing.model import Mechanism
from mechsing.model.mechanism import Displacement

__all__ = [
    "WRITTEN",
    "Group",
    "Joints",
    "expanded",
    "quaternion_of_vector",
    "study_number",
    "working_mpf",
]

#: the joint types the general formulation writes: each a product of factors, one per
#: coordinate, a half-angle pair's rotation or a slide pair's translation (R, P; C and the
#: translation joints T2 and T3, abelian, are the exponential of the sum the kinematic
#: model writes; U, the model's two exponentials) and S by its quaternion; a helical
#: joint's slide is not polynomial in its angle, nor are the exponential coordinates of a
#: planar (E) or Schoenflies (X) joint, whose rotation and translations do not commute
WRITTEN = ("R", "P", "C", "U", "S", "T2", "T3")


@dataclass(frozen=True)
class Group:
    """One variable group: the joint it belongs to, ``kind`` (``R`` a half-angle pair,
    ``P`` a slide's pair, ``S`` a rotation's quaternion), its symbols."""

    joint: str
    kind: str
    gens: tuple[sympy.Symbol, ...]

    @property
    def dim(self) -> int:
        return len(self.gens) - 1


def study_number(x: Any) -> Any:
    """A number at the working digits plus guard digits, as a sympy Float."""
    if isinstance(x, (int, sympy.Integer)):
        return sympy.Integer(x)
    return sympy.Float(
        mpmath.mpf(x) if not isinstance(x, sympy.Basic) else sympy.N(x, mpmath.mp.dps + 10),
        mpmath.mp.dps + 10,
    )


def expanded(v: list[Any]) -> list[Any]:
    return [sympy.expand(x) for x in v]


def working_mpf(x: Any) -> Any:
    """A given value (float, exact) at the working digits plus guard digits."""
    if isinstance(x, (float, int)):
        return mpmath.mpf(x)
    return mpmath.mpf(sympy.N(sympy.sympify(x), mpmath.mp.dps + 10))


class Joints:
    """Each joint's displacement in Study coordinates: unknown (linear in its groups) or
    given (a constant)."""

    def __init__(self, mech: Mechanism, given: dict[str, list[Any]]) -> None:
        from mechsing.kinematics import KinematicModel

        self.mech = mech
        self.km = KinematicModel(mech, f"mp:{mpmath.mp.dps + 10}")
        self.L = mpmath.mpf(self.km.length_scale)
        self.given = given
        self.groups: list[Group] = []
        self.of: dict[str, tuple[int, ...]] = {}
        self.cache: dict[str, list[Any]] = {}

    def _line(self, e: Any) -> list[Any]:
        w = [study_number(x) for x in e[:3]]
        v = [study_number(mpmath.mpf(x) / self.L) for x in e[3:]]
        return [0, *w, 0, *v]

    def _group(self, name: str, kind: str, n: int) -> tuple[sympy.Symbol, ...]:
        k = len(self.groups)
        gens = sympy.symbols(f"g{k}_0:{n}")
        self.groups.append(Group(name, kind, gens))
        self.of[name] = (*self.of.get(name, ()), k)
        return gens

    def element(self, name: str) -> list[Any]:
        """The joint's displacement (8 sympy expressions)."""
        if name in self.cache:
            return self.cache[name]
        j = self.mech.joint(name)
        if j.type not in WRITTEN:
            raise FormulationError(
                f"joint {name} is of type {j.type}: the general formulation writes R, P, C, U, "
                "S, T2 and T3 joints (a helical joint's slide is not polynomial in its angle, "
                "nor are a planar or Schoenflies joint's exponential coordinates)"
            )
        basis = self.km.joint(name).basis
        values = self.given.get(name)
        if isinstance(values, Displacement):
            raise FormulationError(
                f"joint {name} is given as a displacement; modes takes joint values"
            )
        factors = []
        if j.type == "S":
            p = [mpmath.mpf(x) / self.L for x in self.km.point_array(j.params["point"])]
            if values is None:
                r = list(self._group(name, "S", 4))
            else:
                r = quaternion_of_vector([working_mpf(x) for x in values])
            cross = [
                p[1] * r[3] - p[2] * r[2],
                p[2] * r[1] - p[0] * r[3],
                p[0] * r[2] - p[1] * r[1],
            ]
            factors.append([*r, 0, *(c if values is None else study_number(c) for c in cross)])
            factors[0][:4] = [x if values is None else study_number(x) for x in factors[0][:4]]
        else:
            for i, e in enumerate(basis):
                rotates = any(mpmath.mpf(x) != 0 for x in e[:3])
                A = self._line(e) if rotates else [0, 0, 0, 0, 0, *(study_number(x) for x in e[3:])]
                kind = "R" if rotates else "P"
                if values is None:
                    c, s = self._group(name, kind, 2)
                else:
                    q = working_mpf(values[i])
                    c, s = (
                        (mpmath.cos(q / 2), mpmath.sin(q / 2))
                        if rotates
                        else (mpmath.mpf(1), q / (2 * self.L))
                    )
                    c, s = study_number(c), study_number(s)
                factors.append([c if k == 0 else 0 for k in range(8)])
                factors[-1] = [a + s * b for a, b in zip(factors[-1], A, strict=True)]
        out = factors[0]
        for f in factors[1:]:
            out = expanded(study_multiply(out, f))
        self.cache[name] = out
        return out


def quaternion_of_vector(v: list[Any]) -> list[Any]:
    """The unit quaternion of a rotation vector (mpmath)."""
    r = [mpmath.mpf(x) for x in v]
    t = mpmath.sqrt(sum(x * x for x in r))
    if t == 0:
        return [mpmath.mpf(1), 0, 0, 0]
    return [mpmath.cos(t / 2), *(mpmath.sin(t / 2) * x / t for x in r)]
