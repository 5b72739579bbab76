"""What a sweep returns: typed, immutable results and their JSON, CSV and text forms.

Owns :class:`SweepResult` (the sampled measures, the located singularities, the loci of a
grid), :class:`LocatedSingularity`, :class:`Locus` and :class:`SweptVariable`, and the
writers: :func:`json_header` / :func:`json_point` (the JSON document, written point by
point by the command line), :func:`csv_header` / :func:`csv_rows`, and
:func:`text_report`.  JSON and CSV are in SI units and radians like every mechsing
output; the text also shows the file's units.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing.analysis import ConfigurationResult
from mechsing.analysis.contract import finding_class, finding_margin
from mechsing.analysis.display import quantity, unit_text
from mechsing.analysis.html import VERDICT_HEADERS, html_table, verdict_row
from mechsing.analysis.words import finding_label
from mechsing.kinematics.closed import ClosedValue
from mechsing.model import Mechanism
from mechsing.numeric import floored
from mechsing.sweeps.settings import SWEEP_TIE_RTOL
from mechsing.sweeps.words import fold_words

__all__ = [
    "LocatedSingularity",
    "Locus",
    "SweepResult",
    "SweptVariable",
    "csv_header",
    "csv_rows",
    "json_header",
    "json_point",
    "located_rows",
    "text_report",
]


@dataclass(frozen=True)
class SweptVariable:
    """A swept variable: its name, SI unit, the file's unit and factor, its samples (SI)."""

    name: str
    unit: str
    file_unit: str
    factor: float
    values: np.ndarray = field(repr=False, compare=False)
    range: tuple[float, float, float] = (0.0, 0.0, 0.0)  # start, stop, step (file units)
    #: the display floor in the SI unit (:func:`mechsing.analysis.display.floor_for`): a
    #: value below it is round-off and is shown as 0
    floor: float = field(default=0.0, compare=False)

    def shown(self, si: float) -> str:
        """A value in the file's units (and in SI when they differ), 0 below the floor."""
        si = floored(si, self.floor)
        text = quantity(si / self.factor, self.file_unit, spec=".10g")
        if self.file_unit != self.unit:
            text += f" ({quantity(si, self.unit, spec='.10g')})"
        return text

    def to_json(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "unit": self.unit,
            "file_unit": self.file_unit,
            "start": self.range[0],
            "stop": self.range[1],
            "step": self.range[2],
            "samples": len(self.values),
        }


@dataclass(frozen=True)
class LocatedSingularity:
    """A singularity located on a sweep and classified.

    ``values``: the swept variables there (SI); ``kind``: ``fold`` (a limit of the
    swept value: the path turns back), ``crossing`` (a test's determinant changes sign
    there), ``minimum`` (a test's measure touches zero without a sign change); ``tests``:
    the tests whose measure vanishes there; ``ratio``: the smallest of those measures
    after refinement; ``joints``: every joint value (SI); ``configuration``: the full
    analysis of the point at the sweep's precision (None when it was not classified:
    a grid classifies at most ``max_classified`` points); ``far_side``: a fold met on
    the other assembly mode, past which the path resumed; ``between``: for a grid,
    ``row`` (found along a row) or ``column`` (between two rows); ``unresolved``: why a
    limit of travel the full analysis found regular was not resolved (at a fold of the
    swept value some test drops rank, so "regular" there is never the answer);
    ``values_text`` and ``joints_text``: at mp:N, for a point found again at N digits
    before its analysis, the swept values (None for a pose variable's sweep) and the joint
    values as text at N digits (the float fields keep float64's 17)."""

    values: tuple[float, ...]
    kind: str
    tests: tuple[str, ...]
    ratio: float
    joints: tuple[tuple[str, tuple[float, ...]], ...]
    configuration: ConfigurationResult | None = None
    far_side: bool = False
    between: str = "row"
    unresolved: str | None = None
    values_text: tuple[str, ...] | None = None
    joints_text: tuple[tuple[str, tuple[str, ...]], ...] | None = None
    #: the point as a frozen value (source ``located``; at N digits when it was placed
    #: again at mp:N before its analysis); not in the JSON
    point: ClosedValue | None = field(default=None, compare=False, repr=False)

    @property
    def classes(self) -> tuple[str, ...] | None:
        """The classes of the singularities the analysis found there (None: not
        classified)."""
        c = self.configuration
        if c is None:
            return None
        # the JSON's classes (an error entry lists no singularity), without the JSON
        found = () if c.error is not None else c.singularities
        return tuple(dict.fromkeys(finding_class(f) for f in found))

    @property
    def singular(self) -> bool | None:
        """The full analysis's verdict at the point (None: not classified, or undecided)."""
        return None if self.configuration is None else self.configuration.singular

    @property
    def precision(self) -> str | None:
        """The precision that decided the verdict (None: not classified)."""
        return None if self.configuration is None else self.configuration.precision

    @property
    def margin(self) -> dict[str, Any] | None:
        """The margin of the decision behind the first singular finding."""
        c = self.configuration
        if c is None or c.error is not None:
            return None
        for f in c.singularities:
            m = finding_margin(f)
            if m:
                return m
        return None

    def to_json(self) -> dict[str, Any]:
        """The point as an entry of the sweep JSON's ``located`` (SI units and radians)."""
        return {
            "values": list(self.values),
            "kind": self.kind,
            "between": self.between,
            "far_side": self.far_side,
            "tests": list(self.tests),
            "ratio": self.ratio,
            "singular": self.singular,
            "classes": None if self.classes is None else list(self.classes),
            "margin": self.margin,
            "precision": self.precision,
            "joints": {k: list(v) for k, v in self.joints},
            "unresolved": self.unresolved,
            "configuration": None if self.configuration is None else self.configuration.to_json(),
            "values_text": None if self.values_text is None else list(self.values_text),
            "joints_text": (
                None if self.joints_text is None else {k: list(v) for k, v in self.joints_text}
            ),
        }


@dataclass(frozen=True)
class Locus:
    """A singularity locus of a grid: a polyline over the two swept variables (SI) where
    ``test``'s measure vanishes, with the classes found at its classified points."""

    test: str
    classes: tuple[str, ...]
    vertices: np.ndarray = field(repr=False, compare=False)
    closed: bool = False

    def to_json(self) -> dict[str, Any]:
        """The locus as an entry of the sweep JSON's ``loci``."""
        return {
            "test": self.test,
            "classes": list(self.classes),
            "closed": self.closed,
            "vertices": [[float(a), float(b)] for a, b in self.vertices],
        }


@dataclass(frozen=True)
class SweepResult:
    """A sweep: the measures at every sample (arrays shaped like the sweep: (n,) for a
    path, (rows, n) for a grid over (second, first) variable), the located
    singularities and, for a grid, the loci.

    ``rank[test]``: the decided rank (-1 undecided, -2 not reached); ``ratio[test]``:
    the smallest relative singular value (NaN where not reached); ``reached``: closed
    on the start's assembly mode; ``held``: the coordinates held at the start's values;
    ``generic``: each test's generic rank; ``outside``: for each coordinate with limits in
    the file, the samples beyond them."""

    mechanism: Mechanism = field(repr=False, compare=False)
    variables: tuple[SweptVariable, ...]
    from_config: str
    precision: str
    tests: tuple[str, ...]
    generic: dict[str, int]
    held: tuple[str, ...]
    reached: np.ndarray = field(repr=False, compare=False)
    rank: dict[str, np.ndarray] = field(repr=False, compare=False)
    ratio: dict[str, np.ndarray] = field(repr=False, compare=False)
    located: tuple[LocatedSingularity, ...] = ()
    loci: tuple[Locus, ...] = ()
    notes: tuple[str, ...] = ()
    newton_iterations: int = 0
    seconds: float = field(default=0.0, compare=False)
    outside: dict[str, np.ndarray] = field(default_factory=dict, repr=False, compare=False)
    #: the samples' statics under a load (:class:`mechsing.statics.along.SweepStatics`)
    statics: Any = field(default=None, repr=False, compare=False)
    #: the number of the assembly mode the sweep started on (as ``mechsing modes``
    #: numbers them; None: the mode continuation reaches from the start configuration)
    mode: int | None = None
    #: a grid's singularity-free regions (:class:`~mechsing.sweeps.aspects.Aspect`)
    aspects: tuple[Any, ...] = ()
    #: the timed motion along a path (``--duration``: :class:`mechsing.kinetics.timed.TimedSweep`)
    dynamics: Any = field(default=None, repr=False, compare=False)
    #: where the sweep started, a frozen value: the assembly mode given as ``start`` (its
    #: own value, source ``mode``) or the start configuration closed (source ``given``);
    #: not in the JSON
    start: ClosedValue | None = field(default=None, repr=False, compare=False)

    @property
    def grid(self) -> bool:
        """True for a grid (two swept variables), False for a path."""
        return len(self.variables) == 2

    def points(self) -> int:
        """The number of samples."""
        return int(self.reached.size)

    def to_json(self) -> dict[str, Any]:
        """The whole result as one JSON document (the command line writes the same
        document point by point)."""
        out = json_header(self)
        out["points"] = [json_point(self, idx) for idx in np.ndindex(self.reached.shape)]
        out.update(json_tail(self))
        return out

    def to_csv(self) -> str:
        """The sweep as ``mechsing sweep --format csv`` writes it: a header, one line per sample, one per located point."""
        return "".join(
            [csv_header(self), *csv_rows(self, range(self.reached.shape[0])), *csv_located(self)]
        )

    def to_text(self) -> str:
        """The sweep's text report, as ``mechsing sweep`` prints it."""
        return text_report(self)

    def _repr_html_(self) -> str:
        """The located singularities as a table in a notebook (``mechsing.report``
        draws the curves and loci)."""
        return html_table(
            VERDICT_HEADERS, located_rows(self), caption=self.to_text().splitlines()[0]
        )


# --------------------------------------------------------------------------- JSON


def json_header(r: Any) -> dict[str, Any]:
    """The JSON keys before the points (``r``: a SweepResult, or a sweep being run)."""
    mech = r.mechanism
    return {
        "mechanism": mech.name,
        "file": mech.path,
        "from": r.from_config,
        "precision": r.precision,
        "units": {"length": "m", "angle": "rad"},
        "file_units": {"length": mech.units.length, "angle": mech.units.angle},
        "variables": [v.to_json() for v in r.variables],
        "held": list(r.held),
        "tests": list(r.tests),
        "generic": dict(r.generic),
        **({} if r.statics is None else r.statics.header_json()),
        **({} if r.mode is None else {"mode": r.mode}),
        **({} if r.dynamics is None else r.dynamics.header_json()),
    }


def _num(x: float) -> float | None:
    return None if not math.isfinite(x) else float(x)


def json_point(r: Any, idx: tuple[int, ...]) -> dict[str, Any]:
    """One sample: its swept values, whether it was reached, each test's rank and measure."""
    vals = _values_at(r.variables, idx)
    reached = bool(r.reached[idx])
    out: dict[str, Any] = {"values": vals, "reached": reached}
    for t in r.tests:
        rk = int(r.rank[t][idx])
        out[t] = {"rank": None if rk < 0 else rk, "ratio": _num(float(r.ratio[t][idx]))}
    if r.outside:  # the file has limits: the coordinates beyond theirs here
        out["outside_limits"] = [name for name, beyond in r.outside.items() if beyond[idx]]
    if r.statics is not None:
        out.update(r.statics.point_json(idx))
    if r.mode is not None:  # the assembly mode the sweep started on
        out["mode"] = r.mode
    if r.dynamics is not None:
        out.update(r.dynamics.point_json(idx))
    return out


def json_tail(r: Any) -> dict[str, Any]:
    mode = {} if r.mode is None else {"mode": r.mode}
    return {
        "located": [{**p.to_json(), **mode} for p in r.located],
        "loci": [{**lo.to_json(), **mode} for lo in r.loci],
        "notes": list(r.notes),
        "newton_iterations": r.newton_iterations,
        **({} if r.statics is None else r.statics.tail_json()),
        **({"aspects": [{**a.to_json(), **mode} for a in r.aspects]} if r.grid else {}),
        **({} if r.dynamics is None else r.dynamics.tail_json()),
    }


def _values_at(variables: tuple[SweptVariable, ...], idx: tuple[int, ...]) -> list[float]:
    if len(variables) == 1:
        return [float(variables[0].values[idx[0]])]
    j, i = idx
    return [float(variables[0].values[i]), float(variables[1].values[j])]


# --------------------------------------------------------------------------- CSV


def csv_header(r: Any) -> str:
    cols = ["kind", *(f"{v.name} [{v.unit}]" for v in r.variables), "reached"]
    for t in r.tests:
        cols += [f"{t} rank", f"{t} ratio"]
    cols += ["classes", "precision", "tests", "between", "dropped"]
    if r.outside:  # the file has limits
        cols.append("outside limits")
    if r.mode is not None:  # a sweep on an assembly mode that modes found
        cols.append("mode")
    return ",".join(cols) + "\n"


def csv_rows(r: Any, rows: Any) -> list[str]:
    """The CSV lines of the samples of ``rows`` (the rows of a grid; 0 for a path)."""
    out = []
    shape = r.reached.shape
    for j in rows:
        if len(shape) == 1:  # a path is one row: row 0 is all of it
            idxs = [(i,) for i in range(shape[0])] if j == 0 else []
        else:
            idxs = [(j, i) for i in range(shape[1])]
        for idx in idxs:
            p = json_point(r, idx)
            cells = ["sample", *(f"{x:.17g}" for x in p["values"]), str(int(p["reached"]))]
            for t in r.tests:
                rk, ra = p[t]["rank"], p[t]["ratio"]
                cells += ["" if rk is None else str(rk), "" if ra is None else f"{ra:.6e}"]
            cells += ["", "", "", "", ""]
            if r.outside:
                cells.append(";".join(p["outside_limits"]))
            if r.mode is not None:
                cells.append(str(r.mode))
            out.append(",".join(cells) + "\n")
    return out


def csv_located(r: Any) -> list[str]:
    out = []
    for p in r.located:
        cells = [p.kind, *(f"{x:.17g}" for x in p.values), "1"]
        for t in r.tests:
            cells += ["", f"{p.ratio:.6e}" if t in p.tests else ""]
        # "" not classified (a grid's max_classified), "none": classified, nothing found
        classes = "" if p.classes is None else " ".join(p.classes) or "none"
        dropped = (p.margin or {}).get("dropped")
        cells += [
            classes,
            p.precision or "",
            " ".join(p.tests),
            p.between,
            "" if dropped is None else f"{dropped:.3e}",
        ]
        if r.outside:
            cells.append("")
        if r.mode is not None:
            cells.append(str(r.mode))
        out.append(",".join(cells) + "\n")
    return out


# --------------------------------------------------------------------------- text


def _where(r: SweepResult, values: tuple[float, ...]) -> str:
    return ", ".join(f"{v.name} = {v.shown(x)}" for v, x in zip(r.variables, values, strict=True))


def text_report(r: SweepResult) -> str:
    mech = r.mechanism
    lines = []
    kind = "grid" if r.grid else "path"
    what = " x ".join(
        f"{v.name} from {v.range[0]:g} to {v.range[1]:g} {unit_text(v.file_unit)} by {v.range[2]:g}"
        for v in r.variables
    )
    on = "" if r.mode is None else f" on its assembly mode {r.mode}"
    lines.append(f"{mech.name}: sweep ({kind}) of {what}, from {r.from_config!r}{on}")
    held = ", ".join(r.held) if r.held else "nothing"
    lines.append(
        f"  {r.points()} samples, {int(r.reached.sum())} reached on the start's assembly mode; "
        f"held at the start's values: {held}"
    )
    lines.append("  tests (smallest relative singular value over the reached samples):")
    for t in r.tests:
        rho = r.ratio[t]
        ok = np.isfinite(rho)
        if not np.any(ok):
            continue
        lowest, spread = float(np.min(rho[ok])), float(np.max(rho[ok]))
        tie = SWEEP_TIE_RTOL * max(abs(lowest), np.finfo(float).tiny)
        head = f"    {t:<10} generic rank {r.generic[t]}"
        if spread - lowest <= tie:
            lines.append(f"{head}, constant {lowest:.3g} over the reached samples")
            continue
        # the first of the tied lowest samples in sweep order: rounding breaks ties either way
        k = np.unravel_index(int(np.argmax(ok & (rho <= lowest + tie))), rho.shape)
        vals = tuple(_values_at(r.variables, tuple(int(x) for x in k)))
        lines.append(f"{head}, lowest {lowest:.3g} at {_where(r, vals)}")
    if not r.located:
        lines.append("  no singularity located on the sweep")
    else:
        lines.append(f"  located singularities ({len(r.located)}):")
        for p in r.located:
            lines.append("    " + _located_line(r, p))
    for lo in r.loci:
        a, b = lo.vertices[0], lo.vertices[-1]
        lines.append(
            f"  locus of {lo.test} ({', '.join(lo.classes) or 'unclassified'}): "
            f"{len(lo.vertices)} vertices from ({r.variables[0].shown(a[0])}, "
            f"{r.variables[1].shown(a[1])}) to ({r.variables[0].shown(b[0])}, "
            f"{r.variables[1].shown(b[1])})" + (", closed" if lo.closed else "")
        )
    if r.aspects:
        lines.append(f"  singularity-free regions (aspects): {len(r.aspects)}")
        for k, a in enumerate(r.aspects):
            (x0, x1), (y0, y1) = a.box
            vx, vy = r.variables
            lines.append(
                f"    {k + 1}: {a.cells} samples, {vx.name} {vx.shown(x0)} to {vx.shown(x1)}, "
                f"{vy.name} {vy.shown(y0)} to {vy.shown(y1)}"
            )
    if r.statics is not None:
        lines += r.statics.text_lines(
            lambda k: _where(r, tuple(_values_at(r.variables, k))), lambda v: _where(r, v)
        )
    if r.dynamics is not None:
        lines += r.dynamics.text_lines(
            lambda k: _where(r, tuple(_values_at(r.variables, k))), lambda v: _where(r, v)
        )
    for note in r.notes:
        lines.append(f"  note: {note}")
    return "\n".join(lines) + "\n"


def located_rows(r: SweepResult) -> list[tuple[str, ...]]:
    """A verdict row (:data:`mechsing.analysis.html.VERDICT_HEADERS`) per located
    singularity, named by where it is and what located it."""
    rows = []
    for p in r.located:
        kind = (
            fold_words(r.mechanism, p.classes)
            if p.kind == "fold"
            else f"{p.kind} of {', '.join(p.tests)}"
        )
        name = f"sweep: {_where(r, p.values)} ({kind})"
        if p.configuration is None:
            rows.append(
                (name, "not classified", "beyond --max-classified", f"measure {p.ratio:.2g}", "-")
            )
        else:
            rows.append(verdict_row(p.configuration, name))
    return rows


def _located_line(r: SweepResult, p: LocatedSingularity) -> str:
    where = _where(r, p.values)
    if p.kind == "fold":
        head = f"{where}: {fold_words(r.mechanism, p.classes)}" + (
            " (met on the other assembly mode; the path resumes past it)" if p.far_side else ""
        )
    else:
        how = {"crossing": "sign change", "sample": "singular sample"}.get(p.kind, "minimum")
        head = f"{where}: {how} of {', '.join(p.tests)}"
    if p.configuration is None:
        return f"{head} (measure {p.ratio:.2g}; not classified: beyond --max-classified)"
    if p.configuration.error:
        return f"{head}: not analysed: {p.configuration.error}"
    if p.unresolved:
        return f"{head} -> not resolved: {p.unresolved}"
    labels = dict.fromkeys(finding_label(f) for f in p.configuration.singularities)
    classes = ", ".join(labels) or "no singularity found by the full analysis"
    if p.kind == "fold" and not p.classes:
        # not unresolved: the coordinate that turns back is a passive joint's
        classes += " (a passive joint at its extreme: the mechanism moves on through it)"
    margin = p.margin or {}
    shown = ""
    if margin.get("dropped") is not None:
        shown = f", dropped singular value {margin['dropped']:.2g}"
    return f"{head} -> {classes} ({p.precision}{shown})"
