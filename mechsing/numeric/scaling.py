"""The commensurate metric: the characteristic length L and centroid of a mechanism's
axes, and the map that makes screws commensurate before a rank decision.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.numeric.backend import to_float


def characteristic_length(points: Any, override: float | None = None) -> tuple[float, np.ndarray]:
    """Characteristic length L and centroid c of the joints' axis points.

    Parameters
    ----------
    points : array_like, shape (n, 3)
        For each joint, the point of its axis nearest the origin (foot of the
        perpendicular for R, H, C; centre for S and U).  Joints without a point
        (P, T2, T3, G, Y, X, D) are simply not listed.
    override : float, optional
        The file's ``characteristic_length``.

    Returns
    -------
    L : float
        RMS distance of the points from their centroid; ``|c|`` if that is 0;
        1 if that is 0 too.
    c : ndarray, shape (3,)
        The centroid (zeros when there are no points).
    """
    pts = np.asarray(to_float(points), dtype=float).reshape(-1, 3)
    c = pts.mean(axis=0) if len(pts) else np.zeros(3)
    if override is not None:
        return float(override), c
    rms = float(np.sqrt(np.mean(np.sum((pts - c) ** 2, axis=1)))) if len(pts) else 0.0
    if rms > 0:
        return rms, c
    nc = float(np.linalg.norm(c))
    if nc > 0:
        return nc, c
    return 1.0, c


def scale_screws(
    S: np.ndarray, length_scale: Any, centroid: Any = None, length_columns: Any = None
) -> np.ndarray:
    """Make screws commensurate before a rank decision.

    Moves each screw (a *column* of ``S``, layout (omega, v)) to the centroid
    c (``v -> v - c x omega``, i.e. Ad of the translation by -c), divides the
    v rows by L and multiplies the columns flagged in ``length_columns`` (joint
    coordinates that are lengths: P, slides, translations) by L.

    Works on every backend (plain numpy arithmetic).
    """
    S = np.array(S, copy=True)
    if centroid is not None:
        c = np.asarray(centroid)
        w = S[..., 0:3, :]
        # v - c x w, columnwise
        cx = np.stack(
            [
                w[..., 2, :] * c[1] - w[..., 1, :] * c[2],
                w[..., 0, :] * c[2] - w[..., 2, :] * c[0],
                w[..., 1, :] * c[0] - w[..., 0, :] * c[1],
            ],
            axis=-2,
        )
        S[..., 3:6, :] = S[..., 3:6, :] - cx
    S[..., 3:6, :] = S[..., 3:6, :] / length_scale
    if length_columns is not None:
        mask = np.asarray(length_columns, dtype=bool)
        S[..., :, mask] = S[..., :, mask] * length_scale
    return S
