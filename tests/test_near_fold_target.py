"""Continuation to a target just short of a fold of the given values.

A four-bar (ground pivots A (0, 0) and D (4, 0), crank 2, coupler 3/2, rocker 3/2, drawn
with B (2, 0) and C (3, sqrt(5)/2)) has its crank's limit where coupler and rocker fall
in line, |BD| = 3: 20 - 16 cos A = 9, A = acos(11/16).  Just inside it the two assembly
modes are about the square root of the distance apart (a crank 5e-8 rad inside: the
rocker pins 3e-4 apart), nearer the fold than continuation's shortest step, which then
overshoots it.  The configuration closes all the same, on the reference's side of BD
(the mode continuation comes from), and a crank beyond the limit is still refused.  The
closed forms (circles about B and D) are computed here with mpmath, not by mechsing.
At the limit itself the two modes are one double root, which ``modes`` counts once and
marks as the mode continuation reaches (float's closure there is known to about 1e-8).
A crank 1e-13 rad inside is closer to the fold than float can tell: float lands on the
fold itself, and the configuration is closed (``solve`` at mp:N) and its mode marked
(``modes``) from more digits.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import mpmath
import pytest

from mechsing.analysis.solve import solve
from mechsing.model import load
from tests.cli import run_cli

FOUR_BAR = """\
mechanism: four-bar-at-its-limit
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [2, 0, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, "sqrt(5)/2", 0]}
  - {name: D, type: R, between: [rocker, ground], axis: [0, 0, 1], point: [4, 0, 0]}
inputs: [A]
output: {body: rocker}
configurations:
  inside-5e-8: {A: 0.8127555164}
  inside-1e-9: {A: "acos(11/16) - 0.000000001"}
  beyond-1e-9: {A: "acos(11/16) + 0.000000001"}
  inside-1e-13: {A: "acos(11/16) - 0.0000000000001"}
  beyond-1e-13: {A: "acos(11/16) + 0.0000000000001"}
  at-the-limit: {A: "acos(11/16)"}
  from-beyond: {A: 0.5, start: beyond-1e-9}
"""


def _rocker_pin(crank: float | mpmath.mpf) -> tuple[mpmath.mpf, mpmath.mpf]:
    """C at crank angle ``crank``: the circles about B (radius 3/2) and D (3/2) meet on the
    reference's side of BD (C above BD at the reference)."""
    with mpmath.workdps(40):
        a = mpmath.mpf(crank)
        bx, by = 2 * mpmath.cos(a), 2 * mpmath.sin(a)
        ux, uy = 4 - bx, -by
        d = mpmath.sqrt(ux**2 + uy**2)
        ux, uy = ux / d, uy / d
        h = mpmath.sqrt(max(mpmath.mpf(0), mpmath.mpf(9) / 4 - d**2 / 4))  # 0 at the limit
        # the left normal of B -> D: the reference's C = (3, sqrt(5)/2) lies to its left
        return bx + d / 2 * ux - h * uy, by + d / 2 * uy + h * ux


def _solved_rocker_pin(q: dict[str, float]) -> tuple[float, float]:
    """C from the solved joints: the coupler (B -> C, at atan2(sqrt(5)/2, 1) in the
    reference) turned by A + B."""
    a, b = q["A"], q["B"]
    phi = math.atan2(math.sqrt(5) / 2, 1.0) + a + b
    return 2 * math.cos(a) + 1.5 * math.cos(phi), 2 * math.sin(a) + 1.5 * math.sin(phi)


@pytest.mark.parametrize("name", ["inside-5e-8", "inside-1e-9"])
def test_a_crank_just_inside_its_limit_closes_on_the_reference_mode(
    tmp_path: Path, name: str
) -> None:
    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR)
    res = solve(load(str(f)), name, "float")
    q = {joint: values[0] for joint, values in res.joints}
    want = _rocker_pin(q["A"])
    got = _solved_rocker_pin(q)
    # the other mode's C is 1e-4 to 1e-3 away (its mirror image about BD)
    assert abs(got[0] - float(want[0])) < 1e-9 and abs(got[1] - float(want[1])) < 1e-9
    assert math.hypot(got[0] - 4.0, got[1]) == pytest.approx(1.5, abs=1e-12)


def test_a_crank_a_hair_inside_its_limit_closes_at_mp_on_the_reference_mode(
    tmp_path: Path,
) -> None:
    """1e-13 rad inside: float lands on the fold itself (its closure known to about 1e-8,
    the two modes 1e-6 apart), where Newton at 50 digits finds no direction to either
    root; the root is reached from further along the branch."""
    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR)
    res = solve(load(str(f)), "inside-1e-13", "mp:50")
    q = {joint: values[0] for joint, values in res.joints_text}
    with mpmath.workdps(50):
        a, b = mpmath.mpf(q["A"]), mpmath.mpf(q["B"])
        assert abs(a - (mpmath.acos(mpmath.mpf(11) / 16) - mpmath.mpf("1e-13"))) < 1e-45
        want = _rocker_pin(a)
        phi = mpmath.atan2(mpmath.sqrt(5) / 2, 1) + a + b
        got = (2 * mpmath.cos(a) + 1.5 * mpmath.cos(phi), 2 * mpmath.sin(a) + 1.5 * mpmath.sin(phi))
        # the other mode's pin is 2 h = 1.1e-6 away: h = sqrt(9 - |BD|^2) / 2 and
        # |BD|^2 = 20 - 16 cos A
        assert abs(got[0] - want[0]) < 1e-30 and abs(got[1] - want[1]) < 1e-30
    with pytest.raises(Exception, match="beyond a limit of travel"):
        solve(load(str(f)), "beyond-1e-13", "mp:50")


def test_a_crank_just_beyond_its_limit_is_still_refused(tmp_path: Path) -> None:
    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR)
    with pytest.raises(Exception, match="beyond a limit of travel"):
        solve(load(str(f)), "beyond-1e-9", "float")


def test_modes_at_the_limit_count_the_double_root_the_start_reaches(tmp_path: Path) -> None:
    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR)
    rc, out, err = run_cli(["modes", str(f), "--config", "at-the-limit", "--format", "json"])
    assert rc == 0, err
    doc = json.loads(out)
    (mode,) = doc["modes"]
    assert mode["reached_by_continuation"] and not mode["certified"]
    assert not any("misses" in n for n in doc["notes"]), doc["notes"]
    with mpmath.workdps(40):
        want = _rocker_pin(mpmath.acos(mpmath.mpf(11) / 16))
    got = _solved_rocker_pin({k: v[0] for k, v in mode["joints"].items()})
    assert abs(got[0] - float(want[0])) < 1e-9 and abs(got[1] - float(want[1])) < 1e-9


@pytest.mark.parametrize("precision", ["float", "mp:50"])
def test_modes_a_hair_inside_the_limit_mark_the_mode_the_start_reaches(
    tmp_path: Path, precision: str
) -> None:
    """1e-13 rad inside: two modes 1.1e-6 apart; float's continuation lands on the fold
    between them, matching neither, and at more digits reaches the reference's."""
    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR)
    argv = ["modes", str(f), "--config", "inside-1e-13", "--format", "json"]
    rc, out, err = run_cli([*argv, "--precision", precision])
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["count"] == 2 and not doc["notes"], doc["notes"]
    with mpmath.workdps(40):
        want = _rocker_pin(mpmath.acos(mpmath.mpf(11) / 16) - mpmath.mpf("1e-13"))
    for mode in doc["modes"]:
        got = _solved_rocker_pin({k: v[0] for k, v in mode["joints"].items()})
        ours = abs(got[0] - float(want[0])) < 1e-9 and abs(got[1] - float(want[1])) < 1e-9
        assert mode["reached_by_continuation"] == ours


@pytest.mark.parametrize("name", ["beyond-1e-9", "beyond-1e-13"])
def test_no_mode_beyond_the_limit_says_where_the_limit_is(tmp_path: Path, name: str) -> None:
    """A crank 1e-9 rad beyond its limit: no mode (proven), and a note saying by how
    much and where the limit is (acos(11/16), to the digits the note gives).  1e-13 rad
    beyond, float closes the crank to its tolerance; more digits say it is beyond."""

    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR)
    rc, out, err = run_cli(["modes", str(f), "--config", name, "--format", "json"])
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["count"] == 0 and doc["complete"] == "proven"
    (note,) = [n for n in doc["notes"] if "beyond a limit of travel" in n]
    limit = re.search(r"its limit at about A = ([0-9.]+) rad", note)
    assert limit is not None, note
    digits = len(limit.group(1)) - 2
    assert abs(float(limit.group(1)) - math.acos(11 / 16)) <= 10.0**-digits, note


def test_the_error_beyond_a_limit_keeps_its_sentence_when_pickled(tmp_path: Path) -> None:
    import pickle

    from mechsing.errors import BeyondTravelError

    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR)
    with pytest.raises(BeyondTravelError) as caught:
        solve(load(str(f)), "beyond-1e-9", "float")
    again = pickle.loads(pickle.dumps(caught.value))
    assert isinstance(again, BeyondTravelError) and again.travel == caught.value.travel
    assert "beyond its limit at about A = " in again.travel and str(again) == str(caught.value)


def test_a_configuration_started_from_one_beyond_the_limit_is_a_closure_error(
    tmp_path: Path,
) -> None:
    """The start's limit of travel is not the configuration's own: the error names the
    start and is a plain closure error (exit status 3)."""
    from mechsing.errors import BeyondTravelError, ClosureError

    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR)
    with pytest.raises(ClosureError) as caught:
        solve(load(str(f)), "from-beyond", "float")
    assert not isinstance(caught.value, BeyondTravelError)
    assert "starts from 'beyond-1e-9', which could not be closed" in str(caught.value)


FAR = {"far": 2.0, "far-negative": -2.5}


def _solve_beyond(
    tmp_path: Path, targets: dict[str, float], name: str
) -> tuple[Path, float, float, str]:
    """``solve`` of the four-bar at the crank value ``targets[name]``, beyond its limit:
    the file, the target, the limit on its side (acos(11/16)) and the error, which it
    must be."""
    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR + "".join(f"  {k}: {{A: {v}}}\n" for k, v in targets.items()))
    target = targets[name]
    rc, _out, err = run_cli(["solve", str(f), "--config", name])
    assert rc != 0
    return f, target, math.copysign(math.acos(11 / 16), target), err


@pytest.mark.parametrize("name", sorted(FAR))
def test_a_target_far_beyond_the_limit_gets_no_limit_outside_the_path(
    tmp_path: Path, name: str
) -> None:
    """A crank far beyond its limit (acos(11/16) either way): the error never places the
    limit outside the path from the value continuation reached to the target (a
    first-order estimate at a least-squares landing far from the fold once put a
    rocker's limit 2 pi/3 at -2.0); it says the value reached, which lies within 1e-4
    short of the limit, and bounds the excess by the rest of the way."""
    f, target, limit, err = _solve_beyond(tmp_path, FAR, name)
    reached = float(re.search(r"A reached (-?[0-9.]+) rad", err).group(1))  # type: ignore[union-attr]
    assert abs(reached) < abs(limit) and abs(limit - reached) < 1e-4, err
    estimate = re.search(r"at about A = (-?[0-9.]+) rad", err)
    if estimate is not None:
        assert min(reached, target) <= float(estimate.group(1)) <= max(reached, target), err
    else:
        past = re.search(
            r"A is at most ([0-9.]+) rad beyond its limit, which lies past A = (-?[0-9.]+)", err
        )
        assert past is not None, err
        assert float(past.group(2)) == pytest.approx(reached, abs=1e-9)
        assert float(past.group(1)) == pytest.approx(abs(target - reached), rel=5e-3)
        assert float(past.group(1)) >= abs(target - limit)
    rc, out, err = run_cli(["modes", str(f), "--config", name, "--format", "json"])
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["count"] == 0 and doc["complete"] == "proven"
    (note,) = [n for n in doc["notes"] if "beyond a limit of travel" in n]
    assert "lies past A = " in note or "at about A = " in note


def test_solve_says_what_the_closure_notes(tmp_path: Path) -> None:
    """At the crank's limit acos(11/16) itself, float places the unknown joints only to
    about 1e-8: solve says so in its JSON ``notes`` and its text, as analyze does."""
    f = tmp_path / "four_bar_limit.yaml"
    f.write_text(FOUR_BAR)
    rc, out, err = run_cli(["solve", str(f), "--config", "at-the-limit", "--format", "json"])
    assert rc == 0, err
    (note,) = json.loads(out)["notes"]
    assert "the given values are a fold" in note and "about 1e-8" in note
    rc, out, err = run_cli(["solve", str(f), "--config", "at-the-limit"])
    assert rc == 0, err
    assert f"  note: {note}" in out
    rc, out, err = run_cli(["solve", str(f), "--config", "inside-1e-9", "--format", "json"])
    assert rc == 0 and json.loads(out)["notes"] == [], err


NEAR_BEYOND = {"just-beyond": 0.8128, "beyond": 0.85, "beyond-negative": -0.9}


@pytest.mark.parametrize("name", sorted(NEAR_BEYOND))
def test_a_target_beyond_the_limit_is_said_to_be_so_with_its_excess(
    tmp_path: Path, name: str
) -> None:
    """A crank 4.5e-5 to 0.09 rad beyond its limit acos(11/16), either way: continuation
    stalls just short of the limit, and the least squares at the target lands too far
    from the fold to say anything.  The error still says the target is beyond a limit of
    travel, by how much (|target| - acos(11/16), to 0.5%) and where the limit is
    (acos(11/16), to within one unit of the last digit written: a first-order estimate
    from a landing just past the fold), never 'add an intermediate configuration'."""
    _f, target, limit, err = _solve_beyond(tmp_path, NEAR_BEYOND, name)
    assert "intermediate configuration" not in err, err
    said = re.search(r"A is ([0-9.e+-]+) rad beyond its limit at about A = (-?[0-9.]+) rad", err)
    assert said is not None, err
    assert float(said.group(1)) == pytest.approx(abs(target - limit), rel=5e-3)
    shown = said.group(2)
    digits = len(shown.split(".")[1])
    assert abs(float(shown) - limit) <= 10.0**-digits, err
