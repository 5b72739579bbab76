"""Lie closure, identification of a subalgebra, generated subgroups,
intersections and products (recognition, generated subgroups, intersections and products).

Every rank is decided in the commensurate metric (docs/precision.md, "Margins"): screws are moved
to a centre c (Ad of the translation by -c) and their v rows divided by the
length scale L.  Both maps are Lie algebra automorphisms, so brackets are
taken in that metric directly.  The type is looked up in the catalog by its
structure (dimension, dimension of the rotation part, whether a pitch is
needed); the code names no type.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.lie import ANGULAR, LINEAR
from mechsing.numeric import (
    PARALLEL_AXES_ATOL,
    CommensurateFrame,
    Margin,
    Precision,
    RankDecision,
    backend_of,
    characteristic_length,
    decide_nonzero,
    decide_rank,
    display_floor,
    to_float,
)
from mechsing.numeric.field import echelon_form, field_float, field_normal_form, number_field
from mechsing.numeric.lazy import LazyModule
from mechsing.numeric.linalg import svd
from mechsing.subgroups import _linalg
from mechsing.subgroups.instance import Subgroup, as_precision
from mechsing.subgroups.types import _cross, load_catalog

#: sympy's domain matrices, imported when a subgroup is first identified exactly
_matrices = LazyModule("sympy.polys.matrices")

#: the centre an identification moves the screws to is the mean of the axis points of
#: the screws that rotate, but not of one whose rotation is below this fraction of the
#: largest: its axis point is as far as its translation over that rotation (a
#: translation with a trace of rotation: 1e4 away for a rotation of 1e-4), and a centre
#: that far makes the commensurate rows ill-conditioned (an X axis then read to 1e-9)
CENTRE_ROTATION_RTOL = 1e-3

__all__ = [
    "Identification",
    "Intersection",
    "Product",
    "generate",
    "identify",
    "intersect",
    "lie_closure",
    "product",
]

#: most bracket rounds of a closure (the dimension grows at each round, up to 6)
_MAX_ROUNDS = 6


@dataclass
class Identification:
    """The outcome of :func:`identify`.

    ``status`` is ``"ok"`` (``subgroup`` and ``dim`` set), ``"undecided"`` (a
    rank or a pitch fell between the two thresholds of the precision: no type
    is given; ``dim_bounds`` says what is consistent), or ``"ill-conditioned"``
    (the decided ranks describe no subalgebra, e.g. dimension 5: no type is
    given).  ``bracket_norms[i]`` is the largest norm, in the commensurate
    metric, of the part of a bracket of round i outside the span so far
    (orthonormal basis, so 1 is large); the first entry below ``tau_lo`` closed
    the algebra.  ``margin`` combines every decision taken (smallest kept,
    largest dropped singular value, relative).
    """

    status: str
    subgroup: Subgroup | None
    dim: int | None
    bracket_norms: list[float]
    margin: Margin
    precision: str
    message: str = ""
    dim_bounds: tuple[int, int] | None = None
    rotation_dim: int | None = None
    pitch_scaled: float | None = None
    basis: Any = field(default=None, repr=False)

    @property
    def ok(self) -> bool:
        return self.status == "ok"


class _Margins:
    def __init__(self, prec: Precision, L: float):
        self.prec, self.L = prec, L
        self.kept: list[float] = []
        self.dropped: list[float] = []

    def add(self, d: RankDecision) -> None:
        m = d.margin
        if m.kept is not None:
            self.kept.append(float(m.kept))
        if m.dropped is not None:
            self.dropped.append(float(m.dropped))

    def add_values(self, kept: float | None = None, dropped: float | None = None) -> None:
        if kept is not None:
            self.kept.append(kept)
        if dropped is not None:
            self.dropped.append(dropped)

    def margin(self) -> Margin:
        t = self.prec.tolerances
        return Margin(
            min(self.kept) if self.kept else None,
            max(self.dropped) if self.dropped else None,
            t.tau_lo,
            t.tau_hi,
            float(self.L),
        )


def _brackets(B: np.ndarray) -> np.ndarray:
    k = B.shape[0]
    pairs = [(i, j) for i in range(k) for j in range(i + 1, k)]
    if not pairs:
        return B[:0]
    a = np.stack([B[i] for i, _ in pairs])
    b = np.stack([B[j] for _, j in pairs])
    out = lie.bracket(a, b)
    return backend_of(out).simplify(out)


def _residual_norm(B: np.ndarray) -> float:
    """Largest norm, outside span(B), of the brackets of an orthonormal (float)
    basis of span(B): what a bracket round adds, on a scale where 1 is large."""
    fb = to_float(B)
    if fb.shape[0] < 2:
        return 0.0
    q, _ = np.linalg.qr(fb.T)
    Q = q.T
    br = _brackets(Q)
    res = br - (br @ q) @ q.T
    return float(np.max(np.linalg.norm(res, axis=1)))


def _field_brackets(K: Any, B: list[list[Any]]) -> list[list[Any]]:
    """:func:`_brackets` of rows of elements of K: ``[(w1, v1), (w2, v2)] = (w1 x w2,
    w1 x v2 - w2 x v1)`` for each pair i < j, in K."""

    def mul(x: Any, y: Any) -> Any:
        # rows of reduced echelon forms are sparse: no product with a zero factor
        return x * y if x and y else K.zero

    def cross(a: list[Any], b: list[Any]) -> list[Any]:
        return [
            mul(a[1], b[2]) - mul(a[2], b[1]),
            mul(a[2], b[0]) - mul(a[0], b[2]),
            mul(a[0], b[1]) - mul(a[1], b[0]),
        ]

    out = []
    for i in range(len(B)):
        for j in range(i + 1, len(B)):
            (w1, v1), (w2, v2) = (B[i][:3], B[i][3:]), (B[j][:3], B[j][3:])
            a, b = cross(w1, v2), cross(w2, v1)
            out.append(cross(w1, w2) + [x - y for x, y in zip(a, b, strict=True)])
    return out


def _field_closure(
    S: np.ndarray, L: float, margins: _Margins
) -> tuple[np.ndarray, list[float], None] | None:
    """:func:`_closure` in exact mode in the number field of the rows (None: they have
    none): the same decisions (echelon pivots), row spaces (reduced row echelon rows)
    and brackets as the exact path takes on sympy numbers, without converting each
    round's brackets to sympy and back."""
    m = S.shape[0]
    fit = number_field(list(S.flat)) if m else None
    if fit is None:
        return None
    K, els = fit
    rows = [els[6 * i : 6 * i + 6] for i in range(m)]

    def row_space(rows: list[list[Any]]) -> list[list[Any]]:
        D = _matrices.DomainMatrix(rows, (len(rows), 6), K)
        E = echelon_form(D)
        mags = E.pivot_magnitudes()
        margins.add_values(
            kept=min(mags) if mags else None,
            dropped=0.0 if len(E.pivots) < min(len(rows), 6) else None,
        )
        return E.rref_rows()

    def floats(B: list[list[Any]]) -> np.ndarray:
        return np.array([[field_float(K, x) for x in r] for r in B], dtype=float).reshape(-1, 6)

    B = row_space(rows)
    norms: list[float] = []
    for _ in range(_MAX_ROUNDS):
        br = _field_brackets(K, B)
        if not br:
            break
        norms.append(_residual_norm(floats(B)))
        B2 = row_space(B + br)
        if len(B2) == len(B):
            break
        B = B2
    out = np.array([[K.to_sympy(x) for x in r] for r in B], dtype=object).reshape(len(B), 6)
    return out, norms, None


def _closure(
    S: np.ndarray, prec: Precision, L: float, margins: _Margins
) -> tuple[np.ndarray | None, list[float], tuple[int, int] | None]:
    """Lie closure of the rows of S (commensurate metric): basis, bracket norms,
    and the rank bounds when a decision was undecided."""
    if prec.mode == "exact":
        fast = _field_closure(S, L, margins)
        if fast is not None:
            return fast
    dec, B = _linalg.row_space(S, prec, L)
    margins.add(dec)
    if B is None:
        return None, [], dec.rank_bounds
    norms: list[float] = []
    for _ in range(_MAX_ROUNDS):
        br = _brackets(B)
        if br.shape[0] == 0:
            break
        norms.append(_residual_norm(B))
        M = np.concatenate([B, br], axis=0)
        dec, B2 = _linalg.row_space(M, prec, L)
        margins.add(dec)
        if B2 is None:
            return None, norms, dec.rank_bounds
        if B2.shape[0] == B.shape[0]:
            break
        B = B2
    return B, norms, None


def lie_closure(
    screws: Any, length_scale: float = 1.0, precision: Any = None
) -> tuple[np.ndarray | None, list[float]]:
    """Basis (rows, commensurate metric around the origin) of the Lie algebra
    generated by the screws, and the bracket norms; None when undecided."""
    S = np.asarray(screws)
    prec = as_precision(precision, S)
    with prec.context():
        X = _linalg.convert(S, prec).reshape(-1, 6)
        Xs = CommensurateFrame.from_numbers(length_scale).rows(X)
        B, norms, _ = _closure(Xs, prec, length_scale, _Margins(prec, length_scale))
        return B, norms


def _centre_of(X: np.ndarray) -> np.ndarray:
    """Mean of the axis points nearest the origin of the screws that rotate (float), but
    not of those whose rotation is below CENTRE_ROTATION_RTOL of the largest (their axis
    points are far: a centre there would make the commensurate rows ill-conditioned)."""
    f = to_float(X)
    w = f[:, ANGULAR]
    n2 = np.sum(w * w, axis=1)
    big = (n2 > 0) & (n2 >= CENTRE_ROTATION_RTOL**2 * np.max(n2, initial=0.0))
    if not np.any(big):
        return np.zeros(3)
    feet = np.cross(w[big], f[big, 3:6]) / n2[big, None]
    return feet.mean(axis=0)


def identify(
    screws: Any,
    length_scale: float = 1.0,
    precision: Any = None,
    centre: Any = None,
) -> Identification:
    """Type and parameters of the subgroup generated by ``screws`` (recognising a subgroup from spanning screws).

    Parameters
    ----------
    screws : array_like, shape (m, 6)
        Any spanning set, (omega, v) order; redundant or recombined screws are fine.
    length_scale : float
        L of the commensurate metric (the v rows are divided by it).
    precision : str, Precision or None
        ``float``, ``mp:N``, ``exact``, ``auto`` (float, re-decided at mp:50
        when undecided or ill-conditioned), or None: from the data (exact for
        sympy numbers, mp for mpmath numbers, float otherwise).
    centre : array_like, optional
        Point the screws are moved to before deciding; default the mean of
        the axis points of the rotating screws (float and mp; the origin in
        exact mode).

    Returns
    -------
    Identification
        Never dimension 5 and never a guess: undecided ranks or pitches give
        ``status="undecided"``, impossible ranks ``"ill-conditioned"``.
    """
    S = np.asarray(screws)
    if S.ndim == 1:
        S = S.reshape(1, -1) if S.size else S.reshape(0, 6)
    if S.ndim != 2 or S.shape[1] != 6:
        raise ValueError(f"screws must have shape (m, 6), got {S.shape}")
    if isinstance(precision, str) and precision.strip().lower() == "auto":
        first = identify(S, length_scale, "float", centre)
        if first.ok:
            return first
        second = identify(S, length_scale, "mp:50", centre)
        second.message = (second.message + " " if second.message else "") + (
            f"(float was {first.status}; re-decided at mp:50)"
        )
        return second
    prec = as_precision(precision, S)
    with prec.context():
        X = _linalg.convert(S, prec)
        bk = prec.backend
        if centre is None:
            c = bk.frame_centre(_centre_of(X))
        else:
            c = _linalg.convert(np.asarray(centre), prec)
        frame = CommensurateFrame.from_numbers(bk.convert(length_scale), c)
        return _identify_scaled(frame.rows(X), prec, frame)


def _identify_scaled(Xs: np.ndarray, prec: Precision, frame: CommensurateFrame) -> Identification:
    Lf = frame.L_float
    margins = _Margins(prec, Lf)
    B, norms, bounds = _closure(Xs, prec, Lf, margins)

    def result(status: str, message: str, **kw: Any) -> Identification:
        return Identification(status, None, None, norms, margins.margin(), str(prec), message, **kw)

    if B is None:
        return result(
            "undecided",
            "a rank lies between the thresholds of this precision; use a higher one (mp:N or exact)",
            dim_bounds=bounds,
        )
    return _classify(B, prec, frame, margins, norms)


def _translations(bk: Any) -> np.ndarray:
    T = bk.zeros((3, 6))
    for i in range(3):
        T[i, 3 + i] = bk.convert(1)
    return T


def _classify(
    B: np.ndarray,
    prec: Precision,
    frame: CommensurateFrame,
    margins: _Margins,
    norms: list[float],
) -> Identification:
    """Type and parameters of the algebra with commensurate basis rows ``B`` in ``frame``."""
    bk = prec.backend
    L = frame.L
    Lf = frame.L_float
    k = B.shape[0]

    def result(status: str, message: str, **kw: Any) -> Identification:
        return Identification(status, None, None, norms, margins.margin(), str(prec), message, **kw)

    # rotation dimension r = rank([B; translations]) - 3 (well scaled: B is orthonormal)
    dec = decide_rank(np.concatenate([B, _translations(bk)], axis=0), prec, Lf)
    margins.add(dec)
    if dec.rank is None:
        return result(
            "undecided", "the dimension of the rotation part is undecided at this precision"
        )
    r = dec.rank - 3
    candidates = [t for t in load_catalog().values() if t.dimension == k and t.rotation_rank == r]
    if not candidates:
        return result(
            "ill-conditioned",
            f"the decided ranks (dimension {k}, rotations {r}) describe no subalgebra of D; "
            "the input is too close to a degenerate one for this precision",
            rotation_dim=r,
        )
    # the geometric elements the parameters are read from
    W = B[:, ANGULAR]
    geo: dict[str, Any] = {}
    pitch = None
    if r == 1:
        x = _rotating_element(B, prec)
        w, v = x[ANGULAR], x[LINEAR]
        n2 = w @ w
        u = w / bk.sqrt(np.asarray(n2))[()]
        # exactly: the subgroup normalises the direction itself (one square root, not a
        # root of a sum of squares of roots)
        geo["direction"] = w if prec.mode == "exact" else u
        geo["point"] = _cross(w, v) / n2
        pitch = (w @ v) / n2
    elif r == 0 and k in (1, 2):
        vs = B[:, LINEAR]
        d = vs[0] if k == 1 else _cross(vs[0], vs[1])
        geo["direction"] = d if prec.mode == "exact" else d / bk.sqrt(np.asarray(d @ d))[()]
    elif r == 3 and k == 3:
        geo["point"] = _centre_of_rotations(B, prec)
    _ = W
    if len(candidates) > 1:
        pitched = _decide_pitch(pitch, prec, margins)
        if pitched is None:
            return result(
                "undecided",
                f"the pitch ({float(to_float(pitch)) * Lf:.3g}) is too close to zero to decide "
                "at this precision",
                rotation_dim=r,
                pitch_scaled=float(to_float(pitch)),
            )
        candidates = [t for t in candidates if t.pitched == pitched]
    if len(candidates) != 1:
        return result("ill-conditioned", "no single catalog type fits", rotation_dim=r)
    t = candidates[0]
    params: dict[str, Any] = {}
    # numerically, a component below the display floor (the precision's closure
    # tolerance: 1e-12 L in float) is round-off of a zero, read as one: a plane's normal
    # from float screws about z is [0, 0, 1], not [1e-16, -1e-16, 1]
    floor = display_floor(prec, Lf)
    for name, kind in t.parameters:
        if kind in ("direction", "normal"):
            params[name] = _floored(geo["direction"], floor / Lf)
        elif kind == "point":
            params[name] = _floored(frame.point_back(geo["point"]), floor)
        else:
            params[name] = pitch * L
    sub = Subgroup(t, {n: _normal_form(v, prec) for n, v in params.items()})
    # consistency: the rebuilt canonical basis spans the same space
    Bc = frame.rows(sub.basis(prec))
    dec = decide_rank(np.concatenate([B, Bc], axis=0), prec, Lf)
    if dec.rank != k:
        return result(
            "ill-conditioned",
            f"the rebuilt {t.symbol} basis does not span the closure (rank {dec.rank})",
            rotation_dim=r,
        )
    ident = Identification(
        "ok", sub.canonical(), k, norms, margins.margin(), str(prec), "", None, r
    )
    ident.pitch_scaled = None if pitch is None else float(to_float(pitch))
    ident.basis = B
    return ident


def _floored(v: Any, floor: float) -> Any:
    """``v`` with its components below ``floor`` in size set to zero (in their own numbers;
    a floor of 0, exact mode's, leaves every one)."""
    if not floor:
        return v
    out = np.array(v, dtype=object if np.asarray(v).dtype == object else float)
    for i, x in enumerate(out):
        if abs(x) < floor:
            out[i] = x * 0
    return out


def _normal_form(v: Any, prec: Precision) -> Any:
    """A parameter in the backend's normal form; exactly, its number field's when it has
    one (no radical simplification of values that are sums of products in the field)."""
    if prec.mode == "exact":
        fast = field_normal_form(v)
        if fast is not None:
            return fast
    return prec.backend.simplify(v)


def _rotating_element(B: np.ndarray, prec: Precision) -> np.ndarray:
    """The element of span(B) with the largest rotation part (rotations of rank 1)."""
    W = B[:, ANGULAR]
    if prec.mode == "exact":
        # left as a branch: exactly, any basis element that rotates will do (the largest
        # keeps the numbers short); numerically the first left singular vector is the
        # best-conditioned combination
        i = max(range(B.shape[0]), key=lambda j: float(to_float(W[j] @ W[j])))
        return B[i]
    with prec.context():
        U, _s, _V = svd(prec.backend.asarray(W))
    return U[:, 0] @ B


def _centre_of_rotations(B: np.ndarray, prec: Precision) -> np.ndarray:
    """Least-squares N with ``omega_i x N = -v_i`` over the basis (spherical)."""
    rows, rhs = [], []
    for w, v in zip(B[:, ANGULAR], B[:, LINEAR], strict=True):
        rows.extend(lie.hat3(w).tolist())
        rhs.extend(list(-v))
    A = np.array(rows, dtype=B.dtype)
    b = np.array(rhs, dtype=B.dtype)
    return _linalg.solve_coefficients(A.T, b, prec)


def _decide_pitch(h: Any, prec: Precision, margins: _Margins) -> bool | None:
    """Is the (commensurate) pitch non-zero?  Two thresholds, like a rank."""
    nonzero = decide_nonzero(h, prec)
    # left as a branch: an exact margin records pivots, not values (a proved pitch adds none)
    if prec.mode != "exact" and nonzero is not None:
        a = abs(float(to_float(h)))
        margins.add_values(**({"kept": min(a, 1.0)} if nonzero else {"dropped": a}))
    return nonzero


# ---------------------------------------------------------------------------
# Generated subgroup, intersection, product
# ---------------------------------------------------------------------------


def _common_frame(
    subgroups: list[Subgroup], length_scale: float | None
) -> tuple[float, np.ndarray]:
    pts = []
    for s in subgroups:
        ra = s.rotation_axis("float")
        if ra is not None:
            pts.append(to_float(ra[1]))
        for (_n, kind), v in zip(s.type.parameters, s.params.values(), strict=True):
            if kind == "point" and s.type.rotation_rank == 3:
                pts.append(to_float(v))
    L, c = characteristic_length(np.array(pts).reshape(-1, 3))
    return (float(length_scale) if length_scale is not None else L), c


def _precision_of(subgroups: list[Subgroup], precision: Any) -> Precision:
    return as_precision(
        precision, *[np.asarray(list(s.params.values()) or [0], dtype=object) for s in subgroups]
    )


def generate(
    subgroups: list[Subgroup], length_scale: float | None = None, precision: Any = None
) -> Identification:
    """The connected subgroup generated by the given subgroups (generated subgroups):
    the Lie closure of the sum of their algebras, identified.  Default
    length scale: the characteristic length of their axis points."""
    subgroups = list(subgroups)
    prec = _precision_of(subgroups, precision)
    L, c = _common_frame(subgroups, length_scale)
    with prec.context():
        rows = [s.basis(prec) for s in subgroups]
        S = np.concatenate(rows, axis=0) if rows else prec.backend.zeros((0, 6))
        return identify(S, L, prec, prec.backend.frame_centre(c))


@dataclass
class Intersection:
    """``a ∩ b``: the identity component (``identification``) and what is known
    of extra components: ``extra_components`` is True (a discrete set of extra
    pieces exists, described in ``note``), False (the intersection is
    connected) or None (not determined)."""

    identification: Identification
    extra_components: bool | None
    note: str

    @property
    def subgroup(self) -> Subgroup | None:
        return self.identification.subgroup


def intersect(
    a: Subgroup, b: Subgroup, length_scale: float | None = None, precision: Any = None
) -> Intersection:
    """Intersection of two subgroups (intersections of subgroups).

    The identity component has algebra ``a ∩ b`` (a linear intersection,
    decided in the commensurate metric).  Extra discrete components occur
    when a pitched subgroup (H, Y) turns whole turns: ``exp(2 pi k e)`` is the
    translation ``2 pi k h u``; when that lies in the other subgroup but not in
    the identity component, the note says so.
    """
    prec = _precision_of([a, b], precision)
    L, c = _common_frame([a, b], length_scale)
    with prec.context():
        bk = prec.backend
        frame = CommensurateFrame.from_numbers(bk.convert(L), bk.frame_centre(c))
        B1 = frame.rows(a.basis(prec))
        B2 = frame.rows(b.basis(prec))
        margins = _Margins(prec, L)
        if B1.shape[0] == 0 or B2.shape[0] == 0:
            inter = bk.zeros((0, 6))
        else:
            _d1, O1 = _linalg.row_space(B1, prec, L)
            _d2, O2 = _linalg.row_space(B2, prec, L)
            A = np.concatenate([O1, -O2], axis=0).T
            dec, N = _linalg.null_space(A, prec, L)
            margins.add(dec)
            if N is None:
                ident = Identification(
                    "undecided",
                    None,
                    None,
                    [],
                    margins.margin(),
                    str(prec),
                    "the dimension of the intersection is undecided at this precision",
                )
                return Intersection(ident, None, "")
            inter = N[:, : O1.shape[0]] @ O1
        if inter.shape[0] == 0:
            ident = _classify(inter, prec, frame, margins, [])
        else:
            B, norms, bounds = _closure(inter, prec, L, margins)
            if B is None:
                ident = Identification(
                    "undecided",
                    None,
                    None,
                    norms,
                    margins.margin(),
                    str(prec),
                    "the dimension of the intersection is undecided",
                    bounds,
                )
                return Intersection(ident, None, "")
            ident = _classify(B, prec, frame, margins, norms)
        extra, note = _discrete_pieces(a, b, ident, prec)
        return Intersection(ident, extra, note)


def _discrete_pieces(
    a: Subgroup, b: Subgroup, ident: Identification, prec: Precision
) -> tuple[bool | None, str]:
    notes = []
    extra: bool | None = False
    for p, q in ((a, b), (b, a)):
        if not p.type.pitched:
            continue
        u, _pt, h = p.rotation_axis(prec)  # type: ignore[misc]
        turn = p.chart(_unit_turn(p, prec))
        if q.type.pitched and q.rotation_axis(prec) is not None:
            u2 = q.rotation_axis(prec)[0]  # type: ignore[index]
            parallel = float(np.linalg.norm(np.cross(to_float(u), to_float(u2))))
            if parallel < PARALLEL_AXES_ATOL and not q.contains(turn):
                extra = None
                notes.append(
                    f"{p.symbol} and {q.symbol} turn about parallel axes with their own pitches: "
                    "whole-turn coincidences may add discrete pieces (not determined)"
                )
        if q.contains(turn) and not (ident.subgroup is not None and ident.subgroup.contains(turn)):
            extra = True
            notes.append(
                f"the intersection also holds the translations by 2 pi k x {float(to_float(h)):.6g} "
                f"along {np.round(to_float(u), 12).tolist()} (k integer): the whole turns of "
                f"{p.symbol}; these are discrete pieces outside the identity component"
            )
    return extra, "; ".join(notes)


def _unit_turn(p: Subgroup, prec: Precision) -> np.ndarray:
    """Coordinates of exp(2 pi e) for the rotating basis screw e of p."""
    B = p.basis(prec)
    bk = prec.backend
    q = bk.zeros(p.dim)
    i = int(np.argmax(np.abs(to_float(B[:, ANGULAR])).sum(axis=1)))
    n = bk.sqrt(np.asarray(B[i, 0:3] @ B[i, 0:3]))[()]
    q[i] = 2 * bk.pi / n
    return q


@dataclass
class Product:
    """Is the set ``a·b`` a subgroup?  ``is_subgroup`` is True (then
    ``subgroup`` is it), False (``generated`` is the subgroup it generates;
    ``set_dimension`` the dimension of the product set near the identity), or
    None (the algebra sum is closed but no sufficient condition was found)."""

    is_subgroup: bool | None
    subgroup: Subgroup | None
    generated: Identification
    set_dimension: int | None
    note: str


def product(
    a: Subgroup, b: Subgroup, length_scale: float | None = None, precision: Any = None
) -> Product:
    """Is the product set a·b a subgroup, and which one (products of subgroups)?

    Necessary: the linear sum of the algebras is closed under the bracket
    (otherwise a·b is a ``set_dimension``-dimensional subset of the generated
    subgroup).  Sufficient: some ideal n of that sum lies in one factor and
    fills the sum together with the other factor; the ideals tried are each
    factor's algebra and its translation part.
    """
    prec = _precision_of([a, b], precision)
    L, c = _common_frame([a, b], length_scale)
    gen = generate([a, b], L, prec)
    with prec.context():
        bk = prec.backend
        frame = CommensurateFrame.from_numbers(bk.convert(L), bk.frame_centre(c))
        B1 = frame.rows(a.basis(prec))
        B2 = frame.rows(b.basis(prec))
        dec, Ssum = _linalg.row_space(np.concatenate([B1, B2], axis=0), prec, L)
        if Ssum is None:
            return Product(None, None, gen, None, "the dimension of the sum is undecided")
        m = Ssum.shape[0]
        if not gen.ok:
            return Product(
                None, None, gen, m, "the generated subgroup is not decided: " + gen.message
            )
        if gen.dim != m:
            return Product(
                False,
                None,
                gen,
                m,
                f"the algebras sum to dimension {m}, not closed under the bracket: a·b is a "
                f"{m}-dimensional subset of the generated {gen.subgroup.symbol if gen.subgroup else '?'}",
            )

        def rank(M: np.ndarray) -> int | None:
            return decide_rank(M, prec, L).rank if M.shape[0] else 0

        def ideal(n: np.ndarray) -> bool:
            if n.shape[0] == 0:
                return False
            br = lie.bracket(Ssum[:, None, :], n[None, :, :]).reshape(-1, 6)
            return rank(np.concatenate([n, br], axis=0)) == rank(n)

        def translation_part(Bx: np.ndarray) -> np.ndarray:
            if Bx.shape[0] == 0:
                return Bx
            A = np.concatenate([Bx, -_translations(bk)], axis=0).T
            _d, N = _linalg.null_space(A, prec, L)
            if N is None or N.shape[0] == 0:
                return Bx[:0]
            return N[:, : Bx.shape[0]] @ Bx

        for n, other, what in (
            (B1, B2, f"{a.symbol} is normal in the product"),
            (B2, B1, f"{b.symbol} is normal in the product"),
            (translation_part(B1), B2, f"the translations of {a.symbol} form an ideal"),
            (translation_part(B2), B1, f"the translations of {b.symbol} form an ideal"),
        ):
            if ideal(n) and rank(np.concatenate([n, other], axis=0)) == m:
                return Product(True, gen.subgroup, gen, m, what)
        return Product(None, None, gen, m, "the sum is a subalgebra; no sufficient condition found")
