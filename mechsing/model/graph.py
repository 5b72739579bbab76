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

import weakref
from collections import deque
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import networkx as nx

__all__ = [
    "Leg",
    "Loop",
    "MechanismGraph",
    "PathStep",
    "build_graph",
    "canonical_loops",
    "connected_to",
    "coupled_loops",
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
    loops: tuple[Loop, ...]
    tree_paths: Mapping[str, tuple[PathStep, ...]] = field(repr=False)
    tree_joints: tuple[str, ...]
    chord_joints: tuple[str, ...]

    @cached_property
    def multigraph(self) -> nx.MultiGraph:
        """The networkx multigraph (module docstring), built on first use: networkx is
        imported only where a caller asks for it."""
        return _multigraph(self.bodies, self.joints)

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
        found = _LEGS.setdefault(self, {})
        if (body, base) not in found:
            found[body, base] = self._find_legs(body, base)
        return found[body, base]

    def _find_legs(self, body: str, base: str) -> tuple[Leg, ...]:
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


#: the legs found in each graph for each (body, base) (:meth:`MechanismGraph.legs`; a graph
#: does not change), kept beside the graph while it lives
_LEGS: weakref.WeakKeyDictionary[MechanismGraph, dict[tuple[str, str], tuple[Leg, ...]]] = (
    weakref.WeakKeyDictionary()
)

#: radius of the breadth-first trees in which :func:`short_cycle_basis` looks for
#: loops (it finds every loop of 2 * 16 + 1 = 33 joints or fewer)
SHORT_CYCLE_DEPTH = 16
#: largest loops x (bodies + joints)^2 for which the loops are networkx's
#: ``minimum_cycle_basis`` (about 0.4 s there); above it, :func:`short_cycle_basis`
NETWORKX_LOOP_WORK = 400_000


def canonical_loops(bodies: Sequence[str], joints: Sequence[Any]) -> tuple[Loop, ...]:
    """The canonical cycle basis (module docstring) for bodies and joints in file order.

    ``joints`` need ``name`` and ``between`` attributes.  The simple graph has
    integer nodes (bodies 0..nb-1, then joints nb..) inserted in file order,
    so nothing depends on string hashing or on any other memory order.

    networkx's ``minimum_cycle_basis`` costs about loops x nodes^2; above
    :data:`NETWORKX_LOOP_WORK` the basis is :func:`short_cycle_basis` instead,
    also a minimum cycle basis (the same total length, so the same loops
    wherever the minimum basis is unique, as in a ladder of parallelograms),
    with ties broken by the joints' file positions.  With one loop or none the basis
    is unique (the one cycle), and :func:`short_cycle_basis` finds it without networkx.
    """
    pos = {j.name: k for k, j in enumerate(joints)}
    n_loops = len(joints) - len(bodies) + 1
    if 1 < n_loops and n_loops * (len(bodies) + len(joints)) ** 2 <= NETWORKX_LOOP_WORK:
        cycles = _networkx_cycles(bodies, joints)
    else:
        cycles = short_cycle_basis(bodies, [j.between for j in joints])
    loops = [_orient(sorted(ks), joints) for ks in cycles]
    loops.sort(key=lambda lp: (len(lp.joints), sorted(pos[n] for n in lp.joints)))
    return tuple(loops)


def _networkx_cycles(bodies: Sequence[str], joints: Sequence[Any]) -> list[list[int]]:
    """networkx's minimum cycle basis, each cycle as its joints' file positions."""
    import networkx as nx

    index = {b: i for i, b in enumerate(bodies)}
    nb = len(bodies)
    H = nx.Graph()
    H.add_nodes_from(range(nb))
    for k, j in enumerate(joints):
        a, b = j.between
        H.add_node(nb + k)
        H.add_edge(nb + k, index[a])
        H.add_edge(nb + k, index[b])
    return [[n - nb for n in cycle if n >= nb] for cycle in nx.minimum_cycle_basis(H)]


def short_cycle_basis(bodies: Sequence[str], between: Sequence[tuple[str, str]]) -> list[list[int]]:
    """A minimum cycle basis of the body graph (joints of length 1), in near-linear time.

    ``between[k]`` are joint k's two bodies; every body must be connected to
    the others.  Returns each cycle as the sorted file positions of its joints.

    Candidates (Horton's): for a root body v, its breadth-first tree T_v
    (neighbours in joint file order) and a joint e = (x, y) outside T_v with
    both ends reached, the cycle e + (the path from x to y in T_v).  A cycle C
    is the sum over GF(2) of the candidates of its joints from any root on C,
    and each has length at most |C| and ends at depth at most |C| / 2; so the
    candidates from trees of depth R span every cycle of length 2R + 1 or
    less.  Taking the candidates short first (ties: the joints' file
    positions) and keeping each that is independent of those kept (Gaussian
    elimination over GF(2) on bit sets) is the matroid greedy, so the result
    is a minimum cycle basis.  R doubles from 1 until the basis is complete;
    mechanisms' loops are short, so every tree stays small and the cost grows
    with the number of loops times the size of a neighbourhood.  Past
    :data:`SHORT_CYCLE_DEPTH` the fundamental cycles of one breadth-first tree
    complete the basis, shortest first: a loop of more than 33 joints is then
    a loop of the basis but not necessarily of a minimum one.
    """
    index = {b: i for i, b in enumerate(bodies)}
    nb = len(bodies)
    ends = [(index[a], index[b]) for a, b in between]
    adj: list[list[tuple[int, int]]] = [[] for _ in range(nb)]
    for k, (a, b) in enumerate(ends):
        adj[a].append((k, b))
        adj[b].append((k, a))
    need = len(ends) - nb + 1
    if need <= 0:
        return []
    depth_limit = 1
    candidates: set[tuple[int, ...]] = set()
    while True:
        candidates = set()
        longest = 2 * depth_limit + 1
        for root in range(nb):
            candidates.update(_tree_cycles(root, adj, ends, depth_limit, longest))
        basis = _greedy_basis(sorted(candidates, key=lambda c: (len(c), c)), need)
        if len(basis) == need:
            return [list(c) for c in basis]
        if depth_limit >= SHORT_CYCLE_DEPTH:
            break
        depth_limit *= 2
    # loops longer than 2 * SHORT_CYCLE_DEPTH + 1 joints: the fundamental cycles of
    # the breadth-first tree from the first body complete the basis, shortest first
    # (a basis, no longer proved minimum in those long loops)
    whole = _tree_cycles(0, adj, ends, nb, len(ends) + 1)
    pool = sorted(candidates, key=lambda c: (len(c), c)) + sorted(whole, key=lambda c: (len(c), c))
    return [list(c) for c in _greedy_basis(pool, need)]


def _tree_cycles(
    root: int,
    adj: list[list[tuple[int, int]]],
    ends: list[tuple[int, int]],
    depth_limit: int,
    longest: int,
) -> list[tuple[int, ...]]:
    """Horton's candidates of ``root`` (see :func:`short_cycle_basis`) of ``longest`` joints or fewer."""
    depth = {root: 0}
    parent: dict[int, tuple[int, int]] = {}  # body -> (joint, parent body)
    queue = deque([root])
    while queue:
        x = queue.popleft()
        if depth[x] == depth_limit:
            continue
        for k, y in adj[x]:
            if y not in depth:
                depth[y] = depth[x] + 1
                parent[y] = (k, x)
                queue.append(y)
    tree = {k for k, _ in parent.values()}
    out = []
    for x in depth:
        for k, y in adj[x]:
            if k in tree or y not in depth or ends[k][0] != x:
                continue
            path = _tree_path(x, y, depth, parent)
            if len(path) + 1 <= longest:
                out.append(tuple(sorted((*path, k))))
    return out


def _tree_path(
    x: int, y: int, depth: dict[int, int], parent: dict[int, tuple[int, int]]
) -> list[int]:
    """The joints of the tree path between bodies x and y."""
    left: list[int] = []
    right: list[int] = []
    while depth[x] > depth[y]:
        k, x = parent[x]
        left.append(k)
    while depth[y] > depth[x]:
        k, y = parent[y]
        right.append(k)
    while x != y:
        k, x = parent[x]
        left.append(k)
        k, y = parent[y]
        right.append(k)
    return left + right


def _greedy_basis(candidates: Sequence[tuple[int, ...]], need: int) -> list[tuple[int, ...]]:
    """Keep, in order, each candidate independent over GF(2) of those kept (at most ``need``)."""
    pivots: dict[int, int] = {}
    kept: list[tuple[int, ...]] = []
    for cycle in candidates:
        bits = 0
        for k in cycle:
            bits ^= 1 << k
        while bits:
            top = bits.bit_length() - 1
            row = pivots.get(top)
            if row is None:
                pivots[top] = bits
                kept.append(cycle)
                break
            bits ^= row
        if len(kept) == need:
            break
    return kept


def coupled_loops(loops: Sequence[Loop]) -> list[tuple[int, int]]:
    """The loops grouped by shared joints (two loops that share a joint are in one
    group, transitively): (loops, joints) of each group, largest first.  The closure
    system splits into one block per group, the unit of mechsing's dense work."""
    parent = list(range(len(loops)))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owner: dict[str, int] = {}
    for i, lp in enumerate(loops):
        for name in lp.joints:
            if name in owner:
                parent[find(i)] = find(owner[name])
            else:
                owner[name] = i
    groups: dict[int, tuple[int, set[str]]] = {}
    for i, lp in enumerate(loops):
        n, joints = groups.get(find(i), (0, set()))
        joints.update(lp.joints)
        groups[find(i)] = (n + 1, joints)
    return sorted(((n, len(j)) for n, j in groups.values()), reverse=True)


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


def _multigraph(bodies: Sequence[str], joints: Sequence[Any]) -> nx.MultiGraph:
    """The networkx multigraph of :attr:`MechanismGraph.multigraph` (module docstring)."""
    import networkx as nx

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
    return G


def build_graph(bodies: Sequence[str], ground: str, joints: Sequence[Any]) -> MechanismGraph:
    """The graph model of bodies (file order), a ground and joints (file order).

    Every body must be connected to ground (the loader checks it first).
    """
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
        loops=loops,
        tree_paths=paths,
        tree_joints=tree_sorted,
        chord_joints=chords,
    )
