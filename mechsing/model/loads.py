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
