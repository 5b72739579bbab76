"""A timed motion along a sweep's path (``sweep --duration``, mechsing.kinetics.timed,
issue 43): the efforts against Pinocchio's RNEA for a UR5 joint sweep, against the statics
of two-force members for a five-bar whose point mass crosses its Type II singularity
(tests/reference/fivebar_point.py), the crossing condition against its closed form
(bounded when the law's acceleration vanishes at the crossing, 1/distance growth
otherwise), the JSON against the sweep schema, the report's section and the refusals."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import mechsing
from mechsing.model import loads
from tests.cli import ROOT, CliRun, run_cli
from tests.reference.fivebar_point import torques
from tests.reference.timelaw import law

UR5 = ROOT / "examples" / "ur5.urdf"
R3 = math.sqrt(3)
#: the five-bar of examples/five_bar.yaml with one point mass of 2 kg at P
FIVE_BAR = (
    (ROOT / "examples" / "five_bar.yaml")
    .read_text()
    .replace(
        "configurations:",
        "mass:\n  dist1: {kg: 2, centre: [0, 4, 0], inertia: [0, 0, 0, 0, 0, 0]}\nconfigurations:",
    )
)


def _five_bar() -> object:
    return loads(FIVE_BAR, path="five_bar_mass.yaml")


def _timed(y0: float, y1: float, n: int, T: float = 2.0) -> object:
    """The five-bar's point P moved up the line x = 0 from y0 to y1 in n samples."""
    step = (y1 - y0) / (n - 1)
    res = mechsing.sweep(
        _five_bar(), f"pose.y={y0!r}:{y1 + step / 2!r}:{step!r}", "type2", "float", duration=T
    )
    assert res.reached.all()
    return res


def test_ur5_joint_sweep_efforts_are_pinocchio_rnea() -> None:
    pin = pytest.importorskip("pinocchio")
    pm = pin.buildModelFromXML(UR5.read_text())
    pm.gravity.linear = np.zeros(3)  # a URDF gives no gravity: none in the sweep either
    pd = pm.createData()
    names = [f"joint{i}" for i in range(1, 7)]
    order = [pm.joints[pm.getJointId(n)].idx_q for n in names]
    res = mechsing.sweep(UR5, "joint2=-2:0:0.05", duration=1.5)
    dy = res.dynamics
    assert dy.names == tuple(names)
    values = res.variables[0].values
    v0, v1 = float(values[0]), float(values[-1])  # the law runs from the first to the last
    assert abs(v0 + 2) <= 1e-15 and abs(v1) <= 1e-15
    for k, s in enumerate(values):
        _, sd, sdd = law(float(s), v0, v1, 1.5)
        x = dy.times[k] / 1.5  # the time is where the law is at s (ill-conditioned at the ends)
        assert abs(v0 + (v1 - v0) * x**3 * (10 - 15 * x + 6 * x**2) - s) <= 1e-12
        q, v, a = np.zeros(6), np.zeros(6), np.zeros(6)
        q[order[1]], v[order[1]], a[order[1]] = s, sd, sdd
        want = np.asarray(pin.rnea(pm, pd, q, v, a))[order]
        assert np.linalg.norm(dy.efforts[k] - want) <= 1e-10 * max(1.0, np.linalg.norm(want))


@pytest.mark.parametrize("above", [0.5, 0.7])
def test_five_bar_efforts_through_type_ii_are_the_two_force_statics(above: float) -> None:
    """P moves on x = 0 from sqrt 3 - 0.5 to sqrt 3 + above: the inputs' torques at every
    sample (but one at the singularity itself, where they are not unique) are the
    reference's."""
    y0, y1 = R3 - 0.5, R3 + above
    res = _timed(y0, y1, 51 if above == 0.5 else 61)
    dy = res.dynamics
    assert dy.names == ("A1", "A2")
    for k, y in enumerate(res.variables[0].values):
        if abs(y - R3) < 1e-6:
            continue
        want = torques(float(y), 2.0, y0, y1, 2.0)
        assert np.max(np.abs(dy.efforts[k] - want)) <= 1e-9 * max(1.0, np.max(np.abs(want)))


def test_five_bar_crossing_condition_is_its_closed_form() -> None:
    """With the mass at P alone, the dynamic wrench is m a_P and the uncontrolled twist
    moves P across the aligned distal links (vertically): the crossing is possible iff
    y'' = 0 there, i.e. iff sqrt 3 is the middle of the quintic law's range."""
    for y0, y1, n in ((R3 - 0.5, R3 + 0.5, 51), (R3 - 0.5, R3 + 0.7, 61)):
        res = _timed(y0, y1, n)
        (c,) = res.dynamics.crossings
        assert abs(c.values[0] - R3) <= 1e-10
        _, _, ydd = law(R3, y0, y1, 2.0)
        closed_form = abs(ydd) <= 1e-12
        assert c.possible == closed_form
        if closed_form:
            assert c.residual <= 1e-12
        else:
            # the residual is |v . tau| / max |tau|: here m |y''| over the largest |m a_P|
            assert c.residual > 1e-3


def test_five_bar_efforts_bounded_when_the_condition_holds_else_one_over_distance() -> None:
    """Fine samples near the Type II point: with the law centred on it the torques stay
    at their size away from it; off centre |tau| * distance tends to a constant."""
    near = []
    for y0, y1 in ((R3 - 0.1, R3 + 0.1), (R3 - 0.1, R3 + 0.3)):
        n = int(round((y1 - y0) / 0.002)) + 1
        res = _timed(y0, y1, n)
        y = res.variables[0].values
        d = np.abs(y - R3)
        size = np.max(np.abs(res.dynamics.efforts), axis=1)
        near.append((d, size))
    d, size = near[0]
    close, far = (d > 1e-6) & (d < 0.01), (d > 0.05) & (d < 0.1)
    assert np.max(size[close]) <= 2 * np.max(size[far])
    d, size = near[1]
    signed = (np.arange(len(d)) - int(np.argmin(d))).astype(float)
    for side in (-1, 1):
        # the nearest two samples on this side (2 and 4 mm away): log-log slope -1
        k = [int(np.argmin(np.where((signed * side > 0) & (d > 1e-6), d, np.inf)))]
        k.append(k[0] + side)
        slope = np.log(size[k[1]] / size[k[0]]) / np.log(d[k[1]] / d[k[0]])
        assert abs(slope + 1) <= 0.1, (side, slope)
    assert np.max(size[d > 1e-6]) >= 50 * np.median(size)


def test_sweep_duration_json_follows_the_schema(tmp_path) -> None:  # type: ignore[no-untyped-def]
    jsonschema = pytest.importorskip("jsonschema")
    from mechsing.sweeps.schema import sweep_schema

    f = tmp_path / "five_bar_mass.yaml"
    f.write_text(FIVE_BAR)
    y0, y1 = R3 - 0.5, R3 + 0.7

    def timed(*fmt: str) -> CliRun:
        """The five-bar's timed sweep through its Type II, in the format ``fmt`` gives."""
        vary = f"pose.y={y0!r}:{y1!r}:0.02"
        argv = ["sweep", f, "--vary", vary, "--from", "type2", "--duration", "2"]
        return run_cli([*argv, *fmt, "--precision", "float"])

    rc, out, err = timed("--format", "json")
    assert rc == 0, err
    doc = json.loads(out)
    jsonschema.Draft202012Validator(sweep_schema()).validate(doc)
    assert doc["timed"]["duration"] == 2 and doc["timed"]["efforts_of"] == ["A1", "A2"]
    assert doc["points"][0]["time"] == 0
    assert doc["points"][-1]["time"] <= 2
    (c,) = doc["type_ii_crossings"]
    assert c["possible"] is False and c["values"][0] == pytest.approx(R3, abs=1e-10)
    rc, out, err = timed()
    assert rc == 0 and "Type II crossing at pose.y = 1.732050808 m" in out
    assert "not possible" in out


def test_report_shows_the_efforts_along_the_timed_sweep(tmp_path) -> None:  # type: ignore[no-untyped-def]
    out = tmp_path / "ur5.html"
    rc, _, err = run_cli(
        [
            "report",
            UR5,
            "--vary",
            "joint2=-2:0:0.1",
            "--duration",
            "1.5",
            "-o",
            out,
            "--precision",
            "float",
        ]
    )
    assert rc == 0, err
    html = out.read_text()
    assert "Dynamics along the sweep" in html and "efforts along the timed sweep" in html
    assert "--duration 1.5" in html


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (
            ["--vary", "joint2=-1:0:0.5", "--vary", "joint3=-1:0:0.5", "--duration", "1"],
            "not one motion in time",
        ),
    ],
)
def test_duration_refusals_say_why(argv: list[str], words: str) -> None:
    rc, _, err = run_cli(["sweep", UR5, *argv])
    assert rc == 2 and words in err, err


def test_duration_must_be_positive() -> None:
    with pytest.raises(mechsing.errors.UserError, match="positive number of seconds"):
        mechsing.sweep(UR5, "joint2=-1:0:0.5", duration=0.0)
    with pytest.raises(SystemExit) as stop:  # argparse's own check, before the file is read
        run_cli(["sweep", UR5, "--vary", "joint2=-1:0:0.5", "--duration", "-1"])
    assert stop.value.code == 2


def test_duration_needs_masses() -> None:
    rc, _, err = run_cli(
        ["sweep", ROOT / "examples" / "five_bar.yaml", "--vary", "A1=0:0.2:0.1", "--duration", "1"]
    )
    assert rc == 2 and "gives no masses" in err, err


#: a regular start of the UR5 (at the drawn pose the wrist is singular: rates not unique)
UR5_START = {"joint1": 0.3, "joint2": -1.0, "joint3": 1.2, "joint4": -0.8, "joint5": 0.9}


def _ur5_pose_sweep(vary: object, target: object) -> None:
    """A pose sweep of the UR5 from UR5_START against pinocchio.rnea: ``vary(x0, r0)`` the
    --vary text from the start's tool point x0 and rotation vector r0 (of the output
    link's rotation from its drawn one, pin.log3), ``target(s, sd, sdd, r0)`` the tool's
    angular velocity and acceleration (ground axes) and its point's velocity and
    acceleration at the swept value s.  The joints' rates and accelerations from
    Pinocchio's frame Jacobian and the drift of the frame's classical acceleration."""
    pin = pytest.importorskip("pinocchio")
    from mechsing.adhoc import with_set_values

    mech = mechsing.load(UR5)
    pm = pin.buildModelFromXML(UR5.read_text())
    pm.gravity.linear = np.zeros(3)
    pd = pm.createData()
    names = [f"joint{i}" for i in range(1, 7)]
    order = [pm.joints[pm.getJointId(n)].idx_q for n in names]
    frame = pm.getFrameId(mech.output.body)
    pin.framesForwardKinematics(pm, pd, np.zeros(6))  # the drawn pose: every joint at 0
    drawn = pd.oMf[frame].rotation.copy()
    c0 = np.array([float(x) for x in mech.output_reference_point()])
    local = pd.oMf[frame].actInv(c0)  # the point in the output link's frame
    mech = with_set_values(mech, [f"{j}={v}" for j, v in UR5_START.items()], None, str(UR5))
    q0 = np.zeros(6)
    q0[[order[names.index(j)] for j in UR5_START]] = list(UR5_START.values())
    pin.framesForwardKinematics(pm, pd, q0)
    x0 = pd.oMf[frame].act(local)
    r0 = pin.log3(pd.oMf[frame].rotation @ drawn.T)
    res = mechsing.sweep(mech, vary(x0, r0), "cli", duration=1.5)
    assert res.reached.all()
    dy = res.dynamics
    values = res.variables[0].values
    frame_type = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    for k, s in enumerate(values):
        _, sd, sdd = law(float(s), float(values[0]), float(values[-1]), 1.5)
        q = np.empty(6)
        q[order] = dy.joints[k]
        pin.computeJointJacobians(pm, pd, q)
        pin.framesForwardKinematics(pm, pd, q)
        J = pin.getFrameJacobian(pm, pd, frame, frame_type)  # (v of the frame's origin, w)
        r = pd.oMf[frame].rotation @ local
        Jp = np.vstack([J[3:], J[:3] - np.cross(r, J[3:].T).T])  # (w, v of the point)
        velocity, acceleration = target(float(s), sd, sdd, r0, pd.oMf[frame].rotation @ drawn.T)
        qd = np.linalg.solve(Jp, velocity)
        pin.forwardKinematics(pm, pd, q, qd, np.zeros(6))
        acc = pin.getFrameClassicalAcceleration(pm, pd, frame, frame_type)
        w = Jp[:3] @ qd
        drift = np.concatenate(
            [acc.angular, acc.linear + np.cross(acc.angular, r) + np.cross(w, np.cross(w, r))]
        )
        qdd = np.linalg.solve(Jp, acceleration - drift)
        want = np.asarray(pin.rnea(pm, pd, q, qd, qdd))[order]
        assert np.linalg.norm(dy.efforts[k] - want) <= 1e-9 * max(1.0, np.linalg.norm(want))


def test_ur5_straight_line_of_its_tool_point_efforts_are_pinocchio_rnea() -> None:
    """A pose sweep: the output's reference point moves along x, its rotation held."""

    def target(s, sd, sdd, r0, R):  # type: ignore[no-untyped-def]
        return np.array([0, 0, 0, sd, 0, 0]), np.array([0, 0, 0, sdd, 0, 0])

    _ur5_pose_sweep(
        lambda x0, r0: f"pose.x={float(x0[0]) - 0.1!r}:{float(x0[0]) + 0.1!r}:0.02", target
    )


def test_ur5_turn_of_its_tool_about_its_point_efforts_are_pinocchio_rnea() -> None:
    """A pose sweep of a rotation: the output link's rotation exp(r) from its drawn one,
    r = (s, r0_y, r0_z), about its tool point held.  Its angular velocity is
    exp(r) Jexp3(r) r' (Pinocchio's right Jacobian of exp: the body's, turned to the ground
    axes); the rate of that unit velocity along s by a fourth-order central difference."""
    pin = pytest.importorskip("pinocchio")

    def unit(s: float, r0: np.ndarray) -> np.ndarray:
        r = np.array([s, r0[1], r0[2]])
        return pin.exp3(r) @ pin.Jexp3(r) @ np.array([1.0, 0.0, 0.0])

    def target(s, sd, sdd, r0, R):  # type: ignore[no-untyped-def]
        # the sample's rotation is the law's: exp(s, r0_y, r0_z)
        assert np.allclose(pin.log3(R), [s, r0[1], r0[2]], rtol=0, atol=1e-12)
        h = 1e-4
        dw = 8 * (unit(s + h, r0) - unit(s - h, r0)) - (unit(s + 2 * h, r0) - unit(s - 2 * h, r0))
        dw /= 12 * h
        w = unit(s, r0)
        return np.concatenate([w * sd, np.zeros(3)]), np.concatenate(
            [w * sdd + dw * sd**2, np.zeros(3)]
        )

    _ur5_pose_sweep(
        lambda x0, r0: f"pose.rx={float(r0[0]) - 0.2!r}:{float(r0[0]) + 0.2!r}:0.05", target
    )
