"""Naming the geometry where a factor of a condition vanishes (``mechsing condition``).

:class:`Explainer` takes a zero of a factor (the other joints at random values),
places the chain's joint axes there and looks for what is new compared with a
generic configuration: parallel or coincident axes, the output point on an
axis, three planar pivots in line, a wrist centre in a special plane; an arm's
factor is then named wrist, elbow or shoulder.  Also the random exact joint
values (on the circle) and numeric evaluation the derivations share.
"""

from __future__ import annotations

import math
import random
from typing import Any

import numpy as np
import sympy

from mechsing.conditions.symbolic import JointSymbols
from mechsing.numeric import CONDITION_GENERIC_RANK_RTOL, CONDITION_ROOT_RTOL
from mechsing.numeric.numbers import unit_vector
from mechsing.singularity.names import line_facts, name_of

__all__ = ["Explainer", "numeric", "random_point", "rank"]


def random_point(S: list[JointSymbols], rng: random.Random) -> dict[Any, Any]:
    """Random joint values as exact rationals on the circle (c, s) and for q."""
    pt: dict[Any, Any] = {}
    for js in S:
        u = sympy.Rational(rng.randint(-900, 900), 400)
        if js.c is not None:
            pt[js.c] = (1 - u**2) / (1 + u**2)
            pt[js.s] = 2 * u / (1 + u**2)
            pt[js.q] = 2 * sympy.atan(u)
        else:
            pt[js.q] = u / 3
    return pt


def numeric(M: Any, pt: dict[Any, Any], params: list[Any]) -> np.ndarray:
    sub = dict(pt)
    for p in params:
        sub[p] = p.parameter_value
    return np.array(M.xreplace(sub).evalf(30).tolist(), dtype=float)


def rank(A: np.ndarray) -> int:
    s = np.linalg.svd(A, compute_uv=False)
    if s.size == 0 or s[0] == 0:
        return 0
    return int(np.sum(s > CONDITION_GENERIC_RANK_RTOL * s[0]))


# ---------------------------------------------------------------------------
# explanations: geometry where a factor vanishes
# ---------------------------------------------------------------------------


class Explainer:
    """Tests the geometry of a chain's columns at a zero of a factor: parallel or
    coincident axes, the output point on an axis, three planar pivots in line."""

    def __init__(
        self,
        names: list[str],
        types: list[str],
        cols: list[Any],
        S: list[JointSymbols],
        params: list[Any],
        point: Any = None,
        planar: bool = False,
        scale: float = 1.0,
        arm: bool = True,
    ) -> None:
        self.arm = arm  # name the factors as an arm's (wrist, elbow, shoulder)
        self.names, self.types, self.cols = names, types, cols
        self.S, self.params, self.point, self.planar = S, params, point, planar
        self.scale = scale

    def lines(self, pt: dict[Any, Any]) -> list[tuple[str, np.ndarray | None, np.ndarray]]:
        out = []
        for n, t, c in zip(self.names, self.types, self.cols, strict=True):
            x = numeric(c, pt, self.params).ravel()
            w, v = x[:3], x[3:]
            if t == "P":
                out.append((n, None, unit_vector(v)))
            else:
                nw = np.linalg.norm(w)
                out.append((n, np.cross(w, v) / nw**2, w / nw))
        return out

    def facts(self, pt: dict[Any, Any]) -> dict[str, Any]:
        P = None if self.point is None else numeric(self.point, pt, self.params).ravel()
        return line_facts(self.lines(pt), P, self.planar, self.scale)

    def __call__(self, f: Any) -> str | None:
        rng = random.Random(7)
        base = random_point(self.S, rng)
        generic = self.facts(base)
        var = None
        for js in self.S:
            if js.c is not None and (f.has(js.c) or f.has(js.s)):
                var = js
                break
        if var is None:
            return None
        for _ in range(4):
            pt = random_point(self.S, rng)
            root = _root_of(f, var, pt, self.params)
            if root is None:
                continue
            pt[var.c], pt[var.s] = sympy.Float(math.cos(root), 30), sympy.Float(math.sin(root), 30)
            pt[var.q] = sympy.Float(root, 30)
            facts = self.facts(pt)
            new = sorted(t for t in facts if t not in generic)
            joints = sorted(
                {
                    js.q.name
                    for js in self.S
                    if f.has(js.q) or (js.c is not None and (f.has(js.c) or f.has(js.s)))
                }
            )
            if new:
                name = name_of([facts[t][0] for t in new]) if self.arm else None
                kind = f"{name}: " if name else ""
                return kind + "vanishes when " + "; ".join(new)
            return f"a condition on {', '.join(joints)} (no parallel axes or aligned pivots there)"
        if _no_real_zero(f, var, self.params):
            return f"never vanishes: no real value of {var.q.name} makes it zero"
        return None


def _half_angle_coefficients(g: Any, var: JointSymbols) -> list[float] | None:
    """The coefficients (highest first, float) of the numerator of ``g`` written in the
    half angle t = tan(q / 2) of the joint ``var`` (its cosine and sine replaced by
    (1 - t^2) / (1 + t^2) and 2 t / (1 + t^2)); None where it is not a polynomial in t."""
    t = sympy.Dummy("t")
    num = sympy.numer(
        sympy.together(g.xreplace({var.c: (1 - t**2) / (1 + t**2), var.s: 2 * t / (1 + t**2)}))
    )
    try:
        return [float(sympy.N(c, 30)) for c in sympy.Poly(num, t).all_coeffs()]
    except (sympy.PolynomialError, TypeError):
        return None


def _real_roots(coeffs: list[float]) -> list[float]:
    """The real roots of the polynomial of ``coeffs`` (within CONDITION_ROOT_RTOL: a double
    root read as a near pair is a root)."""
    return [
        r.real for r in np.roots(coeffs) if abs(r.imag) < CONDITION_ROOT_RTOL * max(1.0, abs(r))
    ]


def _no_real_zero(f: Any, var: JointSymbols, params: list[Any]) -> bool:
    """Whether ``f``, a function of the one joint angle ``var`` alone (its cosine and
    sine, the parameters at their values), vanishes at no real angle: at the half angle
    its numerator has no real root (:func:`_real_roots`), and f(pi), the one angle the
    half angle misses, is not 0."""
    g = sympy.sympify(f).xreplace({p: p.parameter_value for p in params})
    if var.c is None or g.free_symbols - {var.c, var.s}:
        return False
    coeffs = _half_angle_coefficients(g, var)
    if not coeffs or not any(coeffs):
        return False
    # f(pi), against the numerator's size (at pi it is the numerator's leading coefficient)
    at_pi = float(sympy.N(g.xreplace({var.c: -1, var.s: 0}), 30))
    if abs(at_pi) <= CONDITION_ROOT_RTOL * max(abs(c) for c in coeffs):
        return False
    return len(coeffs) < 2 or not _real_roots(coeffs)


def _root_of(f: Any, var: JointSymbols, pt: dict[Any, Any], params: list[Any]) -> float | None:
    """A real angle of ``var`` where ``f`` vanishes, the other joints at ``pt``."""
    sub = {k: v for k, v in pt.items() if k not in (var.c, var.s, var.q)}
    for p in params:
        sub[p] = p.parameter_value
    coeffs = _half_angle_coefficients(sympy.sympify(f).xreplace(sub), var)
    if coeffs is None:
        return None
    if len(coeffs) < 2:
        return math.pi if len(coeffs) == 1 else None
    roots = _real_roots(coeffs)
    if not roots:
        return None
    return 2 * math.atan(roots[0])
