"""Subgroup instances: a catalog type with its geometric parameters.

Parameters may be floats, mpmath numbers or sympy exact numbers; the instance
keeps the backend of what it was given (exact stays exact).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.lie import ANGULAR
from mechsing.numeric import (
    NEAR_ZERO_VECTOR,
    Backend,
    Precision,
    backend_of,
    coarser_backend,
    parse_precision,
    scale_screws,
    screw_zero_rtol,
    to_float,
)
from mechsing.numeric.backend import holds_objects
from mechsing.numeric.lazy import sympy
from mechsing.numeric.pirational import PiRational, rational_sqrt
from mechsing.subgroups import _linalg
from mechsing.subgroups.types import SubgroupType, _cross, load_catalog

__all__ = ["Subgroup", "as_precision"]

_VECTOR_KINDS = ("direction", "normal", "point")


def as_precision(p: Any, *arrays: Any) -> Precision:
    """A Precision from a Precision, a mode string, a Backend, or (None) the data."""
    if isinstance(p, Precision):
        return p
    if isinstance(p, str):
        return parse_precision(p)
    if isinstance(p, Backend):
        bk = p
    elif any(isinstance(x, PiRational) for a in arrays for x in np.asarray(a, dtype=object).flat):
        return Precision("exact")  # the file's exact numbers
    else:
        bk = backend_of(*arrays)
    return Precision.of(bk)


def _norm2(v: np.ndarray) -> Any:
    return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]


def _plain_parameters(t: SubgroupType, raw: Mapping[str, np.ndarray]) -> bool:
    """Are the parameters the file's plain numbers (PiRational), every direction of a
    rational length (normalised without sympy)?"""
    values = [x for v in raw.values() for x in v.flat]
    if not values or not all(isinstance(x, PiRational) for x in values):
        return False
    return all(
        raw[n].shape == (3,) and rational_sqrt(_norm2(raw[n])) is not None
        for n, kind in t.parameters
        if kind in _VECTOR_KINDS and kind != "point"
    )


def _plain_params(t: SubgroupType, raw: Mapping[str, np.ndarray]) -> dict[str, Any]:
    """The parameters of PiRational numbers, checked as the exact backend checks them,
    directions made unit exactly (their lengths are rational)."""
    out: dict[str, Any] = {}
    for name, kind in t.parameters:
        val = raw[name]
        if kind in _VECTOR_KINDS:
            if val.shape != (3,):
                raise ValueError(f"subgroup {t.symbol}: {name} must be 3 numbers, got {val!r}")
            if kind != "point":
                if np.linalg.norm(to_float(val)) <= NEAR_ZERO_VECTOR:
                    raise ValueError(
                        f"subgroup {t.symbol}: {name} {val.tolist()!r} is zero or nearly so; "
                        "give a non-zero direction"
                    )
                val = val / rational_sqrt(_norm2(val))
            out[name] = val
        else:
            if val.shape != ():
                raise ValueError(f"subgroup {t.symbol}: {name} must be one number")
            if name in t.nonzero and val[()] == 0:
                raise ValueError(
                    f"subgroup {t.symbol}: {name} must not be zero "
                    f"(a zero {name} is a different type)"
                )
            out[name] = val[()]
    return out


def _sympy_array(v: np.ndarray) -> np.ndarray:
    """An array with its PiRational entries as sympy's values."""
    if not any(isinstance(x, PiRational) for x in np.asarray(v).flat):
        return v
    out = np.empty(np.shape(v), dtype=object)
    for idx, x in np.ndenumerate(np.asarray(v, dtype=object)):
        out[idx] = x._sympy_() if isinstance(x, PiRational) else x
    return out


def _first_nonzero_positive(v: np.ndarray, bk: Backend) -> np.ndarray:
    for x in v:
        if not bk.is_zero(x):
            return -v if bk.negative(x) else v
    return v


class Subgroup:
    """A connected Lie subgroup of D: a catalog type and its parameters.

    Parameters
    ----------
    type : SubgroupType or str
        The type or its symbol (``"R"``, ``"T2"`` ...).
    params : mapping, optional
        Parameter values by name (the mechanism-file keys of the type); may
        also be given as keyword arguments.  Directions and normals are
        normalised; a near-zero direction, a missing or unknown key, and a zero
        pitch where the type forbids it raise ``ValueError``.

    Examples
    --------
    >>> r = Subgroup("R", axis=[0, 0, 2], point=[1, 0, 0])
    >>> r.symbol, r.dim, [float(x) for x in r.params["axis"]]
    ('R', 1, [0.0, 0.0, 1.0])
    """

    def __init__(
        self, type: SubgroupType | str, params: Mapping[str, Any] | None = None, **kw: Any
    ):
        t = load_catalog()[type] if isinstance(type, str) else type
        given = dict(params or {}, **kw)
        names = t.parameter_names
        missing = [n for n in names if n not in given]
        extra = [n for n in given if n not in names]
        if missing or extra:
            need = ", ".join(names) or "no parameters"
            raise ValueError(
                f"subgroup {t.symbol} takes {need}"
                + (f"; missing {', '.join(missing)}" if missing else "")
                + (f"; unknown {', '.join(extra)}" if extra else "")
            )
        raw = {n: np.asarray(given[n], dtype=object) for n in names}
        plain = _plain_parameters(t, raw)
        if raw and not plain:  # the file's plain numbers where sympy is needed: its values
            raw = {n: _sympy_array(v) for n, v in raw.items()}
        bk = backend_of(*raw.values()) if raw else Precision("float").backend
        self.type: SubgroupType = t
        #: exact parameters the file wrote as PiRational numbers: made sympy's (and the
        #: backend exact) only when a computation asks for the backend
        self._plain = plain
        self._backend: Backend | None = None if plain else bk
        self.params: dict[str, Any] = {}
        if plain:
            self.params = _plain_params(t, raw)
            return
        for name, kind in t.parameters:
            val = raw[name]
            if kind in _VECTOR_KINDS:
                if val.shape != (3,):
                    raise ValueError(
                        f"subgroup {t.symbol}: {name} must be 3 numbers, got {given[name]!r}"
                    )
                v = bk.asarray(val)
                fv = to_float(v)
                if not np.all(np.isfinite(fv)):
                    raise ValueError(
                        f"subgroup {t.symbol}: {name} must be finite, got {given[name]!r}"
                    )
                if kind != "point":
                    if np.linalg.norm(fv) <= NEAR_ZERO_VECTOR:
                        raise ValueError(
                            f"subgroup {t.symbol}: {name} {given[name]!r} is zero or nearly so; "
                            "give a non-zero direction"
                        )
                    v = bk.simplify(v / bk.sqrt(np.asarray(_norm2(v)))[()])
                self.params[name] = v
            else:
                if val.shape != ():
                    raise ValueError(f"subgroup {t.symbol}: {name} must be one number")
                h = bk.asarray(val)[()]
                if not np.isfinite(to_float(h)):
                    raise ValueError(f"subgroup {t.symbol}: {name} must be finite")
                if name in t.nonzero and bk.is_zero(h, 0):  # exactly zero
                    raise ValueError(
                        f"subgroup {t.symbol}: {name} must not be zero "
                        f"(a zero {name} is a different type)"
                    )
                self.params[name] = h

    @property
    def backend(self) -> Backend:
        """The parameters' backend (exact for a file's numbers)."""
        if self._backend is None:  # PiRational parameters: sympy's values, as exact mode has
            self.params = {k: _sympy_array(v) for k, v in self.params.items()}
            self._backend = backend_of(*self.params.values())
            self._plain = False
        return self._backend

    @backend.setter
    def backend(self, bk: Backend) -> None:
        self._backend, self._plain = bk, False

    # -- description --------------------------------------------------------

    @property
    def symbol(self) -> str:
        return self.type.symbol

    @property
    def dim(self) -> int:
        return self.type.dimension

    def __repr__(self) -> str:
        ps = ", ".join(f"{k}={_show(v)}" for k, v in self.params.items())
        return f"Subgroup({self.symbol}{', ' if ps else ''}{ps})"

    def _params_in(self, prec: Precision) -> dict[str, Any]:
        if not self._plain and prec.backend.accepts(self.backend):
            return self.params
        out = {}
        for k, v in self.params.items():
            out[k] = _linalg.convert(np.asarray(v), prec)
            if out[k].shape == ():
                out[k] = out[k][()]
        return out

    def basis(self, precision: Any = None) -> np.ndarray:
        """The subalgebra basis ``(dim, 6)``, catalog order, in the in-plane convention.

        ``precision``: a Precision, a mode string or a Backend; default: the
        parameters' own backend (exact parameters give an exact basis).
        """
        prec = as_precision(precision, *self.params.values())
        with prec.context():
            return self.type.basis(self._params_in(prec), prec.backend)

    def scaled_basis(
        self, length_scale: Any = 1.0, centre: Any = None, precision: Any = None
    ) -> np.ndarray:
        """The basis made commensurate (docs/precision.md, "Margins"): moved to ``centre``, v rows / L."""
        B = self.basis(precision)
        return scale_screws(B.T, length_scale, centre).T

    def rotation_axis(self, precision: Any = None) -> tuple[Any, Any, Any] | None:
        """``(u, point, pitch)`` of the basis screw that rotates, for types whose
        rotations are about one direction (R, H, C, G, Y, X); None otherwise."""
        if self.type.rotation_rank != 1:
            return None
        B = self.basis(precision)
        bk = backend_of(B)
        i = int(np.argmax(np.abs(to_float(B[:, ANGULAR])).sum(axis=1)))
        w, v = B[i, 0:3], B[i, 3:6]
        n2 = _norm2(w)
        return w / bk.sqrt(np.asarray(n2))[()], _cross(w, v) / n2, (w @ v) / n2

    # -- moving and comparing -------------------------------------------------

    def conjugate(self, g: Any) -> Subgroup:
        """``g H g^-1``: the same type with its parameters moved by ``g`` (4x4)."""
        g = np.asarray(g)
        bk = backend_of(g, *self.params.values())
        prec = as_precision(bk)
        g = _linalg.convert(g, prec)
        R, p = g[:3, :3], g[:3, 3]
        new: dict[str, Any] = {}
        for (name, kind), val in zip(
            self.type.parameters, self._params_in(prec).values(), strict=True
        ):
            if kind == "point":
                new[name] = R @ val + p
            elif kind in ("direction", "normal"):
                new[name] = R @ val
            else:
                new[name] = val
        return Subgroup(self.type, {k: bk.simplify(v) for k, v in new.items()})

    def canonical(self) -> Subgroup:
        """The same subgroup with canonical parameters (recognising a subgroup from spanning screws): directions
        with their first non-zero component positive, points nearest the origin
        (a point is slid along the type's direction when the type has one)."""
        bk = self.backend
        new: dict[str, Any] = {}
        direction = None
        for name, kind in self.type.parameters:
            val = self.params[name]
            if kind in ("direction", "normal"):
                val = _first_nonzero_positive(val, bk)
                direction = val if direction is None else direction
            new[name] = val
        for name, kind in self.type.parameters:
            if kind == "point" and direction is not None:
                p = new[name]
                new[name] = p - (p @ direction) * direction
        new = {k: bk.simplify(v) for k, v in new.items()}
        out = Subgroup.__new__(Subgroup)
        out.type, out.backend, out.params = self.type, bk, new
        return out

    def equals(self, other: Subgroup, length_scale: float = 1.0) -> bool:
        """Same type and same canonical parameters (relative tolerance from
        :mod:`mechsing.numeric`; exactly in exact mode)."""
        if not isinstance(other, Subgroup) or other.type.symbol != self.type.symbol:
            return False
        a, b = self.canonical(), other.canonical()
        bk = coarser_backend(a.backend, b.backend)
        for name, kind in self.type.parameters:
            x, y = a.params[name], b.params[name]
            fx, fy = np.atleast_1d(to_float(x)), np.atleast_1d(to_float(y))
            scale = length_scale if kind in ("point", "pitch") else 1.0
            ref = max(scale, float(np.max(np.abs(fx))), float(np.max(np.abs(fy))))
            d = np.atleast_1d(bk.asarray(x) - bk.asarray(y))
            if not all(bk.is_zero(v, ref) for v in d):
                return False
        return True

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Subgroup) and self.equals(other)

    __hash__ = None  # type: ignore[assignment]  # equality has a tolerance

    # -- membership -----------------------------------------------------------

    def contains_screw(self, xi: Any, length_scale: float = 1.0, precision: Any = None) -> Any:
        """Is the screw (or each screw of a batch (..., 6)) in the subalgebra?

        Decided in the commensurate metric (v / ``length_scale``) on the
        residual of the projection, relative to the screw's norm:
        ``<= screw_zero_rtol`` (1e-9 in float), exactly in exact mode.
        """
        xi = np.asarray(xi)
        prec = as_precision(precision, xi, *self.params.values())
        with prec.context():
            x = _linalg.convert(xi, prec).reshape(-1, 6)
            B = self.basis(prec)
            if prec.mode == "exact":
                # left as a branch: exact membership is an exact rank (the length scale
                # changes nothing); float and mp measure the projection residual in float
                # below (mp's own residual would change mp verdicts: a later step)
                out = []
                for row in x:
                    M = sympy.Matrix([list(r) for r in B] + [list(row)])
                    out.append(M.rank(simplify=True) == B.shape[0])
                return np.array(out).reshape(xi.shape[:-1])[()] if xi.ndim > 1 else out[0]
            Bs = to_float(scale_screws(B.T, length_scale).T)
            xs = to_float(scale_screws(x.T, length_scale).T)
            if Bs.shape[0]:
                q, _ = np.linalg.qr(Bs.T)
                res = xs - (xs @ q) @ q.T
            else:
                res = xs
            tol = float(screw_zero_rtol(prec.backend))
            ok = np.linalg.norm(res, axis=1) <= tol * np.maximum(np.linalg.norm(xs, axis=1), 1e-300)
            ok |= np.linalg.norm(xs, axis=1) == 0
            return ok.reshape(xi.shape[:-1])[()] if xi.ndim > 1 else bool(ok[0])

    def chart(self, q: Any, precision: Any = None) -> np.ndarray:
        """The element ``exp(sum q_i e_i)`` of canonical coordinates ``q`` (dim,).

        ``precision``: a Precision or mode string; default: that of q and the parameters.
        """
        q = np.asarray(q)
        prec = as_precision(precision, q, *self.params.values())
        with prec.context():
            qq = _linalg.convert(q, prec).reshape(self.dim)
            B = self.basis(prec)
            xi = qq @ B if self.dim else prec.backend.zeros(6)
            return lie.exp(xi)

    element = chart

    def coordinates_of(self, g: Any, precision: Any = None) -> np.ndarray:
        """Canonical coordinates q with ``chart(q) == g`` for g in the subgroup.

        Angles are principal, in (-pi, pi], except where the subgroup forces a
        global slide: when the rotating basis screw has a non-zero pitch h and
        the translation along its axis is not in the subgroup (H, Y), the angle
        is read from the slide, ``angle = slide / h``, so it does not wrap.
        Spherical coordinates are the principal rotation vector (``|angle| <= pi``).
        For g outside the subgroup the result is a least-squares projection;
        :meth:`contains` checks it.  For a helical-translating (Y) element whose
        angle is a non-zero multiple of 2 pi with a translation across the
        axis, no first-kind coordinates exist: ``ValueError``.

        ``precision``: a Precision or mode string (the arithmetic of the result);
        default: that of g and the parameters (exact parameters give exact
        coordinates of an exact g).
        """
        g = np.asarray(g)
        prec = as_precision(precision, g, *self.params.values())
        with prec.context():
            gg = _linalg.convert(g, prec)
            bk = prec.backend
            B = self.basis(prec)
            if self.dim == 0:
                return bk.zeros(0)
            R, p = gg[:3, :3], gg[:3, 3]
            r = self.type.rotation_rank
            if r == 0:
                xi = np.concatenate([bk.zeros(3), p])
            elif r == 3:
                xi = lie.log(gg)
            else:
                return self._coordinates_one_axis(R, p, B, prec)
            q = _linalg.solve_coefficients(B, xi, prec)
            return q

    def _coordinates_one_axis(
        self, R: np.ndarray, p: np.ndarray, B: np.ndarray, prec: Precision
    ) -> np.ndarray:
        """Coordinates when all rotations are about one direction u: the angle a
        (global when pitched), then the other coordinates from the translation
        part of the twist ``(a u, V(a u)^-1 p)``."""
        a, xi = _xi_one_axis(self, R, p, prec)
        bk = prec.backend
        fw = to_float(B[:, ANGULAR])
        i = int(np.argmax(np.abs(fw).sum(axis=1)))
        others = [j for j in range(B.shape[0]) if j != i]
        if any(np.any(fw[j] != 0) for j in others):  # not the catalog's layout: least squares
            return _linalg.solve_coefficients(B, xi, prec)
        q = bk.zeros(B.shape[0])
        q[i] = a / bk.sqrt(np.asarray(B[i, 0:3] @ B[i, 0:3]))[()]
        if others:
            rest = _linalg.solve_coefficients(B[others], xi - q[i] * B[i], prec)
            for j, val in zip(others, rest, strict=True):
                q[j] = val
        return bk.simplify(q)

    def contains(
        self,
        g: Any,
        length_scale: float = 1.0,
        precision: Any = None,
        coordinates: Any = None,
    ) -> bool:
        """Is the displacement ``g`` (4x4) an element of the subgroup?

        Compares ``chart(coordinates_of(g))`` with g: rotation entries and
        translation / ``length_scale`` within ``screw_zero_rtol`` of the
        precision (1e-9 in float, 10^(-N/2) at mp:N) times ``max(1, |p| / L)``;
        exactly in exact mode.

        ``precision``: the mode that decides (a Precision or mode string);
        default: that of g and the parameters (exact parameters and an exact g
        decide exactly).  ``coordinates``: g's coordinates when already computed
        (:meth:`coordinates_of`), to save computing them again.
        """
        g = np.asarray(g)
        prec = as_precision(precision, g, *self.params.values())
        with prec.context():
            gg = _linalg.convert(g, prec)
            if coordinates is not None:
                q = _linalg.convert(np.asarray(coordinates), prec)
            else:
                try:
                    q = self.coordinates_of(gg, prec)
                except ValueError:
                    return False
            g2 = self.chart(q, prec)
            d = g2 - gg
            bk = prec.backend
            ref = max(1.0, float(np.linalg.norm(to_float(gg[:3, 3]))) / length_scale)
            return all(bk.is_zero(x, ref) for x in d[:3, :3].flat) and all(
                bk.is_zero(x, ref * length_scale) for x in d[:3, 3]
            )

    def completing_translation(self, R: Any, precision: Any = None) -> np.ndarray:
        """The translation that completes the rotation ``R`` to an element of the subgroup.

        It is the translation of ``exp(xi)`` where xi combines the rotating basis
        screws only (no slide) and has the rotation of R (principal angle); for
        a pitched type (H, Y) it includes the slide the pitch couples to the
        angle.  When no element of the subgroup has the rotation R, xi is the
        least-squares fit and :meth:`contains` refuses the completed element.
        ``precision`` as in :meth:`coordinates_of`.
        """
        R = np.asarray(R)
        prec = as_precision(precision, R, *self.params.values())
        with prec.context():
            RR = _linalg.convert(R, prec)
            B = self.basis(prec)
            rotating = [i for i in range(B.shape[0]) if np.any(to_float(B[i, 0:3]) != 0)]
            if not rotating:
                return prec.backend.zeros(3)
            Br = B[rotating]
            coef = _linalg.solve_coefficients(Br[:, ANGULAR], lie.log_so3(RR), prec)
            return lie.exp(coef @ Br)[:3, 3]


def _show(v: Any) -> str:
    arr = np.asarray(v)
    if holds_objects(arr):
        return "[" + ", ".join(str(x) for x in arr.flat) + "]" if arr.ndim else str(arr[()])
    return np.array2string(arr, precision=6) if arr.ndim else f"{float(arr):.6g}"


def _xi_one_axis(
    sg: Subgroup, R: np.ndarray, p: np.ndarray, prec: Precision
) -> tuple[Any, np.ndarray]:
    """The angle about a one-axis subgroup's direction u (global when pitched) and the
    twist ``(a u, V(a u)^-1 p)`` of the displacement ``(R, p)``."""
    bk = prec.backend
    u, _pt, h0 = sg.rotation_axis(prec)  # type: ignore[misc]
    slide = u @ p
    axial = np.concatenate([bk.zeros(3), u])
    if sg.type.pitched and not sg.contains_screw(axial, precision=prec):
        a = slide / h0
    else:
        s_vec = lie.vee3((R - R.T) / 2)
        y, x = u @ s_vec, (R[0, 0] + R[1, 1] + R[2, 2] - 1) / 2
        if bk.is_zero(y, 0) and bk.is_zero(x, 0):
            # no rotation about u at all (a half turn about a perpendicular axis): the
            # projection's angle is 0 (atan2(0, 0) is undefined, in exact arithmetic too)
            a = bk.convert(0)
        else:
            a = bk.atan2(np.asarray(y), np.asarray(x))[()]
    a = bk.simplify(a)
    p_perp = p - slide * u
    # V(a u) on the plane normal to u is s I + c J (J = u x): invert it.
    # the series below the switch point (exactly a = 0 in exact mode: its limit)
    small = a == 0 or abs(to_float(a)) < bk.threshold(4)
    aa = a if not small else bk.convert(1)
    s = 1 - a * a / 6 if small else bk.sin(np.asarray(aa))[()] / aa
    c = a / 2 - a * a * a / 24 if small else (1 - bk.cos(np.asarray(aa))[()]) / aa
    det = s * s + c * c
    Jp = _cross(u, p_perp)
    translations_across = sg.dim > 1
    if bk.is_zero(det, 0) or not translations_across:
        if translations_across and not all(bk.is_zero(x, 0) for x in p_perp):
            raise ValueError(
                f"{sg.symbol}: this element turns a whole number of turns while moving "
                "across its axis; it has no first-kind exponential coordinates"
            )
        v_perp = p_perp * 0
    else:
        v_perp = (s * p_perp - c * Jp) / det
    xi = np.concatenate([a * u, v_perp + slide * u])
    return a, xi
