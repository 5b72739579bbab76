"""The rigid body in the Lie form: momentum as a dual vector, its coadjoint motion, and the
fundamental law of dynamics as one equation in dimension 6 on the Lie algebra of D.

Chevallier and Lerbet (*Multi-Body Kinematics and Dynamics with Lie Groups*, ISTE/Elsevier
2018), chapter 7, write the fundamental law for a rigid body (not a particle) as one
equation on the dual of the Lie algebra of D = SE(3): the **momentum** ``h = I(xi)`` is the
image of the body's twist by its inertia, a map from twists to dual vectors (wrenches), and
in a Galilean frame

    d/dt h = w                                                   (Galilean form)

with ``w`` the wrench of the external efforts.  The inertia is carried by the body:
``I_g = Ad*_(g^-1) o I_0 o Ad_(g^-1)``, so that with the twist ``xi = g' g^-1`` (spatial,
as everywhere in mechsing) the derivative of the momentum is

    d/dt h = I(xi') + ad*_xi h,        i.e.   I(xi') + [xi, I(xi)] = w

(``ad*_xi`` the coadjoint action of the twist, which keeps the Klein form: the rate of the
momentum of a body whose inertia turns with it).  In a frame F that moves with the twist
``eta`` (its own, in its coordinates) the same law reads, for the body's twist ``xi_F``
in F's coordinates, ``d/dt h_F + [eta, h_F] = w_F`` (the non-Galilean form, the inertia
efforts of the frame's motion being the term ``[eta, h_F]``), and with the body's
motion relative to F (twist ``xi_r``, acceleration ``a_r``, ``xi_F = eta + xi_r``)

    w_F = I_F(a_r + eta' + [eta, xi_r]) + [xi_F, I_F(xi_F)]

(drive and Coriolis accelerations in the first term).  The kinetic energy is half the
pairing of twist and momentum, ``T = 1/2 <h, xi>``.

In mechsing's layout the Klein form pairs a wrench ``(f, m)`` with a twist ``(omega, v)``
(``<(f, m), (omega, v)> = f.v + m.omega``, :func:`mechsing.lie.klein`), which identifies
the dual of the Lie algebra with the algebra itself: the coadjoint action of ``g`` on a
wrench is then :func:`mechsing.lie.act_screw` (the ``Ad`` matrix ``[[R, 0], [p^ R, R]]``
moves ``(f, m)`` as it moves twists) and the coadjoint action of a twist is the bracket
:func:`mechsing.lie.bracket`.  Nothing here is a second algebra: this module adds the
inertia map and the law.

Owns :class:`Inertia` (a body's mass, centre and inertia about the centre, in ground axes
at some pose; :meth:`Inertia.moved` is its coadjoint transport), :func:`momentum`,
:func:`kinetic_energy`, :func:`newton_euler` (Galilean) and :func:`newton_euler_in_frame`
(non-Galilean).  Every function runs on float arrays (batched over leading axes), on
mp:N and on exact object arrays (:mod:`mechsing.numeric`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.lie import ANGULAR, LINEAR
from mechsing.numeric.backend import holds_objects

__all__ = [
    "Inertia",
    "gravity_wrench",
    "kinetic_energy",
    "momentum",
    "newton_euler",
    "newton_euler_in_frame",
]


@dataclass(frozen=True)
class Inertia:
    """A rigid body's inertia at a pose: ``mass`` (kg, shape ``(...)``), ``centre`` (m,
    ``(..., 3)``, the centre of mass at that pose) and ``about_centre`` (kg m^2,
    ``(..., 3, 3)``, about the centre of mass in ground axes)."""

    mass: Any
    centre: Any
    about_centre: Any

    def moved(self, g: Any) -> Inertia:
        """The inertia of the body displaced by ``g`` (the coadjoint transport
        ``Ad*_(g^-1) o I o Ad_(g^-1)``): the centre to ``g(c)``, the inertia to ``R I R^T``."""
        R = lie.rotation(g)
        return Inertia(
            self.mass,
            lie.act_point(g, self.centre),
            R @ self.about_centre @ np.swapaxes(R, -1, -2),
        )

    def matrix(self) -> np.ndarray:
        """The map from twists ``(omega, v)`` to momenta ``(f, m)`` as a (..., 6, 6) matrix:
        ``[[-m c^, m 1], [Ic - m c^ c^, m c^]]``."""
        m = np.asarray(self.mass)[..., None, None]
        C = lie.hat3(self.centre)
        eye = np.broadcast_to(np.eye(3, dtype=int), C.shape) * m
        top = np.concatenate([-m * C, eye], axis=-1)
        bot = np.concatenate([self.about_centre - m * (C @ C), m * C], axis=-1)
        return np.concatenate([top, bot], axis=-2)

    def __add__(self, other: Inertia) -> Inertia:
        """The inertia of two bodies rigidly joined (the composite of a subtree)."""
        m = self.mass + other.mass
        c = (self.centre * _last(self.mass) + other.centre * _last(other.mass)) / _last(m)
        return Inertia(m, c, self._about(c) + other._about(c))

    def _about(self, point: Any) -> np.ndarray:
        """The inertia about ``point`` (parallel axis: Huygens-Steiner)."""
        d = self.centre - point
        D = lie.hat3(d)
        return self.about_centre - _last(_last(self.mass)) * (D @ D)


def _last(x: Any) -> np.ndarray:
    return np.asarray(x)[..., None]


def _arr(x: Any) -> np.ndarray:
    """x as an array of its numbers (object for mp and exact, float64 otherwise)."""
    a = np.asarray(x)
    return a if holds_objects(a) else a.astype(np.float64)


def momentum(inertia: Inertia, xi: Any) -> np.ndarray:
    """The momentum ``h = I(xi)`` of a twist: (f, m) = (linear momentum, angular momentum
    about the ground origin); ``p = m (v + omega x c)``, ``L = Ic omega + c x p``."""
    xi = _arr(xi)
    w, v = xi[..., ANGULAR], xi[..., LINEAR]
    c = inertia.centre
    p = _last(inertia.mass) * (v + lie.cross(w, c))
    Ic = np.asarray(inertia.about_centre)
    # one inertia for every sample (a body at its drawn pose): one matrix product
    Icw = w @ Ic.T if Ic.ndim == 2 else (Ic @ w[..., None])[..., 0]
    L = Icw + lie.cross(c, p)
    return np.concatenate([p, L], axis=-1)


def kinetic_energy(inertia: Inertia, xi: Any) -> np.ndarray:
    """``T = 1/2 <I(xi), xi>`` (the Klein pairing of the momentum with the twist)."""
    return lie.klein(xi, momentum(inertia, xi)) / 2


def newton_euler(inertia: Inertia, xi: Any, xi_dot: Any) -> np.ndarray:
    """The wrench the body needs for the twist ``xi`` and its rate ``xi_dot`` in the
    Galilean ground frame: ``d/dt I(xi) = I(xi_dot) + [xi, I(xi)]``."""
    return momentum(inertia, xi_dot) + lie.bracket(xi, momentum(inertia, xi))


def newton_euler_in_frame(
    inertia_f: Inertia, eta: Any, eta_dot: Any, xi_r: Any, a_r: Any
) -> np.ndarray:
    """The wrench, in the coordinates of a frame F moving with its own twist ``eta`` (and
    rate ``eta_dot``, both in F's coordinates), for a body of inertia ``inertia_f`` (in F's
    coordinates) moving relative to F with the twist ``xi_r`` and the acceleration ``a_r``
    (F's coordinates): ``I_F(a_r + eta' + [eta, xi_r]) + [xi_F, I_F(xi_F)]``,
    ``xi_F = eta + xi_r`` (the body's absolute twist in F's coordinates)."""
    xi_f = _arr(eta) + _arr(xi_r)
    acc = _arr(a_r) + eta_dot + lie.bracket(eta, xi_r)
    return momentum(inertia_f, acc) + lie.bracket(xi_f, momentum(inertia_f, xi_f))


def gravity_wrench(inertia: Inertia, gravity: Any) -> np.ndarray:
    """The weight of the body (SI wrench at the ground origin): ``m g`` through the centre;
    equal to ``-I((0, -g))``, the efforts of a ground accelerating by ``-g``."""
    f = _last(inertia.mass) * np.asarray(gravity)
    return np.concatenate([f, lie.cross(inertia.centre, f)], axis=-1)
