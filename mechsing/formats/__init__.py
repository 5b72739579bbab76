"""Robot descriptions in other formats (URDF, MJCF, DH tables) read as mechanism files.

Owns the recognition of a format by content (:func:`xml_format`: the root
element ``<robot>`` is URDF, ``<mujoco>`` is MJCF, whatever the extension) and
:func:`xml_to_yaml`, the mechsing YAML text of an XML description (what
``mechsing convert`` writes and what the loader reads for an XML file).  The
DH table key of a mechanism file is expanded by :mod:`mechsing.formats.dh`.
Lengths in metres; angles in the source's unit (written in the YAML's
``units``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mechsing.errors import MechanismError
from mechsing.formats.xmlsafe import root_tag

if TYPE_CHECKING:
    from mechsing.formats.writer import MechanismSpec

__all__ = ["xml_format", "xml_spec", "xml_to_yaml"]


def xml_format(text: str) -> str | None:
    """``"urdf"``, ``"mjcf"``, ``"xml"`` (another XML document) or None (not XML)."""
    tag = root_tag(text)
    if tag is None:
        return None
    return {"robot": "urdf", "mujoco": "mjcf"}.get(tag, "xml")


def xml_to_yaml(text: str, path: str) -> str:
    """The mechsing YAML text of a URDF or MJCF description."""
    from mechsing.formats.writer import to_yaml

    return to_yaml(xml_spec(text, path))


def xml_spec(text: str, path: str) -> MechanismSpec:
    """The mechanism file's content of a URDF or MJCF description."""
    kind = xml_format(text)
    if kind == "urdf":
        from mechsing.formats.urdf import read_urdf

        return read_urdf(text, path)
    if kind == "mjcf":
        from mechsing.formats.mjcf import read_mjcf

        return read_mjcf(text, path)
    tag = root_tag(text)
    if tag == "!DOCTYPE":
        raise MechanismError(
            "the file has a <!DOCTYPE> declaration; mechsing does not read document type "
            "declarations or entities (they can expand without bound or read other files); "
            "remove the declaration",
            path=path,
            line=text.count("\n", 0, max(0, text.upper().find("<!DOCTYPE"))) + 1,
        )
    raise MechanismError(
        f"an XML file whose root element is <{tag}>: mechsing reads URDF (<robot>) and MJCF "
        "(<mujoco>) descriptions, and mechanism files in YAML or JSON",
        path=path,
    )
