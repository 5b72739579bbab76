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

#: the formats it writes, named by the extension of -o (:mod:`mechsing.cli.output`)
FORMATS = ("html", "md")


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
    from mechsing.cli import options

    options.add_vary_option(p, False, "the report's sweep, as for `sweep`")
    options.add_from_option(
        p,
        "the configuration the sweep starts from (default reference; with --set, the "
        "configuration the --set values are solved from, and the sweep starts at cli)",
    )
    options.add_set_option(p, from_option=False)
    options.add_scene_options(p)
    options.add_precision_option(
        p, "auto", "auto (default), float, mp:N, or exact (without --vary)"
    )
    options.add_time_limit_option(p)
    options.add_verbose_option(p)
    options.add_load_option(p)
    options.add_max_effort_option(p)
    options.add_duration_option(p)
    p.add_argument(
        "--modes",
        dest="modes_of",
        metavar="NAME",
        help="add a section with every assembly mode of configuration NAME (as `mechsing modes`)",
    )
    p.add_argument(
        "--cusps",
        dest="cusps_vary",
        metavar="NAME=lo:hi,NAME=lo:hi",
        help="add a section with the singular curves and cusps of that section of the input "
        "space, drawn (as `mechsing cusps --vary`)",
    )


def output_path(file: str, out: str | None) -> tuple[Path, str]:
    """Where the report goes and its format (``html`` or ``md``), or a UserError."""
    from mechsing.cli.output import extension_format
    from mechsing.errors import UserError

    if not out:
        return Path(Path(file).stem + ".html"), "html"
    path = Path(out)
    fmt = extension_format(out)
    if fmt is None or fmt not in FORMATS:
        raise UserError(
            f"-o {out}: a report is written as .html or .md; name the output review.html or "
            "review.md"
        )
    return path, fmt


def run(args: argparse.Namespace) -> int:
    from mechsing.cli import NOT_ANALYSED, load_mechanism, with_file
    from mechsing.cli.options import (
        apply_scene,
        apply_set,
        check_shared,
        report_load,
        warn_varies,
    )
    from mechsing.errors import working_on
    from mechsing.files import check_output
    from mechsing.reports import report

    with working_on(file=args.file):
        path, _ = output_path(args.file, args.output)
        # before the work: a missing directory or the input file is refused now
        check_output(path, [args.file], "-o" if args.output else "the default output")
        check_shared(args, "a report")  # the options' own errors before the file is read
        from mechsing.adhoc import set_start

        mech = apply_set(
            apply_scene(
                load_mechanism(args.file, args.verbose, precision=args.prec), args, args.file
            ),
            args.set_values,
            args.from_config if args.set_values else None,  # without --set: the sweep's start
            args.file,
        )
        warn_varies(mech, args.varies)
        start = set_start(mech, args.set_values, "a report's sweep") or args.from_config
        command = "mechsing report " + shlex.join(_argv(args))
        rep = report(
            mech,
            args.config,
            args.varies,
            args.prec,
            start,
            command=command,
            time_limit=args.time_limit,
            **report_load(mech, args.load, args.max_effort),
            modes_of=args.modes_of,
            cusps_vary=args.cusps_vary,
            duration=args.duration,
        )
        rep.write(path, [args.file])
    print(f"mechsing: report written to {path}", file=sys.stderr)
    errors = [c.error for c in rep.analysis.configurations]
    if rep.sweep is not None:
        errors += [p.configuration.error for p in rep.sweep.located if p.configuration]
    for error in filter(None, errors):
        print(f"mechsing: {with_file(error, args.file)}", file=sys.stderr)
    return NOT_ANALYSED if any(errors) else 0


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
    if args.load:
        out += ["--load", args.load]
    for m in args.max_effort or ():
        out += ["--max-effort", m]
    if getattr(args, "duration", None) is not None:
        out += ["--duration", f"{args.duration:g}"]
    if getattr(args, "modes_of", None):
        out += ["--modes", args.modes_of]
    if getattr(args, "cusps_vary", None):
        out += ["--cusps", args.cusps_vary]
    if getattr(args, "time_limit", None) is not None:
        out += ["--time-limit", f"{args.time_limit:g}"]
    return out
