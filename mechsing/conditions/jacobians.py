"""The columns of a chain and the conditions they give (shared by the derivations).

Owns the twists of a chain of joints written in the frame of one of its bodies
(:func:`chain_twists`), the choice of the rows of a fixed span's coordinates
(:func:`reduce_rows`) and the volume those coordinates leave out (:func:`span_volume`),
a condition as the determinant of a square Jacobian or the
gcd of its maximal minors (:func:`maximal_condition`), a factored
:class:`~mechsing.conditions.results.Condition` from one expression
(:func:`condition_from`), and the symbolic parameters of a mechanism
(:func:`parameter_symbols`)."""

from __future__ import annotations

import itertools
import random
from typing import Any

import numpy as np
import sympy

from mechsing.conditions.explain import numeric as _numeric
from mechsing.conditions.explain import random_point as _random_point
from mechsing.conditions.explain import rank as _rank
from mechsing.conditions.factoring import factor_condition
from mechsing.conditions.results import Condition, Factor
from mechsing.conditions.symbolic import (
    SE3,
    JointSymbols,
    motion,
    reference_twist,
    to_trig,
)
from mechsing.model import Mechanism
from mechsing.model.parameters import ParameterSymbol
from mechsing.numeric import CONDITION_GEOMETRY_RTOL
from mechsing.singularity.names import named

#: most maximal minors computed for a redundant or deficient chain
MAX_MINORS = 84

__all__ = [
    "MAX_MINORS",
    "all_joints",
    "chain_twists",
    "condition_from",
    "is_planar",
    "maximal_condition",
    "mechanism_size",
    "parameter_symbols",
    "reduce_rows",
    "span_volume",
]


def parameter_symbols(mech: Mechanism) -> list[Any]:
    found: set[Any] = set()
    for j in mech.joints:
        for v in j.params.values():
            for x in v if isinstance(v, tuple) else (v,):
                for y in x if isinstance(x, tuple) else (x,):
                    found |= sympy.sympify(y).atoms(ParameterSymbol)
    if mech.output is not None and mech.output.point is not None:
        for x in mech.output.point:
            found |= sympy.sympify(x).atoms(ParameterSymbol)
    return sorted(found, key=lambda s: s.name)


def all_joints(S: dict[str, JointSymbols]) -> list[JointSymbols]:
    return list(S.values())


def condition_from(
    name: str,
    form: str,
    expr: Any,
    S: list[JointSymbols],
    params: set[Any],
    note: str,
    meanings: Any = None,
) -> Condition:
    const, factors = factor_condition(expr, S, params)
    out = []
    for f, p in factors:
        trig = to_trig(f, S)
        # combining sums of angles can bring out a number (sqrt(3)*cos(B) - sin(B) is
        # 2*cos(B + pi/6)): it belongs to the constant, not the factor
        number, rest = trig.as_coeff_Mul()
        if number.is_number and number != 1 and rest.free_symbols:
            const, trig = const * number**p, rest
        meaning = meanings(f) if meanings is not None else None
        out.append(Factor(trig, p, meaning, name=named(meaning)))
    variables = sorted(
        {str(s) for f in out for s in f.expression.free_symbols} - {str(p) for p in params}
    )
    return Condition(name, form, tuple(variables), const, tuple(out), note)


def chain_twists(mech: Mechanism, S: dict[str, JointSymbols], steps: list[tuple[str, int]], k: int):
    """Twists of a chain of joints (name, sign) in the frame of body ``k`` (after
    ``k`` steps), and the displacement from that frame to the chain's end."""
    js = [mech.joint(n) for n, _ in steps]
    E = [motion(j, S[j.name], sg) for j, (_, sg) in zip(js, steps, strict=True)]
    cols = []
    for idx, j in enumerate(js):
        g = SE3.identity()
        if idx < k:
            for m in range(idx + 1, k):
                g = g * E[m]
            g = g.inverse()
        else:
            for m in range(k, idx):
                g = g * E[m]
        cols.append(steps[idx][1] * g.twist(reference_twist(j)))
    end = SE3.identity()
    for m in range(k, len(js)):
        end = end * E[m]
    start = SE3.identity()
    for m in range(k):
        start = start * E[m]
    return cols, end, start


def reduce_rows(J: Any, S: list[JointSymbols], params: list[Any]) -> tuple[Any, bool, int]:
    """Keep the rows of a fixed span's coordinates: (matrix, span fixed?, generic rank)."""
    rng = random.Random(12345)
    samples = [_numeric(J, _random_point(S, rng), params) for _ in range(3)]
    r = _rank(samples[0])
    stacked = np.hstack(samples)
    fixed = _rank(stacked) == r
    if not fixed:
        return J, False, r
    rows: list[int] = []
    for i in range(J.rows):
        if _rank(stacked[rows + [i], :]) > len(rows):
            rows.append(i)
        if len(rows) == r:
            break
    return J.extract(rows, list(range(J.cols))), True, r


def span_volume(J: Any, Jr: Any, S: list[JointSymbols], twists: bool) -> Any:
    """The factor from a determinant in the kept coordinates ``Jr`` of a fixed span (the
    rows :func:`reduce_rows` keeps of ``J``) to the determinant in the span's own
    orthonormal coordinates, which do not depend on the frame or on the rows kept.

    Every vector of the span is ``M`` times its kept coordinates, a constant matrix (found
    exactly at a random rational configuration: ``J = M Jr`` at every one), and the
    factor is the volume of ``M``'s columns.  Point velocities (``twists`` False) have the
    Euclidean volume ``sqrt(det(M^T M))``: 3/2 for the plane normal to (1, 2, 2), whose
    projection on x and y shrinks areas by 2/3.  Twists (``twists``: rows (omega, v)) have
    no common metric of rotations and translations, but a span of them has one volume all
    frames agree on, that of its pure translations T (omega = 0) times that of its
    rotations modulo T: a change of origin only adds translations to each twist, a shear
    of determinant 1.  A planar chain's twists about the plane normal to (1, 2, 2) then
    have l1 l2 sin in any plane, a spherical chain's the volume of its rotations."""
    if Jr.rows == J.rows:
        return sympy.Integer(1)
    rng = random.Random(54321)
    for _ in range(3):
        pt = _random_point(S, rng)
        Jx, Jrx = J.xreplace(pt), Jr.xreplace(pt)
        G = sympy.expand(Jrx * Jrx.T)
        if sympy.simplify(G.det()) == 0:
            continue
        M = (Jx * Jrx.T * G.inv()).applyfunc(sympy.simplify)
        r = M.cols
        Mw, Mv = (M[:3, :], M[3:, :]) if twists else (sympy.zeros(0, r), M)
        # kept coordinates of the pure translations, and their orthogonal complement
        K = _columns(Mw.nullspace(), r)
        L = _columns(K.T.nullspace(), r) if K.cols else sympy.eye(r)
        num = _gram(Mv * K) * _gram(Mw * L)
        den = _gram(K) * _gram(L)
        return sympy.sqrt(sympy.factor(sympy.simplify(num / den)))
    return sympy.Integer(1)


def _columns(vectors: list[Any], rows: int) -> Any:
    """The column vectors side by side (a rows x 0 matrix when there is none)."""
    return sympy.Matrix.hstack(*vectors) if vectors else sympy.zeros(rows, 0)


def _gram(A: Any) -> Any:
    """``det(A^T A)``, the squared volume of A's columns (1 with no column)."""
    return (A.T * A).det() if A.cols else sympy.Integer(1)


def symbolic_det(M: Any) -> Any:
    """The determinant of a square sympy matrix, computed fraction-free in a polynomial
    ring.  The numbers that are not rational (``sqrt(3)`` of a 60 degree twist,
    ``cos(pi/9)``) stand for symbols during the computation and are put back after: a
    determinant is a polynomial in the entries, so this is exact, and it keeps sympy out
    of its expression domain, whose every step simplifies (a 6R arm's Jacobian took
    minutes there, seconds here)."""
    from sympy.polys.matrices import DomainMatrix

    numbers: dict[Any, Any] = {}
    for e in M:
        for a in sympy.sympify(e).atoms(sympy.Pow, sympy.Function, sympy.NumberSymbol):
            if a.is_number and not a.is_Rational and a not in numbers:
                numbers[a] = sympy.Dummy(f"number{len(numbers)}")
    # the largest first: sqrt(2 + sqrt(3)) is one number, not a function of sqrt(3)
    order = sorted(numbers, key=sympy.count_ops, reverse=True)
    plain = M.applyfunc(
        lambda e: sympy.expand(sympy.sympify(e).xreplace({a: numbers[a] for a in order}))
    )
    dm = DomainMatrix.from_Matrix(plain)
    det = dm.domain.to_sympy(dm.det())
    return sympy.expand(det.xreplace({v: k for k, v in numbers.items()}))


def maximal_condition(
    J: Any,
    r: int,
    S: list[JointSymbols],
    params: list[Any],
    what: str,
    explain: Any,
    scale: Any = 1,
) -> Condition:
    """The determinant of a square ``J`` (times ``scale``: :func:`span_volume`), else the
    gcd of its maximal (r x r) minors."""
    pset = set(params)
    if J.rows == J.cols == r:
        det = sympy.expand(scale * symbolic_det(J))
        return condition_from(
            what,
            "determinant",
            det,
            S,
            pset,
            f"the determinant of the {r}x{r} output Jacobian",
            explain,
        )
    row_sets = list(itertools.combinations(range(J.rows), r))
    col_sets = list(itertools.combinations(range(J.cols), r))
    pairs = list(itertools.product(row_sets, col_sets))[:MAX_MINORS]
    common: dict[Any, int] | None = None
    for rows, cols in pairs:
        d = symbolic_det(J.extract(list(rows), list(cols)))
        if d == 0:
            continue
        _, fs = factor_condition(d, S, pset)
        here = dict(fs)
        common = (
            here if common is None else {f: min(p, here[f]) for f, p in common.items() if f in here}
        )
    factors = tuple(
        Factor(to_trig(f, S), p, explain(f) if explain else None) for f, p in (common or {}).items()
    )
    note = (
        f"the {len(pairs)} maximal ({r}x{r}) minors of the {J.rows}x{J.cols} output Jacobian "
        "vanish together at a singularity; their greatest common divisor is the "
        "codimension-1 part"
    )
    if not factors:
        note += (
            " and it is 1: the singularities of this redundant chain have codimension 2 or "
            "more (no single equation gives them)"
        )
    variables = sorted({str(s) for f in factors for s in f.expression.free_symbols})
    return Condition(
        what, "gcd of maximal minors", tuple(variables), sympy.Integer(1), factors, note
    )


def is_planar(mech: Mechanism, names: list[str]) -> bool:
    axes = []
    for n in names:
        j = mech.joint(n)
        if j.type in ("R", "H"):
            axes.append(np.array([float(sympy.N(x)) for x in j.params["axis"]]))
    if not axes:
        return False
    return all(np.linalg.norm(np.cross(axes[0], a)) < CONDITION_GEOMETRY_RTOL for a in axes)


def mechanism_size(mech: Mechanism) -> float:
    best = 1e-3  # m: the smallest size a mechanism is taken to have
    for j in mech.joints:
        if "point" in j.params:
            best = max(best, max(abs(float(sympy.N(x))) for x in j.params["point"]))
    return best
