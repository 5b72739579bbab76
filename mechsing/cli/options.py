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
from typing import Any

from mechsing.model.adhoc import SET_CONFIG  # the name of the configuration unnamed values make

__all__ = ["SET_CONFIG", "add_scene_options", "add_set_option", "apply_scene", "apply_set"]


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
        p.add_argument(
            "--from",
            dest="from_config",
            metavar="CONFIG",
            help=f"with --set: the configuration {SET_CONFIG} is solved from (default reference)",
        )


def apply_set(mech: Any, sets: list[str] | None, start: str | None, path: str) -> Any:
    """``mech`` with the configurations the ``--set [NAME:]JOINT=VALUE`` values give
    (:func:`mechsing.model.adhoc.with_set_values`)."""
    from mechsing.model.adhoc import with_set_values

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
