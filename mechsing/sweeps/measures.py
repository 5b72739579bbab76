"""The distance-to-singularity measures of a sweep, batched in float.

Owns :class:`Measures`: for an array of closed configurations ``Q`` (N, n), the rank
and the smallest relative singular value of each test, computed for all rows at once
with numpy's batched SVD (no Python loop over configurations):

* ``closure``: the stacked loop screw systems (each loop's current screws with its
  crossing signs, commensurate).  Their singular values are those of the closure
  system :func:`mechsing.analyze` decides (each loop's rows in an orthonormal basis of
  its subgroup are an isometric image of its six-row screws).
* ``input``: the output map on the motion space, ``T N`` / |T| (``N`` an orthonormal
  basis of the closure kernel, ``T`` the commensurate output twists or point
  velocities): it loses rank where the inputs can move while the output stays still
  (an input singularity; also the impossible-output test).
* ``output``: the input selection on the motion space, ``E N``: it loses rank where
  the output can move with the inputs locked (an output singularity, a dead centre;
  also the impossible-input test).
* ``constraint``: the legs' combined constraint wrench system (each leg's wrenches
  reciprocal to the twists it lets the output make).

Factorisations.  Where the closure's generic rank is its number of rows (every loop's
rows independent, as in a spatial parallel robot), its kernel is the orthogonal
complement of its row space: a QR factorisation of its transpose gives that complement
(the orthogonal factor's last columns, formed from its Householder vectors without the
rest of it, :func:`complement`) and a triangular factor with the same singular values,
so the closure's singular values come without singular vectors, at about half the cost
of its SVD.  Its singular vectors
are then computed only where they are used (:meth:`PointMeasures.basis`: the sign tests
of the few pairs the screen of :meth:`Measures.compressed_pairs` keeps, and the
refinements), by the same SVD of the same kept matrix as otherwise.  So are the other
tests' where their vectors are not read at every configuration (on a path; on a grid,
where the sign tests between rows read them all, the constraint test alone): their
singular values come from LAPACK's values-only SVD (the form ``values first`` of the
table ``sweep test factors``, :mod:`.factors`), the thin SVD's own near a rank decision.

Each test's measure is its ``g``-th singular value, ``g`` its generic rank (the rank
the full analysis finds at regular configurations of the sweep's start), relative to
the same reference as the full analysis: the operator's norm for ``input`` and
``output``, the largest singular value for ``closure`` and ``constraint``; its rank
is decided by float's two-threshold rule (``-1``: undecided).  A measure that
vanishes is a singularity of that test; how close it comes is what a designer plots.

Signs.  A singular value does not change sign, a determinant does: for consecutive
points ``a``, ``b`` of a path (or neighbouring points of a grid),
:meth:`Measures.compressed` compresses the matrix at ``b`` onto the leading singular
vectors of the one at ``a`` (:mod:`.signs`).

Conventions: commensurate matrices (moved to the centroid, v / L, length columns
times L); twists ``(omega, v)``.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing.kinematics import forward
from mechsing.numeric import relative_singular_values
from mechsing.numeric.linalg import complement
from mechsing.singularity.criteria import ClosureTest, ConstraintTest, Criterion, MotionTest
from mechsing.sweeps.factors import VALUES, largest_singular_value, singular_values
from mechsing.sweeps.signs import (
    SCREEN_CHUNK,
    SIGNED,
    UNIT_REFERENCE,
    compressed_of,
    pairs,
    signed_key,
)

__all__ = ["SIGNED", "TESTS", "Measures", "PointMeasures"]

#: the tests a sweep measures, in the order of every output
TESTS = ("closure", "input", "output", "constraint")


#: a closure of full row rank whose matrix is larger than this (bytes per configuration:
#: the hexapod's 30 x 36 is 8640) is computed again where its sign is read, not kept with
#: every measured configuration; a planar loop's 3 x n is kept
_KEPT_CLOSURE_BYTES = 2048


@dataclass
class PointMeasures:
    """The measures of a batch of configurations: per test, the decided rank (int, -1
    undecided), the smallest relative singular value, and the matrices' leading
    singular vectors (kept for :meth:`Measures.compressed`; read them with
    :meth:`basis`)."""

    rank: dict[str, np.ndarray]
    ratio: dict[str, np.ndarray]
    #: the leading singular vectors of the tests whose SVD was computed with the measures
    bases: dict[str, tuple[np.ndarray, np.ndarray]]
    kernel: np.ndarray | None
    #: the signed tests' matrices (for the sign changes between neighbours); a closure of
    #: full row rank's, and the bordered tests' rows, are not kept but computed again
    #: where they are indexed (:class:`_Recomputed`)
    matrices: dict[str, Any] | None = None
    #: tests measured without their singular vectors (the closure of full row rank),
    #: with their generic rank: :meth:`basis` computes the vectors from ``matrices``
    deferred: dict[str, int] = field(default_factory=dict)
    #: the largest singular value of each test's matrix, per configuration
    top: dict[str, np.ndarray] = field(default_factory=dict)
    #: per test measured without its singular vectors: the Frobenius norm of its matrix
    #: at each configuration and of the step to the next one (NaN where there is none),
    #: which :meth:`Measures.compressed_pairs` screens neighbours with
    steps: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    #: deferred tests whose vectors are those of the thin SVD (the others': the full one)
    thin: frozenset[str] = frozenset()
    #: per signed test measured without its singular vectors, of generic rank g >= 2: its
    #: matrix's singular value sigma_(g-1) (absolute), from the same factorisation as the
    #: measure (what :func:`~mechsing.sweeps.falling.others_fall` screens pairs with)
    second: dict[str, np.ndarray] = field(default_factory=dict)
    #: the singular vectors :meth:`basis` computed last, with their test and points
    _last: tuple[Any, tuple[np.ndarray, np.ndarray]] | None = field(
        default=None, repr=False, compare=False
    )

    def __len__(self) -> int:
        return len(next(iter(self.ratio.values()))) if self.ratio else 0

    @staticmethod
    def gather(parts: list[tuple[PointMeasures, Any]]) -> PointMeasures:
        """The measures of the points ``idx`` (an index array or a slice) of each measured
        batch of ``parts``, in order, as one batch (several rows of a grid refined
        together, a row of a chunk's batch, the chunks of a long row).  Every array is per
        point, so each point's entries are those of its own batch; matrices that were not
        kept (:class:`_Recomputed`) stay so, computed again from the points'
        configurations where they are read; the screen's step norms are kept where a
        point's next one is gathered after it (NaN elsewhere)."""
        first = parts[0][0]

        def cat(arrays: list[Any]) -> np.ndarray:
            """The points ``idx`` of each part's array (``arrays``: one per part), in order."""
            got = [a[idx] for a, (_, idx) in zip(arrays, parts, strict=True)]
            return got[0] if len(got) == 1 else np.concatenate(got)

        def kept(pm: PointMeasures) -> dict[str, Any]:
            """A part's matrices (every part keeps them where the first does)."""
            assert pm.matrices is not None, "a gathered batch kept no matrices"
            return pm.matrices

        matrices: dict[str, Any] | None = None
        if first.matrices is not None:
            matrices = {}
            lazy = [
                t
                for t in first.matrices
                if all(isinstance(kept(pm)[t], _Recomputed) for pm, _ in parts)
            ]
            if lazy:
                source = _Source.gather([(kept(pm)[lazy[0]].source, idx) for pm, idx in parts])
            for t in first.matrices:
                if t in lazy:
                    matrices[t] = _Recomputed(source, t)
                else:
                    matrices[t] = cat([kept(pm)[t] for pm, _ in parts])
        return PointMeasures(
            {t: cat([pm.rank[t] for pm, _ in parts]) for t in first.rank},
            {t: cat([pm.ratio[t] for pm, _ in parts]) for t in first.ratio},
            {
                t: (
                    cat([pm.bases[t][0] for pm, _ in parts]),
                    cat([pm.bases[t][1] for pm, _ in parts]),
                )
                for t in first.bases
            },
            None if first.kernel is None else cat([pm.kernel for pm, _ in parts]),
            matrices,
            dict(first.deferred),
            {t: cat([pm.top[t] for pm, _ in parts]) for t in first.top},
            {t: _gathered_steps([(pm.steps[t], idx) for pm, idx in parts]) for t in first.steps},
            first.thin,
            {t: cat([pm.second[t] for pm, _ in parts]) for t in first.second},
        )

    def basis(self, t: str, idx: Any) -> tuple[np.ndarray, np.ndarray]:
        """The leading ``g`` left and right singular vectors of test ``t``'s matrix at the
        configurations ``idx`` (an index array or a slice): (points, rows, g) and
        (points, columns, g)."""
        if t in self.bases:
            U, V = self.bases[t]
            return U[idx], V[idx]
        assert self.matrices is not None, f"no singular vectors of {t} kept"
        # the last ones asked are kept (a refinement asks for the same points again)
        key = (t, repr(idx) if isinstance(idx, slice) else np.asarray(idx).tobytes())
        if self._last is not None and self._last[0] == key:
            return self._last[1]
        g = self.deferred[t]
        U, _, Vt = np.linalg.svd(self.matrices[t][idx], full_matrices=t not in self.thin)
        out = U[..., :g], np.swapaxes(Vt[..., :g, :], -1, -2)
        self._last = (key, out)
        return out


class Measures:
    """The sweep's tests for one float kinematic model.

    Parameters
    ----------
    model : float KinematicModel
    generic : the generic rank of each test (from the full analysis at the start); a
        test with no generic rank (None) or none at all (no loop, no inputs or output,
        fewer than two legs) is not measured
    vectors_everywhere : whether the signed tests' singular vectors are read at every
        configuration (a grid: the sign tests between its rows), so that they are
        computed with the values rather than where they are read
    """

    def __init__(
        self, model: Any, generic: dict[str, int | None], vectors_everywhere: bool = False
    ) -> None:
        self.model = model
        self.vectors_everywhere = vectors_everywhere
        self.mech = mech = model.mech
        self.frame = model.float_frame
        # the tests, each defined once (their plans built once per model)
        self.closure = ClosureTest.of(mech, model)
        self.motion = MotionTest.of(mech, model)
        self.constraint = ConstraintTest.of(mech, model)
        E = self.motion.E
        self.E = None if E is None else np.asarray(E, dtype=float)
        out = mech.output
        self.legs = self.constraint.legs
        present = {
            "closure": bool(mech.loops),
            # T N needs the output; E N only the inputs (every test whose ingredients
            # the file has is measured: :func:`mechsing.singularity.zfb.tests_run`)
            "input": out is not None,
            "output": self.E is not None,
            "constraint": bool(self.legs),
        }
        self.generic: dict[str, int] = {
            t: g for t in TESTS if present[t] and (g := generic.get(t)) is not None and g != 0
        }
        #: the closure's factorisation done with its kernel (:meth:`matrices`): ("qr",
        #: its singular values) or ("svd", U, s, Vt); None before a batch is measured
        self._closure_svd: tuple[Any, ...] | None = None
        self.tests = tuple(self.generic)

    @property
    def loop_signs(self) -> np.ndarray:
        """Each loop's crossing signs per coordinate (:class:`ClosureTest`'s plan)."""
        return self.closure.loop_signs

    @property
    def out_signs(self) -> np.ndarray | None:
        """The output chain's signs per coordinate (:class:`MotionTest`'s plan)."""
        return self.motion.out_signs

    @property
    def out_point(self) -> np.ndarray | None:
        """The output point in floats (:class:`MotionTest`'s plan)."""
        return self.motion.out_point

    @property
    def pointwise(self) -> bool:
        """Whether each configuration's measures are independent of the others measured
        with it (so that several rows may be measured in one batch).  Not so where a
        rank is taken over the whole batch: a leg with inner loops (the rank of their
        system, :meth:`_constraint`), a closure without a generic rank."""
        if any(leg.inner_loops for leg in self.legs) and "constraint" in self.tests:
            return False
        return not (self.mech.loops and not self.generic.get("closure"))

    def levelled(self, t: str, level: int) -> Measures:
        """The same measures for test ``t`` alone, at rank ``level`` instead of its
        generic rank: inside a set where the test is singular, where its rank drops
        further."""
        out = copy.copy(self)
        out.generic = {t: level}
        out.tests = (t,)
        return out

    # ------------------------------------------------------------------ matrices

    def matrices(
        self, Q: np.ndarray, signed: bool = False
    ) -> tuple[dict[str, np.ndarray], np.ndarray | None]:
        """Each test's commensurate matrix at the rows of Q, and the closure kernel
        (``signed``: only the tests whose sign is read, :data:`SIGNED`)."""
        P, S, Ss = self._screws(Q)
        N = Q.shape[0]
        out: dict[str, np.ndarray] = {}
        if self.mech.loops:
            out["closure"] = self._closure(Ss)
        kernel = None
        if self.mech.loops and self.full_row_rank():
            # the kernel is the complement of the row space: C^T = Q R, and C = R^T Q^T
            # has R's singular values
            # (LAPACK's raw form: the Householder vectors below R, not the whole Q)
            C = out["closure"]
            rows = C.shape[1]
            h, tau = np.linalg.qr(np.swapaxes(C, 1, 2), mode="raw")  # h: (N, rows, n)
            if "input" in self.tests or "output" in self.tests:
                kernel = complement(h, tau)  # (N, n, n - rows)
            # h's lower triangle (its first rows columns) is R^T
            Rt = h[:, :, :rows] * np.tri(rows)
            self._closure_svd = ("qr", singular_values(np.swapaxes(Rt, 1, 2)))
        if "input" in self.tests or "output" in self.tests:
            if self.mech.loops and kernel is None:
                g = self.generic.get("closure") or _max_rank(out["closure"])
                U, s, Vt = np.linalg.svd(out["closure"], full_matrices=True)
                kernel = np.swapaxes(Vt[:, g:, :], 1, 2)  # (N, n, n - g)
                self._closure_svd = ("svd", U, s, Vt)
            # without loops every joint rate is a motion: N is the identity
            # without loops, the couplings' kernel (constant) stands for the closure's
            K = kernel if kernel is not None else self.closure.coupling_kernel
            if "input" in self.tests:
                T, nT = self._output_rows(P, S)
                TN = T if K is None else T @ K
                out["input"] = TN / np.maximum(nT, 1e-300)[:, None, None]
                if kernel is not None:  # the rows themselves, for the bordered sign test
                    out["input_rows"] = T / np.maximum(nT, 1e-300)[:, None, None]
            if "output" in self.tests:
                E = self._selection()
                EK: np.ndarray = E if K is None else E @ K
                out["output"] = EK if EK.ndim == 3 else np.broadcast_to(EK, (N, *EK.shape))
                if kernel is not None:
                    out["output_rows"] = np.broadcast_to(E, (N, *E.shape))
        if "constraint" in self.tests and not signed:
            # the legs' combined constraint wrenches as rows, (N, wrenches, 6)
            out["constraint"] = self.constraint.wrench_rows(
                Ss, self.closure.loop_signs, reduced=self.constraint.subalgebra is not None
            )
        return out, kernel

    def _screws(self, Q: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray]:
        """The body poses, the current screws and the commensurate screws at the rows of Q."""
        P = forward.batch_poses(self.model, Q)
        S = forward.current_screws(self.model, Q, P)
        return P, S, self.frame.screws(S)

    def _closure(self, Ss: np.ndarray) -> np.ndarray:
        """The stacked loop screw systems from the commensurate screws, then the couplings'
        rows, (N, 6 loops + couplings, n) (:meth:`ClosureTest.matrices`)."""
        return self.closure.matrices(Ss)

    def _output_rows(
        self, P: dict[str, np.ndarray], S: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """The commensurate output rows T (twists, or the output point's velocities) and
        their norms |T|."""
        x = self.motion.output_point(P, float_point=True)
        T = self.motion.output_rows(S, x)  # makes it commensurate
        return T, largest_singular_value(T)

    def unkept(self, Q: np.ndarray) -> dict[str, np.ndarray]:
        """The matrices a measured batch of a closure of full row rank does not keep
        (:class:`_Recomputed`), at the rows of Q: the closure and the bordered tests'
        rows, computed as :meth:`matrices` computes them (the same numbers)."""
        P, S, Ss = self._screws(Q)
        out = {"closure": self._closure(Ss)}
        if "input" in self.tests:
            T, nT = self._output_rows(P, S)
            out["input_rows"] = T / np.maximum(nT, 1e-300)[:, None, None]
        if "output" in self.tests:
            E = self._selection()
            out["output_rows"] = np.broadcast_to(E, (Q.shape[0], *E.shape))
        return out

    def _selection(self) -> np.ndarray:
        """The input selection E: there when the output test is measured (it is measured
        only where the file names inputs)."""
        assert self.E is not None, "the output test is measured without inputs"
        return self.E

    def full_row_rank(self) -> bool:
        """Whether the closure is measured and its generic rank is its number of rows
        (its kernel then needs no singular vectors)."""
        g = self.generic.get("closure")
        return "closure" in self.tests and g is not None and g == self.closure.rows

    # ------------------------------------------------------------------ measures

    def __call__(self, Q: np.ndarray) -> PointMeasures:
        self._closure_svd = None
        mats, kernel = self.matrices(Q)
        rank, ratio, bases, deferred, top, second = {}, {}, {}, {}, {}, {}
        thin: set[str] = set()
        for t in self.tests:
            A, g, unit = mats[t], self.generic[t], t in UNIT_REFERENCE
            done = self._closure_svd if t == "closure" else None
            # the vectors deferred where they are not read at every configuration
            later = not (t in SIGNED and self.vectors_everywhere and not self.square_rows(t))
            if t == "constraint" and self.constraint.subalgebra is not None:
                # the rows reduced to the legs' subalgebra: their values alone (the test
                # has no sign: no one reads its vectors)
                s = self.constraint.combined_values(np.linalg.svd(A, compute_uv=False))
                vectors = None
            else:
                s, vectors = _test_factors(A, g, unit, done, later)
            if vectors is not None:
                bases[t] = vectors
            else:
                deferred[t] = g
                if done is None:
                    thin.add(t)
                if t in SIGNED and 2 <= g <= s.shape[1]:
                    second[t] = s[:, g - 2]
            if unit:
                rel = s  # already relative to the operator's norm (|T| or |E| = 1)
                bounds = self.motion.ranks_of_relative(rel)
            else:
                rel = relative_singular_values(s)
                bounds = Criterion.ranks_of_relative(rel)
            rank[t] = bounds.decided.astype(np.int16)
            ratio[t] = rel[:, g - 1] if g <= rel.shape[1] else np.zeros(len(rel))
            top[t] = s[:, 0] if s.shape[1] else np.zeros(len(s))
        signed, steps = _kept(self, Q, mats, kernel, deferred, thin)
        return PointMeasures(
            rank, ratio, bases, kernel, signed, deferred, top, steps, frozenset(thin), second
        )

    def bordered_test(self, t: str) -> bool:
        """Whether the sign of test ``t`` is read from the bordered determinant: an input
        or output test of a closed chain whose generic rank is the dimension of the
        closure kernel (its matrix X N square), with the closure measured too."""
        g, gc = self.generic.get(t), self.generic.get("closure")
        return (
            t in ("input", "output")
            and g is not None
            and gc is not None
            and "closure" in self.tests
            and g == self.model.n - gc
        )

    def square_rows(self, t: str) -> bool:
        """Whether the bordered determinant of test ``t`` reads its rows X as they are:
        X N has as many rows as its generic rank (the output test of as many inputs as
        the motion has degrees of freedom), so U_t is square (:func:`.signs.bordered`)."""
        if not self.bordered_test(t):
            return False
        rows = self.E.shape[0] if t == "output" and self.E is not None else None
        return rows is not None and rows == self.generic[t]

    def compressed_pairs(
        self, pm: PointMeasures, ia: np.ndarray, ib: np.ndarray
    ) -> dict[str, np.ndarray]:
        """The sign test between neighbours of one measured batch (rows ``ia`` and
        ``ib``), from the matrices it kept (:func:`.signs.pairs`)."""
        return pairs(pm, ia, ib)

    def compressed(self, a: PointMeasures, ia: np.ndarray, Qb: np.ndarray) -> dict[str, np.ndarray]:
        """For pairs of points (row ``ia`` of the measured batch ``a``, row of ``Qb``): per
        test, the determinant of the matrix at b compressed onto a's leading singular
        vectors.  Positive at a itself; negative where a rank drop was crossed
        (:func:`.signs.compressed_of`)."""
        mats, kernel = self.matrices(Qb, signed=True)
        return compressed_of(self, a, ia, mats, kernel)

    def compressed_measured(
        self, a: PointMeasures, ia: np.ndarray, b: PointMeasures, ib: np.ndarray
    ) -> dict[str, np.ndarray]:
        """:meth:`compressed` where the points b are rows ``ib`` of a measured batch
        ``b`` (a grid's neighbouring row): b's matrices and kernel are the ones it kept,
        not computed again."""
        assert b.matrices is not None
        mats = {k: v[ib] for k, v in b.matrices.items() if signed_key(k)}
        return compressed_of(self, a, ia, mats, None if b.kernel is None else b.kernel[ib])


def _test_factors(
    A: np.ndarray, g: int, unit: bool, done: Any, later: bool
) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray] | None]:
    """A test's singular values and its ``g`` leading singular vectors (U, V), or None
    where the vectors are deferred (computed where they are read,
    :meth:`PointMeasures.basis`): the closure's factorisation done with its kernel
    (``done``: the QR's values alone, or the SVD), the values alone where ``later``
    allows and the table ``sweep test factors`` has a form (:mod:`.factors`), else
    numpy's thin SVD (the generic definition)."""
    if done is not None and done[0] == "qr":
        return done[1], None
    if done is not None:
        _, U, s, Vt = done  # the kernel's SVD, already done
    else:
        values = VALUES.pick(A, g, unit) if later else None
        if values is not None:
            return values(A, g, unit), None
        U, s, Vt = np.linalg.svd(A, full_matrices=False)
    k = min(g, s.shape[1])
    return s, (U[:, :, :k], np.swapaxes(Vt[:, :k, :], 1, 2))


def _kept(
    measures: Measures,
    Q: np.ndarray,
    mats: dict[str, np.ndarray],
    kernel: np.ndarray | None,
    deferred: dict[str, int],
    thin: set[str],
) -> tuple[dict[str, Any], dict[str, tuple[np.ndarray, np.ndarray]]]:
    """The matrices a measured batch keeps (the signed tests', whose neighbours' signs
    read them, the bordered tests' rows, and those of the tests whose vectors are
    deferred), and the step norms of those its neighbours' screen reads."""
    signed: dict[str, Any] = {t: mats[t] for t in measures.tests if t in SIGNED or t in thin}
    for t in ("input", "output"):
        if measures.bordered_test(t) and f"{t}_rows" in mats:
            signed[f"{t}_rows"] = mats[f"{t}_rows"]
    steps = {}
    for t in thin:
        if t in SIGNED and not (t in ("input", "output") and kernel is not None):
            steps[t] = _steps(mats[t])  # screened by Weyl's bound (_screened_pairs)
    if deferred.keys() - thin:
        # the closure of full row rank (its rows' neighbours are read only through the
        # screen's norms); where it is large, its matrices, and the bordered tests' rows,
        # are computed again where they are read
        for t in deferred.keys() - thin:
            steps[t] = _steps(mats[t])
        if mats["closure"][0].nbytes > _KEPT_CLOSURE_BYTES:
            source = _Source(measures, Q)
            for t in signed:
                if t in source.keys:
                    signed[t] = _Recomputed(source, t)
    if measures.constraint.subalgebra is not None:
        # the rows reduced to the legs' subalgebra are not the test's matrix, and no one
        # reads the vectors of a test with no sign (its located points are not placed
        # again: mechsing.sweeps.relocate)
        signed.pop("constraint", None)
    return signed, steps


def _max_rank(A: np.ndarray) -> int:
    return int(np.max(Criterion.ranks(np.linalg.svd(A, compute_uv=False)).hi))


def _steps(M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The Frobenius norm of each matrix of M (N, r, c) and of its difference with the
    next one (NaN for the last): what the neighbours' screen reads."""
    size = np.sqrt(np.einsum("nij,nij->n", M, M))
    ahead = np.full(len(M), np.nan)
    # the differences a block at a time (a small working array, not a second M)
    for lo in range(0, len(M) - 1, SCREEN_CHUNK):
        hi = min(lo + SCREEN_CHUNK, len(M) - 1)
        D = M[lo + 1 : hi + 1] - M[lo:hi]
        ahead[lo:hi] = np.sqrt(np.einsum("nij,nij->n", D, D))
    return size, ahead


def _gathered_steps(
    parts: list[tuple[tuple[np.ndarray, np.ndarray], Any]],
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_steps` of the points ``idx`` of each part, in order: a point's step norm is
    kept where its next point in its batch is the next one gathered, NaN elsewhere."""
    sizes, aheads = [], []
    for (size, ahead), idx in parts:
        pos = np.arange(len(size))[idx]
        follows = np.zeros(len(pos), dtype=bool)
        follows[:-1] = pos[1:] == pos[:-1] + 1
        sizes.append(size[pos])
        aheads.append(np.where(follows, ahead[pos], np.nan))
    if len(parts) == 1:
        return sizes[0], aheads[0]
    return np.concatenate(sizes), np.concatenate(aheads)


class _Source:
    """The configurations of a measured batch, whose large matrices
    (:meth:`Measures.unkept`) are computed again at the rows read; the last rows asked
    are kept (a refinement reads the same points several times).  Sent to another
    process (a distributed grid's rows), it carries the matrices themselves."""

    keys = ("closure", "input_rows", "output_rows")

    def __init__(self, measures: Measures | None, Q: np.ndarray) -> None:
        self.measures = measures
        self.Q = np.array(Q, dtype=float)
        #: the rows asked last (their key) and their matrices
        self._last: tuple[Any, dict[str, np.ndarray]] | None = None
        #: the matrices themselves, where the measures are not here (received whole)
        self._whole: dict[str, np.ndarray] = {}

    @staticmethod
    def gather(parts: list[tuple[_Source, Any]]) -> _Source:
        """The points ``idx`` of each source, in order, as one source: computed again by
        the same measures from their configurations, or, where a part was received whole
        (or the parts' measures differ), whole."""
        measures = parts[0][0].measures
        if measures is not None and all(s.measures is measures for s, _ in parts):
            return _Source(measures, np.concatenate([s.Q[idx] for s, idx in parts]))
        out = _Source(None, np.concatenate([s.Q[idx] for s, idx in parts]))
        got = [s.at(idx) for s, idx in parts]
        out._whole = {k: np.concatenate([g[k] for g in got]) for k in got[0]}
        return out

    def at(self, idx: Any) -> dict[str, np.ndarray]:
        if isinstance(idx, slice):
            key: Any = ("slice", idx.start, idx.stop, idx.step)
        else:
            a = np.asarray(idx)
            key = (a.dtype.str, a.shape, a.tobytes())
        if self._last is not None and self._last[0] == key:
            return self._last[1]
        if self.measures is None:  # received from another process: kept whole
            got = {k: v[idx] for k, v in self._whole.items()}
        else:
            got = self.measures.unkept(self.Q[idx])
        self._last = (key, got)
        return got

    def __getstate__(self) -> dict[str, Any]:
        # sent to another process: the matrices themselves, not the model that computes them
        whole = self.at(slice(None)) if self.measures is not None else self._whole
        return {"measures": None, "Q": self.Q, "_last": None, "_whole": whole}


class _Recomputed:
    """One test's matrices at a measured batch's configurations, not kept but computed
    again (:meth:`Measures.unkept`, the same numbers) at the rows indexed."""

    def __init__(self, source: _Source, t: str) -> None:
        self.source = source
        self.t = t

    def __len__(self) -> int:
        return len(self.source.Q)

    def __getitem__(self, idx: Any) -> np.ndarray:
        return self.source.at(idx)[self.t]

    @property
    def shape(self) -> tuple[int, ...]:
        return (len(self), *self[:1].shape[1:])

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        """Every row's matrix (an array of the whole batch, computed again)."""
        whole = self[:]
        return whole if dtype is None else whole.astype(dtype)
