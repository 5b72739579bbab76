"""Spatial parallel mechanisms on legs (a 3-RPS, Tsai's 3-UPU, a Delta): each leg's
constraint written on the platform's pose in Study coordinates (:mod:`.spatial`), a small
polynomial system solved by homotopy continuation (Bertini 2, the ``modes`` extra).

A leg runs from the base to the output's body (the platform).  The bodies the base
reaches through given joints (a Delta's driven arms: given R or P joints) are known; what
remains of each leg is a *piece*: a rigid body (bodies joined by given slides are one)
joined to a known body by one unknown joint and to the platform by another.  With
``p = R b + t`` where the pose carries the platform joint's centre ``b`` and ``a`` the
other joint's centre, a piece constrains the pose by

* ``S-S`` (a Delta's rods, a rod between two ball joints) and ``U-S`` (a U-P-S leg):
  ``|p - a|^2 = l^2``, one quadric (Husty's);
* ``R-S`` (a 3-RPS leg): the same sphere and the plane ``n.p = n.b_q`` normal to the R
  axis ``n``, two quadrics;
* ``U-U`` (a U-P-U leg whose cross axes lie normal to the leg, the inner ones parallel:
  Tsai's conditions): the sphere and ``(s1 x (p - a)).(R s4) = 0`` (the inner axis, along
  ``s1 x (p - a)``, normal to the platform's axis ``s4``), a quadric and a quartic.

Six equations in all (else the formulation does not apply), with the Study quadric and a
random affine patch: eight in the eight Study coordinates, tracked from a linear-product
start where it has fewer paths than the total degree (:func:`~.spatial.track_study`:
Tsai's 3-UPU 412 paths, not 1024).  A mode is a platform pose; each piece's joints then follow in closed form (the U
joints up to their half-turn flip, counted in ``equivalent_solutions``; an S-S rod with no
spin about its own axis, which is idle).  A real endpoint where the system is singular
gets the local dimension test: on a curve there is no count, only ``infinite``.

Owns :class:`Piece`, :func:`pieces` and :data:`FORMULATION`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import mpmath
import sympy

from mechsing.assembly.chains import Found
from mechsing.assembly.given import NO_INPUTS, Formulation, Given
from mechsing.assembly.settings import MODE_CERTIFY_RADIUS
from mechsing.errors import FormulationError
from mechsing.model import Mechanism
from mechsing.numeric import MODE_MATCH_DISTANCE

__all__ = ["FORMULATION", "Piece", "pieces"]

#: the equations each kind of piece writes on the platform's pose
_EQUATIONS = {"SS": 1, "US": 1, "RS": 2, "UU": 2}

#: the most poses (complex, finitely many) of a platform on these pieces, published: six
#: distances (the Stewart-Gough platform: M. Raghavan, ASME J. Mech. Des. 115, 1993; M.
#: Husty, Mech. Mach. Theory 31(4), 1996), three R-S pieces (the 3-RPS: C. Innocenti and
#: V. Parenti-Castelli, ASME J. Mech. Des. 112, 1990)
_MAXIMA = {
    "six distances": (40, "Raghavan 1993, Husty 1996"),
    "three R-S pieces": (16, "Innocenti and Parenti-Castelli 1990"),
}


def _maximum(found: tuple[Piece, ...]) -> tuple[int, str] | None:
    kinds = sorted(p.kind for p in found)
    if len(kinds) == 6 and set(kinds) <= {"SS", "US"}:
        return _MAXIMA["six distances"]
    if kinds == ["RS"] * 3:
        return _MAXIMA["three R-S pieces"]
    return None


@dataclass(frozen=True)
class Piece:
    """One unknown part of a leg: ``kind`` (``SS``, ``US``, ``RS``, ``UU``: its two unknown
    joints' types), ``inner`` the joint to the known body and ``outer`` the one to the
    platform (names, and +1 or -1 where the file writes them the other way round),
    ``slides`` the given slides inside it, and, at the known body's pose with the inner
    joint at 0 (sympy, exact): ``a`` the inner joint's centre, ``axes`` its axes, ``bq``
    the outer joint's centre, ``outer_axes`` its axes; ``b`` the outer joint's centre on
    the platform at the reference; ``known`` the known body's rotation."""

    kind: str
    inner: tuple[str, int]
    outer: tuple[str, int]
    slides: tuple[str, ...]
    a: sympy.Matrix
    axes: tuple[sympy.Matrix, ...]
    bq: sympy.Matrix
    outer_axes: tuple[sympy.Matrix, ...]
    b: sympy.Matrix
    known: sympy.Matrix
    equations: tuple[sympy.Expr, ...] = field(default=())


def _rotation(n: Any, q: Any) -> sympy.Matrix:
    """Rodrigues' rotation by ``q`` about the unit ``n`` (sympy, exact)."""
    x, y, z = n
    c, s = sympy.cos(q), sympy.sin(q)
    K = sympy.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return sympy.eye(3) + s * K + (1 - c) * K * K


def _known_poses(
    mech: Mechanism, given: dict[str, tuple[Any, ...]], base: str, out: str
) -> dict[str, tuple[sympy.Matrix, sympy.Matrix]]:
    """Each body the base reaches through given R and P joints, with its pose (R, t)."""
    poses = {base: (sympy.eye(3), sympy.zeros(3, 1))}
    todo = [base]
    while todo:
        body = todo.pop()
        Rb, tb = poses[body]
        for j in mech.joints:
            if j.name not in given or body not in j.between:
                continue
            other = j.between[1] if j.between[0] == body else j.between[0]
            if other in poses:
                continue
            if other == out:
                raise FormulationError(f"the given joint {j.name} moves the platform itself")
            sign = 1 if j.between[0] == body else -1
            q = sign * given[j.name][0]
            if j.type == "R":
                Rj = _rotation(j.params["axis"], q)
                c = sympy.Matrix(j.params["point"])
                tj = c - Rj * c
            elif j.type == "P":
                Rj, tj = sympy.eye(3), sympy.Matrix(j.params["axis"]) * q
            else:
                raise FormulationError(f"the given joint {j.name} is a {j.type}, not R or P")
            poses[other] = (Rb * Rj, Rb * tj + tb)
            todo.append(other)
    return poses


def pieces(mech: Mechanism, given: dict[str, tuple[Any, ...]]) -> tuple[Piece, ...]:
    """The pieces of ``mech``'s legs for the ``given`` values (FormulationError: why the
    mechanism is not a platform on legs this formulation writes)."""
    if mech.output is None:
        raise FormulationError("no output body (the platform)")
    out, base = mech.output.body, mech.output.relative_to
    if not mech.legs or len(mech.legs) < 2:
        raise FormulationError(f"{out} is not held by legs")
    if {n for leg in mech.legs for n in leg.joints} != {j.name for j in mech.joints}:
        raise FormulationError(f"some joints are on no leg from {base} to {out}")
    known = _known_poses(mech, given, base, out)
    unknown = [j for j in mech.joints if j.name not in given]
    found = []
    seen: set[str] = set()
    for j in unknown:
        if j.name in seen or not (set(j.between) & set(known)):
            continue
        found.append(_piece(mech, given, known, out, j))
        seen.update((found[-1].inner[0], found[-1].outer[0]))
    missing = [j.name for j in unknown if j.name not in seen]
    if missing:
        raise FormulationError(
            f"joints {', '.join(missing)} are not on a piece between a known body and {out}"
        )
    return tuple(found)


def _piece(
    mech: Mechanism,
    given: dict[str, tuple[Any, ...]],
    known: dict[str, tuple[sympy.Matrix, sympy.Matrix]],
    out: str,
    inner: Any,
) -> Piece:
    """The piece whose inner joint is ``inner`` (it joins a known body to the piece)."""
    k_body = inner.between[0] if inner.between[0] in known else inner.between[1]
    body = inner.between[1] if k_body == inner.between[0] else inner.between[0]
    if body in known or body == out:
        raise FormulationError(f"joint {inner.name} joins two known bodies or the platform")
    shift, slides, cur = sympy.zeros(3, 1), [], body
    while True:  # along given slides to the body the outer joint holds
        nxt = [j for j in mech.joints if cur in j.between and j.name != inner.name]
        nxt = [j for j in nxt if j.name not in slides]
        if len(nxt) != 1:
            raise FormulationError(
                f"body {cur} is not a link of a chain from a known body to {out}"
            )
        j = nxt[0]
        other = j.between[1] if j.between[0] == cur else j.between[0]
        if j.name in given:
            if j.type != "P":
                raise FormulationError(f"the given joint {j.name} inside a leg is not a slide")
            sign = 1 if j.between[0] == cur else -1
            shift += sympy.Matrix(j.params["axis"]) * sign * given[j.name][0]
            slides.append(j.name)
            cur = other
            continue
        if other != out:
            raise FormulationError(f"joint {j.name} does not reach {out}")
        outer = j
        break
    kind = inner.type + outer.type
    if kind not in _EQUATIONS:
        raise FormulationError(
            f"the leg piece {inner.name}...{outer.name} is {inner.type}-{outer.type}; the "
            "formulation writes S-S, U-S, R-S and U-U pieces"
        )
    Rk, tk = known[k_body]
    isign = 1 if inner.between[0] == k_body else -1
    osign = 1 if outer.between[1] == out else -1
    if "U" in kind and (isign < 0 or (outer.type == "U" and osign < 0)):
        raise FormulationError(f"a U joint of {inner.name}...{outer.name} is written outwards-in")
    a = Rk * sympy.Matrix(inner.params["point"]) + tk
    b = sympy.Matrix(outer.params["point"])
    bq = Rk * (b + shift) + tk
    axes = _axes(inner, Rk)
    outer_axes = _axes(outer, Rk)
    piece = Piece(
        kind,
        (inner.name, isign),
        (outer.name, osign),
        tuple(slides),
        a,
        axes,
        bq,
        outer_axes,
        b,
        Rk,
    )
    return _with_equations(piece)


def _axes(joint: Any, Rk: sympy.Matrix) -> tuple[sympy.Matrix, ...]:
    if joint.type == "R":
        return (Rk * sympy.Matrix(joint.params["axis"]),)
    if joint.type == "U":
        return tuple(Rk * sympy.Matrix(v) for v in joint.params["axes"])
    return ()


def _zero(x: Any) -> bool:
    return sympy.simplify(x) == 0


def _with_equations(p: Piece) -> Piece:
    """The piece with its equations on the Study coordinates."""
    from mechsing.assembly.spatial import XS, distance_equation, moved_direction, moved_point

    w0 = p.bq - p.a
    l2 = sympy.nsimplify(sympy.expand(w0.dot(w0)))
    eqs = [distance_equation(p.a, p.b, l2)]
    delta = sum(x * x for x in XS)
    if p.kind == "RS":
        n = p.axes[0]
        P = moved_point(p.b)
        eqs.append(sympy.expand(sum(n[i] * P[i] for i in range(3)) - n.dot(p.bq) * delta))
    elif p.kind == "UU":
        s1, s2 = p.axes
        # the known side's stored axes are the inner U's; the outer U's are at the
        # reference (its second axis fixed in the platform, its first in the piece)
        s3 = p.outer_axes[0]
        s4 = sympy.Matrix(p.outer_axes[1])
        conditions = {
            "the inner U's axes are normal": s1.dot(s2),
            "the inner cross axis is normal to the leg": s2.dot(w0),
            "the outer U's axes are normal": s3.dot(s4),
            "the cross axes are parallel": (s2.cross(s3)).norm(),
        }
        broken = [k for k, v in conditions.items() if not _zero(v)]
        if broken:
            raise FormulationError(
                f"U-U leg piece {p.inner[0]}...{p.outer[0]}: not written (only where "
                f"{'; '.join(conditions)}): {'; '.join(broken)} fails"
            )
        P = moved_point(p.b)
        w = [P[i] - p.a[i] * delta for i in range(3)]
        v = moved_direction(p.known.T * s4)  # the platform's axis at the reference
        cross = sympy.Matrix(s1).cross(sympy.Matrix(w))
        eqs.append(sympy.expand(sum(cross[i] * v[i] for i in range(3))))
    return Piece(
        *[getattr(p, f) for f in Piece.__dataclass_fields__ if f != "equations"],
        equations=tuple(eqs),
    )


def _applies(given: Given) -> str | None:
    if given.values is None:
        return NO_INPUTS
    if given.family.kind not in ("spatial", "translational"):
        return f"the mechanism is {given.family.kind}: its loops' subgroup writes it"
    try:
        found = pieces(given.mech, given.values)
    except FormulationError as reason:
        return str(reason)
    count = sum(len(p.equations) for p in found)
    if count != 6:
        return f"its legs write {count} equations on the platform's pose, not six"
    given.cache["legs"] = found
    return None


def _mp(v: Any) -> mpmath.matrix:
    return mpmath.matrix([mpmath.mpf(sympy.N(x, mpmath.mp.dps + 5)) for x in v])


def _least_angle(p: Any, q: Any) -> tuple[mpmath.matrix, list[Any]]:
    """The least-angle rotation taking the direction ``p`` onto ``q`` (matrix, vector)."""
    from mechsing.assembly.study import rotation

    p, q = p / mpmath.norm(p), q / mpmath.norm(q)
    axis = mpmath.matrix(
        [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]]
    )
    s = mpmath.norm(axis)
    if s == 0:
        return mpmath.eye(3), [mpmath.mpf(0)] * 3
    angle = mpmath.atan2(s, (p.T * q)[0])
    unit = axis / s
    return rotation(list(unit), angle), [unit[i] * angle for i in range(3)]


def _piece_values(p: Piece, R: Any, t: Any) -> dict[str, list[Any]]:
    """The piece's unknown joints' values at the platform pose (R, t) (mpmath)."""
    from mechsing.assembly.spatial import angle_about, rotation_log, two_axes
    from mechsing.assembly.study import rotation

    a, bq, Rk = _mp(p.a), _mp(p.bq), mpmath.matrix(sympy.N(p.known, mpmath.mp.dps + 5).tolist())
    now = R * _mp(p.b) + t - a
    ref = bq - a
    (inner, isign), (outer, osign) = p.inner, p.outer
    if p.kind == "RS":
        n = _mp(p.axes[0])
        q = angle_about(n, ref, now)
        Rp = rotation(list(n), q) * Rk  # the piece's rotation
        first = [isign * q]
    elif p.kind[0] == "U":
        s1, s2 = (_mp(v) for v in p.axes)
        pairs = two_axes(s1, s2, ref / mpmath.norm(ref), now / mpmath.norm(now))
        if p.kind == "UU":  # the pair whose cross axis stays normal to the platform's axis
            s3, s4 = (_mp(v) for v in p.outer_axes)
            Rs4 = R * (Rk.T * s4)

            def off(pair: Any) -> Any:
                Rp = rotation(list(s1), pair[0]) * rotation(list(s2), pair[1])
                return abs(((Rp * s3).T * Rs4)[0]) + (abs(pair[0]) + abs(pair[1])) * 1e-9

            q1, q2 = min(pairs, key=off)
        else:
            q1, q2 = min(pairs, key=lambda pr: abs(pr[0]) + abs(pr[1]))
        Rp = rotation(list(s1), q1) * rotation(list(s2), q2) * Rk
        first = [q1, q2]
    else:  # S-S: the rod without spin about its own axis, relative to the known body
        Q, vec = _least_angle(Rk.T * ref, Rk.T * now)
        Rp = Rk * Q
        first = [isign * x for x in vec]
    values = {inner: first}
    rel = Rp.T * R  # the platform relative to the piece
    if p.kind == "UU":
        s3, s4 = (Rk.T * _mp(v) for v in p.outer_axes)  # at the reference
        q3 = angle_about(s3, s4, rel * s4)
        q4 = angle_about(s4, s3, rotation(list(s3), q3).T * rel * s3)
        values[outer] = [q3, q4]
    else:
        values[outer] = [osign * x for x in rotation_log(rel)]
    return values


def _find(given: Given) -> Found:
    from mechsing.assembly.certify import krawczyk, local_dimension, newton, regular
    from mechsing.assembly.engine import real_endpoints
    from mechsing.assembly.serial import account, unproven
    from mechsing.assembly.spatial import (
        XS,
        YS,
        off_exceptional,
        patch_equation,
        pose_of,
        study_quadric,
        track_study,
    )

    mech, dps = given.mech, given.dps
    found: tuple[Piece, ...] = given.cache["legs"]
    gens = [*XS, *YS]
    eqs = [*(e for p in found for e in p.equations), study_quadric(), patch_equation()]
    degrees = [sympy.Poly(e, *gens).total_degree() for e in eqs]
    bezout = 1
    for d in degrees:
        bezout *= d
    formulation: dict[str, Any] = {
        "name": "leg constraints on the platform's pose (Study coordinates)",
        "method": "homotopy continuation (Bertini 2, total-degree start), Newton refinement",
        "platform": mech.output.body if mech.output else "",
        "unknowns": [str(v) for v in gens],
        "legs": [
            {
                "kind": "-".join(p.kind),
                "joints": [p.inner[0], *p.slides, p.outer[0]],
                "equations": len(p.equations),
            }
            for p in found
        ],
        "polynomial_degree": max(degrees),
        "bezout": bezout,
    }
    # the quartics of U-U pieces: double precision along the paths (adaptive precision
    # crawls along the many paths to the exceptional quadric; again in adaptive where a few
    # failed, engine.RETRY_FAILED); every endpoint is refined
    raw, tracked, start = track_study(eqs[:-1], "double" if max(degrees) > 2 else "adaptive")
    formulation["method"] = f"homotopy continuation (Bertini 2, {start} start), Newton refinement"
    # an endpoint with |X|^2 = 0 (the exceptional quadric of Study's) is no displacement
    genuine = off_exceptional(raw)
    real = real_endpoints(genuine)
    rows: list[tuple[list[Any], bool]] = []
    poses: list[tuple[Any, Any]] = []
    notes: list[str] = []
    duplicates = singular = 0
    for z in real:
        root = newton(eqs, gens, list(z), dps)
        if root is None or not regular(eqs, gens, root):
            singular += 1
            dim = local_dimension(eqs, gens, list(z), dps)
            if dim > 0:
                formulation["dimension"] = dim
                notes.append(
                    f"the given values are reached along a set of dimension {dim} of platform "
                    "poses (the local dimension test at a real endpoint): the modes are not "
                    "finitely many"
                )
                paths = account(tracked, raw, genuine, real, rows, duplicates, singular)
                return Found(
                    formulation, [], None, "infinite", paths, tuple(notes), 1, given.closure
                )
            if root is None:
                continue
        R, t = pose_of(root)
        if any(
            mpmath.norm(R - R2) + mpmath.norm(t - t2) <= MODE_MATCH_DISTANCE for R2, t2 in poses
        ):
            duplicates += 1
            continue
        poses.append((R, t))
        values: dict[str, list[Any]] = {
            n: [mpmath.mpf(sympy.N(x, dps + 5)) for x in v] for n, v in given.values.items()
        }
        for p in found:
            values.update(_piece_values(p, R, t))
        row = [values[name][i] for name, i in mech.coordinates()]
        ok = krawczyk(eqs, gens, root, mpmath.mpf(MODE_CERTIFY_RADIUS))
        rows.append((row, ok))
    paths = account(tracked, raw, genuine, real, rows, duplicates, singular)
    equivalent = 2 ** sum(1 for p in found if p.kind[0] == "U")
    if any(p.kind == "SS" for p in found):
        notes.append(
            "each rod between two ball joints spins idly about its own axis: one joint "
            "vector per platform pose is listed, the rods without spin"
        )
    complete = _proven(eqs, gens, found, genuine, rows, dps, notes)
    if complete != "proven":
        notes.append(
            f"continuation found {len(genuine)} solution{'' if len(genuine) == 1 else 's'} "
            f"(real and complex, off the exceptional quadric |X|^2 = 0) on {tracked} paths; "
            f"{unproven(paths)}"
        )
    return Found(
        formulation, rows, len(rows), complete, paths, tuple(notes), equivalent, given.closure
    )


def _proven(
    eqs: list[sympy.Expr],
    gens: list[sympy.Symbol],
    found: tuple[Piece, ...],
    genuine: list[Any],
    rows: list[tuple[list[Any], bool]],
    dps: int,
    notes: list[str],
) -> str:
    """``proven`` when the solutions number the published most for these pieces and each
    is certified in its own box (:func:`~mechsing.assembly.certify.certified_roots`, the
    boxes pairwise disjoint): none is missing, and the real ones are the modes."""
    from mechsing.assembly.certify import every_solution

    most = _maximum(found)
    if most is None or len(genuine) != most[0] or not all(ok for _, ok in rows):
        return "not proven"
    if not every_solution(eqs, gens, genuine, dps, len(rows)):
        return "not proven"
    notes.append(
        f"all {most[0]} solutions (real and complex) of the published most for these legs "
        f"({most[1]}) found, each certified in its own box: no mode is missing"
    )
    return "proven"


FORMULATION = Formulation("leg constraints of a platform on legs", _applies, _find)
