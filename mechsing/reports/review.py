"""The design-review report: :func:`report` and :class:`Report` (HTML, Markdown, notebook).

A report holds the analysis of a mechanism's configurations (:func:`mechsing.analyze`) and
at most one sweep (:func:`mechsing.sweep`: a path or a grid), and reads them in the order a
reviewer does: the verdict table first (a row per configuration and per located singularity
of a path; a row per locus of a grid), then the mechanism (joints table, graph drawing, each
loop's subgroup in words, the mobility numbers with why they differ), each configuration
(a sketch with the screws of its findings, the findings in sentences with their numbers),
the sweep (curves or loci) and how it was computed.  This module owns the record, the
order of the document, its verdict table and its last section; the mechanism's section is
:mod:`mechsing.reports.review_mechanism`'s, the configurations' and the sweep's
:mod:`mechsing.reports.review_configurations`'.  Everything is in SI units and radians
except the swept values of a sweep, which are also shown in the file's units.

The document is deterministic: the same inputs give the same bytes, except the one line
that says how long it took (``Report.seconds``).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mechsing import __version__
from mechsing.analysis import AnalysisResult, analyze
from mechsing.analysis.html import VERDICT_HEADERS, largest_drop, verdict_row
from mechsing.analysis.words import class_words
from mechsing.model import Mechanism
from mechsing.numeric import Precision, parse_precision
from mechsing.reader import read_mechanism
from mechsing.reports import document as doc
from mechsing.reports.dynamics import dynamics_blocks
from mechsing.reports.review_configurations import configuration_sections, sweep_section
from mechsing.reports.review_mechanism import mechanism_section
from mechsing.reports.statics import kinetostatics_blocks
from mechsing.singularity.zfb import not_run_sentences
from mechsing.statics import with_kinetostatics
from mechsing.sweeps import SweepResult, sweep
from mechsing.sweeps.results import located_rows
from mechsing.sweeps.spec import Vary

__all__ = ["Report", "report"]


@dataclass(frozen=True)
class Report:
    """A design review of a mechanism: ``analysis``, an optional ``sweep``, the
    ``command`` that made it and the ``seconds`` it took.

    ``to_html()``: one self-contained HTML file; ``to_markdown(folder)``: Markdown with
    the figures written into ``folder``; in a notebook the report shows itself."""

    analysis: AnalysisResult
    sweep: SweepResult | None = None
    command: str = ""
    seconds: float = field(default=0.0, compare=False)
    modes: object | None = None  # a ModesResult: the section "Assembly modes"
    cusps: object | None = None  # a CuspsResult: the section "Cusps"

    @property
    def mechanism(self) -> Mechanism:
        """The mechanism reviewed."""
        return self.analysis.mechanism

    def blocks(self) -> list[doc.Block]:
        """The document as blocks (:mod:`mechsing.reports.document`)."""
        return _blocks(self)

    def to_html(self) -> str:
        """The report as one self-contained HTML document (inline CSS and figures, no script)."""
        return doc.to_html(self.blocks(), f"Design review: {self.mechanism.name}")

    def to_markdown(
        self,
        folder: str | Path,
        relative_to: str | Path | None = None,
        inputs: Sequence[str | Path] = (),
    ) -> str:
        """The Markdown text; its figures are written into ``folder`` (created; its parent
        must exist) and linked relative to ``relative_to`` (default: the folder's parent,
        where the Markdown goes); no figure may be one of the files ``inputs``."""
        folder = Path(folder)
        return doc.to_markdown(self.blocks(), folder, relative_to or folder.parent, inputs)

    def write(self, path: str | Path, inputs: Sequence[str | Path] = ()) -> Path:
        """Write the report to ``path``: HTML, or Markdown for a ``.md`` path (its figures
        in the folder of the path's stem + ``_files`` beside it), atomically and never
        over one of the files ``inputs`` (:mod:`mechsing.files`); the file written."""
        from mechsing.files import check_output, write_output

        path = check_output(path, inputs)  # a link resolved: the figures go beside its file
        if path.suffix.lower() != ".md":
            return write_output(path, self.to_html(), inputs)
        folder = path.with_name(path.stem + "_files")
        return write_output(path, self.to_markdown(folder, path.parent, inputs), inputs)

    def _repr_html_(self) -> str:
        return doc.html_fragment(self.blocks())


def report(
    mechanism_or_path: Mechanism | str | Path,
    configs: Sequence[str] | None = None,
    vary: Sequence[str | Vary] | str | Vary | None = None,
    precision: Precision | str = "auto",
    from_config: str | None = None,
    *,
    command: str | None = None,
    time_limit: float | None = None,
    load: Any = None,
    max_effort: dict[str, float] | None = None,
    modes_of: str | None = None,
    cusps_vary: str | None = None,
    duration: float | None = None,
) -> Report:
    """A design review of a mechanism (or a file), ready to write as HTML or Markdown.

    Parameters
    ----------
    mechanism_or_path : Mechanism, str or Path
        The mechanism, or the path of its file (any format mechsing reads).
    configs : sequence of str, optional
        The configurations analysed (as ``mechsing.analyze`` does); default: all.
    vary : sequence of str, or str, optional
        One ``"NAME=START:STOP:STEP"`` for a path, two for a grid (in the file's units):
        the report then sweeps the mechanism too.
    precision : Precision or str
        The analysis's precision mode (``auto``, ``float``, ``mp:N``).
    from_config : str, optional
        The configuration the sweep starts from (default ``reference``).
    command : str, optional
        How the report was asked for, shown at its end (default: this call).
    time_limit : float or None
        The most seconds one configuration (or located point) may take, as for
        ``mechsing.analyze``.
    load, max_effort : Load, dict, optional
        A load on the output replacing the file's (:class:`mechsing.model.loads.Load`)
        and effort limits by input: the kinetostatics section (docs/kinetostatics.md).
    modes_of : str, optional
        A configuration whose every assembly mode (``mechsing.modes``) the report shows
        in a section "Assembly modes", each with a sketch.
    cusps_vary : str, optional
        ``NAME=lo:hi,NAME=lo:hi``: a section "Cusps" with the singular curves and the
        cusps of that section (``mechsing.cusps``; the third input from ``modes_of``'s
        configuration, else the first that gives it), drawn.
    duration : float, optional
        Time the sweep's path over ``duration`` seconds (``sweep(..., duration=)``): the
        section "Dynamics along the sweep" plots the efforts of that motion.

    Returns
    -------
    Report
        ``to_html()``, ``to_markdown(folder)``, ``write(path)``, and ``_repr_html_`` for
        a notebook.
    """
    t0 = time.perf_counter()
    if duration is not None and not vary:
        from mechsing.errors import UserError

        raise UserError("--duration times the report's sweep: give --vary NAME=START:STOP:STEP")
    mech = (
        mechanism_or_path
        if isinstance(mechanism_or_path, Mechanism)
        else read_mechanism(mechanism_or_path, precision=precision)
    )
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    result = analyze(mech, list(configs) if configs else None, prec, time_limit=time_limit)
    result = with_kinetostatics(result, mech, load)
    swept = None
    if vary:
        varies = [vary] if isinstance(vary, str | Vary) else list(vary)
        swept = sweep(
            mech,
            varies,
            from_config,
            prec,
            time_limit=time_limit,
            load=load,
            max_effort=max_effort,
            duration=duration,
        )
    if command is None:
        args = [repr(mech.path or mech.name)]
        if configs:
            args.append(f"configs={list(configs)!r}")
        if vary:
            args.append(f"vary={vary!r}")
        args.append(f"precision={str(prec)!r}")
        if from_config:
            args.append(f"from_config={from_config!r}")
        command = f"mechsing.report({', '.join(args)})"
    found = None
    if modes_of is not None:
        from mechsing.assembly import modes

        found = modes(mech, modes_of, prec, time_limit=time_limit)
    sections = None
    if cusps_vary is not None:
        from mechsing.assembly.cusps import cusps

        sections = cusps(mech, cusps_vary, modes_of)
    return Report(result, swept, command, time.perf_counter() - t0, found, sections)


# --------------------------------------------------------------------------- sections


def _verdict(r: Report) -> list[doc.Block]:
    rows = [verdict_row(c) for c in r.analysis.configurations]
    if r.sweep is not None and not r.sweep.grid:
        rows += located_rows(r.sweep)
    elif r.sweep is not None:
        for k, lo in enumerate(r.sweep.loci):
            on = [
                p
                for p in r.sweep.located
                if p.configuration is not None
                and lo.test in p.tests
                and any(np.allclose(p.values, v) for v in lo.vertices)
            ]
            decided = sorted({p.precision or "-" for p in on}) or ["-"]
            drops = [d for p in on if (d := largest_drop(p.configuration)) is not None]
            if drops:
                d, m = max(drops, key=lambda t: t[0])
                margin = f"largest dropped {d:.3g} <= tau_lo {m.tau_lo:.3g} over its points"
            else:
                margin = "-"
            singular = "yes" if any(p.singular for p in on) else ("undecided" if on else "-")
            rows.append(
                (
                    f"sweep: locus {k + 1} of {lo.test} ({len(lo.vertices)} points)",
                    singular,
                    class_words(lo.classes) if lo.classes else "not classified",
                    margin,
                    ", ".join(decided),
                )
            )
    marked = frozenset(i for i, row in enumerate(rows) if row[1] != "no")
    singular = sum(1 for row in rows if row[1] == "yes")
    if singular:
        lead = f"{singular} of {len(rows)} rows are singular (highlighted)."
    elif marked:
        lead = "No singularity found, but some rows are not decided (highlighted)."
    else:
        lead = f"No singularity: all {len(rows)} rows are regular."
    # what was not looked for is said with what was found
    for sentence in not_run_sentences(r.analysis.mechanism):
        lead += f" Tests not run: {sentence}."
    return [
        doc.Heading(2, "Verdict"),
        doc.Paragraph(lead),
        doc.Table(VERDICT_HEADERS, tuple(rows), marked=marked),
        doc.Paragraph(
            "Margin: the relative singular value that decided the verdict (dropped: at or "
            "below tau_lo, counted as zero; kept: at or above tau_hi, counted as non-zero), "
            "relative to the largest singular value of the same test."
        ),
    ]


def _how(r: Report) -> list[doc.Block]:
    t = r.analysis.precision.tolerances
    mode = str(r.analysis.precision)
    thresholds = (
        "exact ranks"
        if mode == "exact"
        else "rank thresholds tau_lo = {} and tau_hi = {} of the largest singular value".format(
            *t.shown()
        )
    )
    items = [
        f"mechsing {__version__}",
        f"command: {r.command}",
        f"precision: {mode} ({thresholds}); auto re-decides at mp:50 what float leaves open",
        f"characteristic length L = {r.analysis.length_scale:.6g} m (lengths are divided by it "
        "before ranks are decided)",
        f"file: {r.mechanism.path or r.mechanism.name}",
        f"time taken: {r.seconds:.2f} s",
    ]
    return [doc.Heading(2, "How it was computed"), doc.Bullets(tuple(items))]


def _blocks(r: Report) -> list[doc.Block]:
    mech = r.mechanism
    out: list[doc.Block] = [
        doc.Heading(1, f"Design review: {mech.name}"),
        doc.Paragraph(
            f"Singularities of {mech.name} ({mech.path or 'built in Python'}) at "
            f"{len(r.analysis.configurations)} configuration(s)"
            + (", with a sweep." if r.sweep is not None else ".")
        ),
    ]
    out += _verdict(r)
    out += mechanism_section(r.analysis)
    out += configuration_sections(r.analysis)
    if r.sweep is not None:
        out += sweep_section(r.analysis, r.sweep)
    out += kinetostatics_blocks(r)
    out += dynamics_blocks(r)
    if r.modes is not None:
        from mechsing.reports.modes_section import modes_blocks

        out += modes_blocks(mech, r.modes, r.analysis.length_scale)
    if r.cusps is not None:
        from mechsing.reports.cusps import cusps_blocks

        out += cusps_blocks(r.cusps)
    out += _how(r)
    return out
