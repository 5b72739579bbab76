"""Reading and validating mechanism files (the format: ``mechsing schema`` and docs/file-format.md).

:func:`load` reads a YAML or JSON file, :func:`loads` a text.  Every problem
raises :class:`~mechsing.errors.MechanismError` whose message names
the file, the line, the item and the fix.  Numbers are read from their text
as exact sympy values (:mod:`mechsing.model.expressions`) and converted to SI
units and radians exactly.
"""

from __future__ import annotations

import ast
from collections.abc import Callable, Collection
from pathlib import Path
from typing import Any

import sympy

from mechsing.errors import ExpressionError, InputRefError, MechanismError, YAMLReadError
from mechsing.model.couplings import read_couplings
from mechsing.model.expressions import is_plain_decimal, parse_number, radian_power, written_digits
from mechsing.model.graph import build_graph, connected_to, coupled_loops
from mechsing.model.loads import LOAD_KEY, read_load, read_weights
from mechsing.model.mechanism import (
    POSE_KEY,
    U_JOINT,
    Configuration,
    Displacement,
    InputRef,
    Joint,
    Mechanism,
    Output,
    OutputPose,
    Units,
)
from mechsing.model.parameters import check_names, read_parameters
from mechsing.numeric import (
    MAX_NUMBER,
    NEAR_ZERO_VECTOR,
    REFERENCE_SCREEN_RTOL,
    data_resolution,
    is_sensible_size,
)
from mechsing.yamlnodes import MAX_FILE_BYTES, YMap, YScalar, YSeq, YValue, read_yaml_text

__all__ = [
    "ANGLE_UNITS",
    "LENGTH_UNITS",
    "MAX_BODIES",
    "MAX_CONFIGURATIONS",
    "MAX_JOINTS",
    "TOP_LEVEL_KEYS",
    "load",
    "loads",
    "read_text",
]

#: exact factors to metres
LENGTH_UNITS: dict[str, Any] = {
    "m": sympy.Integer(1),
    "cm": sympy.Rational(1, 100),
    "mm": sympy.Rational(1, 1000),
}
#: exact factors to radians
ANGLE_UNITS: dict[str, Any] = {"rad": sympy.Integer(1), "deg": sympy.pi / 180}

#: keys of the top-level mapping, in the order the file format lists them
TOP_LEVEL_KEYS = (
    "mechanism",
    "units",
    "parameters",
    "ground",
    "bodies",
    "joints",
    "inputs",
    "output",
    "characteristic_length",
    "configurations",
    "limits",
    "dh",
    "couplings",
    "mass",
    "gravity",
)
JOINT_BASE_KEYS = ("name", "type", "between")
U_KEYS = (("axes", "axes"), ("point", "point"))
OUTPUT_KEYS = ("body", "relative_to", "point")
DISPLACEMENT_KEYS = ("rotation", "translation")
#: keys of a configuration's output pose: the reference point's position, and the
#: rotation about it written one way (a matrix, a rotation vector, or axis and angle)
POSE_KEYS = ("position", "rotation", "rotation_vector", "axis", "angle")
#: configuration keys that are not joint names (so no joint may be called so)
RESERVED_CONFIGURATION_KEYS = ("start", POSE_KEY, LOAD_KEY)

#: most bodies / joints / configurations in one file
MAX_BODIES = 2000
MAX_JOINTS = 4000
MAX_CONFIGURATIONS = 1000
#: most seconds and bytes the analysis of one configuration is estimated to take
#: (:func:`analysis_cost`) before a file is refused
MAX_ANALYSIS_SECONDS = 600.0
MAX_ANALYSIS_BYTES = 2 * 1024**3
#: the estimate's constants, measured on a 2-core machine (ladders of parallelogram
#: loops and rings of triangles, float): seconds per joint, seconds per unit of a
#: coupled group's dense factorisations (rows x joints^2), bytes per entry of the
#: dense stacked closure matrices (their copies included)
COST_PER_JOINT = 0.005
COST_PER_DENSE_UNIT = 2.6e-8
BYTES_PER_ENTRY = 64

_NAME_HINT = "a name such as crank or link_2"


def analysis_cost(graph: Any) -> tuple[float, float]:
    """Estimated (seconds, bytes) of the float analysis of one configuration.

    Linear in the joints, plus each group of loops that share joints
    (:func:`~mechsing.model.graph.coupled_loops`) factorised densely (6 rows per
    loop times its joints squared), plus the dense stacked closure matrices
    (6 rows per loop times all the joints).  Good to a factor of about 3 on the
    ladders and rings it was measured on; a configuration that needs a long
    continuation or a large tangent cone takes longer."""
    n_joints = len(graph.joints)
    n_loops = len(graph.loops)
    dense = sum(6 * loops * joints**2 for loops, joints in coupled_loops(graph.loops))
    seconds = COST_PER_JOINT * n_joints + COST_PER_DENSE_UNIT * dense
    size = BYTES_PER_ENTRY * (6 * n_loops) * (n_joints + 6 * n_loops)
    return seconds, float(size)


def _catalog() -> dict[str, Any]:
    from mechsing.subgroups import load_catalog

    return load_catalog()


# ---------------------------------------------------------------------------
# Reading context
# ---------------------------------------------------------------------------


class _Reader:
    """Validation helpers that know the file (for messages) and collect notes."""

    def __init__(self, path: str | None) -> None:
        self.path = path
        self.notes: list[str] = []
        self.warnings: list[str] = []
        self.units = Units()
        self.scale = 1.0  # largest point coordinate (file units), for near-zero tests
        self.parameters: dict[str, Any] = {}  # the file's named parameters (parameters.py)
        #: (joint, parameter, entry, resolution in SI, digits) of the geometry written with
        #: digits to spare (Mechanism.resolution)
        self.geometry: list[tuple[str, str, int, float, int]] = []

    def error(self, item: str | None, line: int | None, message: str) -> MechanismError:
        return MechanismError(message, path=self.path, line=line, item=item)

    def warn(self, item: str, line: int | None, message: str) -> None:
        """A likely mistake that is not an error: worded like an error's message."""
        self.warnings.append(str(MechanismError(message, path=self.path, line=line, item=item)))

    # -- shapes ---------------------------------------------------------------

    def mapping(self, v: YValue | None, item: str, what: str) -> YMap:
        if not isinstance(v, YMap):
            line = getattr(v, "line", None)
            got = v.describe() if v is not None else "nothing"
            raise self.error(item, line, f"{what} must be a mapping (key: value), got {got}")
        return v

    def sequence(self, v: YValue, item: str, what: str, example: str) -> YSeq:
        if not isinstance(v, YSeq):
            raise self.error(
                item, v.line, f"{what} must be a list, got {v.describe()}; write e.g. {example}"
            )
        return v

    def keys(
        self,
        m: YMap,
        item: str,
        allowed: tuple[str, ...],
        required: tuple[str, ...] = (),
        hint: str = "",
    ) -> None:
        for k, _ in m.items:
            if k.text not in allowed:
                extra = f" ({hint})" if hint else ""
                close = _closest(k.text, allowed)
                sugg = f"; did you mean {close!r}?" if close else ""
                raise self.error(
                    item,
                    k.line,
                    f"unknown key {k.text!r}{sugg} Allowed keys: {', '.join(allowed)}{extra}",
                )
        for r in required:
            if m.get(r) is None:
                raise self.error(item, m.line, f"missing key {r!r}; add it")

    def name(self, v: YValue, item: str, what: str) -> str:
        if not isinstance(v, YScalar) or v.kind == "null" or not v.text.strip():
            got = v.describe() if isinstance(v, YScalar | YSeq | YMap) else "nothing"
            raise self.error(
                item,
                getattr(v, "line", None),
                f"{what} must be a name, got {got or 'nothing'}; give {_NAME_HINT}",
            )
        text = v.text.strip()
        if len(text) > 200:
            raise self.error(
                item, v.line, f"{what} {text[:40]!r}... is too long (at most 200 characters)"
            )
        return text

    # -- numbers --------------------------------------------------------------

    def number(self, v: YValue | None, item: str, what: str, factor: Any = 1) -> Any:
        line = getattr(v, "line", None)
        if not isinstance(v, YScalar):
            got = v.describe() if v is not None else "nothing"
            raise self.error(item, line, f"{what} must be a number, got {got}")
        if v.kind in ("bool", "null"):
            raise self.error(item, line, f"{what} must be a number, got {v.text or 'nothing'!r}")
        t = v.text.strip().lower()
        if v.kind == "float" and t.lstrip("+-") in (".inf", ".nan"):
            raise self.error(
                item, line, f"{what} is {v.text}, not a finite number; give a finite value"
            )
        try:
            value = parse_number(v.text, self.parameters)
        except ExpressionError as exc:
            raise self.error(item, line, f"{what}: {exc}") from None
        return value * factor if factor != 1 else value

    def resolution(self, node: YValue | None, factor: Any = 1) -> tuple[float, int]:
        """The resolution (times ``factor``: SI) and significant digits of a number as
        written (:func:`mechsing.numeric.data_resolution`); (0, 0) for an exact one (an
        expression, a named parameter, a short decimal)."""
        form = written_digits(node.text) if isinstance(node, YScalar) else None
        if form is None:
            return 0.0, 0
        res = data_resolution(form[0], form[1], float(sympy.N(factor, 17)))
        return res, (form[0] if res else 0)

    def vector(
        self, v: YValue | None, item: str, what: str, factor: Any = 1
    ) -> tuple[Any, Any, Any]:
        line = getattr(v, "line", None)
        if not isinstance(v, YSeq) or len(v.items) != 3:
            got = (
                f"{len(v.items)} entries"
                if isinstance(v, YSeq)
                else (v.describe() if v is not None else "nothing")
            )
            raise self.error(item, line, f"{what} must be a list of 3 numbers [x, y, z], got {got}")
        x, y, z = (self.number(e, item, f"{what}[{i}]", factor) for i, e in enumerate(v.items))
        return (x, y, z)

    def direction(
        self, v: YValue | None, item: str, what: str
    ) -> tuple[tuple[Any, Any, Any], bool]:
        """A unit vector from a non-zero direction; returns (unit, was_normalised)."""
        vec = self.vector(v, item, what)
        line = getattr(v, "line", None)
        n2 = sum(c * c for c in vec)
        if all(c == 0 for c in vec):
            raise self.error(
                item,
                line,
                f"{what} [0, 0, 0] is a zero vector; give a non-zero direction such as [0, 0, 1]",
            )
        nf = float(sympy.N(sympy.sqrt(n2), 30))
        if not nf > NEAR_ZERO_VECTOR * max(1.0, self.scale):
            raise self.error(
                item,
                line,
                f"{what} has length {nf:.3g}, too close to zero to be a direction; "
                "give a direction of length about 1, such as [0, 0, 1]",
            )
        if n2 == 1:
            return vec, False
        n = sympy.sqrt(n2)
        unit = tuple(sympy.radsimp(c / n) for c in vec)
        return (unit[0], unit[1], unit[2]), True


def _closest(word: str, choices: tuple[str, ...]) -> str | None:
    import difflib

    m = difflib.get_close_matches(word, choices, n=1, cutoff=0.6)
    return m[0] if m else None


def _show(vec: tuple[Any, ...]) -> str:
    return "[" + ", ".join(str(c) for c in vec) + "]"


# ---------------------------------------------------------------------------
# Public entry points
# ---------------------------------------------------------------------------


def load(path: str | Path, symbolic: Collection[str] = ()) -> Mechanism:
    """Read and validate a mechanism file in mechsing YAML or JSON (any format, URDF and
    MJCF too: :func:`mechsing.reader.read_mechanism`, which every command uses).

    Parameters
    ----------
    path : str or Path
        The mechanism file.
    symbolic : collection of str, optional
        Parameters of the file to keep as symbols
        (:class:`~mechsing.model.parameters.ParameterSymbol`), for symbolic conditions.

    Returns
    -------
    Mechanism
        The validated mechanism, its configurations included.

    Raises
    ------
    MechanismError
        For every problem: unreadable file, malformed YAML, unknown keys,
        invalid geometry, names, inputs, output or configurations.
    """
    return loads(read_text(path), path=str(path), default_name=Path(path).stem, symbolic=symbolic)


def read_text(path: str | Path, largest: int = MAX_FILE_BYTES) -> str:
    """The text of a mechanism file or robot description (UTF-8, a byte-order mark
    dropped): a regular file, pipe or FIFO of at most ``largest`` bytes
    (:func:`mechsing.files.read_input`); MechanismError otherwise (it cannot be read, is
    not a regular file, pipe or FIFO, is larger, or is not UTF-8 text)."""
    from mechsing.errors import InputError
    from mechsing.files import read_input

    shown = str(path)
    try:
        raw = read_input(path, largest, "mechanism file (YAML, JSON, URDF or MJCF)")
    except InputError as exc:
        raise MechanismError(exc.problem, path=shown) from None
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise MechanismError(
            f"the file is not UTF-8 text (byte {exc.start}); save it as UTF-8", path=shown
        ) from None


#: what turns a file's ``dh`` table into its bodies and joints: ``expand(top, reader)`` ->
#: the top-level mapping without ``dh`` (:func:`mechsing.formats.dh.expand_dh`, given by
#: the reader above both layers, :mod:`mechsing.reader`; the model reads no other format)
TableExpander = Callable[[YMap, Any], YMap]


def loads(
    text: str,
    path: str | None = None,
    default_name: str = "mechanism",
    symbolic: Collection[str] = (),
    expand_dh: TableExpander | None = None,
) -> Mechanism:
    """Validate a mechanism given as YAML or JSON text (``path`` only for messages);
    ``expand_dh`` reads a ``dh`` table (None: a file with one is refused, naming the
    reader that takes it, ``mechsing.load``)."""
    r = _Reader(path if path is not None else "<text>")
    if "\x00" in text:
        raise r.error(None, None, "the file contains NUL bytes: it is not a text file")
    if text.lstrip().startswith("<"):
        raise r.error(
            None,
            None,
            "an XML text: mechsing.model reads mechsing YAML and JSON; read URDF and MJCF "
            "with mechsing.load (mechsing.reader.read_mechanism), as the commands do",
        )
    try:
        doc = read_yaml_text(text)
    except YAMLReadError as exc:
        raise r.error(None, exc.line, exc.message) from None
    builder = _Builder(r, default_name)
    builder.symbolic = tuple(symbolic)
    builder.expand_dh = expand_dh
    return builder.build(doc)


def _limits(v: YValue | None, jmap: dict[str, Joint], r: _Reader) -> dict[str, Any]:
    """``limits``: joint name -> [lower, upper] (a 1-dof joint) or a list of such pairs, one
    per coordinate, in the file's units; returned per coordinate in SI units and radians."""
    if v is None:
        return {}
    m = r.mapping(v, "limits", "limits (joint name: [lower, upper])")
    out: dict[str, Any] = {}
    for k, lv in m.items:
        item = f"limits of {k.text!r}"
        if k.text not in jmap:
            raise r.error(item, k.line, f"unknown joint {k.text!r}; use one of {_few(list(jmap))}")
        j = jmap[k.text]
        seq = r.sequence(lv, item, "the limits", "[lower, upper]")
        pairs = (
            [seq]
            if j.dof == 1 and not isinstance(seq.items[0] if seq.items else None, YSeq)
            else [
                r.sequence(e, item, "each coordinate's limits", "[lower, upper]") for e in seq.items
            ]
        )
        if len(pairs) != j.dof:
            raise r.error(
                item,
                seq.line,
                f"joint {j.name!r} has {j.dof} coordinates: give {j.dof} pairs [lower, upper]",
            )
        got = []
        for i, pair in enumerate(pairs):
            if len(pair.items) != 2:
                raise r.error(item, pair.line, "give two numbers [lower, upper]")
            f = r.units.angle_factor if j.units[i] == "rad" else r.units.length_factor
            lo, hi = (float(sympy.N(r.number(e, item, "a limit", f), 17)) for e in pair.items)
            if not lo < hi:
                raise r.error(item, pair.line, f"lower {lo:g} is not below upper {hi:g}; swap them")
            got.append((lo, hi))
        out[k.text] = tuple(got)
    return out


# ---------------------------------------------------------------------------
# The builder
# ---------------------------------------------------------------------------


class _Builder:
    def __init__(self, r: _Reader, default_name: str) -> None:
        self.r = r
        self.default_name = default_name
        self.catalog = _catalog()
        self.body_lines: dict[str, int] = {}
        self.symbolic: tuple[str, ...] = ()
        self.expand_dh: TableExpander | None = None

    def build(self, doc: YValue) -> Mechanism:
        r = self.r
        top = r.mapping(doc, None, "the file")
        # parameters first: a dh table's rows may use them
        r.parameters = read_parameters(r, top, self.symbolic)
        if top.get("dh") is not None:
            if self.expand_dh is None:
                raise r.error(
                    "dh",
                    top.key_line("dh"),
                    "a DH table: mechsing.model reads bodies and joints; read a file with a "
                    "dh table with mechsing.load (mechsing.reader.read_mechanism), as the "
                    "commands do",
                )
            top = self.expand_dh(top, r)
            check_names(r, top)
        r.keys(
            top,
            None,
            TOP_LEVEL_KEYS,
            ("bodies", "joints"),
            hint="see 'mechsing schema' for the format",
        )

        name = self.default_name
        if top.get("mechanism") is not None:
            name = r.name(top.get("mechanism"), "mechanism", "the mechanism name")
        self.units(top.get("units"))
        self.scan_scale(top.get("joints"))
        bodies = self.bodies(top.get("bodies"))
        ground = self.ground(top.get("ground"), bodies, top)
        joints = self.joints(top.get("joints"), bodies)
        self.connectivity(bodies, ground, joints)
        graph = build_graph(bodies, ground, joints)
        seconds, size = analysis_cost(graph)
        if seconds > MAX_ANALYSIS_SECONDS or size > MAX_ANALYSIS_BYTES:
            groups = coupled_loops(graph.loops)
            raise r.error(
                "joints",
                top.key_line("joints"),
                f"{len(joints)} joints among {len(bodies)} bodies with {len(graph.loops)} "
                f"independent loops, the largest group of loops that share joints having "
                f"{groups[0][0]} loops and {groups[0][1]} joints, is too large a mechanism "
                f"for mechsing's loop analysis: one configuration would take about "
                f"{seconds:.0f} s and {size / 1024**3:.1f} GB (limits "
                f"{MAX_ANALYSIS_SECONDS:.0f} s and {MAX_ANALYSIS_BYTES / 1024**3:.0f} GB); "
                "split it into smaller mechanisms, or into groups of loops that share no joint",
            )
        jmap = {j.name: j for j in joints}
        inputs = self.inputs(top.get("inputs"), jmap)
        output = self.output(top.get("output"), bodies, ground, graph)
        char_len = None
        if top.get("characteristic_length") is not None:
            v = top.get("characteristic_length")
            char_len = r.number(v, "characteristic_length", "the length", r.units.length_factor)
            if not char_len > 0:
                raise r.error(
                    "characteristic_length",
                    v.line,
                    f"must be a positive length, got {char_len}; remove it or give e.g. 1",
                )
            if not is_sensible_size(1 / char_len):
                raise r.error(
                    "characteristic_length",
                    v.line,
                    f"{sympy.N(char_len, 3)} m is too small a length (at least "
                    f"{1 / MAX_NUMBER:g} m); remove it or give the size of the mechanism",
                )
        self.output_given = output
        configs = self.configurations(top.get("configurations"), jmap)
        return Mechanism(
            name=name,
            path=r.path,
            bodies=tuple(bodies),
            ground=ground,
            joints=tuple(joints),
            inputs=tuple(inputs),
            output=output,
            configurations=configs,
            characteristic_length=char_len,
            notes=tuple(r.notes),
            warnings=tuple(r.warnings),
            graph=graph,
            units=r.units,
            limits=_limits(top.get("limits"), jmap, r),
            couplings=read_couplings(r, top.get("couplings"), jmap),
            parameters=dict(r.parameters),
            resolution=tuple(r.geometry),
            weights=read_weights(r, top.get("mass"), top.get("gravity"), bodies, ground),
        )

    # -- units --------------------------------------------------------------

    def units(self, v: YValue | None) -> None:
        r = self.r
        if v is None:
            return
        m = r.mapping(v, "units", "units")
        r.keys(m, "units", ("length", "angle"))
        length, angle = "m", "rad"
        if m.get("length") is not None:
            length = r.name(m.get("length"), "units", "units.length")
            if length not in LENGTH_UNITS:
                raise r.error(
                    "units",
                    m.key_line("length"),
                    f"length unit {length!r} is not one of {', '.join(LENGTH_UNITS)}",
                )
        if m.get("angle") is not None:
            angle = r.name(m.get("angle"), "units", "units.angle")
            if angle not in ANGLE_UNITS:
                raise r.error(
                    "units",
                    m.key_line("angle"),
                    f"angle unit {angle!r} is not one of {', '.join(ANGLE_UNITS)}",
                )
        r.units = Units(length, angle, LENGTH_UNITS[length], ANGLE_UNITS[angle])

    def scan_scale(self, v: YValue | None) -> None:
        """Largest point coordinate (file units), the scale of the near-zero test."""
        if not isinstance(v, YSeq):
            return
        best = 1.0
        for jv in v.items[:MAX_JOINTS]:
            if not isinstance(jv, YMap):
                continue
            p = jv.get("point")
            if isinstance(p, YSeq):
                for e in p.items:
                    if isinstance(e, YScalar) and e.kind in ("int", "float"):
                        try:
                            best = max(best, abs(float(e.text)))
                        except ValueError:
                            pass
        self.r.scale = best if best < float("inf") else 1.0

    # -- bodies and ground ----------------------------------------------------

    def bodies(self, v: YValue | None) -> list[str]:
        r = self.r
        seq = r.sequence(v, "bodies", "bodies", "bodies: [ground, crank, coupler]")
        if not seq.items:
            raise r.error(
                "bodies", seq.line, "the list of bodies is empty; list at least the ground"
            )
        if len(seq.items) > MAX_BODIES:
            raise r.error("bodies", seq.line, f"{len(seq.items)} bodies, more than {MAX_BODIES}")
        out: list[str] = []
        seen: dict[str, int] = {}
        self.body_lines = seen
        for e in seq.items:
            b = r.name(e, "bodies", "a body")
            if b in seen:
                raise r.error(
                    f"body {b!r}",
                    e.line,
                    f"listed twice (first at line {seen[b]}); give each body a different name",
                )
            seen[b] = e.line
            out.append(b)
        return out

    def ground(self, v: YValue | None, bodies: list[str], top: YMap) -> str:
        r = self.r
        if v is None:
            return bodies[0]
        if isinstance(v, YSeq):
            raise r.error(
                "ground",
                v.line,
                "a mechanism has one ground, got a list (two grounds); name one body and "
                "attach the others to it with joints (type E for a rigid connection)",
            )
        g = r.name(v, "ground", "ground")
        if g not in bodies:
            raise r.error(
                "ground",
                v.line,
                f"{g!r} is not in bodies; add it to bodies or name one of {_few(bodies)}",
            )
        return g

    # -- joints ---------------------------------------------------------------

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
                abs(float(sympy.N(c, 17)))
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
                    f"unknown body {x!r}; add it to bodies or use one of {_few(sorted(bodyset))}",
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
                    f"{key} of joint {item.split(' ', 1)[1]} normalised to {_show(unit)}"
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
            r.notes.append(f"axes[0] of joint {name} normalised to {_show(a1)}")
        if ch2:
            r.notes.append(f"axes[1] of joint {name} normalised to {_show(a2)}")
        cross = (
            a1[1] * a2[2] - a1[2] * a2[1],
            a1[2] * a2[0] - a1[0] * a2[2],
            a1[0] * a2[1] - a1[1] * a2[0],
        )
        s = float(sympy.N(sympy.sqrt(sum(c * c for c in cross)), 30))
        if s < NEAR_ZERO_VECTOR:  # |a1 x a2| of unit vectors: the sine of their angle
            raise r.error(
                item,
                av.line,
                "the two axes of a U joint are parallel; a U joint needs two "
                "intersecting, non-parallel axes (usually perpendicular)",
            )
        point = r.vector(m.get("point"), item, "point", r.units.length_factor)
        return {"axes": (a1, a2), "point": point}

    def connectivity(self, bodies: list[str], ground: str, joints: list[Joint]) -> None:
        reach = connected_to(ground, bodies, joints)
        missing = [b for b in bodies if b not in reach]
        if missing:
            raise self.r.error(
                f"body {missing[0]!r}",
                self.body_lines.get(missing[0]),
                f"is not connected to the ground {ground!r} through joints "
                f"(unconnected: {_few(missing)}); add a joint or remove the body",
            )

    # -- inputs and output ---------------------------------------------------

    def inputs(self, v: YValue | None, jmap: dict[str, Joint]) -> list[InputRef]:
        r = self.r
        if v is None:
            return []
        seq = r.sequence(v, "inputs", "inputs", 'inputs: [A] or inputs: ["C1[1]"]')
        out: list[InputRef] = []
        taken: dict[tuple[str, int], int] = {}
        for e in seq.items:
            if not isinstance(e, YScalar) or e.kind == "null":
                raise r.error(
                    "inputs",
                    e.line,
                    'each input must be a joint name or "NAME[i]" '
                    '(quote it in YAML: inputs: ["C1[1]"])',
                )
            text = e.text.strip()
            try:
                ref = InputRef.parse(text, jmap)
            except InputRefError as exc:
                raise r.error(exc.item, e.line, exc.problem) from None
            jname, index, j = ref.joint, ref.index, jmap[ref.joint]
            coords = range(j.dof) if index is None else (index,)
            for c in coords:
                if (jname, c) in taken:
                    raise r.error(
                        f"input {text!r}",
                        e.line,
                        f"coordinate {c} of joint {jname!r} is "
                        f"already an input (line {taken[(jname, c)]}); list it once",
                    )
                taken[(jname, c)] = e.line
            out.append(InputRef(jname, index))
        return out

    def output(self, v: YValue | None, bodies: list[str], ground: str, graph: Any) -> Output | None:
        r = self.r
        if v is None:
            if graph.num_loops == 0:
                deg = {b: 0 for b in bodies}
                for j in graph.joints:
                    deg[j.between[0]] += 1
                    deg[j.between[1]] += 1
                leaves = [b for b in bodies if b != ground and deg[b] == 1]
                if len(leaves) == 1:
                    r.notes.append(f"output defaulted to the unique leaf body {leaves[0]!r}")
                    return Output(leaves[0], ground, None, None, True)
            return None
        m = r.mapping(v, "output", "output")
        r.keys(m, "output", OUTPUT_KEYS, ("body",))
        body = r.name(m.get("body"), "output", "output body")
        if body not in bodies:
            raise r.error(
                "output", m.key_line("body"), f"unknown body {body!r}; use one of {_few(bodies)}"
            )
        rel = ground
        if m.get("relative_to") is not None:
            rel = r.name(m.get("relative_to"), "output", "relative_to")
            if rel not in bodies:
                raise r.error(
                    "output",
                    m.key_line("relative_to"),
                    f"relative_to names unknown body {rel!r}; use one of {_few(bodies)}",
                )
        if rel == body:
            raise r.error(
                "output",
                m.line,
                f"the output body {body!r} is the body it is measured "
                "relative to; name another body (relative_to defaults to the ground)",
            )
        point = None
        if m.get("point") is not None:
            point = r.vector(m.get("point"), "output", "point", r.units.length_factor)
        return Output(body, rel, point, m.line, False)

    # -- configurations --------------------------------------------------------

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
                        f"unknown joint {jk.text!r}; use one of {_few(list(jmap))}, start, "
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
                    f"start names unknown configuration {start!r}; use one of {_few(list(out))}",
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
        return OutputPose(position, rotation, rvec, m.line, form)

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
            if x == 0:
                return True
            bound = REFERENCE_SCREEN_RTOL * (size if unit == "m" else 1)
            return bool(abs(sympy.N(x, 30)) <= bound)

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
        joint value as written (:meth:`_Reader.resolution`): (0, 0) for an expression, a
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
FULL_TURN = 2 * sympy.pi
#: pitched joints: their angle is tied to a slide, many turns are ordinary
_PITCHED = ("H", "Y")
#: joints whose angular coordinates form a rotation vector (its norm is the angle)
_ROTATION_VECTORS = ("S", "D")


def _few(names: list[str], n: int = 8) -> str:
    shown = ", ".join(names[:n])
    return shown + (", ..." if len(names) > n else "")
