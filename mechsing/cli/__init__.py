"""The ``mechsing`` command (a face: :mod:`mechsing.cli.main` holds :func:`main` and the
parser; each sub-command is a module of this package, :mod:`mechsing.cli.options` holds
the options several share)."""

from mechsing.cli.main import (
    BAD_INPUT,
    COMMANDS,
    INTERNAL_ERROR,
    NOT_ANALYSED,
    build_parser,
    exit_status,
    load_mechanism,
    main,
    with_file,
)
from mechsing.errors import ConfigurationError, MechsingError, UserError

__all__ = [
    "BAD_INPUT",
    "COMMANDS",
    "INTERNAL_ERROR",
    "NOT_ANALYSED",
    "ConfigurationError",
    "MechsingError",
    "UserError",
    "build_parser",
    "exit_status",
    "load_mechanism",
    "main",
    "with_file",
]
