"""The dynamics of a mechanism's configurations (docs/dynamics.md): with --accelerations
the joint efforts a motion needs (inverse dynamics), with --efforts the accelerations they
give (forward dynamics), and always the mass matrix, the bias efforts (Coriolis,
centrifugal, gravity) and the kinetic energy.  Rates, accelerations and efforts in SI
(rad/s, m/s, rad/s^2, m/s^2, N m, N); the JSON's schema: mechsing schema --dynamics.
"""

from __future__ import annotations

import argparse
import json
import sys

NAME = "dynamics"
HELP = "joint efforts for a motion (inverse dynamics) or accelerations under efforts (forward)"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE")
    p.add_argument(
        "--config", metavar="NAME", help="the configuration (default: every one of the file)"
    )
    for option, what in (
        ("--rates", "joint rates (rad/s, m/s)"),
        ("--accelerations", "joint accelerations (rad/s^2, m/s^2): inverse dynamics"),
        ("--efforts", "joint efforts (N m, N): forward dynamics"),
    ):
        p.add_argument(
            option,
            nargs="+",
            action="extend",
            metavar="J=V",
            help=f"{what}; a joint not named has 0 (values may be expressions: pi/4)",
        )
    p.add_argument(
        "--gravity",
        metavar="GX,GY,GZ",
        help="the acceleration of gravity in ground axes, m/s^2 (default: the file's "
        "gravity, none without one; a URDF gives none: --gravity 0,0,-9.81)",
    )
    from mechsing.cli import options

    options.add_precision_option(p, "float", "float (default), mp:N or exact")
    p.add_argument("--format", choices=("text", "json", "md"), default="text")
    options.add_verbose_option(p)


def _pairs(values: list[str] | None, option: str) -> dict[str, str] | None:
    from mechsing.errors import UserError

    if values is None:
        return None
    out = {}
    for item in values:
        name, eq, value = item.partition("=")
        if not eq or not name.strip() or not value.strip():
            raise UserError(f"{option} {item!r}: write JOINT=VALUE, e.g. {option} A=0.5")
        out[name.strip()] = value.strip()
    return out


def run(args: argparse.Namespace) -> int:
    from mechsing.cli import load_mechanism
    from mechsing.cli.options import precision_option
    from mechsing.errors import UserError, working_on
    from mechsing.kinetics.api import dynamics

    gravity = None
    if args.gravity is not None:
        gravity = [x.strip() for x in args.gravity.split(",")]
        if len(gravity) != 3 or not all(gravity):
            raise UserError(f"--gravity {args.gravity!r}: give three numbers, e.g. 0,0,-9.81")
    with working_on(file=args.file):
        mech = load_mechanism(args.file, args.verbose)
        result = dynamics(
            mech,
            args.config,
            rates=_pairs(args.rates, "--rates"),
            accelerations=_pairs(args.accelerations, "--accelerations"),
            efforts=_pairs(args.efforts, "--efforts"),
            precision=precision_option(args.precision),
            gravity=gravity,
        )
    if args.format == "json":
        sys.stdout.write(json.dumps(result.to_json(), indent=2) + "\n")
    elif args.format == "md":
        sys.stdout.write(result.markdown())
    else:
        sys.stdout.write(result.text())
    return 0
