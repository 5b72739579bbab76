"""MJCF models (MuJoCo) as mechsing mechanisms, closed loops included.

Owns :func:`read_mjcf`.  The mapping (also in the docs' import page):

* ``<worldbody>`` is the ground; each ``<body>`` is a body; a body without a
  joint is welded to its parent (the two are one body, named after the
  parent); a body with several joints gets one hidden intermediate body per
  extra joint (``BODY.1``, ``BODY.2``...), the joints applied in file order;
* ``hinge`` -> R, ``slide`` -> P, ``ball`` -> S, ``free`` (and
  ``<freejoint>``) -> D, placed at the joint's ``pos`` and ``axis`` in the
  body frame, carried to the ground frame by the bodies' frames at the model's
  initial pose (``qpos0``, every joint at 0), which is the reference
  configuration; ``between`` is ``[parent body, body]``;
* ``<equality><connect body1 body2 anchor>`` (``anchor`` in body1's frame; or
  ``site1``/``site2``) closes a loop with an S joint at the anchor;
  ``<equality><weld body1 body2>`` merges the two bodies (rigid);
* frames: ``pos``, ``quat`` (w x y z), ``axisangle``, ``euler`` (with the
  compiler's ``eulerseq``, default ``xyz``), ``xyaxes``, ``zaxis``; angles in
  the compiler's ``angle`` unit, **degrees unless** ``angle="radian"`` (as
  MuJoCo defines it);
* default classes: ``<default>`` (class ``main``) and nested
  ``<default class="...">``, chosen by an element's ``class`` or the nearest
  ``childclass`` of its bodies, later (inner) values overriding;
* the inputs: the joints named by ``<actuator>`` elements (``joint=``); the
  output: for a serial chain (no connect, no branch), the tip body;
* a hinge or slide ``ref`` is the joint value of the pose drawn in the file, so
  mechsing's joint value (measured from the drawn pose) is ``qpos - ref``, and
  the limits are shifted by ``ref``;
* joint ``range`` (when limited, or with ``autolimits``) -> ``limits`` in the
  file's units.

Refused with a message naming the element and line: ``<include>`` (mechsing
reads one file), ``<equality><joint>``/``<tendon>`` couplings, an unknown
joint type, a connect or weld naming an unknown body, ``coordinate="global"``,
and a connect or weld without the attributes MuJoCo's reference requires of it
(connect: ``body1`` with ``anchor``, or ``site1`` with ``site2``; weld:
``body1``, or ``site1`` with ``site2``).
"""

from __future__ import annotations

import math

import numpy as np

from mechsing.errors import MechanismError
from mechsing.formats.frames import axis_angle, euler, frame, quaternion, xyaxes, zaxis
from mechsing.formats.inertia import body_masses, placed
from mechsing.formats.writer import (
    Bodies,
    JointSpec,
    MechanismSpec,
    joint_name_problem,
    name_problem,
)
from mechsing.formats.xmlsafe import Element, floats, parse, required
from mechsing.numeric import NEAR_ZERO_VECTOR
from mechsing.numeric.numbers import safe_norm, unit_vector

__all__ = ["MJCF_TYPES", "read_mjcf"]

#: MJCF joint type -> mechsing joint type
MJCF_TYPES = {"hinge": "R", "slide": "P", "ball": "S", "free": "D"}
_WORLD = "world"


class _Reader:
    def __init__(self, root: Element, path: str) -> None:
        self.path = path
        self.root = root
        comp = [c for c in root.findall("compiler")]
        attrs: dict[str, str] = {}
        for c in comp:
            attrs.update(c.attrib)
        if attrs.get("coordinate", "local") != "local":
            raise self.err(comp[-1], 'coordinate="global" is not read; use local coordinates')
        self.degree = attrs.get("angle", "degree") == "degree"
        if attrs.get("angle", "degree") not in ("degree", "radian"):
            raise self.err(comp[-1], 'angle must be "degree" or "radian"')
        self.eulerseq = attrs.get("eulerseq", "xyz")
        if len(self.eulerseq) != 3 or any(ch not in "xyzXYZ" for ch in self.eulerseq):
            raise self.err(comp[-1], f"eulerseq {self.eulerseq!r} must be three of x y z X Y Z")
        self.autolimits = attrs.get("autolimits", "true") == "true"
        #: MuJoCo's rule for the bodies' inertia: "auto" (from the geoms when a body has no
        #: <inertial>), "true" (always from the geoms), "false" (never)
        self.inertiafromgeom = attrs.get("inertiafromgeom", "auto")
        # default classes: class -> (parent class, {element tag: attributes})
        self.classes: dict[str, tuple[str | None, dict[str, dict[str, str]]]] = {}
        for d in root.findall("default"):
            self.read_default(d, None)

    def err(self, el: Element, message: str) -> MechanismError:
        return MechanismError(f"{el.where()}: {message}", path=self.path, line=el.line)

    def read_default(self, top: Element, top_parent: str | None) -> None:
        """The classes of a <default> and of the ones nested in it (a stack, not
        recursion), in document order."""
        todo: list[tuple[Element, str | None]] = [(top, top_parent)]
        while todo:
            d, parent = todo.pop()
            name = d.get("class", "main" if parent is None else None)
            if name is None:
                raise self.err(d, 'a nested <default> needs a class name; add class="..."')
            tags: dict[str, dict[str, str]] = {}
            for c in d.children:
                if c.tag != "default":
                    tags[c.tag] = dict(c.attrib)
            self.classes[name] = (parent, tags)
            todo.extend((c, name) for c in reversed(d.findall("default")))

    def attrs(self, el: Element, childclass: str | None) -> dict[str, str]:
        """The element's attributes completed from its default class chain."""
        cls = el.get("class") or childclass or "main"
        if cls not in self.classes and cls != "main":
            raise self.err(el, f"class {cls!r} is not a defined <default class>; define it")
        chain: list[str] = []
        cur: str | None = cls
        while cur is not None and cur in self.classes:
            chain.append(cur)
            cur = self.classes[cur][0]
        out: dict[str, str] = {}
        for c in reversed(chain):
            out.update(self.classes[c][1].get(el.tag, {}))
        out.update(el.attrib)
        return out

    def angle(self, x: float) -> float:
        return math.radians(x) if self.degree else x

    def nums(
        self, el: Element, a: dict[str, str], key: str, n: int, default: list[float]
    ) -> list[float]:
        probe = Element(
            el.tag, {**el.attrib, key: a[key]} if key in a else dict(el.attrib), el.line
        )
        if key not in a:
            return list(default)
        return floats(probe, key, n, self.path)

    def pose(self, el: Element, a: dict[str, str]) -> np.ndarray:
        """The element's frame in its parent's frame."""
        pos = self.nums(el, a, "pos", 3, [0, 0, 0])
        given = [k for k in ("quat", "axisangle", "euler", "xyaxes", "zaxis") if k in a]
        if len(given) > 1:
            raise self.err(el, f"gives the orientation twice ({given[0]} and {given[1]}); keep one")
        rot = np.eye(3)
        try:
            if "quat" in a:
                q = self.nums(el, a, "quat", 4, [1, 0, 0, 0])
                rot = quaternion(*q)
            elif "axisangle" in a:
                v = self.nums(el, a, "axisangle", 4, [0, 0, 1, 0])
                rot = axis_angle(np.array(v[:3]), self.angle(v[3]))
            elif "euler" in a:
                v = self.nums(el, a, "euler", 3, [0, 0, 0])
                rot = euler(tuple(self.angle(x) for x in v), self.eulerseq)  # type: ignore[arg-type]
            elif "xyaxes" in a:
                v = self.nums(el, a, "xyaxes", 6, [1, 0, 0, 0, 1, 0])
                rot = xyaxes(np.array(v[:3]), np.array(v[3:]))
            elif "zaxis" in a:
                rot = zaxis(np.array(self.nums(el, a, "zaxis", 3, [0, 0, 1])))
        except ValueError as exc:
            raise self.err(el, f"the orientation is degenerate ({exc})") from None
        if not np.all(np.isfinite(rot)):
            raise self.err(el, "the orientation is degenerate (a zero vector or quaternion)")
        return frame(rot, np.array(pos))


def read_mjcf(text: str, path: str) -> MechanismSpec:
    """The mechanism of an MJCF text (``path`` names the file in messages)."""
    root = parse(text, path, "MJCF")
    with np.errstate(invalid="ignore", divide="ignore"):
        return _read(root, path)


def _read(root: Element, path: str) -> MechanismSpec:
    if root.tag != "mujoco":
        raise MechanismError(
            f"{root.where()}: an MJCF file's root element is <mujoco>", path=path, line=root.line
        )
    rd = _Reader(root, path)
    if name_problem(root.get("model") or "mjcf", "model name"):
        raise rd.err(root, name_problem(root.get("model") or "mjcf", "model name"))  # type: ignore[arg-type]
    for el in _walk(root):
        if el.tag == "include":
            raise rd.err(
                el,
                f"includes the file {el.get('file')!r}; mechsing reads one file "
                "and nothing it names: paste the included content in",
            )
    for el in root.findall("tendon"):
        if el.children:
            raise rd.err(
                el,
                "tendons couple joints, which mechsing cannot model; remove the "
                "<tendon> section to analyse the linkage without them",
            )
    world = root.find("worldbody")
    if world is None:
        raise rd.err(root, "the model has no <worldbody>; add one with the bodies")
    bodies = Bodies()
    bodies.add(_WORLD)
    placed: dict[str, np.ndarray] = {_WORLD: np.eye(4)}
    sites: dict[str, tuple[str, np.ndarray]] = {}
    joints: list[JointSpec] = []
    names: set[str] = set()
    counter = [0]
    inertials: list = []
    from_geoms: list[str] = []

    # the tree is walked with a stack, not by recursion (a chain nested up to the parser's
    # MAX_DEPTH needs no Python frame per level): in document order, each element with
    # its parent body, its parent's frame and the default class its children inherit
    todo: list[tuple[Element, str, np.ndarray, str | None]] = []

    def visit(
        el: Element, parent_body: str, parent_frame: np.ndarray, childclass: str | None
    ) -> None:
        kids = [c for c in el.children if c.tag in ("site", "body", "frame")]
        todo.extend((c, parent_body, parent_frame, childclass) for c in reversed(kids))

    def site(
        c: Element, parent_body: str, parent_frame: np.ndarray, childclass: str | None
    ) -> None:
        a = rd.attrs(c, childclass)
        if a.get("name"):
            sites[a["name"]] = (parent_body, parent_frame @ rd.pose(c, a))

    def body(el: Element, parent: str, parent_frame: np.ndarray, childclass: str | None) -> None:
        a = dict(el.attrib)
        t = parent_frame @ rd.pose(el, a)
        cc = el.get("childclass") or childclass
        if el.tag == "frame":  # a frame only moves what it holds
            visit(el, parent, t, cc)
            return
        counter[0] += 1
        name = el.get("name") or f"body{counter[0]}"
        if name in placed or name == _WORLD:
            raise rd.err(el, f"body name {name!r} is used twice; give each body its own name")
        if name_problem(name, "body name"):
            raise rd.err(el, name_problem(name, "body name"))  # type: ignore[arg-type]
        jels = [c for c in el.children if c.tag in ("joint", "freejoint")]
        prev = parent
        for k, j in enumerate(jels):
            ja = rd.attrs(j, cc) if j.tag == "joint" else dict(j.attrib)
            jt = "free" if j.tag == "freejoint" else ja.get("type", "hinge")
            if jt not in MJCF_TYPES:
                raise rd.err(
                    j, f"unknown joint type {jt!r}; MJCF joint types are {', '.join(MJCF_TYPES)}"
                )
            this = name if k == len(jels) - 1 else f"{name}.{k + 1}"
            bodies.add(this)
            placed[this] = t
            jname = ja.get("name") or f"{name}_joint{k + 1}"
            if jname in names:
                raise rd.err(j, f"joint name {jname!r} is used twice; rename one")
            if joint_name_problem(jname):
                raise rd.err(j, joint_name_problem(jname))  # type: ignore[arg-type]
            names.add(jname)
            spec = JointSpec(jname, MJCF_TYPES[jt], (prev, this))
            p = t @ np.array([*rd.nums(j, ja, "pos", 3, [0, 0, 0]), 1.0])
            ax = np.array(rd.nums(j, ja, "axis", 3, [0, 0, 1]))
            if jt in ("hinge", "slide"):
                if not safe_norm(ax) > NEAR_ZERO_VECTOR:
                    raise rd.err(j, 'the axis is a zero vector; give a direction such as "0 0 1"')
                w = t[:3, :3] @ unit_vector(ax)
                spec.axis = tuple(w)  # type: ignore[assignment]
                if jt == "hinge":
                    spec.point = tuple(p[:3])  # type: ignore[assignment]
                limited = ja.get("limited", "auto")
                if "range" in ja and (limited == "true" or (limited == "auto" and rd.autolimits)):
                    lo, hi = rd.nums(j, ja, "range", 2, [0, 0])
                    ref = rd.nums(j, ja, "ref", 1, [0])[0]  # the drawn pose is qpos = ref
                    lo, hi = lo - ref, hi - ref
                    if hi < lo:
                        raise rd.err(j, f"range {lo} {hi}: lower above upper; swap them")
                    if hi > lo:
                        spec.limits = [(lo, hi)]
            elif jt == "ball":
                spec.point = tuple(p[:3])  # type: ignore[assignment]
            joints.append(spec)
            prev = this
        if not jels:
            bodies.add(name)
            placed[name] = t
            bodies.merge(parent, name)
        _inertial(rd, el, name, t, inertials, from_geoms)
        visit(el, name, t, cc)

    visit(world, _WORLD, np.eye(4), None)
    while todo:
        item = todo.pop()
        (site if item[0].tag == "site" else body)(*item)
    eq = root.findall("equality")
    n_connect = 0
    for group in eq:
        for c in group.children:
            if c.get("active", "true") == "false":
                continue
            if c.tag == "connect":
                n_connect += 1
                rule = (
                    "MuJoCo's connect is given by body1 with anchor (in body1's frame; body2 "
                    "defaults to the world) or by site1 with site2"
                )
                if required(c, path, rule, ("body1", "anchor"), ("site1", "site2"))[0] == "site1":
                    s1, s2 = c.get("site1"), c.get("site2")
                    for s in (s1, s2):
                        if s not in sites:
                            raise rd.err(c, f"site {s!r} is not a named site of the model")
                    b1, t1 = sites[s1]  # type: ignore[index]
                    b2 = sites[s2][0]  # type: ignore[index]
                    anchor = t1[:3, 3]
                else:
                    b1 = c.get("body1")
                    b2 = c.get("body2") or _WORLD
                    for b in (b1, b2):
                        if b not in placed:
                            raise rd.err(
                                c,
                                f"body {b!r} is not a body of the model; name one "
                                "with body1 and body2",
                            )
                    loc = floats(c, "anchor", 3, path)
                    anchor = (placed[b1] @ np.array([*loc, 1.0]))[:3]  # type: ignore[index]
                jname = c.get("name") or f"connect{n_connect}"
                if jname in names:
                    raise rd.err(c, f"name {jname!r} is already a joint's; rename it")
                if joint_name_problem(jname):
                    raise rd.err(c, joint_name_problem(jname))  # type: ignore[arg-type]
                names.add(jname)
                joints.append(JointSpec(jname, "S", (b1, b2), point=tuple(anchor)))  # type: ignore[arg-type]
            elif c.tag == "weld":
                rule = (
                    "MuJoCo's weld is given by body1 (body2 defaults to the world) or by "
                    "site1 with site2"
                )
                if required(c, path, rule, ("body1",), ("site1", "site2"))[0] == "site1":
                    for s in (c.get("site1"), c.get("site2")):
                        if s not in sites:
                            raise rd.err(c, f"site {s!r} is not a named site of the model")
                    b1, b2 = sites[c.get("site1")][0], sites[c.get("site2")][0]  # type: ignore[index]
                else:
                    b1 = c.get("body1")
                    b2 = c.get("body2") or _WORLD
                for b in (b1, b2):
                    if b not in placed:
                        raise rd.err(c, f"body {b!r} is not a body of the model")
                bodies.merge(b1, b2)  # type: ignore[arg-type]
            else:
                raise rd.err(
                    c,
                    f"<{c.tag}> constraints (couplings of joint values or tendons) "
                    "cannot be modelled by mechsing; remove it, or use connect/weld",
                )
    out_joints = []
    for j in joints:
        a, b = bodies.find(j.between[0]), bodies.find(j.between[1])
        if a == b:
            raise MechanismError(
                f"joint {j.name!r} joins a body to itself after the welds "
                "(a weld makes its two bodies one); remove the weld or the joint",
                path=path,
            )
        j.between = (a, b)
        out_joints.append(j)
    # the output: the tip of a serial chain (no loop, no branch)
    output = None
    used = {x for j in out_joints for x in j.between}
    if n_connect == 0 and out_joints:
        kids: dict[str, int] = {}
        for j in out_joints:
            kids[j.between[0]] = kids.get(j.between[0], 0) + 1
        if all(v == 1 for v in kids.values()):
            tip = out_joints[-1].between[1]
            if tip not in kids:
                output = tip
    model = root.get("model") or "mjcf"
    del used
    inputs: list[str] = []
    for group in root.findall("actuator"):
        for act in group.children:
            jn = act.get("joint")
            if jn is None:
                continue
            if jn not in {j.name for j in out_joints}:
                raise rd.err(act, f"drives joint {jn!r}, which is not a joint of the model")
            if jn not in inputs:
                inputs.append(jn)
    return MechanismSpec(
        name=model,
        source=f"Converted by mechsing from the MJCF file {path} (model {model!r}).",
        ground=bodies.find(_WORLD),
        bodies=bodies.bodies(),
        joints=out_joints,
        angle_unit="deg" if rd.degree else "rad",
        output=output,
        inputs=inputs,
        notes=[_geoms_note(from_geoms)] if from_geoms else [],
        masses=(
            []
            if from_geoms
            else body_masses(inertials, {b: bodies.find(b) for b in placed}, bodies.find(_WORLD))
        ),
    )


def _geoms_note(bodies: list[str]) -> str:
    shown = ", ".join(repr(b) for b in bodies[:4]) + (", ..." if len(bodies) > 4 else "")
    return (
        f"no masses written: the inertia of {shown} comes from its geoms by MuJoCo's "
        "inertiafromgeom, which mechsing does not compute (the dynamics needs every "
        "moving body's mass); give each body an <inertial>"
    )


#: the attributes of an MJCF <inertial>'s fullinertia, in MuJoCo's order
_FULL = ("M11", "M22", "M33", "M12", "M13", "M23")


def _inertial(
    rd: _Reader, el: Element, name: str, t: np.ndarray, out: list, from_geoms: list[str]
) -> None:
    """The body's ``<inertial pos quat mass diaginertia|fullinertia>`` placed in the ground
    frame (``t``: the body's frame at the initial pose), or the body's name in
    ``from_geoms`` when MuJoCo derives its inertia from its geoms (``inertiafromgeom``:
    "true", or "auto" without an <inertial>).  A negative mass or an inertia that is not
    a rigid body's is refused with the element's line."""
    from mechsing.numeric.inertia import inertia_problem

    inertial = el.find("inertial")
    has_geoms = any(c.tag == "geom" for c in el.children)
    if has_geoms and (
        rd.inertiafromgeom == "true" or (inertial is None and rd.inertiafromgeom == "auto")
    ):
        from_geoms.append(name)
        return
    if inertial is None:
        return
    a = dict(inertial.attrib)
    kg = rd.nums(inertial, a, "mass", 1, [0.0])[0]
    if "mass" not in a:
        raise rd.err(inertial, 'an <inertial> gives its mass; add mass="..."')
    if not kg >= 0:
        raise rd.err(inertial, f"body {name!r}: the mass is {kg}; a mass is not negative")
    if "fullinertia" in a:
        xx, yy, zz, xy, xz, yz = rd.nums(inertial, a, "fullinertia", 6, [0.0] * 6)
    elif "diaginertia" in a:
        xx, yy, zz = rd.nums(inertial, a, "diaginertia", 3, [0.0] * 3)
        xy = xz = yz = 0.0
    else:
        raise rd.err(
            inertial, "an <inertial> gives diaginertia or fullinertia (MuJoCo requires one)"
        )
    local = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    problem = inertia_problem(local)
    if problem:
        raise rd.err(inertial, f"body {name!r}: the inertia {problem}")
    out.append(placed(name, t @ rd.pose(inertial, a), kg, local))


def _walk(el: Element):  # type: ignore[no-untyped-def]
    """Every element under ``el`` (itself first), in document order, without recursion."""
    stack = [el]
    while stack:
        e = stack.pop()
        yield e
        stack.extend(reversed(e.children))
