"""Kinetostatics through the command line (issue 35): actuator efforts under a load,
checked against closed forms computed here from the reported joint values (leg lines,
Jacobians, velocity ratios), independently of mechsing's screws; the Type II case; the
transmission indices against the five-bar's transmission angles; scale invariance."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from tests.cli import ROOT, run_cli
from tests.mechanisms import PLANAR_2R_LOADED, scaled_text

EX = ROOT / "examples"


def _json(argv: list[str]) -> dict:
    r = run_cli(["analyze", *map(str, argv), "--format", "json", "--precision", "float"])
    assert r.status == 0, r.err
    return json.loads(r.out)


def _config(doc: dict, name: str) -> dict:
    return next(c for c in doc["configurations"] if c["name"] == name)


def _rot(a: float) -> np.ndarray:
    return np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])


def _cross2(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def test_planar_2r_torques_are_minus_jacobian_transpose_times_the_tip_force(tmp_path: Path) -> None:
    f = tmp_path / "r2.yaml"
    f.write_text(PLANAR_2R_LOADED)
    doc = _json([f, "--config", "bent"])
    c = _config(doc, "bent")
    a, b, l1, l2 = 0.3, 0.9, 1.0, 0.5
    J = np.array(
        [
            [-l1 * np.sin(a) - l2 * np.sin(a + b), -l2 * np.sin(a + b)],
            [l1 * np.cos(a) + l2 * np.cos(a + b), l2 * np.cos(a + b)],
        ]
    )
    tau = -J.T @ np.array([1.0, -2.0])
    assert c["efforts"]["A"] == pytest.approx(tau[0], rel=1e-12)
    assert c["efforts"]["B"] == pytest.approx(tau[1], rel=1e-12)
    ks = c["kinetostatics"]
    assert ks["bounded"] is True and ks["effort_units"] == {"A": "N m", "B": "N m"}
    # the load point moved with l2: the tip now
    tip = l1 * np.array([np.cos(a), np.sin(a)]) + l2 * np.array([np.cos(a + b), np.sin(a + b)])
    assert ks["load"]["point"][:2] == pytest.approx(tip, abs=1e-12)
    # the largest torque over unit tip forces: the norm of each row of J^T
    best = max(np.linalg.norm(J.T, axis=1))
    assert ks["largest_unit_efforts"]["force"]["N m"]["value"] == pytest.approx(best, rel=1e-12)
    # a unit couple on l2 needs 1 N m at each joint (minus the couple)
    assert ks["largest_unit_efforts"]["couple"]["N m"]["value"] == pytest.approx(1.0, rel=1e-12)


def test_load_on_the_command_line_replaces_the_file_load_and_the_text_says_it(
    tmp_path: Path,
) -> None:
    f = tmp_path / "r2.yaml"
    f.write_text(PLANAR_2R_LOADED)
    doc = _json([f, "--config", "straight", "--load", "moment=0,0,2"])
    # a couple M on the tip link: tau = -(M, M)
    assert _config(doc, "straight")["efforts"] == pytest.approx({"A": -2.0, "B": -2.0}, rel=1e-12)
    r = run_cli(["analyze", f, "--config", "bent", "--precision", "float"])
    assert "actuator efforts A 3.03457 N m, B 0.828377 N m" in r.out
    r = run_cli(["analyze", f, "--config", "bent", "--precision", "float", "--format", "md"])
    assert "- load on the output: force (1, -2, 0) N" in r.out


def test_slider_crank_crank_torque_for_a_piston_force() -> None:
    doc = _json(
        [EX / "slider_crank_crank_input.yaml", "--config", "crank-60", "--load", "force=-5,0,0"]
    )
    c = _config(doc, "crank-60")
    q = {k: v[0] for k, v in c["joints"].items()}
    # positions from the joint values: B on the crank, C on the slider (moved along x)
    B0, C0 = np.array([0.0, -1.0]), np.array([16 / 5, 7 / 5])
    B = _rot(q["A"]) @ B0
    C = C0 + np.array([q["P"], 0.0])
    # velocities for a unit crank rate: v_B = k x B; v_C = v_B + w3 k x (C - B) along x
    vB = np.array([-B[1], B[0]])
    r = C - B
    # unknowns w3, xdot: vB + w3 (-r_y, r_x) = (xdot, 0)
    M = np.array([[-r[1], -1.0], [r[0], 0.0]])
    w3, xdot = np.linalg.solve(M, -vB)
    # virtual work: tau * 1 + F * xdot = 0
    assert c["efforts"]["A"] == pytest.approx(5.0 * xdot, rel=1e-10)


def test_four_bar_input_torque_is_the_virtual_work_ratio() -> None:
    doc = _json([EX / "fourbar.yaml", "--config", "crank-30", "--load", "moment=0,0,3"])
    c = _config(doc, "crank-30")
    q = {k: v[0] for k, v in c["joints"].items()}
    A, B0, C0, D = (np.array(p, dtype=float) for p in ([0, 0], [1, 0], [3, 2], [4, 0]))
    B = _rot(q["A"]) @ B0
    C = D + _rot(-q["D"]) @ (C0 - D)  # D is between [rocker, ground]
    # unit crank rate: v_B + w3 k x (C - B) = w4 k x (C - D)
    vB = np.array([-B[1], B[0]])
    rc, rd = C - B, C - D
    M = np.array([[-rc[1], rd[1]], [rc[0], -rd[0]]])
    w3, w4 = np.linalg.solve(M, -vB)
    assert c["efforts"]["A"] == pytest.approx(-3.0 * w4, rel=1e-10)


def _rpr_lines(q: dict) -> tuple[list[np.ndarray], list[np.ndarray]]:
    A = [np.array([0.0, 0]), np.array([4.0, 0]), np.array([0.0, 4])]
    B0 = [np.array([0.9, 0.3]), np.array([2.5, 1.5]), np.array([-0.3, 1.9])]
    u0 = [np.array([0.9, 0.3]), np.array([-1.5, 1.5]), np.array([-0.3, -2.1])]
    pts, dirs = [], []
    for i in range(3):
        u = u0[i] / np.linalg.norm(u0[i])
        R = _rot(q[f"Rb{i + 1}"])
        pts.append(A[i] + R @ (B0[i] + q[f"P{i + 1}"] * u - A[i]))
        dirs.append(R @ u)
    return pts, dirs


def test_3rpr_leg_forces_balance_the_platform_wrench_along_three_leg_lines() -> None:
    doc = _json(
        [
            EX / "planar_3rpr.yaml",
            "--config",
            "stroke",
            "--load",
            "force=1,2,0 moment=0,0,0.5 point=1,1,0",
        ]
    )
    c = _config(doc, "stroke")
    q = {k: v[0] for k, v in c["joints"].items()}
    pts, dirs = _rpr_lines(q)
    # the load point (1, 1) moves with the platform: where the JSON says it is now
    p = np.array(c["kinetostatics"]["load"]["point"][:2])
    # the legs push the platform with tau_i along their lines: sum + load = 0 (planar)
    M = np.array([[d[0], d[1], _cross2(b, d)] for b, d in zip(pts, dirs, strict=True)]).T
    w = np.array([1.0, 2.0, 0.5 + _cross2(p, np.array([1.0, 2.0]))])
    tau = np.linalg.solve(M, -w)
    got = [c["efforts"][f"P{i}"] for i in (1, 2, 3)]
    assert got == pytest.approx(tau, rel=1e-10)
    assert c["kinetostatics"]["effort_units"]["P1"] == "N"
    # the largest leg force over unit forces through p: the largest row norm of
    # M^-1 [I; p x]; over unit couples: the largest |entry| of M^-1's last column
    Minv = np.linalg.inv(M)
    per_force = Minv @ np.array([[1.0, 0], [0, 1], [-p[1], p[0]]])
    largest = c["kinetostatics"]["largest_unit_efforts"]
    assert largest["force"]["N"]["value"] == pytest.approx(
        max(np.linalg.norm(per_force, axis=1)), rel=1e-10
    )
    assert largest["couple"]["N"]["value"] == pytest.approx(max(abs(Minv[:, 2])), rel=1e-10)


def test_3rpr_type2_efforts_unbounded_with_the_load_power_and_min_norm_for_zero_power() -> None:
    doc = _json([EX / "planar_3rpr.yaml", "--config", "concurrent", "--load", "moment=0,0,1"])
    ks = _config(doc, "concurrent")["kinetostatics"]
    assert _config(doc, "concurrent")["efforts"] is None and ks["bounded"] is False
    # the uncontrolled twist: a rotation about the legs' common point (1, 1) along z, on
    # which a couple of 1 N m does 1 W per unit rate
    (t,) = ks["uncontrolled_twists"]
    assert t == pytest.approx([0, 0, 1, 1, -1, 0], abs=1e-12)
    assert ks["load_power"] == pytest.approx([1.0], rel=1e-12)
    # a force through the common point does no power on it: bounded, not unique
    doc = _json(
        [EX / "planar_3rpr.yaml", "--config", "concurrent", "--load", "force=0,-3,0 point=1,1,0"]
    )
    c = _config(doc, "concurrent")
    ks = c["kinetostatics"]
    assert ks["bounded"] is True and set(ks["non_unique"]) == {"P1", "P2", "P3"}
    # every solution balances the force along the three lines through (1, 1); the
    # least-norm one is the pseudo-inverse solution of that 2 x 3 system
    q = {k: v[0] for k, v in c["joints"].items()}
    _, dirs = _rpr_lines(q)
    D = np.array(dirs).T
    tau = -np.linalg.pinv(D) @ np.array([0.0, -3.0])
    assert [c["efforts"][f"P{i}"] for i in (1, 2, 3)] == pytest.approx(tau, rel=1e-9)


def test_stewart_six_leg_forces_along_the_leg_lines() -> None:
    doc = _json(
        [
            EX / "stewart_octahedral.yaml",
            "--config",
            "reference",
            "--load",
            "force=1,-2,-10 moment=0.5,0,0.2",
        ]
    )
    c = _config(doc, "reference")
    s3 = np.sqrt(3)
    a = [
        (1, 0, 0),
        (-0.5, s3 / 2, 0),
        (-0.5, s3 / 2, 0),
        (-0.5, -s3 / 2, 0),
        (-0.5, -s3 / 2, 0),
        (1, 0, 0),
    ]
    b = [
        (0.3, 0.3 * s3, 1), (0.3, 0.3 * s3, 1), (-0.6, 0, 1),
        (-0.6, 0, 1), (0.3, -0.3 * s3, 1), (0.3, -0.3 * s3, 1),
    ]  # fmt: skip
    cols = []
    for ai, bi in zip(a, b, strict=True):
        u = np.subtract(bi, ai)
        u = u / np.linalg.norm(u)
        cols.append(np.concatenate([u, np.cross(bi, u)]))
    p = np.array(c["kinetostatics"]["load"]["point"])
    f = np.array([1.0, -2, -10])
    w = np.concatenate([f, np.array([0.5, 0, 0.2]) + np.cross(p, f)])
    tau = np.linalg.solve(np.array(cols).T, -w)
    assert [c["efforts"][f"P{i}"] for i in range(1, 7)] == pytest.approx(tau, rel=1e-10)
    # output index of leg i: the platform twist t_i with the other legs locked (no power
    # of their forces on it); the cosine between leg i's line and its S point's velocity
    W = np.array(cols)  # rows (u, b x u): power on (omega, v0) is (b x u).omega + u.v0
    T = np.linalg.solve(np.hstack([W[:, 3:], W[:, :3]]), np.eye(6))  # columns (omega, v0)
    want = []
    for i, bi in enumerate(b):
        om, v0 = T[:3, i], T[3:, i]
        vs = v0 + np.cross(om, bi)
        want.append(abs(W[i, :3] @ vs) / np.linalg.norm(vs))
    tr = c["kinetostatics"]["transmission"]
    assert tr["output"] == pytest.approx(want, rel=1e-9)
    assert tr["input"] == pytest.approx([1.0] * 6, rel=1e-12)


def _five_bar_angles(q: dict) -> tuple[float, float, float]:
    A1, B10, P0 = np.array([-1.5, 0]), np.array([-1.5, 2]), np.array([0.0, 4])
    A2, B20 = np.array([1.5, 0]), np.array([1.5, 2])
    B1 = A1 + _rot(q["A1"]) @ (B10 - A1)
    P = B1 + _rot(q["A1"] + q["B1"]) @ (P0 - B10)
    B2 = A2 + _rot(q["A2"]) @ (B20 - A2)

    def sin(u: np.ndarray, v: np.ndarray) -> float:
        return abs(_cross2(u, v)) / (np.linalg.norm(u) * np.linalg.norm(v))

    return sin(B1 - A1, P - B1), sin(B2 - A2, P - B2), sin(P - B1, P - B2)


def test_five_bar_transmission_indices_are_the_sines_of_its_transmission_angles() -> None:
    rng = np.random.default_rng(35)
    sets = []
    names = []
    for k in range(20):
        a1, a2 = (float(x) for x in rng.uniform(-0.5, 0.5, size=2))
        names.append(f"p{k}")
        sets += ["--set", f"p{k}:A1={a1!r}", "--set", f"p{k}:A2={a2!r}"]
    doc = _json(
        [
            EX / "five_bar.yaml",
            *sets,
            "--load",
            "force=0,-1,0",
            *[x for n in names for x in ("--config", n)],
        ]
    )
    for n in names:
        c = _config(doc, n)
        q = {k: v[0] for k, v in c["joints"].items()}
        s1, s2, s_out = _five_bar_angles(q)
        tr = c["kinetostatics"]["transmission"]
        assert tr["input"] == pytest.approx([s1, s2], rel=1e-9)
        assert tr["output"] == pytest.approx([s_out, s_out], rel=1e-9)
        assert tr["local"] == pytest.approx(min(s1, s2, s_out), rel=1e-9)


def test_transmission_indices_null_with_the_reason_outside_their_setting(tmp_path: Path) -> None:
    f = tmp_path / "r2.yaml"
    f.write_text(PLANAR_2R_LOADED)
    tr = _config(_json([f, "--config", "bent"]), "bent")["kinetostatics"]["transmission"]
    assert tr["local"] is None and "two legs" in tr["reason"]


def test_five_bar_output_index_is_zero_at_its_type2_and_input_index_at_its_type1() -> None:
    doc = _json(
        [EX / "five_bar.yaml", "--load", "force=0,-1,0", "--config", "type1", "--config", "type2"]
    )
    t2 = _config(doc, "type2")["kinetostatics"]["transmission"]
    assert t2["output"] == [0.0, 0.0]
    t1 = _config(doc, "type1")["kinetostatics"]["transmission"]
    assert min(t1["input"]) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("k", ["1000", "1/1000"])
def test_scaling_the_mechanism_scales_efforts_by_their_powers_and_not_the_indices(
    tmp_path: Path, k: str
) -> None:
    from fractions import Fraction

    s = float(Fraction(k))
    op = f"*{k}" if "/" not in k else f"/{k.split('/')[1]}"
    path = tmp_path / "five_bar_scaled.yaml"
    path.write_text(scaled_text(EX / "five_bar.yaml", op))
    load = "force=0.3,-1,0 point=0.2,3.5,0"
    base = _config(_json([EX / "five_bar.yaml", "--config", "inputs", "--load", load]), "inputs")
    scaled_load = f"force=0.3,-1,0 point={0.2 * s!r},{3.5 * s!r},0"
    got = _config(_json([path, "--config", "inputs", "--load", scaled_load]), "inputs")
    # revolute actuators: N m = N times a length, so times k; indices unchanged
    for j in ("A1", "A2"):
        assert got["efforts"][j] == pytest.approx(base["efforts"][j] * s, rel=1e-9)
    for key in ("input", "output"):
        assert got["kinetostatics"]["transmission"][key] == pytest.approx(
            base["kinetostatics"]["transmission"][key], rel=1e-9
        )
    base_u = base["kinetostatics"]["largest_unit_efforts"]
    got_u = got["kinetostatics"]["largest_unit_efforts"]
    assert got_u["force"]["N m"]["value"] == pytest.approx(
        base_u["force"]["N m"]["value"] * s, rel=1e-9
    )
    assert got_u["couple"]["N m"]["value"] == pytest.approx(
        base_u["couple"]["N m"]["value"], rel=1e-9
    )


def test_bad_load_option_names_the_fix() -> None:
    r = run_cli(["analyze", EX / "fourbar.yaml", "--load", "forse=1,2,3"])
    assert r.status == 2 and "KEY=x,y,z" in r.err and "force" in r.err
    r = run_cli(["analyze", EX / "fourbar.yaml", "--load", "force=1,2"])
    assert r.status == 2 and "needs 3 numbers" in r.err


def _approach(joint: str, value: str, held: str, ks: range) -> dict:
    """The five-bar analysed at ``joint = value + 10^-k`` (a passive or input angle that
    moves the configuration linearly towards a singularity), ``held`` fixed."""
    argv: list = [EX / "five_bar.yaml", "--load", "force=0.3,-1,0"]
    for k in ks:
        argv += ["--set", f"d{k}:{joint}={value}+{10.0**-k!r}", "--set", f"d{k}:{held}"]
        argv += ["--config", f"d{k}"]
    return _json(argv)


def test_largest_effort_grows_as_one_over_sigma_into_a_type2_and_the_output_index_vanishes() -> (
    None
):
    # the distal links' angle P -> 2 atan(4/3) with A2 = -pi/6: the type2 configuration
    doc = _approach("P", "2*atan(4/3)", "A2=-pi/6", range(1, 6))
    sig, eff, out = [], [], []
    for c in doc["configurations"]:
        (dec,) = [d for d in c["decisions"] if d.get("test") == "output"]
        sig.append(dec["margin"]["kept"])  # the output test's smallest singular value
        eff.append(max(abs(v) for v in c["efforts"].values()))
        out.append(max(c["kinetostatics"]["transmission"]["output"]))
    assert sig[0] / sig[-1] > 1e3  # more than three decades
    slope = np.polyfit(np.log(sig), np.log(eff), 1)[0]
    assert slope == pytest.approx(-1.0, rel=0.05)
    # the output index is the sine of the distal links' angle, which the path takes to 0
    assert out == pytest.approx([np.sin(10.0**-k) for k in range(1, 6)], rel=1e-6)


def test_input_index_vanishes_into_a_type1() -> None:
    # B1 -> 2 atan(1/3) with A2 = 0: the type1 configuration (A1, B1, P aligned)
    doc = _approach("B1", "2*atan(1/3)", "A2=0", range(1, 5))
    got = [c["kinetostatics"]["transmission"]["input"][0] for c in doc["configurations"]]
    # leg 1's input index is |sin| of the angle between crank and distal link: B1's offset
    assert got == pytest.approx([np.sin(10.0**-k) for k in range(1, 5)], rel=1e-6)


def _tau_a(a: float, b: float) -> float:
    """The 2R's shoulder torque for the tip force (1, -2): -(J^T f)[0]."""
    col = np.array([-np.sin(a) - 0.5 * np.sin(a + b), np.cos(a) + 0.5 * np.cos(a + b)])
    return -float(col @ np.array([1.0, -2.0]))


def test_sweep_load_gives_each_sample_its_efforts_and_max_effort_locates_the_limit(
    tmp_path: Path,
) -> None:
    import jsonschema
    from scipy.optimize import brentq

    f = tmp_path / "r2.yaml"
    f.write_text(PLANAR_2R_LOADED)
    argv = ["sweep", f, "--vary", "A=0:1.5:0.1", "--from", "bent", "--precision", "float"]
    r = run_cli([*argv, "--format", "json", "--max-effort", "A=2.5"])
    assert r.status == 0, r.err
    doc = json.loads(r.out)
    schema = json.loads(run_cli(["schema", "--sweep"]).out)
    jsonschema.validate(doc, schema)
    # the load is the --from configuration's (the file's): each sample's torques
    for p in doc["points"]:
        a = p["values"][0]
        assert p["efforts"]["A"] == pytest.approx(_tau_a(a, 0.9), rel=1e-10, abs=1e-12)
    # |tau_A| = 3.04 at A = 0.3 falls to 2.5 once along the path: the root of the closed form
    (lim,) = doc["effort_limits"]
    root = brentq(lambda a: abs(_tau_a(a, 0.9)) - 2.5, 0.0, 1.5, xtol=1e-14)
    assert lim["kind"] == "effort limit" and lim["input"] == "A"
    assert lim["values"][0] == pytest.approx(root, abs=1e-9)
    assert abs(lim["efforts"]["A"]) == pytest.approx(2.5, rel=1e-8)
    assert lim not in doc["located"]  # an effort limit is not a singularity
    text = run_cli([*argv, "--max-effort", "A=2.5"]).out
    assert "effort limit: |A|" in text and "largest |effort| of A" in text


def test_report_shows_efforts_and_indices_of_a_bundled_parallel_robot(tmp_path: Path) -> None:
    load = "force=1,2,0 moment=0,0,0.5"
    doc = _json([EX / "planar_3rpr.yaml", "--config", "stroke", "--load", load])
    c = _config(doc, "stroke")
    out = tmp_path / "review.md"
    argv = ["report", EX / "planar_3rpr.yaml", "--config", "stroke", "--precision", "float"]
    argv += ["--vary", "P1=0:0.2:0.05", "--from", "stroke", "--load", load, "-o", out]
    r = run_cli(argv)
    assert r.status == 0, r.err
    text = out.read_text()
    section = text[text.index("## Kinetostatics") :]
    for name in ("P1", "P2", "P3"):
        assert f"{name} {c['efforts'][name]:.4g} N" in section
    local = c["kinetostatics"]["transmission"]["local"]
    assert f"local {local:.3g}" in section
    assert (tmp_path / "review_files" / "kinetostatics-sweep.svg").exists()
    assert "--load" in text  # the command shown at the end


def test_file_load_errors_name_the_line_and_the_fix(tmp_path: Path) -> None:
    f = tmp_path / "r2.yaml"
    f.write_text(PLANAR_2R_LOADED.replace("load: {force: [1, -2, 0]}", "load: {forse: [1, -2, 0]}"))
    r = run_cli(["analyze", f])
    assert r.status == 2
    assert "r2.yaml:9:" in r.err and "'forse'" in r.err and "did you mean 'force'" in r.err
    f.write_text(PLANAR_2R_LOADED.replace("load: {force: [1, -2, 0]}", "load: {point: [1, 0, 0]}"))
    r = run_cli(["analyze", f])
    assert r.status == 2 and "give force and/or moment" in r.err


def test_four_bar_coupler_carries_a_force_along_its_line_and_the_loop_is_indeterminate_out_of_plane() -> (
    None
):
    doc = _json([EX / "fourbar.yaml", "--config", "crank-30", "--load", "moment=0,0,3"])
    c = _config(doc, "crank-30")
    q = {k: v[0] for k, v in c["joints"].items()}
    B = _rot(q["A"]) @ np.array([1.0, 0])
    D = np.array([4.0, 0])
    C = D + _rot(-q["D"]) @ (np.array([3.0, 2]) - D)
    ks = c["kinetostatics"]
    f = np.array(ks["joint_wrenches"]["B"])
    # the coupler is a two-force member: the wrench through B is a force along BC (no
    # moment about B nor about C), of magnitude M / (distance from D to the line BC)
    u = (C - B) / np.linalg.norm(C - B)
    assert abs(_cross2(f[:2], u)) < 1e-12 * np.linalg.norm(f[:2])
    m_b = f[5] - _cross2(B, f[:2])  # moment about B (planar: z)
    assert abs(m_b) < 1e-12 * np.linalg.norm(f[:2]) * 4
    arm = abs(_cross2(D - B, u))
    assert np.linalg.norm(f[:2]) == pytest.approx(3.0 / arm, rel=1e-10)
    # a planar loop seen in space: 3 wrench dimensions (out of the plane) indeterminate
    (loop,) = ks["loop_wrenches"]
    assert loop["subgroup"] == "G" and loop["indeterminate_dimensions"] == 3
    assert ks["indeterminate_loops"] == []


def test_bennett_input_torque_by_virtual_work_and_its_loop_wrench_indeterminate() -> None:
    from scipy.spatial.transform import Rotation

    h = 1e-5
    argv: list = [EX / "bennett.yaml", "--load", "moment=0,0,1", "--config", "q1-1rad"]
    for name, v in (("lo", 1 - h), ("hi", 1 + h)):
        argv += ["--set", f"{name}:J1={v!r}", "--from", "q1-1rad", "--config", name]
    doc = _json(argv)
    a1 = np.array([0.0, 0, 1])
    a2 = np.array([12 / 25, -9 / 25, 4 / 5])

    def link2(c: dict) -> Rotation:  # spatial product of exponentials (rotation part)
        q = {k: v[0] for k, v in c["joints"].items()}
        return Rotation.from_rotvec(q["J1"] * a1) * Rotation.from_rotvec(q["J2"] * a2)

    lo, hi = link2(_config(doc, "lo")), link2(_config(doc, "hi"))
    omega = (hi * lo.inv()).as_rotvec() / (2 * h)  # link2's angular velocity per unit J1 rate
    c = _config(doc, "q1-1rad")
    # virtual work: tau * 1 + M . omega = 0
    assert c["efforts"]["J1"] == pytest.approx(-omega[2], rel=1e-6)
    ks = c["kinetostatics"]
    assert ks["indeterminate_loops"] == [["J1", "J2", "J3", "J4"]]
    assert ks["loop_wrenches"][0]["wrench"] is None
    assert ks["loop_wrenches"][0]["indeterminate_dimensions"] == 3


def test_bodies_weights_under_gravity_add_their_torques(tmp_path: Path) -> None:
    f = tmp_path / "r2w.yaml"
    f.write_text(
        PLANAR_2R_LOADED.replace(
            "configurations:",
            "mass: {l1: {kg: 2, centre: [0.5, 0, 0]}, l2: {kg: 1, centre: [1.25, 0, 0]}}\n"
            "gravity: [0, -9.81, 0]\nconfigurations:",
        )
    )
    doc = _json([f, "--config", "bent", "--config", "straight"])
    a, b, g = 0.3, 0.9, 9.81
    # holding a weight m g at horizontal distance x from a joint takes m g x (counter-clockwise)
    tau_b = g * 1 * 0.25 * np.cos(a + b)
    tau_a = g * (2 * 0.5 * np.cos(a) + 1 * (np.cos(a) + 0.25 * np.cos(a + b)))
    tip = _tau_a(a, b), -np.array([-0.5 * np.sin(a + b), 0.5 * np.cos(a + b)]) @ [1.0, -2.0]
    c = _config(doc, "bent")  # the file's tip load and the weights
    assert c["efforts"]["A"] == pytest.approx(tau_a + tip[0], rel=1e-12)
    assert c["efforts"]["B"] == pytest.approx(tau_b + tip[1], rel=1e-12)
    assert c["kinetostatics"]["weighed_bodies"] == ["l1", "l2"]
    c = _config(doc, "straight")  # no load: the weights alone, arm straight at A = 0.3
    assert c["efforts"]["B"] == pytest.approx(g * 0.25 * np.cos(a), rel=1e-12)


def test_the_file_schema_takes_load_mass_and_gravity(tmp_path: Path) -> None:
    import jsonschema
    import yaml

    schema = json.loads(run_cli(["schema"]).out)
    text = PLANAR_2R_LOADED.replace(
        "configurations:",
        "mass: {l1: {kg: 2, centre: [0.5, 0, 0]}}\ngravity: [0, 0, -9.81]\nconfigurations:",
    )
    jsonschema.validate(yaml.safe_load(text), schema)
    bad = yaml.safe_load(text.replace("{force: [1, -2, 0]}", "{forse: [1, -2, 0]}"))
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(bad, schema)


def test_load_without_inputs_is_refused_with_the_fix(tmp_path: Path) -> None:
    f = tmp_path / "r2.yaml"
    f.write_text(PLANAR_2R_LOADED.replace("inputs: [A, B]\n", ""))
    r = run_cli(["analyze", f, "--config", "straight", "--load", "force=1,0,0"])
    assert r.status == 2 and "no inputs; add inputs:" in r.err


def test_redundantly_actuated_five_bar_gives_the_least_norm_efforts_and_says_they_are_not_unique(
    tmp_path: Path,
) -> None:
    f = tmp_path / "five_bar_redundant.yaml"
    f.write_text(
        (EX / "five_bar.yaml").read_text().replace("inputs: [A1, A2]", "inputs: [A1, A2, B1]")
    )
    c = _config(_json([f, "--config", "inputs", "--load", "force=0.3,-1,0"]), "inputs")
    q = {k: v[0] for k, v in c["joints"].items()}
    A1, B10, P0 = np.array([-1.5, 0]), np.array([-1.5, 2]), np.array([0.0, 4])
    A2, B20 = np.array([1.5, 0]), np.array([1.5, 2])
    B1 = A1 + _rot(q["A1"]) @ (B10 - A1)
    P = B1 + _rot(q["A1"] + q["B1"]) @ (P0 - B10)
    B2 = A2 + _rot(q["A2"]) @ (B20 - A2)

    def perp(r: np.ndarray) -> np.ndarray:
        return np.array([-r[1], r[0]])

    rows = []  # for each basis motion (w1, w2): the rates of A1, A2, B1 and the power of f
    for w1, w2 in ((1.0, 0.0), (0.0, 1.0)):
        vB1, vB2 = w1 * perp(B1 - A1), w2 * perp(B2 - A2)
        # v_B1 + d1 perp(P - B1) = v_B2 + d2 perp(P - B2)
        d1, d2 = np.linalg.solve(np.column_stack([perp(P - B1), -perp(P - B2)]), vB2 - vB1)
        vP = vB1 + d1 * perp(P - B1)
        rows.append(([w1, w2, d1 - w1], float(np.array([0.3, -1.0]) @ vP)))
    M = np.array([r for r, _ in rows])
    power = np.array([p for _, p in rows])
    tau = np.linalg.pinv(M) @ -power  # the least-norm efforts with tau . rates + power = 0
    assert [c["efforts"][j] for j in ("A1", "A2", "B1")] == pytest.approx(tau, rel=1e-10)
    assert set(c["kinetostatics"]["non_unique"]) == {"A1", "A2", "B1"}


@pytest.mark.parametrize("k", ["1000", "1/1000"])
def test_scaling_the_3rpr_keeps_its_leg_forces_and_indices(tmp_path: Path, k: str) -> None:
    from fractions import Fraction

    s = float(Fraction(k))
    op = f"*{k}" if "/" not in k else f"/{k.split('/')[1]}"
    path = tmp_path / "rpr_scaled.yaml"
    path.write_text(scaled_text(EX / "planar_3rpr.yaml", op))
    base = _config(
        _json([EX / "planar_3rpr.yaml", "--config", "stroke", "--load", "force=1,2,0 point=1,1,0"]),
        "stroke",
    )
    got = _config(
        _json([path, "--config", "stroke", "--load", f"force=1,2,0 point={s!r},{s!r},0"]), "stroke"
    )
    # prismatic actuators under a force: N for N, whatever the scale; couples: 1/k
    assert got["efforts"] == pytest.approx(base["efforts"], rel=1e-9)
    bt, gt = base["kinetostatics"], got["kinetostatics"]
    assert gt["transmission"]["output"] == pytest.approx(bt["transmission"]["output"], rel=1e-9)
    b_c = bt["largest_unit_efforts"]["couple"]["N"]["value"]
    assert gt["largest_unit_efforts"]["couple"]["N"]["value"] == pytest.approx(b_c / s, rel=1e-9)


def test_grid_sweep_samples_carry_the_efforts_analyze_gives_there() -> None:
    load = "force=0.3,-1,0"
    r = run_cli(["sweep", EX / "five_bar.yaml", "--vary", "A1=0.2:0.4:0.1", "--vary", "A2=-0.3:-0.1:0.1",
                 "--load", load, "--precision", "float", "--format", "json"])  # fmt: skip
    assert r.status == 0, r.err
    points = json.loads(r.out)["points"]
    assert len(points) == 9 and all(p["reached"] for p in points)
    p = next(p for p in points if p["values"] == pytest.approx([0.3, -0.2]))
    c = _config(_json([EX / "five_bar.yaml", "--config", "inputs", "--load", load]), "inputs")
    assert p["efforts"] == pytest.approx(c["efforts"], rel=1e-9)
    assert p["transmission"]["local"] == pytest.approx(
        c["kinetostatics"]["transmission"]["local"], rel=1e-9
    )


def test_no_runtime_warning_at_singular_configurations_under_a_load() -> None:
    from tests.cli import runtime_warnings

    for argv in (
        ["analyze", EX / "planar_3rpr.yaml", "--precision", "float", "--load", "moment=0,0,1"],
        ["analyze", EX / "five_bar.yaml", "--config", "type1", "--config", "type2",
         "--precision", "float", "--load", "force=0,1,0"],
    ):  # fmt: skip
        assert runtime_warnings(argv) == []
