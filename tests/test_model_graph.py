"""The graph model: canonical loops, loop count, spanning tree paths and legs."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import networkx as nx
from hypothesis import given, settings
from hypothesis import strategies as st

from mechsing.model import Joint, Leg, build_graph, canonical_loops, load, loads
from tests.strategies import body_graphs

DATA = Path(__file__).parent / "data"


def _walk_ok(loop, joints_by_name):
    n = len(loop.joints)
    assert len(loop.signs) == n == len(loop.bodies)
    assert len(set(loop.joints)) == n
    cur = loop.bodies[0]
    for i, (name, s) in enumerate(zip(loop.joints, loop.signs, strict=True)):
        assert cur == loop.bodies[i]
        a, b = joints_by_name[name].between
        if s == 1:
            assert cur == a
            cur = b
        else:
            assert s == -1 and cur == b
            cur = a
    assert cur == loop.bodies[0]
    assert len(set(loop.bodies)) == n  # a simple cycle


def _gf2_rank(vectors):
    rows = list(vectors)
    rank = 0
    while rows:
        pivot = rows.pop()
        if pivot == 0:
            continue
        rank += 1
        low = pivot & -pivot
        rows = [r ^ pivot if r & low else r for r in rows]
    return rank


@settings(max_examples=150, deadline=None)
@given(body_graphs())
def test_loop_count_and_basis(mech):
    bodies, joints = mech
    g = build_graph(bodies, bodies[0], joints)
    assert g.num_loops == len(joints) - len(bodies) + 1
    pos = {j.name: k for k, j in enumerate(joints)}
    by_name = {j.name: j for j in joints}
    for lp in g.loops:
        _walk_ok(lp, by_name)
        assert lp.signs[0] == 1
        assert pos[lp.joints[0]] == min(pos[n] for n in lp.joints)
    # independent over GF(2)
    vecs = [sum(1 << pos[n] for n in lp.joints) for lp in g.loops]
    assert _gf2_rank(vecs) == g.num_loops
    # short loops first
    lengths = [len(lp) for lp in g.loops]
    assert lengths == sorted(lengths)
    # minimum total length (any minimum cycle basis has the same total)
    H = nx.Graph()
    for k, j in enumerate(reversed(joints)):
        H.add_edge(("j", k), j.between[0])
        H.add_edge(("j", k), j.between[1])
    other = nx.minimum_cycle_basis(H) if joints else []
    assert sum(lengths) == sum(len(c) // 2 for c in other)
    # U joints count once: one edge per joint in the loops, two in the multigraph
    n_u = sum(1 for j in joints if j.type == "U")
    assert g.multigraph.number_of_edges() == len(joints) + n_u
    assert g.multigraph.number_of_nodes() == len(bodies) + n_u


@settings(max_examples=100, deadline=None)
@given(body_graphs(), st.randoms(use_true_random=False))
def test_same_loops_whatever_the_names_and_memory_order(mech, rnd):
    """Renaming bodies and joints (which changes every hash and sort order) and
    rebuilding from fresh objects gives the same loops, joint for joint."""
    bodies, joints = mech
    ref = canonical_loops(bodies, joints)
    names = {b: f"x{rnd.random():.12f}{b}"[::-1] for b in bodies}
    jnames = {j.name: f"{rnd.randint(0, 10**9)}_{j.name}"[::-1] for j in joints}
    bodies2 = [names[b] for b in bodies]
    joints2 = [
        Joint(jnames[j.name], j.type, (names[j.between[0]], names[j.between[1]]), {}, None, j.dof)
        for j in joints
    ]
    got = canonical_loops(tuple(bodies2), tuple(joints2))
    inv = {v: k for k, v in jnames.items()}
    invb = {v: k for k, v in names.items()}
    assert [tuple(inv[n] for n in lp.joints) for lp in got] == [lp.joints for lp in ref]
    assert [lp.signs for lp in got] == [lp.signs for lp in ref]
    assert [tuple(invb[b] for b in lp.bodies) for lp in got] == [lp.bodies for lp in ref]


def test_same_loops_under_another_hash_seed():
    code = (
        "from mechsing.model import load;"
        f"m = load({str(DATA / 'ladder.yaml')!r});"
        "print([(lp.joints, lp.signs) for lp in m.loops])"
    )
    outs = set()
    for seed in ("1", "12345"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        res = subprocess.run(
            [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
        )
        outs.add(res.stdout)
    assert len(outs) == 1


@settings(max_examples=100, deadline=None)
@given(body_graphs())
def test_tree_paths_reach_every_body(mech):
    bodies, joints = mech
    g = build_graph(bodies, bodies[0], joints)
    by_name = {j.name: j for j in joints}
    assert set(g.tree_paths) == set(bodies) | {j.hidden_body for j in joints if j.hidden_body}
    assert len(g.tree_joints) == len(bodies) - 1
    assert len(g.chord_joints) == g.num_loops
    for body, path in g.tree_paths.items():
        cur = bodies[0]
        for step in path:
            a, b = by_name[step.joint].between
            if step.part is None:
                assert cur == (a if step.sign == 1 else b)
                cur = b if step.sign == 1 else a
            else:
                assert (step.part, step.sign) in ((0, 1), (1, -1))
                assert cur == (a if step.part == 0 else b)
                cur = by_name[step.joint].hidden_body
        assert cur == body


def test_fourbar_loop_orientation():
    m = load(DATA / "fourbar_deg.yaml")
    (lp,) = m.loops
    assert lp.joints == ("A", "B", "C", "D")
    assert lp.signs == (1, 1, 1, 1)
    assert lp.bodies == ("ground", "crank", "coupler", "rocker")


def test_loop_starts_at_first_joint_in_file_and_follows_its_between():
    m = loads("""
bodies: [ground, a, b]
joints:
  - {name: J2, type: R, between: [b, a], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: J1, type: R, between: [ground, a], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J3, type: R, between: [b, ground], axis: [0, 0, 1], point: [2, 0, 0]}
""")
    (lp,) = m.loops
    assert lp.joints == ("J2", "J1", "J3")
    assert lp.signs == (1, -1, -1)
    assert lp.bodies == ("b", "a", "ground")


def test_ladder_loops_are_the_short_ones():
    m = load(DATA / "ladder.yaml")
    assert m.graph.num_loops == 3
    assert [set(lp.joints) for lp in m.loops] == [
        {"D2", "D3"},
        {"A1", "A2", "B1", "B2"},
        {"C1", "C2", "D1", "D2"},
    ]


def test_u_joint_counts_once_in_loops():
    m = loads("""
bodies: [ground, a, b]
joints:
  - {name: U1, type: U, between: [ground, a], axes: [[0, 0, 1], [1, 0, 0]], point: [0, 0, 0]}
  - {name: S1, type: S, between: [a, b], point: [1, 0, 0]}
  - {name: R1, type: R, between: [b, ground], axis: [0, 0, 1], point: [2, 0, 0]}
""")
    (lp,) = m.loops
    assert lp.joints == ("U1", "S1", "R1")
    assert m.graph.tree_paths["U1.cross"][-1].joint == "U1"


# --- legs ------------------------------------------------------------------

PLATFORM = """
bodies: [ground, l1a, l1b, l2a, l3a, platform, tail]
joints:
  - {name: A1, type: R, between: [ground, l1a], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B1, type: P, between: [l1a, l1b], axis: [1, 0, 0]}
  - {name: C1, type: S, between: [l1b, platform], point: [0, 0, 1]}
  - {name: A2, type: S, between: [l2a, ground], point: [1, 0, 0]}
  - {name: C2, type: S, between: [platform, l2a], point: [1, 0, 1]}
  - {name: A3, type: U, between: [ground, l3a], axes: [[0, 0, 1], [1, 0, 0]], point: [2, 0, 0]}
  - {name: C3, type: S, between: [l3a, platform], point: [2, 0, 1]}
  - {name: D0, type: C, between: [platform, ground], axis: [0, 0, 1], point: [5, 5, 0]}
  - {name: T1, type: R, between: [platform, tail], axis: [0, 0, 1], point: [9, 9, 9]}
output: {body: platform}
"""


def test_legs_numbered_by_first_joint_in_file_order():
    m = loads(PLATFORM)
    assert m.legs == (
        Leg(("A1", "B1", "C1"), ("l1a", "l1b")),
        Leg(("A2", "C2"), ("l2a",)),
        Leg(("A3", "C3"), ("l3a",)),
        Leg(("D0",), ()),
    )


def test_legs_relative_to_another_body():
    m = loads(
        PLATFORM.replace("output: {body: platform}", "output: {body: tail, relative_to: l2a}")
    )
    # with l2a and tail removed, the rest (ground, platform, legs 1 and 3) is one component
    # touching l2a (A2, C2) and tail (T1)
    (leg,) = m.legs
    assert set(leg.joints) == {j.name for j in m.joints}


def test_dangling_component_is_not_a_leg():
    m = loads("""
bodies: [ground, crank, coupler, rocker, sensor]
joints:
  - {name: A, type: R, between: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: S, type: R, between: [ground, sensor],  axis: [0, 0, 1], point: [9, 0, 0]}
  - {name: B, type: R, between: [crank, coupler],  axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, 2, 0]}
  - {name: D, type: R, between: [rocker, ground],  axis: [0, 0, 1], point: [4, 0, 0]}
output: {body: rocker}
""")
    assert m.legs == (Leg(("A", "B", "C"), ("crank", "coupler")), Leg(("D",), ()))
