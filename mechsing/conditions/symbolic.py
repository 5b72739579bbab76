"""Symbolic kinematics of R, P and H joints for singularity conditions.

Owns the exact, symbolic product of exponentials that the conditions use:
each joint value is a sympy symbol named by its joint, written through the
polynomial symbols ``c_J = cos(J)`` and ``s_J = sin(J)`` for a revolute or
helical joint (so that determinants are polynomials, reduced with
``s_J**2 = 1 - c_J**2``), and the symbol ``J`` itself for a prismatic one.

Conventions are the mechanism file's: a joint with ``between: [a, b]`` sets
``g_b = g_a exp(q xi)`` with ``xi`` its reference screw in the ground frame;
a twist is ``(omega, v)``, angular first, ``v`` the velocity of the body point
at the origin of the frame used; lengths in metres, angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import sympy

from mechsing.errors import UserError
from mechsing.model import Mechanism

__all__ = [
    "JOINT_TYPES",
    "JointSymbols",
    "SE3",
    "joint_symbols",
    "reference_twist",
    "motion",
    "to_trig",
    "reduce_trig",
    "tan_half",
]

#: joint types the symbolic kinematics handles (one coordinate each)
JOINT_TYPES = ("R", "P", "H")


@dataclass(frozen=True)
class JointSymbols:
    """The symbols of one joint: ``q`` (named by the joint), and ``c``, ``s``
    (its cosine and sine) for a revolute or helical joint, else None."""

    q: Any
    c: Any
    s: Any


def joint_symbols(mech: Mechanism) -> dict[str, JointSymbols]:
    """Symbols of every joint; refuses joints the symbolic kinematics does not handle."""
    out: dict[str, JointSymbols] = {}
    for j in mech.joints:
        if j.type not in JOINT_TYPES:
            raise UserError(
                f"{mech.path}:{j.line}: joint {j.name!r}: symbolic conditions handle joints of "
                f"types {', '.join(JOINT_TYPES)} (one coordinate each); this one is of type "
                f"{j.type}. Write it as R and P joints in a copy of the file, or use "
                "'mechsing analyze' for its numerical singularities"
            )
        q = sympy.Symbol(j.name, real=True)
        if j.type == "P":
            out[j.name] = JointSymbols(q, None, None)
        else:
            out[j.name] = JointSymbols(
                q, sympy.Symbol(f"c_{j.name}", real=True), sympy.Symbol(f"s_{j.name}", real=True)
            )
    return out


@dataclass(frozen=True)
class SE3:
    """A displacement ``x -> R x + p`` (sympy 3x3 and 3x1 matrices)."""

    R: Any
    p: Any

    @staticmethod
    def identity() -> SE3:
        return SE3(sympy.eye(3), sympy.zeros(3, 1))

    def __mul__(self, other: SE3) -> SE3:
        return SE3(_expand(self.R * other.R), _expand(self.R * other.p + self.p))

    def inverse(self) -> SE3:
        Rt = self.R.T
        return SE3(Rt, _expand(-Rt * self.p))

    def point(self, x: Any) -> Any:
        return _expand(self.R * x + self.p)

    def twist(self, xi: Any) -> Any:
        """``Ad(g) xi`` for a twist ``(omega, v)``."""
        w = self.R * xi[:3, :]
        v = self.R * xi[3:, :] + self.p.cross(w)
        return _expand(sympy.Matrix.vstack(w, v))


def _expand(m: Any) -> Any:
    return m.applyfunc(sympy.expand)


def _hat(u: Any) -> Any:
    return sympy.Matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])


def reference_twist(joint: Any) -> Any:
    """The joint's reference screw ``(omega, v)`` in the ground frame (a 6x1 matrix)."""
    u = sympy.Matrix(joint.params["axis"])
    if joint.type == "P":
        return sympy.Matrix.vstack(sympy.zeros(3, 1), u)
    p = sympy.Matrix(joint.params["point"])
    h = joint.params.get("pitch", 0) if joint.type == "H" else 0
    return sympy.Matrix.vstack(u, p.cross(u) + h * u)


def motion(joint: Any, sym: JointSymbols, sign: int = 1) -> SE3:
    """``exp(sign * q * xi)`` of the joint, in the symbols ``c``, ``s`` (or ``q``)."""
    u = sympy.Matrix(joint.params["axis"])
    if joint.type == "P":
        return SE3(sympy.eye(3), sign * sym.q * u)
    s = sign * sym.s
    K = _hat(u)
    R = _expand(sympy.eye(3) + s * K + (1 - sym.c) * K * K)
    p = sympy.Matrix(joint.params["point"])
    t = (sympy.eye(3) - R) * p
    if joint.type == "H":
        t = t + sign * joint.params["pitch"] * sym.q * u
    return SE3(R, _expand(t))


def reduce_trig(expr: Any, syms: list[JointSymbols]) -> Any:
    """``expr`` with every ``s**2`` replaced by ``1 - c**2`` (degree at most 1 in each s),
    expanded.  Works on the exponents of the polynomial's terms (a power ``s**k`` becomes
    ``s**(k % 2) * (1 - c**2)**(k // 2)`` by the binomial theorem), which is much faster
    than expanding expressions."""
    e = sympy.expand(expr)
    pairs = [(js.s, js.c) for js in syms if js.s is not None and e.has(js.s)]
    if not pairs:
        return e
    poly = sympy.Poly(e)
    gens = list(poly.gens)
    missing = [c for _, c in pairs if c not in gens]
    if missing:
        gens += missing
        poly = sympy.Poly(e, *gens)
    terms = dict(poly.terms())
    for s, c in pairs:
        i, j = gens.index(s), gens.index(c)
        out: dict[tuple[int, ...], Any] = {}
        for monom, coeff in terms.items():
            k = monom[i]
            if k < 2:
                out[monom] = out.get(monom, 0) + coeff
                continue
            n = k // 2
            for m in range(n + 1):
                mon = list(monom)
                mon[i] = k % 2
                mon[j] += 2 * m
                key = tuple(mon)
                out[key] = out.get(key, 0) + coeff * math.comb(n, m) * (-1) ** m
        terms = {m: v for m, v in out.items() if v != 0}
    if not terms:
        return sympy.Integer(0)
    return sympy.Poly.from_dict(terms, *gens, domain=poly.domain).as_expr()


def tan_half(p: Any, js: JointSymbols, t: Any, k: int | None = None) -> Any:
    """The polynomial ``p(c, s) * (1 + t**2)**k`` with ``c = (1 - t**2)/(1 + t**2)``,
    ``s = 2 t/(1 + t**2)`` (``t = tan(J/2)``), expanded; ``k`` is p's total degree in
    ``c``, ``s`` unless given (at least that).  Its degree in t is ``2 k`` less the
    multiplicity of the zero at ``J = pi`` (``t = oo``).  Composed term by term as
    polynomials in t (no rational functions to cancel)."""
    if not (p.has(js.c) or p.has(js.s)):
        return sympy.expand(p * (1 + t**2) ** (k or 0))
    poly = sympy.Poly(p, js.c, js.s)
    if k is None:
        k = int(poly.total_degree())
    pw: dict[tuple[int, int], sympy.Poly] = {}

    def power(which: int, n: int) -> sympy.Poly:
        if (which, n) not in pw:
            base = (1 - t**2, 2 * t, 1 + t**2)[which]
            pw[(which, n)] = sympy.Poly(base**n, t)
        return pw[(which, n)]

    out = sympy.Poly(0, t)
    for (i, j), coeff in poly.terms():
        out += power(0, i) * power(1, j) * power(2, k - i - j) * sympy.Poly(coeff, t)
    return sympy.expand(out.as_expr())


def to_trig(expr: Any, syms: list[JointSymbols]) -> Any:
    """A polynomial in the ``c``, ``s`` symbols written with ``cos(J)``, ``sin(J)``,
    sums of angles combined where that shortens it."""
    sub = {}
    for js in syms:
        if js.c is not None:
            sub[js.c] = sympy.cos(js.q)
            sub[js.s] = sympy.sin(js.q)
    e = sympy.sympify(expr).xreplace(sub)
    best = e
    try:
        cand = sympy.trigsimp(e)
        if sympy.count_ops(cand) < sympy.count_ops(best):
            best = cand
    except Exception:  # pragma: no cover - sympy failure: keep the plain form
        pass
    return best
