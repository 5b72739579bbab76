"""``mechsing analyze`` through its JSON contract (issue 5, docs/json.md).

Every expected value comes from outside mechsing: the published facts in each example's header
comment (tests/mechanisms.py, PUBLISHED), the definitions of docs/precision.md (thresholds,
commensurate scaling), closed forms derived in tests/mechanisms.py (the change-point four-bar
family and its singular values), or mechsing's own output on an equivalent input (scale
invariance, determinism).

Analyses run in-process through ``mechsing.cli.main`` and are cached per (file, options), so each
example is analysed once per session (one real subprocess run checks the installed command).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from tests.cli import run_cli, run_cli_subprocess
from tests.mechanisms import (
    EXAMPLES,
    LENGTH_COORDS,
    PUBLISHED,
    SCALES,
    all_axis_points_at_origin,
    analyze_json,
    analyze_text,
    by_name,
    changepoint_family,
    changepoint_length_scale,
    classes,
    configuration_names,
    joint_types,
    scaled_file,
    total_dof,
)

EXAMPLE_FILES = sorted(p.name for p in EXAMPLES.glob("*.yaml"))


def loop_map(config: dict) -> dict[frozenset[str], dict]:
    return {frozenset(lp["joints"]): lp for lp in config["loops"]}


def test_every_example_has_published_facts() -> None:
    assert sorted(PUBLISHED) == EXAMPLE_FILES


# ============================================================================ 1. published facts


@pytest.mark.parametrize("name", EXAMPLE_FILES)
def test_published_mobility(name: str) -> None:
    """Published mobility (`finite`) and spatial Gruebler at every configuration; at the regular
    configurations the closure system has the generic rank dof - mobility, no increased mobility;
    the group mobility is total dof minus the loops' subgroup dimensions."""
    pub = PUBLISHED[name]
    path = EXAMPLES / name
    res = analyze_json(path)
    configs = by_name(res)
    assert set(configuration_names(path)) <= set(configs)
    dof = total_dof(path)
    for cname, c in configs.items():
        assert "error" not in c, (cname, c.get("error"))
        mob = c["mobility"]
        assert mob["finite"] == pub.mobility, (cname, mob)
        assert mob["grubler"] == pub.grubler, (cname, mob)
        if pub.loops is not None:
            assert mob["group"] == dof - sum(d for _, d in pub.loops.values()), (cname, mob)
    for cname in pub.regular:
        c = configs[cname]
        mob = c["mobility"]
        assert mob["instantaneous"] == mob["generic"] == pub.mobility, (cname, mob)
        assert c["closure_rank"]["nullity"] == pub.mobility, cname
        assert c["closure_rank"]["rank"] == dof - pub.mobility, cname
        assert "increased-mobility" not in classes(c), cname
    for cname, rank in pub.ranks.items():
        assert configs[cname]["closure_rank"]["rank"] == rank, cname
        assert configs[cname]["closure_rank"]["nullity"] == dof - rank, cname


@pytest.mark.parametrize("name", [n for n in EXAMPLE_FILES if PUBLISHED[n].loops is not None])
def test_published_loops(name: str) -> None:
    """Loops (as sets of joints) with their generated subgroup type and published ranks."""
    pub = PUBLISHED[name]
    assert pub.loops is not None
    for cname, c in by_name(analyze_json(EXAMPLES / name)).items():
        loops = loop_map(c)
        assert set(loops) == set(pub.loops), cname
        for joints, (typ, dim) in pub.loops.items():
            sub = loops[joints]["subgroup"]
            assert (sub["type"], sub["dim"]) == (typ, dim), (cname, sub)
        if cname in pub.loop_ranks:
            (only,) = loops.values()
            assert only["rank"] == pub.loop_ranks[cname], cname


def test_fourbar_loop_is_planar_about_z() -> None:
    # the normal exactly [0, 0, 1] in every precision (the JSON contract): identified from
    # float screws, its components of round-off (1e-16) are below the display floor, zero
    for precision in ("auto", "float", "mp:30"):
        for c in analyze_json(EXAMPLES / "fourbar.yaml", "--precision", precision)[
            "configurations"
        ]:
            (lp,) = c["loops"]
            assert lp["subgroup"]["type"] == "G"
            assert lp["subgroup"]["dim"] == 3
            assert lp["rank"] == 3
            assert lp["subgroup"]["params"]["normal"] == [0, 0, 1], (precision, c["name"])


def test_spherical_4r_loop_is_S_about_the_sphere_centre() -> None:
    """All four axes pass through the origin: the loop moves in S(O), rank 3, unit-free (L is 1
    because every axis point nearest the origin is the origin itself: L's fallback)."""
    res = analyze_json(EXAMPLES / "spherical_4r.yaml")
    assert res["precision"]["length_scale"] == 1.0
    for c in res["configurations"]:
        (lp,) = c["loops"]
        assert (lp["subgroup"]["type"], lp["subgroup"]["dim"], lp["rank"]) == ("S", 3, 3)
        np.testing.assert_allclose(lp["subgroup"]["params"]["point"], [0, 0, 0], atol=1e-12)


def test_bennett_is_D_with_rank_3() -> None:
    """Bennett: the joints generate D, yet the screws have rank 3 everywhere; Gruebler -2,
    finite 1; the fourth singular value vanishes (3 redundant constraints)."""
    for c in analyze_json(EXAMPLES / "bennett.yaml")["configurations"]:
        (lp,) = c["loops"]
        assert (lp["subgroup"]["type"], lp["subgroup"]["dim"], lp["rank"]) == ("D", 6, 3)
        assert c["closure_rank"]["rank"] == 3
        sig = lp["sigma"]
        assert len(sig) == 4
        assert sig[2] >= 1e-9 * sig[0] and sig[3] <= 1e-12 * sig[0], sig
        assert c["mobility"]["grubler"] == -2
        assert c["mobility"]["finite"] == 1
        assert c["singular"] is False


def test_sarrus_moves_although_gruebler_is_zero() -> None:
    configs = by_name(analyze_json(EXAMPLES / "sarrus.yaml"))
    for c in configs.values():
        assert c["mobility"]["grubler"] == 0
        assert c["mobility"]["group"] == 0  # 6 - 6 (the group formula, wrong for Sarrus)
        assert c["mobility"]["finite"] == 1
    # stretched: both legs' axes coplanar, closure rank 4 (header): a singular configuration
    assert configs["stretched"]["singular"] is True
    assert configs["raised"]["singular"] is False


def test_planar_3rpr_loops() -> None:
    """Two independent loops (cycle rank 9 - 8 + 1 = 2), each made of two legs R-P-R, each planar
    in G(z) with rank 3; group mobility 9 - 3 - 3 = 3 = the published mobility."""
    legs = [frozenset({f"Rb{i}", f"P{i}", f"Rp{i}"}) for i in (1, 2, 3)]
    pairs = {a | b for a in legs for b in legs if a != b}
    for c in analyze_json(EXAMPLES / "planar_3rpr.yaml")["configurations"]:
        loops = loop_map(c)
        assert len(loops) == 2 and set(loops) <= pairs, c["name"]
        for lp in loops.values():
            assert (lp["subgroup"]["type"], lp["subgroup"]["dim"], lp["rank"]) == ("G", 3, 3)
            np.testing.assert_allclose(lp["subgroup"]["params"]["normal"], [0, 0, 1], atol=1e-12)
        assert c["mobility"]["group"] == 3


@pytest.mark.parametrize("name", ["ur5.yaml", "puma560.yaml", "general_6r.yaml"])
def test_serial_arms(name: str) -> None:
    res = analyze_json(EXAMPLES / name)
    for c in res["configurations"]:
        assert c["loops"] == []
        assert c["mobility"] == {
            "grubler": 6,
            "group": 6,
            "instantaneous": 6,
            "generic": 6,
            "finite": 6,
        }
    assert "overconstrained" not in [p["kind"] for p in res["properties"]]


@pytest.mark.parametrize("name", EXAMPLE_FILES)
def test_overconstrained_property(name: str) -> None:
    """`overconstrained` (finite above group) exactly for Bennett, Bricard and Sarrus."""
    kinds = [p["kind"] for p in analyze_json(EXAMPLES / name)["properties"]]
    assert ("overconstrained" in kinds) is PUBLISHED[name].overconstrained, kinds
    assert kinds.count("overconstrained") <= 1


RIGID_SPATIAL_4R = """\
mechanism: spatial-4r-rigid
bodies: [ground, a, b, c]
joints:
  - {name: J1, type: R, between: [ground, a], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [a, b], axis: [1, 0, 0], point: [1, 0, 0]}
  - {name: J3, type: R, between: [b, c], axis: [0, 1, 1], point: [1, 1, 0.5]}
  - {name: J4, type: R, between: [c, ground], axis: [1, 1, 0], point: [0, 1, 0.3]}
"""


def test_a_rigid_spatial_loop_is_a_structure_with_redundant_constraints(tmp_path) -> None:
    # Four revolute axes in general position (not Bennett's conditions): the loop's four
    # screws are independent (rank 4, no motion), while Grubler-Kutzbach counts
    # 6*3 - 4*5 = -2.  finite 0 is above group -2, so the contract's `overconstrained`
    # holds; its words say what that means for a structure: 2 redundant constraints.
    path = tmp_path / "rigid.yaml"
    path.write_text(RIGID_SPATIAL_4R)
    res = analyze_json(path)
    (c,) = res["configurations"]
    assert c["closure_rank"]["rank"] == 4
    assert (c["mobility"]["finite"], c["mobility"]["group"], c["mobility"]["grubler"]) == (
        0,
        -2,
        -2,
    )
    (prop,) = [p for p in res["properties"] if p["kind"] == "overconstrained"]
    assert "does not move (a structure)" in prop["explanation"]
    assert "2 of its constraints are redundant" in prop["explanation"]


# ============================================================================ 2. scale invariance


def _close(a: float | None, b: float | None, tol: float) -> bool:
    if a is None or b is None:
        return a is b
    return abs(a - b) <= tol


@pytest.mark.parametrize("scale", sorted(SCALES))
@pytest.mark.parametrize("name", EXAMPLE_FILES)
def test_scale_invariance(name: str, scale: str, scaled_dir: Path) -> None:
    """All lengths times k: same verdicts, sigma within 1e-10 of the largest, L times k."""
    k = SCALES[scale][0]
    path = scaled_file(scaled_dir, name, scale)
    base = analyze_json(EXAMPLES / name)
    res = analyze_json(path)

    L0, L1 = base["precision"]["length_scale"], res["precision"]["length_scale"]
    # L scales with the lengths, except the fallback L = 1 when every axis point is
    # the origin (the spherical 4R: no length at all)
    kL = 1.0 if all_axis_points_at_origin(EXAMPLES / name) else k
    if kL == 1.0:
        assert L0 == L1 == 1.0
    assert L1 == pytest.approx(kL * L0, rel=1e-12)
    assert res["precision"]["mode"] == base["precision"]["mode"]
    assert [p["kind"] for p in res["properties"]] == [p["kind"] for p in base["properties"]]
    assert [c["name"] for c in res["configurations"]] == [c["name"] for c in base["configurations"]]

    for c0, c1 in zip(base["configurations"], res["configurations"], strict=True):
        where = c0["name"]
        assert c1["precision"] == c0["precision"], where
        assert c1["mobility"] == c0["mobility"], where
        assert c1["singular"] == c0["singular"], where
        assert classes(c1) == classes(c0), where
        assert c1["closure_residual"] <= 1e-12 * L1, where
        _same_joint_values(name, c0["joints"], c1["joints"], kL, L0, where)
        r0, r1 = c0["closure_rank"], c1["closure_rank"]
        assert (r1["rank"], r1["nullity"]) == (r0["rank"], r0["nullity"]), where
        _same_margin(r0["margin"], r1["margin"], kL, where)
        assert len(c1["loops"]) == len(c0["loops"]), where
        for l0, l1 in zip(c0["loops"], c1["loops"], strict=True):
            assert set(l1["joints"]) == set(l0["joints"]), where
            s0, s1 = l0["subgroup"], l1["subgroup"]
            assert (s1["type"], s1["dim"]) == (s0["type"], s0["dim"]), where
            assert sorted(s1["params"]) == sorted(s0["params"]), where
            for key, v0 in s0["params"].items():
                v1 = s1["params"][key]
                if key in ("point",):  # a point scales, directions do not
                    np.testing.assert_allclose(np.divide(v1, k), v0, atol=1e-10 * L0)
                elif isinstance(v0, list):
                    np.testing.assert_allclose(v1, v0, atol=1e-10)
                elif key == "pitch":
                    assert v1 / k == pytest.approx(v0, abs=1e-10 * L0), where
            assert l1["rank"] == l0["rank"], where
            if l0["sigma"] is not None:
                smax = max(l0["sigma"]) if l0["sigma"] else 0.0
                assert len(l1["sigma"]) == len(l0["sigma"]), where
                np.testing.assert_allclose(l1["sigma"], l0["sigma"], rtol=0, atol=1e-10 * smax)
            _same_margin(l0["margin"], l1["margin"], kL, where)


def _same_joint_values(name: str, j0: dict, j1: dict, k: float, L0: float, where: str) -> None:
    """Angles unchanged, length coordinates times k (continuation follows the same path)."""
    types = joint_types(EXAMPLES / name)
    assert list(j1) == list(j0), where
    for joint, v0 in j0.items():
        for x0, x1, is_len in zip(v0, j1[joint], LENGTH_COORDS[types[joint]], strict=True):
            if is_len:
                assert x1 / k == pytest.approx(x0, abs=1e-10 * L0), (where, joint)
            else:
                assert x1 == pytest.approx(x0, abs=1e-10), (where, joint)


def _same_margin(m0: dict, m1: dict, k: float, where: str) -> None:
    assert _close(m1["kept"], m0["kept"], 1e-10), (where, m0, m1)
    assert _close(m1["dropped"], m0["dropped"], 1e-10), (where, m0, m1)
    assert (m1["tau_lo"], m1["tau_hi"]) == (m0["tau_lo"], m0["tau_hi"]), where
    assert m1["length_scale"] == pytest.approx(k * m0["length_scale"], rel=1e-12), where


# ============================================================================ 3. transversal path

#: crank angles d = 10**-e, e = 1, 1.5, ..., 6
EXPONENTS = [1 + 0.5 * i for i in range(11)]


@pytest.fixture(scope="session")
def changepoint(tmp_path_factory: pytest.TempPathFactory) -> tuple[dict, list]:
    text, points = changepoint_family(EXPONENTS)
    path = tmp_path_factory.mktemp("family") / "changepoint_family.yaml"
    path.write_text(text)
    return analyze_json(path, "--precision", "float"), points


def test_changepoint_family_is_singular_at_the_closed_form_point(changepoint) -> None:
    """At d = 0 (the flat configuration, closed form: |BD| = b - c, circles tangent) the closure
    system has rank 2, nullity 2 (all four joints collinear) and the configuration is singular."""
    res, _points = changepoint
    flat = by_name(res)["reference"]
    assert (flat["closure_rank"]["rank"], flat["closure_rank"]["nullity"]) == (2, 2)
    assert flat["singular"] is True
    assert flat["mobility"]["finite"] == 1


def test_changepoint_family_sigma_matches_closed_form(changepoint) -> None:
    """Singular values of the loop equal those of the 3 x 4 planar matrix built here in
    the commensurate metric (L, centroid, reduced G coordinates) and the closed-form joint
    points."""
    res, points = changepoint
    assert res["precision"]["length_scale"] == pytest.approx(changepoint_length_scale(), rel=1e-14)
    configs = by_name(res)
    for p in points:
        (lp,) = configs[p.name]["loops"]
        np.testing.assert_allclose(lp["sigma"], p.sigma, rtol=0, atol=1e-12 * p.sigma[0])
        margin = configs[p.name]["closure_rank"]["margin"]
        # kept is the smallest kept singular value (commensurate metric), sigma_max the largest
        assert margin["kept"] == pytest.approx(p.sigma[-1], rel=1e-6)
        assert margin["sigma_max"] == pytest.approx(p.sigma[0], rel=1e-12)


@pytest.mark.parametrize("branch", [1, -1])
def test_changepoint_family_kept_sigma_is_linear_in_distance(changepoint, branch: int) -> None:
    """Approaching the change point along a motion branch, the kept smallest singular value shrinks
    linearly (log-log slope 1 +- 0.1 for d from 1e-1 to 1e-6), and every float verdict stays
    regular: rank 3 decided in float with kept >= tau_hi, no singularity."""
    res, points = changepoint
    configs = by_name(res)
    ds, kept, smin = [], [], []
    for p in points:
        if p.branch != branch:
            continue
        c = configs[p.name]
        margin = c["closure_rank"]["margin"]
        assert c["precision"] == "float", p.name
        assert (c["closure_rank"]["rank"], c["closure_rank"]["nullity"]) == (3, 1), p.name
        assert c["loops"][0]["rank"] == 3, p.name
        assert margin["kept"] / margin["sigma_max"] >= margin["tau_hi"] == 1e-9, p.name
        assert c["singular"] is False and c["singularities"] == [], p.name
        assert c["mobility"]["instantaneous"] == c["mobility"]["finite"] == 1, p.name
        ds.append(p.d)
        kept.append(margin["kept"])
        sig = c["loops"][0]["sigma"]
        smin.append(sig[-1] / sig[0])
    assert len(ds) == len(EXPONENTS)
    assert min(ds) == pytest.approx(1e-6) and max(ds) == pytest.approx(1e-1)
    for values in (kept, smin):
        slope = np.polyfit(np.log(ds), np.log(values), 1)[0]
        assert abs(slope - 1) <= 0.1, slope


# ============================================================================ 4. determinism, contract

CONTRACT_TOP = {"mechanism", "precision", "properties", "configurations"}
CONTRACT_PRECISION = {"mode", "tau_lo", "tau_hi", "length_scale"}
CONTRACT_CONFIG = {
    "name",
    "precision",
    "joints",
    "closure_residual",
    "closure_rank",
    "loops",
    "mobility",
    "singular",
    "singularities",
}
CONTRACT_MARGIN = {"kept", "dropped", "tau_lo", "tau_hi", "length_scale"}
CONTRACT_LOOP = {"joints", "subgroup", "rank", "sigma", "margin"}
CONTRACT_MOBILITY = {"grubler", "group", "instantaneous", "generic", "finite"}
CLASSES = {
    "serial",
    "bifurcation",
    "isolated",
    "degenerate",
    "increased-mobility",
    "input",
    "output",
    "passive-motion",
    "impossible-input",
    "impossible-output",
    "constraint",
    "undecided",
}
PROPERTY_KINDS = {"shaky", "idle-motion", "overconstrained", "redundant-actuation", "underactuated"}


@pytest.mark.parametrize("name", EXAMPLE_FILES)
def test_json_contract_keys(name: str) -> None:
    res = analyze_json(EXAMPLES / name)
    assert CONTRACT_TOP <= set(res)
    assert CONTRACT_PRECISION <= set(res["precision"])
    assert res["precision"]["mode"] == "auto"
    for p in res["properties"]:
        assert p["kind"] in PROPERTY_KINDS, p
    for c in res["configurations"]:
        assert CONTRACT_CONFIG <= set(c), (c["name"], CONTRACT_CONFIG - set(c))
        assert {"rank", "nullity", "margin"} <= set(c["closure_rank"])
        assert CONTRACT_MARGIN <= set(c["closure_rank"]["margin"])
        assert set(c["mobility"]) >= CONTRACT_MOBILITY
        assert c["closure_residual"] <= 1e-12 * res["precision"]["length_scale"]
        for lp in c["loops"]:
            assert CONTRACT_LOOP <= set(lp)
            assert {"type", "dim", "params"} <= set(lp["subgroup"])
            assert CONTRACT_MARGIN <= set(lp["margin"])
        for s in c["singularities"]:
            assert s["class"] in CLASSES, s
            assert "margin" in s and "precision" in s, s
        # singular is true iff a finding other than `undecided`, null if only those
        found = classes(c)
        expected = False if not found else (None if set(found) == {"undecided"} else True)
        assert c["singular"] is expected
        # every joint of the file, with its dof
        assert sum(len(v) for v in c["joints"].values()) == total_dof(EXAMPLES / name)


@pytest.mark.parametrize("name", ["fourbar.yaml", "bennett.yaml", "planar_3rpr.yaml"])
def test_same_file_gives_byte_identical_json(name: str) -> None:
    first, _ = analyze_text(EXAMPLES / name)
    rc, second, _err = run_cli(["analyze", str(EXAMPLES / name), "--format", "json"])
    assert rc == 0
    assert second == first


def test_subprocess_json_matches_in_process() -> None:
    """The installed command (a fresh interpreter, another hash seed) prints the same bytes."""
    first, _ = analyze_text(EXAMPLES / "fourbar.yaml")
    r = run_cli_subprocess(["analyze", "examples/fourbar.yaml", "--format", "json"])
    assert r.status == 0, r.err
    assert r.out == first


def test_precision_float() -> None:
    res = analyze_json(EXAMPLES / "fourbar.yaml", "--precision", "float")
    assert res["precision"]["mode"] == "float"
    assert (res["precision"]["tau_lo"], res["precision"]["tau_hi"]) == (1e-12, 1e-9)
    assert {c["precision"] for c in res["configurations"]} == {"float"}


def test_precision_mp30_fourbar() -> None:
    """mp:30: thresholds 10^(10-N) and 10^(-N/2) (docs/precision.md), same ranks and mobilities as
    auto, closure accepted at 10^(15-N) L = 1e-15 L."""
    base = by_name(analyze_json(EXAMPLES / "fourbar.yaml"))
    res = analyze_json(EXAMPLES / "fourbar.yaml", "--precision", "mp:30")
    assert res["precision"]["mode"] == "mp:30"
    assert res["precision"]["tau_lo"] == pytest.approx(1e-20, rel=1e-12)
    assert res["precision"]["tau_hi"] == pytest.approx(1e-15, rel=1e-12)
    L = res["precision"]["length_scale"]
    assert set(by_name(res)) == set(base)
    for c in res["configurations"]:
        b = base[c["name"]]
        assert c["precision"] == "mp:30"
        assert c["closure_residual"] < 1e-15 * L
        assert c["closure_rank"]["rank"] == b["closure_rank"]["rank"]
        assert c["closure_rank"]["nullity"] == b["closure_rank"]["nullity"]
        assert [lp["rank"] for lp in c["loops"]] == [lp["rank"] for lp in b["loops"]]
        assert c["mobility"] == b["mobility"]
        assert c["closure_rank"]["margin"]["tau_hi"] == pytest.approx(1e-15, rel=1e-12)


#: (file, configuration given exactly, published closure rank, published mobility)
EXACT_CASES = [
    ("fourbar.yaml", "reference", 3, 1),
    ("bennett.yaml", "reference", 3, 1),
    ("bricard.yaml", "reference", 5, 1),
    ("sarrus.yaml", "reference", 5, 1),
]


@pytest.mark.parametrize(("name", "config", "rank", "mobility"), EXACT_CASES)
def test_precision_exact(name: str, config: str, rank: int, mobility: int) -> None:
    """Exact mode on a configuration whose joint values are all given exactly: exact ranks (the
    published ones), sigma null, tau_lo = tau_hi = 0 in every margin."""
    res = analyze_json(EXAMPLES / name, "--precision", "exact", "--config", config)
    assert res["precision"]["mode"] == "exact"
    assert (res["precision"]["tau_lo"], res["precision"]["tau_hi"]) == (0, 0)
    (c,) = res["configurations"]
    assert c["precision"] == "exact"
    assert c["closure_residual"] == 0
    margins = [c["closure_rank"]["margin"]] + [lp["margin"] for lp in c["loops"]]
    for m in margins:
        assert (m["tau_lo"], m["tau_hi"]) == (0, 0)
    for lp in c["loops"]:
        assert lp["sigma"] is None
    # a regular point: nullity = total dof - rank = the published mobility
    assert total_dof(EXAMPLES / name) - rank == mobility
    assert (c["closure_rank"]["rank"], c["closure_rank"]["nullity"]) == (rank, mobility)
    assert [lp["rank"] for lp in c["loops"]] == [rank]
    assert c["mobility"]["instantaneous"] == mobility
    assert c["mobility"]["finite"] == mobility


@pytest.mark.parametrize("precision", ["float", "mp:30", "exact"])
def test_margin_dropped_is_null_when_nothing_is_dropped(precision: str) -> None:
    """The README's four-bar (examples/fourbar.yaml): its 3 x 4 loop and closure systems have rank
    3, every singular value is kept, and both margins say "dropped": null (numeric.Margin: "None if
    full rank"). The same matrix must give the same margin form in every precision mode."""
    res = analyze_json(EXAMPLES / "fourbar.yaml", "--precision", precision, "--config", "reference")
    (c,) = res["configurations"]
    (lp,) = c["loops"]
    assert c["closure_rank"]["rank"] == lp["rank"] == 3
    assert c["closure_rank"]["margin"]["dropped"] is None
    assert lp["margin"]["dropped"] is None


def test_exact_refuses_inexact_configurations() -> None:
    """`exact` needs every joint value given exactly; crank-30 gives only the input: that
    configuration gets an error entry, status 3."""
    rc, out, err = run_cli(
        ["analyze", str(EXAMPLES / "fourbar.yaml"), "--precision", "exact", "--config", "crank-30"]
    )
    assert rc == 3
    assert "'crank-30'" in err and "exact" in err


# ============================================================================ 5. options


def test_output_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from mechsing.cli import main

    out = tmp_path / "report.json"
    rc = main(["analyze", str(EXAMPLES / "fourbar.yaml"), "--format", "json", "-o", str(out)])
    assert rc == 0
    assert capsys.readouterr().out == ""
    assert out.read_text() == analyze_text(EXAMPLES / "fourbar.yaml")[0]


def test_config_restricts(capsys: pytest.CaptureFixture[str]) -> None:
    from mechsing.cli import main

    path = str(EXAMPLES / "parallelogram.yaml")
    rc = main(["analyze", path, "--format", "json", "--config", "flat"])
    assert rc == 0
    res = json.loads(capsys.readouterr().out)
    assert [c["name"] for c in res["configurations"]] == ["flat"]
    full = by_name(analyze_json(EXAMPLES / "parallelogram.yaml"))
    assert res["configurations"][0] == full["flat"]

    rc = main(["analyze", path, "--format", "json", "--config", "crank-30", "--config", "flat"])
    assert rc == 0
    res = json.loads(capsys.readouterr().out)
    assert sorted(c["name"] for c in res["configurations"]) == ["crank-30", "flat"]

    rc = main(["analyze", path, "--config", "no-such-configuration"])
    assert rc == 2
    assert "no-such-configuration" in capsys.readouterr().err


@pytest.mark.parametrize("fmt", ["text", "md"])
@pytest.mark.parametrize("name", ["planar_3rpr.yaml", "fourbar_changepoint.yaml", "ur5.yaml"])
def test_text_and_markdown_mention_every_configuration_and_loop(name: str, fmt: str) -> None:
    rc, text, _err = run_cli(["analyze", str(EXAMPLES / name), "--format", fmt])
    assert rc == 0
    res = analyze_json(EXAMPLES / name)
    assert res["mechanism"] in text
    lines = text.splitlines()
    starts = []
    for c in res["configurations"]:
        word = re.compile(rf"(?<![\w-]){re.escape(c['name'])}(?![\w-])")
        # a section heading: a line that is neither indented nor a list item, naming the config
        heads = [
            i for i, ln in enumerate(lines) if not ln.startswith((" ", "-")) and word.search(ln)
        ]
        assert heads, c["name"]
        starts.append(heads[0])
    assert starts == sorted(starts)  # in file order
    bounds = [*starts, len(lines)]
    for i, c in enumerate(res["configurations"]):
        section = lines[bounds[i] : bounds[i + 1]]
        loop_lines = [ln for ln in section if "loop" in ln.lower()]
        for lp in c["loops"]:
            assert any(all(j in ln for j in lp["joints"]) for ln in loop_lines), (c["name"], lp)
        assert any(str(c["mobility"]["finite"]) in ln for ln in section if "mobility" in ln)


def test_analysis_is_finite_everywhere() -> None:
    """No NaN or infinity leaks into the JSON of any example (they would be invalid JSON)."""
    for name in EXAMPLE_FILES:
        text, _ = analyze_text(EXAMPLES / name)
        assert "NaN" not in text and "Infinity" not in text
        for c in analyze_json(EXAMPLES / name)["configurations"]:
            assert math.isfinite(c["closure_residual"])
