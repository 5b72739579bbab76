"""The general formulation's parts (:mod:`mechsing.assembly.parts`): closures that share
no unknown split apart, and the parts' modes combined as a product, with what the count
claims decided by the rules of a product (no solution in one part: none at all)."""

from __future__ import annotations

from types import SimpleNamespace

import mpmath
import pytest

from mechsing import load
from mechsing.assembly.chains import Found
from mechsing.assembly.given import read_given
from mechsing.assembly.parts import combined, split
from mechsing.numeric import parse_precision
from tests.mechanisms import ROOT

RPR = ROOT / "examples" / "planar_3rpr.yaml"
LEGS = [("Rb1", "P1", "Rp1"), ("Rb2", "P2", "Rp2"), ("Rb3", "P3", "Rp3")]


def _found(rows: list[list[float]], count: int | None, complete: str) -> Found:
    formulation = {"name": "n", "unknowns": [], "closures": [], "randomized": False, "bezout": 6}
    paths = {"tracked": 6, "finite": 6}
    return Found(formulation, [(r, True) for r in rows], count, complete, paths, ("a note",))


def _row(leg: int, value: float) -> list[float]:
    """A row of the 3-RPR's nine coordinates with ``value`` in leg ``leg``'s and 0 in the
    others' (as a part's rows hold them)."""
    return [value if k // 3 == leg else 0.0 for k in range(9)]


def test_the_posed_3rpr_splits_into_its_three_legs(tmp_path) -> None:
    text = RPR.read_text()
    path = tmp_path / "posed.yaml"
    path.write_text(
        text[: text.index("configurations:")]
        + "configurations:\n  reference: {}\n"
        + "  target: {pose: {position: [1.1, 0.9, 0], rotation_vector: [0, 0, 0.1]}}\n"
    )
    from mechsing.assembly.general import problem

    given = read_given(load(path), "target", parse_precision("float"), 50, 1e-9)
    with mpmath.workdps(50):
        parts = split(problem(given))
    assert [tuple(sorted(p.joints)) for p in parts] == [tuple(sorted(leg)) for leg in LEGS]
    for p, leg in zip(parts, LEGS, strict=True):
        assert p.others == frozenset(j for other in LEGS if other != leg for j in other)
        assert len(p.equations) == 3 and p.unknowns == 3


def test_the_3rpr_with_its_inputs_is_one_part() -> None:
    """Given its slides, the 3-RPR's loops share the legs' angles: one system."""
    from mechsing.assembly.general import problem

    given = read_given(load(RPR), "stroke", parse_precision("float"), 50, 1e-9)
    with mpmath.workdps(50):
        prob = problem(given)
        assert split(prob) == [prob]


def _parts() -> list[SimpleNamespace]:
    return [SimpleNamespace(joints={n: (0,) for n in leg}) for leg in LEGS]


def test_modes_are_every_choice_of_one_per_part() -> None:
    found = [
        _found([_row(0, 1.0), _row(0, 2.0)], 2, "proven"),
        _found([_row(1, 3.0)], 1, "proven"),
        _found([_row(2, 4.0), _row(2, 5.0)], 2, "proven"),
    ]
    out = combined(load(RPR), _parts(), found)
    assert out.count == 4 and out.complete == "proven"
    got = sorted(tuple(q) for q, _ in out.rows)
    want = sorted(tuple([a] * 3 + [3.0] * 3 + [c] * 3) for a in (1.0, 2.0) for c in (4.0, 5.0))
    assert got == want
    assert [p["count"] for p in out.formulation["parts"]] == [2, 1, 2]
    assert out.formulation["bezout"] == 18 and out.paths == {"tracked": 18, "finite": 18}
    assert out.notes[0].startswith("the closure equations fall into 3 systems")
    assert "joints Rb1, P1, Rp1: a note" in out.notes


def test_a_part_found_empty_leaves_no_mode_not_proven_beside_a_curve() -> None:
    """A part with no real solution found (its count not proven) and a part on a curve:
    no mode was found, and the count is not proven (the empty part may miss one)."""
    curve = _found([], None, "infinite")
    curve.formulation["dimension"] = 1
    found = [_found([], 0, "not proven"), curve, _found([_row(2, 4.0)], 1, "proven")]
    out = combined(load(RPR), _parts(), found)
    assert out.count == 0 and out.complete == "not proven" and out.rows == []


def test_parts_on_curves_add_their_dimensions() -> None:
    curves = [_found([], None, "infinite") for _ in range(2)]
    for c in curves:
        c.formulation["dimension"] = 1
    found = [curves[0], _found([_row(1, 3.0)], 1, "proven"), curves[1]]
    out = combined(load(RPR), _parts(), found)
    assert out.complete == "infinite" and out.formulation["dimension"] == 2


@pytest.mark.parametrize("other", ["infinite", "not proven"])
def test_a_part_proven_empty_leaves_no_mode_whatever_the_others(other: str) -> None:
    found = [
        _found([], 0, "proven"),
        _found(
            [] if other == "infinite" else [_row(1, 3.0)], None if other == "infinite" else 1, other
        ),
        _found([_row(2, 4.0)], 1, "proven"),
    ]
    found[0].formulation["working_modes"] = True
    out = combined(load(RPR), _parts(), found)
    assert out.count == 0 and out.complete == "proven" and out.rows == []
    assert (
        "no mode: no real solution for joints Rb1, P1, Rp1 (the output's pose is out of that "
        "leg's reach)"
    ) in out.notes


def test_a_part_on_a_curve_makes_the_whole_infinite() -> None:
    curve = _found([], None, "infinite")
    curve.formulation["dimension"] = 1
    found = [_found([_row(0, 1.0)], 1, "proven"), curve, _found([_row(2, 4.0)], 1, "proven")]
    out = combined(load(RPR), _parts(), found)
    assert out.complete == "infinite" and out.count is None
    assert out.formulation["dimension"] == 1


def test_a_part_not_proven_leaves_the_count_not_proven() -> None:
    found = [
        _found([_row(0, 1.0)], 1, "proven"),
        _found([_row(1, 3.0)], 1, "not proven"),
        _found([_row(2, 4.0)], 1, "proven"),
    ]
    out = combined(load(RPR), _parts(), found)
    assert out.count == 1 and out.complete == "not proven"
