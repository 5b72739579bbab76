"""Units of the numbers of an answer key and of a student's sheet.

mechsing answers in SI units and radians; a key states a number in its question's unit
(``deg``, ``mm`` ...), and a student may write any unit of the same kind: each is
converted to SI before the comparison.
"""

from __future__ import annotations

import math
import re

from mechsing.errors import UserError

__all__ = ["UNITS", "parse_quantity", "to_si"]

#: unit -> (quantity, its value in SI units)
UNITS: dict[str, tuple[str, float]] = {
    "m": ("length", 1.0),
    "cm": ("length", 1e-2),
    "mm": ("length", 1e-3),
    "um": ("length", 1e-6),
    "km": ("length", 1e3),
    "in": ("length", 0.0254),
    "rad": ("angle", 1.0),
    "deg": ("angle", math.pi / 180),
    "°": ("angle", math.pi / 180),
    "mrad": ("angle", 1e-3),
    "turn": ("angle", 2 * math.pi),
}
_TRAILING_UNIT = re.compile(r"^(?P<number>.*?)\s*(?P<unit>°|[A-Za-z]+)$")


def to_si(value: float, unit: str | None) -> float:
    """A number in ``unit`` (None: a pure number) in SI units."""
    return value if unit is None else value * UNITS[unit][1]


def parse_quantity(text: str | int | float) -> tuple[float, str | None]:
    """A number of a sheet and its unit: ``33.1 deg``, ``12mm``, ``pi/6 rad``, ``0.5``
    (no unit).  The number is a decimal or a whitelisted expression (``sqrt(2)/2``).

    Raises UserError for a text that is not a number or names an unknown unit.
    """
    from mechsing.errors import ExpressionError
    from mechsing.model.expressions import parse_number

    if isinstance(text, bool):
        raise UserError(f"{text!r} is not a number")
    if isinstance(text, int | float):
        if not math.isfinite(text):
            raise UserError(f"{text!r} is not a finite number")
        return float(text), None
    t = str(text).strip()
    unit = None
    m = _TRAILING_UNIT.match(t)
    if m and m["number"] and m["unit"] != "pi":
        if m["unit"] not in UNITS:
            raise UserError(f"unknown unit {m['unit']!r} in {t!r} (known: {', '.join(UNITS)})")
        t, unit = m["number"].strip(), m["unit"]
    try:
        value = float(parse_number(t))
    except ExpressionError as exc:
        raise UserError(f"{text!r} is not a number: {exc}") from None
    return value, unit
