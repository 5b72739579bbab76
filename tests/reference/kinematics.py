"""Mechanism kinematics for the tests, from the product's conventions alone: the reference basis
screws of every joint type, joint displacements, body poses along a breadth-first spanning tree,
a cycle basis (networkx) and the products around it, closure errors, spatial joint screws, a
path tracker (Gauss-Newton on the cycle products with finite differences) and the closed-form
planar four-bar; the characteristic length and centroid of the commensurate metric, and how far
a displacement is from the identity as a length.

Joint values are dictionaries {joint name: array of its coordinates} in SI units and radians.
Bases, joint displacements, the characteristic length and the mismatch keep the number type of
the joint's data (floats, or mpmath / sympy numbers: give :class:`J` their ``one`` and an ``exp``
in that type, such as :func:`tests.reference.se3.expm_mp`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field

import networkx as nx
import numpy as np

from tests.reference.se3 import (
    adjoint,
    exp_rodrigues,
    expt,
    in_plane,
    inv,
    revolute,
    slide,
    sqrt,
    unit,
)

PI = math.pi

#: kind of each coordinate per joint type: "a" angle (rad), "l" length (m)
KINDS = {
    "R": "a",
    "P": "l",
    "H": "a",
    "C": "al",
    "T2": "ll",
    "T3": "lll",
    "S": "aaa",
    "G": "all",
    "Y": "all",
    "X": "alll",
    "D": "aaalll",
    "U": "aa",
    "E": "",
}

Exp = Callable[[np.ndarray], np.ndarray]
Values = Mapping[str, np.ndarray]


def _eye(n: int, one: object) -> np.ndarray:
    """The n x n identity in the number type of ``one``."""
    if isinstance(one, float):
        return np.eye(n)
    return np.array([[one if i == k else one * 0 for k in range(n)] for i in range(n)])


def basis(jtype: str, prm: dict, one: object = 1.0) -> list[np.ndarray]:
    """The reference basis screws of a joint (SI units), in the number type of ``one`` (1.0,
    ``mpmath.mpf(1)``, ``sympy.Integer(1)``) and of the joint's data."""
    eye = _eye(3, one)
    zero = eye[0] * 0
    if jtype == "R":
        return [revolute(prm["axis"], prm["point"])]
    if jtype == "P":
        return [slide(prm["axis"])]
    if jtype == "H":
        u = unit(prm["axis"])
        return [revolute(u, prm["point"]) + np.concatenate([zero, prm["pitch"] * u])]
    if jtype == "C":
        return [revolute(prm["axis"], prm["point"]), slide(prm["axis"])]
    if jtype == "T2":
        e1, e2 = in_plane(prm["normal"])
        return [slide(e1), slide(e2)]
    if jtype == "T3":
        return [slide(eye[k]) for k in range(3)]
    if jtype == "S":
        return [revolute(eye[k], prm["point"]) for k in range(3)]
    if jtype in ("G", "Y"):
        n = unit(prm["normal"])
        e1, e2 = in_plane(prm["normal"])
        h = prm.get("pitch", one * 0)
        return [np.concatenate([n, h * n]), slide(e1), slide(e2)]
    if jtype == "X":
        a = unit(prm["axis"])
        e1, e2 = in_plane(prm["axis"])
        return [np.concatenate([a, zero]), slide(e1), slide(e2), slide(a)]
    if jtype == "D":
        return list(_eye(6, one))
    if jtype == "U":
        a1, a2 = prm["axes"]
        return [revolute(a1, prm["point"]), revolute(a2, prm["point"])]
    if jtype == "E":
        return []
    raise AssertionError(jtype)


@dataclass
class J:
    """A joint as the reference understands it (SI): between bodies ``a`` and ``b``, its data
    (``prm``) and its values in the number type of ``one`` (1.0: floats)."""

    name: str
    type: str
    a: str
    b: str
    prm: dict = field(default_factory=dict)
    one: object = 1.0

    @functools.cached_property
    def basis(self) -> list[np.ndarray]:
        return basis(self.type, self.prm, self.one)

    def element(self, q: Iterable[float], exp: Exp = expt) -> np.ndarray:
        """The relative displacement M with g_b = g_a M (``exp`` in the joint's number type)."""
        B = self.basis
        q = np.asarray(q, dtype=float if isinstance(self.one, float) else object).reshape(-1)
        assert len(q) == len(B)
        if self.type == "U":
            return exp(q[0] * B[0]) @ exp(q[1] * B[1])
        if not B:
            return np.eye(4)
        return exp(sum(qi * b for qi, b in zip(q, B, strict=True)))


def poses(joints: list[J], ground: str, values: Values, exp: Exp = expt) -> dict[str, np.ndarray]:
    """Body poses along a breadth-first spanning tree (bodies in the order met, joints in list
    order)."""
    out = {ground: np.eye(4)}
    todo = [ground]
    while todo:
        body = todo.pop(0)
        for j in joints:
            if j.a == body and j.b not in out:
                out[j.b] = out[body] @ j.element(values[j.name], exp)
                todo.append(j.b)
            elif j.b == body and j.a not in out:
                out[j.a] = out[body] @ inv(j.element(values[j.name], exp))
                todo.append(j.a)
    return out


def cycles(joints: list[J]) -> list[list[tuple[J, int]]]:
    """A cycle basis of the mechanism: each cycle a list of (joint, +1 if crossed a->b)."""
    H = nx.Graph()
    by = {j.name: j for j in joints}
    for j in joints:
        H.add_edge(("b", j.a), ("j", j.name))
        H.add_edge(("j", j.name), ("b", j.b))
    out = []
    for cyc in nx.cycle_basis(H):
        k = next(i for i, node in enumerate(cyc) if node[0] == "b")
        cyc = cyc[k:] + cyc[:k]
        steps = []
        for i in range(0, len(cyc), 2):
            body, joint, nxt = cyc[i][1], by[cyc[i + 1][1]], cyc[(i + 2) % len(cyc)][1]
            assert {body, nxt} == {joint.a, joint.b}
            steps.append((joint, 1 if joint.a == body else -1))
        out.append(steps)
    return out


def cycle_products(
    joints: list[J],
    values: Values,
    exp: Exp = expt,
    basis_cycles: list[list[tuple[J, int]]] | None = None,
) -> list[np.ndarray]:
    """The product of the joint displacements around each cycle (identity when it closes)."""
    out = []
    for steps in cycles(joints) if basis_cycles is None else basis_cycles:
        P = np.eye(4)
        for j, s in steps:
            M = j.element(values[j.name], exp)
            P = P @ (M if s > 0 else inv(M))
        out.append(P)
    return out


def closure_error(P: np.ndarray, L: float) -> float:
    """A length: |p| and L |R - I|."""
    return max(float(np.linalg.norm(P[:3, 3])), L * float(np.linalg.norm(P[:3, :3] - np.eye(3))))


def closure_residual(products: list[np.ndarray], L: float) -> np.ndarray:
    """The residual vector of the cycle products: (R - I) and p / L per cycle (dimensionless)."""
    if not products:
        return np.zeros(0)
    return np.concatenate([np.r_[(P[:3, :3] - np.eye(3)).ravel(), P[:3, 3] / L] for P in products])


def assert_closes(joints: list[J], values: Values, L: float, exp: Exp = expt) -> None:
    for P in cycle_products(joints, values, exp):
        err = closure_error(P, L)
        assert err <= 1e-10 * L, f"a loop does not close: error {err:.3g} (L = {L:.3g})"


def spatial_screws(
    joints: list[J],
    body_poses: Mapping[str, np.ndarray],
    values: Values,
    names: set[str] | None = None,
    exp: Exp = expt,
) -> np.ndarray:
    """The current spatial joint screws (columns, joints in list order, basis order; only the
    joints in ``names`` when given): each basis screw moved by its joint's ``a`` body; a U
    joint's second axis also by its first rotation."""
    cols = []
    for j in joints:
        if names is not None and j.name not in names:
            continue
        ga = body_poses[j.a]
        if j.type == "U":
            cols.append(adjoint(ga) @ j.basis[0])
            g1 = ga @ exp(values[j.name][0] * j.basis[0])
            cols.append(adjoint(g1) @ j.basis[1])
        else:
            cols.extend(adjoint(ga) @ s for s in j.basis)
    return np.array(cols).T


def track(
    joints: list[J],
    start: Values,
    target: Values,
    L: float,
    nsteps: int = 12,
    exp: Exp | None = None,
    iterations: int = 24,
    refresh: int = 4,
    rcond: float | None = None,
    halvings: int = 8,
) -> tuple[dict[str, np.ndarray] | None, float]:
    """Follow the given joints from ``start`` to ``target`` (straight line, ``nsteps`` steps),
    the others solved at each step by Gauss-Newton on the products around the cycles
    (finite-difference Jacobian refreshed every ``refresh`` iterations, least-squares steps
    with ``rcond``).

    Gauss-Newton has no predictor: a step several times longer than the distance to a fold of
    the given joints (or to a near-singular point, where two assembly modes pass close) can
    converge on the other mode.  A step is therefore taken only when two half steps end at
    the same point and it is reversible (Gauss-Newton from its end, with the given joints back
    at the step's start, returns to the point it left; from the other mode beside a fold, the
    way back lands on that mode too); else it is halved (at most ``halvings`` times below
    ``1 / nsteps``; the next steps grow back).

    Returns the end values and the smallest relative singular value of the closure Jacobian in
    the unknowns met on the way, start included (None when a step fails or jumps).
    """
    exp = exp or exp_rodrigues
    unknown = [j for j in joints if j.name not in target and KINDS[j.type]]
    sizes = [len(KINDS[j.type]) for j in unknown]
    x = np.concatenate([np.asarray(start[j.name], float) for j in unknown] or [np.zeros(0)])
    cyc = cycles(joints)
    # lengths count against L when the way back is compared with the point left
    unit_of = np.concatenate(
        [[L if k == "l" else 1.0 for k in KINDS[j.type]] for j in unknown] or [np.zeros(0)]
    )

    def values_at(x: np.ndarray, given: Values) -> dict[str, np.ndarray]:
        vals = dict(given)
        k = 0
        for j, s in zip(unknown, sizes, strict=True):
            vals[j.name] = x[k : k + s]
            k += s
        for j in joints:
            vals.setdefault(j.name, np.zeros(0))
        return vals

    def F(x: np.ndarray, given: Values) -> np.ndarray:
        return closure_residual(cycle_products(joints, values_at(x, given), exp, cyc), L)

    def jac(x: np.ndarray, given: Values) -> np.ndarray:
        f0 = F(x, given)
        h = 1e-7
        cols = []
        for i in range(len(x)):
            xp = x.copy()
            xp[i] += h
            cols.append((F(xp, given) - f0) / h)
        return np.stack(cols, axis=1)

    def given_at(t: float) -> dict[str, np.ndarray]:
        return {k: start[k] + t * (target[k] - start[k]) for k in target}

    def close(x: np.ndarray, given: Values) -> np.ndarray | None:
        for it in range(iterations):
            if it % refresh == 0:
                Jx = jac(x, given)
            f = F(x, given)
            if np.max(np.abs(f)) <= 1e-13:
                return x
            x = x + np.linalg.lstsq(Jx, -f, rcond=rcond)[0]
        return None

    # the start counts too: from a singular point several branches leave
    s = np.linalg.svd(jac(x, {k: start[k] for k in target}), compute_uv=False)
    worst = float(s[-1] / s[0])
    t, dt, shortest = 0.0, 1.0 / nsteps, 1.0 / nsteps / 2**halvings

    def same(a: np.ndarray | None, b: np.ndarray | None) -> bool:
        if a is None or b is None:
            return False
        return bool(np.max(np.abs(a - b) / unit_of, initial=0.0) <= 1e-6)

    while t < 1.0:
        t_next = min(1.0, t + dt)
        x_next = close(x, given_at(t_next))
        if x_next is not None and np.max(np.abs(x_next - x)) <= 0.5:
            # two half steps end at the same point, and the way back returns
            x_half = close(x, given_at((t + t_next) / 2))
            two = None if x_half is None else close(x_half, given_at(t_next))
            if same(two, x_next) and same(close(x_next, given_at(t)), x):
                s = np.linalg.svd(jac(x_next, given_at(t_next)), compute_uv=False)
                worst = min(worst, float(s[-1] / s[0]))
                x, t = x_next, t_next
                dt = min(2 * dt, 1.0 / nsteps)
                continue
        if dt / 2 < shortest:
            return None, 0.0  # no step short enough to vouch for the branch
        dt /= 2
    return values_at(x, target), worst


def joint_from_entry(entry: Mapping, num: Callable[[object], object], one: object = 1.0) -> J:
    """A reference joint from a mechanism file's joint entry (``name``, ``type``, ``between`` and
    its geometry), each number read by ``num`` (a float reader, or
    :func:`tests.reference.expressions.mp_num` with ``one = mpmath.mpf(1)``)."""
    prm: dict = {}
    for key, val in entry.items():
        if key in ("name", "type", "between"):
            continue
        if key == "axes":
            prm[key] = tuple(np.array([num(x) for x in a]) for a in val)
        elif key == "pitch":
            prm[key] = num(val)
        else:
            prm[key] = np.array([num(x) for x in val])
    a, b = entry["between"]
    return J(entry["name"], entry["type"], a, b, prm, one)


def characteristic_points(joints: Iterable[J]) -> list[np.ndarray]:
    """Each joint's point that the characteristic length is taken over: the axis point nearest
    the origin (the foot of the perpendicular) of R, H and C, the centre of S and U."""
    out = []
    for j in joints:
        if j.type in ("R", "H", "C"):
            u, p = unit(j.prm["axis"]), np.asarray(j.prm["point"])
            out.append(p - (u @ p) * u)
        elif j.type in ("S", "U"):
            out.append(np.asarray(j.prm["point"]))
    return out


def length_scale(joints: Sequence[J]) -> tuple[object, np.ndarray]:
    """The characteristic length L and the centroid c of the characteristic points: L is their
    RMS distance from c; if that is zero, |c|; if that is zero too, 1 (in the joints' type)."""
    one = joints[0].one if joints else 1.0
    pts = characteristic_points(joints)
    c = sum(pts) / len(pts) if pts else _eye(3, one)[0] * 0
    rms = sqrt(sum((p - c) @ (p - c) for p in pts) / len(pts)) if pts else one * 0
    if rms > 0:
        return rms, c
    norm = sqrt(c @ c)
    return (norm, c) if norm > 0 else (one, c)


def mismatch(g: np.ndarray, L: object, c: np.ndarray) -> object:
    """How far a displacement is from the identity, as a length: the larger of L max |R - I|
    and the distance it moves the centroid c."""
    E = np.array(g, copy=True)
    for i in range(4):
        E[i, i] = E[i, i] - 1
    rot = max(abs(E[i, k]) for i in range(3) for k in range(3))
    moved = E[:3, :3] @ c + E[:3, 3]
    return max(L * rot, sqrt(moved @ moved))


def joints_from_model(mech: object) -> list[J]:
    """Reference joints from a loaded mechanism's joint list (``name``, ``type``, ``between``,
    ``params``: duck-typed, read as floats)."""
    out = []
    for j in mech.joints:
        prm = {}
        for key, val in j.params.items():
            if key == "axes":
                prm[key] = tuple(np.array([float(x) for x in a]) for a in val)
            elif key == "pitch":
                prm[key] = float(val)
            else:
                prm[key] = np.array([float(x) for x in val])
        out.append(J(j.name, j.type, j.between[0], j.between[1], prm))
    return out


# ----------------------------------------------------------------------------- planar four-bar


def rot2(t: float) -> np.ndarray:
    return np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])


def cross2(u: np.ndarray, v: np.ndarray) -> float:
    return float(u[0] * v[1] - u[1] * v[0])


def fourbar_closed_form(
    A: np.ndarray, B: np.ndarray, C: np.ndarray, D: np.ndarray, theta: float
) -> tuple[tuple[float, float, float] | None, float]:
    """Crank angle theta -> (coupler angle, rocker angle, sin of the angle at C)
    on the assembly mode of the reference; or, where the loop cannot close,
    None and by how much it misses (a length)."""
    r1, r2 = np.linalg.norm(C - B), np.linalg.norm(C - D)
    side = np.sign(cross2(D - B, C - B))
    Bt = A + rot2(theta) @ (B - A)
    d = np.linalg.norm(D - Bt)
    if d >= r1 + r2 or d <= abs(r1 - r2):
        return None, max(d - r1 - r2, abs(r1 - r2) - d)
    a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    h = math.sqrt(max(r1 * r1 - a * a, 0.0))
    u = (D - Bt) / d
    n = np.array([-u[1], u[0]])
    Ct = Bt + a * u + side * h * n
    psi = math.atan2(cross2(C - B, Ct - Bt), float((C - B) @ (Ct - Bt)))
    phi = math.atan2(cross2(C - D, Ct - D), float((C - D) @ (Ct - D)))
    sin_c = abs(cross2(Ct - Bt, D - Ct)) / (r1 * r2)
    return (psi, phi, sin_c), 0.0
