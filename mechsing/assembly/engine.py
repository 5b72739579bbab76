"""The continuation engine: Bertini 2 (the ``modes`` extra) on a polynomial system, and
the sorting of its endpoints.

Bertini's records are turned off for the solve (``bertini.recording(False)``): nothing is
written in the user's directory and no path is replayed from an earlier run.  The seed is
fixed, so a run repeats: the same random gamma, start points and patches.

Owns :func:`track`, :func:`track_linear_product` (from a linear-product start system),
:func:`linear_product_paths`, :func:`real_endpoints`, :func:`genuine_endpoint` and
:func:`on_normalisations` (the general formulation's endpoints), :func:`system_text`
(the system in Bertini's input language, its variable groups first).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import sympy

from mechsing.assembly.settings import (
    MODE_EXTRANEOUS_RTOL,
    MODE_IMAGINARY_RTOL,
    MODE_ISOTROPIC_RTOL,
)
from mechsing.errors import UserError
from mechsing.timelimit import interruptible

__all__ = [
    "SEED",
    "genuine_endpoint",
    "linear_product_paths",
    "on_normalisations",
    "real_endpoints",
    "system_text",
    "track",
    "track_linear_product",
]

#: the seed of every homotopy (its random gamma, start points and patches): runs repeat
SEED = 34
#: a double-precision tracking of a count (``retry``) in which some paths failed (neither
#: converged nor went to infinity), at most this share of them, is run again in adaptive
#: precision: a failed path may hide a mode (the ladder's rung at ``tilted``: 11 to 15 of
#: its 120 paths failed in double precision, and with them one or both of its two real
#: solutions for some seeds, 2 or 0 of the ladder's 4 modes; adaptive precision failed
#: none, 18 s more); where more failed, the paths end on a set of closed configurations
#: that is not finite, which adaptive precision crawls along for minutes (Sarrus's: 104
#: to 108 of 120 failed; the axis formulation's eliminations of Sarrus's J1, 23 of 24,
#: for over ten minutes, where Bricard's 6R lost 1 of 24, then 24 of 24 and a proven count)
RETRY_FAILED = 0.25
#: Bertini's success codes of a path that did not fail: converged (``_SOLVED``, all that
#: a tight retry accepts), or left for infinity (names of ``bertini.SuccessCode``,
#: resolved there: a renamed one fails loudly)
_SOLVED = ("Success",)
_NOT_FAILED = (*_SOLVED, "SecurityMaxNormReached", "GoingToInfinity")


def system_text(eqs: Sequence[sympy.Expr], groups: Sequence[Sequence[sympy.Symbol]]) -> str:
    """The system in Bertini's input language (coefficients to 17 digits)."""
    lines = ["variable_group " + ",".join(str(v) for v in g) + ";" for g in groups]
    lines.append("function " + ",".join(f"f{i}" for i in range(len(eqs))) + ";")
    for i, e in enumerate(eqs):
        text = sympy.sstr(sympy.N(e, 17), full_prec=False).replace("**", "^")
        lines.append(f"f{i} = {text};")
    return "\n".join(lines) + "\n"


def _bertini() -> Any:
    """The Bertini 2 module (a UserError naming the extra without it)."""
    try:
        import bertini
    except ImportError:
        raise UserError(
            "this configuration needs homotopy continuation: install the extra with "
            "pip install 'mechsing[modes]' (Bertini 2, GPL-3.0-or-later)"
        ) from None
    return bertini


def track(
    eqs: Sequence[sympy.Expr],
    groups: Sequence[Sequence[sympy.Symbol]],
    mptype: str = "adaptive",
    retry: bool = True,
    tight: bool = False,
) -> tuple[list[np.ndarray], int]:
    """Every finite endpoint (complex, double precision, the groups' variables in order)
    of the system's homotopy, and the number of paths tracked.  Several variable groups
    make Bertini's start system multihomogeneous (one path per multihomogeneous Bezout
    root), one group a total-degree start.  ``mptype``: Bertini's precision model
    (``adaptive``, or ``double`` where the endpoints are refined afterwards anyway and
    adaptive precision would crawl along the many singular paths of an overconstrained
    loop's isotropic components); ``retry``: a double-precision run that failed a few
    paths is run again in adaptive precision (:data:`RETRY_FAILED`; not for a search of
    one real point, which tries other slices); ``tight``: every path is to end at a
    finite root (the Bezout number is the count), so one that goes to infinity is lost
    too."""
    bertini = _bertini()
    was = bertini.recording()
    bertini.recording(False)  # no records directory in the user's cwd, no replayed paths
    try:
        text = system_text(eqs, groups)

        def run(model: str) -> tuple[Any, Any]:
            while True:  # a signal stops the tracking; its handler raises once it returns
                with interruptible(bertini.request_stop) as stopped:
                    result = bertini.solve(bertini.parse.system(text), seed=SEED, mptype=model)
                if not stopped():  # (a handler that did not raise: the solve is run again)
                    return result, result.solver

        result, solver = _with_retry(run, mptype, retry, tight)
    finally:
        bertini.recording(was)
    tracked = int(solver.num_paths()) if callable(solver.num_paths) else int(solver.num_paths)
    return [np.asarray(s, dtype=complex) for s in result.solutions], tracked


def _with_retry(
    run: Callable[[str], tuple[Any, Any]], mptype: str, retry: bool, tight: bool = False
) -> tuple[Any, Any]:
    """``run(mptype)`` (the result and its solver), and again in adaptive precision where
    ``retry`` and double precision failed a few paths (:func:`_failed_a_few`); should
    Bertini refuse the adaptive run, the double run's endpoints."""
    first = run(mptype)
    if not (retry and mptype == "double" and _failed_a_few(first[1], tight)):
        return first
    try:
        return run("adaptive")
    except RuntimeError:  # Bertini refused it: what double precision found stands
        return first


def _failed_a_few(solver: Any, tight: bool = False) -> bool:
    """Whether some of the solver's paths failed (``tight``: or went to infinity), at most
    :data:`RETRY_FAILED` of them (a solver without the paths' metadata: no)."""
    meta = getattr(solver, "solution_metadata", None)
    if meta is None:
        return False
    codes = _bertini().SuccessCode
    fine = {getattr(codes, name) for name in (_SOLVED if tight else _NOT_FAILED)}
    paths = [m.endgame_success_code for m in (meta() if callable(meta) else meta)]
    failed = sum(1 for c in paths if c not in fine)
    return 0 < failed <= RETRY_FAILED * len(paths)


def _regular_choice(supports: Sequence[Sequence[int]], n: int) -> bool:
    """Do linear forms with these supports (each a set of variable indices), generic
    coefficients, make a regular n x n system?  So when each can take a variable of its
    own (a perfect matching of the forms to the variables)."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import maximum_bipartite_matching

    rows = [i for i, sup in enumerate(supports) for _ in sup]
    cols = [k for sup in supports for k in sup]
    graph = csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    return bool(np.all(maximum_bipartite_matching(graph, perm_type="column") >= 0))


def linear_product_paths(
    factors: Sequence[Sequence[Sequence[int]]], n: int
) -> list[tuple[int, ...]]:
    """The start points of a linear-product start system: each equation ``k`` a product of
    affine linear forms, its ``j``-th in the variables ``factors[k][j]`` (indices); one
    point per choice of a form in every equation whose generic linear system is regular.
    Their number is the system's linear-product Bezout number, a bound on the isolated
    solutions of every system whose equation ``k`` lies in the span of the products of
    such forms (each of its terms a product of one variable or 1 from each form)."""
    return [
        choice
        for choice in itertools.product(*(range(len(f)) for f in factors))
        if _regular_choice([factors[k][j] for k, j in enumerate(choice)], n)
    ]


def track_linear_product(
    eqs: Sequence[sympy.Expr],
    gens: Sequence[sympy.Symbol],
    factors: Sequence[Sequence[Sequence[int]]],
    choices: Sequence[tuple[int, ...]],
    mptype: str = "adaptive",
    retry: bool = True,
) -> tuple[list[np.ndarray], int]:
    """:func:`track` from a linear-product start system (``choices``, of
    :func:`linear_product_paths`):
    equation ``k`` replaced by a product of affine linear forms with random complex
    coefficients (seeded), its ``j``-th in the variables ``factors[k][j]``; one path per
    regular choice of a form in every equation, tracked by the straight-line homotopy
    with a random gamma (seeded).  Every finite endpoint and the number of paths;
    ``mptype`` and ``retry`` as for :func:`track`."""
    bertini = _bertini()
    from bertini import nag_algorithm

    n = len(gens)
    rng = np.random.default_rng(SEED)
    forms = [
        [
            (rng.normal(size=(len(sup), 2)) @ [1, 1j], complex(rng.normal(size=2) @ [1, 1j]))
            for sup in f
        ]
        for f in factors
    ]
    start = [
        sympy.Mul(
            *(
                sum(
                    sympy.Float(c.real, 17) * gens[i] + sympy.I * sympy.Float(c.imag, 17) * gens[i]
                    for c, i in zip(a, sup, strict=True)
                )
                + sympy.Float(b.real, 17)
                + sympy.I * sympy.Float(b.imag, 17)
                for (a, b), sup in zip(f, fac, strict=True)
            )
        )
        for f, fac in zip(forms, factors, strict=True)
    ]
    points = []
    for choice in choices:
        A = np.zeros((n, n), dtype=complex)
        rhs = np.zeros(n, dtype=complex)
        for k, j in enumerate(choice):
            a, b = forms[k][j]
            A[k, list(factors[k][j])] = a
            rhs[k] = -b
        points.append(np.linalg.solve(A, rhs))
    was = bertini.recording()
    bertini.recording(False)
    try:
        target = bertini.parse.system(system_text(eqs, [gens]))
        begin = bertini.parse.system(system_text(start, [gens]))

        def run(model: str) -> tuple[Any, Any]:
            while True:  # a signal stops the tracking; its handler raises once it returns
                bertini.random.set_random_seed(SEED)  # the gamma
                homotopy = nag_algorithm.straight_line_homotopy(target, begin)
                solver = nag_algorithm.HomotopySolver(homotopy, points, mptype=model)
                with interruptible(bertini.request_stop) as stopped:
                    result = solver.solve()
                if not stopped():
                    return result, solver

        result, _ = _with_retry(run, mptype, retry)
    finally:
        bertini.recording(was)
    return [np.asarray(s, dtype=complex) for s in result.solutions], len(points)


def real_endpoints(points: Sequence[np.ndarray]) -> list[np.ndarray]:
    """The endpoints whose imaginary parts are negligible (their real parts)."""
    out = []
    for z in points:
        scale = max(1.0, float(np.max(np.abs(z))))
        if float(np.max(np.abs(z.imag))) <= MODE_IMAGINARY_RTOL * scale:
            out.append(z.real)
    return out


def genuine_endpoint(groups: Sequence[Any], z: np.ndarray, product: Any) -> bool:
    """An endpoint ``z`` of the general formulation (its ``groups``' homogeneous
    coordinates in order) that is not extraneous: no isotropic pair or quaternion, no
    infinite slide, every closure's ``product`` the identity up to a non-zero scalar."""
    at = 0
    w = []
    for g in groups:
        v = z[at : at + len(g.gens)]
        at += len(g.gens)
        size = float(np.sum(np.abs(v) ** 2))
        if g.kind == "P":
            if abs(v[0]) ** 2 <= MODE_ISOTROPIC_RTOL * size:
                return False
            w += list(v / v[0])
        else:
            norm2 = complex(np.sum(v * v))
            if abs(norm2) <= MODE_ISOTROPIC_RTOL * size:
                return False
            w += list(v / np.sqrt(norm2))
    for P in product(*w):
        P = np.asarray(P, dtype=complex)
        if abs(P[0]) <= MODE_EXTRANEOUS_RTOL or np.max(np.abs(P[1:])) > MODE_EXTRANEOUS_RTOL * abs(
            P[0]
        ):
            return False
    return True


def on_normalisations(groups: Sequence[Any], z: Any) -> list[Any]:
    """A real endpoint scaled onto the normalisations (a slide pair's first coordinate 1,
    a half-angle pair or quaternion of norm 1)."""
    out: list[Any] = []
    at = 0
    for g in groups:
        v = [float(x) for x in z[at : at + len(g.gens)]]
        at += len(g.gens)
        n = v[0] if g.kind == "P" else float(np.sqrt(sum(x * x for x in v)))
        out += [x / n for x in v]
    return out
