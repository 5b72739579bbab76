"""The singularity classification through the JSON contract, on generated families (issue 6).

Each family is random (numpy ``default_rng`` with fixed seeds) and built to be singular from
its geometry; the same instance is then pushed 10^-k off the singular configuration
(k = 1 ... 6).  The mechanisms are written to ``tmp_path`` with exact rationals (tests/families.py)
and analysed in-process, with ``mechsing.analysis.analyze(path).to_json()`` or with
``mechsing.cli.main(["analyze", path, "--format", "json"])``.  Every expected answer is derived
from the geometry in tests/families.py or below (closed forms and the published facts named
there), never from mechsing's output:

* change-point four-bars and parallelograms folded flat: ``bifurcation``, 2 branches of mobility
  1 whose tangents are those of the closed-form motion; off the fold: regular in float;
* four-bars with a + b + c = g, degenerate 3R triangles: ``isolated`` (finite 0, generic null);
* 3-RPR with concurrent leg lines: ``output`` (the platform turns about the common point with
  the P joints locked) and ``impossible-input``; off it: regular;
* Bennett linkages along their motion: never singular, overconstrained, finite 1;
* 3-UPU with coplanar constraint couples: ``constraint`` (the couples of the combined constraint
  system span that plane); off it: no ``constraint``;
* isosceles slider-crank at 90 deg: ``bifurcation`` with the branches x = 2 r cos(theta) and x = 0;
  the slider-crank examples' dead centre: ``input`` with the crank driving, ``output`` with the
  slider driving; 6R arms on each factor of det J: ``serial`` told apart by its support, with its
  evidence (wrenches, twist, null rates) checked against the arm's own screws.

All findings carry ``margin`` and ``precision``, and ``singular`` is true iff a
finding other than ``undecided`` is present (null if only those, false if none).
"""

from __future__ import annotations

import json
from fractions import Fraction as F
from pathlib import Path

import mpmath
import numpy as np
import pytest

from mechsing.analysis import analyze
from tests import families as fam
from tests.cli import cli_json
from tests.mechanisms import assert_same_lines, by_name, classes, finding, normalised, write

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
KS = range(1, 7)
MARGIN_KEYS = {"kept", "dropped", "tau_lo", "tau_hi", "length_scale"}

# ----------------------------------------------------------------------------- helpers


def check_contract(result: dict) -> None:
    """Every finding carries margin and precision; ``singular`` is true iff a finding
    other than ``undecided`` is present, null if only those, false if none."""
    for c in result["configurations"]:
        assert c.get("error") is None, (c["name"], c.get("error"))
        for f in c["singularities"]:
            assert MARGIN_KEYS <= set(f["margin"]), (c["name"], f)
            assert isinstance(f["precision"], str) and f["precision"], (c["name"], f)
        classes = [f["class"] for f in c["singularities"]]
        if not classes:
            expected = False
        elif all(k == "undecided" for k in classes):
            expected = None
        else:
            expected = True
        assert c["singular"] is expected, (c["name"], classes, c["singular"])


def run_api(path: Path) -> dict:
    """``analyze(path).to_json()`` as the JSON text would carry it."""
    out = json.loads(json.dumps(analyze(path).to_json()))
    check_contract(out)
    return out


def run_cli(path: Path, capsys: pytest.CaptureFixture[str], *options: str) -> dict:
    out = cli_json(["analyze", str(path), "--format", "json", *options])
    check_contract(out)
    return out


def assert_regular(config: dict, rank: int) -> None:
    """Regular in float: rank decided at its generic value, nothing found.  Near a
    singularity float may leave the output's motion type undecided (a translation's
    rotation parts are rounding, amplified by the conditioning: 1e-3 from a 3-UPU's
    constraint singularity they fall between the two thresholds); auto then decides the
    configuration again at mp:50, as it does an undecided rank, and the motion type must
    be decided there."""
    if config["precision"] != "float":
        assert config["precision"] == "mp:50", config["name"]
        motion = config["output_motion"]
        assert motion["precision"] == "mp:50" and "undecided" not in motion["summary"], (
            config["name"],
            motion,
        )
    assert config["closure_rank"]["rank"] == rank, (config["name"], config["closure_rank"])
    assert config["singularities"] == [], (config["name"], classes(config))
    assert config["singular"] is False


# ----------------------------------------------------------------------------- 1. change points


def _fourbar_family(kind: str, seed: int) -> fam.FourBar:
    rng = np.random.default_rng(seed)
    if kind == "parallelogram":
        return fam.parallelogram_fourbar(rng)
    # g + a = b + c, g + b = a + c, g + c = a + b
    return fam.changepoint_fourbar(rng, int(kind[-1]))


@pytest.mark.parametrize(
    ("kind", "seed"),
    [(f"changepoint{p}", 11 + p) for p in range(3)] + [("parallelogram", s) for s in (21, 22)],
)
def test_changepoint_fold_is_a_bifurcation_and_regular_off_it(
    tmp_path: Path, kind: str, seed: int
) -> None:
    fb = _fourbar_family(kind, seed)
    g, a, b, c = fb.g, fb.a, fb.b, fb.c
    # the family is what it claims: s + l = p + q, folded flat at the reference
    s = sorted([g, a, b, c])
    assert s[0] + s[3] == s[1] + s[2]
    configs = {}
    for k in KS:
        for branch in (1, -1):
            for side in (1, -1):
                configs[f"k{k}-branch{branch}-side{side}"] = fb.pushed_config(
                    side * mpmath.mpf(10) ** -k, branch
                )
    res = by_name(run_api(write(tmp_path, fb.name, fb.yaml(configs))))

    fold = res["reference"]
    # all joints collinear: the planar closure loses the translation normal to the line
    assert fold["closure_rank"]["rank"] == 2 and fold["closure_rank"]["nullity"] == 2
    m = fold["mobility"]
    assert (m["grubler"], m["instantaneous"], m["generic"], m["finite"]) == (-2, 2, 1, 1)
    assert classes(fold) == ["bifurcation"]
    f = finding(fold, "bifurcation")
    assert f["branches"] == 2
    assert f["branch_mobility"] == [1, 1]
    assert f["joints"] == ["A", "B", "C", "D"]
    # the two tangents of the closed-form motion (one per side of the line BD)
    assert_same_lines(f["branch_tangents"], fb.branch_tangents(), contract=True)
    assert fold["singular"] is True

    pts = np.array([float(x) for x in fb.points])
    L = float(np.sqrt(np.mean((pts - pts.mean()) ** 2)))  # L: RMS distance to the centroid
    for name, c in res.items():
        if name != "reference":
            assert_regular(c, 3)
            assert c["mobility"]["instantaneous"] == 1 and c["mobility"]["finite"] == 1
            assert c["closure_residual"] <= 1e-12 * L


@pytest.mark.parametrize(
    ("kind", "seed"),
    [(f"changepoint{p}", 11 + p) for p in range(3)] + [("parallelogram", s) for s in (21, 22)],
)
def test_crank_input_continued_towards_the_fold_stays_on_its_branch(
    tmp_path: Path, kind: str, seed: int, capsys: pytest.CaptureFixture[str]
) -> None:
    """The crank alone, continued from crank angle 0.1 on one branch to 10^-k (k = 2 ... 6):
    for every crank angle in (0, 0.1] the two assembly modes (the two sides of the line BD) are
    distinct, so continuation must stay on the side it starts on (docs/closure.md: continuation
    stays on the start's assembly mode), and the point is regular."""
    fb = _fourbar_family(kind, seed)
    configs = {"start": fb.pushed_config(mpmath.mpf("0.1"), 1)}
    for k in KS[1:]:
        configs[f"input{k}"] = {"A": f'"1/10**{k}"', "start": "start"}
    path = write(tmp_path, fb.name, fb.yaml(configs))
    options = [x for k in KS[1:] for x in ("--config", f"input{k}")]
    res = by_name(run_cli(path, capsys, *options))
    pts = np.array([float(x) for x in fb.points])
    L = float(np.sqrt(np.mean((pts - pts.mean()) ** 2)))
    wrong = []
    for k in KS[1:]:
        c = res[f"input{k}"]
        assert_regular(c, 3)
        assert c["closure_residual"] <= 1e-12 * L
        got = np.array([c["joints"][j][0] for j in "ABCD"])
        assert got[0] == pytest.approx(10.0**-k, rel=1e-15)
        mine, other = (
            np.array([float(x) for x in fb.pushed(mpmath.mpf(10) ** -k, br)]) for br in (1, -1)
        )
        # the nearer of the two closed-form solutions is the starting branch
        if not np.max(np.abs(got - mine)) < np.max(np.abs(got - other)) / 3:
            wrong.append((k, float(np.max(np.abs(got - mine))), float(np.max(np.abs(got - other)))))
    assert not wrong, (
        f"continuation jumped to the other assembly mode (k, off own, off other): {wrong}"
    )


# ----------------------------------------------------------------------------- 2. stretched


@pytest.mark.parametrize("seed", [31, 32, 33, 34])
def test_stretched_fourbar_is_isolated(tmp_path: Path, seed: int) -> None:
    fb = fam.stretched_fourbar(np.random.default_rng(seed))
    assert fb.a + fb.b + fb.c == fb.g
    res = by_name(run_api(write(tmp_path, fb.name, fb.yaml({}))))
    c = res["reference"]
    assert c["closure_rank"]["rank"] == 2 and c["closure_rank"]["nullity"] == 2
    assert classes(c) == ["isolated"]
    assert c["mobility"]["finite"] == 0
    assert c["mobility"]["generic"] is None
    assert c["mobility"]["instantaneous"] == 2
    assert c["singular"] is True


def test_stretched_fourbar_isolated_through_the_cli(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    fb = fam.stretched_fourbar(np.random.default_rng(35))
    res = by_name(run_cli(write(tmp_path, fb.name, fb.yaml({})), capsys))
    c = res["reference"]
    assert classes(c) == ["isolated"]
    assert (c["mobility"]["finite"], c["mobility"]["generic"]) == (0, None)


# ----------------------------------------------------------------------------- 3. 3-RPR


@pytest.mark.parametrize("seed", [41, 42, 43])
def test_rpr_concurrent_legs_output_singular_and_regular_off_it(tmp_path: Path, seed: int) -> None:
    rng = np.random.default_rng(seed)
    rpr = fam.rpr_concurrent(rng)
    direction = (mpmath.mpf(int(rng.integers(1, 5))), mpmath.mpf(int(rng.integers(-4, 5))))
    norm = mpmath.sqrt(direction[0] ** 2 + direction[1] ** 2)
    direction = (direction[0] / norm, direction[1] / norm)
    configs = {}
    zero = (mpmath.mpf(0), mpmath.mpf(0))
    assert rpr.concurrency(0, zero) == 0  # exactly concurrent at the reference
    for k in KS:
        e = mpmath.mpf(10) ** -k
        pushes = {
            f"turn+{k}": (e, zero),
            f"turn-{k}": (-e, zero),
            f"shift{k}": (mpmath.mpf(0), (e * direction[0], e * direction[1])),
        }
        for name, (turn, shift) in pushes.items():
            # off the singular set at first order (the leg lines are no longer concurrent)
            assert abs(rpr.concurrency(turn, shift)) > e * 1e-3
            configs[name] = rpr.moved(turn, shift)
    res = by_name(run_api(write(tmp_path, "rpr", rpr.yaml(configs))))

    c = res["reference"]
    # c-space regular (rank 6 of the two planar loops); type II: the output turns about O with
    # the P joints locked, and the input rates are restricted; the inverse kinematics stays
    # defined (no input, no impossible-output), the legs keep rank 3
    assert c["closure_rank"]["rank"] == 6
    assert c["mobility"]["finite"] == 3
    assert sorted(classes(c)) == ["impossible-input", "output"]
    f = finding(c, "output")
    assert (f["dimension"], f["generic"]) == (1, 0)
    rates, twist = rpr.output_motion()
    assert f["joints"] == ["Rb1", "Rp1", "Rb2", "Rp2", "Rb3", "Rp3"]
    assert np.max(np.abs(np.array(f["joint_rates"]) - normalised(rates))) < 1e-9
    t = np.array(f["output_twist"])
    t = t / np.linalg.norm(t[:3])
    assert min(np.max(np.abs(t - twist)), np.max(np.abs(t + twist))) < 1e-9
    assert finding(c, "impossible-input")["rank"] == 2

    for name, c in res.items():
        if name != "reference":
            assert_regular(c, 6)


# ----------------------------------------------------------------------------- 4. Bennett


@pytest.mark.parametrize("seed", [51, 52, 53])
def test_bennett_is_never_singular_along_its_motion(tmp_path: Path, seed: int) -> None:
    rng = np.random.default_rng(seed)
    ben = fam.bennett(rng)
    configs = {}
    ts = []
    while len(ts) < 4:
        t = F(int(rng.integers(-9, 10)), int(rng.integers(1, 6)))
        if t != 0 and t != ben.t1 and t not in ts:
            ts.append(t)
    for i, t in enumerate(ts):
        assert ben.closes(t)  # the Bennett relation closes the loop exactly
        configs[f"along{i}"] = ben.config(t)
    configs["input-only"] = {"J1": "0.5"}
    res = run_api(write(tmp_path, "bennett", ben.yaml(configs)))

    props = [p for p in res["properties"] if p["kind"] == "overconstrained"]
    assert len(props) == 1
    # four R joints whose axes generate all of D: group 4 - 6 = -2, yet finite mobility 1
    assert (props[0]["finite"], props[0]["group"], props[0]["grubler"]) == (1, -2, -2)
    for c in res["configurations"]:
        assert c["closure_rank"]["rank"] == 3, (c["name"], c["closure_rank"])
        m = c["mobility"]
        assert (m["grubler"], m["instantaneous"], m["generic"], m["finite"]) == (-2, 1, 1, 1)
        assert c["singular"] is False and c["singularities"] == [], (c["name"], classes(c))

    # the configuration solved from the input alone lies on the Bennett motion
    solved = by_name(res)["input-only"]["joints"]
    theta = [
        float(2 * mpmath.atan(mpmath.mpf(ben.t1.numerator) / ben.t1.denominator)),
        float(2 * mpmath.atan(mpmath.mpf(ben.K.numerator) / (ben.K.denominator * ben.t1))),
    ]
    th1 = theta[0] + solved["J1"][0]
    th2 = theta[1] + solved["J2"][0]
    th3 = -theta[0] + solved["J3"][0]
    th4 = -theta[1] + solved["J4"][0]
    assert abs(np.sin((th1 + th3) / 2)) < 1e-9 and abs(np.sin((th2 + th4) / 2)) < 1e-9
    K = float(ben.K)
    assert abs(np.tan(th1 / 2) * np.tan(th2 / 2) - K) < 1e-9 * max(1.0, abs(K))


# ----------------------------------------------------------------------------- 5. Tsai 3-UPU


@pytest.mark.parametrize("seed", [61, 62, 63])
def test_tsai_coplanar_couples_constraint_singular_and_not_off_it(
    tmp_path: Path, seed: int
) -> None:
    rng = np.random.default_rng(seed)
    tsai = fam.tsai_coplanar(rng)
    direction = [mpmath.mpf(int(x)) for x in rng.integers(-3, 4, size=3)]
    if all(x == 0 for x in direction):
        direction = [mpmath.mpf(1), mpmath.mpf(0), mpmath.mpf(0)]
    norm = mpmath.sqrt(sum(x * x for x in direction))
    zero = (0, 0, 0)
    assert abs(tsai.constraint_det(zero)) < mpmath.mpf(10) ** -50  # coplanar couples
    configs = {}
    for k in KS:
        for side in (1, -1):
            e = side * mpmath.mpf(10) ** -k
            shift = tuple(e * x / norm for x in direction)
            for i in range(3):
                assert tsai.check_leg(i, shift) < mpmath.mpf(10) ** -45  # closed form closes
            assert abs(tsai.constraint_det(shift)) > abs(e) * 1e-4
            configs[f"shift{'+' if side > 0 else '-'}{k}"] = tsai.translated(shift)
    res = by_name(run_api(write(tmp_path, "tsai", tsai.yaml(configs))))

    c = res["reference"]
    f = finding(c, "constraint")
    assert (f["rank"], f["generic_rank"], f["corank"]) == (2, 3, 1)
    # the combined constraint system is spanned by the couples n_i, which lie in the plane
    # normal to m: pure couples, unit moment, normal to m, spanning a plane
    m = np.array([float(x) for x in tsai.m])
    m /= np.linalg.norm(m)
    W = np.array(f["wrenches"])
    assert W.shape == (2, 6)
    assert np.max(np.abs(W[:, :3])) < 1e-9
    assert np.allclose(np.linalg.norm(W[:, 3:], axis=1), 1, atol=1e-12, rtol=0)
    assert np.max(np.abs(W[:, 3:] @ m)) < 1e-9
    assert np.linalg.svd(W[:, 3:], compute_uv=False)[1] > 1e-3
    for w in W:
        assert w[np.flatnonzero(np.abs(w) > 1e-9)[0]] > 0
    assert c["singular"] is True

    for name, c in res.items():
        if name == "reference":
            continue
        assert "constraint" not in classes(c), (name, classes(c))
        assert c["closure_rank"]["rank"] == 12, (name, c["closure_rank"])
        assert c["mobility"]["finite"] == 3
        assert_regular(c, 12)


# ------------------------------------------------------------ 6. slider-crank r = l, flat triangle


@pytest.mark.parametrize("r", [F(1), F(7, 3), F(2, 5)])
def test_isosceles_slider_crank_at_90_degrees_is_a_bifurcation(tmp_path: Path, r: F) -> None:
    res = by_name(run_api(write(tmp_path, "isosceles", fam.isosceles_slider_crank(r))))
    c = res["reference"]
    assert c["closure_rank"]["rank"] == 2
    assert classes(c) == ["bifurcation"]
    f = finding(c, "bifurcation")
    assert f["branches"] == 2 and f["branch_mobility"] == [1, 1]
    # branch x = 2 r cos(theta): (A, B, C, P) rates (1, -2, 1, -2 r) per unit crank rate;
    # branch x = 0 (the slider pin stays on the crank pivot): (1, 0, -1, 0)
    assert_same_lines(
        f["branch_tangents"], [[1, -2, 1, -2 * float(r)], [1, 0, -1, 0]], contract=True
    )


@pytest.mark.parametrize(("a", "b"), [(F(1), F(2)), (F(3, 2), F(5, 7))])
def test_degenerate_triangle_is_isolated(tmp_path: Path, a: F, b: F) -> None:
    res = by_name(run_api(write(tmp_path, "triangle", fam.degenerate_triangle(a, b))))
    c = res["reference"]
    assert c["closure_rank"]["rank"] == 2 and c["mobility"]["instantaneous"] == 1
    assert classes(c) == ["isolated"]
    assert (c["mobility"]["finite"], c["mobility"]["generic"]) == (0, None)


# ----------------------------------------------------------------------------- 6. slider-crank dead centre

# Both example files: r = 1, l = 4, outer dead centre B = (24/25, 7/25), C = (24/5, 7/5) (crank and
# rod along u = (24, 7)/25).  With the slider (C) still, the crank turns at 1 and the rod at
# -r/l = -1/4 about C: joint rates (A, B, C, P) = (1, -5/4, 1/4, 0); the crank's twist is a
# rotation about A = origin.
DEAD_CENTRE_RATES = normalised([1, -5 / 4, 1 / 4, 0])


def test_slider_crank_dead_centre_crank_input_is_an_input_singularity(
    capsys: pytest.CaptureFixture[str],
) -> None:
    res = by_name(run_cli(EXAMPLES / "slider_crank_crank_input.yaml", capsys))
    c = res["dead-centre"]
    assert c["closure_rank"]["rank"] == 3  # a regular point of the c-space
    assert "input" in classes(c) and "output" not in classes(c)
    f = finding(c, "input")
    assert f["joints"] == ["A", "B", "C"]
    assert np.max(np.abs(np.array(f["joint_rates"]) - DEAD_CENTRE_RATES)) < 1e-9
    for name in ("reference", "crank-60"):
        assert_regular(res[name], 3)


def test_slider_crank_dead_centre_slider_input_is_an_output_singularity(
    capsys: pytest.CaptureFixture[str],
) -> None:
    res = by_name(run_cli(EXAMPLES / "slider_crank_slider_input.yaml", capsys))
    c = res["dead-centre"]
    assert c["closure_rank"]["rank"] == 3
    assert "output" in classes(c) and "input" not in classes(c)
    f = finding(c, "output")
    assert f["joints"] == ["A", "B", "C"]
    assert np.max(np.abs(np.array(f["joint_rates"]) - DEAD_CENTRE_RATES)) < 1e-9
    t = np.array(f["output_twist"]) / np.linalg.norm(f["output_twist"][:3])
    assert np.max(np.abs(np.abs(t) - [0, 0, 1, 0, 0, 0])) < 1e-9
    for name in ("reference", "slider-4"):
        assert_regular(res[name], 3)


# ----------------------------------------------------------------------------- 6. 6R arms


def test_arm_examples_tell_wrist_elbow_shoulder_apart(capsys: pytest.CaptureFixture[str]) -> None:
    ur5 = by_name(run_cli(EXAMPLES / "ur5.yaml", capsys))
    # the four parallel axes 2, 3, 4, 6 at theta5 = 0 lie in one planar subalgebra
    assert finding(ur5["wrist"], "serial")["joints"] == ["J2", "J3", "J4", "J6"]
    assert finding(ur5["elbow"], "serial")["joints"] == ["J2", "J3", "J4"]
    assert "J1" in finding(ur5["shoulder"], "serial")["joints"]
    for name in ("wrist", "elbow"):
        assert "J1" not in finding(ur5[name], "serial")["joints"]
    assert_regular(ur5["regular"], 0)
    puma = by_name(run_cli(EXAMPLES / "puma560.yaml", capsys))
    # spherical wrist at theta5 = 0: axes 4 and 6 collinear
    assert finding(puma["wrist"], "serial")["joints"] == ["J4", "J6"]
    assert "J1" in finding(puma["shoulder"], "serial")["joints"]
    assert "J1" not in finding(puma["elbow"], "serial")["joints"]
    assert_regular(puma["regular"], 0)


def _power(wrench, twist) -> float:
    f, m = np.asarray(wrench[:3]), np.asarray(wrench[3:])
    w, v = np.asarray(twist[:3]), np.asarray(twist[3:])
    return float(f @ v + m @ w)


@pytest.mark.parametrize(("arm", "example"), [("ur5", "ur5.yaml"), ("puma", "puma560.yaml")])
def test_arm_on_each_factor_serial_with_its_support_and_regular_off_it(
    tmp_path: Path, arm: str, example: str
) -> None:
    rng = np.random.default_rng(71 if arm == "ur5" else 72)
    text = (EXAMPLES / example).read_text().split("configurations:")[0]
    lines = ["configurations:", "  reference: {}"]
    expected: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    pushed: list[str] = []
    solved = {"wrist": 4, "elbow": 2, "shoulder": 1}  # the joint moved off the factor
    for factor in ("wrist", "elbow", "shoulder"):
        for i in range(2):
            while True:
                th = fam.arm_on_factor(arm, factor, rng.uniform(-np.pi, np.pi, 6))
                others = fam.arm_factors(arm, th)
                if all(abs(v) > 0.05 for k, v in others.items() if k != factor):
                    break
            name = f"{factor}{i}"
            lines.append(
                f"  {name}: {{" + ", ".join(f"J{j + 1}: {fam.d(th[j])}" for j in range(6)) + "}"
            )
            J = fam.arm_screws(arm, th)
            expected[name] = (
                fam.kernel_vector(J),
                np.array([[float(J[r, c]) for c in range(6)] for r in range(6)]),
            )
            for k in KS:
                for side in (1, -1):
                    off = list(th)
                    off[solved[factor]] += side * mpmath.mpf(10) ** -k
                    # the factor moves off zero linearly, the others stay away from zero
                    assert abs(fam.arm_factors(arm, off)[factor]) > mpmath.mpf(10) ** -k * 1e-3
                    pname = f"{name}-off{'+' if side > 0 else '-'}{k}"
                    pushed.append(pname)
                    lines.append(
                        f"  {pname}: {{"
                        + ", ".join(f"J{j + 1}: {fam.d(off[j])}" for j in range(6))
                        + "}"
                    )
    res = by_name(run_api(write(tmp_path, arm, text + "\n".join(lines) + "\n")))

    names = [f"J{j + 1}" for j in range(6)]
    for name, (kernel, J) in expected.items():
        c = res[name]
        assert classes(c) == ["serial"], (name, classes(c))
        f = finding(c, "serial")
        assert (f["rank"], f["generic_rank"], f["corank"]) == (5, 6, 1)
        support = [names[j] for j in range(6) if abs(kernel[j]) > 1e-9]
        assert f["joints"] == support, (name, f["joints"], support)
        assert ("J1" in support) == name.startswith("shoulder")
        if name.startswith("wrist"):
            assert support == (["J2", "J3", "J4", "J6"] if arm == "ur5" else ["J4", "J6"])
        if arm == "ur5" and name.startswith("elbow"):
            assert support == ["J2", "J3", "J4"]
        # the evidence: null rates in ker J, the wrench resisted with zero joint effort,
        # the lost twist does power against it
        rates = np.array(f["null_joint_rates"])
        assert np.max(np.abs(rates - kernel)) < 1e-9
        assert np.linalg.norm(J @ rates) < 1e-9 * np.linalg.norm(J)
        assert len(f["wrenches"]) == 1
        w = f["wrenches"][0]
        assert abs(np.linalg.norm(w[:3]) - 1) < 1e-12 or (
            np.linalg.norm(w[:3]) < 1e-9 and abs(np.linalg.norm(w[3:]) - 1) < 1e-12
        )
        for j in range(6):
            assert abs(_power(w, J[:, j])) < 1e-9 * np.linalg.norm(J[:, j])
        assert abs(_power(w, f["twist"])) > 1e-3 * np.linalg.norm(f["twist"])
    for name in pushed:
        assert res[name]["precision"] == "float"
        assert res[name]["singularities"] == [], (name, classes(res[name]))
        assert res[name]["singular"] is False
