"""An independent solver of a platform's poses (imports nothing from mechsing): the pose
as a rotation vector and a translation, some extra unknowns (a leg's joint angles), and a
residual the caller writes from the legs' geometry; every real solution damped Newton
(Levenberg-Marquardt, least squares: the residual may have more entries than unknowns)
reaches from many random starts, the distinct poses kept.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def rotation(axis: np.ndarray, angle: float | None = None) -> np.ndarray:
    """Rodrigues: the rotation by ``angle`` about the unit ``axis``; without an angle,
    ``axis`` is a rotation vector."""
    v = np.asarray(axis, float)
    if angle is None:
        angle = float(np.linalg.norm(v))
        if angle == 0.0:
            return np.eye(3)
        v = v / angle
    else:
        v = v / np.linalg.norm(v)
    K = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def platform_poses(
    residual: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray],
    extra: int = 0,
    starts: int = 400,
    seed: int = 1,
    scale: float = 3.0,
) -> list[tuple[np.ndarray, np.ndarray]]:
    """Every distinct real pose (R, t) with ``residual(R, t, extra) = 0`` that damped
    Newton reaches from ``starts`` random starts (rotation vectors in the ball of radius
    pi, translations and extras within ``scale``; the extras are angles)."""
    rng = np.random.default_rng(seed)
    n = 6 + extra

    def f(x: np.ndarray) -> np.ndarray:
        return residual(rotation(x[:3]), x[3:6], x[6:])

    found: list[tuple[np.ndarray, np.ndarray]] = []
    for _ in range(starts):
        x = np.concatenate(
            [
                rng.uniform(-2, 2, 3),
                rng.uniform(-scale, scale, 3),
                rng.uniform(-np.pi, np.pi, extra),
            ]
        )
        lam = 1e-3
        r = f(x)
        for _ in range(300):
            if np.linalg.norm(r) < 1e-13:
                break
            J = np.empty((len(r), n))
            for i in range(n):
                dx = np.zeros(n)
                dx[i] = 1e-7
                J[:, i] = (f(x + dx) - r) / 1e-7
            step = np.linalg.solve(J.T @ J + lam * np.eye(n), -J.T @ r)
            trial = x + step
            rt = f(trial)
            if np.linalg.norm(rt) < np.linalg.norm(r):
                x, r, lam = trial, rt, max(lam / 3, 1e-12)
            else:
                lam *= 10
                if lam > 1e8:
                    break
        if np.linalg.norm(r) > 1e-10:
            continue
        R, t = rotation(x[:3]), x[3:6]
        if all(np.linalg.norm(R - R2) + np.linalg.norm(t - t2) > 1e-6 for R2, t2 in found):
            found.append((R, t))
    return found
