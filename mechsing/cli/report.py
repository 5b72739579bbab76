"""Write a design-review report of a mechanism: one self-contained HTML file, or Markdown.

The configurations are analysed as `analyze` does (every one of the file, or those named
with --config), and with --vary the mechanism is swept as `sweep` does (once: a path, twice:
a grid, from --from).  The report reads in the order a reviewer does: the verdict table,
the mechanism (joints, graph, loops, mobility), a sketch and the findings of each
configuration, the sweep's curves or loci, and how it was computed.

-o OUT chooses the format by its extension: .html (one file, figures inline, nothing
fetched) or .md (GitHub Markdown; the figures go in OUT's stem + "_files" beside it).  The
default is the mechanism file's stem with .html in the current directory.  Exit status: 0
success, 2 bad input, 3 some configuration could not be analysed (the report is written
and says which).
"""

from __future__ import annotations

import argparse
import shlex
import sys
from pathlib import Path

NAME = "report"
HELP = "write a design-review report (HTML or Markdown, with figures)"

#: the formats, by the extension of -o
EXTENSIONS = {".html": "html", ".htm": "html", ".md": "md"}


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "file", metavar="FILE", help="mechanism file (YAML or JSON, a DH table), URDF or MJCF"
    )
    p.add_argument(
        "-o",
        "--output",
        metavar="OUT",
        help="review.html or review.md (default: the file's stem with .html, here)",
    )
    p.add_argument(
        "--config", action="append", metavar="NAME", help="configuration to analyse (repeatable)"
    )
    p.add_argument(
        "--vary",
        action="append",
        metavar="NAME=START:STOP:STEP",
        help="a swept variable in the file's units, as for `sweep`: once for a path, twice "
        "for a grid (e.g. --vary A=0:360:2)",
    )
    p.add_argument(
        "--from",
        dest="from_config",
        metavar="CONFIG",
        help="the configuration the sweep starts from (default reference; with --set, the "
        "configuration the --set values are solved from, and the sweep starts at cli)",
    )
    from mechsing.cli.options import add_scene_options, add_set_option

    add_set_option(p, from_option=False)
    add_scene_options(p)
    p.add_argument(
        "--precision", default="auto", metavar="MODE", help="auto (default), float or mp:N"
    )
    p.add_argument(
        "-v", "--verbose", action="store_true", help="also print what mechsing did silently"
    )


def output_path(file: str, out: str | None) -> tuple[Path, str]:
    """Where the report goes and its format (``html`` or ``md``), or a UserError."""
    from mechsing.errors import UserError

    if not out:
        return Path(Path(file).stem + ".html"), "html"
    path = Path(out)
    fmt = EXTENSIONS.get(path.suffix.lower())
    if fmt is None:
        raise UserError(
            f"-o {out}: a report is written as .html or .md; name the output review.html or "
            "review.md"
        )
    return path, fmt


def run(args: argparse.Namespace) -> int:
    from mechsing.cli import NOT_ANALYSED, load_mechanism, precision_option, with_file
    from mechsing.errors import UserError, working_on
    from mechsing.report import report
    from mechsing.sweeps.spec import Vary

    with working_on(file=args.file):
        path, fmt = output_path(args.file, args.output)
        if args.vary and len(args.vary) > 2:
            raise UserError(
                f"--vary is given {len(args.vary)} times: a report sweeps one variable (a "
                "path) or two (a grid); give --vary once or twice"
            )
        for text in args.vary or ():
            Vary.parse(text).count()  # the range's own errors before the file is read
        if args.from_config and not args.vary and not args.set_values:
            raise UserError(
                "--from names where a sweep starts (or where --set values are solved from): "
                "give --vary or --set too"
            )
        prec = precision_option(args.precision)
        if prec.mode == "exact" and args.vary:
            raise UserError(
                "--precision exact: a sweep locates its singularities numerically, so their "
                "values are not exact data; use --precision auto (the default) or mp:N"
            )
        from mechsing.cli.options import apply_scene, apply_set
        from mechsing.model.adhoc import set_start

        mech = apply_set(
            apply_scene(load_mechanism(args.file, args.verbose), args, args.file),
            args.set_values,
            args.from_config if args.set_values else None,  # without --set: the sweep's start
            args.file,
        )
        start = set_start(mech, args.set_values, "a report's sweep") or args.from_config
        command = "mechsing report " + shlex.join(_argv(args))
        rep = report(mech, args.config, args.vary, prec, start, command=command)
        try:
            if fmt == "html":
                path.write_text(rep.to_html(), encoding="utf-8")
            else:
                folder = path.with_name(path.stem + "_files")
                path.write_text(rep.to_markdown(folder, path.parent), encoding="utf-8")
        except OSError as exc:
            raise UserError(
                f"-o {path}: cannot write it ({exc.strerror}); choose a writable path"
            ) from None
    print(f"mechsing: report written to {path}", file=sys.stderr)
    for c in rep.analysis.configurations:
        if c.error:
            print(f"mechsing: {with_file(c.error, args.file)}", file=sys.stderr)
    return NOT_ANALYSED if rep.analysis.failed else 0


def _argv(args: argparse.Namespace) -> list[str]:
    """The command's arguments as given (the report shows them)."""
    out = [args.file]
    if args.output:
        out += ["-o", args.output]
    for c in args.config or ():
        out += ["--config", c]
    for v in args.vary or ():
        out += ["--vary", v]
    if args.from_config:
        out += ["--from", args.from_config]
    for v in args.set_values or ():
        out += ["--set", v]
    if args.precision != "auto":
        out += ["--precision", args.precision]
    return out
