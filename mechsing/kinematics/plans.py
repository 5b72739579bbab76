"""The plans of one kinematic model: :class:`ModelPlans`.

A plan is what depends only on a model, not on a configuration: the order in which the
spanning tree's poses are composed, the basis screws stacked for one call of
:func:`mechsing.lie.act_screw`, the chain between two bodies, a singularity test's
matrices that do not move (:mod:`mechsing.singularity.criteria`).  Each is built the
first time it is asked for and kept.

Where they are kept is this one object, made with its model (Pinocchio's split of a
model from the data computed for it): a :class:`~mechsing.kinematics.KinematicModel`
or a :class:`~mechsing.kinematics.pose.PoseModel` makes its own in its constructor, as
its attribute ``plans``, and the code that builds a plan reads and writes it there and
nowhere else (no attribute attached to a model afterwards, no cache keyed by a model's
``id``).  So two models never share a plan: not two models alive at once, not a model
built after another one was let go at the same address.  A plan, once kept, is never
changed (its arrays are read only where they are handed out), so threads that share one
model share finished plans only; two threads asking for a plan not yet built may both
build it, and the one kept is equal to the other.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["ModelPlans"]


class ModelPlans:
    """The plans of one model, each ``None`` (or an empty table) until first built."""

    __slots__ = (
        "chord_entries",
        "chord_signs",
        "coordinate_joints",
        "elements",
        "pose_order",
        "screws",
        "tests",
        "tree_chains",
    )

    def __init__(self) -> None:
        #: each user body with the joint of its tree path's last step, the body before
        #: that step and the step's sign, shorter paths first
        #: (:func:`mechsing.kinematics.forward.poses`)
        self.pose_order: list[tuple[str, Any, str, int]] | None = None
        #: the body carrying each coordinate's screw, the basis screws stacked, the U
        #: joints (:func:`mechsing.kinematics.forward.current_screws`)
        self.screws: tuple[list[str], Any, list[Any]] | None = None
        #: what one exp of stacked twists needs, per set of joints (None: all)
        #: (:func:`mechsing.kinematics.forward.elements_at_once`)
        self.elements: dict[tuple[str, ...] | None, tuple[Any, ...]] = {}
        #: the joint of every coordinate (:mod:`mechsing.kinematics.chains`)
        self.coordinate_joints: tuple[str, ...] | None = None
        #: the chain of each (body, relative_to) through the spanning tree
        #: (:func:`mechsing.kinematics.chains.tree_chain`)
        self.tree_chains: dict[tuple[str, str], Any] = {}
        #: each chord's closure chain, and their non-zero entries as (chord, column,
        #: sign) arrays (:func:`mechsing.kinematics.jacobians.chord_signs`)
        self.chord_signs: list[np.ndarray] | None = None
        self.chord_entries: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        #: each singularity test's plan, by the test's class
        #: (:meth:`mechsing.singularity.criteria.Criterion.of`)
        self.tests: dict[type, Any] = {}
