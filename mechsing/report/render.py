"""Text, Markdown and JSON renderings of an :class:`~mechsing.analysis.AnalysisResult`.

All three read the one serializer's output (:func:`mechsing.analysis.results.to_json`, the
JSON contract); none builds JSON of its own.  JSON is deterministic: the same file gives byte-identical output (keys in a
fixed order, floats printed by ``repr``).  Text and Markdown explain each
finding in a sentence a student understands.
"""

from __future__ import annotations

import json
import math
from typing import Any

from mechsing.analysis.results import AnalysisResult, to_json

EXPLAIN = {
    "serial": "the chain's screws span fewer directions than usual: it has lost a direction of motion "
    "and now resists some wrenches with no joint effort",
    "bifurcation": "several branches of motion cross here: the mechanism can leave this configuration "
    "along different paths",
    "isolated": "no motion leaves this configuration: it is a rigid, isolated assembly",
    "degenerate": "the loops lose rank and the higher-order test cannot describe the motions here "
    "(a cusp or tangential branches)",
    "increased-mobility": "the joints can move instantaneously in more ways than the mechanism can "
    "actually move (first-order motions that do not extend)",
    "input": "an input can move while the output stays still",
    "output": "the output can move while the inputs are locked: the mechanism loses stiffness",
    "passive-motion": "passive joints can move while the inputs and the output stay still",
    "impossible-input": "some input rates cannot be produced",
    "impossible-output": "some output twists cannot be produced",
    "constraint": "the legs' constraint wrenches lose rank: the output gains a motion outside its "
    "generic motion type",
    "undecided": "the precision used cannot decide a rank here (a singular value lies between the two "
    "thresholds)",
}


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


def _fmt_num(x: Any) -> str:
    if x is None:
        return "-"
    if isinstance(x, float):
        return f"{x:.4g}"
    return str(x)


def _margin(m: dict[str, Any] | None) -> str:
    if not m:
        return ""
    parts = [f"kept {_fmt_num(m.get('kept'))}", f"dropped {_fmt_num(m.get('dropped'))}"]
    if "eig_margin" in m:
        parts.append(f"eigenvalue margin {_fmt_num(m['eig_margin'])}")
    return (
        ", ".join(parts)
        + f" (thresholds {m['tau_lo']:g}/{m['tau_hi']:g}, L = {m['length_scale']:.4g} m)"
    )


def _names(xs: list[str]) -> str:
    if not xs:
        return "no joint"
    return ", ".join(xs[:-1]) + (" and " if len(xs) > 1 else "") + xs[-1]


def explain(f: dict[str, Any]) -> str:
    """One sentence a student understands, with the finding's own numbers."""
    cls = f["class"]
    j = _names(f.get("joints", []))
    if cls == "serial":
        what = f"leg {f['leg']}" if f.get("chain") == "leg" else "the chain to the output"
        return (
            f"{what} loses {f['corank']} direction(s) of motion (rank {f['rank']} instead of "
            f"{f['generic_rank']}): joints {j} can move while its end stays still, and it resists "
            f"{f['corank']} more wrench(es) than usual with no joint effort ({len(f['wrenches'])} in all)"
        )
    if cls == "bifurcation":
        mobs = ", ".join("?" if m is None else str(m) for m in f.get("branch_mobility", []))
        kin = (
            " (branches of different mobility meet: a kinematotropic point)"
            if f.get("kinematotropic")
            else ""
        )
        return (
            f"{f['branches']} branches of motion cross here (branch mobilities {mobs}){kin}: from this "
            f"configuration the mechanism can leave along different paths, decided at order {f.get('order')}"
        )
    if cls == "isolated":
        return (
            f"the joints have {f.get('instantaneous')} instantaneous motion(s), but none extends to a real "
            "motion: this assembly is rigid and no nearby configuration closes"
        )
    if cls == "degenerate":
        return f"the loops lose rank and the higher-order test cannot describe the motion here ({f.get('note', '')})"
    if cls == "increased-mobility":
        return (
            f"the joints have {f['instantaneous']} instantaneous motion(s) where the mechanism moves with "
            f"{f['generic']}: the extra ones do not extend, and one smooth branch passes through"
        )
    if cls == "input":
        return f"an input can move while the output stays still (moving joints: {j}): the output loses a direction"
    if cls == "output":
        return (
            f"with the inputs locked the output can still move (moving joints: {j}): the mechanism loses "
            "stiffness and actuator forces can grow without bound"
        )
    if cls == "passive-motion":
        return f"passive joints {j} can move while the inputs and the output stay still"
    if cls == "impossible-input":
        return (
            f"the inputs can take only {f['rank']} independent rates here instead of {f['generic']}"
        )
    if cls == "impossible-output":
        return f"the output can make only {f['rank']} independent motions here instead of {f['generic']}"
    if cls == "constraint":
        return (
            f"the legs' constraint wrenches drop to rank {f['rank']} (generically {f['generic_rank']}): the output "
            "gains a motion outside its usual motion type"
        )
    if cls == "undecided":
        what = f.get("what", "system")
        bounds = f.get("rank_bounds")
        why = (
            f"its rank lies between {bounds[0]} and {bounds[1]}"
            if bounds
            else f.get("note", "a singular value lies between the two thresholds")
        )
        return f"the precision used cannot decide the {what} ({why}); {_more_precise(f)}"
    return EXPLAIN.get(cls, cls)


def _more_precise(f: dict[str, Any]) -> str:
    """What to try after an undecided test, from the precision that left it open."""
    prec = str(f.get("precision", "float"))
    if prec.startswith("mp:"):
        digits = int(prec[3:])
        return (
            f"try --precision mp:{2 * digits}, or exact with exact data (the configuration may "
            f"be within 10^-{digits // 2} of a singularity)"
        )
    if prec == "exact":
        return "the test ran at mp:50 from the exact data: try a larger --precision mp:N"
    return "try --precision mp:50 or exact"


def _subgroup(sg: dict[str, Any]) -> str:
    if not sg or sg.get("type") is None:
        return "undecided"
    ps = ", ".join(
        f"{k} [{', '.join(f'{v:.4g}' for v in val)}]" if isinstance(val, list) else f"{k} {val:.4g}"
        for k, val in sg.get("params", {}).items()
    )
    return f"{sg['type']} (dimension {sg['dim']}{', ' + ps if ps else ''})"


def render_text(result: AnalysisResult, markdown: bool = False) -> str:
    d = to_json(result)
    h1, h2 = ("# ", "## ") if markdown else ("", "")
    bullet = "- " if markdown else "  "
    lines = [f"{h1}mechsing analysis: {d['mechanism']}", ""]
    p = d["precision"]
    thresholds = (
        "exact ranks"
        if p["mode"] == "exact"
        else f"rank thresholds {p['tau_lo']:g} and {p['tau_hi']:g} of the largest singular value"
    )
    lines.append(
        f"Precision {p['mode']} ({thresholds}); characteristic length L = {p['length_scale']:.4g} m."
    )
    if d["properties"]:
        lines += ["", f"{h2}Properties" if markdown else "Properties:"]
        for prop in d["properties"]:
            text = prop.get("explanation") or ", ".join(
                f"{k} {v}" for k, v in prop.items() if k != "kind"
            )
            lines.append(f"{bullet}{prop['kind']}: {text}")
    for c in d["configurations"]:
        lines += [
            "",
            f"{h2}Configuration {c['name']}"
            if markdown
            else f"Configuration {c['name']} ({c['precision']}):",
        ]
        if "error" in c:
            lines.append(f"{bullet}not analysed: {c['error']}")
            continue
        vals = ", ".join(
            f"{k} = [{', '.join(f'{x:.6g}' for x in v)}]" for k, v in c["joints"].items()
        )
        lines.append(f"{bullet}joint values (m, rad): {vals}")
        lines.append(f"{bullet}closure residual {c['closure_residual']:.3g} m")
        for note in c.get("notes", []):
            lines.append(f"{bullet}note: {note}")
        for lp in c["loops"]:
            sig = ", ".join(f"{s:.4g}" for s in (lp["sigma"] or []))
            lines.append(
                f"{bullet}loop {'-'.join(lp['joints'])}: moves inside {_subgroup(lp['subgroup'])}; "
                f"rank {_fmt_num(lp['rank'])}" + (f", singular values {sig}" if sig else "")
            )
        cr = c["closure_rank"]
        lines.append(
            f"{bullet}closure system: rank {_fmt_num(cr['rank'])}, nullity {_fmt_num(cr['nullity'])}; "
            f"margin: {_margin(cr['margin'])}"
        )
        m = c["mobility"]
        lines.append(
            f"{bullet}mobility: finite {_fmt_num(m['finite'])} (generic {_fmt_num(m['generic'])}, "
            f"instantaneous {_fmt_num(m['instantaneous'])}, group {_fmt_num(m['group'])}, "
            f"spatial Grubler-Kutzbach count {_fmt_num(m['grubler'])})"
        )
        if not c["singularities"]:
            lines.append(f"{bullet}regular: no singularity.")
        for s in c["singularities"]:
            lines.append(f"{bullet}{s['class']}: {explain(s)}.")
            if "margin" in s:
                sub = "  - " if markdown else "    "
                verb = "tested" if s["class"] == "undecided" else "decided"
                lines.append(
                    f"{sub}{verb} in {s.get('precision', c['precision'])}; margin: {_margin(s['margin'])}"
                )
    return "\n".join(lines) + "\n"


def render(result: AnalysisResult, fmt: str) -> str:
    if fmt == "json":
        return to_json_text(result)
    if fmt == "md":
        return render_text(result, markdown=True)
    return render_text(result)
