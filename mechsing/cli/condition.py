"""Write the singularity conditions of a mechanism as factored formulas in its joint
variables (named by the joints, measured from the drawn pose, radians and metres) or, for a
parallel robot, its pose variables x, y, phi; keep the parameters named in --symbolic as
symbols; with --config, evaluate each factor there and say which vanish.  Output as text,
JSON (its schema: mechsing schema --condition; each formula also in LaTeX), LaTeX, or
Markdown with the formulas as $...$ (--format md).
"""

from __future__ import annotations

import argparse
import json
import sys

NAME = "condition"
HELP = "singularity conditions as factored formulas in the joint (or pose) variables"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE")
    p.add_argument(
        "--config",
        metavar="NAME",
        help="evaluate each factor at this configuration and say which vanish",
    )
    p.add_argument(
        "--symbolic",
        default="",
        metavar="A,B",
        help="parameters of the file to keep as symbols (comma-separated)",
    )
    p.add_argument("--format", choices=("text", "json", "latex", "md"), default="text")


def run(args: argparse.Namespace) -> int:
    from mechsing.conditions import condition

    result = condition(args.file, config=args.config, symbolic=args.symbolic)
    if args.format == "json":
        sys.stdout.write(json.dumps(result.to_json(), indent=2) + "\n")
    elif args.format == "latex":
        sys.stdout.write(result.latex())
    elif args.format == "md":
        sys.stdout.write(result.markdown())
    else:
        sys.stdout.write(result.text())
    return 0
