"""Closure of named configurations: :class:`Closer` owns the order of the work and
the check of a configuration that gives every value; the given values' coordinates are
:mod:`mechsing.kinematics.given`'s, the path :mod:`mechsing.kinematics.continuation`'s,
the mp polish :mod:`mechsing.kinematics.polish`'s.

From the configuration named by ``start`` (default ``reference``: every joint
at identity), the given values move along a straight line in small steps; at
each step a first-order predictor and a damped Newton corrector on the group
(each update in the joint's own subalgebra, :meth:`KinematicModel.update`)
close the loops again, so the result stays on the starting assembly mode.

* The path stops with :class:`ClosureError` naming the step when the closure
  Jacobian in the unknown coordinates loses rank before the target.
* A target that is itself singular is reached and accepted when Newton still
  closes there.
* When the given values leave the configuration undetermined, each step takes
  the minimum-norm correction and the result says ``underdetermined``.
* A configuration giving every value is checked, not solved.
* Acceptance: ``1e-12 L`` in float, ``10^(15-N) L`` at mp:N (float
  continuation, then Newton at N digits), exactly in exact mode.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from mechsing.errors import (
    BeyondTravelError,
    ClosureError,
    ConfigurationError,
    ExactDataError,
    UserError,
)
from mechsing.kinematics.closed import ClosedConfiguration, shown_residual
from mechsing.kinematics.continuation import Continuation
from mechsing.kinematics.couplings import impose_couplings
from mechsing.kinematics.given import GivenValues
from mechsing.kinematics.model import KinematicModel
from mechsing.kinematics.polish import MpPolisher, newton_mp
from mechsing.kinematics.pose import PoseModel, pose_problem
from mechsing.kinematics.protocol import ClosureModel
from mechsing.model import Configuration, Mechanism
from mechsing.model.couplings import coupling_source, describe_coupling
from mechsing.numeric import EXACT_ZERO_DIGITS, Precision, to_float
from mechsing.numeric.backend import exact_is_zero
from mechsing.timelimit import activity

__all__ = ["ClosedConfiguration", "Closer", "solve_configuration"]


class Closer:
    """Solves the named configurations of one kinematic model (memoised)."""

    def __init__(self, model: KinematicModel, data_precision: Precision | None = None) -> None:
        self.model = model
        self.mech = model.mech
        self._solved: dict[str, ClosedConfiguration] = {}
        self._family: Any = None  # the joints' family, once a pose is checked against it
        prec = model.precision
        self.tolerance = prec.closure_tolerance(model.length_scale)
        #: the mode whose tolerance decides whether a given value is what it claims
        #: to be (a displacement in its joint's subgroup): the analysis's own; auto
        #: keeps float's when it re-decides a configuration at mp:50
        self.data_precision: Precision = data_precision or prec
        self.given = GivenValues(model, self.data_precision, self.tolerance)
        self.polisher = MpPolisher(model, self.tolerance)
        self.continuation = Continuation(
            model, self.tolerance, self.polisher, at_folds=self.data_precision == prec
        )

    # ---------------------------------------------------------------- public

    def solve(self, name: str, _chain: tuple[str, ...] = ()) -> ClosedConfiguration:
        """Close the named configuration (memoised), at the model's precision."""
        with self.model.precision.context():
            return self._solve(name, _chain)

    def solve_many(self, names: list[str]) -> None:
        """Close the named configurations together where they can be (memoised, for
        :meth:`solve`): in float, those that give every joint value (no pose) of a
        mechanism of one-dof and U joints are checked in one batch, their poses kept for the model (:meth:`KinematicModel.keep_poses`):
        each residual, pose and verdict is bitwise that of :meth:`solve` on its own.  One
        that does not close is left to :meth:`solve`, which says why; the others are not
        touched here."""
        m = self.model
        # a joint of several coordinates (but U) has the twist q @ basis, a matrix product
        # numpy may sum in another order for a batch than for one configuration
        if (
            m.precision.mode != "float"
            or not m.blocks
            or any(jk.type != "U" and jk.basis.shape[0] != 1 for jk in m.joints)
        ):
            return
        n = m.n
        todo: list[tuple[str, np.ndarray]] = []
        with m.precision.context():
            for name in names:
                cfg = self.mech.configurations.get(name)
                if name in self._solved or cfg is None or cfg.pose is not None:
                    continue
                try:
                    target, given = self.given.of(cfg)
                except UserError:
                    continue  # solve says why
                if len(given) == n and target.dtype == float:
                    todo.append((name, target))
            if not todo:
                return
            Q = np.stack([q for _, q in todo])
            poses = m.poses(Q)
            deltas = m.chord_residuals(Q, poses)
            m.keep_poses(Q, poses)
            for i, (name, q) in enumerate(todo):
                res = m.residual_norm([D[i] for D in deltas], native=True)
                if res <= self.tolerance:
                    self._solved[name] = ClosedConfiguration(
                        name, q, float(res), False, 0, tuple(range(n))
                    )

    def _solve(self, name: str, _chain: tuple[str, ...] = ()) -> ClosedConfiguration:
        if name in self._solved:
            return self._solved[name]
        if name in _chain:
            raise UserError(
                f"configuration {name!r}: its start chain loops back on itself ({' -> '.join(_chain + (name,))})"
            )
        cfg = self.mech.configurations[name]
        target, given = self.given.of(cfg)
        n = self.model.n
        if len(given) == n and cfg.pose is None:
            out = self._check(cfg, target)
        elif self.model.precision.mode == "exact" and not given and cfg.pose is None:
            # a configuration that gives nothing is its start configuration, which exact
            # mode takes (and proves) as it is
            start = cfg.start if cfg.start else None
            q0 = self.model.zeros() if start is None else self._solve(start, _chain + (name,)).q
            out = replace(self._check(cfg, q0), given=())
        else:
            if self.model.precision.mode == "exact" and (self.model.chords or cfg.pose):
                # the joints not given would be solved numerically: refused before solving
                # the start configuration (whose own problems are not this one's)
                where = f"configuration {cfg.name!r}" + (f" (line {cfg.line})" if cfg.line else "")
                why = (
                    "it gives the output's pose, and the joints are then solved numerically"
                    if cfg.pose is not None
                    else f"it gives {len(given)} of {n} coordinates; the others would be "
                    "solved numerically"
                )
                raise ExactDataError(
                    f"{where}: exact precision needs every joint value given exactly ({why}); "
                    "give them all, or use --precision auto, float or mp:N for this configuration",
                    cfg.name,
                )
            start_name = cfg.start if cfg.start else None
            if start_name is None or (cfg.is_reference and not cfg.values):
                q0 = self.model.zeros()
            else:
                try:
                    q0 = self._solve(start_name, _chain + (name,)).q
                except ConfigurationError as exc:
                    # the same kind of failure, now this configuration's (the start's limit
                    # of travel is not this configuration's: a closure error)
                    kind = ClosureError if isinstance(exc, BeyondTravelError) else type(exc)
                    raise kind(
                        f"configuration {name!r} starts from {start_name!r}, which could not be "
                        f"{'closed' if isinstance(exc, ClosureError) else 'analysed'}: {exc}",
                        name,
                        exc.residual,
                    ) from None
            if cfg.pose is not None:
                out = self._solve_pose(cfg, q0, target, given)
            elif not self.model.chords:
                # no loop: nothing to solve; the joints not given keep their start values
                q = np.array(q0, copy=True)
                q[list(given)] = target[list(given)]
                q = impose_couplings(self.model, q, set(given))  # the followers follow
                out = ClosedConfiguration(cfg.name, q, 0.0, False, 0, given)
            else:
                out = self.continuation.run(cfg, q0, target, given)
        self._solved[name] = out
        return out

    def _solve_pose(
        self, cfg: Configuration, q0: np.ndarray, target: np.ndarray, given: tuple[int, ...]
    ) -> ClosedConfiguration:
        """A configuration that gives the output's pose (and perhaps some joint values):
        continuation from ``q0`` in the pose model (:mod:`mechsing.kinematics.pose`),
        whose six pose coordinates are given and follow the geodesic from the start's
        pose; every joint not given is solved."""
        m = self.model
        pose = cfg.pose
        assert pose is not None
        if pose.rotation is not None:
            at = f"{self.mech.path}:{pose.line}: " if self.mech.path and pose.line else ""
            with m.precision.context():
                self.given.check_rotation(
                    f"{at}configuration {cfg.name!r}: pose of the output body "
                    f"{self.mech.output.body if self.mech.output else ''!r}",
                    m.asarray([list(row) for row in pose.rotation]),
                )
        self._pose_in_motion(cfg)
        with m.precision.context():
            pm, start, goal = pose_problem(m, cfg, q0)
            full = np.concatenate([target, goal])
        pgiven = tuple(given) + tuple(range(m.n, m.n + 6))
        out = self.continuation.run(cfg, start, full, pgiven, pm)
        q = out.q[: m.n]
        res = m.residual_norm(m.chord_residuals(q), native=m.precision.mode == "mp")
        return ClosedConfiguration(
            cfg.name, q, float(res), out.underdetermined, out.steps, given, out.notes, out.at_fold
        )

    def _pose_in_motion(self, cfg: Configuration) -> None:
        """Refuse a pose the output cannot take: where the joints generate a subgroup
        smaller than D (a planar mechanism's G), every body, and so the output relative to
        any body, moves in it; a pose that is not an element of it (a planar platform
        lifted off its plane, or turned about an axis not normal to it) is reached by no
        assembly mode, and continuation would only say it stopped (float's test of the
        element, to 1e-9: the closure accepts 1e-12 L)."""
        from mechsing import lie
        from mechsing.kinematics.family import family, pose_words

        pose = cfg.pose
        if pose is None:
            return
        if self._family is None:
            self._family = family(self.mech)
        fam = self._family
        if fam.subgroup is None or fam.dim is None or fam.dim >= 6:
            return
        c0 = np.asarray(to_float(np.array(self.mech.output_reference_point(), dtype=object)))
        c0 = c0.astype(float)
        if pose.rotation is not None:
            R = np.asarray(to_float(np.array(pose.rotation, dtype=object)), dtype=float)
        elif pose.rotation_vector is not None:
            rv = np.asarray(to_float(np.array(pose.rotation_vector, dtype=object)), dtype=float)
            R = lie.exp(np.concatenate([rv, np.zeros(3)]))[:3, :3]
        else:
            R = np.eye(3)
        x = (
            c0
            if pose.position is None
            else np.asarray(to_float(np.array(pose.position, dtype=object)), dtype=float)
        )
        g = np.eye(4)
        g[:3, :3], g[:3, 3] = R, x - R @ c0
        if fam.subgroup.contains(g, float(self.model.length_scale), "float"):
            return
        raise ClosureError(
            f"configuration {cfg.name!r}: the output's pose is not reachable: it is not a "
            "displacement from the drawn pose in the subgroup every body moves in, "
            f"{pose_words(fam)}",
            cfg.name,
            None,
        )

    def follow(
        self,
        q0: np.ndarray,
        target: np.ndarray,
        given: tuple[int, ...],
        model: PoseModel | None = None,
        label: str = "sweep",
        start: str = "the previous point",
    ) -> ClosedConfiguration:
        """Continuation from the closed ``q0`` to the given coordinates of ``target`` on
        the same assembly mode (float; ``model``: a pose model), with the predictor,
        Newton on the group, branch checks and fold landing of a named configuration's
        closure.  Raises :class:`ClosureError` where the path cannot be followed (a
        fold, a singularity on the way); ``label`` and ``start`` name the two ends in
        its message.  The sweeps' continuation between their nodes."""
        cfg = Configuration(label, {}, start=start)
        return self.continuation.run(cfg, q0, target, tuple(given), model)

    def polish(
        self,
        q: np.ndarray,
        target: np.ndarray,
        given: tuple[int, ...],
        model: ClosureModel | None = None,
    ) -> tuple[np.ndarray, Any]:
        """Newton at the model's digits (mp:N) from ``q`` (float or mp), the coordinates in
        ``given`` held at their values in ``target`` (``model``: a pose model on this
        Closer's model): the coordinates and their residual (m, the model's numbers).
        Converges where float's point is within Newton's reach (a multiple root: slowly,
        with the doubled step).  The sweeps' relocation of a float point at N digits."""
        m = self.model if model is None else model
        gmask = np.zeros(m.n, dtype=bool)
        gmask[list(given)] = True
        with m.precision.context():
            qm, res, _ = newton_mp(m, q, m.asarray(list(target)), gmask)
        return qm, res

    # ---------------------------------------------------------------- checking

    def _block_named(self, i: int) -> str:
        """The closure block ``i`` of the model (:meth:`KinematicModel.chord_residuals`'
        order: the chords' loops, then the couplings) in words."""
        m = self.model
        if i < len(m.chords):
            return self._loop_named(m.chords[i].name)
        c = m.couplings[i - len(m.chords)].coupling
        return f"the coupling {describe_coupling(c)} ({coupling_source(c)})"

    def _loop_named(self, chord: str) -> str:
        """'loop A-B-C-D' for the shortest canonical loop through a chord joint."""
        loops = [lp for lp in self.mech.loops if chord in lp.joints]
        if not loops:
            return f"the loop through joint {chord!r}"
        return f"loop {'-'.join(min(loops, key=len).joints)}"

    def _closes_as_data(self, res: Any) -> bool:
        """Do given values that miss the model's tolerance still close to that of the
        mode their digits were checked in (auto's float, when it re-decides at mp:50)?"""
        d = self.data_precision
        return (
            self.model.precision.mode == "mp"
            and d.mode == "float"
            and float(res) <= d.closure_tolerance(self.model.length_scale)
        )

    def _residual(self, q: np.ndarray) -> float:
        return self.model.residual_norm(self.model.chord_residuals(q))

    def _check(self, cfg: Configuration, q: np.ndarray) -> ClosedConfiguration:
        m = self.model
        deltas = m.chord_residuals(q)
        if m.precision.mode == "exact":  # policy: exact mode proves closure, never measures it
            fk = m.field_kinematics(q)
            with activity("proving that the loops close exactly"):
                if fk is not None:
                    # the residuals in the data's number field: zero there is zero
                    proofs = [[ok] for ok in fk.closes()]
                else:
                    proofs = [
                        [exact_is_zero(x, m.length_scale) for x in (D - m.backend.eye(4)).flat]
                        for D in deltas
                    ]
            bad = [i for i, pr in enumerate(proofs) if False in pr]
            unproven = [i for i, pr in enumerate(proofs) if None in pr]
            res = m.residual_norm(deltas)
            if unproven and not bad:
                raise ExactDataError(
                    f"configuration {cfg.name!r}: {self._block_named(unproven[0])} closes to "
                    f"{EXACT_ZERO_DIGITS} digits but sympy cannot prove that it closes exactly; "
                    "use --precision mp:N for this configuration",
                    cfg.name,
                )
            if bad:
                raise ClosureError(
                    f"configuration {cfg.name!r} does not close exactly: {self._block_named(bad[0])} "
                    f"leaves a residual of {res:.3g} m; give joint values that close the loops exactly, "
                    "or leave the passive joints out so they are solved",
                    cfg.name,
                    res,
                )
            return ClosedConfiguration(cfg.name, q, 0.0, False, 0, tuple(range(m.n)))
        res = m.residual_norm(deltas, native=True)
        if res > self.tolerance and self._closes_as_data(res):
            # auto re-deciding at N digits values that close to float's tolerance: the
            # file's digits say no more, so the configuration they give is the closed
            # one nearest to them (passive joints corrected, inputs kept; every joint
            # when that fails), far below what the values themselves claim
            keep = np.zeros(m.n, dtype=bool)
            for jn, i in self.mech.input_coordinates():
                keep[m.joint(jn).columns.start + i] = True
            for gmask in (keep, np.zeros(m.n, dtype=bool)):
                qm, rm = self.polisher.polish(m, q, q, gmask, cfg)
                if rm <= self.tolerance:
                    moved = float(np.max(np.abs(to_float(qm) - to_float(q)), initial=0.0))
                    note = (
                        f"the given values close to {shown_residual(res, 3)} m (float's tolerance); "
                        f"projected onto closure at {m.precision} (largest change {moved:.2g})"
                    )
                    return ClosedConfiguration(
                        cfg.name, qm, float(rm), False, 0, tuple(range(m.n)), [note]
                    )
        if res > self.tolerance:
            worst = max(range(len(deltas)), key=lambda i: m.residual_norm([deltas[i]], True))
            raise ClosureError(
                f"configuration {cfg.name!r} gives every joint value but does not close: "
                f"{self._block_named(worst)} leaves a residual of {shown_residual(res, 3)} m "
                f"(accepted: {shown_residual(self.tolerance, 1)} m); "
                "leave the passive joints out so they are solved, or give more digits",
                cfg.name,
                float(res),
            )
        return ClosedConfiguration(cfg.name, q, float(res), False, 0, tuple(range(m.n)))


def solve_configuration(
    mech: Mechanism, name: str, precision: Precision | str = "float"
) -> tuple[KinematicModel, ClosedConfiguration]:
    """Close one named configuration; returns the model and the closed configuration."""
    model = KinematicModel(mech, precision)
    return model, Closer(model).solve(name)
