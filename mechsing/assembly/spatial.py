"""Spatial platforms on distance legs (U-P-S or S-P-S with the slides given): every
platform pose in Study coordinates, by homotopy continuation (Bertini 2, the ``modes``
extra), refined by Newton's method at the working precision.

The pose ``x -> R x + t`` is the dual quaternion ``X + eps Y`` with ``Y = t X / 2``:
``R b = X b X* / |X|^2`` and ``t = 2 Y X* / |X|^2``.  A leg from the base point ``a`` to
the platform point ``b`` of length ``l`` is then one quadric (M. Husty, Mech. Mach.
Theory 31(4), 1996):

    (|a|^2 + |b|^2 - l^2) |X|^2 + 4 |Y|^2 + 4 b.vec(X* Y) - 2 a.vec(X b X*) - 4 a.vec(Y X*) = 0,

with the Study quadric ``X.Y = 0`` and a random affine patch: eight quadrics in eight
unknowns, 2^7 = 128 paths, 40 finite solutions for a general platform.  A mode is a
platform pose; each leg's U (or S) joint then has two solutions (the U's half-turn flip
with the leg turned about its axis), the same mode: one joint vector is listed, the
nearest the reference, and ``equivalent_solutions`` counts the others.

Owns :class:`SpatialSystem`, :func:`spatial_system`, :func:`solve_study`,
:func:`joint_values_spatial`, and the Study-coordinate pieces the leg formulation
(:mod:`.legs`) shares: :func:`distance_equation`, :func:`moved_point`,
:func:`moved_direction`, :func:`study_quadric`, :func:`two_axes`, :func:`angle_about`,
:func:`rotation_log`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.assembly.certify import newton
from mechsing.assembly.engine import SEED, real_endpoints, track
from mechsing.assembly.settings import MODE_ISOTROPIC_RTOL
from mechsing.assembly.study import rotation
from mechsing.errors import ConfigurationError, FormulationError
from mechsing.lie.quaternion import quat_conjugate, quat_multiply
from mechsing.model import Mechanism

__all__ = [
    "GENERIC_COUNT",
    "angle_about",
    "distance_equation",
    "moved_direction",
    "moved_point",
    "rotation_log",
    "study_quadric",
    "two_axes",
    "SpatialSystem",
    "joint_values_spatial",
    "linear_product_study",
    "off_exceptional",
    "out_of_reach",
    "patch_equation",
    "pose_of",
    "solve_study",
    "spatial_system",
    "track_study",
]

XS = sympy.symbols("x0:4", real=True)
YS = sympy.symbols("y0:4", real=True)
#: the generic number of finite solutions (Raghavan 1993; Dietmaier's platform has 40 real)
GENERIC_COUNT = 40


@dataclass(frozen=True)
class SpatialSystem:
    """The platform, each leg's (joints, base point a, platform point b, length^2) and
    the Study-coordinate equations (sympy, exact data)."""

    platform: str
    legs: tuple[tuple[tuple[str, str, str], Any, Any, Any], ...]
    equations: tuple[sympy.Expr, ...]


def spatial_system(mech: Mechanism, given: dict[str, tuple[Any, ...]]) -> SpatialSystem:
    """The Study-coordinate system of a platform on six U-P-S / S-P-S legs."""
    out = mech.output.body if mech.output is not None else None
    legs = []
    for leg in mech.legs:
        types = [mech.joint(n).type for n in leg.joints]
        if len(types) != 3 or types[0] not in ("U", "S") or types[1:] != ["P", "S"]:
            raise FormulationError(f"leg {'-'.join(leg.joints)} is not U-P-S or S-P-S")
        first, slide, last = (mech.joint(n) for n in leg.joints)
        if slide.name not in given or first.name in given or last.name in given:
            raise FormulationError(f"leg {'-'.join(leg.joints)}: give its slide and only it")
        if first.between[0] != mech.ground or last.between[1] != out:
            raise FormulationError(
                f"leg {'-'.join(leg.joints)} is not written from ground to {out}"
            )
        a = sympy.Matrix(first.params["point"])
        b = sympy.Matrix(last.params["point"])
        u = sympy.Matrix(slide.params["axis"])
        w = b - a + u * given[slide.name][0]
        legs.append(((first.name, slide.name, last.name), a, b, sympy.nsimplify(w.dot(w))))
    if len(legs) != 6:
        raise FormulationError(f"{len(legs)} legs, not six")
    eqs = [distance_equation(a, b, l2) for _names, a, b, l2 in legs]
    eqs.append(study_quadric())
    return SpatialSystem(out or "", tuple(legs), tuple(eqs))


def study_quadric() -> sympy.Expr:
    """``X.Y = 0``: the Study quadric, on which the coordinates are a displacement."""
    return sum(x * y for x, y in zip(XS, YS, strict=True))


def distance_equation(a: Any, b: Any, l2: Any) -> sympy.Expr:
    """The platform point ``b`` (at the reference pose) at squared distance ``l2`` from the
    fixed point ``a``: one quadric in the Study coordinates (Husty's, the module's)."""
    X, Y = list(XS), list(YS)
    XbX = quat_multiply(quat_multiply(X, [0, *b]), quat_conjugate(X))
    XcY = quat_multiply(quat_conjugate(X), Y)
    YXc = quat_multiply(Y, quat_conjugate(X))
    k = a.dot(a) + b.dot(b) - l2
    eq = (
        k * sum(x * x for x in X)
        + 4 * sum(y * y for y in Y)
        + 4 * sum(b[i] * XcY[i + 1] for i in range(3))
        - 2 * sum(a[i] * XbX[i + 1] for i in range(3))
        - 4 * sum(a[i] * YXc[i + 1] for i in range(3))
    )
    return sympy.expand(eq)


def moved_point(b: Any) -> list[sympy.Expr]:
    """``|X|^2 (R b + t)``: where the pose carries the point ``b``, times ``|X|^2`` (three
    quadratic forms in the Study coordinates)."""
    X, Y = list(XS), list(YS)
    XbX = quat_multiply(quat_multiply(X, [0, *b]), quat_conjugate(X))
    YXc = quat_multiply(Y, quat_conjugate(X))
    return [sympy.expand(XbX[i + 1] + 2 * YXc[i + 1]) for i in range(3)]


def moved_direction(v: Any) -> list[sympy.Expr]:
    """``|X|^2 R v``: the pose's rotation of the direction ``v``, times ``|X|^2``."""
    X = list(XS)
    XvX = quat_multiply(quat_multiply(X, [0, *v]), quat_conjugate(X))
    return [sympy.expand(XvX[i + 1]) for i in range(3)]


def out_of_reach(system: SpatialSystem) -> str | None:
    """Why no pose can close the legs, when two legs' lengths differ by more than their
    base points' and platform points' distances together (the triangle inequality:
    ``|l_i - l_j| <= |a_i - a_j| + |b_i - b_j|`` at every pose), or None."""
    legs = system.legs
    for i in range(len(legs)):
        for k in range(i + 1, len(legs)):
            (ni, ai, bi, li), (nk, ak, bk, lk) = legs[i], legs[k]
            room = sympy.sqrt((ai - ak).dot(ai - ak)) + sympy.sqrt((bi - bk).dot(bi - bk))
            gap = sympy.Abs(sympy.sqrt(li) - sympy.sqrt(lk))
            if sympy.N(gap - room, 30) > 0:
                return (
                    f"legs {'-'.join(ni)} and {'-'.join(nk)} differ in length by "
                    f"{float(gap):.6g} m, more than their base and platform points' distances "
                    f"together ({float(room):.6g} m): no pose closes them"
                )
    return None


def patch_equation() -> sympy.Expr:
    """The affine patch: a fixed random linear form of the Study coordinates equal to 1
    (its coefficients are the floats written, exactly)."""
    coeffs = np.random.default_rng(SEED).normal(size=8)
    return sum(sympy.Rational(float(c)) * v for c, v in zip(coeffs, (*XS, *YS), strict=True)) - 1


def linear_product_study(eqs: list[sympy.Expr]) -> tuple[list[sympy.Expr], list[list[list[int]]]]:
    """The homogeneous equations ``eqs`` in the Study coordinates as the system a
    linear-product start system tracks in fewer paths than their total degree, and its
    factors' variables (:func:`~mechsing.assembly.engine.track_linear_product`).

    Each leg's sphere carries the same ``4 |Y|^2``: every sphere after the first less
    its multiple of the first is linear in Y (the same solutions).  An equation whose
    terms have Y-degree from ``b0`` to ``b1`` (total degree d) lies in the span of the
    products of ``b0`` forms in Y, ``b1 - b0`` in X and Y and ``d - b1`` in X.  The patch
    is a random form in X alone (a displacement has X != 0, so the form is non-zero at
    each solution), one more form in X alone: few choices of forms leave a regular
    system.  Tsai's 3-UPU: 412 paths (total degree 1024)."""
    gens = [*XS, *YS]
    polys = [sympy.Poly(e, *gens) for e in eqs]
    y2 = tuple([0] * 4 + [2, 0, 0, 0])
    first = next((p for p in polys if p.coeff_monomial(y2) != 0), None)
    system, factors = [], []
    for p in polys:
        if first is not None and p is not first and p.coeff_monomial(y2) != 0:
            less = p - first * (p.coeff_monomial(y2) / first.coeff_monomial(y2))
            if max(sum(m[4:]) for m in less.monoms()) <= 1:
                p = less
        ydeg = [sum(m[4:]) for m in p.monoms()]
        b0, b1, d = min(ydeg), max(ydeg), p.total_degree()
        factors.append(
            [[4, 5, 6, 7]] * b0 + [list(range(8))] * (b1 - b0) + [[0, 1, 2, 3]] * (d - b1)
        )
        system.append(p.as_expr())
    coeffs = np.random.default_rng(SEED + 1).normal(size=4)
    system.append(sum(sympy.Rational(float(c)) * v for c, v in zip(coeffs, XS, strict=True)) - 1)
    factors.append([[0, 1, 2, 3]])
    return system, factors


def track_study(eqs: list[sympy.Expr], mptype: str) -> tuple[list[np.ndarray], int, str]:
    """Every finite endpoint of the homogeneous equations ``eqs`` in the Study
    coordinates with :func:`patch_equation` (on that patch), the paths tracked and the
    start system: a linear-product one (:func:`linear_product_study`) where it has fewer
    paths than the total degree, else the total degree's."""
    from mechsing.assembly.engine import linear_product_paths, track_linear_product

    gens = [*XS, *YS]
    total = 1
    for e in eqs:
        total *= sympy.Poly(e, *gens).total_degree()
    system, factors = linear_product_study(eqs)
    choices = linear_product_paths(factors, 8)
    if len(choices) >= total:
        raw, tracked = track([*eqs, patch_equation()], [gens], mptype=mptype)
        return raw, tracked, "total degree"
    raw, tracked = track_linear_product(system, gens, factors, choices, mptype=mptype)
    patch = np.random.default_rng(SEED).normal(size=8)  # patch_equation's form
    out = []
    for z in raw:
        scale = complex(patch @ z)
        if abs(scale) > 0:
            out.append(z / scale)
    return out, tracked, "linear product"


def solve_study(
    system: SpatialSystem, dps: int
) -> tuple[list[list[Any]], dict[str, Any], list[np.ndarray]]:
    """The real finite solutions (8 Study coordinates, refined to ``dps`` digits), the
    paths' account (tracked, finite, solutions, real, at infinity, failed) and every
    solution continuation found (complex, off the exceptional quadric)."""
    eqs = [*system.equations, patch_equation()]
    try:
        raw, tracked = track(eqs, [[*XS, *YS]])
    except RuntimeError as exc:  # Bertini 2 refuses the system (rank-deficient in double)
        lengths = ", ".join(f"{float(sympy.sqrt(l2)):.3g}" for *_, l2 in system.legs)
        raise ConfigurationError(
            f"the platform's system could not be solved by homotopy continuation at these "
            f"slides (leg lengths {lengths} m): Bertini 2 says: {exc}; legs many times "
            "longer than the base and the platform are wide put the system beyond double "
            "precision",
            "",
        ) from None
    genuine = off_exceptional(raw)
    real = real_endpoints(genuine)
    refined = [r for r in (newton(eqs, [*XS, *YS], z, dps) for z in real) if r is not None]
    paths = {
        "tracked": tracked,
        "finite": len(raw),
        "solutions": len(genuine),
        "real": len(real),
        "refined": len(refined),
        "failed_or_infinite": tracked - len(raw),
    }
    return refined, paths, genuine


def off_exceptional(raw: list[np.ndarray]) -> list[np.ndarray]:
    """The endpoints off Study's exceptional quadric ``|X|^2 = 0`` (there the coordinates
    are no displacement)."""
    return [
        z
        for z in raw
        if abs(sum(z[i] ** 2 for i in range(4)))
        > MODE_ISOTROPIC_RTOL * max(1.0, float(max(abs(z)))) ** 2
    ]


def pose_of(study: list[Any]) -> tuple[mpmath.matrix, mpmath.matrix]:
    """(R, t) of Study coordinates (mpmath)."""
    X, Y = study[:4], study[4:]
    delta = sum(x * x for x in X)
    R = mpmath.matrix(3, 3)
    for j in range(3):
        e = [0, 0, 0, 0]
        e[j + 1] = 1
        col = quat_multiply(quat_multiply(X, e), quat_conjugate(X))
        for i in range(3):
            R[i, j] = col[i + 1] / delta
    t = quat_multiply(Y, quat_conjugate(X))
    return R, mpmath.matrix([2 * t[i + 1] / delta for i in range(3)])


def angle_about(axis: Any, p: Any, q: Any) -> Any:
    """The angle about unit ``axis`` taking p to q (their components normal to it)."""
    w = mpmath.matrix(axis)
    pp = p - w * (w.T * p)[0]
    qq = q - w * (w.T * q)[0]
    cross = mpmath.matrix(
        [
            pp[1] * qq[2] - pp[2] * qq[1],
            pp[2] * qq[0] - pp[0] * qq[2],
            pp[0] * qq[1] - pp[1] * qq[0],
        ]
    )
    return mpmath.atan2((w.T * cross)[0], (pp.T * qq)[0])


def two_axes(a1: Any, a2: Any, p: Any, t: Any) -> list[tuple[Any, Any]]:
    """(q1, q2) with Rot(a1, q1) Rot(a2, q2) p = t (Paden-Kahan subproblem 2)."""
    w1, w2 = mpmath.matrix(a1), mpmath.matrix(a2)
    d = (w1.T * w2)[0]
    n = mpmath.matrix(
        [
            w1[1] * w2[2] - w1[2] * w2[1],
            w1[2] * w2[0] - w1[0] * w2[2],
            w1[0] * w2[1] - w1[1] * w2[0],
        ]
    )
    u1, u2 = (w1.T * t)[0], (w2.T * p)[0]
    alpha = (d * u2 - u1) / (d * d - 1)
    beta = (d * u1 - u2) / (d * d - 1)
    g2 = ((p.T * p)[0] - alpha**2 - beta**2 - 2 * alpha * beta * d) / (n.T * n)[0]
    out = []
    for sgn in (1, -1):
        z = alpha * w1 + beta * w2 + sgn * mpmath.sqrt(max(g2, 0)) * n
        out.append((angle_about(w1, z, t), angle_about(w2, p, z)))
    return out


def rotation_log(R: mpmath.matrix) -> list[Any]:
    """The rotation vector of R (angle in [0, pi))."""
    c = (R[0, 0] + R[1, 1] + R[2, 2] - 1) / 2
    v = [R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]
    s = mpmath.sqrt(sum(x * x for x in v)) / 2
    angle = mpmath.atan2(s, c)
    if s == 0:
        return [mpmath.mpf(0)] * 3
    return [angle * x / (2 * s) for x in v]


def joint_values_spatial(
    mech: Mechanism, system: SpatialSystem, given: dict, study: list[Any]
) -> list[Any]:
    """Every joint coordinate at the platform pose of ``study`` (mpmath)."""
    R, t = pose_of(study)
    values: dict[str, list[Any]] = {}
    for (n1, n2, n3), a, b, _l2 in system.legs:
        first, slide = mech.joint(n1), mech.joint(n2)
        av = mpmath.matrix([mpmath.mpf(sympy.N(x, mpmath.mp.dps + 5)) for x in a])
        bv = mpmath.matrix([mpmath.mpf(sympy.N(x, mpmath.mp.dps + 5)) for x in b])
        u = mpmath.matrix([mpmath.mpf(sympy.N(x, mpmath.mp.dps + 5)) for x in slide.params["axis"]])
        q = mpmath.mpf(sympy.N(given[n2][0], mpmath.mp.dps + 5))
        ref = bv - av + u * q
        now = R * bv + t - av
        ref_dir, now_dir = ref / mpmath.norm(ref), now / mpmath.norm(now)
        if first.type == "U":
            a1, a2 = (
                [mpmath.mpf(sympy.N(x, mpmath.mp.dps + 5)) for x in ax]
                for ax in first.params["axes"]
            )
            pairs = two_axes(a1, a2, ref_dir, now_dir)
            q1, q2 = min(pairs, key=lambda p: abs(p[0]) + abs(p[1]))
            values[n1] = [q1, q2]
            Rc = rotation(a1, q1) * rotation(a2, q2)
        else:  # S: the rotation taking the leg's direction onto the current one, least angle
            axis = mpmath.matrix(
                [
                    ref_dir[1] * now_dir[2] - ref_dir[2] * now_dir[1],
                    ref_dir[2] * now_dir[0] - ref_dir[0] * now_dir[2],
                    ref_dir[0] * now_dir[1] - ref_dir[1] * now_dir[0],
                ]
            )
            ang = mpmath.atan2(mpmath.norm(axis), (ref_dir.T * now_dir)[0])
            unit = axis / mpmath.norm(axis)
            values[n1] = [unit[i] * ang for i in range(3)]
            Rc = rotation(list(unit), ang)
        values[n2] = [q]
        values[n3] = rotation_log(Rc.T * R)
    return [values[name][i] for name, i in mech.coordinates()]
