"""The singularity loci of a grid: polylines through the located points (marching squares).

Owns :func:`loci_of`.  Every located point of a grid lies on an edge of the sampling
grid: a row edge (between two samples of one row: a sign change, a minimum or a fold
along the row) or a column edge (between two rows at one sample).  For each test, the
points on the four edges of a grid cell are joined inside the cell (two points: one
segment; four: the pairing with the shorter segments, as marching squares resolves its
saddle cells), and the segments that share a point are chained into polylines, closed
when they come back to their first point.  A locus is labelled with its test and with
the classes the full analysis found at its classified points.
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING, Any

import numpy as np

from mechsing.sweeps.results import LocatedSingularity, Locus
from mechsing.sweeps.settings import SWEEP_MERGE_RTOL

if TYPE_CHECKING:  # networkx is imported where a grid's loci are drawn (0.17 s at start-up)
    import networkx as nx

__all__ = ["loci_of"]


def _edges(p: LocatedSingularity, xs: np.ndarray, ys: np.ndarray) -> list[tuple[str, int, int]]:
    """The grid edges a located point lies on: its own (a row edge between two samples of
    its row, or a column edge between two rows), and, when it lies on a sample of the
    grid (a locus through the grid's vertices, as a 2R arm's elbow line on a sampled
    value; within SWEEP_MERGE_RTOL of the range), the edges on both sides of that sample,
    so that the points of a locus through vertices share cells whichever side their
    rounding put them on."""
    x, y = p.values
    along, other, v, w = (xs, ys, x, y) if p.between == "row" else (ys, xs, y, x)
    k = int(np.argmin(np.abs(other - w)))
    i = int(np.clip(np.searchsorted(along, v) - 1, 0, max(len(along) - 2, 0)))
    near = int(np.argmin(np.abs(along - v)))
    ends = {i}
    if abs(along[near] - v) <= SWEEP_MERGE_RTOL * max(float(np.ptp(along)), 1e-300):
        ends = {e for e in (near - 1, near) if 0 <= e <= len(along) - 2} or {i}
    kind = "h" if p.between == "row" else "v"
    return [(kind, k, e) if kind == "h" else (kind, e, k) for e in sorted(ends)]


def loci_of(run: Any, located: list[LocatedSingularity]) -> list[Locus]:
    """The loci of a grid sweep (``run``: its SweepRun) through its located points."""
    import networkx as nx

    xs = np.sort(run.vars[0].values)
    ys = np.sort(run.vars[1].values)
    out: list[Locus] = []
    for test in run.tests:
        pts = [p for p in located if test in p.tests]
        if len(pts) < 2:
            continue
        on: dict[tuple[str, int, int], list[int]] = {}
        for k, p in enumerate(pts):
            for e in _edges(p, xs, ys):
                on.setdefault(e, []).append(k)
        cells: dict[tuple[int, int], list[int]] = {}
        for (kind, j, i), ks in on.items():
            touching = [(j, i), (j - 1, i)] if kind == "h" else [(j, i), (j, i - 1)]
            for c in touching:
                cells.setdefault(c, []).extend(ks)
        g = nx.Graph()
        g.add_nodes_from(range(len(pts)))
        xy = np.array([p.values for p in pts], dtype=float)
        span = np.array([max(np.ptp(xs), 1e-300), max(np.ptp(ys), 1e-300)])
        for ks in cells.values():
            ks = sorted(set(ks))
            for a, b in _pairs(ks, xy / span):
                g.add_edge(a, b)
        for a, b in _fold_links(run, pts):
            if not g.has_edge(a, b) and g.degree(a) < 2 and g.degree(b) < 2:
                g.add_edge(a, b)
        for comp in nx.connected_components(g):
            if len(comp) < 2:
                continue
            for order, closed in _chains(g.subgraph(comp)):
                classes: dict[str, None] = {}
                for k in order:
                    for c in pts[k].classes or ():
                        classes[c] = None
                out.append(Locus(test, tuple(classes), xy[order], closed))
    return out


def _fold_links(run: Any, pts: list[LocatedSingularity]) -> list[tuple[int, int]]:
    """Links between the folds of neighbouring rows that bound the reached region on the
    same side (a row stopped going right, or left, at each): a fold curve crosses no
    column edge whose two ends are reached, so marching squares cannot join its points
    when the curve runs closer to the rows' direction than to the columns'.  Each fold
    is linked to the nearest fold on the same side of the next row when each is the
    other's nearest."""
    xv, yv = np.asarray(run.vars[0].values), np.asarray(run.vars[1].values)
    reached = np.asarray(run.reached, dtype=bool).reshape(len(yv), len(xv))
    ascending = xv[-1] >= xv[0]
    side: dict[int, tuple[int, int]] = {}  # point -> (row, +1 right boundary / -1 left)
    for k, p in enumerate(pts):
        if p.kind != "fold" or p.between != "row":
            continue
        j = int(np.argmin(np.abs(yv - p.values[1])))
        i = int(np.searchsorted(xv if ascending else xv[::-1], p.values[0]))
        i = i if ascending else len(xv) - i  # the first sample past the fold in x
        left = reached[j, i - 1] if 0 < i <= len(xv) else False
        right = reached[j, i] if 0 <= i < len(xv) else False
        if left != right:
            side[k] = (j, 1 if (left ^ (not ascending)) else -1)
    links = []
    for a, (j, s) in side.items():
        near = [b for b, (jb, sb) in side.items() if jb == j + 1 and sb == s]
        if not near:
            continue
        b = min(near, key=lambda m: abs(pts[m].values[0] - pts[a].values[0]))
        back = [m for m, (jm, sm) in side.items() if jm == j and sm == s]
        if min(back, key=lambda m: abs(pts[m].values[0] - pts[b].values[0])) == a:
            links.append((a, b))
    return links


def _pairs(ks: list[int], xy: np.ndarray) -> list[tuple[int, int]]:
    """The segments of one cell through its edge points."""
    if len(ks) < 2:
        return []
    if len(ks) == 2:
        return [(ks[0], ks[1])]
    # four (or more) points: the perfect matching of shortest total length
    best, pairs = np.inf, []
    for perm in itertools.permutations(ks):
        cand = [(perm[i], perm[i + 1]) for i in range(0, len(perm) - 1, 2)]
        cost = sum(float(np.linalg.norm(xy[a] - xy[b])) for a, b in cand)
        if cost < best:
            best, pairs = cost, cand
        if len(ks) > 6:
            break
    return pairs


def _chains(g: nx.Graph) -> list[tuple[list[int], bool]]:
    """A connected piece as polylines that follow its segments only: the piece itself
    when no point joins more than two segments (:func:`_walk`); else one polyline from
    each such junction (or end) to the next, so no polyline jumps between two branches
    (a straight line that is no locus)."""
    if max(d for _, d in g.degree) <= 2:
        return [_walk(g)]
    stops = {v for v in g.nodes if g.degree(v) != 2}
    used: set[frozenset[int]] = set()
    out = []
    for a in sorted(stops):
        for b in sorted(g.neighbors(a)):
            if frozenset((a, b)) in used:
                continue
            chain = [a, b]
            used.add(frozenset((a, b)))
            while chain[-1] not in stops:
                nxt = [v for v in g.neighbors(chain[-1]) if frozenset((chain[-1], v)) not in used]
                if not nxt:
                    break
                used.add(frozenset((chain[-1], nxt[0])))
                chain.append(nxt[0])
            out.append((chain, False))
    return out


def _walk(g: nx.Graph) -> tuple[list[int], bool]:
    """The points of a connected piece in order along it (from an end when it has one)."""
    import networkx as nx

    ends = [v for v in g.nodes if g.degree(v) == 1]
    start = ends[0] if ends else min(g.nodes)
    order = list(nx.dfs_preorder_nodes(g, start))
    closed = not ends and len(order) > 2
    if closed:
        order.append(order[0])
    return order, closed
