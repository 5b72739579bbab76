"""The graph model: bodies, joints, loops, spanning tree and legs.

* :attr:`MechanismGraph.multigraph` -- a networkx ``MultiGraph`` whose nodes are
  the bodies (plus the hidden ``<joint>.cross`` body of each U joint, node
  attribute ``hidden=True``) and whose edges are the joints.  An edge carries
  ``joint`` (the :class:`~mechsing.model.mechanism.Joint`), ``part`` (None for a
  whole joint; 0 or 1 for the two revolutes of a U joint), ``tail`` and
  ``head`` (the edge is oriented tail -> head like the joint's ``between``).
  Edge keys are the joint name, or ``(name, 0)`` / ``(name, 1)`` for U parts.
* :attr:`MechanismGraph.loops` -- the canonical cycle basis:
  ``networkx.minimum_cycle_basis`` of the simple graph whose nodes
  are the bodies and the joints (each joint a node between its two bodies, so
  parallel joints are fine and a U joint counts once), built with bodies and
  joints inserted in file order; loops are sorted short first, then by their
  joints' file positions; each starts at its joint that comes first in the
  file and is oriented by that joint's ``between``.
* :attr:`MechanismGraph.tree_paths` -- a breadth-first spanning tree from
  ground (neighbours in joint file order): for each body, the steps from
  ground.  The pose of a body is the product, in order, of
  ``exp(value)`` (sign +1: crossing the joint from ``between[0]`` to
  ``between[1]``) or its inverse (sign -1).
* :meth:`MechanismGraph.legs` -- the legs between a base body and the output body.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import networkx as nx

__all__ = [
    "Leg",
    "Loop",
    "MechanismGraph",
    "PathStep",
    "build_graph",
    "canonical_loops",
    "connected_to",
]


@dataclass(frozen=True)
class Loop:
    """A loop of the canonical basis.

    ``joints[i]`` is crossed from ``bodies[i]`` to ``bodies[i+1]`` (the last one
    back to ``bodies[0]``); ``signs[i]`` is +1 when that crossing is the
    joint's ``between`` order (a -> b), -1 otherwise.  ``joints[0]`` is the
    loop's joint that comes first in the file, and ``signs[0]`` is +1.
    The closure condition of the loop is ``prod_i exp(q_i)^signs[i] = identity``.
    """

    joints: tuple[str, ...]
    signs: tuple[int, ...]
    bodies: tuple[str, ...]

    def __len__(self) -> int:
        return len(self.joints)


@dataclass(frozen=True)
class Leg:
    """A leg between the base (ground or ``relative_to``) and the output body.

    ``joints`` in file order; ``bodies`` are the leg's intermediate bodies in
    file order (empty for a joint that connects base and output directly).
    """

    joints: tuple[str, ...]
    bodies: tuple[str, ...] = ()


@dataclass(frozen=True)
class PathStep:
    """One factor of a tree path: ``exp(value of joint)`` raised to ``sign``.

    ``part`` is None for the whole joint; for a U joint, 0 means only the first
    factor ``exp(q1 R(a1, c))`` and 1 only the second ``exp(q2 R(a2, c))``
    (used to reach the hidden cross body).
    """

    joint: str
    sign: int
    part: int | None = None


@dataclass(frozen=True, eq=False)
class MechanismGraph:
    """Graph structure of a mechanism (see the module docstring; compared by identity)."""

    bodies: tuple[str, ...]
    ground: str
    joints: tuple[Any, ...]
    multigraph: nx.MultiGraph = field(repr=False, compare=False)
    loops: tuple[Loop, ...]
    tree_paths: Mapping[str, tuple[PathStep, ...]] = field(repr=False)
    tree_joints: tuple[str, ...]
    chord_joints: tuple[str, ...]

    @property
    def num_loops(self) -> int:
        """Number of independent loops, E - V + 1 (U joints counted once)."""
        return len(self.loops)

    def joint(self, name: str) -> Any:
        for j in self.joints:
            if j.name == name:
                return j
        raise KeyError(name)

    def legs(self, body: str, base: str) -> tuple[Leg, ...]:
        """The legs between ``base`` and ``body``.

        With ``base`` and ``body`` removed, each connected component that has a
        joint to both is a leg (its inner joints and the joints that attach
        it), and so is each joint that connects ``base`` and ``body`` directly.
        Legs are numbered by their first joint in file order.
        """
        order = {j.name: i for i, j in enumerate(self.joints)}
        rest = [b for b in self.bodies if b not in (body, base)]
        adj: dict[str, list[Any]] = {b: [] for b in self.bodies}
        for j in self.joints:
            a, b = j.between
            adj[a].append(j)
            adj[b].append(j)
        seen: set[str] = set()
        legs: list[Leg] = []
        for j in self.joints:
            if set(j.between) == {body, base}:
                legs.append(Leg((j.name,), ()))
        for start in rest:
            if start in seen:
                continue
            comp = []
            queue = deque([start])
            seen.add(start)
            while queue:
                x = queue.popleft()
                comp.append(x)
                for j in adj[x]:
                    y = j.other(x)
                    if y in (body, base) or y in seen:
                        continue
                    seen.add(y)
                    queue.append(y)
            cset = set(comp)
            joints = {j.name for x in comp for j in adj[x]}
            ends = {j.other(x) for x in comp for j in adj[x]} - cset
            if body in ends and base in ends:
                bodies = tuple(b for b in self.bodies if b in cset)
                legs.append(Leg(tuple(sorted(joints, key=order.__getitem__)), bodies))
        legs.sort(key=lambda leg: order[leg.joints[0]])
        return tuple(legs)


def canonical_loops(bodies: Sequence[str], joints: Sequence[Any]) -> tuple[Loop, ...]:
    """The canonical cycle basis (module docstring) for bodies and joints in file order.

    ``joints`` need ``name`` and ``between`` attributes.  The simple graph has
    integer nodes (bodies 0..nb-1, then joints nb..) inserted in file order,
    so nothing depends on string hashing or on any other memory order.
    """
    index = {b: i for i, b in enumerate(bodies)}
    nb = len(bodies)
    H = nx.Graph()
    H.add_nodes_from(range(nb))
    for k, j in enumerate(joints):
        a, b = j.between
        H.add_node(nb + k)
        H.add_edge(nb + k, index[a])
        H.add_edge(nb + k, index[b])
    loops = []
    for cycle in nx.minimum_cycle_basis(H):
        ks = sorted(n - nb for n in cycle if n >= nb)
        loops.append(_orient(ks, joints))
    pos = {j.name: k for k, j in enumerate(joints)}
    loops.sort(key=lambda lp: (len(lp.joints), sorted(pos[n] for n in lp.joints)))
    return tuple(loops)


def _orient(ks: list[int], joints: Sequence[Any]) -> Loop:
    """Walk a cycle given as joint indices from its first joint, a -> b."""
    first = joints[ks[0]]
    start, cur = first.between
    names, signs, bodies = [first.name], [1], [start]
    remaining = set(ks[1:])
    while remaining:
        nxt = None
        for k in sorted(remaining):
            if cur in joints[k].between:
                nxt = k
                break
        if nxt is None:  # pragma: no cover - minimum_cycle_basis returns cycles
            raise RuntimeError("cycle basis returned a set of joints that is not a cycle")
        remaining.discard(nxt)
        j = joints[nxt]
        bodies.append(cur)
        sign = 1 if j.between[0] == cur else -1
        names.append(j.name)
        signs.append(sign)
        cur = j.between[1] if sign == 1 else j.between[0]
    return Loop(tuple(names), tuple(signs), tuple(bodies))


def connected_to(ground: str, bodies: Sequence[str], joints: Sequence[Any]) -> set[str]:
    """Bodies reachable from ``ground`` through joints."""
    adj: dict[str, list[str]] = {b: [] for b in bodies}
    for j in joints:
        a, b = j.between
        adj[a].append(b)
        adj[b].append(a)
    seen = {ground}
    queue = deque([ground])
    while queue:
        x = queue.popleft()
        for y in adj[x]:
            if y not in seen:
                seen.add(y)
                queue.append(y)
    return seen


def build_graph(bodies: Sequence[str], ground: str, joints: Sequence[Any]) -> MechanismGraph:
    """The graph model of bodies (file order), a ground and joints (file order).

    Every body must be connected to ground (the loader checks it first).
    """
    G = nx.MultiGraph()
    for b in bodies:
        G.add_node(b, hidden=False)
    for j in joints:
        a, b = j.between
        if getattr(j, "is_composite", False):
            c = j.hidden_body
            G.add_node(c, hidden=True, joint=j.name)
            G.add_edge(a, c, key=(j.name, 0), joint=j, part=0, tail=a, head=c)
            G.add_edge(c, b, key=(j.name, 1), joint=j, part=1, tail=c, head=b)
        else:
            G.add_edge(a, b, key=j.name, joint=j, part=None, tail=a, head=b)

    # breadth-first spanning tree from ground, neighbours in joint file order
    inc: dict[str, list[Any]] = {b: [] for b in bodies}
    for j in joints:
        inc[j.between[0]].append(j)
        inc[j.between[1]].append(j)
    paths: dict[str, tuple[PathStep, ...]] = {ground: ()}
    tree: list[str] = []
    queue = deque([ground])
    while queue:
        x = queue.popleft()
        for j in inc[x]:
            y = j.other(x)
            if y in paths:
                continue
            sign = 1 if j.between[0] == x else -1
            paths[y] = paths[x] + (PathStep(j.name, sign),)
            tree.append(j.name)
            queue.append(y)
    tree_set = set(tree)
    order = {j.name: i for i, j in enumerate(joints)}
    tree_sorted = tuple(sorted(tree, key=order.__getitem__))
    chords = tuple(j.name for j in joints if j.name not in tree_set)
    for j in joints:
        if getattr(j, "is_composite", False):
            a, b = j.between
            if a in paths and (b not in paths or len(paths[a]) <= len(paths[b])):
                paths[j.hidden_body] = paths[a] + (PathStep(j.name, 1, 0),)
            elif b in paths:
                paths[j.hidden_body] = paths[b] + (PathStep(j.name, -1, 1),)
    loops = canonical_loops(bodies, joints)
    return MechanismGraph(
        bodies=tuple(bodies),
        ground=ground,
        joints=tuple(joints),
        multigraph=G,
        loops=loops,
        tree_paths=paths,
        tree_joints=tree_sorted,
        chord_joints=chords,
    )
