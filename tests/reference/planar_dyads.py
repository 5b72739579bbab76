"""Closed forms for planar linkages built of dyads (imports nothing from mechsing): each
unknown joint point is the intersection of two circles about points already placed, so
every assembly mode is one choice of intersection per dyad.

* :func:`turn`: the rotation angle that takes a body's reference vector to its current one.
* :func:`place`: a point of a body rotated by an angle about a placed point.
"""

from __future__ import annotations

import numpy as np


def turn(ref: np.ndarray, now: np.ndarray) -> float:
    """The angle of the rotation taking the vector ``ref`` to ``now`` (same length)."""
    return float(np.arctan2(now[1], now[0]) - np.arctan2(ref[1], ref[0]))


def place(
    pivot_ref: np.ndarray, pivot_now: np.ndarray, angle: float, p_ref: np.ndarray
) -> np.ndarray:
    """Where a body's point ``p_ref`` is when the body has turned by ``angle`` and its
    point ``pivot_ref`` is at ``pivot_now``."""
    c, s = np.cos(angle), np.sin(angle)
    d = np.asarray(p_ref, float) - np.asarray(pivot_ref, float)
    return np.asarray(pivot_now, float) + np.array([c * d[0] - s * d[1], s * d[0] + c * d[1]])


def wrap(a: float) -> float:
    """An angle in (-pi, pi]."""
    return float((a + np.pi) % (2 * np.pi) - np.pi)
