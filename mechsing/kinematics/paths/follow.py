"""Following one path of a sweep: the closed configuration at each sample, and its folds.

Owns :func:`follow` (and :func:`follow_together`, several paths in lockstep, and
:func:`first_nodes_of`): from a closed configuration at the first sample value, the swept
coordinate moves through the sample values in order, and every sample is closed on the
assembly mode the path started on.  The steps it strings together live beside it: the
problem it closes (:mod:`.problem`), the nodes (:mod:`.nodes`), the samples between them
(:mod:`.segments`) and the curve through folds (:mod:`.arc`).

* **Nodes.**  Samples at most :data:`~mechsing.sweeps.settings.SWEEP_NODE_STEP` apart (radians,
  or lengths / L) are *nodes*, reached one after the other by the continuation of a
  named configuration's closure (:meth:`mechsing.kinematics.Closer.follow`: predictor,
  Newton on the group, branch checks), each first predicted from the last step (the
  first step from the tangent at the start) and kept when Newton corrects it little.
  The samples between two nodes are closed together by batched Newton
  (:class:`~mechsing.kinematics.batch_newton.BatchClosure`) from their interpolation on the
  group (a row's two directions in one batch: :func:`~.segments.close_segments`); one whose
  correction is large next to the node spacing is closed again by continuation from
  its predecessor.
* **Folds.**  Where continuation cannot reach the next node, the path is followed along
  its curve by pseudo-arclength continuation (the swept coordinate solved with the
  others, one more equation fixing the step along the tangent).  A fold of the swept
  value (a limit of its travel: a dead centre, the end of a rocker's swing) is where the
  tangent's swept component changes sign; it is located by Brent's method on that
  component, so the limit value itself (quadratic in the arclength there) is known to
  far better than :data:`~mechsing.sweeps.settings.SWEEP_LOCATE_TOL`.
* **The other side.**  Past a fold the curve comes back on the other assembly mode; it
  is followed to its next fold, after which the swept value moves forward again.  For a
  revolute angle that value is taken modulo 2 pi into what is left of the range, and the
  path resumes there (a double rocker swept over a full turn comes back past its other
  limit); otherwise, or when the curve does not come back, the rest of the path is not
  reached.  A path whose curve is not one-dimensional (more freedom than the swept
  value) stops at the fold.

Conventions: coordinates ``z`` are the model's (joints in file order; for a sweep of the
output's pose, then the six pose coordinates), SI units and radians; distances along a
path are commensurate (radians, lengths / L).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mechsing.errors import ClosureError
from mechsing.kinematics.paths.arc import Arc
from mechsing.kinematics.paths.folds import Fold, close_to_fold, near_fold
from mechsing.kinematics.paths.nodes import (
    node_bounds,
    node_index,
    polynomial_prediction,
    reach_node,
    tangent_points,
    tangent_step,
)
from mechsing.kinematics.paths.problem import Problem
from mechsing.kinematics.paths.segments import close_segments
from mechsing.kinematics.paths.trace import PathTrace

__all__ = [
    "PathTrace",
    "first_nodes_of",
    "follow",
    "follow_together",
]

#: most folds one direction of a path passes
_MAX_FOLDS = 8
#: nodes a node's predictor is extrapolated through, besides the last (a cubic)
_HISTORY = 3


def first_nodes_of(
    pb: Problem, starts: list[tuple[np.ndarray, list[np.ndarray]]], col: int
) -> list[list[np.ndarray | None]]:
    """The first node of each path of several starts (the rows of a grid), all in one
    batched Newton: each start's closed z0 and its paths (each path's ``values`` start at
    z0's value); per start, its paths' first nodes: the prediction and the test
    :func:`~.nodes.reach_node` makes for a first step (the tangent at z0).  None for a
    path whose first node is not kept that way (:func:`follow` then takes it as it takes
    any node)."""
    out: list[list[np.ndarray | None]] = [[None] * len(paths) for _, paths in starts]
    steps, which, targets = [], [], []
    sc = pb.scale(col)
    for s, (z0, paths) in enumerate(starts):
        for m, values in enumerate(paths):
            if len(values) < 2:
                continue
            value = values[node_index(values, 0, sc)]
            d = tangent_step(pb, z0, col, value)
            if d is None:
                continue
            steps.append(d)
            which.append((s, m))
            targets.append(value)
    if steps:
        # the tangents' predictions, every path's in one update
        Z0 = np.array([np.asarray(starts[s][0], dtype=float) for s, _ in which])
        preds = tangent_points(pb, Z0, np.array(steps), col, np.array(targets))
        Q, ok, _ = pb.close_near(preds, node_bounds(pb, preds, Z0))
        for (s, m), q, good in zip(which, Q, ok, strict=True):
            out[s][m] = q if good else None
    return out


@dataclass
class _Walk:
    """Where :func:`follow` is on its path: the closed samples so far, the last node
    (sample i, configuration z), the node before it and the older ones on the same
    stretch (the predictor's history), the node pairs whose samples are still to close."""

    Z: np.ndarray
    its: np.ndarray
    i: int
    z: np.ndarray
    z_prev: np.ndarray | None = None
    older: list[np.ndarray] = field(default_factory=list)
    segments: list[tuple[int, int]] = field(default_factory=list)

    @classmethod
    def start(cls, pb: Problem, z0: np.ndarray, values: np.ndarray) -> _Walk:
        Z = np.full((len(values), pb.n), np.nan)
        Z[0] = z0
        return cls(Z, np.zeros(len(values), dtype=int), 0, np.array(z0, dtype=float))

    def take(self, j: int, zj: np.ndarray) -> None:
        """The next node, sample j, is zj."""
        if j > self.i + 1:
            self.segments.append((self.i, j))
        self.Z[j] = zj
        if self.z_prev is not None:
            self.older = [*self.older[-(_HISTORY - 1) :], self.z_prev]
        self.i, self.z, self.z_prev = j, np.asarray(zj, dtype=float), self.z


def follow(
    pb: Problem,
    z0: np.ndarray,
    col: int,
    values: np.ndarray,
    fine: bool = True,
    first: np.ndarray | None = None,
    walk: _Walk | None = None,
) -> PathTrace:
    """Follow the swept coordinate ``col`` through ``values`` (monotone) from ``z0``,
    closed at ``values[0]``.  With ``fine=False`` only the nodes (and the samples near
    folds) are closed: the trace's ``segments`` are left to :func:`~.segments.close_segments`.
    ``first``: the first node when it is already closed (:func:`first_nodes_of`);
    ``walk``: where the path already is (:func:`follow_together`), to go on from."""
    K = len(values)
    if walk is None:
        walk = _Walk.start(pb, z0, values)
    Z, its = walk.Z, walk.its
    folds: list[Fold] = []
    if K < 2:
        return PathTrace(Z, folds, None, its, [], values)
    direction = 1 if values[-1] > values[0] else -1
    sc = pb.scale(col)
    i, z, z_prev = walk.i, walk.z, walk.z_prev
    #: the nodes before z_prev on this stretch of the path (the predictor's history)
    older: list[np.ndarray] = walk.older
    stopped = None
    #: node pairs whose samples in between are closed together at the end
    segments: list[tuple[int, int]] = walk.segments
    while i < K - 1:
        j = node_index(values, i, sc)
        # where the tangent's prediction cannot reach the next node (a fold, a singular
        # point, a sharp bend) the curve itself is followed below
        if i == 0 and first is not None:
            zj = first
        else:
            zj = reach_node(pb, z, z_prev, col, values[j], older)
        if zj is not None:
            if j > i + 1:
                segments.append((i, j))
            Z[j] = zj
            if z_prev is not None:
                older = [*older[-(_HISTORY - 1) :], z_prev]
            i, z, z_prev = j, np.asarray(zj, dtype=float), z
            continue
        older = []
        # continuation cannot reach the next node: follow the curve itself
        if len(folds) >= _MAX_FOLDS:
            stopped = f"more than {_MAX_FOLDS} limits of travel on one path"
            break
        arc = Arc(pb, col, direction)
        out = arc.to_fold_or(z, values[j])
        if out is None:
            stopped = arc.why or "continuation cannot go on (a singularity of the path's curve)"
            break
        kind, zs = out
        if kind == "passed":  # no fold: the curve passes a point continuation refused
            if j > i + 1:
                segments.append((i, j))
            Z[j] = zs
            i, z, z_prev = j, zs, None
            continue
        fold = Fold(float(zs[col]), zs, direction)
        folds.append(fold)
        ks = [k for k in range(i + 1, j + 1) if (values[k] - fold.value) * direction <= 0]
        if ks:
            close_to_fold(pb, Z, col, values, ks, [*arc.trail, zs])
        prev, before = z, z_prev
        for k in ks:
            if not np.isnan(Z[k, 0]):
                prev, before = Z[k], prev
                continue
            nxt = reach_node(pb, prev, before, col, values[k])
            if nxt is None:
                nxt = near_fold(pb, prev, zs, col, values[k])
            if nxt is None:
                try:
                    nxt = pb.reach(prev, col, values[k])
                except ClosureError:
                    break
            Z[k], prev, before = nxt, nxt, prev
        reached = [k for k in range(i + 1, j + 1) if not np.isnan(Z[k, 0])]
        last = max(reached) if reached else i
        if last == K - 1:
            break  # every sample reached: the fold lies beyond the range
        resume = arc.other_side(zs, values, last)
        if resume is None:
            stopped = arc.why
            break
        far, k, zk = resume
        folds.append(far)
        Z[k] = zk
        i, z, z_prev = k, zk, None
    trace = PathTrace(Z, folds, stopped, its, segments, values)
    if fine:
        close_segments(pb, [trace], col)
    return trace


def follow_together(
    pb: Problem,
    col: int,
    paths: list[tuple[np.ndarray, np.ndarray, np.ndarray | None]],
) -> list[PathTrace]:
    """:func:`follow` (``fine=False``) of several paths (the rows of a grid), each
    ``(z0, values, first)``, in lockstep: at each step, every path whose next node
    :func:`~.nodes.reach_node` predicts from its last two nodes (the secant or the
    polynomial through the older ones) has it closed by one batched Newton over all of
    them, kept by the same test.  A path whose node is not kept that way (a fold, a sharp bend), or that
    needs the tangent's prediction, leaves the lockstep where it is: :func:`follow`
    goes on from there, as it would have alone.  Each path's trace is the one
    :func:`follow` gives it alone."""
    sc = pb.scale(col)
    walks = [_Walk.start(pb, z0, values) for z0, values, _ in paths]
    going = []
    for m, (_, values, first) in enumerate(paths):
        if len(values) >= 2 and first is not None:
            walks[m].take(node_index(values, 0, sc), first)
            going.append(m)
    bc = pb.batch
    while going:
        steps = []
        for m in going:
            w, values = walks[m], paths[m][1]
            if w.i >= len(values) - 1 or w.z_prev is None or w.z_prev[col] == w.z[col]:
                continue
            steps.append((m, node_index(values, w.i, sc)))
        if not steps:
            break
        preds = np.zeros((len(steps), pb.n))
        secant = []
        for s, (m, j) in enumerate(steps):
            w, value = walks[m], paths[m][1][j]
            zp = polynomial_prediction(pb, w.z, w.z_prev, col, value, w.older)
            if zp is None:
                secant.append(s)
            else:
                preds[s] = zp
        if secant:
            # the last step repeated, scaled to the new one: z_prev -> z continued past z
            zs = np.array([walks[steps[s][0]].z for s in secant])
            zq = np.array([walks[steps[s][0]].z_prev for s in secant])
            v = np.array([paths[steps[s][0]][1][steps[s][1]] for s in secant])
            f = (v - zs[:, col]) / (zs[:, col] - zq[:, col])
            preds[secant] = bc.between(zs, zq, -f)
        for s, (m, j) in enumerate(steps):
            preds[s, col] = paths[m][1][j]
        Z = np.array([walks[m].z for m, _ in steps])
        Q, ok, _ = pb.close_near(preds, node_bounds(pb, preds, Z))
        going = []
        for s, (m, j) in enumerate(steps):
            if ok[s]:
                walks[m].take(j, Q[s])
                going.append(m)
    return [
        follow(pb, z0, col, values, fine=False, walk=walks[m])
        for m, (z0, values, _) in enumerate(paths)
    ]
