"""Planar one-input linkages written in the angles of their bodies (``mechsing condition``).

A planar linkage of R joints (axes along z) and P joints (axes in the plane) is
written here as the classical vector loops: each body ``X`` turns by the angle
``phi_X`` from its drawn pose (symbols ``c_phi_X``, ``s_phi_X`` for its cosine
and sine; bodies joined by a P joint turn together and share one angle, the
ground's is 0), each P joint slides by its own value, and every joint outside a
spanning tree of the bodies closes a loop with two equations, each linear in
the cosine and sine of every angle (positions of the tree's bodies follow from
the ground's).  With one input (an R joint or a P joint on the ground):

* the **output (type II)** condition is the determinant of the closure
  equations' Jacobian in the passive variables (they can move with the input
  locked);
* the **input (type I)** condition is the same determinant without the
  output's variable and with the input's: the output stands still whatever the
  input rate.

Each factor of a determinant is recognised, where it can be, as two links in
line (pivots ``K``, ``J``, ``L`` in line), a link parallel or perpendicular to a
slide; :mod:`mechsing.conditions.elimination` then writes each factor in the
input alone.  Angles in radians, lengths in metres.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import Any

import sympy

from mechsing.conditions.symbolic import JointSymbols, reduce_trig
from mechsing.model import Mechanism

__all__ = ["PlanarLinkage", "planar_linkage", "slide_axis"]


@dataclass
class PlanarLinkage:
    """The vector-loop form of a planar linkage (see the module docstring)."""

    #: body -> the body that names its angle class (the ground's class has no angle)
    classes: dict[str, str]
    #: angle symbols of each class but the ground's, by naming body
    angles: dict[str, JointSymbols]
    #: slide symbols of the P joints, by joint
    slides: dict[str, Any]
    #: the closure equations (two per joint outside the spanning tree)
    equations: list[Any]
    #: direction vectors that name geometry: (label, body, vector or None, slide axis or None)
    directions: list[tuple[str, str, Any, Any]] = field(default_factory=list)

    @property
    def symbols(self) -> list[JointSymbols]:
        return [*self.angles.values(), *(JointSymbols(q, None, None) for q in self.slides.values())]

    def variable(self, kind: str, name: str) -> Any:
        """The symbol ``phi_X`` of class ``name`` or the slide of joint ``name``."""
        return self.angles[name].q if kind == "angle" else self.slides[name]

    def jacobian(self, variables: list[tuple[str, str]]) -> Any:
        """The closure equations' derivatives in ``variables`` (("angle", body) or
        ("slide", joint)) as a matrix, an angle's derivative written in ``c``, ``s``."""
        cols = []
        for kind, name in variables:
            if kind == "angle":
                js = self.angles[name]
                col = [
                    sympy.diff(e, js.c) * (-js.s) + sympy.diff(e, js.s) * js.c
                    for e in self.equations
                ]
            else:
                col = [sympy.diff(e, self.slides[name]) for e in self.equations]
            cols.append(col)
        return sympy.Matrix(cols).T

    def meaning(self, factor: Any) -> str | None:
        """What the vanishing of ``factor`` (in these symbols) means, where recognised."""
        syms = self.symbols
        f = reduce_trig(factor, syms)
        for label, h in self._geometry():
            if _proportional(f, h, syms):
                return label
        return None

    def _geometry(self) -> list[tuple[str, Any]]:
        out = []
        syms = self.symbols
        dirs = self.directions
        for (la, ba, va, ua), (lb, bb, vb, ub) in itertools.combinations(dirs, 2):
            a = va if va is not None else ua
            b = vb if vb is not None else ub
            cross = reduce_trig(a[0] * b[1] - a[1] * b[0], syms)
            dot = reduce_trig(a[0] * b[0] + a[1] * b[1], syms)
            if va is not None and vb is not None:
                shared = set(la.split(",")) & set(lb.split(","))
                if ba != bb and shared:
                    (j,) = shared
                    k = next(p for p in la.split(",") if p != j)
                    m = next(p for p in lb.split(",") if p != j)
                    out.append((f"{ba} and {bb} in line (pivots {k}, {j} and {m} in line)", cross))
                elif ba != bb:
                    out.append(
                        (
                            f"{ba} ({la.replace(',', '-')}) parallel to {bb} "
                            f"({lb.replace(',', '-')})",
                            cross,
                        )
                    )
                out.append(
                    (
                        f"{ba} ({la.replace(',', '-')}) perpendicular to {bb} "
                        f"({lb.replace(',', '-')})",
                        dot,
                    )
                )
            elif va is not None or vb is not None:
                (lv, bv), lu = ((la, ba), lb) if va is not None else ((lb, bb), la)
                out.append(
                    (f"{bv} (pivots {lv.replace(',', ' and ')}) along the slide of {lu}", cross)
                )
                out.append(
                    (
                        f"{bv} (pivots {lv.replace(',', ' and ')}) perpendicular to the slide of {lu}",
                        dot,
                    )
                )
            else:
                out.append((f"the slides of {la} and {lb} parallel", cross))
        return out


def _proportional(f: Any, h: Any, syms: list[JointSymbols]) -> bool:
    if h == 0 or f == 0:
        return False
    ratio = sympy.cancel(sympy.expand(f) / sympy.expand(h))
    names = set()
    for js in syms:
        names |= {js.q} | ({js.c, js.s} if js.c is not None else set())
    return not (ratio.free_symbols & names)


def _rot(js: JointSymbols | None, v: Any) -> Any:
    if js is None:
        return sympy.Matrix([v[0], v[1]])
    return sympy.Matrix([js.c * v[0] - js.s * v[1], js.s * v[0] + js.c * v[1]])


def planar_linkage(mech: Mechanism, written_axes: bool = False) -> PlanarLinkage | str:
    """The vector-loop form of ``mech``, or why it is not a planar linkage of R and P
    joints (R axes along z, P axes in the xy plane).

    ``written_axes``: a P joint's axis as written, not normalised when its length is a
    radical of the parameters (``[d, r, 0]``, not divided by ``sqrt(d**2 + r**2)``): its
    slide is then measured in units of that length, and the equations stay polynomials
    in the parameters (see :func:`slide_axis`)."""
    for j in mech.joints:
        if j.type not in ("R", "P"):
            return f"joint {j.name!r} is of type {j.type} (the planar form has R and P joints)"
        axis = [
            sympy.nsimplify(x) if isinstance(x, float) else sympy.sympify(x)
            for x in j.params["axis"]
        ]
        if j.type == "R" and not (axis[0] == 0 and axis[1] == 0 and axis[2] in (1, -1)):
            return f"joint {j.name!r} turns about {list(axis)}, not about z"
        if j.type == "P" and axis[2] != 0:
            return f"joint {j.name!r} slides along {list(axis)}, out of the xy plane"
    ground = mech.ground
    bodies = list(mech.bodies)
    parent = {b: b for b in bodies}

    def find(b: str) -> str:
        while parent[b] != b:
            b = parent[b]
        return b

    for j in mech.joints:
        if j.type == "P":
            a, b = find(j.between[0]), find(j.between[1])
            if a != b:
                parent[b] = a
    groups: dict[str, list[str]] = {}
    for b in bodies:
        groups.setdefault(find(b), []).append(b)
    out_body = mech.output.body if mech.output is not None else None
    classes: dict[str, str] = {}
    angles: dict[str, JointSymbols] = {}
    for members in groups.values():
        if ground in members:
            name = ground
        elif out_body in members:
            name = out_body
        else:
            name = members[0]
        for b in members:
            classes[b] = name
        if name != ground:
            q = sympy.Symbol(f"phi_{name}", real=True)
            angles[name] = JointSymbols(
                q,
                sympy.Symbol(f"c_phi_{name}", real=True),
                sympy.Symbol(f"s_phi_{name}", real=True),
            )
    slides = {j.name: sympy.Symbol(j.name, real=True) for j in mech.joints if j.type == "P"}

    def R(body: str) -> JointSymbols | None:
        return angles.get(classes[body])

    # spanning tree from the ground: body positions p_b (2-vectors)
    pos: dict[str, Any] = {ground: sympy.zeros(2, 1)}
    tree: set[str] = set()
    frontier = [ground]
    while frontier:
        nxt = []
        for a in frontier:
            for j in mech.joints:
                if j.name in tree or a not in j.between:
                    continue
                b = j.between[1] if j.between[0] == a else j.between[0]
                if b in pos:
                    continue
                tree.add(j.name)
                pos[b] = _expand(pos[a] + _relative(j, a, b, R, slides, written_axes))
                nxt.append(b)
        frontier = nxt
    equations = []
    for j in mech.joints:
        if j.name in tree:
            continue
        a, b = j.between
        if a not in pos or b not in pos:
            return f"body {a if a not in pos else b!r} is not connected to the ground"
        diff = _expand(pos[a] + _relative(j, a, b, R, slides, written_axes) - pos[b])
        equations += [e for e in diff if e != 0]
    # directions: each body's pivot pairs and each slide axis, as they turn
    directions: list[tuple[str, str, Any, Any]] = []
    for b in bodies:
        if b == ground:
            continue
        pivots = [j for j in mech.joints if j.type == "R" and b in j.between]
        for j1, j2 in itertools.combinations(pivots, 2):
            v = sympy.Matrix(j2.params["point"][:2]) - sympy.Matrix(j1.params["point"][:2])
            directions.append((f"{j1.name},{j2.name}", b, _expand(_rot(R(b), v)), None))
    for j in mech.joints:
        if j.type == "P":
            u = slide_axis(j, written_axes)
            directions.append((j.name, j.between[0], None, _expand(_rot(R(j.between[0]), u))))
    return PlanarLinkage(classes, angles, slides, equations, directions)


def slide_axis(j: Any, written: bool) -> Any:
    """The in-plane axis of P joint ``j`` (a 2-vector): the unit axis, or with ``written``
    the unit axis times the radicals of the parameters that normalised it (its length
    ``sqrt(d**2 + r**2)`` when written ``[d, r, 0]``)."""
    u = sympy.Matrix([sympy.sympify(x) for x in j.params["axis"][:2]])
    if not written:
        return u
    norms = {
        a.base ** sympy.Rational(1, a.exp.q)
        for x in u
        for a in x.atoms(sympy.Pow)
        if a.free_symbols and a.exp.is_Rational and not a.exp.is_Integer
    }
    for a in sorted(norms, key=str):
        u = (u * a).applyfunc(lambda x: sympy.expand(sympy.cancel(x)))
    return u


def _relative(
    j: Any, a: str, b: str, R: Any, slides: dict[str, Any], written_axes: bool = False
) -> Any:
    """``p_b - p_a`` across joint ``j`` (traversed from ``a`` to ``b``)."""
    if j.type == "R":
        P = sympy.Matrix(j.params["point"][:2])
        return _rot(R(a), P) - _rot(R(b), P)
    u = slide_axis(j, written_axes)
    step = _rot(R(j.between[0]), u) * slides[j.name]
    return step if a == j.between[0] else -step


def _expand(m: Any) -> Any:
    return m.applyfunc(sympy.expand)
