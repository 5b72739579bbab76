"""An independent computation of a planar 3-RPR's cusps in a section of its joint space,
and of the loops around them (imports nothing from mechsing).

The section holds the first leg's length rho1; the platform is then placed by two numbers,
the first leg's direction phi (its platform pivot B1 = rho1 (cos phi, sin phi), the base
pivot A1 at the origin) and the platform's angle theta (B2 = B1 + d1 (cos theta, sin
theta), B3 = B1 + d3 (cos(theta + beta), sin(theta + beta)), beta the platform's angle at
B1).  The map F(phi, theta) = (rho2, rho3) = (|B2 - A2|, |B3 - A3|) takes a pose of the
section to the other two legs' lengths; its critical points (det DF = 0) are the
singularities of the section, their images the singular curves, and the cusps are the
critical points where the kernel of DF is tangent to the critical curve (the derivative of
det DF along the kernel vanishes): there three poses over one (rho2, rho3) coalesce
(Zein, Wenger & Chablat, Mech. Mach. Theory 43, 2008).

* :func:`cusps` solves {det DF = 0, d det DF . k = 0} by Newton (derivatives by central
  differences of the closed-form DF) from a grid of starts.
* :func:`poses_over` lists every pose of the section over (rho2, rho3): theta on a fine
  grid, phi from the two circle conditions.
* :func:`follow_rectangle` follows one pose around a rectangle of (rho2, rho3) by small
  steps of Newton on F, and says where it ends (or that DF became singular on the way).
"""

from __future__ import annotations

import math

import numpy as np

#: the design of Innocenti & Parenti-Castelli (1998), as Zein, Wenger & Chablat (2008)
#: give it: base pivots, platform sides d1 = |B1 B2|, d2 = |B2 B3|, d3 = |B3 B1|
A1 = np.array([0.0, 0.0])
A2 = np.array([15.91, 0.0])
A3 = np.array([0.0, 10.0])
D1, D2, D3 = 17.04, 16.54, 20.84
BETA = math.acos((D1**2 + D3**2 - D2**2) / (2 * D1 * D3))


def pivots(rho1: float, phi: float, theta: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The platform pivots B1, B2, B3 of the pose (phi, theta) of the section rho1."""
    b1 = rho1 * np.array([math.cos(phi), math.sin(phi)])
    b2 = b1 + D1 * np.array([math.cos(theta), math.sin(theta)])
    b3 = b1 + D3 * np.array([math.cos(theta + BETA), math.sin(theta + BETA)])
    return b1, b2, b3


def lengths(rho1: float, x: np.ndarray) -> np.ndarray:
    """F(phi, theta) = (rho2, rho3)."""
    _, b2, b3 = pivots(rho1, x[0], x[1])
    return np.array([np.linalg.norm(b2 - A2), np.linalg.norm(b3 - A3)])


def jacobian(rho1: float, x: np.ndarray) -> np.ndarray:
    """DF at (phi, theta), in closed form."""
    phi, theta = x
    _, b2, b3 = pivots(rho1, phi, theta)
    db1 = rho1 * np.array([-math.sin(phi), math.cos(phi)])
    dth2 = D1 * np.array([-math.sin(theta), math.cos(theta)])
    dth3 = D3 * np.array([-math.sin(theta + BETA), math.cos(theta + BETA)])
    u2 = (b2 - A2) / np.linalg.norm(b2 - A2)
    u3 = (b3 - A3) / np.linalg.norm(b3 - A3)
    return np.array([[u2 @ db1, u2 @ dth2], [u3 @ db1, u3 @ dth3]])


def _det(rho1: float, x: np.ndarray) -> float:
    return float(np.linalg.det(jacobian(rho1, x)))


def _grad(f, x: np.ndarray, h: float = 1e-6) -> np.ndarray:
    return np.array([(f(x + h * e) - f(x - h * e)) / (2 * h) for e in np.eye(2)])


def _cusp_equations(rho1: float, x: np.ndarray) -> np.ndarray:
    J = jacobian(rho1, x)
    # the kernel of a 2x2 matrix of rank 1: orthogonal to its larger row
    row = J[0] if np.linalg.norm(J[0]) >= np.linalg.norm(J[1]) else J[1]
    k = np.array([-row[1], row[0]]) / np.linalg.norm(row)
    return np.array([_det(rho1, x), _grad(lambda y: _det(rho1, y), x) @ k])


def cusps(rho1: float, starts: int = 48) -> list[tuple[np.ndarray, np.ndarray]]:
    """The cusps of the section rho1: each (pose (phi, theta), image (rho2, rho3)), found
    by Newton from a grid of starts, duplicates removed."""
    found: list[tuple[np.ndarray, np.ndarray]] = []
    grid = np.linspace(-math.pi, math.pi, starts, endpoint=False)
    for p0 in grid:
        for t0 in grid:
            x = np.array([p0, t0])
            for _ in range(60):
                g = _cusp_equations(rho1, x)
                if not np.all(np.isfinite(g)):
                    break
                G = np.array(
                    [
                        (_cusp_equations(rho1, x + 1e-7 * e) - _cusp_equations(rho1, x - 1e-7 * e))
                        / 2e-7
                        for e in np.eye(2)
                    ]
                ).T
                try:
                    dx = np.linalg.solve(G, -g)
                except np.linalg.LinAlgError:
                    break
                x = x + dx
                if np.linalg.norm(dx) < 1e-13:
                    break
            if not np.all(np.isfinite(x)) or np.linalg.norm(_cusp_equations(rho1, x)) > 1e-9:
                continue
            x = (x + math.pi) % (2 * math.pi) - math.pi
            if all(np.linalg.norm(_wrap(x - y)) > 1e-6 for y, _ in found):
                found.append((x, lengths(rho1, x)))
    return found


def _wrap(d: np.ndarray) -> np.ndarray:
    return (d + math.pi) % (2 * math.pi) - math.pi


def poses_over(rho1: float, rho2: float, rho3: float, samples: int = 200_000) -> list[np.ndarray]:
    """Every pose (phi, theta) of the section over (rho2, rho3): for theta on a fine grid,
    B1 lies on the circle rho1 about A1 and on the circle rho2 about A2 - d1 (cos theta,
    sin theta); the third leg's length is then a function of theta whose roots (sign
    changes, refined by Newton on F) are the poses."""
    out: list[np.ndarray] = []
    for branch in (1.0, -1.0):
        ths = np.linspace(-math.pi, math.pi, samples + 1)
        c = A2[None, :] - D1 * np.stack([np.cos(ths), np.sin(ths)], axis=1)
        d = np.linalg.norm(c, axis=1)
        a = (rho1**2 - rho2**2 + d**2) / (2 * d)
        h2 = rho1**2 - a**2
        ok = h2 >= 0
        e = c / d[:, None]
        n = np.stack([-e[:, 1], e[:, 0]], axis=1)
        b1 = a[:, None] * e + branch * np.sqrt(np.where(ok, h2, 0))[:, None] * n
        b3 = b1 + D3 * np.stack([np.cos(ths + BETA), np.sin(ths + BETA)], axis=1)
        f = np.where(ok, np.linalg.norm(b3 - A3, axis=1) - rho3, np.nan)
        for k in np.nonzero((np.sign(f[1:]) != np.sign(f[:-1])) & ok[1:] & ok[:-1])[0]:
            x = np.array([math.atan2(b1[k, 1], b1[k, 0]), ths[k]])
            x = _newton(rho1, x, np.array([rho2, rho3]))
            if x is not None and all(np.linalg.norm(_wrap(x - y)) > 1e-7 for y in out):
                out.append(x)
    return out


def _newton(rho1: float, x: np.ndarray, target: np.ndarray) -> np.ndarray | None:
    for _ in range(50):
        r = lengths(rho1, x) - target
        if np.linalg.norm(r) < 1e-13:
            return _wrap(x)
        try:
            x = x - np.linalg.solve(jacobian(rho1, x), r)
        except np.linalg.LinAlgError:
            return None
    return _wrap(x) if np.linalg.norm(lengths(rho1, x) - target) < 1e-10 else None


def follow_rectangle(
    rho1: float, x0: np.ndarray, corners: list[tuple[float, float]], step: float = 1e-3
) -> np.ndarray | None:
    """Follow the pose x0 (over the first corner) around the polygon of ``corners``
    (closed back to the first) by steps of ``step`` in (rho2, rho3), Newton on F at each;
    the pose it comes back with, or None where Newton fails or DF is nearly singular
    (a fold of the section met on the way)."""
    x = np.array(x0, dtype=float)
    pts = [*corners, corners[0]]
    for p, q in zip(pts[:-1], pts[1:], strict=True):
        p, q = np.asarray(p, float), np.asarray(q, float)
        n = max(1, int(math.ceil(np.linalg.norm(q - p) / step)))
        for s in range(1, n + 1):
            t = p + (q - p) * s / n
            y = _newton(rho1, x, t)
            if y is None or np.linalg.norm(_wrap(y - x)) > 50 * step:
                return None
            if abs(np.linalg.det(jacobian(rho1, y))) < 1e-6:
                return None
            x = y
    return x
