"""Serial arms: every inverse-kinematics solution of a six-joint arm (revolute and
prismatic joints) for the output's pose, in the half-angle pairs of four of its joints.

Each joint's displacement is a dual quaternion (:mod:`.study`) linear in a homogeneous
pair ``(c, s)``: ``F = c + s A`` with ``A`` the joint's line ``w + eps (p x w)`` and
``(c, s) ~ (cos q/2, sin q/2)`` for a revolute, ``A = eps u`` and ``q = 2 s / c`` (over
L) for a prismatic joint.  The arm reaches the output's displacement ``T`` (from the
reference configuration) when ``F1 F2 F3 F4 F5 F6 = T`` up to a scalar.

Two consecutive joints a, b whose lines are skew (neither parallel nor meeting) reach
exactly the displacements of the Study quadric in the four-dimensional span
``V = (1, Aa, Ab, Aa Ab)`` (M. Husty, M. Pfurner, H.-P. Schroecker, Mech. Mach. Theory
42(1), 2007).  With the loop turned so that such a pair sits third and fourth (a joint
taken past the target becomes ``T* F T``), the arm closes when

    ``G2* G1* T G6* G5*``  lies in ``V``:

four linear conditions on a product that is linear in each of the other four joints'
pairs, so four equations of multidegree (1, 1, 1, 1) in four projective lines, with a
fixed random real patch on each pair: 4! = 24 paths from a multihomogeneous start
system.  An endpoint with an isotropic pair (``c^2 + s^2 = 0``: a zero divisor, no joint
value) is extraneous; the others are the arm's solutions, at most 16 (H.-Y. Lee and
C.-G. Liang, Mech. Mach. Theory 23(3), 1988; M. Raghavan and B. Roth, ASME J. Mech. Des.
115(3), 1993) and at most 8 when three consecutive revolute axes meet in a point or are
parallel (D. Pieper, 1968).  The pair in the middle follows from the rank-one
factorisation of the coordinates in ``V``: ``(c3 c4, s3 c4, c3 s4, s3 s4)``.

When no consecutive pair is skew (a UR arm with its tool's axis along the base's), a
parallel (else meeting) pair carries the formulation: its displacements form a subgroup
whose span lies in the Study quadric, so the system holds three random combinations of the
four span conditions and the rank-one condition ``(c3 c4)(s3 s4) = (s3 c4)(c3 s4)``:
2 x 4! = 48 paths, the endpoints off the span extraneous.  A chain of more joints with
all but six given (a redundant arm, a single loop) is reduced to six first
(:func:`six_joint_chain`).

Owns :class:`SerialArm`, :func:`arm_chain`, :func:`serial_arm`, :func:`six_joint_chain`,
:func:`loop_arm`, :func:`serial_target`, :func:`pose_target`, :class:`SerialSystem`,
:func:`serial_system`, :func:`solve_serial`, :func:`all_certified`.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.assembly.certify import certified_roots, newton, regular, singular_root
from mechsing.assembly.engine import SEED, real_endpoints, track
from mechsing.assembly.settings import (
    MODE_CERTIFY_RADIUS,
    MODE_ENDPOINT_SINGULAR_RTOL,
    MODE_EXTRANEOUS_RTOL,
    MODE_ISOTROPIC_RTOL,
    MODE_PAIR_SKEW,
    MODE_PIEPER_ATOL,
    MODE_SINGULAR_IMAGINARY_RTOL,
)
from mechsing.assembly.study import (
    line,
    rotation,
    rotation_quaternion,
    slide,
)
from mechsing.errors import FormulationError, UserError
from mechsing.lie.dual import study_conjugate, study_multiply
from mechsing.lie.quaternion import quat_multiply
from mechsing.model import Mechanism
from mechsing.numeric import MODE_MATCH_DISTANCE

__all__ = [
    "SerialArm",
    "all_certified",
    "already_found",
    "SerialSystem",
    "serial_arm",
    "serial_system",
    "given_solution",
    "loop_arm",
    "pairs_of",
    "posture_distance",
    "serial_target",
    "six_joint_chain",
    "account",
    "arm_chain",
    "arm_value",
    "chain_to_output",
    "half_angle_value",
    "pose_target",
    "solve_serial",
]

#: the most solutions of a six-joint arm, and of Pieper's arms
GENERIC_COUNT, PIEPER_COUNT = 16, 8


def _mp(x: Any) -> Any:
    """A number of the file (exact or float) at the working digits plus guard digits."""
    if isinstance(x, float):
        return mpmath.mpf(x)
    return mpmath.mpf(sympy.N(sympy.sympify(x), mpmath.mp.dps + 10))


@dataclass(frozen=True)
class SerialArm:
    """The six joints from ground to the output (names, ``R``/``P``), each joint's line
    (8 Study coordinates, lengths over ``L``, oriented from ground to the output), the
    length scale and the most solutions the arm can have (with why)."""

    joints: tuple[str, ...]
    kinds: tuple[str, ...]
    lines: tuple[list[Any], ...]
    L: Any
    generic_count: int
    pieper: str | None


def arm_chain(mech: Mechanism) -> tuple[list[str], list[int]]:
    """The joints of a mechanism without loops from ground to its output, each R or P
    (every joint of the file on that chain, six or more), and each one's direction along it."""
    names, signs = chain_to_output(mech)
    bad = [n for n in names if mech.joint(n).type not in ("R", "P")]
    if bad:
        raise FormulationError(
            f"the arm's joints must be R or P, and joint {bad[0]} is {mech.joint(bad[0]).type}"
        )
    if len(names) < 6:
        raise FormulationError(
            f"the arm needs six R or P joints from ground, and it has {len(names)} (its "
            "postures for a whole pose are the solutions of more equations than unknowns)"
        )
    return names, signs


def chain_to_output(mech: Mechanism) -> tuple[list[str], list[int]]:
    """The joints of a mechanism without loops from ground to its output (every joint of
    the file on that chain), and each one's direction along it."""
    out = mech.output
    if mech.loops:
        raise FormulationError("the mechanism has loops: it is not a serial arm")
    if out is None:
        raise FormulationError("the file has no output: the arm's end is not named")
    if out.relative_to != mech.ground:
        raise FormulationError(f"the output is relative to {out.relative_to}, not to ground")
    steps = mech.graph.tree_paths[out.body]
    names = [st.joint for st in steps]
    off = [j.name for j in mech.joints if j.name not in names]
    if off:
        raise FormulationError(
            f"joint {off[0]} is not on the chain from ground to the output {out.body} (each "
            "joint must be: remove the side branch, or make its body the output)"
        )
    return names, [st.sign for st in steps]


def serial_arm(mech: Mechanism, L: float) -> SerialArm:
    """The six-joint arm of a mechanism without loops (:func:`arm_chain`)."""
    names, signs = arm_chain(mech)
    if len(names) != 6:
        raise FormulationError(
            f"the arm has {len(names)} joints: give the output's pose and {len(names) - 6} "
            "joint values (a redundant arm reaches a pose alone along a curve)"
        )
    return six_joint_chain(mech, names, signs, {}, IDENTITY, L)[0]


#: the identity displacement's Study coordinates
IDENTITY = (1, 0, 0, 0, 0, 0, 0, 0)


def six_joint_chain(
    mech: Mechanism,
    names: list[str],
    signs: list[int],
    given: dict[str, tuple[Any, ...]],
    T: Any,
    L: float,
) -> tuple[SerialArm, list[Any]]:
    """Joints ``names`` in a chain whose product is ``T`` (a serial arm's output pose; a
    loop's identity), ``given`` fixing all but six: the six-joint chain (its lines past the
    given joints' constant displacements) and the displacement it reaches.  The constants
    are moved to the end, ``X C = C (C* X C)``: each later joint's line is conjugated, and
    ``G1 ... G6 C = T`` gives ``G1 ... G6 = T C*``."""
    unknown = [n for n in names if n not in given]
    if len(unknown) != 6:
        raise FormulationError(
            f"{len(names)} joints and {len(names) - len(unknown)} given values leave "
            f"{len(unknown)} unknown, not six; give "
            + (f"{len(unknown) - 6} more joint values" if len(unknown) > 6 else "fewer")
        )
    Lm = mpmath.mpf(L)
    C: list[Any] = list(IDENTITY)  # the given joints' displacements so far
    lines = []
    for name, sign in zip(names, signs, strict=True):
        ln = _joint_line(mech, name, sign, Lm)
        if name in given:
            kind = mech.joint(name).type
            C = study_multiply(C, _factor(*_pair(kind, _mp(given[name][0]), Lm), ln))
        else:
            lines.append(study_multiply(study_multiply(C, ln), study_conjugate(C)))
    return _arm(mech, unknown, lines, Lm), study_multiply(list(T), study_conjugate(C))


def _arm(mech: Mechanism, names: list[str], lines: list[list[Any]], L: Any) -> SerialArm:
    kinds = tuple(mech.joint(n).type for n in names)
    pieper = _pieper(names, kinds, lines)
    count = PIEPER_COUNT if pieper else GENERIC_COUNT
    return SerialArm(tuple(names), kinds, tuple(lines), L, count, pieper)


def _joint_line(mech: Mechanism, name: str, sign: int, L: Any) -> list[Any]:
    """A joint's line (Study coordinates, lengths over L), turned by ``sign``."""
    j = mech.joint(name)
    axis = [_mp(x) for x in j.params["axis"]]
    n = mpmath.sqrt(sum(x * x for x in axis))
    axis = [sign * x / n for x in axis]
    if j.type == "R":
        return line(axis, [_mp(x) / L for x in j.params["point"]])
    return slide(axis)


def loop_arm(
    mech: Mechanism, given: dict[str, tuple[Any, ...]], L: float
) -> tuple[SerialArm, list[Any]]:
    """A single loop with six joints left unknown by ``given``: the six-joint chain and
    the displacement it reaches (:func:`six_joint_chain` with the identity)."""
    if len(mech.loops) != 1:
        raise FormulationError(f"the mechanism has {len(mech.loops)} loops, not one")
    loop = mech.loops[0]
    off = [j.name for j in mech.joints if j.name not in loop.joints]
    if off:
        raise FormulationError(f"joint {off[0]} is not on the loop")
    bad = [n for n in loop.joints if mech.joint(n).type not in ("R", "P")]
    if bad:
        raise FormulationError(f"joint {bad[0]} is {mech.joint(bad[0]).type}, not R or P")
    return six_joint_chain(mech, list(loop.joints), list(loop.signs), given, IDENTITY, L)


def _pieper(names: list[str], kinds: tuple[str, ...], lines: list[list[Any]]) -> str | None:
    """Three consecutive revolute axes that meet in a point or are parallel, in words."""
    w = [np.array([float(x) for x in ln[1:4]]) for ln in lines]
    m = [np.array([float(x) for x in ln[5:8]]) for ln in lines]
    for i in range(4):
        if kinds[i : i + 3] != ("R", "R", "R"):
            continue
        trio = ", ".join(names[i : i + 3])
        ws = w[i : i + 3]
        if all(np.linalg.norm(np.cross(ws[0], v)) <= MODE_PIEPER_ATOL for v in ws[1:]):
            return f"the axes of {trio} are parallel"
        # the point nearest the three lines: p x w = m on each, in least squares
        rows = np.vstack([_skew(v) for v in ws])
        rhs = np.concatenate([-mm for mm in m[i : i + 3]])
        p, *_ = np.linalg.lstsq(rows, rhs, rcond=None)
        if float(np.linalg.norm(rows @ p - rhs)) <= MODE_PIEPER_ATOL:
            return f"the axes of {trio} meet in a point"
    return None


def _skew(w: np.ndarray) -> np.ndarray:
    """The matrix of ``p -> w x p`` (so ``p x w = -skew(w) p``)."""
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def _factor(c: Any, s: Any, ln: list[Any]) -> list[Any]:
    return [c * (1 if i == 0 else 0) + s * ln[i] for i in range(8)]


def _pair(kind: str, q: Any, L: Any) -> tuple[Any, Any]:
    """The pair ``(c, s)`` of a joint value (rad, or m for a slide)."""
    if kind == "R":
        return mpmath.cos(q / 2), mpmath.sin(q / 2)
    return mpmath.mpf(1), q / (2 * L)


def serial_target(
    mech: Mechanism, config: str, arm: SerialArm, atol: Any
) -> tuple[list[Any], bool]:
    """The output's displacement ``T`` (Study coordinates, lengths over L) a configuration
    of a six-joint arm asks for: its ``pose`` (:func:`pose_target`), or the pose its six
    joint values reach; and whether the values were given (then the given configuration
    is one of the modes)."""
    cfg = mech.configurations[config]
    given = [n for n in arm.joints if n in cfg.values]
    if cfg.pose is None:
        T: list[Any] = list(IDENTITY)
        for n, kind, ln in zip(arm.joints, arm.kinds, arm.lines, strict=True):
            T = study_multiply(T, _factor(*_pair(kind, _mp(arm_value(mech, config, n)), arm.L), ln))
        return T, True
    if given:
        raise FormulationError(
            f"configuration {config!r} gives the output's pose and joint {given[0]}: the "
            "pose alone fixes a six-joint arm's modes"
        )
    return pose_target(mech, config, arm.L, atol), False


def pose_target(mech: Mechanism, config: str, L: Any, atol: Any) -> list[Any]:
    """The displacement (Study coordinates, lengths over L) a configuration's ``pose``
    asks of the output (an omitted position or rotation is the reference's).  A rotation
    matrix must be orthonormal to ``atol`` (largest entry of ``R^T R - I``: the
    classification's precision, as ``solve`` asks); the modes are then found for the
    nearest rotation."""
    pose = mech.configurations[config].pose
    assert pose is not None
    if pose.rotation is not None:
        R = mpmath.matrix([[_mp(x) for x in row] for row in pose.rotation])
        _check_rotation(mech, config, R, atol)
    elif pose.rotation_vector is not None:
        R = rotation([_mp(x) for x in pose.rotation_vector])
    else:
        R = mpmath.eye(3)
    c0 = mpmath.matrix([_mp(x) for x in mech.output_reference_point()])
    x1 = c0 if pose.position is None else mpmath.matrix([_mp(x) for x in pose.position])
    t = (x1 - R * c0) / mpmath.mpf(L)
    X = rotation_quaternion(R)
    norm = mpmath.sqrt(sum(x * x for x in X))  # the nearest rotation's, when R is rounded
    X = [x / norm for x in X]
    Y = [v / 2 for v in quat_multiply([0, t[0], t[1], t[2]], X)]
    return [*X, *Y]


def _check_rotation(mech: Mechanism, config: str, R: Any, atol: Any) -> None:
    E = R.T * R - mpmath.eye(3)
    err = max(abs(E[i, k]) for i in range(3) for k in range(3))
    if mpmath.det(R) <= 0 or err > atol:
        raise UserError(
            f"{mech.path or mech.name}: configuration {config!r}: the pose's rotation is not "
            f"a rotation matrix (R^T R = I, det R = 1) to {mpmath.nstr(mpmath.mpf(atol), 3)}; "
            "give an orthonormal matrix (with more digits)"
        )


def arm_value(mech: Mechanism, config: str, name: str) -> Any:
    """A joint's value in a configuration of an arm without loops: given there, else in
    its start's (the chain of starts), else the reference's 0."""
    cur: str | None = config
    while cur is not None:
        cfg = mech.configurations[cur]
        if name in cfg.values:
            return cfg.values[name][0]
        if cfg.pose is not None:
            raise FormulationError(
                f"configuration {config!r} leaves joint {name} to its start {cur!r}, which "
                "gives the output's pose: give every joint, or the pose"
            )
        cur = cfg.start
    return 0


def given_solution(
    mech: Mechanism, config: str, system: SerialSystem
) -> tuple[list[Any], list[Any]]:
    """The four outer pairs and six joint values of a configuration that gives the arm's
    joints (one of its own modes)."""
    arm = system.arm
    q = [_mp(arm_value(mech, config, n)) for n in arm.joints]
    return pairs_of(system, q), [
        _value(k, *_pair(k, v, arm.L), arm.L) for k, v in zip(arm.kinds, q, strict=True)
    ]


def pairs_of(system: SerialSystem, q: list[Any]) -> list[Any]:
    """The four outer pairs (the formulation's unknowns) of six joint values."""
    arm = system.arm
    pairs: list[Any] = []
    for i in system.outer:
        pairs += list(_pair(arm.kinds[i], q[i], arm.L))
    return pairs


@dataclass(frozen=True)
class SerialSystem:
    """The formulation for one target: the loop's turn (``order``: the arm's joint
    indices as G1..G6, the last ones taken past the target), the middle pair's basis of
    ``V`` (8 x 4, orthonormal) and its triangular factor, the four unknown pairs
    (``gens``: c, s per outer joint), the patched equations the engine tracks
    (``patched``, by ``groups``) and the square system every mode is refined and
    certified in (``square``: each revolute pair on its unit circle, each slide's c = 1),
    and the four conditions of ``M`` in ``V`` (``linear``; with a pair that is not skew,
    ``skew`` is 0 and the system holds three combinations of them and the rank-one
    condition)."""

    arm: SerialArm
    target: list[Any]
    order: tuple[int, ...]
    lines: tuple[list[Any], ...]
    basis: Any
    triangle: Any
    skew: float
    gens: tuple[sympy.Symbol, ...]
    groups: tuple[tuple[sympy.Symbol, sympy.Symbol], ...]
    patched: tuple[sympy.Expr, ...]
    square: tuple[sympy.Expr, ...]
    linear: tuple[sympy.Expr, ...]

    @property
    def outer(self) -> tuple[int, ...]:
        """The arm's indices of the four joints whose pairs are the unknowns."""
        o = self.order
        return (o[0], o[1], o[4], o[5])

    @property
    def middle(self) -> tuple[int, int]:
        return self.order[2], self.order[3]


def _pair_space(a: list[Any], b: list[Any]) -> tuple[Any, Any, Any, float, float]:
    """V = span(1, a, b, ab): its orthonormal basis Q (8 x 4), R (B = Q R), the
    orthonormal basis of its complement (8 x 4) and how far from degenerate it is (the
    least |eigenvalue| of the Study quadric on V; 0 when the lines are parallel or meet,
    or the span has not four dimensions) and how far the span is from fewer dimensions
    (the least pivot of R)."""
    B = mpmath.matrix(8, 4)
    for k, v in enumerate(([1, 0, 0, 0, 0, 0, 0, 0], a, b, study_multiply(a, b))):
        for i in range(8):
            B[i, k] = v[i]
    full, R8 = mpmath.qr(B, mode="full")
    Q, N, R = mpmath.matrix(8, 4), mpmath.matrix(8, 4), mpmath.matrix(4, 4)
    for i in range(8):
        for k in range(4):
            Q[i, k], N[i, k] = full[i, k], full[i, k + 4]
    for i in range(4):
        for k in range(4):
            R[i, k] = R8[i, k]
    span = float(min(abs(R[k, k]) for k in range(4)))
    if span <= MODE_PAIR_SKEW:
        return Q, R, N, 0.0, span
    S = mpmath.matrix(4, 4)
    for i in range(4):
        for k in range(4):
            S[i, k] = sum(Q[r, i] * Q[r + 4, k] + Q[r + 4, i] * Q[r, k] for r in range(4)) / 2
    eig = mpmath.eigsy(S)[0]
    return Q, R, N, float(min(abs(e) for e in eig)), span


def serial_system(arm: SerialArm, target: list[Any], shift: int | None = None) -> SerialSystem:
    """The formulation on the consecutive pair (a joint and the next, or the last and the
    first past the target) whose lines are the farthest from parallel or meeting
    (``shift``: on the pair of the arm's joints ``shift + 2`` and ``shift + 3``, counted
    from 0 and past the target, whatever its lines)."""
    Tc = study_conjugate(target)
    moved = [
        study_multiply(study_multiply(Tc, ln), target) for ln in arm.lines
    ]  # T* A T: past the target
    pairs = []
    for turn in range(6):
        order = tuple((turn + i) % 6 for i in range(6))
        lines = tuple(arm.lines[j] if turn + i < 6 else moved[j] for i, j in enumerate(order))
        pairs.append((order, lines, _pair_space(lines[2], lines[3])))
    order, lines, (Q, R, N, skew, span) = max(pairs, key=lambda p: (p[2][3], p[2][4]))
    if shift is not None:
        order, lines, (Q, R, N, skew, span) = pairs[shift]
    if skew <= MODE_PAIR_SKEW:
        # no skew pair (the tool's axis parallel to the base's, say): the pair whose span
        # is the best conditioned, its rank-one condition written out
        if shift is None:  # a parallel pair first (its endpoints are cleaner), then the span
            order, lines, (Q, R, N, skew, span) = max(
                pairs, key=lambda p: (_parallel(p[1][2], p[1][3]), p[2][4])
            )
        if span <= MODE_PAIR_SKEW:
            raise FormulationError(
                "no two consecutive joints span four dimensions of displacements (each "
                "pair is coaxial, or two slides): the half-angle formulation has no pair"
            )
        skew = 0.0
    gens = sympy.symbols("c0 s0 c1 s1 c2 s2 c3 s3")
    groups = tuple((gens[2 * k], gens[2 * k + 1]) for k in range(4))
    digits = mpmath.mp.dps + 10

    def num(x: Any) -> Any:
        return sympy.Float(x, digits) if not isinstance(x, int) else x

    G = [[num(x) for x in lines[i]] for i in (0, 1, 4, 5)]
    F = [_factor(c, s, g) for (c, s), g in zip(groups, G, strict=True)]
    M = study_multiply(
        study_multiply(
            study_multiply(
                study_multiply(study_conjugate(F[1]), study_conjugate(F[0])),
                [num(x) for x in target],
            ),
            study_conjugate(F[3]),
        ),
        study_conjugate(F[2]),
    )
    # M in V: its components along V's complement (N's columns) vanish
    linear = [sympy.expand(sum(num(N[i, k]) * M[i] for i in range(8))) for k in range(4)]
    rng = np.random.default_rng(SEED)
    if skew:
        # on the Study quadric (where M lies), V holds only the pair's displacements
        eqs = linear
    else:
        # V lies in the Study quadric (a subgroup): three random combinations of the four
        # conditions (V and one more 3-space V') and the rank-one condition on M's
        # coordinates in V, (c3 c4)(s3 s4) = (s3 c4)(c3 s4); the endpoints in V' are
        # extraneous (the fourth condition fails there): 2 x 4! = 48 paths
        mix = rng.normal(size=(3, 4))
        eqs = [
            sympy.expand(sum(sympy.Rational(float(mix[r, k])) * linear[k] for k in range(4)))
            for r in range(3)
        ]
        Rinv = mpmath.inverse(R)
        coords = [
            sum(num(sum(Rinv[a, b] * Q[i, b] for b in range(4))) * M[i] for i in range(8))
            for a in range(4)
        ]
        eqs.append(sympy.expand(coords[0] * coords[3] - coords[1] * coords[2]))
    patched = [*eqs]
    square = [*eqs]
    for (c, s), j in zip(groups, (order[0], order[1], order[4], order[5]), strict=True):
        r = rng.normal(size=2)
        patched.append(sympy.Rational(float(r[0])) * c + sympy.Rational(float(r[1])) * s - 1)
        square.append(c * c + s * s - 1 if arm.kinds[j] == "R" else c - 1)
    return SerialSystem(
        arm,
        target,
        order,
        lines,
        Q,
        R,
        skew,
        gens,
        groups,
        tuple(patched),
        tuple(square),
        tuple(linear),
    )


def _parallel(a: list[Any], b: list[Any]) -> bool:
    """Are two revolute lines parallel (their directions, to ``MODE_PIEPER_ATOL``)?"""
    wa = np.array([float(x) for x in a[1:4]])
    wb = np.array([float(x) for x in b[1:4]])
    both = np.linalg.norm(wa) > 0.5 and np.linalg.norm(wb) > 0.5
    return bool(both and np.linalg.norm(np.cross(wa, wb)) <= MODE_PIEPER_ATOL)


def _extraneous(z: np.ndarray, kinds: list[str], off: Any = None) -> bool:
    """An endpoint with an isotropic revolute pair or an infinite slide, or (``off``:
    the relative residual of the four conditions of M in V) one off the pair's span."""
    if off is not None and off(z) > MODE_EXTRANEOUS_RTOL:
        return True
    for k, kind in enumerate(kinds):
        c, s = z[2 * k], z[2 * k + 1]
        size = abs(c) ** 2 + abs(s) ** 2
        if kind == "R" and abs(c * c + s * s) <= MODE_ISOTROPIC_RTOL * size:
            return True
        if kind == "P" and abs(c) ** 2 <= MODE_ISOTROPIC_RTOL * size:
            return True
    return False


def _off(system: SerialSystem) -> Any:
    """The relative residual of the four conditions of M in V at an endpoint (numpy)."""
    f = sympy.lambdify(system.gens, list(system.linear), "numpy")
    size = sympy.lambdify(
        system.gens, [sum(abs(t) for t in sympy.Add.make_args(e)) for e in system.linear], "numpy"
    )

    def off(z: np.ndarray) -> float:
        w = [complex(v) for v in z]
        return float(np.max(np.abs(f(*w))) / max(1e-300, float(np.max(np.abs(size(*w))))))

    return off


def _normalised(z: np.ndarray, kinds: list[str]) -> list[Any]:
    """An endpoint's pairs scaled to the square system's: each revolute pair onto
    ``c^2 + s^2 = 1``, each slide's ``c`` to 1 (real endpoints stay real floats)."""
    out: list[Any] = []
    real = not np.iscomplexobj(z)
    for k, kind in enumerate(kinds):
        c, s = z[2 * k], z[2 * k + 1]
        if real:
            c, s = float(c), float(s)
            n = np.hypot(c, s) if kind == "R" else c
        else:
            n = np.sqrt(c * c + s * s) if kind == "R" else c
        out += [c / n, s / n]
    return out


def already_found(arm: SerialArm, q: list[Any], found: list[tuple[Any, list[Any], bool]]) -> bool:
    """Is posture ``q`` one of ``found``'s (within ``MODE_MATCH_DISTANCE``)?"""
    return any(posture_distance(arm, q, other) <= MODE_MATCH_DISTANCE for _, other, _ in found)


def _value(kind: str, c: Any, s: Any, L: Any) -> Any:
    """A joint value (rad in (-pi, pi], or a slide) of its pair ``(c, s)``."""
    if kind == "R":
        q = 2 * mpmath.atan2(s, c)  # in (-2 pi, 2 pi]: brought to (-pi, pi]
        if q > mpmath.pi:
            q -= 2 * mpmath.pi
        elif q <= -mpmath.pi:
            q += 2 * mpmath.pi
        # a half-turn refined to the working digits from either side is +pi
        if abs(q + mpmath.pi) <= mpmath.mpf(10) ** (-(mpmath.mp.dps // 2)):
            return +mpmath.pi
        return q
    return 2 * L * s / c


def joint_values_serial(system: SerialSystem, pairs: list[Any]) -> list[Any]:
    """The arm's six joint values (in the arm's order) from the four outer pairs: the
    middle pair from the rank-one coordinates of the product in V."""
    arm = system.arm
    F = [
        _factor(pairs[2 * k], pairs[2 * k + 1], system.lines[i]) for k, i in enumerate((0, 1, 4, 5))
    ]
    M = study_multiply(
        study_multiply(
            study_multiply(
                study_multiply(study_conjugate(F[1]), study_conjugate(F[0])), system.target
            ),
            study_conjugate(F[3]),
        ),
        study_conjugate(F[2]),
    )
    Qt = system.basis.T * mpmath.matrix(M)
    q = mpmath.lu_solve(system.triangle, Qt)  # (c3 c4, s3 c4, c3 s4, s3 s4)
    col = (q[0], q[1]) if abs(q[0]) + abs(q[1]) >= abs(q[2]) + abs(q[3]) else (q[2], q[3])
    row = (q[0], q[2]) if abs(q[0]) + abs(q[2]) >= abs(q[1]) + abs(q[3]) else (q[1], q[3])
    values: dict[int, Any] = {}
    for k, i in enumerate(system.outer):
        values[i] = _value(arm.kinds[i], pairs[2 * k], pairs[2 * k + 1], arm.L)
    a, b = system.middle
    values[a] = _value(arm.kinds[a], col[0], col[1], arm.L)
    values[b] = _value(arm.kinds[b], row[0], row[1], arm.L)
    return [values[i] for i in range(6)]


def solve_serial(
    system: SerialSystem, dps: int
) -> tuple[list[tuple[list[Any], list[Any], bool]], dict[str, Any], str | None, list[np.ndarray]]:
    """Every real solution: (its four outer pairs refined to ``dps`` digits, the arm's
    six joint values, whether the root is regular), the paths' account, where the
    solutions are not finitely many (a real endpoint on a curve of solutions: None when
    none is), and every solution's endpoint, real or complex (not extraneous)."""
    kinds = [system.arm.kinds[i] for i in system.outer]
    raw, tracked = track(system.patched, system.groups)
    off = None if system.skew else _off(system)
    genuine = [z for z in raw if not _extraneous(z, kinds, off)]
    real = real_endpoints(genuine)
    singular = _singular_endpoints(system, genuine, kinds, dps)
    flat = len(singular)
    # a multiple root's endpoint is accurate to the square root of the engine's precision
    # or worse: a singular endpoint nearly real may be a real root
    near = [z for z in singular if not real_endpoints([z]) and _nearly_real(z)]
    found: list[tuple[list[Any], list[Any], bool]] = []
    duplicates = 0
    for z in [*real, *(z.real for z in near)]:
        start = _normalised(z, kinds)
        pairs = newton(system.square, system.gens, start, dps)
        ok = pairs is not None and regular(system.square, system.gens, pairs)
        if not ok:
            pairs, curve = singular_root(system.square, system.gens, start, dps)
            if pairs is None:
                continue
            q = joint_values_serial(system, pairs)
            if curve:
                names = system.arm.joints
                at = ", ".join(f"{n} = {float(v):.6g}" for n, v in zip(names, q, strict=True))
                return [], account(tracked, raw, genuine, real, found, 0, flat), at, genuine
        q = joint_values_serial(system, pairs)
        if already_found(system.arm, q, found):
            duplicates += 1
            continue
        found.append((pairs, q, ok))
    found.sort(key=lambda f: [float(x) for x in f[1]])
    return found, account(tracked, raw, genuine, real, found, duplicates, flat), None, genuine


def all_certified(system: SerialSystem, points: list[np.ndarray], dps: int) -> int | None:
    """How many of the endpoints are real roots, when every endpoint, real or complex, is
    a regular root refined at ``dps`` digits and certified by the Krawczyk test (on its
    real and imaginary parts), the certified boxes pairwise disjoint even after turning
    any revolute pair's sign (the same posture): so many distinct solutions, none missing
    when they number the arm's most (None: not all certified).  A root refined to real
    values to half the digits is certified in a box centred on its real part: the box is
    symmetric under conjugation and holds one root, which is then its own conjugate, real;
    the others' boxes lie clear of the real space, so their roots are not real."""
    kinds = [system.arm.kinds[i] for i in system.outer]
    radius = mpmath.mpf(MODE_CERTIFY_RADIUS)
    roots = certified_roots(
        system.square, system.gens, [_normalised(z.astype(complex), kinds) for z in points], dps
    )
    if roots is None:
        return None
    flips = [k for k, kind in enumerate(kinds) if kind == "R"]
    for i, a in enumerate(roots):
        for b in roots[i + 1 :]:
            for signs in itertools.product((1, -1), repeat=len(flips)):
                turned = list(a)
                for k, sg in zip(flips, signs, strict=True):
                    turned[2 * k] *= sg
                    turned[2 * k + 1] *= sg
                gap = max(
                    max(abs(mpmath.re(u - v)), abs(mpmath.im(u - v)))
                    for u, v in zip(turned, b, strict=True)
                )
                if gap <= 2 * radius:
                    return None
    return sum(1 for x in roots if all(mpmath.im(v) == 0 for v in x))


def _singular_endpoints(
    system: SerialSystem, points: list[np.ndarray], kinds: list[str], dps: int
) -> list[np.ndarray]:
    """The endpoints (complex, double precision) that are singular roots of the square
    system: multiple roots, or points of a curve of solutions."""
    jac = sympy.lambdify(
        system.gens, [[sympy.diff(e, g) for g in system.gens] for e in system.square], "numpy"
    )
    out = []
    for z in points:
        w = _normalised(z.astype(complex), kinds)
        sv = np.linalg.svd(np.array(jac(*w), dtype=complex), compute_uv=False)
        if sv[-1] > MODE_ENDPOINT_SINGULAR_RTOL * sv[0]:
            continue
        # ill-conditioned in double precision: singular only if it is at the working digits
        root = newton(system.square, system.gens, w, dps)
        if root is None or not regular(system.square, system.gens, root):
            out.append(z)
    return out


def _nearly_real(z: np.ndarray) -> bool:
    scale = max(1.0, float(np.max(np.abs(z))))
    return float(np.max(np.abs(z.imag))) <= MODE_SINGULAR_IMAGINARY_RTOL * scale


def account(
    tracked: int, raw: list, genuine: list, real: list, found: list, duplicates: int, singular: int
) -> dict[str, Any]:
    """The paths' account of a homotopy (``found``: the distinct real modes refined)."""
    return {
        "tracked": tracked,
        "finite": len(raw),
        "extraneous": len(raw) - len(genuine),
        "solutions": len(genuine),
        "real": len(real),
        "refined": len(found) + duplicates,
        "singular": singular,  # endpoints (real or complex) where the Jacobian is singular
        "failed_or_infinite": tracked - len(raw),
        "duplicates": duplicates,
    }


def unproven(paths: dict[str, Any]) -> str:
    """Why a homotopy's paths (their :func:`account`) do not prove its count: the clause
    that ends a ``not proven`` note."""
    lost = paths["failed_or_infinite"]
    if lost:
        return (
            f"{lost} of the {paths['tracked']} paths failed or went to infinity (a failed "
            "one could hide a mode), so the count is not proven"
        )
    return (
        "every path ended finite, but not each at a solution certified in a box of its own "
        f"({paths['finite'] - paths['solutions']} of the endpoints are extraneous: no "
        "configuration), so the paths do not rule out one that jumped onto another's "
        "solution and left a mode unreached: the count is not proven"
    )


def posture_distance(arm: SerialArm, q1: list[Any], q2: list[Any]) -> float:
    """The commensurate distance between two postures (angles modulo 2 pi, slides over L)."""
    total = 0.0
    for kind, a, b in zip(arm.kinds, q1, q2, strict=True):
        d = float(a - b)
        if kind == "R":
            d = (d + np.pi) % (2 * np.pi) - np.pi
        else:
            d /= float(arm.L)
        total += d * d
    return float(np.sqrt(total))


#: a joint's value of its half-angle pair (the general formulation reads its pairs so)
half_angle_value = _value
