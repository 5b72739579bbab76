"""The condition of an open chain (``mechsing condition`` on a serial arm).

The determinant of its output Jacobian, the columns being the joint twists (or,
with ``output.point``, the velocities of that point) written in the frame of the
chain's middle body (determinants do not depend on the frame, and the middle frame
keeps the expressions short).  When the twists span a subgroup smaller than SE(3)
(a planar chain spans 3 directions, a point in a plane 2), only the rows of that
subgroup's coordinates are kept, and the determinant is scaled back from that projection
to the span's own volume (:func:`~mechsing.conditions.jacobians.span_volume`: a 2R or 3R
arm in any plane has the determinant l1 l2 sin, as in the xy plane); a redundant chain gives the gcd of its maximal
minors (:mod:`mechsing.conditions.jacobians`)."""

from __future__ import annotations

from typing import Any

import sympy

from mechsing.conditions.explain import Explainer
from mechsing.conditions.jacobians import (
    all_joints,
    chain_twists,
    is_planar,
    maximal_condition,
    mechanism_size,
    parameter_symbols,
    reduce_rows,
    span_volume,
)
from mechsing.conditions.results import Condition
from mechsing.conditions.symbolic import JointSymbols
from mechsing.errors import UserError
from mechsing.model import Mechanism

__all__ = ["open_chain"]


def open_chain(mech: Mechanism, S: dict[str, JointSymbols]) -> tuple[list[Condition], list[str]]:
    out = mech.output
    assert out is not None
    tp = mech.graph.tree_paths
    base = list(tp.get(out.relative_to, ()))
    path = list(tp[out.body])
    if path[: len(base)] == base:
        steps = [(s.joint, s.sign) for s in path[len(base) :]]
    else:
        raise UserError(
            f"{mech.path}: output: the output body {out.body!r} is not further from the ground "
            f"than {out.relative_to!r} along the chain; measure it relative to the ground"
        )
    n = len(steps)
    k = n // 2
    cols, end, _ = chain_twists(mech, S, steps, k)
    params = parameter_symbols(mech)
    Sl = all_joints(S)
    point = None
    if out.point is not None:
        P = end.point(sympy.Matrix(out.point))
        point = P
        cols_p = [c[3:, :] + c[:3, :].cross(P) for c in cols]
        J = sympy.Matrix.hstack(*cols_p)
        what = "output point's velocity"
    else:
        J = sympy.Matrix.hstack(*cols)
        what = "output twist"
    Jr, fixed, r = reduce_rows(J, Sl, params)
    planar = is_planar(mech, [s for s, _ in steps])
    explain = Explainer(
        [s for s, _ in steps],
        [mech.joint(s).type for s, _ in steps],
        cols,
        Sl,
        params,
        point,
        planar,
        mechanism_size(mech),
    )
    notes = []
    scale: Any = 1
    if fixed and r < J.rows:
        # the span's own volume, not that of its projection on the rows kept
        scale = span_volume(J, Jr, Sl, twists=point is None)
        notes.append(
            f"the chain's {what} spans {r} of {J.rows} directions at every configuration (a "
            f"subgroup); the condition is written in {r} of its coordinates"
            + (", scaled to the span's own orthonormal coordinates" if scale != 1 else "")
        )
    cond = maximal_condition(Jr, r, Sl, params, f"output Jacobian ({what})", explain, scale)
    if not fixed:
        notes.append(
            f"the chain's {what}s span a space that turns with the configuration; the condition "
            "is the gcd of all maximal minors"
        )
    return [cond], notes
