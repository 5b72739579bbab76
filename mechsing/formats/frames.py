"""Rigid frames of robot descriptions: rotations from the ways URDF and MJCF write them.

Owns the float homogeneous-transform arithmetic of the importers.  A frame is
a 4x4 numpy array ``T`` (rotation ``T[:3, :3]``, origin ``T[:3, 3]``) giving a
child frame in its parent's coordinates; angles are in radians here (the
callers convert a file's degrees first).  Conventions, as the formats define
them: URDF ``rpy`` is ``Rz(yaw) Ry(pitch) Rx(roll)`` (fixed axes X, then Y,
then Z); MJCF ``quat`` is ``w x y z``, ``axisangle`` is an axis and an angle,
``euler`` follows the compiler's ``eulerseq`` (a lower-case letter turns about
the moving axis, an upper-case one about the fixed axis), ``xyaxes`` gives the
frame's x and y axes, ``zaxis`` the frame's z axis reached by the smallest
rotation from z.
"""

from __future__ import annotations

import numpy as np

from mechsing.numeric import NEAR_ZERO_VECTOR
from mechsing.numeric.numbers import safe_norm, unit_vector

__all__ = [
    "axis_angle",
    "euler",
    "frame",
    "quaternion",
    "rpy",
    "xyaxes",
    "zaxis",
]


def frame(rotation: np.ndarray | None = None, origin: np.ndarray | None = None) -> np.ndarray:
    """The 4x4 transform of a rotation and an origin (identity for what is omitted)."""
    t = np.eye(4)
    if rotation is not None:
        t[:3, :3] = rotation
    if origin is not None:
        t[:3, 3] = origin
    return t


def axis_angle(axis: np.ndarray, angle: float) -> np.ndarray:
    """The rotation by ``angle`` (rad) about the unit direction of ``axis`` (Rodrigues)."""
    a = unit_vector(axis)
    k = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


_UNIT = {"x": np.array([1.0, 0, 0]), "y": np.array([0, 1.0, 0]), "z": np.array([0, 0, 1.0])}


def rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """URDF's ``rpy``: ``Rz(yaw) Ry(pitch) Rx(roll)``."""
    return (
        axis_angle(_UNIT["z"], yaw) @ axis_angle(_UNIT["y"], pitch) @ axis_angle(_UNIT["x"], roll)
    )


def quaternion(w: float, x: float, y: float, z: float) -> np.ndarray:
    """The rotation of the quaternion ``w x y z`` (normalised first)."""
    w, x, y, z = unit_vector([w, x, y, z])
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def euler(angles: tuple[float, float, float], seq: str) -> np.ndarray:
    """MJCF's ``euler`` with the compiler's ``eulerseq``: each lower-case letter turns about
    the frame's current (moving) axis, each upper-case letter about the fixed axis."""
    r = np.eye(3)
    for letter, angle in zip(seq, angles, strict=True):
        step = axis_angle(_UNIT[letter.lower()], angle)
        r = r @ step if letter.islower() else step @ r
    return r


def xyaxes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """MJCF's ``xyaxes``: x normalised, y made orthogonal to it, z = x cross y."""
    x = unit_vector(x)
    y = unit_vector(y)
    y = y - (y @ x) * x
    if not safe_norm(y) > NEAR_ZERO_VECTOR:
        raise ValueError("xyaxes: the two directions are parallel")
    y = unit_vector(y)
    return np.column_stack([x, y, np.cross(x, y)])


def zaxis(z: np.ndarray) -> np.ndarray:
    """MJCF's ``zaxis``: the smallest rotation taking z to the given direction."""
    z = unit_vector(z)
    e = _UNIT["z"]
    c = float(e @ z)
    v = np.cross(e, z)
    s = float(np.linalg.norm(v))
    if s < 1e-15:
        return np.eye(3) if c > 0 else axis_angle(_UNIT["x"], np.pi)
    return axis_angle(v, float(np.arctan2(s, c)))
