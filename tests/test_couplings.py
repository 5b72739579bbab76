"""The ``couplings`` key (a URDF mimic): read in the file's units, checked, and modelled
by the analysis as one constraint of the closure system (q_f = m q_l + c: the row
dq_f - m dq_l = 0), with answers derived by hand.

Planar 3R (links l1, l2, l3 along x, axes z) with joint C = m x joint B (m = 1): the tip
p moves with the two columns z x p and z x (p - a2) + z x (p - a3) of the leader rates
(dA, dB).  With theta1 = 0 and theta2 = theta3 = t, det[p, (p - a2) + (p - a3)] =
l1 l2 sin t + 2 l1 l3 sin 2t + l2 l3 sin t = sin t (l1 l2 + l2 l3 + 4 l1 l3 cos t): for
(1, 1, 0.5) the coupled chain is singular at t = 0, pi and cos t = -3/4, where the
uncoupled 3R (three columns) keeps rank 2.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import sympy

from mechsing.kinematics import KinematicModel
from mechsing.kinematics.closure import Closer
from mechsing.model import MechanismError, loads
from mechsing.screws import closure_system
from tests.cli import ROOT, cli_json, run_cli

HEAD = """
units: {length: mm, angle: deg}
bodies: [g, a, b, c]
joints:
  - {name: S, type: P, between: [g, a], axis: [1, 0, 0]}
  - {name: B, type: R, between: [a, b], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: T, type: S, between: [b, c], point: [1, 0, 0]}
"""


def test_a_coupling_is_read_in_the_files_units() -> None:
    mech = loads(HEAD + "couplings:\n  - {joint: B, leader: S, multiplier: 2, offset: 10}\n")
    (c,) = mech.couplings
    assert (c.joint, c.leader, c.line) == ("B", "S", 9)
    # B [deg] = 2 S [mm] + 10 deg  <=>  B [rad] = 2 (pi/180) / (1/1000) S [m] + 10 pi/180
    assert sympy.simplify(c.multiplier - 2 * (sympy.pi / 180) * 1000) == 0
    assert sympy.simplify(c.offset - 10 * sympy.pi / 180) == 0


@pytest.mark.parametrize(
    ("entry", "words"),
    [
        ("{joint: B, leader: Q}", "unknown joint 'Q'"),
        ("{joint: B, leader: B}", "coupled to itself"),
        ("{joint: T, leader: B}", "has 3 coordinates"),
        ("{joint: B, leader: S, gain: 2}", "unknown key 'gain'"),
        ("{joint: B}", "missing key 'leader'"),
    ],
)
def test_a_bad_coupling_names_its_line(entry: str, words: str) -> None:
    with pytest.raises(MechanismError) as exc:
        loads(HEAD + f"couplings:\n  - {entry}\n")
    assert words in str(exc.value) and exc.value.line == 9


def test_a_joint_coupled_twice_is_refused() -> None:
    text = HEAD + "couplings:\n  - {joint: B, leader: S}\n  - {joint: B, leader: S}\n"
    with pytest.raises(MechanismError, match="already coupled"):
        loads(text)


def test_the_analysis_refuses_an_inconsistent_value_and_symbolic_conditions(tmp_path) -> None:
    f = tmp_path / "r3.yaml"
    f.write_text(_three_r("  bent: {A: 0.3, B: 0.7, C: 0.5}\n"))
    r = run_cli(["analyze", f, "--config", "bent"])
    assert r.status == 2 and "'C' = 0.5 rad" in r.err and "'B' = 0.7 rad" in r.err, r.err
    assert "C = 1 x B (coupling, line 9" in r.err and "Traceback" not in r.err
    r = run_cli(["condition", f])
    assert r.status == 2 and "symbolic conditions" in r.err and f"{f}:9:" in r.err, r.err


L1, L2, L3 = 1.0, 1.0, 0.5


def _three_r(configurations: str, coupled: bool = True) -> str:
    coupling = "couplings:\n  - {joint: C, leader: B, multiplier: 1}\n" if coupled else ""
    return f"""mechanism: planar 3R, C mimics B
units: {{length: m, angle: rad}}
bodies: [g, l1, l2, l3]
joints:
  - {{name: A, type: R, between: [g, l1], axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: B, type: R, between: [l1, l2], axis: [0, 0, 1], point: [{L1}, 0, 0]}}
  - {{name: C, type: R, between: [l2, l3], axis: [0, 0, 1], point: [{L1 + L2}, 0, 0]}}
{coupling}output: {{body: l3, point: [{L1 + L2 + L3}, 0, 0]}}
inputs: [A, B]
configurations:
{configurations}"""


def _planar_point_jacobian(t1: float, t2: float, t3: float) -> tuple[np.ndarray, np.ndarray]:
    """The tip and the planar 3R's point Jacobian (2 x 3) from the link lengths."""
    a = [np.zeros(2)]
    angle = 0.0
    for length, t in zip((L1, L2, L3), (t1, t2, t3), strict=True):
        angle += t
        a.append(a[-1] + length * np.array([math.cos(angle), math.sin(angle)]))
    p = a[3]
    J = np.array([[-(p - a[i])[1], (p - a[i])[0]] for i in range(3)]).T
    return p, J


def test_a_coupled_serial_3r_has_mobility_2_and_its_kernel_follows_the_coupling() -> None:
    mech = loads(_three_r("  bent: {A: 0.3, B: 0.7}\n"))
    model = KinematicModel(mech, "float")
    q = Closer(model).solve("bent").q
    assert q.tolist() == pytest.approx([0.3, 0.7, 0.7], abs=1e-15)  # C follows B
    cs = closure_system(model, q)
    assert cs.nullity == 2 and cs.couplings == 1
    N = np.array([model.float_frame.rates_back(v) for v in np.asarray(cs.rank.null_space).T])
    assert np.allclose(N[:, 2], 1 * N[:, 1], atol=1e-14)  # dC = m dB
    # the tip's velocity from the model's screws is J (dA, dB, m dB)
    p, J = _planar_point_jacobian(0.3, 0.7, 0.7)
    S = model.current_screws(q)
    x = np.array([p[0], p[1], 0.0])
    for dq in N:
        tw = S @ dq
        v = tw[3:] + np.cross(tw[:3], x)
        assert np.allclose(v[:2], J @ np.array([dq[0], dq[1], 1 * dq[1]]), atol=1e-12)


@pytest.mark.parametrize(
    ("t", "singular"),
    [(0.0, True), (math.acos(-0.75), True), (1.0, False), (2.5, False)],
)
def test_the_coupled_chain_is_singular_where_its_two_columns_align(
    t: float, singular: bool, tmp_path: Path
) -> None:
    cfg = f"  here: {{A: 0.2, B: {t!r}}}\n"
    f = tmp_path / "r3.yaml"
    f.write_text(_three_r(cfg))
    doc = cli_json(["analyze", f, "--config", "here", "--format", "json"])
    (c,) = doc["configurations"]
    m = c["mobility"]
    assert (m["finite"], m["instantaneous"], m["grubler"], m["group"]) == (2, 2, 2, 2)
    assert c["joints"]["C"] == pytest.approx([t], abs=1e-15)
    _, J = _planar_point_jacobian(0.2, t, t)
    Jc = np.column_stack([J[:, 0], J[:, 1] + 1 * J[:, 2]])
    det = np.linalg.det(Jc)
    # the closed form sin t (l1 l2 + l2 l3 + 4 l1 l3 cos t)
    assert det == pytest.approx(math.sin(t) * (L1 * L2 + L2 * L3 + 4 * L1 * L3 * math.cos(t)))
    classes = {s["class"] for s in c["singularities"]}
    assert ("serial" in classes) is singular, c["singularities"]
    assert doc["couplings"] == [
        {
            "joint": "C",
            "leader": "B",
            "multiplier": 1.0,
            "offset": 0.0,
            "line": 9,
            "source_line": None,
            "rows": 1,
        }
    ]
    if t == math.acos(-0.75):
        # the uncoupled 3R at the same angles keeps rank 2: the coupling made it singular
        f.write_text(_three_r(f"  here: {{A: 0.2, B: {t!r}, C: {t!r}}}\n", coupled=False))
        (c,) = cli_json(["analyze", f, "--config", "here", "--format", "json"])["configurations"]
        assert c["mobility"]["finite"] == 3 and not c["singularities"]


GRIPPER = """mechanism: 2R arm with a two-finger gripper
units: {length: m, angle: rad}
bodies: [g, upper, hand, fa, fb]
joints:
  - {name: shoulder, type: R, between: [g, upper], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: elbow, type: R, between: [upper, hand], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: fa_slide, type: P, between: [hand, fa], axis: [0, 1, 0]}
  - {name: fb_slide, type: P, between: [hand, fb], axis: [0, 1, 0]}
couplings:
  - {joint: fb_slide, leader: fa_slide, multiplier: -1}
configurations:
  open: {shoulder: 0.4, elbow: -0.9, fa_slide: 0.02}
"""


def test_a_gripper_with_a_mimic_on_a_2r_arm_is_analysed_whole_with_mobility_3(
    tmp_path: Path,
) -> None:
    f = tmp_path / "gripper.yaml"
    f.write_text(GRIPPER)
    doc = cli_json(["analyze", f, "--format", "json"])
    for c in doc["configurations"]:
        m = c["mobility"]
        # arm 2 + gripper 1: four joint coordinates, one coupling
        assert (m["finite"], m["instantaneous"], m["grubler"]) == (3, 3, 3), c["name"]
        assert c["closure_rank"] == {**c["closure_rank"], "rank": 1, "nullity": 3}
    open_ = next(c for c in doc["configurations"] if c["name"] == "open")
    assert open_["joints"]["fb_slide"] == pytest.approx([-0.02], abs=1e-15)
    r = run_cli(["analyze", f, "--config", "open"])
    assert "coupling fb_slide = -1 x fa_slide (coupling, line 10): one row" in r.out, r.out
    html = tmp_path / "gripper.html"
    r = run_cli(["report", f, "-o", html])
    assert r.status == 0, r.err
    assert "fb_slide = -1 x fa_slide (coupling, line 10; SI, radians): one row" in html.read_text()


def test_the_two_arm_robot_is_analysed_whole_with_its_mimic() -> None:
    urdf = ROOT / "tests" / "data" / "two_arm_mimic.urdf"
    line = next(i for i, t in enumerate(urdf.read_text().splitlines(), 1) if "<mimic" in t)
    doc = cli_json(
        ["analyze", urdf, "--format", "json", "--set", "r_finger_a_slide=0.03", "--config", "cli"]
    )
    (c,) = doc["configurations"]
    # seven one-dof joints (head, two 2R arms, two fingers), one coupling
    assert c["mobility"]["finite"] == 6 and c["mobility"]["grubler"] == 6
    assert c["joints"]["r_finger_b_slide"] == pytest.approx([-0.03], abs=1e-15)
    (cp,) = doc["couplings"]
    assert (cp["joint"], cp["leader"], cp["multiplier"], cp["source_line"]) == (
        "r_finger_b_slide",
        "r_finger_a_slide",
        -1.0,
        line,
    )
    r = run_cli(["analyze", urdf])
    assert r.status == 0, r.err
    assert f"coupling r_finger_b_slide = -1 x r_finger_a_slide (<mimic>, line {line})" in r.out


def _five_bar(coupled: bool) -> str:
    """examples/five_bar.yaml (symmetric: A1 at (-3/2, 0), A2 at (3/2, 0)), its two
    inputs geared as A2 = -A1 when ``coupled`` (inputs: [A1])."""
    text = (ROOT / "examples" / "five_bar.yaml").read_text()
    head, _, _ = text.partition("configurations:")
    if coupled:
        head = head.replace(
            "inputs: [A1, A2]",
            "inputs: [A1]\ncouplings:\n  - {joint: A2, leader: A1, multiplier: -1}",
        )
        values = "  geared: {A1: 0.3}\n"
    else:
        values = "  geared: {A1: 0.3, A2: -0.3}\n"
    type2 = next(ln for ln in text.splitlines() if ln.strip().startswith("type2:"))
    return head + "configurations:\n" + values + type2 + "\n"


def test_a_coupling_inside_a_loop_is_closed_by_newton_with_the_loop(tmp_path: Path) -> None:
    # the symmetric five-bar with A2 = -A1: one degree of freedom; its closure is the
    # two-input five-bar's at (A1, -A1); at type2 (the distal links collinear, A2 = -A1 =
    # -pi/6) locking A1 locks A2, and the output still moves: an output singularity
    f, g = tmp_path / "geared.yaml", tmp_path / "free.yaml"
    f.write_text(_five_bar(True))
    g.write_text(_five_bar(False))
    for precision in ("float", "mp:30"):
        doc = cli_json(["analyze", f, "--format", "json", "--precision", precision])
        by = {c["name"]: c for c in doc["configurations"]}
        free = cli_json(["analyze", g, "--format", "json", "--config", "geared"])
        (ref,) = free["configurations"]
        for j, v in ref["joints"].items():
            assert by["geared"]["joints"][j] == pytest.approx(v, abs=1e-12), j
        for c in by.values():
            assert c["mobility"]["finite"] == 1 and c["mobility"]["instantaneous"] == 1
        assert not by["geared"]["singularities"]
        assert "output" in {s["class"] for s in by["type2"]["singularities"]}
        for s in by["type2"]["singularities"]:
            rates = s.get("joint_rates")
            if rates:  # joint rates in file order A1, B1, P, B2, A2: A2 = -A1
                assert rates[4] == pytest.approx(-rates[0], abs=1e-12), s


def test_the_chain_scanner_refuses_a_coupling_naming_it() -> None:
    from mechsing.sweeps.scan import ChainScanner

    with pytest.raises(MechanismError) as exc:
        ChainScanner(loads(_three_r("  bent: {A: 0.3, B: 0.7}\n")))
    assert exc.value.line == 9 and "the chain scanner" in str(exc.value)
    assert "'C' is coupled to joint 'B'" in str(exc.value)


def test_a_sweep_of_the_leader_locates_the_coupled_chains_singularity(tmp_path: Path) -> None:
    from mechsing.sweeps import sweep

    # B (and C with it) from 0.2 to 3 rad, A held: the closed form's root cos t = -3/4
    f = tmp_path / "r3.yaml"
    f.write_text(_three_r("  start: {A: 0.2, B: 0.2}\n"))
    r = sweep(f, ["B=0.2:3:0.1"], "start")
    assert r.reached.all() and r.held == ("A",)
    (p,) = r.located
    assert p.values[0] == pytest.approx(math.acos(-0.75), abs=1e-9)
    assert "serial" in (p.classes or ())


def test_a_coupling_in_degrees_with_an_offset_and_the_reference(tmp_path: Path) -> None:
    # B [deg] = 2 A [deg] + 10 deg: A = 20 deg gives B = 50 deg; the reference puts B at
    # its offset, 10 deg; both joints swept together are refused
    f = tmp_path / "deg.yaml"
    f.write_text(
        _three_r("  reference: {}\n  twenty: {A: 20}\n")
        .replace("angle: rad", "angle: deg")
        .replace(
            "{joint: C, leader: B, multiplier: 1}",
            "{joint: B, leader: A, multiplier: 2, offset: 10}",
        )
        .replace("inputs: [A, B]", "inputs: [A, C]")
    )
    doc = cli_json(["analyze", f, "--format", "json"])
    by = {c["name"]: c for c in doc["configurations"]}
    assert by["twenty"]["joints"]["B"] == pytest.approx([math.radians(50)], abs=1e-15)
    assert by["reference"]["joints"]["B"] == pytest.approx([math.radians(10)], abs=1e-15)
    assert by["reference"]["joints"]["A"] == [0.0]
    assert doc["couplings"][0]["offset"] == pytest.approx(math.radians(10), abs=1e-15)
    r = run_cli(["sweep", f, "--vary", "A=0:10:5", "--vary", "B=0:10:5"])
    assert r.status == 2 and "sweep one of them, the other follows" in r.err, r.err


def test_exact_mode_proves_the_coupled_chains_singularity(tmp_path: Path) -> None:
    # the root cos t = -3/4 given exactly: the folded chain's rank 1 is decided exactly
    f = tmp_path / "r3.yaml"
    f.write_text(_three_r('  exs: {A: "pi/6", B: "acos(-3/4)"}\n  ex: {A: "pi/6", B: "pi/3"}\n'))
    doc = cli_json(["analyze", f, "--format", "json", "--precision", "exact"])
    by = {c["name"]: c for c in doc["configurations"]}
    assert {s["class"] for s in by["exs"]["singularities"]} == {"serial"}
    assert not by["ex"]["singularities"]
    for c in by.values():
        assert c["mobility"]["finite"] == 2 and c["precision"] == "exact"
