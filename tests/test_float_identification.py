"""Float means float: at ``--precision float`` (and in auto's first pass) the loops'
subgroups are identified from float screws, with the rank rule and margins of every other
float decision; exactly only when the user asks for exact, or when float is undecided.

The 25-digit Stewart platform (tests/data/stewart_octahedral_25digits.yaml: the example
with every number rounded to 25 digits, as a CAD export writes it) is the same mechanism
as the example: its float verdicts are the example's, and those are the published ones
(Fichter 1986, Merlet 2006: regular at the centred pose; at +-90 degrees the six leg lines
are dependent, rank 5, and the platform gains one infinitesimal motion)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechsing.kinematics import KinematicModel
from mechsing.model import load
from mechsing.screws import reference_loop_identification
from tests.cli import run_cli

ROOT = Path(__file__).resolve().parents[1]
PLAIN = ROOT / "examples" / "stewart_octahedral.yaml"
DIGITS25 = ROOT / "tests" / "data" / "stewart_octahedral_25digits.yaml"


def _verdicts(path: Path) -> dict[str, object]:
    import json

    run = run_cli(["analyze", path, "--precision", "float", "--format", "json"])
    assert run.status in (0, 1), run.err
    doc = json.loads(run.out)
    out = {}
    for c in doc["configurations"]:
        out[c["name"]] = (
            c["singular"],
            sorted((s["class"], s.get("dimension", s.get("rank"))) for s in c["singularities"]),
            c["mobility"],
            c["closure_rank"]["rank"],
            [(lp["subgroup"]["type"], lp["rank"]) for lp in c["loops"]],
        )
    return out


def test_25_digit_stewart_has_the_verdicts_of_the_exact_file() -> None:
    plain, digits = _verdicts(PLAIN), _verdicts(DIGITS25)
    assert digits == plain
    # the published facts (module docstring)
    assert plain["reference"][0] is False
    for name in ("rotated+90", "rotated-90"):
        singular, kinds, mobility, _rank, loops = plain[name]
        assert singular is True
        assert kinds == [("impossible-input", 5), ("output", 1)]
        assert mobility["finite"] == 6
        assert loops == [("D", 6)] * 5


@pytest.mark.parametrize("path", [PLAIN, DIGITS25], ids=["exact-file", "25-digits"])
def test_float_model_identifies_loops_in_float_and_exact_model_exactly(path: Path) -> None:
    mech = load(path)
    km = KinematicModel(mech, "float")
    for loop in mech.loops:
        ident = reference_loop_identification(km, loop)
        assert ident.ok and ident.precision == "float"
        assert (ident.subgroup.symbol, ident.dim) == ("D", 6)


def test_exact_model_identifies_loops_exactly() -> None:
    mech = load(ROOT / "examples" / "fourbar.yaml")
    for loop in mech.loops:
        f = reference_loop_identification(KinematicModel(mech, "float"), loop)
        e = reference_loop_identification(KinematicModel(mech, "exact"), loop)
        assert f.precision == "float" and e.precision == "exact"
        # a planar four-bar's loop moves in the plane's G (dimension 3), both ways
        assert (f.subgroup.symbol, f.dim) == (e.subgroup.symbol, e.dim) == ("G", 3)
