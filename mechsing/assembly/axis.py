"""One spatial loop of six joints, one of them given and the other five revolutes: a
square system by eliminating one unknown revolute through its axis.

The loop closes when ``G_e R = 1`` up to a scalar, ``G_e`` the eliminated revolute's
displacement (``c + s A``, ``A`` its line; conjugated where the loop crosses it
backwards) and ``R`` the product of the other five in the loop's order from it (the
given one a constant, the four unknown ones each linear in its half-angle pair).  (An
unknown slide is not taken: its pair at infinity, ``c = 0``, makes its displacement ``s
eps u``, the product then lies in ``eps D`` and the commutator below vanishes along a
curve there.)  ``G_e`` commutes with ``A``, so at every closed configuration so does ``R``:
``A R - R A = 0``.  That map has rank four (its kernel, the dual quaternions ``a + b A``
with ``a``, ``b`` dual numbers: the cylindrical motions about the line), so its
components along an orthonormal basis of its image are four equations, each of degree
one in each of the four pairs, in the four pairs' four dimensions: a square system with
no choice of components (the placements of ``A`` from either side of the loop are the
same line, oriented).  Its multihomogeneous Bezout number is ``4! = 24``.  Conversely a
solution makes ``R = a + b A`` a cylindrical motion: a turn about ``A`` (``G_e``, its
pair read off ``R``'s primal part) and a slide along it, ``R``'s components ``a_1``
(along ``eps``) and ``b_1`` (along ``eps A``'s vector part); the loop closes where both
vanish.

Bertini 2 tracks the 24 paths (a random affine patch on each pair, as the general
formulation's), in double precision (each endpoint is refined and certified after; a
path that jumps leaves a root unreached and the count below fails, it proves nothing
false), again in adaptive precision where a path fails.  The count is proven when every
path ends finite at its own root, each certified by the Krawczyk test in a box disjoint
from the others' (:func:`~mechsing.assembly.certify.certified_roots`): 24 distinct
isolated roots, the Bezout number, so there is no other (each equation is a hyperplane
section of the Segre embedding of the four lines, a variety of degree 24, and by the
refined Bezout theorem the components of the intersection, of any dimension, have
degrees summing to at most 24: none of positive dimension is left).  Every mode is a
real root (its pairs real on the real patches); the complex roots' boxes lie clear of
the real space; a real root is a mode where its slide's interval over its box holds 0
and the slide at the refined root is below ``10^-(N/2)`` (the refinement's own residual
rule, N the working digits), not a mode where the interval excludes 0.  Each mode is
then refined and certified in the general formulation's coordinates (:mod:`.general`:
the same rows, the same certificates).  Anything else (a failed path, a root not
certified, a slide neither, for each of the first two revolutes tried as the eliminated one) hands
the problem to the general formulation, which also tells a curve of closed
configurations from isolated modes.

Owns :data:`FORMULATION`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.assembly.chains import Found
from mechsing.assembly.given import Formulation, Given
from mechsing.errors import FormulationError
from mechsing.lie.dual import study_conjugate, study_multiply

__all__ = ["FORMULATION"]

#: the seed of the patches (each pair's random affine chart)
SEED = 43
#: how many revolutes are tried as the eliminated one before the general formulation
#: takes the loop (each failed try costs a tracking and a certification: 2 to 7 s on
#: Sarrus's curve, where every choice fails)
ELIMINATIONS = 2


@dataclass(frozen=True)
class _System:
    """The square system of one eliminated revolute: the patched equations, the pairs
    (each unknown joint but the eliminated one, in the loop's order), the product ``R``
    (8 expressions), the eliminated joint's line and sign, the Bezout number."""

    joint: str
    sign: int
    line: list[Any]
    product: list[sympy.Expr]
    patched: list[sympy.Expr]
    groups: list[tuple[str, str, tuple[sympy.Symbol, ...]]]
    bezout: int

    @property
    def gens(self) -> list[sympy.Symbol]:
        return [x for _, _, g in self.groups for x in g]


def _layout(given: Given) -> tuple[Any, list[str], list[int], list[str]]:
    """The general formulation's problem, the loop's joints and signs, and the unknown
    revolutes that may be eliminated, the farthest from the given joint first
    (FormulationError: why the mechanism is not such a loop)."""
    from mechsing.assembly.general import problem

    mech = given.mech
    if given.values is None or len(mech.loops) != 1:
        raise FormulationError("not a single loop with given joint values")
    loop = mech.loops[0]
    names, signs = list(loop.joints), list(loop.signs)
    if len(names) != 6 or {j.name for j in mech.joints} != set(names):
        raise FormulationError("not one loop of six joints holding every joint")
    unknown = [n for n in names if n not in given.values]
    if len(unknown) != 5 or any(mech.joint(n).type != "R" for n in unknown):
        # (an unknown slide's pair at infinity, c = 0, makes its displacement s eps u: the
        # product R then lies in eps D, and the commutator vanishes on a curve there)
        raise FormulationError("the given values do not leave five unknown revolutes")
    revolutes = unknown
    prob = given.cache.get("general") or problem(given)
    given.cache["general"] = prob
    if len(prob.closures[0].equations) != 6:
        raise FormulationError("the loop's joints generate a subgroup of fewer than six dimensions")
    (fixed,) = [i for i, n in enumerate(names) if n in given.values]
    far = sorted(
        revolutes, key=lambda n: -min((names.index(n) - fixed) % 6, (fixed - names.index(n)) % 6)
    )
    return prob, names, signs, far


def _applies(given: Given) -> str | None:
    try:
        _layout(given)
    except FormulationError as reason:
        return str(reason)
    return None


def _system(given: Given, prob: Any, names: list[str], signs: list[int], joint: str) -> _System:
    """The square system of eliminating ``joint`` (FormulationError: the commutator's
    image is not four-dimensional)."""
    from mechsing.assembly.displacements import Joints, study_number
    from mechsing.assembly.general import bezout

    joints = Joints(given.mech, prob.given)
    e = names.index(joint)
    own = joints.element(joint)  # (its pair's symbols first: they take no part in R)
    product: list[Any] = [1, 0, 0, 0, 0, 0, 0, 0]
    for d in range(1, 6):
        m = (e + d) % 6
        F = joints.element(names[m])
        product = [
            sympy.expand(x)
            for x in study_multiply(product, F if signs[m] > 0 else study_conjugate(F))
        ]
    (k,) = joints.of[joint]
    t = joints.groups[k].gens[1]
    line = [sympy.expand(x).coeff(t) for x in own]
    A = [mpmath.mpf(sympy.N(x, mpmath.mp.dps + 10)) for x in line]
    M = mpmath.matrix(8, 8)
    for j in range(8):
        E = [0] * 8
        E[j] = 1
        col = [a - b for a, b in zip(study_multiply(A, E), study_multiply(E, A), strict=True)]
        for i in range(8):
            M[i, j] = col[i]
    U, S, _ = mpmath.svd_r(M)
    from mechsing.numeric import MODE_SPAN_RTOL

    rank = sum(1 for s in S if s > MODE_SPAN_RTOL * S[0])
    if rank != 4:
        raise FormulationError(f"joint {joint}'s commutator has rank {rank}, not 4")
    comm = [
        a - b
        for a, b in zip(study_multiply(line, product), study_multiply(product, line), strict=True)
    ]
    eqs = [sympy.expand(sum(study_number(U[i, r]) * comm[i] for i in range(8))) for r in range(4)]
    groups = [
        (joints.groups[g].joint, joints.groups[g].kind, joints.groups[g].gens)
        for n in names
        if n != joint and n in joints.of
        for g in joints.of[n]
    ]
    rng = np.random.default_rng(SEED)
    patches = []
    for _, _, g in groups:
        r = rng.normal(size=len(g))
        patches.append(sum(sympy.Rational(float(c)) * x for c, x in zip(r, g, strict=True)) - 1)
    supports = [{i for i, (_, _, g) in enumerate(groups) if set(g) & q.free_symbols} for q in eqs]
    count = bezout(supports, [1] * len(groups))
    return _System(joint, signs[e], A, product, [*eqs, *patches], groups, count)


def _slides(sy: _System) -> list[sympy.Expr]:
    """``R``'s components off the rotations about the line: along ``eps`` and along the
    line's direction in the dual vector part (both zero where the loop closes)."""
    w = sy.line[1:4]
    return [
        sy.product[4],
        sum(sympy.Float(w[i], mpmath.mp.dps + 10) * sy.product[5 + i] for i in range(3)),
    ]


def _classify(sy: _System, roots: list[list[Any]]) -> tuple[list[list[Any]], int] | None:
    """The real roots that are modes, and how many roots (real or complex) close the loop
    at the working digits (None: one real root is neither provably a mode's nor
    provably not)."""
    from mechsing.assembly.certify import interval_function
    from mechsing.assembly.settings import MODE_CERTIFY_RADIUS

    gens = sy.gens
    slides = _slides(sy)
    exact = sympy.lambdify(gens, slides, "mpmath")
    boxed = interval_function(slides, gens)
    radius = mpmath.mpf(MODE_CERTIFY_RADIUS)
    small = mpmath.mpf(10) ** (-(mpmath.mp.dps // 2))
    modes = []
    closing = 0
    before = mpmath.iv.dps
    mpmath.iv.dps = mpmath.mp.dps
    try:
        for x in roots:
            size = mpmath.sqrt(sum(abs(v) ** 2 for v in x))
            closes = max(abs(v) for v in exact(*x)) <= small * size
            closing += closes
            if any(mpmath.im(v) != 0 for v in x):
                continue  # certified clear of the real space
            z = [mpmath.re(v) for v in x]
            box = boxed([mpmath.iv.mpf([v - radius, v + radius]) for v in z])
            if any(0 not in b for b in box):
                continue  # its slide provably off zero
            if not closes:
                return None
            modes.append(z)
    finally:
        mpmath.iv.dps = before
    return modes, closing


def _values(sy: _System, z: list[Any], L: Any) -> dict[str, list[Any]]:
    """Each unknown joint's value at a root: the pairs', and the eliminated one's from
    ``R``'s primal part (``G_e`` is ``R``'s conjugate up to a scalar)."""
    from mechsing.assembly.serial import half_angle_value

    out: dict[str, list[Any]] = {}
    for k, (joint, kind, _) in enumerate(sy.groups):
        out.setdefault(joint, []).append(half_angle_value(kind, z[2 * k], z[2 * k + 1], L))
    P = sympy.lambdify(sy.gens, sy.product[:4], "mpmath")(*z)
    a0 = P[0]
    b0 = sum(P[1 + i] * sy.line[1 + i] for i in range(3)) / sum(x * x for x in sy.line[1:4])
    c, s = (a0, -b0) if sy.sign > 0 else (a0, b0)
    out[sy.joint] = [half_angle_value("R", c, s, L)]
    return out


def _attempt(given: Given, prob: Any, sy: _System) -> tuple[Any, ...] | str:
    """The modes of eliminating ``sy.joint`` with their refined general coordinates and
    the paths' account, or why the count is not proven that way."""
    from mechsing.assembly.certify import apart, certified_roots
    from mechsing.assembly.engine import RETRY_FAILED, track

    gens = sy.gens
    groups = [g for _, _, g in sy.groups]
    # tracked again in adaptive precision where double lost a few paths (engine.RETRY_FAILED,
    # a path to infinity lost too); where it lost more, most paths end on a set of closed
    # configurations that is not finite, which no precision turns into a count (Sarrus's
    # with J1 given: 23 of 24): that elimination fails at once
    raw, tracked = track(sy.patched, groups, mptype="double", tight=True)
    lost = sy.bezout - len(raw)
    if lost > RETRY_FAILED * sy.bezout:
        return f"{lost} of {sy.bezout} paths failed or went to infinity in double precision"
    if tracked != sy.bezout:
        return f"{tracked} paths, not the Bezout number {sy.bezout}"
    if len(raw) != tracked:
        return f"{tracked - len(raw)} of {tracked} paths failed or went to infinity"
    roots = certified_roots(sy.patched, gens, raw, given.dps)
    if roots is None or not apart(roots):
        return f"the {tracked} endpoints are not each certified in a box of its own"
    got = _classify(sy, roots)
    if got is None:
        return "a real root's slide along the axis is neither zero nor provably not"
    real = sum(1 for x in roots if all(mpmath.im(v) == 0 for v in x))
    return *got, tracked, real


def _find(given: Given) -> Found:
    from mechsing.assembly.certify import krawczyk, newton, regular
    from mechsing.assembly.general import _coordinates, _normalisations, _randomized, _row
    from mechsing.assembly.settings import MODE_CERTIFY_RADIUS

    prob, names, signs, order = _layout(given)
    reasons = []
    for joint in order[:ELIMINATIONS]:
        sy = _system(given, prob, names, signs, joint)
        got = _attempt(given, prob, sy)
        if isinstance(got, str):
            reasons.append(f"eliminating {joint}: {got}")
            continue
        modes, closing, tracked, real = got
        break
    else:
        raise FormulationError("the axis formulation proves no count (" + "; ".join(reasons) + ")")
    gens = prob.gens
    square = [*_randomized(prob), *_normalisations(prob)]
    radius = mpmath.mpf(MODE_CERTIFY_RADIUS)
    rows = []
    for z in modes:
        start = _coordinates(prob, _values(sy, z, prob.L))
        root = newton(square, gens, start, given.dps)
        if root is None or not regular(square, gens, root):
            raise FormulationError(
                f"a mode of the axis formulation (eliminating {joint}) is singular in the "
                "general formulation's coordinates"
            )
        rows.append((_row(given.mech, prob, root), krawczyk(square, gens, root, radius)))
    rows.sort(key=lambda r: [float(x) for x in r[0]])
    pairs = [f"{j} ({'half-angle pair' if k == 'R' else 'slide pair'})" for j, k, _ in sy.groups]
    formulation: dict[str, Any] = {
        "name": "a six-joint loop squared by one revolute's axis",
        "method": "homotopy continuation (Bertini 2, multihomogeneous start) on the other "
        f"unknowns' pairs with {joint}'s displacement eliminated, every root certified; "
        "each mode refined and certified in Study coordinates",
        "unknowns": pairs,
        "eliminated": joint,
        "polynomial_degree": 1,
        "bezout": tracked,
    }
    paths = {
        "tracked": tracked,
        "finite": tracked,
        "extraneous": tracked - closing,
        "solutions": closing,
        "real": len(rows),
        "refined": len(rows),
        "singular": 0,
        "failed_or_infinite": 0,
        "duplicates": 0,
    }
    notes = [
        *(f"{r}, so another revolute was eliminated" for r in reasons),
        f"{joint}'s displacement commutes with its axis, so at every closed configuration "
        "so does the product of the other five joints' (the axis placed from either side "
        f"of the loop is the same line): 4 equations in the pairs of "
        f"{', '.join(j for j, _, _ in sy.groups)}; each of the {tracked} paths (their "
        "multihomogeneous Bezout number) ended at its own certified root, so there is no "
        f"other; {real} real, of which {len(rows)} close the loop (the product's slide "
        f"along {joint}'s axis zero; the others' provably not): no mode is missing",
    ]
    proven = all(ok for _, ok in rows)
    return Found(
        formulation,
        rows,
        len(rows),
        "proven" if proven else "not proven",
        paths,
        tuple(notes),
        1,
        given.cache.get("closure"),
    )


FORMULATION = Formulation(
    "one revolute's axis squares a loop of six joints, one given, five revolutes unknown",
    _applies,
    _find,
)
