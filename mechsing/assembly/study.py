"""Dual quaternions, the coordinates of D the assembly formulations share.

A displacement ``x -> R x + t`` is the dual quaternion ``X + eps Y`` with ``X`` the unit
quaternion of ``R`` and ``Y = t X / 2``; its eight Study coordinates are ``(X, Y)``, a
point of the Study quadric ``X.Y = 0``.  A quaternion is ``[w, x, y, z]``; a dual
quaternion the list of its eight coordinates.  Every function takes any numbers that add
and multiply (float, mpmath, sympy), so one formula serves the solver's polynomial text,
its refinement at 50 digits and its interval certificate.

The products and conjugates are :mod:`mechsing.lie`'s (:func:`~mechsing.lie.quat_multiply`,
:func:`~mechsing.lie.study_multiply`, :func:`~mechsing.lie.study_conjugate`).

Owns :func:`line`,
:func:`slide`, :func:`rotation_quaternion`, :func:`rotation` (a rotation matrix of mpmath
numbers, from an axis and an angle or from a rotation vector).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import mpmath

__all__ = [
    "line",
    "rotation",
    "rotation_quaternion",
    "slide",
]


def line(axis: Sequence[Any], point: Sequence[Any]) -> list[Any]:
    """The line through ``point`` along the unit ``axis``: ``w + eps (p x w)``; the
    rotation by ``q`` about it is ``cos(q/2) + sin(q/2) line``."""
    w, p = axis, point
    m = [p[1] * w[2] - p[2] * w[1], p[2] * w[0] - p[0] * w[2], p[0] * w[1] - p[1] * w[0]]
    return [0, *w, 0, *m]


def slide(axis: Sequence[Any]) -> list[Any]:
    """``eps u`` for the unit ``axis`` u: the translation by ``d`` along it is
    ``1 + (d/2) eps u``."""
    return [0, 0, 0, 0, 0, *axis]


def rotation_quaternion(R: Any) -> list[Any]:
    """The unit quaternion (either sign) of a rotation matrix (mpmath), from its largest
    diagonal combination (no cancellation near a half-turn)."""
    t = R[0, 0] + R[1, 1] + R[2, 2]
    cases = [
        t,
        R[0, 0] - R[1, 1] - R[2, 2],
        R[1, 1] - R[0, 0] - R[2, 2],
        R[2, 2] - R[0, 0] - R[1, 1],
    ]
    k = max(range(4), key=lambda i: cases[i])
    r = mpmath.sqrt(1 + cases[k])
    h = 1 / (2 * r)
    if k == 0:
        return [r / 2, (R[2, 1] - R[1, 2]) * h, (R[0, 2] - R[2, 0]) * h, (R[1, 0] - R[0, 1]) * h]
    if k == 1:
        return [(R[2, 1] - R[1, 2]) * h, r / 2, (R[0, 1] + R[1, 0]) * h, (R[0, 2] + R[2, 0]) * h]
    if k == 2:
        return [(R[0, 2] - R[2, 0]) * h, (R[0, 1] + R[1, 0]) * h, r / 2, (R[1, 2] + R[2, 1]) * h]
    return [(R[1, 0] - R[0, 1]) * h, (R[0, 2] + R[2, 0]) * h, (R[1, 2] + R[2, 1]) * h, r / 2]


def rotation(axis: Sequence[Any], q: Any | None = None) -> Any:
    """The rotation by ``q`` about the unit ``axis`` (Rodrigues, mpmath); without ``q``,
    ``axis`` is a rotation vector (its direction and length)."""
    if q is None:
        q = mpmath.sqrt(sum(x * x for x in axis))
        if q == 0:
            return mpmath.eye(3)
        axis = [x / q for x in axis]
    x, y, z = axis
    c, s, v = mpmath.cos(q), mpmath.sin(q), 1 - mpmath.cos(q)
    return mpmath.matrix(
        [
            [c + x * x * v, x * y * v - z * s, x * z * v + y * s],
            [y * x * v + z * s, c + y * y * v, y * z * v - x * s],
            [z * x * v - y * s, z * y * v + x * s, c + z * z * v],
        ]
    )
