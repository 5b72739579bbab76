"""The general formulation: every mechanism of R, P, C, U, S, T2 and T3 joints whose given
values leave finitely many closed configurations (or say that they do not, with the
dimension).

Each unknown joint's displacement is a dual quaternion (Study coordinates, lengths over
L) linear in its own homogeneous coordinates: a revolute's half-angle pair ``(c, s)`` ~
``(cos(q/2), sin(q/2))``, ``c + s A`` with ``A`` its line; a prismatic joint's pair
``(1, q/(2L))``, ``c + s eps u``; a C joint the two, a U joint its two revolutes'
(``exp(q1 e1) exp(q2 e2)``); an S joint the quaternion ``r`` of its rotation, ``r + eps
(p x r)`` about its point p (four homogeneous coordinates, three dimensions).  A given
joint is the constant its values make.

Every independent loop closes when the product of its joints' displacements (each
reversed where the loop crosses it backwards) is the identity up to a scalar; a serial
arm when its chain's product is the output's target pose ``T`` (``F1 ... Fn T* ~ 1``),
and a mechanism with loops given the output's pose when each of its serial legs' is
(:func:`~mechsing.assembly.chains.pose_chains`: its working modes).
The product lies in the span of the loop's displacements, the linear hull of the
subgroup its joints generate in Study coordinates (``{1, k, eps i, eps j}`` for planar
motions across z, the quaternions for rotations about the origin, all eight for D).  The
closure is written in those coordinates: the product's components along the span
orthogonal to ``1`` and ``eps`` (on the Study quadric they vanish only at the
identity), three equations for a planar or spherical loop, four for a Schoenflies one,
six in general.  Each equation is linear in each pair, so Bertini 2 tracks the paths of
a multihomogeneous start system, one variable group per joint coordinate set (the
multihomogeneous Bezout number).  With more equations than unknowns (an overconstrained
loop: Bennett's, Bricard's, Sarrus's) the system is randomized to as many random
combinations and each endpoint is checked on every equation.

An endpoint with an isotropic pair (``c^2 + s^2 = 0``), an infinite slide or a product
off the identity is extraneous; the real ones are refined by Newton's method at the
working digits and certified by the Krawczyk test, as the other formulations' are; a
singular one gets the local dimension test (:func:`~mechsing.assembly.certify.local_dimension`):
on a curve of closed configurations there is no count, only ``infinite`` with the
dimension.  Closures that share no unknown (a parallel mechanism's legs at a pose) are
solved apart, and a mode is one solution of each (:mod:`.parts`).

Owns :class:`Problem`, :func:`problem`, :func:`bezout` and :data:`FORMULATION`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.assembly.chains import Found, arm_chain, pose_chains
from mechsing.assembly.displacements import (
    Group,
    Joints,
    expanded,
    quaternion_of_vector,
    study_number,
    working_mpf,
)
from mechsing.assembly.engine import genuine_endpoint, on_normalisations
from mechsing.assembly.given import Formulation, Given
from mechsing.assembly.settings import (
    MODE_CERTIFY_RADIUS,
    MODE_ENDPOINT_SINGULAR_RTOL,
)
from mechsing.errors import FormulationError, TooManyModes, UserError
from mechsing.lie.dual import study_conjugate, study_multiply
from mechsing.model import Mechanism
from mechsing.numeric import MODE_MATCH_DISTANCE, MODE_SPAN_RTOL

__all__ = ["FORMULATION", "Problem", "bezout", "patched_system", "problem"]

#: the most paths the general formulation tracks (its multihomogeneous Bezout number,
#: summed over the parts solved apart); a system of more is refused with the count (a
#: multi-loop platform of U joints closed whole, Tsai's 3-UPU at its inputs, has
#: millions), not left running for hours
MAX_PATHS = 4000
#: Bertini's precision model for a randomized system (an overconstrained loop's, and the
#: slices'): double precision (each real endpoint is refined at 50 digits afterwards;
#: adaptive precision crawls for minutes along the singular paths of such a system's
#: isotropic components: Sarrus's); a square system keeps adaptive precision (in double,
#: 8 of a SCARA's 24 paths fail); a system with an idle rod's spin equation in double too
#: (its ball joints' isotropic quaternions make many singular endpoints: an RSSR's 60
#: paths took minutes in adaptive precision, 4 s in double, the same two modes); but a
#: leg closed on the output's pose keeps adaptive precision, overconstrained or not (a
#: 3-PRS's leg of five joints: in double some paths fail and a posture with them, its
#: long slide found or missed with the seed; adaptive found every posture of seven
#: poses, 14 to 75 s for the three legs, where double took 5 to 10 s); a double run of a
#: count that failed a few paths is run again in adaptive precision (a failed path may hide
#: a mode: :data:`mechsing.assembly.engine.RETRY_FAILED`; the RSSR's 41 of 60 are too
#: many), a slice's is not (another slice is tried)
MPTYPE = "double"
#: the most paths whose every endpoint is certified to prove a count (above: not tried)
PROOF_PATHS = 200
#: how many random slicings of an underdetermined system are tried for a real point
SLICE_TRIES = 4
#: the seed of the randomization of an overconstrained system and of the patches
SEED = 41


@dataclass(frozen=True)
class Closure:
    """One closure: the joints in order, the subgroup they generate (its symbol), the
    product's eight Study coordinates and the closure equations in the span's coordinates."""

    joints: tuple[str, ...]
    subgroup: str | None
    product: tuple[sympy.Expr, ...]
    equations: tuple[sympy.Expr, ...]


@dataclass(frozen=True)
class Problem:
    """The system: the variable groups, each unknown joint's groups, the closures, the
    length scale, the given joints' values, whether it is a serial arm's (its chain
    closed on a target) and whether a mechanism with loops is closed on the output's
    pose (``pose``: its working modes)."""

    groups: tuple[Group, ...]
    joints: dict[str, tuple[int, ...]]
    closures: tuple[Closure, ...]
    L: Any
    given: dict[str, list[Any]]
    arm: bool
    #: each idle rod (body, first S, second S) and its spin equation (:mod:`.spins`)
    spins: tuple[tuple[str, str, str], ...] = ()
    spin_equations: tuple[sympy.Expr, ...] = ()
    pose: bool = False
    #: a part's (:func:`~mechsing.assembly.parts.split`): the other parts' unknown joints,
    #: held at 0 in its rows
    others: frozenset[str] = frozenset()
    #: the closures of chains whose joints are all given: they close or leave no mode
    fixed: tuple[Closure, ...] = ()

    @property
    def gens(self) -> list[sympy.Symbol]:
        return [g for grp in self.groups for g in grp.gens]

    @property
    def unknowns(self) -> int:
        return sum(g.dim for g in self.groups)

    @property
    def equations(self) -> list[sympy.Expr]:
        return [*(e for c in self.closures for e in c.equations), *self.spin_equations]


def _span(product: list[Any], gens: list[sympy.Symbol]) -> Any:
    """An orthonormal basis (8 x r, mpmath) of the span of the product's coefficient
    vectors and of 1."""
    from mechsing.assembly.certify import poly_terms

    cols: dict[Any, list[Any]] = {}
    for k, comp in enumerate(product):
        terms = poly_terms(comp, gens) if gens else [((), comp)]
        for mono, coeff in terms:
            cols.setdefault(mono, [0] * 8)[k] = mpmath.mpf(sympy.N(coeff, mpmath.mp.dps))
    M = mpmath.matrix(8, len(cols) + 1)
    M[0, 0] = 1
    for j, col in enumerate(cols.values()):
        for k in range(8):
            M[k, j + 1] = col[k]
    # mpmath.svd_r's steps less the right singular vectors (the same U and S, bit for bit)
    from mpmath.matrices.eigen_symmetric import svd_r_raw

    U = M.copy()
    S = svd_r_raw(mpmath.mp, U, V=False, calc_u=True)[: min(U.rows, U.cols)]
    U = U[:, : len(S)] if U.cols > U.rows else U
    r = sum(1 for x in S if x > MODE_SPAN_RTOL * S[0])
    return U[:, :r] if r < U.cols else U


def _closure_equations(product: list[Any], gens: list[sympy.Symbol]) -> list[sympy.Expr]:
    """The product's components along its span orthogonal to ``1`` and ``eps``."""
    V = _span(product, gens)
    r = V.cols
    M = mpmath.matrix(max(r, 2), r)  # the span's components along 1 and eps, padded square
    for k in range(r):
        M[0, k], M[1, k] = V[0, k], V[4, k]
    _, S, Vt = mpmath.svd_r(M)
    rank = sum(1 for x in S if x > MODE_SPAN_RTOL)
    eqs = []
    for i in range(rank, r):
        w = [sum(V[n, k] * Vt[i, k] for k in range(r)) for n in range(8)]
        eqs.append(sympy.expand(sum(study_number(w[n]) * product[n] for n in range(8))))
    return eqs


def problem(given: Given) -> Problem:
    """The general formulation of ``given``: the loops' closures with the given values, or
    a serial arm's chain to its target."""
    mech = given.mech
    if mech.loops and given.values is not None:
        values = {n: list(vals) for n, vals in given.values.items()}
        chains = [(list(lp.joints), list(lp.signs), None) for lp in mech.loops]
    else:  # the output's pose given: a serial arm's chain, or each serial leg's
        chains, values = pose_chains(given) if mech.loops else arm_chain(given)
    joints = Joints(mech, values)
    arm = not mech.loops
    closures: list[Closure] = []
    fixed: list[Closure] = []  # the chains of given joints only: checked, not solved
    for names, signs, target in chains:
        product: list[Any] = [1, 0, 0, 0, 0, 0, 0, 0]
        for name, sign in zip(names, signs, strict=True):
            F = joints.element(name)
            product = expanded(study_multiply(product, F if sign > 0 else study_conjugate(F)))
        gens = [
            g
            for k in sorted({k for n in names for k in joints.of.get(n, ())})
            for g in joints.groups[k].gens
        ]
        if target is not None:
            T = _target(given, joints.L, target)
            if gens:  # a chain of given joints only reaches its target or misses it
                _check_in_span(given, product, gens, T, names)
            product = expanded(
                study_multiply(product, [study_number(x) for x in study_conjugate(T)])
            )
        closure = Closure(
            tuple(names),
            _symbol(mech, names),
            tuple(product),
            tuple(_closure_equations(product, gens)),
        )
        (closures if gens else fixed).append(closure)
    from mechsing.assembly.spins import idle_rods, spin_equation

    rods = tuple(r for r in idle_rods(mech, values) if r[1] in joints.of)
    spins = tuple(spin_equation(mech, r, joints.groups[joints.of[r[1]][0]].gens) for r in rods)
    return Problem(
        tuple(joints.groups),
        joints.of,
        tuple(closures),
        joints.L,
        values,
        arm,
        rods,
        spins,
        pose=bool(mech.loops) and given.values is None,
        fixed=tuple(fixed),
    )


def _symbol(mech: Mechanism, names: list[str]) -> str | None:
    from mechsing.kinematics.family import family

    return family(mech, names).symbol


def _target(given: Given, L: Any, target: Any) -> list[Any]:
    """The target's Study coordinates (lengths over L): the configuration's pose, or the
    displacement the arm's joints reach at ``target``'s values."""
    from mechsing.assembly.serial import chain_to_output, pose_target

    if target == "pose":
        return pose_target(given.mech, given.config, L, given.atol)
    fixed = Joints(given.mech, target)
    T: list[Any] = [1, 0, 0, 0, 0, 0, 0, 0]
    for name, sign in zip(*chain_to_output(given.mech), strict=True):
        F = fixed.element(name)
        T = study_multiply(T, F if sign > 0 else study_conjugate(F))
    return [mpmath.mpf(sympy.N(x, mpmath.mp.dps + 10)) for x in T]


def _check_in_span(
    given: Given, product: list[Any], gens: list[Any], T: list[Any], names: list[str]
) -> None:
    """Refuse (exit 2) a target outside the subgroup the arm's end (the output, along its
    chain) moves in, naming it."""
    from mechsing.kinematics.family import family, pose_words

    V = _span(product, gens)
    coeffs = [sum(V[i, k] * T[i] for i in range(8)) for k in range(V.cols)]
    off = mpmath.sqrt(
        sum((T[i] - sum(V[i, k] * coeffs[k] for k in range(V.cols))) ** 2 for i in range(8))
    )
    size = mpmath.sqrt(sum(x * x for x in T))
    if off <= MODE_SPAN_RTOL * size:
        return
    fam = family(given.mech, names)
    raise UserError(
        f"{given.where}: the pose lies outside the subgroup "
        + (
            "the arm's end moves in, "
            if not given.mech.loops
            else f"the output moves in on its chain {' - '.join(names)}, "
        )
        + pose_words(fam)
        + f" (the target's Study coordinates are {float(off):.3g} of their size outside its span)"
    )


def bezout(supports: list[set[int]], dims: list[int]) -> int:
    """The multihomogeneous Bezout number of equations each of degree one in each group of
    its support (``dims``: each group's projective dimension): the number of ways to give
    every group as many equations as its dimension, each from its support."""

    @functools.cache
    def count(i: int, left: tuple[int, ...]) -> int:
        if i == len(supports):
            return int(not any(left))
        total = 0
        for g in supports[i]:
            if left[g]:
                rest = list(left)
                rest[g] -= 1
                total += count(i + 1, tuple(rest))
        return total

    return count(0, tuple(dims))


def _normalisations(prob: Problem) -> list[sympy.Expr]:
    """One equation per group fixing its scale: a revolute pair on its unit circle, a
    slide's c = 1, a quaternion of norm 1."""
    out = []
    for g in prob.groups:
        if g.kind == "P":
            out.append(g.gens[0] - 1)
        else:
            out.append(sum(x * x for x in g.gens) - 1)
    return out


def _randomized(prob: Problem, n: int | None = None) -> list[sympy.Expr]:
    """As many equations as unknowns (``n``: as many as that): the closures' own when they
    are as many or fewer, else random combinations of them."""
    eqs = prob.equations
    n = prob.unknowns if n is None else n
    if len(eqs) <= n:
        return eqs
    rng = np.random.default_rng(SEED)
    mix = rng.normal(size=(n, len(eqs)))
    return [
        sympy.expand(sum(sympy.Rational(float(mix[r, k])) * eqs[k] for k in range(len(eqs))))
        for r in range(n)
    ]


def patched_system(prob: Problem) -> tuple[list[sympy.Expr], list[tuple[sympy.Symbol, ...]]]:
    """The system Bertini tracks: the closure equations (randomized to as many as the
    unknowns) and a fixed random affine patch on each group; and the groups."""
    rng = np.random.default_rng(SEED + 1)
    patched = [*_randomized(prob)]
    for g in prob.groups:
        r = rng.normal(size=len(g.gens))
        patched.append(
            sum(sympy.Rational(float(c)) * x for c, x in zip(r, g.gens, strict=True)) - 1
        )
    return patched, [g.gens for g in prob.groups]


def _applies(given: Given) -> str | None:
    try:
        prob = problem(given)
    except FormulationError as reason:
        return str(reason)
    if prob.unknowns == 0:
        return "the given values fix every joint (nothing is left to solve)"
    given.cache["general"] = prob
    if len(prob.equations) >= prob.unknowns:
        from mechsing.assembly.parts import split

        # the parts are tracked one after the other: their paths add (how many modes
        # their solutions combine into is known once they are solved: parts.combined)
        paths = sum(_bezout(part) for part in split(prob))
        if paths > MAX_PATHS:
            return (
                f"its multihomogeneous start system has {paths} paths (the most tracked is "
                f"{MAX_PATHS})"
            )
        given.cache["general paths"] = paths
    return None


def _bezout(prob: Problem) -> int:
    """The multihomogeneous Bezout number of the system Bertini tracks for ``prob``."""
    eqs = _randomized(prob)
    supports = [{k for k, g in enumerate(prob.groups) if set(g.gens) & e.free_symbols} for e in eqs]
    return bezout(supports, [g.dim for g in prob.groups])


def _values(prob: Problem, z: list[Any]) -> dict[str, list[Any]]:
    """Each unknown joint's values from its groups' coordinates (mpmath)."""
    from mechsing.assembly.serial import half_angle_value
    from mechsing.lie.quaternion import quat_log

    out: dict[str, list[Any]] = {}
    at = 0
    for g in prob.groups:
        v = z[at : at + len(g.gens)]
        at += len(g.gens)
        if g.kind == "S":
            r = np.empty(4, dtype=object)
            r[:] = [mpmath.mpf(mpmath.re(x)) for x in v]
            out.setdefault(g.joint, []).extend(list(quat_log(r)))
        else:
            out.setdefault(g.joint, []).append(half_angle_value(g.kind, v[0], v[1], prob.L))
    return out


def _row(mech: Mechanism, prob: Problem, z: list[Any]) -> list[Any]:
    values = {**{n: [working_mpf(x) for x in v] for n, v in prob.given.items()}, **_values(prob, z)}
    zero = mpmath.mpf(0)
    return [zero if name in prob.others else values[name][i] for name, i in mech.coordinates()]


def _find(given: Given) -> Found:
    from mechsing.assembly.parts import combined, split

    prob: Problem = given.cache["general"]
    off = _fixed_gaps(given, prob)
    if off:
        names, gap = off
        why = (
            f"the given joints of the chain {' - '.join(names)} leave it "
            + ("off the output's pose" if prob.pose or prob.arm else "open")
            + f" by {float(gap):.3g} m, over the {given.prec} tolerance: no mode"
        )
        formulation = {**_formulation(prob), "proven_without_tracking": why}
        return Found(formulation, [], 0, "proven", None, (why,), 1, given.closure)
    parts = split(prob)
    if len(parts) == 1:
        return _find_part(given, prob)
    found = [_find_part(given, p) for p in parts]
    try:
        return combined(given.mech, parts, found)
    except TooManyModes as exc:  # what was found, not a method that does not apply
        raise UserError(f"{given.where}: {exc}") from None


def _fixed_gaps(given: Given, prob: Problem) -> tuple[tuple[str, ...], Any] | None:
    """The first chain of given joints only that does not close (its joints, and its gap
    read from its equations as a root's is, t / 2L and half an angle: 2L times their
    norm, in metres), or None: every such chain closes to the precision's tolerance."""
    from mechsing.assembly.certify import left_open
    from mechsing.assembly.result import closure_gap

    for c in prob.fixed:
        miss = mpmath.norm([mpmath.mpf(sympy.N(e, given.dps)) for e in c.equations] or [0])
        if not left_open(miss, given.dps):
            continue
        gap = closure_gap(given.mech, given.prec, [], 2 * prob.L * miss)
        if gap:
            return c.joints, gap
    return None


def _formulation(prob: Problem) -> dict[str, Any]:
    """The formulation's JSON: its name, method, unknowns and closures."""
    return {
        "name": "joint displacements in Study coordinates, each loop in its subgroup's",
        "method": "homotopy continuation (Bertini 2, multihomogeneous start), Newton refinement",
        "unknowns": [
            f"{g.joint} ({'quaternion' if g.kind == 'S' else 'half-angle pair' if g.kind == 'R' else 'slide pair'})"
            for g in prob.groups
        ],
        "closures": [
            {"joints": list(c.joints), "subgroup": c.subgroup, "equations": len(c.equations)}
            for c in prob.closures
        ],
        "polynomial_degree": 1,
        "randomized": len(prob.equations) > prob.unknowns,
        "working_modes": prob.pose,
    }


def _find_part(given: Given, prob: Problem) -> Found:
    from mechsing.assembly import certify
    from mechsing.assembly.certify import krawczyk, local_dimension, newton, regular
    from mechsing.assembly.engine import real_endpoints, track
    from mechsing.assembly.result import closure_gap, joint_distance
    from mechsing.assembly.serial import account, unproven

    mech, dps = given.mech, given.dps
    gens = prob.gens
    norms = _normalisations(prob)
    full = [*prob.equations, *norms]
    n, m = prob.unknowns, len(prob.equations)
    formulation = _formulation(prob)
    notes: list[str] = []
    if prob.spins:
        formulation["idle_spins"] = [list(r) for r in prob.spins]
        notes.extend(
            f"body {body} spins idly about the line through its ball joints {a} and {b}: "
            f"each mode is listed with {a}'s rotation free of spin about that line"
            for body, a, b in prob.spins
        )
    if m < n:
        # fewer closure equations than unknowns: no finite set (where it is not empty)
        dim, at = _dimension_at_start(given, prob, full)
        formulation["dimension"] = dim if dim is not None else n - m
        notes.append(
            f"the given values leave {n} unknowns and {m} closure equations: the closed "
            f"configurations are not finitely many (dimension "
            + (
                f"{dim}, by the local dimension test at {at})"
                if dim is not None
                else f"at least {n - m})"
            )
        )
        return Found(formulation, [], None, "infinite", None, tuple(notes), 1, given.closure)
    square = [*_randomized(prob), *norms]
    # a leg closed on the pose keeps adaptive precision (MPTYPE)
    double = (m > n or prob.spins) and not prob.pose
    raw, tracked = track(*patched_system(prob), mptype=MPTYPE if double else "adaptive")
    product = certify.polynomial_rows([c.product for c in prob.closures], gens)
    genuine = [z for z in raw if genuine_endpoint(prob.groups, z, product)]
    pairs = [(g, r[0]) for g in genuine for r in [real_endpoints([g])] if r]
    real = [z for _, z in pairs]
    found: list[tuple[list[Any], list[Any], bool]] = []
    duplicates = singular = 0

    def along_a_set(dim: int, point: list[Any], also: str, where: str) -> Found:
        """The answer where the given values are reached along a set of dimension ``dim``
        through ``point`` (found by the local dimension test at ``where``): no count."""
        formulation["dimension"] = dim
        row = _row(mech, prob, point)
        at = ", ".join(
            f"{c[0]} = {float(v):.6g}"
            for c, v in zip(mech.coordinates(), row, strict=True)
            if c[0] not in prob.others
        )
        notes.append(
            f"the given values are {also}reached along a set of dimension {dim} (the local "
            f"dimension test at {where}, through {at}): the modes are not finitely many"
        )
        paths = account(tracked, raw, genuine, real, found, duplicates, singular)
        return Found(formulation, [], None, "infinite", paths, tuple(notes), 1, given.closure)

    L = float(prob.L)
    open_roots: list[Any] = []  # roots of the combinations that leave a loop open (m)
    for endpoint, z in pairs:
        start = on_normalisations(prob.groups, z)
        root = newton(square, gens, start, dps)
        ok = root is not None and regular(square, gens, root)
        miss = ok and m > n and certify.misses(prob.equations, gens, root, dps)
        # a gap to a target pose read from the equations (t / 2L, half an angle)
        gap = miss and closure_gap(
            mech,
            given.prec,
            _row(mech, prob, root),
            (prob.arm or prob.pose or bool(prob.others)) and 2 * L * miss,
        )
        if gap:
            open_roots.append(gap)
            genuine = [g for g in genuine if g is not endpoint]
            real = [x for x in real if x is not z]
            continue
        if not ok:
            singular += 1
            dim = local_dimension(full, gens, start, dps)
            if dim > 0:
                return along_a_set(dim, start, "", "a real endpoint")
            from mechsing.assembly.certify import singular_root

            root, _ = singular_root(full, gens, start, dps)
            if root is None:
                continue
        row = _row(mech, prob, root)
        if any(
            joint_distance(mech, [float(x) for x in row], [float(x) for x in q], L)
            <= MODE_MATCH_DISTANCE
            for _, q, _ in found
        ):
            duplicates += 1
            continue
        found.append((root, row, ok))
    # components of dimension 1 or more (an overconstrained loop's second branch, where
    # the homotopy's paths end singular or fail): one slice, the local dimension test at
    # each real point of it; not where every path ended finite at a genuine endpoint
    # regular in double precision or at an extraneous one (paths end on every component)
    for z in (
        _sliced(prob, 1)
        if (n > 1 or m > n) and _may_hide_a_set(prob, raw, tracked, genuine)
        else []
    ):
        dim = local_dimension(full, gens, z, dps)
        if dim > 0:
            return along_a_set(dim, z, "also ", "a real point of a slice")
    found.sort(key=lambda f: [float(x) for x in f[1]])
    radius = mpmath.mpf(MODE_CERTIFY_RADIUS)
    rows = [(q, ok and krawczyk(square, gens, root, radius)) for root, q, ok in found]
    paths = account(tracked, raw, genuine, real, found, duplicates, singular)
    if open_roots:
        notes.append(
            f"{len(open_roots)} real root(s) of the random combinations miss the other "
            f"closure equations at {dps} digits, "
            + (
                "the arm's end off its target"
                if prob.arm
                else "the loops left open or the output off its pose"
                if prob.pose
                else "the loops left open"
            )
            + f" by {float(min(open_roots)):.3g} m (the least), over the {given.prec} "
            "tolerance: no mode with the numbers as written (where the data are rounded, "
            "give them with more digits or exactly)"
        )
    formulation["bezout"] = tracked
    if m > n:
        notes.append(
            f"{m} closure equations in {n} unknowns (an overconstrained mechanism): solved as "
            f"{n} random combinations, every endpoint checked on all {m}; each certificate "
            "proves one root of the combinations in its box"
        )
    if _every_root(prob, raw, tracked, genuine, rows, dps):
        notes.append(
            f"each of the {tracked} paths (the multihomogeneous Bezout number, a bound on the "
            "isolated solutions) ended at its own certified solution: no mode is missing"
        )
        return Found(formulation, rows, len(rows), "proven", paths, tuple(notes), 1, given.closure)
    notes.append(
        f"continuation found {len(genuine)} solution{'' if len(genuine) == 1 else 's'} "
        f"(real and complex) on {tracked} paths; {unproven(paths)}"
    )
    return Found(formulation, rows, len(rows), "not proven", paths, tuple(notes), 1, given.closure)


def _may_hide_a_set(prob: Problem, raw: list[Any], tracked: int, genuine: list[Any]) -> bool:
    """Could the closed configurations hold a set of dimension 1 or more that the
    endpoints do not show?  Yes where a path failed, went to infinity or shared its
    endpoint (Bertini lists the distinct finite ones), or where a genuine endpoint is
    singular in double precision (its Jacobian's least singular value at most
    ``MODE_ENDPOINT_SINGULAR_RTOL`` of its largest: a point of a curve, or a multiple
    root).  A component of the tracked system's solutions draws paths of the homotopy,
    each ending singular on it (its share of the Bezout number: positive for a
    total-degree start by Fulton's refined Bezout theorem, taken to be so for the
    multihomogeneous start); with every path at its own regular genuine endpoint or at
    an extraneous one, no genuine component is left for the slice to find."""
    from mechsing.assembly.certify import conditioning

    if len(raw) < tracked:
        return True
    eqs, groups = patched_system(prob)
    gens = [x for g in groups for x in g]
    return any(conditioning(eqs, gens, z) <= MODE_ENDPOINT_SINGULAR_RTOL for z in genuine)


def _every_root(
    prob: Problem, raw: list[Any], tracked: int, genuine: list[Any], rows: list[Any], dps: int
) -> bool:
    """Has the tracked system as many isolated solutions as its multihomogeneous Bezout
    number (its most): every path finite, every endpoint certified in its own box
    (:func:`~mechsing.assembly.certify.certified_roots`, the boxes pairwise disjoint), and
    the real genuine ones as many as the modes?  Then none is missing."""
    from mechsing.assembly.certify import apart, certified_roots

    if len(raw) != tracked or tracked > PROOF_PATHS or not all(ok for _, ok in rows):
        return False
    eqs, groups = patched_system(prob)
    gens = [x for g in groups for x in g]
    roots = certified_roots(eqs, gens, raw, dps)
    if roots is None:
        return False
    if not apart(roots):
        return False
    kept = {id(z) for z in genuine}
    real = sum(
        1
        for z, x in zip(raw, roots, strict=True)
        if id(z) in kept and all(mpmath.im(v) == 0 for v in x)
    )
    return real == len(rows)


def _dimension_at_start(given: Given, prob: Problem, full: list[Any]) -> tuple[int | None, str]:
    """The local dimension where continuation from the start closes the configuration,
    else at the closed configuration least-squares Newton reaches from the reference (None
    where neither closes), and where."""
    from mechsing.assembly.certify import local_dimension

    res, _ = given.closure
    starts = []
    if res is not None:
        at = ", ".join(f"{n} = {float(v[0]):.6g}" for n, v in res.joints)
        starts.append((_coordinates(prob, dict(res.joints)), f"continuation's closure, {at}"))
    z = _real_point(prob)
    if z is not None:
        row = _row(given.mech, prob, z)
        at = ", ".join(
            f"{c[0]} = {float(v):.6g}" for c, v in zip(given.mech.coordinates(), row, strict=True)
        )
        starts.append((z, f"a real endpoint of the sliced system, {at}"))
    for z, where in starts:
        dim = local_dimension(full, prob.gens, z, given.dps)
        if dim > 0:
            return dim, where
    return None, ""


def _real_point(prob: Problem) -> list[Any] | None:
    """A real closed configuration of an underdetermined system (the first of
    :func:`_sliced`; None: none)."""
    points = _sliced(prob, prob.unknowns - len(prob.equations))
    return points[0] if points else None


def _sliced(prob: Problem, k: int) -> list[list[Any]]:
    """Real closed configurations on the components of dimension ``k`` or more: the
    closure equations (random combinations of them, down to ``n - k``) and ``k`` random
    real linear forms, each in one group (a revolute's fixes its angle), tracked; the real
    endpoints that close every loop (none in ``SLICE_TRIES`` slicings: an empty list)."""
    from mechsing.assembly.certify import polynomial_rows
    from mechsing.assembly.engine import real_endpoints, track

    rng = np.random.default_rng(SEED + 2)
    product = polynomial_rows([c.product for c in prob.closures], prob.gens)
    n = prob.unknowns
    for attempt in range(SLICE_TRIES):
        left = [g.dim for g in prob.groups]
        eqs = _randomized(prob, n - k)
        at = (len(left) - 1 - attempt) % len(left)  # each try slices other groups first
        while len(eqs) < n:
            while not left[at]:
                at = (at - 1) % len(left)
            left[at] -= 1
            g = prob.groups[at]
            r = rng.normal(size=len(g.gens))
            eqs.append(sum(sympy.Rational(float(c)) * x for c, x in zip(r, g.gens, strict=True)))
            at = (at - 1) % len(left)
        patched = list(eqs)
        for g in prob.groups:
            r = rng.normal(size=len(g.gens))
            patched.append(
                sum(sympy.Rational(float(c)) * x for c, x in zip(r, g.gens, strict=True)) - 1
            )
        # one real point is sought (the next try slices otherwise): no adaptive re-run
        raw, _ = track(patched, [g.gens for g in prob.groups], mptype=MPTYPE, retry=False)
        real = real_endpoints([z for z in raw if genuine_endpoint(prob.groups, z, product)])
        if real:
            return [on_normalisations(prob.groups, z) for z in real]
    return []


def _coordinates(prob: Problem, values: dict[str, Any]) -> list[Any]:
    """The groups' coordinates of joint values."""
    z: list[Any] = []
    for i, g in enumerate(prob.groups):
        vals = values[g.joint]
        k = prob.joints[g.joint].index(i)
        if g.kind == "S":
            z += quaternion_of_vector([mpmath.mpf(x) for x in vals])
        elif g.kind == "R":
            q = mpmath.mpf(vals[k])
            z += [mpmath.cos(q / 2), mpmath.sin(q / 2)]
        else:
            z += [mpmath.mpf(1), mpmath.mpf(vals[k]) / (2 * prob.L)]
    return z


FORMULATION = Formulation(
    "joint displacements in Study coordinates (homotopy continuation)", _applies, _find
)
