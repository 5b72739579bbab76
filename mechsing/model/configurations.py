"""Reading the configurations of a mechanism file: :class:`ConfigurationReader` reads
each configuration's joint values (numbers, lists, displacements) in SI units and
radians with their written resolution, the output body's pose, the ``start`` chain, and
the unit trap of angles (radians in a degree file, more than a full turn in a radian
file).
"""

from __future__ import annotations

from typing import Any

from mechsing.model.expressions import is_plain_decimal, radian_power
from mechsing.model.loads import LOAD_KEY, read_load
from mechsing.model.mechanism import (
    POSE_KEY,
    Configuration,
    Displacement,
    Joint,
    Output,
    OutputPose,
)
from mechsing.model.reading import Reader, few
from mechsing.numeric import REFERENCE_SCREEN_RTOL
from mechsing.numeric.lazy import sympy
from mechsing.numeric.pirational import PI, PiRational, evalf_float
from mechsing.yamlnodes import YMap, YScalar, YSeq, YValue

__all__ = [
    "DISPLACEMENT_KEYS",
    "MAX_CONFIGURATIONS",
    "POSE_KEYS",
    "RESERVED_CONFIGURATION_KEYS",
    "ConfigurationReader",
    "radians_in_degree_file",
]

DISPLACEMENT_KEYS = ("rotation", "translation")
#: keys of a configuration's output pose: the reference point's position, and the
#: rotation about it written one way (a matrix, a rotation vector, or axis and angle)
POSE_KEYS = ("position", "rotation", "rotation_vector", "axis", "angle")
#: configuration keys that are not joint names (so no joint may be called so)
RESERVED_CONFIGURATION_KEYS = ("start", POSE_KEY, LOAD_KEY)
#: most configurations in one file
MAX_CONFIGURATIONS = 1000


class ConfigurationReader:
    """The ``configurations`` mapping of a file, read through ``r``; ``output_given`` is
    the file's output (None: a configuration's pose is refused)."""

    def __init__(self, r: Reader, output_given: Output | None) -> None:
        self.r = r
        self.output_given = output_given

    def configurations(self, v: YValue | None, jmap: dict[str, Joint]) -> dict[str, Configuration]:
        r = self.r
        out: dict[str, Configuration] = {}
        if v is None:
            return {"reference": Configuration("reference", {}, None, None)}
        m = r.mapping(v, "configurations", "configurations")
        if len(m.items) > MAX_CONFIGURATIONS:
            raise r.error(
                "configurations",
                m.line,
                f"{len(m.items)} configurations, more than {MAX_CONFIGURATIONS}",
            )
        starts: dict[str, tuple[str, int]] = {}
        if m.get("reference") is None:
            out["reference"] = Configuration("reference", {}, None, None)
        for k, cv in m.items:
            cname = k.text.strip()
            if not cname or k.kind == "null":
                raise r.error("configurations", k.line, "a configuration needs a name")
            item = f"configuration {cname!r}"
            if cv is None or (isinstance(cv, YScalar) and cv.kind == "null"):
                cmap = YMap((), k.line)
            else:
                cmap = r.mapping(cv, item, "a configuration")
            values: dict[str, Any] = {}
            lines: dict[str, int] = {}
            resolution: dict[str, tuple[tuple[float, int], ...]] = {}
            start: str | None = None if cname == "reference" else "reference"
            pose: OutputPose | None = None
            load = None
            for jk, jv in cmap.items:
                if jk.text == LOAD_KEY:
                    load = read_load(r, jv, item, jk.line, self.output_given is not None)
                    continue
                if jk.text == POSE_KEY:
                    if cname == "reference":
                        raise r.error(
                            item,
                            jk.line,
                            "the reference configuration (all joints at identity) has the "
                            "output at its reference pose; give a pose in a new configuration",
                        )
                    pose = self.pose(jv, item, jk.line)
                    continue
                if jk.text == "start":
                    if cname == "reference":
                        raise r.error(
                            item,
                            jk.line,
                            "the reference configuration (all joints at "
                            "identity) has no start; remove it",
                        )
                    start = r.name(jv, item, "start")
                    starts[cname] = (start, jk.line)
                    continue
                if jk.text not in jmap:
                    raise r.error(
                        item,
                        jk.line,
                        f"unknown joint {jk.text!r}; use one of {few(list(jmap))}, start, "
                        f"{POSE_KEY} or {LOAD_KEY}",
                    )
                values[jk.text] = self.value(jv, jmap[jk.text], item)
                lines[jk.text] = jk.line
                written = self.written(jv, jmap[jk.text])
                if any(res for res, _ in written):
                    resolution[jk.text] = written
            if cname == "reference":
                for jn, val in values.items():
                    if not self.near_identity(val, jmap[jn]):
                        raise r.error(
                            item,
                            lines[jn],
                            f"joint {jn!r}: the reference configuration has every "
                            "joint at identity (value 0); give other values in a new "
                            "configuration",
                        )
            if pose is not None and sum(jmap[jn].dof for jn in values) == sum(
                j.dof for j in jmap.values()
            ):
                raise r.error(
                    item,
                    cmap.key_line(POSE_KEY),
                    f"gives every joint value and the output's {POSE_KEY} too: the joint "
                    f"values fix the pose; remove {POSE_KEY} or the values of the joints to "
                    "be solved",
                )
            out[cname] = Configuration(
                cname, values, start, k.line, lines, pose, resolution=resolution, load=load
            )
        for cname, (start, line) in starts.items():
            if start not in out:
                raise r.error(
                    f"configuration {cname!r}",
                    line,
                    f"start names unknown configuration {start!r}; use one of {few(list(out))}",
                )
        for cname in starts:
            chain = [cname]
            cur = out[cname].start
            while cur is not None:
                if cur in chain:
                    cyc = " -> ".join(chain[chain.index(cur) :] + [cur])
                    raise r.error(
                        f"configuration {cname!r}",
                        starts[cname][1],
                        f"the start chain is a cycle ({cyc}); let one of them start from reference",
                    )
                chain.append(cur)
                cur = out[cur].start
        return out

    def pose(self, v: YValue | None, item: str, line: int) -> OutputPose:
        """The output body's pose in a configuration: ``position`` of the output's
        reference point (file lengths) and the rotation about it, as ``rotation`` (a 3x3
        matrix), ``rotation_vector`` or ``axis`` and ``angle`` (file angles)."""
        r = self.r
        out = self.output_given
        if out is None:
            raise r.error(
                item,
                line,
                f"{POSE_KEY} gives the output body's pose, but the file has no output; add "
                "output: {body: NAME} (the body whose pose this is)",
            )
        m = r.mapping(
            v,
            item,
            f"{POSE_KEY} (e.g. {{position: [x, y, z], rotation_vector: [rx, ry, rz]}})",
        )
        r.keys(m, item, POSE_KEYS, hint=f"the output body's {POSE_KEY}")
        what = f"{POSE_KEY} of the output body {out.body!r}"
        if not m.items:
            raise r.error(item, m.line, f"{what}: give position and/or a rotation")
        forms = [k for k in ("rotation", "rotation_vector", "axis") if m.get(k) is not None]
        if len(forms) > 1:
            raise r.error(
                item,
                m.key_line(forms[1]),
                f"{what}: give the rotation one way, not both {forms[0]} and {forms[1]}: "
                "rotation (a 3x3 matrix), rotation_vector, or axis and angle",
            )
        if (m.get("axis") is None) != (m.get("angle") is None):
            has, lacks = ("axis", "angle") if m.get("axis") is not None else ("angle", "axis")
            raise r.error(
                item,
                m.key_line(has),
                f"{what}: {has} needs {lacks} (a rotation by an angle about an axis); add {lacks}",
            )
        position = None
        if m.get("position") is not None:
            position = r.vector(m.get("position"), item, f"{what}: position", r.units.length_factor)
        rotation = rvec = None
        form = None
        af = r.units.angle_factor
        if m.get("rotation") is not None:
            rotation = self.rotation_matrix(
                m.get("rotation"), item, what, " (or write rotation_vector, or axis and angle)"
            )
            form = "matrix"
        elif m.get("rotation_vector") is not None:
            node = m.get("rotation_vector")
            raw = r.vector(node, item, f"{what}: rotation_vector")
            for i, x in enumerate(raw):
                self.angle_in_file_units(node.items[i], x, item, f"{what}: rotation_vector[{i}]")
            rvec = (raw[0] * af, raw[1] * af, raw[2] * af)
            form = "rotation_vector"
        elif m.get("axis") is not None:
            unit, _ = r.direction(m.get("axis"), item, f"{what}: axis")
            raw_angle = r.number(m.get("angle"), item, f"{what}: angle")
            self.angle_in_file_units(m.get("angle"), raw_angle, item, f"{what}: angle")
            angle = raw_angle * af
            rvec = (unit[0] * angle, unit[1] * angle, unit[2] * angle)
            form = "axis_angle"
        resolution = self.pose_written(m, form, rvec)
        return OutputPose(position, rotation, rvec, m.line, form, resolution)

    def pose_written(
        self, m: YMap, form: str | None, rvec: tuple[Any, Any, Any] | None
    ) -> tuple[tuple[float, int], ...]:
        """The resolution (SI, radians) and significant digits of a pose as written, in
        the pose coordinates' order (rx, ry, rz, x, y, z): each position coordinate its
        own; each rotation coordinate a bound on the angle of the rotation the written
        decimals can move: the norm of the rotation vector's resolutions (the rotation's
        differential has norm at most 1), the angle's plus the angle times the unit
        axis's, or the Frobenius norm of a matrix's (sqrt(2) times the angle).  Empty when
        every number is exact."""
        r = self.r

        def entries(node: Any, factor: Any = 1) -> list[tuple[float, int]]:
            items = node.items if isinstance(node, YSeq) else (node,)
            return [r.resolution(e, factor) for e in items if isinstance(e, YScalar)]

        position = [(0.0, 0)] * 3
        if m.get("position") is not None:
            position = entries(m.get("position"), r.units.length_factor)
        rot: list[tuple[float, int]] = []
        bound = 0.0
        if form == "rotation_vector":
            rot = entries(m.get("rotation_vector"), r.units.angle_factor)
            bound = sum(x * x for x, _ in rot) ** 0.5
        elif form == "axis_angle" and rvec is not None:
            axis = m.get("axis")
            (a_res, a_digits) = r.resolution(m.get("angle"), r.units.angle_factor)
            raw = [evalf_float(x, 17) for x in r.vector(axis, "pose", "axis")]
            size = sum(x * x for x in raw) ** 0.5
            rot = [*entries(axis), (a_res, a_digits)]
            angle = sum(evalf_float(x, 17) ** 2 for x in rvec) ** 0.5
            axis_res = sum(x * x for x, _ in rot[:-1]) ** 0.5 / size if size else 0.0
            bound = a_res + angle * axis_res
        elif form == "matrix":
            rot = [e for row in m.get("rotation").items for e in entries(row)]
            bound = sum(x * x for x, _ in rot) ** 0.5
        digits = [d for res, d in rot if res]
        rotation = (bound, min(digits)) if bound and digits else (0.0, 0)
        out = (rotation,) * 3 + tuple(position)
        return out if any(res for res, _ in out) else ()

    def angle_in_file_units(self, node: Any, raw: Any, item: str, what: str) -> None:
        """In a degree file, an angle of a pose written in radians (``pi``, an inverse
        trigonometric function) is an error that gives both fixes, as for joint values."""
        r = self.r
        if r.units.angle != "rad" and radian_power(raw) > 0:
            raise r.error(
                item,
                getattr(node, "line", None),
                radians_in_degree_file(what, node, raw, r.units.angle),
            )

    def rotation_matrix(self, rv: YValue, item: str, what: str, hint: str = "") -> Any:
        """A rotation written as a 3x3 matrix (three rows of three numbers); ``hint`` ends
        the message when it is not one (the other ways to write it, where there are)."""
        r = self.r
        if not isinstance(rv, YSeq) or len(rv.items) != 3:
            raise r.error(
                item,
                rv.line,
                f"{what}: rotation must be a 3x3 matrix "
                f"[[r11, r12, r13], [r21, r22, r23], [r31, r32, r33]]{hint}",
            )
        rows = tuple(
            r.vector(row, item, f"{what}: rotation row {i}") for i, row in enumerate(rv.items)
        )
        return (rows[0], rows[1], rows[2])

    def near_identity(self, val: Any, j: Joint) -> bool:
        """A value is near the identity when it is within :data:`REFERENCE_SCREEN_RTOL`
        of it (radians, rotation entries, lengths relative to the file's largest
        coordinate): the reference configuration may list such values, and the
        analysis decides in its mode whether they are the identity."""
        size = self.r.scale * self.r.units.length_factor

        def small(x: Any, unit: str) -> bool:
            return _within(x, REFERENCE_SCREEN_RTOL * (size if unit == "m" else 1))

        if isinstance(val, Displacement):
            rot = val.rotation or ((1, 0, 0), (0, 1, 0), (0, 0, 1))
            return all(
                small(rot[i][k] - (1 if i == k else 0), "rad") for i in range(3) for k in range(3)
            ) and all(small(x, "m") for x in val.translation or (0, 0, 0))
        return all(small(x, u) for x, u in zip(val, j.units, strict=True))

    def value(self, v: YValue, j: Joint, item: str) -> Any:
        r = self.r
        what = f"value of joint {j.name!r}"
        factors = [r.units.angle_factor if u == "rad" else r.units.length_factor for u in j.units]
        if j.dof == 0:
            raise r.error(
                item, v.line, f"joint {j.name!r} of type {j.type} has no coordinates; remove it"
            )
        if isinstance(v, YMap):
            if j.dof < 2:
                raise r.error(
                    item,
                    v.line,
                    f"{what}: a joint of type {j.type} takes one number, not a displacement",
                )
            r.keys(v, item, DISPLACEMENT_KEYS, hint="a displacement value")
            if not v.items:
                raise r.error(item, v.line, f"{what}: give rotation and/or translation")
            rot = None
            if v.get("rotation") is not None:
                rot = self.rotation_matrix(v.get("rotation"), item, what)
            tr = None
            if v.get("translation") is not None:
                tr = r.vector(
                    v.get("translation"), item, f"{what}: translation", r.units.length_factor
                )
            return Displacement(rot, tr, v.line)
        if isinstance(v, YScalar):
            if j.dof != 1:
                raise r.error(
                    item,
                    v.line,
                    f"{what}: a joint of type {j.type} has {j.dof} coordinates; give a "
                    f"list of {j.dof} numbers (or a displacement)",
                )
            raw = (r.number(v, item, what),)
            self.check_angles(j, (v,), raw, item, (what,))
            return (raw[0] * factors[0] if factors[0] != 1 else raw[0],)
        if isinstance(v, YSeq):
            if len(v.items) != j.dof:
                raise r.error(
                    item,
                    v.line,
                    f"{what}: a joint of type {j.type} has {j.dof} coordinate"
                    f"{'s' if j.dof > 1 else ''}, got {len(v.items)} values",
                )
            labels = tuple(f"{what}[{i}]" for i in range(j.dof))
            raw = tuple(r.number(e, item, labels[i]) for i, e in enumerate(v.items))
            self.check_angles(j, v.items, raw, item, labels)
            return tuple(x * f if f != 1 else x for x, f in zip(raw, factors, strict=True))
        raise r.error(
            item, getattr(v, "line", None), f"{what} must be a number or a list"
        )  # pragma: no cover

    def written(self, v: YValue, j: Joint) -> tuple[tuple[float, int], ...]:
        """The resolution (SI, radians) and significant digits of each coordinate of a
        joint value as written (:meth:`Reader.resolution`): (0, 0) for an expression, a
        named parameter or a displacement."""
        r = self.r
        nodes = v.items if isinstance(v, YSeq) else (v,) if isinstance(v, YScalar) else ()
        if len(nodes) != j.dof:
            return tuple((0.0, 0) for _ in range(j.dof))
        return tuple(
            r.resolution(node, r.units.angle_factor if unit == "rad" else r.units.length_factor)
            for node, unit in zip(nodes, j.units, strict=True)
        )

    def check_angles(
        self,
        j: Joint,
        nodes: tuple[YValue, ...],
        raw: tuple[Any, ...],
        item: str,
        labels: tuple[str, ...],
    ) -> None:
        """The unit trap of angles, on the values as written (before the unit factor).

        In a degree file, an angle written with ``pi`` or an inverse trigonometric
        function is a radian value (:func:`radian_power`): an error that gives both
        fixes.  In a radian file, a plain number above a full turn is probably meant
        in degrees: a warning (an R, C, U, G or X angle; the norm of an S or D
        rotation vector; not the angle of a pitched joint, H or Y, whose many turns
        are ordinary).
        """
        r = self.r
        angles = [i for i, u in enumerate(j.units) if u == "rad"]
        if not angles:
            return
        if r.units.angle != "rad":
            for i in angles:
                if radian_power(raw[i]) > 0:
                    node = nodes[i]
                    raise r.error(
                        item,
                        getattr(node, "line", None),
                        radians_in_degree_file(labels[i], node, raw[i], r.units.angle),
                    )
            return
        if j.type in _PITCHED:
            return
        plain = [
            i for i in angles if isinstance(nodes[i], YScalar) and is_plain_decimal(nodes[i].text)
        ]
        if j.type in _ROTATION_VECTORS:
            if len(plain) == len(angles) and sum(raw[i] ** 2 for i in angles) > FULL_TURN**2:
                shown = ", ".join(nodes[i].text for i in angles)
                norm = float(sympy.N(sympy.sqrt(sum(raw[i] ** 2 for i in angles)), 15))
                r.warn(
                    item,
                    nodes[angles[0]].line,
                    f"{labels[0].rsplit('[', 1)[0]}: the rotation vector [{shown}] turns by "
                    f"{norm:.6g}, more than a full turn (2 pi) in a file whose angles are in "
                    "radians; if its angles are meant in degrees, set units: {angle: deg}",
                )
            return
        for i in plain:
            if abs(raw[i]) > FULL_TURN:
                node = nodes[i]
                in_rad = raw[i] * sympy.pi / 180
                r.warn(
                    item,
                    node.line,
                    f"{labels[i]}: the angle {node.text} is more than a full turn (2 pi) in a "
                    "file whose angles are in radians; if it is meant in degrees, set "
                    f"units: {{angle: deg}} (or write it in radians: {str(in_rad)!r})",
                )


def radians_in_degree_file(label: str, node: Any, raw: Any, unit: str) -> str:
    """The message for an angle written in radians (with ``pi`` or an inverse
    trigonometric function) in a file whose angles are in degrees."""
    text = node.text if isinstance(node, YScalar) else str(raw)
    as_deg = float(sympy.N(raw * 180 / sympy.pi, 15))
    read = float(sympy.N(raw, 15))
    return (
        f"{label}: {text!r} is an angle in radians (pi, asin, acos, atan "
        f"and atan2 give radians), but this file's angles are in degrees "
        f"(units: {{angle: {unit}}}), so it would be read as "
        f"{read:.6g} degrees; write the value in degrees (e.g. {as_deg:.6g}), "
        "or set units: {angle: rad} and write every angle of the file in radians"
    )


#: a full turn (rad): a plain angle above it in a radian file gets a warning
FULL_TURN = 2 * PI
#: pitched joints: their angle is tied to a slide, many turns are ordinary
_PITCHED = ("H", "Y")
#: joints whose angular coordinates form a rotation vector (its norm is the angle)
_ROTATION_VECTORS = ("S", "D")


def _within(x: Any, bound: float) -> bool:
    """``|x| <= bound`` for one of the file's numbers (a PiRational, or a sympy value
    compared at 30 digits)."""
    if x == 0:
        return True
    if isinstance(x, PiRational):
        return bool(abs(x) <= bound)
    return bool(abs(sympy.N(x, 30)) <= bound)
