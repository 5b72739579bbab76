"""The names people give singularities of arms and legs, and the geometry that earns them.

One place for the words: ``condition`` names the factors of its formulas with them and
``analyze``, ``sweep`` and ``report`` name ``serial`` findings with them (the JSON key
``name``).  A name is given only where the chain's joint axes show the pattern it names:

- ``wrist``: axes meeting at one point (a wrist centre) become dependent -- two coincide, two
  become parallel, or the three lie in one plane;
- ``elbow`` (an arm) or ``leg fully stretched or folded`` (a leg of a parallel mechanism):
  parallel axes (a planar chain's pivots) come to lie in one plane (in line), or the wrist
  centre comes into the plane of two parallel axes; an output singularity whose moving
  joints, in line, include none on the base (a five-bar's three joints beyond its two
  cranks) is ``distal links stretched or folded``;
- ``shoulder``: the wrist centre (or, for an arm without one, the point where its last two
  axes meet; for a positioning task, the output point) comes into the plane through one
  axis parallel to another.

The facts are tested on the chain's joint lines (a point and a unit direction each; None
for a prismatic joint's point) at the configuration, and only the facts that do not hold
at every configuration (those of a generic one are given) count.  A chain that matches no
pattern gets no name: the generic sentence is kept, never a guessed name.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Any

import numpy as np

from mechsing.numeric import CONDITION_GEOMETRY_RTOL

__all__ = [
    "DISTAL",
    "ELBOW",
    "LEG",
    "NAMES",
    "SHOULDER",
    "WRIST",
    "Line",
    "line_facts",
    "lines_of_screws",
    "meaning_of",
    "name_of",
    "named",
    "singularity_name",
]

WRIST = "wrist"
ELBOW = "elbow"
SHOULDER = "shoulder"
LEG = "leg fully stretched or folded"
DISTAL = "distal links stretched or folded"

#: each name with what it means: the one source of these words in every command
NAMES = {
    WRIST: "the wrist's axes become dependent",
    ELBOW: "the arm fully stretched or folded",
    SHOULDER: (
        "the wrist centre (a positioning arm's output point) in the plane through the "
        "first axis parallel to the second, on the first axis for an arm without shoulder "
        "offset"
    ),
    LEG: "its pivots in line",
    DISTAL: "the pivots of its moving joints in line, none of them on the base",
}

#: a joint line: its name, a point on it (None for a prismatic joint), its unit direction
Line = tuple[str, Any, np.ndarray]

# each fact with its kind (None: a fact that earns no name) and the joints whose axes it is about
_Facts = dict[str, tuple[str | None, frozenset[str]]]


def lines_of_screws(names: Sequence[str], screws: Any) -> list[Line]:
    """The joint lines of SI screws (6 x n columns (omega, v) at the ground origin)."""
    out: list[Line] = []
    S = np.asarray(screws, dtype=float)
    for n, col in zip(names, S.T, strict=True):
        w, v = col[:3], col[3:]
        nw = float(np.linalg.norm(w))
        if nw <= CONDITION_GEOMETRY_RTOL * max(1.0, float(np.linalg.norm(v))):
            nv = float(np.linalg.norm(v))
            out.append((n, None, v / nv if nv else v))
        else:
            out.append((n, np.cross(w, v) / nw**2, w / nw))
    return out


def line_facts(
    lines: Sequence[Line], point: Any = None, planar: bool = False, scale: float = 1.0
) -> _Facts:
    """The geometric facts of joint ``lines`` (and an output ``point``), each with the kind of
    singularity it shows: parallel or coincident axes, the output point on an axis, parallel
    axes in one plane (planar pivots in line), a wrist centre in a special plane."""
    tol = CONDITION_GEOMETRY_RTOL
    facts: _Facts = {}
    for (a, pa, ua), (b, pb, ub) in itertools.combinations(lines, 2):
        if pa is None or pb is None:
            continue
        if np.linalg.norm(np.cross(ua, ub)) < tol:
            d = np.linalg.norm(np.cross(pb - pa, ua))
            if d < tol * scale:
                facts[f"the axes of {a} and {b} coincide"] = (WRIST, frozenset((a, b)))
            elif not planar:
                facts[f"the axes of {a} and {b} are parallel"] = (WRIST, frozenset((a, b)))
    P = None
    if point is not None:
        P = np.asarray(point, dtype=float).ravel()
        for n, p, u in lines:
            if p is not None and np.linalg.norm(np.cross(P - p, u)) < tol * scale:
                facts[f"the output point is on the axis of {n}"] = (None, frozenset((n,)))
    facts.update(_centre_facts(lines, scale, P))
    # three parallel axes (or two and the output point) in one plane
    items = [(n, p, u) for n, p, u in lines if p is not None]
    if P is not None and items:
        items.append(("the output point", P, items[0][2]))
    for (a, pa, ua), (b, pb, ub), (c, pc, uc) in itertools.combinations(items, 3):
        point = c == "the output point"  # the point comes last; it has no direction
        if point:
            uc = ua
        if max(np.linalg.norm(np.cross(ua, ub)), np.linalg.norm(np.cross(ua, uc))) > tol:
            continue
        d1 = pb - pa - ua * np.dot(pb - pa, ua)
        d2 = pc - pa - ua * np.dot(pc - pa, ua)
        if np.linalg.norm(np.cross(d1, d2)) < tol * scale**2:
            if planar:
                text = (
                    f"the pivots of {a}, {b} and {c} are in line (the links between them "
                    "stretched or folded)"
                )
            elif point:
                text = (
                    f"the output point lies in the plane of the parallel axes of {a} and {b} "
                    "(the links between them stretched or folded)"
                )
            else:
                text = (
                    f"the parallel axes of {a}, {b} and {c} lie in one plane (the links "
                    "between them stretched or folded)"
                )
            facts[text] = (ELBOW, frozenset((a, b, c)) - {"the output point"})
    return facts


def _centres(R: Sequence[Line], scale: float) -> list[tuple[str, list[str], np.ndarray]]:
    """Where three or more axes meet (wrist centres), each as (who, names, point); without
    one, where the last two axes of the chain meet."""
    tol = CONDITION_GEOMETRY_RTOL
    out = []
    for trio in itertools.combinations(R, 3):
        us = [u for _, _, u in trio]
        if min(np.linalg.norm(np.cross(a, b)) for a, b in itertools.combinations(us, 2)) < tol:
            continue
        W = _meet(trio[0], trio[1])
        if any(np.linalg.norm(np.cross(W - p, u)) > tol * scale for _, p, u in trio):
            continue
        out.append((", ".join(n for n, _, _ in trio), [n for n, _, _ in trio], W))
    if not out and len(R) >= 2:
        a, b = R[-2], R[-1]
        if np.linalg.norm(np.cross(a[2], b[2])) >= tol:
            W = _meet(a, b)
            if all(np.linalg.norm(np.cross(W - p, u)) <= tol * scale for _, p, u in (a, b)):
                out.append((f"{a[0]} and {b[0]}", [a[0], b[0]], W))
    return out


def _meet(a: Line, b: Line) -> np.ndarray:
    (_, p1, u1), (_, p2, u2) = a, b
    t = np.linalg.lstsq(np.column_stack([u1, -u2]), p2 - p1, rcond=None)[0]
    return p1 + t[0] * u1


def _centre_facts(lines: Sequence[Line], scale: float, point: Any = None) -> _Facts:
    """Where axes meet (a wrist centre): are its axes in one plane, is it in the plane of two
    parallel axes, or in the plane through one axis parallel to another?  A positioning
    task's output ``point`` is its arm's wrist centre for the last (the shoulder); its
    plane of two parallel axes is :func:`line_facts`' (the elbow)."""
    tol = CONDITION_GEOMETRY_RTOL
    R = [(n, p, u) for n, p, u in lines if p is not None]
    out: _Facts = {}
    centres = _centres(R, scale)
    if point is not None:
        centres.append(("the output point", [], point))
    for who, members, W in centres:
        own = not members  # the output point: not a meet of two of the axes
        trio = [x for x in R if x[0] in members]
        if len(trio) == 3 and abs(np.linalg.det(np.column_stack([u for *_, u in trio]))) < tol:
            out[f"the axes of {who} (meeting at one point) are in one plane"] = (
                WRIST,
                frozenset(members),
            )
        for (a, pa, ua), (b, pb, ub) in itertools.combinations(R, 2):
            if a in members or b in members:
                continue
            normal = np.cross(ua, ub)
            if np.linalg.norm(normal) < tol:
                if own:
                    continue
                normal = np.cross(ua, pb - pa)
                if np.linalg.norm(normal) < tol * scale:
                    continue
                where, kind = f"the plane of the parallel axes of {a} and {b}", ELBOW
                about = frozenset((a, b))
            else:
                where, kind = (
                    f"the plane through the axis of {a} parallel to the axis of {b}",
                    SHOULDER,
                )
                about = frozenset((a,))
            normal = normal / np.linalg.norm(normal)
            # a centre on the second axis, when that axis lies in the plane, is in it by
            # that alone (a wrist whose first axis coincides with its last puts the point
            # where its last two meet on its first): no fact of the plane; on the first
            # axis it is one (the shoulder of an arm without shoulder offset); the output
            # point is on the second axis by no construction
            if (
                not own
                and abs(np.dot(pb - pa, normal)) < tol * scale
                and np.linalg.norm(np.cross(W - pb, ub)) < tol * scale
            ):
                continue
            if abs(np.dot(W - pa, normal)) < tol * scale:
                if own:
                    out[f"the output point is in {where}"] = (kind, about)
                    continue
                centre = "the wrist centre" if len(members) == 3 else "the wrist point"
                out[f"{centre} (where {who} meet) is in {where}"] = (kind, about)
    return out


def name_of(kinds: Sequence[str | None], leg: bool = False, corank: int = 1) -> str | None:
    """The name of a singularity whose new facts have these kinds (None: no pattern).

    A chain that loses one direction gets one name, the first of shoulder, elbow, wrist
    its facts show; one that loses ``corank`` directions gets up to that many, joined by
    "and" (an arm stretched with its wrist axes in line: "elbow and wrist")."""
    found = [n for n in (SHOULDER, ELBOW, WRIST) if n in kinds]
    if leg:
        return LEG if ELBOW in found[:1] else None
    return " and ".join(found[: max(1, corank)]) or None


def meaning_of(name: str) -> str | None:
    """What a name given by :func:`name_of` means (a joined name: each part's meaning);
    None for a text that is not such a name."""
    parts = name.split(" and ")
    if not all(part in NAMES for part in parts):
        return None
    return "; ".join(NAMES[part] for part in parts)


def singularity_name(
    here: Sequence[Line],
    generic: Sequence[Line],
    scale: float,
    point: Any = None,
    generic_point: Any = None,
    leg: bool = False,
    moving: Sequence[str] = (),
    corank: int = 1,
) -> str | None:
    """The name of a chain's singularity from its joint lines ``here`` and at a ``generic``
    configuration (the facts that hold there do not count, nor those about an axis whose
    joint is not ``moving`` in the lost motion: a pose's accidental parallels); None where
    no pattern fits."""
    planar = _planar(here)
    new = line_facts(here, point, planar, scale)
    old = line_facts(generic, generic_point, planar, scale)
    moving = set(moving)
    kinds = [k for t, (k, about) in new.items() if t not in old and about <= moving]
    return name_of(kinds, leg, corank)


def _planar(lines: Sequence[Line]) -> bool:
    axes = [u for _, p, u in lines if p is not None]
    if not axes:
        return False
    return all(np.linalg.norm(np.cross(axes[0], a)) < CONDITION_GEOMETRY_RTOL for a in axes)


def named(meaning: str | None) -> str | None:
    """The name a meaning written by :func:`name_of`'s caller starts with (``"elbow: ..."``),
    else None."""
    if meaning is None:
        return None
    head = meaning.split(": ", 1)[0]
    return head if meaning_of(head) is not None and head != meaning else None
