"""The sweep itself: its rows, measured, with the singularities located along them.

Owns :class:`Sweep` (one sweep, built once from its :class:`~.plan.Plan`) and the
row-by-row work, which it composes from the modules that own each step:

* a **path** (one swept variable) starts at the sample nearest the ``--from``
  configuration's value (:mod:`.start`, reached from it by continuation), and is
  followed forward to the end of the range and back to its beginning
  (:func:`mechsing.kinematics.paths.follow.follow`);
* a **grid** (two) is rows of paths in the first variable, each started from a first
  column (a path in the second variable at the first variable's start sample, bridged
  to the rows it misses: :mod:`.bridge`); the rows are computed in chunks
  (:meth:`Sweep.rows_of`): their batched Newton calls, measures and refinements are
  shared by the chunk's rows, each row's result that of the row alone;
* every reached sample gets the float measures of :class:`~.measures.Measures`;
* along a row the singularities are located (:class:`~.locate.Locator`) and refined
  (:class:`~.refine.Refiner`); between rows of a grid, the sign changes along the
  columns are refined the same way (:func:`~.bridge.between_rows`);
* each located point is then classified by the full analysis at the sweep's precision
  (:mod:`.classify`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

import numpy as np

from mechsing.kinematics.paths.follow import first_nodes_of, follow_together
from mechsing.kinematics.paths.segments import close_segments
from mechsing.model import Mechanism
from mechsing.numeric import dispatch
from mechsing.sweeps.bridge import between_rows, bridge_column
from mechsing.sweeps.limits import outside
from mechsing.sweeps.locate import Locator, measured
from mechsing.sweeps.measures import Measures, PointMeasures
from mechsing.sweeps.plan import check_determined, plan_sweep
from mechsing.sweeps.records import Located, PathTrace, RowResult, RowSamples, merge_located
from mechsing.sweeps.spec import Variable
from mechsing.sweeps.start import start_of

__all__ = ["Sweep"]

#: rows of a grid followed, measured and refined together hold about this many samples
_ROWS_SAMPLES = 8192
#: ... and at most about this many bytes of their measures (a big mechanism's matrices;
#: 64 MB made the 3-RPR grid's chunks of 8192 samples large enough to be mapped and
#: faulted in again at every chunk, about 6% of its CPU time; 16 MB keeps the five-bar's
#: chunks of 8192, whose halves measured 5% slower)
_ROWS_BYTES = 16 * 2**20


class Sweep:
    """One sweep: its plan (the model, what is held and swept, the start), its measures,
    and its rows with the singularities located along them."""

    def __init__(
        self, mech: Mechanism, variables: list[Variable], from_config: str | None = None
    ) -> None:
        plan = plan_sweep(mech, variables, from_config)
        self.mech = mech
        self.variables = variables
        self.from_config = plan.from_config
        self.model = plan.model
        self.limited = plan.limited
        self.pose = plan.pose
        self.cols = plan.cols
        self.z0 = plan.z0
        self.problem = plan.problem
        #: said once, in the first row's notes: how the path left a singular start
        self.start_notes: list[str] = []
        self.measures = Measures(self.model, plan.generic, vectors_everywhere=len(variables) > 1)
        check_determined(plan, mech, variables)
        #: the commensurate unit of each swept coordinate
        self.scales = tuple(self.scale(c) for c in self.cols)
        self.locator = Locator(self.problem, self.cols, self.measures)

    @property
    def tests(self) -> tuple[str, ...]:
        return self.measures.tests

    def scale(self, col: int) -> float:
        return self.problem.scale(col)

    def _variable(self, col: int) -> Variable:
        return self.variables[self.cols.index(col)]

    def start_of(self, col: int, values: np.ndarray, z: np.ndarray) -> tuple[int, np.ndarray]:
        """The sample nearest z's value of ``col`` that can be reached from z, and its
        configuration (:func:`~.start.start_of`)."""
        return start_of(
            self.problem, col, values, z, self._variable(col), self.from_config, self.start_notes
        )

    def between_many(
        self, pairs: list[tuple[RowResult, RowResult]], col: int
    ) -> list[list[Located]]:
        """The sign changes of each test between neighbouring rows of a grid, for several
        pairs of rows (:func:`~.bridge.between_rows`)."""
        return between_rows(self.locator, pairs, col)

    # ------------------------------------------------------------------ rows

    def row(self, index: int, col: int, values: np.ndarray, z: np.ndarray) -> RowResult:
        """One path in ``col`` through ``values`` from the closed z (at any value of col),
        with its measures and the singularities located along it."""
        return self.rows_of([(index, z)], col, values)[0]

    def rows_of(
        self, starts: list[tuple[int, np.ndarray]], col: int, values: np.ndarray
    ) -> list[RowResult]:
        """:meth:`row` of several rows of a grid (each its index and closed configuration
        at any value of ``col``), the rows' batched work done together: their first
        nodes in one batched Newton, the samples between their nodes in one, their
        measures in one batch, and the crossings along them refined together.  Each row
        is followed, measured and refined exactly as alone (every batched step is per
        configuration)."""
        pb = self.problem
        K = len(values)
        begun = [self.start_of(col, values, z) for _, z in starts]
        # the first node of each direction of each row: one batched Newton
        firsts = first_nodes_of(pb, [(zk, [values[k0:], values[k0::-1]]) for k0, zk in begun], col)
        # both directions of every row, node by node in lockstep
        flat = follow_together(
            pb,
            col,
            [
                (zk, v, f)
                for (k0, zk), first in zip(begun, firsts, strict=True)
                for v, f in ((values[k0:], first[0]), (values[k0::-1], first[1]))
            ],
        )
        traces: list[tuple[PathTrace, PathTrace]] = list(zip(flat[0::2], flat[1::2], strict=True))
        # the samples between the nodes of every row's two directions: one batched Newton
        close_segments(
            pb,
            [tr for pair in traces for tr in pair],
            col,
            [[2 * r, 2 * r + 1] for r in range(len(traces))],
        )
        Zs, reacheds = [], []
        for (k0, _), (fwd, bwd) in zip(begun, traces, strict=True):
            Z = np.full((K, pb.n), np.nan)
            Z[k0:] = fwd.Z
            Z[: k0 + 1] = bwd.Z[::-1]
            Zs.append(Z)
            reacheds.append(~np.isnan(Z[:, 0]))
        pm_all, offsets = self._measure_rows(Zs, reacheds)
        pms = [
            pm if pm is not None else PointMeasures.gather([(pm_all, slice(o, o + int(np.sum(r))))])
            for pm, o, r in zip(
                pm_all if isinstance(pm_all, list) else [None] * len(Zs),
                offsets,
                reacheds,
                strict=True,
            )
        ]
        ratios = []
        ranks = []
        for pm, reached in zip(pms, reacheds, strict=True):
            rank = {t: np.full(K, -2, dtype=np.int16) for t in self.tests}
            ratio = {t: np.full(K, np.nan) for t in self.tests}
            for t in self.tests:
                rank[t][reached] = pm.rank[t]
                ratio[t][reached] = pm.ratio[t]
            ranks.append(rank)
            ratios.append(ratio)
        if isinstance(pm_all, list):  # measured row by row: refined row by row
            along = [
                self.locator.along(Z, reached, pm, ratio, col, i)
                for (i, _), Z, reached, pm, ratio in zip(
                    starts, Zs, reacheds, pms, ratios, strict=True
                )
            ]
        else:
            along = self.locator.along_rows(
                pm_all,
                [
                    RowSamples(Z, reached, o, ratio, col, i)
                    for (i, _), Z, reached, o, ratio in zip(
                        starts, Zs, reacheds, offsets, ratios, strict=True
                    )
                ],
            )
        out = []
        for r, (index, _) in enumerate(starts):
            fwd, bwd = traces[r]
            Z, reached, pm, rank, ratio = Zs[r], reacheds[r], pms[r], ranks[r], ratios[r]
            newton = int(np.sum(fwd.newton)) + int(np.sum(bwd.newton))
            located = [self.locator.fold(f, index, values) for f in [*fwd.folds, *bwd.folds]]
            located += along[r]
            stopped = self.locator.inside(Z, reached, rank, ratio, col, index, located)
            var = self._variable(col)
            for trace, end in ((fwd, values[-1]), (bwd, values[0])):
                if trace.stopped:
                    # where it stopped: the last sample reached towards that end
                    got = trace.Z[~np.isnan(trace.Z[:, 0])]
                    last = (
                        f"{var.name} = {var.shown(float(got[-1][col]))}"
                        if len(got)
                        else "its start"
                    )
                    stopped.append(
                        f"towards {var.name} = {var.shown(float(end))}: stopped after {last}: "
                        f"{trace.stopped}"
                    )
            out.append(
                RowResult(
                    index,
                    reached,
                    rank,
                    ratio,
                    merge_located(located, self.scales),
                    stopped,
                    newton,
                    Z,
                    pm,
                    outside(self.limited, Z[:, : self.model.n], reached),
                )
            )
        return out

    def _measure_rows(
        self, Zs: list[np.ndarray], reacheds: list[np.ndarray]
    ) -> tuple[PointMeasures | list[PointMeasures], list[int]]:
        """The measures of several rows' reached samples: one batch (in chunks:
        :func:`~.locate.measured`), with each row's offset in it, when the measures are per
        configuration; otherwise a list, row by row (each row its own batch, as alone)."""
        sizes = [int(np.sum(r)) for r in reacheds]
        offsets = [int(x) for x in np.cumsum([0, *sizes[:-1]])]
        if not (self.measures.pointwise and dispatch.enabled()):
            return [
                measured(self.measures, Z, r, self.model.n)
                for Z, r in zip(Zs, reacheds, strict=True)
            ], offsets
        Z = np.concatenate([Z[r] for Z, r in zip(Zs, reacheds, strict=True)])
        return measured(self.measures, Z, np.ones(len(Z), dtype=bool), self.model.n), offsets

    def row_chunks(self, values: list[np.ndarray]) -> list[range]:
        """The rows of a grid in the chunks that are followed, measured and refined
        together: as many rows as hold about _ROWS_SAMPLES samples and _ROWS_BYTES of
        their measures (at least one)."""
        rows, k = len(values[1]), len(values[0])
        # a sample's measures keep its matrices (the closure's rows by the coordinates,
        # the closure kernel, the tests' rows and singular vectors): about this many bytes
        n, loops = self.problem.n, 6 * len(self.mech.loops)
        size = 8 * (2 * loops * n + 2 * n * n + 24 * n)
        per = max(1, min(_ROWS_SAMPLES, _ROWS_BYTES // max(size, 1)) // max(k, 1))
        return [range(lo, min(lo + per, rows)) for lo in range(0, rows, per)]

    def chunk_rows(
        self, chunk: range, column: RowResult, values: list[np.ndarray]
    ) -> list[RowResult]:
        """The rows of one chunk (:meth:`row_chunks`), from the first column's
        configurations: the reached ones together (:meth:`rows_of`)."""
        assert column.Z is not None
        starts = [(j, column.Z[j]) for j in chunk if column.reached[j]]
        got = dict(
            zip(
                [j for j, _ in starts],
                self.rows_of(starts, self.cols[0], values[0]) if starts else [],
                strict=True,
            )
        )
        return [got[j] if j in got else self.unreached_row(j, len(values[0])) for j in chunk]

    def rows(
        self, values: list[np.ndarray], progress: Callable[[int], None] | None = None
    ) -> Iterator[RowResult]:
        """The rows of the sweep in order (one for a path), each with its measures and the
        points located along it (the crossings between rows are the caller's:
        :meth:`between_many`).  A grid's rows are computed in chunks
        (:meth:`row_chunks`)."""
        if len(self.cols) == 1:
            res = self.row(0, self.cols[0], values[0], self.z0)
            if progress:
                progress(len(values[0]))
            yield res
            return
        column = self.first_column(values)
        for chunk in self.row_chunks(values):
            for res in self.chunk_rows(chunk, column, values):
                if progress:  # before the row is yielded: its consumer may stop there
                    progress(len(values[0]))
                yield res

    def first_column(self, values: list[np.ndarray]) -> RowResult:
        """A grid's first column: a path in the second variable, at the first variable's
        sample nearest the start; its configurations start the rows (which are then
        independent of each other)."""
        cx, cy = self.cols
        _, zx = self.start_of(cx, values[0], self.z0)
        column = self.row(-1, cy, values[1], zx)
        bridge_column(self.problem, column, values, self.cols, self.z0, self.start_notes)
        return column

    def unreached_row(self, j: int, k: int) -> RowResult:
        """Row j of k samples when the first column does not reach it: nothing reached."""
        empty = np.zeros(k, dtype=bool)
        return RowResult(
            j,
            empty,
            {t: np.full(k, -2, dtype=np.int16) for t in self.tests},
            {t: np.full(k, np.nan) for t in self.tests},
            [],
            [f"row {j}: the first column does not reach it"],
        )
