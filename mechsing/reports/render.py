"""Text, Markdown and JSON renderings of an :class:`~mechsing.analysis.AnalysisResult`.

JSON is the one serializer's output (:func:`mechsing.analysis.results.to_json`, the JSON
contract) as text; nothing here builds JSON of its own.  It is deterministic: the same file
gives byte-identical output (keys in a fixed order, floats printed by ``repr``).  Text and
Markdown read the typed results (configurations, findings, margins, mobility, properties)
and explain each finding in a sentence a student understands.
"""

from __future__ import annotations

import json
import math
from typing import Any

from mechsing.analysis.contract import subgroup_params
from mechsing.analysis.describe import OutputMotion
from mechsing.analysis.display import angle_floor, floor_for, shown, unit_text
from mechsing.analysis.results import AnalysisResult, to_json
from mechsing.analysis.words import (
    describe,
    explain,
    joint_list,
    margin_text,
    number_text,
    subgroup_words,
    velocity_space_words,
)
from mechsing.model.couplings import coupling_source, describe_coupling
from mechsing.singularity.findings import (
    ConstraintFinding,
    Finding,
    SerialFinding,
    UndecidedFinding,
)
from mechsing.singularity.zfb import not_run_sentences
from mechsing.subgroups import Subgroup


def _clean(x: Any) -> Any:
    """JSON-safe values: non-finite floats become null, numpy scalars plain."""
    if isinstance(x, dict):
        return {k: _clean(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_clean(v) for v in x]
    if hasattr(x, "item") and not isinstance(x, str):
        x = x.item()
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def to_json_text(result: AnalysisResult) -> str:
    """The JSON contract as text (non-finite floats as null)."""
    return json.dumps(_clean(to_json(result)), indent=2) + "\n"


def _subgroup(sg: Subgroup | None, floor: float = 0.0, L: float = 1.0) -> str:
    """A subgroup and its parameters as text, shown through the display ``floor`` (a
    point's coordinates below it, a direction's below ``floor / L``, are round-off: 0)."""
    if sg is None:
        return "undecided"
    kinds = dict(sg.type.parameters)

    def value(k: str, v: float) -> str:
        return shown(v, floor if kinds.get(k) == "point" else angle_floor(floor, L), ".4g")

    ps = ", ".join(
        f"{k} [{', '.join(value(k, v) for v in val)}]"
        if isinstance(val, list)
        else f"{k} {val:.4g}"
        for k, val in subgroup_params(sg).items()
    )
    return f"{sg.symbol} (dimension {sg.dim}{', ' + ps if ps else ''})"


def _motion_words(m: OutputMotion, length_scale: float) -> str:
    """The output's twist space in words: its subgroup, or its dimension and its twists."""
    head = f"{m.body}" + ("" if m.relative_to == "ground" else f" relative to {m.relative_to}")
    text = _body_motion_words(m, head, length_scale)
    p = m.point
    if p is None:
        return text
    at = ", ".join(f"{x:.4g}" for x in p.position)
    if p.dim is None:
        return f"{text}; its point at ({at}) {unit_text('m')}: undecided"
    return f"{text}; its point at ({at}) {unit_text('m')} {velocity_space_words(p.velocities)}"


def _body_motion_words(m: OutputMotion, head: str, length_scale: float) -> str:
    if m.dim is None:
        return f"{head}'s twists: undecided at {m.precision} ({m.note})"
    if m.instantaneous_screw and m.subgroup is not None:
        # one twist: the screw the output turns about at this instant, not a motion type
        screw = describe(m.twists[0], "twist", length_scale)
        return f"{head}'s instantaneous screw: {screw} ({subgroup_words(m.subgroup)})"
    if m.is_subgroup and m.subgroup is not None:
        return f"{head}'s twists span {subgroup_words(m.subgroup)}"
    if m.dim == 0:
        return f"{head} cannot move here (to first order)"
    if m.is_subgroup is False and m.generated is not None:
        kind = f"not a subgroup: they generate {m.generated.symbol}, dimension {m.generated.dim}"
    else:
        kind = "not a subgroup" if m.is_subgroup is False else (m.note or "type not identified")
    text = f"{head}'s twists span dimension {m.dim} ({kind})"
    if m.point is not None:  # the point's motion says what matters
        return text
    if m.dim > _TWISTS_IN_WORDS:
        return f"{text}; a basis is in the JSON"
    return f"{text}, e.g. " + "; ".join(describe(t, "twist", length_scale) for t in m.twists)


#: the most basis twists of an output motion the text spells out (more read as noise)
_TWISTS_IN_WORDS = 3


def screw_lines(f: Finding, length_scale: float) -> list[str]:
    """The twists and wrenches of a finding in words (lost twist, resisted or constraint
    wrenches, the output's motion), one line each."""
    out = []
    if isinstance(f, SerialFinding):
        out.append(f"lost twist: {describe(f.twist, 'twist', length_scale)}")
        for w in f.wrenches:
            out.append(f"resisted wrench: {describe(w, 'wrench', length_scale)}")
    elif isinstance(f, ConstraintFinding):
        for w in f.wrenches:
            out.append(f"constraint wrench: {describe(w, 'wrench', length_scale)}")
    elif getattr(f, "output_twist", None) is not None:
        out.append(f"output motion: {describe(f.output_twist, 'twist', length_scale)}")
    return out


def scene_line(note: str) -> str:
    """A scene note (:class:`mechsing.model.Scene`) as a sentence of a report."""
    return f"{note[:1].upper()}{note[1:]}."


def joint_values_text(c: Any, length_scale: float) -> str:
    """A configuration's joint values (m, rad) as text, each below the display floor of
    its precision (:func:`mechsing.analysis.display.floor_for`; the smaller of a length's
    and an angle's, as a coordinate may be either) shown as 0."""
    floor = floor_for(c.precision, length_scale)
    floor = min(floor, angle_floor(floor, length_scale))
    return ", ".join(f"{k} = [{', '.join(shown(x, floor) for x in v)}]" for k, v in c.joints)


def _units() -> str:
    """``m, rad``: the units of joint values, limits and poses, as the text spells them."""
    return f"{unit_text('m')}, {unit_text('rad')}"


def render_text(result: AnalysisResult, markdown: bool = False) -> str:
    """The text (or Markdown) report of ``result``: the precision, the mechanism's
    properties, then each configuration with its loops, closure rank, mobility and
    findings, each finding explained in a sentence with its margin."""
    h1, h2 = ("# ", "## ") if markdown else ("", "")
    bullet = "- " if markdown else "  "
    lines = [f"{h1}mechsing analysis: {result.mechanism.name}", ""]
    mode, t = str(result.precision), result.precision.tolerances
    thresholds = (
        "exact ranks"
        if mode == "exact"
        else "rank thresholds {} and {} of the largest singular value".format(*t.shown())
    )
    lines.append(
        f"Precision {mode} ({thresholds}); characteristic length L = "
        f"{result.length_scale:.4g} {unit_text('m')}."
    )
    if result.mechanism.limits:
        limits = ", ".join(
            f"{k} " + " ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in v)
            for k, v in result.mechanism.limits.items()
        )
        lines.append(f"Joint limits ({_units()}): {limits}.")
    if result.mechanism.scene is not None:
        lines += [scene_line(note) for note in result.mechanism.scene.notes]
    for sentence in not_run_sentences(result.mechanism):
        lines.append(f"Tests not run: {sentence}.")
    if result.properties:
        lines += ["", f"{h2}Properties" if markdown else "Properties:"]
        for prop in result.properties:
            lines.append(f"{bullet}{prop.kind}: {prop.explanation}")
    L = result.length_scale
    if result.legs:
        first = result.legs[0]
        title = f"Legs (joints from {first.base} to {first.body})"
        lines += ["", f"{h2}{title}" if markdown else f"{title}:"]
        for leg in result.legs:
            inner = (
                f" (and {joint_list(leg.other_joints)} in loops inside the leg)"
                if leg.other_joints
                else ""
            )
            lines.append(f"{bullet}leg {leg.number}: {' - '.join(leg.joints)}{inner}")
    if result.output_motion is not None:
        om = result.output_motion
        lines += [
            "",
            f"{h2}Output motion" if markdown else "Output motion:",
            f"{bullet}generic (at the first regular configuration, {om.configuration}): "
            f"{_motion_words(om, L)}",
        ]
    for c in result.configurations:
        lines += [
            "",
            f"{h2}Configuration {c.name}"
            if markdown
            else f"Configuration {c.name} ({c.precision}):",
        ]
        if c.error is not None:
            lines.append(f"{bullet}not analysed: {c.error}")
            continue
        floor = floor_for(c.precision, result.length_scale)
        if c.pose is not None:
            gp = c.pose
            rel = (
                ""
                if gp.relative_to == result.mechanism.ground
                else f" relative to {gp.relative_to}"
            )
            lines.append(
                f"{bullet}given pose of {gp.body}{rel} ({_units()}): reference point at "
                f"({', '.join(shown(x, floor) for x in gp.position)}), rotation vector "
                f"({', '.join(shown(x, angle_floor(floor, L)) for x in gp.rotation_vector)})"
                " about it"
            )
        lines.append(f"{bullet}joint values ({_units()}): {joint_values_text(c, L)}")
        if c.underdetermined:
            lines.append(f"{bullet}{_underdetermined(result.mechanism, c)}")
        outside = _outside_limits(result.mechanism.limits, c.joints)
        if outside:
            lines.append(f"{bullet}outside the joint limits: {', '.join(outside)}")
        lines.append(
            f"{bullet}closure residual {shown(c.closure_residual, floor, '.3g')} {unit_text('m')}"
        )
        for note in c.notes:
            lines.append(f"{bullet}note: {note}")
        for lp in c.loops:
            sig = ", ".join(f"{s:.4g}" for s in (lp.sigma or ()))
            lines.append(
                f"{bullet}loop {'-'.join(lp.joints)}: moves inside {_subgroup(lp.subgroup, floor, L)}; "
                f"rank {number_text(lp.rank)}" + (f", singular values {sig}" if sig else "")
            )
        for cp in result.mechanism.couplings:
            lines.append(
                f"{bullet}coupling {describe_coupling(cp)} ({coupling_source(cp)}): one row of "
                "the closure system"
            )
        cr = c.closure_rank
        assert cr is not None and c.mobility is not None  # an analysed configuration has both
        lines.append(
            f"{bullet}closure system: rank {number_text(cr.rank)}, nullity {number_text(cr.nullity)}; "
            f"margin: {margin_text(cr.margin)}"
        )
        m = c.mobility
        lines.append(
            f"{bullet}mobility: finite {number_text(m.finite)} (generic {number_text(m.generic)}, "
            f"instantaneous {number_text(m.instantaneous)}, group {number_text(m.group)}, "
            f"spatial Grubler-Kutzbach count {number_text(m.grubler)})"
        )
        if c.output_motion is not None:
            lines.append(f"{bullet}output motion: {_motion_words(c.output_motion, L)}")
        if c.data_resolution is not None:
            lines.append(f"{bullet}verdict: {c.data_resolution.verdict} (see the note).")
        if c.kinetostatics is not None:
            lines += [f"{bullet}{t}." for t in c.kinetostatics.text_lines()]
        if not c.singularities:
            lines.append(f"{bullet}regular: no singularity.")
        for s in c.singularities:
            lines.append(f"{bullet}{s.cls}: {explain(s)}.")
            sub = "  - " if markdown else "    "
            lines += [f"{sub}{line}" for line in screw_lines(s, L)]
            verb = "tested" if isinstance(s, UndecidedFinding) else "decided"
            lines.append(f"{sub}{verb} in {s.precision}; margin: {margin_text(s.margin)}")
    return "\n".join(lines) + "\n"


def _underdetermined(mech: Any, c: Any) -> str:
    """Why some joint values were chosen rather than given: the configuration's values
    leave freedom, and continuation took the minimum-norm steps."""
    conf = mech.configurations.get(c.name)
    given = sorted(conf.values, key=[j.name for j in mech.joints].index) if conf else []
    start = conf.start if conf is not None and conf.start else "reference"
    said = f"the values given ({', '.join(given)})" if given else "the values given"
    return (
        f"underdetermined: {said} leave the mechanism free to move, so the other joints "
        f"took the smallest (minimum-norm) steps from {start}; give more joint values to fix them"
    )


def _outside_limits(limits: Any, joints: Any) -> list[str]:
    """The joints of a configuration whose values lie outside the file's ``limits``."""
    out = []
    for k, v in joints:
        for x, (lo, hi) in zip(v, limits.get(k, ()), strict=False):
            if not lo <= x <= hi:
                out.append(k)
                break
    return out


def render(result: AnalysisResult, fmt: str) -> str:
    if fmt == "json":
        return to_json_text(result)
    if fmt == "md":
        return render_text(result, markdown=True)
    return render_text(result)
