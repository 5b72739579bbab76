"""Close one configuration of a mechanism file and print every joint value (SI units,
radians): to every digit of the precision mode (N significant digits at mp:N, the exact
expression in exact mode); the JSON is :class:`mechsing.analysis.solve.SolveResult`'s."""

from __future__ import annotations

import argparse
import json
import sys

NAME = "solve"
HELP = "close a configuration and print all joint values"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE")
    p.add_argument(
        "--config", metavar="NAME", help="the configuration to close (default with --set: cli)"
    )
    from mechsing.cli import options

    options.add_precision_option(p, "float", "float (default), mp:N or exact")
    options.add_time_limit_option(p)
    p.add_argument("--format", choices=("text", "json"), default="text")
    options.add_verbose_option(p)
    options.add_set_option(p)
    options.add_scene_options(p)


def run(args: argparse.Namespace) -> int:
    from mechsing.analysis.solve import solve
    from mechsing.cli import UserError, load_mechanism
    from mechsing.cli.options import apply_scene, apply_set, check_shared

    check_shared(args)
    from mechsing.adhoc import set_start

    mech = apply_set(
        apply_scene(load_mechanism(args.file, args.verbose, precision=args.prec), args, args.file),
        args.set_values,
        args.from_config,
        args.file,
    )
    if args.config is None:
        if not args.set_values:
            raise UserError("solve needs --config NAME (or --set JOINT=VALUE for an ad-hoc one)")
        args.config = set_start(mech, args.set_values, "solve")
    if args.config not in mech.configurations:
        raise UserError(
            f"{args.file}: no configuration named {args.config!r}; the file has: {', '.join(mech.configurations)}"
        )
    res = solve(mech, args.config, args.prec, time_limit=args.time_limit)
    if args.format == "json":
        sys.stdout.write(json.dumps(res.to_json(), indent=2) + "\n")
    else:
        print(
            f"{mech.name}, configuration {args.config} ({res.precision}): residual "
            f"{res.closure_residual:.3g} m"
            + (", underdetermined (minimum-norm steps)" if res.underdetermined else "")
        )
        # the values as solved: every digit of mp:N, the exact expression in exact mode
        for k, v in res.joints_text:
            units = mech.joint(k).units if k in mech.joint_names else ()
            shown = (
                ", ".join(f"{x} {u}" for x, u in zip(v, units, strict=False))
                if units
                else ", ".join(v)
            )
            print(f"  {k}: {shown}")
        for note in res.notes:
            print(f"  note: {note}")
    return 0
