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
        help="evaluate each factor at this configuration and say which vanish (default with "
        "--set: cli)",
    )
    p.add_argument(
        "--symbolic",
        default="",
        metavar="A,B",
        help="parameters of the file to keep as symbols (comma-separated)",
    )
    p.add_argument("--format", choices=("text", "json", "latex", "md"), default="text")
    from mechsing.cli import options

    options.add_time_limit_option(p)
    options.add_verbose_option(p)
    options.add_set_option(p)
    options.add_scene_options(p)


def run(args: argparse.Namespace) -> int:
    from mechsing.adhoc import set_start
    from mechsing.cli import load_mechanism
    from mechsing.cli.options import apply_scene, apply_set, check_shared
    from mechsing.conditions import condition

    check_shared(args)
    names = [s.strip() for s in args.symbolic.split(",") if s.strip()]
    mech = apply_set(
        apply_scene(
            load_mechanism(args.file, args.verbose, symbolic=names, exact_tables=True),
            args,
            args.file,
        ),
        args.set_values,
        args.from_config,
        args.file,
    )
    config = args.config or set_start(mech, args.set_values, "condition")
    result = condition(
        mech,
        config=config,
        symbolic=names,
        # the file read again with its parameters' values (--config) gets the same scene
        scene=lambda m: apply_scene(m, args, args.file),
        time_limit=args.time_limit,
    )
    if args.format == "json":
        sys.stdout.write(json.dumps(result.to_json(), indent=2) + "\n")
    elif args.format == "latex":
        sys.stdout.write(result.latex())
    elif args.format == "md":
        sys.stdout.write(result.markdown())
    else:
        sys.stdout.write(result.text())
    return 0
