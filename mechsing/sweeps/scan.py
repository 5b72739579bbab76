"""Batched float scans of an open chain over many configurations.

Owns :func:`scan`, :class:`ChainScanner` and :class:`ScanResult`.

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
from pathlib import Path
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.kinematics import KinematicModel, forward
from mechsing.kinematics.chains import tree_chain
from mechsing.kinematics.forward import SerialJacobian
from mechsing.model import Mechanism
from mechsing.numeric import (
    MAX_JOINT_VALUE,
    SCAN_ROUNDING_FACTOR,
    SCAN_SCREEN_FACTOR,
    Precision,
    dispatch,
    relative_singular_values,
)
from mechsing.reader import read_mechanism
from mechsing.screws import chain_matrix
from mechsing.singularity.criteria import SerialTest
from mechsing.sweeps import scan_kernel  # noqa: F401 - registers the compiled screen

__all__ = ["ChainScanner", "ScanResult", "scan"]

#: configurations processed together (bounds the working memory: about
#: 2 kB per configuration of a 6 x 6 chain; small enough to stay in cache)
DEFAULT_CHUNK = 4096
#: rows per call of the compiled screen (its memory is the rows' joint values and results)
COMPILED_CHUNK = 65536
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
        """Boolean mask of the configurations whose rank is undecided (``rank == -1``)."""
        return self.rank == UNDECIDED

    @property
    def singular(self) -> np.ndarray:
        """Decided below the generic rank (undecided configurations are not singular)."""
        return (self.rank >= 0) & (self.rank < self.generic_rank)

    def __len__(self) -> int:
        return len(self.rank)

    def summary(self) -> dict[str, Any]:
        """Counts: configurations, singular, undecided and screened ones, and the generic rank."""
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


class ChainScanner:
    """The output chain of an open-chain mechanism, ready to scan.

    Parameters
    ----------
    mech : Mechanism
        A mechanism without loops, with an output (the file's ``output``).
    """

    def __init__(self, mech: Any) -> None:
        from mechsing.errors import MechanismError

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
        from mechsing.model.couplings import refuse_couplings

        refuse_couplings(mech, "the chain scanner (mechsing.sweeps.scan)")
        self.mech = mech
        self.model = KinematicModel(mech, "float")
        self.chain = tree_chain(self.model, mech.output.body, mech.output.relative_to)
        self.columns = np.array(self.chain.columns, dtype=int)
        self.n = self.model.n
        self.point = (
            None if mech.output.point is None else np.array([float(x) for x in mech.output.point])
        )
        self.rows = 3 if self.point is not None else 6
        self.length_scale = float(self.model.length_scale)
        self.centroid = np.asarray(self.model.centroid, dtype=float)
        self.length_columns = np.asarray(self.model.length_columns[self.columns], dtype=bool)
        self.tolerances = Precision("float").tolerances
        #: the serial test (:class:`mechsing.singularity.criteria.SerialTest`) that decides
        self.test = SerialTest.of(mech, self.model)
        names = list(dict.fromkeys(self.chain.joints))
        self._chain_joints = [self.model.joint(j) for j in names]
        self._generic: int | None = None
        # the fast path: a serial chain of one-dof joints from ground to the output body
        self._serial = (
            SerialJacobian(self.model, self._path_joints(), list(self.columns), self.point)
            if mech.output.relative_to == mech.ground
            and SerialJacobian.applies(self.model, mech.output.body, self._chain_joints)
            else None
        )

    def _path_joints(self) -> list[Any]:
        steps = self.mech.graph.tree_paths[self.mech.output.body]
        return [self.model.joint(st.joint) for st in steps]

    # ---------------------------------------------------------------- matrices

    def matrices(self, Q: np.ndarray) -> np.ndarray:
        """The chain's commensurate matrices, shape (N, rows, columns), for the rows of Q.

        The batched kinematics of :mod:`mechsing.kinematics.forward` and the chain
        builder :func:`mechsing.screws.chain_matrix`, as the one-configuration
        analysis uses them (equal to rounding: the serial fast path is the same
        product of exponentials in the commensurate frame).
        """
        Q = self._checked(Q)
        if self._serial is not None and dispatch.enabled():
            return self._serial(Q)
        out = self.mech.output
        need = [jk.a for jk in self._chain_joints]
        if self.point is not None:
            need.append(out.body)
        poses = forward.poses(self.model, Q, need)
        S = forward.current_screws(self.model, Q, poses, self._chain_joints)
        x = None if self.point is None else lie.act_point(poses[out.body], self.point)
        return chain_matrix(self.model, S, self.chain.columns, x)

    def _checked(self, Q: np.ndarray) -> np.ndarray:
        """Q as a float array of configurations, refused when a value is not sensible."""
        Q = np.asarray(Q, dtype=float)
        if Q.ndim != 2 or Q.shape[1] != self.n:
            raise ValueError(
                f"configurations must be an array of shape (N, {self.n}) "
                f"(joint coordinates in file order), not {Q.shape}"
            )
        # the limits of `analyze` (numeric.MAX_JOINT_VALUE): radians, or times L for a length
        bound = self.model.float_frame.rates_back(np.full(self.n, MAX_JOINT_VALUE))
        bad = ~np.all(np.isfinite(Q) & (np.abs(Q) <= bound), axis=1)
        if np.any(bad):
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(
                f"configuration row {i} has a joint value that is not finite or not of a "
                f"sensible size (at most {MAX_JOINT_VALUE:g} rad, or {MAX_JOINT_VALUE:g} L for "
                f"a length): {Q[i].tolist()}"
            )
        return Q

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
            rel = relative_singular_values(s)
            # the serial test's rule (UNDECIDED is its -1)
            decided = self.test.ranks_of_relative(rel).decided.astype(np.int8)
            # the screen and the SVD agree where both ran (the bound is certified)
            rank[todo] = np.where(screened[todo], rank[todo], decided)
            ratio[todo] = rel[:, -1]
        return rank, screened, ratio, bound

    @property
    def compiled(self) -> bool:
        """Does :meth:`scan` screen with the compiled kernel (:mod:`mechsing.sweeps.scan_kernel`:
        a serial chain of one-dof joints from ground, and numba installed)?"""
        return self._serial is not None and self.test.compiled_screen() is not None

    def _decide_compiled(self, Q: np.ndarray) -> tuple[np.ndarray, ...]:
        """:meth:`_decide` with the compiled screen: the numpy matrices and SVD only at the
        rows it cannot certify."""
        rows = self.rows
        k = len(self.columns)
        m = min(rows, k)
        N = Q.shape[0]
        if m < 2:
            return self._decide(self.matrices(Q), False)
        err = SCAN_ROUNDING_FACTOR * m * _EPS
        bound = self.test.screen(self._serial, Q, err if rows == k else np.sqrt(err))
        screened = bound >= SCAN_SCREEN_FACTOR * self.tolerances.tau_hi
        rank = np.full(N, m, dtype=np.int8)
        ratio = np.full(N, np.nan)
        rest = ~screened
        if np.any(rest):
            r, _s, ra, b = self._decide(self.matrices(Q[rest]), False)
            rank[rest] = r
            ratio[rest] = ra
            bound[rest] = b
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
        compiled = self.compiled and not all_sigma
        # the compiled screen keeps no per-row temporaries: bigger chunks cost no memory
        rows = max(chunk, COMPILED_CHUNK) if compiled and chunk >= 1 else chunk
        for block in _chunks(configurations, rows):
            if compiled:
                r, s, ra, b = self._decide_compiled(self._checked(block))
            else:
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
    mech: Mechanism | str | Path,
    configurations: np.ndarray | Iterable[np.ndarray],
    *,
    chunk: int = DEFAULT_CHUNK,
    all_sigma: bool = False,
) -> ScanResult:
    """Float verdicts of an open chain's output at many configurations, batched.

    The verdict ``analyze`` gives for the output chain (the same commensurate matrix and
    float thresholds), computed with array arithmetic: a determinant bound certifies most
    configurations as full rank, and only the rest get an SVD (see :class:`ChainScanner`).

    Parameters
    ----------
    mech : Mechanism, str or Path
        An open-chain mechanism with an output, or the path of its file.
    configurations : array (N, n) or iterable of such arrays
        Joint coordinates in file order (radians, metres).  An iterable is consumed
        chunk by chunk and never held whole.
    chunk : int
        Rows processed together.
    all_sigma : bool
        Run the SVD everywhere (``ratio`` for every configuration; slower).

    Returns
    -------
    ScanResult
        Each configuration's rank, screened flag, ratio and bound.
    """
    if not isinstance(mech, Mechanism):
        mech = read_mechanism(mech)
    return ChainScanner(mech).scan(configurations, chunk=chunk, all_sigma=all_sigma)
