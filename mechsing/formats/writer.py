"""What an imported description becomes: a mechanism file's content, and its YAML text.

Owns :class:`MechanismSpec` (bodies, joints placed in the ground frame at the
reference configuration, joint limits, output), the union-find that merges
rigidly joined links into one body (:class:`Bodies`), and :func:`to_yaml`, the
mechsing YAML text that ``mechsing convert`` writes and that the loader reads
for an XML file, so analysing a URDF or MJCF file and analysing its converted
YAML are the same computation.  Lengths are written in metres; angles (only
limits carry angles) in the unit the source uses (radians for URDF, the
compiler's unit for MJCF).  Numbers are written with ``repr`` after snapping
float round-off within :data:`SNAP` (times the number when above 1) of a 15-digit value (so ``0.08915900000000001``
is written ``0.089159`` and ``6e-17`` is written ``0``); limits are written as given.
"""

from __future__ import annotations

import dataclasses
import json
import math
import unicodedata
from dataclasses import dataclass, field
from typing import Any

__all__ = [
    "SNAP",
    "Bodies",
    "CouplingSpec",
    "JointSpec",
    "MechanismSpec",
    "number",
    "restrict_to",
    "to_yaml",
]

#: relative round-off snapped when numbers are written (far below any tolerance of mechsing)
SNAP = 1e-14


def number(x: float) -> str:
    """A float as the YAML text of the number (round-off snapped, see :data:`SNAP`)."""
    x = float(x)
    if abs(x) < SNAP:
        return "0"
    short = float(f"{x:.15g}")
    if abs(short - x) <= SNAP * max(1.0, abs(x)):
        x = short
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


#: names a joint may not have (configuration keys); a joint name may not hold '[' or ']'
RESERVED_JOINT_NAMES = ("start", "pose")


def _unwritable(ch: str) -> bool:
    # control characters (C0, DEL, C1 with NEL), line and paragraph separators,
    # surrogates and the non-characters U+FFFE, U+FFFF: YAML refuses them, or reads a
    # line break inside a name
    return unicodedata.category(ch) in ("Cc", "Cs", "Zl", "Zp") or ch in "\ufffe\uffff"


def name_problem(name: str, what: str) -> str | None:
    """Why ``name`` (a body's, a model's ...; ``what`` says which) cannot be written in a
    mechanism file (None when it can): a control character, a line separator ..."""
    bad = next((ch for ch in name if _unwritable(ch)), None)
    if bad is None:
        return None
    kind = (
        "a line or paragraph separator"
        if unicodedata.category(bad) in ("Zl", "Zp")
        else ("a control character" if unicodedata.category(bad) == "Cc" else "not a character")
    )
    return (
        f"the {what} {name!r} holds U+{ord(bad):04X} ({kind}), which a mechanism file "
        "cannot carry; rename it"
    )


def _comment(text: str) -> str:
    """``text`` for a YAML comment: the characters a name may not hold, escaped."""
    return "".join(ch.encode("unicode_escape").decode() if _unwritable(ch) else ch for ch in text)


def joint_name_problem(name: str) -> str | None:
    """Why ``name`` cannot be a mechsing joint's name (None when it can): the importers
    say so on the element's line rather than on a line of the converted YAML."""
    problem = name_problem(name, "joint name")
    if problem:
        return problem
    if "[" in name or "]" in name:
        return (
            f"the joint name {name!r} holds '[' or ']', which select coordinates in mechsing; "
            "rename the joint"
        )
    if name in RESERVED_JOINT_NAMES:
        return f"the joint name {name!r} is a reserved configuration key in mechsing; rename it"
    if len(name) > 200:
        return "the joint name is longer than 200 characters; shorten it"
    return None


def _name(text: str) -> str:
    return json.dumps(text, ensure_ascii=False)


def _vec(v: object) -> str:
    return "[" + ", ".join(number(c) for c in v) + "]"  # type: ignore[attr-defined]


@dataclass
class JointSpec:
    """One mechsing joint: type symbol, [a, b] bodies and geometry in the ground frame."""

    name: str
    type: str
    between: tuple[str, str]
    axis: tuple[float, float, float] | None = None
    point: tuple[float, float, float] | None = None
    normal: tuple[float, float, float] | None = None
    limits: list[tuple[float, float]] | None = None


@dataclass
class CouplingSpec:
    """A coupling of two joints' values: ``joint = multiplier * leader + offset`` (a URDF
    mimic); ``source_line``: the line of the element it comes from."""

    joint: str
    leader: str
    multiplier: float = 1.0
    offset: float = 0.0
    source_line: int | None = None


@dataclass
class MechanismSpec:
    """A mechanism file's content built from another description."""

    name: str
    source: str
    ground: str
    bodies: list[str]
    joints: list[JointSpec]
    angle_unit: str = "rad"
    output: str | None = None
    inputs: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    couplings: list[CouplingSpec] = field(default_factory=list)
    #: each link joined rigidly into a body named after another link: link -> (its body,
    #: its origin: m, ground frame, reference configuration); not written to the YAML
    #: (the command line's ``--output-body LINK`` reads it)
    merged_links: dict[str, tuple[str, tuple[float, float, float]]] = field(default_factory=dict)
    #: the output's point (m, ground frame, reference configuration) and relative_to
    output_point: tuple[float, float, float] | None = None
    output_relative_to: str | None = None
    #: the bodies' masses and inertia (:class:`mechsing.formats.inertia.MassSpec`)
    masses: list[Any] = field(default_factory=list)


def restrict_to(spec: MechanismSpec, mech: Any) -> MechanismSpec:
    """``spec`` reduced to the scene ``mech`` holds (a Mechanism read from ``spec`` and given
    another output, inputs, and only the part they require: ``mechsing.model.scene``):
    its bodies, joints, ground, inputs, output and couplings, and the scene's notes."""
    from mechsing.numeric import to_float

    kept = set(mech.joint_names)
    out = mech.output
    return dataclasses.replace(
        spec,
        ground=mech.ground,
        bodies=[b for b in spec.bodies if b in mech.bodies],
        joints=[j for j in spec.joints if j.name in kept],
        inputs=[str(i) for i in mech.inputs],
        output=out.body if out is not None else None,
        output_point=None if out is None or out.point is None else tuple(to_float(out.point)),
        output_relative_to=(
            out.relative_to if out is not None and out.relative_to != mech.ground else None
        ),
        couplings=[c for c in spec.couplings if c.joint in kept],
        masses=[m for m in spec.masses if m.body in mech.bodies and m.body != mech.ground],
        notes=[*spec.notes, *(mech.scene.notes if mech.scene else ())],
    )


class Bodies:
    """Links merged into bodies: a rigid joint (URDF fixed, MJCF weld or a body without
    joints) makes two links one body, named after the link nearer the root."""

    def __init__(self) -> None:
        self.parent: dict[str, str] = {}
        self.order: list[str] = []

    def add(self, link: str) -> None:
        if link not in self.parent:
            self.parent[link] = link
            self.order.append(link)

    def find(self, link: str) -> str:
        root = link
        while self.parent[root] != root:
            root = self.parent[root]
        while self.parent[link] != root:
            self.parent[link], link = root, self.parent[link]
        return root

    def merge(self, keep: str, other: str) -> None:
        a, b = self.find(keep), self.find(other)
        if a != b:
            # the body keeps the name of the link listed first (nearer the root)
            first, second = (a, b) if self.order.index(a) < self.order.index(b) else (b, a)
            self.parent[second] = first

    def bodies(self) -> list[str]:
        return [b for b in self.order if self.find(b) == b]


def to_yaml(spec: MechanismSpec) -> str:
    """The mechsing YAML text of ``spec``, with a comment naming its source."""
    lines = [f"# {_comment(line)}" for line in spec.source.splitlines()]
    for note in spec.notes:
        lines.append(f"# {_comment(note)}")
    lines.append(f"mechanism: {_name(spec.name)}")
    lines.append(f"units: {{length: m, angle: {spec.angle_unit}}}")
    lines.append(f"ground: {_name(spec.ground)}")
    lines.append("bodies: [" + ", ".join(_name(b) for b in spec.bodies) + "]")
    lines.append("joints:")
    if not spec.joints:
        lines[-1] = "joints: []"
    for j in spec.joints:
        parts = [
            f"name: {_name(j.name)}",
            f"type: {j.type}",
            f"between: [{_name(j.between[0])}, {_name(j.between[1])}]",
        ]
        if j.axis is not None:
            parts.append(f"axis: {_vec(j.axis)}")
        if j.normal is not None:
            parts.append(f"normal: {_vec(j.normal)}")
        if j.point is not None:
            parts.append(f"point: {_vec(j.point)}")
        lines.append("  - {" + ", ".join(parts) + "}")
    limited = [j for j in spec.joints if j.limits]
    if limited:
        lines.append(f"limits:  # per joint coordinate: [lower, upper] (m, {spec.angle_unit})")
        for j in limited:
            assert j.limits is not None
            if len(j.limits) == 1:
                lo, hi = j.limits[0]
                lines.append(f"  {_name(j.name)}: [{float(lo)!r}, {float(hi)!r}]")
            else:
                pairs = ", ".join(f"[{float(lo)!r}, {float(hi)!r}]" for lo, hi in j.limits)
                lines.append(f"  {_name(j.name)}: [{pairs}]")
    if spec.inputs:
        lines.append("inputs: [" + ", ".join(_name(n) for n in spec.inputs) + "]")
    if spec.output is not None:
        rel = (
            f", relative_to: {_name(spec.output_relative_to)}"
            if spec.output_relative_to is not None
            else ""
        )
        point = f", point: {_vec(spec.output_point)}" if spec.output_point is not None else ""
        lines.append(f"output: {{body: {_name(spec.output)}{rel}{point}}}")
    if spec.couplings:
        lines.append("couplings:  # joint = multiplier * leader + offset (a URDF <mimic>)")
        for c in spec.couplings:
            src = f", source_line: {c.source_line}" if c.source_line is not None else ""
            lines.append(
                f"  - {{joint: {_name(c.joint)}, leader: {_name(c.leader)}, "
                f"multiplier: {float(c.multiplier)!r}, offset: {float(c.offset)!r}{src}}}"
            )
    if spec.masses:
        lines.append(
            "mass:  # kg; centre of mass (m, drawn pose); inertia about it, ground axes "
            "(kg m^2): [ixx, iyy, izz, ixy, ixz, iyz]"
        )
        for ms in spec.masses:
            i = ms.inertia
            six = (i[0][0], i[1][1], i[2][2], i[0][1], i[0][2], i[1][2])
            lines.append(
                f"  {_name(ms.body)}: {{kg: {number(ms.kg)}, centre: {_vec(ms.centre)}, "
                f"inertia: {_vec(six)}}}"
            )
    lines.append("configurations:")
    lines.append("  reference: {}")
    return "\n".join(lines) + "\n"


def finite(values: list[float]) -> bool:
    return all(math.isfinite(v) for v in values)
