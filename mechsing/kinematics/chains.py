"""Chains between two bodies: which joint coordinates they cross, and with which sign.

Owns the tree-path sign sums: the relative twist of ``body`` with respect to
``relative_to`` is ``sum_i s_i u_i S_i`` (current screws ``S_i``, rates
``u_i``) with ``s_i = +1`` for a coordinate whose joint the tree path to
``body`` crosses forward (``between[0]`` to ``between[1]``), ``-1`` backward,
and the opposite for the path to ``relative_to``; the joints the two paths
share cancel.  Output chains, the closure rows of chord joints and the legs of a
parallel mechanism are all such chains.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Chain", "path_chain", "tree_chain"]


@dataclass(frozen=True)
class Chain:
    """A chain of joint coordinates: ``signs`` (n,) integers, +1 or -1 on the coordinates
    the chain crosses forward or backward, 0 elsewhere; ``joint_names``: the joint of
    every coordinate of the mechanism (file order)."""

    signs: np.ndarray
    joint_names: tuple[str, ...]

    @property
    def columns(self) -> list[int]:
        """The coordinates the chain crosses, in file order."""
        return [int(i) for i in np.flatnonzero(self.signs)]

    @property
    def joints(self) -> list[str]:
        """The joint of each of :attr:`columns`."""
        return [self.joint_names[i] for i in self.columns]


def _names(model: Any) -> tuple[str, ...]:
    """The joint of every coordinate (built once per model)."""
    names = model.plans.coordinate_joints
    if names is None:
        names = tuple(
            jk.name for jk in model.joints for _ in range(jk.columns.stop - jk.columns.start)
        )
        model.plans.coordinate_joints = names
    return names


def _shared(a: tuple[Any, ...], b: tuple[Any, ...]) -> int:
    """How many first steps two tree paths share (their common prefix: the path to the
    bodies' last common ancestor).  Found by bisection: in a tree, two paths that take
    the same step at the same depth share every step before it."""
    lo, hi = 0, min(len(a), len(b))
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if a[mid - 1] == b[mid - 1]:
            lo = mid
        else:
            hi = mid - 1
    return lo


def path_chain(model: Any, steps: Iterable[tuple[str, int]]) -> Chain:
    """The chain of a path of whole joints ``(name, sign)`` (each joint crossed once)."""
    signs = np.zeros(model.n, dtype=int)
    for name, sign in steps:
        signs[model.joint(name).columns] += sign
    return Chain(signs, _names(model))


def tree_chain(model: Any, body: str, relative_to: str) -> Chain:
    """The chain of ``body`` relative to ``relative_to`` through the spanning tree (built
    once per model and pair of bodies; its signs are read only)."""
    cache = model.plans.tree_chains
    got = cache.get((body, relative_to))
    if got is None:
        got = cache[(body, relative_to)] = _tree_chain(model, body, relative_to)
        got.signs.flags.writeable = False
    return got


def _tree_chain(model: Any, body: str, relative_to: str) -> Chain:
    paths = model.mech.graph.tree_paths
    a, b = paths[body], paths[relative_to]
    # the steps the two paths share cancel (+s and -s): only the rest is crossed
    k = _shared(a, b)
    steps = [(st.joint, st.sign) for st in a[k:]]
    steps += [(st.joint, -st.sign) for st in b[k:]]
    return path_chain(model, steps)
