"""URDF robot descriptions (ROS) as mechsing mechanisms.

Owns :func:`read_urdf`.  The mapping (also in the docs' import page):

* each ``<link>`` is a body; a ``fixed`` joint merges its two links into one
  body (named after the link nearer the root); the root link (the one that is
  no joint's child) is the ground;
* a link merged into another's body keeps its origin (``merged_links``): ``--output-body``
  may name it, the output then being that point of the body (a tool centre point);
* ``revolute`` and ``continuous`` -> R (``axis`` and ``point``), ``prismatic``
  -> P (``axis``), ``planar`` -> G (``normal`` = the URDF axis, the plane's
  normal), ``floating`` -> D; the joint's ``between`` is ``[parent, child]``;
* geometry: forward kinematics of the tree at the zero configuration gives
  each joint frame in the ground (root link) frame, ``T_joint = T_parent
  origin(xyz, rpy)``; the joint's axis is the URDF ``axis`` (default ``1 0 0``)
  turned into the ground frame and its point is the joint frame's origin.  A
  joint value is then the URDF joint position (radians or metres) and the
  reference configuration is the URDF zero configuration;
* ``<limit lower upper>`` of revolute and prismatic joints -> ``limits``; a bound beyond
  1e12 or infinite (``lower="-1e+16"``: how URDF writers say "no limit") and a continuous
  joint's ``<limit>`` leave the joint unlimited, said in the notes;
* the inputs: every revolute and prismatic joint (a robot arm's actuated joints) but
  those of a ``<mimic>`` (their leader drives them);
* the output: for a serial chain (no link with two children), the body of the
  tip link (its twist is the tool frame's; no ``point``, which would make the
  output a positioning task of three rows).

* ``<mimic joint multiplier offset>`` -> an entry of ``couplings`` (the joint's value
  is ``multiplier * (the named joint's value) + offset``), with the ``<mimic>``'s line:
  kept when the robot is read, dropped with its branch when the scene options leave the
  branch out, and analysed as one constraint of the closure system
  (:mod:`mechsing.model.couplings`, :mod:`mechsing.kinematics.couplings`).

Refused with a message naming the element and line: an unknown joint type, a mimic
that couples a joint of several coordinates (a mimic that names a joint the robot does
not define is kept, and refused only when its joint is analysed; one of a fixed joint
couples nothing and is ignored), a link that is the child of two joints, a cycle, a
joint naming an unknown link, and an attribute the URDF specification requires of an
element read here missing (the robot's, a link's and a joint's ``name``, a joint's
``type``, ``<parent link>`` and ``<child link>``, an ``<axis>``'s ``xyz``).
"""

from __future__ import annotations

import numpy as np

from mechsing.errors import MechanismError
from mechsing.formats.frames import frame, rpy
from mechsing.formats.inertia import body_masses, placed
from mechsing.formats.writer import (
    Bodies,
    CouplingSpec,
    JointSpec,
    MechanismSpec,
    joint_name_problem,
    name_problem,
)
from mechsing.formats.xmlsafe import Element, floats, parse, required
from mechsing.numeric import MAX_NUMBER, NEAR_ZERO_VECTOR
from mechsing.numeric.numbers import is_decimal_text, safe_norm, unit_vector

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
    required(root, path, "a URDF robot has a name (the URDF specification requires it)", ("name",))
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
    notes: list[str] = []
    inertials = _inertials(links, world, path, notes)
    out_joints: list[JointSpec] = []
    unlimited: list[tuple[str, str, Element]] = []
    for el, tj in ordered:
        jtype = URDF_TYPES[el.get("type")]  # type: ignore[index]
        if not jtype:
            continue
        a = bodies.find(el.find("parent").get("link"))  # type: ignore[union-attr]
        b = bodies.find(el.find("child").get("link"))  # type: ignore[union-attr]
        axis_el = el.find("axis")
        if axis_el is not None:  # the element is optional, its xyz is not
            required(axis_el, path, "a URDF <axis> gives its direction", ("xyz",))
        axis = floats(axis_el, "xyz", 3, path) if axis_el is not None else [1, 0, 0]
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
            lo, hi = _limit_side(limit, "lower", path), _limit_side(limit, "upper", path)
            if lo is None or hi is None:
                unlimited.append((el.get("name"), el.get("type"), limit))  # type: ignore[arg-type]
            elif hi < lo:
                raise err(limit, f"lower {lo} is above upper {hi}; swap them")
            elif hi > lo:
                spec.limits = [(lo, hi)]
        elif (
            limit is not None
            and el.get("type") == "continuous"
            and (limit.get("lower") is not None or limit.get("upper") is not None)
        ):
            unlimited.append((el.get("name"), el.get("type"), limit))  # type: ignore[arg-type]
        out_joints.append(spec)
    for name, kind, limit in unlimited:
        notes.append(
            f"joint {name!r} (line {limit.line}) is read without limits: its <limit "
            f'lower="{limit.get("lower")}" upper="{limit.get("upper")}"> '
            + (
                "is on a continuous joint, which has none"
                if kind == "continuous"
                else "says no limit (a bound beyond "
                f"{UNLIMITED:g} or infinite; mechsing's limits are two-sided, so a finite "
                "other bound is not kept)"
            )
        )
    couplings = _mimics(joints, seen, path, notes)
    followers = {c.joint for c in couplings}  # driven by their leaders: not inputs
    # the output: the tip link of a serial chain
    output = None
    if all(len(c) <= 1 for c in children.values()):
        tip = base
        while children[tip]:
            tip = children[tip][0].find("child").get("link")  # type: ignore[union-attr]
        if bodies.find(tip) != bodies.find(base):
            output = bodies.find(tip)
    name = root.get("name")
    merged = {
        link: (bodies.find(link), tuple(float(x) for x in world[link][:3, 3]))
        for link in links
        if bodies.find(link) != link
    }
    return MechanismSpec(
        name=name,
        source=f"Converted by mechsing from the URDF file {path} (robot {name!r}).",
        ground=bodies.find(base),
        bodies=bodies.bodies(),
        joints=out_joints,
        angle_unit="rad",
        output=output,
        inputs=[j.name for j in out_joints if j.type in ("R", "P") and j.name not in followers],
        couplings=couplings,
        notes=notes,
        merged_links=merged,  # type: ignore[arg-type]
        masses=body_masses(inertials, {n: bodies.find(n) for n in links}, bodies.find(base)),
    )


#: a joint limit beyond this (in magnitude: radians or metres), or infinite, is how URDF
#: writers say "no limit" (``lower="-1e+16"``): the bound of absurd numbers the reader keeps
#: for geometry (:data:`mechsing.numeric.MAX_NUMBER`)
UNLIMITED = MAX_NUMBER


def _limit_side(limit: Element, key: str, path: str) -> float | None:
    """A ``<limit>``'s ``lower`` or ``upper`` (default 0), or None when it says "no
    limit": infinite, or beyond :data:`UNLIMITED` on its own side (below -UNLIMITED for
    ``lower``, above it for ``upper``).  Anything else is read as any number is."""
    text = (limit.get(key) or "").strip()
    word = text.lower().lstrip("+")
    sign = -1.0 if key == "lower" else 1.0
    if word in ("inf", "infinity", "-inf", "-infinity") or is_decimal_text(text):
        if sign * float(word) > UNLIMITED:  # infinite included
            return None
    return floats(limit, key, 1, path, [0])[0]


#: the attributes of a URDF <inertia>, in the order of a mechsing inertia's six numbers
_URDF_INERTIA = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")


def _inertials(
    links: dict[str, Element], world: dict[str, np.ndarray], path: str, notes: list[str]
) -> list:
    """Each link's ``<inertial>`` (``<origin xyz rpy>``, ``<mass value>``, ``<inertia
    ixx ... izz>`` about the centre of mass in the origin's axes) placed in the ground frame
    at the zero configuration; refused with its line when the mass is negative; an
    inertia that is not a rigid body's is read as a point mass, said in ``notes``."""
    from mechsing.numeric.inertia import inertia_problem

    out = []
    for name, link in links.items():
        el = link.find("inertial")
        if el is None or name not in world:
            continue

        def err(e: Element, message: str, name: str = name) -> MechanismError:
            return MechanismError(f"{e.where()}: link {name!r}: {message}", path=path, line=e.line)

        origin = el.find("origin")
        xyz = floats(origin, "xyz", 3, path, [0, 0, 0]) if origin is not None else [0, 0, 0]
        angles = floats(origin, "rpy", 3, path, [0, 0, 0]) if origin is not None else [0, 0, 0]
        mass_el = el.find("mass")
        if mass_el is None:
            raise err(el, 'an <inertial> gives its <mass value="..."/>; add it')
        required(mass_el, path, "a URDF <mass> gives its value", ("value",))
        kg = floats(mass_el, "value", 1, path)[0]
        if not kg >= 0:
            raise err(mass_el, f"the mass is {kg}; a mass is not negative")
        inertia_el = el.find("inertia")
        xx, yy, zz, xy, xz, yz = (
            [floats(inertia_el, a, 1, path, [0.0])[0] for a in _URDF_INERTIA]
            if inertia_el is not None
            else [0.0] * 6
        )
        local = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
        problem = inertia_problem(local)
        if problem:
            # written inertias in the wild often are no rigid body's (a dummy izz alone):
            # the link kept as a point mass, said in the notes, not the robot refused
            where = inertia_el if inertia_el is not None else el
            notes.append(
                f"link {name!r} (line {where.line}): the <inertia> {problem}; read as a point "
                f"mass of {kg:g} kg at its centre of mass (the kinematics do not use it; the "
                "dynamics do: fix the <inertia> for them)"
            )
            local = np.zeros((3, 3))
        out.append(placed(name, world[name] @ frame(rpy(*angles), np.array(xyz)), kg, local))
    return out


def _prefixed_ancestor(el: Element, leader: str, joints: list[Element]) -> str | None:
    """The one joint between ``el`` and the root whose name is ``leader`` after a prefix
    (``Left_index_q1`` for ``index_q1``: a xacro that prefixed the joints of each copy of
    a hand but not the names its mimics give); None when there is not exactly one."""
    by_child = {j.find("child").get("link"): j for j in joints if j.find("child") is not None}  # type: ignore[union-attr]
    found = []
    seen = set()
    link = el.find("parent").get("link") if el.find("parent") is not None else None  # type: ignore[union-attr]
    while link in by_child and link not in seen:
        seen.add(link)
        j = by_child[link]
        name = j.get("name") or ""
        if len(name) > len(leader) and name.endswith(leader) and name[-len(leader) - 1] in "_-/:.":
            found.append(name)
        link = j.find("parent").get("link") if j.find("parent") is not None else None  # type: ignore[union-attr]
    return found[0] if len(found) == 1 else None


#: URDF joint types a <mimic> may couple (one coordinate each)
MIMIC_TYPES = ("revolute", "continuous", "prismatic")


def _mimics(
    joints: list[Element], by_name: dict[str, Element], path: str, notes: list[str]
) -> list[CouplingSpec]:
    """The couplings of the ``<mimic joint multiplier offset>`` elements: the joint's value
    is ``multiplier * (the named joint's value) + offset`` (URDF defaults 1 and 0).  The
    mimic of a fixed joint couples nothing (the joint has no value): it is ignored, and
    ``notes`` says so."""
    out = []
    for el in joints:
        mimic = el.find("mimic")
        if mimic is None:
            continue
        if el.get("type") == "fixed":
            notes.append(
                f"the <mimic> of the fixed joint {el.get('name')!r} (line {mimic.line}) is "
                "ignored: a fixed joint has no value to couple"
            )
            continue

        def err(message: str, mimic: Element = mimic) -> MechanismError:
            return MechanismError(f"{mimic.where()}: {message}", path=path, line=mimic.line)

        leader = mimic.get("joint")
        if not leader:
            raise err('a <mimic> names the joint it follows; add joint="..."')
        if leader not in by_name:
            prefixed = _prefixed_ancestor(el, leader, joints)
            if prefixed is not None:
                notes.append(
                    f"the <mimic> of joint {el.get('name')!r} (line {mimic.line}) names "
                    f"{leader!r}, which the robot does not define; read as {prefixed!r}, the "
                    f"one joint between it and the root named {leader!r} after a prefix (the "
                    "prefix its generator left out)"
                )
                leader = prefixed
        if leader == el.get("name"):
            raise err("a joint cannot mimic itself; name another joint")
        # a leader the robot does not define is kept as written: the coupling cannot be
        # modelled, which is refused only when the joint is analysed (not on a branch left
        # out), naming this line
        pairs = [(el.get("name"), el)] + ([(leader, by_name[leader])] if leader in by_name else [])
        for name, joint in pairs:
            if joint.get("type") not in MIMIC_TYPES:
                raise err(
                    f"joint {name!r} is {joint.get('type')}; a mimic couples two joints of "
                    f"one coordinate ({', '.join(MIMIC_TYPES)}); remove the <mimic>"
                )
        mult = floats(mimic, "multiplier", 1, path, [1.0])[0]
        offset = floats(mimic, "offset", 1, path, [0.0])[0]
        out.append(CouplingSpec(el.get("name"), leader, mult, offset, mimic.line))  # type: ignore[arg-type]
    return out
