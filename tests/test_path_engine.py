"""The one path engine (mechsing.kinematics.paths): its crossing locator on closed forms,
and one fold definition serving both continuation and the sweeps.

The slider-crank of examples/slider_crank_slider_input.yaml (crank r = 1, rod l = 4, offset
e = 7/5, the slider input P measured from x = 16/5) has its outer dead centre at
x = sqrt((l + r)^2 - e^2) = 24/5, P = 8/5: a fold of P (a limit of its travel), where the
crank points at (24/25, 7/25): A = 2 atan(4/3), B = -2 atan(2), C = 2 atan(2/11) (the
file's exactly closed ``dead-centre`` configuration).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechsing
from mechsing.kinematics.paths import folds
from mechsing.kinematics.paths.crossing import locate_crossing

EX = Path(__file__).resolve().parents[1] / "examples"

#: the dead centre's joint values (closed form, above)
DEAD_CENTRE = {
    "A": 2 * math.atan(4 / 3),
    "B": -2 * math.atan(2),
    "C": 2 * math.atan(2 / 11),
    "P": 8 / 5,
}


def test_the_crossing_of_a_smooth_reading_is_its_root() -> None:
    assert locate_crossing(lambda v: v * v - 2.0, 0.0, 2.0, 1e-15) == pytest.approx(
        math.sqrt(2), abs=4e-15
    )
    assert locate_crossing(lambda v: math.cos(v), 3.0, 1.0, 1e-15) == pytest.approx(
        math.pi / 2, abs=4e-15
    )


def test_a_reading_that_only_changes_sign_is_located_at_its_jump() -> None:
    # an unbounded effort reads as over the limit: the reading may jump, not cross
    at = locate_crossing(lambda v: 1.0 if v > 0.3 else -0.5, 0.0, 1.0, 1e-13)
    assert at is not None and abs(at - 0.3) <= 2e-13


def test_no_crossing_when_the_ends_agree_or_the_path_is_lost() -> None:
    assert locate_crossing(lambda v: v + 1.0, 0.0, 1.0, 1e-12) is None
    assert locate_crossing(lambda v: None if v > 0.5 else v - 0.7, 0.0, 1.0, 1e-12) is None


def _with_a_fold_target(tmp_path: Path) -> Path:
    text = (EX / "slider_crank_slider_input.yaml").read_text()
    text = text.replace('  slider-4: {P: "4/5"}', '  slider-4: {P: "4/5"}\n  at-fold: {P: "8/5"}')
    f = tmp_path / "slider_crank.yaml"
    f.write_text(text)
    return f


def test_continuation_and_a_sweep_land_on_a_fold_by_the_same_definitions(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    calls = {"land": 0, "samples": 0}
    land, samples = folds.land_on_fold, folds.fold_samples

    def counted_land(*a, **k):  # type: ignore[no-untyped-def]
        calls["land"] += 1
        return land(*a, **k)

    def counted_samples(*a, **k):  # type: ignore[no-untyped-def]
        calls["samples"] += 1
        return samples(*a, **k)

    import mechsing.kinematics.continuation as continuation

    monkeypatch.setattr(continuation, "land_on_fold", counted_land)
    monkeypatch.setattr(folds, "fold_samples", counted_samples)
    f = _with_a_fold_target(tmp_path)
    # continuation: the given P is the fold itself, landed on from just short of it
    r = mechsing.analyze(f, precision="float", configs=["at-fold"])
    (c,) = r.configurations
    got = {name: v[0] for name, v in c.joints}
    for name, want in DEAD_CENTRE.items():
        assert got[name] == pytest.approx(want, abs=1e-7), name  # float: ~1e-8 at a fold
    assert calls["land"] >= 1
    # a sweep over P through the dead centre: the fold located along the curve, the
    # samples just short of it placed by the square-root law of the same module
    s = mechsing.sweep(f, ["P=0:2:0.01"], "reference")
    (p,) = [p for p in s.located if p.kind == "fold"]
    assert p.values[0] == pytest.approx(8 / 5, abs=1e-12)
    at = {name: v[0] for name, v in p.joints}
    for name, want in DEAD_CENTRE.items():
        assert at[name] == pytest.approx(want, abs=1e-9), name
    assert calls["samples"] >= 1
    # every sample short of the fold was reached, none beyond it on this mode's way
    reached = np.asarray(s.reached)
    values = np.asarray(s.variables[0].values)
    assert reached[values <= 8 / 5].all()


def test_one_turning_at_a_fold_onto_the_side_asked_for() -> None:
    """folds.leave_fold is the one turning: from the dead centre with the slider moved back
    by d, each side of the kernel gives one of the two assembly modes that meet there, in
    closed form: the slider pin C = (24/5 - d, 7/5), the crank pin B = (sin A, -cos A),
    |C - B| = 4, so sin(A - phi) = (|C|^2 - 15) / (2 |C|), phi = atan2(7/5, 24/5): the two
    roots either side of the dead centre's A = phi + pi/2.  Continuation, a sweep's start
    and a path past a fold turn by that same function."""
    import mechsing.kinematics.continuation as continuation
    from mechsing.kinematics import KinematicModel
    from mechsing.kinematics.paths import arc

    assert continuation.leave_fold is folds.leave_fold and arc.leave_fold is folds.leave_fold
    mech = mechsing.load(EX / "slider_crank_slider_input.yaml")
    fm = KinematicModel(mech, "float")
    q0 = np.array([DEAD_CENTRE[j] for j in "ABCP"])
    gmask = np.array([False, False, False, True])
    d = 1e-6
    target = q0.copy()
    target[3] -= d
    cx, cy = 24 / 5 - d, 7 / 5
    rc, phi = math.hypot(cx, cy), math.atan2(cy, cx)
    s = math.asin((rc * rc - 15) / (2 * rc))
    roots = sorted([phi + s, phi + math.pi - s])
    assert roots[0] < DEAD_CENTRE["A"] < roots[1]
    for sign, want in ((1.0, roots[1]), (-1.0, roots[0])):
        toward = np.array([sign, 0.0, 0.0, 0.0])  # the kernel's side where A grows or falls
        fold, q = folds.leave_fold(fm, q0, target, gmask, 1.0, toward)
        assert fold and q is not None
        assert q[3] == pytest.approx(8 / 5 - d, abs=1e-15)
        # closed to a step's tolerance (1e-9 L): at sigma_min ~ sqrt(d) the joints to 1e-6,
        # the two roots 3e-3 apart
        assert q[0] == pytest.approx(want, abs=1e-6)
    # either side, the + one first, when no side is asked for (a start drawn at a fold)
    fold, q = folds.leave_fold(fm, q0, target, gmask, 1.0)
    assert fold and min(abs(q[0] - r) for r in roots) < 1e-6
    # beyond the limit of travel there is no landing on either side
    beyond = q0.copy()
    beyond[3] += d
    assert folds.leave_fold(fm, q0, beyond, gmask, 1.0, np.array([1.0, 0, 0, 0])) == (True, None)


def test_a_path_past_a_fold_turns_by_the_one_turning(monkeypatch: pytest.MonkeyPatch) -> None:
    """A double rocker swept over a full turn meets a limit of travel on each side and
    comes back past the other (Arc.other_side): it turns there by folds.leave_fold, onto
    the side of the curve it came along, and finds both limits, +-2 pi/3 in closed form
    (the coupler and rocker in line: the law of cosines on the file's lengths)."""
    from mechsing.kinematics.paths import arc

    sides: list[bool] = []

    def spied(*a, **k):  # type: ignore[no-untyped-def]
        out = folds.leave_fold(*a, **k)
        sides.append(a[5] is not None if len(a) > 5 else k.get("toward") is not None)
        return out

    monkeypatch.setattr(arc, "leave_fold", spied)
    r = mechsing.sweep(EX / "double_rocker.yaml", ["A=-3.1:3.1:0.01"])
    folds_at = sorted(p.values[0] for p in r.located if p.kind == "fold")
    assert folds_at == pytest.approx([-2 * math.pi / 3, 2 * math.pi / 3], abs=1e-9)
    assert sides and all(sides)  # every turn past a fold asked for the side it came along
