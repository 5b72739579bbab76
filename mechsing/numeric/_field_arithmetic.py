"""The arithmetic of :mod:`mechsing.numeric.field`'s elimination: the number field's
own elements (sympy's domain elements), or, in an algebraic field on pure-Python or
gmpy2 rationals, its elements as integer coefficient vectors over one denominator
(:class:`IntegerArithmetic`: 5 times faster in degree 8, the same elements).
:func:`integer_arithmetic` is the one choice between them."""

from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache
from typing import Any

from mechsing.numeric.lazy import LazyModule

_domains = LazyModule("sympy.polys.domains")


class DomainArithmetic:
    """The field's own arithmetic (sympy's domain elements) in :func:`mechsing.numeric.field._eliminate`'s terms."""

    def __init__(self, K: Any) -> None:
        self.K = K
        self.one = K.one
        self.zero = K.zero
        self.is_zero = K.is_zero

    def rational(self, p: int, q: int) -> Any:
        return self.K.convert_from(_domains.QQ(p, q), _domains.QQ)

    @staticmethod
    def add(a: Any, b: Any) -> Any:
        return a + b

    @staticmethod
    def vector(x: Any) -> Any:
        return x

    @staticmethod
    def element(x: Any) -> Any:
        return x

    @staticmethod
    def mul(a: Any, b: Any) -> Any:
        return a * b

    def revert(self, a: Any) -> Any:
        return self.one / a

    @staticmethod
    def sub_mul(x: Any, f: Any, y: Any) -> Any:
        return x - f * y


#: an element of an algebraic field of degree d as integers over one positive denominator:
#: (coefficients of 1, alpha, ..., alpha^(d-1); denominator), without a common factor
Vector = tuple[tuple[int, ...], int]


class IntegerArithmetic:
    """The algebraic field K's arithmetic on :data:`Vector` elements: a product is the
    integer product of the coefficient vectors, reduced by the table of alpha^k
    (d <= k <= 2d - 2) modulo the minimal polynomial, with one gcd to cancel; sympy's
    ``ANP`` reduces a product of polynomials with rational coefficients (a gcd per
    coefficient operation).  The same elements (normal forms are unique), converted
    from and back to K's at the ends of an elimination."""

    def __init__(self, K: Any) -> None:
        self.K = K
        mod = [
            Fraction(int(_domains.QQ.numer(c)), int(_domains.QQ.denom(c))) for c in K.mod.to_list()
        ]
        mod = [c / mod[0] for c in mod]
        d = len(mod) - 1
        low = [-c for c in reversed(mod[1:])]  # alpha^d as a polynomial of degree < d
        table, power = [], list(low)
        for _ in range(d - 1):
            table.append(power)
            top = power[-1]
            power = [Fraction(0), *power[:-1]]
            power = [p + top * q for p, q in zip(power, low, strict=True)]
        self.d = d
        self.E = math.lcm(*(f.denominator for row in table for f in row)) if table else 1
        self.table = [[int(f * self.E) for f in row] for row in table]
        self.one: Vector = ((1,) + (0,) * (d - 1), 1)
        self.zero: Vector = ((0,) * d, 1)

    def rational(self, p: int, q: int) -> Vector:
        """The rational ``p / q`` (q > 0, in lowest terms)."""
        return ((p,) + (0,) * (self.d - 1), q)

    def add(self, a: Vector, b: Vector) -> Vector:
        (xs, qa), (ys, qb) = a, b
        if qa == qb:
            return self._cancel([u + v for u, v in zip(xs, ys, strict=True)], qa)
        return self._cancel([u * qb + v * qa for u, v in zip(xs, ys, strict=True)], qa * qb)

    def vector(self, x: Any) -> Vector:
        coeffs = x.to_list()[::-1]
        nums = [int(_domains.QQ.numer(c)) for c in coeffs]
        dens = [int(_domains.QQ.denom(c)) for c in coeffs]
        den = math.lcm(*dens) if dens else 1
        out = [n * (den // q) for n, q in zip(nums, dens, strict=True)]
        return tuple(out + [0] * (self.d - len(out))), den

    def element(self, v: Vector) -> Any:
        QQ = _domains.QQ
        nums, den = v
        return self.K.new([QQ(int(c), int(den)) for c in reversed(nums)])

    @staticmethod
    def is_zero(v: Vector) -> bool:
        return not any(v[0])

    def _product(self, a: Vector, b: Vector) -> tuple[list[int], int]:
        """``a b`` with its common factor not cancelled."""
        d, E = self.d, self.E
        conv = [0] * (2 * d - 1)
        B = b[0]
        for i, x in enumerate(a[0]):
            if x:
                for j, y in enumerate(B):
                    if y:
                        conv[i + j] += x * y
        out = conv[:d] if E == 1 else [c * E for c in conv[:d]]
        for k in range(d, 2 * d - 1):
            c = conv[k]
            if c:
                for i, t in enumerate(self.table[k - d]):
                    out[i] += c * t
        return out, a[1] * b[1] * E

    @staticmethod
    def _cancel(nums: list[int], den: int) -> Vector:
        g = math.gcd(*nums, den)
        if g == 1:
            return tuple(nums), den
        return tuple(c // g for c in nums), den // g

    def mul(self, a: Vector, b: Vector) -> Vector:
        return self._cancel(*self._product(a, b))

    def revert(self, a: Vector) -> Vector:
        return self.vector(self.K.one / self.element(a))

    def sub_mul(self, x: Vector, f: Vector, y: Vector) -> Vector:
        """``x - f y``."""
        p, q = self._product(f, y)
        xs, qx = x
        return self._cancel([u * q - v * qx for u, v in zip(xs, p, strict=True)], qx * q)


def arithmetic(K: Any) -> DomainArithmetic | IntegerArithmetic:
    """:func:`integer_arithmetic` when it serves K, else the field's own elements."""
    return integer_arithmetic(K) or DomainArithmetic(K)


def integer_arithmetic(K: Any) -> IntegerArithmetic | None:
    """The elimination's arithmetic for K: integer vectors in an algebraic field on
    sympy's pure-Python or gmpy2 rationals, None (the field's own elements) in QQ or
    with python-flint's (FLINT's polynomials are faster than the vectors)."""
    if not K.is_AlgebraicField or _ground_types() == "flint":
        return None
    return _integer_field(K)


@lru_cache(maxsize=64)
def _integer_field(K: Any) -> IntegerArithmetic:
    return IntegerArithmetic(K)


def _ground_types() -> str:
    from sympy.external.gmpy import GROUND_TYPES

    return str(GROUND_TYPES)
