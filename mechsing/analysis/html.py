"""The verdict of an analysis in words and as a small HTML table (a notebook's view).

Owns the verdict row of a configuration (:func:`verdict_row`: singular or not, classes in words, margin, the precision
that decided it; the classes' words are :mod:`mechsing.analysis.words`'), and :func:`html_table`, an escaped HTML table with no style of its own.
:meth:`AnalysisResult._repr_html_ <mechsing.analysis.results.AnalysisResult>` and the
sweeps' result show these tables in a Jupyter notebook; the design-review report
(:mod:`mechsing.reports`) builds its verdict table from the same rows, so the two agree.

Margins are relative singular values: ``dropped / sigma_max`` for a singular verdict (the
decision needed it at or below ``tau_lo``) and ``kept / sigma_max`` for the closest regular
decision (at or above ``tau_hi``); exact mode shows the smallest kept pivot.
"""

from __future__ import annotations

from collections.abc import Sequence
from html import escape
from typing import Any

from mechsing.analysis.words import class_words, finding_label
from mechsing.numeric import Margin

#: a ConfigurationResult (not imported: the results import this module)
ConfigurationResult = Any

__all__ = [
    "VERDICT_HEADERS",
    "decided_in",
    "html_table",
    "largest_drop",
    "margin_words",
    "verdict_row",
]

VERDICT_HEADERS = ("configuration", "singular", "classes", "margin", "decided in")


def _relative(m: Margin, value: float | None) -> float | None:
    if value is None:
        return None
    return value / m.sigma_max if m.sigma_max else value


def largest_drop(c: ConfigurationResult) -> tuple[float, Margin] | None:
    """The largest relative singular value a singular finding of ``c`` counted as zero,
    with its margin (None when there is none: regular, or decided exactly)."""
    drops = [
        (_relative(s.margin, s.margin.dropped), s.margin)
        for s in c.singularities
        if s.cls != "undecided" and s.margin is not None
    ]
    known = [(d, m) for d, m in drops if d is not None]
    return max(known, key=lambda t: t[0]) if known else None


def margin_words(c: ConfigurationResult) -> str:
    """The margin of a configuration's verdict in words (see the module docstring)."""
    if c.error is not None:
        return "-"
    singular = [s for s in c.singularities if s.cls != "undecided" and s.margin is not None]
    if singular:
        worst = largest_drop(c)
        if worst is not None:
            return f"dropped {worst[0]:.3g} <= tau_lo {worst[1].tau_lo:.3g}"
        return "rank decided exactly"
    if any(s.cls == "undecided" for s in c.singularities):
        return "a singular value between tau_lo and tau_hi"
    kept = [
        (_relative(d.margin, d.margin.kept), d.margin)
        for d in c.decisions
        if d.rank is not None and d.margin.kept is not None
    ]
    if not kept:
        return "-"
    k, m = min(kept, key=lambda t: t[0])
    if m.sigma_max is None:
        return f"smallest kept pivot {k:.3g}"
    return f"smallest kept {k:.3g} >= tau_hi {m.tau_hi:.3g}"


def verdict_row(c: ConfigurationResult, name: str | None = None) -> tuple[str, ...]:
    """One row of the verdict table (:data:`VERDICT_HEADERS`) for a configuration."""
    if c.error is not None:
        return (name or c.name, "not analysed", c.error, "-", c.precision)
    singular = {True: "yes", False: "no", None: "undecided"}[c.singular]
    classes = class_words([finding_label(s) for s in c.singularities])
    margin = margin_words(c)
    below = getattr(c, "data_resolution", None)
    if below is not None:  # the verdict holds of the written decimals only
        margin = f"{margin}; {below.verdict}"
    return (name or c.name, singular, classes, margin, decided_in(c))


def decided_in(c: ConfigurationResult) -> str:
    """The precision a configuration's verdict was decided at, with the tests that ran at
    another (exact mode runs the input/output and cone tests at mp:50 from exact data)."""
    other: dict[str, list[str]] = {}
    for d in c.decisions:
        if d.precision != c.precision:
            other.setdefault(d.precision, []).append(d.test)
    for s in c.singularities:
        ran = getattr(s, "test_precision", None) or s.precision
        if ran != c.precision and s.cls not in other.get(ran, []):
            other.setdefault(ran, []).append(s.cls)
    if not other:
        return c.precision
    parts = [f"the {', '.join(dict.fromkeys(tests))} tests at {p}" for p, tests in other.items()]
    return f"{c.precision} ({'; '.join(parts)})"


def html_table(
    headers: Sequence[str], rows: Sequence[Sequence[str]], caption: str | None = None
) -> str:
    """An HTML table, every cell escaped; no style of its own (the page's applies)."""
    out = ["<table>"]
    if caption:
        out.append(f"<caption>{escape(caption)}</caption>")
    out.append("<thead><tr>" + "".join(f"<th>{escape(h)}</th>" for h in headers) + "</tr></thead>")
    out.append("<tbody>")
    for row in rows:
        out.append("<tr>" + "".join(f"<td>{escape(str(x))}</td>" for x in row) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)
