"""Closure of many configurations at once, in float: the batched Newton of the sweeps.

Owns :class:`BatchClosure`: the chord residuals, the closure Jacobian and the update on
the group of a float :class:`~mechsing.kinematics.KinematicModel` (and, for a sweep of
the output's pose, of its :class:`~mechsing.kinematics.pose.PoseModel`), written for an
array of configurations ``Q`` of shape ``(N, n)`` with :mod:`mechsing.lie` (which
broadcasts over leading axes), and :meth:`BatchClosure.newton`, damped Gauss-Newton on
the group for all rows together.  The one-configuration kinematics
(:mod:`mechsing.kinematics.forward`) computes the poses and screws; this module adds what
closing a batch needs.  Nothing here decides a rank: it closes.

Conventions: those of :mod:`mechsing.kinematics.model`.  Residual twists and Jacobian
rows are commensurate (moved to the centroid, v / L, length columns times L), as in
:func:`mechsing.kinematics.newton.scaled_system`; the residual norm is the length of
:meth:`KinematicModel.residual_norm` (m).  With a pose model the coordinate vector is
the joints' followed by the six pose coordinates ``(rx, ry, rz, x, y, z)``, which are
always given (never moved by Newton).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Literal

import numpy as np

from mechsing import lie
from mechsing.kinematics import forward
from mechsing.kinematics.chains import tree_chain
from mechsing.kinematics.couplings import coupling_residuals
from mechsing.kinematics.jacobians import chord_signs
from mechsing.kinematics.settings import NEWTON_DAMPING
from mechsing.lie import exp_so3, log_so3
from mechsing.numeric import Precision

__all__ = ["BatchClosure", "truncated_steps"]


class BatchClosure:
    """Batched float closure of one kinematic model (or pose model).

    Parameters
    ----------
    model : a float KinematicModel, or a PoseModel on one
    """

    def __init__(self, model: Any) -> None:
        base = getattr(model, "base", model)
        if base.backend.name != "float":
            raise ValueError("BatchClosure works in float")
        self.model = model
        self.base = base
        self.nb: int = base.n
        self.n: int = model.n
        self.pose = model if model is not base else None
        self.L = float(base.length_scale)
        self.c = np.asarray(base.float_frame.c, dtype=float)
        self.frame = base.float_frame
        self.chords = list(base.chords)
        self.signs = np.array(chord_signs(base), dtype=float).reshape(-1, self.nb)
        if self.pose is not None:
            out = base.mech.output
            self.pose_a, self.pose_b = out.relative_to, out.body
            self.pose_signs = tree_chain(base, out.relative_to, out.body).signs.astype(float)
            self.c0 = np.asarray(self.pose.c0, dtype=float)
            self.R0 = np.asarray(self.pose.R0, dtype=float)
        #: the couplings' closure blocks (after the chords', before the pose's),
        #: commensurate (:mod:`mechsing.kinematics.couplings`)
        self.couplings = len(base.couplings)
        self.coupling_rows = base.coupling_block(self.frame) if self.couplings else None
        self.blocks = len(self.chords) + self.couplings + (1 if self.pose is not None else 0)
        #: the legs' split of the pose-fixed closure, per set of moved columns
        self._split: dict[bytes, _Split | None] = {}
        # the first-kind coordinates of a non-abelian joint from a commensurate log:
        # least squares against its commensurate basis, one pseudo-inverse per joint
        self._pinv = {}
        #: a spherical joint's rotation vectors composed directly: (angular basis, inverse)
        self._turns = {}
        for jk in base.joints:
            if jk.type == "S":
                W = np.asarray(jk.basis, dtype=float)[:, :3]
                self._turns[jk.name] = (W, np.linalg.inv(W))
            if not jk.abelian:
                B = self.frame.twists(np.asarray(jk.basis, dtype=float).T)
                self._pinv[jk.name] = np.linalg.pinv(B)
        #: the spherical joints in file order (their turns composed all at once), and
        #: their coordinate columns, joint after joint
        self._turn_list = [jk for jk in base.joints if jk.name in self._turns]
        self._turn_columns = np.array(
            [c for jk in self._turn_list for c in range(jk.columns.start, jk.columns.stop)],
            dtype=int,
        )

    # ------------------------------------------------------------------ residuals

    def deltas(
        self,
        Q: np.ndarray,
        P: dict[str, np.ndarray] | None = None,
        T: np.ndarray | None = None,
    ) -> np.ndarray:
        """The closure residual of every chord (and the pose), (N, blocks, 4, 4); ``T``:
        the output's displacements :meth:`target` of Q's pose coordinates, when known."""
        q = Q[:, : self.nb]
        P = forward.batch_poses(self.base, q) if P is None else P
        out = np.empty((Q.shape[0], self.blocks, 4, 4))
        for i, jk in enumerate(self.chords):
            np.matmul(P[jk.a] @ forward.batch_element(jk, q), lie.inverse(P[jk.b]), out=out[:, i])
        if self.couplings:
            k = len(self.chords)
            out[:, k : k + self.couplings] = np.stack(coupling_residuals(self.base, q), axis=1)
        if self.pose is not None:
            T = self.target(Q[:, self.nb :]) if T is None else T
            np.matmul(P[self.pose_a] @ T, lie.inverse(P[self.pose_b]), out=out[:, -1])
        return out

    def target(self, s: np.ndarray) -> np.ndarray:
        """The output's displacement ``T(s)`` for pose coordinates s (N, 6)."""
        R = self.R0 @ exp_so3(s[:, :3])
        g = np.zeros(s.shape[:-1] + (4, 4))
        g[..., :3, :3] = R
        g[..., :3, 3] = s[:, 3:] - R @ self.c0
        g[..., 3, 3] = 1.0
        return g

    def residual_norm(self, D: np.ndarray) -> np.ndarray:
        """The closure residual (m) of each row: the largest over its blocks of
        ``sqrt(|p_c|^2 + L^2 |R - I|_F^2 / 2)`` (:meth:`KinematicModel.residual_norm`)."""
        if D.shape[1] == 0:
            return np.zeros(D.shape[0])
        R = D[..., :3, :3]
        p = D[..., :3, 3] + R @ self.c - self.c
        E = R - np.eye(3)
        r2 = np.sum(p * p, axis=-1) + self.L**2 * np.sum(E * E, axis=(-1, -2)) / 2
        return np.sqrt(np.max(r2, axis=1))

    def residual_twists(self, D: np.ndarray) -> np.ndarray:
        """The commensurate residual twists, stacked: (N, 6 * blocks)."""
        N, b = D.shape[:2]
        r = lie.log(D.reshape(N * b, 4, 4)).reshape(N, b, 6)
        rs = self.frame.twists(np.swapaxes(r, 1, 2))  # (N, 6, b)
        return np.swapaxes(rs, 1, 2).reshape(N, 6 * b)

    # ------------------------------------------------------------------ Jacobian

    def screws(self, Q: np.ndarray, P: dict[str, np.ndarray] | None = None) -> np.ndarray:
        """The commensurate current screws of the joint coordinates: (N, 6, nb)."""
        q = Q[:, : self.nb]
        P = forward.batch_poses(self.base, q) if P is None else P
        return self.frame.screws(forward.current_screws(self.base, q, P))

    def jacobian(self, Q: np.ndarray, P: dict[str, np.ndarray] | None = None) -> np.ndarray:
        """The commensurate closure Jacobian in the joint coordinates: (N, 6 * blocks, nb)
        (the pose coordinates are given and have no column)."""
        Ss = self.screws(Q, P)  # (N, 6, nb)
        signs = self.signs
        if self.pose is not None:
            signs = np.concatenate([signs, self.pose_signs[None, :]], axis=0)
        if signs.shape[0] == 0 and not self.couplings:
            return np.zeros((Q.shape[0], 0, self.nb))
        J = (Ss[:, None, :, :] * signs[None, :, None, :]).reshape(
            Q.shape[0], 6 * signs.shape[0], self.nb
        )  # (N, 6 blocks, nb)
        if self.couplings:
            C = np.broadcast_to(self.coupling_rows, (Q.shape[0],) + self.coupling_rows.shape)
            k = 6 * len(self.chords)
            J = np.concatenate([J[:, :k], C, J[:, k:]], axis=1)
        return J

    # ------------------------------------------------------------------ update

    def update(self, Q: np.ndarray, D: np.ndarray) -> np.ndarray:
        """Trivialised increments D (N, nb) of the joints applied on the group (abelian
        joints add; the others ``M <- exp(sum d_i e_i) M``), pose coordinates unchanged."""
        out = np.array(Q, copy=True)
        q = Q[:, : self.nb]
        turns = self._turn_list
        if turns:
            # every spherical joint's turns at once: R = exp(d W) exp(q W), read back by log
            cols = self._turn_columns
            R = self._turned(D[:, cols], turns) @ self._turned(q[:, cols], turns)
            x = log_so3(R)
            for k, jk in enumerate(turns):
                out[:, jk.columns] = x[:, k] @ self._turns[jk.name][1]
        for jk in self.base.joints:
            d = D[:, jk.columns]
            if jk.abelian:
                out[:, jk.columns] = q[:, jk.columns] + d
                continue
            if jk.name in self._turns:
                continue
            M = lie.exp(d @ jk.basis) @ forward.batch_element(jk, q)
            x = self.frame.twists(lie.log(M)[..., None])[..., 0]  # (N, 6) commensurate
            out[:, jk.columns] = x @ self._pinv[jk.name].T
        return out

    def _turned(self, x: np.ndarray, turns: list[Any]) -> np.ndarray:
        """``exp_so3(x_j W_j)`` of every spherical joint j at once: (N, joints, 3, 3) from
        the joints' coordinates side by side, x (N, 3 joints)."""
        N = x.shape[0]
        w = np.empty((N, len(turns), 3))
        for k, jk in enumerate(turns):
            w[:, k] = x[:, 3 * k : 3 * k + 3] @ self._turns[jk.name][0]
        return exp_so3(w)

    def difference(self, Q1: np.ndarray, Q0: np.ndarray) -> np.ndarray:
        """The increments D with ``update(Q0, D) == Q1`` row by row, measured on the group
        (:meth:`KinematicModel.difference`); pose coordinates subtract."""
        D = np.asarray(Q1, dtype=float) - np.asarray(Q0, dtype=float)
        q1, q0 = Q1[:, : self.nb], Q0[:, : self.nb]
        turns = self._turn_list
        if turns:
            cols = self._turn_columns
            R0 = self._turned(q0[:, cols], turns)
            x = log_so3(self._turned(q1[:, cols], turns) @ np.swapaxes(R0, -1, -2))
            for k, jk in enumerate(turns):
                D[:, jk.columns] = x[:, k] @ self._turns[jk.name][1]
        for jk in self.base.joints:
            if jk.abelian or jk.name in self._turns:
                continue
            M = forward.batch_element(jk, q1) @ lie.inverse(forward.batch_element(jk, q0))
            x = self.frame.twists(lie.log(M)[..., None])[..., 0]
            D[:, jk.columns] = x @ self._pinv[jk.name].T
        return D

    def between(self, QA: np.ndarray, QB: np.ndarray, f: np.ndarray) -> np.ndarray:
        """The points a fraction f (per row) of the way from QA to QB on the group."""
        D = self.difference(QB, QA)
        out = self.update(QA, f[:, None] * D[:, : self.nb])
        out[:, self.nb :] = QA[:, self.nb :] + f[:, None] * D[:, self.nb :]
        return out

    # ------------------------------------------------------------------ Newton

    def newton(
        self,
        Q: np.ndarray,
        free: np.ndarray,
        tolerance: float,
        iterations: int = 8,
        polish: bool = True,
        solve: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
        accept: Literal["better", "finite"] = "better",
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Gauss-Newton on the group for every row of Q, moving the joint coordinates in
        ``free`` (bool, nb); stops a row once its residual is below ``tolerance`` (m)
        and, with ``polish``, one more step no longer gains (the last digits, for a point
        whose singular values are read near zero).  Returns (Q, residual (m), Newton
        iterations per row).

        ``solve(J, r)``: the steps of a batch of commensurate systems (N, rows, moved) and
        residual twists (N, rows); by default the damped least squares (legs apart where
        the closure splits into them: :meth:`split`), else e.g. :func:`truncated_steps`.
        A row whose system is not finite stops; a step is taken when its residual is
        lower (``accept="better"``) or finite (``"finite"``), else the row stops."""
        Q = np.array(Q, dtype=float, copy=True)
        cols = np.flatnonzero(free)
        lengths = self.frame.length_columns[cols]
        # the poses and residuals of the current rows, carried from one iteration to the
        # next (each trial point's are computed once)
        P = {k: np.array(v) for k, v in forward.batch_poses(self.base, Q[:, : self.nb]).items()}
        # the pose coordinates are given: the output's target is computed once
        T = None if self.pose is None else self.target(Q[:, self.nb :])
        D = self.deltas(Q, P, T)
        res = self.residual_norm(D)
        its = np.zeros(Q.shape[0], dtype=int)
        active = np.ones(Q.shape[0], dtype=bool)
        if not len(cols) or D.shape[1] == 0:
            return Q, res, its
        polished = np.zeros(Q.shape[0], dtype=int)
        split = self.split(cols)
        for _ in range(iterations):
            # a closed row is polished once more (the step after tolerance gains the
            # last digits), then left alone
            done = res <= tolerance
            polished[done] += 1
            active &= ~(done & (polished > (1 if polish else 0)))
            if not np.any(active):
                break
            idx = np.flatnonzero(active)
            its[idx] += 1
            if len(idx) == len(Q):  # every row: the arrays themselves, not copies
                Qa, Pa, r = Q, P, self.residual_twists(D)
            else:
                Qa = Q[idx]
                Pa = {k: v[idx] for k, v in P.items()}
                r = self.residual_twists(D[idx])
            if split is not None and solve is None:
                du = split.step(self.screws(Qa, Pa), r)
            else:
                J = self.jacobian(Qa, Pa)[:, :, cols]
                finite = np.isfinite(J).all(axis=(1, 2)) & np.isfinite(r).all(axis=1)
                if not finite.all():  # such a system is no step: its row stops
                    active[idx[~finite]] = False
                    idx, Qa, J, r = idx[finite], Qa[finite], J[finite], r[finite]
                    Pa = {k: v[finite] for k, v in Pa.items()}
                    if not len(idx):
                        break
                du = (_damped_step if solve is None else solve)(J, r)
            du = np.where(lengths[None, :], du * self.L, du)
            step = np.zeros((len(idx), self.nb))
            step[:, cols] = du
            Qn = self.update(Qa, step)
            Pn = forward.batch_poses(self.base, Qn[:, : self.nb])
            Dn = self.deltas(Qn, Pn, None if T is None else T[idx])
            rn = self.residual_norm(Dn)
            better = rn < res[idx] if accept == "better" else np.isfinite(rn)
            keep = idx[better]
            Q[keep] = Qn[better]
            res[keep] = rn[better]
            D[keep] = Dn[better]
            for k in P:
                P[k][keep] = Pn[k][better]
            # a row whose step is not taken stops
            active[idx[~better]] = False
        return Q, res, its

    # ------------------------------------------------------------------ the legs' split

    def split(self, cols: np.ndarray) -> _Split | None:
        """The closure of a pose model with the output's pose given, split by legs, for
        the moved columns ``cols`` (None when it does not split).

        With the output's pose given, each leg (a component of the graph left when the
        base and the output body are removed, :meth:`MechanismGraph.legs`) closes on its
        own: every closure block (the chords' loops and the pose) restricted to a leg's
        columns is a combination of that leg's own rows, ``signs[:, leg] = A_leg B_leg``
        (``B_leg``: independent sign rows, one per loop of the leg with the output held,
        the leg's path from base to output among them).  When the legs' rows number the
        blocks, ``A = [A_leg ...]`` is square and invertible, and the Jacobian is
        ``(A kron I6) diag(J_leg)``: the Newton step is ``J_leg^-1`` applied to the leg's
        rows of ``(A^-1 kron I6) r``, small solves instead of one of every coordinate.
        Only square legs split (as many coordinates as rows: the step is then the same
        Newton step as the whole system's)."""
        key = np.asarray(cols).tobytes()
        if key not in self._split:
            self._split[key] = self._find_split(np.asarray(cols))
        return self._split[key]

    def _find_split(self, cols: np.ndarray) -> _Split | None:
        if self.pose is None or len(self.base.mech.loops) == 0 or self.couplings:
            return None  # a coupling may tie two legs: the whole system's step
        mech = self.base.mech
        signs = np.concatenate([self.signs, self.pose_signs[None, :]], axis=0)
        position = {int(c): k for k, c in enumerate(cols)}
        legs, A_parts, covered = [], [], set()
        for leg in mech.legs:
            lc = [
                c
                for j in leg.joints
                for c in range(self.base.joint(j).columns.start, self.base.joint(j).columns.stop)
                if c in position
            ]
            if not lc:
                continue
            M = signs[:, lc]
            basis = _independent_rows(M)
            B = M[basis]
            if 6 * len(basis) != len(lc):
                return None  # not square: no split
            A_parts.append(M @ np.linalg.pinv(B))
            legs.append((np.array([position[c] for c in lc]), np.array(lc), B))
            covered.update(lc)
        if len(covered) != len(cols) or not legs:
            return None
        A = np.concatenate(A_parts, axis=1)
        if A.shape[0] != A.shape[1] or np.linalg.matrix_rank(A) < A.shape[0]:
            return None
        # A is a matrix of small integers: so is its inverse, to rounding
        return _Split(np.linalg.inv(A), legs, len(cols))


def _independent_rows(M: np.ndarray) -> list[int]:
    """The first rows of M (small integers) that are linearly independent, in order."""
    out: list[int] = []
    for i in range(M.shape[0]):
        trial = M[[*out, i]]
        if np.linalg.matrix_rank(trial) > len(out):
            out.append(i)
    return out


class _Split:
    """The pose-fixed closure split by legs (:meth:`BatchClosure.split`): ``Ainv`` turns
    the residual's blocks into the legs' rows (leg by leg, in order), each leg its
    columns (positions among the moved ones, and the coordinates themselves) and sign
    rows ``B``."""

    def __init__(
        self, Ainv: np.ndarray, legs: list[tuple[np.ndarray, np.ndarray, np.ndarray]], n: int
    ) -> None:
        self.Ainv = Ainv
        self.legs = legs
        self.n = n
        # legs of one shape are solved in one batched call
        self.shapes: dict[tuple[int, int], list[int]] = {}
        for k, (c, _, B) in enumerate(legs):
            self.shapes.setdefault((B.shape[0], len(c)), []).append(k)
        starts = np.cumsum([0] + [B.shape[0] for _, _, B in legs])
        self.rows = [slice(int(a), int(b)) for a, b in zip(starts[:-1], starts[1:], strict=True)]

    def step(self, Ss: np.ndarray, r: np.ndarray) -> np.ndarray:
        """The Newton steps (N, moved columns) from the commensurate screws of every joint
        coordinate ``Ss`` (N, 6, nb) and the stacked residual twists ``r`` (N, 6 blocks):
        the damped least squares of :func:`_damped_step`, leg by leg."""
        N = r.shape[0]
        rl = np.einsum("kb,nbi->nki", self.Ainv, r.reshape(N, -1, 6))  # (N, leg rows, 6)
        out = np.zeros((N, self.n))
        for (nr, nc), ks in self.shapes.items():
            Js, rs = [], []
            for k in ks:
                _, cols, B = self.legs[k]
                S = Ss[:, :, cols]  # (N, 6, nc)
                Js.append((B[None, :, None, :] * S[:, None, :, :]).reshape(N, 6 * nr, nc))
                rs.append(rl[:, self.rows[k], :].reshape(N, 6 * nr))
            J = np.concatenate(Js)  # (len(ks) N, 6 nr, nc)
            du = _damped_step(J, np.concatenate(rs)).reshape(len(ks), N, nc)
            for k, d in zip(ks, du, strict=True):
                out[:, self.legs[k][0]] = d
        return out


def _damped_step(J: np.ndarray, r: np.ndarray) -> np.ndarray:
    """The damped least-squares steps ``-(J^T J + lam^2 I)^-1 J^T r`` of a batch (the
    normal equations: a batched Cholesky-sized solve instead of an SVD per row), with
    ``lam`` = NEWTON_DAMPING times the row's Frobenius norm (a bound of sigma_max)."""
    JtJ = np.matmul(np.swapaxes(J, 1, 2), J)
    g = np.einsum("nji,nj->ni", J, r)
    lam2 = (NEWTON_DAMPING**2) * np.einsum("nii->n", JtJ)
    k = JtJ.shape[1]
    JtJ[:, np.arange(k), np.arange(k)] += np.maximum(lam2, np.finfo(float).tiny)[:, None]
    return -np.linalg.solve(JtJ, g[..., None])[..., 0]


def truncated_steps(J: np.ndarray, r: np.ndarray) -> np.ndarray:
    """The minimum-norm steps ``-J^+ r`` of a batch, singular values at or below float's
    ``tau_lo`` times the largest dropped (the batched
    :func:`~mechsing.kinematics.newton.truncated_least_squares`)."""
    tau = Precision("float").tolerances.tau_lo
    U, s, Vt = np.linalg.svd(J, full_matrices=False)
    keep = s > tau * s[:, :1]
    inv = np.where(keep, 1.0 / np.where(keep, s, 1.0), 0.0)
    return -np.einsum("nji,nj->ni", Vt, inv * np.einsum("nji,nj->ni", U, r))
