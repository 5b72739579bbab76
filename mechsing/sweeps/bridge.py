"""Bridging a grid's rows: the singularities between neighbouring rows, and the rows the
first column misses.

Owns :func:`between_rows` (the sign changes of each test along the columns of a grid,
between neighbouring rows at the same samples, refined along the column: with the rows'
points they make the loci) and :func:`bridge_column` (the rows the first column does not
reach, started from a neighbouring row that is reached).
"""

from __future__ import annotations

import numpy as np

from mechsing.errors import ClosureError
from mechsing.kinematics.paths.follow import follow
from mechsing.kinematics.paths.problem import Problem
from mechsing.numeric import Precision
from mechsing.sweeps.falling import column_samples
from mechsing.sweeps.locate import Locator
from mechsing.sweeps.measures import PointMeasures
from mechsing.sweeps.records import ColumnBrackets, Located, Refined, RowResult

__all__ = ["between_rows", "bridge_column"]

#: most samples of a reached row tried to start a neighbouring row the first column misses
_BRIDGE_TRIES = 6
_TAU_HI = Precision("float").tolerances.tau_hi
_TAU_LO = Precision("float").tolerances.tau_lo


def between_rows(
    loc: Locator, pairs: list[tuple[RowResult, RowResult]], col: int
) -> list[list[Located]]:
    """The sign changes of each test between neighbouring rows of a grid, for several
    pairs of rows (ra, rb) at the same samples of the row variable: refined along the
    column, every pair's together (each bracket on its own, as for one pair), by the
    locator ``loc`` of the sweep."""
    found: list[dict[str, ColumnBrackets]] = []
    for ra, rb in pairs:
        assert ra.Z is not None and rb.Z is not None and ra.measures is not None
        mine: dict[str, ColumnBrackets] = {}
        found.append(mine)
        both = np.flatnonzero(ra.reached & rb.reached)
        if not len(both):
            continue
        pos = {int(k): i for i, k in enumerate(np.flatnonzero(ra.reached))}
        ia = np.array([pos[int(k)] for k in both])
        if rb.measures is not None and rb.measures.matrices is not None:
            # row b's matrices at those samples were kept by its own measures
            pos_b = {int(k): i for i, k in enumerate(np.flatnonzero(rb.reached))}
            ib = np.array([pos_b[int(k)] for k in both])
            dets = loc.measures.compressed_measured(ra.measures, ia, rb.measures, ib)
        else:
            dets = loc.measures.compressed(ra.measures, ia, rb.Z[both][:, : loc.n])
        for t in dets:
            # between two samples both singular for the test its sign is noise (a row's
            # rule, :meth:`Locator._sign_changes`): one end must be regular; an end
            # decided singular is itself the point (:func:`~.falling.column_samples`)
            ends = np.stack([ra.ratio[t][both], rb.ratio[t][both]])
            regular = (ends.max(axis=0) > _TAU_HI) & (ends.min(axis=0) > _TAU_LO)
            hits = np.flatnonzero((dets[t] < 0) & regular)
            if len(hits):
                K = both[hits]
                mine[t] = ColumnBrackets(K, ra.Z[K], rb.Z[K], ia[hits])
    # each test's sign changes, every pair's together
    refined: dict[str, list[Refined | None]] = {}
    for t in loc.tests:
        which = [p for p, mine in enumerate(found) if t in mine]
        if not which:
            continue
        pm = PointMeasures.gather(
            [(pairs[p][0].measures, found[p][t].ia) for p in which]  # type: ignore[misc]
        )
        ZA = np.concatenate([found[p][t].ZA for p in which])
        ZB = np.concatenate([found[p][t].ZB for p in which])
        refined[t] = loc.refiner.crossings(t, ZA, ZB, col, pm, np.arange(len(ZA)))
    out: list[list[Located]] = []
    at = dict.fromkeys(refined, 0)
    for (ra, _), mine in zip(pairs, found, strict=True):
        got: list[Located] = []
        for t, brackets in mine.items():
            K = brackets.K
            for k, f in zip(K, refined[t][at[t] : at[t] + len(K)], strict=True):
                if f is not None:
                    z, r = f
                    got.append(loc.at(z, "crossing", (t,), r, "column", (ra.index, int(k))))
            at[t] += len(K)
        column_samples(loc, ra, rb, got)
        out.append(got)
    return out


def bridge_column(
    pb: Problem,
    column: RowResult,
    values: list[np.ndarray],
    cols: list[int],
    z0: np.ndarray,
    notes: list[str],
) -> None:
    """Rows the first column does not reach (the reachable region does not cover
    the start's value of the first variable there) are started from a neighbouring
    row that is reached: that row is followed, and from its reached samples (the
    nearest the first column first) the column is continued to the row's value; the
    row's start (at that sample) goes into ``column``.  Repeated outwards until no
    row is added, so a reachable region that the first column crosses only in part is
    covered on the start's assembly mode (``z0``: the start, ``cols``: the swept columns;
    the rows added are said in ``notes``)."""
    assert column.Z is not None
    reached = column.reached
    if reached.all() or not reached.any():
        return
    cx, cy = cols
    xs, ys = values
    k0 = int(np.argmin(np.abs(xs - z0[cx])))
    paths: dict[int, np.ndarray] = {}

    def path_of(n: int) -> np.ndarray:
        if n not in paths:
            assert column.Z is not None
            z = column.Z[n]
            kn = int(np.argmin(np.abs(xs - z[cx])))
            Zn = np.full((len(xs), pb.n), np.nan)
            Zn[kn:] = follow(pb, z, cx, xs[kn:]).Z
            Zn[: kn + 1] = follow(pb, z, cx, xs[kn::-1]).Z[::-1]
            paths[n] = Zn
        return paths[n]

    bridged = 0
    added = True
    while added:
        added = False
        for j in range(len(ys)):
            if reached[j]:
                continue
            for n in (j - 1, j + 1):
                if not (0 <= n < len(ys) and reached[n]):
                    continue
                Zn = path_of(n)
                ks = np.flatnonzero(~np.isnan(Zn[:, 0]))
                ks = ks[np.argsort(np.abs(ks - k0), kind="stable")]
                picks = ks[:: max(1, len(ks) // _BRIDGE_TRIES)][:_BRIDGE_TRIES]
                for k in picks:
                    try:
                        zj = pb.reach(Zn[k], cy, float(ys[j]))
                    except ClosureError:
                        continue
                    column.Z[j], reached[j] = zj, True
                    added, bridged = True, bridged + 1
                    break
                if reached[j]:
                    break
    if bridged:
        notes.append(
            f"{bridged} rows the first column does not reach were started from a neighbouring row"
        )
