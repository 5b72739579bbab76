"""The conditions of a single loop with one input.

The input (type I) condition is the determinant of the loop's twists without the
output joint (the output stands still whatever the input rate), the output (type
II) condition the determinant without the input joint (the passive joints move with
the input locked).  Then the passive joints are eliminated: with symbolic
parameters by :mod:`mechsing.conditions.linkage` (planar linkages), with numbers by
a lex Groebner basis of the closure equations within a time limit, giving the
conditions in the input alone with the input values where they vanish."""

from __future__ import annotations

import math
from typing import Any

import sympy

from mechsing.conditions.elimination import angles as _angles
from mechsing.conditions.elimination import distinct as _distinct
from mechsing.conditions.elimination import groebner
from mechsing.conditions.explain import Explainer
from mechsing.conditions.factoring import factor_condition
from mechsing.conditions.jacobians import (
    all_joints,
    chain_twists,
    condition_from,
    is_planar,
    mechanism_size,
    parameter_symbols,
    reduce_rows,
    span_volume,
)
from mechsing.conditions.linkage import linkage_conditions
from mechsing.conditions.results import Condition, Factor
from mechsing.conditions.symbolic import (
    SE3,
    JointSymbols,
    reduce_trig,
    tan_half,
    to_trig,
)
from mechsing.errors import TimeLimitExceeded, UserError
from mechsing.model import Mechanism
from mechsing.numeric import CONDITION_ROOT_RTOL
from mechsing.timelimit import TimeLimit

__all__ = ["single_loop"]


def single_loop(
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
    cols, end, start = chain_twists(mech, S, steps, k)
    params = parameter_symbols(mech)
    Sl = all_joints(S)
    K = sympy.Matrix.hstack(*cols)
    Kr, fixed, r = reduce_rows(K, Sl, params)
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
        is_planar(mech, names),
        mechanism_size(mech),
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
    # the span's own volume, not that of its projection on the rows kept (a loop drawn in
    # a plane other than xy has the conditions it has in the xy plane)
    scale = span_volume(K, Kr, Sl, twists=True)
    for name, drop, note in wanted:
        M = Kr.extract(list(range(r)), [i for i, n in enumerate(names) if n != drop])
        det = sympy.expand(scale * M.det(method="berkowitz"))
        conds.append(condition_from(name, "determinant", det, Sl, pset, note, explain))
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
            G = groebner(eqs, [*pvars, *ivars], "grevlex")
            if G.is_zero_dimensional:
                G = G.fglm("lex")
            else:
                G = groebner(eqs, [*pvars, *ivars], "lex")
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
    g = tan_half(polys[0], js, t)
    for p in polys[1:]:
        g = sympy.gcd(g, tan_half(p, js, t))
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
