"""The singular curves and the cusps of a section of the input space, and whether the
mechanism is cuspidal (can change assembly mode, or posture, without a singularity):
for a planar mechanism with three inputs whose direct kinematics has finitely many
modes (a 3-RPR, 3-RRR, 3-PRR), the third input fixed at the configuration's value and
two varied (--vary P2=lo:hi,P3=lo:hi); for a positional 3R arm (three revolute joints,
an output point), the workspace half-plane (--vary rho=lo:hi,z=lo:hi) about the first
axis.  The modes are the real roots of one polynomial (the planar formulation's
eliminant; the arm's inverse kinematics in its third joint's half-angle); a singular
curve is where two meet, a cusp where three meet (a triple root), each cusp refined at
50 digits and certified by the Krawczyk test.  The curves are located on a grid's lines
(--points); a cusp none of whose curves crosses a grid line is missed.  Exit status: 0
success, 2 bad input or a mechanism of another kind.
"""

from __future__ import annotations

import argparse
import sys

NAME = "cusps"
HELP = "singular curves and cusps of a section of the input space; cuspidal or not"
#: the formats it writes (the first the default)
FORMATS = ("text", "json", "md")


def add_arguments(p: argparse.ArgumentParser) -> None:
    from mechsing.cli import output

    p.add_argument("file", metavar="FILE", help="mechanism file (YAML or JSON), URDF or MJCF")
    p.add_argument(
        "--vary",
        metavar="NAME=lo:hi,NAME=lo:hi",
        required=True,
        help="the two varied coordinates: two inputs, or rho and z of a 3R arm, in the "
        "file's units (the output is in SI units and radians)",
    )
    p.add_argument(
        "--config",
        metavar="NAME",
        help="the configuration whose value of the third input is kept (default: the "
        "first that gives it); one that gives the output's pose is closed first",
    )
    p.add_argument(
        "--points", type=int, metavar="N", help="grid points along each side (default 81)"
    )
    output.add_output_options(p, FORMATS, "the result")
    p.add_argument(
        "--plot",
        metavar="PNG",
        help="draw the section (modes, singular curves, cusps) to PNG or SVG",
    )


def run(args: argparse.Namespace) -> int:
    from mechsing.assembly.cusps import cusps
    from mechsing.assembly.cusps_render import render_cusps
    from mechsing.cli import UserError, load_mechanism
    from mechsing.cli.output import output_format
    from mechsing.files import check_output, write_output

    if args.points is not None and not 5 <= args.points <= 1001:
        raise UserError(f"{args.file}: --points {args.points}: give 5 to 1001")
    fmt = output_format(args.format, args.output, FORMATS, NAME)
    if args.plot and not args.plot.lower().endswith((".png", ".svg")):
        raise UserError(
            f"{args.file}: --plot {args.plot}: the figure is PNG or SVG: name it .png or .svg"
        )
    for out in (args.output, args.plot):
        if out:
            check_output(out, [args.file])
    mech = load_mechanism(args.file)
    doc = cusps(mech, args.vary, args.config, args.points).to_json()
    text = render_cusps(doc, fmt)
    if args.output:
        write_output(args.output, text, [args.file])
    else:
        sys.stdout.write(text)
    if args.plot:
        from mechsing.reports.cusps import write_figure

        write_figure(doc, args.plot)
    return 0
