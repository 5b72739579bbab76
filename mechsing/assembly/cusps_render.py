"""The ``cusps`` document as text, Markdown or JSON.

Owns :func:`render_cusps`.
"""

from __future__ import annotations

import json
from typing import Any

__all__ = ["render_cusps"]


def _line(k: int, c: dict[str, Any], names: tuple[str, str]) -> str:
    where = ", ".join(f"{n} = {c['inputs'][n]:.12g}" for n in names)
    how = "certified" if c["certified"] else "not certified"
    if "degenerate cusp" in (c.get("not_certified") or ""):
        how += ": a degenerate cusp, its triple-root system singular there"
    if "platform" in c["modes"]:
        at = "the platform at " + ", ".join(
            f"{n} = {v:.6g}" for n, v in c["modes"]["platform"].items()
        )
    else:
        at = ", ".join(f"{n} = {v:.6g}" for n, v in c["modes"].get("joints", {}).items())
    return (
        f"{k}. {where}: three modes meet ({how}"
        + (f", radius {c['radius']:.0e}" if c["certified"] else "")
        + f"){'; at ' + at if at else ''}; {c['modes']['real_modes_at_cusp']} distinct real "
        "modes there"
    )


def render_cusps(doc: dict[str, Any], fmt: str) -> str:
    """``doc`` (:meth:`~mechsing.assembly.cusps.CuspsResult.to_json`) in ``fmt``
    (``text``, ``md`` or ``json``)."""
    if fmt == "json":
        return json.dumps(doc, indent=2) + "\n"
    names = tuple(doc["section"]["vary"])
    ranges = ", ".join(
        f"{n} in [{lo:.6g}, {hi:.6g}]" for n, (lo, hi) in doc["section"]["vary"].items()
    )
    fixed = ", ".join(f"{n} = {v:.12g}" for n, v in doc["section"]["fixed"].items())
    verdict = "cuspidal" if doc["cuspidal"] else "not cuspidal"
    head = f"{doc['mechanism']} ({doc['problem']}): {verdict}; section {ranges}" + (
        f", {fixed}" if fixed else ""
    )
    lines = [head, f"evidence: {doc['evidence']['reason']}"]
    counts = doc["formulation"].get("modes_counts")
    if counts:
        lines.append("real modes on the grid: " + ", ".join(str(c) for c in counts))
    n = len(doc["singular_curves"]["points"])
    if n:
        lines.append(f"singular curves: {n} points located on the grid lines")
    if doc["cusps"]:
        lines.append(f"cusps ({len(doc['cusps'])}):")
        lines += [_line(k, c, names) for k, c in enumerate(doc["cusps"], start=1)]
    if fmt == "md":
        out = [f"## {head}", "", f"*Evidence:* {doc['evidence']['reason']}", ""]
        # the grid's lines of the text (counts of real modes, located points), as there
        out += [f"- {ln}" for ln in lines[2:] if ln.startswith(("real", "sing"))]
        out += [""] if out[-1] != "" else []
        if doc["cusps"]:
            out += [
                f"| # | {names[0]} | {names[1]} | certified | modes there |",
                "|---|---|---|---|---|",
            ]
            for k, c in enumerate(doc["cusps"], start=1):
                out.append(
                    f"| {k} | {c['inputs'][names[0]]:.12g} | {c['inputs'][names[1]]:.12g} | "
                    f"{'yes' if c['certified'] else 'no'} | {c['modes']['real_modes_at_cusp']} |"
                )
        return "\n".join(out) + "\n"
    return "\n".join(lines) + "\n"
