"""Reading a mechanism from a file of any format: the one way every command reads one.

Owns :func:`read_mechanism` (a path: mechsing YAML or JSON, with or without a
``dh`` table, a URDF or an MJCF description, recognised by content whatever
the extension), :func:`read_source` (the file's text and its mechsing YAML,
what ``mechsing convert`` writes) and :func:`mechanism_from_text`.  It sits
above :mod:`mechsing.model` (which reads mechsing YAML and JSON) and
:mod:`mechsing.formats` (which turns URDF and MJCF into mechsing YAML, and a
``dh`` table into bodies and joints: the reader hands it to the model), so the
model imports no format.  The mechanism's ``warnings`` (likely mistakes that
are not errors) and ``notes`` travel with it: the command line prints them,
a program reads them.  Every problem is a
:class:`~mechsing.errors.MechanismError` (exit status 2) naming the file.
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass
from functools import partial
from pathlib import Path

from mechsing.formats import xml_format, xml_to_yaml
from mechsing.formats.dh import expand_dh
from mechsing.formats.xmlsafe import MAX_XML_BYTES
from mechsing.model import Mechanism, loads
from mechsing.model.loader import read_text
from mechsing.numeric import Precision, parse_precision
from mechsing.yamlnodes import MAX_FILE_BYTES

__all__ = ["LARGEST_FILE", "Source", "mechanism_from_text", "read_mechanism", "read_source"]

#: the largest file read (bytes): a YAML text is bounded again when it is parsed
LARGEST_FILE = max(MAX_FILE_BYTES, MAX_XML_BYTES)


@dataclass(frozen=True)
class Source:
    """A mechanism file as read: ``kind`` is ``"yaml"`` (mechsing YAML or JSON),
    ``"urdf"`` or ``"mjcf"``; ``yaml`` is its mechsing YAML text (the text itself
    for a mechsing file)."""

    path: str
    text: str
    kind: str
    yaml: str

    @property
    def name(self) -> str:
        """The mechanism's default name: the file name without its extension."""
        return Path(self.path).stem


def read_source(path: str | Path) -> Source:
    """Read a mechanism file's text and recognise its format (MechanismError when the
    file cannot be read, is too large, is not UTF-8 text, or is XML of another kind)."""
    return _source(read_text(path, LARGEST_FILE), str(path))


def _source(text: str, path: str) -> Source:
    kind = xml_format(text)
    if kind is None:
        return Source(path, text, "yaml", text)
    return Source(path, text, kind, xml_to_yaml(text, path))


def read_mechanism(
    source: str | Path | Source,
    symbolic: Collection[str] = (),
    exact_tables: bool = False,
    precision: Precision | str | None = None,
) -> Mechanism:
    """The mechanism of a file of any format mechsing reads (YAML or JSON, a ``dh``
    table, URDF, MJCF), with its ``warnings`` and ``notes``.

    ``symbolic`` names parameters of the file to keep as symbols
    (:class:`~mechsing.model.parameters.ParameterSymbol`), for symbolic conditions;
    ``exact_tables`` has a ``dh`` table's frames computed exactly (as symbolic
    conditions need), not in floats.  ``precision``: the precision the mechanism is read
    for.  A float one, or auto (whose first pass is float), keeps the file's rationals
    times powers of pi as :class:`~mechsing.numeric.pirational.PiRational` numbers instead
    of sympy values (a float analysis then imports no sympy; an exact or mp computation
    that needs one converts it); ``mp:N``, ``exact`` and None (the default: any use) read
    sympy values.
    Raises :class:`~mechsing.errors.MechanismError` for every problem of the file."""
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    plain_numbers = prec is not None and prec.mode in ("float", "auto")
    src = source if isinstance(source, Source) else read_source(source)
    expand = partial(expand_dh, keep_exact=True) if exact_tables else expand_dh
    return loads(
        src.yaml,
        path=src.path,
        default_name=src.name,
        symbolic=symbolic,
        expand_dh=expand,
        plain_numbers=plain_numbers,
    )


def mechanism_from_text(
    text: str,
    path: str | None = None,
    default_name: str = "mechanism",
    symbolic: Collection[str] = (),
) -> Mechanism:
    """The mechanism of a text in any format :func:`read_mechanism` reads (``path`` only
    for messages)."""
    src = _source(text, path if path is not None else "<text>")
    return loads(
        src.yaml, path=src.path, default_name=default_name, symbolic=symbolic, expand_dh=expand_dh
    )
