"""Naming the geometry where a factor of a condition vanishes (``mechsing condition``).

:class:`Explainer` takes a zero of a factor (the other joints at random values),
places the chain's joint axes there and looks for what is new compared with a
generic configuration: parallel or coincident axes, the output point on an
axis, three planar pivots in line, a wrist centre in a special plane; an arm's
factor is then named wrist, elbow or shoulder.  Also the random exact joint
values (on the circle) and numeric evaluation the derivations share.
"""

from __future__ import annotations

import itertools
import math
import random
from typing import Any

import numpy as np
import sympy

from mechsing.conditions.symbolic import JointSymbols
from mechsing.numeric import (
    CONDITION_GENERIC_RANK_RTOL,
    CONDITION_GEOMETRY_RTOL,
    CONDITION_ROOT_RTOL,
)

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
                out.append((n, None, v / np.linalg.norm(v)))
            else:
                nw = np.linalg.norm(w)
                out.append((n, np.cross(w, v) / nw**2, w / nw))
        return out

    def facts(self, pt: dict[Any, Any]) -> set[str]:
        tol = CONDITION_GEOMETRY_RTOL
        L = self.lines(pt)
        facts: set[str] = set()
        for (a, pa, ua), (b, pb, ub) in itertools.combinations(L, 2):
            if pa is None or pb is None:
                continue
            if np.linalg.norm(np.cross(ua, ub)) < tol:
                d = np.linalg.norm(np.cross(pb - pa, ua))
                if d < tol * self.scale:
                    facts.add(f"the axes of {a} and {b} coincide")
                elif not self.planar:
                    facts.add(f"the axes of {a} and {b} are parallel")
        P = None
        if self.point is not None:
            P = numeric(self.point, pt, self.params).ravel()
            for n, p, u in L:
                if p is not None and np.linalg.norm(np.cross(P - p, u)) < tol * self.scale:
                    facts.add(f"the output point is on the axis of {n}")
        facts |= self.centre_facts(L)
        # three parallel axes (or two and the output point) in one plane
        items = [(n, p, u) for n, p, u in L if p is not None]
        if P is not None and items:
            items.append(("the output point", P, items[0][2]))
        for (a, pa, ua), (b, pb, ub), (c, pc, uc) in itertools.combinations(items, 3):
            if max(np.linalg.norm(np.cross(ua, ub)), np.linalg.norm(np.cross(ua, uc))) > tol:
                continue
            d1 = pb - pa - ua * np.dot(pb - pa, ua)
            d2 = pc - pa - ua * np.dot(pc - pa, ua)
            if np.linalg.norm(np.cross(d1, d2)) < tol * self.scale**2:
                if self.planar:
                    facts.add(
                        f"the pivots of {a}, {b} and {c} are in line (the links between them "
                        "stretched or folded)"
                    )
                else:
                    facts.add(
                        f"the parallel axes of {a}, {b} and {c} lie in one plane (the links "
                        "between them stretched or folded)"
                    )
        return facts

    def centre_facts(self, L: list[tuple[str, Any, Any]]) -> set[str]:
        """Where three or more axes meet (a wrist centre): is it in the plane of two
        parallel axes, or in the plane through one axis parallel to another?"""
        tol = CONDITION_GEOMETRY_RTOL
        R = [(n, p, u) for n, p, u in L if p is not None]
        out: set[str] = set()
        for trio in itertools.combinations(R, 3):
            us = [u for _, _, u in trio]
            if min(np.linalg.norm(np.cross(a, b)) for a, b in itertools.combinations(us, 2)) < tol:
                continue
            (_, p1, u1), (_, p2, u2) = trio[0], trio[1]
            A = np.column_stack([u1, -u2])
            t = np.linalg.lstsq(A, p2 - p1, rcond=None)[0]
            W = p1 + t[0] * u1
            if any(np.linalg.norm(np.cross(W - p, u)) > tol * self.scale for _, p, u in trio):
                continue
            who = ", ".join(n for n, _, _ in trio)
            if abs(np.linalg.det(np.column_stack(us))) < tol:
                out.add(f"the axes of {who} (meeting at one point) are in one plane")
            for (a, pa, ua), (b, pb, ub) in itertools.combinations(R, 2):
                if a in who.split(", ") or b in who.split(", "):
                    continue
                normal = np.cross(ua, ub)
                if np.linalg.norm(normal) < tol:
                    normal = np.cross(ua, pb - pa)
                    if np.linalg.norm(normal) < tol * self.scale:
                        continue
                    where = f"the plane of the parallel axes of {a} and {b}"
                else:
                    where = f"the plane through the axis of {a} parallel to the axis of {b}"
                normal = normal / np.linalg.norm(normal)
                if abs(np.dot(W - pa, normal)) < tol * self.scale:
                    out.add(f"the wrist centre (where {who} meet) is in {where}")
        return out

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
            new = sorted(self.facts(pt) - generic)
            joints = sorted(
                {
                    js.q.name
                    for js in self.S
                    if f.has(js.q) or (js.c is not None and (f.has(js.c) or f.has(js.s)))
                }
            )
            if new:
                kind = _kind(new) if self.arm else ""
                return kind + "vanishes when " + "; ".join(new)
            return f"a condition on {', '.join(joints)} (no parallel axes or aligned pivots there)"
        return None


def _kind(facts: list[str]) -> str:
    """The name arm designers give a singularity with these geometric facts."""
    text = " ".join(facts)
    if "plane through the axis" in text:
        return "shoulder: "
    if "plane of the parallel axes" in text or "in line" in text or "lie in one plane" in text:
        return "elbow: "
    if "coincide" in text or "are parallel" in text:
        return "wrist: "
    return ""


def _root_of(f: Any, var: JointSymbols, pt: dict[Any, Any], params: list[Any]) -> float | None:
    """A real angle of ``var`` where ``f`` vanishes, the other joints at ``pt``."""
    sub = {k: v for k, v in pt.items() if k not in (var.c, var.s, var.q)}
    for p in params:
        sub[p] = p.parameter_value
    t = sympy.Dummy("t")
    g = sympy.sympify(f).xreplace(sub)
    g = sympy.together(g.xreplace({var.c: (1 - t**2) / (1 + t**2), var.s: 2 * t / (1 + t**2)}))
    num = sympy.numer(g)
    try:
        coeffs = [float(sympy.N(c, 30)) for c in sympy.Poly(num, t).all_coeffs()]
    except (sympy.PolynomialError, TypeError):
        return None
    if len(coeffs) < 2:
        return math.pi if len(coeffs) == 1 else None
    roots = [
        r.real for r in np.roots(coeffs) if abs(r.imag) < CONDITION_ROOT_RTOL * max(1.0, abs(r))
    ]
    if not roots:
        return None
    return 2 * math.atan(roots[0])
