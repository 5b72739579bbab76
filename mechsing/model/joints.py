"""Reading the joints of a mechanism file: :class:`JointReader` checks each joint's
name, type (the subgroup catalog's, or U), the two bodies it connects and its geometric
parameters (directions normalised, points and pitches in SI units, their written
resolution recorded), and refuses a mechanism of no sensible size.
"""

from __future__ import annotations

import ast
from typing import Any

from mechsing.model.configurations import RESERVED_CONFIGURATION_KEYS
from mechsing.model.loads import LOAD_KEY
from mechsing.model.mechanism import POSE_KEY, U_JOINT, Joint
from mechsing.model.reading import Reader, few, float_root, show_vector
from mechsing.numeric import MAX_NUMBER, NEAR_ZERO_VECTOR
from mechsing.numeric.numbers import is_sensible_size
from mechsing.numeric.pirational import evalf_float
from mechsing.yamlnodes import YMap, YSeq, YValue

__all__ = ["JOINT_BASE_KEYS", "MAX_JOINTS", "U_KEYS", "JointReader"]

JOINT_BASE_KEYS = ("name", "type", "between")
U_KEYS = (("axes", "axes"), ("point", "point"))
#: most joints in one file
MAX_JOINTS = 4000


class JointReader:
    """The ``joints`` list of a file, read through ``r`` with the subgroup ``catalog``
    (joint type -> :class:`~mechsing.subgroups.SubgroupType`)."""

    def __init__(self, r: Reader, catalog: dict[str, Any]) -> None:
        self.r = r
        self.catalog = catalog

    def joints(self, v: YValue | None, bodies: list[str]) -> list[Joint]:
        r = self.r
        seq = r.sequence(
            v,
            "joints",
            "joints",
            "joints: [{name: A, type: R, between: [ground, crank], axis: [0, 0, 1], "
            "point: [0, 0, 0]}]",
        )
        if len(seq.items) > MAX_JOINTS:
            raise r.error("joints", seq.line, f"{len(seq.items)} joints, more than {MAX_JOINTS}")
        bodyset = set(bodies)
        out: list[Joint] = []
        seen: dict[str, int] = {}
        for e in seq.items:
            j = self.joint(e, bodyset)
            if j.name in seen:
                raise r.error(
                    f"joint {j.name!r}",
                    e.line,
                    f"defined twice (first at line {seen[j.name]}); give each joint a "
                    "different name",
                )
            seen[j.name] = e.line
            out.append(j)
        for j in out:
            hb = j.hidden_body
            if hb and hb in bodyset:
                raise r.error(
                    f"body {hb!r}",
                    j.line,
                    f"clashes with the hidden body of U joint {j.name!r}; rename the body",
                )
        self.check_size(out, seq.line)
        return out

    def check_size(self, joints: list[Joint], line: int) -> None:
        """A mechanism whose every joint point lies within 1/MAX_NUMBER m of the origin (but
        not all at it) is of no sensible size: its residuals would underflow."""
        size = max(
            (
                abs(evalf_float(c, 17))
                for j in joints
                if "point" in j.params
                for c in j.params["point"]
            ),
            default=0.0,
        )
        if 0.0 < size and not is_sensible_size(1 / size):
            raise self.r.error(
                "joints",
                line,
                f"every joint point lies within {size:.3g} m of the origin: too small a "
                f"mechanism (some point must be at least {1 / MAX_NUMBER:g} m from it); check "
                "the lengths and their unit",
            )

    def joint(self, e: YValue, bodyset: set[str]) -> Joint:
        r = self.r
        m = r.mapping(e, "joints", "each joint")
        nv = m.get("name")
        if nv is None:
            raise r.error("joint", m.line, "missing key 'name'; give every joint a name")
        name = r.name(nv, "joint", "the joint name")
        item = f"joint {name!r}"
        if "[" in name or "]" in name:
            raise r.error(
                item,
                nv.line,
                "a joint name may not contain '[' or ']' (they select "
                "coordinates in inputs); rename it",
            )
        if name in RESERVED_CONFIGURATION_KEYS:
            what = {
                "start": "the start configuration",
                POSE_KEY: "the output body's pose",
                LOAD_KEY: "the load on the output",
            }[name]
            raise r.error(
                item,
                nv.line,
                f"{name!r} is reserved in configurations ({what}); rename the joint",
            )
        tv = m.get("type")
        if tv is None:
            raise r.error(item, m.line, f"missing key 'type'; give one of {self.type_list()}")
        jtype = r.name(tv, item, "type")
        if jtype == U_JOINT:
            geo: tuple[tuple[str, str], ...] = U_KEYS
            stype = None
        elif jtype in self.catalog:
            stype = self.catalog[jtype]
            geo = tuple(stype.parameters)
        else:
            same = [t for t in (*self.catalog, U_JOINT) if t.lower() == jtype.lower()]
            hint = f" (did you mean {same[0]!r}? types are case-sensitive)" if same else ""
            raise r.error(
                item, tv.line, f"unknown joint type {jtype!r}{hint}; use one of {self.type_list()}"
            )
        geo_keys = tuple(k for k, _ in geo)
        allowed = JOINT_BASE_KEYS + geo_keys
        for k, _ in m.items:
            if k.text not in allowed:
                takes = ", ".join(geo_keys) if geo_keys else "no geometric key"
                raise r.error(
                    item,
                    k.line,
                    f"key {k.text!r} does not belong to a joint of type {jtype} ({jtype} takes "
                    f"{takes}); remove it or fix its name",
                )
        for k in ("between",) + geo_keys:
            if m.get(k) is None:
                raise r.error(
                    item,
                    m.line,
                    f"missing key {k!r} (a joint of type {jtype} needs "
                    f"{', '.join(('between',) + geo_keys)}); add it",
                )
        bv = m.get("between")
        if not isinstance(bv, YSeq) or len(bv.items) != 2:
            raise r.error(
                item, bv.line, "between must be a list of two bodies, e.g. between: [ground, crank]"
            )
        a = r.name(bv.items[0], item, "between[0]")
        b = r.name(bv.items[1], item, "between[1]")
        for x, node in ((a, bv.items[0]), (b, bv.items[1])):
            if x not in bodyset:
                raise r.error(
                    item,
                    node.line,
                    f"unknown body {x!r}; add it to bodies or use one of {few(sorted(bodyset))}",
                )
        if a == b:
            raise r.error(
                item,
                bv.line,
                f"connects body {a!r} to itself; a joint is between two different bodies",
            )
        if jtype == U_JOINT:
            params = self.u_params(m, item)
            return Joint(name, U_JOINT, (a, b), params, m.line, 2, ("rad", "rad"))
        assert stype is not None
        params = {}
        for key, kind in geo:
            params[key] = self.param(m, item, jtype, key, kind, key in stype.nonzero)
        units = tuple(u for _, u in stype.coordinates)
        return Joint(name, jtype, (a, b), params, m.line, stype.dimension, units)

    def type_list(self) -> str:
        return ", ".join(list(self.catalog) + [U_JOINT])

    def param(self, m: YMap, item: str, jtype: str, key: str, kind: str, nonzero: bool) -> Any:
        r = self.r
        v = m.get(key)
        # the written resolution of each entry (a direction's before it is normalised)
        factor = 1 if kind in ("direction", "normal") else r.units.length_factor
        nodes = v.items if isinstance(v, YSeq) else (v,)
        for i, node in enumerate(nodes):
            res, digits = r.resolution(node, factor)
            if res:
                name = ast.literal_eval(item.split(" ", 1)[1])  # item is f"joint {name!r}"
                r.geometry.append((name, key, i, res, digits))
        if kind in ("direction", "normal"):
            unit, changed = r.direction(v, item, key)
            if changed:
                r.notes.append(
                    f"{key} of joint {item.split(' ', 1)[1]} normalised to {show_vector(unit)}"
                )
            return unit
        if kind == "point":
            return r.vector(v, item, key, r.units.length_factor)
        if kind == "pitch":
            h = r.number(v, item, key, r.units.length_factor)
            if nonzero and h == 0:
                alt = {"H": "R", "Y": "G"}.get(jtype)
                fix = f"use type {alt}" if alt else "give a non-zero pitch"
                raise r.error(
                    item,
                    v.line,
                    f"a joint of type {jtype} needs a non-zero pitch; with pitch 0 {fix}",
                )
            return h
        raise r.error(item, m.line, f"the catalog gives parameter {key!r} an unknown kind {kind!r}")

    def u_params(self, m: YMap, item: str) -> dict[str, Any]:
        r = self.r
        av = m.get("axes")
        if not isinstance(av, YSeq) or len(av.items) != 2:
            raise r.error(
                item,
                av.line,
                "axes of a U joint must be a list of two directions "
                "[a1, a2] (a1 fixed in between[0], a2 in between[1])",
            )
        a1, ch1 = r.direction(av.items[0], item, "axes[0]")
        a2, ch2 = r.direction(av.items[1], item, "axes[1]")
        name = item.split(" ", 1)[1]
        if ch1:
            r.notes.append(f"axes[0] of joint {name} normalised to {show_vector(a1)}")
        if ch2:
            r.notes.append(f"axes[1] of joint {name} normalised to {show_vector(a2)}")
        cross = (
            a1[1] * a2[2] - a1[2] * a2[1],
            a1[2] * a2[0] - a1[0] * a2[2],
            a1[0] * a2[1] - a1[1] * a2[0],
        )
        s = float_root(sum(c * c for c in cross))
        if s < NEAR_ZERO_VECTOR:  # |a1 x a2| of unit vectors: the sine of their angle
            raise r.error(
                item,
                av.line,
                "the two axes of a U joint are parallel; a U joint needs two "
                "intersecting, non-parallel axes (usually perpendicular)",
            )
        point = r.vector(m.get("point"), item, "point", r.units.length_factor)
        return {"axes": (a1, a2), "point": point}
