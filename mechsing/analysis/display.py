"""The one rendering rule: how a result's numbers, units and tables are shown as text and
Markdown.

Every text and Markdown rendering takes its primitives from here -- an analysis
(:mod:`mechsing.reports.render`), a sweep (:mod:`mechsing.sweeps.results`), the assembly
modes (:mod:`mechsing.assembly.render`) and the conditions
(:mod:`mechsing.conditions.results`) -- so that a change made here shows in all of them:

* a number with its display floor (:func:`floor_for`, :func:`shown`): a length below the
  closure tolerance of its precision is round-off and is shown as 0, an angle below that
  divided by L likewise (:func:`mechsing.numeric.display_floor`); the JSON keeps the
  numbers;
* a unit as the text spells it (:data:`UNIT_TEXT`, :func:`unit_text`), and a number with
  its unit (:func:`quantity`, :func:`with_unit`: also the lengths and pitches of the screw
  sentences, :mod:`mechsing.analysis.words`); JSON and CSV keep the SI identifiers
  (``m``, ``rad``);
* a table (:func:`markdown_table`);
* a finding's sentence and a class's words stay in :mod:`mechsing.analysis.words` (the one
  place the words a student reads are made).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from mechsing.numeric import Precision, display_floor, floored

__all__ = [
    "UNIT_TEXT",
    "angle_floor",
    "floor_for",
    "markdown_table",
    "quantity",
    "shown",
    "unit_text",
    "with_unit",
]

#: how the text spells each unit (the JSON's unit identifiers, and the file units a user
#: may write); a unit not listed is shown as written
UNIT_TEXT: dict[str, str] = {"m": "m", "rad": "rad", "deg": "deg"}


def unit_text(unit: str) -> str:
    """The unit ``unit`` as text and Markdown spell it (a quotient such as ``m/rad``:
    each of its units so)."""
    return "/".join(UNIT_TEXT.get(u, u) for u in unit.split("/"))


def floor_for(precision: Precision | str, length_scale: float) -> float:
    """The display floor of a length at ``precision`` (round-off below it: shown as 0);
    an angle's is :func:`angle_floor` of it."""
    return float(display_floor(precision, length_scale))


def angle_floor(floor: float, length_scale: float) -> float:
    """The display floor of an angle (rad), from a length's ``floor``: ``floor / L``."""
    return floor / length_scale


def shown(x: Any, floor: float = 0.0, spec: str = ".6g") -> str:
    """``x`` as displayed: 0 below ``floor`` (never -0), formatted with ``spec``."""
    return format(floored(float(x), floor), spec)


def quantity(x: Any, unit: str, floor: float = 0.0, spec: str = ".6g") -> str:
    """``x`` with its unit (``0.5 m``, ``0 rad`` below the floor)."""
    return with_unit(shown(x, floor, spec), unit)


def with_unit(text: str, unit: str) -> str:
    """A number already written (``text``, e.g. at a working precision's digits) with its
    unit."""
    return f"{text} {unit_text(unit)}"


def markdown_table(headers: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    """The lines of a Markdown table: the header, its rule, then one line per row."""
    out = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    out += ["| " + " | ".join(row) + " |" for row in rows]
    return out
