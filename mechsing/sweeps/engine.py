"""The sweep itself: paths and grids, their measures, and the singularities located on them.

Owns :class:`Sweep` (the problem of one sweep, built once) and the row-by-row work:

* a **path** (one swept variable) starts at the sample nearest the ``--from``
  configuration's value (reached from it by continuation), and is followed forward to
  the end of the range and back to its beginning (:func:`mechsing.sweeps.path.follow`);
* a **grid** (two) is rows of paths in the first variable, each started from a first
  column (a path in the second variable at the first variable's start sample); the rows
  are computed in chunks (:meth:`Sweep.rows_of`): their batched Newton calls, measures
  and refinements are shared by the chunk's rows, each row's result that of the row
  alone;
* every reached sample gets the float measures of :class:`~.measures.Measures`;
* along a row, every sign change of a test's compressed determinant between two
  samples is refined by Brent's method, every sampled minimum that could hide a zero
  by golden-section search, and every fold comes located from the path; between rows of
  a grid, the sign changes along the columns are refined the same way (they make the
  loci, with the rows' points);
* each located point is classified by the full analysis at the sweep's precision
  (:func:`mechsing.analysis.analyze_found`).

Which coordinates a sweep holds: a sweep of joint coordinates that are all inputs holds
the other inputs at their ``--from`` values and solves the passive joints; a sweep of a
joint that is not an input lets it drive the mechanism alone (the inputs are solved
with the passive joints); a sweep of the output's pose holds the other pose coordinates
and solves every joint (the inverse kinematics of a parallel robot).  A mechanism
without loops solves nothing: every other coordinate keeps its ``--from`` value.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from mechsing.analysis import analyze, analyze_found
from mechsing.errors import ClosureError, UserError
from mechsing.kinematics import Closer, KinematicModel
from mechsing.kinematics.batch_newton import BatchClosure
from mechsing.kinematics.newton import scaled_system
from mechsing.kinematics.pose import PoseModel
from mechsing.lie import log_so3
from mechsing.model import Mechanism
from mechsing.model.couplings import describe_coupling
from mechsing.numeric import (
    SWEEP_BRANCH_OFFSET,
    SWEEP_JUMP_RATIO,
    SWEEP_LOCATE_TOL,
    SWEEP_MINIMUM_SCREEN,
    Precision,
    dispatch,
    to_float,
)
from mechsing.sweeps.limits import limited_coordinates, outside
from mechsing.sweeps.measures import Measures, PointMeasures
from mechsing.sweeps.path import (
    Fold,
    PathTrace,
    Problem,
    _Arc,
    _nodes,
    close_segments,
    first_nodes_of,
    follow,
    follow_together,
)
from mechsing.sweeps.spec import Variable

__all__ = ["Located", "RowResult", "Sweep"]

_TAU_LO = Precision("float").tolerances.tau_lo
_TAU_HI = Precision("float").tolerances.tau_hi
#: most regula falsi steps of one crossing (superlinear: about ten are needed)
_ILLINOIS_ITERATIONS = 60

#: the samples nearest the start's value tried as the sweep's first (the start may be at a
#: limit of travel, with its nearest samples beyond it)
_START_TRIES = 4
#: the tests a fold is listed under: those whose measure there is below this (a fold is
#: located on the path's curve to rounding, where the vanishing measure is ~1e-12 or
#: less; the others stay of order one)
_FOLD_TEST_RTOL = 1e-6
#: a swept pose coordinate is refused when adding its column raises the rank of the
#: closure system in the solved joints by a singular value above this (relative)
_DETERMINED_RTOL = 1e-8
#: the step (commensurate arclength) that leaves a singular start along its curve
_OFF_SINGULAR_STEP = 1e-3
#: most steps of a walk towards a singular point the path passes through
_WALK_STEPS = 60
#: most samples of a reached row tried to start a neighbouring row the first column misses
_BRIDGE_TRIES = 6
#: a start where branches cross: directions tried over the kernel, the smallest share of
#: the swept value in one of them, and the relative size of a kernel singular value
_BRANCH_DIRECTIONS = 24
_BRANCH_MIN_SWEPT = 0.05
_KERNEL_RTOL = 1e-9
#: measures are computed this many configurations at a time (bounds the working memory)
_CHUNK = 4096
#: rows of a grid followed, measured and refined together hold about this many samples
_ROWS_SAMPLES = 8192
#: ... and at most about this many bytes of their measures (a big mechanism's matrices)
_ROWS_BYTES = 64 * 2**20


@dataclass
class Located:
    """A singularity located on a sweep, before its classification: the swept values
    (SI), how it was found (``fold``, ``crossing``, ``minimum``), the tests whose measure
    vanishes there, the refined measure, the configuration (joint coordinates), and for
    a grid the row and column it lies between (``edge``: "row" or "column")."""

    values: tuple[float, ...]
    kind: str
    tests: tuple[str, ...]
    ratio: float
    q: np.ndarray
    row: int = 0
    edge: str = "row"
    cell: tuple[int, int] = (0, 0)
    far_side: bool = False
    #: the sweep's coordinates there (joints, then the pose's for a pose sweep)
    z: np.ndarray | None = None


@dataclass
class RowResult:
    """One row of a sweep (the whole path for a path): the reached samples, each test's
    rank and measure there, the located points, and why the row stopped early."""

    index: int
    reached: np.ndarray
    rank: dict[str, np.ndarray]
    ratio: dict[str, np.ndarray]
    located: list[Located]
    stopped: list[str] = field(default_factory=list)
    newton: int = 0
    Z: np.ndarray | None = None
    measures: PointMeasures | None = None
    #: limited coordinate -> the samples beyond its limits (:mod:`mechsing.sweeps.limits`)
    outside: dict[str, np.ndarray] = field(default_factory=dict)


class Sweep:
    """One sweep's problem: the model, what is held and swept, the start, the measures."""

    def __init__(
        self, mech: Mechanism, variables: list[Variable], from_config: str | None = None
    ) -> None:
        self.mech = mech
        self.variables = variables
        self.from_config = from_config or "reference"
        if self.from_config not in mech.configurations:
            raise UserError(
                f"{mech.path or mech.name}: --from {self.from_config!r}: no such configuration; "
                f"the file has: {', '.join(mech.configurations)}"
            )
        model = KinematicModel(mech, "float")
        self.model = model
        self.limited = limited_coordinates(mech)
        closer = Closer(model)
        q0 = np.asarray(to_float(closer.solve(self.from_config).q), dtype=float)
        self.pose = variables[0].kind == "pose"
        n = model.n
        if self.pose:
            c0 = [float(x) for x in to_float(np.array(mech.output_reference_point(), dtype=object))]
            cm: Any = PoseModel(model, c0, np.eye(3))
            g = cm.output_pose(np.concatenate([q0, np.zeros(6)]))
            r0 = log_so3(g[:3, :3])
            x0 = g[:3, :3] @ np.array(c0) + g[:3, 3]
            z0 = np.concatenate([q0, r0, x0])
            given = np.zeros(cm.n, dtype=bool)
            given[n:] = True
            cols = [n + v.column for v in variables]
        else:
            cm = model
            z0 = q0
            cols = [v.column for v in variables]
            inputs = {model.joint(j).columns.start + i for j, i in mech.input_coordinates()}
            given = np.zeros(n, dtype=bool)
            if not mech.loops:
                given[:] = True
            elif set(cols) <= inputs:
                given[list(inputs)] = True
            given[cols] = True
            for ck in model.couplings:
                # a coupled joint follows its swept partner (never held against it)
                swept = {ck.follower, ck.leader} & set(cols)
                if len(swept) == 2:
                    c = ck.coupling
                    raise UserError(
                        f"--vary: joint {c.joint!r} is coupled to {c.leader!r} "
                        f"({describe_coupling(c)}): sweep one of them, the other follows"
                    )
                for k in {ck.follower, ck.leader} - swept if swept else ():
                    given[k] = False
        self.cols = cols
        self.z0 = z0
        #: said once, in the first row's notes: how the path left a singular start
        self.start_notes: list[str] = []
        periodic = np.zeros(cm.n, dtype=bool)
        for v, c in zip(variables, cols, strict=True):
            periodic[c] = v.periodic
        self.problem = Problem(
            model,
            cm,
            given,
            closer,
            BatchClosure(cm),
            model.precision.closure_tolerance(model.length_scale),
            periodic,
        )
        self.generic_mobility: int | None = None
        self.measures = Measures(model, self._generic())
        self._check_determined()

    def _check_determined(self) -> None:
        """A sweep whose path is not a curve is refused before it starts: holding the
        given coordinates must leave one degree of freedom to the swept one (a joint
        sweep), and the output must be able to move along a swept pose coordinate with
        the rest of its pose held."""

        mech, pb = self.mech, self.problem
        names = ", ".join(v.name for v in self.variables)
        M = self.generic_mobility
        if not mech.loops or M is None:
            return
        if not self.pose:
            g = int(np.sum(pb.given))
            inputs = ", ".join(
                j if mech.joint(j).dof == 1 else f"{j}[{i}]" for j, i in mech.input_coordinates()
            )
            if g < M:
                raise UserError(
                    f"--vary {names}: with the other coordinates solved, the mechanism keeps "
                    f"{M - g} more degree(s) of freedom (its mobility is {M}), so the sweep's path "
                    "is not determined; sweep an input of the file"
                    + (f" ({inputs}): the others are then held" if inputs else "")
                    + ", or declare inputs (inputs: [...]) so that the sweep holds them"
                )
            if g > M:
                raise UserError(
                    f"--vary {names}: the file's inputs ({inputs}) are {g} coordinates for a "
                    f"mechanism of mobility {M}; held at their start values they leave the swept "
                    "one no motion; sweep a mechanism whose inputs match its mobility"
                )
            return
        Js, _ = scaled_system(pb.cm, self.z0)
        free = ~pb.given
        A = Js[:, free]
        for v, c in zip(self.variables, self.cols, strict=True):
            B = np.concatenate([A, Js[:, [c]]], axis=1)
            sa = np.linalg.svd(A, compute_uv=False)
            sb = np.linalg.svd(B, compute_uv=False)
            ra = int(np.sum(sa > _DETERMINED_RTOL * sb[0]))
            rb = int(np.sum(sb > _DETERMINED_RTOL * sb[0]))
            if rb > ra:
                raise UserError(
                    f"--vary {v.name}: the output {mech.output.body!r} cannot move along "
                    f"{v.name} with the rest of its pose held (its motion at {self.from_config!r} "
                    "does not contain that direction: the mechanism moves its output in a "
                    "smaller set of displacements); sweep a pose coordinate the output can "
                    "move along, or a joint"
                )

    # ------------------------------------------------------------------ generic ranks

    def _generic(self) -> dict[str, int | None]:
        """Each test's generic rank, from the full float analysis of the start."""
        res = analyze(self.mech, [self.from_config], "float").configurations[0]
        dec = {d.test: d for d in res.decisions}
        n = self.model.n
        out: dict[str, int | None] = {}
        if res.mobility is not None:
            self.generic_mobility = res.mobility.generic
        if self.mech.loops and res.mobility is not None and res.mobility.generic is not None:
            out["closure"] = n - res.mobility.generic
        for test, name in (("input", "impossible-output"), ("output", "impossible-input")):
            if name in dec:
                out[test] = dec[name].generic
        if "output chain" in dec:  # no loop: T N is the output chain's matrix
            out["input"] = dec["output chain"].generic
            out["output"] = len(self.mech.input_coordinates()) or None
        if "constraint" in dec:
            out["constraint"] = dec["constraint"].generic
        return out

    @property
    def tests(self) -> tuple[str, ...]:
        return self.measures.tests

    # ------------------------------------------------------------------ closing

    def scale(self, col: int) -> float:
        return self.problem.scale(col)

    def start_of(self, col: int, values: np.ndarray, z: np.ndarray) -> tuple[int, np.ndarray]:
        """The sample nearest z's value of ``col`` that can be reached from z (the start
        may be at a limit of travel, its nearest sample beyond it), and its configuration."""
        order = np.argsort(np.abs(values - z[col]), kind="stable")
        k0 = int(order[0])
        if z[col] == values[k0]:
            if self.problem.tangent(np.asarray(z, dtype=float), col) is not None:
                return k0, np.array(z, dtype=float)
            # a start where branches cross (a bifurcation): onto one of them
            for k in (k0 + 1, k0 - 1):
                if 0 <= k < len(values):
                    off = self._onto_branch(z, col, float(values[k]))
                    if off is not None:
                        return k, off
            return k0, np.array(z, dtype=float)
        first: ClosureError | None = None
        for k in order[:_START_TRIES]:
            try:
                return int(k), self.problem.reach(z, col, values[k])
            except ClosureError as exc:
                first = first or exc
            # a start at a fold or another singular point: step off it along the curve
            off = self._off_singular(z, col, float(values[k]))
            if off is None:
                off = self._onto_branch(z, col, float(values[k]))
            if off is not None:
                return int(k), off
        var = self._variable(col)
        assert first is not None
        why = str(first).split(": ", 1)[-1]
        raise ClosureError(
            f"the sweep cannot start: none of the {min(_START_TRIES, len(values))} samples of "
            f"{var.name} nearest its value at {self.from_config!r} ({var.shown(z[col])}) can be "
            f"reached from that configuration on its assembly mode ({why}); start from another "
            "configuration (--from) or sweep a range that contains the start's value",
            self.from_config,
            first.residual,
        ) from None

    def _off_singular(self, z: np.ndarray, col: int, value: float) -> np.ndarray | None:
        """From a singular start (a fold: continuation has no direction there), a short
        step along the path's curve towards ``value``, then continuation to it."""
        d = 1 if value > z[col] else -1
        arc = _Arc(self.problem, col, d)
        tau = arc.tangent(np.asarray(z, dtype=float))
        if tau is None:
            return None
        for sign in (1.0, -1.0):
            zn = arc.step(np.asarray(z, dtype=float), sign * tau, _OFF_SINGULAR_STEP)
            if zn is None or (zn[col] - z[col]) * d <= 0:
                continue
            # along the curve (near a fold the joints move like the square root of the
            # swept value: continuation in the swept value cannot leave it)
            out = _Arc(self.problem, col, d).to_fold_or(zn, value)
            if out is not None and out[0] == "passed":
                return np.asarray(out[1], dtype=float)
        return None

    def _onto_branch(self, z: np.ndarray, col: int, value: float) -> np.ndarray | None:
        """From a start where branches cross (the curve of the path has a kernel of more
        than one direction there, as at a change-point four-bar's flat position): the
        branches leave along some directions of that kernel.  A short pseudo-arclength
        step is tried along directions spread over it (towards ``value``); the step whose
        corrector moves least lies on a branch, and the path goes on from there to
        ``value`` along the curve.  The branch taken is said in the sweep's notes."""
        pb = self.problem
        d = 1 if value > z[col] else -1
        arc = _Arc(pb, col, d)
        z = np.asarray(z, dtype=float)
        Js, _ = scaled_system(pb.cm, z)
        _, s, Vt = np.linalg.svd(Js[:, arc.free], full_matrices=True)
        K = Vt[int(np.sum(s > _KERNEL_RTOL * (s[0] if len(s) else 1.0))) :]
        if K.shape[0] < 2:
            return None
        fr = pb.cm.float_frame
        best: tuple[float, np.ndarray] | None = None
        for th in np.linspace(0.0, math.pi, _BRANCH_DIRECTIONS, endpoint=False):
            tau = math.cos(th) * K[0] + math.sin(th) * K[1]
            if abs(tau[arc.cidx]) < _BRANCH_MIN_SWEPT:
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
        out = _Arc(pb, col, d).to_fold_or(best[1], value)
        if out is None or out[0] != "passed":
            return None
        var = self._variable(col)
        self.start_notes.append(
            f"the start {self.from_config!r} is a singular point where branches of the path "
            f"cross ({var.name} = {var.shown(float(z[col]))}): the path follows one of them; "
            "start from a configuration on a branch (--from) to choose"
        )
        return np.asarray(out[1], dtype=float)

    def _variable(self, col: int) -> Variable:
        return self.variables[self.cols.index(col)]

    def close_at(self, za: np.ndarray, zb: np.ndarray, col: int, t: float) -> np.ndarray:
        """The configuration with ``col`` at t between two closed neighbours za, zb (their
        interpolation closed by Newton; by continuation from za when that jumps)."""
        pb = self.problem
        ta, tb = za[col], zb[col]
        f = 0.0 if tb == ta else (t - ta) / (tb - ta)
        zp = pb.batch.between(za[None, :], zb[None, :], np.array([f]))[0]
        zp[col] = t
        span = pb.comm(pb.cm.difference(zb, za))
        Q, ok, _ = pb.close_near(zp[None, :], SWEEP_JUMP_RATIO * max(span, 1e-300))
        if ok[0]:
            return Q[0]
        # along the path from za by the tangent in halved steps, then the careful
        # continuation
        walked = _nodes(pb, np.asarray(za, dtype=float), None, col, t)
        return walked if walked is not None else pb.reach(za, col, t)

    # ------------------------------------------------------------------ rows

    def row(self, index: int, col: int, values: np.ndarray, z: np.ndarray) -> RowResult:
        """One path in ``col`` through ``values`` from the closed z (at any value of col),
        with its measures and the singularities located along it."""
        return self.rows_of([(index, z)], col, values)[0]

    def rows_of(
        self, starts: list[tuple[int, np.ndarray]], col: int, values: np.ndarray
    ) -> list[RowResult]:
        """:meth:`row` of several rows of a grid (each its index and closed configuration
        at any value of ``col``), the rows' batched work done together: their first
        nodes in one batched Newton, the samples between their nodes in one, their
        measures in one batch, and the crossings along them refined together.  Each row
        is followed, measured and refined exactly as alone (every batched step is per
        configuration)."""
        pb = self.problem
        K = len(values)
        begun = [self.start_of(col, values, z) for _, z in starts]
        # the first node of each direction of each row: one batched Newton
        firsts = first_nodes_of(pb, [(zk, [values[k0:], values[k0::-1]]) for k0, zk in begun], col)
        # both directions of every row, node by node in lockstep
        flat = follow_together(
            pb,
            col,
            [
                (zk, v, f)
                for (k0, zk), first in zip(begun, firsts, strict=True)
                for v, f in ((values[k0:], first[0]), (values[k0::-1], first[1]))
            ],
        )
        traces: list[tuple[PathTrace, PathTrace]] = list(zip(flat[0::2], flat[1::2], strict=True))
        # the samples between the nodes of every row's two directions: one batched Newton
        close_segments(
            pb,
            [tr for pair in traces for tr in pair],
            col,
            [[2 * r, 2 * r + 1] for r in range(len(traces))],
        )
        Zs, reacheds = [], []
        for (k0, _), (fwd, bwd) in zip(begun, traces, strict=True):
            Z = np.full((K, pb.n), np.nan)
            Z[k0:] = fwd.Z
            Z[: k0 + 1] = bwd.Z[::-1]
            Zs.append(Z)
            reacheds.append(~np.isnan(Z[:, 0]))
        pm_all, offsets = self._measure_rows(Zs, reacheds)
        pms = [
            pm if pm is not None else PointMeasures.gather([(pm_all, slice(o, o + int(np.sum(r))))])
            for pm, o, r in zip(
                pm_all if isinstance(pm_all, list) else [None] * len(Zs),
                offsets,
                reacheds,
                strict=True,
            )
        ]
        ratios = []
        ranks = []
        for pm, reached in zip(pms, reacheds, strict=True):
            rank = {t: np.full(K, -2, dtype=np.int16) for t in self.tests}
            ratio = {t: np.full(K, np.nan) for t in self.tests}
            for t in self.tests:
                rank[t][reached] = pm.rank[t]
                ratio[t][reached] = pm.ratio[t]
            ranks.append(rank)
            ratios.append(ratio)
        if isinstance(pm_all, list):  # measured row by row: refined row by row
            along = [
                self._along(Z, reached, pm, ratio, col, i)
                for (i, _), Z, reached, pm, ratio in zip(
                    starts, Zs, reacheds, pms, ratios, strict=True
                )
            ]
        else:
            along = self._along_rows(
                pm_all,
                [
                    (Z, reached, o, ratio, col, i)
                    for (i, _), Z, reached, o, ratio in zip(
                        starts, Zs, reacheds, offsets, ratios, strict=True
                    )
                ],
            )
        out = []
        for r, (index, _) in enumerate(starts):
            fwd, bwd = traces[r]
            Z, reached, pm, rank, ratio = Zs[r], reacheds[r], pms[r], ranks[r], ratios[r]
            newton = int(np.sum(fwd.newton)) + int(np.sum(bwd.newton))
            located = [self._fold(f, index, values) for f in [*fwd.folds, *bwd.folds]]
            located += along[r]
            stopped = self._inside(Z, reached, rank, ratio, col, index, located)
            var = self._variable(col)
            for trace, end in ((fwd, values[-1]), (bwd, values[0])):
                if trace.stopped:
                    # where it stopped: the last sample reached towards that end
                    got = trace.Z[~np.isnan(trace.Z[:, 0])]
                    last = var.shown(float(got[-1][col])) if len(got) else "its start"
                    stopped.append(
                        f"towards {var.name} = {var.shown(float(end))}: stopped after {last}: "
                        f"{trace.stopped}"
                    )
            out.append(
                RowResult(
                    index,
                    reached,
                    rank,
                    ratio,
                    _merge(located, self),
                    stopped,
                    newton,
                    Z,
                    pm,
                    outside(self.limited, Z[:, : self.model.n], reached),
                )
            )
        return out

    def _inside(
        self,
        Z: np.ndarray,
        reached: np.ndarray,
        rank: dict[str, np.ndarray],
        ratio: dict[str, np.ndarray],
        col: int,
        index: int,
        located: list[Located],
    ) -> list[str]:
        """The tests singular at every reached sample of a row (the path lies in their
        singular set): said in the row's notes, and where the rank they keep along the
        path drops further, those points located (added to ``located``)."""
        K = len(Z)
        always = [t for t in self.tests if np.any(reached) and np.all(ratio[t][reached] <= _TAU_HI)]
        stopped: list[str] = []
        for t in always:
            g = self.measures.generic[t]
            stopped.append(
                f"{t} is singular at every reached sample (rank below its generic {g} all "
                "along): the path lies in that singular set"
            )
            # inside the set, the rank it keeps along the path can drop further (a PUMA's
            # elbow on a path inside its wrist singularity): located at that level
            level = int(np.max(rank[t][reached]))
            if 0 < level < g:
                with self._levelled(t, level):
                    pm_t = self._measure(Z, reached)
                    ratio_t = np.full(K, np.nan)
                    ratio_t[reached] = pm_t.ratio[t]
                    if np.any(ratio_t[reached] > _TAU_HI):
                        located += self._along(Z, reached, pm_t, {t: ratio_t}, col, index)
                        stopped.append(
                            f"{t}: inside that set its rank is {level} along the path; "
                            f"the points where it drops below {level} are located"
                        )
        return stopped

    @contextlib.contextmanager
    def _levelled(self, t: str, level: int) -> Iterator[None]:
        """Within the block, the sweep measures test ``t`` alone, at rank ``level``
        instead of its generic rank (the refinements read ``self.measures``)."""
        whole = self.measures
        self.measures = whole.levelled(t, level)
        try:
            yield
        finally:
            self.measures = whole

    def _measure_rows(
        self, Zs: list[np.ndarray], reacheds: list[np.ndarray]
    ) -> tuple[PointMeasures | list[PointMeasures], list[int]]:
        """The measures of several rows' reached samples: one batch (in chunks of
        _CHUNK configurations), with each row's offset in it, when the measures are per
        configuration; otherwise a list, row by row (each row its own batch, as alone)."""
        sizes = [int(np.sum(r)) for r in reacheds]
        offsets = [int(x) for x in np.cumsum([0, *sizes[:-1]])]
        if not (self.measures.pointwise and dispatch.enabled()):
            return [self._measure(Z, r) for Z, r in zip(Zs, reacheds, strict=True)], offsets
        Z = np.concatenate([Z[r] for Z, r in zip(Zs, reacheds, strict=True)])
        return self._measure(Z, np.ones(len(Z), dtype=bool)), offsets

    def _measure(self, Z: np.ndarray, reached: np.ndarray) -> PointMeasures:
        Q = Z[reached][:, : self.model.n]
        parts = [self.measures(Q[i : i + _CHUNK]) for i in range(0, max(len(Q), 1), _CHUNK)]
        if len(parts) == 1:
            return parts[0]
        return PointMeasures.gather([(p, slice(None)) for p in parts])

    def values_of(self, z: np.ndarray) -> tuple[float, ...]:
        return tuple(float(z[c]) for c in self.cols)

    def _fold(self, f: Fold, index: int, values: np.ndarray) -> Located:
        pm = self.measures(f.z[None, : self.model.n])
        vanishing = tuple(t for t in self.tests if pm.ratio[t][0] <= _FOLD_TEST_RTOL)
        ratio = min((float(pm.ratio[t][0]) for t in self.tests), default=0.0)
        i = int(np.searchsorted(np.sort(values), f.value)) - 1
        return self._at(f.z, "fold", vanishing, ratio, "row", (index, max(i, 0)), f.far_side)

    def _at(
        self,
        z: np.ndarray,
        kind: str,
        tests: tuple[str, ...],
        ratio: float,
        edge: str,
        cell: tuple[int, int],
        far_side: bool = False,
    ) -> Located:
        """A located point at the sweep's coordinates z, on a row's or column's edge
        ``cell`` (row index first)."""
        z = np.array(z, dtype=float)
        return Located(
            self.values_of(z),
            kind,
            tests,
            ratio,
            z[: self.model.n].copy(),
            cell[0],
            edge,
            cell,
            far_side,
            z,
        )

    def _along(
        self,
        Z: np.ndarray,
        reached: np.ndarray,
        pm: PointMeasures,
        ratio: dict[str, np.ndarray],
        col: int,
        index: int,
    ) -> list[Located]:
        """Sign changes and minima of each test along one row."""
        return self._along_rows(pm, [(Z, reached, 0, ratio, col, index)])[0]

    def _along_rows(
        self,
        pm: PointMeasures,
        rows: list[tuple[np.ndarray, np.ndarray, int, dict[str, np.ndarray], int, int]],
    ) -> list[list[Located]]:
        """Sign changes and minima of each test along several rows, each ``(Z, reached,
        offset, ratio, col, index)``: its reached samples are the measured batch ``pm``'s
        from ``offset`` on, in order.  Test by test, the sign changes of every row are
        refined together (:meth:`_crossings`, each bracket on its own), then each row's
        minima; each row's points are found as when it is alone."""
        outs: list[list[Located]] = [[] for _ in rows]
        # per row: its pairs of neighbouring reached samples, and their rows in the batch
        # (which holds the row's reached samples in order, from its offset)
        info: list[tuple[list[tuple[int, int]], np.ndarray, np.ndarray, np.ndarray] | None] = []
        ias, ibs = [], []
        for Z, reached, off, _, _, _ in rows:
            where = np.flatnonzero(reached)
            first = np.flatnonzero((where[:-1] + 1 == where[1:]) if len(where) else [])
            PA = where[first]
            pairs = [(int(a), int(a) + 1) for a in PA]
            if not pairs:
                info.append(None)
                continue
            K = len(Z)
            # the samples whose neighbours are both reached (the minima's candidates)
            inner = np.zeros(K, dtype=bool)
            inner[1:-1] = reached[:-2] & reached[1:-1] & reached[2:]
            info.append((pairs, PA, off + first, inner))
            ias.append(off + first)
            ibs.append(off + first + 1)
        if not ias:
            return outs
        dets_all = self.measures.compressed_pairs(pm, np.concatenate(ias), np.concatenate(ibs))
        dets: list[dict[str, np.ndarray] | None] = []
        at = 0
        for got in info:
            if got is None:
                dets.append(None)
                continue
            n = len(got[0])
            dets.append({t: d[at : at + n] for t, d in dets_all.items()})
            at += n
        crossed: list[set[int]] = [set() for _ in rows]
        for t in self.tests:
            # the sign changes of every row (A: the first sample of each pair)
            todo: list[np.ndarray | None] = []
            for r, (Z, _, _, ratio, col, _) in enumerate(rows):
                crossed[r] = set()
                got, dr = info[r], dets[r]
                if got is None or dr is None:
                    todo.append(None)
                    continue
                pairs, PA, _, _ = got
                d = dr.get(t)
                rho = ratio[t]
                # between two samples that are both singular for the test, its sign is
                # noise: a sign change counts only where one end has a decided full generic
                # rank
                hits = (
                    []
                    if d is None
                    else np.flatnonzero(
                        (d < 0) & (np.maximum(rho[PA], rho[PA + 1]) > _TAU_HI)
                    ).tolist()
                )
                # a pair holding a point already located for another test (the closure's
                # first) that zeroes this one too: the same point, placed by that test
                # (near a singular point of the closure this test's zero is blurred)
                done = [
                    k
                    for k in hits
                    if self._holds(outs[r], t, Z[pairs[k][0], col], Z[pairs[k][1], col], col)
                ]
                crossed[r].update(x for k in done for x in pairs[k])
                hits = [k for k in hits if k not in done]
                todo.append(np.array(hits, dtype=int) if hits else None)
            # a sign change of the closure is a singular point the path passes through: a
            # double root for Newton, placed by the path on both sides (row by row);
            # the others' zeros, every row's together
            refined: list[list[tuple[np.ndarray, float] | None]] = [[] for _ in rows]
            if t == "closure":
                for r, hits_r in enumerate(todo):
                    if hits_r is not None:
                        Z, reached, _, _, col, _ = rows[r]
                        refined[r] = [
                            self._through(Z, reached, int(a), int(a) + 1, col)
                            for a in info[r][1][hits_r]  # type: ignore[index]
                        ]
            else:
                which = [r for r, h in enumerate(todo) if h is not None]
                if which:
                    col = rows[which[0]][4]
                    ZA = np.concatenate([rows[r][0][info[r][1][todo[r]]] for r in which])  # type: ignore[index]
                    ZB = np.concatenate([rows[r][0][info[r][1][todo[r]] + 1] for r in which])  # type: ignore[index]
                    ia = np.concatenate([info[r][2][todo[r]] for r in which])  # type: ignore[index]
                    found_all = self._crossings(t, ZA, ZB, col, pm, ia)
                    at = 0
                    for r in which:
                        n = len(todo[r])  # type: ignore[arg-type]
                        refined[r] = found_all[at : at + n]
                        at += n
            for r, hits_r in enumerate(todo):
                got = info[r]
                if got is None:
                    continue
                Z, _, _, ratio, col, index = rows[r]
                out = outs[r]
                if hits_r is not None:
                    A = got[1][hits_r]
                    crossed[r].update(A.tolist() + (A + 1).tolist())
                    for a, found in zip(A, refined[r], strict=True):
                        if found is None:
                            crossed[r].difference_update((int(a), int(a) + 1))
                            continue
                        z, rr = found
                        out.append(self._at(z, "crossing", (t,), rr, "row", (index, int(a))))
                self._minima(t, Z, rows[r][1], ratio[t], got[3], crossed[r], col, index, out)
        return outs

    def _minima(
        self,
        t: str,
        Z: np.ndarray,
        reached: np.ndarray,
        rho: np.ndarray,
        inner: np.ndarray,
        crossed: set[int],
        col: int,
        index: int,
        out: list[Located],
    ) -> None:
        """A row's sampled minima of test ``t`` that could hide a zero, refined (added to
        ``out``): not singular on both sides (no isolated zero to place there), at most
        its neighbours, and low next to how far they rise."""
        K = len(Z)
        lo, mid, hi = np.full(K, np.nan), rho, np.full(K, np.nan)
        lo[1:], hi[:-1] = rho[:-1], rho[1:]
        big = np.maximum(lo, hi)
        with np.errstate(invalid="ignore"):
            low = (
                inner
                & (big > _TAU_HI)
                & (mid <= lo)
                & (mid <= hi)
                & ~(mid > SWEEP_MINIMUM_SCREEN * (big - mid))
            )
        for k in np.flatnonzero(low).tolist():
            if k in crossed:
                continue
            if self._holds(out, t, Z[k - 1, col], Z[k + 1, col], col):
                continue  # the point located there for another test zeroes this one
            found = None
            if t == "closure":
                found = self._through(Z, reached, k - 1, k + 1, col)
            if found is None:
                found = self._minimum(t, Z[k - 1], Z[k], Z[k + 1], col)
            if found is not None:
                z, r = found
                out.append(self._at(z, "minimum", (t,), r, "row", (index, k)))

    def _holds(self, out: list[Located], t: str, va: float, vb: float, col: int) -> bool:
        """Whether a point of ``out`` lies between the swept values va and vb and is
        singular for test ``t`` too (its measure below float's tau_hi there), or is a
        singular point of the closure (where the input and output tests' sign, read
        through the closure, changes too, and their measure is not defined)."""
        lo, hi = sorted((float(va), float(vb)))
        return any(
            lo <= float(p.z[col]) <= hi and ("closure" in p.tests or self._ratio(t, p.z) <= _TAU_HI)
            for p in out
            if p.z is not None
        )

    # ------------------------------------------------------------------ refinement

    def _ratio(self, t: str, z: np.ndarray) -> float:
        return float(self.measures(z[None, : self.model.n]).ratio[t][0])

    def _crossings(
        self,
        t: str,
        ZA: np.ndarray,
        ZB: np.ndarray,
        col: int,
        pm: PointMeasures,
        ia: np.ndarray,
    ) -> list[tuple[np.ndarray, float] | None]:
        """The zero of the test's compressed determinant between each pair of samples
        (ZA, ZB), all pairs together: the Illinois variant of regula falsi, each trial
        point closed by batched Newton from its interpolation; a zero where the measure
        does not reach float's tau_hi is not a singularity (the compressed determinant
        also vanishes where the two samples' singular vectors turned too far apart)."""
        pb = self.problem
        bc = pb.batch
        nb = bc.nb
        free = ~pb.given[:nb]
        za, zb = np.array(ZA, dtype=float), np.array(ZB, dtype=float)
        a, b = za[:, col].copy(), zb[:, col].copy()
        fa = self.measures.compressed(pm, ia, za[:, : self.model.n])[t]
        fb = self.measures.compressed(pm, ia, zb[:, : self.model.n])[t]
        ok = np.ones(len(a), dtype=bool)
        tol = SWEEP_LOCATE_TOL * self.scale(col)
        side = np.zeros(len(a), dtype=int)
        # the kept end's true value (Illinois halves fa), the iterate before the last
        ta = fa.copy()
        p, fp, zq = b.copy(), np.full(len(a), np.nan), zb.copy()
        for _ in range(_ILLINOIS_ITERATIONS):
            act = ok & (np.abs(b - a) > tol) & (fb != 0)
            if not np.any(act):
                break
            i = np.flatnonzero(act)
            c = b[i] - fb[i] * (b[i] - a[i]) / (fb[i] - fa[i])
            lo, hi = np.minimum(a[i], b[i]), np.maximum(a[i], b[i])
            bad = ~((c > lo) & (c < hi))
            c[bad] = (a[i][bad] + b[i][bad]) / 2
            f = (c - a[i]) / (b[i] - a[i])
            zp = bc.between(za[i], zb[i], f)
            zp[:, col] = c
            zc, res, _ = bc.newton(zp, free, pb.tolerance)
            lost = res > pb.tolerance
            ok[i[lost]] = False
            fc = self.measures.compressed(pm, ia[i], zc[:, : self.model.n])[t]
            same = fc * fb[i] > 0
            # the end that keeps its sign twice in a row has its value halved (Illinois)
            j = i[same]
            fa[j] = np.where(side[j] == 1, fa[j] / 2, fa[j])
            side[j] = 1
            k = i[~same]
            a[k], fa[k], za[k], ta[k] = b[k], fb[k], zb[k], fb[k]
            side[k] = 0
            p[i], fp[i], zq[i] = b[i], fb[i], zb[i]
            b[i], fb[i], zb[i] = c, fc, zc
        # the bracket is within the tolerance: the end nearer the zero (by its true
        # value), then one secant step through the last two iterates (or, when the kept
        # end is the nearer, through the bracket's two ends), put the zero at the
        # rounding level, where the analysis of the point decides in float too
        swap = ok & (np.abs(ta) < np.abs(fb))
        p[swap], fp[swap], zq[swap] = b[swap], fb[swap], zb[swap]
        b[swap], fb[swap], zb[swap] = a[swap], ta[swap], za[swap]
        act = np.flatnonzero(ok & np.isfinite(fp) & (fb != fp) & (fb != 0))
        if len(act):
            c = b[act] - fb[act] * (b[act] - p[act]) / (fb[act] - fp[act])
            near = np.abs(c - b[act]) <= np.abs(b[act] - p[act])
            act, c = act[near], c[near]
        if len(act):
            f = (c - b[act]) / np.where(p[act] != b[act], p[act] - b[act], 1.0)
            zp = bc.between(zb[act], zq[act], f)
            zp[:, col] = c
            zc, res, _ = bc.newton(zp, free, pb.tolerance)
            fc = self.measures.compressed(pm, ia[act], zc[:, : self.model.n])[t]
            better = (res <= pb.tolerance) & (np.abs(fc) < np.abs(fb[act]))
            zb[act[better]] = zc[better]
        out: list[tuple[np.ndarray, float] | None] = []
        rho = self.measures(zb[:, : self.model.n]).ratio[t]
        for m in range(len(a)):
            out.append((zb[m], float(rho[m])) if ok[m] and rho[m] <= _TAU_HI else None)
        return out

    def _minimum(
        self, t: str, za: np.ndarray, zm: np.ndarray, zb: np.ndarray, col: int
    ) -> tuple[np.ndarray, float] | None:
        """Golden-section search of the test's measure between two samples' neighbours;
        the point when the measure reaches float's tau_lo there."""
        g = (math.sqrt(5) - 1) / 2
        a, b = float(za[col]), float(zb[col])

        m, a0 = float(zm[col]), a

        def at(v: float) -> np.ndarray:
            pair = (za, zm) if (v - m) * (a0 - m) > 0 else (zm, zb)
            return self.close_at(pair[0], pair[1], col, v)

        try:
            c, d = b - g * (b - a), a + g * (b - a)
            zc, zd = at(c), at(d)
            fc, fd = self._ratio(t, zc), self._ratio(t, zd)
            while abs(b - a) > SWEEP_LOCATE_TOL * self.scale(col):
                if fc < fd:
                    b, d, zd, fd = d, c, zc, fc
                    c = b - g * (b - a)
                    zc = at(c)
                    fc = self._ratio(t, zc)
                else:
                    a, c, zc, fc = c, d, zd, fd
                    d = a + g * (b - a)
                    zd = at(d)
                    fd = self._ratio(t, zd)
        except ClosureError:
            return None
        z, r = (zc, fc) if fc < fd else (zd, fd)
        return (z, r) if r <= _TAU_LO else None

    def _through(
        self, Z: np.ndarray, reached: np.ndarray, ka: int, kb: int, col: int
    ) -> tuple[np.ndarray, float] | None:
        """A singular point of the closure that the path passes through (two branches
        crossing, as at a change-point four-bar's flat position), between samples ka and
        kb of the path Z.

        There the unknown joints are a double root of the closure equations for the held
        values, so float closes them only to about 1e-8 and the measure has a floor
        there: neither Newton at the point nor a search down to it can place it to
        1e-10.  The path itself is smooth through the point, and the measure along it
        is, near the point, proportional to the distance from it (a V).  So the path is
        walked from each side towards the point, each step half the estimated distance
        left (the estimate from the last two steps' measures) and predicted from the
        last two points of the walk (the other branch is as near as the point is: a
        prediction from the coarse samples could land on it), until SWEEP_BRANCH_OFFSET
        away; then from six points on both sides, 1, 2 and 3 offsets away (far outside
        the double root's reach, closed to full accuracy), the measure signed by side is
        fitted by a cubic whose root is the swept value, and the configuration there is
        the cubic interpolation of theirs.  None when the walks lose the path, when the
        six points do not make one smooth signed curve or when the interpolated point is
        not singular to float's tau_lo."""
        t = "closure"
        cm = self.problem.cm
        sc = self.scale(col)
        a, b = float(Z[ka, col]), float(Z[kb, col])
        rho = [self._ratio(t, Z[k]) for k in range(ka, kb + 1)]
        ra, rb = rho[0], rho[-1]
        if kb == ka + 2:
            # a minimum at the middle sample: on a V through it, c |v - g|, the point g is
            # on its lower neighbour's side, 2 h r_mid / (r_a + r_b) from it
            mid = (a + b) / 2
            toward = np.sign(b - a) * (1.0 if rb < ra else -1.0)
            guess = mid + toward * abs(b - a) * rho[1] / (ra + rb) if ra + rb > 0 else mid
        else:
            guess = a + (b - a) * ra / (ra + rb) if ra + rb > 0 else (a + b) / 2
        lo, hi = min(a, b), max(a, b)
        delta = min(SWEEP_BRANCH_OFFSET * sc, (hi - lo) / 8)
        if not lo + 3 * delta < guess < hi - 3 * delta:
            guess = min(max(guess, lo + 4 * delta), hi - 4 * delta)

        def behind(k: int, step: int) -> np.ndarray | None:
            j = k - step
            return Z[j] if 0 <= j < len(Z) and reached[j] else None

        walks = []
        for k, step in ((ka, 1), (kb, -1)):
            z, zp, r = np.asarray(Z[k], dtype=float), behind(k, step), (ra if k == ka else rb)
            g = guess
            for _ in range(_WALK_STEPS):
                v = float(z[col])
                if abs(g - v) <= 4 * delta:
                    break
                zn = _nodes(self.problem, z, zp, col, v + (g - v) / 2)
                if zn is None:
                    return None
                rn = self._ratio(t, zn)
                vn = float(zn[col])
                if rn < r:  # still descending the V: the distance left, from its slope
                    c = (r - rn) / abs(vn - v)
                    g_new = vn + np.sign(g - v) * rn / c
                    if lo < g_new < hi:
                        g = g_new
                z, zp, r = np.asarray(zn, dtype=float), z, rn
            else:
                return None
            walks.append((z, zp, g))
        guess = (walks[0][2] + walks[1][2]) / 2
        u = np.array([-3.0, -2.0, -1.0, 1.0, 2.0, 3.0])
        zs: list[np.ndarray] = []
        for (z, zp, _), side in zip(walks, (-1.0, 1.0), strict=True):
            pts = []
            for k in (3.0, 2.0, 1.0):
                zn = _nodes(self.problem, z, zp, col, guess + side * k * delta)
                if zn is None:
                    return None
                z, zp = np.asarray(zn, dtype=float), z
                pts.append(z)
            zs += pts if side < 0 else pts[::-1]
        f = np.sign(u) * np.array([self._ratio(t, z) for z in zs])
        coef = np.polyfit(u, f, 3)
        if np.max(np.abs(np.polyval(coef, u) - f)) > 1e-6 * np.max(np.abs(f)):
            return None  # not one smooth signed curve: not a crossing of the path
        roots = [r.real for r in np.roots(coef) if abs(r.imag) < 1e-9 and abs(r.real) < 1]
        if not roots:
            return None
        root = min(roots, key=abs)
        base = zs[2]
        D = np.array([cm.difference(z, base) for z in zs])
        dstar = np.array([np.polyval(np.polyfit(u, D[:, i], 3), root) for i in range(D.shape[1])])
        z = np.asarray(cm.update(base, dstar), dtype=float)
        z[col] = guess + root * delta
        r = self._ratio(t, z)
        return (z, r) if r <= _TAU_LO else None

    # ------------------------------------------------------------------ columns of a grid

    def between_many(
        self, pairs: list[tuple[RowResult, RowResult]], col: int
    ) -> list[list[Located]]:
        """The sign changes of each test between neighbouring rows of a grid, for several
        pairs of rows (ra, rb) at the same samples of the row variable: refined along the
        column, every pair's together (each bracket on its own, as for one pair)."""
        found: list[dict[str, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]] = []
        for ra, rb in pairs:
            assert ra.Z is not None and rb.Z is not None and ra.measures is not None
            mine: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = {}
            found.append(mine)
            both = np.flatnonzero(ra.reached & rb.reached)
            if not len(both):
                continue
            pos = {int(k): i for i, k in enumerate(np.flatnonzero(ra.reached))}
            ia = np.array([pos[int(k)] for k in both])
            if rb.measures is not None and rb.measures.matrices is not None:
                # row b's matrices at those samples were kept by its own measures
                pos_b = {int(k): i for i, k in enumerate(np.flatnonzero(rb.reached))}
                ib = np.array([pos_b[int(k)] for k in both])
                dets = self.measures.compressed_measured(ra.measures, ia, rb.measures, ib)
            else:
                dets = self.measures.compressed(ra.measures, ia, rb.Z[both][:, : self.model.n])
            for t in dets:
                hits = np.flatnonzero(dets[t] < 0)
                if len(hits):
                    K = both[hits]
                    mine[t] = (K, ra.Z[K], rb.Z[K], ia[hits])
        # each test's sign changes, every pair's together
        refined: dict[str, list[tuple[np.ndarray, float] | None]] = {}
        for t in self.tests:
            which = [p for p, mine in enumerate(found) if t in mine]
            if not which:
                continue
            pm = PointMeasures.gather(
                [(pairs[p][0].measures, found[p][t][3]) for p in which]  # type: ignore[misc]
            )
            ZA = np.concatenate([found[p][t][1] for p in which])
            ZB = np.concatenate([found[p][t][2] for p in which])
            refined[t] = self._crossings(t, ZA, ZB, col, pm, np.arange(len(ZA)))
        out: list[list[Located]] = []
        at = dict.fromkeys(refined, 0)
        for (ra, _), mine in zip(pairs, found, strict=True):
            got: list[Located] = []
            for t, (K, _, _, _) in mine.items():
                for k, f in zip(K, refined[t][at[t] : at[t] + len(K)], strict=True):
                    if f is not None:
                        z, r = f
                        got.append(self._at(z, "crossing", (t,), r, "column", (ra.index, int(k))))
                at[t] += len(K)
            out.append(got)
        return out

    def row_chunks(self, values: list[np.ndarray]) -> list[range]:
        """The rows of a grid in the chunks that are followed, measured and refined
        together: as many rows as hold about _ROWS_SAMPLES samples and _ROWS_BYTES of
        their measures (at least one)."""
        rows, k = len(values[1]), len(values[0])
        # a sample's measures keep its matrices (the closure's rows by the coordinates,
        # the closure kernel, the tests' rows and singular vectors): about this many bytes
        n, loops = self.problem.n, 6 * len(self.mech.loops)
        size = 8 * (2 * loops * n + 2 * n * n + 24 * n)
        per = max(1, min(_ROWS_SAMPLES, _ROWS_BYTES // max(size, 1)) // max(k, 1))
        return [range(lo, min(lo + per, rows)) for lo in range(0, rows, per)]

    def chunk_rows(
        self, chunk: range, column: RowResult, values: list[np.ndarray]
    ) -> list[RowResult]:
        """The rows of one chunk (:meth:`row_chunks`), from the first column's
        configurations: the reached ones together (:meth:`rows_of`)."""
        assert column.Z is not None
        starts = [(j, column.Z[j]) for j in chunk if column.reached[j]]
        got = dict(
            zip(
                [j for j, _ in starts],
                self.rows_of(starts, self.cols[0], values[0]) if starts else [],
                strict=True,
            )
        )
        return [got[j] if j in got else self.unreached_row(j, len(values[0])) for j in chunk]

    def rows(
        self, values: list[np.ndarray], progress: Callable[[int], None] | None = None
    ) -> Iterator[RowResult]:
        """The rows of the sweep in order (one for a path), each with its measures and the
        points located along it (the crossings between rows are the caller's:
        :meth:`between_many`).  A grid's rows are computed in chunks
        (:meth:`row_chunks`)."""
        if len(self.cols) == 1:
            res = self.row(0, self.cols[0], values[0], self.z0)
            if progress:
                progress(len(values[0]))
            yield res
            return
        column = self.first_column(values)
        for chunk in self.row_chunks(values):
            for res in self.chunk_rows(chunk, column, values):
                if progress:  # before the row is yielded: its consumer may stop there
                    progress(len(values[0]))
                yield res

    def first_column(self, values: list[np.ndarray]) -> RowResult:
        """A grid's first column: a path in the second variable, at the first variable's
        sample nearest the start; its configurations start the rows (which are then
        independent of each other)."""
        cx, cy = self.cols
        _, zx = self.start_of(cx, values[0], self.z0)
        column = self.row(-1, cy, values[1], zx)
        self._bridge(column, values)
        return column

    def _bridge(self, column: RowResult, values: list[np.ndarray]) -> None:
        """Rows the first column does not reach (the reachable region does not cover
        the start's value of the first variable there) are started from a neighbouring
        row that is reached: that row is followed, and from its reached samples (the
        nearest the first column first) the column is continued to the row's value; the
        row's start (at that sample) goes into ``column``.  Repeated outwards until no
        row is added, so a reachable region that the first column crosses only in part is
        covered on the start's assembly mode."""
        assert column.Z is not None
        reached = column.reached
        if reached.all() or not reached.any():
            return
        cx, cy = self.cols
        xs, ys = values
        k0 = int(np.argmin(np.abs(xs - self.z0[cx])))
        pb = self.problem
        paths: dict[int, np.ndarray] = {}

        def path_of(n: int) -> np.ndarray:
            if n not in paths:
                assert column.Z is not None
                z = column.Z[n]
                kn = int(np.argmin(np.abs(xs - z[cx])))
                Zn = np.full((len(xs), pb.n), np.nan)
                Zn[kn:] = follow(pb, z, cx, xs[kn:]).Z
                Zn[: kn + 1] = follow(pb, z, cx, xs[kn::-1]).Z[::-1]
                paths[n] = Zn
            return paths[n]

        bridged = 0
        added = True
        while added:
            added = False
            for j in range(len(ys)):
                if reached[j]:
                    continue
                for n in (j - 1, j + 1):
                    if not (0 <= n < len(ys) and reached[n]):
                        continue
                    Zn = path_of(n)
                    ks = np.flatnonzero(~np.isnan(Zn[:, 0]))
                    ks = ks[np.argsort(np.abs(ks - k0), kind="stable")]
                    picks = ks[:: max(1, len(ks) // _BRIDGE_TRIES)][:_BRIDGE_TRIES]
                    for k in picks:
                        try:
                            zj = pb.reach(Zn[k], cy, float(ys[j]))
                        except ClosureError:
                            continue
                        column.Z[j], reached[j] = zj, True
                        added, bridged = True, bridged + 1
                        break
                    if reached[j]:
                        break
        if bridged:
            self.start_notes.append(
                f"{bridged} rows the first column does not reach were started from a "
                "neighbouring row"
            )

    def unreached_row(self, j: int, k: int) -> RowResult:
        """Row j of k samples when the first column does not reach it: nothing reached."""
        empty = np.zeros(k, dtype=bool)
        return RowResult(
            j,
            empty,
            {t: np.full(k, -2, dtype=np.int16) for t in self.tests},
            {t: np.full(k, np.nan) for t in self.tests},
            [],
            [f"row {j}: the first column does not reach it"],
        )


def _merge(located: list[Located], sw: Sweep) -> list[Located]:
    """Points of one row found by several tests (or a fold and a test) at the same value
    are one point: their tests together, placed by the fold if there is one, else by the
    closure's test (near a singular point of the closure the other tests' measures are
    blurred by its double root; the closure's own placement is not)."""
    order = {"fold": 0, "crossing": 1, "minimum": 2}
    located = sorted(located, key=lambda p: (p.values, order[p.kind]))
    groups: list[list[Located]] = []
    for p in located:
        for g in groups:
            o = g[0]
            if o.edge == p.edge and all(
                abs(a - b) <= 1e3 * SWEEP_LOCATE_TOL * sw.scale(c) + 1e-9 * sw.scale(c)
                for a, b, c in zip(o.values, p.values, sw.cols, strict=True)
            ):
                g.append(p)
                break
        else:
            groups.append([p])
    out = []
    for g in groups:
        best = min(g, key=lambda p: (order[p.kind] > 0, "closure" not in p.tests))
        best.tests = tuple(dict.fromkeys(t for p in [best, *g] for t in p.tests))
        out.append(best)
    return out


def classify_located(
    sweep: Sweep, located: list[Located], precision: Precision, time_limit: float | None = None
) -> tuple[list[Any], list[bool], list[Any]]:
    """The full analysis of each located point at the sweep's precision, each within
    ``time_limit`` seconds (None: no limit); at mp:N each point is first found again at N
    digits (:mod:`.relocate`).  Also says, per point, whether it was relocated, and gives
    the joints it was analysed at (at N digits when relocated)."""
    if not located:
        return [], [], []
    points: dict[str, Any] = {}
    moved = []
    relocators: dict[str, Any] = {}

    def relocator(test: str, prec: Precision) -> Any:
        # a singular point of the closure is a double root of the closure for the held
        # values: N digits of residual place it to N/2 digits only, so it is placed at
        # 2N + 10 digits (and read at N)
        from mechsing.sweeps.relocate import Relocator

        digits = prec.digits * 2 + 10 if test == "closure" else prec.digits
        key = str(digits)
        if key not in relocators:
            relocators[key] = Relocator(sweep, Precision("mp", digits))
        return relocators[key]

    def again_at(p: Located, prec: Precision) -> Any:
        if p.z is None:
            return None
        if p.kind == "fold":  # placed by its own conditions, whatever test vanishes there
            return relocator("fold", prec).relocate(p.z, "fold", "fold")
        test = next((t for t in p.tests if t in sweep.tests), None)
        if test is None:
            return None
        return relocator(test, prec).relocate(p.z, test, p.edge)

    for i, p in enumerate(located):
        # policy: only mp places the points again, at its digits
        again = again_at(p, precision) if precision.mode == "mp" else None
        moved.append(again is not None)
        points[f"located-{i + 1}"] = p.q if again is None else again
    results = analyze_found(sweep.mech, points, precision, time_limit)
    if precision.mode == "auto":
        # auto re-decided some points at mp:50 (an undecided float rank): at 50 digits the
        # float point is a regular neighbour of the singular one, so it is found again there
        deep = Precision("mp", 50)
        for i, (p, res) in enumerate(zip(located, results, strict=True)):
            if res.precision == "float" or res.error is not None:
                continue
            again = again_at(p, deep)
            if again is not None:
                res2 = analyze_found(sweep.mech, {f"located-{i + 1}": again}, deep, time_limit)[0]
                results[i] = replace(res2, escalated_for=res.escalated_for)
                moved[i] = True
                points[f"located-{i + 1}"] = again
    return results, moved, list(points.values())
