"""Options shared by several commands: ``--set JOINT=VALUE`` (an ad-hoc configuration) and
the scene options ``--output-body``, ``--output-point``, ``--relative-to``, ``--inputs``.

Owns :func:`add_set_option` and :func:`apply_set`, :func:`add_scene_options` and
:func:`apply_scene` (whose policy is :func:`mechsing.model.scene.choose_scene`).  ``--set`` (repeatable) gives
joint values in the file's units (a joint of several coordinates takes a
comma-separated list, ``--set S1=0.1,0,0.2``; exact expressions such as ``pi/4``
are read as in a mechanism file); together they form a configuration named
``cli``, added to the mechanism and solved by closure from ``reference`` or
from the configuration ``--from`` names.  A file that already has a
configuration called ``cli`` is refused (exit 2).
"""

from __future__ import annotations

import argparse
import dataclasses
from typing import Any

from mechsing.errors import UserError

__all__ = ["SET_CONFIG", "add_scene_options", "add_set_option", "apply_scene", "apply_set"]

#: the name of the configuration --set adds
SET_CONFIG = "cli"


def add_set_option(p: argparse.ArgumentParser, from_option: bool = True) -> None:
    """Add ``--set JOINT=VALUE`` (and ``--from CONFIG`` unless the command has its own)."""
    p.add_argument(
        "--set",
        dest="set_values",
        action="append",
        metavar="JOINT=VALUE",
        help=f"a joint value in the file's units (repeatable; a joint of several coordinates "
        f"takes a comma-separated list, e.g. --set S1=0.1,0,0.2): together they make a "
        f"configuration named {SET_CONFIG}, solved by closure from reference (or --from)",
    )
    if from_option:
        p.add_argument(
            "--from",
            dest="from_config",
            metavar="CONFIG",
            help=f"with --set: the configuration {SET_CONFIG} is solved from (default reference)",
        )


def apply_set(mech: Any, sets: list[str] | None, start: str | None, path: str) -> Any:
    """``mech`` with the configuration ``cli`` the ``--set`` values give (``mech`` itself
    when there is none); ``start`` is the configuration it is solved from (None:
    reference); ``path`` names the file in messages."""
    from mechsing.model.expressions import ExpressionError, parse_number
    from mechsing.model.mechanism import Configuration

    if not sets:
        if start is not None:
            raise UserError(
                f"--from {start}: names the configuration --set values are solved from; give "
                "--set JOINT=VALUE too (or --config to analyse a configuration of the file)"
            )
        return mech
    if SET_CONFIG in mech.configurations:
        raise UserError(
            f"{path}: the file already has a configuration named {SET_CONFIG!r}, the name "
            f"--set gives its values; rename the file's configuration or use --config "
            f"{SET_CONFIG} without --set"
        )
    start = start or "reference"
    if start not in mech.configurations:
        raise UserError(
            f"{path}: --from {start!r}: no such configuration; the file has: "
            f"{', '.join(mech.configurations)}"
        )
    units = mech.units
    values: dict[str, tuple[Any, ...]] = {}
    for text in sets:
        name, eq, raw = text.partition("=")
        name = name.strip()
        if not eq or not name or not raw.strip():
            raise UserError(f"--set {text!r}: expected JOINT=VALUE, e.g. --set J2=30")
        if name not in mech.joint_names:
            shown = ", ".join(mech.joint_names[:12]) + (", ..." if len(mech.joints) > 12 else "")
            raise UserError(f"--set {text!r}: {path} has no joint {name!r}; its joints are {shown}")
        if name in values:
            raise UserError(f"--set {name} is given twice; give each joint once")
        j = mech.joint(name)
        parts = [t.strip() for t in raw.split(",")]
        if j.dof == 0:
            raise UserError(f"--set {text!r}: joint {name!r} ({j.type}) has no coordinates")
        if len(parts) != j.dof:
            raise UserError(
                f"--set {text!r}: joint {name!r} ({j.type}) has {j.dof} coordinate"
                f"{'s' if j.dof > 1 else ''}; give {j.dof} comma-separated value"
                f"{'s' if j.dof > 1 else ''} in the file's units"
            )
        coords = []
        for t, unit in zip(parts, j.units, strict=True):
            try:
                x = parse_number(t)
            except ExpressionError as exc:
                raise UserError(f"--set {text!r}: {exc}") from None
            factor = units.angle_factor if unit == "rad" else units.length_factor
            coords.append(x * factor if factor != 1 else x)
        values[name] = tuple(coords)
    conf = Configuration(SET_CONFIG, values, start, None, {}, None)
    configs = {**mech.configurations, SET_CONFIG: conf}
    return dataclasses.replace(mech, configurations=configs)


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


def apply_scene(mech: Any, args: argparse.Namespace, path: str) -> Any:
    """``mech`` with the output and inputs of ``add_scene_options``'s options and only the
    part of it they require; the mechanism's notes (``-v``) say what replaced what.
    ``path`` names the file in messages."""
    from mechsing.errors import working_on
    from mechsing.model.scene import SceneChoice, choose_scene, refuse_left_out

    choice = SceneChoice(
        output_body=getattr(args, "output_body", None),
        output_point=getattr(args, "output_point", None),
        relative_to=getattr(args, "relative_to", None),
        inputs=getattr(args, "inputs", None),
    )
    if not choice:
        return mech
    with working_on(file=path):
        chosen = choose_scene(mech, choice)
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
