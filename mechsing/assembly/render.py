"""The ``modes`` document as text, Markdown or JSON.

Owns :func:`render_modes`.
"""

from __future__ import annotations

import json

from mechsing.analysis.display import angle_floor, floor_for, markdown_table, shown, with_unit
from mechsing.assembly.api import ModesResult

__all__ = ["modes_heading", "render_modes"]


def _verdict(m: dict) -> str:
    if m["singular"] is None and not m["singularities"]:
        return "not classified"
    if not m["singular"]:
        return "regular"
    classes = sorted({s["class"] for s in m["singularities"]})
    return "singular: " + ", ".join(classes)


def _value(text: str, unit: str, floor: dict[str, float]) -> str:
    """A joint value (its text at the working digits) with its unit: 0 below the display
    floor of its unit (round-off of a joint at 0), else as computed."""
    if abs(float(text)) < floor.get(unit, 0.0):
        text = shown(0.0)
    return with_unit(text, unit)


def modes_heading(res: ModesResult) -> str:
    f = res.formulation
    if res.count is None:
        return (
            f"{res.mechanism}, configuration {res.configuration}: the closed configurations "
            "with these values form a curve, not a finite set of modes (no count)"
        )
    if f.get("proven_without_tracking"):  # nothing solved: the proof is what happened
        how = f"proven without tracking: {f['proven_without_tracking']}"
    elif res.paths:
        how = (
            f"{f['method']} in {f['name']}: {res.paths['tracked']} paths, "
            f"{res.paths['finite']} finite"
        )
    else:
        how = f"{f['method']} in the {f['name']}, a polynomial of degree {f['polynomial_degree']}"
    kind = "working" if f.get("working_modes") else "assembly"
    return (
        f"{res.mechanism}, configuration {res.configuration}: {res.count} {kind} "
        f"mode{'s' if res.count != 1 else ''} (complete: {res.complete}; {how})"
    )


def render_modes(
    res: ModesResult, fmt: str, units: dict[str, tuple[str, ...]] | None = None
) -> str:
    """``res`` as ``text``, ``md`` or ``json``; ``units``: each joint's coordinates' units
    (SI, radians: :attr:`Joint.units`), shown after the values in text and Markdown."""
    doc = res.to_json()
    if fmt == "json":
        return json.dumps(doc, indent=2) + "\n"
    md = fmt == "md"
    L = res.precision.get("length_scale", 1.0)
    floor = floor_for(res.precision["mode"], L)
    floor = {"m": floor, "rad": angle_floor(floor, L)}
    lines = [("# " if md else "") + modes_heading(res), ""]
    for k, m in enumerate(doc["modes"], 1):
        marks = []
        if m["reached_by_continuation"]:
            marks.append("reached by continuation")
        if m["outside_limits"]:
            marks.append("outside the limits of " + ", ".join(m["outside_limits"]))
        cert = (
            f"certified (radius {m['certified_radius']:.0e})" if m["certified"] else "not certified"
        )
        if m["equivalent_solutions"] > 1:
            marks.append(f"stands for {m['equivalent_solutions']} joint solutions")
        head = f"mode {k}: {_verdict(m)}, {cert}" + (f" [{'; '.join(marks)}]" if marks else "")
        lines.append(("## " if md else "") + head)
        rows = []
        for name, vals in m["joints_text"].items():
            marks_of = (units or {}).get(name, ())
            shown = ", ".join(
                _value(v, marks_of[i], floor) if i < len(marks_of) else v
                for i, v in enumerate(vals)
            )
            rows.append((name, shown))
        if md:
            lines += ["", *markdown_table(("joint", "value"), rows)]
        else:
            lines += [f"  {name}: {shown}" for name, shown in rows]
        lines.append("")
    said = doc["formulation"].get("proven_without_tracking")
    for note in doc["notes"]:
        if note != said:  # the heading says it
            lines.append(f"note: {note}")
    return "\n".join(lines).rstrip() + "\n"
