"""Closure of named configurations by continuation.

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

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import sympy

from mechsing import lie
from mechsing.errors import ClosureError, ConfigurationError, ExactDataError, UserError
from mechsing.kinematics.couplings import couple_given, impose_couplings
from mechsing.kinematics.model import KinematicModel
from mechsing.kinematics.newton import (
    damped_least_squares,
    finite_system,
    mp_least_squares,
    newton_on_group,
)
from mechsing.kinematics.pose import PoseModel, pose_problem
from mechsing.kinematics.travel import beyond_target, beyond_travel
from mechsing.lie import ANGULAR
from mechsing.model import Configuration, Displacement
from mechsing.model.couplings import coupling_source, describe_coupling
from mechsing.numeric import (
    CONTINUATION_CORRECTOR_RATIO,
    CONTINUATION_FOLD_GAP,
    CONTINUATION_FOLD_REACH,
    CONTINUATION_JUMP_FLOOR,
    CONTINUATION_RETURN_RATIO,
    CONTINUATION_REVERSE_RTOL,
    CONTINUATION_SINGULAR_RTOL,
    CONTINUATION_STEP_RTOL,
    EXACT_ZERO_DIGITS,
    MAX_JOINT_VALUE,
    POLISH_DIGITS_SPARE,
    POLISH_MAX_STEPS,
    Precision,
    decide_rank,
    exact_is_zero,
    rotation_orthonormal_atol,
    screw_zero_rtol,
    to_float,
)
from mechsing.numeric.blocks import block_svd
from mechsing.timelimit import activity

#: largest step of a given coordinate: radians, or this times L for a length
_MAX_STEP = 0.1
#: largest predicted step of all coordinates together (commensurate norm)
_MAX_PREDICTED_STEP = 0.15
_MAX_HALVINGS = 14
_NEWTON_ITERATIONS = 12
#: most planned steps of one continuation (a crank of 300 turns)
_MAX_STEPS = 20000
#: step attempts allowed per planned step before continuation gives up
_MAX_ATTEMPTS_PER_STEP = 20


@dataclass
class ClosedConfiguration:
    """A closed configuration: all coordinates ``q`` (model backend), its residual (m)."""

    name: str
    q: np.ndarray
    residual: float
    underdetermined: bool = False
    steps: int = 0
    given: tuple[int, ...] = ()
    notes: list[str] = field(default_factory=list)
    #: reached by landing on a fold of the given values (float locates it to ~1e-8 only)
    at_fold: bool = False


class Closer:
    """Solves the named configurations of one kinematic model (memoised)."""

    def __init__(self, model: KinematicModel, data_precision: Precision | None = None) -> None:
        self.model = model
        self.mech = model.mech
        self._solved: dict[str, ClosedConfiguration] = {}
        prec = model.precision
        self.tolerance = prec.closure_tolerance(model.length_scale)
        #: the mode whose tolerance decides whether a given value is what it claims
        #: to be (a displacement in its joint's subgroup): the analysis's own; auto
        #: keeps float's when it re-decides a configuration at mp:50
        self.data_precision: Precision = data_precision or prec

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
                    target, given = self._given(cfg)
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
        target, given = self._given(cfg)
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
                    # the same kind of failure, now this configuration's
                    raise type(exc)(
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
                out = self._continue(cfg, q0, target, given)
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
                self._check_rotation(
                    f"{at}configuration {cfg.name!r}: pose of the output body "
                    f"{self.mech.output.body if self.mech.output else ''!r}",
                    m.asarray([list(row) for row in pose.rotation]),
                )
        with m.precision.context():
            pm, start, goal = pose_problem(m, cfg, q0)
            full = np.concatenate([target, goal])
        pgiven = tuple(given) + tuple(range(m.n, m.n + 6))
        out = self._continue(cfg, start, full, pgiven, pm)
        q = out.q[: m.n]
        res = m.residual_norm(m.chord_residuals(q), native=m.precision.mode == "mp")
        return ClosedConfiguration(
            cfg.name, q, float(res), out.underdetermined, out.steps, given, out.notes, out.at_fold
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
        return self._continue(cfg, q0, target, tuple(given), model)

    def polish(
        self, q: np.ndarray, target: np.ndarray, given: tuple[int, ...], model: Any = None
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
            qm, res, _ = self._newton_mp(m, q, m.asarray(list(target)), gmask)
        return qm, res

    # ---------------------------------------------------------------- given values

    def _given(self, cfg: Configuration) -> tuple[np.ndarray, tuple[int, ...]]:
        """Target coordinates (zeros where not given) and the indices given."""
        m = self.model
        target = m.zeros()
        given: list[int] = []
        if cfg.is_reference:
            # every joint at identity; the values it lists must be the identity
            if cfg.values:
                self._check_reference(cfg)
            # a coupled joint at its leader's image: its offset (identity when none)
            return impose_couplings(m, target, set()), tuple(range(m.n))
        for jname, val in cfg.values.items():
            jk = m.joint(jname)
            coords = self._coordinates_of_value(cfg, jname, val)
            fc = np.asarray(to_float(coords), dtype=float)
            # lengths are measured against the mechanism's own size L, angles in radians
            bound = m.float_frame.rates_back(
                np.full(len(fc), MAX_JOINT_VALUE), range(jk.columns.start, jk.columns.stop)
            )
            if not np.all(np.isfinite(fc)) or np.any(np.abs(fc) > bound):
                where = f"configuration {cfg.name!r}, joint {jname!r}" + (
                    f" (line {cfg.line})" if cfg.line else ""
                )
                raise UserError(
                    f"{where}: the value {[float(x) for x in fc]} (SI) is not a finite joint value of a "
                    f"sensible size (at most {MAX_JOINT_VALUE:g} rad, or {MAX_JOINT_VALUE:g} times the "
                    f"mechanism's size {m.length_scale:.3g} m for a length); check the value and the units"
                )
            if m.precision.mode == "exact":  # policy: exact mode takes exact values only
                self._refuse_transcendental(cfg, jk, coords)
            target[jk.columns] = coords
            given.extend(range(jk.columns.start, jk.columns.stop))
        if m.couplings:
            where = f"configuration {cfg.name!r}" + (f" (line {cfg.line})" if cfg.line else "")
            target, have = couple_given(m, target, set(given), self.tolerance, where)
            given = list(have)
        return target, tuple(sorted(given))

    def _coordinates_of_value(self, cfg: Configuration, jname: str, val: Any) -> np.ndarray:
        """A given value's coordinates in its joint's subgroup, in the model's numbers."""
        if isinstance(val, Displacement):
            return self._coordinates_of_displacement(cfg, jname, val)
        return self.model.asarray(list(val))

    def _check_reference(self, cfg: Configuration) -> None:
        """The values the reference configuration lists must be the identity in the
        analysis's mode: zero coordinates (angles to the mode's tolerance, lengths to
        it times L; exactly in exact mode), or an identity displacement."""
        m, decide = self.model, self.data_precision
        for jname, val in cfg.values.items():
            jk = m.joint(jname)
            coords = self._coordinates_of_value(cfg, jname, val)
            # a length against L, an angle against 1 (exact: proved zero)
            scale = m.float_frame.rates_back(
                np.ones(len(coords)), range(jk.columns.start, jk.columns.stop)
            )
            with decide.context():
                zero = all(
                    decide.backend.is_zero(x, s)
                    for x, s in zip(decide.asarray(coords), scale, strict=True)
                )
            if not zero:
                line = val.line if isinstance(val, Displacement) else cfg.lines.get(jname)
                where = f"{self.mech.path}:{line}: " if self.mech.path and line else ""
                raise UserError(
                    f"{where}configuration {cfg.name!r}: joint {jname!r}: the reference "
                    "configuration has every joint at identity (value 0), and this value is not "
                    f"the identity {_to_the_tolerance(decide)}; give it in a new configuration"
                )

    def _refuse_transcendental(self, cfg: Configuration, jk: Any, coords: np.ndarray) -> None:
        """Exact data: every rotation a joint value produces must have
        algebraic entries (angles that are rational multiples of pi, atan/asin/acos of
        algebraic numbers and their sums).  sympy must *prove* it (``is_algebraic``
        after expanding the trigonometric functions): 1 rad, pi*sqrt(2) or pi**2 are
        refused rather than mis-checked."""
        if jk.type in ("R", "H", "C", "U"):
            angles = list(coords) if jk.type == "U" else [coords[0]]
            entries = [f(v) for v in angles for f in (sympy.sin, sympy.cos)]
        else:
            rotates = any(any(x != 0 for x in row[ANGULAR]) for row in jk.basis.tolist())
            if not rotates:
                return
            q = self.model.zeros()
            q[jk.columns] = coords
            entries = list(self.model.element(jk, q)[:3, :3].flat)
        for x in entries:
            # the stable forms of exp write 1 - cos a as 2 sin(a/2)**2: trigsimp folds the
            # half angles back (cos(atan(4/3)) is 3/5) when expansion alone cannot tell
            with activity(f"showing that the value of joint {jk.name!r} is exact data"):
                algebraic = sympy.expand_trig(x).is_algebraic is True or (
                    sympy.expand_trig(sympy.trigsimp(x)).is_algebraic is True
                )
            if not algebraic:
                where = f"configuration {cfg.name!r}, joint {jk.name!r}" + (
                    f" (line {cfg.line})" if cfg.line else ""
                )
                shown = ", ".join(str(v) for v in coords)
                raise ExactDataError(
                    f"{where}: the value [{shown}] is not exact data (sympy cannot show that "
                    'the rotation it gives is algebraic); exact mode needs angles such as "pi/6", '
                    '"atan(1/2)" or "2*atan(1/3)"; use --precision auto, float or mp:N for this '
                    "configuration",
                    cfg.name,
                )

    def _coordinates_of_displacement(
        self, cfg: Configuration, jname: str, val: Displacement
    ) -> np.ndarray:
        """The joint's coordinates (its log in the subgroup) of a displacement value.

        The displacement is read in the model's arithmetic and its membership in
        the joint's subgroup decided with the tolerance of the analysis's mode
        (:attr:`data_precision`): 1e-9 in float, 10^(-N/2) at mp:N, exactly in
        exact mode.  An omitted rotation is the identity; an omitted translation
        is completed (:meth:`Subgroup.completing_translation`).
        """
        m = self.model
        jk = m.joint(jname)
        where = f"configuration {cfg.name!r}, joint {jname!r}" + (
            f" (line {val.line})" if val.line else ""
        )
        if jk.subgroup is None:
            raise UserError(f"{where}: a U joint takes two angles [q1, q2], not a displacement")
        prec, decide = m.precision, self.data_precision
        with prec.context():
            R = (
                m.backend.eye(3)
                if val.rotation is None
                else m.asarray([list(r) for r in val.rotation])
            )
            self._check_rotation(where, R)
            if val.translation is None:
                p = jk.subgroup.completing_translation(R, prec)
            else:
                p = m.asarray(list(val.translation))
            g = lie.pose(R, p)
            try:
                q = jk.subgroup.coordinates_of(g, prec)
            except ValueError:
                q = None
            if q is None or not jk.subgroup.contains(g, m.length_scale, decide, q):
                if val.translation is None:
                    raise UserError(
                        f"{where}: no displacement of the joint's {jk.type} subgroup has this "
                        "rotation (whatever the translation); give a rotation the joint can produce"
                    )
                raise UserError(
                    f"{where}: this displacement is not in the joint's {jk.type} subgroup "
                    f"(decided {_to_the_tolerance(decide)}); give a rotation and translation the "
                    "joint can produce, or leave the translation out to have it completed"
                )
            return q

    def _check_rotation(self, where: str, R: np.ndarray) -> None:
        """A given rotation must be orthonormal with det 1, to the mode's tolerance."""
        decide = self.data_precision
        Rf = to_float(R)
        if np.linalg.det(Rf) > 0:
            E = R.T @ R - self.model.backend.eye(3)
            if decide.mode == "exact":  # policy: exact entries only, with its own advice
                if all(exact_is_zero(x) is True for x in E.flat):
                    return
                raise UserError(
                    f"{where}: the rotation is not exactly a rotation matrix (R^T R = I); exact "
                    'mode needs exact entries, such as "sqrt(2)/2" or 0.6 and 0.8; use '
                    "--precision auto, float or mp:N for decimals rounded from a rotation"
                )
            atol = rotation_orthonormal_atol(decide)
            with decide.context():
                err = max(abs(x) for x in decide.asarray(E).flat)
            if err <= atol:
                return
        raise UserError(
            f"{where}: the rotation is not a rotation matrix (R^T R = I, det R = 1) "
            f"{_to_the_tolerance(decide)}; give an orthonormal matrix (with more digits)"
        )

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
                qm, rm = self._polish_mp(m, q, q, gmask, cfg)
                if rm <= self.tolerance:
                    moved = float(np.max(np.abs(to_float(qm) - to_float(q)), initial=0.0))
                    note = (
                        f"the given values close to {_g(res, 3)} m (float's tolerance); "
                        f"projected onto closure at {m.precision} (largest change {moved:.2g})"
                    )
                    return ClosedConfiguration(
                        cfg.name, qm, float(rm), False, 0, tuple(range(m.n)), [note]
                    )
        if res > self.tolerance:
            worst = max(range(len(deltas)), key=lambda i: m.residual_norm([deltas[i]], True))
            raise ClosureError(
                f"configuration {cfg.name!r} gives every joint value but does not close: "
                f"{self._block_named(worst)} leaves a residual of {_g(res, 3)} m "
                f"(accepted: {_g(self.tolerance, 1)} m); "
                "leave the passive joints out so they are solved, or give more digits",
                cfg.name,
                float(res),
            )
        return ClosedConfiguration(cfg.name, q, float(res), False, 0, tuple(range(m.n)))

    # ---------------------------------------------------------------- continuation

    def _continue(
        self,
        cfg: Configuration,
        q0: np.ndarray,
        target: np.ndarray,
        given: tuple[int, ...],
        model: PoseModel | None = None,
    ) -> ClosedConfiguration:
        """Continuation from ``q0`` to the given coordinates of ``target`` in the model
        (``model``: a pose model of this configuration, else the Closer's own)."""
        m: Any = self.model if model is None else model
        # policy: continuation is float by design (an mp model polishes its end point)
        fm: Any = m.float_twin()
        gmask = np.zeros(m.n, dtype=bool)
        gmask[list(given)] = True
        q = to_float(q0).copy()
        qt = to_float(target)
        # straight line in the given coordinates
        span = np.abs(qt - q)[gmask]
        scale = fm.float_frame.rates_back(np.ones(int(gmask.sum())), np.flatnonzero(gmask))
        nsteps = max(1, math.ceil(float(np.max(span / scale, initial=0.0)) / _MAX_STEP))
        if nsteps > _MAX_STEPS:
            raise UserError(
                f"configuration {cfg.name!r}: the given values are {nsteps * _MAX_STEP:.3g} (rad, or lengths / L) "
                f"from {cfg.start or 'reference'!r}, more than continuation follows ({_MAX_STEPS * _MAX_STEP:g}); "
                "add intermediate configurations with start, or give values nearer the start"
            )
        q_start = q.copy()
        t = 0.0
        dt = 1.0 / nsteps
        steps = 0
        underdetermined = False
        at_fold = False
        best_rank = None
        attempts = 0
        while t < 1.0:
            attempts += 1
            if attempts > _MAX_ATTEMPTS_PER_STEP * nsteps + 4 * _MAX_HALVINGS:
                raise ClosureError(
                    f"configuration {cfg.name!r}: continuation from {cfg.start or 'reference'!r} makes no progress "
                    f"after {attempts - 1} step attempts ({_given_reached(fm, q, qt, gmask)}): the path keeps meeting "
                    "near-singular configurations; add intermediate configurations",
                    cfg.name,
                    None,
                )
            t_next = min(1.0, t + dt)
            final = t_next >= 1.0
            qg = q.copy()
            qg[gmask] = (
                qt[gmask] if final else q_start[gmask] + t_next * (qt[gmask] - q_start[gmask])
            )
            ok, qn, info = self._correct(fm, q, qg, gmask, final)
            if ok and not self._same_branch(fm, q, qn, info, gmask):
                ok = False
            if not ok:
                dt /= 2
                if dt < 1.0 / nsteps / 2**_MAX_HALVINGS:
                    landed = self._land_on_fold(fm, q, qt, gmask)
                    if landed is not None:  # the target is the fold itself: reached
                        q, info = landed
                        t, steps, at_fold = 1.0, steps + 1, True
                        continue
                    # values the loops tie together, or a target beyond a limit of travel
                    # (which value, by how much)
                    why = _tied_given(fm, q_start, gmask) or beyond_target(fm, q, qt, gmask)
                    raise ClosureError(
                        f"configuration {cfg.name!r}: continuation from {cfg.start or 'reference'!r} stopped at step "
                        f"{steps + 1}: {_given_reached(fm, q, qt, gmask)}; "
                        + (
                            f"{why}"
                            if why
                            else "the given values cannot be followed further on this assembly "
                            "mode (a singularity or a limit of motion lies on the path); add an "
                            "intermediate configuration or change the target"
                        ),
                        cfg.name,
                        info["residual"],
                    )
                continue
            steps += 1
            underdetermined = underdetermined or info["underdetermined"]
            # loss of rank of the closure Jacobian in the unknowns before the target
            if not final:
                r = info["rank"]
                if (
                    best_rank is not None
                    and r is not None
                    and r < best_rank
                    and info["smin"] < CONTINUATION_SINGULAR_RTOL
                ):
                    raise ClosureError(
                        f"configuration {cfg.name!r}: continuation from {cfg.start or 'reference'!r} meets a "
                        f"singularity at step {steps} ({_given_reached(fm, qn, qt, gmask)}): the closure Jacobian in the unknown joints "
                        f"loses rank ({r} < {best_rank}); joint values there: {_fmt(fm, qn)}; "
                        "choose a target on this side of the singularity, or start from a configuration beyond it",
                        cfg.name,
                        info["residual"],
                    )
                if r is not None:
                    best_rank = r if best_rank is None else max(best_rank, r)
            q = qn
            t = t_next
            dt = min(dt * 1.5, 1.0 / nsteps)
        res = info["residual"]
        notes = []
        if at_fold:
            notes.append(
                "the given values are a fold (a limit of their motion): the unknown joints were "
                "found by Newton from just short of it; float places them only to about 1e-8 there"
            )
        if m.precision.mode == "mp":  # policy: only mp polishes the float landing
            # (a pose model is not rebuilt deeper: its target is polished at N digits)
            qm, res = self._polish_mp(m, q, target, gmask, cfg if model is None else None)
            q_out = qm
        else:
            q_out = q
        if res > self.tolerance:
            # just beyond a fold of the given values: say which limit, and by how much
            with m.precision.context():
                why = beyond_travel(m, q_out, gmask)
            raise ClosureError(
                f"configuration {cfg.name!r} does not close: "
                + (f"{why}; " if why else "")
                + f"residual {_g(res, 3)} m after continuation "
                f"(accepted: {_g(self.tolerance, 1)} m)",
                cfg.name,
                float(res),
            )
        return ClosedConfiguration(
            cfg.name, q_out, float(res), underdetermined, steps, given, notes, at_fold
        )

    def _land_on_fold(
        self, fm: KinematicModel, q: np.ndarray, qt: np.ndarray, gmask: np.ndarray
    ) -> tuple[np.ndarray, dict] | None:
        """The target, when continuation stalls just short of it because it is a fold
        (a limit of the given values: a dead centre, a Type II pose given by the inputs).

        There the unknown joints move like the square root of the given ones, so no
        step is short enough for the predictor, and Newton at the double root only
        halves the distance at each step.  From the last point reached, Newton with the
        given values at the target (a slow step is doubled, which converges at a double
        root) must close; the landing is accepted only where the two branches meet: the
        Jacobian in the unknown joints is singular there (relative smallest singular
        value below CONTINUATION_SINGULAR_RTOL) and the joints moved at most
        CONTINUATION_FOLD_REACH times the square root of what was left.  None otherwise
        (a target beyond the fold has no solution; one before it is not a fold)."""
        L = fm.length_scale

        def comm(d: np.ndarray) -> float:
            return float(np.linalg.norm(fm.float_frame.rates(d)))

        left = comm(np.where(gmask, qt - q, 0.0))
        free = ~gmask
        if left > CONTINUATION_FOLD_GAP or not np.any(free) or not fm.blocks:
            return None
        tol = fm.precision.closure_tolerance(L)
        qn = q.copy()
        qn[gmask] = qt[gmask]
        # the doubled step removes the halving at a double root
        landed = newton_on_group(
            fm, qn, free, solve=damped_least_squares, max_steps=POLISH_MAX_STEPS, doubling=True
        )
        qn, res = landed.q, landed.residual
        if res > tol or comm(fm.difference(qn, q)) > CONTINUATION_FOLD_REACH * math.sqrt(left):
            return None
        Js = _closure_matrix(fm, qn)
        sigma = block_svd(Js[:, free], compute_uv=False)
        if not len(sigma) or sigma[-1] > CONTINUATION_SINGULAR_RTOL * sigma[0]:
            return None
        rank = int(np.sum(sigma > CONTINUATION_SINGULAR_RTOL * sigma[0]))
        info = {
            "residual": res,
            "rank": rank,
            "smin": float(sigma[-1] / sigma[0]),
            "underdetermined": False,
            "predicted": qn,
        }
        return qn, info

    def _same_branch(
        self, fm: KinematicModel, q: np.ndarray, qn: np.ndarray, info: dict, gmask: np.ndarray
    ) -> bool:
        """Did the step stay on the assembly mode it started from?

        Newton's correction must be small next to the predictor step, and near a
        singularity (where two modes are close) the step must be reversible:
        stepping back from ``qn`` returns to ``q``.
        """

        def comm(d: np.ndarray) -> float:
            return float(np.linalg.norm(fm.float_frame.rates(d)))

        step = comm(fm.difference(info["predicted"], q))
        if step == 0.0:
            return True
        # the whole predicted step, passive joints included, stays short: a path on
        # which the passive joints move much faster than the given ones is cut finer
        if step > _MAX_PREDICTED_STEP:
            return False
        if comm(fm.difference(qn, info["predicted"])) > max(
            CONTINUATION_CORRECTOR_RATIO * step, CONTINUATION_JUMP_FLOOR
        ):
            return False
        # with a continuum of solutions (underdetermined) stepping back may land
        # elsewhere on it: reversibility only means something for a determined step
        if info["smin"] < CONTINUATION_REVERSE_RTOL and not info["underdetermined"]:
            back_target = qn.copy()
            back_target[gmask] = q[gmask]
            ok, qb, _ = self._correct(fm, qn, back_target, gmask, False)
            if not ok or comm(fm.difference(qb, q)) > max(
                CONTINUATION_RETURN_RATIO * step, CONTINUATION_JUMP_FLOOR
            ):
                return False
        return True

    def _correct(
        self, fm: KinematicModel, q_prev: np.ndarray, qg: np.ndarray, gmask: np.ndarray, final: bool
    ) -> tuple[bool, np.ndarray, dict]:
        """Predictor (tangent) + damped Newton on the unknown coordinates."""
        free = ~gmask
        L = fm.length_scale
        # the float stage accepts at float's tolerance (an mp model polishes afterwards)
        tol_final = fm.precision.closure_tolerance(L)
        tol = tol_final if final else max(tol_final, CONTINUATION_STEP_RTOL * L)
        # predictor: J_u du = -J_g dg at the previous point
        Js = _closure_matrix(fm, q_prev)
        dg = np.where(gmask, qg - q_prev, 0.0)
        dgs = fm.float_frame.rates(dg)
        q = q_prev.copy()
        if np.any(free) and Js.shape[0]:
            du = damped_least_squares(Js[:, free], -Js[:, gmask] @ dgs[gmask])
            dus = np.zeros(fm.n)
            dus[free] = du
            dus = fm.float_frame.rates_back(dus)
            q = fm.update(q_prev, np.where(gmask, dg, dus))
        else:
            q = fm.update(q_prev, dg)
        q[gmask] = qg[gmask]
        predicted = q.copy()
        res = fm.residual_norm(fm.chord_residuals(q))
        info: dict[str, Any] = {
            "residual": res,
            "rank": None,
            "smin": 1.0,
            "underdetermined": False,
            "predicted": predicted,
        }
        polish = 0

        def stop(it: int, res: float) -> bool:
            nonlocal polish
            if res <= tol and it > 0:
                # at the target, keep iterating while Newton still gains (rounding level)
                if not final or polish >= 2:
                    return True
                polish += 1
            return not fm.blocks or not np.any(free)

        out = newton_on_group(
            fm,
            q,
            free,
            solve=damped_least_squares,
            max_steps=_NEWTON_ITERATIONS,
            residual=res,
            stop=stop,
            # polishing at the target stops when it no longer gains
            keep=lambda res, new: not (res <= tol and new >= res),
            diverged=lambda it, res, new: (
                not np.isfinite(new) or new > 10 * max(res, tol) and it > 2
            ),
        )
        info["residual"] = out.residual
        if out.diverged:
            return False, out.q, info
        q, res = out.q, out.residual
        if res > tol:
            return False, q, info
        if np.any(free) and fm.blocks:
            Js = _closure_matrix(fm, q)
            if not finite_system(Js):
                # closed, but at coordinates so far off that the Jacobian's series
                # overflow (a degenerate loop whose S joint turned without end): no step
                return False, q, info
            dec = decide_rank(Js[:, free], "float", L)
            rank = dec.rank if dec.rank is not None else dec.rank_bounds[0]
            info["rank"] = rank
            s = [x / dec.sigma[0] for x in dec.sigma] if dec.sigma and dec.sigma[0] > 0 else [0.0]
            info["smin"] = s[min(rank, len(s)) - 1] if rank else 0.0
            info["underdetermined"] = rank < int(np.sum(free))
        return True, q, info

    def _polish_mp(
        self,
        m: KinematicModel,
        q: np.ndarray,
        target: np.ndarray,
        gmask: np.ndarray,
        cfg: Configuration | None = None,
    ) -> tuple[np.ndarray, Any]:
        """Newton at N digits from the float solution (given values at full precision).

        Polished to the working precision (10^(5-N) L), not merely to the acceptance
        tolerance 10^(15-N) L: at mp:30 the float solution (1e-16 L) is already
        accepted, and the rank decisions that follow need the screws to N digits (a
        dropped singular value of 1e-17 lies between mp:30's thresholds).

        A target that is itself singular (a change point, a flat parallelogram reached
        from its input) is a multiple root: the residual is quadratic in the distance d
        along the kernel, so N digits of residual place the configuration only to
        d = 10^(-N/2), where its rank cannot be decided at N digits (the kernel's
        singular value is d).  Such a root shows itself by slow steps (see
        :meth:`_newton_mp`); it is then polished again at 2N + 10 digits (the model
        rebuilt from the file's numbers at those digits) and rounded back to N digits.
        """
        qm, res, slow = self._newton_mp(m, q, target, gmask)
        if slow and cfg is not None:
            import mpmath

            deep = self._deeper_model()
            with deep.precision.context():
                dtarget, _ = Closer(deep)._given(cfg)
                qd, _rd, _ = self._newton_mp(deep, qm, dtarget, gmask)
            with m.precision.context():
                qn = np.array([+mpmath.mpf(x) for x in qd], dtype=object)
                rn = m.residual_norm(m.chord_residuals(qn), native=True)
            if rn <= max(res, self.tolerance):
                qm, res = qn, rn
        return qm, res

    def _deeper_model(self) -> KinematicModel:
        """The model at 2N + 10 digits (built once), for multiple roots."""
        if getattr(self, "_deep", None) is None:
            digits = self.model.precision.digits
            self._deep = KinematicModel(self.mech, Precision("mp", 2 * digits + 10))
        return self._deep

    def _newton_mp(
        self, m: KinematicModel, q: np.ndarray, target: np.ndarray, gmask: np.ndarray
    ) -> tuple[np.ndarray, Any, bool]:
        """Newton on the group at the model's digits: (coordinates, residual, whether a
        step was slow).  A step is slow when it lowers the residual by less than
        POLISH_SLOW_RATIO (Newton at a multiple root halves the distance, so lowers the
        residual by 4); the doubled step is then tried too, which for a double root
        converges quadratically again.  Goes on until the correction itself is below
        working precision (at a multiple root a small residual still leaves d =
        sqrt(residual)), and stops when a step no longer lowers the residual."""
        import mpmath

        with m.precision.context():
            if np.asarray(q).dtype == object:
                qm = np.array([mpmath.mpf(x) for x in q], dtype=object)
            else:
                qm = m.asarray([repr(float(x)) for x in q])
            qm[gmask] = target[gmask]
            small = mpmath.mpf(10) ** (POLISH_DIGITS_SPARE - mpmath.mp.dps)
            goal = small * m.length_scale
            out = newton_on_group(
                m,
                qm,
                ~gmask,
                solve=mp_least_squares,
                max_steps=POLISH_MAX_STEPS,
                native=True,
                stop=lambda _it, _res: not m.blocks,
                # closed, and what is left to correct is below working precision
                converged=lambda res, du: (
                    res <= goal and max((abs(x) for x in du), default=0) <= small
                ),
                doubling=True,
            )
            return out.q, out.residual, out.slow


def _closure_matrix(fm: KinematicModel, q: np.ndarray) -> Any:
    """The commensurate closure Jacobian of the float model at q: sparse for a big
    mechanism (:attr:`KinematicModel.sparse_closure`: built from each loop's own
    joints and factorised block by block), dense otherwise."""
    if fm.sparse_closure:
        return fm.sparse_closure_jacobian(q, fm.float_frame)
    return fm.scaled_closure_jacobian(q, fm.float_frame)


def _g(x: Any, digits: int) -> str:
    """A residual or tolerance (float or mpf) in %g style, also below float's range."""
    f = float(x)
    if f != 0 or x == 0:
        return f"{f:.{digits}g}"
    import mpmath

    return mpmath.nstr(x, digits)


def _fmt(m: KinematicModel, q: np.ndarray) -> str:
    return ", ".join(f"{k}={[round(x, 6) for x in v]}" for k, v in m.values(q).items())


def _tied_given(fm: KinematicModel, q: np.ndarray, gmask: np.ndarray) -> str:
    """Why a path in the given coordinates leaves the mechanism's motion when the loops
    tie those coordinates together at ``q`` ('' when they are independent there, or
    when the ranks are not decided).

    The given rates dg can be followed when some rates du of the other coordinates close
    the loops: J_g dg + J_u du = 0.  Those dg form a space of dimension
    n_g - (rank J - rank J_u): when rank J > rank J_u the given values obey that many
    relations, and a straight path between a start and a target (even two that both
    close) generally leaves the set where they hold.  Said only where J_u has full
    column rank (the other coordinates determined): at a fold of the given values J_u
    loses rank instead, and the given values are not tied elsewhere."""
    free = ~gmask
    if isinstance(fm, PoseModel) or not fm.chords or not np.any(free):
        return ""
    Js = _closure_matrix(fm, q)
    if not finite_system(Js):
        return ""
    L = fm.length_scale
    whole = decide_rank(Js[:, np.ones(fm.n, dtype=bool)], "float", L).rank
    part = decide_rank(Js[:, free], "float", L).rank
    # the other coordinates determined (J_u of full column rank) and still fewer
    # constraints absorbed than there are: the given values over-determine; where J_u
    # loses column rank instead, the start is a singularity of the given values (a fold
    # of the inputs), which the caller's words describe
    if whole is None or part is None or whole <= part or part < int(np.sum(free)):
        return ""
    dof = {j.name: j.dof for j in fm.mech.joints}
    labels = [
        jname if dof[jname] == 1 else f"{jname}[{i}]"
        for col, (jname, i) in enumerate(fm.mech.coordinates())
        if gmask[col]
    ]
    n_given = len(labels)
    free_dims = n_given - (whole - part)
    return (
        f"the given coordinates {', '.join(labels)} are not independent: the loops tie them by "
        f"{whole - part} relation(s), so only {free_dims} of the {n_given} can be chosen and the "
        "others follow; give at most "
        f"{free_dims} of them and let mechsing solve the rest (or every joint value of a "
        "configuration that closes)"
    )


def _given_reached(m: Any, q: np.ndarray, target: np.ndarray, gmask: np.ndarray) -> str:
    """The given coordinates where continuation stopped, against their targets,
    in the file's units: ``A reached 173.13 deg, 26.87 deg short of the target 200 deg``."""
    units = m.mech.units
    joints = {j.name: j for j in m.mech.joints}
    parts = []
    for col, (jname, i) in enumerate(m.mech.coordinates()):
        if not gmask[col]:
            continue
        j = joints[jname]
        length = j.units[i] == "m"
        factor = float(units.length_factor if length else units.angle_factor)
        unit = units.length if length else units.angle
        label = jname if j.dof == 1 else f"{jname}[{i}]"
        reached, goal = float(q[col]) / factor, float(target[col]) / factor
        parts.append(
            f"{label} reached {reached:.10g} {unit}, {abs(goal - reached):.3g} {unit} short "
            f"of the target {goal:.10g} {unit}"
        )
    if isinstance(m, PoseModel):
        dx, angle = m.distance(q, target)
        parts.append(
            f"the output {m.mech.output.body!r} is {dx:.3g} m and {angle:.3g} rad "
            f"({math.degrees(angle):.3g} deg) from the target pose"
        )
    return "; ".join(parts)


def solve_configuration(
    mech: Any, name: str, precision: Precision | str = "float"
) -> tuple[KinematicModel, ClosedConfiguration]:
    """Close one named configuration; returns the model and the closed configuration."""
    model = KinematicModel(mech, precision)
    return model, Closer(model).solve(name)


def _to_the_tolerance(prec: Precision) -> str:
    """How a precision mode decides that a given value is what it claims, for messages."""
    if prec.mode == "exact":  # the wording differs, not the arithmetic
        return "exactly, in exact mode"
    with prec.context():
        tol = float(screw_zero_rtol(prec.backend))
    return f"to {tol:.0e} (relative) at {prec} precision"
