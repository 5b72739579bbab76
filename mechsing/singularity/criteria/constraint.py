"""The constraint test (Zlatanov, Bonev, Gosselin 2002), defined once: each leg's twist
system ``T_i`` (the output twists through a path of the leg's joints from the base, over
the solutions of the leg's own inner loops: for a serial leg, simply its screws), its
reciprocal (constraint) wrench system ``W_i``, and the legs' combined constraint system
``W_c = sum W_i``, whose rank loss below its generic value lets the output move outside
its generic motion type.

Reference: each leg's twist system and the combined wrenches are decided relative to
their own largest singular value.

:meth:`ConstraintTest.decide` decides one configuration at any precision from its
closure system; :meth:`ConstraintTest.batch_values` and
:meth:`ConstraintTest.wrench_rows` compute a batch of float configurations.  Where every
leg moves in one subgroup (a planar parallel robot in its plane's G), a batch is modelled
only that far: each leg's wrenches within the subalgebra, the annihilator every leg
resists counted in closed form (:meth:`ConstraintTest.combined_values`).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from mechsing.kinematics import KinematicModel
from mechsing.kinematics.protocol import ClosureModel
from mechsing.model import Leg, Mechanism
from mechsing.numeric import Precision, RankDecision, decide_rank
from mechsing.numeric.linalg import clear_complements, clear_row_rank, svd
from mechsing.screws import fixed_loop_basis
from mechsing.singularity.criteria.base import Criterion, singular_values

if TYPE_CHECKING:
    from mechsing.screws import ClosureSystem

__all__ = ["ConstraintTest", "LegPlan", "leg_path"]


def leg_path(mech: Mechanism, leg: Leg, base: str, body: str) -> list[tuple[str, int]]:
    """A path of (joint, sign) from base to body through the leg's joints (BFS, file order)."""
    joints = [mech.joint(j) for j in leg.joints]
    prev: dict[str, tuple[str, str, int] | None] = {base: None}
    queue = deque([base])
    while queue:
        x = queue.popleft()
        if x == body:
            break
        for j in joints:
            a, b = j.between
            if x not in (a, b):
                continue
            y = b if x == a else a
            if y in prev or (y == base):
                continue
            prev[y] = (x, j.name, 1 if x == a else -1)
            queue.append(y)
    path: list[tuple[str, int]] = []
    x = body
    while prev.get(x) is not None:
        step = prev[x]
        assert step is not None  # the loop's condition
        px, jn, sg = step
        path.append((jn, sg))
        x = px
    return path[::-1]


@dataclass(frozen=True)
class LegPlan:
    """A leg of a parallel mechanism, as its tests use it: its coordinate columns, the
    joint of each column, the signs of its path from the base to the output body (one
    per coordinate of the model), and the indices of the loops that lie inside it."""

    columns: list[int]
    names: list[str]
    path_signs: np.ndarray
    inner: tuple[int, ...]
    joints: frozenset[str]

    @property
    def inner_loops(self) -> bool:
        return bool(self.inner)


class ConstraintTest(Criterion):
    """The constraint test of one mechanism and model; plan: its legs (none with fewer
    than two legs or without an output: the test is then not run)."""

    name = "constraint"
    reference = "each leg's twists and the combined wrenches relative to their largest"

    def __init__(self, mech: Mechanism, model: ClosureModel) -> None:
        super().__init__(mech, model)
        out = mech.output
        legs: list[LegPlan] = []
        if out is not None and len(mech.legs) >= 2:
            for leg in mech.legs:
                legset = set(leg.joints)
                cols: list[int] = []
                names: list[str] = []
                for j in leg.joints:
                    jk = model.joint(j)
                    cols.extend(range(jk.columns.start, jk.columns.stop))
                    names.extend([jk.name] * (jk.columns.stop - jk.columns.start))
                coef = np.zeros(model.n)
                for jn, sg in leg_path(mech, leg, out.relative_to, out.body):
                    coef[model.joint(jn).columns] = sg
                inner = tuple(i for i, lp in enumerate(mech.loops) if set(lp.joints) <= legset)
                legs.append(LegPlan(cols, names, coef, inner, frozenset(legset)))
        self.legs = tuple(legs)
        #: an orthonormal commensurate basis (6, d), d < 6, of the one subalgebra every
        #: leg's twists stay in (:meth:`_common_subalgebra`), or None
        self.subalgebra = self._common_subalgebra(mech, model) if self.legs else None

    def _common_subalgebra(self, mech: Mechanism, model: ClosureModel) -> np.ndarray | None:
        """The subalgebra h of the loops' one fixed subgroup (each loop's first body the
        ground: :func:`mechsing.screws.fixed_loop_basis`; the loops' bases together span
        no more than one of them, by the rank rule), when every joint on a leg's path
        lies in a loop: the legs' twists then lie in h at every configuration (a planar
        five-bar's in its plane's g).  None where there is no such h, or it is all of D."""
        if not isinstance(model, KinematicModel) or not mech.loops:
            return None
        bases = [fixed_loop_basis(model, loop) for loop in mech.loops]
        if any(b is None for b in bases):
            return None
        first = bases[0]
        assert first is not None
        d = first.shape[1]
        if len(bases) > 1:
            together = np.hstack([b for b in bases if b is not None])
            if decide_rank(together, Precision("float")).rank != d:
                return None
        looped = np.zeros(model.n, dtype=bool)
        for loop in mech.loops:
            for name in loop.joints:
                looped[model.joint(name).columns] = True
        if any(np.any((leg.path_signs != 0) & ~looped) for leg in self.legs):
            return None
        return first

    # ------------------------------------------------------------------ one configuration

    def decide(
        self, cs: ClosureSystem, prec: Precision
    ) -> tuple[RankDecision, list[np.ndarray]] | None:
        """Rank of the combined constraint wrench system at the configuration of the
        closure system ``cs``, and each leg's constraint wrenches (commensurate vectors y
        with y . twist = 0 for every twist the leg lets the output make), computed and
        decided at ``prec`` (float or mp:N); None when the test is not run."""
        if not self.legs:
            return None
        model = self.model
        with model.precision.context():
            Ss0 = (
                cs.scaled_screws if cs.scaled_screws is not None else model.frame.screws(cs.screws)
            )
        L = model.length_scale
        with prec.context():
            Ss = prec.asarray(Ss0)
            wrenches = []
            for leg in self.legs:
                cols = leg.columns
                inner = [ls.matrix for ls in cs.loops if set(ls.loop.joints) <= leg.joints]
                if inner:
                    Mi = prec.asarray(np.concatenate(inner, axis=0))[:, cols]
                    dec = decide_rank(Mi, prec, L, want_spaces=True, native_spaces=True)
                    K = dec.null_space
                else:
                    K = prec.backend.eye(len(cols))
                Tl = (Ss * leg.path_signs[None, :])[:, cols] @ K
                dec = decide_rank(Tl, prec, L)
                r = dec.rank if dec.rank is not None else dec.rank_bounds[1]
                if r < Tl.shape[0]:
                    U, _s, _ = svd(Tl)
                    wrenches.append(U[:, r:])
                else:  # the leg moves the output freely: no constraint wrench, no SVD
                    wrenches.append(prec.backend.zeros((Tl.shape[0], 0)))
            Wc = np.concatenate(wrenches, axis=1) if wrenches else prec.backend.zeros((6, 0))
            return decide_rank(Wc.T if Wc.shape[1] else np.zeros((0, 6)), prec, L), wrenches

    # ------------------------------------------------------------------ batches

    def _leg_wrenches(self, Ss: np.ndarray, leg: LegPlan) -> tuple[np.ndarray, np.ndarray]:
        """A serial leg's left singular vectors (B, 6, 6) and the rank taken at each
        configuration of commensurate screws ``Ss`` (B, 6, n): its wrenches are the
        columns beyond that rank."""
        Tl = (Ss * leg.path_signs[None, None, :])[:, :, leg.columns]
        r = self.ranks(singular_values(Tl)).taken
        return np.linalg.svd(Tl, full_matrices=True)[0], r

    def batch_values(self, Ss: np.ndarray) -> list[int | None]:
        """The decided rank of the combined constraint wrenches at each of a batch of float
        configurations (commensurate screws ``Ss`` (B, 6, n)) of legs without inner
        loops, as :meth:`decide` decides one."""
        B = Ss.shape[0]
        per_leg = [self._leg_wrenches(Ss, leg) for leg in self.legs]
        out: list[int | None] = [None] * B
        groups: dict[tuple[int, ...], list[int]] = {}
        for b in range(B):
            groups.setdefault(tuple(int(r[b]) for _, r in per_leg), []).append(b)
        for ranks, idx in groups.items():
            ix = np.array(idx)
            Wc = np.concatenate(
                [U[ix][:, :, r:] for (U, _), r in zip(per_leg, ranks, strict=True)], axis=2
            )
            if Wc.shape[2] == 0:
                for b in idx:
                    out[b] = 0
                continue
            got = self.ranks(singular_values(np.swapaxes(Wc, 1, 2))).ranks()
            for b, v in zip(idx, got, strict=True):
                out[b] = v
        return out

    def wrench_rows(
        self, Ss: np.ndarray, loop_signs: np.ndarray, reduced: bool = False
    ) -> np.ndarray:
        """The legs' combined constraint wrenches as rows of one width, (B, 6 legs, 6), at a
        batch of float configurations (the columns beyond each leg's rank zero): a leg with
        inner loops (``loop_signs``: each loop's crossing signs per coordinate) over the
        solutions of those loops at the highest rank they take in the batch.

        ``reduced`` (where the legs share a :attr:`subalgebra` h of dimension d): each
        leg's twists in h's coordinates and its wrenches within h, (B, d legs, d); the
        six-row system's singular values are :meth:`combined_values` of theirs."""
        B = Ss.shape[0]
        Qt = self.subalgebra.T if reduced and self.subalgebra is not None else None
        D = 6 if Qt is None else Qt.shape[0]
        blocks = []
        for leg in self.legs:
            Tl = (Ss * leg.path_signs[None, None, :])[:, :, leg.columns]
            if leg.inner:
                Mi = (Ss[:, None, :, :] * loop_signs[list(leg.inner)][None, :, None, :]).reshape(
                    B, -1, Ss.shape[2]
                )[:, :, leg.columns]
                _, s, Vt = np.linalg.svd(Mi, full_matrices=True)
                r = int(np.max(self.ranks(s).hi))
                Tl = Tl @ np.swapaxes(Vt[:, r:, :], 1, 2)
            if Qt is not None:
                Tl = Qt @ Tl  # an isometry of h: the same singular values
            k = Tl.shape[2]
            if 0 < k < D:
                # a leg clearly of full rank: its wrenches are the complement of its
                # twists' span from their QR (the same span as U's last columns below)
                clear, K = clear_complements(Tl)
                W = np.zeros((B, D, D))
                W[:, k:, :] = np.swapaxes(K, 1, 2)
                rest = np.flatnonzero(~clear)
                if len(rest):
                    W[rest] = self._wrenches_by_svd(Tl[rest])
            elif k:
                # a leg whose twists clearly span the whole space resists nothing in it
                W = np.zeros((B, D, D))
                rest = np.flatnonzero(~clear_row_rank(Tl))
                if len(rest):
                    W[rest] = self._wrenches_by_svd(Tl[rest])
            else:
                W = self._wrenches_by_svd(Tl)
            blocks.append(W)
        return np.concatenate(blocks, axis=1)

    def _wrenches_by_svd(self, Tl: np.ndarray) -> np.ndarray:
        """A leg's wrenches as rows (B, D, D) at the rank each matrix of its twists ``Tl``
        (B, D, k) takes: the left singular vectors beyond it (rows before it zero)."""
        U, s, _ = np.linalg.svd(Tl, full_matrices=True)
        hi = self.ranks(s).hi
        mask = np.arange(Tl.shape[1])[None, :] >= hi[:, None]
        return np.swapaxes(U * mask[:, None, :], 1, 2)

    def combined_values(self, s: np.ndarray) -> np.ndarray:
        """The singular values (B, 6), descending, of the six-row combined wrenches
        (:meth:`wrench_rows`) from those ``s`` (B, d) of the reduced rows.  Each leg's
        twists lie in h, so its wrenches are h's annihilator (6 - d of them) beside its
        wrenches within h, orthogonal to them: the Gram matrix of all the legs' rows is
        ``legs`` times the projector on the annihilator plus the reduced rows' own, and
        the values are sqrt(legs), 6 - d times, and ``s`` (none above it: a sum of
        ``legs`` projectors)."""
        assert self.subalgebra is not None
        d = self.subalgebra.shape[1]
        fixed = np.full((s.shape[0], 6 - d), np.sqrt(len(self.legs)))
        both: np.ndarray = np.sort(np.concatenate([fixed, s], axis=1), axis=1)[:, ::-1]
        return both
