"""A grid stays on the assembly mode it starts on, where the passive joints swing fast.

The five-bar below has unequal distal links (|B1P| = sqrt(8), |B2P| = sqrt(13)).  Over the
grid A1 in [-1.5, 1.5], A2 in [0.2, 0.4] the proximal pivots B1 and B2 come to 0.91 of each
other, so the distal links swing by over 2 rad while A1 moves by 0.25: a node predicted
a whole step ahead overshot to the other assembly mode (P mirrored across B1B2), and
Newton closed it there.  A row with A2 held can change mode only through a Type II
singularity (B1, P, B2 in line), which is a fold of that row: the row ends there.  So
every point the sweep locates off a fold is on the reference's side of B1B2.  The side is
worked out here from the located point's joint angles by plane rotations, and which samples
close at all from |B1B2| (within [|l1 - l2|, l1 + l2]).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

import mechsing

UNEQUAL_DISTAL_FIVE_BAR = """\
mechanism: five-bar with unequal distal links
bodies: [ground, prox1, dist1, prox2, dist2]
joints:
  - {name: A1, type: R, between: [ground, prox1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B1, type: R, between: [prox1, dist1],  axis: [0, 0, 1], point: [0, 3, 0]}
  - {name: P,  type: R, between: [dist1, dist2],  axis: [0, 0, 1], point: [2, 5, 0]}
  - {name: B2, type: R, between: [prox2, dist2],  axis: [0, 0, 1], point: [4, 2, 0]}
  - {name: A2, type: R, between: [ground, prox2], axis: [0, 0, 1], point: [4, 0, 0]}
inputs: [A1, A2]
output: {body: dist1, point: [2, 5, 0]}
configurations:
  reference: {}
"""
A1, B1, P, B2, A2 = (np.array(p, dtype=float) for p in ([0, 0], [0, 3], [2, 5], [4, 2], [4, 0]))


def _turn(t: float, v: np.ndarray) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _side(q: dict[str, float]) -> float:
    """cross(B2 - B1, P - B1) at the joint angles q: positive on the reference's side."""
    b1 = A1 + _turn(q["A1"], B1 - A1)
    p = b1 + _turn(q["A1"] + q["B1"], P - B1)  # dist1 turns by A1 + B1
    b2 = A2 + _turn(q["A2"], B2 - A2)
    u, w = b2 - b1, p - b1
    return float(u[0] * w[1] - u[1] * w[0])


def _pivots_apart(a1: float, a2: float) -> float:
    return float(np.linalg.norm(A1 + _turn(a1, B1 - A1) - (A2 + _turn(a2, B2 - A2))))


def _closes(a1: float, a2: float) -> bool:
    l1, l2 = math.dist(B1, P), math.dist(B2, P)
    return abs(l1 - l2) <= _pivots_apart(a1, a2) <= l1 + l2


def test_a_grid_where_the_distal_links_swing_fast_stays_on_its_mode(tmp_path: Path) -> None:
    path = tmp_path / "five_bar.yaml"
    path.write_text(UNEQUAL_DISTAL_FIVE_BAR)
    assert _side({"A1": 0.0, "B1": 0.0, "A2": 0.0}) > 0  # the reference: 2*3 - (-2)*2 = 10
    r = mechsing.sweep(path, ["A1=-1.5:1.5:0.05", "A2=0.2:0.4:0.05"])
    a1s, a2s = np.linspace(-1.5, 1.5, 61), np.linspace(0.2, 0.4, 5)
    for j, a2 in enumerate(a2s):
        reached = a1s[r.reached[j]]
        assert all(_closes(a1, a2) for a1 in reached)
        for a1 in a1s[~r.reached[j]]:
            if _closes(a1, a2):  # a sample that closes is left only past a gap of its row
                near = reached[np.argmin(abs(reached - a1))]
                assert not all(_closes(t, a2) for t in np.linspace(near, a1, 200)), (a1, a2)
    crossings = [p for p in r.located if p.kind != "fold"]
    assert len(crossings) >= 10  # the serial singularities of the rows (a leg in line)
    for p in crossings:
        q = {name: v[0] for name, v in p.joints}
        # 4.2 and more: well away from the in-line distal links (side 0)
        assert _side(q) > 1.0, (p.values, _side(q))
