"""Closed chains' inverse dynamics (mechsing.kinetics.closed, issue 43): a four-bar with
masses driven by its crank at constant speed (and accelerating) against its Lagrangian
computed by sympy in tests/reference/fourbar.py; the Type II crossing condition at the
dead point of the crank when the rocker drives (the weights cannot be held there, a motion
at rest without gravity can), and the input effort growing as 1/distance approaching it."""

from __future__ import annotations

import math
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp

import mechsing
from mechsing.model import loads
from tests.mechanisms import FOURBAR_JOINTS
from tests.reference.fourbar import FourBar

FOURBAR = (
    "mechanism: four-bar\n"
    + FOURBAR_JOINTS
    + """\
inputs: [INPUT]
mass:
  crank: {kg: 1, centre: [0.5, 0, 0], inertia: [0.01, 0.09, 0.09, 0, 0, 0]}
  coupler: {kg: 2, centre: [2, 1, 0], inertia: [0.02, 1.3, 1.3, 0, 0, 0]}
  rocker: {kg: 1.5, centre: [3.5, 1, 0], inertia: [0.015, 0.6, 0.6, 0, 0, 0]}
gravity: [0, -9.81, 0]
configurations:
CONFIGS
"""
)
REFERENCE = FourBar(
    {"crank": (1, (0.5, 0), 0.09), "coupler": (2, (2, 1), 1.3), "rocker": (1.5, (3.5, 1), 0.6)},
    (0, sp.Rational(-981, 100)),
)
#: the same with the file's decimals as exact rationals (the 50-digit comparisons)
R = sp.Rational
EXACT = FourBar(
    {
        "crank": (1, (R(1, 2), 0), R(9, 100)),
        "coupler": (2, (2, 1), R(13, 10)),
        "rocker": (R(3, 2), (R(7, 2), 1), R(3, 5)),
    },
    (0, R(-981, 100)),
)
#: the crank's dead point when the rocker drives: crank and coupler in line, |AC| = 1 + 2 sqrt(2)
DEAD = math.acos(((1 + 2 * math.sqrt(2)) ** 2 + 16 - 5) / 8 / (1 + 2 * math.sqrt(2)))


def _fourbar(inputs: str, angles: dict[str, float]) -> object:
    configs = "\n".join(f"  {name}: {{A: {a!r}}}" for name, a in angles.items())
    return loads(FOURBAR.replace("INPUT", inputs).replace("CONFIGS", configs), path="fourbar.yaml")


ANGLES = {"a03": 0.3, "a17": 1.7, "a35": 3.5, "a52": 5.2}


@pytest.mark.parametrize("acc", [0.0, 0.5])
def test_crank_torque_for_a_motion_of_the_crank_is_the_lagrangian(acc: float) -> None:
    res = mechsing.dynamics(_fourbar("A", ANGLES), rates={"A": 2}, accelerations={"A": acc})
    for c in res.configurations:
        theta = c.joints["A"]
        want = float(REFERENCE.torque(sp.Float(theta, 30), 2, sp.Float(acc)))
        assert abs(c.efforts["A"] - want) <= 1e-10 * max(1.0, abs(want))
        assert c.efforts["B"] == c.efforts["C"] == c.efforts["D"] == 0  # passive
        assert c.crossing["possible"] and c.crossing["residual"] < 1e-12


def test_at_the_dead_point_the_rocker_cannot_hold_the_weights() -> None:
    mech = _fourbar("D", {"dead": DEAD, "near": DEAD + 0.2})
    held = mechsing.dynamics(mech, "near").configurations[0]
    assert held.crossing["possible"]
    dead = mechsing.dynamics(mech, "dead").configurations[0]
    assert not dead.crossing["possible"] and dead.crossing["residual"] > 1e-3
    # without gravity, at rest: nothing to balance, the crossing is possible
    free = mechsing.dynamics(mech, "dead", gravity=(0, 0, 0)).configurations[0]
    assert free.crossing["possible"]


def test_the_rocker_effort_grows_as_one_over_the_distance_to_the_dead_point() -> None:
    steps = [1e-3, 1e-4, 1e-5, 1e-6]
    names = {f"d{i}": DEAD + d for i, d in enumerate(steps)}
    res = mechsing.dynamics(_fourbar("D", names), list(names))
    efforts = [abs(c.efforts["D"]) for c in res.configurations]
    slopes = np.diff(np.log(efforts)) / np.diff(np.log(steps))
    assert np.allclose(slopes, -1, atol=0.01)


def test_forward_dynamics_of_a_four_bar_inverts_the_lagrangian() -> None:
    """The crank's acceleration under the torque the Lagrangian gives for 0.5 rad/s^2 at
    2 rad/s is 0.5 rad/s^2."""
    for name, theta in ANGLES.items():
        tau = float(REFERENCE.torque(sp.Float(theta, 30), 2, sp.Rational(1, 2)))
        res = mechsing.dynamics(_fourbar("A", ANGLES), name, rates={"A": 2}, efforts={"A": tau})
        c = res.configurations[0]
        assert res.problem == "forward"
        assert abs(c.accelerations["A"] - 0.5) <= 1e-10
        assert abs(c.efforts["A"] - tau) <= 1e-10 * abs(tau)


def _closed_at(mech: object, name: str, precision: str, rate: object, acc: object) -> object:
    """The crank's motion and efforts at ``name`` in ``precision`` (kinetics.closed)."""
    from mechsing.kinematics import solve_configuration
    from mechsing.kinetics.closed import closed_inverse
    from mechsing.kinetics.tree import TreeDynamics
    from mechsing.numeric import parse_precision

    prec = parse_precision(precision)
    model, closed = solve_configuration(mech, name, prec)
    with prec.context():
        td = TreeDynamics(model, None, closed=True)
        k = model.joint("A").columns.start
        one = model.asarray([rate, acc])
        return closed_inverse(td, closed.q, [k], one[:1], one[1:]), k


@pytest.mark.parametrize("acc", [0, sp.Rational(1, 2)])
def test_crank_torque_at_50_digits_is_the_lagrangian(acc: object) -> None:
    """A closed chain in mp:50: the crank's torque at 2 rad/s to 1e-40 (the configuration
    A = 3/10 exactly, the sympy Lagrangian evaluated at 60 digits)."""
    mech = _fourbar("A", {"a03": "3/10", "a17": "17/10"})
    with mpmath.workdps(50):
        for name, theta in (("a03", sp.Rational(3, 10)), ("a17", sp.Rational(17, 10))):
            res, k = _closed_at(mech, name, "mp:50", 2, acc)
            want = mpmath.mpf(str(EXACT.torque(sp.Float(theta, 80), 2, acc, digits=60)))
            got = res.efforts[k]
            assert isinstance(got, mpmath.mpf)
            assert abs(got - want) <= mpmath.mpf("1e-40") * max(1, abs(want))
            assert res.residual <= 1e-40


def test_crank_torque_in_exact_mode_at_the_drawn_pose() -> None:
    """Exact mode: at the drawn pose (crank angle 0, every position rational) the torque
    is the Lagrangian's exactly (compared at 40 digits)."""
    text = FOURBAR.replace("INPUT", "A").replace("CONFIGS", "  drawn: {A: 0, B: 0, C: 0, D: 0}")
    mech = loads(text, path="fourbar.yaml")
    res, k = _closed_at(mech, "drawn", "exact", 2, sp.Rational(1, 2))
    want = EXACT.torque(sp.Float(0, 80), 2, sp.Rational(1, 2), digits=50)
    assert abs(sp.N(sp.sympify(res.efforts[k]) - want, 50)) <= sp.Float("1e-40")
    assert res.residual == 0


def test_at_the_dead_point_in_mp_and_exact_the_crossing_is_decided_as_in_float() -> None:
    """At the crank's dead point the rocker cannot drive: in mp:30 the Type II is decided
    and the crossing condition with it, as float's residual decides it: the weights cannot
    be held, a motion at rest without gravity can."""
    mech = _fourbar("D", {"dead": "acos(((1 + 2*sqrt(2))**2 + 11)/8/(1 + 2*sqrt(2)))"})
    for precision in ("float", "mp:30"):
        c = mechsing.dynamics(mech, "dead", precision=precision).configurations[0]
        assert c.crossing["possible"] is False and c.crossing["residual"] > 1e-3, precision
        c = mechsing.dynamics(mech, "dead", precision=precision, gravity=(0, 0, 0))
        assert c.configurations[0].crossing["possible"] is True, precision


def test_rates_that_are_no_motion_at_a_type_ii_are_refused_with_the_reason() -> None:
    """At the dead point the rocker is at its extreme: a rate of the rocker is no motion."""
    mech = _fourbar("D", {"dead": "acos(((1 + 2*sqrt(2))**2 + 11)/8/(1 + 2*sqrt(2)))"})
    with pytest.raises(mechsing.errors.UserError, match="not a motion of the mechanism"):
        mechsing.dynamics(mech, "dead", rates={"D": 1}, precision="mp:30")


#: the five-bar of examples/five_bar.yaml with a point mass of 2 kg at its output point P
FIVE_BAR = (
    (Path(__file__).resolve().parents[1] / "examples" / "five_bar.yaml")
    .read_text()
    .replace(
        "configurations:",
        "mass:\n  dist1: {kg: 2, centre: [0, 4, 0], inertia: [0, 0, 0, 0, 0, 0]}\nconfigurations:",
    )
)


@pytest.mark.parametrize("precision", ["mp:50", "exact"])
def test_five_bar_at_its_type_ii_holds_a_weight_along_the_distal_links_only(
    precision: str,
) -> None:
    """The configuration type2 (distal links aligned along x, P = (0, sqrt 3)) at rest.
    The massless distal links push the mass along x only (two-force members), so the
    crossing is possible iff gravity has no y component.  Along x (g = 9.81 m/s^2): the
    links' forces f1 e1 + f2 e2 = -m g with e2 = -e1 = (-1, 0) leave f1 - f2 = -m g; the
    motors' torques are tau_i = ((B_i - A_i) x f_i e_i)_z = (-sqrt 3 f1, sqrt 3 f2), and
    the family's least-norm member is f1 = -m g / 2: tau1 = tau2 = sqrt(3) m g / 2.  Along
    -y: not possible, as float says."""
    mech = loads(FIVE_BAR, path="five_bar_mass.yaml")
    with mpmath.workdps(60):
        want = mpmath.sqrt(3) * 2 * mpmath.mpf("9.81") / 2
    c = mechsing.dynamics(mech, "type2", precision=precision, gravity=(9.81, 0, 0))
    c = c.configurations[0]
    assert c.crossing["possible"] is True
    assert abs(c.efforts["A1"] - float(want)) <= 1e-12 * float(want)
    assert abs(c.efforts["A2"] - float(want)) <= 1e-12 * float(want)
    if precision == "mp:50":
        with mpmath.workdps(50):
            res, ins = _closed_five_bar(mech, precision, (sp.Rational(981, 100), 0, 0))
            for k in ins:
                assert isinstance(res.efforts[k], mpmath.mpf)
                assert abs(res.efforts[k] - want) <= mpmath.mpf("1e-40") * want
        assert res.residual <= 1e-40
    for g in ((0, -9.81, 0), (1, -9.81, 0)):
        for p in (precision, "float"):
            c = mechsing.dynamics(mech, "type2", precision=p, gravity=g).configurations[0]
            assert c.crossing["possible"] is False and c.crossing["residual"] > 0.1, (g, p)
    free = mechsing.dynamics(mech, "type2", precision=precision, gravity=(0, 0, 0))
    c = free.configurations[0]
    assert c.crossing == {"possible": True, "residual": 0.0}
    assert c.efforts["A1"] == c.efforts["A2"] == 0


def _closed_five_bar(mech: object, precision: str, gravity: object) -> object:
    from mechsing.kinematics import solve_configuration
    from mechsing.kinetics.closed import closed_inverse
    from mechsing.kinetics.tree import TreeDynamics
    from mechsing.numeric import parse_precision

    prec = parse_precision(precision)
    model, closed = solve_configuration(mech, "type2", prec)
    with prec.context():
        td = TreeDynamics(model, model.asarray(list(gravity)), closed=True)
        ins = [model.joint(j).columns.start for j in ("A1", "A2")]
        zero = model.backend.zeros(2)
        return closed_inverse(td, closed.q, ins, zero, zero), ins


SLIDER_CRANK = """\
mechanism: slider-crank
bodies: [ground, crank, rod, slider]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [0, 1, 0]}
  - {name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: [2*sqrt(2), 0, 0]}
  - {name: P, type: P, between: [ground, slider], axis: [1, 0, 0]}
inputs: [A]
mass:
  crank: {kg: 1.2, centre: [0, 0.5, 0], inertia: [0.1, 0.01, 0.1, 0, 0, 0]}
  rod: {kg: 2, centre: [1.4, 0.5, 0], inertia: [0.02, 1.5, 1.5, 0, 0, 0]}
  slider: {kg: 3, centre: [2.9, 0, 0], inertia: [0.05, 0.05, 0.05, 0, 0, 0]}
gravity: [0, -9.81, 0]
configurations:
CONFIGS
"""


@pytest.mark.parametrize("acc", [0.0, -1.5])
def test_slider_crank_torque_is_the_lagrangian(acc: float) -> None:
    """A loop with a prismatic joint: the crank's torque at 3 rad/s (and decelerating)."""
    from tests.reference.fourbar import SliderCrank

    angles = {"s1": 0.4, "s2": 2.0, "s3": -2.5, "s4": 4.0}
    configs = "\n".join(f"  {name}: {{A: {a!r}}}" for name, a in angles.items())
    mech = loads(SLIDER_CRANK.replace("CONFIGS", configs), path="slider.yaml")
    ref = SliderCrank(
        {
            "crank": (sp.Rational(6, 5), (0, 0.5), sp.Rational(1, 10)),
            "rod": (2, (1.4, 0.5), sp.Rational(3, 2)),
            "slider": (3, (2.9, 0), 0),
        },
        (0, sp.Rational(-981, 100)),
    )
    res = mechsing.dynamics(mech, list(angles), rates={"A": 3}, accelerations={"A": acc})
    for c in res.configurations:
        want = float(ref.torque(sp.Float(c.joints["A"], 30), 3, sp.Float(acc)))
        assert abs(c.efforts["A"] - want) <= 1e-10 * max(1.0, abs(want))
        assert c.efforts["P"] == 0


def test_slider_crank_torque_at_50_digits_is_the_lagrangian() -> None:
    """A loop with a prismatic joint (a length column of the closure's rows) in mp:50."""
    from tests.reference.fourbar import SliderCrank

    R = sp.Rational
    mech = loads(SLIDER_CRANK.replace("CONFIGS", "  s1: {A: '2/5'}"), path="slider.yaml")
    ref = SliderCrank(
        {
            "crank": (R(6, 5), (0, R(1, 2)), R(1, 10)),
            "rod": (2, (R(7, 5), R(1, 2)), R(3, 2)),
            "slider": (3, (R(29, 10), 0), 0),
        },
        (0, R(-981, 100)),
    )
    with mpmath.workdps(50):
        res, k = _closed_at(mech, "s1", "mp:50", 3, R(-3, 2))
        want = mpmath.mpf(str(ref.torque(sp.Float(R(2, 5), 80), 3, R(-3, 2), digits=60)))
        assert abs(res.efforts[k] - want) <= mpmath.mpf("1e-40") * max(1, abs(want))


RPR = (
    (Path(__file__).resolve().parents[1] / "examples" / "planar_3rpr.yaml")
    .read_text()
    .replace(
        "configurations:",
        "mass:\n  platform: {kg: 3, centre: [1, '6/5', 0], inertia: [0.2, 0.2, 0.4, 0, 0, 0]}\n"
        "gravity: [0, '-981/100', 0]\nconfigurations:",
    )
)


@pytest.mark.parametrize("precision", ["float", "mp:50"])
def test_3rpr_holds_its_platform_by_forces_along_the_three_legs(precision: str) -> None:
    """Two loops with prismatic inputs, at rest at the drawn pose under gravity: the legs
    are massless with a pin at each end, so each pushes the platform along its line with
    its actuator's force f_i; the platform's balance (force and moment about its centre)
    is a 3x3 linear system, solved here in mpmath at 60 digits."""
    mech = loads(RPR, path="rpr.yaml")
    with mpmath.workdps(60):
        f = mpmath.mpf
        base = [(0, 0), (4, 0), (0, 4)]
        pins = [(f(9) / 10, f(3) / 10), (f(5) / 2, f(3) / 2), (-f(3) / 10, f(19) / 10)]
        centre = (f(1), f(6) / 5)
        rows = [[], [], []]
        for (bx, by), (px, py) in zip(base, pins, strict=True):
            ux, uy = px - bx, py - by
            n = mpmath.sqrt(ux**2 + uy**2)
            ux, uy = ux / n, uy / n
            rows[0].append(ux)
            rows[1].append(uy)
            rows[2].append((px - centre[0]) * uy - (py - centre[1]) * ux)
        want = mpmath.lu_solve(mpmath.matrix(rows), mpmath.matrix([0, 3 * f(981) / 100, 0]))
    if precision == "float":
        c = mechsing.dynamics(mech, "reference").configurations[0]
        got = [c.efforts[j] for j in ("P1", "P2", "P3")]
        for g, w in zip(got, want, strict=True):
            assert abs(g - float(w)) <= 1e-10 * max(1.0, float(abs(w)))
        assert c.efforts["Rb1"] == c.efforts["Rp3"] == 0 and c.crossing["possible"]
        return
    with mpmath.workdps(50):
        from mechsing.kinematics import solve_configuration
        from mechsing.kinetics.closed import closed_inverse
        from mechsing.kinetics.tree import TreeDynamics
        from mechsing.numeric import parse_precision

        prec = parse_precision(precision)
        model, closed = solve_configuration(mech, "reference", prec)
        with prec.context():
            td = TreeDynamics(model, None, closed=True)
            ins = [model.joint(j).columns.start for j in ("P1", "P2", "P3")]
            zero = model.backend.zeros(3)
            res = closed_inverse(td, closed.q, ins, zero, zero)
        for k, w in zip(ins, want, strict=True):
            assert abs(res.efforts[k] - w) <= mpmath.mpf("1e-40") * max(1, abs(w))


@pytest.mark.parametrize("precision", ["mp:30", "exact"])
def test_forward_dynamics_at_a_type_ii_exits_2_with_the_reason(
    tmp_path: Path, precision: str
) -> None:
    """At the five-bar's Type II the inputs' efforts do not determine the accelerations."""
    from tests.cli import run_cli

    f = tmp_path / "five_bar_mass.yaml"
    f.write_text(FIVE_BAR)
    argv = ["dynamics", f, "--config", "type2", "--efforts", "A1=1", "--precision"]
    rc, _, err = run_cli([*argv, precision])
    assert rc == 2 and "do not determine the accelerations" in err, err
