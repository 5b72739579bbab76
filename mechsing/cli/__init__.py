"""The ``mechsing`` command.

Each sub-command lives in its own module of this package and exposes
``NAME`` (the sub-command), ``HELP`` (one line), ``add_arguments(parser)`` and
``run(args) -> int``.  Exit status: 0 success, 2 bad input, 3 a configuration
could not be analysed (not closed, or refused or stopped by exact mode; the
others are reported).
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING

from mechsing import __version__

# mechsing works on many tiny matrices: BLAS threads only add overhead there (and
# on a loaded machine make a 4x4 product hundreds of times slower).  This module
# imports no numpy, and the commands import their layers lazily, so this runs
# before numpy is loaded; a user's own setting wins.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

if TYPE_CHECKING:  # the commands import their layers lazily: `mechsing --version` stays fast
    from mechsing.model import Mechanism
    from mechsing.numeric import Precision

#: sub-command modules, in the order ``--help`` lists them
COMMANDS = ("analyze", "solve", "catalog", "identify", "schema")


class UserError(Exception):
    """Bad input: printed without a traceback, exit status 2 (or ``status``)."""

    def __init__(self, message: str, status: int = 2) -> None:
        super().__init__(message)
        self.status = status


def precision_option(text: str) -> Precision:
    """The ``--precision`` option, or a UserError that says what is accepted."""
    from mechsing.numeric import parse_precision

    try:
        return parse_precision(text)
    except ValueError as exc:
        raise UserError(f"--precision: {exc}") from None


def load_mechanism(path: str, verbose: bool = False) -> Mechanism:
    """Read a mechanism file; with ``verbose`` print what was done silently (axes normalised...)."""
    from mechsing.model import load

    mech = load(path)
    if verbose:
        for note in mech.notes:
            print(f"mechsing: {note}", file=sys.stderr)
    return mech


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # argparse exits 2 already; keep its words
        self.print_usage(sys.stderr)
        self.exit(2, f"mechsing: error: {message}\n")


def _load_commands() -> list:
    mods = []
    for name in COMMANDS:
        try:
            mods.append(importlib.import_module(f"mechsing.cli.{name}"))
        except ModuleNotFoundError as exc:  # a command not built yet
            if exc.name != f"mechsing.cli.{name}":
                raise
    return mods


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="mechsing",
        description="Find and classify the singularities of mechanisms with Lie groups.",
    )
    parser.add_argument("--version", action="version", version=f"mechsing {__version__}")
    parser.add_argument(
        "-T",
        "--traceback",
        action="store_true",
        help="show a Python traceback on errors (debugging)",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for mod in _load_commands():
        p = sub.add_parser(mod.NAME, help=mod.HELP, description=mod.__doc__)
        mod.add_arguments(p)
        p.set_defaults(_run=mod.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "_run", None):
        parser.print_help()
        return 0
    try:
        return int(args._run(args))
    except UserError as exc:
        if args.traceback:
            raise
        print(f"mechsing: error: {exc}", file=sys.stderr)
        return exc.status
    except BrokenPipeError:
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
