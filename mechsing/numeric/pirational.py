"""The model's own exact number for a file's plain numbers: a rational times a power of pi.

A mechanism file's numbers are exact in every precision mode (``0.1`` is 1/10, ``30``
degrees is pi/6).  Most files write nothing else: decimals, degrees, ``pi/6``.  Such a
number is :class:`PiRational` ``q * pi**k`` (``q`` a :class:`fractions.Fraction`, ``k`` an
integer), held without sympy: its float is correctly rounded (from pi to 380 bits), its
sums, products and integer powers stay PiRationals where they can (a sum of two powers
of pi, a root, a function's value cannot: those are computed by sympy, imported then); with
a float they give the float of ``float(x)`` and the float (float arithmetic).
An exact or mp computation asks for its sympy value (``sympy.sympify(x)``, which calls
:meth:`PiRational._sympy_`: the very value the reader built before, ``Rational(1, 10)``,
``pi/6``), so those modes see what they always saw; a float analysis of such a file never
imports sympy.  Attributes of sympy's numbers that PiRational does not have itself
(``free_symbols``, ``evalf``, ``is_algebraic`` ...) are answered by its sympy value.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

from mechsing.numeric.lazy import sympy

__all__ = ["PI", "PiRational", "as_pirational", "evalf_float", "rational_sqrt"]

#: pi * 2**380, rounded down: pi to 380 bits, enough that every float of q * pi**k is
#: decided (the float of the value's lower and upper bound agree) for any sensible q, k
_PI_BITS = 380
_PI_FLOOR = int(
    "3243f6a8885a308d313198a2e03707344a4093822299f31d0082efa98ec4e6c89452821e638d01377be5466cf34e90c6",
    16,
)


#: half the spacing of floats near 1 (a correctly rounded float's relative error)
_UNIT_ROUNDOFF = 2.0**-53


def _pi_power_bounds(k: int) -> tuple[Fraction, Fraction]:
    lo = Fraction(_PI_FLOOR, 1 << _PI_BITS) ** abs(k)
    hi = Fraction(_PI_FLOOR + 1, 1 << _PI_BITS) ** abs(k)
    return (lo, hi) if k > 0 else (1 / hi, 1 / lo)


class PiRational:
    """``q * pi**k``, exact, immutable: ``ratio`` q (a Fraction) and ``pi_power`` k (an int,
    0 when q is 0).  Equal to the sympy number of the same value; its hash is not sympy's
    (do not mix the two kinds as keys of one dict)."""

    __slots__ = ("ratio", "pi_power", "_float", "_sympy")

    ratio: Fraction
    pi_power: int

    def __init__(self, q: Fraction | int, k: int = 0) -> None:
        q = Fraction(q)
        object.__setattr__(self, "ratio", q)
        object.__setattr__(self, "pi_power", int(k) if q else 0)
        object.__setattr__(self, "_float", None)
        object.__setattr__(self, "_sympy", None)

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("a PiRational is immutable")

    def __reduce__(self) -> tuple[Any, ...]:
        return (PiRational, (self.ratio, self.pi_power))

    # -- conversions -----------------------------------------------------------

    def _sympy_(self) -> Any:
        """The sympy value (``Rational(p, q) * pi**k``), built once."""
        if self._sympy is None:
            value = sympy.Rational(self.ratio.numerator, self.ratio.denominator)
            if self.pi_power:
                value = value * sympy.pi**self.pi_power
            object.__setattr__(self, "_sympy", value)
        return self._sympy

    def __float__(self) -> float:
        """The float nearest the exact value (ties to even)."""
        if self._float is None:
            object.__setattr__(self, "_float", _nearest_float(self.ratio, self.pi_power))
        return self._float

    def __int__(self) -> int:
        if self.pi_power:
            return int(self._sympy_())
        return int(self.ratio)

    def __bool__(self) -> bool:
        return self.ratio != 0

    @property
    def is_Rational(self) -> bool:  # noqa: N802 - sympy's name
        return self.pi_power == 0

    @property
    def is_zero(self) -> bool:
        return self.ratio == 0

    def __getattr__(self, name: str) -> Any:
        # sympy's other attributes (free_symbols, evalf, is_algebraic ...) from the sympy
        # value; private and special names are not sympy's API (numpy, copy and pickle
        # probe them)
        if name.startswith("_"):
            raise AttributeError(name)
        return getattr(self._sympy_(), name)

    # -- text --------------------------------------------------------------------

    def __str__(self) -> str:
        return str(self.ratio) if self.pi_power == 0 else str(self._sympy_())

    def __repr__(self) -> str:
        return str(self)

    # -- arithmetic --------------------------------------------------------------

    def __hash__(self) -> int:
        return hash(self.ratio) if self.pi_power == 0 else hash((self.ratio, self.pi_power))

    def __eq__(self, other: object) -> Any:
        o = as_pirational(other)
        if o is not None:
            return self.ratio == o.ratio and self.pi_power == o.pi_power
        if isinstance(other, float):
            return self.pi_power == 0 and self.ratio == other  # pi**k times a rational is no float
        return self._sympy_() == other

    def __ne__(self, other: object) -> Any:
        return not self.__eq__(other)

    def _compare(self, other: Any) -> int | None:
        """The sign of ``self - other`` when it is decided without sympy (the same power
        of pi, or one of them zero), else None."""
        if isinstance(other, float) and math.isfinite(other):
            if self.pi_power == 0:
                d = self.ratio - Fraction(other)
            elif float(self) != other:  # the float nearest self is on self's side of other
                d = Fraction(float(self)) - Fraction(other)
            else:
                return None
            return (d > 0) - (d < 0)
        o = as_pirational(other)
        if o is None:
            return None
        if self.pi_power == o.pi_power:
            d = self.ratio - o.ratio
        elif not o.ratio:
            d = self.ratio
        elif not self.ratio:
            d = -o.ratio
        else:
            # two powers of pi: their correctly rounded floats tell the order unless
            # within a few units of rounding of each other (then sympy decides)
            x, y = float(self), float(o)
            if abs(x - y) <= 4 * _UNIT_ROUNDOFF * max(abs(x), abs(y)):
                return None
            return (x > y) - (x < y)
        return (d > 0) - (d < 0)

    def __lt__(self, other: Any) -> Any:
        c = self._compare(other)
        return c < 0 if c is not None else self._sympy_() < other

    def __le__(self, other: Any) -> Any:
        c = self._compare(other)
        return c <= 0 if c is not None else self._sympy_() <= other

    def __gt__(self, other: Any) -> Any:
        c = self._compare(other)
        return c > 0 if c is not None else self._sympy_() > other

    def __ge__(self, other: Any) -> Any:
        c = self._compare(other)
        return c >= 0 if c is not None else self._sympy_() >= other

    def __neg__(self) -> PiRational:
        return PiRational(-self.ratio, self.pi_power)

    def __pos__(self) -> PiRational:
        return self

    def __abs__(self) -> PiRational:
        return PiRational(abs(self.ratio), self.pi_power)

    def __add__(self, other: Any) -> Any:
        o = as_pirational(other)
        if isinstance(other, float):
            return float(self) + other
        if o is None:
            return self._sympy_() + other
        if not o.ratio:
            return self
        if not self.ratio:
            return o
        if self.pi_power == o.pi_power:
            return PiRational(self.ratio + o.ratio, self.pi_power)
        return self._sympy_() + o._sympy_()

    def __radd__(self, other: Any) -> Any:
        o = as_pirational(other)
        if isinstance(other, float):
            return other + float(self)
        if o is None:
            return other + self._sympy_()
        return o + self

    def __sub__(self, other: Any) -> Any:
        o = as_pirational(other)
        if isinstance(other, float):
            return float(self) - other
        if o is None:
            return self._sympy_() - other
        return self + (-o)

    def __rsub__(self, other: Any) -> Any:
        o = as_pirational(other)
        if isinstance(other, float):
            return other - float(self)
        if o is None:
            return other - self._sympy_()
        return o + (-self)

    def __mul__(self, other: Any) -> Any:
        o = as_pirational(other)
        if isinstance(other, float):
            return float(self) * other
        if o is None:
            return self._sympy_() * other
        return PiRational(self.ratio * o.ratio, self.pi_power + o.pi_power)

    def __rmul__(self, other: Any) -> Any:
        o = as_pirational(other)
        if isinstance(other, float):
            return other * float(self)
        if o is None:
            return other * self._sympy_()
        return o * self

    def __truediv__(self, other: Any) -> Any:
        o = as_pirational(other)
        if isinstance(other, float):
            return float(self) / other
        if o is None:
            return self._sympy_() / other
        if not o.ratio:
            raise ZeroDivisionError("division of an exact number by zero")
        return PiRational(self.ratio / o.ratio, self.pi_power - o.pi_power)

    def __rtruediv__(self, other: Any) -> Any:
        o = as_pirational(other)
        if isinstance(other, float):
            return other / float(self)
        if o is None:
            return other / self._sympy_()
        return o / self

    def __pow__(self, exponent: Any) -> Any:
        e = as_pirational(exponent)
        if e is not None and e.pi_power == 0 and e.ratio.denominator == 1:
            n = e.ratio.numerator
            if n < 0 and not self.ratio:
                raise ZeroDivisionError("zero to a negative power")
            return PiRational(self.ratio**n, self.pi_power * n)
        return self._sympy_() ** exponent

    def __rpow__(self, base: Any) -> Any:
        b = as_pirational(base)
        if b is not None:
            return b**self
        return base ** self._sympy_()


#: pi as a PiRational
PI = PiRational(1, 1)


def rational_sqrt(x: Any) -> PiRational | None:
    """The rational square root of a PiRational that is a rational square (``9/4``: 3/2),
    else None."""
    if not isinstance(x, PiRational) or x.pi_power != 0 or x.ratio < 0:
        return None
    p, q = x.ratio.numerator, x.ratio.denominator
    rp, rq = math.isqrt(p), math.isqrt(q)
    if rp * rp != p or rq * rq != q:
        return None
    return PiRational(Fraction(rp, rq))


def as_pirational(x: Any) -> PiRational | None:
    """``x`` as a PiRational when it is one, an int or a Fraction (None otherwise: a
    float, a sympy or an mpmath value)."""
    if isinstance(x, PiRational):
        return x
    if isinstance(x, int | Fraction) and not isinstance(x, bool):
        return PiRational(x)
    return None


def _nearest_float(q: Fraction, k: int) -> float:
    if k == 0 or not q:
        return float(q)
    lo, hi = _pi_power_bounds(k)
    a, b = float(q * lo), float(q * hi)
    if a == b:
        return a
    # q * pi**k within 2**-370 of a tie between two floats: decided at more digits
    import mpmath

    with mpmath.workprec(4 * _PI_BITS + q.numerator.bit_length() + q.denominator.bit_length()):
        return float(mpmath.mpf(q.numerator) / q.denominator * mpmath.pi**k)


def _binary_digits(digits: int) -> int:
    """The bits of sympy's working precision for ``digits`` decimal digits
    (``mpmath.libmp.dps_to_prec``)."""
    return max(1, int(round((int(digits) + 1) * 3.3219280948873626)))


def _round_bits(x: Fraction, bits: int) -> Fraction:
    """``x`` rounded to ``bits`` significant bits, to nearest, ties to even."""
    if not x:
        return x
    a = abs(x)
    shift = bits - (a.numerator.bit_length() - a.denominator.bit_length())
    while a * Fraction(2) ** shift >= 1 << bits:
        shift -= 1
    while a * Fraction(2) ** shift < 1 << (bits - 1):
        shift += 1
    m = round(a * Fraction(2) ** shift)
    r = Fraction(m) / Fraction(2) ** shift
    return r if x > 0 else -r


def evalf_float(x: Any, digits: int = 20) -> float:
    """The float of ``sympy.N(x, digits)`` (the value rounded to ``digits`` digits' bits,
    then to a float, as mpmath rounds: to nearest, ties to even), for a PiRational
    computed without sympy; any other value through sympy.  The float path's conversions
    of the file's numbers (:func:`mechsing.numeric.backend.to_float` at 20 digits) give
    with it the very floats they gave when the numbers were sympy's."""
    if isinstance(x, int | Fraction) and not isinstance(x, bool):
        x = PiRational(x)
    if not isinstance(x, PiRational):
        return float(sympy.N(x, digits))
    bits = _binary_digits(digits)
    if x.pi_power == 0:
        return float(_round_bits(x.ratio, bits))
    lo, hi = _pi_power_bounds(x.pi_power)
    a, b = _round_bits(x.ratio * lo, bits), _round_bits(x.ratio * hi, bits)
    if a == b:
        return float(a)
    return float(sympy.N(x._sympy_(), digits))  # within 2**-370 of a tie: as sympy rounds
