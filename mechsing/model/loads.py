"""The load of a configuration: the wrench the environment applies to the output body.

A configuration may give ``load: {force: [fx, fy, fz], moment: [mx, my, mz], point:
[x, y, z]}``: the force (N) and the moment about ``point`` (N times the file's length
unit) in ground axes; ``point`` is a point of the output body given where it is in the
drawn (reference) pose, so it moves with the body, in the file's length unit (default:
the output's reference point).  Omitted force or moment is zero.  ``load`` is reserved
in configurations like ``start`` and ``pose``.  The statics (:mod:`mechsing.statics`)
read it; the values here are exact, in SI.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["LOAD_KEY", "LOAD_KEYS", "Load", "read_load"]

#: the configuration key of the load
LOAD_KEY = "load"
#: the keys of a load
LOAD_KEYS = ("force", "moment", "point")


@dataclass(frozen=True)
class Load:
    """A wrench the environment applies to the output body, in SI (exact or float
    numbers): ``force`` (N), ``moment`` (N m) about ``point`` (m, in the reference pose,
    moving with the output body; None: the output's reference point)."""

    force: tuple[Any, Any, Any] = (0, 0, 0)
    moment: tuple[Any, Any, Any] = (0, 0, 0)
    point: tuple[Any, Any, Any] | None = None
    line: int | None = None


def read_load(r: Any, v: Any, item: str, line: int, has_output: bool) -> Load:
    """The ``load`` of a configuration from its file node; ``r`` is the loader's reader
    (its ``mapping``, ``keys``, ``vector`` and ``units``)."""
    if not has_output:
        raise r.error(
            item,
            line,
            f"{LOAD_KEY} is a wrench applied to the output body, but the file has no output; "
            "add output: {body: NAME}",
        )
    m = r.mapping(v, item, f"{LOAD_KEY} (e.g. {{force: [0, 0, -10], point: [1, 0, 0]}})")
    r.keys(m, item, LOAD_KEYS, hint="the wrench the environment applies to the output")
    if m.get("force") is None and m.get("moment") is None:
        raise r.error(
            item,
            m.line,
            f"{LOAD_KEY}: give force and/or moment (a point alone is no load), e.g. "
            "{force: [0, 0, -10], point: [1, 0, 0]}",
        )
    lf = r.units.length_factor
    force = (0, 0, 0)
    moment = (0, 0, 0)
    point = None
    if m.get("force") is not None:
        force = r.vector(m.get("force"), item, f"{LOAD_KEY}: force (N)")
    if m.get("moment") is not None:
        moment = r.vector(m.get("moment"), item, f"{LOAD_KEY}: moment (N times length)", lf)
    if m.get("point") is not None:
        point = r.vector(m.get("point"), item, f"{LOAD_KEY}: point", lf)
    return Load(force, moment, point, line)


#: the top-level keys of the bodies' weights
WEIGHT_KEYS = ("mass", "gravity")
#: the keys of one body's ``mass`` entry
MASS_KEYS = ("kg", "centre", "inertia")
#: the order of an inertia's six numbers
INERTIA_ORDER = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")


@dataclass(frozen=True)
class Weights:
    """The bodies' masses: ``gravity`` (m/s^2, SI, ground axes; None: the file gives none,
    the bodies have inertia for the dynamics and no weight) and per body its mass (kg) and
    centre of mass (SI, in the drawn pose, moving with the body; None: the centroid of the
    body's joint points); ``inertias``: per body that gives one, its inertia about the
    centre of mass (kg m^2, ground axes at the drawn pose, a 3x3 tuple of rows, exact or
    float numbers); a body without one is a point mass."""

    gravity: tuple[Any, Any, Any] | None
    masses: tuple[tuple[str, Any, tuple[Any, Any, Any] | None], ...]
    inertias: tuple[tuple[str, tuple[tuple[Any, ...], ...]], ...] = ()

    @property
    def weighs(self) -> bool:
        """Whether the bodies weigh (the file gives gravity): the statics hold the weights."""
        return self.gravity is not None


def mass_centre(mech: Any, body: str, centre: Any) -> tuple[Any, Any, Any]:
    """A body's centre of mass in the drawn pose (exact numbers): the file's ``centre``,
    else the centroid of the points of the body's joints (the origin without any)."""
    if centre is not None:
        return centre
    pts = [j.params["point"] for j in mech.joints if body in j.between and "point" in j.params]
    if not pts:
        return (0, 0, 0)
    return tuple(sum(p[i] for p in pts) / len(pts) for i in range(3))  # type: ignore[return-value]


def read_weights(r: Any, mass: Any, gravity: Any, bodies: list[str], ground: str) -> Weights | None:
    """The file's ``mass: {BODY: {kg: M, centre: [x, y, z], inertia: [...]}}`` and
    ``gravity: [gx, gy, gz]`` (the file's length unit per s^2) as :class:`Weights` (None
    without ``mass``).  ``gravity`` may be left out only when some body gives its inertia
    (the masses are then for the dynamics: docs/dynamics.md)."""
    if mass is None:
        if gravity is not None:
            raise r.error(
                "gravity",
                gravity.line,
                "gravity without mass weighs nothing; add mass: {BODY: {kg: M, centre: "
                "[x, y, z]}} or remove gravity",
            )
        return None
    m = r.mapping(mass, "mass", "mass (e.g. {crank: {kg: 2, centre: [0.5, 0, 0]}})")
    out = []
    inertias = []
    for k, v in m.items:
        body = k.text
        if body not in bodies:
            raise r.error("mass", k.line, f"unknown body {body!r}; use one of {', '.join(bodies)}")
        if body == ground:
            raise r.error(
                "mass", k.line, f"{body!r} is the ground: its weight does no work; remove it"
            )
        e = r.mapping(v, f"mass of {body!r}", "a body's mass ({kg: M, centre: [x, y, z]})")
        r.keys(
            e,
            f"mass of {body!r}",
            MASS_KEYS,
            ("kg",),
            hint="kg, the centre of mass and the inertia about it",
        )
        kg = r.number(e.get("kg"), f"mass of {body!r}", "kg")
        if not kg >= 0:
            raise r.error(f"mass of {body!r}", e.line, f"kg must not be negative, got {kg}")
        centre = None
        if e.get("centre") is not None:
            centre = r.vector(e.get("centre"), f"mass of {body!r}", "centre", r.units.length_factor)
        out.append((body, kg, centre))
        if e.get("inertia") is not None:
            inertias.append((body, read_inertia(r, e.get("inertia"), body)))
    if gravity is None and not inertias:
        raise r.error(
            "mass",
            mass.line,
            "mass needs gravity, the acceleration of gravity in ground axes (the file's "
            "length unit per s^2), e.g. gravity: [0, 0, -9.81] (or, for the dynamics "
            "without weights, the bodies' inertia)",
        )
    g = None if gravity is None else r.vector(gravity, "gravity", "gravity", r.units.length_factor)
    return Weights(g, tuple(out), tuple(inertias))


def read_inertia(r: Any, v: Any, body: str) -> tuple[tuple[Any, ...], ...]:
    """A body's ``inertia``: six numbers ``[ixx, iyy, izz, ixy, ixz, iyz]`` or a 3x3 matrix
    (kg times the file's length unit squared, about the centre of mass, ground axes at the
    drawn pose), as a 3x3 tuple in SI; refused when it is not a rigid body's (not
    symmetric, not positive semi-definite, principal moments breaking the triangle
    inequality)."""
    item = f"mass of {body!r}"
    what = "inertia"
    lf2 = r.units.length_factor**2
    from mechsing.yamlnodes import YSeq

    shape = f"{what} must be a list of 6 numbers [{', '.join(INERTIA_ORDER)}] or a 3x3 matrix"
    if not isinstance(v, YSeq):
        got = v.describe() if v is not None else "nothing"
        raise r.error(item, getattr(v, "line", None), f"{shape}, got {got}")
    items = list(v.items)
    if len(items) == 6 and not any(isinstance(x, YSeq) for x in items):
        xx, yy, zz, xy, xz, yz = (
            r.number(x, item, f"{what} {n}", lf2) for x, n in zip(items, INERTIA_ORDER, strict=True)
        )
        rows = ((xx, xy, xz), (xy, yy, yz), (xz, yz, zz))
    elif len(items) == 3 and all(isinstance(x, YSeq) for x in items):
        rows = tuple(r.vector(x, item, f"{what} row {i}", lf2) for i, x in enumerate(items))
    else:
        raise r.error(item, v.line, f"{shape}, got {len(items)} entries")
    from mechsing.numeric.inertia import inertia_problem

    problem = inertia_problem(rows)
    if problem:
        raise r.error(item, v.line, f"the inertia of {body!r} {problem}")
    return rows
