"""URDF robot descriptions (ROS) as mechsing mechanisms.

Owns :func:`read_urdf`.  The mapping (also in the docs' import page):

* each ``<link>`` is a body; a ``fixed`` joint merges its two links into one
  body (named after the link nearer the root); the root link (the one that is
  no joint's child) is the ground;
* ``revolute`` and ``continuous`` -> R (``axis`` and ``point``), ``prismatic``
  -> P (``axis``), ``planar`` -> G (``normal`` = the URDF axis, the plane's
  normal), ``floating`` -> D; the joint's ``between`` is ``[parent, child]``;
* geometry: forward kinematics of the tree at the zero configuration gives
  each joint frame in the ground (root link) frame, ``T_joint = T_parent
  origin(xyz, rpy)``; the joint's axis is the URDF ``axis`` (default ``1 0 0``)
  turned into the ground frame and its point is the joint frame's origin.  A
  joint value is then the URDF joint position (radians or metres) and the
  reference configuration is the URDF zero configuration;
* ``<limit lower upper>`` of revolute and prismatic joints -> ``limits``;
* the inputs: every revolute and prismatic joint (a robot arm's actuated joints);
* the output: for a serial chain (no link with two children), the body of the
  tip link (its twist is the tool frame's; no ``point``, which would make the
  output a positioning task of three rows).

Refused with a message naming the element and line: a ``<mimic>`` joint (a
coupling mechsing cannot model), an unknown joint type, a link that is the
child of two joints, a cycle, a joint naming an unknown link.
"""

from __future__ import annotations

import numpy as np

from mechsing.formats.frames import frame, rpy
from mechsing.formats.writer import (
    Bodies,
    JointSpec,
    MechanismSpec,
    joint_name_problem,
    name_problem,
)
from mechsing.formats.xmlsafe import Element, floats, parse
from mechsing.model.mechanism import MechanismError
from mechsing.numeric import NEAR_ZERO_VECTOR, safe_norm, unit_vector

__all__ = ["URDF_TYPES", "read_urdf"]

#: URDF joint type -> mechsing joint type ("" for a rigid joint: the links merge)
URDF_TYPES = {
    "revolute": "R",
    "continuous": "R",
    "prismatic": "P",
    "fixed": "",
    "planar": "G",
    "floating": "D",
}


def read_urdf(text: str, path: str) -> MechanismSpec:
    """The mechanism of a URDF text (``path`` names the file in messages)."""
    root = parse(text, path, "URDF")

    def err(el: Element, message: str) -> MechanismError:
        return MechanismError(f"{el.where()}: {message}", path=path, line=el.line)

    if root.tag != "robot":
        raise err(root, "a URDF file's root element is <robot>")
    if name_problem(root.get("name") or "robot", "robot name"):
        raise err(root, name_problem(root.get("name") or "robot", "robot name"))  # type: ignore[arg-type]
    links: dict[str, Element] = {}
    for el in root.findall("link"):
        name = el.get("name")
        if not name:
            raise err(el, 'a link needs a name; add name="..."')
        if name in links:
            raise err(el, f"link {name!r} is defined twice (first at line {links[name].line})")
        if name_problem(name, "link name"):
            raise err(el, name_problem(name, "link name"))  # type: ignore[arg-type]
        links[name] = el
    if not links:
        raise err(root, "the robot has no <link>; a URDF robot needs links and joints")
    joints: list[Element] = []
    parent_of: dict[str, Element] = {}
    seen: dict[str, Element] = {}
    for el in root.findall("joint"):
        name = el.get("name")
        if not name:
            raise err(el, 'a joint needs a name; add name="..."')
        if name in seen:
            raise err(el, f"joint {name!r} is defined twice (first at line {seen[name].line})")
        seen[name] = el
        problem = joint_name_problem(name)
        if problem and el.get("type") != "fixed":
            raise err(el, problem)
        jtype = el.get("type")
        if jtype not in URDF_TYPES:
            raise err(
                el,
                f"unknown joint type {jtype!r}; URDF joint types are {', '.join(URDF_TYPES)}",
            )
        mimic = el.find("mimic")
        if mimic is not None:
            raise MechanismError(
                f'{el.where()}: <mimic joint="{mimic.get("joint")}"> ties this joint\'s value '
                "to another joint's, a coupling mechsing cannot model; remove the <mimic> "
                "element (the joint becomes independent) or make the joint fixed",
                path=path,
                line=mimic.line,
            )
        for tag in ("parent", "child"):
            sub = el.find(tag)
            if sub is None or not sub.get("link"):
                raise err(el, f'needs <{tag} link="..."/>; add it')
            if sub.get("link") not in links:
                raise MechanismError(
                    f'{el.where()}: <{tag} link="{sub.get("link")}"> names no link of the '
                    f"robot; define the link or fix the name",
                    path=path,
                    line=sub.line,
                )
        child = el.find("child").get("link")  # type: ignore[union-attr]
        if child in parent_of:
            raise err(
                el,
                f"link {child!r} is already the child of joint "
                f"{parent_of[child].get('name')!r} (line {parent_of[child].line}); a URDF "
                "is a tree: close loops with another format (MJCF <equality><connect>) or a "
                "mechsing file",
            )
        parent_of[child] = el
        joints.append(el)
    roots = [n for n in links if n not in parent_of]
    if not roots:
        raise err(
            root,
            "every link is some joint's child: the joints form a cycle; a URDF "
            "is a tree with one root link",
        )
    # order the joints from the root (also detects cycles not reachable from the root)
    children: dict[str, list[Element]] = {n: [] for n in links}
    for el in joints:
        children[el.find("parent").get("link")].append(el)  # type: ignore[union-attr]
    base = roots[0]
    if len(roots) > 1:
        raise err(
            root,
            f"the links {', '.join(repr(r) for r in roots[:4])} are all roots (no joint's "
            "child): the robot is not one tree; join them with joints",
        )
    world: dict[str, np.ndarray] = {base: np.eye(4)}
    ordered: list[tuple[Element, np.ndarray]] = []
    stack = [base]
    while stack:
        link = stack.pop()
        for el in reversed(children[link]):
            child = el.find("child").get("link")  # type: ignore[union-attr]
            origin = el.find("origin")
            xyz = floats(origin, "xyz", 3, path, [0, 0, 0]) if origin is not None else [0, 0, 0]
            angles = floats(origin, "rpy", 3, path, [0, 0, 0]) if origin is not None else [0, 0, 0]
            tj = world[link] @ frame(rpy(*angles), np.array(xyz))
            world[child] = tj
            ordered.append((el, tj))
            stack.append(child)
    missing = [el for el in joints if el.find("child").get("link") not in world]  # type: ignore[union-attr]
    if missing:
        raise err(
            missing[0],
            "this joint is on a cycle of joints not connected to the root "
            f"link {base!r}; a URDF is a tree",
        )
    # rigid joints merge links
    bodies = Bodies()
    for n in [base, *(el.find("child").get("link") for el, _ in ordered)]:  # type: ignore[union-attr]
        bodies.add(n)
    for el, _ in ordered:
        if el.get("type") == "fixed":
            bodies.merge(el.find("parent").get("link"), el.find("child").get("link"))  # type: ignore[union-attr]
    out_joints: list[JointSpec] = []
    for el, tj in ordered:
        jtype = URDF_TYPES[el.get("type")]  # type: ignore[index]
        if not jtype:
            continue
        a = bodies.find(el.find("parent").get("link"))  # type: ignore[union-attr]
        b = bodies.find(el.find("child").get("link"))  # type: ignore[union-attr]
        axis_el = el.find("axis")
        axis = floats(axis_el, "xyz", 3, path, [1, 0, 0]) if axis_el is not None else [1, 0, 0]
        if not safe_norm(axis) > NEAR_ZERO_VECTOR:
            raise err(axis_el or el, 'the axis is a zero vector; give a direction such as "0 0 1"')
        w = tj[:3, :3] @ unit_vector(axis)
        p = tj[:3, 3]
        spec = JointSpec(el.get("name"), jtype, (a, b))  # type: ignore[arg-type]
        if jtype == "R":
            spec.axis, spec.point = tuple(w), tuple(p)  # type: ignore[assignment]
        elif jtype == "P":
            spec.axis = tuple(w)  # type: ignore[assignment]
        elif jtype == "G":
            spec.normal = tuple(w)  # type: ignore[assignment]
        limit = el.find("limit")
        if limit is not None and el.get("type") in ("revolute", "prismatic"):
            lo = floats(limit, "lower", 1, path, [0])[0]
            hi = floats(limit, "upper", 1, path, [0])[0]
            if hi < lo:
                raise err(limit, f"lower {lo} is above upper {hi}; swap them")
            if hi > lo:
                spec.limits = [(lo, hi)]
        out_joints.append(spec)
    # the output: the tip link of a serial chain
    output = None
    if all(len(c) <= 1 for c in children.values()):
        tip = base
        while children[tip]:
            tip = children[tip][0].find("child").get("link")  # type: ignore[union-attr]
        if bodies.find(tip) != bodies.find(base):
            output = bodies.find(tip)
    name = root.get("name") or "robot"
    return MechanismSpec(
        name=name,
        source=f"Converted by mechsing from the URDF file {path} (robot {name!r}).",
        ground=bodies.find(base),
        bodies=bodies.bodies(),
        joints=out_joints,
        angle_unit="rad",
        output=output,
        inputs=[j.name for j in out_joints if j.type in ("R", "P")],
    )
