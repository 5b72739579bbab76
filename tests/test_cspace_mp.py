"""Higher-order (tangent-cone) and input/output tests at the analysis precision (issue 7).

With ``--precision mp:N`` the forms of the second-order test (on the kernel, projected on the
cokernel), their definiteness, the splitting of their zero set, the third-order test and the
ZFB ranks run at N digits with the mp thresholds (tau_lo = 10^(10-N),
tau_hi = 10^(-N/2)), and each finding says so in ``test_precision``; ``exact`` evaluates them at
mp:50; float stays numpy.

The expected answers come from outside the code under test: the mp:N thresholds; closed-form
quadratic forms and their zero lines; the planar four-bars of tests/families.py (parallelogram,
change point, stretched: branch tangents from the closed-form circle intersection, evaluated
here with mpmath at 150+ digits); singular values of the four-bar's reduced closure matrix
rebuilt here in the commensurate metric (L, centroid, G coordinates) and the closed-form joint
points; the 3-RPR with concurrent leg lines (tests/families.py: the platform turns about the
common point with the P joints locked).
"""

from __future__ import annotations

import json
import math
from fractions import Fraction as F
from pathlib import Path

import mpmath
import numpy as np
import pytest

from mechsing import numeric
from mechsing.analysis import analyze
from mechsing.numeric import Precision, linalg
from mechsing.singularity.cspace import Expansion, LoopChain, _zero_set, tangent_cone
from tests import families as fam
from tests.mechanisms import assert_same_lines, by_name, classes, finding, normalised, write

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
MP = [Precision("mp", 30), Precision("mp", 50)]


# ----------------------------------------------------------------------------- helpers


def run(path: Path, precision: str) -> dict:
    return json.loads(json.dumps(analyze(path, precision=precision).to_json()))


def tau(n: int) -> tuple[float, float]:
    """The mp:N thresholds: tau_lo = 10^(10-N), tau_hi = 10^(-N/2)."""
    return 10.0 ** (10 - n), 10.0 ** (-n / 2)


def closed_form_tangents(fb: fam.FourBar, digits: int = 200) -> list[list[mpmath.mpf]]:
    """Branch tangents (A, B, C, D rates) at the fold, from the closed-form motion at a crank
    angle h = 10^-80 (first-order difference; its error is O(h))."""
    with mpmath.workdps(digits):
        h = mpmath.mpf(10) ** -80
        return [[v / h for v in fb.pushed(h, br)] for br in (1, -1)]


def closed_form_sigma(fb: fam.FourBar, values: list[mpmath.mpf]) -> list[mpmath.mpf]:
    """Singular values of the four-bar's closure system at joint values (A, B, C, D), in
    the commensurate metric: L and the centroid c of the joint points at the reference, R screws
    about z moved to c with v / L; in G's coordinates (omega_z, v_x, v_y) the column of a joint
    at p is (1, (p - c)_y / L, -(p - c)_x / L) up to its sign, which no singular value sees."""
    ref = [mpmath.mpf(x.numerator) / x.denominator for x in fb.points]
    c = sum(ref) / 4
    L = mpmath.sqrt(sum((x - c) ** 2 for x in ref) / 4)
    qa, qb, qc, _qd = values
    th1, th2 = qa, qa + qb
    B = (ref[1] * mpmath.cos(th1), ref[1] * mpmath.sin(th1))
    C = (B[0] + (ref[2] - ref[1]) * mpmath.cos(th2), B[1] + (ref[2] - ref[1]) * mpmath.sin(th2))
    pts = [(mpmath.mpf(0), mpmath.mpf(0)), B, C, (ref[3], mpmath.mpf(0))]
    M = mpmath.matrix([[1] * 4, [p[1] / L for p in pts], [-(p[0] - c) / L for p in pts]])
    s = mpmath.svd_r(M, compute_uv=False)
    return sorted((s[i] for i in range(3)), reverse=True)


# ----------------------------------------------------------------------------- 1. numeric layer


@pytest.mark.parametrize("n", [30, 50])
def test_higher_order_tolerances_are_placed_at_the_modes_tau_hi(n: int) -> None:
    """The cone tolerances keep their float values (1e-10, 1e-8, 1e-9 = tau_hi / 10, 10 tau_hi,
    tau_hi with float's tau_hi = 1e-9) and move with tau_hi = 10^(-N/2) at mp:N."""
    fl = Precision("float")
    assert numeric.subspace_rank_rtol(fl) == pytest.approx(1e-10, rel=1e-12)
    assert numeric.subspace_containment_atol(fl) == pytest.approx(1e-8, rel=1e-12)
    assert numeric.order3_residual_rtol(fl) == pytest.approx(1e-9, rel=1e-12)
    mp = Precision("mp", n)
    hi = 10.0 ** (-n / 2)
    assert numeric.subspace_rank_rtol(mp) == pytest.approx(hi / 10, rel=1e-12)
    assert numeric.subspace_containment_atol(mp) == pytest.approx(10 * hi, rel=1e-12)
    assert numeric.order3_residual_rtol(mp) == pytest.approx(hi, rel=1e-12)


def test_numeric_precision_of_each_mode() -> None:
    """float and mp:N test at themselves, an auto stage is float (or the mp:50 stage after
    escalation), exact evaluates its forms at mp:50."""
    assert str(numeric.numeric_precision(Precision("float"))) == "float"
    assert str(numeric.numeric_precision(Precision("auto"))) == "float"
    assert str(numeric.numeric_precision(Precision("mp", 40))) == "mp:40"
    assert str(numeric.numeric_precision(Precision("exact"))) == "mp:50"


def test_generic_factorisations_keep_every_digit_at_mp() -> None:
    """svd, eigh, QR and least squares on mp object arrays reproduce their matrix to 50 digits
    (float64 could not: the entries differ in their 30th digit)."""
    prec = Precision("mp", 50)
    with prec.context():
        rng = np.random.default_rng(3)
        base = rng.normal(size=(4, 3))
        A = np.array(
            [
                [mpmath.mpf(x) + mpmath.mpf(10) ** -30 * (i + j) for j, x in enumerate(r)]
                for i, r in enumerate(base)
            ],
            dtype=object,
        )
        U, s, Vt = linalg.svd(A)
        assert U.dtype == object and isinstance(s[0], mpmath.mpf)
        assert list(s) == sorted(s, reverse=True)
        S = np.zeros((4, 3), dtype=object)
        S.fill(mpmath.mpf(0))
        for i in range(3):
            S[i, i] = s[i]
        assert linalg.max_abs(U @ S @ Vt - A) < mpmath.mpf(10) ** -45
        assert linalg.max_abs(U.T @ U - np.eye(4)) < mpmath.mpf(10) ** -45
        Sym = A.T @ A
        w, V = linalg.eigh(Sym)
        assert list(w) == sorted(w)
        for i in range(3):
            assert linalg.norm(Sym @ V[:, i] - w[i] * V[:, i]) < mpmath.mpf(10) ** -45
        Q = linalg.orthonormal_columns(A)
        assert Q.shape == (4, 3) and linalg.max_abs(Q.T @ Q - np.eye(3)) < mpmath.mpf(10) ** -45
        b = A @ np.array([mpmath.mpf(1), mpmath.mpf(-2), mpmath.mpf(3)], dtype=object)
        x = linalg.lstsq(A, b)
        assert linalg.max_abs(x - np.array([1, -2, 3])) < mpmath.mpf(10) ** -40


# ----------------------------------------------------------------------------- 2. the cone machinery


def _rotated_form(ratio: mpmath.mpf, angle: mpmath.mpf) -> tuple[np.ndarray, list]:
    """R diag(1, -ratio) R^T and the two lines of its zero set, R (+- sqrt(ratio), 1)."""
    c, s = mpmath.cos(angle), mpmath.sin(angle)
    R = [[c, -s], [s, c]]
    D = [mpmath.mpf(1), -ratio]
    Q = np.array(
        [[sum(R[i][k] * D[k] * R[j][k] for k in range(2)) for j in range(2)] for i in range(2)],
        dtype=object,
    )
    r = mpmath.sqrt(ratio)
    lines = [[R[i][0] * sgn * r + R[i][1] for i in range(2)] for sgn in (1, -1)]
    return Q, lines


def test_form_float_cannot_decide_is_decided_at_mp() -> None:
    """x^2 - 1e-11 y^2 (rotated): its small eigenvalue lies between float's thresholds (1e-12,
    1e-9), so float leaves it undecided; mp:30 (tau_hi = 1e-15) splits it into its two zero
    lines, each correct to mp accuracy (far below float's 1e-16)."""
    prec = Precision("mp", 30)
    with prec.context():
        Q, lines = _rotated_form(mpmath.mpf("1e-11"), mpmath.mpf(2) / 7)
        kind, subs, silent, margins, undecided = _zero_set([Q], prec)
    *_, und_float = _zero_set([numeric.to_float(Q)], Precision("float"))
    assert und_float
    assert not undecided and kind == "subspaces" and silent == [False, False]
    assert margins and margins[0] == pytest.approx(1e-11, rel=1e-9)
    assert len(subs) == 2
    with prec.context():
        for line in lines:
            v = np.array(line, dtype=object) / mpmath.sqrt(line[0] ** 2 + line[1] ** 2)
            dist = min(linalg.norm(v - S[:, 0] * (S[:, 0] @ v)) for S in subs)
            assert dist < mpmath.mpf(10) ** -25


def _flat_fourbar_screws(fb: fam.FourBar) -> np.ndarray:
    """R screws (z, p x z) = (0, 0, 1, 0, -x, 0) of the four joints on the x axis (mp)."""
    xs = [mpmath.mpf(x.numerator) / x.denominator for x in fb.points]
    S = np.empty((6, 4), dtype=object)
    S.fill(mpmath.mpf(0))
    for k, x in enumerate(xs):
        S[2, k] = mpmath.mpf(1)
        S[4, k] = -x
    return S


@pytest.mark.parametrize("prec", MP, ids=str)
def test_tangent_cone_of_a_folded_parallelogram_at_mp(prec: Precision) -> None:
    """The loop ground-crank-coupler-rocker of a parallelogram folded on the x axis, with its
    screws given exactly (no closure, no scaling): rank 2 on G, two transversal branches whose
    tangents are the closed-form ones to mp accuracy, found at order 2, decided at mp:N."""
    fb = fam.FourBar(F(2), F(1), F(2), F(1), (1, 1, -1), "parallelogram")
    expected = closed_form_tangents(fb)
    with prec.context():
        S = _flat_fourbar_screws(fb)
        G = np.zeros((6, 3), dtype=object)
        G.fill(mpmath.mpf(0))
        G[2, 0] = G[3, 1] = G[4, 2] = mpmath.mpf(1)  # omega_z, v_x, v_y
        chain = LoopChain([([k], 1) for k in range(4)], G)
        M = G.T @ S
        cone = tangent_cone(Expansion([chain], S), M, prec)
    assert cone.kind == "subspaces" and cone.order == 2 and cone.precision == str(prec)
    assert cone.eig_margin is not None and cone.eig_margin >= tau(prec.digits)[1]
    assert len(cone.subspaces) == 2 and all(W.shape == (4, 1) for W in cone.subspaces)
    assert all(W.dtype == object for W in cone.subspaces)
    with prec.context():
        for t in expected:
            v = np.array(t, dtype=object) / mpmath.sqrt(sum(x * x for x in t))
            dist = min(linalg.norm(v - W[:, 0] * (W[:, 0] @ v)) for W in cone.subspaces)
            assert dist < mpmath.mpf(10) ** (-(prec.digits // 2))


def test_float_cone_stays_numpy() -> None:
    fb = fam.FourBar(F(2), F(1), F(2), F(1), (1, 1, -1), "parallelogram")
    S = numeric.to_float(_flat_fourbar_screws(fb))
    G = np.eye(6)[:, 2:5]
    cone = tangent_cone(
        Expansion([LoopChain([([k], 1) for k in range(4)], G)], S), G.T @ S, Precision("float")
    )
    assert cone.precision == "float" and cone.kind == "subspaces"
    assert all(W.dtype == np.float64 for W in cone.subspaces)
    assert_same_lines(
        [W[:, 0] for W in cone.subspaces],
        [np.array(t, dtype=float) for t in closed_form_tangents(fb)],
        1e-12,
    )


# ----------------------------------------------------------------------------- 3. mechanisms at mp:N


@pytest.mark.parametrize("precision", ["mp:30", "mp:50"])
def test_parallelogram_example_fold_is_a_bifurcation_decided_at_mp(precision: str) -> None:
    """examples/parallelogram.yaml, configuration flat: A = (0,0), B = (1,0), C = (3,0),
    D = (2,0), i.e. the folded parallelogram g = 2, a = 1, b = 2, c = 1 of tests/families.py;
    two branches (parallelogram, anti-parallelogram) of mobility 1 with the closed-form
    tangents, every test at mp:N."""
    n = int(precision[3:])
    res = by_name(run(EXAMPLES / "parallelogram.yaml", precision))
    flat = res["flat"]
    assert flat["precision"] == precision
    assert (flat["closure_rank"]["rank"], flat["closure_rank"]["nullity"]) == (2, 2)
    f = finding(flat, "bifurcation")
    assert f["branches"] == 2 and f["branch_mobility"] == [1, 1] and f["order"] == 2
    assert f["precision"] == precision and f["test_precision"] == precision
    assert tau(n)[1] <= f["margin"]["eig_margin"] <= 1
    assert (f["margin"]["tau_lo"], f["margin"]["tau_hi"]) == pytest.approx(tau(n), rel=1e-12)
    fb = fam.FourBar(F(2), F(1), F(2), F(1), (1, 1, -1), "parallelogram")
    expected = [np.array([float(x) for x in t]) for t in closed_form_tangents(fb)]
    assert_same_lines(f["branch_tangents"], expected, 1e-12)
    # the input/output findings there are decided at mp:N as well
    for g in flat["singularities"]:
        assert g.get("test_precision", g["precision"]) == precision, g
    for name in ("reference", "crank-30", "anti-parallelogram"):
        assert res[name]["singularities"] == [], name


@pytest.mark.parametrize("precision", ["mp:30", "mp:50"])
@pytest.mark.parametrize(
    ("kind", "seed"), [("parallelogram", 21), ("parallelogram", 22), ("changepoint", 12)]
)
def test_family_folds_are_bifurcations_at_mp(
    tmp_path: Path, precision: str, kind: str, seed: int
) -> None:
    rng = np.random.default_rng(seed)
    fb = (
        fam.parallelogram_fourbar(rng)
        if kind == "parallelogram"
        else fam.changepoint_fourbar(rng, 1)
    )
    res = by_name(run(write(tmp_path, fb.name, fb.yaml({})), precision))
    fold = res["reference"]
    assert (fold["closure_rank"]["rank"], fold["closure_rank"]["nullity"]) == (2, 2)
    assert classes(fold) == ["bifurcation"]
    f = finding(fold, "bifurcation")
    assert f["branches"] == 2 and f["branch_mobility"] == [1, 1]
    assert f["test_precision"] == precision and "eig_margin" in f["margin"]
    expected = [np.array([float(x) for x in t]) for t in closed_form_tangents(fb)]
    assert_same_lines(f["branch_tangents"], expected, 1e-12)


def test_stretched_fourbar_is_isolated_at_mp50(tmp_path: Path) -> None:
    """a + b + c = g: the only configuration; the second-order form is definite (cone {0}) and
    nothing closes nearby: isolated, finite 0, generic null, decided at mp:50."""
    fb = fam.stretched_fourbar(np.random.default_rng(31))
    assert fb.a + fb.b + fb.c == fb.g
    c = by_name(run(write(tmp_path, fb.name, fb.yaml({})), "mp:50"))["reference"]
    assert c["precision"] == "mp:50"
    assert (c["closure_rank"]["rank"], c["closure_rank"]["nullity"]) == (2, 2)
    assert classes(c) == ["isolated"]
    f = finding(c, "isolated")
    assert f["test_precision"] == "mp:50" and f["margin"]["eig_margin"] >= tau(50)[1]
    assert (c["mobility"]["finite"], c["mobility"]["generic"], c["mobility"]["instantaneous"]) == (
        0,
        None,
        2,
    )


def test_near_a_change_point_fold_rank_and_cone_are_decided_at_mp50(tmp_path: Path) -> None:
    """A change-point four-bar moved by a crank angle d along each branch (closed form, 200
    digits).  d = 1e-20: float cannot tell the point from the fold (sigma_3 / sigma_1 ~ 1e-20 <
    tau_lo) and reports the fold's bifurcation; mp:50 decides rank 3 with the closed-form
    sigma_3 and finds a regular point.  d = 1e-45 is the fold to 50 digits (sigma_3 below
    tau_lo = 1e-40): mp:50 decides rank 2 and its cone, two branches with the fold's tangents."""
    fb = fam.changepoint_fourbar(np.random.default_rng(11), 0)
    configs, values = {}, {}
    with mpmath.workdps(200):
        for e in (20, 45):
            for br in (1, -1):
                name = f"d{e}-{'up' if br > 0 else 'down'}"
                values[name] = fb.pushed(mpmath.mpf(10) ** -e, br)
                configs[name] = {k: fam.d(v) for k, v in zip("ABCD", values[name], strict=True)}
    path = write(tmp_path, fb.name, fb.yaml(configs))
    flt = by_name(run(path, "float"))
    mp = by_name(run(path, "mp:50"))
    expected = [np.array([float(x) for x in t]) for t in closed_form_tangents(fb)]
    for name in configs:
        assert classes(flt[name]) == ["bifurcation"], name  # float: the fold
        c = mp[name]
        assert c["precision"] == "mp:50"
        if name.startswith("d20"):
            with mpmath.workdps(60):
                sig = closed_form_sigma(fb, values[name])
            assert 1e-22 < sig[2] / sig[0] < 1e-19  # of order d, far above tau_hi = 1e-25
            assert c["closure_rank"]["rank"] == 3, name
            margin = c["closure_rank"]["margin"]
            assert margin["kept"] == pytest.approx(float(sig[2]), rel=1e-6), name
            assert margin["sigma_max"] == pytest.approx(float(sig[0]), rel=1e-12), name
            assert c["singularities"] == [] and c["mobility"]["instantaneous"] == 1, name
        else:
            assert c["closure_rank"]["rank"] == 2, name
            f = finding(c, "bifurcation")
            assert f["branches"] == 2 and f["test_precision"] == "mp:50", name
            assert f["margin"]["dropped"] / f["margin"]["sigma_max"] <= tau(50)[0]
            assert_same_lines(f["branch_tangents"], expected, 1e-12)


def test_nearly_tangent_branches_float_cannot_decide_mp50_can(tmp_path: Path) -> None:
    """A change-point four-bar with a crank of 1e-11 (g = 5, b = 6, c = g + b - a, exact):
    its two branches cross at an angle of order sqrt(1e-11), so the eigenvalues of the
    second-order form differ by a ratio of order 1e-11, between float's thresholds: float
    cannot decide the form (degenerate, 'undecided'), mp:50 decides it: a bifurcation with the
    closed-form tangents."""
    a = F(1, 10**11)
    fb = fam.FourBar(F(5), a, F(6), F(11) - a, (1, -1, 1), "tiny-crank")
    path = write(tmp_path, fb.name, fb.yaml({}))
    flt = by_name(run(path, "float"))["reference"]
    f = finding(flt, "degenerate")
    assert f["test_precision"] == "float" and "undecided" in f["note"]
    c = by_name(run(path, "mp:50"))["reference"]
    assert (c["closure_rank"]["rank"], c["closure_rank"]["nullity"]) == (2, 2)
    f = finding(c, "bifurcation")
    assert f["branches"] == 2 and f["branch_mobility"] == [1, 1] and f["test_precision"] == "mp:50"
    # decided at mp:50 although float's tau_hi could not
    assert tau(50)[1] <= f["margin"]["eig_margin"] < 1e-9
    tangents = closed_form_tangents(fb, digits=300)
    expected = [np.array([float(x) for x in t]) for t in tangents]
    # the two tangents differ by about 1e-6: told apart to 1e-12
    got = [normalised(x) for x in f["branch_tangents"]]
    assert 1e-7 < np.max(np.abs(got[0] - got[1])) < 1e-5
    assert_same_lines(f["branch_tangents"], expected, 1e-12)
    # auto: an undecided form is an undecided verdict, re-decided at mp:50
    c = by_name(run(path, "auto"))["reference"]
    assert c["precision"] == "mp:50"
    assert finding(c, "bifurcation")["branch_mobility"] == [1, 1]


def test_rpr_output_singularity_is_decided_at_mp50(tmp_path: Path) -> None:
    """3-RPR with concurrent leg lines (tests/families.py): at the reference the platform turns
    about the common point O with the P joints locked (output, dimension 1) and the input
    rates are restricted; the ZFB ranks are decided at mp:50.  Turned by 1e-20 about O the
    lines are no longer concurrent (the concurrency determinant is ~1e-20, computed here):
    float cannot tell (it reports the output singularity), mp:50 finds it regular; turned by
    1e-45 it is the concurrent pose again to 50 digits."""
    rng = np.random.default_rng(41)
    rpr = fam.rpr_concurrent(rng)
    zero = (mpmath.mpf(0), mpmath.mpf(0))
    configs = {}
    with mpmath.workdps(200):
        for e in (20, 45):
            turn = mpmath.mpf(10) ** -e
            assert abs(rpr.concurrency(turn, zero)) > turn * 1e-3
            configs[f"turn{e}"] = rpr.moved(turn, zero)
    path = write(tmp_path, "rpr", rpr.yaml(configs))
    flt = by_name(run(path, "float"))
    mp = by_name(run(path, "mp:50"))
    rates, twist = rpr.output_motion()
    assert sorted(classes(flt["turn20"])) == ["impossible-input", "output"]
    assert mp["turn20"]["singularities"] == []
    assert mp["turn20"]["closure_rank"]["rank"] == 6
    for name in ("reference", "turn45"):
        c = mp[name]
        assert sorted(classes(c)) == ["impossible-input", "output"], name
        f = finding(c, "output")
        assert (f["dimension"], f["generic"]) == (1, 0)
        assert f["precision"] == f["test_precision"] == "mp:50"
        assert (f["margin"]["tau_lo"], f["margin"]["tau_hi"]) == pytest.approx(tau(50), rel=1e-12)
        assert np.max(np.abs(np.array(f["joint_rates"]) - normalised(rates))) < 1e-12
        t = np.array(f["output_twist"])
        t = t / np.linalg.norm(t[:3])
        assert min(np.max(np.abs(t - twist)), np.max(np.abs(t + twist))) < 1e-12
        g = finding(c, "impossible-input")
        assert g["rank"] == 2 and g["test_precision"] == "mp:50"


def test_exact_analysis_evaluates_its_tests_at_mp50() -> None:
    """exact: the rank is exact, the forms and the input/output ranks are evaluated at mp:50
    from the exact configuration, and the findings say so."""
    res = analyze(EXAMPLES / "parallelogram.yaml", configs=["flat"], precision="exact").to_json()
    (c,) = json.loads(json.dumps(res))["configurations"]
    assert c["precision"] == "exact" and c["closure_rank"]["rank"] == 2
    f = finding(c, "bifurcation")
    assert f["precision"] == "exact" and f["test_precision"] == "mp:50"
    assert f["branches"] == 2 and f["margin"]["eig_margin"] >= tau(50)[1]
    fb = fam.FourBar(F(2), F(1), F(2), F(1), (1, 1, -1), "parallelogram")
    expected = [np.array([float(x) for x in t]) for t in closed_form_tangents(fb)]
    assert_same_lines(f["branch_tangents"], expected, 1e-12)
    for g in c["singularities"]:
        if g["class"] != "bifurcation":
            assert g["test_precision"] == "mp:50", g


def test_float_and_auto_findings_say_float() -> None:
    for precision in ("float", "auto"):
        flat = by_name(run(EXAMPLES / "parallelogram.yaml", precision))["flat"]
        assert flat["precision"] == "float"
        for g in flat["singularities"]:
            assert g["test_precision"] == "float", g
        assert math.isclose(finding(flat, "bifurcation")["margin"]["tau_hi"], 1e-9)
