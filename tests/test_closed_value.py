"""The frozen closed-configuration value (:class:`mechsing.ClosedValue`, issue 42): what
``analyze``, ``modes``, ``sweep(start=...)`` and a sweep's located points hand on.

Its invariants: it cannot be changed (frozen, its coordinates a tuple copied from what it
was given); its provenance (given, located, a certified mode) survives every hand-off (a
mode's value is the sweep's start, a located point's value is its analysis's); and its
digits are those of the precision that placed it: a slider-crank's dead centres located at
mp:30 carry 30 digits, checked against their closed form (crank 1, rod 4, offset: the
slider at 8/5 and at 4 sqrt(11)/5 - 16/5, the law of cosines along the slide).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import mpmath
import numpy as np
import pytest

import mechsing
from mechsing.kinematics.closed import FLOAT_DIGITS, ClosedValue, digits_of
from mechsing.numeric import Precision

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SLIDER = EXAMPLES / "slider_crank_slider_input.yaml"
FOURBAR = EXAMPLES / "fourbar.yaml"


def _dead_centres() -> list[mpmath.mpf]:
    """The slider's dead centres (P, m) in closed form, at 40 digits: C0 = (16/5, 7/5)
    moves along x; A at the origin, crank AB = 1, rod BC = 4; aligned where |AC| = 5
    or 3: P = -16/5 + sqrt(L^2 - (7/5)^2)."""
    with mpmath.workdps(40):
        return [-mpmath.mpf(16) / 5 + mpmath.sqrt(L * L - mpmath.mpf(49) / 25) for L in (5, 3)]


def test_a_closed_value_cannot_be_changed():
    q = np.array([0.1, -0.2, 0.3])
    v = ClosedValue(q, FLOAT_DIGITS, "located", "located-1")
    q[0] = 9.0  # the array it was made from changes: the value does not
    assert v.q == (0.1, -0.2, 0.3) and isinstance(v.q, tuple)
    with pytest.raises(dataclasses.FrozenInstanceError):
        v.source = "mode"  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        v.q = (0.0,)  # type: ignore[misc]
    f = v.floats()
    f[1] = 7.0  # a float copy, not a view
    assert v.q[1] == -0.2
    moved = v.at([0.1, -0.2, 0.31], 30)
    assert (moved.source, moved.name, moved.digits) == ("located", "located-1", 30)
    assert v.digits == FLOAT_DIGITS and v.q[2] == 0.3
    assert hash(v) == hash(ClosedValue((0.1, -0.2, 0.3), FLOAT_DIGITS, "located", "located-1"))


def test_a_closed_value_says_where_it_came_from():
    with pytest.raises(ValueError, match="source"):
        ClosedValue((0.0,), FLOAT_DIGITS, "guessed")
    with pytest.raises(ValueError, match="only an assembly mode"):
        ClosedValue((0.0,), FLOAT_DIGITS, "located", certified=True)
    with pytest.raises(ValueError, match="digits"):
        ClosedValue((0.0,), 0, "given")
    assert digits_of(Precision("float")) == 15  # float64: eps 2.2e-16
    assert digits_of(Precision("mp", 40)) == 40
    assert digits_of(Precision("exact")) is None


def test_analyze_hands_on_the_given_configurations_at_their_digits():
    for prec, digits in (("float", 15), ("mp:40", 40)):
        res = mechsing.analyze(FOURBAR, precision=prec)
        for c in res.configurations:
            p = c.point
            assert (p.source, p.name, p.digits, p.certified) == ("given", c.name, digits, False)
            # the coordinates analysed: the configuration's joints, in coordinate order
            assert np.allclose(p.floats(), [x for _, v in c.joints for x in v], atol=0)
            if prec == "mp:40":
                assert all(isinstance(x, mpmath.mpf) for x in p.q)


@pytest.fixture(scope="module")
def fourbar_modes():
    return mechsing.modes(FOURBAR, "crank-30", "float")


def test_a_mode_is_its_certified_value_and_a_sweep_from_it_keeps_it(fourbar_modes):
    found = fourbar_modes
    assert found.count == 2  # a four-bar's crank angle: two assembly modes (open, crossed)
    for k, m in enumerate(found.modes):
        p = m.point
        assert (p.source, p.certified, p.name) == ("mode", m.certified, f"crank-30#mode{k + 1}")
        assert p.floats().tolist() == [x for v in m.joints.values() for x in v]
        # the mode's analysis is the analysis of that value, its provenance kept
        assert p.digits == FLOAT_DIGITS
    mode = found.modes[1]
    by_mode = mechsing.sweep(FOURBAR, "A=30:60:10", "crank-30", "float", start=mode)
    by_value = mechsing.sweep(FOURBAR, "A=30:60:10", "crank-30", "float", start=mode.point)
    by_index = mechsing.sweep(FOURBAR, "A=30:60:10", "crank-30", "float", start=1)
    for r in (by_mode, by_value, by_index):
        assert r.mode == 2
        assert r.start == mode.point
    # handed on unchanged: the very value (an index finds the modes again: an equal one)
    assert by_mode.start is mode.point and by_value.start is mode.point
    plain = mechsing.sweep(FOURBAR, "A=30:60:10", "crank-30", "float")
    assert plain.start.source == "given" and plain.start.name == "crank-30"
    with pytest.raises(mechsing.errors.UserError, match="not an assembly mode"):
        mechsing.sweep(FOURBAR, "A=30:60:10", "crank-30", "float", start=plain.start)


def test_located_points_are_located_values_and_their_analysis_keeps_that():
    r = mechsing.sweep(SLIDER, "P=-4:4:0.05", precision="float")
    assert len(r.located) == 2
    exact = [float(x) for x in _dead_centres()]
    for i, p in enumerate(r.located):
        v = p.point
        assert (v.source, v.digits, v.name, v.certified) == (
            "located",
            15,
            f"located-{i + 1}",
            False,
        )
        assert v.floats().tolist() == [x for _, xs in p.joints for x in xs]
        assert min(abs(v.q[3] - e) for e in exact) < 1e-12  # the slider, column P
        assert p.configuration.point.source == "located"


def test_located_points_carry_the_digits_of_mp_n():
    """At mp:30 each dead centre is placed again at 30 digits: its value carries them (the
    closed form to 1e-25, where float's is 1e-16 off), and its analysis's point too."""
    r = mechsing.sweep(SLIDER, "P=-4:4:0.5", precision="mp:30")
    exact = _dead_centres()
    assert len(r.located) == 2
    for p in r.located:
        v = p.point
        assert (v.source, v.digits) == ("located", 30)
        assert all(isinstance(x, mpmath.mpf) for x in v.q)
        with mpmath.workdps(40):
            assert min(abs(v.q[3] - e) for e in exact) < mpmath.mpf(10) ** -25
        a = p.configuration.point
        assert (a.source, a.digits, a.name) == ("located", 30, v.name)
