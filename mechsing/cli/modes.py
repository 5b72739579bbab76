"""Every assembly mode of a configuration: all real closed configurations that have its
given values (the inputs), each certified (a Krawczyk proof that one true solution lies
within the stated radius) and classified exactly as ``mechsing analyze`` classifies it,
with the one continuation from the configuration's start reaches marked, the distances
between modes and the joints outside their limits.  ``complete`` says what the count
claims: ``proven`` (exact elimination with certified real-root isolation), ``not
proven``, ``maximal`` (the generic count, every mode certified; or every solution, real and
complex, found and certified, as many as the most there can be) or ``infinite`` (the given
values leave a curve: no count, the dimension in the notes).  The first formulation of
the registry that applies is used: (1) a planar mechanism (its joints generate the planar
motions, in any plane) whose unknown part is one body held by legs (a four-bar, a
slider-crank, a 3-RPR): built-in exact elimination; (2) a platform on six U-P-S or S-P-S
legs: Study coordinates; (2b) any other spatial platform on legs whose unknown part is,
leg by leg, one piece between a known body (the ground, or an arm its given joints place)
and the platform (R-S, S-S, U-S, U-U: a 3-RPS, a Delta, Tsai's 3-UPU): each leg's
constraint on the platform's Study coordinates; (3) a single loop of R and P joints with six unknown: half-angle
pairs of a single loop; (4) a serial arm of six R or P joints (or more, with all but six
given) at a pose: half-angle pairs of a serial arm; (4b) one loop closed by a rod
between two ball joints with one other joint unknown (an RSSR with its crank given): the
rod's length, a quadratic in that joint's half-angle pair (or slide) solved in closed
form, each root's solution certified, the count proven; (4c) one loop of six joints, one
given and five unknown revolutes: one revolute eliminated through its axis (the product
of the other five commutes with its line: four equations, 24 paths), the count proven
when every path ends at its own certified root; (5) any other mechanism of R, P, C, U,
S, T2 and T3 joints, or an arm of fewer joints at a pose in the subgroup its end moves in (a
pose outside it exits 2, naming the subgroup): each joint's displacement in Study
coordinates, each loop's closure in its own subgroup's (three equations for a planar or
spherical loop, six in general; a body on exactly two ball joints, an RSSR's coupler,
taken free of its idle spin about their line); a parallel mechanism at a pose (its
working modes: each serial leg closed on the pose alone), and equations that share no
unknown, solved apart (a mode: one solution of each; more than 4000 modes combined exit 2
with each part's count).  (2) to (5), but (4b), use homotopy
continuation with the ``modes``
extra (pip install 'mechsing[modes]': Bertini 2, GPL-3.0-or-later).  Exit status: 0
success, 2 bad input or no method applies, 3 a mode that could not be analysed.
"""

from __future__ import annotations

import argparse
import sys

NAME = "modes"
HELP = "every assembly mode of a configuration, certified and classified"
#: the formats it writes (the first the default)
FORMATS = ("text", "json", "md")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE", help="mechanism file (YAML or JSON), URDF or MJCF")
    p.add_argument(
        "--config", metavar="NAME", help="the configuration whose given values the modes share"
    )
    from mechsing.cli import options, output

    options.add_precision_option(p, "auto", "auto (default), float or mp:N (the classification's)")
    options.add_time_limit_option(p)
    output.add_output_options(p, FORMATS, "the result")
    options.add_verbose_option(p)
    options.add_set_option(p)


def run(args: argparse.Namespace) -> int:
    from mechsing.adhoc import set_start
    from mechsing.assembly import modes
    from mechsing.assembly.render import render_modes
    from mechsing.cli import NOT_ANALYSED, UserError, load_mechanism
    from mechsing.cli.options import apply_set, check_shared
    from mechsing.cli.output import output_format
    from mechsing.errors import TimeLimitExceeded
    from mechsing.files import check_output, write_output

    check_shared(args, from_alone=args.config is not None)
    fmt = output_format(args.format, args.output, FORMATS, NAME)
    if args.output:
        check_output(args.output, [args.file])
    # --from with --config: the start whose continuation marks a mode; with --set: the
    # start the --set values are solved from (and so marked from)
    from_config = args.from_config if args.set_values else None
    mech = apply_set(
        load_mechanism(args.file, args.verbose), args.set_values, from_config, args.file
    )
    if args.config is None:
        if not args.set_values:
            raise UserError("modes needs --config NAME (or --set JOINT=VALUE for the inputs)")
        args.config = set_start(mech, args.set_values, "modes")
    start = None if args.set_values else args.from_config
    try:
        result = modes(mech, args.config, args.prec, time_limit=args.time_limit, start=start)
    except TimeLimitExceeded:
        print(
            f"mechsing: {args.file}: configuration {args.config!r}: the modes were not all "
            f"found and classified within --time-limit {args.time_limit:g} s; give it more "
            "time (nothing was written)",
            file=sys.stderr,
        )
        return NOT_ANALYSED
    text = render_modes(result, fmt, {j.name: j.units for j in mech.joints})
    if args.output:
        write_output(args.output, text, [args.file])
    else:
        sys.stdout.write(text)
    failed = [m for m in result.modes if m.analysis.get("error")]
    for m in failed:
        print(f"mechsing: {args.file}: {m.analysis['error']}", file=sys.stderr)
    return NOT_ANALYSED if failed else 0
