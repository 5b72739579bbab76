"""Exact arithmetic in the algebraic number field K the data of a configuration live in.

Exact mode's numbers are sympy expressions; sympy's general arithmetic and
simplification on them is slow (a Bennett configuration's closure residual is a sum
of products of nested radicals and inverse trigonometric functions).  When every
datum is an algebraic number -- rationals, radicals, and the cosines and sines of the
joint angles (``2*atan(1/3)``, ``pi/6``, ``acos(13/14)``) -- they all lie in one number
field ``K = Q(alpha)`` (``QQ`` in the common case of rational data and angles
``2*atan(rational)``), whose elements sympy's polynomial domains add, multiply and
divide exactly and in normal form (a rational, or a polynomial in the primitive element
alpha reduced by its minimal polynomial).  Zero in K is zero: no simplification, no
proof by expansion.

This module owns:

* :func:`cos_sin`: the cosine and sine of an angle as radicals, or None;
* :func:`number_field`: the field K of a list of sympy numbers and their elements in K
  (None when they do not fit one: a transcendental number, a sine sympy cannot
  write as radicals);
* :func:`domain_matrix`, :func:`field_echelon`, :func:`field_null_space`,
  :func:`field_row_space`, :func:`field_solve`, :func:`field_product`: exact linear algebra on object arrays of
  sympy numbers through :class:`sympy.polys.matrices.DomainMatrix` over their field
  (None when the entries have no field: the caller keeps its sympy path); the
  elimination, the square solve and the evaluation into the field compute in
  :func:`mechsing.numeric._field_arithmetic.arithmetic`'s numbers (integer coefficient
  vectors in an algebraic field without python-flint).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np

from mechsing.numeric._field_arithmetic import arithmetic, integer_arithmetic
from mechsing.numeric.lazy import LazyModule, mpmath, sympy

if TYPE_CHECKING:
    from sympy.polys.matrices import DomainMatrix

#: sympy's polynomial domains, imported when exact mode first builds a field
_constructor = LazyModule("sympy.polys.constructor")
_domains = LazyModule("sympy.polys.domains")
_matrices = LazyModule("sympy.polys.matrices")

#: the largest degree (bounded by the product of the radicals' indices) of a number field
#: exact mode builds for a configuration's data (the bundled 6-UPS and 3-UPU platforms: 32,
#: five square roots); beyond it, the primitive element and the factoring over it can take
#: longer than the general sympy path, which then serves (float mode's loop identification
#: at the drawn pose of a file with many different radicals stalled there)
EXACT_FIELD_MAX_DEGREE = 32


__all__ = [
    "FieldEchelon",
    "cos_sin",
    "domain_matrix",
    "echelon_form",
    "field_echelon",
    "field_float",
    "field_floats",
    "field_normal_form",
    "field_null_space",
    "field_product",
    "field_row_space",
    "field_solve",
    "from_field",
    "number_field",
]


#: sympy's trigonometric functions and their inverses (a value holding one fits no field)
def _trig() -> tuple[Any, ...]:
    trig = sympy.functions.elementary.trigonometric
    return (trig.TrigonometricFunction, trig.InverseTrigonometricFunction)


def _algebraic_form(x: Any) -> bool:
    """Is the sympy number ``x`` written with rationals and radicals only (no pi, no
    trigonometric or other function, no symbol)?"""
    x = sympy.sympify(x)
    if x.is_Rational:
        return True
    if x.free_symbols or x.has(sympy.Function) or x.has(sympy.pi) or x.has(sympy.E):
        return False
    if x.has(sympy.I) or x.has(sympy.Float):
        return False
    return all(
        a.is_Rational or (a.is_Pow and a.exp.is_Rational) or a.is_Add or a.is_Mul
        for a in sympy.preorder_traversal(x)
    )


@lru_cache(maxsize=4096)
def cos_sin(theta: Any) -> tuple[Any, Any] | None:
    """The cosine and sine of the angle ``theta`` (a sympy number) as expressions in
    rationals and radicals (``2*atan(1/3)`` -> (4/5, 3/5), ``pi/6`` -> (sqrt(3)/2, 1/2),
    ``acos(13/14)`` -> (13/14, 3*sqrt(3)/14)), or None when sympy cannot write them so
    (``1``, ``pi/7``)."""
    theta = sympy.sympify(theta)
    c = sympy.expand_trig(sympy.cos(theta))
    s = sympy.expand_trig(sympy.sin(theta))
    if c.has(*_trig()) or s.has(*_trig()) or not (_algebraic_form(c) and _algebraic_form(s)):
        return None
    return c, s


def number_field(values: list[Any]) -> tuple[Any, list[Any]] | None:
    """The number field K of the sympy numbers ``values`` and their elements of K.

    K is ``QQ`` when every value is rational, else ``QQ<alpha>`` (sympy's
    :class:`~sympy.polys.domains.AlgebraicField`, alpha a primitive element of the
    field the values generate).  None when the values do not fit a number field
    (a value that is not written in rationals and radicals)."""
    vals = [sympy.sympify(v) for v in values]
    if all(v.is_Rational for v in vals):
        return _domains.QQ, [_domains.QQ.from_sympy(v) for v in vals]
    # each distinct value once (a matrix repeats its entries: 5 times over on a platform)
    distinct = list(dict.fromkeys(vals))
    if not all(_algebraic_form(v) for v in distinct):
        return None
    gens: set[Any] = set()
    for v in distinct:
        _radicals(v, gens)
    if _degree_bound(gens) > EXACT_FIELD_MAX_DEGREE:
        return None
    fit = _field_of(tuple(sorted(gens, key=sympy.default_sort_key)))
    if fit is None:
        return None
    K, images = fit
    ar = arithmetic(K)
    numbers = {g: ar.vector(e) for g, e in images.items()}
    try:
        elements = {v: ar.element(_evaluate(ar, numbers, v)) for v in distinct}
    except (KeyError, ZeroDivisionError, NotImplementedError):
        return None
    return K, [elements[v] for v in vals]


def _radicals(x: Any, out: set[Any]) -> None:
    """The radicals (powers with a non-integer exponent) ``x`` is written with, outermost."""
    if x.is_Rational:
        return
    if x.is_Pow and not x.exp.is_Integer:
        out.add(x)
        return
    for a in x.args:
        _radicals(a, out)


def _degree_bound(gens: set[Any]) -> int:
    """A bound on the degree of QQ(gens): the product of the radicals' indices, the
    radicals inside them included (``sqrt(1 + sqrt(2))``: 4), except that the square
    roots of rationals count by the degree they generate together, ``2^k`` with k the
    rank over GF(2) of their radicands' square classes (``sqrt 3, sqrt 11, sqrt 33``: 4,
    not 8)."""
    bound = 1
    classes: list[int] = []
    for g in gens:
        if not g.exp.is_Rational:
            return EXACT_FIELD_MAX_DEGREE + 1
        if g.exp.q == 2 and g.base.is_Rational:
            cls = _square_class(g.base)
            if cls is not None:
                classes.append(cls)
                continue
        inner: set[Any] = set()
        _radicals(g.base, inner)
        bound *= int(g.exp.q) * _degree_bound(inner)
    return bound * 2 ** _gf2_rank(classes)


#: radicands (numerator times denominator) beyond this are not factored: they count as
#: a square class of their own (the product bound)
_FACTOR_LIMIT = 10**12


def _square_class(r: Any) -> int | None:
    """The square class of the positive rational ``r`` as a bit mask (bit i: the prime
    ``_PRIMES[i]`` divides its square-free part an odd number of times), or None (negative,
    or too large to factor: counted by the product bound)."""
    n = int(r.p) * int(r.q)
    if n <= 0 or n > _FACTOR_LIMIT:
        return None
    mask = 0
    for prime, e in sympy.factorint(n).items():
        if e % 2:
            mask |= 1 << _prime_index(prime)
    return mask


_PRIMES: dict[int, int] = {}


def _prime_index(p: int) -> int:
    return _PRIMES.setdefault(p, len(_PRIMES))


def _gf2_rank(masks: list[int]) -> int:
    """The rank over GF(2) of bit vectors (Gaussian elimination on the highest bit)."""
    lead: dict[int, int] = {}
    for m in masks:
        while m:
            top = m.bit_length() - 1
            if top not in lead:
                lead[top] = m
                break
            m ^= lead[top]
    return len(lead)


@lru_cache(maxsize=256)
def _field_of(gens: tuple[Any, ...]) -> tuple[Any, dict[Any, Any]] | None:
    """The field QQ(gens) (a primitive element: computed once per set of radicals) and
    each radical's element in it.  The square roots of integers enter through a basis
    of their square classes (:func:`_quadratic_basis`): the others are a rational times
    a product of basis roots (sqrt 6 = sqrt 2 sqrt 3), so the primitive element is
    built from as few radicals as the degree allows (sympy's construction slows down
    steeply with their number)."""
    dependent = _quadratic_basis(gens)
    build = [g for g in gens if g not in dependent]
    try:
        K, elements = _constructor.construct_domain(build, field=True, extension=True)
    except (sympy.polys.polyerrors.PolynomialError, NotImplementedError, ValueError):
        return None
    if K.is_ZZ or K.is_QQ:
        K = _domains.QQ
        elements = [_domains.QQ.from_sympy(g) for g in build]
    elif not K.is_AlgebraicField:
        return None
    images = dict(zip(build, elements, strict=True))
    for g, (factor, roots) in dependent.items():
        el = K.convert_from(_domains.QQ.from_sympy(factor), _domains.QQ)
        for b in roots:
            el = el * images[b]
        images[g] = el
    return K, images


def _quadratic_basis(gens: tuple[Any, ...]) -> dict[Any, tuple[Any, list[Any]]]:
    """The square roots of positive integers among ``gens`` that depend on the others
    before them (their square classes over GF(2)), each as ``(r, [b1, b2, ...])``:
    ``g = r b1 b2 ...`` with r rational and b_i independent roots among ``gens``."""
    lead: dict[int, tuple[int, frozenset[Any]]] = {}
    dependent: dict[Any, tuple[Any, list[Any]]] = {}
    for g in gens:
        if not (g.exp == sympy.S.Half and g.base.is_Integer and g.base > 0):
            continue
        mask = _square_class(g.base)
        if mask is None:
            continue
        combo: frozenset[Any] = frozenset()
        while mask:
            top = mask.bit_length() - 1
            if top not in lead:
                break
            m, c = lead[top]
            mask ^= m
            combo = combo ^ c
        if mask:
            lead[mask.bit_length() - 1] = (mask, combo ^ {g})
            continue
        roots = sorted(combo, key=sympy.default_sort_key)
        prod = sympy.Integer(1)
        for b in roots:
            prod = prod * b.base
        # g / prod(roots) = sqrt(n / prod b_i), a rational (the same square class)
        dependent[g] = (sympy.sqrt(sympy.Rational(g.base, prod)), roots)
    return dependent


def _evaluate(ar: Any, images: dict[Any, Any], x: Any) -> Any:
    """The element of K that the expression ``x`` (rationals, the radicals of
    ``images``, +, *, integer powers) denotes, in the numbers of ``ar`` (:func:`arithmetic`
    of K): exact arithmetic in K, no minimal polynomial per value."""
    if x.is_Rational:
        return ar.rational(int(x.p), int(x.q))
    if x.is_Add:
        total = ar.zero
        for a in x.args:
            total = ar.add(total, _evaluate(ar, images, a))
        return total
    if x.is_Mul:
        prod = ar.one
        for a in x.args:
            prod = ar.mul(prod, _evaluate(ar, images, a))
        return prod
    if x.is_Pow and x.exp.is_Integer:
        base = _evaluate(ar, images, x.base)
        e = int(x.exp)
        if e < 0:
            base = ar.revert(base)
            e = -e
        out = ar.one
        for _ in range(e):
            out = ar.mul(out, base)
        return out
    return images[x]


def field_floats(A: Any) -> np.ndarray | None:
    """The array of sympy numbers ``A`` as floats, evaluated in the number field of its
    entries (:func:`field_float`: no adaptive evaluation per entry), or None (no field)."""
    arr = np.asarray(A, dtype=object)
    if arr.size == 0:
        return np.zeros(arr.shape)
    fit = number_field(list(arr.flat))
    if fit is None:
        return None
    K, els = fit
    return np.array([field_float(K, x) for x in els], dtype=float).reshape(arr.shape)


def field_normal_form(x: Any) -> Any:
    """A sympy number or array written back from its elements of the number field its
    entries lie in (rationals and polynomials in the primitive element, expanded: zero is
    zero, denominators rational), or None when they have no field."""
    arr = np.asarray(x, dtype=object)
    fit = number_field(list(arr.flat)) if arr.size else None
    if fit is None:
        return None
    K, els = fit
    out = np.array([K.to_sympy(e) for e in els], dtype=object).reshape(arr.shape)
    return out[()] if out.shape == () else out


def from_field(K: Any, x: Any) -> Any:
    """A sympy number from an element of K (or an array of them, elementwise)."""
    if isinstance(x, np.ndarray):
        out = np.empty(x.shape, dtype=object)
        for idx, v in np.ndenumerate(x):
            out[idx] = K.to_sympy(v)
        return out
    return K.to_sympy(x)


def domain_matrix(A: Any) -> DomainMatrix | None:
    """The matrix of sympy numbers ``A`` (m, n) as a DomainMatrix over the number field
    of its entries (QQ or an algebraic field), or None (entries without a field)."""
    arr = np.asarray(A, dtype=object)
    m, n = arr.shape
    flat = [sympy.sympify(x) for x in arr.flat]
    if not flat:
        return _matrices.DomainMatrix([[] for _ in range(m)], (m, n), _domains.QQ)
    fit = number_field(flat)
    if fit is None:
        return None
    K, elements = fit
    rows = [elements[i * n : (i + 1) * n] for i in range(m)]
    return _matrices.DomainMatrix(rows, (m, n), K)


@dataclass
class FieldEchelon:
    """The echelon form of a matrix over its number field K (see :func:`field_echelon`):
    ``D`` the matrix over K, ``pivots`` its pivot columns and ``pivot_elements`` the
    pivot values (elements of K); the null basis and the reduced row echelon form are
    computed when asked for."""

    D: DomainMatrix
    pivots: list[int]
    pivot_elements: list[Any]
    #: the rows of the elimination (with division) that hold the pivots, in order, in the
    #: numbers of ``arithmetic`` (:func:`mechsing.numeric._field_arithmetic.arithmetic`)
    rows: list[list[Any]] | None = None
    arithmetic: Any = None

    @property
    def K(self) -> Any:
        return self.D.domain

    def rref_rows(self) -> list[list[Any]]:
        """The non-zero rows of the reduced row echelon form (unique: sympy's ``rref``),
        elements of K: the elimination's rows, each divided by its pivot and cleared above
        it (back substitution)."""
        if self.rows is None:
            R, piv = self.D.rref()
            return [list(r) for r in R.to_list()[: len(piv)]]
        ar = self.arithmetic
        out = [list(r) for r in self.rows]
        for i in range(len(out) - 1, -1, -1):
            c = self.pivots[i]
            p = out[i][c]
            if p != ar.one:
                # one inversion per row (a division in K inverts its divisor each time)
                inv = ar.revert(p)
                out[i] = [x if ar.is_zero(x) else ar.mul(x, inv) for x in out[i]]
            row = out[i]
            for k in range(i):
                a = out[k][c]
                if not ar.is_zero(a):
                    out[k] = [
                        x if ar.is_zero(y) else ar.sub_mul(x, a, y)
                        for x, y in zip(out[k], row, strict=True)
                    ]
        return [[ar.element(x) for x in r] for r in out]

    def pivot_values(self) -> list[Any]:
        """The pivot values as sympy numbers."""
        return [self.K.to_sympy(p) for p in self.pivot_elements]

    def pivot_magnitudes(self) -> list[float]:
        """``|pivot value|`` as floats (at least 25 correct digits before rounding)."""
        return [abs(field_float(self.K, p)) for p in self.pivot_elements]

    def null_basis(self) -> list[list[Any]]:
        """The reduced null-space basis (:meth:`sympy.Matrix.nullspace`'s: one vector per
        free column, 1 there), elements of K."""
        K = self.K
        n = self.D.shape[1]
        rl = self.rref_rows()
        rpiv = self.pivots
        basis = []
        for free in (j for j in range(n) if j not in rpiv):
            vec = [K.zero] * n
            vec[free] = K.one
            for i, pc in enumerate(rpiv):
                vec[pc] = vec[pc] - rl[i][free]
            basis.append(vec)
        return basis


def echelon_form(A: Any) -> FieldEchelon | None:
    """The echelon form of ``A`` (sympy numbers, or a DomainMatrix over its field) in the
    number field of its entries (None when they have none); see :func:`field_echelon`."""
    D = A if isinstance(A, _matrices.DomainMatrix) else domain_matrix(A)
    return None if D is None else _echelon(D)


def _echelon(D: DomainMatrix) -> FieldEchelon:
    K = D.domain
    m, n = D.shape
    ar = arithmetic(K)
    rows = [[ar.vector(x) for x in r] for r in D.to_list()]
    pivots, values, kept = _eliminate(ar, rows, m, n)
    return FieldEchelon(D, pivots, [ar.element(v) for v in values], kept, ar)


def _eliminate(
    K: Any, rows: list[list[Any]], m: int, n: int
) -> tuple[list[int], list[Any], list[list[Any]]]:
    """The elimination of :func:`field_echelon` on ``rows`` (changed in place) in the
    arithmetic ``K`` (:class:`DomainArithmetic` or :class:`IntegerArithmetic`): pivot columns,
    pivot values and the rows holding the pivots."""
    scale = [K.one] * m
    pivots: list[int] = []
    values: list[Any] = []
    pr = 0
    for col in range(n):
        if pr >= m:
            break
        off = next((i for i in range(pr, m) if not K.is_zero(rows[i][col])), None)
        if off is None:
            continue
        rows[pr], rows[off] = rows[off], rows[pr]
        scale[pr], scale[off] = scale[off], scale[pr]
        prow = rows[pr]
        t = prow[col]
        pv = K.mul(scale[pr], t)
        inv = None  # 1 / t, once per pivot (the same element as each a / t, in K)
        # the pivot row's non-zero columns: x - f * 0 is x, so only these change
        live = [j for j in range(col, n) if not K.is_zero(prow[j])]
        for r in range(pr + 1, m):
            row = rows[r]
            a = row[col]
            if K.is_zero(a):
                continue
            if inv is None:
                inv = K.revert(t)
            f = K.mul(a, inv)
            for j in live:
                row[j] = K.sub_mul(row[j], f, prow[j])
            scale[r] = K.mul(scale[r], pv)
        pivots.append(col)
        values.append(pv)
        pr += 1
    return pivots, values, rows[:pr]


def field_echelon(A: Any) -> tuple[list[int], list[Any], list[list[Any]]] | None:
    """Pivot columns, pivot values and the reduced null-space basis of ``A`` (sympy
    numbers), computed in the number field of its entries; None when they have none.

    The echelon form is :meth:`sympy.Matrix.echelon_form`'s: fraction-free elimination
    below each pivot (``row_i <- p row_i - a_i pivot_row``, p the pivot value), the pivot
    the first non-zero entry of its column (zero is decided in K).  Its rows are
    computed as ``s_i t_i``: ``t_i`` the rows of ordinary elimination (with division,
    numbers of bounded size) and ``s_i`` the product of the pivot values row i was
    multiplied by, so a pivot value is ``s_p t_p[c]`` -- the fraction-free numbers
    without their growth.  The null space is :meth:`sympy.Matrix.nullspace`'s (one
    vector per free column, 1 there, from the reduced row echelon form)."""
    E = echelon_form(A)
    if E is None:
        return None
    K = E.K
    return E.pivots, E.pivot_values(), [[K.to_sympy(x) for x in v] for v in E.null_basis()]


#: digits at which an element of an algebraic field is evaluated as a polynomial in its
#: primitive element, and the cancellation (value over the sum of the terms' sizes) below
#: which sympy's adaptive evaluation serves instead
_EVAL_DIGITS = 60
_EVAL_CANCELLATION = 1e-30


@lru_cache(maxsize=256)
def _primitive_value(K: Any) -> Any:
    """The primitive element of the algebraic field K at :data:`_EVAL_DIGITS` digits."""
    return mpmath.mpf(sympy.N(K.ext.as_expr(), _EVAL_DIGITS + 10))


def field_float(K: Any, a: Any) -> float:
    """The element ``a`` of K (QQ or an algebraic field) as a float: a rational's correct
    rounding; an algebraic element's polynomial in the primitive element evaluated at
    60 digits (sympy's adaptive evaluation when its terms cancel to 30 digits)."""
    if K.is_QQ:
        return int(_domains.QQ.numer(a)) / int(_domains.QQ.denom(a))
    coeffs = a.to_list()
    if not coeffs:
        return 0.0
    with mpmath.workdps(_EVAL_DIGITS):
        x = _primitive_value(K)
        val = mpmath.mpf(0)
        size = mpmath.mpf(0)
        ax = abs(x)
        for c in coeffs:
            cq = mpmath.mpf(int(_domains.QQ.numer(c))) / int(_domains.QQ.denom(c))
            val = val * x + cq
            size = size * ax + abs(cq)
        if abs(val) <= _EVAL_CANCELLATION * size:
            return float(sympy.N(K.to_sympy(a), 30))
        return float(val)


def field_null_space(A: Any) -> np.ndarray | None:
    """Rows spanning the right null space of ``A`` (the reduced basis of
    :meth:`sympy.Matrix.nullspace`: one per free column, 1 there), or None."""
    arr = np.asarray(A, dtype=object)
    D = domain_matrix(arr)
    if D is None:
        return None
    K = D.domain
    basis = [[K.to_sympy(x) for x in v] for v in _echelon(D).null_basis()]
    return np.array(basis, dtype=object).reshape(len(basis), arr.shape[1])


def field_row_space(A: Any) -> np.ndarray | None:
    """The non-zero rows of the reduced row echelon form of ``A``, or None."""
    D = domain_matrix(A)
    if D is None:
        return None
    n = D.shape[1]
    R, pivots = D.rref()
    rows = R.to_list()[: len(pivots)]
    K = R.domain
    out = [[K.to_sympy(x) for x in row] for row in rows]
    return np.array(out, dtype=object).reshape(len(out), n)


def field_product(A: Any, B: Any) -> np.ndarray | None:
    """The product ``A @ B`` of two matrices of sympy numbers, computed in the number
    field of their entries (sums of products reduced in K, no simplification), or None
    when they have none."""
    a = np.asarray(A, dtype=object)
    b = np.asarray(B, dtype=object)
    (m, k), (k2, n) = a.shape, b.shape
    if k != k2:
        raise ValueError(f"field_product: shapes {a.shape} and {b.shape} do not match")
    if 0 in (m, k, n):
        return np.array([[sympy.S.Zero] * n for _ in range(m)], dtype=object).reshape(m, n)
    fit = number_field([*a.flat, *b.flat])
    if fit is None:
        return None
    K, els = fit
    at = m * k
    rows = _matmul(
        K, [els[i * k : (i + 1) * k] for i in range(m)], [els[at + j :: n] for j in range(n)]
    )
    out = np.array([[K.to_sympy(x) for x in row] for row in rows], dtype=object)
    return out.reshape(m, n)


def _matmul(K: Any, rows: list[list[Any]], cols: list[list[Any]]) -> list[list[Any]]:
    """The product of a matrix over K given by its rows and one given by its columns
    (elements of K): each entry the sum of the products of its non-zero factors.  In an
    algebraic field the products are polynomials in the primitive element summed before
    one reduction modulo the minimal polynomial per entry (the normal form of the sum:
    the element ``DomainMatrix``'s product, which reduces each product, gives)."""
    if not K.is_AlgebraicField:
        out = []
        for row in rows:
            live = [(i, a) for i, a in enumerate(row) if a]
            out.append([sum((a * col[i] for i, a in live if col[i]), K.zero) for col in cols])
        return out
    mod = K.one.mod_to_DMP()
    dom = K.one.dom
    polys = [[c.to_DMP() if c else None for c in col] for col in cols]
    result = []
    for row in rows:
        live = [(i, a.to_DMP()) for i, a in enumerate(row) if a]
        line = []
        for col in polys:
            acc = None
            for i, a in live:
                b = col[i]
                if b is not None:
                    acc = a.mul(b) if acc is None else acc.add(a.mul(b))
            line.append(K.zero if acc is None else K.dtype.new(acc.rem(mod), mod, dom))
        result.append(line)
    return result


def _solve(A: DomainMatrix, B: DomainMatrix) -> list[list[Any]]:
    """X with ``A X = B`` (A square, invertible) as rows of elements of the field.  In an
    algebraic field on Python or gmpy2 rationals: elimination on ``[A | B]``
    (:func:`_eliminate` on :func:`integer_arithmetic`'s vectors), then back substitution,
    the unique solution; else, or when A is singular, ``A.lu_solve(B)`` (which raises)."""
    ar = integer_arithmetic(A.domain)
    if ar is None:
        return [list(r) for r in A.lu_solve(B).to_list()]
    n, k = A.shape[0], B.shape[1]
    rows = [[ar.vector(x) for x in (*a, *b)] for a, b in zip(A.to_list(), B.to_list(), strict=True)]
    pivots, _, t = _eliminate(ar, rows, n, n + k)
    if pivots[:n] != list(range(n)):
        return [list(r) for r in A.lu_solve(B).to_list()]
    X: list[list[Any]] = [[]] * n
    for i in range(n - 1, -1, -1):
        inv = ar.revert(t[i][i])
        line = []
        for c in range(k):
            acc = t[i][n + c]
            for j in range(i + 1, n):
                if not ar.is_zero(t[i][j]):
                    acc = ar.sub_mul(acc, t[i][j], X[j][c])
            line.append(ar.mul(acc, inv))
        X[i] = line
    return [[ar.element(v) for v in row] for row in X]


def _exact_zero(x: Any) -> bool:
    """Is ``x`` written as the exact zero (sympy's ``0`` or the integer 0; not a float)?"""
    return x is sympy.S.Zero or (type(x) is int and x == 0)


def field_solve(A: Any, b: Any) -> np.ndarray | None:
    """X with ``A^T A X = A^T b`` (A (m, n) of full column rank, b (m,) or (m, k)): the
    least-squares solution, exact when b is in the range; None when the entries have no
    number field.

    The same X computed with less field arithmetic: a column of b that is zero has the
    zero solution (a loop's screws are the mechanism's with the other joints' columns
    zero), and a square A is invertible, so that ``A X = b`` is solved without the
    normal equations' products (most of exact mode's reduced coordinates)."""
    arr = np.asarray(A, dtype=object)
    rhs = np.asarray(b, dtype=object)
    m, n = arr.shape
    vector = rhs.ndim == 1
    rhs = rhs.reshape(m, -1)
    live = [j for j in range(rhs.shape[1]) if not all(_exact_zero(x) for x in rhs[:, j])]
    D = domain_matrix(np.concatenate([arr, rhs[:, live]], axis=1))
    if D is None:
        return None
    out = np.full((n, rhs.shape[1]), sympy.S.Zero, dtype=object)
    if live:
        Am = D[:, :n]
        bm = D[:, n:]
        if m != n:
            At = Am.transpose()
            Am, bm = At * Am, At * bm
        K = D.domain
        for i, row in enumerate(_solve(Am, bm)):
            for j, v in zip(live, row, strict=True):
                out[i, j] = K.to_sympy(v)
    return out[:, 0] if vector else out
