"""Write the singularity conditions of a mechanism as factored formulas in its joint
variables (named by the joints, measured from the drawn pose, radians and metres) or, for a
parallel robot, its pose variables x, y, phi; keep the parameters named in --symbolic as
symbols; with --config, evaluate each factor there and say which vanish.  Output as text,
JSON (its schema: mechsing schema --condition; each formula also in LaTeX), LaTeX, or
Markdown with the formulas as $...$ (--format md); -o OUT writes it to OUT, in the format
its extension names (.json, .tex, .md; any other: text) unless --format is given.
"""

from __future__ import annotations

import argparse
import json
import sys

NAME = "condition"
HELP = "singularity conditions as factored formulas in the joint (or pose) variables"
#: the formats it writes (the first the default)
FORMATS = ("text", "json", "latex", "md")


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
    from mechsing.cli import options, output

    output.add_output_options(p, FORMATS, "the condition")

    options.add_time_limit_option(p)
    options.add_verbose_option(p)
    options.add_set_option(p)
    options.add_scene_options(p)


def run(args: argparse.Namespace) -> int:
    from mechsing.adhoc import set_start
    from mechsing.cli import load_mechanism
    from mechsing.cli.options import apply_scene, apply_set, check_shared
    from mechsing.cli.output import output_format
    from mechsing.conditions import condition
    from mechsing.files import check_output, write_output

    check_shared(args)
    fmt = output_format(args.format, args.output, FORMATS, NAME)
    if args.output:  # before the work: a missing directory or the input file is refused now
        check_output(args.output, [args.file])
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
    if fmt == "json":
        text = json.dumps(result.to_json(), indent=2) + "\n"
    elif fmt == "latex":
        text = result.latex()
    elif fmt == "md":
        text = result.markdown()
    else:
        text = result.text()
    if args.output:
        write_output(args.output, text, [args.file])
    else:
        sys.stdout.write(text)
    return 0
