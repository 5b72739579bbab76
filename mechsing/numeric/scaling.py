"""The commensurate metric: the characteristic length L and centroid of a mechanism's
axes, and :class:`CommensurateFrame`, the one home of the maps into the commensurate
metric (before a rank decision) and back to SI at the ground origin (for reports).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import Any

import numpy as np

from mechsing.numeric.backend import Backend, to_float
from mechsing.numeric.lazy import sympy
from mechsing.numeric.numbers import safe_norm
from mechsing.numeric.tolerances import NEAR_ZERO_VECTOR


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
        RMS distance of the points from their centroid; ``|c|`` if that is 0 or
        no more than :data:`NEAR_ZERO_VECTOR` times the largest ``|point|`` (the
        points coincide, and their spread is the rounding of their coordinates: a
        length of 1e-137 next to points 3.37 from the origin would divide the
        commensurate v rows by it and blow their rounding up to 1e119); 1 if ``|c|``
        is 0 too.
    c : ndarray, shape (3,)
        The centroid (zeros when there are no points).
    """
    pts = np.asarray(to_float(points), dtype=float).reshape(-1, 3)
    c = pts.mean(axis=0) if len(pts) else np.zeros(3)
    if override is not None:
        return float(override), c
    d = pts - c
    big = float(np.max(np.abs(d))) if len(pts) else 0.0
    # scaled by the largest offset first, so that no square underflows or overflows
    rms = big * float(np.sqrt(np.mean(np.sum((d / big) ** 2, axis=1)))) if big > 0 else 0.0
    if 1e-100 < big < 1e100:  # squares far from both ends of the range: the same rounding
        rms = float(np.sqrt(np.mean(np.sum(d**2, axis=1))))  # as always (results unchanged)
    far = max((safe_norm(p) for p in pts), default=0.0)
    if rms > NEAR_ZERO_VECTOR * far:
        return rms, c
    nc = safe_norm(c)
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
        c0, c1, c2 = c[0], c[1], c[2]
        w0, w1, w2 = S[..., 0, :], S[..., 1, :], S[..., 2, :]
        # v - c x w, columnwise, row by row (the omega rows are not written): the same
        # operations as on the three rows stacked, without the stack's copies
        S[..., 3, :] = S[..., 3, :] - (w2 * c1 - w1 * c2)
        S[..., 4, :] = S[..., 4, :] - (w0 * c2 - w2 * c0)
        S[..., 5, :] = S[..., 5, :] - (w1 * c0 - w0 * c1)
    S[..., 3:6, :] = S[..., 3:6, :] / length_scale
    if length_columns is not None:
        mask = np.asarray(length_columns, dtype=bool)
        S[..., :, mask] = S[..., :, mask] * length_scale
    return S


def cross3(a: Any, b: Any) -> Any:
    """``numpy.cross`` of two 3-vectors; of two float ones in Python floats (the same
    products and differences, a fraction of numpy's per-call cost)."""
    if (
        type(a) is np.ndarray
        and type(b) is np.ndarray
        and a.dtype == np.float64
        and b.dtype == np.float64
        and a.shape == b.shape == (3,)
    ):
        a0, a1, a2 = a.tolist()
        b0, b1, b2 = b.tolist()
        return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])
    return np.cross(a, b)


#: (f, m) <-> (m, f): the swap between a wrench and its twist-pairing vector
_SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])


@lru_cache(maxsize=1024)
def _simple_rational(x: float) -> Any:
    """``sympy.nsimplify(x, rational=True)``: the exact centre of a frame whose centroid
    is not rational.  A function of the float alone, computed once per value (mpmath's
    ``identify`` searches for a simple closed form first: 6 to 20 ms a coordinate, a
    fifth of a linkage's analysis in a field of degree 2)."""
    return sympy.nsimplify(x, rational=True)


@dataclass(frozen=True, eq=False)
class CommensurateFrame:
    """The commensurate frame of a mechanism (or of a loop): where ranks are decided so
    that the mechanism's scale does not change a verdict.

    Forward (SI at the ground origin -> commensurate): a twist is moved to the centroid
    ``c`` (``v -> v - c x omega``) and its linear part divided by ``L``; a joint
    coordinate that is a length (a ``length_columns`` entry) is divided by ``L``, so
    its screw column is multiplied by ``L``.  Inverse (commensurate -> SI at the
    origin): ``v_0 = L v_c + c x omega``; length rates times ``L``; a wrench by the
    dual map (it pairs with twists as the commensurate wrench paired with the
    commensurate twists).

    Attributes
    ----------
    L, c : number, ndarray (3,) or None
        The characteristic length and centroid in the numbers of one backend (float,
        mp, or exact rationals); ``c`` None: the origin.
    length_columns : ndarray of bool (n,) or None
        Which joint coordinates are lengths (None: a frame of screws only).
    """

    L: Any
    c: Any
    length_columns: np.ndarray | None = None
    #: the float values of L and c (the float twin's numbers)
    L_float: float = 1.0
    c_float: np.ndarray | None = None

    @classmethod
    def of(
        cls,
        L: float,
        c: Any,
        length_columns: Any = None,
        backend: Backend | None = None,
        exact_centre: Any = None,
    ) -> CommensurateFrame:
        """The frame of the float ``L`` and centroid ``c`` in ``backend``'s numbers
        (None: float).  Exact: the decimals of the float values as rationals, or the
        centroid ``exact_centre`` when given (the exact mean of rational points, of which
        ``c`` is the float rounding)."""
        cf = np.asarray(to_float(c), dtype=float).reshape(3)
        lc = None if length_columns is None else np.asarray(length_columns, dtype=bool)
        name = "float" if backend is None else backend.name
        if name == "exact":
            # any exact non-zero factor keeps exact ranks, any exact centre (a translation
            # is an automorphism); the decimals as rationals
            Lb: Any = sympy.Rational(repr(float(L)))
            if exact_centre is not None:
                cb: Any = np.array([sympy.sympify(x) for x in exact_centre], dtype=object)
            else:
                cb = np.array([_simple_rational(float(x)) for x in cf], dtype=object)
        elif name == "mp":
            assert backend is not None
            Lb, cb = backend.convert(L), backend.asarray(cf)
        else:
            Lb, cb = float(L), cf
        return cls(Lb, cb, lc, float(L), cf)

    @classmethod
    def from_numbers(cls, L: Any, c: Any = None, length_columns: Any = None) -> CommensurateFrame:
        """The frame of ``L`` and ``c`` already in one backend's numbers (``c`` None:
        the origin, screws are not moved)."""
        cf = np.zeros(3) if c is None else np.asarray(to_float(c), dtype=float).reshape(3)
        lc = None if length_columns is None else np.asarray(length_columns, dtype=bool)
        return cls(L, c, lc, float(to_float(L)), cf)

    def as_float(self) -> CommensurateFrame:
        """The float twin (same L, c and length columns, float numbers)."""
        if isinstance(self.L, float):
            return self
        return CommensurateFrame(
            self.L_float, self.c_float, self.length_columns, self.L_float, self.c_float
        )

    def lengths(self, columns: Any = None) -> np.ndarray | None:
        """Which of the joint coordinates ``columns`` (None: all) are lengths."""
        if self.length_columns is None:
            return None
        return self.length_columns if columns is None else self.length_columns[list(columns)]

    # -- forward: SI at the origin -> commensurate ------------------------------------

    def screws(self, S: np.ndarray, columns: Any = None) -> np.ndarray:
        """Commensurate screw columns ``(..., 6, k)`` of joint coordinates (``columns``:
        their indices among the frame's coordinates; None: all): moved to c, v / L,
        length columns times L."""
        return scale_screws(S, self.L, self.c, self.lengths(columns))

    def columns_in_place(self, J: np.ndarray, columns: Any = None) -> np.ndarray:
        """Multiply the length columns of ``J`` (..., rows, k) by L in place (the column
        factor of :meth:`screws` alone, for batched float matrices already moved to c
        and divided by L); returns ``J``."""
        lc = self.lengths(columns)
        if lc is not None and np.any(lc):
            J[..., lc] *= self.L
        return J

    def twists(self, S: np.ndarray) -> np.ndarray:
        """Commensurate twist columns ``(..., 6, k)`` with no column factor (twists that
        are not joint screws: residuals, lost twists)."""
        return scale_screws(S, self.L, self.c)

    def rows(self, B: np.ndarray) -> np.ndarray:
        """Commensurate basis rows ``(k, 6)`` (a subgroup's basis): moved to c, v / L."""
        return scale_screws(B.T, self.L, self.c).T

    def blocks(self, M: np.ndarray, columns: bool = True) -> np.ndarray:
        """Stacked 6-row screw blocks ``(6b, n)`` (closure Jacobians), each block made
        commensurate; the length columns multiplied by L unless ``columns`` is False."""
        if M.shape[0] == 0:
            return M
        k = M.shape[0] // 6
        lc = self.length_columns if columns else None
        return scale_screws(M.reshape(k, 6, M.shape[1]), self.L, self.c, lc).reshape(M.shape)

    def stacked(self, r: np.ndarray) -> np.ndarray:
        """Stacked residual twists (a vector of 6b entries), each made commensurate."""
        return self.twists(r.reshape(-1, 6).T).T.reshape(-1)

    def rates(self, d: np.ndarray) -> np.ndarray:
        """SI joint rates or increments -> commensurate (lengths / L)."""
        lc = False if self.length_columns is None else self.length_columns  # False: none
        return np.where(lc, d / self.L, d)

    def random_coordinates(self, rng: np.random.Generator, count: int) -> np.ndarray:
        """``count`` random joint coordinates (rows, float): angles uniform in
        [-pi, pi), lengths in [-L, L) (uniform in the commensurate metric)."""
        assert self.length_columns is not None
        q = rng.uniform(-np.pi, np.pi, size=(count, len(self.length_columns)))
        return np.where(self.length_columns[None, :], q * self.L_float / np.pi, q)

    def point(self, x: Any) -> Any:
        """A point's commensurate position: ``(x - c) / L``."""
        return x / self.L if self.c is None else (x - self.c) / self.L

    # -- inverse: commensurate -> SI at the origin -----------------------------------

    def rates_back(self, x: np.ndarray, columns: Any = None) -> np.ndarray:
        """Commensurate joint rates -> SI (lengths times L); ``columns`` as in
        :meth:`screws`."""
        lc = self.lengths(columns)
        return np.where(False if lc is None else lc, x * self.L, x)  # False: no lengths

    def twist_back(self, t: np.ndarray) -> np.ndarray:
        """An SI twist at the ground origin from a commensurate one:
        ``v_0 = L v_c + c x omega``."""
        w, v = t[0:3], t[3:6] * self.L
        return (
            np.concatenate([w, v]) if self.c is None else np.concatenate([w, v + cross3(self.c, w)])
        )

    def point_back(self, x: Any) -> Any:
        """A point's SI position from its commensurate one: ``x L + c``."""
        return x * self.L if self.c is None else x * self.L + self.c

    def velocity_back(self, v: np.ndarray) -> np.ndarray:
        """A point's SI velocity from a commensurate one (times L)."""
        return v * self.L

    def wrench_back(self, y: np.ndarray) -> np.ndarray:
        """The SI wrench (f, m) at the ground origin of a commensurate left-null vector
        ``y`` (float): the one with ``f . v_0 + m . omega = y . twist`` for every twist,
        i.e. ``swap(Ad(T(-c))^T D y)`` with ``D = diag(1, 1, 1, 1/L, 1/L, 1/L)``."""
        AdT, D = self._wrench_maps
        return _SWAP @ (AdT @ (D @ np.asarray(y, dtype=float)))

    @cached_property
    def _wrench_maps(self) -> tuple[np.ndarray, np.ndarray]:
        """``Ad(T(-c))^T`` and ``D`` of :meth:`wrench_back` (float, built once)."""
        L, c = self.L_float, self.c_float
        assert c is not None  # every constructor sets the float centre
        D = np.diag([1, 1, 1, 1 / L, 1 / L, 1 / L])
        # Ad of the translation by -c (rotation identity): [[I, 0], [hat(-c), I]]
        Ad = np.eye(6)
        Ad[3:6, 0:3] = np.array([[0, c[2], -c[1]], [-c[2], 0, c[0]], [c[1], -c[0], 0]])
        return Ad.T, D
