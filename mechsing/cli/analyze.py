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
import math
import sys

NAME = "analyze"
HELP = "analyse a mechanism file (loops, ranks, mobility, singularities)"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE", help="mechanism file (YAML or JSON), URDF or MJCF")
    p.add_argument(
        "--config", action="append", metavar="NAME", help="configuration to analyse (repeatable)"
    )
    p.add_argument(
        "--precision", default="auto", metavar="MODE", help="auto (default), float, mp:N or exact"
    )
    p.add_argument(
        "--time-limit",
        type=_seconds,
        default=None,
        metavar="S",
        help="seconds exact mode may spend on one configuration before it stops it with an "
        f"error entry (default {_default_limit():g})",
    )
    p.add_argument("--format", choices=("text", "json", "md"), default="text")
    p.add_argument(
        "-o", "--output", metavar="OUT", help="write the report to OUT instead of standard output"
    )
    p.add_argument(
        "-v", "--verbose", action="store_true", help="also print what mechsing did silently"
    )
    from mechsing.cli.options import add_scene_options, add_set_option

    add_set_option(p)
    add_scene_options(p)


def _default_limit() -> float:
    # the time-limit module imports no numerics: building the parser stays fast
    from mechsing.timelimit import EXACT_TIME_LIMIT

    return EXACT_TIME_LIMIT


def _seconds(text: str) -> float:
    """--time-limit: a positive, finite number of seconds."""
    try:
        x = float(text)
    except ValueError:
        x = math.nan
    if not 0 < x < math.inf:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a positive number of seconds (e.g. --time-limit 120)"
        )
    return x


def _progress(line: str) -> None:
    print(f"mechsing: {line}", file=sys.stderr, flush=True)


def run(args: argparse.Namespace) -> int:
    from mechsing.analysis import analyze
    from mechsing.cli import NOT_ANALYSED, load_mechanism, precision_option, with_file
    from mechsing.report import render

    prec = precision_option(args.precision)
    from mechsing.cli.options import apply_scene, apply_set
    from mechsing.files import check_output, write_output

    if args.output:  # before the work: a missing directory or the input file is refused now
        check_output(args.output, [args.file])

    mech = apply_set(
        apply_scene(load_mechanism(args.file, args.verbose), args, args.file),
        args.set_values,
        args.from_config,
        args.file,
    )
    limit = args.time_limit if args.time_limit is not None else _default_limit()
    result = analyze(mech, args.config, prec, time_limit=limit, progress=_progress)
    text = render(result, args.format)
    if args.output:
        write_output(args.output, text, [args.file])
    else:
        sys.stdout.write(text)
    for c in result.configurations:
        if c.error:
            print(f"mechsing: {with_file(c.error, args.file)}", file=sys.stderr)
    return NOT_ANALYSED if result.failed else 0
