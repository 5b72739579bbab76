"""Exact kinematics of one configuration in the number field of its data.

In exact mode a configuration's joint elements, body poses, current screws and chord
residuals are computed in the algebraic number field K that the geometry and the
joint values generate (:func:`mechsing.numeric.field.number_field`): a revolute
coordinate enters through the cosine and sine of its angle (radicals, found by
:func:`mechsing.numeric.field.cos_sin`), a prismatic one through its length.  The
element of a one-dof screw ``e = (u, v)``, ``|u| = 1``, ``u . v = 0`` at angle theta
is the Rodrigues form ``R = I + s K + (1 - c) K^2``, ``p = (1 - c) u x v + s v``
(``K = u^``; the closed form of :func:`mechsing.lie.exp`, whose ``theta v`` terms
cancel exactly for a pure rotation); a translation ``e = (0, v)`` gives ``p = d v``.
Joints whose rows commute (C, planar, translational) are products of their rows'
elements, a U joint the product of its two turns.

An S joint's rotation vector w turns by the angle |w| (its cosine and sine as radicals)
about the unit axis w / |w| through the joint's centre c: ``p = (I - R) c``.

Not a fast path that ``MECHSING_FAST=0`` turns off (:mod:`mechsing.numeric.dispatch`):
the sympy path does not prove every zero the field proves (without it, the 3-RPR's
concurrent configuration is not proved closed).  What does not fit falls back to the
sympy path (:meth:`FieldKinematics.of` returns
None): an H joint (its translation ``pitch * theta`` is transcendental), a non-abelian
joint other than S at a non-zero value, an angle whose sine sympy cannot write as
radicals, an S joint's axis that is not, geometry that is not written in radicals.

The arrays handed out are sympy numbers (``K.to_sympy``: rationals, or short sums of
radicals), equal to what the sympy path computes.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.numeric.field import cos_sin, from_field, number_field

__all__ = ["FieldKinematics"]


def _rot(K: Any, u: list[Any], c: Any, s: Any, v: list[Any]) -> np.ndarray:
    one, zero = K.one, K.zero
    Ku = [[zero, -u[2], u[1]], [u[2], zero, -u[0]], [-u[1], u[0], zero]]
    K2 = [[_dot(K, Ku[i], [Ku[k][j] for k in range(3)]) for j in range(3)] for i in range(3)]
    c1 = one - c
    g = np.empty((4, 4), dtype=object)
    for i in range(3):
        for j in range(3):
            g[i, j] = _dot(K, [one if i == j else zero, s, c1], [one, Ku[i][j], K2[i][j]])
    uxv = _cross(K, u, v)
    for i in range(3):
        g[i, 3] = _dot(K, [c1, s], [uxv[i], v[i]])
    g[3, :3] = zero
    g[3, 3] = one
    return g


def _turn(jk: Any, vals: list[Any]) -> list[Any] | None:
    """An S joint's rotation vector ``w = sum q_i u_i`` as (cos, sin) of its angle
    ``|w|`` and its unit axis ``w / |w|`` (sympy numbers), or None when they are not
    written in radicals."""
    import sympy

    w = [
        sum((q * e[k] for q, e in zip(vals, jk.basis, strict=True)), sympy.S.Zero) for k in range(3)
    ]
    theta = sympy.sqrt(sum((x * x for x in w), sympy.S.Zero))
    cs = cos_sin(theta)
    if cs is None:
        return None
    axis = [sympy.cancel(x / theta) for x in w]
    if not all(_in_radicals(x) for x in axis):
        return None
    return [*cs, *axis]


def _in_radicals(x: Any) -> bool:
    return number_field([x]) is not None


def _spherical(K: Any, B: np.ndarray, turn: list[Any]) -> np.ndarray | None:
    """The element of an S joint (basis rows ``(u_i, c x u_i)``, ``u_i`` orthonormal) that
    turns by the angle of (cos, sin) about the unit axis n through its centre c:
    ``R = I + s N + (1 - c) N^2``, ``p = (I - R) c`` (None if the basis is not of that form)."""
    c, s, *n = turn
    U = [list(B[i, :3]) for i in range(3)]
    for i in range(3):
        for j in range(3):
            dot = sum((a * b for a, b in zip(U[i], U[j], strict=True)), K.zero)
            if dot != (K.one if i == j else K.zero):
                return None
    # sum_i u_i x (c x u_i) = sum_i (c - u_i (u_i . c)) = 2 c for an orthonormal u_i
    half = K.one / (K.one + K.one)
    centre = [K.zero] * 3
    for i in range(3):
        u, v = U[i], list(B[i, 3:])
        if sum((a * b for a, b in zip(u, v, strict=True)), K.zero) != K.zero:
            return None
        uxv = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        centre = [a + half * b for a, b in zip(centre, uxv, strict=True)]
    if sum((x * x for x in n), K.zero) != K.one:
        return None
    v = [
        centre[1] * n[2] - centre[2] * n[1],
        centre[2] * n[0] - centre[0] * n[2],
        centre[0] * n[1] - centre[1] * n[0],
    ]
    return _rot(K, n, c, s, v)


def _trans(K: Any, v: list[Any], d: Any) -> np.ndarray:
    g = _eye(K)
    for i in range(3):
        g[i, 3] = d * v[i]
    return g


def _eye(K: Any) -> np.ndarray:
    g = np.empty((4, 4), dtype=object)
    g.fill(K.zero)
    for i in range(4):
        g[i, i] = K.one
    return g


def _dot(K: Any, a: Any, b: Any) -> Any:
    """``sum a_k b_k`` in K, skipping the products with a zero factor (axes and rotation
    matrices are sparse; a product in an algebraic field costs a polynomial remainder)."""
    out = K.zero
    for x, y in zip(a, b, strict=True):
        if x and y:
            out = out + x * y
    return out


def _compose(K: Any, g: np.ndarray, h: np.ndarray) -> np.ndarray:
    """``g h`` for two displacements (4 x 4, last row 0 0 0 1), elements of K: the
    rotation block and the translation only."""
    out = _eye(K)
    for i in range(3):
        row = g[i, :3]
        for j in range(3):
            out[i, j] = _dot(K, row, h[:3, j])
        out[i, 3] = _dot(K, row, h[:3, 3]) + g[i, 3]
    return out


def _inverse(K: Any, g: np.ndarray) -> np.ndarray:
    out = _eye(K)
    Rt = g[:3, :3].T
    out[:3, :3] = Rt
    for i in range(3):
        out[i, 3] = -_dot(K, Rt[i], g[:3, 3])
    return out


def _cross(K: Any, a: Any, b: Any) -> list[Any]:
    return [
        _dot(K, [a[1], -a[2]], [b[2], b[1]]),
        _dot(K, [a[2], -a[0]], [b[0], b[2]]),
        _dot(K, [a[0], -a[1]], [b[1], b[0]]),
    ]


def _act(K: Any, g: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Ad(g) e: (R w, p x R w + R v), elements of K."""
    R, p = g[:3, :3], g[:3, 3]
    w = [_dot(K, R[i], e[:3]) for i in range(3)]
    Rv = [_dot(K, R[i], e[3:]) for i in range(3)]
    pxw = _cross(K, p, w)
    return np.array(w + [a + b for a, b in zip(pxw, Rv, strict=True)], dtype=object)


def _frozen(a: np.ndarray) -> np.ndarray:
    # handed out to every caller of the configuration: read-only
    a.flags.writeable = False
    return a


class FieldKinematics:
    """Poses, current screws and chord residuals of one exact configuration, computed
    in the number field K of its data (see the module's docstring).

    Build with :meth:`of`; ``K`` is the field, ``degree`` its degree over Q."""

    def __init__(
        self,
        model: Any,
        K: Any,
        elements: dict[str, np.ndarray],
        basis: dict[str, np.ndarray],
        u_first: dict[str, tuple[Any, Any]],
    ) -> None:
        self.model = model
        self._u_first = u_first
        self.K = K
        self._elements = elements
        self._basis = basis
        self._poses: dict[str, np.ndarray] | None = None
        self._poses_sympy: dict[str, np.ndarray] | None = None
        self._screws_sympy: np.ndarray | None = None
        self._residuals_sympy: list[np.ndarray] | None = None

    @property
    def degree(self) -> int:
        K = self.K
        return 1 if K.is_QQ else int(K.mod.degree())

    @classmethod
    def of(cls, model: Any, q: np.ndarray) -> FieldKinematics | None:
        """The field kinematics of the exact configuration ``q`` (n,), or None when a
        joint or a datum does not fit a number field (the sympy path then serves)."""
        # what each row of each joint needs: ("R", row, angle) or ("P", row, length)
        plan: list[tuple[Any, list[tuple[str, int, Any]]]] = []
        needed: list[Any] = []
        for jk in model.joints:
            vals = [q[c] for c in range(jk.columns.start, jk.columns.stop)]
            rows = []
            if jk.type != "U" and not jk.abelian:
                if all(v == 0 for v in vals):
                    plan.append((jk, []))
                    continue
                turn = _turn(jk, vals) if jk.type == "S" else None
                if turn is None:
                    return None  # other non-abelian joints away from zero: sympy
                plan.append((jk, [("S", 0, len(needed))]))
                needed.extend(turn)
                continue
            for i, (e, val) in enumerate(zip(jk.basis, vals, strict=True)):
                if all(x == 0 for x in e[:3]):
                    rows.append(("P", i, len(needed)))
                    needed.append(val)
                else:
                    cs = cos_sin(val)
                    if cs is None:
                        return None
                    rows.append(("R", i, len(needed)))
                    needed.extend(cs)
            plan.append((jk, rows))
        geometry_at = len(needed)
        for jk in model.joints:
            needed.extend(jk.basis.flat)
        fit = number_field(needed)
        if fit is None:
            return None
        K, els = fit
        at = geometry_at
        basis: dict[str, np.ndarray] = {}
        for jk in model.joints:
            k = jk.basis.size
            basis[jk.name] = np.array(els[at : at + k], dtype=object).reshape(jk.basis.shape)
            at += k
        elements: dict[str, np.ndarray] = {}
        u_first: dict[str, tuple[Any, Any]] = {}
        for jk, rows in plan:
            B = basis[jk.name]
            g = _eye(K)
            for kind, i, where in rows:
                u, v = list(B[i, :3]), list(B[i, 3:])
                if kind == "P":
                    gi = _trans(K, v, els[where])
                elif kind == "S":
                    gi = _spherical(K, B, els[where : where + 5])
                    if gi is None:
                        return None
                else:
                    uu = sum((x * x for x in u), K.zero)
                    uv = sum((a * b for a, b in zip(u, v, strict=True)), K.zero)
                    if uu != K.one or uv != K.zero:
                        return None  # a pitch (H) or an axis not of unit length: sympy
                    gi = _rot(K, u, els[where], els[where + 1], v)
                    if jk.type == "U" and i == 0:
                        u_first[jk.name] = (els[where], els[where + 1])
                g = _compose(K, g, gi)
            elements[jk.name] = g
        return cls(model, K, elements, basis, u_first)

    # ------------------------------------------------------------ in the field

    def poses_in_field(self) -> dict[str, np.ndarray]:
        """Every user body's pose (ground = identity), elements of K."""
        if self._poses is None:
            model, K = self.model, self.K
            mech = model.mech
            out: dict[str, np.ndarray] = {mech.ground: _eye(K)}
            for body, steps in sorted(mech.graph.tree_paths.items(), key=lambda kv: len(kv[1])):
                if body in out or not steps:
                    continue
                last = steps[-1]
                if last.part is not None:
                    continue  # hidden cross bodies (as forward.poses)
                jk = model.joint(last.joint)
                prev = out[jk.a if last.sign > 0 else jk.b]
                M = self._elements[jk.name]
                out[body] = _compose(K, prev, M if last.sign > 0 else _inverse(K, M))
            self._poses = out
        return self._poses

    def screws_in_field(self) -> np.ndarray:
        """The current screws (6, n), elements of K."""
        poses = self.poses_in_field()
        cols = []
        for jk in self.model.joints:
            B = self._basis[jk.name]
            ga = poses[jk.a]
            if jk.type == "U":
                cols.append(_act(self.K, ga, B[0]))
                first = _rot(self.K, list(B[0, :3]), *self._cs_of_u(jk), list(B[0, 3:]))
                cols.append(_act(self.K, _compose(self.K, ga, first), B[1]))
            else:
                cols.extend(_act(self.K, ga, e) for e in B)
        if not cols:
            out = np.empty((6, 0), dtype=object)
            return out
        return np.stack(cols, axis=-1)

    def _cs_of_u(self, jk: Any) -> tuple[Any, Any]:
        # (cos, sin) of a U joint's first angle: its second screw is carried by
        # g_a exp(q1 b0)
        return self._u_first[jk.name]

    def residuals_in_field(self) -> list[np.ndarray]:
        """``Delta_j = g_a M_j g_b^-1`` for each chord joint, elements of K."""
        poses = self.poses_in_field()
        return [
            _compose(
                self.K,
                _compose(self.K, poses[jk.a], self._elements[jk.name]),
                _inverse(self.K, poses[jk.b]),
            )
            for jk in self.model.chords
        ]

    def closes(self) -> list[bool]:
        """Does each chord's loop close?  Exactly: its residual is the identity in K."""
        eye = _eye(self.K)
        return [bool(np.all(D == eye)) for D in self.residuals_in_field()]

    # ------------------------------------------------------------ as sympy numbers

    def poses(self) -> dict[str, np.ndarray]:
        if self._poses_sympy is None:
            self._poses_sympy = {
                b: _frozen(from_field(self.K, g)) for b, g in self.poses_in_field().items()
            }
        return dict(self._poses_sympy)

    def current_screws(self) -> np.ndarray:
        if self._screws_sympy is None:
            self._screws_sympy = from_field(self.K, self.screws_in_field())
        return self._screws_sympy.copy()

    def chord_residuals(self) -> list[np.ndarray]:
        if self._residuals_sympy is None:
            self._residuals_sympy = [from_field(self.K, D) for D in self.residuals_in_field()]
        return [D.copy() for D in self._residuals_sympy]
