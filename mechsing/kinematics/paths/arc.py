"""Following a path's curve itself: pseudo-arclength continuation through folds.

Owns :class:`Arc` (the swept coordinate solved with the unknown ones, one more equation
fixing the step along the tangent), the curve's tangent (:func:`curve_tangent`) and the
ways off a singular start along the curve (:func:`off_singular` at a fold,
:func:`onto_branch` where branches cross).  Where continuation in the swept value cannot
go on, a path follows its curve: a fold of the swept value (a limit of its travel: a dead
centre, the end of a rocker's swing, a :class:`~.folds.Fold`) is where the tangent's
swept component changes sign, located by the crossing locator on that component
(:func:`~.crossing.locate_crossing`); past it the curve comes back on the other assembly
mode (:meth:`Arc.other_side`: turned onto it by the engine's one turning at a fold,
:func:`~.folds.leave_fold`, then followed) to its next fold, after which the swept value
moves forward again (modulo 2 pi for a revolute angle).
"""

from __future__ import annotations

import math

import numpy as np

from mechsing.errors import ClosureError
from mechsing.kinematics.newton import scaled_jacobian, scaled_system
from mechsing.kinematics.paths.crossing import locate_crossing
from mechsing.kinematics.paths.folds import Fold, leave_fold
from mechsing.kinematics.paths.problem import Problem
from mechsing.kinematics.settings import (
    SWEEP_ARC_MAX_TURN_DEG,
    SWEEP_ARC_MIN_STEP,
    SWEEP_ARC_STEP,
    SWEEP_ARC_STEP_ATOL,
    SWEEP_ARC_STEP_RTOL,
    SWEEP_BRANCH_MIN_SWEPT,
    SWEEP_CURVE_RANK_RTOL,
    SWEEP_LOCATE_TOL,
    SWEEP_TANGENT_KEPT,
)
from mechsing.numeric.blocks import dense_svd

__all__ = ["Arc", "curve_tangent", "off_singular", "onto_branch"]

#: tangents a Problem keeps (a row's start asks for the same one up to three times, and
#: the rows of a grid are started together: a chunk of rows' starts, then their first
#: nodes; a tangent is a few hundred bytes)
_TANGENTS_KEPT = 4096
#: most arclength steps spent on the far side of one fold
_ARC_BUDGET = 4000
#: the longest step along a curve (commensurate): the tangent may turn less than
#: SWEEP_ARC_MAX_TURN_DEG degrees per step, which shortens it where the curve bends
_ARC_LONGEST = 10 * SWEEP_ARC_STEP
#: Newton iterations of one arclength step
_ARC_NEWTON = 10
#: the step (commensurate arclength) that leaves a singular start along its curve
_OFF_SINGULAR_STEP = 1e-3
#: a start where branches cross: directions tried over the kernel
_BRANCH_DIRECTIONS = 24


class Arc:
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
        Js = scaled_jacobian(self.cm, z)
        A = Js[:, self.free]
        _, s, Vt = dense_svd(A, full_matrices=True)
        rank = int(np.sum(s > SWEEP_CURVE_RANK_RTOL * (s[0] if len(s) else 1.0)))
        K = Vt[rank:]
        if K.shape[0] == 0:
            return None
        if K.shape[0] > 1:
            if prev is None:
                self.why = "the path's curve has more freedom than the swept value"
                return None
            t = K.T @ (K @ prev)  # the kernel direction nearest the previous tangent
            nt = np.linalg.norm(t)
            if nt < SWEEP_TANGENT_KEPT:
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
        settled = SWEEP_ARC_STEP_ATOL + SWEEP_ARC_STEP_RTOL * abs(h)
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
            if res <= tol and np.linalg.norm(du) <= settled:
                return zc
        res = cm.residual_norm(cm.chord_residuals(zc))
        return zc if res <= tol else None

    def _g(self, tau: np.ndarray) -> float:
        return float(tau[self.cidx]) * self.direction

    def _advance(
        self, z: np.ndarray, tau: np.ndarray, h: float
    ) -> tuple[np.ndarray, np.ndarray, float] | None:
        """One accepted step (the step halved until Newton closes and the tangent turns
        less than SWEEP_ARC_MAX_TURN_DEG degrees); (z, tangent, step taken)."""
        while h >= SWEEP_ARC_MIN_STEP:
            zn = self.step(z, tau, h)
            if zn is not None:
                tn = self.tangent(zn, tau)
                if tn is not None and tn @ tau > math.cos(math.radians(SWEEP_ARC_MAX_TURN_DEG)):
                    return zn, tn, h
            h /= 2
        self.why = "the path's curve could not be followed (a singular point of the curve)"
        return None

    def _turn(self, z: np.ndarray, tau: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
        """The fold between z (g > 0) and its step h (g <= 0): where the tangent's swept
        component changes sign (:func:`~.crossing.locate_crossing`); the step h itself
        when the curve is lost on the way."""
        cache: dict[float, tuple[np.ndarray, np.ndarray]] = {0.0: (z, tau)}

        def g(s: float) -> float | None:
            if s == 0.0:  # z itself (the fold when the path starts on it)
                return self._g(tau)
            zs = self.step(z, tau, s)
            ts = None if zs is None else self.tangent(zs, tau)
            if zs is None or ts is None:
                return None
            cache[s] = (zs, ts)
            return self._g(ts)

        s = locate_crossing(g, 0.0, h, SWEEP_LOCATE_TOL)
        if s is None:
            s = h
        if s not in cache and g(s) is None:
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
        """Past the fold at zf, the curve on the other assembly mode (turned onto by
        :func:`~.folds.leave_fold` along the way the path came) up to its next fold;
        beyond that the swept value moves forward again: the next sample it reaches
        (modulo 2 pi for a revolute angle) and its configuration, with the far fold."""
        h = SWEEP_ARC_STEP
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
            probe = self.step(zf, tau, h)
            if probe is not None and (probe[self.col] - zf[self.col]) * self.direction > 0:
                tau = -tau
        # the turn onto the other assembly mode (:func:`~.folds.leave_fold`, as a start
        # at a fold turns): the swept value moved back by so little that the joints move
        # about _OFF_SINGULAR_STEP along tau
        z = self._turned(zf, tau)
        if z is None:
            return None
        tau = self.tangent(z, tau)
        if tau is None:
            return None
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

    def _turned(self, zf: np.ndarray, tau: np.ndarray) -> np.ndarray | None:
        """The point of the curve past the fold zf along its tangent tau there (free
        coordinates), by the engine's one turning at a fold (:func:`~.folds.leave_fold`)."""
        target = np.array(zf, dtype=float)
        target[self.col] -= self.direction * _OFF_SINGULAR_STEP**2 * self.pb.scale(self.col)
        toward = np.zeros(self.pb.n)
        toward[self.free] = tau
        _, z = leave_fold(self.cm, zf, target, self.pb.given, 1.0, toward)
        if z is None:
            self.why = "the path's curve could not be turned at the limit of travel"
        return z

    def _turn_back(self, z: np.ndarray, tau: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
        self.direction = -self.direction
        try:
            return self._turn(z, tau, h)
        finally:
            self.direction = -self.direction


def curve_tangent(pb: Problem, z: np.ndarray, col: int) -> np.ndarray | None:
    """The unit commensurate tangent of the path's curve at the closed z (every
    coordinate of cm, zero on the given ones but ``col``; its sign arbitrary), or None
    where the curve is not one-dimensional.  The last ones are kept (in ``pb.tangents``):
    a row's start asks for it once to check that it can leave and once per direction."""
    key = (col, np.asarray(z, dtype=float).tobytes())
    if key in pb.tangents:
        return pb.tangents[key]
    arc = Arc(pb, col, 1)
    t = arc.tangent(np.asarray(z, dtype=float))
    out = None
    if t is not None:
        out = np.zeros(pb.n)
        out[arc.free] = t
    if len(pb.tangents) >= _TANGENTS_KEPT:
        pb.tangents.pop(next(iter(pb.tangents)))
    pb.tangents[key] = out
    return out


def off_singular(pb: Problem, z: np.ndarray, col: int, value: float) -> np.ndarray | None:
    """From a start at a fold of the swept value (continuation has no direction there):
    turned at the fold onto the assembly mode that goes towards ``value``, as continuation
    leaves a start drawn at a fold (:func:`~.folds.leave_fold`: the swept value moved by
    so little that the joints move about _OFF_SINGULAR_STEP along the kernel), then along
    the path's curve to ``value`` (near a fold the joints move like the square root of
    the swept value: continuation in the swept value cannot leave it).  None when the
    start is not such a fold or the curve does not get there."""
    z = np.asarray(z, dtype=float)
    d = 1 if value > z[col] else -1
    target = z.copy()
    target[col] = value
    span = abs(value - float(z[col])) / pb.scale(col)
    if span == 0.0:
        return None
    _, left = leave_fold(pb.cm, z, target, pb.given, min(1.0, _OFF_SINGULAR_STEP**2 / span))
    if left is None:
        return None
    out = Arc(pb, col, d).to_fold_or(left, value)
    if out is not None and out[0] == "passed":
        return np.asarray(out[1], dtype=float)
    return None


def onto_branch(pb: Problem, z: np.ndarray, col: int, value: float) -> np.ndarray | None:
    """From a start where branches cross (the curve of the path has a kernel of more
    than one direction there, as at a change-point four-bar's flat position): the
    branches leave along some directions of that kernel.  A short pseudo-arclength
    step is tried along directions spread over it (towards ``value``); the step whose
    corrector moves least lies on a branch, and the path goes on from there to
    ``value`` along the curve (None when none does)."""
    d = 1 if value > z[col] else -1
    arc = Arc(pb, col, d)
    z = np.asarray(z, dtype=float)
    Js = scaled_jacobian(pb.cm, z)
    _, s, Vt = dense_svd(Js[:, arc.free], full_matrices=True)
    K = Vt[int(np.sum(s > SWEEP_CURVE_RANK_RTOL * (s[0] if len(s) else 1.0))) :]
    if K.shape[0] < 2:
        return None
    fr = pb.cm.float_frame
    best: tuple[float, np.ndarray] | None = None
    for th in np.linspace(0.0, math.pi, _BRANCH_DIRECTIONS, endpoint=False):
        tau = math.cos(th) * K[0] + math.sin(th) * K[1]
        if abs(tau[arc.cidx]) < SWEEP_BRANCH_MIN_SWEPT:
            continue  # hardly moves the swept value
        tau = tau if tau[arc.cidx] * d > 0 else -tau
        zn = arc.step(z, tau, _OFF_SINGULAR_STEP)
        if zn is None or (zn[col] - z[col]) * d <= 0 or arc.tangent(zn) is None:
            continue
        moved = np.zeros(pb.cm.n)
        moved[arc.free] = _OFF_SINGULAR_STEP * tau
        off = float(np.linalg.norm(fr.rates(pb.cm.difference(zn, z)) - moved))
        if best is None or off < best[0]:
            best = (off, zn)
    if best is None:
        return None
    out = Arc(pb, col, d).to_fold_or(best[1], value)
    if out is None or out[0] != "passed":
        return None
    return np.asarray(out[1], dtype=float)


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
