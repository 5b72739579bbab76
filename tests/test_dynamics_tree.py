"""The dynamics of trees (mechsing.kinetics.tree, issue 43) against answers computed
elsewhere: Pinocchio's RNEA, CRBA and ABA on examples/ur5.urdf and on random trees of
revolute and prismatic joints (to 1e-10 relative; skipped without ``pinocchio``), a
Lagrangian of planar 2R and 3R arms derived in tests/reference/lagrangian.py at 50
digits (to 1e-40), the same arm in exact arithmetic, and the conservation of kinetic
energy under zero efforts without gravity over 1 s on the UR5 and a 7-joint arm."""

from __future__ import annotations

from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy
from hypothesis import given, settings

from mechsing.errors import UserError
from mechsing.kinematics import KinematicModel
from mechsing.kinetics.tree import TreeDynamics
from mechsing.model import loads
from mechsing.reader import mechanism_from_text, read_mechanism
from tests.reference.lagrangian import PlanarArm
from tests.strategies import robot_trees

ROOT = Path(__file__).resolve().parents[1]
UR5 = ROOT / "examples" / "ur5.urdf"
G = (0.0, 0.0, -9.81)


def _tree(source: object, precision: str = "float", gravity: object = None) -> TreeDynamics:
    mech = read_mechanism(source) if isinstance(source, Path) else source
    return TreeDynamics(KinematicModel(mech, precision), gravity)


def _close(a: np.ndarray, b: np.ndarray, rtol: float) -> bool:
    """Relative to the reference's norm, or to 1 (SI) when that is smaller (a zero
    reference is met to ``rtol`` absolute)."""
    return float(np.linalg.norm(a - b)) <= rtol * max(float(np.linalg.norm(b)), 1.0)


# ---------------------------------------------------------------- against Pinocchio


def _pinocchio(urdf_text: str, names: list[str]):  # type: ignore[no-untyped-def]
    pin = pytest.importorskip("pinocchio")
    pm = pin.buildModelFromXML(urdf_text)
    pm.gravity.linear = np.array(G)
    pd = pm.createData()
    order = [pm.joints[pm.getJointId(n)].idx_q for n in names]
    assert sorted(order) == list(range(len(names)))

    def to_pin(x: np.ndarray) -> np.ndarray:
        out = np.empty(len(names))
        out[order] = x
        return out

    def from_pin(x: np.ndarray) -> np.ndarray:
        return np.asarray(x)[order]

    def rnea(q, v, a):  # type: ignore[no-untyped-def]
        return from_pin(pin.rnea(pm, pd, to_pin(q), to_pin(v), to_pin(a)))

    def mass(q):  # type: ignore[no-untyped-def]
        M = pin.crba(pm, pd, to_pin(q))
        M = np.triu(M) + np.triu(M, 1).T
        return M[np.ix_(order, order)]

    def aba(q, v, tau):  # type: ignore[no-untyped-def]
        return from_pin(pin.aba(pm, pd, to_pin(q), to_pin(v), to_pin(tau)))

    return rnea, mass, aba


def _check_against_pinocchio(urdf_text: str, samples: np.ndarray) -> None:
    td = _tree(mechanism_from_text(urdf_text, path="robot.urdf"), gravity=G)
    names = [jk.name for jk in td.model.joints]
    rnea, mass, aba = _pinocchio(urdf_text, names)
    q, qd, qdd = samples[:, 0], samples[:, 1], samples[:, 2]
    tau = td.inverse(q, qd, qdd)  # batched over the samples
    M = td.mass_matrix(q)
    acc = td.forward(q, qd, tau)
    for i in range(len(q)):
        assert _close(tau[i], rnea(q[i], qd[i], qdd[i]), 1e-10)
        assert _close(M[i], mass(q[i]), 1e-10)
        assert _close(acc[i], aba(q[i], qd[i], tau[i]), 1e-10)
        assert _close(td.inverse(q[i], qd[i], qdd[i]), tau[i], 1e-13)  # one = batched


def test_ur5_against_pinocchio() -> None:
    rng = np.random.default_rng(43)
    _check_against_pinocchio(UR5.read_text(), rng.uniform(-3, 3, size=(20, 3, 6)))


@settings(max_examples=25, deadline=None)
@given(robot_trees())
def test_random_trees_against_pinocchio(tree: tuple[str, np.ndarray]) -> None:
    _check_against_pinocchio(*tree)


# ---------------------------------------------------------------- 50 digits, exact

PLANAR = """\
mechanism: planar
bodies: [ground, b1, b2, b3]
joints:
  - {name: J1, type: R, between: [ground, b1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [b1, b2], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: J3, type: R, between: [b2, b3], axis: [0, 0, 1], point: [17/10, 0, 0]}
inputs: [J1, J2, J3]
mass:
  b1: {kg: 2, centre: [1/2, 0, 0], inertia: [1/50, 1/6, 1/6, 0, 0, 0]}
  b2: {kg: 3/2, centre: [13/10, 0, 0], inertia: [1/40, 1/16, 1/16, 0, 0, 0]}
  b3: {kg: 1/2, centre: [21/10, 0, 0], inertia: [1/100, 1/48, 1/40, 0, 0, 0]}
gravity: [0, -981/100, 0]
"""


def _planar(n: int) -> tuple[object, PlanarArm]:
    """The 2R (first two links) or 3R arm of PLANAR, and the same arm for the Lagrangian:
    links 1 and 0.7 m, centres 0.5, 0.3 and 0.4 m from their joints, moments about z."""
    text = PLANAR
    if n == 2:
        text = "\n".join(
            line for line in text.splitlines() if "b3:" not in line and "J3," not in line
        )
        text = text.replace("[J1, J2, J3]", "[J1, J2]").replace(", b2, b3]", ", b2]") + "\n"
    f = mpmath.mpf
    arm = PlanarArm(
        [1, f(7) / 10, 1][:n],
        [2, f(3) / 2, f(1) / 2][:n],
        [f(1) / 2, f(3) / 10, f(2) / 5][:n],
        [f(1) / 6, f(1) / 16, f(1) / 40][:n],
        gravity=(0, -f(981) / 100),
    )
    return loads(text, path="planar.yaml"), arm


MOTIONS = [
    (["3/10", "9/10", "-1/2"], ["1", "-2", "1/2"], ["1/2", "3", "-1"]),
    (["-2", "1/7", "3"], ["5/3", "0", "-2"], ["0", "-1/3", "2"]),
]


@pytest.mark.parametrize("n", [2, 3])
def test_planar_arms_at_50_digits_against_the_lagrangian(n: int) -> None:
    with mpmath.workdps(50):
        mech, arm = _planar(n)
        td = _tree(mech, "mp:50")
        tol = mpmath.mpf("1e-40")
        for motion in MOTIONS:
            q, qd, qdd = ([mpmath.mpf(sympy.Rational(x)) for x in v[:n]] for v in motion)
            with td.model.precision.context():
                Q, Qd, Qdd = (td.model.asarray(v) for v in (q, qd, qdd))
                got = td.inverse(Q, Qd, Qdd)
                M = td.mass_matrix(Q)
                acc = td.forward(Q, Qd, got)
                T = td.kinetic_energy(Q, Qd)
            want = arm.efforts(q, qd, qdd)
            Mref = arm.mass_matrix(q)
            for i in range(n):
                assert abs(got[i] - want[i]) <= tol * max(1, abs(want[i]))
                assert abs(acc[i] - qdd[i]) <= tol * max(1, abs(qdd[i]))
                for j in range(n):
                    assert abs(M[i, j] - Mref[i, j]) <= tol * max(1, abs(Mref[i, j]))
            Tref = arm.kinetic_energy(q, qd)
            assert abs(T - Tref) <= tol * max(1, abs(Tref))


def test_planar_2r_in_exact_arithmetic_is_the_lagrangian() -> None:
    """At q = (0, pi/2) every number is rational: mechsing's exact efforts against the
    Lagrangian evaluated at 60 digits."""
    with mpmath.workdps(60):
        mech, arm = _planar(2)
    td = _tree(mech, "exact")
    with td.model.precision.context():
        q = td.model.asarray([0, sympy.pi / 2])
        qd = td.model.asarray([1, -2])
        qdd = td.model.asarray([sympy.Rational(1, 2), 3])
        tau = td.inverse(q, qd, qdd)
        acc = td.forward(q, qd, tau)
    assert all(isinstance(x, sympy.Rational) for x in tau)
    assert list(acc) == [sympy.Rational(1, 2), 3]
    with mpmath.workdps(60):
        want = arm.efforts([0, mpmath.pi / 2], [1, -2], [mpmath.mpf(1) / 2, 3])
        for x, y in zip(tau, want, strict=True):
            assert abs(mpmath.mpf(sympy.N(x, 70)) - y) < mpmath.mpf("1e-55")


# ---------------------------------------------------------------- energy

ARM7 = (
    """\
<robot name="arm7">
  <link name="base"/>
"""
    + "".join(
        f"""  <link name="a{i}"><inertial><origin xyz="{0.02 * i} {0.01 * (-1) ** i} 0.12" rpy="{0.3 * i} 0 {0.1 * i}"/>
    <mass value="{3.5 - 0.4 * i}"/><inertia ixx="{0.03 - 0.003 * i}" iyy="{0.025 - 0.002 * i}" izz="{0.012 - 0.001 * i}" ixy="0.001" ixz="0" iyz="-0.0005"/></inertial></link>
  <joint name="q{i + 1}" type="revolute"><parent link="{"base" if i == 0 else f"a{i - 1}"}"/><child link="a{i}"/>
    <origin xyz="0 {0.05 * (i % 2)} {0.0 if i == 0 else 0.25}" rpy="{1.5707963267948966 * (-1) ** i} 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
"""
        for i in range(7)
    )
    + "</robot>\n"
)


@pytest.mark.parametrize("which", ["ur5", "arm7"])
def test_zero_efforts_without_gravity_keep_the_kinetic_energy(which: str) -> None:
    from scipy.integrate import solve_ivp

    mech = read_mechanism(UR5) if which == "ur5" else mechanism_from_text(ARM7, path="arm7.urdf")
    td = _tree(mech, gravity=(0, 0, 0))
    n = td.n
    rng = np.random.default_rng(7)
    q0, qd0 = rng.uniform(-1.5, 1.5, n), rng.uniform(-1.5, 1.5, n)
    zero = np.zeros(n)

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        return np.concatenate([y[n:], td.forward(y[:n], y[n:], zero)])

    sol = solve_ivp(rhs, (0, 1), np.concatenate([q0, qd0]), method="DOP853", rtol=1e-13, atol=1e-13)
    assert sol.success
    T0 = float(td.kinetic_energy(q0, qd0))
    T1 = float(td.kinetic_energy(sol.y[:n, -1], sol.y[n:, -1]))
    assert abs(T1 - T0) <= 1e-9 * T0
    # and the motion is not trivial: the joints moved
    assert np.abs(sol.y[:n, -1] - q0).max() > 0.1


# ---------------------------------------------------------------- refusals


def test_closed_chains_and_joints_of_several_coordinates_are_refused() -> None:
    four = read_mechanism(ROOT / "examples" / "fourbar.yaml")
    with pytest.raises(UserError, match="closed loop"):
        _tree(four)
    text = PLANAR.replace(
        "type: R, between: [b1, b2], axis: [0, 0, 1]", "type: S, between: [b1, b2]"
    )
    with pytest.raises(UserError, match="joint 'J2' is S"):
        _tree(loads(text, path="s.yaml"))
    massless = "\n".join(
        line for line in PLANAR.splitlines() if not line.startswith(("mass", "  b", "grav"))
    )
    with pytest.raises(UserError, match="gives no masses"):
        _tree(loads(massless + "\n", path="m.yaml"))


def test_a_joint_that_moves_no_mass_makes_the_mass_matrix_singular() -> None:
    text = PLANAR.replace(
        "  b3: {kg: 1/2, centre: [21/10, 0, 0], inertia: [1/100, 1/48, 1/40, 0, 0, 0]}\n", ""
    )
    td = _tree(loads(text, path="p.yaml"))
    with pytest.raises(UserError, match="J3 moves no mass"):
        td.forward(np.zeros(3), np.zeros(3), np.zeros(3))
