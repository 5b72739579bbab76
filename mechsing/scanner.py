"""Batched float scans of an open chain over many configurations.

A workspace scan asks one question of each of many configurations of an open
chain: is the output screw system of full (generic) rank there?  The answer is
the same rank decision as :func:`mechsing.analyze` makes for the output chain
(the two-threshold rank rule: the commensurate matrix of the chain's current
screws, or of its output point's velocity, float thresholds ``tau_lo = 1e-12``,
``tau_hi = 1e-9`` relative to sigma_max), made for a whole array of
configurations at once:

1. the chain's commensurate matrices J (rows 6, or 3 for a point output;
   columns the chain's coordinates) are built for a chunk of configurations
   with array arithmetic (closed-form exponentials of one-dof joints, batched
   3x3 products), never a Python loop over configurations;
2. a *screen* certifies most configurations as full rank without an SVD: with
   m = min(rows, columns) and G the m x m Gram matrix (``J`` itself when
   square), ``sigma_min >= |det| / (|J|_F^2 / (m - 1))^((m - 1) / 2)`` (the
   other m - 1 singular values have their product bounded by the
   arithmetic-geometric mean of their squares) and ``sigma_max <= |J|_F``, so
   ``bound = |det| / (...) / |J|_F`` is a lower bound of sigma_min / sigma_max.
   It is lowered by the backward error of the determinant
   (:data:`~mechsing.numeric.SCAN_ROUNDING_FACTOR`) and accepted when it is
   :data:`~mechsing.numeric.SCAN_SCREEN_FACTOR` times ``tau_hi``;
3. only the configurations the screen cannot certify (near a singularity, or
   a chain whose generic rank is below m) get a batched SVD and the
   two-threshold rule.

Memory is bounded by the chunk size: the configurations may come as one array
or as an iterable of arrays (a generator never holds them all); the result
keeps 18 bytes per configuration (rank, screened flag, ratio and bound).

Conventions: twists ``(omega, v)``; joint values in the mechanism's coordinate
order (:meth:`mechsing.model.Mechanism.coordinates`), SI units and radians.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.lie import ANGULAR, LINEAR
from mechsing.numeric import (
    MAX_JOINT_VALUE,
    SCAN_ROUNDING_FACTOR,
    SCAN_SCREEN_FACTOR,
    Precision,
    rank_bounds,
    scale_screws,
)

__all__ = ["ChainScanner", "ScanResult", "scan"]

#: configurations processed together (bounds the working memory: about
#: 2 kB per configuration of a 6 x 6 chain; small enough to stay in cache)
DEFAULT_CHUNK = 4096
#: decided rank of a configuration whose rank the float thresholds cannot decide
UNDECIDED = -1

_EPS = float(np.finfo(float).eps)


@dataclass
class ScanResult:
    """Verdicts of a scan, one entry per configuration.

    ``rank``: the decided rank of the output screw system (``-1``: undecided,
    a singular value between ``tau_lo`` and ``tau_hi``); ``generic_rank``: its
    value at generic configurations; ``screened``: decided full rank by the
    determinant bound, with no SVD; ``ratio``: sigma_min / sigma_max from the
    SVD (NaN where the screen decided, unless the scan was asked for every
    singular value); ``bound``: the screen's certified lower bound of that
    ratio (0 where it certified nothing).
    """

    rank: np.ndarray
    generic_rank: int
    screened: np.ndarray
    ratio: np.ndarray
    bound: np.ndarray
    tau_lo: float
    tau_hi: float
    length_scale: float
    precision: str = "float"

    @property
    def undecided(self) -> np.ndarray:
        return self.rank == UNDECIDED

    @property
    def singular(self) -> np.ndarray:
        """Decided below the generic rank (undecided configurations are not singular)."""
        return (self.rank >= 0) & (self.rank < self.generic_rank)

    def __len__(self) -> int:
        return len(self.rank)

    def summary(self) -> dict[str, Any]:
        n = len(self)
        return {
            "configurations": n,
            "generic_rank": self.generic_rank,
            "singular": int(np.count_nonzero(self.singular)),
            "undecided": int(np.count_nonzero(self.undecided)),
            "screened": int(np.count_nonzero(self.screened)),
            "precision": self.precision,
            "tau_lo": self.tau_lo,
            "tau_hi": self.tau_hi,
            "length_scale": self.length_scale,
        }


@dataclass(frozen=True)
class _JointPlan:
    """What the batched poses need of one joint."""

    name: str
    a: str
    b: str
    columns: slice
    basis: np.ndarray  # (dof, 6) float reference screws
    kind: str  # "one" (R, P, H), "U", or "general"


def _exp_one(theta: np.ndarray, e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """exp(theta e) for a fixed one-dof screw e (|omega| = 1, or omega = 0): (R, p) batched.

    With ``e = (u, v)``, |u| = 1: pitch ``h = u . v``, axis point ``a = u x v``,
    ``R = I + sin K + (1 - cos) K^2`` (K = u^), ``p = (I - R) a + h theta u``;
    with u = 0: ``R = I``, ``p = theta v``.  Both are one small matrix product
    of the coefficients ``(sin, 1 - cos, theta)`` with fixed 3 x 9 and 3 x 3 tables.
    """
    n = theta.shape[0]
    u, v = e[ANGULAR], e[LINEAR]
    if not np.any(u):
        R = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
        return R, theta[:, None] * v[None, :]
    K = _hat3(u)
    K2 = K @ K
    a = np.cross(u, v)
    h = float(u @ v)
    coef = np.empty((n, 3))
    np.sin(theta, out=coef[:, 0])
    np.cos(theta, out=coef[:, 1])
    coef[:, 1] = 1.0 - coef[:, 1]
    coef[:, 2] = theta
    R = coef[:, :2] @ np.stack([K.ravel(), K2.ravel()])
    R += np.eye(3).ravel()
    # (I - R) a = -(sin K a + (1 - cos) K^2 a)
    p = coef @ np.stack([-(K @ a), -(K2 @ a), h * u])
    return R.reshape(n, 3, 3), p


def _hat3(u: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])


def _compose(
    Ra: np.ndarray, pa: np.ndarray, Rb: np.ndarray, pb: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(Ra, pa) (Rb, pb) batched."""
    return Ra @ Rb, (Ra @ pb[:, :, None])[:, :, 0] + pa


def _inverse(R: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    Rt = np.swapaxes(R, 1, 2)
    return Rt, -(Rt @ p[:, :, None])[:, :, 0]


class ChainScanner:
    """The output chain of an open-chain mechanism, ready to scan.

    Parameters
    ----------
    mech : Mechanism
        A mechanism without loops, with an output (the file's ``output``).
    """

    def __init__(self, mech: Any) -> None:
        from mechsing.kinematics import KinematicModel
        from mechsing.model.mechanism import MechanismError
        from mechsing.singularity import output_chain

        where = mech.path
        if mech.loops:
            raise MechanismError(
                f"scan covers open chains; this mechanism has {len(mech.loops)} loop(s): "
                "use `mechsing analyze` for closed chains",
                path=where,
            )
        if mech.output is None:
            raise MechanismError(
                "scan needs an output: add `output: {body: NAME}` to the file", path=where
            )
        self.mech = mech
        self.model = KinematicModel(mech, "float")
        names, cols = output_chain(mech, self.model)
        self.columns = np.array(cols, dtype=int)
        self.n = self.model.n
        self.point = (
            None if mech.output.point is None else np.array([float(x) for x in mech.output.point])
        )
        self.rows = 3 if self.point is not None else 6
        self.length_scale = float(self.model.length_scale)
        self.centroid = np.asarray(self.model.centroid, dtype=float)
        self.length_columns = np.asarray(self.model.length_columns[self.columns], dtype=bool)
        self.tolerances = Precision("float").tolerances
        self._plans = {}
        for jk in self.model.joints:
            basis = np.asarray(jk.basis, dtype=float)
            if jk.type == "U":
                kind = "U"
            elif basis.shape[0] == 1:
                kind = "one"
            else:
                kind = "general"
            self._plans[jk.name] = _JointPlan(jk.name, jk.a, jk.b, jk.columns, basis, kind)
        # the bodies whose pose the chain needs, and every body on their tree paths
        self._chain_joints = []
        seen = set()
        for j in names:
            if j not in seen:
                seen.add(j)
                self._chain_joints.append(self._plans[j])
        self._generic: int | None = None
        self._serial = self._serial_plan()

    # ---------------------------------------------------------------- poses

    def _element(self, plan: _JointPlan, Q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        q = Q[:, plan.columns]
        if plan.kind == "one":
            return _exp_one(q[:, 0], plan.basis[0])
        if plan.kind == "U":
            R1, p1 = _exp_one(q[:, 0], plan.basis[0])
            R2, p2 = _exp_one(q[:, 1], plan.basis[1])
            return _compose(R1, p1, R2, p2)
        g = lie.exp(q @ plan.basis)
        return np.ascontiguousarray(g[:, :3, :3]), np.ascontiguousarray(g[:, :3, 3])

    def _poses(
        self, Q: np.ndarray, bodies: Iterable[str]
    ) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        """Poses (R, p) of the given bodies, batched over the rows of Q."""
        n = Q.shape[0]
        ground = self.mech.ground
        eye = (np.broadcast_to(np.eye(3), (n, 3, 3)).copy(), np.zeros((n, 3)))
        out: dict[str, tuple[np.ndarray, np.ndarray]] = {ground: eye}
        elements: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        paths = self.mech.graph.tree_paths
        for body in bodies:
            if body in out:
                continue
            g = eye
            here = ground
            for st in paths[body]:
                plan = self._plans[st.joint]
                nxt = plan.b if st.sign > 0 else plan.a
                if st.part is not None:
                    raise AssertionError("tree paths to user bodies cross whole joints")
                if nxt in out:
                    g = out[nxt]
                else:
                    if st.joint not in elements:
                        elements[st.joint] = self._element(plan, Q)
                    M = elements[st.joint]
                    g = _compose(*g, *(M if st.sign > 0 else _inverse(*M)))
                    out[nxt] = g
                here = nxt
            assert here == body
        return out

    # ---------------------------------------------------------------- matrices

    def matrices(self, Q: np.ndarray) -> np.ndarray:
        """The chain's commensurate matrices, shape (N, rows, columns), for the rows of Q.

        Equal (to rounding) to :func:`mechsing.singularity.serial.chain_matrix`
        of the float model at each configuration.
        """
        Q = np.asarray(Q, dtype=float)
        if Q.ndim != 2 or Q.shape[1] != self.n:
            raise ValueError(
                f"configurations must be an array of shape (N, {self.n}) "
                f"(joint coordinates in file order), not {Q.shape}"
            )
        # the limits of `analyze` (numeric.MAX_JOINT_VALUE): radians, or times L for a length
        bound = np.where(
            self.model.length_columns, MAX_JOINT_VALUE * self.length_scale, MAX_JOINT_VALUE
        )
        bad = ~np.all(np.isfinite(Q) & (np.abs(Q) <= bound), axis=1)
        if np.any(bad):
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(
                f"configuration row {i} has a joint value that is not finite or not of a "
                f"sensible size (at most {MAX_JOINT_VALUE:g} rad, or {MAX_JOINT_VALUE:g} L for "
                f"a length): {Q[i].tolist()}"
            )
        if self._serial is not None:
            return self._serial_matrices(Q)
        need = {p.a for p in self._chain_joints}
        if self.point is not None:
            need.add(self.mech.output.body)
        poses = self._poses(Q, sorted(need))
        cols = []
        for plan in self._chain_joints:
            R, p = poses[plan.a]
            if plan.kind == "U":
                q1 = Q[:, plan.columns.start]
                M1 = _exp_one(q1, plan.basis[0])
                R2, p2 = _compose(R, p, *M1)
                cols.append(_act(R, p, plan.basis[0]))
                cols.append(_act(R2, p2, plan.basis[1]))
            else:
                for e in plan.basis:
                    cols.append(_act(R, p, e))
        S = np.stack(cols, axis=2)  # (N, 6, k)
        L = self.length_scale
        if self.point is None:
            return scale_screws(S, L, self.centroid, self.length_columns)
        Rb, pb = poses[self.mech.output.body]
        x = Rb @ self.point + pb
        w, v = S[:, :3, :], S[:, 3:, :]
        vel = (v + np.cross(w, x[:, :, None], axis=1)) / L
        return np.where(self.length_columns[None, None, :], vel * L, vel)

    def _serial_plan(self) -> list[tuple[int, int, np.ndarray]] | None:
        """The fast path: an output body reached from ground through one-dof joints, each
        crossed forward, and those joints are the whole chain.  One entry per joint:
        (coordinate column, its position among the chain's columns, a table of
        fixed vectors in the commensurate frame, see :meth:`_serial_matrices`)."""
        out = self.mech.output
        if out.relative_to != self.mech.ground:
            return None
        steps = self.mech.graph.tree_paths[out.body]
        if any(st.sign < 0 or st.part is not None for st in steps):
            return None
        plans = [self._plans[st.joint] for st in steps]
        if any(p.kind != "one" for p in plans) or {p.name for p in plans} != {
            p.name for p in self._chain_joints
        }:
            return None
        order = list(self.columns)
        L, c = self.length_scale, self.centroid
        table = []
        for p in plans:
            # the screw in the commensurate frame: moved to the centroid, v / L (an
            # automorphism of D, so exp and Ad commute with it)
            e = scale_screws(p.basis[0][:, None], L, c)[:, 0]
            u, v = e[ANGULAR], e[LINEAR]
            K = _hat3(u)
            K2 = K @ K
            a = np.cross(u, v)
            h = float(u @ v)
            # columns: K, K^2 (rotation update), K a, K^2 a (translation update), u, v
            T = np.concatenate(
                [K, K2, (K @ a)[:, None], (K2 @ a)[:, None], u[:, None], v[:, None]], axis=1
            )
            table.append((p.columns.start, order.index(p.columns.start), T, h, bool(np.any(u))))
        return table

    def _serial_matrices(self, Q: np.ndarray) -> np.ndarray:
        """Commensurate chain matrices of a serial chain of one-dof joints.

        The pose (R, P) is carried in the commensurate frame (origin at the centroid,
        lengths / L).  For each joint, one product ``R @ [K, K^2, K a, K^2 a, u, v]``
        gives its current screw ``(R u, R v + P x R u)`` and the next pose
        ``R + sin R K + (1 - cos) R K^2``, ``P - sin R K a - (1 - cos) R K^2 a + h theta R u``
        (:func:`_exp_one` composed on the right).
        """
        n = Q.shape[0]
        k = len(self.columns)
        J = np.empty((n, 6, k))
        R = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
        P = np.zeros((n, 3))
        last = len(self._serial) - 1
        for i, (col, pos, T, h, rotates) in enumerate(self._serial):
            RT = (R.reshape(-1, 3) @ T).reshape(n, 3, T.shape[1])
            w = RT[:, :, 8]
            J[:, :3, pos] = w
            J[:, 3:, pos] = RT[:, :, 9] + _cross(P, w)
            if i == last and self.point is None:
                break
            th = Q[:, col]
            if rotates:
                s = np.sin(th)
                c1 = 1.0 - np.cos(th)
                R = R + s[:, None, None] * RT[:, :, 0:3] + c1[:, None, None] * RT[:, :, 3:6]
                P = P - s[:, None] * RT[:, :, 6] - c1[:, None] * RT[:, :, 7]
                if h:
                    P = P + (h * th)[:, None] * w
            else:
                P = P + th[:, None] * RT[:, :, 9]
        lc = self.length_columns
        if self.point is not None:
            x = (self.point - self.centroid) / self.length_scale
            X = R @ x + P
            w = J[:, :3, :]
            vel = J[:, 3:, :] + np.cross(w, X[:, :, None], axis=1)
            J = np.ascontiguousarray(vel)
        if np.any(lc):
            J[:, :, lc] *= self.length_scale
        return J

    # ---------------------------------------------------------------- decisions

    def _decide(self, J: np.ndarray, all_sigma: bool) -> tuple[np.ndarray, ...]:
        """(rank, screened, ratio, bound) for a chunk of matrices."""
        N, rows, k = J.shape
        m = min(rows, k)
        tol = self.tolerances
        rank = np.full(N, UNDECIDED, dtype=np.int8)
        ratio = np.full(N, np.nan)
        bound = np.zeros(N)
        screened = np.zeros(N, dtype=bool)
        if m == 0:
            rank[:] = 0
            return rank, screened, ratio, bound
        F2 = np.einsum("nij,nij->n", J, J)
        if m >= 2:
            if rows == k:
                d = np.abs(np.linalg.det(J))
                err = SCAN_ROUNDING_FACTOR * m * _EPS
            else:
                G = np.swapaxes(J, 1, 2) @ J if k < rows else J @ np.swapaxes(J, 1, 2)
                d = np.sqrt(np.maximum(np.linalg.det(G), 0.0))
                err = np.sqrt(SCAN_ROUNDING_FACTOR * m * _EPS)
            with np.errstate(divide="ignore", invalid="ignore"):
                lb = d / (F2 / (m - 1)) ** ((m - 1) / 2) / np.sqrt(F2)
            lb = np.where(F2 > 0, lb, 0.0)
            bound = np.maximum(lb - err, 0.0)
            screened = bound >= SCAN_SCREEN_FACTOR * tol.tau_hi
            rank[screened] = m
        todo = np.ones(N, dtype=bool) if all_sigma else ~screened
        if np.any(todo):
            s = np.linalg.svd(J[todo], compute_uv=False)  # (N', m), descending
            smax = s[:, :1]
            with np.errstate(divide="ignore", invalid="ignore"):
                rel = np.where(smax > 0, s / smax, 0.0)
            lo_rank, hi_rank = rank_bounds(rel, tol)
            decided = np.where(lo_rank == hi_rank, lo_rank, UNDECIDED).astype(np.int8)
            # the screen and the SVD agree where both ran (the bound is certified)
            rank[todo] = np.where(screened[todo], rank[todo], decided)
            ratio[todo] = rel[:, -1]
        return rank, screened, ratio, bound

    # ---------------------------------------------------------------- scans

    @property
    def generic_rank(self) -> int:
        """The largest rank decided at random configurations (as :func:`mechsing.analyze` does)."""
        if self._generic is None:
            from mechsing.singularity import GENERIC_SAMPLES, random_configurations

            Q = random_configurations(self.model, GENERIC_SAMPLES)
            r, *_ = self._decide(self.matrices(Q), all_sigma=False)
            self._generic = int(max(0, int(r.max())))
        return self._generic

    def scan(
        self,
        configurations: np.ndarray | Iterable[np.ndarray],
        *,
        chunk: int = DEFAULT_CHUNK,
        all_sigma: bool = False,
    ) -> ScanResult:
        """Decide the rank of the output screw system at every configuration.

        Parameters
        ----------
        configurations : array (N, n) or iterable of such arrays
            Joint coordinates in file order (radians, metres).  An iterable is
            consumed chunk by chunk and never held whole.
        chunk : int
            Rows processed together.
        all_sigma : bool
            Run the SVD everywhere (``ratio`` for every configuration; slower).
        """
        ranks, scr, rat, bnd = [], [], [], []
        for block in _chunks(configurations, chunk):
            r, s, ra, b = self._decide(self.matrices(block), all_sigma)
            ranks.append(r)
            scr.append(s)
            rat.append(ra)
            bnd.append(b)
        tol = self.tolerances

        def cat(parts: list[np.ndarray], dtype: Any) -> np.ndarray:
            return np.concatenate(parts) if parts else np.zeros(0, dtype=dtype)

        return ScanResult(
            cat(ranks, np.int8),
            self.generic_rank,
            cat(scr, bool),
            cat(rat, float),
            cat(bnd, float),
            tol.tau_lo,
            tol.tau_hi,
            self.length_scale,
        )


def _act(R: np.ndarray, p: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Ad(R, p) e batched: (R w, R v + p x R w), shape (N, 6)."""
    out = np.empty((R.shape[0], 6))
    w = out[:, ANGULAR]
    np.matmul(R, e[ANGULAR], out=w)
    v = R @ e[LINEAR]
    v[:, 0] += p[:, 1] * w[:, 2] - p[:, 2] * w[:, 1]
    v[:, 1] += p[:, 2] * w[:, 0] - p[:, 0] * w[:, 2]
    v[:, 2] += p[:, 0] * w[:, 1] - p[:, 1] * w[:, 0]
    out[:, LINEAR] = v
    return out


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b for (N, 3) arrays (faster than np.cross on small rows)."""
    out = np.empty_like(b)
    out[:, 0] = a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]
    out[:, 1] = a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2]
    out[:, 2] = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    return out


def _chunks(configurations: Any, chunk: int) -> Iterator[np.ndarray]:
    if chunk < 1:
        raise ValueError(f"chunk must be a positive number of rows, not {chunk}")
    if isinstance(configurations, (list, tuple)):
        try:
            arr = np.asarray(configurations, dtype=float)
        except ValueError:  # blocks of different lengths
            arr = None
        if arr is not None and arr.ndim == 2:  # rows of joint values, not a list of blocks
            configurations = arr
    if isinstance(configurations, np.ndarray):
        for i in range(0, configurations.shape[0], chunk):
            yield configurations[i : i + chunk]
        return
    for block in configurations:
        arr = np.asarray(block, dtype=float)
        for i in range(0, arr.shape[0], chunk):
            yield arr[i : i + chunk]


def scan(
    mech: Any,
    configurations: np.ndarray | Iterable[np.ndarray],
    *,
    chunk: int = DEFAULT_CHUNK,
    all_sigma: bool = False,
) -> ScanResult:
    """Scan an open chain (a :class:`~mechsing.model.Mechanism` or a file path); see :class:`ChainScanner`."""
    if not hasattr(mech, "graph"):
        from mechsing.model import load

        mech = load(mech)
    return ChainScanner(mech).scan(configurations, chunk=chunk, all_sigma=all_sigma)
