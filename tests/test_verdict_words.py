"""Verdicts in words that do not mislead (issue 27, items 9, 10 and 16)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.cli import cli_json, run_cli

#: an in-line slider-crank drawn at its outer dead centre: A, B and C on the x axis
#: (crank 1, rod 4), the slider as input and the crank as output.  With crank and rod
#: collinear the slider's rate is zero whatever the crank's rate: with the slider locked
#: the crank can still turn (an output singularity, type II), and the dropped singular
#: value is exactly zero (every screw is exact: points on the axes, axes along z and x)
INLINE = """\
mechanism: inline-slider-crank
bodies: [ground, crank, rod, slider]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: [5, 0, 0]}
  - {name: P, type: P, between: [ground, slider], axis: [1, 0, 0]}
inputs: [P]
output: {body: crank}
configurations:
  reference: {}
"""


@pytest.mark.parametrize("precision", ["float", "exact"])
def test_an_exactly_singular_output_finding_shows_its_dropped_zero(
    tmp_path: Path, precision: str
) -> None:
    path = tmp_path / "inline.yaml"
    path.write_text(INLINE)
    c = cli_json(["analyze", path, "--precision", precision, "--format", "json"])["configurations"][
        0
    ]
    (out,) = [s for s in c["singularities"] if s["class"] == "output"]
    assert out["margin"]["dropped"] == 0.0
    rc, text, _ = run_cli(["analyze", path, "--precision", precision])
    assert rc == 0
    block = text[text.index("  output: ") :]  # "output: [its name (...): ]with the inputs locked"
    assert "with the inputs locked" in block.splitlines()[0]
    margin_line = next(line for line in block.splitlines() if "margin:" in line)
    assert "dropped 0 " in margin_line and "dropped -" not in margin_line


def test_exact_report_says_which_tests_ran_at_mp50(tmp_path: Path) -> None:
    """Exact mode runs the input/output tests at mp:50 from the exact data: the verdict
    table says so rather than "exact" for them."""
    path = tmp_path / "inline.yaml"
    path.write_text(INLINE)
    out = tmp_path / "review.md"
    rc, _, err = run_cli(["report", path, "--precision", "exact", "-o", out])
    assert rc == 0, err
    row = next(line for line in out.read_text().splitlines() if line.startswith("| **reference**"))
    assert "exact (the " in row and "tests at mp:50)" in row
    assert "output" in row.split("exact (the ")[1]


SCARA = Path(__file__).parent / "data" / "scara.yaml"


def test_auto_re_decides_an_undecided_output_motion_at_mp50() -> None:
    """1.7e-5 rad from the SCARA's elbow the arm is bent: its end effector's twists span
    the Schoenflies subgroup X about z (rotations about vertical axes, every translation),
    which float leaves undecided there; auto re-decides it at mp:50, as mp:50 finds."""
    by = {
        p: {
            c["name"]: c
            for c in cli_json(["analyze", SCARA, "--precision", p, "--format", "json"])[
                "configurations"
            ]
        }
        for p in ("auto", "mp:50", "float")
    }
    assert by["float"]["near-elbow"]["output_motion"]["type"] is None  # float: undecided
    for p in ("auto", "mp:50"):
        c = by[p]["near-elbow"]
        assert c["precision"] == "mp:50"
        m = c["output_motion"]
        assert (m["type"], m["dim"], m["is_subgroup"]) == ("X", 4, True)
        assert m["params"]["axis"] == pytest.approx([0.0, 0.0, 1.0], abs=1e-12)
    # at the elbow itself (stretched) the twists span dimension 3 in every mode
    assert {by[p]["elbow"]["output_motion"]["dim"] for p in by} == {3}


def test_report_never_lists_an_undecided_type_where_it_differs(tmp_path: Path) -> None:
    out = tmp_path / "review.md"
    rc, _, err = run_cli(["report", SCARA, "--precision", "float", "-o", out])
    assert rc == 0, err
    text = out.read_text()
    differs = text[text.index("Where it differs") :].split("\n\n")[1]
    assert "at elbow" in differs
    assert "near-elbow" not in differs


#: a screw jack: one helical joint of pitch 0.01 m/rad about the vertical axis through
#: (1, 2, 0); the lifted body's only twist is that screw's, (z; (1, 2, 0) x z + 0.01 z)
JACK = """\
mechanism: screw-jack
bodies: [ground, nut]
joints:
  - {name: H1, type: H, between: [ground, nut], axis: [0, 0, 1], point: [1, 2, 0], pitch: 0.01}
output: {body: nut}
configurations:
  turned: {H1: 0.5}
"""


def test_one_twist_is_an_instantaneous_screw_not_a_motion_type(tmp_path: Path) -> None:
    path = tmp_path / "jack.yaml"
    path.write_text(JACK)
    res = cli_json(["analyze", path, "--format", "json"])
    for m in (res["output_motion"], res["configurations"][0]["output_motion"]):
        assert (m["type"], m["dim"], m["summary"]) == ("H", 1, "H (dimension 1)")  # kept
        screw = m["instantaneous_screw"]
        assert screw["type"] == "H"
        assert screw["params"]["pitch"] == pytest.approx(0.01, rel=1e-12)
        assert screw["twist"] == pytest.approx([0, 0, 1, 2, -1, 0.01], abs=1e-12)
    for fmt in ("text", "md"):
        rc, out, _ = run_cli(["analyze", path, "--format", fmt])
        assert rc == 0
        assert "nut's instantaneous screw: a screw motion of pitch 0.01 m/rad" in out
        assert "motion type" not in out
    review = tmp_path / "review.md"
    rc, _, err = run_cli(["report", path, "-o", review])
    assert rc == 0, err
    text = review.read_text()
    assert "### Output motion\n" in text and "Output motion type" not in text
    assert "its instantaneous screw H" in text
    assert "An instantaneous screw is not a motion type" in text
