"""Analyse a mechanism file: loops, ranks, mobility and singularities at its configurations.

Without --config every configuration of the file is analysed.  Exit status:
0 success, 2 bad input, 3 some configuration could not be closed (the others
are still reported; the failed one carries "error").
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

NAME = "analyze"
HELP = "analyse a mechanism file (loops, ranks, mobility, singularities)"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE", help="mechanism file (YAML or JSON)")
    p.add_argument(
        "--config", action="append", metavar="NAME", help="configuration to analyse (repeatable)"
    )
    p.add_argument(
        "--precision", default="auto", metavar="MODE", help="auto (default), float, mp:N or exact"
    )
    p.add_argument("--format", choices=("text", "json", "md"), default="text")
    p.add_argument(
        "-o", "--output", metavar="OUT", help="write the report to OUT instead of standard output"
    )
    p.add_argument(
        "-v", "--verbose", action="store_true", help="also print what mechsing did silently"
    )


def run(args: argparse.Namespace) -> int:
    from mechsing.analysis import analyze
    from mechsing.cli import UserError, load_mechanism, precision_option
    from mechsing.report import render

    prec = precision_option(args.precision)
    mech = load_mechanism(args.file, args.verbose)
    result = analyze(mech, args.config, prec)
    text = render(result, args.format)
    if args.output:
        try:
            Path(args.output).write_text(text)
        except OSError as exc:
            raise UserError(
                f"cannot write {args.output}: {exc.strerror}; choose a writable path"
            ) from None
    else:
        sys.stdout.write(text)
    for c in result.configurations:
        if c.error:
            print(f"mechsing: {c.error}", file=sys.stderr)
    return 3 if result.failed else 0
