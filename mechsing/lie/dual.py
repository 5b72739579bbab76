"""Dual numbers, dual vectors (screws), unit dual quaternions and the dual rank.

Conventions
-----------
* A **dual number** is ``a + eps b`` with ``eps^2 = 0``: :class:`Dual` holds the
  primal part ``a`` and the dual part ``b`` as two arrays of the same shape
  (batched over any axes; any backend of :mod:`mechsing.numeric`).
* A **screw** ``xi = (omega, v)`` (shape (..., 6), angular first) is the dual
  vector ``omega + eps v`` (:func:`screw_to_dual`).  A length unit change
  ``v -> v / L`` is the ring automorphism ``eps -> eps / L``.  The dual cross
  product is the Lie bracket, and the dual part of the dual dot product is
  the Klein form: ``dual_dot(X, Y) = w1.w2 + eps (w1.v2 + w2.v1)``.
* A **line** is given by Plücker coordinates ``(u, m)``, ``m = N x u`` for a
  point N on it (the layout of a zero-pitch twist).  Functions taking a line
  accept any screw with ``u != 0`` and use its axis (the pitch part of m is
  removed) and accept any non-zero length of u.
* A **unit dual quaternion** is a :class:`Dual` of two quaternions (..., 4),
  layout (w, x, y, z) as in :mod:`mechsing.lie.quaternion`:
  ``Q = r + eps d`` with ``r`` the unit quaternion of R and ``d = (0, p) r / 2``
  for the displacement ``x -> R x + p``.  ``Q`` and ``-Q`` are the same
  displacement; :func:`dual_quat_from_displacement` picks ``r`` as
  :func:`mechsing.lie.quaternion.quat_from_rotation_matrix` does (w >= 0).
* The **dual matrix** of a displacement is ``R + eps p^ R`` (the blocks of
  ``Ad(g)``); it maps lines ``u + eps m`` to their images.

References: the length-scale problem item 3 (dual-number rank), Chevallier's dual-number approach (Chevallier 1991,
screws as a module over the dual numbers; Hao 1998), the invariant forms of se(3) (Klein form
``K = -d sin(alpha)`` of two lines); J. M. McCarthy, *Introduction to
Theoretical Kinematics*, MIT Press 1990 (dual angle, dual Rodrigues formula,
transference principle).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.lie._se3 import ANGULAR, LINEAR
from mechsing.lie._so3 import _asarr as _arr
from mechsing.lie._so3 import _mask, cross, hat3, vee3
from mechsing.lie._so3 import dot as _dot
from mechsing.lie.quaternion import (
    quat_conjugate,
    quat_from_rotation_matrix,
    quat_multiply,
    quat_to_rotation_matrix,
)
from mechsing.numeric import Margin, Precision, backend_of, decide_rank, parse_precision

__all__ = [
    "Dual",
    "DualRank",
    "displacement_from_dual_matrix",
    "dual_angle",
    "dual_atan2",
    "dual_cos",
    "dual_cross",
    "dual_dot",
    "dual_matmul",
    "dual_matrix_from_displacement",
    "dual_quat_conjugate",
    "dual_quat_from_displacement",
    "dual_quat_multiply",
    "dual_quat_to_displacement",
    "dual_rank",
    "dual_rodrigues",
    "dual_sin",
    "dual_sqrt",
    "dual_to_screw",
    "screw_displacement",
    "screw_to_dual",
    "study_conjugate",
    "study_multiply",
]


def _to_backend(x: np.ndarray, bk: Any) -> np.ndarray:
    return bk.asarray(x)


# ---------------------------------------------------------------------------
# Dual numbers
# ---------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Dual:
    """A (batch of) dual number(s) ``a + eps b``, ``eps^2 = 0``.

    Both parts are converted to one backend (float, mp or exact: the richest
    of the two).  Arithmetic ``+ - * /`` works between dual numbers and with
    plain numbers or arrays; indexing ``X[...]`` indexes both parts, so a dual
    vector or matrix is a :class:`Dual` whose parts have trailing axes (3,) or
    (3, 3).  ``x / y`` raises ``ZeroDivisionError`` where the primal part of y
    is 0 (a pure dual number has no inverse).

    Parameters
    ----------
    a : array_like, shape S
        Primal part.
    b : array_like, shape S, default 0
        Dual part (broadcast to the shape of ``a``).
    """

    a: Any
    b: Any = 0

    __array_ufunc__ = None  # make ndarray (op) Dual defer to Dual's reflected operators

    def __post_init__(self) -> None:
        a = _arr(self.a)
        b = _arr(self.b)
        bk = backend_of(a, b)
        a = _to_backend(a, bk)
        b = _to_backend(b, bk)
        if a.shape != b.shape:
            shape = np.broadcast_shapes(a.shape, b.shape)
            a = np.broadcast_to(a, shape).copy()
            b = np.broadcast_to(b, shape).copy()
        object.__setattr__(self, "a", a)
        object.__setattr__(self, "b", b)

    @property
    def shape(self) -> tuple[int, ...]:
        return self.a.shape

    def __getitem__(self, idx: Any) -> Dual:
        return Dual(self.a[idx], self.b[idx])

    def __repr__(self) -> str:
        return f"Dual(a={self.a!r}, b={self.b!r})"

    def __neg__(self) -> Dual:
        return Dual(-self.a, -self.b)

    def __pos__(self) -> Dual:
        return self

    def __add__(self, other: Any) -> Dual:
        o = _as_dual(other, self)
        return Dual(self.a + o.a, self.b + o.b)

    __radd__ = __add__

    def __sub__(self, other: Any) -> Dual:
        o = _as_dual(other, self)
        return Dual(self.a - o.a, self.b - o.b)

    def __rsub__(self, other: Any) -> Dual:
        return _as_dual(other, self) - self

    def __mul__(self, other: Any) -> Dual:
        o = _as_dual(other, self)
        return Dual(self.a * o.a, self.a * o.b + self.b * o.a)

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> Dual:
        o = _as_dual(other, self)
        if np.any(_mask(o.a == 0)):
            raise ZeroDivisionError("dual division: the divisor has a zero primal part")
        return Dual(self.a / o.a, (self.b * o.a - self.a * o.b) / (o.a * o.a))

    def __rtruediv__(self, other: Any) -> Dual:
        return _as_dual(other, self) / self


def _as_dual(x: Any, like: Dual | None = None) -> Dual:
    """x as a Dual; a plain number or array takes the backend of ``like`` too
    (so ``1 + x`` stays exact when x is exact)."""
    if isinstance(x, Dual):
        return x
    arr = _arr(x)
    if like is not None:
        arr = _to_backend(arr, backend_of(like.a, like.b, arr))
    return Dual(arr, 0)


def dual_sqrt(x: Any) -> Dual:
    """``sqrt(a + eps b) = sqrt(a) + eps b / (2 sqrt(a))`` for ``a > 0``.

    ``sqrt(0) = 0``; ``a + eps b`` with ``a = 0``, ``b != 0`` has no square root
    (ValueError), nor has ``a < 0`` in this real setting.
    """
    x = _as_dual(x)
    bk = backend_of(x.a, x.b)
    if np.any(_mask(x.a < 0)) or np.any(_mask((x.a == 0) & _mask(x.b != 0))):
        raise ValueError("dual_sqrt: needs a > 0 (or a = b = 0) for a + eps b")
    zero = _mask(x.a == 0)
    s = bk.sqrt(x.a)
    return Dual(s, x.b / (2 * np.where(zero, bk.convert(1), s)))


def dual_sin(x: Any) -> Dual:
    """``sin(a + eps b) = sin a + eps b cos a``."""
    x = _as_dual(x)
    bk = backend_of(x.a, x.b)
    return Dual(bk.sin(x.a), x.b * bk.cos(x.a))


def dual_cos(x: Any) -> Dual:
    """``cos(a + eps b) = cos a - eps b sin a``."""
    x = _as_dual(x)
    bk = backend_of(x.a, x.b)
    return Dual(bk.cos(x.a), -x.b * bk.sin(x.a))


def dual_atan2(y: Any, x: Any) -> Dual:
    """``atan2(y, x) + eps (x_a y_b - y_a x_b) / (x_a^2 + y_a^2)``.

    Raises ``ValueError`` where both primal parts are 0.
    """
    y = _as_dual(y)
    x = _as_dual(x)
    bk = backend_of(x.a, x.b, y.a, y.b)
    r2 = x.a * x.a + y.a * y.a
    if np.any(_mask(r2 == 0)):
        raise ValueError("dual_atan2: undefined where both primal parts are 0")
    return Dual(bk.atan2(y.a, x.a), (x.a * y.b - y.a * x.b) / r2)


# ---------------------------------------------------------------------------
# Dual vectors and matrices
# ---------------------------------------------------------------------------


def screw_to_dual(xi: Any) -> Dual:
    """The dual vector ``omega + eps v`` of a screw ``(omega, v)``: (..., 6) -> Dual (..., 3)."""
    xi = _arr(xi)
    if xi.ndim < 1 or xi.shape[-1] != 6:
        raise ValueError(f"screw_to_dual: expected a screw of shape (..., 6), got {xi.shape}")
    return Dual(xi[..., ANGULAR], xi[..., LINEAR])


def dual_to_screw(X: Dual) -> np.ndarray:
    """The screw ``(omega, v)`` of a dual vector ``omega + eps v``: Dual (..., 3) -> (..., 6)."""
    return np.concatenate([X.a, X.b], axis=-1)


def dual_dot(X: Dual, Y: Dual) -> Dual:
    """Dual inner product over the last axis: ``a.c + eps (a.d + b.c)``.

    For screws, the primal part is ``w1.w2`` and the dual part the Klein form
    ``w1.v2 + w2.v1``; for unit lines it is ``cos(theta + eps d)``.
    """
    return Dual(_dot(X.a, Y.a), _dot(X.a, Y.b) + _dot(X.b, Y.a))


def dual_cross(X: Dual, Y: Dual) -> Dual:
    """Dual cross product: ``a x c + eps (a x d + b x c)``; on screws, the Lie bracket."""
    return Dual(cross(X.a, Y.a), cross(X.a, Y.b) + cross(X.b, Y.a))


def dual_matmul(A: Dual, B: Dual) -> Dual:
    """Dual matrix product with ``@`` semantics: ``A_a B_a + eps (A_a B_b + A_b B_a)``."""
    return Dual(A.a @ B.a, A.a @ B.b + A.b @ B.a)


def _unit_line(line: Any, name: str) -> tuple[np.ndarray, np.ndarray]:
    """(u, m) of the axis of a screw with |u| = 1 and u.m = 0."""
    L = _arr(line)
    if L.ndim < 1 or L.shape[-1] != 6:
        raise ValueError(f"{name}: expected a line (u, m) of shape (..., 6), got {L.shape}")
    bk = backend_of(L)
    u, m = L[..., ANGULAR], L[..., LINEAR]
    u2 = _dot(u, u)
    if np.any(_mask(u2 == 0)):
        raise ValueError(f"{name}: a line needs a non-zero direction u (got u = 0)")
    m = m - np.asarray(_dot(u, m) / u2)[..., None] * u
    n = bk.sqrt(u2)[..., None]
    return u / n, m / n


def dual_angle(line1: Any, line2: Any) -> Dual:
    """Dual angle ``theta + eps d`` between two lines: (..., 6), (..., 6) -> Dual (...).

    Conventions: with ``n = u1 x u2 / |u1 x u2|`` (the common normal),
    ``theta`` in [0, pi] is the angle from u1 to u2, right-handed about n, and
    ``d = (p2 - p1) . n`` is the signed distance along n from line 1 to line 2
    (p1, p2 any points of the lines).  Then ``u1 . u2 + eps (u1.m2 + m1.u2) =
    cos(theta + eps d) |u1| |u2|``, i.e. the Klein form of the unit lines is
    ``-d sin(theta)`` (the invariant forms of se(3)).  The dual angle is symmetric in the two
    lines.  Intersecting lines: ``d = 0``.  Parallel or antiparallel lines
    (``u1 x u2 = 0`` exactly; theta = 0 or pi): the common normal is not
    unique and ``d >= 0`` is their distance.  Near-parallel lines have an
    ill-conditioned common normal (d jumps as they become parallel).

    Any screw with ``u != 0`` is accepted; its axis is used (pitch removed),
    and the length of u does not matter.
    """
    u1, m1 = _unit_line(line1, "dual_angle")
    u2, m2 = _unit_line(line2, "dual_angle")
    bk = backend_of(u1, m1, u2, m2)
    c = _dot(u1, u2)
    cp = cross(u1, u2)
    s2 = _dot(cp, cp)
    c1 = _dot(u1, m2) + _dot(m1, u2)  # = -d sin(theta)
    cd = cross(u1, m2) + cross(m1, u2)
    par = _mask(s2 <= 0)
    one = bk.convert(1)
    s = bk.sqrt(s2)
    s_safe = np.where(par, one, s)
    s1 = _dot(cp, cd) / s_safe  # = d cos(theta) (dual part of |u1^ x u2^|)
    theta = bk.atan2(s, c)
    d_skew = c * s1 - s * c1  # unit lines: c^2 + s^2 = 1
    d_par = bk.sqrt(_dot(cd, cd))  # u2 = +-u1: |cd| = distance
    return Dual(theta, np.where(par, d_par, d_skew))


def dual_rodrigues(line: Any, angle: Dual) -> Dual:
    """Dual rotation matrix of a screw motion (generalized Rodrigues formula).

    ``R^ = I + sin(t^) U^ + (1 - cos(t^)) U^ U^`` with ``t^ = theta + eps d`` and
    ``U^ = hat(u) + eps hat(m)`` the skew dual matrix of the unit line
    ``u + eps m`` (the axis of ``line``, normalised).  The result
    ``R + eps p^ R`` is the dual matrix of the displacement rotating by theta
    (right-handed about u) about the line and sliding d along u
    (:func:`displacement_from_dual_matrix` gives it as 4x4).

    Parameters
    ----------
    line : array_like, shape (..., 6)
        Plücker coordinates (u, m) of the axis (any screw with u != 0).
    angle : Dual, shape (...)
        The dual angle ``theta + eps d``.

    Returns
    -------
    Dual, parts of shape (..., 3, 3)
    """
    u, m = _unit_line(line, "dual_rodrigues")
    angle = _as_dual(angle)
    bk = backend_of(u, m, angle.a, angle.b)
    U = Dual(hat3(u), hat3(m))
    U2 = dual_matmul(U, U)
    s = dual_sin(angle)[..., None, None]
    c = dual_cos(angle)[..., None, None]
    eye = Dual(bk.eye(3), bk.zeros((3, 3)))
    return eye + s * U + (1 - c) * U2


def dual_matrix_from_displacement(g: Any) -> Dual:
    """Dual matrix ``R + eps p^ R`` of a displacement: (..., 4, 4) -> Dual (..., 3, 3)."""
    g = _arr(g)
    R = g[..., :3, :3]
    return Dual(R, hat3(g[..., :3, 3]) @ R)


def displacement_from_dual_matrix(M: Dual) -> np.ndarray:
    """Displacement (4x4) of a dual rotation matrix ``R + eps p^ R``: p = vee(P R^T)."""
    R = M.a
    bk = backend_of(M.a, M.b)
    p = vee3(M.b @ np.swapaxes(R, -1, -2))
    return _pose(bk, R, p)


def screw_displacement(line: Any, angle: Dual) -> np.ndarray:
    """Displacement (..., 4, 4) rotating by theta about ``line`` and sliding d along it.

    ``angle = theta + eps d`` (a :class:`Dual`); via :func:`dual_rodrigues`.
    """
    return displacement_from_dual_matrix(dual_rodrigues(line, angle))


def _pose(bk: Any, R: np.ndarray, p: np.ndarray) -> np.ndarray:
    top = np.concatenate([R, p[..., None]], axis=-1)
    row = np.concatenate([bk.zeros(3), bk.eye(1)[0]])
    bottom = np.broadcast_to(row, R.shape[:-2] + (1, 4))
    return np.concatenate([top, bottom], axis=-2)


# ---------------------------------------------------------------------------
# Unit dual quaternions
# ---------------------------------------------------------------------------


def dual_quat_from_displacement(g: Any) -> Dual:
    """Unit dual quaternion ``r + eps (0, p) r / 2`` of a displacement: (..., 4, 4) -> Dual (..., 4).

    ``r`` from :func:`mechsing.lie.quaternion.quat_from_rotation_matrix`
    (w >= 0; at a half-turn the largest vector component is positive).
    """
    g = _arr(g)
    if g.ndim < 2 or g.shape[-2:] != (4, 4):
        raise ValueError(f"dual_quat_from_displacement: expected shape (..., 4, 4), got {g.shape}")
    r = quat_from_rotation_matrix(g[..., :3, :3])
    p = g[..., :3, 3]
    tq = np.concatenate([p[..., :1] * 0, p], axis=-1)
    return Dual(r, quat_multiply(tq, r) / 2)


def dual_quat_to_displacement(Q: Dual) -> np.ndarray:
    """Displacement (..., 4, 4) of a dual quaternion ``r + eps d``.

    ``R = R(r)``, ``p = vector part of 2 d r* / |r|^2``: valid for any non-zero
    real multiple of a unit dual quaternion (Study condition ``r . d = 0``).
    """
    bk = backend_of(Q.a, Q.b)
    r, d = Q.a, Q.b
    R = quat_to_rotation_matrix(r)
    p = 2 * quat_multiply(d, quat_conjugate(r))[..., 1:] / _dot(r, r)[..., None]
    return _pose(bk, R, p)


def dual_quat_multiply(P: Dual, Q: Dual) -> Dual:
    """``P Q = p_r q_r + eps (p_r q_d + p_d q_r)``; the displacement of ``P Q`` is ``g_P g_Q``."""
    return Dual(quat_multiply(P.a, Q.a), quat_multiply(P.a, Q.b) + quat_multiply(P.b, Q.a))


def dual_quat_conjugate(Q: Dual) -> Dual:
    """Quaternion conjugate ``r* + eps d*``: the inverse of a unit dual quaternion.

    (The other two conjugates, ``r - eps d`` and ``r* - eps d*``, are not used.)
    """
    return Dual(quat_conjugate(Q.a), quat_conjugate(Q.b))


def study_multiply(a: Any, b: Any) -> list[Any]:
    """:func:`dual_quat_multiply` on Study coordinates: ``a``, ``b`` the eight numbers
    ``(r, d)`` of ``r + eps d`` (any that add and multiply: float, mpmath, sympy
    expressions, so one formula serves a polynomial system, its refinement and its
    interval certificate); the product's eight, as a list."""
    ar, ad, br, bd = (_quaternion_of(x) for x in (a[:4], a[4:], b[:4], b[4:]))
    r = quat_multiply(ar, br)
    d = quat_multiply(ar, bd) + quat_multiply(ad, br)
    return [*r.tolist(), *d.tolist()]


def _quaternion_of(x: Any) -> np.ndarray:
    """Four numbers as an array quat_multiply takes: float64 for Python floats, objects
    else (ints, mpmath and sympy stay what they are)."""
    out = np.empty(4, dtype=object)
    out[:] = list(x)
    return out.astype(float) if all(isinstance(v, float) for v in out) else out


def study_conjugate(a: Any) -> list[Any]:
    """:func:`dual_quat_conjugate` on Study coordinates (both parts conjugated): ``a a* =
    |r|^2 + 2 eps r.d``, so on the Study quadric ``a*`` is the inverse up to a scalar."""
    return [a[0], -a[1], -a[2], -a[3], a[4], -a[5], -a[6], -a[7]]


# ---------------------------------------------------------------------------
# Dual rank of a screw set
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class DualRank:
    """Unit-free rank data of a set of screws seen as dual vectors ``omega + eps v``.

    Over the dual numbers the screws span a module isomorphic to
    ``D^primal + (eps D)^dual`` (D the ring of dual numbers).

    Attributes
    ----------
    primal : int or None
        Rank of the omega parts (number of independent directions).
    dual : int or None
        Rank of the v parts of the combinations whose omega part vanishes,
        modulo the span of the omega parts.
    total : int or None
        ``primal + dual`` (at most 3): the dual rank of the set.  A cylindrical
        pair (a rotation and a slide on one line) has total 1 (one dual line),
        all of D has total 3.
    real : int or None
        ``primal`` + rank of the v parts of those combinations (not modulo the
        omega span): the rank of the screws over the reals, decided without
        mixing units.
    primal_margin, dual_margin, real_margin : Margin or None
        Margins of the decisions (numeric.Margin).  The dual and real parts are
        decided relative to the Frobenius norm of all v parts (the scale of
        their rounding errors); ``kept`` is None when that rank is 0.
    precision : str
        The precision used.

    A field is None when it could not be decided (a singular value between
    the two thresholds); the margins then say how close it was.
    """

    primal: int | None
    dual: int | None
    total: int | None
    real: int | None
    primal_margin: Margin
    dual_margin: Margin | None
    real_margin: Margin | None
    precision: str


def _pivoted_orthogonal_basis(rows: np.ndarray, r: int) -> list[np.ndarray]:
    """r mutually orthogonal (unnormalised) vectors spanning the dominant r-dim
    row space of ``rows``: Gram-Schmidt with pivoting on the largest residual
    row, re-orthogonalised once ("twice is enough").  Rational in exact mode."""
    res = rows.copy()
    basis: list[np.ndarray] = []
    for _ in range(r):
        norms = _dot(res, res)
        best = 0
        for i in range(1, len(norms)):
            if norms[i] > norms[best]:
                best = i
        q = res[best].copy()
        for b in basis:  # second orthogonalisation pass against the accepted basis
            q = q - (_dot(q, b) / _dot(b, b)) * b
        basis.append(q)
        res = res - (res @ q / _dot(q, q))[:, None] * q[None, :]
    return basis


def _complement_projector(bk: Any, basis: list[np.ndarray], n: int) -> np.ndarray:
    P = bk.eye(n)
    for b in basis:
        P = P - np.outer(b, b) / _dot(b, b)
    return P


def _decide_relative(
    X: np.ndarray, ref: Any, prec: Precision, bk: Any
) -> tuple[int | None, Margin | None]:
    """Rank of X with singular values taken relative to ``ref >= ||X||_2``.

    decide_rank normalises by the largest singular value of its argument, so
    X is decided as the block matrix ``diag(X, ref)``: its singular values are
    those of X and ``ref`` (the largest), and its rank is ``rank(X) + 1``.
    """
    if ref == 0:  # X is exactly zero
        return 0, None
    m, n = X.shape
    M = bk.zeros((m + 1, n + 1))
    M[:m, :n] = X
    M[m, n] = ref
    dec = decide_rank(M, prec)
    if dec.rank is None:
        return None, dec.margin
    rank = dec.rank - 1
    margin = dec.margin if rank else dataclasses.replace(dec.margin, kept=None)
    return rank, margin


def dual_rank(screws: Any, precision: Precision | str = "float") -> DualRank:
    """Unit-free dual rank of a set of screws (the length-scale problem item 3).

    With ``A`` the omega parts and ``B`` the v parts (one screw per row),
    ``primal = rank(A)``.  With ``N`` an orthonormal basis of the combinations
    killing A (left kernel) and ``K`` one of the directions orthogonal to the
    omega span (right kernel), ``dual = rank(N^T B K)`` and
    ``real = primal + rank(N^T B)``.  ``primal`` and ``dual`` are the invariants
    of the module the screws span over the dual numbers (its Smith form is
    ``diag(1,..,1, eps,..,eps, 0,..)``); ``real`` is their ordinary rank.
    Each rank is decided by :func:`mechsing.numeric.decide_rank` on a matrix in
    one unit only, so a change of length unit (``v -> lambda v``) changes no
    verdict and no margin: the decision is unit-free.  (Moving the origin
    changes neither rank, but the reference scale of the v parts; keep the
    origin near the screws, as :func:`mechsing.numeric.scale_screws` does.)

    Parameters
    ----------
    screws : array_like, shape (n, 6)
        One screw ``(omega, v)`` per row.
    precision : Precision or str
        ``float``, ``mp:N``, ``exact`` (``auto`` decides in float).

    Returns
    -------
    DualRank
    """
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    with prec.context():
        S = prec.asarray(screws)
        if S.ndim != 2 or S.shape[1] != 6:
            raise ValueError(f"dual_rank: expected screws of shape (n, 6), got {S.shape}")
        bk = prec.backend
        A = S[:, ANGULAR]
        B = S[:, LINEAR]
        n = S.shape[0]
        pdec = decide_rank(A, prec)
        r0 = pdec.rank
        if r0 is None:
            return DualRank(None, None, None, None, pdec.margin, None, None, str(prec))
        row_basis = _pivoted_orthogonal_basis(A, r0)
        col_basis = _pivoted_orthogonal_basis(np.ascontiguousarray(A.T), r0)
        PK = _complement_projector(bk, row_basis, 3)  # onto the complement of the omega span
        PN = _complement_projector(bk, col_basis, n)  # onto the left kernel of A
        ref = bk.sqrt(np.asarray(_dot(B.ravel(), B.ravel())))[()] if n else 0
        NB = PN @ B
        real_t, real_margin = _decide_relative(NB, ref, prec, bk)
        dual_t, dual_margin = _decide_relative(NB @ PK, ref, prec, bk)
    total = None if dual_t is None else r0 + dual_t
    real = None if real_t is None else r0 + real_t
    return DualRank(r0, dual_t, total, real, pdec.margin, dual_margin, real_margin, str(prec))
