"""The reading context of a mechanism file: :class:`Reader` knows the file (for the
messages of :class:`~mechsing.errors.MechanismError`: path, line, item), its units,
scale and named parameters, collects notes and warnings, and checks the shape of each
node (mapping, list, name, number, vector, direction) as it converts it to exact
values (sympy's, or with ``plain`` a :class:`~mechsing.numeric.pirational.PiRational`
where the number is a rational times a power of pi).  The loader (:mod:`mechsing.model.loader`), the joints'
(:mod:`mechsing.model.joints`) and the configurations' readers
(:mod:`mechsing.model.configurations`), the parameters and the couplings read
through one.
"""

from __future__ import annotations

import math
from typing import Any

from mechsing.errors import ExpressionError, MechanismError
from mechsing.model.expressions import parse_number, written_digits
from mechsing.model.mechanism import Units
from mechsing.numeric import NEAR_ZERO_VECTOR, data_resolution
from mechsing.numeric.lazy import sympy
from mechsing.numeric.pirational import PiRational, evalf_float, rational_sqrt
from mechsing.yamlnodes import YMap, YScalar, YSeq, YValue

__all__ = ["Reader", "closest", "few", "show_vector"]

_NAME_HINT = "a name such as crank or link_2"


class Reader:
    """Validation helpers that know the file (for messages) and collect notes."""

    def __init__(self, path: str | None, plain: bool = False) -> None:
        self.path = path
        #: keep the file's rationals times powers of pi as PiRational numbers (no sympy)
        self.plain = plain
        self.notes: list[str] = []
        self.warnings: list[str] = []
        self.units = Units()
        self.scale = 1.0  # largest point coordinate (file units), for near-zero tests
        self.parameters: dict[str, Any] = {}  # the file's named parameters (parameters.py)
        #: (joint, parameter, entry, resolution in SI, digits) of the geometry written with
        #: digits to spare (Mechanism.resolution)
        self.geometry: list[tuple[str, str, int, float, int]] = []

    def error(self, item: str | None, line: int | None, message: str) -> MechanismError:
        return MechanismError(message, path=self.path, line=line, item=item)

    def warn(self, item: str, line: int | None, message: str) -> None:
        """A likely mistake that is not an error: worded like an error's message."""
        self.warnings.append(str(MechanismError(message, path=self.path, line=line, item=item)))

    # -- shapes ---------------------------------------------------------------

    def mapping(self, v: YValue | None, item: str, what: str) -> YMap:
        if not isinstance(v, YMap):
            line = getattr(v, "line", None)
            got = v.describe() if v is not None else "nothing"
            raise self.error(item, line, f"{what} must be a mapping (key: value), got {got}")
        return v

    def sequence(self, v: YValue, item: str, what: str, example: str) -> YSeq:
        if not isinstance(v, YSeq):
            raise self.error(
                item, v.line, f"{what} must be a list, got {v.describe()}; write e.g. {example}"
            )
        return v

    def keys(
        self,
        m: YMap,
        item: str,
        allowed: tuple[str, ...],
        required: tuple[str, ...] = (),
        hint: str = "",
    ) -> None:
        for k, _ in m.items:
            if k.text not in allowed:
                extra = f" ({hint})" if hint else ""
                close = closest(k.text, allowed)
                sugg = f"; did you mean {close!r}?" if close else ""
                raise self.error(
                    item,
                    k.line,
                    f"unknown key {k.text!r}{sugg} Allowed keys: {', '.join(allowed)}{extra}",
                )
        for r in required:
            if m.get(r) is None:
                raise self.error(item, m.line, f"missing key {r!r}; add it")

    def name(self, v: YValue, item: str, what: str) -> str:
        if not isinstance(v, YScalar) or v.kind == "null" or not v.text.strip():
            got = v.describe() if isinstance(v, YScalar | YSeq | YMap) else "nothing"
            raise self.error(
                item,
                getattr(v, "line", None),
                f"{what} must be a name, got {got or 'nothing'}; give {_NAME_HINT}",
            )
        text = v.text.strip()
        if len(text) > 200:
            raise self.error(
                item, v.line, f"{what} {text[:40]!r}... is too long (at most 200 characters)"
            )
        return text

    # -- numbers --------------------------------------------------------------

    def number(self, v: YValue | None, item: str, what: str, factor: Any = 1) -> Any:
        line = getattr(v, "line", None)
        if not isinstance(v, YScalar):
            got = v.describe() if v is not None else "nothing"
            raise self.error(item, line, f"{what} must be a number, got {got}")
        if v.kind in ("bool", "null"):
            raise self.error(item, line, f"{what} must be a number, got {v.text or 'nothing'!r}")
        t = v.text.strip().lower()
        if v.kind == "float" and t.lstrip("+-") in (".inf", ".nan"):
            raise self.error(
                item, line, f"{what} is {v.text}, not a finite number; give a finite value"
            )
        try:
            value = parse_number(v.text, self.parameters, plain=self.plain)
        except ExpressionError as exc:
            raise self.error(item, line, f"{what}: {exc}") from None
        return value * factor if factor != 1 else value

    def resolution(self, node: YValue | None, factor: Any = 1) -> tuple[float, int]:
        """The resolution (times ``factor``: SI) and significant digits of a number as
        written (:func:`mechsing.numeric.data_resolution`); (0, 0) for an exact one (an
        expression, a named parameter, a short decimal)."""
        form = written_digits(node.text) if isinstance(node, YScalar) else None
        if form is None:
            return 0.0, 0
        res = data_resolution(form[0], form[1], evalf_float(factor, 17))
        return res, (form[0] if res else 0)

    def vector(
        self, v: YValue | None, item: str, what: str, factor: Any = 1
    ) -> tuple[Any, Any, Any]:
        line = getattr(v, "line", None)
        if not isinstance(v, YSeq) or len(v.items) != 3:
            got = (
                f"{len(v.items)} entries"
                if isinstance(v, YSeq)
                else (v.describe() if v is not None else "nothing")
            )
            raise self.error(item, line, f"{what} must be a list of 3 numbers [x, y, z], got {got}")
        x, y, z = (self.number(e, item, f"{what}[{i}]", factor) for i, e in enumerate(v.items))
        return (x, y, z)

    def direction(
        self, v: YValue | None, item: str, what: str
    ) -> tuple[tuple[Any, Any, Any], bool]:
        """A unit vector from a non-zero direction; returns (unit, was_normalised)."""
        vec = self.vector(v, item, what)
        line = getattr(v, "line", None)
        n2 = sum(c * c for c in vec)
        if all(c == 0 for c in vec):
            raise self.error(
                item,
                line,
                f"{what} [0, 0, 0] is a zero vector; give a non-zero direction such as [0, 0, 1]",
            )
        nf = float_root(n2)
        if not nf > NEAR_ZERO_VECTOR * max(1.0, self.scale):
            raise self.error(
                item,
                line,
                f"{what} has length {nf:.3g}, too close to zero to be a direction; "
                "give a direction of length about 1, such as [0, 0, 1]",
            )
        if n2 == 1:
            return vec, False
        root = rational_sqrt(n2)
        if root is not None:  # a rational length: the unit vector is rational (as radsimp's)
            unit = tuple(c / root for c in vec)
            return (unit[0], unit[1], unit[2]), True
        n = sympy.sqrt(n2)
        unit = tuple(sympy.radsimp(c / n) for c in vec)
        return (unit[0], unit[1], unit[2]), True

    def exact(self, x: Any) -> Any:
        """An exact factor of the reader's own (a unit's, a PiRational) in the reader's
        number type: itself with ``plain``, else its sympy value."""
        return x if self.plain or not isinstance(x, PiRational) else x._sympy_()


def float_root(n2: Any) -> float:
    """``sqrt(n2)`` as a float (n2 a squared length): for a PiRational from its float,
    else at 30 digits by sympy."""
    if isinstance(n2, PiRational):
        return math.sqrt(float(n2))
    return float(sympy.N(sympy.sqrt(n2), 30))


def closest(word: str, choices: tuple[str, ...]) -> str | None:
    import difflib

    m = difflib.get_close_matches(word, choices, n=1, cutoff=0.6)
    return m[0] if m else None


def show_vector(vec: tuple[Any, ...]) -> str:
    return "[" + ", ".join(str(c) for c in vec) + "]"


def few(names: list[str], n: int = 8) -> str:
    shown = ", ".join(names[:n])
    return shown + (", ..." if len(names) > n else "")
