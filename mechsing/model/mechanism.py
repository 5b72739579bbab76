"""The data model of a mechanism (frozen dataclasses).

All numbers are exact values in SI units and radians (the file's ``units`` already
applied): sympy values, or, in a mechanism read with ``plain_numbers`` (a float analysis),
:class:`~mechsing.numeric.pirational.PiRational` numbers where the file has a rational
times a power of pi (sympy values elsewhere); directions are exact unit vectors.  Vectors are
tuples of three exact values.  The kinematics layer converts them to the
backend of its precision mode (``Precision.asarray``).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mechsing.errors import InputRefError, MechanismError

if TYPE_CHECKING:  # pragma: no cover
    from mechsing.model.graph import Leg, MechanismGraph

__all__ = [
    "U_JOINT",
    "Configuration",
    "Coupling",
    "Displacement",
    "InputRef",
    "InputRefError",
    "Joint",
    "Mechanism",
    "MechanismError",
    "Output",
    "OutputPose",
    "Scene",
    "Units",
]

#: the type name of the composite universal joint (not a catalog subgroup)
U_JOINT = "U"
#: suffix of the hidden body that a U joint inserts
CROSS_SUFFIX = ".cross"

Vector = tuple[Any, Any, Any]


@dataclass(frozen=True)
class Units:
    """The file's units and their exact factors to SI (metre, radian).

    A pitch is a length per radian, so it takes ``length_factor`` only.
    """

    length: str = "m"
    angle: str = "rad"
    length_factor: Any = 1
    angle_factor: Any = 1


@dataclass(frozen=True)
class Joint:
    """A joint between two bodies.

    Attributes
    ----------
    name : str
    type : str
        A catalog symbol (``"R"``, ``"P"``, ``"C"``, ``"S"`` ... ``"D"``, ``"E"``)
        or ``"U"`` for the composite universal joint.
    between : (str, str)
        ``(a, b)``: the joint value q sets ``g_b = g_a . exp(sum q_i e_i)``.
    params : dict
        The geometric parameters at the reference configuration in the ground
        frame, keyed by the catalog's parameter names: a direction/normal is
        an exact unit 3-tuple, a point a 3-tuple of lengths (m), a pitch a
        length per radian.  For U: ``{"axes": (a1, a2), "point": c}``
        with ``a1`` fixed in ``a`` and ``a2`` in ``b``.
    line : int or None
        Line of the joint in the file.
    dof : int
        Number of coordinates (the subgroup's dimension; 2 for U).
    units : tuple of str
        ``"rad"`` or ``"m"`` for each coordinate (catalog order).
    """

    name: str
    type: str
    between: tuple[str, str]
    params: Mapping[str, Any] = field(default_factory=dict, hash=False)
    line: int | None = None
    dof: int = 1
    units: tuple[str, ...] = ("rad",)

    @property
    def is_composite(self) -> bool:
        """True for a U joint (two revolutes through a hidden cross body)."""
        return self.type == U_JOINT

    @property
    def hidden_body(self) -> str | None:
        """``"<name>.cross"`` for a U joint, else None."""
        return self.name + CROSS_SUFFIX if self.is_composite else None

    def other(self, body: str) -> str:
        """The body at the other end of the joint."""
        a, b = self.between
        return b if body == a else a


_INPUT = re.compile(r"^(?P<name>[^\[\]]+?)\s*\[\s*(?P<index>-?\d+)\s*\]$")


@dataclass(frozen=True)
class InputRef:
    """An actuated joint (``index`` None: all its coordinates) or one coordinate."""

    joint: str
    index: int | None = None

    @staticmethod
    def parse(text: str, joints: Mapping[str, Joint]) -> InputRef:
        """The input written ``NAME`` or ``NAME[i]`` (0-based, catalog basis order) among
        ``joints`` (name -> Joint); InputRefError when it names no actuable coordinate.
        Both the file's ``inputs`` and ``--inputs`` are read by it."""
        text = text.strip()
        mt = _INPUT.match(text)
        jname, index = (mt.group("name").strip(), int(mt.group("index"))) if mt else (text, None)
        if "[" in jname or "]" in jname or not jname:
            raise InputRefError(
                "inputs",
                f'cannot read {text!r}; write "NAME[i]" with a 0-based index, e.g. "C1[1]"',
            )
        item = f"input {text!r}"
        if jname not in joints:
            names = list(joints)
            shown = ", ".join(names[:8]) + (", ..." if len(names) > 8 else "")
            raise InputRefError(item, f"unknown joint {jname!r}; use one of {shown}")
        j = joints[jname]
        if j.dof == 0:
            raise InputRefError(
                item, f"joint {jname!r} of type {j.type} has no coordinate to actuate"
            )
        if index is not None and not 0 <= index < j.dof:
            raise InputRefError(
                item,
                f"index {index} out of range: joint {jname!r} ({j.type}) has {j.dof} "
                f"coordinate{'s' if j.dof > 1 else ''}, indices 0 to {j.dof - 1}",
            )
        return InputRef(jname, index)

    def __str__(self) -> str:
        return self.joint if self.index is None else f"{self.joint}[{self.index}]"


@dataclass(frozen=True)
class Output:
    """The output: the twist of ``body`` relative to ``relative_to``.

    ``point`` (SI, reference configuration, ground frame) restricts it to the
    velocity of that body point.  ``default`` is True when mechsing chose the
    output (the unique leaf of a mechanism without loops).
    """

    body: str
    relative_to: str
    point: Vector | None = None
    line: int | None = None
    default: bool = False


@dataclass(frozen=True)
class Displacement:
    """A multi-dof joint value given as the relative displacement it produces.

    ``rotation`` is a 3x3 tuple of exact values (None if omitted), ``translation``
    a 3-tuple of lengths in SI (None if omitted).  The kinematics layer
    completes an omitted part, checks membership in the joint's subgroup and
    converts to coordinates.
    """

    rotation: tuple[Vector, Vector, Vector] | None = None
    translation: Vector | None = None
    line: int | None = None


JointValue = tuple[Any, ...] | Displacement


@dataclass(frozen=True)
class Coupling:
    """A linear coupling of two joint coordinates (a URDF ``<mimic>``): the value of
    ``joint`` is ``multiplier * value of leader + offset`` (both joints of one
    coordinate; ``offset`` in SI units or radians, the follower's unit).

    ``line`` is the line of the entry in the mechanism file; ``source_line`` the line
    of the element it was converted from (a URDF's ``<mimic>``), when there is one;
    ``leader_defined`` is False when that element names a joint the description does
    not define (kept so that the robot is read; refused when its joint is analysed)."""

    joint: str
    leader: str
    multiplier: Any = 1
    offset: Any = 0
    line: int | None = None
    source_line: int | None = None
    #: False for a converted description's coupling to a joint it does not define
    leader_defined: bool = True


@dataclass(frozen=True)
class Scene:
    """What the command line's scene options (``--output-body``, ``--output-point``,
    ``--relative-to``, ``--inputs``) chose and what the analysis left out
    (:func:`mechsing.model.scene.choose_scene`).

    ``left_out``: the branches left out, each ``(bodies, joints)`` in file order (they
    neither lead from ``output.relative_to`` to the output body nor close a loop with
    such a path); ``dropped_couplings``: the couplings whose joint was left out;
    ``notes``: sentences for a reader (what replaced what, what was left out)."""

    left_out: tuple[tuple[tuple[str, ...], tuple[str, ...]], ...] = ()
    dropped_couplings: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()


#: the configuration key of the output body's pose (a reserved name: no joint may have it)
POSE_KEY = "pose"


@dataclass(frozen=True)
class OutputPose:
    """The pose of the output body that a configuration gives (relative to
    ``output.relative_to``, ground by default), exact values in SI and radians.

    ``position`` is where the output's reference point
    (:meth:`Mechanism.output_reference_point`) is; the rotation, about that point and
    relative to the reference configuration, is a 3x3 ``rotation`` matrix or a
    ``rotation_vector`` (an axis and angle is read as the rotation vector
    ``angle * axis``).  An omitted position or rotation is the reference
    configuration's.  ``form`` says how the file wrote the rotation (``matrix``,
    ``rotation_vector``, ``axis_angle`` or None).
    """

    position: Vector | None = None
    rotation: tuple[Vector, Vector, Vector] | None = None
    rotation_vector: Vector | None = None
    line: int | None = None
    form: str | None = None
    #: what its decimals resolve, in the pose coordinates' order (rx, ry, rz, x, y, z):
    #: (resolution in SI units and radians, significant digits), (0, 0) for an exact one;
    #: each rotation coordinate carries the whole rotation's (its angle's bound); empty
    #: when the pose is exact
    resolution: tuple[tuple[float, int], ...] = ()


@dataclass(frozen=True)
class Configuration:
    """A named configuration: the joint values it gives (the others are solved).

    ``values`` maps a joint name to a tuple of exact coordinates (SI, radians,
    catalog order; length ``dof``) or a :class:`Displacement`.  ``start`` is the
    configuration continuation starts from: ``"reference"`` when the file
    does not say, None for the reference configuration itself (all joints at
    identity).  ``lines`` gives the line of each value in the file.  ``pose``: the
    output body's pose the configuration gives (None: none), solved for by closure
    with the joints not given.  ``resolution``: for a joint whose value was written
    with digits to spare, each coordinate's (resolution in SI units and radians,
    significant digits) -- half a unit in its last written digit
    (:func:`mechsing.numeric.data_resolution`); a joint not listed is exact.
    """

    name: str
    values: Mapping[str, JointValue] = field(hash=False)
    start: str | None = "reference"
    line: int | None = None
    lines: Mapping[str, int] = field(default_factory=dict, hash=False, compare=False)
    pose: OutputPose | None = field(default=None, hash=False)
    resolution: Mapping[str, tuple[tuple[float, int], ...]] = field(
        default_factory=dict, hash=False, compare=False
    )
    #: the load on the output the configuration gives (:class:`mechsing.model.loads.Load`)
    load: Any = field(default=None, hash=False, compare=False)

    @property
    def is_reference(self) -> bool:
        return self.name == "reference"


@dataclass(frozen=True, eq=False)
class Mechanism:
    """A validated mechanism (compared and hashed by identity).

    Attributes
    ----------
    name : str
        The file's ``mechanism`` (default: the file name without extension).
    path : str or None
        The file it was read from.
    bodies : tuple of str
        User bodies in file order (hidden U cross bodies are not listed; see
        :attr:`hidden_bodies`).
    ground : str
    joints : tuple of Joint
        In file order.
    inputs : tuple of InputRef
    output : Output or None
        None when the file has none and none can be chosen by default.
    configurations : dict name -> Configuration
        File order; ``"reference"`` is always present (first if the file does
        not list it).
    characteristic_length : exact value or None
        The file's override of L, in metres.
    notes : tuple of str
        What mechsing did silently (axes normalised, defaults chosen); ``-v``
        prints them.
    warnings : tuple of str
        Likely mistakes that are not errors (a plain angle above a full turn in
        a file in radians: degrees meant?), worded like an error message (file,
        line, item, fix); the command line always prints them.
    graph : MechanismGraph
        Bodies, joints, loops, the spanning tree and legs.
    units : Units
        The file's units (values here are already in SI).
    limits : dict name -> tuple of (lower, upper)
        The file's ``limits`` (per joint coordinate; SI units and radians).
    couplings : tuple of Coupling
        The file's ``couplings`` (a URDF's ``<mimic>`` joints).
    scene : Scene or None
        What ``--output-body``, ``--inputs``... chose and left out.
    parameters : dict name -> exact value
        The file's named ``parameters`` in the order written (pure numbers, the file's
        units not applied); those kept symbolic are
        :class:`~mechsing.model.parameters.ParameterSymbol`.
    resolution : tuple
        The geometry written with digits to spare (see the field).
    """

    name: str
    path: str | None
    bodies: tuple[str, ...]
    ground: str
    joints: tuple[Joint, ...]
    inputs: tuple[InputRef, ...]
    output: Output | None
    configurations: Mapping[str, Configuration]
    characteristic_length: Any
    notes: tuple[str, ...]
    graph: MechanismGraph = field(repr=False)
    units: Units = field(default_factory=Units)
    warnings: tuple[str, ...] = ()
    # joint limits: joint name -> ((lower, upper), ...) per coordinate, SI units and radians
    limits: Mapping[str, tuple[tuple[float, float], ...]] = field(default_factory=dict)
    # linear couplings of joint coordinates (URDF ``<mimic>``), in file order
    couplings: tuple[Coupling, ...] = ()
    # what the command line's scene options chose and left out (None: no such option)
    scene: Scene | None = None
    # the file's named parameters: name -> exact value (or ParameterSymbol), as written
    parameters: Mapping[str, Any] = field(default_factory=dict)
    # the geometry written with digits to spare: (joint, parameter, entry, resolution in
    # SI, significant digits) -- half a unit in the last written digit of a decimal of
    # RESOLUTION_MIN_DIGITS digits or more (a direction's entry before normalisation)
    resolution: tuple[tuple[str, str, int, float, int], ...] = ()
    # the bodies' weights (file keys mass and gravity; :class:`mechsing.model.loads.Weights`)
    weights: Any = None

    def joint(self, name: str) -> Joint:
        """The joint called ``name`` (KeyError if none)."""
        for j in self.joints:
            if j.name == name:
                return j
        raise KeyError(name)

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(j.name for j in self.joints)

    @property
    def hidden_bodies(self) -> tuple[str, ...]:
        """The hidden cross bodies of U joints, in joint order."""
        return tuple(j.hidden_body for j in self.joints if j.hidden_body)

    @property
    def dof(self) -> int:
        """Total joint degrees of freedom."""
        return sum(j.dof for j in self.joints)

    @property
    def loops(self) -> tuple:
        """The canonical loops (:attr:`MechanismGraph.loops`)."""
        return self.graph.loops

    @property
    def legs(self) -> tuple[Leg, ...]:
        """The legs between ``output.relative_to`` and ``output.body`` (empty without output)."""
        if self.output is None:
            return ()
        return self.graph.legs(self.output.body, self.output.relative_to)

    def input_coordinates(self) -> tuple[tuple[str, int], ...]:
        """Every actuated coordinate as ``(joint, index)``, inputs expanded in order."""
        out: list[tuple[str, int]] = []
        for ref in self.inputs:
            if ref.index is None:
                out.extend((ref.joint, i) for i in range(self.joint(ref.joint).dof))
            else:
                out.append((ref.joint, ref.index))
        return tuple(out)

    def coordinates(self) -> tuple[tuple[str, int], ...]:
        """Every joint coordinate as ``(joint, index)`` in file and catalog order."""
        return tuple((j.name, i) for j in self.joints for i in range(j.dof))

    def coordinate_label(self, joint: str, index: int) -> str:
        """How messages name a coordinate: the joint's name for a one-dof joint, else
        ``joint[index]``."""
        return joint if self.joint(joint).dof == 1 else f"{joint}[{index}]"

    def output_reference_point(self) -> Vector:
        """The output's reference point at the reference configuration (exact, SI, ground
        frame): ``output.point`` when the file gives one, else the centroid of the points
        of the joints attached to the output body (the origin when none has a point).
        A configuration's ``pose`` gives this point's position and the rotation about it."""
        if self.output is None:
            raise ValueError("the mechanism has no output")
        if self.output.point is not None:
            return self.output.point
        pts = [
            j.params["point"]
            for j in self.joints
            if self.output.body in j.between and "point" in j.params
        ]
        if not pts:
            return (0, 0, 0)
        n = len(pts)
        return (
            sum(p[0] for p in pts) / n,
            sum(p[1] for p in pts) / n,
            sum(p[2] for p in pts) / n,
        )

    def source_path(self) -> Path | None:
        return Path(self.path) if self.path else None
