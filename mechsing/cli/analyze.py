"""Analyse a mechanism file: loops, ranks, mobility and singularities at its configurations.

Without --config every configuration of the file is analysed.  Exit status:
0 success, 2 bad input, 3 some configuration could not be analysed (not
closed, joint values exact mode cannot take, or stopped by exact mode's time
limit): the others are still reported, the failed one carries "error".

Exact mode works on each configuration for at most --time-limit seconds
(default 60); when a file takes long it says on standard error which
configuration it is working on.
"""

from __future__ import annotations

import argparse
import sys

NAME = "analyze"
HELP = "analyse a mechanism file (loops, ranks, mobility, singularities)"
#: the formats it writes (the first the default)
FORMATS = ("text", "json", "md")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE", help="mechanism file (YAML or JSON), URDF or MJCF")
    p.add_argument(
        "--config", action="append", metavar="NAME", help="configuration to analyse (repeatable)"
    )
    from mechsing.cli import options, output

    options.add_precision_option(p, "auto", "auto (default), float, mp:N or exact")
    options.add_time_limit_option(p)
    output.add_output_options(p, FORMATS, "the report")
    options.add_verbose_option(p)
    options.add_set_option(p)
    options.add_scene_options(p)
    options.add_load_option(p)


def _progress(line: str) -> None:
    print(f"mechsing: {line}", file=sys.stderr, flush=True)


def run(args: argparse.Namespace) -> int:
    from mechsing.analysis import analyze
    from mechsing.cli import NOT_ANALYSED, load_mechanism, with_file
    from mechsing.cli.options import apply_scene, apply_set, check_shared, with_load
    from mechsing.cli.output import output_format
    from mechsing.files import check_output, write_output
    from mechsing.reports import render

    check_shared(args)
    fmt = output_format(args.format, args.output, FORMATS, NAME)
    if args.output:  # before the work: a missing directory or the input file is refused now
        check_output(args.output, [args.file])
    mech = apply_set(
        apply_scene(load_mechanism(args.file, args.verbose, precision=args.prec), args, args.file),
        args.set_values,
        args.from_config,
        args.file,
    )
    result = analyze(mech, args.config, args.prec, time_limit=args.time_limit, progress=_progress)
    result = with_load(result, mech, args.load)
    text = render(result, fmt)
    if args.output:
        write_output(args.output, text, [args.file])
    else:
        sys.stdout.write(text)
    for c in result.configurations:
        if c.error:
            print(f"mechsing: {with_file(c.error, args.file)}", file=sys.stderr)
    return NOT_ANALYSED if result.failed else 0
