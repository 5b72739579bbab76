"""Deriving singularity conditions as factored formulas (``mechsing condition``).

Owns the three derivations the command offers, on mechanisms of R, P and H
joints (:mod:`mechsing.conditions.symbolic`):

* an open chain: the determinant of its output Jacobian, the columns being
  the joint twists (or, with ``output.point``, the velocities of that point)
  written in the frame of the chain's middle body (determinants do not
  depend on the frame, and the middle frame keeps the expressions short).
  When the twists span a subgroup smaller than SE(3) (a planar chain spans
  3 directions, a point in a plane 2), only the rows of that subgroup's
  coordinates are kept (chosen at random joint values: a fixed span in every
  configuration).  A redundant chain gives its maximal minors, which vanish
  together: their greatest common divisor is the codimension-1 part.
* a single loop with one input: the input (type I) condition is the
  determinant of the loop's twists without the output joint (the output
  stands still whatever the input rate) and the output (type II) condition
  the determinant without the input joint (the passive joints move with the
  input locked); then the passive joints are eliminated (a lex Groebner basis
  with the closure equations, within a time limit) to give the conditions in
  the input alone, with the input values where they vanish.
* a planar parallel robot of R-P-R legs with the P joints actuated, in the
  pose variables ``x``, ``y`` (the output's reference point, m) and ``phi``
  (its rotation about the plane's normal from the file's pose, rad): type II
  is the determinant of the legs' actuation wrenches (the lines through each
  leg's two pivots: zero when they are concurrent or parallel), type I the
  vanishing of a leg's length.

Joint values are measured from the pose drawn in the file (all zero there);
angles in radians, lengths in metres.  Parameters named in ``symbolic`` stay
symbols, the others take their exact values.
"""

from __future__ import annotations

import itertools
import math
import random
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import sympy

from mechsing.conditions.elimination import angles as _angles
from mechsing.conditions.elimination import distinct as _distinct
from mechsing.conditions.elimination import half_angle
from mechsing.conditions.explain import Explainer
from mechsing.conditions.explain import numeric as _numeric
from mechsing.conditions.explain import random_point as _random_point
from mechsing.conditions.explain import rank as _rank
from mechsing.conditions.factoring import factor_condition
from mechsing.conditions.linkage import linkage_conditions
from mechsing.conditions.results import Condition, ConditionResult, Factor
from mechsing.conditions.spatial import gough_stewart
from mechsing.conditions.symbolic import (
    SE3,
    JointSymbols,
    joint_symbols,
    motion,
    reduce_trig,
    reference_twist,
    to_trig,
)
from mechsing.conditions.translational import translational_3upu
from mechsing.errors import ConfigurationError, TimeLimitExceeded, UserError
from mechsing.model import Mechanism
from mechsing.model.couplings import refuse_couplings
from mechsing.model.parameters import ParameterSymbol
from mechsing.numeric import (
    CONDITION_GEOMETRY_RTOL,
    CONDITION_ROOT_RTOL,
    CONDITION_VANISH_RTOL,
)
from mechsing.reader import read_mechanism
from mechsing.singularity.names import named
from mechsing.timelimit import SHORTEST_TIME_LIMIT, TimeLimit

__all__ = ["ELIMINATION_SECONDS", "MAX_MINORS", "condition"]

#: time allowed to eliminate the passive joints of a loop (s)
ELIMINATION_SECONDS = 60.0
#: most maximal minors computed for a redundant or deficient chain
MAX_MINORS = 84


def condition(
    source: str | Path | Mechanism,
    config: str | None = None,
    symbolic: str | list[str] | tuple[str, ...] = (),
    scene: Callable[[Mechanism], Mechanism] | None = None,
    time_limit: float | None = None,
) -> ConditionResult:
    """The singularity conditions of a mechanism file as factored formulas.

    Parameters
    ----------
    source : str, Path or Mechanism
        The mechanism file (any format :func:`mechsing.load` reads), or a mechanism read
        with ``symbolic`` kept as symbols.
    config : str, optional
        A configuration of the file: each factor is evaluated there.
    symbolic : str or sequence of str
        Parameters of the file to keep as symbols (a list, or ``"a2,a3"``).
    scene : callable, optional
        Applied to the mechanism as read from a file (e.g. the command line's output and
        inputs, :func:`mechsing.model.scene.choose_scene`), before anything is derived
        (a mechanism given as ``source`` is taken as it is).
    time_limit : float or None
        The most seconds the derivation may take (None: no limit); stopped there, a
        ConfigurationError (exit status 3) that says so.  The elimination of a linkage's
        passive joints gets half of it for each condition (without a limit,
        :data:`ELIMINATION_SECONDS`): past that the condition is given in the joint
        variables, with a note.

    Returns
    -------
    ConditionResult
        The conditions, each a product of factors with their meaning.

    Raises
    ------
    UserError
        For a file that cannot be read, a parameter or configuration that does
        not exist, joints other than R, P and H, or a mechanism none of the
        three derivations applies to (the message says which exist).
    """
    names = [s.strip() for s in symbolic.split(",")] if isinstance(symbolic, str) else symbolic
    names = [s for s in names if s]
    mech = _symbolic_mechanism(source, names)
    if scene is not None and not isinstance(source, Mechanism):
        mech = scene(mech)
    refuse_couplings(mech, "symbolic conditions (mechsing condition)")
    try:
        with TimeLimit(time_limit):
            # the elimination gets half the limit: past it, the joint-variable form within it
            elim = (
                ELIMINATION_SECONDS
                if time_limit is None
                else max(time_limit / 2, SHORTEST_TIME_LIMIT)
            )
            return _condition(mech, config, names, scene, elim)
    except TimeLimitExceeded:
        raise ConfigurationError(
            f"{mech.path or mech.name}: the conditions were stopped by the time limit after "
            f"{time_limit:g} s; allow more time with --time-limit S",
            config or "reference",
        ) from None


def _condition(
    mech: Mechanism,
    config: str | None,
    names: list[str],
    scene: Callable[[Mechanism], Mechanism] | None,
    time_limit: float | None,
) -> ConditionResult:
    """The conditions of ``mech``; ``time_limit``: the seconds the elimination of a
    linkage's passive joints may take for each condition."""
    source = mech.path or mech.name
    if config is not None and config not in mech.configurations:
        raise UserError(
            f"{source}: no configuration named {config!r}; the file has: "
            f"{', '.join(mech.configurations)}"
        )
    if mech.output is None:
        raise UserError(
            f"{source}: the file has no output; a condition is about the output's motion: "
            "name one with --output-body BODY (in a mechsing file, add output: {body: NAME})"
        )
    platform = gough_stewart(mech) or translational_3upu(mech)
    if platform is not None:
        if config is not None:
            raise UserError(
                f"{source}: --config: the conditions of this platform are written in the "
                "position x, y, z of its reference point at the drawn orientation; evaluate "
                "them at a pose by putting x, y, z into them, or use 'mechsing analyze --config'"
            )
        return ConditionResult(
            mechanism=mech.name,
            method="parallel robot, pose variables",
            symbolic=tuple(names),
            parameters={k: v for k, v in mech.parameters.items() if k not in names},
            conditions=tuple(platform[0]),
            notes=tuple(platform[1]),
            file_angle_unit=mech.units.angle,
        )
    S = joint_symbols(mech)
    params = _parameters(mech)
    if mech.graph.num_loops == 0:
        method, conds, notes = "open chain", *_open_chain(mech, S)
    elif mech.graph.num_loops == 1 and len(mech.input_coordinates()) == 1:
        method, conds, notes = "single loop, one input", *_single_loop(mech, S, time_limit)
    elif len(mech.input_coordinates()) == 1:
        ((in_joint, _),) = mech.input_coordinates()
        found = linkage_conditions(mech, S[in_joint], set(_parameters(mech)), time_limit, True)
        if isinstance(found, str):
            raise UserError(
                f"{source}: a linkage of {mech.graph.num_loops} loops with one input: symbolic "
                "conditions of multi-loop linkages cover planar linkages of R and P joints "
                "with the input on the ground (Watt and Stephenson six-bars ...); this one is "
                f"not: {found}; use 'mechsing analyze' for its singularities"
            )
        method, conds, notes = "linkage, one input", *found
    else:
        method, conds, notes = "parallel robot, pose variables", *_parallel(mech, S, str(source))
    printable = {p: sympy.Symbol(p.name, real=True) for p in params}
    conds = [_printable(c, printable) for c in conds]
    values: dict[str, float] = {}
    if config is not None:
        numeric = mech
        if names and mech.path:  # the same file with its parameters' values
            numeric = read_mechanism(mech.path)
            if scene is not None:
                numeric = scene(numeric)
            # a configuration added to the mechanism read (mechsing condition --set)
            added = {
                k: v for k, v in mech.configurations.items() if k not in numeric.configurations
            }
            if added:
                numeric = replace(numeric, configurations={**numeric.configurations, **added})
        values = _configuration_values(numeric, config, method)
        conds = [_evaluate(c, values, params) for c in conds]
    fixed = {k: v for k, v in mech.parameters.items() if k not in names}
    return ConditionResult(
        mechanism=mech.name,
        method=method,
        symbolic=tuple(names),
        parameters=fixed,
        conditions=tuple(conds),
        notes=(*(mech.scene.notes if mech.scene else ()), *notes),
        configuration=config,
        values=values,
        file_angle_unit=mech.units.angle,
    )


# ---------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------


def _parameters(mech: Mechanism) -> list[Any]:
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


def _symbolic_mechanism(source: str | Path | Mechanism, names: list[str]) -> Mechanism:
    """The mechanism with the parameters ``names`` kept as symbols: read from the file,
    or ``source`` itself when it was read so."""
    if not isinstance(source, Mechanism):
        return read_mechanism(source, symbolic=names)
    kept = {k for k, v in source.parameters.items() if isinstance(v, ParameterSymbol)}
    if kept == set(names):
        return source
    if source.path is None or not Path(source.path).is_file():
        raise UserError(
            f"{source.name}: the mechanism keeps {', '.join(sorted(kept)) or 'no parameter'} "
            f"as symbols, not {', '.join(names) or 'none'}; read it with "
            "mechsing.load(path, symbolic=...) or pass its path"
        )
    return read_mechanism(source.path, symbolic=names)


def _printable(c: Condition, printable: dict[Any, Any]) -> Condition:
    factors = tuple(
        Factor(f.expression.xreplace(printable), f.power, f.meaning, name=f.name) for f in c.factors
    )
    return Condition(
        c.name,
        c.form,
        c.variables,
        sympy.sympify(c.constant).xreplace(printable),
        factors,
        c.note,
        c.roots,
        c.units,
    )


def _all_joints(S: dict[str, JointSymbols]) -> list[JointSymbols]:
    return list(S.values())


def _conditions_from(
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


# ---------------------------------------------------------------------------
# columns of a chain in the frame of one of its bodies
# ---------------------------------------------------------------------------


def _chain(mech: Mechanism, S: dict[str, JointSymbols], steps: list[tuple[str, int]], k: int):
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


def _reduce_rows(J: Any, S: list[JointSymbols], params: list[Any]) -> tuple[Any, bool, int]:
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


def _maximal(
    J: Any, r: int, S: list[JointSymbols], params: list[Any], what: str, explain: Any
) -> Condition:
    """The determinant of a square ``J``, else the gcd of its maximal (r x r) minors."""
    from sympy.polys.matrices import DomainMatrix

    pset = set(params)
    if J.rows == J.cols == r:
        det = DomainMatrix.from_Matrix(J).det()
        det = DomainMatrix.from_Matrix(J).domain.to_sympy(det)
        return _conditions_from(
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
        M = J.extract(list(rows), list(cols))
        dm = DomainMatrix.from_Matrix(M)
        d = dm.domain.to_sympy(dm.det())
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


# ---------------------------------------------------------------------------
# open chains
# ---------------------------------------------------------------------------


def _open_chain(mech: Mechanism, S: dict[str, JointSymbols]) -> tuple[list[Condition], list[str]]:
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
    cols, end, _ = _chain(mech, S, steps, k)
    params = _parameters(mech)
    Sl = _all_joints(S)
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
    Jr, fixed, r = _reduce_rows(J, Sl, params)
    planar = _is_planar(mech, [s for s, _ in steps])
    explain = Explainer(
        [s for s, _ in steps],
        [mech.joint(s).type for s, _ in steps],
        cols,
        Sl,
        params,
        point,
        planar,
        _size(mech),
    )
    notes = []
    if fixed and r < J.rows:
        notes.append(
            f"the chain's {what} spans {r} of {J.rows} directions at every configuration (a "
            f"subgroup); the condition is written in {r} of its coordinates"
        )
    cond = _maximal(Jr, r, Sl, params, f"output Jacobian ({what})", explain)
    if not fixed:
        notes.append(
            f"the chain's {what}s span a space that turns with the configuration; the condition "
            "is the gcd of all maximal minors"
        )
    return [cond], notes


def _is_planar(mech: Mechanism, names: list[str]) -> bool:
    axes = []
    for n in names:
        j = mech.joint(n)
        if j.type in ("R", "H"):
            axes.append(np.array([float(sympy.N(x)) for x in j.params["axis"]]))
    if not axes:
        return False
    return all(np.linalg.norm(np.cross(axes[0], a)) < CONDITION_GEOMETRY_RTOL for a in axes)


def _size(mech: Mechanism) -> float:
    best = 1e-3  # m: the smallest size a mechanism is taken to have
    for j in mech.joints:
        if "point" in j.params:
            best = max(best, max(abs(float(sympy.N(x))) for x in j.params["point"]))
    return best


# ---------------------------------------------------------------------------
# single loops
# ---------------------------------------------------------------------------


def _single_loop(
    mech: Mechanism, S: dict[str, JointSymbols], time_limit: float | None
) -> tuple[list[Condition], list[str]]:
    loop = mech.graph.loops[0]
    ground = mech.ground
    if ground not in loop.bodies:
        raise UserError(
            f"{mech.path}: the loop does not contain the ground; symbolic conditions need it"
        )
    i0 = loop.bodies.index(ground)
    steps = [
        (loop.joints[(i0 + i) % len(loop)], loop.signs[(i0 + i) % len(loop)])
        for i in range(len(loop))
    ]
    names = [n for n, _ in steps]
    ((in_joint, _),) = mech.input_coordinates()
    out = mech.output
    assert out is not None
    out_joint = None
    if out.relative_to == ground:
        for j in mech.joints:
            if set(j.between) == {ground, out.body} and j.name in names:
                out_joint = j.name
    m = len(steps)
    k = m // 2
    cols, end, start = _chain(mech, S, steps, k)
    params = _parameters(mech)
    Sl = _all_joints(S)
    K = sympy.Matrix.hstack(*cols)
    Kr, fixed, r = _reduce_rows(K, Sl, params)
    notes: list[str] = []
    if not fixed or r != m - 1:
        raise UserError(
            f"{mech.path}: the loop's twists span {r} directions with {m} joints; symbolic "
            "loop conditions need a loop of mobility 1 in a fixed subgroup (e.g. a planar "
            "four-bar or slider-crank); use 'mechsing analyze'"
        )
    if r < 6:
        notes.append(
            f"the loop's twists span {r} directions at every configuration (a subgroup); the "
            f"conditions are written in {r} of its coordinates"
        )
    explain = Explainer(
        names,
        [mech.joint(n).type for n in names],
        cols,
        Sl,
        params,
        None,
        _is_planar(mech, names),
        _size(mech),
        arm=False,
    )
    pset = set(params)
    conds: list[Condition] = []
    wanted: list[tuple[str, str, str]] = []
    if out_joint is not None and out_joint != in_joint:
        wanted.append(
            (
                "input (type I)",
                out_joint,
                f"the determinant of the loop's twists without the output joint {out_joint}: "
                "the output stands still whatever the input rate (dead centre, limit of the "
                "output)",
            )
        )
    else:
        notes.append(
            "the output body is not joined to the ground by a joint of the loop, so only the "
            "output (type II) condition is given"
        )
    wanted.append(
        (
            "output (type II)",
            in_joint,
            f"the determinant of the loop's twists without the input joint {in_joint}: the "
            "passive joints move with the input locked",
        )
    )
    closure = _closure_equations(start, end)
    for name, drop, note in wanted:
        M = Kr.extract(list(range(r)), [i for i, n in enumerate(names) if n != drop])
        det = sympy.expand(M.det(method="berkowitz"))
        conds.append(_conditions_from(name, "determinant", det, Sl, pset, note, explain))
    if pset:
        found = linkage_conditions(mech, S[in_joint], pset, time_limit, False)
        if isinstance(found, str):
            notes.append(
                "the passive joints are eliminated with symbolic parameters for planar "
                f"linkages of R and P joints with the input on the ground; not here ({found}): "
                "the conditions above are in all joint variables"
            )
            return conds, notes
        return conds + found[0], notes + found[1]
    for name, drop, _ in wanted:
        M = Kr.extract(list(range(r)), [i for i, n in enumerate(names) if n != drop])
        det = sympy.expand(M.det(method="berkowitz"))
        elim = _eliminate(det, closure, S, in_joint, pset, time_limit)
        if isinstance(elim, str):
            notes.append(f"{name}: {elim}")
        else:
            conds.append(
                Condition(
                    f"{name} in the input {in_joint}",
                    elim.form,
                    elim.variables,
                    elim.constant,
                    elim.factors,
                    elim.note,
                    elim.roots,
                    elim.units,
                )
            )
    return conds, notes


def _closure_equations(start: SE3, end: SE3) -> list[Any]:
    """The loop closes when the chain's first half equals the inverse of its second."""
    inv = end.inverse()
    eqs = []
    for a, b in zip(list(start.R) + list(start.p), list(inv.R) + list(inv.p), strict=True):
        d = sympy.expand(a - b)
        if d != 0:
            eqs.append(d)
    return eqs


def _eliminate(
    det: Any,
    closure: list[Any],
    S: dict[str, JointSymbols],
    in_joint: str,
    params: set[Any],
    time_limit: float | None,
) -> Condition | str:
    """``det`` with the passive joints eliminated by a lex Groebner basis, or why not
    (numeric parameters)."""
    inp = S[in_joint]
    passive = [js for n, js in S.items() if n != in_joint]
    pvars: list[Any] = []
    for js in passive:
        pvars += [js.s, js.c] if js.c is not None else [js.q]
    ivars = [inp.s, inp.c] if inp.c is not None else [inp.q]
    circle = [js.s**2 + js.c**2 - 1 for js in S.values() if js.c is not None]
    Sl = list(S.values())
    eqs = [reduce_trig(det, Sl), *[reduce_trig(e, Sl) for e in closure], *circle]
    try:
        with TimeLimit(time_limit):
            G = sympy.groebner(eqs, *pvars, *ivars, order="grevlex")
            if G.is_zero_dimensional:
                G = G.fglm("lex")
            else:
                G = sympy.groebner(eqs, *pvars, *ivars, order="lex")
    except TimeLimitExceeded:
        return (
            f"sympy could not eliminate the passive joints within {time_limit:g} s; "
            "the condition above is in all joint variables"
        )
    if G.exprs == [1]:
        return (
            "no configuration of the loop makes it vanish: this singularity is never reached; "
            "no condition on the input"
        )
    own = sympy.expand(inp.s**2 + inp.c**2 - 1) if inp.c is not None else None
    polys = [
        g
        for g in G.exprs
        if g.free_symbols
        and not (g.free_symbols & set(pvars))
        and (own is None or sympy.expand(g - own) != 0)
    ]
    if not polys:
        return "the closure equations leave the input free there: no condition on the input alone"
    g, exact = _eliminant(polys, inp)
    const, factors = factor_condition(g, [inp], set())
    fs = tuple(Factor(to_trig(f, [inp]), p, None) for f, p in factors)
    roots = _common_roots(polys, inp)
    note = (
        f"after eliminating the passive joints (exact, lex Groebner basis): the values of "
        f"{in_joint} where this singularity occurs (on one assembly branch or another)"
    )
    if not exact:
        shown = ", ".join(f"{r:.6g}" for r in roots) or "none"
        note += (
            f"; this one equation also has other zeros: the singularity occurs only at "
            f"{in_joint} = {shown}"
        )
    if not roots:
        note += "; no real value: this singularity is never reached"
    unit = "rad" if inp.c is not None else "m"
    return Condition(
        "eliminated", "eliminated", (in_joint,), const, fs, note, tuple(roots), (unit,)
    )


def _eliminant(polys: list[Any], js: JointSymbols) -> tuple[Any, bool]:
    """One polynomial in the input whose zeros are those common to ``polys`` (a lex
    basis may give two: ``s - p(c)`` and ``q(c)``, whose common zeros are fewer than
    ``q``'s), and whether its zeros are exactly those."""
    if js.c is None:
        g = polys[0]
        for p in polys[1:]:
            g = sympy.gcd(g, p)
        return g, True
    if len(polys) == 1:
        return polys[0], True
    t = sympy.Dummy("t")
    g = half_angle(polys[0], js, t)
    for p in polys[1:]:
        g = sympy.gcd(g, half_angle(p, js, t))
    at_pi = all(p.xreplace({js.c: -1, js.s: 0}) == 0 for p in polys)
    deg = int(sympy.degree(g, t))
    k = (deg + 1) // 2 + (1 if at_pi and deg % 2 == 0 else 0)
    if (2 * k > deg) != at_pi or k == 0:
        return polys[-1], False
    from mechsing.conditions.factoring import to_circle

    return to_circle(g, t, k, js), True


def _common_roots(polys: list[Any], js: JointSymbols) -> list[float]:
    """Real values of the input where every polynomial of ``polys`` vanishes."""
    candidates = _distinct(_angles(sympy.sqf_part(polys[-1]), js))
    out = []
    for a in candidates:
        sub = {js.q: a} if js.c is None else {js.c: math.cos(a), js.s: math.sin(a)}
        ok = True
        for p in polys:
            terms = sympy.Add.make_args(sympy.expand(p))
            scale = (
                sum(
                    abs(
                        float(
                            sympy.N(x.xreplace({js.c: 1, js.s: 1} if js.c else {js.q: abs(a)}), 30)
                        )
                    )
                    for x in terms
                )
                or 1.0
            )
            if abs(float(sympy.N(p.xreplace(sub), 30))) > CONDITION_ROOT_RTOL * scale:
                ok = False
        if ok:
            out.append(a)
    return out


# ---------------------------------------------------------------------------
# planar parallel robots in pose variables
# ---------------------------------------------------------------------------


def _parallel(
    mech: Mechanism, S: dict[str, JointSymbols], source: str
) -> tuple[list[Condition], list[str]]:
    out = mech.output
    assert out is not None
    inputs = {n for n, _ in mech.input_coordinates()}
    legs = mech.legs
    refuse = UserError(
        f"{source}: a mechanism of {mech.graph.num_loops} loops with {len(inputs)} inputs: "
        "symbolic conditions of mechanisms with several inputs cover planar parallel robots "
        "whose legs are R-P-R (revolute pivots with parallel axes, the P joint actuated: a "
        "3-RPR); this one is not; use 'mechsing analyze' or 'mechsing sweep' with pose "
        "configurations"
    )
    if not _is_planar(mech, list(mech.joint_names)):
        raise refuse
    normal = sympy.Matrix(mech.joints[0].params["axis"]) if mech.joints[0].type == "R" else None
    if normal is None or list(normal) != [0, 0, 1]:
        raise refuse
    clash = [p.name for p in _parameters(mech) if p.name in ("x", "y", "phi")]
    if clash:
        raise UserError(
            f"{source}: parameter {clash[0]!r} has the name of a pose variable (x, y, phi); "
            "rename it to keep it symbolic"
        )
    x, y, phi = (sympy.Symbol(n, real=True) for n in ("x", "y", "phi"))
    cphi, sphi = sympy.Symbol("c_phi", real=True), sympy.Symbol("s_phi", real=True)
    pose = JointSymbols(phi, cphi, sphi)
    c0 = sympy.Matrix(mech.output_reference_point())
    Rz = sympy.Matrix([[cphi, -sphi, 0], [sphi, cphi, 0], [0, 0, 1]])
    rows = []
    lengths = []
    leg_names = []
    for leg in legs:
        types = [mech.joint(n).type for n in leg.joints]
        acts = [n for n in leg.joints if n in inputs]
        if sorted(types) != ["P", "R", "R"] or len(acts) != 1 or mech.joint(acts[0]).type != "P":
            raise refuse
        rs = [mech.joint(n) for n in leg.joints if mech.joint(n).type == "R"]
        base = [j for j in rs if mech.ground in j.between]
        top = [j for j in rs if out.body in j.between]
        if len(base) != 1 or len(top) != 1:
            raise refuse
        A = sympy.Matrix(base[0].params["point"])
        B0 = sympy.Matrix(top[0].params["point"])
        B = sympy.Matrix([x, y, c0[2]]) + Rz * (B0 - c0)
        f = B - A
        rows.append([f[0], f[1], A[0] * f[1] - A[1] * f[0]])
        lengths.append(sympy.expand(f[0] ** 2 + f[1] ** 2))
        leg_names.append(acts[0])
    params = set(_parameters(mech))
    W = sympy.Matrix(rows)
    det = sympy.expand(W.det(method="berkowitz"))
    conds = [
        _conditions_from(
            "output (type II)",
            "determinant",
            det,
            [pose],
            params,
            "the determinant of the legs' actuation wrenches (rows: force along each leg line "
            "and its moment about the origin); it vanishes when the leg lines are concurrent or "
            "all parallel",
            lambda f: "the leg lines are concurrent or all parallel",
        )
    ]
    for name, L in zip(leg_names, lengths, strict=True):
        c = _conditions_from(
            f"input (type I), leg {name}",
            "determinant",
            L,
            [pose],
            params,
            f"the squared length of leg {name} (pivot to pivot); it vanishes only when the two "
            "pivots meet",
            lambda f, n=name: f"leg {n} has zero length",
        )
        conds.append(c)
    notes = [
        "pose variables: x, y = the position of the output's reference point (m), phi = its "
        "rotation about z from the file's pose (rad)"
    ]
    return conds, notes


# ---------------------------------------------------------------------------
# evaluation at a configuration
# ---------------------------------------------------------------------------


def _configuration_values(numeric: Mechanism, config: str, method: str) -> dict[str, float]:
    """The joint (or pose) variables of a configuration of ``numeric`` (no symbols)."""
    from mechsing.kinematics import solve_configuration

    model, closed = solve_configuration(numeric, config, "float")
    vals = {k: float(v[0]) for k, v in model.values(closed.q).items() if k in numeric.joint_names}
    if method.startswith("parallel"):
        assert numeric.output is not None
        g = np.array(model.poses(closed.q)[numeric.output.body], dtype=float)
        c0 = np.array([float(sympy.N(v)) for v in numeric.output_reference_point()])
        pos = g[:3, :3] @ c0 + g[:3, 3]
        return {"x": float(pos[0]), "y": float(pos[1]), "phi": math.atan2(g[1, 0], g[0, 0])}
    return vals


def _evaluate(c: Condition, values: dict[str, float], params: list[Any]) -> Condition:
    sub: dict[Any, Any] = {}
    for f in c.factors:
        for s in f.expression.free_symbols:
            if s.name in values:
                sub[s] = sympy.Float(values[s.name], 30)
    for p in params:
        sub[sympy.Symbol(p.name, real=True)] = p.parameter_value
    out = []
    for f in c.factors:
        e = f.expression.xreplace(sub)
        val = complex(sympy.N(e, 30))
        # the scale of the factor: its terms with every sine and cosine at its largest, 1
        terms = sympy.Add.make_args(sympy.expand(f.expression))
        bound = [
            t.replace(sympy.sin, lambda *_: sympy.Integer(1)).replace(
                sympy.cos, lambda *_: sympy.Integer(1)
            )
            for t in terms
        ]
        scale = sum(abs(complex(sympy.N(t.xreplace(sub), 30))) for t in bound) or 1.0
        vanishes = abs(val) <= CONDITION_VANISH_RTOL * scale if not e.free_symbols else None
        out.append(Factor(f.expression, f.power, f.meaning, float(val.real), vanishes, f.name))
    return Condition(c.name, c.form, c.variables, c.constant, tuple(out), c.note, c.roots, c.units)
