"""A four-bar's input torque from its Lagrangian, with sympy (imports nothing from mechsing).

Ground pivots A = (0, 0) and D = (4, 0), crank AB = 1, coupler BC = 2 sqrt(2), rocker
CD = sqrt(5), in the plane z = 0 (examples/fourbar.yaml; drawn at crank angle 0 with
C = (3, 2)).  The crank angle theta is the one coordinate: B = (cos theta, sin theta), C
the intersection of the circles about B and D on the drawn branch, each body's centre of
mass and angle closed-form functions of theta.  With the kinetic energy
T = 1/2 J(theta) thetadot^2 (J = sum m |dc/dtheta|^2 + I (dphi/dtheta)^2) and the potential
V = -sum m g . c, Lagrange's equation gives the input torque
tau = J thetaddot + 1/2 J'(theta) thetadot^2 + V'(theta); sympy differentiates.
"""

from __future__ import annotations

import sympy as sp

__all__ = ["FourBar", "SliderCrank"]

th = sp.Symbol("theta", real=True)


def _rot(a: sp.Expr, v: tuple[sp.Expr, sp.Expr]) -> sp.Matrix:
    return sp.Matrix([sp.cos(a) * v[0] - sp.sin(a) * v[1], sp.sin(a) * v[0] + sp.cos(a) * v[1]])


class FourBar:
    """``bodies``: per body (mass, centre of mass where drawn, moment of inertia about z
    through the centre) for crank, coupler and rocker; ``gravity``: (gx, gy)."""

    def __init__(self, bodies: dict[str, tuple], gravity: tuple) -> None:
        A, D = sp.Matrix([0, 0]), sp.Matrix([4, 0])
        B = sp.Matrix([sp.cos(th), sp.sin(th)])
        l2, l3 = 2 * sp.sqrt(2), sp.sqrt(5)
        DB = D - B
        d = sp.sqrt(DB.dot(DB))
        a = (l2**2 - l3**2 + d**2) / (2 * d)
        h = sp.sqrt(l2**2 - a**2)
        C = B + a * DB / d + h * sp.Matrix([-DB[1], DB[0]]) / d
        phi = sp.atan2(C[1] - B[1], C[0] - B[0])  # the coupler's direction B -> C
        psi = sp.atan2(C[1] - D[1], C[0] - D[0])  # the rocker's direction D -> C
        phi0, psi0 = sp.atan2(2, 2), sp.atan2(2, -1)
        turns = {
            "crank": (th, A, sp.Matrix([0, 0])),
            "coupler": (phi - phi0, B, sp.Matrix([1, 0])),
            "rocker": (psi - psi0, D, sp.Matrix([4, 0])),
        }
        J = 0
        V = 0
        for name, (m, c0, inertia) in bodies.items():
            angle, pivot, pivot0 = turns[name]
            rel = (sp.nsimplify(c0[0]) - pivot0[0], sp.nsimplify(c0[1]) - pivot0[1])
            c = pivot + _rot(angle, rel)
            dc = c.diff(th)
            J += m * dc.dot(dc) + inertia * sp.diff(angle, th) ** 2
            V += -m * (gravity[0] * c[0] + gravity[1] * c[1])
        self.J = J
        self.dJ = sp.diff(J, th)
        self.dV = sp.diff(V, th)

    def torque(
        self, theta: object, rate: object, acceleration: object, digits: int = 30
    ) -> sp.Float:
        at = {th: theta}
        return sp.N(
            self.J.subs(at) * acceleration + self.dJ.subs(at) * rate**2 / 2 + self.dV.subs(at),
            digits,
        )


class SliderCrank:
    """A slider-crank in the plane z = 0: crank A = (0, 0) -> B of length 1 drawn at
    B = (0, 1), rod BC of length 3, the slider's pin C on the line y = 0 drawn at
    C = (2 sqrt(2), 0); the crank's joint value theta turns it from the drawn pose
    (B = (cos a, sin a), a = pi/2 + theta).  ``bodies`` as for :class:`FourBar` (crank,
    rod, slider: the slider translates, its inertia unused)."""

    def __init__(self, bodies: dict[str, tuple], gravity: tuple) -> None:
        a = sp.pi / 2 + th
        B = sp.Matrix([sp.cos(a), sp.sin(a)])
        C = sp.Matrix([sp.cos(a) + sp.sqrt(9 - sp.sin(a) ** 2), 0])
        rod = sp.atan2(C[1] - B[1], C[0] - B[0])
        rod0 = sp.atan2(-1, 2 * sp.sqrt(2))
        C0 = sp.Matrix([2 * sp.sqrt(2), 0])
        J = 0
        V = 0
        for name, (m, c0, inertia) in bodies.items():
            c0 = sp.Matrix([sp.nsimplify(c0[0]), sp.nsimplify(c0[1])])
            if name == "crank":
                angle, c = th, _rot(th, (c0[0], c0[1]))
            elif name == "rod":
                angle = rod - rod0
                rel = c0 - sp.Matrix([0, 1])
                c = B + _rot(angle, (rel[0], rel[1]))
            else:
                angle, c = sp.Integer(0), c0 + (C - C0)
            dc = c.diff(th)
            J += m * dc.dot(dc) + inertia * sp.diff(angle, th) ** 2
            V += -m * (gravity[0] * c[0] + gravity[1] * c[1])
        self.J = J
        self.dJ = sp.diff(J, th)
        self.dV = sp.diff(V, th)

    torque = FourBar.torque
