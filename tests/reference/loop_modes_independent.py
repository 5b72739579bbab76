"""An independent solver of closed configurations (imports nothing from mechsing): the
closure of loops of revolute and prismatic joints written as 4x4 matrices (Rodrigues'
formula), every real solution for some joints' given values found by damped Newton
(Levenberg-Marquardt) from many random starts, and the distinct ones kept.

A joint is ``(kind, axis, point)`` in the ground frame at the reference configuration
(``kind`` ``"R"`` or ``"P"``); a loop a list of ``(joint index, sign)``: its closure is
``prod exp(sign q xi) = I``; an arm's chain closes on a target ``T`` instead.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np


def _exp(kind: str, axis: np.ndarray, point: np.ndarray, q: float) -> np.ndarray:
    """The displacement of a joint by q (rotation about its line, or slide along it)."""
    u = np.asarray(axis, float) / np.linalg.norm(axis)
    G = np.eye(4)
    if kind == "P":
        G[:3, 3] = q * u
        return G
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    R = np.eye(3) + np.sin(q) * K + (1 - np.cos(q)) * K @ K
    p = np.asarray(point, float)
    G[:3, :3] = R
    G[:3, 3] = p - R @ p
    return G


def closure_residual(
    joints: Sequence, loops: Sequence, q: np.ndarray, targets: Sequence | None = None
) -> np.ndarray:
    """The closure residuals of every loop (12 entries of ``prod - T`` each)."""
    out = []
    for k, loop in enumerate(loops):
        G = np.eye(4)
        for idx, sign in loop:
            kind, axis, point = joints[idx]
            G = G @ _exp(kind, axis, point, sign * q[idx])
        T = np.eye(4) if targets is None else targets[k]
        out.append((G - T)[:3, :].ravel())
    return np.concatenate(out)


def wrap_angles(kinds: Sequence[str], q: np.ndarray) -> np.ndarray:
    q = np.array(q, float)
    for i, k in enumerate(kinds):
        if k == "R":
            q[i] = (q[i] + np.pi) % (2 * np.pi) - np.pi
    return q


def solve_all(
    joints: Sequence,
    loops: Sequence,
    given: dict[int, float],
    targets: Sequence | None = None,
    starts: int = 3000,
    seed: int = 1,
    scale: float = 1.0,
) -> list[np.ndarray]:
    """Every distinct real solution (all joint values, angles in (-pi, pi]) damped Newton
    reaches from ``starts`` random starts (angles uniform, slides within ``scale``)."""
    rng = np.random.default_rng(seed)
    n = len(joints)
    kinds = [j[0] for j in joints]
    free = [i for i in range(n) if i not in given]
    found: list[np.ndarray] = []
    for _ in range(starts):
        q = np.zeros(n)
        for i, v in given.items():
            q[i] = v
        for i in free:
            q[i] = rng.uniform(-np.pi, np.pi) if kinds[i] == "R" else rng.uniform(-scale, scale)
        lam = 1e-3
        for _ in range(200):
            r = closure_residual(joints, loops, q, targets)
            if np.linalg.norm(r) < 1e-13:
                break
            J = np.empty((len(r), len(free)))
            for c, i in enumerate(free):
                dq = np.zeros(n)
                dq[i] = 1e-7
                J[:, c] = (closure_residual(joints, loops, q + dq, targets) - r) / 1e-7
            step = np.linalg.solve(J.T @ J + lam * np.eye(len(free)), -J.T @ r)
            trial = q.copy()
            trial[free] += step
            if np.linalg.norm(closure_residual(joints, loops, trial, targets)) < np.linalg.norm(r):
                q, lam = trial, max(lam / 3, 1e-12)
            else:
                lam *= 10
        if np.linalg.norm(closure_residual(joints, loops, q, targets)) > 1e-10:
            continue
        q = wrap_angles(kinds, q)
        if all(np.linalg.norm(wrap_angles(kinds, q - f)) > 1e-6 for f in found):
            found.append(q)
    return found
