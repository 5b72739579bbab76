"""Following one path of a sweep: the closed configuration at each sample, and its folds.

Owns :class:`Problem` (what a sweep holds fixed and what it solves) and
:func:`follow`: from a closed configuration at the first sample value, the swept
coordinate moves through the sample values in order, and every sample is closed on the
assembly mode the path started on.

* **Nodes.**  Samples at most :data:`~mechsing.numeric.SWEEP_NODE_STEP` apart (radians,
  or lengths / L) are *nodes*, reached one after the other by the continuation of a
  named configuration's closure (:meth:`mechsing.kinematics.Closer.follow`: predictor,
  Newton on the group, branch checks), each first predicted from the last step (the
  first step from the tangent at the start) and kept when Newton corrects it little.
  The samples between two nodes are closed together by batched Newton
  (:class:`~mechsing.kinematics.batch_newton.BatchClosure`) from their interpolation on the
  group (a row's two directions in one batch: :func:`close_segments`); one whose
  correction is large next to the node spacing is closed again by continuation from
  its predecessor.
* **Folds.**  Where continuation cannot reach the next node, the path is followed along
  its curve by pseudo-arclength continuation (the swept coordinate solved with the
  others, one more equation fixing the step along the tangent).  A fold of the swept
  value (a limit of its travel: a dead centre, the end of a rocker's swing) is where the
  tangent's swept component changes sign; it is located by Brent's method on that
  component, so the limit value itself (quadratic in the arclength there) is known to
  far better than :data:`~mechsing.numeric.SWEEP_LOCATE_TOL`.
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

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing.errors import ClosureError
from mechsing.kinematics import Closer, KinematicModel
from mechsing.kinematics.batch_newton import BatchClosure
from mechsing.kinematics.newton import scaled_system
from mechsing.numeric import (
    SWEEP_ARC_MIN_STEP,
    SWEEP_ARC_STEP,
    SWEEP_JUMP_RATIO,
    SWEEP_KNOT_STEP,
    SWEEP_LOCATE_TOL,
    SWEEP_NODE_STEP,
)

__all__ = [
    "Fold",
    "PathTrace",
    "Problem",
    "close_segments",
    "first_nodes_of",
    "follow",
    "follow_together",
]

#: most arclength steps spent on the far side of one fold
_ARC_BUDGET = 4000
#: the longest step along a curve (commensurate): the tangent may turn at most 30 degrees
#: per step, which shortens it where the curve bends
_ARC_LONGEST = 10 * SWEEP_ARC_STEP
#: most folds one direction of a path passes
_MAX_FOLDS = 8
#: Newton iterations of one arclength step
_ARC_NEWTON = 10
#: a node closed from the secant predictor is kept when Newton moved it at most this
#: fraction of the step (a well-predicted step stays on its branch)
_NODE_CORRECTION = 0.3
#: samples closed by one batched Newton call at most (bounds its working memory)
_FINE_CHUNK = 8192
#: fewer samples than this between the nodes of a row are closed in one pass (no knots)
_KNOTS_FROM = 1000
#: a badly predicted node is tried again in this many halvings of its step
_NODE_HALVINGS = 3
#: nodes a node's predictor is extrapolated through, besides the last (a cubic)
_HISTORY = 3
#: tangents a Problem keeps (a row's start asks for the same one up to three times, and
#: the rows of a grid are started together: a chunk of rows' starts, then their first
#: nodes; a tangent is a few hundred bytes)
_TANGENTS_KEPT = 4096


@dataclass
class Problem:
    """A sweep's kinematic problem: the float model it closes (the mechanism's, or its
    pose model when the output's pose is swept), which coordinates are given (held at
    the start's values or swept), the closure tolerance, and the tools that close."""

    model: KinematicModel
    cm: Any  # the model continuation works in (a PoseModel for a pose sweep)
    given: np.ndarray  # bool over cm.n
    closer: Closer
    batch: BatchClosure
    tolerance: float
    #: which columns of cm are revolute angles (a value and itself plus 2 pi are one pose)
    periodic: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    #: the tangents asked last (:meth:`tangent`), by (column, configuration's bytes)
    _tangents: dict[tuple[int, bytes], np.ndarray | None] = field(
        default_factory=dict, repr=False, compare=False
    )

    @property
    def n(self) -> int:
        return int(self.cm.n)

    def scale(self, col: int) -> float:
        """The commensurate unit of column ``col``: 1 for an angle, L for a length."""
        return float(self.cm.float_frame.rates_back(np.ones(1), [col])[0])

    def comm(self, d: np.ndarray) -> float:
        return float(np.linalg.norm(self.cm.float_frame.rates(d)))

    def close_near(
        self, Qp: np.ndarray, bound: Any, polish: bool = True
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Batched Newton from the predicted rows Qp (the given coordinates held): the
        closed rows, which of them closed to the tolerance within ``bound`` of their
        prediction (commensurate; a scalar or one per row: farther, a row may have jumped
        to another assembly mode), and the Newton iterations per row."""
        Q, res, its = self.batch.newton(
            Qp, ~self.given[: self.batch.nb], self.tolerance, polish=polish
        )
        moved = np.linalg.norm(self.cm.float_frame.rates(Q - Qp), axis=1)
        ok = (res <= self.tolerance) & np.isfinite(res) & (moved <= bound)
        return Q, ok, its

    def tangent(self, z: np.ndarray, col: int) -> np.ndarray | None:
        """The unit commensurate tangent of the path's curve at the closed z (every
        coordinate of cm, zero on the given ones but ``col``; its sign arbitrary), or None
        where the curve is not one-dimensional.  The last ones are kept: a row's start
        asks for it once to check that it can leave and once per direction."""
        key = (col, np.asarray(z, dtype=float).tobytes())
        if key in self._tangents:
            return self._tangents[key]
        arc = _Arc(self, col, 1)
        t = arc.tangent(np.asarray(z, dtype=float))
        out = None
        if t is not None:
            out = np.zeros(self.n)
            out[arc.free] = t
        if len(self._tangents) >= _TANGENTS_KEPT:
            self._tangents.pop(next(iter(self._tangents)))
        self._tangents[key] = out
        return out

    def reach(self, z: np.ndarray, col: int, value: float) -> np.ndarray:
        """From the closed z, the configuration with coordinate ``col`` at ``value`` (the
        other given coordinates kept), by the careful continuation of a named
        configuration's closure; raises :class:`ClosureError` where it cannot go."""
        target = np.array(z, dtype=float)
        target[col] = value
        given = tuple(int(i) for i in np.flatnonzero(self.given))
        pose = self.cm if self.cm is not self.model else None
        return np.asarray(self.closer.follow(z, target, given, pose).q, dtype=float)


@dataclass(frozen=True)
class Fold:
    """A limit of the swept value: where the path's curve turns back.  ``value`` (SI) is
    the limit, ``z`` the configuration there, ``direction`` +1 when the swept value was
    increasing, ``far_side`` True for a fold met on the other assembly mode (the limit
    the path comes back past)."""

    value: float
    z: np.ndarray
    direction: int
    far_side: bool = False


@dataclass
class PathTrace:
    """The closed configurations of one direction of a path: ``Z`` (K, n), NaN rows at
    samples not reached; its folds; ``stopped``: why the path ended early (None: it
    reached every sample it could); ``newton``: batched Newton iterations per sample."""

    Z: np.ndarray
    folds: list[Fold]
    stopped: str | None = None
    newton: np.ndarray | None = None
    #: node pairs whose samples in between are still to be closed (``follow(...,
    #: fine=False)``: :func:`close_segments` closes them, several traces together)
    segments: list[tuple[int, int]] = field(default_factory=list)
    values: np.ndarray | None = None


def first_nodes_of(
    pb: Problem, starts: list[tuple[np.ndarray, list[np.ndarray]]], col: int
) -> list[list[np.ndarray | None]]:
    """The first node of each path of several starts (the rows of a grid), all in one
    batched Newton: each start's closed z0 and its paths (each path's ``values`` start at
    z0's value); per start, its paths' first nodes: the prediction and the test
    :func:`_node` makes for a first step (the tangent at z0).  None for a path whose first
    node is not kept that way (:func:`follow` then takes it as it takes any node)."""
    out: list[list[np.ndarray | None]] = [[None] * len(paths) for _, paths in starts]
    steps, which, targets = [], [], []
    sc = pb.scale(col)
    for s, (z0, paths) in enumerate(starts):
        for m, values in enumerate(paths):
            if len(values) < 2:
                continue
            value = values[_next_node(values, 0, sc)]
            d = _tangent_step(pb, z0, col, value)
            if d is None:
                continue
            steps.append(d)
            which.append((s, m))
            targets.append(value)
    if steps:
        # the tangents' predictions, every path's in one update
        Z0 = np.array([np.asarray(starts[s][0], dtype=float) for s, _ in which])
        preds = _tangent_points(pb, Z0, np.array(steps), col, np.array(targets))
        bounds = [_NODE_CORRECTION * pb.comm(zp - z0) for zp, z0 in zip(preds, Z0, strict=True)]
        Q, ok, _ = pb.close_near(preds, np.array(bounds))
        for (s, m), q, good in zip(which, Q, ok, strict=True):
            out[s][m] = q if good else None
    return out


def _next_node(values: np.ndarray, i: int, sc: float) -> int:
    """The next node after sample i: the farthest sample at most SWEEP_NODE_STEP away
    (and at least the next one)."""
    j = i + 1
    while j + 1 < len(values) and abs(values[j + 1] - values[i]) / sc <= SWEEP_NODE_STEP:
        j += 1
    return j


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
    folds) are closed: the trace's ``segments`` are left to :func:`close_segments`.
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
        j = _next_node(values, i, sc)
        # where the tangent's prediction cannot reach the next node (a fold, a singular
        # point, a sharp bend) the curve itself is followed below
        if i == 0 and first is not None:
            zj = first
        else:
            zj = _nodes(pb, z, z_prev, col, values[j], older)
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
        arc = _Arc(pb, col, direction)
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
            _to_fold(pb, Z, col, values, ks, [*arc.trail, zs])
        prev, before = z, z_prev
        for k in ks:
            if not np.isnan(Z[k, 0]):
                prev, before = Z[k], prev
                continue
            nxt = _nodes(pb, prev, before, col, values[k])
            if nxt is None:
                nxt = _near_fold(pb, prev, zs, col, values[k])
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
    :func:`_node` predicts from its last two nodes (the secant or the polynomial through
    the older ones) has it closed by one batched Newton over all of them, kept by the
    same test.  A path whose node is not kept that way (a fold, a sharp bend), or that
    needs the tangent's prediction, leaves the lockstep where it is: :func:`follow`
    goes on from there, as it would have alone.  Each path's trace is the one
    :func:`follow` gives it alone."""
    sc = pb.scale(col)
    walks = [_Walk.start(pb, z0, values) for z0, values, _ in paths]
    going = []
    for m, (_, values, first) in enumerate(paths):
        if len(values) >= 2 and first is not None:
            walks[m].take(_next_node(values, 0, sc), first)
            going.append(m)
    bc = pb.batch
    while going:
        steps = []
        for m in going:
            w, values = walks[m], paths[m][1]
            if w.i >= len(values) - 1 or w.z_prev is None or w.z_prev[col] == w.z[col]:
                continue
            steps.append((m, _next_node(values, w.i, sc)))
        if not steps:
            break
        preds = np.zeros((len(steps), pb.n))
        secant = []
        for s, (m, j) in enumerate(steps):
            w, value = walks[m], paths[m][1][j]
            zp = _polynomial_prediction(pb, w.z, w.z_prev, col, value, w.older)
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
        bounds = np.array(
            [_NODE_CORRECTION * pb.comm(preds[s] - walks[m].z) for s, (m, _) in enumerate(steps)]
        )
        Q, ok, _ = pb.close_near(preds, bounds)
        going = []
        for s, (m, j) in enumerate(steps):
            if ok[s]:
                walks[m].take(j, Q[s])
                going.append(m)
    return [
        follow(pb, z0, col, values, fine=False, walk=walks[m])
        for m, (z0, values, _) in enumerate(paths)
    ]


def _nodes(
    pb: Problem,
    z: np.ndarray,
    z_prev: np.ndarray | None,
    col: int,
    value: float,
    older: list[np.ndarray] | None = None,
) -> np.ndarray | None:
    """The next node by :func:`_node`, in halved steps when the whole one is not well
    predicted (at most _NODE_HALVINGS times), before the careful continuation.
    ``older``: the nodes before z_prev on the same stretch of the path (oldest first)."""
    parts = 1
    for attempt in range(_NODE_HALVINGS + 1):
        # the previous nodes' extrapolation, then the tangent (a secant from a point just
        # behind): a far previous node predicts a short step no better than a long one
        here, prev = z, (z_prev if attempt == 0 else None)
        start = float(z[col])
        for k in range(1, parts + 1):
            nxt = _node(
                pb,
                here,
                prev,
                col,
                start + (value - start) * k / parts,
                older if attempt == 0 and k == 1 else None,
            )
            if nxt is None:
                break
            here, prev = nxt, here
        else:
            return here
        parts *= 2
    return None


def _node(
    pb: Problem,
    z: np.ndarray,
    z_prev: np.ndarray | None,
    col: int,
    value: float,
    older: list[np.ndarray] | None = None,
) -> np.ndarray | None:
    """The next node by one batched Newton from the secant predictor (the last step
    repeated, scaled to the new one; with ``older`` nodes before z_prev, the polynomial
    through them all, extrapolated on the group; a first step from the tangent at z);
    None when it does not close there or its correction is not small next to the step
    (the careful continuation then takes it)."""
    bc = pb.batch
    if z_prev is None or z_prev[col] == z[col]:
        # a first step: the tangent at z (the kernel of the closure Jacobian, no Newton)
        # predicts it
        zp = _tangent_prediction(pb, z, col, value)
        if zp is not None:
            Q, ok, _ = pb.close_near(zp[None, :], _NODE_CORRECTION * pb.comm(zp - z))
            if ok[0]:
                return Q[0]
        # where the tangent's step is not kept: a point a thousandth of it behind,
        # closed from z itself, gives the secant (the tangent, to first order)
        zq = np.array(z, dtype=float)
        zq[col] = z[col] - 1e-3 * (value - z[col])
        Q, ok, _ = pb.close_near(zq[None, :], np.inf)
        if not ok[0]:
            return None
        z_prev = Q[0]
    zp = _polynomial_prediction(pb, z, z_prev, col, value, older)
    if zp is None:
        # the last step repeated, scaled to the new one: z_prev -> z continued past z
        f = (value - z[col]) / (z[col] - z_prev[col])
        zp = bc.between(z[None, :], z_prev[None, :], np.array([-f]))[0]
    zp[col] = value
    Q, ok, _ = pb.close_near(zp[None, :], _NODE_CORRECTION * pb.comm(zp - z))
    return Q[0] if ok[0] else None


def _polynomial_prediction(
    pb: Problem,
    z: np.ndarray,
    z_prev: np.ndarray,
    col: int,
    value: float,
    older: list[np.ndarray] | None,
) -> np.ndarray | None:
    """:func:`_node`'s prediction through the older nodes: the polynomial through them,
    z_prev and z (increments on the group from z), at ``value``; None when there are no
    older nodes of distinct values (the secant predicts then)."""
    bc = pb.batch
    knots = [p for p in (older or []) if p[col] != z[col]]
    if not (knots and len({float(p[col]) for p in [*knots, z_prev, z]}) == len(knots) + 2):
        return None
    pts = np.array([*knots, z_prev])
    D = bc.difference(pts, np.repeat(np.asarray(z, dtype=float)[None, :], len(pts), 0))
    tk = np.concatenate([pts[:, col], [z[col]]])
    D = np.concatenate([D, np.zeros((1, D.shape[1]))])
    w = np.ones(len(tk))
    for a in range(len(tk)):
        for b in range(len(tk)):
            if a != b:
                w[a] *= (value - tk[b]) / (tk[a] - tk[b])
    d = w @ D
    zp = bc.update(np.asarray(z, dtype=float)[None, :], d[None, : bc.nb])[0]
    zp[bc.nb :] = z[bc.nb :] + d[bc.nb :]
    return zp


def _tangent_prediction(pb: Problem, z: np.ndarray, col: int, value: float) -> np.ndarray | None:
    """The point on the tangent of the path's curve at z where coordinate ``col`` is
    ``value`` (on the group, as :meth:`BatchClosure.update` moves), or None where the
    tangent is not defined or does not move ``col``."""
    d = _tangent_step(pb, z, col, value)
    if d is None:
        return None
    return _tangent_points(pb, np.asarray(z, dtype=float)[None, :], d[None, :], col, [value])[0]


def _tangent_step(pb: Problem, z: np.ndarray, col: int, value: float) -> np.ndarray | None:
    """The increment along the tangent at z that takes coordinate ``col`` to ``value``
    (None where the tangent is not defined or does not move ``col``)."""
    tau = pb.tangent(z, col)
    if tau is None or tau[col] == 0:
        return None
    return pb.cm.float_frame.rates_back(tau * ((value - z[col]) / pb.scale(col) / tau[col]))


def _tangent_points(pb: Problem, Z: np.ndarray, D: np.ndarray, col: int, values: Any) -> np.ndarray:
    """The points reached from the rows of Z by the increments D (:func:`_tangent_step`),
    on the group, with ``col`` set to ``values``: one batched update for every row."""
    bc = pb.batch
    zp = bc.update(Z, D[:, : bc.nb])
    zp[:, bc.nb :] = Z[:, bc.nb :] + D[:, bc.nb :]
    zp[:, col] = values
    return zp


def _to_fold(
    pb: Problem, Z: np.ndarray, col: int, values: np.ndarray, ks: list[int], trail: list[np.ndarray]
) -> None:
    """The samples ``ks`` between a path's last node and the fold at ``trail[-1]``, all
    together: each predicted between the two points of the curve traced to the fold that
    bracket its value (by the square-root law in the last stretch, where the swept value is
    quadratic in the distance along the curve), then batched Newton; a sample that does
    not close near its prediction is left for the caller (NaN)."""
    cm, bc = pb.cm, pb.batch
    tt = np.array([float(p[col]) for p in trail])
    sign = 1.0 if tt[-1] >= tt[0] else -1.0
    A, B, F, spans = [], [], [], []
    last = len(trail) - 2
    for k in ks:
        v = float(values[k])
        m = int(np.clip(np.searchsorted(sign * tt, sign * v) - 1, 0, last))
        ta, tb = tt[m], tt[m + 1]
        if m == last and tb != ta:
            f = 1.0 - math.sqrt(max(0.0, (tb - v) / (tb - ta)))
        else:
            f = 0.0 if tb == ta else (v - ta) / (tb - ta)
        A.append(trail[m])
        B.append(trail[m + 1])
        F.append(f)
        spans.append(pb.comm(cm.difference(trail[m + 1], trail[m])))
    Qp = bc.between(np.array(A), np.array(B), np.array(F))
    idx = np.array(ks)
    Qp[:, col] = values[idx]
    Q, ok, _ = pb.close_near(Qp, SWEEP_JUMP_RATIO * np.array(spans), polish=False)
    Z[idx[ok]] = Q[ok]


def _near_fold(
    pb: Problem, z: np.ndarray, zf: np.ndarray, col: int, value: float
) -> np.ndarray | None:
    """A sample between z and the fold zf: near a fold the swept value is quadratic in
    the distance along the curve, so the sample lies at the fraction
    ``1 - sqrt((t* - value) / (t* - t))`` of the way from z to zf; Newton from there."""
    cm, bc = pb.cm, pb.batch
    tz, tf = float(z[col]), float(zf[col])
    if (value - tz) * (tf - tz) <= 0 or (tf - value) * (tf - tz) < 0:
        return None
    f = 1.0 - math.sqrt((tf - value) / (tf - tz))
    zp = bc.between(z[None, :], zf[None, :], np.array([f]))[0]
    zp[col] = value
    Q, ok, _ = pb.close_near(zp[None, :], SWEEP_JUMP_RATIO * pb.comm(cm.difference(zf, z)))
    return Q[0] if ok[0] else None


def close_segments(
    pb: Problem, traces: list[PathTrace], col: int, groups: list[list[int]] | None = None
) -> None:
    """The samples strictly between the nodes of each segment (i, j) of each trace, all
    segments of the traces together (the two directions of a path are one batch), in two
    passes of batched Newton (in chunks of _FINE_CHUNK rows):

    1. where the samples are closer together than SWEEP_KNOT_STEP, *knots*: every m-th
       sample of the segment, m the samples in that step; otherwise every sample;
    2. the samples between the knots.

    (One pass, every sample from the nodes' cubic, when the traces hold fewer than
    _KNOTS_FROM samples to close: a grid's short rows, where a second batched call costs
    more than the Newton steps it saves.)

    Each sample is predicted by the cubic through the two closed points around it (nodes,
    or knots) and the one before and after them (a quadratic at the ends of the path), on
    the group, from the first of the two: knots only some hundredths of a radian apart
    predict to about 1e-10, so one Newton step closes a sample where the nodes' cubic
    needs two or three.  A sample that does not close near its prediction is closed
    again by continuation from the previous one.  Fills each trace's Z and newton in
    place.

    ``groups``: the traces (indices) of each path, when several paths are closed together
    (the rows of a grid): whether a path's samples are closed in one pass or two is
    decided by its own traces, as when it is closed alone (default: one path)."""
    sc = pb.scale(col)
    first: list[tuple[int, int, int, list[int], list[int]]] = []
    later: list[tuple[int, list[int]]] = []  # (trace, its knots in order) per segment
    many_of = {}
    for group in groups if groups is not None else [list(range(len(traces)))]:
        many = sum(j - i - 1 for m in group for i, j in traces[m].segments) >= _KNOTS_FROM
        many_of.update({m: many for m in group})
    for m, tr in enumerate(traces):
        many = many_of[m]
        Z, values = tr.Z, tr.values
        assert values is not None
        for i, j in tr.segments:
            stride = _knot_stride(values, i, j, sc) if many else 1
            knots = [i, *range(i + stride, j - stride // 2, stride), j] if stride > 1 else [i, j]
            if len(knots) == 2:
                first.append((m, i, j, _cubic_knots(Z, i, j), list(range(i + 1, j))))
                continue
            first.append((m, i, j, _cubic_knots(Z, i, j), knots[1:-1]))
            later.append((m, knots))
    _close_between(pb, traces, col, first)
    second = []
    for m, knots in later:
        Z = traces[m].Z
        closed = [k for k in knots if not np.isnan(Z[k, 0])]
        for p in range(len(closed) - 1):
            a, b = closed[p], closed[p + 1]
            if b - a < 2:
                continue
            around = [closed[p - 1]] if p > 0 else []
            around += [a, b] + ([closed[p + 2]] if p + 2 < len(closed) else [])
            # at the ends of the segment, the nodes' neighbours as for the first pass
            if p == 0 or p + 2 == len(closed):
                around = sorted(set(around) | set(_cubic_knots(Z, a, b)))
                around = _nearest(around, a, b)
            second.append((m, a, b, around, list(range(a + 1, b))))
    _close_between(pb, traces, col, second)
    # the samples Newton did not close near their prediction: continuation, in order
    for tr in traces:
        Z, values = tr.Z, tr.values
        assert values is not None
        for i, j in tr.segments:
            for k in range(i + 1, j):
                if not np.isnan(Z[k, 0]):
                    continue
                prev = Z[k - 1]
                if np.isnan(prev[0]):
                    continue
                try:
                    Z[k] = pb.reach(prev, col, values[k])
                except ClosureError:
                    continue
        tr.segments = []


def _knot_stride(values: np.ndarray, i: int, j: int, sc: float) -> int:
    """Samples per knot between nodes i and j: as many samples as SWEEP_KNOT_STEP holds
    (commensurate), at least 1."""
    spacing = abs(float(values[j]) - float(values[i])) / (j - i) / sc
    return max(1, int(SWEEP_KNOT_STEP / spacing)) if spacing > 0 else 1


def _cubic_knots(Z: np.ndarray, i: int, j: int) -> list[int]:
    """The closed points a segment (i, j) is interpolated through: its ends and the points
    as far before and after them, where closed."""
    return [k for k in (2 * i - j, i, j, 2 * j - i) if 0 <= k < len(Z) and not np.isnan(Z[k, 0])]


def _nearest(knots: list[int], a: int, b: int) -> list[int]:
    """At most four of the sorted closed points ``knots``: a, b and the nearest one before
    a and after b."""
    before = [k for k in knots if k < a][-1:]
    after = [k for k in knots if k > b][:1]
    return [*before, a, b, *after]


def _close_between(
    pb: Problem,
    traces: list[PathTrace],
    col: int,
    jobs: list[tuple[int, int, int, list[int], list[int]]],
) -> None:
    """One batched Newton over ``jobs``: (trace, a, b, knots, rows) closes the samples
    ``rows`` of a trace from the Lagrange interpolation through its closed samples
    ``knots`` (a among them), as increments on the group from sample a; a sample moved
    by Newton more than SWEEP_JUMP_RATIO times the distance from a to b is left NaN."""
    bc = pb.batch
    nb = bc.nb
    jobs = [job for job in jobs if job[4]]
    if not jobs:
        return
    # every knot's increment from its job's first point, in one call
    K1 = np.concatenate([traces[m].Z[knots] for m, _, _, knots, _ in jobs])
    K0 = np.concatenate(
        [np.repeat(traces[m].Z[a][None, :], len(kn), axis=0) for m, a, _, kn, _ in jobs]
    )
    Dall = bc.difference(K1, K0)
    which, rows, base, preds, spans, tvals = [], [], [], [], [], []
    at = 0
    for m, a, b, knots, ks_list in jobs:
        Z, values = traces[m].Z, traces[m].values
        assert values is not None
        D = Dall[at : at + len(knots)]
        at += len(knots)
        tk = values[knots]
        ks = np.array(ks_list)
        tv = values[ks]
        # Lagrange weights of the knots at the samples
        W = np.ones((len(ks), len(knots)))
        for p in range(len(knots)):
            for q in range(len(knots)):
                if p != q:
                    W[:, p] *= (tv - tk[q]) / (tk[p] - tk[q])
        preds.append(W @ D)
        rows.extend(ks_list)
        which.extend([m] * len(ks))
        base.append(np.repeat(Z[a][None, :], len(ks), axis=0))
        tvals.append(tv)
        spans.extend([pb.comm(D[knots.index(b)])] * len(ks))
    if not rows:
        return
    rows_a, which_a = np.array(rows), np.array(which)
    A = np.concatenate(base)
    P = np.concatenate(preds)
    T = np.concatenate(tvals)
    span_a = np.array(spans)
    for lo in range(0, len(rows_a), _FINE_CHUNK):
        sl = slice(lo, lo + _FINE_CHUNK)
        Qp = bc.update(A[sl], P[sl, :nb])
        Qp[:, nb:] = A[sl, nb:] + P[sl, nb:]
        Qp[:, col] = T[sl]
        # closed to the tolerance and no further: a sample read near a singularity is
        # closed again (polished) by the refinement that locates it
        Q, ok, it = pb.close_near(Qp, SWEEP_JUMP_RATIO * span_a[sl], polish=False)
        Q[~ok] = np.nan
        for m, tr in enumerate(traces):
            mine = which_a[sl] == m
            if not np.any(mine):
                continue
            tr.Z[rows_a[sl][mine]] = Q[mine]
            assert tr.newton is not None
            tr.newton[rows_a[sl][mine]] += it[mine]


class _Arc:
    """Pseudo-arclength continuation of a path's curve: the swept coordinate is solved
    with the unknown ones, and one more equation fixes the step along the tangent."""

    def __init__(self, pb: Problem, col: int, direction: int) -> None:
        self.pb = pb
        self.cm = pb.cm
        self.col = col
        self.direction = direction
        free = ~pb.given.copy()
        free[col] = True
        self.free = free
        self.cidx = int(np.flatnonzero(free).tolist().index(col))
        self.why: str | None = None
        #: the points of the curve traced by :meth:`to_fold_or`, in order
        self.trail: list[np.ndarray] = []
        #: the curve's tangent at the fold :meth:`to_fold_or` found, along the way it
        #: came (the way on past the fold, whatever the step that found it)
        self.fold_tangent: np.ndarray | None = None

    # -- the curve ------------------------------------------------------------------

    def tangent(self, z: np.ndarray, prev: np.ndarray | None = None) -> np.ndarray | None:
        """The unit commensurate tangent (free coordinates) at z, oriented along ``prev``
        (or with the swept value increasing in the path's direction); None when the
        curve is not one-dimensional there."""
        Js, _ = scaled_system(self.cm, z)
        A = Js[:, self.free]
        _, s, Vt = np.linalg.svd(A, full_matrices=True)
        rank = int(np.sum(s > 1e-9 * (s[0] if len(s) else 1.0)))
        K = Vt[rank:]
        if K.shape[0] == 0:
            return None
        if K.shape[0] > 1:
            if prev is None:
                self.why = "the path's curve has more freedom than the swept value"
                return None
            t = K.T @ (K @ prev)  # the kernel direction nearest the previous tangent
            nt = np.linalg.norm(t)
            if nt < 0.5:
                return None
            t = t / nt
        else:
            t = K[0]
        if prev is not None:
            return t if t @ prev >= 0 else -t
        return t if t[self.cidx] * self.direction >= 0 else -t

    def step(self, z: np.ndarray, tau: np.ndarray, h: float) -> np.ndarray | None:
        """The point of the curve at arclength ``h`` along ``tau`` from z (None when
        Newton does not close it)."""
        cm, free = self.cm, self.free
        fr = cm.float_frame
        d = np.zeros(cm.n)
        d[free] = h * tau
        zp = cm.update(z, fr.rates_back(d))
        zc = zp
        tol = self.pb.tolerance
        for _ in range(_ARC_NEWTON):
            Js, rs = scaled_system(cm, zc)
            off = fr.rates(cm.difference(zc, zp))[free]
            A = np.vstack([Js[:, free], tau[None, :]])
            b = np.concatenate([-rs, [-(tau @ off)]])
            du, *_ = np.linalg.lstsq(A, b, rcond=None)
            dd = np.zeros(cm.n)
            dd[free] = du
            zc = cm.update(zc, fr.rates_back(dd))
            res = cm.residual_norm(cm.chord_residuals(zc))
            if res <= tol and np.linalg.norm(du) <= 1e-13 + 1e-9 * abs(h):
                return zc
        res = cm.residual_norm(cm.chord_residuals(zc))
        return zc if res <= tol else None

    def _g(self, tau: np.ndarray) -> float:
        return float(tau[self.cidx]) * self.direction

    def _advance(
        self, z: np.ndarray, tau: np.ndarray, h: float
    ) -> tuple[np.ndarray, np.ndarray, float] | None:
        """One accepted step (the step halved until Newton closes and the tangent turns
        less than 30 degrees); (z, tangent, step taken)."""
        while h >= SWEEP_ARC_MIN_STEP:
            zn = self.step(z, tau, h)
            if zn is not None:
                tn = self.tangent(zn, tau)
                if tn is not None and tn @ tau > math.cos(math.radians(30)):
                    return zn, tn, h
            h /= 2
        self.why = "the path's curve could not be followed (a singular point of the curve)"
        return None

    def _turn(self, z: np.ndarray, tau: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
        """The fold between z (g > 0) and its step h (g <= 0): Brent on g(s)."""
        from scipy.optimize import brentq

        cache: dict[float, tuple[np.ndarray, np.ndarray]] = {0.0: (z, tau)}

        def g(s: float) -> float:
            if s == 0.0:  # z itself (the fold when the path starts on it)
                return self._g(tau)
            zs = self.step(z, tau, s)
            ts = None if zs is None else self.tangent(zs, tau)
            if zs is None or ts is None:
                raise _Lost
            cache[s] = (zs, ts)
            return self._g(ts)

        try:
            s = brentq(g, 0.0, h, xtol=SWEEP_LOCATE_TOL, rtol=4 * np.finfo(float).eps)
        except (_Lost, ValueError):
            s = h
        if s not in cache:
            try:
                g(s)
            except _Lost:
                return cache[0.0]
        return cache[s]

    # -- what the path asks ---------------------------------------------------------

    def to_fold_or(self, z: np.ndarray, stop: float) -> tuple[str, np.ndarray] | None:
        """From z, along the curve: the first fold before the swept value reaches
        ``stop`` ("fold", its configuration), or the configuration at ``stop`` when the
        curve gets there without one ("passed").  The samples passed on the way are
        not closed here (the caller closes them); None when the curve is lost."""
        tau = self.tangent(z)
        self.trail = [z]
        if tau is None:
            return None
        if self._g(tau) <= 0:
            self.fold_tangent = tau
            return "fold", z
        h = SWEEP_ARC_STEP
        for _ in range(_ARC_BUDGET):
            out = self._advance(z, tau, h)
            if out is None:
                return None
            zn, tn, h = out
            if self._g(tn) <= 0:
                zf, self.fold_tangent = self._turn(z, tau, h)
                return "fold", zf
            self.trail.append(zn)
            if (zn[self.col] - stop) * self.direction >= 0:
                zs = self._reach(z, stop)
                if zs is None:
                    return None
                return "passed", zs
            z, tau = zn, tn
            h = min(2 * h, _ARC_LONGEST)
        self.why = "the path's curve is longer than sweeps follow"
        return None

    def _reach(self, z: np.ndarray, value: float) -> np.ndarray | None:
        """The curve's point with the swept value ``value``, by continuation from z."""
        try:
            return self.pb.reach(z, self.col, value)
        except ClosureError:
            return None

    def other_side(
        self, zf: np.ndarray, values: np.ndarray, last: int
    ) -> tuple[Fold, int, np.ndarray] | None:
        """Past the fold at zf, the curve on the other assembly mode up to its next fold;
        beyond that the swept value moves forward again: the next sample it reaches
        (modulo 2 pi for a revolute angle) and its configuration, with the far fold."""
        h = SWEEP_ARC_STEP
        z = zf
        if self.fold_tangent is not None:
            # on along the curve the way it came into the fold (the kernel direction
            # nearest it where several chains reach their limit there together)
            tau = self.tangent(zf, self.fold_tangent)
            if tau is None:
                return None
        else:
            tau = self.tangent(zf)
            if tau is None:
                return None
            # orient along the curve away from where the path came from
            probe = self.step(z, tau, h)
            if probe is not None and (probe[self.col] - zf[self.col]) * self.direction > 0:
                tau = -tau
        passed = False
        for _ in range(_ARC_BUDGET):
            out = self._advance(z, tau, h)
            if out is None:
                return None
            zn, tn, h = out
            g = self._g(tn)
            if (
                not passed
                and g > 0
                and np.linalg.norm(self.cm.float_frame.rates(self.cm.difference(zn, zf)))
                > 10 * SWEEP_ARC_MIN_STEP
            ):
                zfar, _ = self._turn_back(z, tau, h)
                passed = True
                far = Fold(float(zfar[self.col]), zfar, -self.direction, far_side=True)
                z, tau = zn, tn
                continue
            if passed:
                # moving forward again: the next sample this value reaches
                wrap = 2 * math.pi if self.pb.periodic[self.col] else None
                nxt = _next_sample(values, last, zn[self.col], self.direction, wrap)
                if nxt is None:
                    self.why = "the rest of the range is beyond the limits of travel"
                    return None
                k, shift = nxt
                zs = zn.copy()
                zs[self.col] += shift
                zk = self._reach(zs, values[k])
                if zk is None:
                    return None
                far = Fold(float(far.value + shift), far.z.copy(), far.direction, far_side=True)
                far.z[self.col] += shift
                return far, k, zk
            z, tau = zn, tn
            h = min(2 * h, _ARC_LONGEST)
        self.why = "the curve past the limit does not come back within the range"
        return None

    def _turn_back(self, z: np.ndarray, tau: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
        self.direction = -self.direction
        try:
            return self._turn(z, tau, h)
        finally:
            self.direction = -self.direction


def _next_sample(
    values: np.ndarray, last: int, v: float, direction: int, wrap: float | None
) -> tuple[int, float] | None:
    """The first sample after ``last`` that a swept value moving forward from v reaches,
    and the multiple of ``wrap`` (a full turn, when given) that takes v into the rest
    of the range: (index, shift)."""
    for k in range(last + 1, len(values)):
        if wrap is None:
            # the value comes back only beyond where the path stopped
            if (v - values[last]) * direction > 0 and (values[k] - v) * direction >= 0:
                return k, 0.0
            continue
        # the turn count m with v + m wrap after values[last] and at or before values[k]
        m = math.floor((values[k] - v) / wrap * direction) * direction
        vv = v + m * wrap
        if (vv - values[last]) * direction > 0 and (values[k] - vv) * direction >= 0:
            return k, m * wrap
    return None


class _Lost(Exception):
    """The curve was lost while locating a fold."""
