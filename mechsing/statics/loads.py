"""``--load``: a load on the output written on the command line.

The form is words ``KEY=x,y,z`` in one argument, keys ``force`` (N), ``moment`` (N times
the file's length unit, about the point) and ``point`` (the file's length unit, a point
of the output body in the drawn pose, as the file's ``load``), e.g.
``--load "force=0,0,-10 point=1,0,0"``.  Entries are numbers or the file format's
whitelisted expressions.  It replaces the file's ``load`` of every configuration.
"""

from __future__ import annotations

from typing import Any

from mechsing.errors import ExpressionError, UserError
from mechsing.model.loads import LOAD_KEYS, Load

__all__ = ["parse_load"]


def parse_load(text: str, mech: Any) -> Load:
    """The :class:`~mechsing.model.loads.Load` of a ``--load`` argument, in SI with the
    file's length unit (``mech.units``)."""
    from mechsing.model.expressions import parse_number

    if mech.output is None:
        raise UserError(
            "--load is a wrench applied to the output body, but the file has no output; add "
            "output: {body: NAME} to the file (or --output-body)"
        )
    if not mech.inputs:
        raise UserError(
            "--load asks for the actuator efforts, but the file has no inputs; add inputs: "
            "[JOINT, ...] to the file (or --inputs)"
        )
    lf = mech.units.length_factor
    got: dict[str, tuple[Any, Any, Any]] = {}
    for word in text.replace(";", " ").split():
        key, eq, value = word.partition("=")
        key = key.strip().lower()
        if not eq or key not in LOAD_KEYS:
            raise UserError(
                f"--load {text!r}: {word!r} is not KEY=x,y,z with KEY one of "
                f'{", ".join(LOAD_KEYS)}; write e.g. --load "force=0,0,-10 point=1,0,0"'
            )
        if key in got:
            raise UserError(f"--load {text!r}: {key} is given twice; give it once")
        parts = [p for p in value.split(",")]
        if len(parts) != 3:
            raise UserError(
                f"--load {text!r}: {key} needs 3 numbers x,y,z separated by commas, got "
                f"{len(parts)}"
            )
        try:
            nums = tuple(parse_number(p.strip(), {}) for p in parts)
        except ExpressionError as exc:
            raise UserError(f"--load {text!r}: {key}: {exc}") from None
        factor = 1 if key == "force" else lf
        got[key] = (nums[0] * factor, nums[1] * factor, nums[2] * factor)
    if "force" not in got and "moment" not in got:
        raise UserError(
            f"--load {text!r}: give force=FX,FY,FZ and/or moment=MX,MY,MZ (a point alone is "
            "no load)"
        )
    return Load(got.get("force", (0, 0, 0)), got.get("moment", (0, 0, 0)), got.get("point"))
