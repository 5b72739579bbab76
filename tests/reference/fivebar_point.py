"""A five-bar's input torques for a point mass moved along a line, by statics of two-force
members (numpy; imports nothing from mechsing).

The planar five-bar of examples/five_bar.yaml: ground pivots A1 = (-3/2, 0) and
A2 = (3/2, 0), proximal links of length 2, distal links of length 5/2 meeting at P.  The
only mass is a point mass m at P (on the first distal link, at the joint P), the links
are massless and there is no gravity in the plane.  The point P moves on the vertical
line x = 0, its height following the quintic rest-to-rest law from y0 to y1 over T
seconds: y(t) = y0 + (y1 - y0) h(t/T), h(x) = 10 x^3 - 15 x^4 + 6 x^5.

Statics of the massless links: the distal links carry forces along themselves only
(their joint at P bears the mass), so the force on the mass F = m a_P = f1 e1 + f2 e2
with e_i = (P - B_i)/|P - B_i|; the proximal link i is balanced by its motor's torque
tau_i = ((B_i - A_i) x f_i e_i)_z.  When the distal links line up (the Type II
singularity, at y = sqrt(3) with B1 = (-5/2, sqrt 3) and B2 = (5/2, sqrt 3)) the 2x2
solve is singular: the torques stay bounded only when F has no component across the
line, here m y'' = 0 at the crossing (the crossing condition); otherwise they grow as
1/|y - sqrt 3|.
"""

from __future__ import annotations

import numpy as np

from tests.reference.timelaw import law

__all__ = ["A", "DISTAL", "PROXIMAL", "elbows", "torques"]

A = (np.array([-1.5, 0.0]), np.array([1.5, 0.0]))
PROXIMAL = 2.0
DISTAL = 2.5


def elbows(P: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """B1 and B2 for the point P: each on its circles' intersection farther from x = 0."""
    out = []
    for a, side in zip(A, (-1.0, 1.0), strict=True):
        d = P - a
        L = float(np.hypot(*d))
        along = (PROXIMAL**2 - DISTAL**2 + L**2) / (2 * L)
        h = np.sqrt(PROXIMAL**2 - along**2)
        base = a + along * d / L
        perp = np.array([-d[1], d[0]]) / L
        cands = [base + h * perp, base - h * perp]
        out.append(max(cands, key=lambda b: side * b[0]))
    return out[0], out[1]


def torques(y: float, m: float, y0: float, y1: float, T: float) -> np.ndarray:
    """(tau1, tau2), N m, at the height y of the motion from y0 to y1 over T s."""
    _, _, ydd = law(y, y0, y1, T)
    P = np.array([0.0, y])
    B = elbows(P)
    e = [(P - b) / np.hypot(*(P - b)) for b in B]
    F = m * np.array([0.0, ydd])
    f = np.linalg.solve(np.column_stack(e), F)
    out = []
    for a, b, fi, ei in zip(A, B, f, e, strict=True):
        r, F_i = b - a, fi * ei
        out.append(float(r[0] * F_i[1] - r[1] * F_i[0]))
    return np.array(out)
