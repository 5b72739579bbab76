"""Options shared by several commands, declared and checked here once.

Owns the declarations of ``--precision``, ``--time-limit``, ``-v/--verbose``,
``--vary``, ``--from``, ``--set`` and the scene options ``--output-body``,
``--output-point``, ``--relative-to``, ``--inputs`` (one ``add_*`` function each,
the same words on every command) and :func:`check_shared`, which checks every
shared option a command was given, before the file is read, by the library's
policy: :func:`mechsing.numeric.parse_precision`,
:func:`mechsing.timelimit.check_time_limit`, :func:`mechsing.sweeps.spec.check_varies`
and :func:`mechsing.sweeps.spec.sweep_precision` say what is refused and with which
words; :func:`apply_scene`'s policy is :func:`mechsing.model.scene.choose_scene`.

``--set`` (repeatable) gives joint values in the file's units (a joint of
several coordinates takes a comma-separated list, ``--set S1=0.1,0,0.2``; exact
expressions such as ``pi/4`` are read as in a mechanism file); together they
form a configuration named ``cli``, added to the mechanism and solved by
closure from ``reference`` or from the configuration ``--from`` names
(:func:`apply_set`).  A file that already has a configuration called ``cli`` is
refused (exit 2).
"""

from __future__ import annotations

import argparse
import re
from typing import Any

from mechsing.adhoc import SET_CONFIG  # the name of the configuration unnamed values make
from mechsing.errors import UserError

__all__ = [
    "SET_CONFIG",
    "add_from_option",
    "add_precision_option",
    "add_scene_options",
    "add_set_option",
    "add_time_limit_option",
    "add_vary_option",
    "add_verbose_option",
    "apply_scene",
    "apply_set",
    "check_shared",
    "precision_option",
    "warn_varies",
]

#: a number of seconds as written on the command line: ASCII decimal syntax only
_DECIMAL = re.compile(r"^\s*[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?\s*$", re.ASCII)


def add_precision_option(p: argparse.ArgumentParser, default: str, modes: str) -> None:
    """``--precision MODE`` (``modes``: the modes the command takes, for its help)."""
    p.add_argument("--precision", default=default, metavar="MODE", help=modes)


def add_time_limit_option(p: argparse.ArgumentParser) -> None:
    """``--time-limit S``: the most seconds the computation of one configuration may take,
    in every precision mode (default: exact mode's limit in exact mode, none in the others)."""
    # the time-limit module imports no numerics: building the parser stays fast
    from mechsing.timelimit import EXACT_TIME_LIMIT, LONGEST_TIME_LIMIT, SHORTEST_TIME_LIMIT

    p.add_argument(
        "--time-limit",
        type=_seconds,
        default=None,
        metavar="S",
        help=f"the most seconds one configuration may take (from {SHORTEST_TIME_LIMIT:g} to "
        f"{LONGEST_TIME_LIMIT:g}); one stopped there is reported as stopped, exit status 3 "
        f"(default: {EXACT_TIME_LIMIT:g} s in exact mode, none in the others)",
    )


def add_verbose_option(p: argparse.ArgumentParser) -> None:
    """``-v/--verbose``: the file's notes (what mechsing did silently) on standard error."""
    p.add_argument(
        "-v", "--verbose", action="store_true", help="also print what mechsing did silently"
    )


def add_vary_option(p: argparse.ArgumentParser, required: bool, what: str) -> None:
    """``--vary NAME=START:STOP:STEP`` (repeatable: once a path, twice a grid); ``what``
    says what the sweep is for in this command."""
    p.add_argument(
        "--vary",
        action="append",
        required=required,
        metavar="NAME=START:STOP:STEP",
        help=f"{what}: a swept variable in the file's units, once for a path, twice for a grid "
        "(e.g. --vary A=0:360:1, --vary C1[1]=0:0.5:0.01, --vary pose.x=-0.1:0.1:0.01); a "
        "joint given without a range (--vary J2) is swept over its limits",
    )


def add_from_option(p: argparse.ArgumentParser, what: str) -> None:
    """``--from CONFIG`` (``what``: what it starts in this command)."""
    p.add_argument("--from", dest="from_config", metavar="CONFIG", help=what)


def add_set_option(p: argparse.ArgumentParser, from_option: bool = True) -> None:
    """Add ``--set JOINT=VALUE`` (and ``--from CONFIG`` unless the command has its own)."""
    p.add_argument(
        "--set",
        dest="set_values",
        action="append",
        metavar="[NAME:]JOINT=VALUE",
        help=f"a joint value in the file's units (repeatable; a joint of several coordinates "
        f"takes a comma-separated list, e.g. --set S1=0.1,0,0.2): the values with the same "
        f"NAME make a configuration of that name, those without one a configuration named "
        f"{SET_CONFIG}; each solved by closure from reference (or --from)",
    )
    if from_option:
        add_from_option(
            p, f"with --set: the configuration {SET_CONFIG} is solved from (default reference)"
        )


def _seconds(text: str) -> float:
    """``--time-limit``: a number of seconds in the accepted range (argparse: exit 2)."""
    from mechsing.timelimit import check_time_limit

    try:
        if not _DECIMAL.match(text):
            raise ValueError(text)
        return check_time_limit(float(text))
    except ValueError:
        from mechsing.timelimit import LONGEST_TIME_LIMIT, SHORTEST_TIME_LIMIT

        raise argparse.ArgumentTypeError(
            f"{text!r} is not a number of seconds from {SHORTEST_TIME_LIMIT:g} to "
            f"{LONGEST_TIME_LIMIT:g} (e.g. --time-limit 120)"
        ) from None


def precision_option(text: str) -> Any:
    """The ``--precision`` option as a :class:`~mechsing.numeric.Precision`, or a
    UserError that says what is accepted."""
    from mechsing.numeric import parse_precision

    try:
        return parse_precision(text)
    except ValueError as exc:
        raise UserError(f"--precision: {exc}") from None


def warn_varies(mech: Any, varies: list[Any]) -> None:
    """Print the likely mistakes of the swept ranges on standard error, as the file's own
    warnings are (:func:`mechsing.sweeps.spec.vary_warnings` says which)."""
    import sys

    from mechsing.sweeps.spec import vary_warnings

    for warning in vary_warnings(mech, varies):
        print(f"mechsing: warning: {warning}", file=sys.stderr)


def check_shared(
    args: argparse.Namespace, sweeps: str = "a sweep", from_alone: bool = False
) -> None:
    """Check the shared options a command was given, before its file is read: sets
    ``args.prec`` (the Precision of ``--precision``) and ``args.varies`` (the ``--vary``
    values read, each range checked; a joint without a range is checked once its limits
    are read).  ``sweeps``: what sweeps in the command, for the messages; ``from_alone``:
    ``--from`` means something without ``--set`` (modes: where continuation starts)."""
    texts = getattr(args, "vary", None) or []
    if texts:
        from mechsing.sweeps.spec import check_varies

        args.varies = check_varies(texts, sweeps)
    else:
        args.varies = []
    if getattr(args, "precision", None) is not None:
        args.prec = precision_option(args.precision)
        if args.varies:
            from mechsing.sweeps.spec import sweep_precision

            sweep_precision(args.prec)
    set_values = getattr(args, "set_values", None)
    if getattr(args, "from_config", None) and not (set_values or args.varies or from_alone):
        if hasattr(args, "vary"):
            raise UserError(
                f"--from {args.from_config}: names where a sweep starts (or where --set values "
                "are solved from): give --vary or --set too"
            )
        raise UserError(
            f"--from {args.from_config}: names the configuration --set values are solved "
            "from; give --set JOINT=VALUE too (or --config to analyse a configuration of the "
            "file)"
        )


def apply_set(mech: Any, sets: list[str] | None, start: str | None, path: str) -> Any:
    """``mech`` with the configurations the ``--set [NAME:]JOINT=VALUE`` values give
    (:func:`mechsing.adhoc.with_set_values`)."""
    from mechsing.adhoc import with_set_values

    return with_set_values(mech, sets, start, path)


# ------------------------------------------------------------------ the scene options


def add_scene_options(p: argparse.ArgumentParser) -> None:
    """Add ``--output-body BODY``, ``--output-point X,Y,Z``, ``--relative-to BODY`` and
    ``--inputs JOINT[,JOINT...]``: the output and inputs, as the file's ``output`` and
    ``inputs`` keys mean them (:mod:`mechsing.model.scene`)."""
    g = p.add_argument_group(
        "scene (the output and inputs, for a file that names none or other ones)"
    )
    g.add_argument(
        "--output-body",
        metavar="BODY",
        help="the output body (replaces the file's output); the branches that neither lead "
        "to it nor close a loop with that path are left out of the analysis",
    )
    g.add_argument(
        "--output-point",
        metavar="X,Y,Z",
        help="the output is the velocity of this point of the output body (the file's length "
        "unit, at the reference configuration, ground frame): a positioning task",
    )
    g.add_argument(
        "--relative-to",
        metavar="BODY",
        help="the output's motion relative to this body (default the ground)",
    )
    g.add_argument(
        "--inputs",
        metavar="JOINT[,JOINT...]",
        help='the actuated joints (replace the file\'s inputs); "NAME[i]" for one coordinate',
    )


def _merged_link(mech: Any, path: str, name: str | None) -> tuple[str, Any] | None:
    """For ``--output-body`` naming a link of a URDF or MJCF file that is joined rigidly
    into a body named after another link: (that body, the link's origin: m, ground frame,
    reference configuration); None for a body's own name or anything else."""
    if not name or name.strip() in mech.bodies or not isinstance(path, str):
        return None
    from mechsing.formats import xml_spec
    from mechsing.reader import read_source

    src = read_source(path)
    if src.kind == "yaml":
        return None
    return xml_spec(src.text, src.path).merged_links.get(name.strip())


def apply_scene(mech: Any, args: argparse.Namespace, path: str) -> Any:
    """``mech`` with the output and inputs of ``add_scene_options``'s options and only the
    part of it they require; the mechanism's notes (``-v``) say what replaced what.
    ``path`` names the file in messages.  ``--output-body`` may name a link of a URDF
    or MJCF file joined rigidly to another (a tool centre point): the output is then that
    link's origin on the body it belongs to (:func:`_merged_link`)."""
    from mechsing.errors import working_on
    from mechsing.model.scene import SceneChoice, choose_scene, refuse_left_out

    body = getattr(args, "output_body", None)
    point = getattr(args, "output_point", None)
    link = _merged_link(mech, path, body)
    if link is not None:  # a link joined rigidly into another's body: its origin
        body, origin = link
        point = point if point is not None else ",".join(repr(x) for x in origin)
    choice = SceneChoice(
        output_body=body,
        output_point=point,
        relative_to=getattr(args, "relative_to", None),
        inputs=getattr(args, "inputs", None),
    )
    if not choice:
        return mech
    with working_on(file=path):
        chosen = choose_scene(mech, choice)
        if link is not None:
            import dataclasses

            said = (
                f"--output-body {args.output_body.strip()}: the link is joined rigidly to "
                f"body {body!r}; the output is the point {point} m of it"
                + (" (the link's origin)" if getattr(args, "output_point", None) is None else "")
            )
            chosen = dataclasses.replace(chosen, notes=(*chosen.notes, said))
        for option in ("set_values", "vary"):
            given = [
                t.partition("=")[0].split("[")[0].strip() for t in getattr(args, option, None) or ()
            ]
            refuse_left_out(chosen, given, f"--{option.removesuffix('_values')}")
    if getattr(args, "verbose", False):
        import sys

        for note in chosen.notes[len(mech.notes) :]:
            print(f"mechsing: {note}", file=sys.stderr)
    return chosen


def add_load_option(p: argparse.ArgumentParser) -> None:
    """Add ``--load`` (a wrench on the output): its text is kept as given and read when the
    command runs (:func:`mechsing.statics.loads.parse_load`), so the parser imports no
    statics (``--help`` stays light)."""
    p.add_argument(
        "--load",
        metavar='"force=FX,FY,FZ ..."',
        help='a load on the output: "force=FX,FY,FZ moment=MX,MY,MZ point=X,Y,Z" (N; moment '
        "in N times the file's length unit about the point, a point of the output body in the "
        "drawn pose in the file's length unit; each part optional, the point defaults to the "
        "output's reference point); it replaces the file's load",
    )


def with_load(result: Any, mech: Any, text: str | None) -> Any:
    """The analysis ``result`` with the statics of its configurations under ``--load``
    (``text``) or the file's loads (docs/kinetostatics.md)."""
    from mechsing.statics import with_kinetostatics
    from mechsing.statics.loads import parse_load

    return with_kinetostatics(result, mech, None if text is None else parse_load(text, mech))


def add_max_effort_option(p: argparse.ArgumentParser) -> None:
    """Add ``--max-effort INPUT=VALUE`` (repeatable; :mod:`mechsing.statics.along`)."""
    p.add_argument(
        "--max-effort",
        action="append",
        metavar="INPUT=VALUE",
        help="locate where the input's |effort| under the load (--load or the --from "
        "configuration's) first exceeds VALUE (N for a prismatic input, N m for a rotation); "
        "reported as an effort limit, not a singularity (repeatable; along a path, or along "
        "each row of a grid)",
    )


def with_sweep_load(sweep_run: Any, mech: Any, text: str | None, limits: list[str] | None) -> None:
    """Give ``sweep_run`` the statics of its samples under ``--load`` (``text``), or the
    load of the configuration it starts from, and the ``--max-effort`` limits."""
    from mechsing.statics.along import attach, parse_max_effort
    from mechsing.statics.loads import parse_load

    load = None if text is None else parse_load(text, mech)
    attach(sweep_run, load, parse_max_effort(limits, mech))


def report_load(mech: Any, text: str | None, limits: list[str] | None) -> dict[str, Any]:
    """``report``'s keyword arguments for ``--load`` and ``--max-effort``."""
    from mechsing.statics.along import parse_max_effort
    from mechsing.statics.loads import parse_load

    return {
        "load": None if text is None else parse_load(text, mech),
        "max_effort": parse_max_effort(limits, mech) or None,
    }


def add_duration_option(p: argparse.ArgumentParser) -> None:
    """Add ``--duration T`` (:mod:`mechsing.kinetics.timed`)."""
    p.add_argument(
        "--duration",
        type=_duration,
        metavar="T",
        help="time the path: the swept value follows a smooth rest-to-rest law over T seconds, "
        "and each sample gets the efforts that motion needs (the file's masses and gravity; "
        "a closed chain: its inputs' efforts and the Type II crossing condition; a path only)",
    )


def _duration(text: str) -> float:
    """``--duration``: a positive, finite number of seconds (argparse: exit 2)."""
    from mechsing.numeric.numbers import decimal_float

    try:
        x = decimal_float(text)
    except ValueError:
        x = 0.0
    if not 0 < x < float("inf"):
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a positive number of seconds (e.g. --duration 2)"
        )
    return x
