"""The format a command writes: ``--format``, else the one the extension of ``-o OUT``
names, else text.

One table (:data:`EXTENSIONS`) names the format of each extension, and one function
(:func:`output_format`) decides, for every command that writes to ``-o`` (``analyze``,
``modes``, ``condition``, ``sweep``, ``cusps``; ``report``, whose output is HTML or
Markdown, reads the same table).  An extension the table does not know writes text; one
that names a format the command does not write is refused (exit 2) before the work.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from pathlib import Path

from mechsing.errors import UserError

__all__ = ["EXTENSIONS", "add_output_options", "extension_format", "output_format"]

#: the format each extension of ``-o`` names
EXTENSIONS = {
    ".txt": "text",
    ".json": "json",
    ".md": "md",
    ".csv": "csv",
    ".tex": "latex",
    ".html": "html",
    ".htm": "html",
}


def _either(words: Sequence[str]) -> str:
    return ", ".join(words[:-1]) + f" or {words[-1]}" if len(words) > 1 else words[0]


def _extensions(formats: Sequence[str]) -> list[str]:
    return [ext for ext, fmt in EXTENSIONS.items() if fmt in formats]


def add_output_options(p: argparse.ArgumentParser, formats: Sequence[str], what: str) -> None:
    """``--format`` (one of ``formats``, the first the default) and ``-o OUT`` (write
    ``what`` there), the format following OUT's extension when ``--format`` is not given."""
    p.add_argument(
        "--format",
        choices=formats,
        default=None,
        help=f"{_either(formats)} (default {formats[0]}); with -o and no --format, from OUT's "
        f"extension ({', '.join(_extensions(formats))}; one that names no format: {formats[0]})",
    )
    p.add_argument(
        "-o", "--output", metavar="OUT", help=f"write {what} to OUT instead of standard output"
    )


def extension_format(out: str) -> str | None:
    """The format the extension of ``out`` names (None: an extension not in the table)."""
    return EXTENSIONS.get(Path(out).suffix.lower())


def output_format(fmt: str | None, out: str | None, formats: Sequence[str], command: str) -> str:
    """The format ``command`` writes: ``fmt`` when given, else the one OUT's extension
    names, else the first of ``formats`` (text); a UserError when the extension names a
    format the command does not write."""
    if fmt:
        return fmt
    named = extension_format(out) if out else None
    if named is None:
        return formats[0]
    if named not in formats:
        raise UserError(
            f"-o {out}: {command} writes {_either(formats)}, not {named}: name the output "
            f"{_either(_extensions(formats))}, or give --format"
        )
    return named
