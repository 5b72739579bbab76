"""An independent solver of the assembly modes the tests check (imports nothing from
mechsing): closed forms and a one-variable scan, written from the geometry alone.

* :func:`rpr_poses`: the planar 3-RPR's forward kinematics (Gosselin, Sefrioui & Richard
  1992): for a platform angle theta, two leg equations minus the first are linear in the
  platform's position (x, y); Cramer's rule gives it, and the first leg's equation
  becomes one function of theta, whose sign changes on a fine grid, refined by
  bisection, are the real solutions.
* :func:`circle_points`: the two intersections of two circles (a four-bar's coupler
  point, between the crank's end and the rocker's pivot).
"""

from __future__ import annotations

import numpy as np


def _rot(theta: float) -> np.ndarray:
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, -s], [s, c]])


def _position(
    theta: float, A: np.ndarray, b: np.ndarray, L: np.ndarray
) -> tuple[np.ndarray, float]:
    """(x, y) from legs 2 and 3 minus leg 1 at angle theta, and the determinant."""
    w = [_rot(theta) @ b[i] - A[i] for i in range(3)]
    M = np.array([2 * (w[1] - w[0]), 2 * (w[2] - w[0])])
    rhs = -np.array(
        [
            w[1] @ w[1] - L[1] ** 2 - w[0] @ w[0] + L[0] ** 2,
            w[2] @ w[2] - L[2] ** 2 - w[0] @ w[0] + L[0] ** 2,
        ]
    )
    det = float(np.linalg.det(M))
    return np.linalg.solve(M, rhs), det


def _f(theta: float, A: np.ndarray, b: np.ndarray, L: np.ndarray) -> float:
    p, det = _position(theta, A, b, L)
    w0 = _rot(theta) @ b[0] - A[0]
    return float(((p + w0) @ (p + w0) - L[0] ** 2) * det * det)


def rpr_poses(A: list, b: list, L: list, samples: int = 400_000) -> list[tuple[float, np.ndarray]]:
    """Every real pose (theta, position) of a planar 3-RPR with base pivots ``A``,
    platform pivots ``b`` (platform frame) and leg lengths ``L``."""
    A, b, L = np.asarray(A, float), np.asarray(b, float), np.asarray(L, float)
    grid = np.linspace(-np.pi, np.pi, samples + 1)
    values = np.array([_f(t, A, b, L) for t in grid])
    out = []
    for k in np.nonzero(np.sign(values[1:]) != np.sign(values[:-1]))[0]:
        lo, hi = grid[k], grid[k + 1]
        flo = values[k]
        for _ in range(60):
            mid = (lo + hi) / 2
            fm = _f(mid, A, b, L)
            if np.sign(fm) == np.sign(flo):
                lo, flo = mid, fm
            else:
                hi = mid
        theta = (lo + hi) / 2
        out.append((theta, _position(theta, A, b, L)[0]))
    return out


def circle_points(c1: np.ndarray, r1: float, c2: np.ndarray, r2: float) -> list[np.ndarray]:
    """The real intersections of the circles (c1, r1) and (c2, r2)."""
    c1, c2 = np.asarray(c1, float), np.asarray(c2, float)
    d = float(np.linalg.norm(c2 - c1))
    a = (r1**2 - r2**2 + d**2) / (2 * d)
    h2 = r1**2 - a**2
    if h2 < 0:
        return []
    e = (c2 - c1) / d
    n = np.array([-e[1], e[0]])
    base = c1 + a * e
    return [base + np.sqrt(h2) * n, base - np.sqrt(h2) * n]


def rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' rotation about the unit ``axis``."""
    x, y, z = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def ups_platform_pose(
    u_axes: tuple,
    slide_axis: np.ndarray,
    slide: float,
    s_vector: np.ndarray,
    base: np.ndarray,
    platform_ref: np.ndarray,
    u_angles: tuple,
) -> tuple[np.ndarray, np.ndarray]:
    """The platform's pose (R, t) that one U-P-S leg's joint values give (spatial product
    of exponentials, every axis at the reference in the ground frame): the U turns about
    its first then its second axis through the base point, the P slides along its axis,
    the S turns by its rotation vector about the platform point."""
    Rc = rotation(u_axes[0], u_angles[0]) @ rotation(u_axes[1], u_angles[1])
    angle = float(np.linalg.norm(s_vector))
    Rs = np.eye(3) if angle == 0 else rotation(s_vector / angle, angle)
    R = Rc @ Rs
    # the platform point: the U about base, then the slide
    point_now = base + Rc @ (
        platform_ref - base + slide * np.asarray(slide_axis) / np.linalg.norm(slide_axis)
    )
    return R, point_now - R @ platform_ref


def leg1_platform_pose(file_joints: dict, mode_joints: dict) -> tuple[np.ndarray, np.ndarray]:
    """A six-leg platform mode's pose (R, t) from leg 1's joint values alone: the file's
    joints by name (``U1``, ``P1``, ``S1`` as written in the mechanism file) and the mode's
    joint values by name, through :func:`ups_platform_pose`."""
    return ups_platform_pose(
        file_joints["U1"]["axes"],
        np.array(file_joints["P1"]["axis"], float),
        mode_joints["P1"][0],
        np.array(mode_joints["S1"]),
        np.array(file_joints["U1"]["point"], float),
        np.array(file_joints["S1"]["point"], float),
        tuple(mode_joints["U1"]),
    )
