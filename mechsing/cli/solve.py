"""Close one configuration of a mechanism file and print every joint value (SI units, radians)."""

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
    p.add_argument(
        "--precision", default="float", metavar="MODE", help="float (default), mp:N or exact"
    )
    p.add_argument("--format", choices=("text", "json"), default="text")
    p.add_argument(
        "-v", "--verbose", action="store_true", help="also print what mechsing did silently"
    )
    from mechsing.cli.options import add_set_option

    add_set_option(p)


def run(args: argparse.Namespace) -> int:
    from mechsing.cli import UserError, load_mechanism, precision_option
    from mechsing.kinematics import solve_configuration

    prec = precision_option(args.precision)
    from mechsing.cli.options import SET_CONFIG, apply_set

    mech = apply_set(
        load_mechanism(args.file, args.verbose), args.set_values, args.from_config, args.file
    )
    if args.config is None:
        if not args.set_values:
            raise UserError("solve needs --config NAME (or --set JOINT=VALUE for an ad-hoc one)")
        args.config = SET_CONFIG
    if args.config not in mech.configurations:
        raise UserError(
            f"{args.file}: no configuration named {args.config!r}; the file has: {', '.join(mech.configurations)}"
        )
    model, closed = solve_configuration(mech, args.config, prec)
    values = model.values(closed.q)
    if args.format == "json":
        out = {
            "mechanism": mech.name,
            "configuration": args.config,
            "precision": str(model.precision),
            "joints": values,
            "closure_residual": closed.residual,
            "underdetermined": closed.underdetermined,
            "steps": closed.steps,
        }
        sys.stdout.write(json.dumps(out, indent=2) + "\n")
    else:
        print(
            f"{mech.name}, configuration {args.config} ({model.precision}): residual {closed.residual:.3g} m"
            + (", underdetermined (minimum-norm steps)" if closed.underdetermined else "")
        )
        for k, v in values.items():
            units = mech.joint(k).units if k in mech.joint_names else ()
            shown = (
                ", ".join(f"{x!r} {u}" for x, u in zip(v, units, strict=False))
                if units
                else ", ".join(repr(x) for x in v)
            )
            print(f"  {k}: {shown}")
    return 0
