"""A grid's loci are polylines that follow the segments joining located points: where more
than two segments meet (two loci crossing or touching), each branch is its own polyline, so
no polyline draws a straight line between two branches (a line that is no locus)."""

from __future__ import annotations

import networkx as nx

from mechsing.sweeps.loci import _chains


def _check(g: nx.Graph) -> list[list[int]]:
    chains = _chains(g)
    drawn = []
    for order, _closed in chains:
        steps = list(zip(order, order[1:], strict=False))
        assert all(g.has_edge(a, b) for a, b in steps), order  # only along segments
        drawn += [frozenset(s) for s in steps]
    # every segment drawn once
    assert sorted(map(sorted, drawn)) == sorted(map(sorted, (frozenset(e) for e in g.edges)))
    return [order for order, _ in chains]


def test_a_plain_curve_is_one_polyline() -> None:
    g = nx.path_graph(6)
    assert _check(g) == [[0, 1, 2, 3, 4, 5]]


def test_branches_meeting_at_a_point_are_separate_polylines() -> None:
    # a T: 0-1-2-3 and 2-4-5 (a depth-first walk would jump from 3 back to 4)
    g = nx.Graph([(0, 1), (1, 2), (2, 3), (2, 4), (4, 5)])
    chains = _check(g)
    assert len(chains) == 3


def test_two_curves_crossing() -> None:
    g = nx.Graph([(0, 1), (1, 2), (2, 3), (4, 5), (5, 2), (2, 6), (6, 7)])
    assert len(_check(g)) == 4
