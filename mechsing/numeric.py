"""Precision modes, number backends, tolerances and rank decisions (the leaf layer).

Every other layer of mechsing may import this module; it imports none of them.

Three precision modes run the *same* formulas:

``float``
    numpy float64 arrays (fast, batched).
``mp:N``
    numpy object arrays of ``mpmath.mpf`` evaluated at N significant digits.
``exact``
    numpy object arrays of sympy numbers (rationals and algebraic expressions).

A formula never branches on the mode.  It asks :func:`backend_of` for the
backend of its input array and calls the backend's elementary functions
(``bk.sin``, ``bk.sqrt``, ``bk.atan2`` ...), uses numpy's arithmetic and
``np.where`` for its branches, and derives the switch point of a Taylor series
from ``bk.eps`` (``eps ** (1/(k+1))`` for a series with k retained orders).
In exact mode ``eps`` is 0, so a series is used only at exactly 0, where its
value is the exact limit.

Decision tolerances (is this singular value zero?) live here and nowhere else:
:class:`Tolerances` gives the two rank thresholds ``tau_lo`` and ``tau_hi`` of
each mode (the two-threshold rule), and :func:`decide_rank` returns a
rank *with its margin* or ``None`` (undecided).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import mpmath
import numpy as np
import sympy

__all__ = [
    "FLOAT",
    "Backend",
    "Margin",
    "Precision",
    "RankDecision",
    "DefinitenessDecision",
    "Tolerances",
    "backend_of",
    "characteristic_length",
    "decide_definiteness",
    "decide_rank",
    "exact_is_zero",
    "eigh",
    "eigsy",
    "float_drop_is_real",
    "lstsq",
    "max_abs",
    "norm",
    "numeric_precision",
    "order3_residual_rtol",
    "orthonormal_columns",
    "parse_precision",
    "rank_bounds",
    "rank_difference",
    "decide_nonzero",
    "rotation_orthonormal_atol",
    "pinv_truncated",
    "scale_screws",
    "screw_zero_rtol",
    "spectral_norm",
    "subspace_containment_atol",
    "subspace_rank_rtol",
    "singular_values",
    "svd",
    "svd_r",
    "to_float",
]

# ---------------------------------------------------------------------------
# Decision tolerances that are not rank thresholds.  Each is a *decision*
# (membership, identification, classification), so each lives here.
# ---------------------------------------------------------------------------

#: relative tolerance for "this screw lies in that subalgebra" / "these are equal"
#: decisions on float data, relative to the largest entry involved.
MEMBERSHIP_RTOL_FLOAT = 1e-9
#: norm below which a geometric vector given by a user (an axis, a normal) is
#: refused as near-zero (relative to the largest length of the mechanism or 1).
NEAR_ZERO_VECTOR = 1e-9
#: support threshold of a kernel vector (entries above 1e-9 of the largest)
SUPPORT_RTOL = 1e-9
#: two unit axes are parallel when the norm of their cross product is below this (a
#: product of subgroups turning about parallel axes with their own pitches)
PARALLEL_AXES_ATOL = 1e-9
#: closure acceptance in float mode, relative to the characteristic length L
#: (mp:N accepts at 10^(15-N) L, never looser than this)
CLOSURE_RTOL_FLOAT = 1e-12
#: fewest digits of mp:N: below 20, tau_lo = 10^(10-N) exceeds tau_hi = 10^(-N/2)
MP_MIN_DIGITS = 20
#: continuation stops when the smallest kept singular value of the closure
#: Jacobian in the unknown joints (relative to the largest) falls below this
#: before the target while the rank drops
CONTINUATION_SINGULAR_RTOL = 1e-6
#: a continuation step is rejected (and halved) when Newton's correction is
#: larger than this fraction of the predictor step: it may have jumped to
#: another assembly mode
CONTINUATION_CORRECTOR_RATIO = 0.5
#: below this relative smallest singular value (unknown joints) a step must be
#: reversible: stepping back must return within CONTINUATION_RETURN_RATIO of
#: the step to the previous point (near a fold two modes are close)
CONTINUATION_REVERSE_RTOL = 1e-2
CONTINUATION_RETURN_RATIO = 0.1
#: corrections and returns smaller than this (commensurate: radians, or
#: lengths / L) are rounding, never a jump between assembly modes
CONTINUATION_JUMP_FLOOR = 1e-9
#: a target continuation cannot step onto is tried directly (Newton from the last point
#: reached) when what is left is at most this (commensurate); it is accepted only at a
#: fold: the unknown joints' Jacobian there has relative smallest singular value below
#: CONTINUATION_SINGULAR_RTOL, and the landing moved them at most CONTINUATION_FOLD_REACH
#: times the square root of what was left (the two branches meet like a square root)
CONTINUATION_FOLD_GAP = 1e-4
CONTINUATION_FOLD_REACH = 10.0


#: mp:N polishes a closed configuration with Newton at N digits until its
#: residual is below 10^(POLISH_DIGITS_SPARE - N) L (working precision, with a
#: few digits spare for the rounding of poses), in at most POLISH_MAX_STEPS steps
POLISH_DIGITS_SPARE = 5
POLISH_MAX_STEPS = 24
#: a polish step that lowers the residual by less than this factor is slow (Newton at a
#: multiple root lowers it by 4): the doubled step is tried too
POLISH_SLOW_RATIO = 8
#: largest joint value accepted in a configuration: radians, or times the
#: characteristic length L for a length; larger is an absurd size (an angle of
#: 1e6 rad is 160 000 turns)
MAX_JOINT_VALUE = 1e6
#: continuation accepts intermediate steps at this residual (times L); the target
#: itself is accepted at the precision's closure tolerance
CONTINUATION_STEP_RTOL = 1e-9
#: a nearby configuration found by sampling or by following a branch counts as
#: closed at this residual (times L)
SAMPLE_CLOSURE_RTOL = 1e-10
#: a sample that lands closer to q than this fraction of its step is q itself
#: (Newton fell back): not a nearby configuration
SAMPLE_DISTINCT_RATIO = 0.1
#: a branch probe follows its tangent when the cosine between the tangent and
#: the displacement found is above this (a smooth branch through the point)
BRANCH_ALIGNMENT = 0.9
#: The tolerances of the higher-order (tangent-cone) tests are placed relative to
#: the mode's ``tau_hi`` (1e-9 in float, 10^(-N/2) at mp:N), so that they keep
#: their meaning at every precision (see :func:`subspace_rank_rtol`,
#: :func:`subspace_containment_atol`, :func:`order3_residual_rtol`):
#:
#: relative singular value below which a direction is dropped from a basis of a
#: subspace (bases of cone pieces, orthonormalised): tau_hi / 10 (float: 1e-10)
SUBSPACE_RANK_FACTOR = 0.1
#: two orthonormal bases span nested subspaces when the projection residual is
#: below 10 tau_hi (float: 1e-8)
SUBSPACE_CONTAINMENT_FACTOR = 10.0
#: the third-order condition holds on a direction when its residual, relative to
#: the size of its linear part, is below tau_hi (float: 1e-9)
ORDER3_RESIDUAL_FACTOR = 1.0
#: digits of the higher-order and input/output tests of an ``exact`` analysis:
#: the configuration and its screws are exact, the tests run at mp:50 (and say so)
EXACT_TEST_DIGITS = 50
#: the reference configuration has every joint at identity: reading a file refuses a
#: value listed there when it is farther than this from the identity (radians, rotation
#: entries, or lengths relative to the file's largest coordinate); nearer values are
#: decided by the analysis in its mode (to 1e-9 in float, 10^(-N/2) at mp:N, exactly)
REFERENCE_SCREEN_RTOL = 1e-6
#: a given rotation matrix must satisfy |R^T R - I| below this in float (and det R > 0);
#: at mp:N below 10^(-N/2), exactly in exact mode (:func:`rotation_orthonormal_atol`)
ROTATION_ORTHONORMAL_ATOL = 1e-9
#: batched scans (:mod:`mechsing.scanner`) decide "full rank" without an SVD when
#: the determinant bound on sigma_min / sigma_max is at least this many times
#: float's tau_hi (room for the SVD's own rounding, which is near eps)
SCAN_SCREEN_FACTOR = 10.0
#: rounding allowance of that bound, in units of (matrix size) x eps: the
#: determinant of J (or of its Gram matrix) is the exact one of a matrix within
#: this of J (backward error of LU), so the bound is lowered by as much
SCAN_ROUNDING_FACTOR = 16.0


#: auto re-decides at mp:50 a float rank decision whose largest dropped singular value
#: exceeds this many times float's own rounding of it (:func:`float_drop_is_real`).  A
#: computed singular value is off by at most the norm of the error in the matrix (Weyl):
#: the rounding of its entries, about eps |M|_F (recorded as the margin's ``rounding``),
#: plus the SVD's backward error and the roundings that built each entry (products of
#: exponentials, Jacobians, earlier float factorisations) -- this factor -- plus the
#: effect of a configuration closed only to a residual r: r / L |M|.  Singular values
#: that are exactly zero come out below 2 eps |M|_F on the examples and the
#: near-singular families, and up to about 5 eps |M|_F on matrices built from other
#: float factorisations (the legs' constraint wrenches); 10^-14 from a singularity the
#: deciding singular values of benchmarks/speed_accuracy.py's families are 5 to 20
#: eps |M|_F.  A drop above the bound is a singular value that float's thresholds call
#: zero but that float itself sees is not: auto re-decides the configuration at mp:50
#: when float found it singular (at a singular configuration a zero above the bound only
#: costs that second analysis; a regular one is never re-decided).
FLOAT_ROUNDING_FACTOR = 4.0

#: exact mode first evaluates a quantity to this many digits: clearly non-zero
#: there (above 10^-(EXACT_ZERO_DIGITS - 15) of its scale) it is not zero, and
#: only the rest is handed to sympy to prove it zero
EXACT_ZERO_DIGITS = 60


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

    def asarray(self, x: Any) -> np.ndarray:
        """Convert nested sequences / arrays / scalars to an array of this backend."""
        if self.dtype is np.float64 or self.dtype == np.float64:
            return np.asarray(to_float(x), dtype=np.float64)
        a = np.asarray(x, dtype=object)
        return _objfunc(self.convert, 1)(a) if a.size else a

    def zeros(self, shape: tuple[int, ...] | int) -> np.ndarray:
        if self.dtype == np.float64:
            return np.zeros(shape)
        out = np.empty(shape, dtype=object)
        out.fill(self.convert(0))
        return out

    def eye(self, n: int) -> np.ndarray:
        out = self.zeros((n, n))
        for i in range(n):
            out[i, i] = self.convert(1)
        return out

    def threshold(self, order: int) -> Any:
        """Switch point ``eps ** (1/(order+1))`` of a series whose first neglected
        term is of relative order ``order + 1`` (0 in exact mode)."""
        if self.name == "exact":
            return 0
        if self.name == "float":
            return float(self.eps) ** (1.0 / (order + 1))
        return self.eps ** (mpmath.mpf(1) / (order + 1))


def _mp_convert(x: Any) -> Any:
    if isinstance(x, mpmath.mpf | mpmath.mpc):
        return +x  # re-round at the current working precision
    if isinstance(x, sympy.Basic):
        return mpmath.mpf(sympy.N(x, mpmath.mp.dps + 5))
    if isinstance(x, bool | np.bool_):
        return mpmath.mpf(int(x))
    if isinstance(x, np.floating | np.integer):
        x = x.item()
    return mpmath.mpf(x)


def _exact_convert(x: Any) -> Any:
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


FLOAT = Backend(
    name="float",
    eps=float(np.finfo(np.float64).eps),
    dtype=np.float64,
    sin=np.sin,
    cos=np.cos,
    sqrt=np.sqrt,
    atan2=np.arctan2,
    convert=float,
    pi=math.pi,
)


def _mp_backend() -> Backend:
    # mpmath functions read the *current* working precision, so one backend
    # object serves every N; Precision.context() sets N.
    return Backend(
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


EXACT = Backend(
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


def backend_of(*arrays: Any) -> Backend:
    """The backend of the given arrays: exact if any holds a sympy number, else
    mp if any holds an mpmath number, else float.

    The mp backend works at the current ``mpmath.mp.dps`` (see
    :meth:`Precision.context`).
    """
    found = FLOAT
    for a in arrays:
        arr = np.asarray(a) if not isinstance(a, np.ndarray) else a
        if arr.dtype != object:
            continue
        for x in arr.flat:
            if isinstance(x, sympy.Basic):
                return EXACT
            if isinstance(x, mpmath.mpf | mpmath.mpc):
                found = _mp_backend()
                break
    return found


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
    if isinstance(v, sympy.Basic):
        return float(sympy.N(v, 20))
    if isinstance(v, str):
        return float(v)
    return float(v)


def screw_zero_rtol(bk: Backend) -> Any:
    """Relative tolerance for "this part of a screw / displacement is zero".

    1e-9 (:data:`MEMBERSHIP_RTOL_FLOAT`) in float, 10^(-N/2) at mp:N (the
    ``tau_hi`` of the mode), exactly 0 in exact mode.
    """
    if bk.name == "float":
        return MEMBERSHIP_RTOL_FLOAT
    if bk.name == "mp":
        return mpmath.mpf(10) ** (-(mpmath.mp.dps // 2))
    return 0


def rotation_orthonormal_atol(prec: Precision) -> Any:
    """Largest entry of ``R^T R - I`` for which a given 3x3 matrix is a rotation.

    :data:`ROTATION_ORTHONORMAL_ATOL` (1e-9) in float and auto, 10^(-N/2) at
    mp:N (the mode's ``tau_hi``, as for subgroup membership), 0 in exact mode.
    """
    if prec.mode == "mp":
        with prec.context():
            return screw_zero_rtol(prec.backend)
    if prec.mode == "exact":
        return 0
    return ROTATION_ORTHONORMAL_ATOL


# ---------------------------------------------------------------------------
# Precision policy and tolerances
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Tolerances:
    """The two rank thresholds of a precision mode, relative to sigma_max.

    A rank is ``r`` when ``sigma_r >= tau_hi`` and ``sigma_{r+1} <= tau_lo``
    (both relative to the largest singular value); a singular value strictly
    between the two leaves the rank undecided.
    """

    tau_lo: float
    tau_hi: float


@dataclass(frozen=True)
class Precision:
    """A precision mode: ``float``, ``mp`` with ``digits`` N, ``exact`` or ``auto``.

    ``auto`` decides in float and re-decides undecided verdicts at mp:50.
    """

    mode: str
    digits: int | None = None

    def __str__(self) -> str:
        return f"mp:{self.digits}" if self.mode == "mp" else self.mode

    @property
    def tolerances(self) -> Tolerances:
        if self.mode in ("float", "auto"):
            return Tolerances(1e-12, 1e-9)
        if self.mode == "mp":
            n = self.digits or 50
            return Tolerances(10.0 ** (10 - n), 10.0 ** (-n / 2))
        return Tolerances(0.0, 0.0)

    @property
    def backend(self) -> Backend:
        if self.mode == "mp":
            with self.context():
                return _mp_backend()
        if self.mode == "exact":
            return EXACT
        return FLOAT

    @contextmanager
    def context(self) -> Iterator[None]:
        """Set mpmath's working precision to N digits for the block (no-op otherwise)."""
        if self.mode == "mp":
            with mpmath.workdps(self.digits or 50):
                yield
        else:
            yield

    def asarray(self, x: Any) -> np.ndarray:
        """Numbers of this mode from numbers, decimal strings or sympy numbers."""
        with self.context():
            return self.backend.asarray(x)

    def closure_tolerance(self, length_scale: float) -> Any:
        """Closure acceptance: 1e-12 L in float, 10^(15-N) L at mp:N, 0 exact.

        At mp:N an ``mpf`` (10^(15-N) underflows float beyond N = 323); compare it with
        residuals in the model's numbers (``KinematicModel.residual_norm(native=True)``).
        """
        if self.mode in ("float", "auto"):
            return CLOSURE_RTOL_FLOAT * length_scale
        if self.mode == "mp":
            # never looser than float's: more digits must not accept what float refuses
            n = self.digits or 50
            if 15 - n >= math.log10(CLOSURE_RTOL_FLOAT):
                return CLOSURE_RTOL_FLOAT * length_scale
            with mpmath.workdps(max(n, 15)):
                return mpmath.mpf(10) ** (15 - n) * length_scale
        return 0.0


def parse_precision(text: str) -> Precision:
    """Parse ``float``, ``mp:N`` (20 <= N <= 10000), ``exact`` or ``auto``.

    N starts at 20: below it the two thresholds cross (``tau_lo = 10^(10-N)``
    exceeds ``tau_hi = 10^(-N/2)``), so no rank could be decided consistently.

    Raises
    ------
    ValueError
        with a message that says what is accepted.
    """
    t = text.strip().lower()
    if t in ("float", "exact", "auto"):
        return Precision(t)
    if t.startswith("mp:"):
        try:
            n = int(t[3:])
        except ValueError:
            n = -1
        if MP_MIN_DIGITS <= n <= 10000:
            return Precision("mp", n)
    raise ValueError(
        f"precision {text!r} is not one of auto, float, mp:N ({MP_MIN_DIGITS} <= N <= 10000) "
        "or exact (below 20 digits the two rank thresholds of mp:N cross)"
    )


def numeric_precision(prec: Precision) -> Precision:
    """The precision at which the numerical tests of an analysis run.

    The higher-order forms of the tangent cone and the input/output ranks are
    computed and decided at the analysis precision when it is numerical
    (``float``, ``mp:N``; an ``auto`` stage is float, or mp:50 after
    escalation); an ``exact`` analysis evaluates them at
    mp::data:`EXACT_TEST_DIGITS` from its exact configuration.
    """
    if prec.mode == "exact":
        return Precision("mp", EXACT_TEST_DIGITS)
    if prec.mode == "auto":
        return Precision("float")
    return prec


def subspace_rank_rtol(prec: Precision) -> float:
    """Relative singular value below which a direction is dropped from a basis of
    a cone piece: :data:`SUBSPACE_RANK_FACTOR` tau_hi (1e-10 in float)."""
    return SUBSPACE_RANK_FACTOR * prec.tolerances.tau_hi


def subspace_containment_atol(prec: Precision) -> float:
    """Projection residual below which an orthonormal basis lies in another's span:
    :data:`SUBSPACE_CONTAINMENT_FACTOR` tau_hi (1e-8 in float)."""
    return SUBSPACE_CONTAINMENT_FACTOR * prec.tolerances.tau_hi


def order3_residual_rtol(prec: Precision) -> float:
    """Relative residual below which a direction extends to third order:
    :data:`ORDER3_RESIDUAL_FACTOR` tau_hi (1e-9 in float)."""
    return ORDER3_RESIDUAL_FACTOR * prec.tolerances.tau_hi


# ---------------------------------------------------------------------------
# Characteristic length and scaling (the commensurate metric)
# ---------------------------------------------------------------------------


def characteristic_length(points: Any, override: float | None = None) -> tuple[float, np.ndarray]:
    """Characteristic length L and centroid c of the joints' axis points.

    Parameters
    ----------
    points : array_like, shape (n, 3)
        For each joint, the point of its axis nearest the origin (foot of the
        perpendicular for R, H, C; centre for S and U).  Joints without a point
        (P, T2, T3, G, Y, X, D) are simply not listed.
    override : float, optional
        The file's ``characteristic_length``.

    Returns
    -------
    L : float
        RMS distance of the points from their centroid; ``|c|`` if that is 0;
        1 if that is 0 too.
    c : ndarray, shape (3,)
        The centroid (zeros when there are no points).
    """
    pts = np.asarray(to_float(points), dtype=float).reshape(-1, 3)
    c = pts.mean(axis=0) if len(pts) else np.zeros(3)
    if override is not None:
        return float(override), c
    rms = float(np.sqrt(np.mean(np.sum((pts - c) ** 2, axis=1)))) if len(pts) else 0.0
    if rms > 0:
        return rms, c
    nc = float(np.linalg.norm(c))
    if nc > 0:
        return nc, c
    return 1.0, c


def scale_screws(
    S: np.ndarray, length_scale: Any, centroid: Any = None, length_columns: Any = None
) -> np.ndarray:
    """Make screws commensurate before a rank decision.

    Moves each screw (a *column* of ``S``, layout (omega, v)) to the centroid
    c (``v -> v - c x omega``, i.e. Ad of the translation by -c), divides the
    v rows by L and multiplies the columns flagged in ``length_columns`` (joint
    coordinates that are lengths: P, slides, translations) by L.

    Works on every backend (plain numpy arithmetic).
    """
    S = np.array(S, copy=True)
    if centroid is not None:
        c = np.asarray(centroid)
        w = S[..., 0:3, :]
        # v - c x w, columnwise
        cx = np.stack(
            [
                w[..., 2, :] * c[1] - w[..., 1, :] * c[2],
                w[..., 0, :] * c[2] - w[..., 2, :] * c[0],
                w[..., 1, :] * c[0] - w[..., 0, :] * c[1],
            ],
            axis=-2,
        )
        S[..., 3:6, :] = S[..., 3:6, :] - cx
    S[..., 3:6, :] = S[..., 3:6, :] / length_scale
    if length_columns is not None:
        mask = np.asarray(length_columns, dtype=bool)
        S[..., :, mask] = S[..., :, mask] * length_scale
    return S


# ---------------------------------------------------------------------------
# Linear algebra on the numerical backends (float: numpy; mp: mpmath at the
# working precision, so call these inside ``Precision.context()``).  Exact
# arrays are decided by decide_rank / decide_definiteness, not factorised.
# ---------------------------------------------------------------------------


def _numerical_backend(*arrays: Any) -> Backend:
    bk = backend_of(*arrays)
    if bk.name == "exact":
        raise TypeError("exact arrays have no numerical factorisation; convert them to mp first")
    return bk


def _object_array(M: Any, shape: tuple[int, ...]) -> np.ndarray:
    out = np.empty(shape, dtype=object)
    rows = M.tolist()
    for i in range(shape[0]):
        for j in range(shape[1]):
            out[i, j] = rows[i][j]
    return out


def _mp_matrix(arr: np.ndarray) -> Any:
    """An ``mpmath.matrix`` of a 2-d array, entries rounded to the working precision."""
    return mpmath.matrix([[_mp_convert(x) for x in row] for row in arr.tolist()])


#: most sweeps of the one-sided Jacobi SVD (it converges quadratically: about ten
#: sweeps reach 50 digits; the bound only guards against a pathological matrix)
_JACOBI_MAX_SWEEPS = 100
#: extra digits of the second attempt of mpmath's SVD
_SVD_RETRY_DIGITS = 10


def svd_r(A: Any, full_matrices: bool = False, compute_uv: bool = True) -> Any:
    """``mpmath.svd_r`` that always converges (same arguments and results).

    mpmath's Golub-Reinsch iteration declares a bidiagonal entry negligible only when
    adding it to the matrix norm does not change the norm (less than half an ulp).  With a
    repeated singular value (repeated rows, as stacked wrench systems often have) the
    implicit-shift QR step can leave that entry at about half an ulp of the norm, flipping
    its sign at every step, and mpmath gives up with ``RuntimeError: svd: no convergence``
    at some working precisions and not at others.  Then this tries again with a few more
    digits (which moves the last bits), and failing that computes the SVD by one-sided
    (Hestenes) Jacobi rotations, whose stopping test is relative (two columns are
    orthogonal when their inner product is below ``m eps`` times their norms): it always
    converges, and to high relative accuracy.
    """
    try:
        return mpmath.svd_r(A, full_matrices=full_matrices, compute_uv=compute_uv)
    except (RuntimeError, ZeroDivisionError):
        pass
    # the stall depends on the last bits: a few more digits usually break it (cheap) ...
    try:
        with mpmath.workdps(mpmath.mp.dps + _SVD_RETRY_DIGITS):
            out = mpmath.svd_r(A, full_matrices=full_matrices, compute_uv=compute_uv)
        return (+out) if not compute_uv else tuple(+x for x in out)
    except (RuntimeError, ZeroDivisionError):
        pass
    # ... and Jacobi always converges
    return _jacobi_svd(A, full_matrices, compute_uv)


def _dot(a: list[Any], b: list[Any]) -> Any:
    return mpmath.fdot(a, b)


def _jacobi_svd(A: Any, full_matrices: bool, compute_uv: bool) -> Any:
    """SVD by one-sided Jacobi rotations at the working precision, in the layout of
    ``mpmath.svd_r`` (``A = U diag(S) V``, singular values descending)."""
    m, n = A.rows, A.cols
    rows = [[A[i, j] for j in range(n)] for i in range(m)]
    # orthogonalise the columns of B = A (m >= n) or of B = A^T (m < n): k columns of length p
    transpose = m < n
    cols = (
        [list(r) for r in rows] if transpose else [[rows[i][j] for i in range(m)] for j in range(n)]
    )
    k, p = len(cols), (n if transpose else m)
    zero, one = mpmath.mpf(0), mpmath.mpf(1)
    W = [[one if i == j else zero for i in range(k)] for j in range(k)]  # columns of W
    tol = mpmath.mp.eps * p
    for _sweep in range(_JACOBI_MAX_SWEEPS):
        rotated = False
        for i in range(k - 1):
            for j in range(i + 1, k):
                a, b = cols[i], cols[j]
                gamma = _dot(a, b)
                if not gamma:
                    continue
                alpha, beta = _dot(a, a), _dot(b, b)
                if abs(gamma) <= tol * mpmath.sqrt(alpha * beta):
                    continue
                rotated = True
                zeta = (beta - alpha) / (2 * gamma)
                t = (1 if zeta >= 0 else -1) / (abs(zeta) + mpmath.sqrt(1 + zeta * zeta))
                c = 1 / mpmath.sqrt(1 + t * t)
                s = c * t
                cols[i] = [c * x - s * y for x, y in zip(a, b, strict=True)]
                cols[j] = [s * x + c * y for x, y in zip(a, b, strict=True)]
                wa, wb = W[i], W[j]
                W[i] = [c * x - s * y for x, y in zip(wa, wb, strict=True)]
                W[j] = [s * x + c * y for x, y in zip(wa, wb, strict=True)]
        if not rotated:
            break
    sig = [mpmath.sqrt(_dot(col, col)) for col in cols]
    order = sorted(range(k), key=lambda j: -sig[j])
    S = mpmath.matrix(k, 1)
    for r, j in enumerate(order):
        S[r] = sig[j]
    if not compute_uv:
        return S
    # B = Q diag(sig) W^T with Q's columns cols[j] / sig[j]; columns of (numerical) zero
    # singular values and the missing ones are completed to an orthonormal basis
    smax = sig[order[0]] if k else zero
    Q = [[x / sig[j] for x in cols[j]] for j in order if sig[j] > tol * smax and sig[j] > 0]
    Q = _complete_orthonormal(Q, p, p if (full_matrices or not transpose) else k)
    Wt = [W[j] for j in order]  # rows: right singular vectors of B
    if transpose:
        # A = B^T = W diag(sig) Q^T: U = W (m x m), V = Q^T (k' x n)
        U = mpmath.matrix([[Wt[c][r] for c in range(k)] for r in range(k)])
        V = mpmath.matrix(Q if full_matrices else Q[:k])
        return U, S, V
    # A = B = Q diag(sig) W^T: U = Q (m x m or m x n), V = W^T (n x n)
    U = mpmath.matrix([[Q[c][r] for c in range(len(Q) if full_matrices else k)] for r in range(p)])
    V = mpmath.matrix(Wt)
    return U, S, V


def _complete_orthonormal(Q: list[list[Any]], p: int, count: int) -> list[list[Any]]:
    """``count`` orthonormal vectors of length p: those of Q (orthonormal), then the
    coordinate vector least in their span, orthogonalised against them (Gram-Schmidt twice),
    and so on."""
    Q = [list(q) for q in Q]
    while len(Q) < count:
        # |e - P e|^2 = 1 - sum_q q[e]^2 for the coordinate vector e
        e = max(range(p), key=lambda i: (1 - mpmath.fsum(q[i] * q[i] for q in Q), -i))
        v = [mpmath.mpf(1) if i == e else mpmath.mpf(0) for i in range(p)]
        for _pass in range(2):
            for q in Q:
                d = _dot(q, v)
                v = [x - d * y for x, y in zip(v, q, strict=True)]
        nv = mpmath.sqrt(_dot(v, v))
        Q.append([x / nv for x in v])
    return Q[:count]


def eigsy(A: Any, eigvals_only: bool = False) -> Any:
    """``mpmath.eigsy`` that always converges (same arguments and results): when the QL
    iteration gives up, the cyclic Jacobi eigenvalue method (each rotation removes an
    off-diagonal pair, so the off-diagonal mass decreases until it is below ``eps`` of the
    matrix's norm)."""
    try:
        return mpmath.eigsy(A, eigvals_only=eigvals_only)
    except (RuntimeError, ZeroDivisionError):
        return _jacobi_eigsy(A, eigvals_only)


def _jacobi_eigsy(A: Any, eigvals_only: bool) -> Any:
    n = A.rows
    a = [[A[i, j] for j in range(n)] for i in range(n)]
    zero, one = mpmath.mpf(0), mpmath.mpf(1)
    V = [[one if i == j else zero for j in range(n)] for i in range(n)]
    fro = mpmath.sqrt(mpmath.fsum(x * x for row in a for x in row))
    for _sweep in range(_JACOBI_MAX_SWEEPS):
        off = mpmath.sqrt(mpmath.fsum(a[i][j] ** 2 for i in range(n) for j in range(n) if i != j))
        if off <= mpmath.mp.eps * fro:
            break
        for p in range(n - 1):
            for q in range(p + 1, n):
                apq = a[p][q]
                if abs(apq) <= mpmath.mp.eps * fro / n:
                    continue
                theta = (a[q][q] - a[p][p]) / (2 * apq)
                t = (1 if theta >= 0 else -1) / (abs(theta) + mpmath.sqrt(theta * theta + 1))
                c = 1 / mpmath.sqrt(t * t + 1)
                s = t * c
                for k in range(n):  # columns p, q
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(n):  # rows p, q
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
                a[p][q] = a[q][p] = zero
                for k in range(n):
                    vkp, vkq = V[k][p], V[k][q]
                    V[k][p], V[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    order = sorted(range(n), key=lambda i: a[i][i])
    E = mpmath.matrix(n, 1)
    for r, i in enumerate(order):
        E[r] = a[i][i]
    if eigvals_only:
        return E
    return E, mpmath.matrix([[V[k][i] for i in order] for k in range(n)])


def svd(A: Any, full_matrices: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``A = U diag(s) Vt`` in the backend of ``A``, singular values descending.

    float: :func:`numpy.linalg.svd`; mp: :func:`svd_r` (mpmath's, with a Jacobi fallback)
    at the working precision, object arrays of ``mpf``.
    """
    arr = np.asarray(A)
    bk = _numerical_backend(arr)
    if bk.name == "float":
        return np.linalg.svd(to_float(arr), full_matrices=full_matrices)
    m, n = arr.shape
    k = min(m, n)
    if k == 0:
        U = bk.eye(m) if full_matrices else bk.zeros((m, 0))
        Vt = bk.eye(n) if full_matrices else bk.zeros((0, n))
        return U, bk.zeros(0), Vt
    Um, S, Vm = svd_r(_mp_matrix(arr), full_matrices=full_matrices)
    s = [S[i] for i in range(k)]
    order = sorted(range(k), key=lambda i: -s[i])
    U = _object_array(Um, (Um.rows, Um.cols))
    Vt = _object_array(Vm, (Vm.rows, Vm.cols))
    if order != list(range(k)):
        U = U[:, order + list(range(k, U.shape[1]))]
        Vt = Vt[order + list(range(k, Vt.shape[0]))]
    sv = np.empty(k, dtype=object)
    sv[:] = [s[i] for i in order]
    return U, sv, Vt


def singular_values(A: Any) -> list[Any]:
    """Singular values (descending) of an mp array or matrix, at the working precision."""
    M = A if isinstance(A, mpmath.matrix) else _mp_matrix(np.asarray(A))
    sig = svd_r(M, compute_uv=False)
    return sorted((abs(sig[i]) for i in range(len(sig))), reverse=True)


def eigh(A: Any) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues (ascending) and orthonormal eigenvectors (columns) of the
    symmetric part of ``A``, in its backend (numpy ``eigh`` / :func:`eigsy`)."""
    arr = np.asarray(A)
    bk = _numerical_backend(arr)
    if bk.name == "float":
        F = to_float(arr)
        return np.linalg.eigh((F + F.T) / 2)
    n = arr.shape[0]
    if n == 0:
        return bk.zeros(0), bk.zeros((0, 0))
    S = _mp_matrix(arr)
    E, Q = eigsy((S + S.T) / 2)
    w = [E[i] for i in range(n)]
    order = sorted(range(n), key=lambda i: w[i])
    V = _object_array(Q, (n, n))[:, order]
    wv = np.empty(n, dtype=object)
    wv[:] = [w[i] for i in order]
    return wv, V


def orthonormal_columns(A: Any) -> np.ndarray:
    """Q of the thin QR decomposition of ``A`` (m x k, k <= m): an orthonormal
    basis of its columns' span when they are independent (numpy / mpmath QR)."""
    arr = np.asarray(A)
    bk = _numerical_backend(arr)
    if bk.name == "float":
        Q, _ = np.linalg.qr(to_float(arr))
        return Q
    m, k = arr.shape
    if k == 0:
        return bk.zeros((m, 0))
    Q, _ = mpmath.qr(_mp_matrix(arr))
    return _object_array(Q, (m, m))[:, :k]


def norm(A: Any) -> Any:
    """Euclidean norm of a vector, Frobenius norm of a matrix, in its backend."""
    arr = np.asarray(A)
    bk = _numerical_backend(arr)
    if bk.name == "float":
        return np.linalg.norm(to_float(arr))
    return mpmath.sqrt(mpmath.fsum(x * x for x in arr.flat))


def spectral_norm(A: Any) -> Any:
    """Largest singular value (0 for an empty matrix), in the array's backend."""
    arr = np.asarray(A)
    if arr.size == 0:
        return 0.0
    bk = _numerical_backend(arr)
    if bk.name == "float":
        return float(np.linalg.norm(to_float(arr), 2))
    return singular_values(arr)[0]


def max_abs(A: Any) -> Any:
    """Largest |entry| (0 for an empty array), in the array's backend."""
    arr = np.asarray(A)
    if arr.size == 0:
        return 0.0
    return np.max(np.abs(arr))


def lstsq(A: Any, b: Any) -> np.ndarray:
    """Minimum-norm least-squares solution of ``A x = b``; singular values below
    ``eps max(m, n)`` of the largest are dropped (numpy's ``rcond=None``)."""
    arr = np.asarray(A)
    bk = _numerical_backend(arr, b)
    if bk.name == "float":
        return np.linalg.lstsq(to_float(arr), to_float(b), rcond=None)[0]
    U, s, Vt = svd(arr, full_matrices=False)
    if len(s) == 0:
        return bk.zeros(arr.shape[1])
    cut = bk.eps * max(arr.shape) * s[0]
    keep = [i for i in range(len(s)) if s[i] > cut]
    c = np.array([(U[:, i] @ b) / s[i] for i in keep], dtype=object)
    return Vt[keep].T @ c if keep else bk.zeros(arr.shape[1])


def pinv_truncated(U: np.ndarray, s: np.ndarray, Vt: np.ndarray, r: int) -> np.ndarray:
    """Pseudo-inverse of the rank-``r`` truncation of ``U diag(s) Vt`` (any backend)."""
    return (Vt[:r].T / s[:r][None, :]) @ U[:, :r].T


# ---------------------------------------------------------------------------
# Rank and definiteness decisions with margins
# ---------------------------------------------------------------------------


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

    def to_json(self) -> dict[str, Any]:
        d: dict[str, Any] = {
            "kept": self.kept,
            "dropped": self.dropped,
            "tau_lo": self.tau_lo,
            "tau_hi": self.tau_hi,
            "length_scale": self.length_scale,
        }
        if self.sigma_max is not None:
            d["sigma_max"] = self.sigma_max
        if self.rounding is not None:
            d["rounding"] = self.rounding
        if self.eig_margin is not None:
            d["eig_margin"] = self.eig_margin
        return d


@dataclass(frozen=True)
class RankDecision:
    """A rank with its evidence.

    ``rank`` is None when undecided; ``rank_bounds`` then gives (lowest, highest)
    consistent ranks.  ``sigma`` are all singular values (absolute, in the
    scaled metric), largest first; ``null_space`` is an orthonormal basis of
    the (right) kernel (columns), ``range_space`` of the range and
    ``left_null_space`` of its orthogonal complement, when requested: float
    arrays, or the mode's own numbers with ``native_spaces`` at mp:N.
    """

    rank: int | None
    sigma: tuple[float, ...] | None
    margin: Margin
    precision: str
    rank_bounds: tuple[int, int] = (0, 0)
    null_space: np.ndarray | None = field(default=None, compare=False, repr=False)
    range_space: np.ndarray | None = field(default=None, compare=False, repr=False)
    left_null_space: np.ndarray | None = field(default=None, compare=False, repr=False)

    @property
    def decided(self) -> bool:
        return self.rank is not None

    def record(self, test: str, generic: int | None = None) -> dict[str, Any]:
        """This decision as an entry of a configuration's ``decisions`` (JSON): the test
        (``closure``, ``loop A-B-C-D``, ``output chain``, ``leg k chain``, ``input``,
        ``output``, ``impossible-input``, ``impossible-output``, ``constraint``), its
        rank (with ``rank_bounds`` when undecided), the ``generic`` value it is measured
        against where there is one, its margin and the precision that decided it."""
        d: dict[str, Any] = {"test": test, "rank": self.rank}
        if self.rank is None:
            d["rank_bounds"] = list(self.rank_bounds)
        if generic is not None:
            d["generic"] = generic
        d["margin"] = self.margin.to_json()
        d["precision"] = self.precision
        return d


def decide_nonzero(value: Any, prec: Precision) -> bool | None:
    """Is a relative (dimensionless, at most about 1) quantity non-zero?  The
    two-threshold rule of a rank on one value: True at or above ``tau_hi``, False at
    or below ``tau_lo``, None between (undecided); exactly in exact mode."""
    if prec.mode == "exact":
        return bool(sympy.simplify(value) != 0)
    t = prec.tolerances
    a = abs(float(to_float(value)))
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
    return RankDecision(rank, None, min(a.margin, b.margin, key=_slack), a.precision, (lo, hi))


def _slack(m: Margin) -> float:
    """How far a margin is from flipping its decision: the smaller of the kept value's
    ratio to tau_hi and tau_lo's ratio to the dropped value (relative to sigma_max);
    exact margins (no thresholds) never flip."""
    if not m.tau_hi or not m.sigma_max:
        return math.inf
    out = math.inf
    if m.kept is not None:
        out = min(out, m.kept / m.sigma_max / m.tau_hi)
    if m.dropped is not None:
        out = min(out, m.tau_lo / max(m.dropped / m.sigma_max, 1e-300))
    return out


def rank_bounds(rel: Any, tol: Tolerances) -> tuple[np.ndarray, np.ndarray]:
    """The two-threshold rank rule on singular values
    relative to the largest, batched over leading axes: (lowest, highest) rank
    consistent with them, i.e. the counts ``sigma >= tau_hi`` and ``sigma > tau_lo``.
    The rank is decided when the two agree."""
    r = np.asarray(rel, dtype=float)
    return np.count_nonzero(r >= tol.tau_hi, axis=-1), np.count_nonzero(r > tol.tau_lo, axis=-1)


def _split_rank(rel: list[float], tol: Tolerances) -> tuple[int | None, tuple[int, int]]:
    lo_rank, hi_rank = (int(x) for x in rank_bounds(rel, tol))
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
    arr = np.asarray(M)
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
            rel = [float(x / smax) if smax else 0.0 for x in s]
            sigma = tuple(float(x) for x in s)
    else:
        F = to_float(arr)
        s_np = np.linalg.svd(F, compute_uv=False)
        smax = float(s_np[0]) if len(s_np) else 0.0
        if reference is not None and reference > smax:
            smax = float(reference)
        rel = [float(x / smax) if smax > 0 else 0.0 for x in s_np]
        sigma = tuple(float(x) for x in s_np)
        # the entries' rounding: of F itself, or of the factors of a product decided
        # against the norm of its first factor (``reference``)
        rounding = FLOAT.eps * max(float(np.linalg.norm(F)), float(reference or 0.0))
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
            Um, _s, Vm = np.linalg.svd(to_float(arr))
        elif not native_spaces:
            Um, Vm = to_float(Um), to_float(Vm)
        ns = Vm[k:].T.copy()
        rs = Um[:, :k].copy()
        ls = Um[:, k:]
    return RankDecision(rank, sigma, margin, str(prec), bounds, ns, rs, ls)


def float_drop_is_real(margin: Margin | dict[str, Any], data_error: float = 0.0) -> bool:
    """Did a float rank decision drop a singular value that float itself sees is not zero?

    True when the largest dropped singular value exceeds :data:`FLOAT_ROUNDING_FACTOR`
    times ``rounding + data_error * sigma_max``: ``rounding`` is the margin's (eps |M|_F),
    ``data_error`` the relative error of the configuration the matrix was built at (its
    closure residual divided by the characteristic length).  Such a drop is decided by the
    two thresholds but not by the data: ``auto`` re-decides it at mp:50, as it does an
    undecided rank.  False for mp and exact decisions, and when nothing was dropped.
    ``margin`` is a :class:`Margin` or its JSON (a decision record's ``margin``).
    """
    m = margin.to_json() if isinstance(margin, Margin) else margin
    rounding, dropped, smax = m.get("rounding"), m.get("dropped"), m.get("sigma_max")
    if rounding is None or dropped is None or not smax:
        return False
    return dropped > FLOAT_ROUNDING_FACTOR * (rounding + data_error * smax)


def _exact_rank(
    arr: np.ndarray, prec: Precision, tol: Tolerances, length_scale: float, want_spaces: bool
) -> RankDecision:
    M = sympy.Matrix(arr.tolist()).applyfunc(
        lambda x: sympy.nsimplify(x) if isinstance(x, float) else x
    )
    E, pivots = M.echelon_form(with_pivots=True, simplify=True)
    rank = len(pivots)
    piv_vals = []
    for row, col in enumerate(pivots):
        piv_vals.append(abs(float(sympy.N(E[row, col], 30))))
    kept = min(piv_vals) if piv_vals else None
    dropped = None if rank == min(M.shape) else 0.0
    ns = rs = None
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
    return RankDecision(
        rank, None, Margin(kept, dropped, 0.0, 0.0, length_scale), "exact", (rank, rank), ns, rs
    )


def _orthonormal(A: np.ndarray) -> np.ndarray:
    q, _ = np.linalg.qr(A)
    return q[:, : A.shape[1]]


@dataclass(frozen=True)
class DefinitenessDecision:
    """Sign pattern of a symmetric form: ``kind`` is ``"definite"``, ``"indefinite"``,
    ``"semidefinite"`` (a zero eigenvalue, no sign change), ``"zero"`` or ``None``
    (undecided).  ``eig_margin`` is the smallest decided |eigenvalue| relative to
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
    (default: the largest |eigenvalue|).  An eigenvalue between the two
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
            vals = sorted(float(x) for x in ev)
    else:
        F = to_float(arr)
        vals = sorted(float(x) for x in np.linalg.eigvalsh((F + F.T) / 2))
    ref = scale if scale else max((abs(v) for v in vals), default=0.0)
    if ref == 0:
        return DefinitenessDecision("zero", tuple(vals), None, 0, 0, n)
    rel = [v / ref for v in vals]
    if any(tol.tau_lo < abs(r) < tol.tau_hi for r in rel):
        return DefinitenessDecision(None, tuple(vals), None, 0, 0, 0)
    npos = sum(1 for r in rel if r >= tol.tau_hi)
    nneg = sum(1 for r in rel if r <= -tol.tau_hi)
    nz = n - npos - nneg
    decided = [abs(r) for r in rel if abs(r) >= tol.tau_hi]
    eig_margin = min(decided) if decided else None
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
