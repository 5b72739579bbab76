"""The number backends of the precision modes, and the questions formulas ask them.

Three precision modes run the *same* formulas:

``float``
    numpy float64 arrays (fast, batched).
``mp:N``
    numpy object arrays of ``mpmath.mpf`` evaluated at N significant digits.
``exact``
    numpy object arrays of sympy numbers (rationals and algebraic expressions).

A formula never branches on the mode.  It asks :func:`backend_of` for the backend of
its input array and calls the backend: its elementary functions (``bk.sin``,
``bk.sqrt``, ``bk.atan2`` ...), and its answers to the questions whose answer depends
on the arithmetic -- :meth:`Backend.is_zero` (below the backend's tolerance; proved in
exact mode), :meth:`Backend.null_space`, :meth:`Backend.row_space` and
:meth:`Backend.solve` (numpy / mpmath / sympy), :meth:`Backend.simplify` (the exact
normal form; nothing elsewhere), the switch point of a Taylor series
(:meth:`Backend.threshold`, :meth:`Backend.series_switch`: only exactly 0 in exact mode,
where ``eps`` is 0) and how an undefined value or a frame centre is represented.

This module owns :class:`Backend`, the three backends (:data:`FLOAT`, the mp backend
of the working precision, :data:`EXACT`), :func:`backend_of`, :func:`to_float`,
:func:`screw_zero_rtol` and :func:`exact_is_zero`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from mechsing.numeric._mp import _mp_convert, mp_svd
from mechsing.numeric.field import field_null_space, field_row_space, field_solve
from mechsing.numeric.lazy import is_mp, is_sympy, mpmath, sympy
from mechsing.numeric.pirational import PiRational, evalf_float
from mechsing.numeric.tolerances import EXACT_ZERO_DIGITS, MEMBERSHIP_RTOL_FLOAT

# ---------------------------------------------------------------------------
# Backends
# ---------------------------------------------------------------------------


def _objfunc(f: Callable[..., Any], nin: int) -> Callable[..., np.ndarray]:
    """Elementwise version of a scalar function on object arrays, keeping 0-d shape."""
    uf = np.frompyfunc(f, nin, 1)

    def apply(*args: Any) -> np.ndarray:
        out = uf(*args)
        if not isinstance(out, np.ndarray):
            arr = np.empty((), dtype=object)
            arr[()] = out
            return arr
        return out

    return apply


@dataclass(frozen=True)
class Backend:
    """The number backend of one precision mode.

    Attributes
    ----------
    name : str
        ``"float"``, ``"mp"`` or ``"exact"``.
    eps : number
        Unit roundoff of the backend (0 in exact mode).  Formulas derive their
        series switch points from it.
    dtype : numpy dtype
        ``float64`` or ``object``.
    inf : number or None
        What an infinite value (the pitch of a translation) is: ``inf`` in float,
        None in the object backends.

    The three backends are the subclasses :class:`FloatBackend`, :class:`MpBackend`
    and :class:`ExactBackend`; each answers the questions below in its arithmetic.
    """

    name: str
    eps: Any
    dtype: Any
    sin: Callable[[Any], np.ndarray]
    cos: Callable[[Any], np.ndarray]
    sqrt: Callable[[Any], np.ndarray]
    atan2: Callable[[Any, Any], np.ndarray]
    convert: Callable[[Any], Any]
    pi: Any
    inf: Any = None

    def asarray(self, x: Any) -> np.ndarray:
        """Convert nested sequences / arrays / scalars to an array of this backend."""
        a = np.asarray(x, dtype=object)
        return _objfunc(self.convert, 1)(a) if a.size else a

    def zeros(self, shape: tuple[int, ...] | int) -> np.ndarray:
        out = np.empty(shape, dtype=object)
        out.fill(self.convert(0))
        return out

    def eye(self, n: int) -> np.ndarray:
        out = self.zeros((n, n))
        for i in range(n):
            out[i, i] = self.convert(1)
        return out

    # -- series ------------------------------------------------------------------

    def threshold(self, order: int) -> Any:
        """Switch point ``eps ** (1/(order+1))`` of a series whose first neglected
        term is of relative order ``order + 1`` (0 in exact mode)."""
        return self.eps ** (mpmath.mpf(1) / (order + 1))

    def series_switch(self, limit: Any) -> Any:
        """Where a series replaces its closed form, given the switch ``limit`` of a
        rounding arithmetic: ``limit`` itself (0 in exact mode, where the series is
        used only at exactly 0, its exact limit)."""
        return limit

    @property
    def digits(self) -> float:
        """-log10(eps): the digits a truncated series must reach (0 in exact mode, where
        no series is truncated)."""
        return _mp_digits(int(mpmath.mp.dps))

    @property
    def key(self) -> tuple[str, int]:
        """What a cache of converted constants is keyed on: ``(name, working digits)``."""
        return (self.name, 0)

    def rational(self, p: int, q: int) -> Any:
        """The rational p / q in this arithmetic (correctly rounded)."""
        return mpmath.mpf(p) / q

    # -- decisions in the backend's arithmetic ---------------------------------------

    def zero_rtol(self) -> Any:
        """Relative tolerance of "this is zero" (see :func:`screw_zero_rtol`)."""
        return mpmath.mpf(10) ** (-(mpmath.mp.dps // 2))

    def is_zero(self, x: Any, scale: Any = 1.0) -> bool:
        """Is ``x`` zero?  float and mp: ``|x| <= zero_rtol * scale`` (so ``scale=0``
        asks for exactly 0); exact: proved zero (:func:`exact_is_zero`)."""
        return bool(abs(x) <= self.zero_rtol() * scale)

    def negative(self, x: Any) -> bool:
        """Is the (non-zero) number ``x`` negative?"""
        return bool(x < 0)

    def simplify(self, x: Any) -> Any:
        """The normal form of a number or array (only exact numbers have one)."""
        return x

    def accepts(self, other: Backend) -> bool:
        """Can numbers of ``other`` be used as they are (without conversion)?  mp numbers
        are always re-rounded to the working precision."""
        return False

    def frame_centre(self, centre: Any) -> np.ndarray:
        """The point screws are moved to before a decision, from the centroid of their
        axes: the centroid in float and mp (it conditions the matrix); the origin in
        exact mode, where a rank does not depend on conditioning and a decimal centroid
        would only lengthen the numbers."""
        return self.asarray(centre)

    # -- linear algebra --------------------------------------------------------------

    def _svd(self, A: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return mp_svd(self.asarray(A))

    def _rank(self, A: np.ndarray, s: np.ndarray, rank: int | None) -> int:
        if rank is not None:
            return rank
        cut = self.eps * max(A.shape) * s[0] if len(s) else 0
        return sum(1 for x in s if x > cut)

    def null_space(self, A: Any, rank: int | None = None) -> np.ndarray:
        """Rows spanning the right null space of ``A`` (m, n): orthonormal in float and
        mp (the last right singular vectors), reduced in exact mode.  ``rank``: the
        decided rank of A (:func:`mechsing.numeric.decide_rank`); default: singular
        values above ``eps max(m, n) sigma_max`` (exact: the exact rank)."""
        A = np.asarray(A)
        _U, s, Vt = self._svd(A)
        return Vt[self._rank(A, s, rank) :].copy()

    def row_space(self, A: Any, rank: int | None = None) -> np.ndarray:
        """Rows spanning the row space of ``A``: orthonormal in float and mp, the reduced
        row echelon rows in exact mode (``rank`` as in :meth:`null_space`)."""
        A = np.asarray(A)
        _U, s, Vt = self._svd(A)
        return Vt[: self._rank(A, s, rank)].copy()

    def solve(self, A: Any, b: Any) -> np.ndarray:
        """x with ``A x = b`` in the least-squares sense, A (m, n) of full column rank:
        the normal equations solved by LU (mpmath, sympy; exact when b is in the range),
        numpy's ``lstsq`` in float."""
        A = np.asarray(A)
        n = A.shape[1]
        if n == 0:
            return self.zeros(0)
        At = mpmath.matrix(A.T.tolist())
        x = mpmath.lu_solve(At * At.T, At * mpmath.matrix(list(b)))
        return np.array([x[i] for i in range(n)], dtype=object)


class FloatBackend(Backend):
    """numpy float64 (batched); tolerances relative to float's rounding."""

    def asarray(self, x: Any) -> np.ndarray:
        return np.asarray(to_float(x), dtype=np.float64)

    def zeros(self, shape: tuple[int, ...] | int) -> np.ndarray:
        return np.zeros(shape)

    def threshold(self, order: int) -> Any:
        return float(self.eps) ** (1.0 / (order + 1))

    @property
    def digits(self) -> float:
        return _FLOAT_DIGITS

    def rational(self, p: int, q: int) -> Any:
        return p / q

    def zero_rtol(self) -> Any:
        return MEMBERSHIP_RTOL_FLOAT

    def accepts(self, other: Backend) -> bool:
        return other.name == "float"

    def _svd(self, A: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return np.linalg.svd(to_float(A))

    def solve(self, A: Any, b: Any) -> np.ndarray:
        A = np.asarray(A)
        if A.shape[1] == 0:
            return self.zeros(0)
        x, *_ = np.linalg.lstsq(to_float(A), to_float(b), rcond=None)
        return x


class MpBackend(Backend):
    """numpy object arrays of mpmath numbers at the current working precision
    (``mpmath.mp.dps``: one backend object serves every N)."""

    @property
    def key(self) -> tuple[str, int]:
        return (self.name, int(mpmath.mp.dps))


class ExactBackend(Backend):
    """numpy object arrays of sympy numbers; zero is proved, spaces are exact."""

    def threshold(self, order: int) -> Any:
        return 0

    def series_switch(self, limit: Any) -> Any:
        return 0

    @property
    def digits(self) -> float:
        return 0.0

    def rational(self, p: int, q: int) -> Any:
        return sympy.Rational(p, q)

    def zero_rtol(self) -> Any:
        return 0

    def is_zero(self, x: Any, scale: Any = 1.0) -> bool:
        return exact_is_zero(x, to_float(scale) if scale else 1.0) is True

    def negative(self, x: Any) -> bool:
        return bool(sympy.N(x, 30) < 0)

    def simplify(self, x: Any) -> Any:
        if isinstance(x, np.ndarray) and x.ndim == 0:
            x = x[()]
        if isinstance(x, np.ndarray):
            out = np.empty(x.shape, dtype=object)
            for idx, v in np.ndenumerate(x):
                out[idx] = exact_normal_form(v)
            return out
        return exact_normal_form(x)

    def accepts(self, other: Backend) -> bool:
        return other.name == "exact"

    def frame_centre(self, centre: Any) -> np.ndarray:
        return self.zeros(3)

    def null_space(self, A: Any, rank: int | None = None) -> np.ndarray:
        A = np.asarray(A)
        fast = field_null_space(A) if A.size else None
        if fast is not None:  # in the number field of the entries: no simplification
            return fast
        ker = sympy.Matrix(A.tolist()).nullspace(simplify=True)
        rows = [[exact_normal_form(x) for x in v] for v in ker]
        return np.array(rows, dtype=object).reshape(len(rows), A.shape[1])

    def row_space(self, A: Any, rank: int | None = None) -> np.ndarray:
        A = np.asarray(A)
        fast = field_row_space(A) if A.size else None
        if fast is not None:
            return fast
        R, piv = sympy.Matrix(A.tolist()).rref(simplify=True)
        rows = [[exact_normal_form(x) for x in R.row(i)] for i in range(len(piv))]
        return np.array(rows, dtype=object).reshape(len(piv), A.shape[1])

    def solve(self, A: Any, b: Any) -> np.ndarray:
        A = np.asarray(A)
        if A.shape[1] == 0:
            return self.zeros(0)
        fast = field_solve(A, b) if A.shape[0] else None
        if fast is not None:
            return fast
        At = sympy.Matrix(A.T.tolist())
        x = (At * At.T).LUsolve(At * sympy.Matrix(list(b)))
        return np.array([exact_normal_form(v) for v in x], dtype=object)


#: exact numbers converted to float (or put in normal form) are kept: a file's numbers
#: are converted again at every model of it (a sweep builds three, and a script that
#: sweeps or analyses a file again builds more), each a sympy evaluation of tens of us
_EXACT_KEPT = 4096


_FLOAT_DIGITS = -math.log10(float(np.finfo(np.float64).eps))


@lru_cache(maxsize=64)
def _mp_digits(dps: int) -> float:
    # from log10(eps), never float(eps): at N > 300 digits eps underflows to 0 in float
    with mpmath.workdps(dps):
        return float(-mpmath.log10(mpmath.mp.eps))


def exact_normal_form(x: Any) -> Any:
    """A normal form of an exact value: expanded and with rationalised
    denominators; ``sympy.simplify`` only when functions (atan2 ...) remain."""
    if not isinstance(x, sympy.Basic) or x.is_Rational:
        return x
    return _normal_form(x)


@lru_cache(maxsize=_EXACT_KEPT)
def _normal_form(x: sympy.Basic) -> Any:
    y = sympy.expand(x)
    if y.has(sympy.Function):
        y = sympy.simplify(y)
    return sympy.radsimp(y)


def _exact_convert(x: Any) -> Any:
    if isinstance(x, PiRational):
        return x._sympy_()
    if isinstance(x, sympy.Basic):
        return x
    if isinstance(x, np.integer | int):
        return sympy.Integer(int(x))
    if isinstance(x, str):
        return sympy.Rational(x)
    if isinstance(x, np.floating | float):
        # a float reaching exact mode is taken at its decimal repr, never its binary value
        return sympy.Rational(repr(float(x)))
    if isinstance(x, mpmath.mpf):
        return sympy.Rational(mpmath.nstr(x, mpmath.mp.dps))
    return sympy.sympify(x, strict=True)


FLOAT = FloatBackend(
    name="float",
    eps=float(np.finfo(np.float64).eps),
    dtype=np.float64,
    sin=np.sin,
    cos=np.cos,
    sqrt=np.sqrt,
    atan2=np.arctan2,
    convert=float,
    pi=math.pi,
    inf=np.inf,
)


def _mp_backend() -> Backend:
    # mpmath functions read the *current* working precision, so one backend
    # object serves every N; Precision.context() sets N.
    return MpBackend(
        name="mp",
        eps=mpmath.mp.eps,
        dtype=object,
        sin=_objfunc(mpmath.sin, 1),
        cos=_objfunc(mpmath.cos, 1),
        sqrt=_objfunc(mpmath.sqrt, 1),
        atan2=_objfunc(mpmath.atan2, 2),
        convert=_mp_convert,
        pi=+mpmath.pi,
    )


def _exact_sqrt(x: Any) -> Any:
    return sympy.sqrt(x)


@lru_cache(maxsize=1)
def _exact_backend() -> ExactBackend:
    """The exact backend, made (and sympy imported) when first asked for: ``EXACT``."""
    return ExactBackend(
        name="exact",
        eps=0,
        dtype=object,
        sin=_objfunc(sympy.sin, 1),
        cos=_objfunc(sympy.cos, 1),
        sqrt=_objfunc(_exact_sqrt, 1),
        atan2=_objfunc(sympy.atan2, 2),
        convert=_exact_convert,
        pi=sympy.pi,
    )


def __getattr__(name: str) -> Any:
    # EXACT, the exact backend, is made when first asked for (it holds sympy's functions)
    if name == "EXACT":
        return _exact_backend()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def backend_of(*arrays: Any) -> Backend:
    """The backend of the given arrays: exact if any holds a sympy number, else
    mp if any holds an mpmath number, else float.

    The mp backend works at the current ``mpmath.mp.dps`` (see
    :meth:`Precision.context`).
    """
    found: Backend = FLOAT
    for a in arrays:
        arr = np.asarray(a) if not isinstance(a, np.ndarray) else a
        if arr.dtype != object:
            continue
        for x in arr.flat:
            if is_sympy(x):
                return _exact_backend()
            if is_mp(x):
                found = _mp_backend()
                break
    return found


def holds_objects(a: Any) -> bool:
    """Does the array hold Python objects (mp or exact numbers, or a mix)?  The one test
    of an array's kind outside the backends' own code: formulas ask it (or
    :func:`is_float64`) instead of comparing dtypes."""
    return a.dtype == object


def is_float64(a: Any) -> bool:
    """Is the array one of float64 numbers (the float mode's; an int or bool array is
    not)?"""
    return a.dtype == _F64


def bool_mask(c: Any) -> np.ndarray:
    """A boolean array of a comparison's result (an object array of sympy or mpmath
    truth values included)."""
    c = np.asarray(c)
    return c if c.dtype == bool else c.astype(bool)


_F64 = np.dtype(np.float64)


def coarser_backend(a: Backend, b: Backend) -> Backend:
    """The backend two numbers are compared in: the coarser arithmetic of the two
    (float before mp before exact), so a float is never compared exactly."""
    rank = {"float": 0, "mp": 1, "exact": 2}
    return a if rank[a.name] <= rank[b.name] else b


def to_float(x: Any) -> Any:
    """float64 array (or float) from any backend's array or scalar."""
    if isinstance(x, np.ndarray) and x.dtype != object:
        return x.astype(np.float64, copy=False)
    if isinstance(x, list | tuple | np.ndarray):
        arr = np.asarray(x, dtype=object)
        out = np.empty(arr.shape, dtype=np.float64)
        for idx, v in np.ndenumerate(arr):
            out[idx] = _scalar_float(v)
        return out
    return _scalar_float(x)


def _scalar_float(v: Any) -> float:
    if isinstance(v, PiRational):
        return evalf_float(v, 20)
    if is_sympy(v):
        return _sympy_float(v)
    if isinstance(v, str):
        return float(v)
    return float(v)


@lru_cache(maxsize=_EXACT_KEPT)
def _sympy_float(v: sympy.Basic) -> float:
    """An exact number in float (through 20 digits: the nearest double)."""
    return float(sympy.N(v, 20))


def screw_zero_rtol(bk: Backend) -> Any:
    """Relative tolerance for "this part of a screw / displacement is zero".

    1e-9 (:data:`MEMBERSHIP_RTOL_FLOAT`) in float, 10^(-N/2) at mp:N (the
    ``tau_hi`` of the mode), exactly 0 in exact mode.
    """
    return bk.zero_rtol()


def exact_is_zero(x: Any, scale: float = 1.0) -> bool | None:
    """Is an exact (sympy) number zero?  True (proved), False, or None (zero to
    :data:`EXACT_ZERO_DIGITS` digits but not proved).

    Cheap first: a value clearly non-zero at 60 digits (relative to ``scale``, e.g.
    the characteristic length for a translation) is not zero, so a configuration
    that does not close fails at once; the rest is proved by expansion, then
    trigonometric simplification, then ``simplify`` (in that order of cost).
    """
    x = sympy.sympify(x)
    if x == 0:
        return True
    if x.is_number:
        v = sympy.N(x, EXACT_ZERO_DIGITS)
        if abs(v) > sympy.Float(10) ** (15 - EXACT_ZERO_DIGITS) * max(1.0, float(scale)):
            return False
    for prove in (sympy.expand, sympy.trigsimp, sympy.simplify):
        if prove(x) == 0:
            return True
    return None if x.is_number else False
