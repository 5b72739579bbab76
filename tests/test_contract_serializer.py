"""The one serializer builds the JSON of every value the lower layers hand up (margins,
subgroups, identifications, intersections, products, catalog types) with the contract's keys
in order; the lower layers build none, and the text renderer reads the typed results."""

from __future__ import annotations

import ast
import math
from pathlib import Path

import numpy as np
import pytest
import sympy

from mechsing.analysis import analyze
from mechsing.analysis.contract import subgroup_json, subgroup_params, to_json
from mechsing.analysis.words import explain
from mechsing.numeric import Margin
from mechsing.reports.render import render_text
from mechsing.singularity.findings import (
    ConstraintFinding,
    MotionFinding,
    SerialFinding,
    UndecidedFinding,
)
from mechsing.subgroups import Subgroup, identify, intersect, load_catalog, product

ROOT = Path(__file__).resolve().parents[1]
MARGIN = ["kept", "dropped", "tau_lo", "tau_hi", "length_scale"]
IDENTIFICATION = ["type", "dim", "params", "bracket_norms", "margin", "status", "precision"]


def test_a_margin_lists_its_optional_evidence_only_when_known_and_after_the_thresholds():
    bare = Margin(0.5, None, 1e-12, 1e-9, 2.0)
    assert to_json(bare) == {
        "kept": 0.5,
        "dropped": None,
        "tau_lo": 1e-12,
        "tau_hi": 1e-9,
        "length_scale": 2.0,
    }
    full = Margin(0.5, 1e-17, 1e-12, 1e-9, 2.0, eig_margin=0.25, sigma_max=1.0, rounding=2e-16)
    assert list(to_json(full)) == [*MARGIN, "sigma_max", "rounding", "eig_margin"]
    assert to_json(full)["rounding"] == 2e-16 and to_json(full)["eig_margin"] == 0.25


def test_a_subgroup_serializes_canonical_float_parameters():
    r = Subgroup("R", axis=[0, 0, -3], point=[1, 2, 5])
    got = to_json(r)
    assert got == {
        "type": "R",
        "dim": 1,
        "params": {"axis": [0.0, 0.0, 1.0], "point": [1.0, 2.0, 0.0]},
    }
    assert list(got) == ["type", "dim", "params"] and got["params"] == subgroup_params(r)
    assert all(math.copysign(1.0, x) == 1.0 for x in got["params"]["point"])  # no -0.0
    h = Subgroup("H", axis=[0, 0, 1], point=[0, 0, 0], pitch=sympy.Rational(1, 2))
    pitch = to_json(h)["params"]["pitch"]
    assert type(pitch) is float and pitch == 0.5
    assert subgroup_json(None) == {"type": None, "dim": None, "params": {}}


def test_an_identification_puts_its_subgroup_first_then_its_evidence():
    ok = identify(np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -1, 0.0]]), precision="float")
    got = to_json(ok)
    assert list(got) == IDENTIFICATION
    assert got["type"] == "G" and got["status"] == "ok" and got["margin"] == to_json(ok.margin)
    assert all(type(x) is float for x in got["bracket_norms"])
    open_ = identify(np.array([[0, 0, 1, 0, 0, 0], [0, 1e-11, 1, 0, -1, 0]]), precision="float")
    got = to_json(open_)
    assert list(got) == [*IDENTIFICATION, "message", "dim_bounds"]
    assert got["type"] is None and got["status"] == "undecided" and got["dim_bounds"] == [3, 4]


def test_an_intersection_and_a_product_wrap_their_identifications():
    plane = Subgroup("G", normal=[0, 0, 1])
    slide = Subgroup("P", axis=[1, 0, 0])
    meet = intersect(plane, slide)
    got = to_json(meet)
    assert list(got) == [*IDENTIFICATION, "extra_components", "note"]
    assert got["type"] == "P" and got["note"] == meet.note
    prod = product(slide, Subgroup("R", axis=[0, 0, 1], point=[0, 0, 0]))
    got = to_json(prod)
    assert list(got) == ["is_subgroup", "subgroup", "generated", "set_dimension", "note"]
    assert list(got["generated"]) == IDENTIFICATION
    assert got["subgroup"] == (None if prod.subgroup is None else to_json(prod.subgroup))


def test_every_catalog_type_serializes_with_the_catalog_keys_in_order():
    for t in load_catalog().values():
        got = to_json(t)
        assert list(got) == [
            "symbol",
            "name",
            "dimension",
            "parameters",
            "basis",
            "coordinates",
            "normal_in_D",
            "invariants",
            "joints",
            "explanation",
        ]
        assert got["symbol"] == t.symbol and len(got["basis"]) == got["dimension"]
        assert got["explanation"] == got["explanation"].strip()
        assert all(list(p) == ["name", "kind"] for p in got["parameters"])


def test_no_layer_below_the_analysis_builds_json():
    """Margins, decisions, subgroups and findings carry fields; only the serializer of
    ``mechsing.analysis`` turns them into JSON."""
    offenders = []
    for layer in ("numeric", "lie", "subgroups", "model", "kinematics", "screws", "singularity"):
        for path in (ROOT / "mechsing" / layer).rglob("*.py"):
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
                if isinstance(node, ast.FunctionDef) and node.name in ("to_json", "record"):
                    offenders.append(f"{path.relative_to(ROOT)}:{node.lineno} {node.name}")
    assert offenders == []


# --------------------------------------------------------------------------- the renderer

M = Margin(0.5, 1e-17, 1e-10, 1e-8, 2.0, sigma_max=1.0)


def test_explain_reads_each_finding_type_with_its_own_numbers():
    serial = SerialFinding(
        "leg", ("A", "B"), 4, 6, ((1.0,) * 6,) * 2, (0.0,) * 6, (1.0, -1.0), M, "float", leg=3
    )
    assert explain(serial).startswith("leg 3 loses 2 direction(s) of motion (rank 4 instead of 6)")
    assert "joints A and B" in explain(serial) and "(2 in all)" in explain(serial)
    constraint = ConstraintFinding(("A",), 2, 3, (), M, "float", "float")
    assert "drop to rank 2 (generically 3)" in explain(constraint)
    impossible = MotionFinding("impossible-output", ("A",), 3, M, "float", "float", rank=1)
    assert "only 1 independent motions here instead of 3" in explain(impossible)
    output = MotionFinding("output", ("A", "C"), 0, M, "float", "float", 1, joint_rates=(1.0, 0.0))
    assert "moving joints: A and C" in explain(output)
    bounded = UndecidedFinding("input test", (0, 1), M, "mp:30")
    assert "between 0 and 1" in explain(bounded) and "mp:60" in explain(bounded)
    why = UndecidedFinding(
        "configuration at a fold", None, M, "float", "too coarse", "configuration"
    )
    assert "(too coarse)" in explain(why) and "mp:50 or exact" in explain(why)


@pytest.mark.parametrize("file", ["fourbar_changepoint.yaml", "bennett.yaml"])
def test_the_text_report_states_what_the_typed_result_holds(file):
    """A singular configuration (fourbar_changepoint) and a property (bennett)."""
    res = analyze(ROOT / "examples" / file, precision="float")
    text = render_text(res)
    md = render_text(res, markdown=True)
    assert text.startswith(f"mechsing analysis: {res.mechanism.name}\n")
    assert md.startswith(f"# mechsing analysis: {res.mechanism.name}\n")
    for c in res.configurations:
        assert f"Configuration {c.name} ({c.precision}):" in text
        assert f"## Configuration {c.name}" in md
        for f in c.singularities:
            assert f"  {f.cls}: {explain(f)}." in text
        if not c.singularities:
            assert "regular: no singularity." in text
    for p in res.properties:
        assert f"  {p.kind}: {p.explanation}" in text
    assert res.properties or any(c.singularities for c in res.configurations)
