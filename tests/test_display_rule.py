"""One rendering rule: the display floor and the units' spelling are set in one place
(:mod:`mechsing.analysis.display`) and show alike in the text of ``analyze``, ``sweep``,
``modes`` and ``condition``.

Each test changes the rule once (monkeypatched) and checks that all four outputs change
as the rule says; the four-bar of the README (crank 1, coupler 2 sqrt 2, rocker sqrt 5,
ground 4; its file in degrees) is run in-process.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mechsing.analysis import display
from tests.cli import run_cli

FOURBAR = str(Path(__file__).resolve().parents[1] / "examples" / "fourbar.yaml")

#: the four commands, each printing text
COMMANDS = {
    "analyze": ["analyze", FOURBAR, "--config", "crank-30"],
    "sweep": ["sweep", FOURBAR, "--vary", "A=0:1:0.5"],
    "modes": ["modes", FOURBAR, "--config", "crank-30"],
    "condition": ["condition", FOURBAR],
}


def _outputs() -> dict[str, str]:
    out = {}
    for name, argv in COMMANDS.items():
        run = run_cli(argv)
        assert run.status == 0, (name, run.err)
        out[name] = run.out
    return out


def test_a_units_spelling_changes_in_all_four(monkeypatch: pytest.MonkeyPatch) -> None:
    before = _outputs()
    monkeypatch.setitem(display.UNIT_TEXT, "rad", "radian")
    after = _outputs()
    for name in COMMANDS:
        assert " rad" in before[name] and "radian" not in before[name], name
        assert "radian" in after[name], name
        # only the spelling changed: spelt back, the output is the same
        assert after[name].replace("radian", "rad") == before[name], name


def test_the_display_floor_changes_in_all_four(monkeypatch: pytest.MonkeyPatch) -> None:
    before = _outputs()
    # a floor far above every value shown: each one the rule covers is shown as 0
    monkeypatch.setattr(display, "display_floor", lambda precision, length_scale: 1e6)
    after = _outputs()
    # analyze: crank-30's joint values (A = 30 deg = 0.5236 rad) and its residual
    assert "A = [0.523599]" in before["analyze"]
    assert re.search(
        r"joint values \(m, rad\): A = \[0\], B = \[0\], C = \[0\], D = \[0\]", after["analyze"]
    )
    # sweep: the swept value where a test is lowest (A = 1 deg)
    assert "at A = 1 deg (0.01745329252 rad)" in before["sweep"]
    assert "at A = 0 deg (0 rad)" in after["sweep"]
    # modes: every joint value of both modes
    assert "A: 0.5235987755982989 rad" in before["modes"]
    assert re.findall(r"^  [ABCD]: (\S+) rad$", after["modes"], re.M) == ["0"] * 8
    # condition: the roots of 28 cos^2 A + 4 cos A - 23 = 0, cos A = (-1 +- 9 sqrt 2) / 14
    assert "vanishes at A = -2.94412, -0.577722, 0.577722, 2.94412 rad" in before["condition"]
    assert "vanishes at A = 0, 0, 0, 0 rad" in after["condition"]


PUMA = str(Path(__file__).resolve().parents[1] / "examples" / "puma560.yaml")


def test_the_screw_sentences_spell_their_units_by_the_rule(monkeypatch: pytest.MonkeyPatch) -> None:
    """The lost twists and resisted wrenches of an analysis (the PUMA 560's wrist and
    elbow), and a screw's pitch, spell the metre as the rule does."""
    from mechsing.analysis.words import twist_words, wrench_words

    before = run_cli(["analyze", PUMA]).out
    monkeypatch.setitem(display.UNIT_TEXT, "m", "metre")
    after = run_cli(["analyze", PUMA]).out
    lines = before.splitlines()
    lost = [x for x in lines if "lost twist: a rotation about the axis through" in x]
    resisted = [x for x in lines if "resisted wrench: a force along" in x]
    assert lost and resisted and "metre" not in before
    for line in lost:
        assert line.replace(") m along", ") metre along") in after
    for line in resisted:
        assert line.endswith(") m") and line[: -len("m")] + "metre" in after
    assert after.replace("metre", "m") == before  # only the spelling changed
    # a screw motion of pitch 0.5 m/rad about z through the origin; a wrench of pitch 2 m
    # along x through (0, 0, 1) (m = p x f + h f = (2, 1, 0) for f = (1, 0, 0))
    assert twist_words([0, 0, 1, 0, 0, 0.5]) == (
        "a screw motion of pitch 0.5 metre/rad about the axis through (0, 0, 0) metre along z"
    )
    assert wrench_words([1, 0, 0, 2, 1, 0]) == (
        "a force along x through (0, 0, 1) metre with a couple along it (a wrench of pitch 2 metre)"
    )
