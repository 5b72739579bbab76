"""How much a configuration's given values can move its tests' singular values.

Owns :func:`test_sigmas` (every test's singular values at a configuration, relative to
its largest, in float: the closure system and its loops, the output chain, each leg's
chain, the input/output ranks ``T N`` and ``E N``) and
:func:`value_slopes`, their first-order sensitivity to each given coordinate: the
largest change of any relative singular value per unit of that coordinate (radians,
metres), by finite one-sided
differences of step :data:`mechsing.numeric.RESOLUTION_STEP`
(radians, or lengths / L) with the other joint values held.

By Weyl's inequality every singular value of a matrix moves by at most the norm of the
matrix's change, so the largest change over the singular values of a test bounds the
change of the one that decided it; the largest over the tests serves for all of them
(a first-order bound, on the safe side).  The analysis (:mod:`mechsing.analysis`) turns
these slopes and the data's resolution into the spread of
:func:`mechsing.numeric.resolution_spread` and asks each decision whether it could flip
within it (:func:`mechsing.numeric.flips_within`).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from mechsing.kinematics import KinematicModel
from mechsing.numeric import RESOLUTION_STEP, Precision, RankDecision, decide_rank
from mechsing.screws import closure_system
from mechsing.singularity.criteria import ConstraintTest, SerialTest
from mechsing.singularity.zfb import io_quantities, output_chain

__all__ = ["geometry_slopes", "test_sigmas", "value_slopes"]

_FLOAT = Precision("float")


def _relative(dec: RankDecision) -> np.ndarray:
    s = np.asarray(dec.sigma if dec.sigma is not None else (), dtype=float)
    smax = dec.margin.sigma_max or (float(s[0]) if s.size else 0.0)
    return s / smax if smax else s


def test_sigmas(mech: Any, fm: Any, q: np.ndarray) -> list[np.ndarray]:
    """The relative singular values of every test at ``q`` (float model ``fm``), in a
    fixed order for a given mechanism (so that two configurations can be compared)."""
    q = np.asarray(q, dtype=float)
    out: list[np.ndarray] = []
    cs = closure_system(fm, q, _FLOAT)
    if mech.loops:
        out.append(_relative(cs.rank))
        out.extend(_relative(ls.rank) for ls in cs.loops)
    if mech.output is None:
        return out
    if not mech.loops:
        T, _ = output_chain(mech, fm, q, cs, mech.output.point is not None)
        out.append(_relative(decide_rank(T, _FLOAT, fm.length_scale)))
        return out
    N = cs.rank.null_space
    if N is not None and mech.inputs:
        io = io_quantities(mech, fm, q, N, _FLOAT, screws=cs.screws, cs=cs)
        if io is not None:
            out += [_relative(io.input_rank), _relative(io.output_rank)]
    serial = SerialTest.of(mech, fm)
    for leg in ConstraintTest.of(mech, fm).legs:
        here = serial.decide(cs.screws, leg.columns, None, _FLOAT, cs.scaled_screws)
        out.append(_relative(here.rank))
    # not the legs' constraint wrenches: each leg's wrenches are the complement of its
    # decided rank, so their matrix jumps where a leg's rank does (no derivative there);
    # the legs' own chains above move as continuously as the data
    return out


def _change(a: list[np.ndarray], b: list[np.ndarray]) -> float:
    """The largest change of a relative singular value between two lists of tests."""
    worst = 0.0
    for x, y in zip(a, b, strict=False):
        k = min(x.size, y.size)
        if k:
            worst = max(worst, float(np.max(np.abs(x[:k] - y[:k]))))
    return worst


def value_slopes(mech: Any, fm: Any, q: np.ndarray, columns: list[int]) -> list[float]:
    """For each coordinate column, the largest rate of change of a test's relative
    singular value per SI unit of that coordinate (radian, metre) at ``q``: one-sided
    differences on both sides (a singular value that vanishes at q grows like |x| on
    both, which a central difference would cancel)."""
    q = np.asarray(q, dtype=float)
    here = test_sigmas(mech, fm, q)
    out = []
    for col in columns:
        step = RESOLUTION_STEP * (fm.length_scale if fm.length_columns[col] else 1.0)
        worst = 0.0
        for sign in (1.0, -1.0):
            qq = q.copy()
            qq[col] += sign * step
            worst = max(worst, _change(here, test_sigmas(mech, fm, qq)))
        out.append(worst / step)
    return out


def geometry_slopes(
    mech: Any, fm: Any, q: np.ndarray, entries: list[tuple[str, str, int]]
) -> list[float]:
    """For each geometry entry (joint, parameter, index: a point's or pitch's length, a
    direction's component), the largest rate of change of a test's relative singular
    value per SI unit of it at the joint values ``q`` (held): the tests of a float model
    of the mechanism with that entry moved (a direction renormalised), one-sided on
    both sides as :func:`value_slopes`."""
    q = np.asarray(q, dtype=float)
    here = test_sigmas(mech, fm, q)
    out = []
    for joint, key, index in entries:
        j = mech.joint(joint)
        value = j.params[key]
        direction = key in ("axis", "normal")
        step = RESOLUTION_STEP * (1.0 if direction else fm.length_scale)
        worst = 0.0
        for sign in (1.0, -1.0):
            if isinstance(value, tuple):
                moved = [float(x) for x in value]
                moved[index] += sign * step
                if direction:
                    n = float(np.linalg.norm(moved))
                    moved = [x / n for x in moved]
                new = tuple(moved)
            else:
                new = float(value) + sign * step
            other = replace(
                mech,
                joints=tuple(
                    replace(jj, params={**jj.params, key: new}) if jj.name == joint else jj
                    for jj in mech.joints
                ),
            )
            worst = max(worst, _change(here, test_sigmas(other, KinematicModel(other, _FLOAT), q)))
        out.append(worst / step)
    return out
