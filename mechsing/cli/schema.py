"""Print the JSON Schema (draft 2020-12) of the mechanism file format.

Point an editor's YAML or JSON language server at it to get completion and
checks while writing a mechanism file.  mechsing's own validation
(``mechsing analyze``) checks more than the schema can (names, geometry,
expressions) and is the authority.  With --sweep, the schema of the document
``mechsing sweep --format json`` writes instead; with --condition, that of
``mechsing condition --format json``; with --modes, --dynamics or --cusps, that of
the ``mechsing modes``, ``dynamics`` or ``cusps`` document.
"""

from __future__ import annotations

import argparse
import json

NAME = "schema"
HELP = "print the JSON Schema of the mechanism file format (or of a command's JSON document)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--compact", action="store_true", help="print on one line instead of indented"
    )
    # one document at a time (two of these printed one of them, silently)
    one = parser.add_mutually_exclusive_group()
    one.add_argument(
        "--sweep",
        action="store_true",
        help="the schema of mechsing sweep's JSON document instead of the file format's",
    )
    one.add_argument(
        "--modes",
        action="store_true",
        help="the schema of mechsing modes' JSON document instead of the file format's",
    )
    one.add_argument(
        "--condition",
        action="store_true",
        help="the schema of mechsing condition's JSON document instead of the file format's",
    )
    one.add_argument(
        "--dynamics",
        action="store_true",
        help="the schema of mechsing dynamics' JSON document instead of the file format's",
    )
    one.add_argument(
        "--cusps",
        action="store_true",
        help="the schema of mechsing cusps' JSON document instead of the file format's",
    )


def run(args: argparse.Namespace) -> int:
    if getattr(args, "cusps", False):
        from mechsing.assembly.cusps_schema import cusps_schema

        schema = cusps_schema()
    elif getattr(args, "dynamics", False):
        from mechsing.kinetics.schema import dynamics_schema

        schema = dynamics_schema()
    elif getattr(args, "modes", False):
        from mechsing.assembly.schema import modes_schema

        schema = modes_schema()
    elif getattr(args, "condition", False):
        from mechsing.conditions.schema import condition_schema

        schema = condition_schema()
    elif getattr(args, "sweep", False):
        from mechsing.sweeps.schema import sweep_schema

        schema = sweep_schema()
    else:
        from mechsing.model.schema import mechanism_schema

        schema = mechanism_schema()
    if getattr(args, "compact", False):
        print(json.dumps(schema, separators=(",", ":")))
    else:
        print(json.dumps(schema, indent=2))
    return 0
