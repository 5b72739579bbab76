"""Input and output conditions of a planar one-input linkage, in the input alone.

For a four-bar, a slider-crank, a quick return, a Watt or a Stephenson
six-bar (any planar linkage of R and P joints with one input on the ground):
the determinants of :mod:`mechsing.conditions.planar` (in the angles
``phi_X`` of the bodies and the slides), each factor with its meaning, and
each factor with the passive joints eliminated
(:mod:`mechsing.conditions.elimination`): a polynomial in the cosine and sine
of the input angle (or in the input slide), the named parameters kept as
symbols.  The eliminated factors are checked against an exact Groebner basis
at the file's parameter values, which drops the extra factors resultants can
bring.  Everything runs within a time limit; past it, the output says so and
keeps the determinants.
"""

from __future__ import annotations

from typing import Any

import sympy

from mechsing.conditions.elimination import angles, distinct, eliminate, genuine
from mechsing.conditions.factoring import factor_condition, to_circle
from mechsing.conditions.planar import PlanarLinkage, planar_linkage, slide_axis
from mechsing.conditions.results import Condition, Factor
from mechsing.conditions.symbolic import JointSymbols, reduce_trig, tan_half, to_trig
from mechsing.errors import EliminationTooLarge
from mechsing.model import Mechanism
from mechsing.timelimit import TimeLimit, TimeLimitExceeded

__all__ = ["linkage_conditions"]


def _input(mech: Mechanism, L: PlanarLinkage, name: str) -> tuple[tuple[str, str], int] | str:
    """The input's variable (("angle", class) or ("slide", joint)) and the sign that
    turns the class angle into the joint's value."""
    j = mech.joint(name)
    if j.type == "P":
        return ("slide", name), 1
    a, b = j.between
    ground = L.classes[mech.ground]
    if L.classes[a] == ground and L.classes[b] != ground:
        sign = 1
        moving = b
    elif L.classes[b] == ground and L.classes[a] != ground:
        sign = -1
        moving = a
    else:
        return (
            f"the input {name} joins two moving bodies; the elimination covers an input "
            "joint on the ground"
        )
    axis_z = sympy.sympify(j.params["axis"][2])
    return ("angle", L.classes[moving]), int(sign * axis_z)


def _output(mech: Mechanism, L: PlanarLinkage) -> tuple[str, str] | None:
    assert mech.output is not None
    body = mech.output.body
    ground = L.classes[mech.ground]
    if mech.output.relative_to != mech.ground:
        return None
    if L.classes[body] != ground:
        return ("angle", L.classes[body])
    for j in mech.joints:
        if j.type == "P" and body in j.between:
            other = j.between[0] if j.between[1] == body else j.between[1]
            if L.classes[other] == ground:
                return ("slide", j.name)
    return None


def linkage_conditions(
    mech: Mechanism,
    in_joint: JointSymbols,
    params: set[Any],
    time_limit: float | None,
    determinants: bool,
) -> tuple[list[Condition], list[str]] | str:
    """The conditions (and notes) of a planar one-input linkage, or why it is not one.

    ``in_joint`` are the symbols of the input joint (the eliminated conditions are
    written in them); ``determinants`` adds the conditions in the bodies' angles."""
    L = planar_linkage(mech)
    if isinstance(L, str):
        return L
    name = str(in_joint.q)
    scaled: list[str] = []
    irrational = _irrational_parameters(L)
    if irrational is not None and mech.joint(name).type != "P":
        # a P joint's axis written with symbols is normalised by its length, a radical of
        # the parameters: measure its slide in units of that length (the slide is a passive
        # variable, eliminated; the conditions in the input do not change)
        written = planar_linkage(mech, written_axes=True)
        assert not isinstance(written, str)  # the same joints as L
        if _irrational_parameters(written) is None:
            scaled = [
                f"{j.name} (axis {list(_printed(slide_axis(j, True)))})"
                for j in mech.joints
                if j.type == "P" and list(slide_axis(j, True)) != list(slide_axis(j, False))
            ]
            L, irrational = written, None
    if irrational is not None:
        return (
            f"its closure holds {_printed(irrational)}, an irrational function of the "
            "parameters (a radical in a joint's point or axis, or a P joint's axis written "
            "with symbols, which is normalised by its length), and elimination works on "
            "polynomials"
            + (
                "; with the input a P joint, its slide cannot be measured in other units"
                if mech.joint(name).type == "P"
                else ""
            )
        )
    found = _input(mech, L, name)
    if isinstance(found, str):
        return found
    in_var, sign = found
    variables = [("angle", n) for n in L.angles] + [("slide", n) for n in L.slides]
    if len(L.equations) != len(variables) - 1:
        return (
            f"its closure has {len(L.equations)} equations in {len(variables)} variables "
            "(one degree of freedom needs one equation fewer than variables)"
        )
    out_var = _output(mech, L)
    keep = L.angles[in_var[1]] if in_var[0] == "angle" else JointSymbols(L.slides[name], None, None)
    unknowns = [js for js in L.symbols if js.q != keep.q]
    to_input = {keep.c: in_joint.c, keep.s: sign * in_joint.s} if keep.c is not None else {}
    values = {p: p.parameter_value for p in params}
    wanted: list[tuple[str, tuple[str, str], str]] = []
    if out_var is not None and out_var != in_var:
        wanted.append(
            (
                "input (type I)",
                out_var,
                "the determinant of the closure equations' Jacobian in every variable but the "
                "output's: the output stands still whatever the input rate",
            )
        )
    wanted.append(
        (
            "output (type II)",
            in_var,
            "the determinant of the closure equations' Jacobian in the passive variables: they "
            "can move with the input locked",
        )
    )
    conds: list[Condition] = []
    notes = (
        [
            "phi_X is the angle body X has turned from its drawn pose (rad; bodies joined by a P "
            "joint turn together); a P joint's name is its slide (m)"
        ]
        if determinants
        else []
    )
    if scaled:
        notes.append(
            "the slide of P joint " + ", ".join(scaled) + " is measured in units of the length "
            "of its axis as written (that length is a radical of the parameters): the "
            "conditions in the input do not depend on it"
        )
    for cname, drop, note in wanted:
        J = L.jacobian([v for v in variables if v != drop])
        det = sympy.expand(J.det(method="berkowitz"))
        const, factors = factor_condition(det, L.symbols, params)
        meanings = [L.meaning(g) for g, _ in factors]
        if determinants:
            shown = []
            for (g, p), m in zip(factors, meanings, strict=True):
                number, trig = _split(to_trig(g, L.symbols), L.symbols)
                const *= number**p
                shown.append(Factor(trig, p, m))
            conds.append(
                Condition(
                    cname,
                    "determinant",
                    _names(factors, L.symbols, params),
                    const,
                    tuple(shown),
                    note,
                )
            )
        try:
            with TimeLimit(time_limit):
                elim = _eliminated(
                    L, factors, meanings, unknowns, keep, in_joint, to_input, params, values
                )
        except TimeLimitExceeded:
            notes.append(
                f"{cname}: the passive joints were not eliminated within {time_limit:g} s; the "
                "condition is given in the joint (or body) variables"
            )
            continue
        if isinstance(elim, str):
            notes.append(f"{cname}: {elim}")
            continue
        efactors, enote, roots = elim
        conds.append(
            Condition(
                f"{cname} in the input {name}",
                "eliminated",
                (name,),
                sympy.Integer(1),
                tuple(efactors),
                enote,
                tuple(roots),
                ("rad",) if keep.c is not None else ("m",),
            )
        )
    return conds, notes


def _printed(m: Any) -> Any:
    """``m`` with the parameters' symbols by their names (a Dummy prints as ``_d``)."""
    return m.xreplace(
        {p: sympy.Symbol(p.name) for p in m.free_symbols if isinstance(p, sympy.Dummy)}
    )


def _irrational_parameters(L: PlanarLinkage) -> Any:
    """A radical or a function of the parameters alone in the closure equations (None when
    they are polynomials in the parameters)."""
    variables = {x for js in L.symbols for x in (js.c, js.s, js.q) if x is not None}
    for e in L.equations:
        e = sympy.sympify(e)
        for a in sorted(e.atoms(sympy.Pow, sympy.Function), key=str):
            if a.free_symbols & variables or not a.free_symbols:
                continue
            if isinstance(a, sympy.Function) or not a.exp.is_Integer:
                return a
    return None


def _names(factors: list[tuple[Any, int]], syms: list[JointSymbols], params: set[Any]) -> tuple:
    found: set[str] = set()
    for g, _ in factors:
        for js in syms:
            if g.has(js.q) or (js.c is not None and (g.has(js.c) or g.has(js.s))):
                found.add(str(js.q))
    return tuple(sorted(found))


def _eliminated(
    L: PlanarLinkage,
    factors: list[tuple[Any, int]],
    meanings: list[str | None],
    unknowns: list[JointSymbols],
    keep: JointSymbols,
    in_joint: JointSymbols,
    to_input: dict[Any, Any],
    params: set[Any],
    values: dict[Any, Any],
) -> tuple[list[Factor], str, list[float]] | str:
    out: list[Factor] = []
    found: list[float] = []
    dropped = 0
    never = []
    # every factor eliminated before any is checked (the checks are the costly part): a
    # condition in the input is given whole or not at all
    eliminated = []
    for (g, _), meaning in zip(factors, meanings, strict=True):
        try:
            eliminated.append(eliminate([*L.equations, g], unknowns, keep))
        except EliminationTooLarge as e:
            what = meaning or "a factor of the determinant"
            return (
                f"the passive joints were not eliminated: for {what}, sympy would need {e} "
                "(the linkage's loops together, with coefficients of the file's digits); "
                "the condition is given in the joint "
                "(or body) variables; 'mechsing analyze' or 'mechsing sweep' finds the input's "
                "values numerically"
            )
    for (g, _), meaning, polys in zip(factors, meanings, eliminated, strict=True):
        if polys is None:
            never.append(meaning or str(to_trig(g, L.symbols)))
            continue
        if not polys:
            return (
                f"the factor {to_trig(g, L.symbols)} vanishes at some configuration for every "
                "value of the input; no condition on the input alone"
            )
        poly = _common(polys, keep)
        if keep.c is not None:
            poly = reduce_trig(sympy.expand(poly.xreplace(to_input)), [in_joint])
        _, hs = factor_condition(poly, [in_joint], params)
        backs = [
            sympy.expand(
                h.xreplace(
                    {in_joint.c: keep.c, in_joint.s: keep.s * _sign(to_input, keep, in_joint)}
                )
            )
            for h, _ in hs
        ]
        ok = genuine(backs, [*L.equations, g], unknowns, keep, values)
        for (h, _), real in zip(hs, ok, strict=True):
            if real:
                out.append(Factor(_in_input(h, in_joint), 1, meaning))
                if not params:
                    found += angles(h, in_joint)
            else:
                dropped += 1
    note = (
        f"each factor of the determinant with the passive joints eliminated (exact resultants, "
        f"the parameters kept as symbols): the values of {in_joint.q} where it holds, on one "
        "assembly branch or another"
    )
    if dropped:
        note += (
            f"; {dropped} extra factor(s) of the resultants, with no configuration of the "
            "linkage at the file's parameter values, left out"
        )
    if never:
        note += "; never reached (no configuration): " + "; ".join(never)
    if not out:
        return (
            "no configuration of the linkage makes it vanish at the file's parameter values: "
            "this singularity is never reached there; no condition on the input"
        )
    return out, note, distinct(found)


def _in_input(h: Any, js: JointSymbols) -> Any:
    """A polynomial in the input's ``c``, ``s`` written in ``cos``, ``sin`` as it is (a
    polynomial in cos(A) and sin(A), collected by powers of cos(A)), a slide as it is."""
    if js.c is None:
        return h
    poly = sympy.Poly(h, js.c, js.s)
    cos, sin = sympy.cos(js.q), sympy.sin(js.q)
    return sympy.Add(*(sympy.factor(coeff) * cos**i * sin**j for (i, j), coeff in poly.terms()))


def _split(trig: Any, syms: list[JointSymbols]) -> tuple[Any, Any]:
    """A number (or parameters) brought out by combining angles, and the rest:
    ``-sin(x)`` is ``-1`` times ``sin(x)``, ``sqrt(2)*cos(x + pi/4)`` is ``sqrt(2)`` times."""
    names = [js.q for js in syms]
    number, rest = trig.as_independent(*names, as_Add=False)
    if number != 1 and rest.free_symbols:
        return number, rest
    return sympy.Integer(1), trig


def _sign(to_input: dict[Any, Any], keep: JointSymbols, in_joint: JointSymbols) -> int:
    if keep.c is None:
        return 1
    return 1 if to_input[keep.s] == in_joint.s else -1


def _common(polys: list[Any], js: JointSymbols) -> Any:
    """One polynomial whose zeros are the common zeros of ``polys`` (their gcd, on the
    circle through the half-angle variable)."""
    if len(polys) == 1:
        return polys[0]
    if js.c is None:
        g = polys[0]
        for p in polys[1:]:
            g = sympy.gcd(g, p)
        return g
    t = sympy.Dummy("t")
    g = tan_half(polys[0], js, t)
    for p in polys[1:]:
        g = sympy.gcd(g, tan_half(p, js, t))
    deg = int(sympy.degree(g, t))
    return to_circle(g, t, (deg + 1) // 2, js)
