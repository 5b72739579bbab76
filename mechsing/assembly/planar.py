"""The planar platform-pose formulation: one body's pose ``(x, y, theta)`` from three
scalar constraints that the legs between it and the known bodies impose.

The *known* bodies are ground and those the given joint values place (a crank whose
angle is given).  The *platform* is one unknown body; every other unknown body lies on
a leg from a known body to the platform, and each leg is one constraint on the platform
pose (Gosselin, Sefrioui & Richard 1992 for the 3-RPR):

* a revolute joint straight to a known body: the joint's point is shared (2 equations);
* R-R through one body (a binary link, a four-bar's rocker): a fixed distance (1);
* R-P-R with the slide given (a 3-RPR leg): a distance ``|b - a + q u|`` (1);
* P-R or R-P with the slide unknown (a slider-crank's slider): a point on a line (1).

Distances are quadratic in ``(x, y)`` with leading term ``x^2 + y^2``: subtracting one
from the others leaves equations linear in ``(x, y)``; two of them give ``(x, y)`` by
Cramer's rule and the third becomes one univariate polynomial in ``t = tan((theta -
theta0) / 2)`` (``theta0`` an offset with rational sine and cosine, chosen so that no
solution sits at ``t = oo``).  The mechanism's joints must have axes along z (R) or in
the xy plane (P).  A given angle enters by its cosine and sine: in radicals where sympy
writes them so, else as ``cos(q)``, ``sin(q)`` (0.3 rad), which the elimination encloses.

A linkage of several loops that no one body's legs fix is taken in stages
(:func:`planar_stages`): a Watt II's four-bar first, then the dyad on its rocker, whose
known bodies' poses are the first stage's symbols.

Owns :class:`PlanarSystem`, :func:`planar_system`, :func:`planar_stages`,
:func:`stages_system` and :func:`joint_values`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import mpmath
import networkx as nx
import sympy

from mechsing.errors import FormulationError
from mechsing.model import Mechanism
from mechsing.numeric.field import cos_sin

__all__ = ["PlanarSystem", "joint_values", "planar_stages", "planar_system", "stages_system"]


#: tan(theta0 / 2) of the offsets tried for the platform angle (rational: theta0's sine
#: and cosine are rational); the next is taken when a solution sits at theta0 + pi
OFFSETS = (sympy.Rational(1, 7), sympy.Rational(-2, 9), sympy.Rational(3, 11))

X, Y, C, S = sympy.symbols("x y c s", real=True)


@dataclass(frozen=True)
class Leg:
    """One leg: ``kind`` (``point``, ``distance``, ``line-fixed``, ``line-moving``), its
    joints from the known body to the platform, the known body, and its equations in
    (x, y, c, s)."""

    kind: str
    joints: tuple[str, ...]
    known: str
    equations: tuple[sympy.Expr, ...]


@dataclass(frozen=True)
class PlanarSystem:
    """The platform ``platform``, the known bodies' exact planar poses, the legs and the
    equations in (x, y, c, s) (with ``c^2 + s^2 = 1``)."""

    platform: str
    known: dict[str, tuple[Any, Any, Any, Any] | None]  # body -> (cos, sin, px, py)
    legs: tuple[Leg, ...]
    #: a stage's own platform pose as symbols (cos, sin, x, y) for the later stages
    symbols: tuple[sympy.Symbol, ...] = ()

    @property
    def equations(self) -> list[sympy.Expr]:
        return [e for leg in self.legs for e in leg.equations]


def _xy(v: Any) -> tuple[Any, Any]:
    return sympy.sympify(v[0]), sympy.sympify(v[1])


def _check_planar(mech: Mechanism) -> None:
    for j in mech.joints:
        if j.type == "R":
            a = j.params["axis"]
            if a[0] != 0 or a[1] != 0:
                raise FormulationError(
                    f"joint {j.name}'s axis is not along z (a planar formulation)"
                )
        elif j.type == "P":
            if j.params["axis"][2] != 0:
                raise FormulationError(f"joint {j.name}'s axis is not in the xy plane")
        else:
            raise FormulationError(
                f"joint {j.name} is {j.type}; the planar formulation takes R and P"
            )


def _cos_sin(q: Any, what: str) -> tuple[Any, Any]:
    """The cosine and sine of a given angle: in radicals where sympy can write them so
    (30 deg, 2*atan(1/3)), else as ``cos(q)``, ``sin(q)`` (0.3 rad: known to any number
    of digits, which the elimination encloses in intervals)."""
    q = sympy.sympify(q)
    if not (q.is_number and q.is_real and q.is_finite):
        raise FormulationError(f"{what} is {q}, not a real number")
    exact = cos_sin(q)
    if exact is not None:
        return exact
    return sympy.cos(q), sympy.sin(q)


def _compose(g: tuple, h: tuple) -> tuple:
    """g . h for planar poses (cos, sin, px, py)."""
    c1, s1, x1, y1 = g
    c2, s2, x2, y2 = h
    return (c1 * c2 - s1 * s2, s1 * c2 + c1 * s2, c1 * x2 - s1 * y2 + x1, s1 * x2 + c1 * y2 + y1)


def _joint_motion(j: Any, q: Any) -> tuple:
    """The planar pose exp(q e) of joint ``j`` at value ``q`` (exact)."""
    if j.type == "P":
        ux, uy = _xy(j.params["axis"])
        return (sympy.S.One, sympy.S.Zero, q * ux, q * uy)
    sign = sympy.sympify(j.params["axis"][2])
    c, s = _cos_sin(q, f"{j.name}'s given angle")
    s = sign * s
    px, py = _xy(j.params["point"])
    return (c, s, px - c * px + s * py, py - s * px - c * py)


def _inverse(g: tuple) -> tuple:
    c, s, x, y = g
    return (c, -s, -(c * x + s * y), s * x - c * y)


def _apply(g: tuple, p: tuple) -> tuple:
    c, s, x, y = g
    return (c * p[0] - s * p[1] + x, s * p[0] + c * p[1] + y)


def planar_system(mech: Mechanism, given: dict[str, tuple[Any, ...]]) -> PlanarSystem:
    """The legs' constraints on one unknown body's pose (the output body first)."""
    _check_planar(mech)
    G, known = _graph(mech), _known(mech, given)
    return _stage(mech, G, known, given, defer=False)


def planar_stages(mech: Mechanism, given: dict[str, tuple[Any, ...]]) -> list[PlanarSystem]:
    """One platform on its legs (:func:`planar_system`), or, for a mechanism of several
    loops that no one body's legs fix (a Watt or Stephenson six-bar), stages: a body
    whose supported legs give three equations, the other unknown bodies left for later;
    then, that body known (its pose the symbols of the stage, ``c1, s1, x1, y1``), the
    next stage among the rest.  A later stage may rest on the known bodies and the
    earlier platforms, not on the bodies inside an earlier leg."""
    _check_planar(mech)
    G, known = _graph(mech), _known(mech, given)
    try:
        return [_stage(mech, G, known, given, defer=False)]
    except FormulationError as whole:
        stages: list[PlanarSystem] = []
        while len(stages) < len(mech.bodies):
            try:
                system = _stage(mech, G, known, given, defer=True, index=len(stages) + 1)
            except FormulationError as exc:
                if not stages:
                    raise whole from None
                raise FormulationError(
                    f"{whole}; in stages: {', '.join(st.platform for st in stages)} placed, "
                    f"then {exc}"
                ) from None
            stages.append(system)
            known = {**known, system.platform: system.symbols}
            for leg in system.legs:
                for body in _leg_bodies(mech, leg, system.platform):
                    known[body] = None  # placed by the leg, not a base for later stages
            if all(b in known for b in mech.bodies):
                return stages
        raise whole from None


def _graph(mech: Mechanism) -> nx.MultiGraph:
    G = nx.MultiGraph()
    G.add_nodes_from(mech.bodies)
    for j in mech.joints:
        G.add_edge(*j.between, key=j.name)
    return G


def _known(mech: Mechanism, given: dict) -> dict[str, tuple | None]:
    """The exact planar poses of ground and of the bodies the given values place."""
    known: dict[str, tuple | None] = {
        mech.ground: (sympy.S.One, sympy.S.Zero, sympy.S.Zero, sympy.S.Zero)
    }
    changed = True
    while changed:
        changed = False
        for j in mech.joints:
            a, b = j.between
            if j.name not in given or (a in known) == (b in known):
                continue
            m = _joint_motion(j, sympy.sympify(given[j.name][0]))
            if a in known:
                known[b] = tuple(sympy.simplify(v) for v in _compose(known[a], m))
            else:
                known[a] = tuple(sympy.simplify(v) for v in _compose(known[b], _inverse(m)))
            changed = True
    return known


def _stage(
    mech: Mechanism, G: nx.MultiGraph, known: dict, given: dict, defer: bool, index: int = 0
) -> PlanarSystem:
    """One unknown body fixed by three leg equations (``defer``: the unknown bodies that
    form no supported leg to it are left for a later stage)."""
    unknown = [b for b in mech.bodies if b not in known]
    if not unknown:
        raise FormulationError("the given values place every body (nothing is left to solve)")
    candidates = sorted(
        unknown, key=lambda b: (mech.output is None or b != mech.output.body, -G.degree(b))
    )
    symbols = sympy.symbols(f"c{index} s{index} x{index} y{index}", real=True) if index else ()
    reasons = []
    for platform in candidates:
        try:
            legs = _legs(mech, G, known, platform, given, defer)
        except FormulationError as exc:
            reasons.append(f"{platform}: {exc}")
            continue
        n = sum(len(leg.equations) for leg in legs)
        if n == 3:
            return PlanarSystem(platform, known, tuple(legs), tuple(symbols))
        reasons.append(f"{platform}: its legs give {n} equations, not 3")
    raise FormulationError(
        "no body's pose is fixed by three leg constraints (" + "; ".join(reasons) + ")"
    )


def _legs(
    mech: Mechanism, G: nx.MultiGraph, known: dict, platform: str, given: dict, defer: bool
) -> list[Leg]:
    legs = []
    for a, b, name in G.edges(keys=True):  # joints straight between a known body and the platform
        if {a, b} & {platform} and ({a, b} - {platform}) <= set(known) and a != b:
            j = mech.joint(name)
            other = a if b == platform else b
            if name in given:
                raise FormulationError(f"joint {name} is given and joins it to a known body")
            if j.type != "R":
                raise FormulationError(f"joint {name} (P) joins it to a known body")
            if known[other] is None:
                raise FormulationError(f"joint {name} joins it to {other}, inside an earlier leg")
            p = _xy(j.params["point"])
            gk = _apply(known[other], p)
            gp = _apply((C, S, X, Y), p)
            legs.append(Leg("point", (name,), other, (gp[0] - gk[0], gp[1] - gk[1])))
    rest = G.subgraph([n for n in G if n not in known and n != platform])
    for comp in nx.connected_components(rest):
        try:
            legs.append(_chain_leg(mech, G, known, platform, sorted(comp), given))
        except FormulationError:
            if not defer:
                raise
    return legs


def _chain_leg(
    mech: Mechanism, G: nx.MultiGraph, known: dict, platform: str, comp: list[str], given: dict
) -> Leg:
    """The leg through the unknown bodies ``comp``: a path known - ... - platform."""
    edges = [(a, b, k) for a, b, k in G.edges(keys=True) if a in comp or b in comp]
    H = nx.MultiGraph()
    H.add_edges_from(edges)
    ends = [n for n in H if n not in comp]
    if len(edges) != len(comp) + 1 or platform not in ends or len(ends) != 2:
        raise FormulationError(f"bodies {', '.join(comp)} do not form one leg to it")
    start = next(n for n in ends if n != platform)
    if known[start] is None:
        raise FormulationError(f"bodies {', '.join(comp)} rest on {start}, inside an earlier leg")
    path = nx.shortest_path(H, start, platform)
    names = []
    for u, v in zip(path, path[1:], strict=False):
        names.append(next(iter(H.get_edge_data(u, v))))
    joints = [mech.joint(n) for n in names]
    types = "".join(j.type for j in joints)
    free = [n for n in names if n not in given]
    gk = known[start]
    plat = (C, S, X, Y)
    if types == "RR" and not (set(names) & set(given)):
        a, b = (_xy(j.params["point"]) for j in joints)
        pa, pb = _apply(gk, a), _apply(plat, b)
        d2 = (a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2
        eq = (pb[0] - pa[0]) ** 2 + (pb[1] - pa[1]) ** 2 - d2
        return Leg("distance", tuple(names), start, (sympy.expand(eq),))
    if types == "RPR" and free == [names[0], names[2]]:
        a, b = _xy(joints[0].params["point"]), _xy(joints[2].params["point"])
        u = _xy(joints[1].params["axis"])
        q = sympy.sympify(given[names[1]][0])
        # the slide is along u in the frame of the body before it on the path: q u or -q u
        sign = 1 if joints[1].between[0] == path[1] else -1
        w = (b[0] + sign * q * u[0] - a[0], b[1] + sign * q * u[1] - a[1])
        pa, pb = _apply(gk, a), _apply(plat, b)
        eq = (pb[0] - pa[0]) ** 2 + (pb[1] - pa[1]) ** 2 - sympy.simplify(w[0] ** 2 + w[1] ** 2)
        return Leg("distance", tuple(names), start, (sympy.expand(eq),))
    if types == "PR" and not (set(names) & set(given)):
        u, b = _xy(joints[0].params["axis"]), _xy(joints[1].params["point"])
        uk = _apply((gk[0], gk[1], 0, 0), u)
        pk, pb = _apply(gk, b), _apply(plat, b)
        eq = uk[0] * (pb[1] - pk[1]) - uk[1] * (pb[0] - pk[0])
        return Leg("line-fixed", tuple(names), start, (sympy.expand(eq),))
    if types == "RP" and not (set(names) & set(given)):
        a, u = _xy(joints[0].params["point"]), _xy(joints[1].params["axis"])
        up = _apply((C, S, 0, 0), u)
        pk, pa = _apply(gk, a), _apply(plat, a)
        eq = up[0] * (pk[1] - pa[1]) - up[1] * (pk[0] - pa[0])
        return Leg("line-moving", tuple(names), start, (sympy.expand(eq),))
    raise FormulationError(
        f"leg {'-'.join(names)} ({types}) is not R, R-R, R-P-R (slide given), P-R or R-P"
    )


def stages_system(stages: list[PlanarSystem]) -> tuple[list[sympy.Expr], list[sympy.Symbol]]:
    """Every stage's leg equations as one square system in each platform's ``x, y,
    theta`` (the cosines and sines written as cos and sin of theta): the system the
    Krawczyk test certifies each closed configuration on."""
    eqs, unknowns, sub = [], [], {}
    for k, system in enumerate(stages, start=1):
        x, y, theta = sympy.symbols(f"x{k} y{k} theta{k}", real=True)
        own = {X: x, Y: y, C: sympy.cos(theta), S: sympy.sin(theta)}
        eqs += [e.xreplace(own).xreplace(sub) for e in system.equations]
        unknowns += [x, y, theta]
        if system.symbols:
            sub.update(zip(system.symbols, (own[C], own[S], x, y), strict=True))
    return eqs, unknowns


# -- from the platform's pose back to every joint value --------------------------------


def _num(g: tuple) -> tuple:
    return tuple(
        mpmath.mpf(sympy.N(v, mpmath.mp.dps + 5)) if not isinstance(v, mpmath.mpf) else v for v in g
    )


def _angle_of(g: tuple) -> Any:
    return mpmath.atan2(g[1], g[0])


def _rotation_pose(theta: Any, fixed_ref: tuple, fixed_now: tuple) -> tuple:
    """The planar pose of rotation ``theta`` that takes ``fixed_ref`` to ``fixed_now``."""
    c, s = mpmath.cos(theta), mpmath.sin(theta)
    return (
        c,
        s,
        fixed_now[0] - (c * fixed_ref[0] - s * fixed_ref[1]),
        fixed_now[1] - (s * fixed_ref[0] + c * fixed_ref[1]),
    )


def joint_values(
    mech: Mechanism, stages: list[PlanarSystem], given: dict, platforms: list[tuple]
) -> list[Any]:
    """Every joint coordinate (the mechanism's order) at the platform poses ``platforms``
    of the stages (cos, sin, x, y as mpmath numbers; one stage for one platform)."""
    poses = {b: _num(g) for b, g in stages[0].known.items() if g is not None}
    for system, pose in zip(stages, platforms, strict=True):
        _place_legs(mech, system, given, pose, poses)
    out = []
    for name, _i in mech.coordinates():
        if name in given:
            out.append(mpmath.mpf(sympy.N(given[name][0], mpmath.mp.dps + 5)))
            continue
        j = mech.joint(name)
        rel = _compose(_inverse(poses[j.between[0]]), poses[j.between[1]])
        if j.type == "R":
            out.append(_angle_of(rel) * mpmath.mpf(sympy.N(j.params["axis"][2])))
        else:
            u = _xy(j.params["axis"])
            out.append(
                rel[2] * mpmath.mpf(sympy.N(u[0], mpmath.mp.dps + 5))
                + rel[3] * mpmath.mpf(sympy.N(u[1], mpmath.mp.dps + 5))
            )
    return out


def _place_legs(
    mech: Mechanism, system: PlanarSystem, given: dict, pose: tuple, poses: dict
) -> None:
    """The platform's and its legs' bodies' poses into ``poses``."""
    poses[system.platform] = pose
    for leg in system.legs:
        if leg.kind == "point":
            continue
        joints = [mech.joint(n) for n in leg.joints]
        gk = poses[leg.known]
        mids = _leg_bodies(mech, leg, system.platform)
        if leg.kind == "distance" and len(joints) == 2:
            a, b = (
                tuple(mpmath.mpf(sympy.N(v, mpmath.mp.dps + 5)) for v in _xy(j.params["point"]))
                for j in joints
            )
            pa, pb = _apply(gk, a), _apply(pose, b)
            theta = _angle_of((pb[0] - pa[0], pb[1] - pa[1])) - mpmath.atan2(
                b[1] - a[1], b[0] - a[0]
            )
            poses[mids[0]] = _rotation_pose(theta, a, pa)
        elif leg.kind == "distance":
            a, b = (
                tuple(mpmath.mpf(sympy.N(v, mpmath.mp.dps + 5)) for v in _xy(j.params["point"]))
                for j in (joints[0], joints[2])
            )
            u = tuple(
                mpmath.mpf(sympy.N(v, mpmath.mp.dps + 5)) for v in _xy(joints[1].params["axis"])
            )
            q = mpmath.mpf(sympy.N(given[leg.joints[1]][0], mpmath.mp.dps + 5))
            sign = 1 if joints[1].between[0] == mids[0] else -1
            w = (b[0] + sign * q * u[0] - a[0], b[1] + sign * q * u[1] - a[1])
            pa, pb = _apply(gk, a), _apply(pose, b)
            theta = _angle_of((pb[0] - pa[0], pb[1] - pa[1])) - mpmath.atan2(w[1], w[0])
            first = _rotation_pose(theta, a, pa)
            slide = (1, 0, sign * q * u[0], sign * q * u[1])
            poses[mids[0]] = first
            poses[mids[1]] = _compose(first, slide)
        elif leg.kind == "line-fixed":  # known -P- body -R- platform: the body turns with known
            b = tuple(
                mpmath.mpf(sympy.N(v, mpmath.mp.dps + 5)) for v in _xy(joints[1].params["point"])
            )
            poses[mids[0]] = _rotation_pose(_angle_of(gk), b, _apply(pose, b))
        else:  # known -R- body -P- platform: the body turns with the platform about a
            a = tuple(
                mpmath.mpf(sympy.N(v, mpmath.mp.dps + 5)) for v in _xy(joints[0].params["point"])
            )
            poses[mids[0]] = _rotation_pose(_angle_of(pose), a, _apply(gk, a))


def _leg_bodies(mech: Mechanism, leg: Leg, platform: str) -> list[str]:
    """The unknown bodies along ``leg`` from its known body to the platform."""
    bodies, at = [], leg.known
    for name in leg.joints[:-1]:
        at = mech.joint(name).other(at)
        bodies.append(at)
    return bodies
