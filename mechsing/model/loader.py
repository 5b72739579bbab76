"""Reading and validating mechanism files (the format: ``mechsing schema`` and docs/file-format.md).

:func:`load` reads a YAML or JSON file, :func:`loads` a text: this module owns the
top level of a file (its keys, units, bodies, ground, connectivity, inputs, output,
limits, the size refusal) and hands the joints to :mod:`mechsing.model.joints`, the
configurations to :mod:`mechsing.model.configurations`, each node's checks to the
reading context :mod:`mechsing.model.reading`.  Every problem
raises :class:`~mechsing.errors.MechanismError` whose message names
the file, the line, the item and the fix.  Numbers are read from their text
as exact values (:mod:`mechsing.model.expressions`: sympy's, or PiRational numbers with
``plain_numbers``) and converted to SI units and radians exactly.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from fractions import Fraction
from pathlib import Path
from typing import Any

from mechsing.errors import InputRefError, MechanismError, YAMLReadError
from mechsing.model.configurations import ConfigurationReader
from mechsing.model.couplings import read_couplings
from mechsing.model.graph import MechanismGraph, build_graph, connected_to, coupled_loops
from mechsing.model.joints import MAX_JOINTS, JointReader
from mechsing.model.loads import read_weights
from mechsing.model.mechanism import InputRef, Joint, Mechanism, Output, Units
from mechsing.model.parameters import check_names, read_parameters
from mechsing.model.reading import Reader, few
from mechsing.numeric import MAX_NUMBER
from mechsing.numeric.lazy import sympy
from mechsing.numeric.numbers import is_sensible_size
from mechsing.numeric.pirational import PI, PiRational, evalf_float
from mechsing.yamlnodes import MAX_FILE_BYTES, YMap, YScalar, YSeq, YValue, read_yaml_text

__all__ = [
    "ANGLE_UNITS",
    "LENGTH_UNITS",
    "MAX_BODIES",
    "TOP_LEVEL_KEYS",
    "load",
    "loads",
    "read_text",
]

#: exact factors to metres (a reader hands them on as its numbers: Reader.exact)
LENGTH_UNITS: dict[str, Any] = {
    "m": PiRational(1),
    "cm": PiRational(Fraction(1, 100)),
    "mm": PiRational(Fraction(1, 1000)),
}
#: exact factors to radians
ANGLE_UNITS: dict[str, Any] = {"rad": PiRational(1), "deg": PI / 180}

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
OUTPUT_KEYS = ("body", "relative_to", "point")

#: most bodies in one file (joints: :data:`~mechsing.model.joints.MAX_JOINTS`,
#: configurations: :data:`~mechsing.model.configurations.MAX_CONFIGURATIONS`)
MAX_BODIES = 2000
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


def analysis_cost(graph: MechanismGraph) -> tuple[float, float]:
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
TableExpander = Callable[[YMap, Reader], YMap]


def loads(
    text: str,
    path: str | None = None,
    default_name: str = "mechanism",
    symbolic: Collection[str] = (),
    expand_dh: TableExpander | None = None,
    plain_numbers: bool = False,
) -> Mechanism:
    """Validate a mechanism given as YAML or JSON text (``path`` only for messages);
    ``expand_dh`` reads a ``dh`` table (None: a file with one is refused, naming the
    reader that takes it, ``mechsing.load``).  With ``plain_numbers`` the file's
    rationals times powers of pi are kept as
    :class:`~mechsing.numeric.pirational.PiRational` numbers (a float analysis then
    needs no sympy), not as sympy values."""
    r = Reader(path if path is not None else "<text>", plain=plain_numbers)
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


def _limits(v: YValue | None, jmap: dict[str, Joint], r: Reader) -> dict[str, Any]:
    """``limits``: joint name -> [lower, upper] (a 1-dof joint) or a list of such pairs, one
    per coordinate, in the file's units; returned per coordinate in SI units and radians."""
    if v is None:
        return {}
    m = r.mapping(v, "limits", "limits (joint name: [lower, upper])")
    out: dict[str, Any] = {}
    for k, lv in m.items:
        item = f"limits of {k.text!r}"
        if k.text not in jmap:
            raise r.error(item, k.line, f"unknown joint {k.text!r}; use one of {few(list(jmap))}")
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
            lo, hi = (evalf_float(r.number(e, item, "a limit", f), 17) for e in pair.items)
            if not lo < hi:
                raise r.error(item, pair.line, f"lower {lo:g} is not below upper {hi:g}; swap them")
            got.append((lo, hi))
        out[k.text] = tuple(got)
    return out


# ---------------------------------------------------------------------------
# The builder
# ---------------------------------------------------------------------------


class _Builder:
    """One file's top-level mapping -> :class:`~mechsing.model.mechanism.Mechanism`."""

    def __init__(self, r: Reader, default_name: str) -> None:
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
        joints = JointReader(r, self.catalog).joints(top.get("joints"), bodies)
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
        configs = ConfigurationReader(r, output).configurations(top.get("configurations"), jmap)
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
        r.units = Units(length, angle, r.exact(LENGTH_UNITS[length]), r.exact(ANGLE_UNITS[angle]))

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
                f"{g!r} is not in bodies; add it to bodies or name one of {few(bodies)}",
            )
        return g

    def connectivity(self, bodies: list[str], ground: str, joints: list[Joint]) -> None:
        reach = connected_to(ground, bodies, joints)
        missing = [b for b in bodies if b not in reach]
        if missing:
            raise self.r.error(
                f"body {missing[0]!r}",
                self.body_lines.get(missing[0]),
                f"is not connected to the ground {ground!r} through joints "
                f"(unconnected: {few(missing)}); add a joint or remove the body",
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

    def output(
        self, v: YValue | None, bodies: list[str], ground: str, graph: MechanismGraph
    ) -> Output | None:
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
                "output", m.key_line("body"), f"unknown body {body!r}; use one of {few(bodies)}"
            )
        rel = ground
        if m.get("relative_to") is not None:
            rel = r.name(m.get("relative_to"), "output", "relative_to")
            if rel not in bodies:
                raise r.error(
                    "output",
                    m.key_line("relative_to"),
                    f"relative_to names unknown body {rel!r}; use one of {few(bodies)}",
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
