"""Inverse kinematics of six-joint revolute arms, independently of mechsing.

Imports nothing from mechsing: numpy, and the project's numpy-only references
(:mod:`tests.reference.dh` for the UR5's DH table and product, :mod:`tests.reference.se3` for
twists and their exponential).

* :func:`ur5_ik`: the closed-form (geometric) inverse kinematics of the UR5 from its standard
  DH table, ``T_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)``; up to 8 real solutions.
* :func:`poe`: the forward kinematics of a revolute chain as a product of exponentials of its
  joints' twists at the reference configuration (mechsing's joint values: all 0 there), on a
  batch of joint vectors.
* :func:`numeric_ik`: every solution a batch of damped Newton (Levenberg-Marquardt) runs from
  random starts reaches, distinct modulo 2 pi: the check for an arm without a closed form.

Frames: a DH table's joint values are its angles theta_i and its forward kinematics ``FK``
gives frame 6 in frame 0; mechsing's output pose at joint values q is the displacement of the
output body from its reference pose, ``FK(q) FK(0)^-1`` (see tests/test_modes_serial.py, which
checks this mapping on the UR5 file first).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from tests.reference.dh import UR5, dh_product
from tests.reference.se3 import revolute

TWO_PI = 2 * math.pi


def wrap(q: np.ndarray) -> np.ndarray:
    """Angles brought to (-pi, pi]."""
    w = np.mod(np.asarray(q, dtype=float) + math.pi, TWO_PI) - math.pi
    return np.where(w == -math.pi, math.pi, w)


def angle_gap(q1: Sequence[float], q2: Sequence[float]) -> float:
    """The largest joint difference of two joint vectors, modulo 2 pi."""
    return float(np.max(np.abs(wrap(np.subtract(q1, q2)))))


# ---------------------------------------------------------------- the UR5 in closed form


def ur5_ik(T: np.ndarray, dh: list = UR5) -> list[np.ndarray]:
    """Every real joint vector (theta_1..theta_6 in (-pi, pi]) whose DH tool frame is ``T``
    (4 x 4, frame 6 in frame 0) for a UR-type table: a_1 = a_4 = a_5 = a_6 = 0,
    d_2 = d_3 = 0, alpha = (pi/2, 0, 0, pi/2, -pi/2, 0).  Up to 8; fewer when the wrist centre
    is out of reach or a branch is singular (sin theta_5 = 0: theta_6 is then not determined
    and the pose is skipped, as the closed form has no single answer).

    Derivation (axes 2, 3, 4 are parallel to z_1):
    * the origin p5 of frame 5 is ``p6 - d6 z6``; every offset from frame 1 to frame 5 along
      z_1 = (sin t1, -cos t1, 0) is d4, so ``p5x sin t1 - p5y cos t1 = d4``: two theta_1;
    * z_1 is y of frame 4, and z_6 = z_5 = R_4 (-sin t5, cos t5, 0), so
      ``z6 . z1 = cos t5``: two theta_5 (+-);
    * z_1 in frame 6 is (sin t5 cos t6, -sin t5 sin t6, cos t5): theta_6;
    * frame 4 in frame 1 is Rz(t2) Tx(a2) Rz(t3) Tx(a3) Rz(t4) Tz(d4) Rx(pi/2): its origin
      (x, y) = (a2 c2 + a3 c23, a2 s2 + a3 s23) is a planar two-link arm (theta_3 +-, then
      theta_2), and its x axis makes the angle t2 + t3 + t4 with x_1 (theta_4).
    """
    d1, a2, a3 = dh[0][1], dh[1][2], dh[2][2]
    d4, d5, d6 = dh[3][1], dh[4][1], dh[5][1]
    z6, p6 = T[:3, 2], T[:3, 3]
    p5 = p6 - d6 * z6
    r = math.hypot(p5[0], p5[1])
    if r < abs(d4):
        return []
    phi = math.atan2(p5[1], p5[0])
    out: list[np.ndarray] = []
    for t1 in (phi + math.asin(d4 / r), phi + math.pi - math.asin(d4 / r)):
        z1 = np.array([math.sin(t1), -math.cos(t1), 0.0])
        c5 = float(np.clip(z6 @ z1, -1.0, 1.0))
        for t5 in (math.acos(c5), -math.acos(c5)):
            s5 = math.sin(t5)
            if abs(s5) < 1e-12:
                continue
            t6 = math.atan2(-(z1 @ T[:3, 1]) / s5, (z1 @ T[:3, 0]) / s5)
            T01 = dh_product([(0.0, d1, 0.0, math.pi / 2)], np.array([t1]))
            T46 = dh_product(
                [(0.0, d5, 0.0, -math.pi / 2), (0.0, d6, 0.0, 0.0)], np.array([t5, t6])
            )
            T14 = np.linalg.inv(T01) @ T @ np.linalg.inv(T46)
            x, y = T14[0, 3], T14[1, 3]
            c3 = (x * x + y * y - a2 * a2 - a3 * a3) / (2 * a2 * a3)
            if abs(c3) > 1:
                continue
            t234 = math.atan2(T14[1, 0], T14[0, 0])
            for t3 in (math.acos(c3), -math.acos(c3)):
                t2 = math.atan2(y, x) - math.atan2(a3 * math.sin(t3), a2 + a3 * math.cos(t3))
                t4 = t234 - t2 - t3
                out.append(wrap(np.array([t1, t2, t3, t4, t5, t6])))
    return out


# ---------------------------------------------------------------- product of exponentials


def _rodrigues(w: np.ndarray, v: np.ndarray, q: np.ndarray) -> np.ndarray:
    """exp(q (w, v)) for a unit w, on a batch of angles q (N,): (N, 4, 4)."""
    n = q.shape[0]
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    s, c = np.sin(q)[:, None, None], np.cos(q)[:, None, None]
    R = np.eye(3) + s * W + (1 - c) * (W @ W)
    # translation of a rotation about the line (w, v = p x w): (I - R) (w x v)
    g = np.zeros((n, 4, 4))
    g[:, :3, :3] = R
    g[:, :3, 3] = (np.eye(3) - R) @ np.cross(w, v)
    g[:, 3, 3] = 1.0
    return g


def poe(axes: Sequence, points: Sequence) -> Callable[[np.ndarray], np.ndarray]:
    """The forward kinematics of a chain of revolute joints, each given by its axis and a point
    on it at the reference configuration (a mechanism file's ``axis`` and ``point``): a function
    of joint values Q (N, 6) giving the output's displacement from its reference pose,
    ``exp(q1 xi1) ... exp(q6 xi6)`` (N, 4, 4)."""
    twists = [
        revolute(np.asarray(u, float), np.asarray(p, float))
        for u, p in zip(axes, points, strict=True)
    ]

    def fk(Q: np.ndarray) -> np.ndarray:
        Q = np.atleast_2d(np.asarray(Q, dtype=float))
        g = np.broadcast_to(np.eye(4), (Q.shape[0], 4, 4)).copy()
        for i, xi in enumerate(twists):
            g = g @ _rodrigues(xi[:3], xi[3:], Q[:, i])
        return g

    return fk


# ---------------------------------------------------------------- numeric inverse kinematics


def _residual(G: np.ndarray, T: np.ndarray, L: float) -> np.ndarray:
    """(N, 12): the rotation's difference and the translation's over L."""
    dR = (G[:, :3, :3] - T[:3, :3]).reshape(-1, 9)
    dp = (G[:, :3, 3] - T[:3, 3]) / L
    return np.concatenate([dR, dp], axis=1)


def numeric_ik(
    fk: Callable[[np.ndarray], np.ndarray],
    T: np.ndarray,
    starts: int = 2000,
    L: float = 1.0,
    seed: int = 0,
    iterations: int = 200,
    tol: float = 1e-13,
    distinct: float = 1e-6,
) -> list[np.ndarray]:
    """Every joint vector (in (-pi, pi]) that Levenberg-Marquardt reaches from ``starts``
    uniformly random starts in [-pi, pi]^6 with ``fk(Q) == T`` to ``tol`` (the rotation's
    entries, the translation over L), distinct modulo 2 pi by more than ``distinct`` rad;
    sorted.  ``fk`` maps a batch of joint vectors (N, 6) to poses (N, 4, 4).  The Jacobian is
    a central difference (step 1e-7): Newton with it still converges to the root, only more
    slowly in its last digits."""
    rng = np.random.default_rng(seed)
    Q = rng.uniform(-math.pi, math.pi, size=(starts, 6))
    lam = np.full(starts, 1e-3)
    r = _residual(fk(Q), T, L)
    cost = np.einsum("ij,ij->i", r, r)
    h = 1e-7
    eye = np.eye(6)
    for _ in range(iterations):
        J = np.empty((starts, 12, 6))
        for k in range(6):
            step = h * eye[k]
            J[:, :, k] = (_residual(fk(Q + step), T, L) - _residual(fk(Q - step), T, L)) / (2 * h)
        JtJ = np.einsum("nik,nil->nkl", J, J)
        g = np.einsum("nik,ni->nk", J, r)
        A = JtJ + lam[:, None, None] * (
            np.diagonal(JtJ, axis1=1, axis2=2)[:, :, None] * eye + 1e-12 * eye
        )
        dq = np.linalg.solve(A, -g[:, :, None])[:, :, 0]
        Qn = Q + dq
        rn = _residual(fk(Qn), T, L)
        cn = np.einsum("ij,ij->i", rn, rn)
        better = cn < cost
        Q[better], r[better], cost[better] = Qn[better], rn[better], cn[better]
        lam = np.where(better, np.maximum(lam / 3, 1e-15), np.minimum(lam * 4, 1e8))
        if np.all((cost < tol * tol) | (lam >= 1e8)):
            break
    found: list[np.ndarray] = []
    for q in wrap(Q[cost < tol * tol]):
        if all(angle_gap(q, f) > distinct for f in found):
            found.append(q)
    return sorted(found, key=lambda q: tuple(q))


def same_sets(a: Sequence[Sequence[float]], b: Sequence[Sequence[float]], tol: float) -> bool:
    """Whether two lists of joint vectors are the same set modulo 2 pi (each of a matches one
    of b within ``tol`` rad in every joint, and the counts agree)."""
    if len(a) != len(b):
        return False
    left = list(b)
    for q in a:
        hit = [k for k, p in enumerate(left) if angle_gap(q, p) <= tol]
        if len(hit) != 1:
            return False
        left.pop(hit[0])
    return True


def rotation_vector(R: np.ndarray) -> np.ndarray:
    """The rotation vector (axis times angle, angle in [0, pi)) of a rotation matrix."""
    c = (np.trace(R) - 1) / 2
    angle = math.acos(max(-1.0, min(1.0, c)))
    v = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    if angle < 1e-12:
        return 0.5 * v
    if math.pi - angle < 1e-6:
        raise ValueError("rotation by (nearly) pi: choose another pose")
    return angle / (2 * math.sin(angle)) * v
