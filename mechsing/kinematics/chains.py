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
    return tuple(jk.name for jk in model.joints for _ in range(jk.columns.stop - jk.columns.start))


def path_chain(model: Any, steps: Iterable[tuple[str, int]]) -> Chain:
    """The chain of a path of whole joints ``(name, sign)`` (each joint crossed once)."""
    signs = np.zeros(model.n, dtype=int)
    for name, sign in steps:
        signs[model.joint(name).columns] += sign
    return Chain(signs, _names(model))


def tree_chain(model: Any, body: str, relative_to: str) -> Chain:
    """The chain of ``body`` relative to ``relative_to`` through the spanning tree."""
    paths = model.mech.graph.tree_paths
    steps = [(st.joint, st.sign) for st in paths[body]]
    steps += [(st.joint, -st.sign) for st in paths[relative_to]]
    return path_chain(model, steps)
