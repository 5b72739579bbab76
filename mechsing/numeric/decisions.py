"""Decisions with margins: ranks (:func:`decide_rank`, the two-threshold rule, or
undecided), differences of ranks, the non-zero test of one value, the definiteness of a
quadratic form, and whether float's dropped singular value is real
(:func:`float_drop_is_real`).  :class:`Margin` and :class:`RankDecision` carry the
evidence of a decision.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, cast

import numpy as np

from mechsing.numeric._mp import _mp_convert, _mp_eye, _mp_matrix, _object_array, eigsy
from mechsing.numeric.backend import FLOAT, to_float
from mechsing.numeric.blocks import block_svd, issparse
from mechsing.numeric.field import echelon_form, field_float, number_field
from mechsing.numeric.lazy import is_mp, mpmath, sympy
from mechsing.numeric.linalg import singular_values, svd
from mechsing.numeric.precision import Precision, parse_precision
from mechsing.numeric.tolerances import (
    FLOAT_ROUNDING_FACTOR,
    RESOLUTION_MIN_DIGITS,
    Tolerances,
)


@dataclass(frozen=True)
class Margin:
    """How far a decision was from flipping (the JSON "margin").

    ``kept``: the smallest kept singular value (None if rank 0); ``dropped``:
    the largest dropped one (None when every singular value is kept), both in
    the commensurate metric, like ``sigma``; ``sigma_max``: the largest
    singular value, which ``tau_lo`` and ``tau_hi`` are relative to (so the
    decision was ``kept / sigma_max >= tau_hi`` and ``dropped / sigma_max <=
    tau_lo``).  ``eig_margin`` where a quadratic form was decided (relative to
    its largest eigenvalue).  In exact mode ``kept`` is the smallest non-zero
    pivot (30 digits) and there is no ``sigma_max``.  ``rounding`` (float only): the
    rounding level of the singular values, eps times the Frobenius norm of the matrix
    (or of the reference it was decided against); see :func:`float_drop_is_real`.
    """

    kept: float | None
    dropped: float | None
    tau_lo: float
    tau_hi: float
    length_scale: float
    eig_margin: float | None = None
    sigma_max: float | None = None
    rounding: float | None = None
    #: tau_lo and tau_hi as text, also below the float range (``1e-690``)
    thresholds: tuple[str, str] = field(default=("", ""), compare=False, repr=False)

    def __post_init__(self) -> None:
        # the record is in floats (JSON): an mp:N threshold below the float range
        # (N > 333) is recorded as 0 (its text keeps it); the decision compared mp numbers
        if self.thresholds == ("", ""):  # (dataclasses.replace passes them on)
            object.__setattr__(self, "thresholds", Tolerances(self.tau_lo, self.tau_hi).shown())
        object.__setattr__(self, "tau_lo", float(self.tau_lo))
        object.__setattr__(self, "tau_hi", float(self.tau_hi))


@dataclass(frozen=True)
class RankDecision:
    """A rank with its evidence.

    ``rank`` is None when undecided; ``rank_bounds`` then gives (lowest, highest)
    consistent ranks.  ``sigma`` are all singular values (absolute, in the
    scaled metric), largest first; ``null_space`` is an orthonormal basis of
    the (right) kernel (columns), ``range_space`` of the range and
    ``left_null_space`` of its orthogonal complement, when requested: float
    arrays, or the mode's own numbers with ``native_spaces`` at mp:N.  An exact
    decision with spaces also gives them exactly: ``exact_null_space`` the reduced
    kernel basis (columns, :meth:`sympy.Matrix.nullspace`'s, 1 in each free column) and
    ``exact_range_space`` the pivot columns of the matrix (sympy numbers, not
    orthonormal).
    """

    rank: int | None
    sigma: tuple[float, ...] | None
    margin: Margin
    precision: str
    rank_bounds: tuple[int, int] = (0, 0)
    null_space: np.ndarray | None = field(default=None, compare=False, repr=False)
    range_space: np.ndarray | None = field(default=None, compare=False, repr=False)
    left_null_space: np.ndarray | None = field(default=None, compare=False, repr=False)
    exact_null_space: np.ndarray | None = field(default=None, compare=False, repr=False)
    exact_range_space: np.ndarray | None = field(default=None, compare=False, repr=False)
    #: a decision taken from an exact one (:func:`decide_from_exact`): its native kernel
    #: is ``exact_null_space @ kernel_coefficients`` (k x k, N-digit numbers), so that a
    #: product ``A @ null_space`` can be formed as ``(A @ exact_null_space) @ coefficients``
    #: with ``A @ exact_null_space`` exact (its exact zeros kept)
    kernel_coefficients: np.ndarray | None = field(default=None, compare=False, repr=False)

    @property
    def decided(self) -> bool:
        return self.rank is not None


def decide_nonzero(value: Any, prec: Precision) -> bool | None:
    """Is a relative (dimensionless, at most about 1) quantity non-zero?  The
    two-threshold rule of a rank on one value: True at or above ``tau_hi``, False at
    or below ``tau_lo``, None between (undecided); exactly in exact mode."""
    if prec.mode == "exact":
        fit = number_field([value]) if isinstance(value, sympy.Basic | int) else None
        if fit is not None:  # zero in its number field is zero
            K, (el,) = fit
            return not K.is_zero(el)
        return bool(sympy.simplify(value) != 0)
    t = prec.tolerances
    # at mp:N in the mode's numbers: a float would underflow below 1e-308
    a = abs(value) if is_mp(value) else abs(float(to_float(value)))
    if a >= t.tau_hi:
        return True
    if a <= t.tau_lo:
        return False
    return None


def rank_difference(a: RankDecision, b: RankDecision) -> RankDecision:
    """The decision ``rank(a) - rank(b)`` (a dimension such as dim(K cap ker T) -
    dim(K cap ker T cap ker E) = rank [TN; EN] - rank TN), decided when both are.

    Its bounds are the widest the two allow; its margin is that of the decision
    nearer to flipping (the smaller of kept / sigma_max / tau_hi and
    tau_lo / (dropped / sigma_max)), so the reader sees the tighter evidence.
    """
    if a.precision != b.precision:
        raise ValueError(f"rank_difference of decisions at {a.precision} and {b.precision}")
    (alo, ahi), (blo, bhi) = (
        (d.rank, d.rank) if d.rank is not None else d.rank_bounds for d in (a, b)
    )
    lo, hi = max(0, alo - bhi), max(0, ahi - blo)
    rank = lo if lo == hi else None
    margin = _tighter(a.margin, b.margin, a.precision)
    return RankDecision(rank, None, margin, a.precision, (lo, hi))


def _tighter(a: Margin, b: Margin, precision: str = "float") -> Margin:
    """The margin nearer to flipping (:func:`_slack`), with the other's dropped value
    when it has none of its own: a dropped value that is zero never flips (exactly zero,
    or within the rounding of the matrix at the decisions' precision:
    :func:`_drop_is_rounding`), so a kept one is the nearer, but the difference rests on
    that drop too and shows it (relative to the kept margin's sigma_max; exact margins
    have none and drop 0).  The same margin is chosen in float and at mp:N."""
    digits = int(precision[3:]) if precision.startswith("mp:") else None
    near, far = (a, b) if _slack(a, digits) <= _slack(b, digits) else (b, a)
    if near.dropped is not None or far.dropped is None:
        return near
    scale = 1.0 if not far.sigma_max or not near.sigma_max else near.sigma_max / far.sigma_max
    return replace(near, dropped=far.dropped * scale)


def _slack(m: Margin, digits: int | None = None) -> float:
    """How far a margin is from flipping its decision: the smaller of the kept value's
    ratio to tau_hi and tau_lo's ratio to the dropped value (relative to sigma_max);
    exact margins (no thresholds) never flip, nor does a dropped value that is zero.

    A float drop within the rounding of its matrix (:func:`_drop_is_rounding`) counts as
    zero: whether such a singular value comes out as 5e-17 or exactly 0 is decided by
    rounding (the same matrix at another length scale, on another machine's BLAS), and
    the margin chosen must not be; nor at mp:N (``digits`` N) a drop within the rounding of N
    digits."""
    if not m.tau_hi or not m.sigma_max:
        return math.inf
    out = math.inf
    if m.kept is not None:
        out = min(out, m.kept / m.sigma_max / m.tau_hi)
    if m.dropped is not None and m.dropped > 0 and not _drop_is_rounding(m, digits):
        out = min(out, m.tau_lo / (m.dropped / m.sigma_max))
    return out


def _drop_is_rounding(m: Margin, digits: int | None = None) -> bool:
    """Is a margin's dropped singular value within its matrix's rounding
    (:data:`FLOAT_ROUNDING_FACTOR` times ``rounding``, the bound below which a computed
    singular value cannot be told from zero: :func:`float_drop_is_real`)?  At mp:N
    (``digits`` N; its margins record no ``rounding``) the rounding is 10^-N sigma_max."""
    if digits is not None and m.rounding is None:
        return (
            m.dropped is not None
            and m.sigma_max is not None
            and m.dropped <= FLOAT_ROUNDING_FACTOR * 10.0**-digits * m.sigma_max
        )
    return (
        m.rounding is not None
        and m.dropped is not None
        and (m.dropped <= FLOAT_ROUNDING_FACTOR * m.rounding)
    )


def rank_bounds(rel: Any, tol: Tolerances) -> tuple[Any, Any]:
    """The two-threshold rank rule, the one place it is written: on singular values
    relative to the largest (``rel``, descending along the last axis, any leading batch
    shape; floats, or mp numbers compared as they are), the (lowest, highest) rank
    consistent with them, i.e. the counts ``sigma >= tau_hi`` and ``sigma > tau_lo``.
    The rank is decided when the two agree.  Integers (arrays of the batch shape; Python
    ints for one matrix's values given as a list)."""
    if isinstance(rel, list):
        # one matrix's values (a few, floats or mp numbers): counted in Python, where an
        # array would cost more than the comparisons (decide_rank's every decision)
        return sum(x >= tol.tau_hi for x in rel), sum(x > tol.tau_lo for x in rel)
    r = np.asarray(rel)
    if r.dtype != object:
        r = r.astype(float, copy=False)
    return np.count_nonzero(r >= tol.tau_hi, axis=-1), np.count_nonzero(r > tol.tau_lo, axis=-1)


def relative_singular_values(s: Any, reference: Any = None) -> np.ndarray:
    """Float singular values ``s`` (..., k), descending, relative to the largest of each
    matrix, or to ``reference`` (a number or an array of the batch shape) where it is
    larger: what :func:`rank_bounds` reads (0 where the largest is 0)."""
    s = np.asarray(s, dtype=float)
    if s.shape[-1] == 0:
        return s
    if reference is None:  # the same numbers as below, in fewer array operations
        big = s[..., :1]
        return np.where(big > 0, s / np.where(big > 0, big, 1.0), 0.0)
    smax = s[..., 0].copy()
    if reference is not None:
        ref = np.broadcast_to(np.asarray(reference, dtype=float), smax.shape)
        smax = np.where(ref > smax, ref, smax)
    positive = smax > 0
    return np.where(positive[..., None], s / np.where(positive, smax, 1.0)[..., None], 0.0)


def batched_rank_bounds(s: Any, tol: Tolerances, reference: Any = None) -> tuple[Any, Any]:
    """:func:`rank_bounds` of float singular values ``s`` (..., k) relative to the largest
    of each matrix or to ``reference`` where larger (:func:`relative_singular_values`),
    as :func:`decide_rank` decides one matrix."""
    return rank_bounds(relative_singular_values(s, reference), tol)


def batched_kernels(J: np.ndarray, tol: Tolerances) -> list[tuple[int | None, np.ndarray]]:
    """Each float matrix of ``J`` (B, m, n): its nullity (None: rank undecided) and an
    orthonormal basis of its kernel at the lowest rank the bounds allow (n, n - r), by
    numpy's batched SVD and :func:`batched_rank_bounds` relative to its largest singular
    value, as :func:`decide_rank` decides one matrix with its spaces."""
    n = J.shape[2]
    s = np.linalg.svd(J, compute_uv=False)
    Vt = np.linalg.svd(J, full_matrices=True)[2]
    lo, hi = batched_rank_bounds(s, tol)
    out = []
    for b in range(J.shape[0]):
        r = int(lo[b])
        out.append((n - r if r == int(hi[b]) else None, Vt[b, r:].T.copy()))
    return out


def _split_rank(rel: list[Any], tol: Tolerances) -> tuple[int | None, tuple[int, int]]:
    """:func:`rank_bounds` of one matrix's relative singular values, as Python ints."""
    lo, hi = rank_bounds(rel, tol)
    lo_rank, hi_rank = int(lo), int(hi)
    return (lo_rank if lo_rank == hi_rank else None), (lo_rank, hi_rank)


def decide_rank(
    M: Any,
    precision: Precision | str = "float",
    length_scale: float = 1.0,
    want_spaces: bool = False,
    reference: Any = None,
    native_spaces: bool = False,
) -> RankDecision:
    """Rank of a (scaled) matrix with the two-threshold rule and its margin.

    Parameters
    ----------
    M : array_like, shape (m, n)
        Already commensurate (see :func:`scale_screws`).  Any backend.
    precision : Precision or str
        ``float``/``auto``: numpy SVD; ``mp:N``: mpmath SVD at N digits;
        ``exact``: sympy exact rank.
    length_scale : float
        Recorded in the margin.
    want_spaces : bool
        Also return orthonormal bases of the kernel, the range and the left
        kernel (float arrays unless ``native_spaces``).
    reference : number, optional
        Magnitude the thresholds are relative to when it exceeds the largest
        singular value: for a product ``A @ B`` with B orthonormal, pass the
        norm of A, so that a product that is nearly zero is decided as rank 0
        rather than judged against its own rounding noise.
    native_spaces : bool
        At mp:N, return the bases as object arrays of N-digit numbers (the
        spaces that later mp computations need) instead of their float
        rounding.  No effect in float and exact mode.
    """
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    tol = prec.tolerances
    if issparse(M) and (prec.mode in ("mp", "exact") or want_spaces):
        M = M.toarray()
    # a sparse float matrix (a big closure Jacobian) is factorised block by block
    arr = M if issparse(M) else np.asarray(M)
    m, n = arr.shape if arr.ndim == 2 else (0, 0)
    if m == 0 or n == 0:
        native = native_spaces and prec.mode == "mp"
        with prec.context():
            bk = prec.backend if native else FLOAT
            ns = bk.eye(n) if want_spaces else None
            rs = bk.zeros((m, 0)) if want_spaces else None
            ls = bk.eye(m) if want_spaces else None
        return RankDecision(
            0,
            (),
            Margin(None, None, tol.tau_lo, tol.tau_hi, length_scale),
            str(prec),
            (0, 0),
            ns,
            rs,
            ls,
        )
    if prec.mode == "exact":
        return _exact_rank(arr, prec, tol, length_scale, want_spaces)
    Um = Vm = None
    rounding: float | None = None  # float's rounding level of the singular values
    if prec.mode == "mp":
        with prec.context():
            A = np.array(
                [[_mp_convert(x) for x in row] for row in arr.tolist()], dtype=object
            ).reshape(m, n)
            if want_spaces:
                # one full SVD: its singular values are those of compute_uv=False
                Um, s_mp, Vm = svd(A)
                s = list(s_mp)
            else:
                s = singular_values(A)
            smax = s[0] if s else mpmath.mpf(0)
            if reference is not None and reference > smax:
                smax = mpmath.mpf(reference)
            # relative values in mp: as floats they underflow beyond 1e-308 (N > 300)
            rel = [x / smax if smax else mpmath.mpf(0) for x in s]
            sigma = tuple(float(x) for x in s)
    else:
        F = arr if issparse(arr) else to_float(arr)
        s_np = cast(np.ndarray, block_svd(F, compute_uv=False))
        smax = float(s_np[0]) if len(s_np) else 0.0
        if reference is not None and reference > smax:
            smax = float(reference)
        values = s_np.tolist()  # Python floats: the same numbers
        rel = [x / smax if smax > 0 else 0.0 for x in values]
        sigma = tuple(values)
        # the entries' rounding: of F itself, or of the factors of a product decided
        # against the norm of its first factor (``reference``)
        if issparse(F):
            sparse_data = cast(Any, F).data  # a sparse matrix's stored entries
            norm = float(np.sqrt(np.sum(sparse_data**2)))
        else:  # numpy.linalg.norm's Frobenius norm (the root of the entries' dot
            entries = np.asarray(F).ravel(order="K")  # product), without its checks
            norm = math.sqrt(float(entries.dot(entries)))
        rounding = FLOAT.eps * max(norm, float(reference or 0.0))
    rank, bounds = _split_rank(rel, tol)
    r_eff = rank if rank is not None else bounds[0]
    kept = sigma[r_eff - 1] if r_eff else None
    dropped = sigma[r_eff] if r_eff < len(sigma) else None
    margin = Margin(
        kept,
        dropped,
        tol.tau_lo,
        tol.tau_hi,
        length_scale,
        None,
        float(smax),
        rounding,
    )
    ns = rs = ls = None
    if want_spaces:
        k = r_eff
        if Um is None or Vm is None:
            Um, _s, Vm = block_svd(to_float(arr))
        elif not native_spaces:
            Um, Vm = to_float(Um), to_float(Vm)
        ns = Vm[k:].T.copy()
        rs = Um[:, :k].copy()
        ls = Um[:, k:]
    return RankDecision(rank, sigma, margin, str(prec), bounds, ns, rs, ls)


def decide_from_exact(M: Any, precision: Precision, exact: RankDecision) -> RankDecision | None:
    """The decision of ``M`` (m, n) at mp:N taken from ``exact``: an exact decision, with
    its spaces, of a matrix with M's kernel (the closure system in other row
    coordinates, e.g. its exact reduced coordinates where M has orthonormal ones).

    The rank is the one ``exact`` proved (its margin and precision are given); the
    native orthonormal spaces of M at N digits come from the exact kernel instead of an
    SVD: the kernel ``N = Z C`` by Gram-Schmidt on the exact kernel basis Z (exact zeros
    kept; Z and C are given, ``exact_null_space`` and ``kernel_coefficients``), its
    complement Y from the Householder QR of Z, the range and the left kernel from the QR
    of ``M Y`` (full column rank r).  None (decide M itself) unless ``precision`` is mp:N and ``exact`` has an exact
    kernel of M's width, or when M does not annihilate that kernel: ``|M N|_F`` above
    ``tau_lo |M|_F`` (M is not the matrix the caller took it for).
    """
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    Z = exact.exact_null_space
    arr = np.asarray(M)
    if prec.mode != "mp" or exact.rank is None or Z is None or arr.ndim != 2:
        return None
    m, n = arr.shape
    k = Z.shape[1]
    r = n - k
    if Z.shape[0] != n or r != exact.rank or r > m:
        return None
    with prec.context():
        A = _mp_matrix(arr)
        C = None
        if k:
            Zm = _mp_matrix(Z)
            # the complement Y serves only the range and left kernel of a rank below both
            # sizes (full row rank: the range is everything, the left kernel empty)
            if 0 < r < m:
                Q, _ = mpmath.qr(Zm)
                Y = _object_array(Q, (n, n))[:, k:]
            C = _gram_schmidt(Zm, n, k)
            N = _object_array(Zm * mpmath.matrix(C.tolist()), (n, k))
            AN = _object_array(A * mpmath.matrix(N.tolist()), (m, k))
            size = mpmath.sqrt(mpmath.fsum(x * x for x in A))
            if mpmath.sqrt(mpmath.fsum(x * x for x in AN.flat)) > prec.tolerances.tau_lo * size:
                return None
        else:
            N, Y = _mp_eye(n)[:, :0], _mp_eye(n)
        if r == 0:
            R, P = _mp_eye(m)[:, :0], _mp_eye(m)
        elif r == m:
            R, P = _mp_eye(m), _mp_eye(m)[:, :0]
        else:
            Qr, _ = mpmath.qr(A * mpmath.matrix(Y.tolist()))
            Qm = _object_array(Qr, (m, m))
            R, P = Qm[:, :r], Qm[:, r:]
    return RankDecision(
        r,
        None,
        exact.margin,
        exact.precision,
        (r, r),
        N,
        R,
        P,
        exact_null_space=Z,
        kernel_coefficients=C,
    )


def _gram_schmidt(Z: Any, n: int, k: int) -> np.ndarray:
    """The coefficients C (k x k object array, upper triangular) with ``Z C`` orthonormal:
    modified Gram-Schmidt on the columns of Z (mpmath matrix), twice, each vector
    carried as its coefficients on Z.  ``Z C`` keeps Z's exact zeros (a coordinate zero
    in every column stays exactly zero), which a Householder QR would fill with
    rounding."""
    vecs: list[list[Any]] = []  # the orthonormal vectors so far
    coefs: list[list[Any]] = []  # their coefficients on the columns of Z
    zero, one = mpmath.mpf(0), mpmath.mpf(1)
    for j in range(k):
        v = [Z[i, j] for i in range(n)]
        c = [one if i == j else zero for i in range(k)]
        for _pass in range(2):
            for q, cq in zip(vecs, coefs, strict=True):
                d = mpmath.fsum(a * b for a, b in zip(q, v, strict=True))
                v = [a - d * b for a, b in zip(v, q, strict=True)]
                c = [a - d * b for a, b in zip(c, cq, strict=True)]
        nv = mpmath.sqrt(mpmath.fsum(a * a for a in v))
        vecs.append([a / nv for a in v])
        coefs.append([a / nv for a in c])
    out = np.empty((k, k), dtype=object)
    for j, c in enumerate(coefs):
        out[:, j] = c
    return out


def float_drop_is_real(margin: Margin, data_error: float = 0.0) -> bool:
    """Did a float rank decision drop a singular value that float itself sees is not zero?

    True when the largest dropped singular value exceeds :data:`FLOAT_ROUNDING_FACTOR`
    times ``rounding + data_error * sigma_max``: ``rounding`` is the margin's (``eps |M|_F``),
    ``data_error`` the relative error of the configuration the matrix was built at (its
    closure residual divided by the characteristic length).  Such a drop is decided by the
    two thresholds but not by the data: ``auto`` re-decides it at mp:50, as it does an
    undecided rank.  False for mp and exact decisions, and when nothing was dropped.
    """
    rounding, dropped, smax = margin.rounding, margin.dropped, margin.sigma_max
    if rounding is None or dropped is None or not smax:
        return False
    return dropped > FLOAT_ROUNDING_FACTOR * (rounding + data_error * smax)


def data_resolution(digits: int, last: int, factor: float = 1.0) -> float:
    """The resolution of a given value written as a decimal of ``digits`` significant
    digits whose last digit is 10^``last`` (in units that ``factor`` turns into SI):
    half a unit in that digit, or 0 for a decimal shorter than
    :data:`RESOLUTION_MIN_DIGITS` (taken as exact, like an expression)."""
    if digits < RESOLUTION_MIN_DIGITS:
        return 0.0
    return 0.5 * 10.0**last * abs(float(factor))


def resolution_spread(slopes: list[float], resolutions: list[float]) -> float:
    """The first-order bound on how far the data's resolution can move a relative
    singular value: ``sum_i |d sigma / d x_i| res_i`` (``slopes`` relative to sigma_max per
    SI unit of each given value, ``resolutions`` in SI)."""
    return float(sum(abs(s) * r for s, r in zip(slopes, resolutions, strict=True)))


def flips_within(margin: Margin, spread: float, singular: bool) -> float | None:
    """Could a decision flip when its singular values move by ``spread`` (relative to
    sigma_max: :func:`resolution_spread`)?  The relative value it rests on when it could,
    else None.

    ``singular``: the decision stands for a singular verdict, which rests on its largest
    dropped value staying at or below ``tau_lo``; else for a regular one, which rests on
    its smallest kept value staying at or above ``tau_hi``.  Exact margins have no
    ``sigma_max`` and thresholds 0: their pivot is compared as it is."""
    if spread <= 0:
        return None
    smax = margin.sigma_max or 1.0
    if singular:
        if margin.dropped is None:
            return None
        d = abs(float(margin.dropped)) / smax
        return d if d + spread > margin.tau_lo else None
    if margin.kept is None:
        return None
    k = abs(float(margin.kept)) / smax
    return k if k - spread < margin.tau_hi else None


def _exact_rank(
    arr: np.ndarray, prec: Precision, tol: Tolerances, length_scale: float, want_spaces: bool
) -> RankDecision:
    fast = _field_rank(arr, length_scale, want_spaces)
    if fast is not None:
        return fast
    M = sympy.Matrix(arr.tolist()).applyfunc(
        lambda x: sympy.nsimplify(x) if isinstance(x, float) else x
    )
    E, pivots = M.echelon_form(with_pivots=True, simplify=True)
    rank = len(pivots)
    piv_vals = []
    for row, col in enumerate(pivots):
        piv_vals.append(abs(float(sympy.N(E[row, col], 30))))
    ns = rs = ens = ers = None
    if want_spaces:
        ker = M.nullspace(simplify=True)
        ns = (
            _orthonormal(np.array([[float(sympy.N(x, 30)) for x in v] for v in ker]).T)
            if ker
            else np.zeros((M.shape[1], 0))
        )
        cols = M.columnspace(simplify=True)
        rs = (
            _orthonormal(np.array([[float(sympy.N(x, 30)) for x in v] for v in cols]).T)
            if cols
            else np.zeros((M.shape[0], 0))
        )
        ens = _columns([list(v) for v in ker], M.shape[1])
        ers = _columns([list(v) for v in cols], M.shape[0])
    return _exact_decision(rank, piv_vals, arr.shape, length_scale, (ns, rs, ens, ers))


def _field_rank(arr: np.ndarray, length_scale: float, want_spaces: bool) -> RankDecision | None:
    """:func:`_exact_rank` in the number field of the entries (the same echelon form,
    pivots and spaces, without simplification), or None when they have no field (a
    float, a transcendental number)."""
    if arr.ndim != 2 or 0 in arr.shape or any(isinstance(x, float) for x in arr.flat):
        return None
    E = echelon_form(arr)
    if E is None:
        return None
    K = E.K
    pivots = E.pivots
    m, n = arr.shape
    rank = len(pivots)
    piv_vals = E.pivot_magnitudes()
    ns = rs = ens = ers = None
    if want_spaces:
        ker = E.null_basis()
        ns = (
            _orthonormal(np.array([[field_float(K, x) for x in v] for v in ker]).T)
            if ker
            else np.zeros((n, 0))
        )
        entries = E.D.to_list()
        cols = [[field_float(K, entries[i][j]) for i in range(m)] for j in pivots]
        rs = _orthonormal(np.array(cols).T) if cols else np.zeros((m, 0))
        ens = _columns([[K.to_sympy(x) for x in v] for v in ker], n)
        ers = _columns([[sympy.sympify(arr[i, j]) for i in range(m)] for j in pivots], m)
    return _exact_decision(rank, piv_vals, arr.shape, length_scale, (ns, rs, ens, ers))


def _exact_decision(
    rank: int,
    pivots: list[float],
    shape: tuple[int, ...],
    length_scale: float,
    spaces: tuple[Any, ...],
) -> RankDecision:
    """An exact rank decision: its smallest pivot magnitude kept, 0 dropped when the
    rank is below full; ``spaces``: (null, range, exact null, exact range) or Nones."""
    kept = min(pivots) if pivots else None
    dropped = None if rank == min(shape) else 0.0
    ns, rs, ens, ers = spaces
    return RankDecision(
        rank,
        None,
        Margin(kept, dropped, 0.0, 0.0, length_scale),
        "exact",
        (rank, rank),
        ns,
        rs,
        exact_null_space=ens,
        exact_range_space=ers,
    )


def _columns(vectors: list[list[Any]], length: int) -> np.ndarray:
    """The vectors as the columns of an object array (length x len(vectors))."""
    out = np.empty((length, len(vectors)), dtype=object)
    for j, v in enumerate(vectors):
        out[:, j] = v
    return out


def _orthonormal(A: np.ndarray) -> np.ndarray:
    q, _ = np.linalg.qr(A)
    return q[:, : A.shape[1]]


@dataclass(frozen=True)
class DefinitenessDecision:
    """Sign pattern of a symmetric form: ``kind`` is ``"definite"``, ``"indefinite"``,
    ``"semidefinite"`` (a zero eigenvalue, no sign change), ``"zero"`` or ``None``
    (undecided).  ``eig_margin`` is the smallest decided ``|eigenvalue|`` relative to
    the largest (or the largest in exact mode)."""

    kind: str | None
    eigenvalues: tuple[float, ...]
    eig_margin: float | None
    n_pos: int
    n_neg: int
    n_zero: int


def decide_definiteness(
    Q: Any, precision: Precision | str = "float", scale: float | None = None
) -> DefinitenessDecision:
    """Decide the definiteness of a symmetric matrix on its eigenvalues.

    Eigenvalues are compared with ``tau_lo``/``tau_hi`` relative to ``scale``
    (default: the largest ``|eigenvalue|``).  An eigenvalue between the two
    thresholds leaves the verdict undecided.
    """
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    tol = prec.tolerances
    arr = np.asarray(Q)
    n = arr.shape[0] if arr.ndim == 2 else 0
    if n == 0:
        return DefinitenessDecision("zero", (), None, 0, 0, 0)
    if prec.mode == "exact":
        M = sympy.Matrix(arr.tolist())
        M = (M + M.T) / 2
        # exact signature: eigenvalues of a symmetric algebraic matrix are real
        ev = [sympy.nsimplify(e) if isinstance(e, float) else e for e in _exact_eigs(M)]
        vals = [float(sympy.N(e, 30)) for e in ev]
        zero = [sympy.simplify(e) == 0 for e in ev]
        npos = sum(1 for v, z in zip(vals, zero, strict=True) if not z and v > 0)
        nneg = sum(1 for v, z in zip(vals, zero, strict=True) if not z and v < 0)
        nz = sum(zero)
        nonzero = [abs(v) for v, z in zip(vals, zero, strict=True) if not z]
        eig_margin = (min(nonzero) / max(nonzero)) if nonzero else None
        return DefinitenessDecision(
            _kind(npos, nneg, nz), tuple(sorted(vals)), eig_margin, npos, nneg, nz
        )
    if prec.mode == "mp":
        with prec.context():
            A = _mp_matrix(arr)
            ev = eigsy((A + A.T) / 2, eigvals_only=True)
            exact_vals = sorted(ev[i] for i in range(n))
            ref_mp = scale if scale else max((abs(v) for v in exact_vals), default=0)
            # relative values in mp (floats underflow below 1e-308)
            rel = [v / ref_mp for v in exact_vals] if ref_mp else []
        vals = [float(x) for x in exact_vals]
    else:
        F = to_float(arr)
        vals = sorted(float(x) for x in np.linalg.eigvalsh((F + F.T) / 2))
        ref = scale if scale else max((abs(v) for v in vals), default=0.0)
        rel = [v / ref for v in vals] if ref else []
    if not rel:
        return DefinitenessDecision("zero", tuple(vals), None, 0, 0, n)
    if any(tol.tau_lo < abs(r) < tol.tau_hi for r in rel):
        return DefinitenessDecision(None, tuple(vals), None, 0, 0, 0)
    npos = sum(1 for r in rel if r >= tol.tau_hi)
    nneg = sum(1 for r in rel if r <= -tol.tau_hi)
    nz = n - npos - nneg
    decided = [abs(r) for r in rel if abs(r) >= tol.tau_hi]
    eig_margin = float(min(decided)) if decided else None
    return DefinitenessDecision(_kind(npos, nneg, nz), tuple(vals), eig_margin, npos, nneg, nz)


def _exact_eigs(M: sympy.Matrix) -> list[Any]:
    out: list[Any] = []
    for val, mult in M.eigenvals().items():
        out.extend([val] * mult)
    return out


def _kind(npos: int, nneg: int, nz: int) -> str:
    if npos and nneg:
        return "indefinite"
    if npos + nneg == 0:
        return "zero"
    if nz:
        return "semidefinite"
    return "definite"
