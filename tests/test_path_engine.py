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
