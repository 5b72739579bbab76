"""Sweeps against answers mechsing does not compute: closed forms from the planar geometry
(tests/reference/sweep_truth.py), each also on the mechanism scaled by 1e-3 (the same file
in millimetres: the same numbers, a thousandth of the size in SI)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from mechsing.sweeps import sweep
from tests.reference import sweep_truth as truth

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

#: how well a located value must match its closed form (the issue asks 1e-10)
LOCATED = 1e-10


def _millimetres(tmp_path: Path, name: str) -> Path:
    """The example with ``units: {length: mm}``: every length a thousandth in SI."""
    text = (EXAMPLES / name).read_text()
    lines = [ln for ln in text.splitlines() if not ln.startswith("units:")]
    i = next(k for k, ln in enumerate(lines) if ln.startswith("mechanism:"))
    angle = "deg" if "angle: deg" in text else "rad"
    lines.insert(i + 1, f"units: {{length: mm, angle: {angle}}}")
    out = tmp_path / name
    out.write_text("\n".join(lines) + "\n")
    return out


def _values(r, kind=None, test=None):
    return sorted(
        p.values[0]
        for p in r.located
        if (kind is None or p.kind == kind) and (test is None or test in p.tests)
    )


@pytest.mark.parametrize("k", [1e-3, 1.0, 1e3])
def test_crank_rocker_turns_fully_and_meets_only_its_rockers_limits(tmp_path, k):
    """The crank turns 360 deg with no fold, no closure and no output singularity; the input
    test vanishes exactly where the rocker stops (crank and coupler collinear); the same
    angles on the four-bar scaled by k."""
    path = EXAMPLES / "fourbar.yaml" if k == 1.0 else _scaled(tmp_path, "fourbar.yaml", k)
    r = sweep(path, ["A=0:360:0.5"])
    assert r.reached.all()
    assert not [p for p in r.located if p.kind == "fold"]
    assert not [p for p in r.located if {"closure", "output"} & set(p.tests)]
    limits = truth.four_bar_output_limits((0, 0), (1, 0), (3, 2), (4, 0))
    expected = sorted(lim.value % (2 * math.pi) for lim in limits)
    found = _values(r, test="input")
    assert len(found) == 2
    np.testing.assert_allclose(found, expected, atol=LOCATED)
    for p in r.located:
        assert p.classes is not None and "input" in p.classes


@pytest.mark.parametrize("scaled", [False, True])
def test_double_rocker_stops_at_its_limits_from_the_law_of_cosines(tmp_path, scaled):
    """A non-Grashof input rocks between -120 and +120 deg: two folds located to 1e-10 rad and
    classified as output singularities; the samples beyond are not reached."""
    path = (
        _millimetres(tmp_path, "double_rocker.yaml") if scaled else EXAMPLES / "double_rocker.yaml"
    )
    r = sweep(path, ["A=-3.1:3.1:0.01"])
    folds = _values(r, kind="fold")
    np.testing.assert_allclose(folds, [-2 * math.pi / 3, 2 * math.pi / 3], atol=LOCATED)
    values = r.variables[0].values
    inside = np.abs(values) < 2 * math.pi / 3 - 1e-9
    assert np.array_equal(r.reached, inside)
    for p in r.located:
        if p.kind == "fold":
            assert "output" in (p.classes or ())


@pytest.mark.parametrize("scaled", [False, True])
def test_offset_slider_crank_dead_centres(tmp_path, scaled):
    """The slider (input) stops at its two dead centres x = sqrt((l +- r)^2 - e^2)."""
    name = "slider_crank_slider_input.yaml"
    path = _millimetres(tmp_path, name) if scaled else EXAMPLES / name
    k = 1e-3 if scaled else 1.0
    r = sweep(path, ["P=-4:4:0.01"])
    dead = truth.slider_crank_dead_centres((0, 0), (0, -1), (3.2, 1.4), (1, 0))
    expected = sorted(v * k for v in dead.values())
    np.testing.assert_allclose(_values(r, kind="fold"), expected, atol=LOCATED * k)
    assert all("output" in (p.classes or ()) for p in r.located if p.kind == "fold")


@pytest.mark.parametrize("k", [1e-3, 1.0, 1e3])
def test_ur5_grid_loci_lie_where_the_closed_form_det_j_vanishes(tmp_path, k):
    """Over (J3, J5) the output chain loses rank where det J = 0 (elbow: sin J3 = 0; wrist:
    sin J5 = 0): every located point zeroes the closed form, and every grid cell where it
    changes sign along a row holds a located point; the same on the arm scaled by k."""
    path = EXAMPLES / "ur5.yaml" if k == 1.0 else _scaled(tmp_path, "ur5.yaml", k)
    r = sweep(path, ["J3=-2:2:0.25", "J5=-2:2:0.25"], "regular")
    regular = {"J1": 0.0, "J2": -math.pi / 4, "J4": -math.pi / 4, "J6": 0.0}
    assert r.located
    for p in r.located:
        theta = np.array(
            [regular["J1"], regular["J2"], p.values[0], regular["J4"], p.values[1], regular["J6"]]
        )
        scale = truth.ur5_det_j(np.array([0.0, -0.7, 1.0, -0.3, 1.0, 0.0]))
        assert abs(truth.ur5_det_j(theta)) <= 1e-8 * abs(scale)
    xs, ys = r.variables[0].values, r.variables[1].values
    for _j, y in enumerate(ys):
        th = np.zeros((len(xs), 6))
        th[:, 1], th[:, 2], th[:, 3], th[:, 4] = -math.pi / 4, xs, -math.pi / 4, y
        d = truth.ur5_det_j(th)
        for i in range(len(xs) - 1):
            if d[i] * d[i + 1] < 0:
                assert any(
                    p.between == "row"
                    and abs(p.values[1] - y) < 1e-12
                    and xs[i] - 1e-12 <= p.values[0] <= xs[i + 1] + 1e-12
                    for p in r.located
                ), (y, xs[i])


@pytest.mark.parametrize("k", [1e-3, 1.0, 1e3])
def test_five_bar_grid_type_one_loci_match_the_independent_determinant(tmp_path, k):
    """Over the two inputs, the input (Type I) singularities the sweep locates zero the
    determinant written from the planar geometry, and every grid cell whose corners give
    that determinant opposite signs holds one; the folds (the end of the assembled region)
    zero the discriminant of the assembly (Type II); the same on the five-bar scaled by k."""
    path = EXAMPLES / "five_bar.yaml" if k == 1.0 else _scaled(tmp_path, "five_bar.yaml", k)
    r = sweep(path, ["A1=-0.6:0.6:0.1", "A2=-0.6:0.6:0.1"])
    assert [p for p in r.located if p.kind == "fold"] and [
        p for p in r.located if "input" in p.tests
    ]
    mode = truth.FIVE_BAR.reference_mode()
    size = max(truth.FIVE_BAR.lengths()) ** 2
    for p in r.located:
        t1, t2 = p.values
        if p.kind == "fold":
            # the distal links aligned: the discriminant of the assembly vanishes (it changes
            # sign there, where the Type II determinant, its square root, is not defined)
            assert abs(truth.five_bar_discriminant(np.array(t1), np.array(t2))) <= 1e-9 * size**2
        elif "input" in p.tests:
            d = truth.five_bar_type1_det(np.array(t1), np.array(t2), mode)
            assert abs(d) <= 1e-8 * size**2
    xs, ys = r.variables[0].values, r.variables[1].values
    D = truth.five_bar_type1_det(xs[None, :], ys[:, None], mode)
    type1 = [p for p in r.located if p.kind != "fold" and "input" in p.tests]
    for j in range(len(ys) - 1):
        for i in range(len(xs) - 1):
            corners = D[j : j + 2, i : i + 2]
            if np.all(np.isfinite(corners)) and corners.min() < 0 < corners.max():
                assert any(
                    xs[i] - 1e-9 <= p.values[0] <= xs[i + 1] + 1e-9
                    and ys[j] - 1e-9 <= p.values[1] <= ys[j + 1] + 1e-9
                    for p in type1
                ), (xs[i], ys[j])


@pytest.mark.parametrize(
    ("spec", "k"),
    [
        ("A=-3.1:3.1:0.007", 1.0),
        ("A=1:-1:0.013", 1.0),
        ("A=-6.3:6.3:0.05", 1.0),
        # coarse steps: samples 0.2 apart, one of them exactly on the flat position
        ("A=-7:7:0.2", 1.0),
        ("A=-7:7:0.2", 1e-3),
        ("A=-3.1:3.1:0.007", 1e-3),
        ("A=-3.1:3.1:0.007", 1e3),
    ],
)
def test_change_point_four_bar_bifurcation_at_its_flat_position(tmp_path, spec, k):
    """At the Grashof change point the crank passes the flat position (A = 0 mod 2 pi, all
    joints collinear), where two branches cross: located to 1e-10 rad and classified as a
    bifurcation, wherever the samples fall and whatever the mechanism's size."""
    name = "fourbar_changepoint.yaml"
    path = EXAMPLES / name if k == 1.0 else _scaled(tmp_path, name, k)
    r = sweep(path, [spec], "crank-up")
    assert r.reached.all()
    flats = truth.four_bar_flat_positions((0, 0), (1, 0), (6, 0), (4, 0))
    lo, hi = sorted(r.variables[0].values[[0, -1]])
    expected = sorted(
        f + 2 * math.pi * k for f in flats for k in range(-2, 3) if lo <= f + 2 * math.pi * k <= hi
    )
    found = _values(r, test="closure")
    np.testing.assert_allclose(found, expected, atol=LOCATED)
    for p in r.located:
        if "closure" in p.tests:
            assert "bifurcation" in (p.classes or ())


def _scaled(tmp_path: Path, name: str, k: float) -> Path:
    """The example with every length times k (points, the output point, the values of
    prismatic joints), written as expressions of the file's own numbers."""
    import yaml

    data = yaml.safe_load((EXAMPLES / name).read_text())

    def times(x):
        return f"({x})*{k!r}"

    prismatic = {j["name"] for j in data["joints"] if j["type"] == "P"}
    for j in data["joints"]:
        if "point" in j:
            j["point"] = [times(x) for x in j["point"]]
    if isinstance(data.get("output"), dict) and "point" in data["output"]:
        data["output"]["point"] = [times(x) for x in data["output"]["point"]]
    for cfg in (data.get("configurations") or {}).values():
        for jn in list(cfg or {}):
            if jn in prismatic:
                cfg[jn] = times(cfg[jn])
    out = tmp_path / f"x{k:g}-{name}"
    out.write_text(yaml.safe_dump(data, sort_keys=False))
    return out


@pytest.mark.parametrize("k", [1e-3, 1.0, 1e3])
def test_three_rpr_type_two_locus_where_the_legs_are_concurrent(tmp_path, k):
    """Over the platform's (x, y) at its reference orientation, the output (Type II) locus
    is where the three leg lines meet in a point: every located point zeroes the
    concurrency determinant, and every grid cell whose corners give it opposite signs
    holds a located point; the same, scaled, on the mechanism scaled by k."""
    path = EXAMPLES / "planar_3rpr.yaml" if k == 1.0 else _scaled(tmp_path, "planar_3rpr.yaml", k)
    r = sweep(
        path,
        [
            f"pose.x={0.4 * k!r}:{1.6 * k!r}:{0.2 * k!r}",
            f"pose.y={2.4 * k!r}:{3.4 * k!r}:{0.2 * k!r}",
        ],
    )
    assert r.reached.all()
    xs, ys = r.variables[0].values / k, r.variables[1].values / k
    typ2 = [p for p in r.located if "output" in p.tests]
    assert typ2 and r.loci
    for p in typ2:
        d = truth.rpr3_concurrency_det(
            np.array(p.values[0] / k), np.array(p.values[1] / k), np.array(0.0), unit=False
        )
        assert abs(d) <= 1e-8
        if p.between == "row":  # the points found along the rows are classified
            assert "output" in (p.classes or ())
    D = truth.rpr3_concurrency_det(
        xs[None, :], ys[:, None], np.zeros((len(ys), len(xs))), unit=False
    )
    for j in range(len(ys) - 1):
        for i in range(len(xs) - 1):
            corners = D[j : j + 2, i : i + 2]
            if corners.min() < 0 < corners.max():
                assert any(
                    xs[i] - 1e-9 <= p.values[0] / k <= xs[i + 1] + 1e-9
                    and ys[j] - 1e-9 <= p.values[1] / k <= ys[j + 1] + 1e-9
                    for p in typ2
                ), (xs[i], ys[j])


def test_three_rpr_every_grid_edge_the_locus_crosses_holds_a_located_point():
    """On a coarse grid (samples 0.2 m and 0.25 m apart, the locus bending between them),
    every edge of the grid, along a row or a column, whose ends give the independent
    concurrency determinant opposite signs holds a located point on it, and the points
    make one locus."""
    r = sweep(EXAMPLES / "planar_3rpr.yaml", ["pose.x=0:2:0.2", "pose.y=0:2.5:0.25"])
    assert r.reached.all()
    xs, ys = r.variables[0].values, r.variables[1].values
    typ2 = [p for p in r.located if "output" in p.tests]
    D = truth.rpr3_concurrency_det(
        xs[None, :], ys[:, None], np.zeros((len(ys), len(xs))), unit=False
    )

    def on(x0, x1, y0, y1):
        return any(
            min(x0, x1) - 1e-9 <= p.values[0] <= max(x0, x1) + 1e-9
            and min(y0, y1) - 1e-9 <= p.values[1] <= max(y0, y1) + 1e-9
            for p in typ2
        )

    crossed = 0
    for j in range(len(ys)):
        for i in range(len(xs)):
            if i + 1 < len(xs) and D[j, i] * D[j, i + 1] < 0:
                crossed += 1
                assert on(xs[i], xs[i + 1], ys[j], ys[j]), ("row", ys[j], xs[i])
            if j + 1 < len(ys) and D[j, i] * D[j + 1, i] < 0:
                crossed += 1
                assert on(xs[i], xs[i], ys[j], ys[j + 1]), ("column", xs[i], ys[j])
    assert crossed == len(typ2)
    assert len(r.loci) == 1


@pytest.mark.parametrize("k", [1e-3, 1e3])
def test_scaled_slider_crank_and_double_rocker(tmp_path, k):
    """The slider's dead centres scale with the mechanism; the rocker's angular limits do
    not move."""
    r = sweep(
        _scaled(tmp_path, "slider_crank_slider_input.yaml", k),
        [f"P={-4 * k!r}:{4 * k!r}:{0.01 * k!r}"],
    )
    dead = truth.slider_crank_dead_centres((0, 0), (0, -1), (3.2, 1.4), (1, 0))
    np.testing.assert_allclose(
        _values(r, kind="fold"), sorted(k * v for v in dead.values()), atol=LOCATED * k
    )
    r = sweep(_scaled(tmp_path, "double_rocker.yaml", k), ["A=-3.1:3.1:0.01"])
    np.testing.assert_allclose(
        _values(r, kind="fold"), [-2 * math.pi / 3, 2 * math.pi / 3], atol=LOCATED
    )


@pytest.mark.parametrize(
    ("name", "spec", "start", "cls"),
    [
        ("slider_crank_slider_input.yaml", "P=-4:4:0.05", None, "output"),
        ("fourbar.yaml", "A=0:360:2", None, "input"),
        ("fourbar_changepoint.yaml", "A=-1:1:0.3", "crank-up", "bifurcation"),
    ],
)
def test_located_points_classified_at_mp_digits(name, spec, start, cls):
    """At mp:30 each located point is found again at 30 digits before its analysis (a point
    only float-close to the singularity would be regular at 30 digits): every one gets its
    class, decided at mp:30 on a singular value far below mp:30's thresholds."""
    r = sweep(EXAMPLES / name, [spec], start, precision="mp:30")
    assert r.located
    for p in r.located:
        assert p.precision == "mp:30"
        assert cls in (p.classes or ()), (p.values, p.classes)
        assert p.margin is not None and p.margin["dropped"] < 1e-25
    assert any("located again at mp:30" in n for n in r.notes)


FIVE_BAR_IRRATIONAL_POINT = """\
mechanism: five-bar-irrational-point
bodies: [ground, prox1, dist1, prox2, dist2]
joints:
  - {name: A1, type: R, between: [ground, prox1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B1, type: R, between: [prox1, dist1], axis: [0, 0, 1], point: [0, "3/2", 0]}
  - {name: P, type: R, between: [dist1, dist2], axis: [0, 0, 1], point: [1, "3/2 + sqrt(3)", 0]}
  - {name: B2, type: R, between: [prox2, dist2], axis: [0, 0, 1], point: [2, "3/2", 0]}
  - {name: A2, type: R, between: [ground, prox2], axis: [0, 0, 1], point: [2, 0, 0]}
inputs: [A1, A2]
output: {body: dist1, point: [1, "3/2 + sqrt(3)", 0]}
"""


def test_an_input_singularity_is_placed_again_with_the_files_output_point(tmp_path):
    """A five-bar whose output point is irrational (x = 1, y = 3/2 + sqrt(3)): at mp:30 the
    input singularity of leg 1 (its proximal and distal links in line, |P - A1| = 7/2,
    with A2 held at 0) is found again to 30 digits, as the circle about A1 of radius 7/2
    meets the circle about B2 = (2, 3/2) of radius 2; the test's matrix must take the
    point at 30 digits (its float rounding moves the zero by about 1e-17, and the
    analysis there then finds nothing decided)."""
    import mpmath

    f = tmp_path / "five_bar_irrational_point.yaml"
    f.write_text(FIVE_BAR_IRRATIONAL_POINT)
    r = sweep(f, ["A1=-0.5:-0.1:0.05"], precision="mp:30")
    stretched = [p for p in r.located if "input" in p.tests]
    assert len(stretched) == 1 and stretched[0].values_text is not None
    with mpmath.workdps(40):
        # the intersection of the two circles on the reference's side (P above B1 B2)
        d = mpmath.mpf(5) / 2
        along = (mpmath.mpf(7) ** 2 / 4 - 4 + d**2) / (2 * d)
        h = mpmath.sqrt(mpmath.mpf(7) ** 2 / 4 - along**2)
        e = (mpmath.mpf(2) / d, mpmath.mpf(3) / 2 / d)
        px, py = along * e[0] - h * e[1], along * e[1] + h * e[0]
        want = mpmath.atan2(-px, py)  # B1 = 3/2 (-sin A1, cos A1) points at P
        got = mpmath.mpf(stretched[0].values_text[0])
        assert abs(got - want) < mpmath.mpf(10) ** -28, (got, want)
    assert "input" in (stretched[0].classes or ())
    assert stretched[0].margin is not None and stretched[0].margin["dropped"] < 1e-25


def test_a_bifurcation_is_placed_again_to_all_its_digits():
    """The change-point four-bar's flat positions (A = 0, +-2 pi: the closure loses rank,
    two branches cross) found again at mp:30 carry 30 correct digits, not the 15 a double
    root of the closure leaves to a search on the test's determinant: each within a unit
    in the 29th place of 2 pi k (the placed point solves the regular system of the
    singular point, not the closure for a held crank angle)."""
    import mpmath

    r = sweep(EXAMPLES / "fourbar_changepoint.yaml", ["A=-7:7:0.2"], precision="mp:30")
    flats = [p for p in r.located if "closure" in p.tests]
    assert len(flats) == 3 and all(p.values_text is not None for p in flats)
    with mpmath.workdps(60):
        for p, k in zip(sorted(flats, key=lambda p: p.values[0]), (-1, 0, 1), strict=True):
            error = abs(mpmath.mpf(p.values_text[0]) - 2 * k * mpmath.pi)
            assert error < mpmath.mpf(10) ** -29 * max(1, 2 * mpmath.pi * abs(k)), (k, error)
            assert p.margin is not None and p.margin["dropped"] < 1e-29


def _joint_digits(p) -> list:
    import mpmath

    return [mpmath.mpf(x) for _, texts in p.joints_text for x in texts]


def test_a_bifurcation_placed_at_n_digits_agrees_with_its_2n_plus_10_placement(monkeypatch):
    """The anti-parallelogram's flat positions (A = +-pi/2) at mp:30: placed by their
    regular system at N digits and a few guard digits, their joints agree with the
    placement at 2N + 10 digits (the first attempt of the earlier rule) to 30 digits, with
    the same classes; and where that system does not converge at N digits the point is
    still placed, at 2N + 10 digits (the secant's fallback as before)."""
    import mpmath

    import mechsing.sweeps.classify as classify
    from mechsing.sweeps.relocate import Relocator

    args = (EXAMPLES / "parallelogram.yaml", ["A=-4:4:0.2"], "anti-parallelogram")

    def flats(r) -> list:
        out = sorted((p for p in r.located if "closure" in p.tests), key=lambda p: p.values[0])
        assert len(out) == 2 and all("bifurcation" in p.classes for p in out)
        assert all(p.margin is not None and p.margin["dropped"] < 1e-29 for p in out)
        return out

    at_n = flats(sweep(*args, precision="mp:30"))
    with monkeypatch.context() as m:
        m.setattr(classify, "BIFURCATION_GUARD_DIGITS", 30 + 10)
        deep = flats(sweep(*args, precision="mp:30"))
    asked = []
    bifurcation = Relocator.bifurcation

    def fails_below_70(self, z):
        asked.append(self.prec.digits)
        return None if self.prec.digits < 70 else bifurcation(self, z)

    monkeypatch.setattr(Relocator, "bifurcation", fails_below_70)
    fallback = flats(sweep(*args, precision="mp:30"))
    assert sorted(set(asked)) == [30 + classify.BIFURCATION_GUARD_DIGITS, 70]
    with mpmath.workdps(60):
        for a, b, c in zip(at_n, deep, fallback, strict=True):
            assert a.classes == b.classes == c.classes
            for x, y, z in zip(_joint_digits(a), _joint_digits(b), _joint_digits(c), strict=True):
                assert abs(x - y) < mpmath.mpf(10) ** -30 * max(1, abs(y)), (x, y)
                assert abs(z - y) < mpmath.mpf(10) ** -30 * max(1, abs(y)), (z, y)


def test_sweep_starting_at_a_limit_of_travel_goes_the_reachable_way():
    """From the double rocker's limit (a fold: continuation has no direction there) the
    sweep steps off along the curve and reaches the other limit."""
    r = sweep(EXAMPLES / "double_rocker.yaml", ["A=-3:3:0.1"], "limit")
    np.testing.assert_allclose(
        _values(r, kind="fold"), [-2 * math.pi / 3, 2 * math.pi / 3], atol=LOCATED
    )


def test_sweep_starting_at_a_dead_centre_reports_both():
    r = sweep(EXAMPLES / "slider_crank_slider_input.yaml", ["P=-1:2:0.1"], "dead-centre")
    dead = truth.slider_crank_dead_centres((0, 0), (0, -1), (3.2, 1.4), (1, 0))
    np.testing.assert_allclose(_values(r, kind="fold"), sorted(dead.values()), atol=LOCATED)


@pytest.mark.parametrize(
    ("name", "spec", "words"),
    [
        ("stewart_octahedral.yaml", "S1[2]=-1:1:0.1", "5 more degree(s) of freedom"),
        ("fourbar.yaml", "pose.rz=-90:90:1", "cannot move along pose.rz"),
        ("planar_3rpr.yaml", "pose.z=0:1:0.1", "cannot move along pose.z"),
    ],
)
def test_a_sweep_whose_path_is_not_a_curve_is_refused(name, spec, words):
    """Sweeping a passive coordinate of a mechanism of mobility 6 leaves the path
    undetermined; a pose coordinate the output cannot move along leaves none: both are
    refused with the reason, before anything is followed."""
    from mechsing.errors import UserError

    with pytest.raises(UserError, match=re.escape(words)):
        sweep(EXAMPLES / name, [spec])


def test_a_start_on_a_bifurcation_follows_a_branch_both_ways():
    """The change-point four-bar's reference is its flat position, where two branches
    cross (the path's curve has two directions there): the sweep steps onto one branch,
    says so, goes both ways and still locates the flat positions on it (A = 0, +-2 pi)."""
    r = sweep(EXAMPLES / "fourbar_changepoint.yaml", ["A=-7:7:0.2"])
    assert r.reached.all()
    assert any("branches of the path cross" in n for n in r.notes)
    found = _values(r, test="closure")
    np.testing.assert_allclose(found, [-2 * math.pi, 0.0, 2 * math.pi], atol=LOCATED)
    assert all("bifurcation" in (p.classes or ()) for p in r.located if "closure" in p.tests)


@pytest.mark.parametrize("step", [0.1, 0.2])
def test_auto_locates_again_at_mp50_what_it_re_decides_there(step):
    """The anti-parallelogram passes its flat position (a bifurcation): where auto re-decides
    the located point at mp:50, it first finds the point again at 50 digits, so the verdict
    is the bifurcation, not the regular neighbour float placed."""
    r = sweep(EXAMPLES / "parallelogram.yaml", [f"A=-4:4:{step}"], "anti-parallelogram")
    flats = [p for p in r.located if "closure" in p.tests]
    np.testing.assert_allclose(
        sorted(p.values[0] for p in flats), [-math.pi / 2, math.pi / 2], atol=LOCATED
    )
    assert all("bifurcation" in (p.classes or ()) for p in flats)


def test_a_path_inside_a_singular_set_says_so_instead_of_locating_noise():
    """From the UR5's reference pose (wrist singular: J5 = 0) a sweep of J3 keeps the wrist
    singularity all along: the output chain's rank is 5 at every sample, so there is no
    isolated singularity to place, and the report says that the path lies in the set."""
    r = sweep(EXAMPLES / "ur5.yaml", ["J3=-4:4:0.1"])
    assert not r.located
    assert any("input is singular at every reached sample" in n for n in r.notes)


def test_a_further_rank_drop_inside_a_singular_set_is_located():
    """The PUMA 560's reference has its wrist singular (J5 = 0), so a sweep of J3 lies in
    that singular set all along; the elbow singularity is a further drop of the arm's
    rank inside it, located where the wrist centre, rotated about J3's axis (y), comes in
    line with J2 and J3: the J3-to-wrist-centre vector (0.0203, 0, -0.4318) rotated by q
    about y has no z component, tan q = -0.4318 / 0.0203, q = pi - atan(4318/203) here."""
    r = sweep(EXAMPLES / "puma560.yaml", ["J3=1.5:1.7:0.003"])
    elbow = math.pi - math.atan(4318 / 203)
    np.testing.assert_allclose(_values(r, test="input"), [elbow], atol=LOCATED)
    assert any("inside that set its rank is 5" in n for n in r.notes)


def test_a_grid_covers_the_assembled_region_beyond_its_first_column():
    """The five-bar over a wide grid of its inputs: the first column (A1 = 0) misses the
    rows where the assembled region lies to one side, and those rows are started from a
    neighbouring row instead.  Every sample of the start's assembled region (the
    discriminant of the assembly positive, connected to the start on the grid) is
    reached, and nothing outside the assembled set; the folds that bound the region on
    neighbouring rows are chained into loci."""
    from scipy import ndimage

    r = sweep(EXAMPLES / "five_bar.yaml", ["A1=-3:3:0.25", "A2=-3:3:0.25"], precision="float")
    xs, ys = r.variables[0].values, r.variables[1].values
    D = truth.five_bar_discriminant(xs[None, :], ys[:, None])
    labels, _ = ndimage.label(D > 0)
    region = labels == labels[np.argmin(np.abs(ys)), np.argmin(np.abs(xs))]
    reached = np.asarray(r.reached).reshape(len(ys), len(xs))
    assert not np.any(region & ~reached)
    assert np.all(D[reached] > 0)
    assert any("started from a neighbouring row" in n for n in r.notes)
    folds = [p for p in r.located if p.kind == "fold"]
    size = max(truth.FIVE_BAR.lengths()) ** 2
    for p in folds:
        assert abs(truth.five_bar_discriminant(np.array(p.values[0]), np.array(p.values[1]))) <= (
            1e-9 * size**2
        )
    step = float(ys[1] - ys[0])
    loci = [lc for lc in r.loci if lc.test == "output"]
    assert loci and 3 * len(loci) < len(folds)
    for lc in loci:
        rows = lc.vertices[:, 1] / step
        assert np.all(np.abs(np.diff(rows)) <= 1 + 1e-9)


def test_located_classes_and_margin_are_those_of_the_json():
    """A located point's classes and margin, read from its findings, are the ones its
    configuration's JSON lists (the contract the sweep's summary quotes): the five-bar's
    grid crosses serial (type I) and input/output singularities."""
    r = sweep(EXAMPLES / "five_bar.yaml", ["A1=-0.4:0.4:0.1", "A2=-0.4:0.4:0.1"])
    classified = [p for p in r.located if p.configuration is not None]
    assert classified
    seen = set()
    for p in classified:
        js = p.configuration.to_json()["singularities"]
        assert p.classes == tuple(dict.fromkeys(s["class"] for s in js))
        assert p.margin == next((s["margin"] for s in js if s.get("margin")), None)
        seen.update(p.classes)
    assert "serial" in seen
