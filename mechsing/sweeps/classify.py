"""Classifying the points a sweep located: the full analysis of each at the sweep's precision.

Owns :func:`classify_located` (each located point analysed by
:func:`mechsing.analysis.analyze_found`, first found again at N digits at mp:N:
:mod:`.relocate`), :func:`located_texts` (the joints of a point found again, as text at
its digits) and :func:`unresolved` (why a limit of travel the analysis found regular is
not resolved).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, NamedTuple

import numpy as np

from mechsing.analysis import analyze_found
from mechsing.analysis.solve import value_text
from mechsing.kinematics.closed import FLOAT_DIGITS, ClosedValue, digits_of
from mechsing.numeric import Precision, parse_precision
from mechsing.sweeps.engine import Sweep
from mechsing.sweeps.records import Located

__all__ = ["Classified", "classify_located", "located_texts", "unresolved"]

#: digits beyond N at which a bifurcation's regular system is solved for mp:N
BIFURCATION_GUARD_DIGITS = 5


class Classified(NamedTuple):
    """The full analyses of located points, in their order: each point's analysis result
    (:class:`~mechsing.analysis.results.ConfigurationResult`), whether it was placed again
    at N digits first, and the point it was analysed at (a
    :class:`~mechsing.kinematics.closed.ClosedValue`, source ``located``, at N digits when
    placed again)."""

    results: list[Any]
    moved: list[bool]
    points: list[Any]


def classify_located(
    sweep: Sweep, located: list[Located], precision: Precision, time_limit: float | None = None
) -> Classified:
    """The full analysis of each located point at the sweep's precision, each within
    ``time_limit`` seconds (None: no limit); at mp:N each point is first found again at N
    digits (:mod:`.relocate`).  Also says, per point, whether it was relocated, and gives
    the joints it was analysed at (at N digits when relocated)."""
    if not located:
        return Classified([], [], [])
    points: dict[str, Any] = {}
    moved = []
    relocators: dict[str, Any] = {}

    def relocator(digits: int) -> Any:
        from mechsing.sweeps.relocate import Relocator

        key = str(digits)
        if key not in relocators:
            relocators[key] = Relocator(sweep, Precision("mp", digits))
        return relocators[key]

    def again_at(p: Located, prec: Precision) -> Any:
        if p.z is None:
            return None
        if p.kind == "fold":  # placed by its own conditions, whatever test vanishes there
            return relocator(prec.digits).relocate(p.z, "fold", "fold")
        test = next((t for t in p.tests if t in sweep.tests), None)
        if test is None:
            return None
        if test == "closure":
            # a bifurcation: its own regular system places it at N digits (and a few
            # guard digits); where that does not converge, the secant on the test's
            # determinant, a double root of the closure for the held values, places it
            # to half the working digits only: at 2N + 10 digits (read at N)
            q = relocator(prec.digits + BIFURCATION_GUARD_DIGITS).bifurcation(p.z)
            if q is not None:
                return q
            return relocator(prec.digits * 2 + 10).relocate(p.z, test, p.edge)
        return relocator(prec.digits).relocate(p.z, test, p.edge)

    for i, p in enumerate(located):
        # policy: only mp places the points again, at its digits
        again = again_at(p, precision) if precision.mode == "mp" else None
        moved.append(again is not None)
        name = f"located-{i + 1}"
        points[name] = ClosedValue(p.q, FLOAT_DIGITS, "located", name)
        if again is not None:
            points[name] = points[name].at(again, digits_of(precision))
    results = analyze_found(sweep.mech, points, precision, time_limit)
    if precision.mode == "auto":
        # auto re-decided some points at mp:50 (an undecided float rank): at 50 digits the
        # float point is a regular neighbour of the singular one, so it is found again there
        deep = Precision("mp", 50)
        for i, (p, res) in enumerate(zip(located, results, strict=True)):
            if res.precision == "float" or res.error is not None:
                continue
            again = again_at(p, deep)
            if again is not None:
                name = f"located-{i + 1}"
                points[name] = points[name].at(again, digits_of(deep))
                res2 = analyze_found(sweep.mech, {name: points[name]}, deep, time_limit)[0]
                results[i] = replace(res2, escalated_for=res.escalated_for)
                moved[i] = True
    return Classified(results, moved, list(points.values()))


def located_texts(eng: Sweep, q: Any, analysed: Any) -> tuple[Any, Any]:
    """The swept values (None when one is a pose variable) and every joint value of a
    point found again at N digits (its coordinates, or its
    :class:`~mechsing.kinematics.closed.ClosedValue`), as text at its analysis's N digits."""
    if isinstance(q, ClosedValue):
        q = np.array(q.q, dtype=object)
    prec = parse_precision(analysed.precision)
    joints = tuple(
        (jk.name, tuple(value_text(x, prec) for x in q[jk.columns])) for jk in eng.model.joints
    )
    n = eng.model.n
    values = (
        tuple(value_text(q[c], prec) for c in eng.cols) if all(c < n for c in eng.cols) else None
    )
    return values, joints


def unresolved(p: Any, analysed: Any, moved: bool, drives: bool) -> str | None:
    """Why a limit of travel the full analysis found regular is not resolved (None for
    any other point).  At a fold of an input or of a coordinate of the output's pose
    (``drives``) the closure for the held values loses rank, and so does a test (the
    inputs', or the output's, rank on the motion space): a regular verdict there means
    the point was not placed closely enough for the precision that decided it."""
    if p.kind != "fold" or not drives or analysed is None or analysed.error is not None:
        return None
    if analysed.singular is not False:
        return None
    kept = [
        (d.margin.kept, d.test)
        for d in analysed.decisions
        if d.rank is not None and d.margin is not None and d.margin.kept is not None
    ]
    low = f" (smallest kept singular value {min(kept)[0]:.2g}, {min(kept)[1]})" if kept else ""
    where = (
        "placed again at its digits"
        if moved
        else "kept its float values (placing it again at the analysis's digits failed)"
    )
    return (
        f"the full analysis at {analysed.precision} found every test at its generic rank{low}; "
        f"the point {where}, and at a limit of travel some test drops rank"
    )
