"""The rigid body in the Lie form (mechsing.kinetics.rigid, issue 43), property-tested:
the momentum against its textbook form (m v_c, I_c omega + c x p), the coadjoint action's
defining identities (the Klein pairing kept), invariance under a change of frame, the
Galilean law against the rate of the momentum computed by finite differences at 50 digits
along motions whose twists are known in closed form, the non-Galilean form against the
Galilean one, and the energy balance of a free body integrated with zero efforts."""

from __future__ import annotations

import mpmath
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from mechsing import lie
from mechsing.kinetics.rigid import (
    Inertia,
    kinetic_energy,
    momentum,
    newton_euler,
    newton_euler_in_frame,
)
from tests.strategies import body_inertias

vec = st.lists(st.floats(-2, 2), min_size=3, max_size=3).map(np.array)
screws = st.lists(st.floats(-2, 2), min_size=6, max_size=6).map(np.array)


def inertias() -> st.SearchStrategy[Inertia]:
    return body_inertias().map(lambda b: Inertia(*b))


def _textbook(I: Inertia, xi: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    w, v = xi[:3], xi[3:]
    vc = v + np.cross(w, I.centre)  # the velocity of the centre of mass
    p = I.mass * vc
    L = I.about_centre @ w + np.cross(I.centre, p)
    return p, L, 0.5 * I.mass * vc @ vc + 0.5 * w @ I.about_centre @ w


@given(inertias(), screws)
def test_momentum_and_energy_are_the_textbook_ones(I: Inertia, xi: np.ndarray) -> None:
    p, L, T = _textbook(I, xi)
    h = momentum(I, xi)
    assert np.allclose(h, np.concatenate([p, L]), rtol=1e-12, atol=1e-12)
    assert np.isclose(float(kinetic_energy(I, xi)), T, rtol=1e-12, atol=1e-14)
    assert np.allclose(I.matrix() @ xi, h, rtol=1e-12, atol=1e-12)


@given(st.lists(screws, min_size=3, max_size=3), vec)
def test_the_coadjoint_action_keeps_the_klein_pairing(s: list[np.ndarray], r: np.ndarray) -> None:
    xi, eta, h = s
    g = lie.exp(np.concatenate([r, xi[3:]]))
    assert np.isclose(
        lie.klein(lie.act_screw(g, h), lie.act_screw(g, xi)), lie.klein(h, xi), atol=1e-11
    )
    # its derivative: <[xi, h], eta> = -<h, [xi, eta]>
    assert np.isclose(
        lie.klein(lie.bracket(xi, h), eta), -lie.klein(h, lie.bracket(xi, eta)), atol=1e-11
    )


@given(inertias(), st.lists(screws, min_size=3, max_size=3))
def test_the_law_is_invariant_under_a_change_of_frame(I: Inertia, s: list[np.ndarray]) -> None:
    a, xi, acc = s
    g = lie.exp(a)
    moved = I.moved(g)
    Xi, Acc = lie.act_screw(g, xi), lie.act_screw(g, acc)
    assert np.isclose(kinetic_energy(moved, Xi), kinetic_energy(I, xi), rtol=1e-11, atol=1e-12)
    assert np.allclose(momentum(moved, Xi), lie.act_screw(g, momentum(I, xi)), atol=1e-10)
    assert np.allclose(
        newton_euler(moved, Xi, Acc), lie.act_screw(g, newton_euler(I, xi, acc)), atol=1e-9
    )


def _mp(x: np.ndarray) -> np.ndarray:
    return np.array([mpmath.mpf(float(v)) for v in np.ravel(x)], dtype=object).reshape(np.shape(x))


def _mp_inertia(I: Inertia) -> Inertia:
    return Inertia(mpmath.mpf(float(I.mass)), _mp(I.centre), _mp(I.about_centre))


def _two_screw_motion(a: np.ndarray, b: np.ndarray, t: object) -> tuple:
    """g(t) = exp(t a) exp(t b) g0-free: spatial twist a + Ad(exp(t a)) b, its rate
    [a, Ad(exp(t a)) b] (closed forms)."""
    ea = lie.exp(a * t)
    g = ea @ lie.exp(b * t)
    moved_b = lie.act_screw(ea, b)
    return g, a + moved_b, lie.bracket(a, moved_b)


@settings(max_examples=20, deadline=None)
@given(inertias(), screws, screws, st.floats(-1, 1))
def test_galilean_law_is_the_rate_of_the_momentum(
    I: Inertia, a: np.ndarray, b: np.ndarray, t0: float
) -> None:
    with mpmath.workdps(50):
        I0, a, b, t = _mp_inertia(I), _mp(a), _mp(b), mpmath.mpf(t0)
        step = mpmath.mpf("1e-12")

        def h(t: object) -> np.ndarray:
            g, xi, _ = _two_screw_motion(a, b, t)
            return momentum(I0.moved(g), xi)

        rate = (h(t + step) - h(t - step)) / (2 * step)
        g, xi, acc = _two_screw_motion(a, b, t)
        w = newton_euler(I0.moved(g), xi, acc)
        scale = max(1, max(abs(x) for x in w))
        assert max(abs(x) for x in w - rate) < mpmath.mpf("1e-18") * scale


@settings(max_examples=20, deadline=None)
@given(inertias(), st.lists(screws, min_size=4, max_size=4), st.floats(-1, 1))
def test_non_galilean_form_agrees_with_the_galilean_one(
    I: Inertia, s: list[np.ndarray], t0: float
) -> None:
    """A frame F moving as exp(t e1) exp(t e2), the body moving relative to F as
    exp(t r1) exp(t r2): the wrench written in F (relative acceleration, F's twist and
    its rate in closed form) moved to the ground equals the Galilean wrench of the
    absolute motion, whose twist and acceleration are finite differences of g_F g_r."""
    with mpmath.workdps(50):
        I0 = _mp_inertia(I)
        e1, e2, r1, r2 = (_mp(x) for x in s)
        t = mpmath.mpf(t0)
        step = mpmath.mpf("1e-12")

        def absolute(t: object) -> np.ndarray:
            return _two_screw_motion(e1, e2, t)[0] @ _two_screw_motion(r1, r2, t)[0]

        def twist(t: object) -> np.ndarray:
            dg = (absolute(t + step) - absolute(t - step)) / (2 * step)
            return lie.vee(dg @ lie.inverse(absolute(t)))

        xi = twist(t)
        acc = (twist(t + step) - twist(t - step)) / (2 * step)
        w = newton_euler(I0.moved(absolute(t)), xi, acc)

        gf = _two_screw_motion(e1, e2, t)[0]
        back = lie.exp(-e2 * t)
        eta = lie.act_screw(back, e1) + e2  # g_F^-1 g_F'
        eta_dot = lie.bracket(lie.act_screw(back, e1), e2)
        gr, xi_r, a_r = _two_screw_motion(r1, r2, t)
        w_f = newton_euler_in_frame(I0.moved(gr), eta, eta_dot, xi_r, a_r)
        diff = lie.act_screw(gf, w_f) - w
        scale = max(1, max(abs(x) for x in w))
        assert max(abs(x) for x in diff) < mpmath.mpf("1e-15") * scale


@settings(max_examples=8, deadline=None)
@given(inertias(), screws)
def test_a_free_body_keeps_its_energy_and_momentum(I: Inertia, xi0: np.ndarray) -> None:
    """Zero efforts: I(xi') = -[xi, I(xi)] integrated over 1 s with the pose."""
    from scipy.integrate import solve_ivp

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        g = np.eye(4)
        g[:3, :] = y[:12].reshape(3, 4)
        xi = y[12:]
        here = I.moved(g)
        acc = np.linalg.solve(here.matrix(), -lie.bracket(xi, momentum(here, xi)))
        dg = lie.hat(xi) @ g
        return np.concatenate([dg[:3, :].ravel(), acc])

    y0 = np.concatenate([np.eye(4)[:3, :].ravel(), xi0])
    sol = solve_ivp(rhs, (0, 1), y0, method="DOP853", rtol=1e-12, atol=1e-12)
    g1 = np.eye(4)
    g1[:3, :] = sol.y[:12, -1].reshape(3, 4)
    xi1 = sol.y[12:, -1]
    T0, T1 = kinetic_energy(I, xi0), kinetic_energy(I.moved(g1), xi1)
    assert abs(T1 - T0) <= 1e-9 * max(T0, 1e-12)
    h0, h1 = momentum(I, xi0), momentum(I.moved(g1), xi1)
    assert np.allclose(h1, h0, rtol=1e-8, atol=1e-9 * (1 + np.abs(h0).max()))
