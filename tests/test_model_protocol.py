"""The protocol closure asks of a kinematic model (:class:`ClosureModel`) is true of both
classes that answer it: every member present, every method taking the protocol's
parameters by the same names in the same order, in every precision mode."""

from __future__ import annotations

import inspect
from pathlib import Path

import pytest

from mechsing.kinematics import KinematicModel
from mechsing.kinematics.pose import PoseModel
from mechsing.kinematics.protocol import ClosureModel
from mechsing.model.loader import load

ROOT = Path(__file__).resolve().parents[1]

#: the protocol's methods (its data members and property aside)
METHODS = sorted(
    name
    for name, member in vars(ClosureModel).items()
    if inspect.isfunction(member) and not name.startswith("_")
)


def _models(precision: str) -> list[object]:
    mech = load(ROOT / "examples" / "fourbar.yaml")
    base = KinematicModel(mech, precision)
    with base.precision.context():
        pose = PoseModel(base, base.zeros()[:3], base.backend.eye(3))
    return [base, pose]


def _parameters(function: object) -> list[str]:
    return [p for p in inspect.signature(function).parameters if p != "self"]


def test_the_protocol_lists_what_closure_calls():
    assert {"poses", "chord_residuals", "update", "difference", "float_twin"} <= set(METHODS)


@pytest.mark.parametrize("precision", ["float", "mp:30", "exact"])
def test_both_models_answer_the_protocol_with_its_signatures(precision):
    for model in _models(precision):
        assert isinstance(model, ClosureModel), type(model).__name__
        for name in METHODS:
            want = _parameters(getattr(ClosureModel, name))
            got = _parameters(getattr(type(model), name))
            assert got == want, f"{type(model).__name__}.{name}{got}: the protocol says {want}"
        assert isinstance(model.float_twin(), ClosureModel)
        assert isinstance(model.sparse_closure, bool)


def test_a_model_without_a_member_does_not_answer_it():
    class Partial:
        def __init__(self, model: KinematicModel) -> None:
            for name in ("mech", "precision", "backend", "length_scale", "n", "chords"):
                setattr(self, name, getattr(model, name))

    model = KinematicModel(load(ROOT / "examples" / "fourbar.yaml"), "float")
    assert isinstance(model, ClosureModel)
    assert not isinstance(Partial(model), ClosureModel)
