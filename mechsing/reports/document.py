"""A design-review document as a list of blocks, and its HTML and Markdown forms.

Owns the blocks (:class:`Heading`, :class:`Paragraph`, :class:`Bullets`, :class:`Table`,
:class:`Figure`, :class:`Details`) that :mod:`mechsing.reports.review` builds, and the two
writers: :func:`to_html` (one self-contained HTML5 file: inline CSS, figures as SVG data
URIs, no script, nothing fetched; tables scroll sideways and figures shrink on a narrow
window; printable) and :func:`to_markdown` (GitHub-flavoured Markdown, the figures written
as SVG files in a folder and linked relatively).  Every text is escaped by the writers: the
blocks hold plain text.
"""

from __future__ import annotations

import base64
import os
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from html import escape
from pathlib import Path

__all__ = [
    "Block",
    "Bullets",
    "Details",
    "Figure",
    "Heading",
    "Paragraph",
    "Table",
    "markdown",
    "slug",
    "to_html",
    "to_markdown",
]


@dataclass(frozen=True)
class Heading:
    level: int
    text: str


@dataclass(frozen=True)
class Paragraph:
    text: str
    #: a short lead in bold (e.g. "Verdict:")
    lead: str = ""


@dataclass(frozen=True)
class Bullets:
    items: tuple[str, ...]


@dataclass(frozen=True)
class Table:
    headers: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    caption: str = ""
    #: the row index of each row that marks a problem (shown highlighted)
    marked: frozenset[int] = frozenset()


@dataclass(frozen=True)
class Figure:
    """A figure: its file name (``name.svg`` in Markdown), the SVG text, a text
    alternative and a caption."""

    name: str
    svg: str = field(repr=False)
    alt: str
    caption: str = ""


@dataclass(frozen=True)
class Details:
    """A block a reader opens on demand (``<details>`` in HTML; a plain section in
    Markdown)."""

    summary: str
    blocks: tuple[Block, ...]


Block = Heading | Paragraph | Bullets | Table | Figure | Details


def slug(text: str) -> str:
    """A file or anchor name from a text: lower case, letters, digits and dashes."""
    s = re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")
    return s or "x"


# --------------------------------------------------------------------------- HTML

#: the page's style: readable at 1280 px and at phone width, printable
CSS = """
.mechsing-report { font-family: system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans",
  sans-serif; line-height: 1.45; color: #1a1a1a; max-width: 1100px; margin: 0 auto;
  padding: 0 1rem 2rem; }
.mechsing-report p, .mechsing-report li, .mechsing-report figcaption { overflow-wrap: anywhere; }
.mechsing-report h1 { font-size: 1.6rem; margin: 1rem 0 0.5rem; }
.mechsing-report h2 { font-size: 1.3rem; margin: 1.8rem 0 0.5rem; border-bottom: 1px solid #ccc; }
.mechsing-report h3 { font-size: 1.1rem; margin: 1.4rem 0 0.4rem; }
.mechsing-report .table-wrap { overflow-x: auto; margin: 0.5rem 0 1rem; }
.mechsing-report table { border-collapse: collapse; font-size: 0.9rem; min-width: 36rem; }
.mechsing-report th { white-space: nowrap; }
.mechsing-report caption { text-align: left; font-style: italic; padding: 0.2rem 0; }
.mechsing-report th, .mechsing-report td { border: 1px solid #bbb; padding: 0.25rem 0.5rem;
  text-align: left; vertical-align: top; }
.mechsing-report th { background: #eef1f5; }
.mechsing-report tr.problem td { background: #fdecea; }
.mechsing-report figure { margin: 0.8rem 0 1.2rem; }
.mechsing-report figure img { max-width: 100%; height: auto; display: block;
  border: 1px solid #ddd; }
.mechsing-report figcaption { font-size: 0.85rem; color: #444; margin-top: 0.3rem; }
.mechsing-report details { margin: 0.5rem 0 1rem; }
.mechsing-report summary { cursor: pointer; }
@media (max-width: 600px) {
  .mechsing-report { padding: 0 0.5rem 1rem; }
  .mechsing-report table { font-size: 0.8rem; }
}
@media print {
  .mechsing-report { max-width: none; }
  .mechsing-report figure, .mechsing-report table { break-inside: avoid; }
  .mechsing-report details > * { display: block; }
}
"""


def _svg_uri(svg: str) -> str:
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode("ascii")


def _html_block(b: Block) -> str:
    if isinstance(b, Heading):
        return f'<h{b.level} id="{slug(b.text)}">{escape(b.text)}</h{b.level}>'
    if isinstance(b, Paragraph):
        lead = f"<strong>{escape(b.lead)}</strong> " if b.lead else ""
        return f"<p>{lead}{escape(b.text)}</p>"
    if isinstance(b, Bullets):
        return "<ul>\n" + "\n".join(f"<li>{escape(x)}</li>" for x in b.items) + "\n</ul>"
    if isinstance(b, Table):
        out = ['<div class="table-wrap"><table>']
        if b.caption:
            out.append(f"<caption>{escape(b.caption)}</caption>")
        out.append(
            "<thead><tr>" + "".join(f"<th>{escape(h)}</th>" for h in b.headers) + "</tr></thead>"
        )
        out.append("<tbody>")
        for i, row in enumerate(b.rows):
            cls = ' class="problem"' if i in b.marked else ""
            out.append(f"<tr{cls}>" + "".join(f"<td>{escape(x)}</td>" for x in row) + "</tr>")
        out.append("</tbody></table></div>")
        return "\n".join(out)
    if isinstance(b, Figure):
        cap = f"<figcaption>{escape(b.caption)}</figcaption>" if b.caption else ""
        return f'<figure><img src="{_svg_uri(b.svg)}" alt="{escape(b.alt)}">{cap}</figure>'
    inner = "\n".join(_html_block(x) for x in b.blocks)
    return f"<details><summary>{escape(b.summary)}</summary>\n{inner}\n</details>"


def html_fragment(blocks: Sequence[Block]) -> str:
    """The blocks as an HTML fragment with its own style (a notebook's output)."""
    body = "\n".join(_html_block(b) for b in blocks)
    return f'<style>{CSS}</style>\n<div class="mechsing-report">\n{body}\n</div>\n'


def to_html(blocks: Sequence[Block], title: str) -> str:
    """One self-contained HTML5 page of the blocks."""
    body = "\n".join(_html_block(b) for b in blocks)
    return (
        "<!DOCTYPE html>\n"
        '<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        '<meta name="viewport" content="width=device-width, initial-scale=1">\n'
        f"<title>{escape(title)}</title>\n<style>{CSS}</style>\n</head>\n"
        f'<body>\n<main class="mechsing-report">\n{body}\n</main>\n</body>\n</html>\n'
    )


# --------------------------------------------------------------------------- Markdown


def _md_text(text: str) -> str:
    """Plain text safe in Markdown (the characters Markdown would read as markup)."""
    return re.sub(r"([\\`*_\[\]<>|#])", r"\\\1", text)


def _md_block(b: Block, figures: dict[str, str], link: str) -> list[str]:
    if isinstance(b, Heading):
        return ["#" * b.level + " " + _md_text(b.text), ""]
    if isinstance(b, Paragraph):
        lead = f"**{_md_text(b.lead)}** " if b.lead else ""
        return [lead + _md_text(b.text), ""]
    if isinstance(b, Bullets):
        return [f"- {_md_text(x)}" for x in b.items] + [""]
    if isinstance(b, Table):
        out = [f"*{_md_text(b.caption)}*", ""] if b.caption else []
        out.append("| " + " | ".join(_md_text(h) for h in b.headers) + " |")
        out.append("|" + "|".join("---" for _ in b.headers) + "|")
        for i, row in enumerate(b.rows):
            cells = [_md_text(x) for x in row]
            if i in b.marked:
                cells[0] = f"**{cells[0]}**"
            out.append("| " + " | ".join(cells) + " |")
        return [*out, ""]
    if isinstance(b, Figure):
        figures[f"{b.name}.svg"] = b.svg
        out = [f"![{_md_text(b.alt)}]({link}/{b.name}.svg)", ""]
        if b.caption:
            out += [f"*{_md_text(b.caption)}*", ""]
        return out
    lines = [f"**{_md_text(b.summary)}**", ""]
    for x in b.blocks:
        lines += _md_block(x, figures, link)
    return lines


def markdown(blocks: Sequence[Block], link: str) -> tuple[str, dict[str, str]]:
    """The blocks as GitHub-flavoured Markdown, its figures linked as ``link/NAME.svg``,
    and the figures to write there (file name to SVG text)."""
    figures: dict[str, str] = {}
    lines: list[str] = []
    for b in blocks:
        lines += _md_block(b, figures, link)
    return "\n".join(lines).rstrip("\n") + "\n", figures


def to_markdown(
    blocks: Sequence[Block],
    folder: str | Path,
    relative_to: str | Path,
    inputs: Sequence[str | Path] = (),
) -> str:
    """The blocks as GitHub-flavoured Markdown; the figures are written into ``folder``
    (created; its parent must exist) and linked relative to the directory ``relative_to``
    (where the Markdown file is).  No figure may be one of the files ``inputs``
    (:mod:`mechsing.files`: each is written atomically)."""
    from mechsing.files import check_output, make_output_folder, write_output

    folder = make_output_folder(folder, inputs)
    link = Path(os.path.relpath(folder, Path(relative_to).resolve())).as_posix()
    text, figures = markdown(blocks, link)
    paths = [folder / name for name in figures]
    for path in paths:  # every figure checked before any is written
        check_output(path, inputs)
    for path, svg in zip(paths, figures.values(), strict=True):
        write_output(path, svg, inputs)
    return text
