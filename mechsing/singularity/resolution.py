"""How much a configuration's given values can move its tests' singular values.

Owns :func:`test_sigmas` (every test's singular values at a configuration, relative to
its largest, in float: the closure system and its loops, the output chain, each leg's
chain, the input/output ranks ``T N`` and ``E N``) and
:func:`value_slopes`, their first-order sensitivity to each given coordinate: the
largest change of any relative singular value per unit of that coordinate (radians,
metres), by finite one-sided
differences of step :data:`mechsing.singularity.resolution.RESOLUTION_STEP`
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
from mechsing.numeric import Precision, RankDecision, decide_rank
from mechsing.screws import closure_system
from mechsing.screws.systems import share_loop_identifications
from mechsing.singularity.criteria import ConstraintTest, SerialTest
from mechsing.singularity.zfb import io_quantities, output_chain

#: the finite-difference step (radians, or lengths / L) over which the tests' singular
#: values are differentiated with respect to a given value, for the first-order bound
#: of what the data's resolution can move them by: far above float's rounding of the
#: differences (1e-16 / 1e-6 relative) and small enough that the first order holds
RESOLUTION_STEP = 1e-6

__all__ = [
    "closure_nullity",
    "geometry_slopes",
    "geometry_step",
    "test_sigmas",
    "value_slopes",
    "value_step",
]

_FLOAT = Precision("float")


def _relative(dec: RankDecision) -> np.ndarray:
    s = np.asarray(dec.sigma if dec.sigma is not None else (), dtype=float)
    smax = dec.margin.sigma_max or (float(s[0]) if s.size else 0.0)
    return s / smax if smax else s


def test_sigmas(mech: Any, fm: Any, q: np.ndarray, nullity: int | None = None) -> list[np.ndarray]:
    """The relative singular values of every test at ``q`` (float model ``fm``), in a
    fixed order for a given mechanism (so that two configurations can be compared).

    ``nullity``: the closure kernel's dimension to hold (the one decided at the
    configuration compared with, :func:`closure_nullity`): the input/output tests are
    then those of the closure's ``nullity`` smallest singular directions, which move as
    continuously as the data, where the kernel decided at ``q`` would jump with its
    rank (a kernel of dimension 2 at a bifurcation, of 1 beside it)."""
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
    if nullity is not None and nullity != cs.nullity:
        N = _smallest_directions(np.asarray(cs.matrix, dtype=float), nullity)
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


def value_step(fm: Any, column: int) -> float:
    """The finite-difference step of a coordinate column (:func:`value_slopes`): radians,
    or metres (lengths / L)."""
    return RESOLUTION_STEP * (fm.length_scale if fm.length_columns[column] else 1.0)


def geometry_step(fm: Any, key: str) -> float:
    """The finite-difference step of a geometry entry (:func:`geometry_slopes`): a
    direction's component, or metres (lengths / L)."""
    return RESOLUTION_STEP * (1.0 if key in ("axis", "normal") else fm.length_scale)


def closure_nullity(fm: Any, q: np.ndarray) -> int | None:
    """The closure kernel's dimension decided at ``q`` (float), to hold in
    :func:`test_sigmas` at the configurations compared with it."""
    return closure_system(fm, np.asarray(q, dtype=float), _FLOAT).nullity


def _smallest_directions(A: np.ndarray, k: int) -> np.ndarray | None:
    """The right singular directions of ``A``'s ``k`` smallest singular values (n x k)."""
    if k <= 0:
        return None
    _, _, vt = np.linalg.svd(A, full_matrices=True)
    return vt[-k:].T


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
    k = closure_nullity(fm, q)
    here = test_sigmas(mech, fm, q, k)
    out = []
    for col in columns:
        step = value_step(fm, col)
        worst = 0.0
        for sign in (1.0, -1.0):
            qq = q.copy()
            qq[col] += sign * step
            worst = max(worst, _change(here, test_sigmas(mech, fm, qq, k)))
        out.append(worst / step)
    return out


def _float_params(value: Any) -> Any:
    """A joint parameter in float (tuples entry by entry); what has no float (a symbol) as
    it is."""
    if isinstance(value, tuple):
        return tuple(_float_params(x) for x in value)
    try:
        return float(value)
    except (TypeError, ValueError):
        return value


def _in_float(mech: Any) -> Any:
    """``mech`` with its joints' parameters in float (the models built from it then need
    no exact arithmetic: about a millisecond each), sharing its loop identifications (the
    subgroups identified from the file's values)."""
    out = replace(
        mech,
        joints=tuple(
            replace(j, params={k: _float_params(v) for k, v in j.params.items()})
            for j in mech.joints
        ),
    )
    share_loop_identifications(mech, out)
    return out


def geometry_slopes(
    mech: Any, fm: Any, q: np.ndarray, entries: list[tuple[str, str, int]]
) -> list[float]:
    """For each geometry entry (joint, parameter, index: a point's or pitch's length, a
    direction's component), the largest rate of change of a test's relative singular
    value per SI unit of it at the joint values ``q`` (held): the tests of a float model
    of the mechanism with that entry moved (a direction renormalised), one-sided on
    both sides as :func:`value_slopes`.

    The moved models are built from the mechanism's parameters in float and keep its
    loops' subgroups (identified once, from the file's values): the tests' matrices are
    those of the configuration, moved, and each model costs no exact arithmetic."""
    if not entries:
        return []
    q = np.asarray(q, dtype=float)
    k = closure_nullity(fm, q)
    base = _in_float(mech)
    here = test_sigmas(base, KinematicModel(base, _FLOAT), q, k)
    index_of = {j.name: i for i, j in enumerate(base.joints)}
    out = []
    for joint, key, index in entries:
        at = index_of[joint]
        j = base.joints[at]
        value = j.params[key]
        direction = key in ("axis", "normal")
        step = geometry_step(fm, key)
        worst = 0.0
        for sign in (1.0, -1.0):
            if isinstance(value, tuple):
                moved = list(value)
                moved[index] += sign * step
                if direction:
                    n = float(np.linalg.norm(moved))
                    moved = [x / n for x in moved]
                new = tuple(moved)
            else:
                new = value + sign * step
            joints = list(base.joints)
            joints[at] = replace(j, params={**j.params, key: new})
            other = replace(base, joints=tuple(joints))
            share_loop_identifications(mech, other)
            moved_model = KinematicModel(other, _FLOAT)
            worst = max(worst, _change(here, test_sigmas(other, moved_model, q, k)))
        out.append(worst / step)
    return out
