"""One loop closed by a rod between two ball joints, with one other joint unknown (an
RSSR with its crank given, an RSSP, a PSSR): the distance between the rod's balls.

A rod held by exactly two S joints constrains the rest of its loop only by the distance
between their centres, ``|c - b| = l`` (its spin about their line is idle, :mod:`.spins`).
With every other joint of the loop given but one, ``k``, the loop's closure ``F_1 F_2 X =
1`` (the rod's joints ``F_1``, ``F_2`` about their centres ``p1``, ``p2``; ``X = K1 F_k
K2`` the rest, ``K1`` and ``K2`` the given joints' products) keeps ``|p2 - X(p1)| = |p2
- p1|``, so with ``a = K1^-1(p2)``, ``b = K2(p1)``:

* ``k`` a revolute about the line through ``o`` along the unit ``w``, turned by ``t``:
  ``|a - o - R(t)(b - o)|^2 = l^2``, that is ``A cos t + B sin t + K = 0`` (``R(t) u = u
  cos t + (w x u) sin t + w (w.u)(1 - cos t)``): in its half-angle pair ``(c, s)`` the
  quadratic form ``(K + A) c^2 + 2 B c s + (K - A) s^2``, two real roots where ``A^2 +
  B^2 - K^2 > 0``, none where it is negative (the classical RSSR: F. Freudenstein and E.
  J. F. Primrose, ASME J. Eng. Ind. 85, 1963);
* ``k`` a slide by ``x`` along ``w``: ``|a - b - x w|^2 = l^2``, a quadratic in ``x``,
  two real roots where ``(w.(a - b))^2 - |a - b|^2 + l^2 > 0``.

Each real root is one mode: the rod taken free of its spin (the least rotation of the
ball joint :mod:`.spins` names turning the rod where it points), written in the general
formulation's coordinates (:mod:`.general`: the same system, the same modes), refined by
Newton's method and certified by the Krawczyk test there.  Two certified modes apart
prove the count: a certified mode is isolated, so the quadratic is not identically zero
and has at most two roots, and each root has one mode (the least rotation is unique
unless the rod is turned half about an axis normal to it, where a circle of spins closes
and Newton's Jacobian is singular).  Where its two roots are complex, their solutions
are certified in boxes clear of the real ones (:func:`~mechsing.assembly.certify.certified_roots`):
no mode, proven.  A double root (a dead centre of the loop) or a root whose mode is
singular hands the problem to the general formulation.

Owns :data:`FORMULATION`.
"""

from __future__ import annotations

from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.assembly.chains import Found
from mechsing.assembly.given import Formulation, Given
from mechsing.errors import FormulationError
from mechsing.lie import cross, dot
from mechsing.lie.dual import study_conjugate, study_multiply
from mechsing.lie.quaternion import quat_rotate

__all__ = ["FORMULATION"]


def _layout(given: Given) -> Any:
    """The general formulation's problem and the loop read as ``(S1, S2, k1 ... km)``
    cyclically (each with its sign), the unknown joint's place among ``k1 ... km``
    (FormulationError: why the mechanism is not such a loop)."""
    from mechsing.assembly.general import problem
    from mechsing.assembly.spins import idle_rods

    mech = given.mech
    if given.values is None or len(mech.loops) != 1:
        raise FormulationError("not a single loop with given joint values")
    loop = mech.loops[0]
    if {j.name for j in mech.joints} != set(loop.joints):
        raise FormulationError("not every joint lies on the loop")
    rods = idle_rods(mech, given.values)
    if len(rods) != 1:
        raise FormulationError("the loop has no rod between two ball joints")
    _, first, second = rods[0]
    others = [n for n in loop.joints if n not in (first, second, *given.values)]
    if len(others) != 1 or mech.joint(others[0]).type not in ("R", "P"):
        raise FormulationError(
            "besides the rod's ball joints, the unknown joints are not one revolute or slide"
        )
    (k,) = others
    prob = given.cache.get("general") or problem(given)  # (built once the rest applies)
    given.cache["general"] = prob
    names, signs = list(loop.joints), list(loop.signs)
    n = len(names)
    i, j = names.index(first), names.index(second)
    if (j - i) % n == n - 1:
        i = j  # the rod's joints are crossed second-first
    order = [(i + d) % n for d in range(n)]
    seq = [(names[m], signs[m]) for m in order]
    rest = seq[2:]
    place = [nm for nm, _ in rest].index(k)
    return prob, seq[:2], rest, place


def _applies(given: Given) -> str | None:
    try:
        _layout(given)
    except FormulationError as reason:
        return str(reason)
    return None


def _dot(u: Any, v: Any) -> Any:
    return dot(u, v)[()]


def _cross(u: Any, v: Any) -> list[Any]:
    return list(cross(u, v))


def _act(D: list[Any], x: list[Any]) -> list[Any]:
    """The displacement of the Study coordinates ``D`` applied to the point ``x``: ``R x
    + t``, ``t`` the vector part of ``2 Y X* / |X|^2``."""
    X, Y = D[:4], D[4:]
    n2 = _dot(X[1:], X[1:]) + X[0] * X[0]
    o = [X[0] * 0] * 4  # (zeros of the numbers' own kind: numpy reads plain 0s as floats)
    t = study_multiply([*Y, *o], [*study_conjugate([*X, *o])[:4], *o])
    moved = list(quat_rotate(_objects(X), _objects(x)))
    return [moved[m] + 2 * t[m + 1] / n2 for m in range(3)]


def _objects(v: Any) -> Any:
    """An object array of the numbers (what the quaternion functions take for mpmath)."""
    out = np.empty(len(v), dtype=object)
    out[:] = list(v)
    return out


def _product(parts: list[list[Any]], one: Any) -> list[Any]:
    """The parts' product (``one``: the numbers' kind of 1)."""
    out: list[Any] = [one, *[one * 0] * 7]
    for p in parts:
        out = study_multiply(out, p)
    return out


class _Loop:
    """The loop's numbers (mpmath, at the working digits plus guard digits): the rod's
    centres, the given joints' products before and after the unknown one, its line."""

    def __init__(self, given: Given) -> None:
        from mechsing.assembly.displacements import Joints

        prob, rod, rest, place = _layout(given)
        self.prob, self.rod, self.rest, self.place = prob, rod, rest, place
        joints = Joints(given.mech, prob.given)
        self.joints = joints
        L = joints.L

        def num(v: list[Any]) -> list[Any]:
            return [mpmath.mpf(sympy.N(x, mpmath.mp.dps + 10)) for x in v]

        self.p = [
            num([x / L for x in joints.km.point_array(given.mech.joint(nm).params["point"])])
            for nm, _ in rod
        ]
        parts = []
        for nm, sign in rest:
            F = joints.element(nm)
            parts.append(F if sign > 0 else study_conjugate(F))
        self.k, self.sign = rest[place]
        grp = joints.groups[joints.of[self.k][0]]  # (this object's own symbols)
        self.kind = grp.kind
        line = [sympy.expand(x).coeff(grp.gens[1]) for x in joints.element(self.k)]
        self.line = num(line)
        self.one = num([1])[0]
        self.K1 = _product([num(F) for F in parts[:place]], self.one)
        self.K2 = _product([num(F) for F in parts[place + 1 :]], self.one)

    def coefficients(self) -> tuple[Any, Any, Any]:
        """``(A, B, K)`` of ``A cos t + B sin t + K = 0`` (a revolute turned by ``t`` as
        the loop crosses it) or of ``A x^2 + B x + K = 0`` (a slide by ``x``, over L)."""
        p1, p2 = self.p
        a = _act(study_conjugate(self.K1), p2)
        b = _act(self.K2, p1)
        d0 = [p2[m] - p1[m] for m in range(3)]
        l2 = _dot(d0, d0)
        if self.kind == "R":
            w, mom = self.line[1:4], self.line[5:8]
            o = _cross(w, mom)
            u = [b[m] - o[m] for m in range(3)]
            v = [a[m] - o[m] for m in range(3)]
            wu, wv = _dot(w, u), _dot(w, v)
            alpha = _dot(v, u) - wv * wu
            beta = _dot(v, _cross(w, u))
            return -2 * alpha, -2 * beta, _dot(v, v) + _dot(u, u) - 2 * wv * wu - l2
        w = self.line[5:8]  # the slide's direction: c + s eps w, the slide 2 s over L
        g = [a[m] - b[m] for m in range(3)]
        return 1, -2 * _dot(w, g), _dot(g, g) - l2


def _roots(A: Any, B: Any, K: Any, kind: str) -> list[Any]:
    """The two roots (mpmath, complex conjugates where the discriminant is negative):
    the angles ``t`` or slides ``x``."""
    if kind == "R":
        h = mpmath.sqrt(A * A + B * B)
        phi, dt = mpmath.atan2(B, A), mpmath.acos(-K / h)
        return [phi - dt, phi + dt]
    h = mpmath.sqrt(B * B - 4 * A * K)
    return [(-B - h) / (2 * A), (-B + h) / (2 * A)]


def _spin_free(d: list[Any], e: list[Any]) -> list[Any]:
    """The least rotation (a quaternion, of square norm 1) turning the direction ``d`` to
    ``e``, where ``e.e = d.d`` (at a root of the rod's distance equation; complex there
    where the root is)."""
    r = [_dot(d, d) + _dot(d, e), *_cross(d, e)]
    size = mpmath.sqrt(sum(x * x for x in r))
    if abs(size) <= mpmath.mpf(10) ** (-(mpmath.mp.dps // 2)) * abs(_dot(d, d)):
        raise FormulationError("the rod is turned half about an axis normal to it")
    return [x / size for x in r]


def _point(lp: _Loop, t: Any) -> list[Any]:
    """The general formulation's coordinates of the mode where the unknown joint is at
    ``t`` as the loop crosses it (its angle, or its slide over L)."""
    prob = lp.prob
    q = lp.sign * t
    pair = [mpmath.cos(q / 2), mpmath.sin(q / 2)] if lp.kind == "R" else [mpmath.mpf(1), q / 2]
    F = [pair[1] * x for x in lp.line]
    F[0] += pair[0]
    Fk = F if lp.sign > 0 else study_conjugate(F)
    X = _product([lp.K1, Fk, lp.K2], lp.one)
    p1, p2 = lp.p
    Xi = study_conjugate(X)
    (n1, s1), (n2, s2) = lp.rod
    spin = prob.spins[0][1]
    if spin == n1:  # F_1 turns p2 - p1 to X^-1(p2) - p1
        e = _act(Xi, p2)
        F1 = _rotation(
            _spin_free([p2[m] - p1[m] for m in range(3)], [e[m] - p1[m] for m in range(3)]), p1
        )
        F2 = _product([study_conjugate(F1), Xi], lp.one)
    else:  # F_2^-1 turns p1 - p2 to X(p1) - p2
        e = _act(X, p1)
        G = _rotation(
            _spin_free([p1[m] - p2[m] for m in range(3)], [e[m] - p2[m] for m in range(3)]), p2
        )
        F2 = study_conjugate(G)
        F1 = _product([Xi, G], lp.one)
    quats = {
        n1: F1[:4] if s1 > 0 else study_conjugate(F1)[:4],
        n2: F2[:4] if s2 > 0 else study_conjugate(F2)[:4],
    }
    z: list[Any] = []
    for g in prob.groups:
        z += list(quats[g.joint]) if g.kind == "S" else pair
    return z


def _rotation(r: list[Any], p: list[Any]) -> list[Any]:
    """The rotation ``r`` about the point ``p``: ``r + eps (p x vec(r))``."""
    return [*r, 0, *_cross(p, r[1:])]


def _find(given: Given) -> Found:
    from mechsing.assembly.certify import apart, certified_roots, krawczyk, newton, regular
    from mechsing.assembly.general import _normalisations, _row
    from mechsing.assembly.result import joint_distance
    from mechsing.assembly.settings import MODE_CERTIFY_RADIUS
    from mechsing.numeric import MODE_MATCH_DISTANCE

    lp = _Loop(given)
    prob = lp.prob
    A, B, K = lp.coefficients()
    disc = A * A + B * B - K * K if lp.kind == "R" else B * B - 4 * A * K
    if disc == 0:
        raise FormulationError(
            "the rod's distance equation has a double root here (a dead centre of the loop)"
        )
    gens = prob.gens
    square = [*prob.equations, *_normalisations(prob)]
    radius = mpmath.mpf(MODE_CERTIFY_RADIUS)
    points = [_point(lp, t) for t in _roots(A, B, K, lp.kind)]
    rows = []
    if disc < 0:  # two complex roots: no mode, proven where both are certified not real
        found = certified_roots(square, gens, points, given.dps)
        proven = (
            found is not None
            and apart(found)
            and all(any(mpmath.im(v) != 0 for v in x) for x in found)
        )
    for start in points if disc > 0 else []:
        z = newton(square, gens, start, given.dps)
        if z is None or not regular(square, gens, z):
            raise FormulationError(
                "a root of the rod's distance equation is not a regular closed "
                "configuration (the rod turned half about an axis normal to it)"
            )
        rows.append((_row(given.mech, prob, z), krawczyk(square, gens, z, radius)))
    rows.sort(key=lambda r: [float(x) for x in r[0]])
    body, a, b = prob.spins[0]
    what = "half-angle pair" if lp.kind == "R" else "slide"
    formulation: dict[str, Any] = {
        "name": "distance formulation of a rod between two ball joints",
        "method": f"the rod's length as a quadratic in {lp.k}'s {what}, solved in closed "
        "form, each mode refined by Newton's method and certified in Study coordinates",
        "unknowns": [f"{lp.k} ({'half-angle pair' if lp.kind == 'R' else 'slide pair'})"],
        "polynomial_degree": 2,
        "idle_spins": [list(r) for r in prob.spins],
    }
    notes = [
        f"body {body} spins idly about the line through its ball joints {a} and {b}: "
        f"each mode is listed with {a}'s rotation free of spin about that line"
    ]
    if rows:
        (q1, ok1), (q2, ok2) = rows
        far = joint_distance(
            given.mech, [float(x) for x in q1], [float(x) for x in q2], float(lp.joints.L)
        )
        proven = ok1 and ok2 and far > MODE_MATCH_DISTANCE
    if proven:
        notes.append(
            f"{b}'s distance from {a} is the rod's length: a quadratic in {lp.k}'s {what} "
            "(not identically zero, since each of its solutions is certified isolated), so "
            "at most two closed configurations with the rod free of spin; "
            + (
                "both are found, each certified and apart from the other: no mode is missing"
                if rows
                else "both are complex, each certified in a box clear of the real ones: "
                "no real mode"
            )
        )
    return Found(
        formulation,
        rows,
        len(rows),
        "proven" if proven else "not proven",
        None,
        tuple(notes),
        1,
        given.cache.get("closure"),
    )


FORMULATION = Formulation(
    "the distance between a rod's two ball joints (one loop, one other unknown joint)",
    _applies,
    _find,
)
