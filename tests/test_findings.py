"""The typed results: findings, decisions and results are immutable values, classification is
a pure function of its inputs, and one serializer gives each kind the contract's keys."""

from __future__ import annotations

import copy
import dataclasses
from pathlib import Path

import numpy as np
import pytest

from mechsing.analysis import analyze
from mechsing.analysis.results import (
    Actuation,
    AnalysisResult,
    ConfigurationResult,
    IdleMotion,
    Mobility,
    Overconstrained,
    Shaky,
    to_json,
)
from mechsing.kinematics import Closer, KinematicModel
from mechsing.model import load
from mechsing.numeric import Margin, Precision, RankDecision
from mechsing.screws import closure_system
from mechsing.singularity import classify
from mechsing.singularity.cspace import Cone
from mechsing.singularity.findings import (
    BranchFinding,
    Classification,
    ConstraintFinding,
    Decision,
    DegenerateReason,
    MotionFinding,
    SerialFinding,
    UndecidedFinding,
    branch_finding,
    decision,
    degenerate,
    undecided_rank,
)

ROOT = Path(__file__).resolve().parents[1]
M = Margin(kept=0.5, dropped=1e-17, tau_lo=1e-10, tau_hi=1e-8, length_scale=2.0, sigma_max=1.0)
MARGIN_KEYS = ["kept", "dropped", "tau_lo", "tau_hi", "length_scale", "sigma_max"]
CONE = Cone("subspaces", [np.eye(3)[:, :1]], order=2, eig_margin=0.25, notes=["why"])


def _examples() -> list:
    serial = SerialFinding(
        "leg",
        ("A", "B"),
        4,
        5,
        ((1.0, 0, 0, 0, 0, 0),),
        (0, 0, 1.0, 0, 0, 0),
        (1.0, -0.5),
        M,
        "float",
        leg=2,
    )
    bif = branch_finding(
        "bifurcation",
        ("A", "B"),
        CONE,
        M,
        "float",
        2,
        branches=2,
        branch_tangents=((1.0, 0.0), (0.0, 1.0)),
        branch_mobility=(1, None),
        branch_dimensions=(1, 1),
        kinematotropic=None,
    )
    motion = MotionFinding(
        "output",
        ("A",),
        0,
        M,
        "float",
        "float",
        dimension=1,
        joint_rates=(1.0, 0.0),
        output_twist=(0, 0, 1.0, 0, 0, 0),
    )
    impossible = MotionFinding("impossible-input", ("A",), 1, M, "float", "float", rank=0)
    constraint = ConstraintFinding(("A", "B"), 4, 5, ((1.0, 0, 0, 0, 0, 0),), M, "mp:30", "mp:30")
    undecided = UndecidedFinding("constraint test", (4, 5), M, "float")
    return [serial, bif, motion, impossible, constraint, undecided]


# --------------------------------------------------------------------------- immutability


@pytest.mark.parametrize("finding", _examples(), ids=lambda f: f.cls)
def test_a_finding_is_frozen_and_holds_no_list(finding):
    field = dataclasses.fields(finding)[0].name
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(finding, field, None)
    for f in dataclasses.fields(finding):
        assert not isinstance(getattr(finding, f.name), list | dict), f.name
    hash(finding)  # a value: hashable, usable as a key


def test_results_and_records_are_frozen():
    res = ConfigurationResult("c", "float")
    mob = Mobility(-2, 1, 1, 1, 1)
    d = Decision("closure", 3, M, "float")
    for x, name in ((res, "name"), (mob, "finite"), (d, "rank")):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(x, name, None)


# --------------------------------------------------------------------------- the serializer


def test_each_kind_serializes_with_the_contract_keys_in_order():
    got = {f.cls: to_json(f) for f in _examples()}
    assert list(got["serial"]) == [
        "class",
        "chain",
        "leg",
        "joints",
        "corank",
        "rank",
        "generic_rank",
        "wrenches",
        "twist",
        "null_joint_rates",
        "margin",
        "precision",
        "name",
        "null_joint_rate_basis",
    ]
    assert got["serial"]["corank"] == 1 and got["serial"]["wrenches"] == [[1.0, 0, 0, 0, 0, 0]]
    assert list(got["bifurcation"]) == [
        "class",
        "joints",
        "order",
        "branches",
        "branch_tangents",
        "branch_mobility",
        "branch_dimensions",
        "instantaneous",
        "margin",
        "precision",
        "test_precision",
    ]
    # the cone's eigenvalue margin joins the closure rank's margin
    assert got["bifurcation"]["margin"]["eig_margin"] == 0.25
    assert got["bifurcation"]["branch_mobility"] == [1, None]
    assert list(got["output"]) == [
        "class",
        "joints",
        "dimension",
        "generic",
        "joint_rates",
        "output_twist",
        "margin",
        "precision",
        "test_precision",
    ]
    assert list(got["impossible-input"]) == [
        "class",
        "joints",
        "rank",
        "generic",
        "margin",
        "precision",
        "test_precision",
    ]
    assert list(got["constraint"]) == [
        "class",
        "joints",
        "rank",
        "generic_rank",
        "corank",
        "wrenches",
        "margin",
        "precision",
        "test_precision",
    ]
    assert list(got["undecided"]) == ["class", "what", "rank_bounds", "margin", "precision"]
    for f in got.values():
        assert list(f["margin"])[: len(MARGIN_KEYS)] == MARGIN_KEYS
        assert all(not isinstance(v, tuple) for v in f.values())  # JSON lists, not tuples


def test_a_decision_record_carries_bounds_only_when_undecided():
    undecided = RankDecision(None, (1.0, 1e-9), M, "float", rank_bounds=(1, 2))
    decided = RankDecision(2, (1.0, 0.5), M, "float", rank_bounds=(2, 2))
    assert to_json(decision("input", undecided, 1)) == {
        "test": "input",
        "rank": None,
        "rank_bounds": [1, 2],
        "generic": 1,
        "margin": to_json(M),
        "precision": "float",
    }
    assert list(to_json(decision("closure", decided))) == ["test", "rank", "margin", "precision"]


def test_an_undecided_rank_leaves_the_verdict_open_only_when_the_bounds_straddle_it():
    def d(test, lo, hi, generic):
        return Decision(test, None, M, "float", (lo, hi), generic)

    assert not d("constraint", 5, 6, 5).verdict_open  # regular at 5 and at 6
    assert d("constraint", 4, 5, 5).verdict_open
    assert d("input", 0, 1, 0).verdict_open  # a motion test is singular above generic
    assert not d("input", 0, 1, 1).verdict_open
    assert Decision("output", None, M, "float", None, 0, note="x").verdict_open
    assert not Decision("closure", 3, M, "float").verdict_open


def test_properties_serialize_with_their_explanation_last():
    for p, keys in (
        (Overconstrained(1, 0, -2, "c"), ["kind", "finite", "group", "grubler", "configuration"]),
        (Shaky(2, 1, ("a", "b")), ["kind", "instantaneous", "finite", "configurations"]),
        (IdleMotion(1, "c"), ["kind", "dimension", "configuration"]),
        (
            Actuation("underactuated", 1, 2, 0, "c"),
            ["kind", "inputs", "finite", "idle", "configuration"],
        ),
    ):
        assert list(to_json(p)) == [*keys, "explanation"], p
        assert str(p.finite if hasattr(p, "finite") else p.dimension) in to_json(p)["explanation"]


def test_the_serializer_refuses_what_it_does_not_know():
    with pytest.raises(TypeError, match="dict"):
        to_json({"class": "serial"})


# --------------------------------------------------------------------------- degenerate


def test_every_degenerate_is_built_by_one_constructor_with_a_note_from_its_reason():
    notes = {
        r: degenerate(r, ("A",), CONE, M, "float", 2, generic=3).note for r in DegenerateReason
    }
    assert notes[DegenerateReason.INCONCLUSIVE] == "why"  # the cone's own notes
    assert "dimension 1, not the branch dimension 3" in notes[DegenerateReason.WRONG_DIMENSION]
    assert len(set(notes.values())) == len(DegenerateReason)
    assert all(isinstance(n, str) and n for n in notes.values())
    for path in (ROOT / "mechsing" / "singularity").glob("*.py"):
        if path.name != "findings.py":
            assert '"degenerate"' not in path.read_text(), path
    with pytest.raises(ValueError):
        BranchFinding("serial", (), 1, 1, M, "float", "float")


# --------------------------------------------------------------------------- classification


def _closed(file: str, name: str):
    mech = load(str(ROOT / "examples" / file))
    model = KinematicModel(mech, "float")
    q = Closer(model, data_precision=Precision("float")).solve(name).q
    return mech, model, q, closure_system(model, q, model.precision)


@pytest.mark.parametrize(
    ("file", "config"), [("fourbar_changepoint.yaml", None), ("puma560.yaml", None)]
)
def test_classification_is_a_pure_function_of_its_inputs(file, config):
    mech = load(str(ROOT / "examples" / file))
    name = config or next(iter(mech.configurations))
    mech, model, q, cs = _closed(file, name)
    q0, matrix0, rank0 = q.copy(), copy.deepcopy(cs.matrix), cs.rank
    first = classify(mech, model, q, cs)
    assert isinstance(first, Classification)
    assert np.array_equal(q, q0) and np.array_equal(cs.matrix, matrix0) and cs.rank is rank0
    again = classify(mech, model, q, cs)
    assert again == first  # same inputs, same values: nothing was written between the calls


def test_an_analysis_result_is_typed_and_its_json_is_the_serializers():
    res = analyze(ROOT / "examples" / "fourbar_changepoint.yaml", precision="float")
    assert isinstance(res, AnalysisResult) and isinstance(res.configurations, tuple)
    kinds = (SerialFinding, BranchFinding, MotionFinding, ConstraintFinding, UndecidedFinding)
    found = [f for c in res.configurations for f in c.singularities]
    assert found and all(isinstance(f, kinds) for f in found)
    assert all(isinstance(d, Decision) for c in res.configurations for d in c.decisions)
    assert res.to_json() == to_json(res)
    assert [to_json(c) for c in res.configurations] == res.to_json()["configurations"]


def test_an_undecided_rank_finding_names_its_bounds():
    dec = RankDecision(None, (1.0, 1e-9), M, "mp:30", rank_bounds=(2, 3))
    f = undecided_rank("loop A-B-C-D", dec)
    assert to_json(f)["rank_bounds"] == [2, 3] and to_json(f)["precision"] == "mp:30"


def test_an_undecided_configuration_says_why_before_its_margin():
    """A fold that float places too coarsely: no rank is in question, the note says why."""
    f = UndecidedFinding("configuration at a fold", None, M, "float", "why", "configuration")
    assert list(to_json(f)) == ["class", "what", "rank_bounds", "note", "margin", "precision"]
    g = UndecidedFinding("input test", None, M, "float", "rests on another rank")
    assert list(to_json(g)) == ["class", "what", "rank_bounds", "margin", "precision", "note"]


def test_the_classify_function_is_not_shadowed_by_a_submodule():
    # a submodule named like the package's function would replace it as the package's
    # attribute once imported (it did, as mechsing.singularity.classify)
    import importlib
    import pkgutil

    import mechsing.singularity as singularity

    for info in pkgutil.iter_modules(singularity.__path__):
        importlib.import_module(f"mechsing.singularity.{info.name}")
    assert callable(singularity.classify) and not hasattr(singularity.classify, "__path__")
    assert type(singularity.classify).__name__ == "function"
