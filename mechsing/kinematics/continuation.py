"""Continuation: from a closed configuration to given coordinates on the same
assembly mode.

The given values move along a straight line in small steps; at each step a
first-order predictor and a damped Newton corrector on the group (each update in the
joint's own subalgebra, :meth:`KinematicModel.update`) close the loops again, and the
step is accepted only when it stayed on its branch (:func:`~mechsing.kinematics.paths.steps.same_branch`).
The path stops with :class:`ClosureError` naming the step when the closure Jacobian
in the unknown coordinates loses rank before the target; a target that is a fold of
the given values is landed on (:func:`~mechsing.kinematics.paths.folds.land_on_fold`).  Float by design:
an mp model's landing is polished by :class:`~mechsing.kinematics.polish.MpPolisher`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mechsing.errors import BeyondTravelError, ClosureError, UserError
from mechsing.kinematics.closed import ClosedConfiguration, shown_residual
from mechsing.kinematics.model import KinematicModel
from mechsing.kinematics.newton import finite_system, increment, scaled_jacobian, scaled_system
from mechsing.kinematics.paths.folds import approach_fold, land_on_fold, leave_fold
from mechsing.kinematics.paths.steps import closure_matrix, correct, same_branch
from mechsing.kinematics.polish import MpPolisher, fold_mp, newton_mp
from mechsing.kinematics.pose import POSE_COORDINATES, PoseModel
from mechsing.kinematics.protocol import ClosureModel
from mechsing.kinematics.settings import CONTINUATION_LEAVE_FRACTION, CONTINUATION_SINGULAR_RTOL
from mechsing.kinematics.travel import Fold, beyond_target, coordinate_words, fold_excess
from mechsing.model import Configuration
from mechsing.numeric import decide_rank, to_float

__all__ = ["Continuation", "closure_matrix"]

#: largest step of a given coordinate: radians, or this times L for a length
_MAX_STEP = 0.1
_MAX_HALVINGS = 14
#: most planned steps of one continuation (a crank of 300 turns)
_MAX_STEPS = 20000
#: step attempts allowed per planned step before continuation gives up
_MAX_ATTEMPTS_PER_STEP = 20


class Continuation:
    """Continuation in one kinematic model (or a pose model of it), accepting at
    ``tolerance`` (the model's closure tolerance); ``polisher`` polishes an mp model's
    landing."""

    def __init__(
        self, model: KinematicModel, tolerance: Any, polisher: MpPolisher, at_folds: bool = False
    ) -> None:
        self.model = model
        self.tolerance = tolerance
        self.polisher = polisher
        #: given values just beyond a fold, within their resolution, are analysed at the
        #: fold (an mp:N the user asked for; auto's re-decision keeps float's analysis)
        self.at_folds = at_folds

    def run(
        self,
        cfg: Configuration,
        q0: np.ndarray,
        target: np.ndarray,
        given: tuple[int, ...],
        model: PoseModel | None = None,
    ) -> ClosedConfiguration:
        """Continuation from ``q0`` to the given coordinates of ``target`` in the model
        (``model``: a pose model of this configuration, else the Closer's own)."""
        m: ClosureModel = self.model if model is None else model
        # policy: continuation is float by design (an mp model polishes its end point)
        fm = m.float_twin()
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
        left_fold = start_is_fold = False
        best_rank = None
        attempts = 0
        behind = None  # the start of the last step
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
            ok, qn, info = correct(fm, q, qg, gmask, final)
            if ok and not same_branch(fm, q, qn, info, gmask):
                ok = False
            if not ok:
                dt /= 2
                if dt < 1.0 / nsteps / 2**_MAX_HALVINGS:
                    landed = land_on_fold(fm, q, qt, gmask)
                    if landed is not None:  # the target is the fold itself: reached
                        q, info = landed.q, landed.info
                        t, steps, at_fold = 1.0, steps + 1, True
                        continue
                    near = approach_fold(fm, q, qt, gmask)
                    if near is not None:  # the target lies just short of a fold: reached
                        q, info = near[0].q, near[0].info
                        t, steps = 1.0, steps + near[1]
                        continue
                    if steps == 0 and not left_fold:
                        # a start drawn at a fold: no step of the predictor leaves it
                        t1 = CONTINUATION_LEAVE_FRACTION / nsteps
                        fold, left = leave_fold(fm, q_start, qt, gmask, t1)
                        if left is not None:
                            q, t, steps, left_fold = left, t1, 1, True
                            dt = 1.0 / nsteps
                            continue
                        start_is_fold = fold
                    # values the loops tie together, or a target beyond a limit of travel
                    # (which value, by how much)
                    # (a start that is itself the fold says so first: the target lies
                    # beyond the start, whatever the estimate of the excess says)
                    tied = _tied_given(fm, q_start, gmask)
                    travel = None if tied or start_is_fold else beyond_target(fm, q, qt, gmask)
                    why = tied or travel
                    if not why and start_is_fold:
                        why = (
                            f"the start {cfg.start or 'reference'!r} is a fold of the given "
                            "values (a limit of their travel: the unknown joints lose a "
                            "direction there) and the target lies beyond it; give values on "
                            "the other side of the start"
                        )
                    message = (
                        f"configuration {cfg.name!r}: continuation from {cfg.start or 'reference'!r} stopped at step "
                        f"{steps + 1}: {_given_reached(fm, q, qt, gmask)}; "
                        + (
                            f"{why}"
                            if why
                            else "the given values cannot be followed further on this assembly "
                            "mode (a singularity or a limit of motion lies on the path); add an "
                            "intermediate configuration or change the target"
                        )
                    )
                    if travel:
                        raise BeyondTravelError(message, cfg.name, info.residual, travel)
                    raise ClosureError(message, cfg.name, info.residual)
                continue
            steps += 1
            underdetermined = underdetermined or info.underdetermined
            # loss of rank of the closure Jacobian in the unknowns before the target
            if not final:
                r = info.rank
                if (
                    best_rank is not None
                    and r is not None
                    and r < best_rank
                    and info.smin < CONTINUATION_SINGULAR_RTOL
                ):
                    raise ClosureError(
                        f"configuration {cfg.name!r}: continuation from {cfg.start or 'reference'!r} meets a "
                        f"singularity at step {steps} ({_given_reached(fm, qn, qt, gmask)}): the closure Jacobian in the unknown joints "
                        f"loses rank ({r} < {best_rank}); joint values there: {_fmt(fm, qn)}; "
                        "choose a target on this side of the singularity, or start from a configuration beyond it",
                        cfg.name,
                        info.residual,
                    )
                if r is not None:
                    best_rank = r if best_rank is None else max(best_rank, r)
            behind = q
            q = qn
            t = t_next
            dt = min(dt * 1.5, 1.0 / nsteps)
        res = info.residual
        notes = []
        if left_fold:
            notes.append(
                f"the start {cfg.start or 'reference'!r} is a fold of the given values (two "
                "assembly modes meet there): continuation left it along the first of the two "
                "that reaches the target; the other may be reached from a start beyond it"
            )
        fold_note = (
            "the given values are a fold (a limit of their motion): the unknown joints were "
            "found by Newton from just short of it; "
            + (
                f"at a double root Newton at {m.precision.digits} digits places them to about "
                "half of those digits"
                if m.precision.mode == "mp"
                else "float places them only to about 1e-8 there"
            )
        )
        if at_fold:
            notes.append(fold_note)
        if m.precision.mode == "mp":  # policy: only mp polishes the float landing
            qm, res = self.polisher.polish(m, q, target, gmask, cfg)
            q_out = qm
        else:
            q_out = q
        if res > self.tolerance:
            # just beyond a fold of the given values: say which limit, and by how much
            with m.precision.context():
                fold = fold_excess(m, q_out, gmask)
            at_limit = (
                _within_resolution(
                    self.polisher, self.tolerance, m, cfg, q_out, target, fold, gmask
                )
                if self.at_folds  # joint values or a pose the user gave, at mp:N
                else None
            )
            if (
                at_limit is None
                and self.at_folds  # not auto's re-decision, which keeps float's analysis
                and m.precision.mode == "mp"
                and behind is not None
            ):
                down = _down_the_branch(m, behind, target, gmask, self.tolerance)
                if down is not None:
                    # a simple root at N digits: the values are not the fold float took
                    q_out, res = down
                    return ClosedConfiguration(
                        cfg.name,
                        q_out,
                        float(res),
                        underdetermined,
                        steps,
                        given,
                        [x for x in notes if x != fold_note],
                    )
            if at_limit is None and self.at_folds:
                at_limit = _across_self_motion(
                    self.polisher, self.tolerance, m, cfg, q_out, target, gmask
                )
            if at_limit is not None:
                qf, rf, note, on_fold = at_limit
                # placed on the fold at N digits: float's caveat about folds no longer holds
                kept = [x for x in notes if not (on_fold and x == fold_note)]
                return ClosedConfiguration(
                    cfg.name, qf, float(rf), underdetermined, steps, given, [*kept, note]
                )
            why = None if fold is None else fold.sentence
            message = (
                f"configuration {cfg.name!r} does not close: "
                + (f"{why}; " if why else "")
                + f"residual {shown_residual(res, 3)} m after continuation "
                f"(accepted: {shown_residual(self.tolerance, 1)} m)"
            )
            if why:
                raise BeyondTravelError(message, cfg.name, float(res), why)
            raise ClosureError(message, cfg.name, float(res))
        return ClosedConfiguration(
            cfg.name, q_out, float(res), underdetermined, steps, given, notes, at_fold
        )


def _down_the_branch(
    m: ClosureModel, behind: np.ndarray, target: np.ndarray, gmask: np.ndarray, tolerance: Any
) -> tuple[np.ndarray, Any] | None:
    """Given values a hair short of a fold (1e-13 rad): float lands on the fold itself,
    where the two roots (about the square root of that away) are not told apart and
    Newton at N digits has no direction to them.  From the start of continuation's last
    step (``behind``: on the branch, far from the fold next to the roots' distance) plain
    Newton at N digits goes down the branch to its own root: on x^2 = c it never crosses
    to the other sign (the doubled steps for a double root would throw it across the
    fold).  The root and its residual, or None when it does not close (values beyond the
    fold)."""
    qa, ra, _ = newton_mp(m, behind, target, gmask, doubling=False)
    return (qa, ra) if ra <= tolerance else None


def _fmt(m: ClosureModel, q: np.ndarray) -> str:
    return ", ".join(f"{k}={[round(x, 6) for x in v]}" for k, v in m.values(q).items())


def _tied_given(fm: ClosureModel, q: np.ndarray, gmask: np.ndarray) -> str:
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
    Js = closure_matrix(fm, q)
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


def _given_reached(m: ClosureModel, q: np.ndarray, target: np.ndarray, gmask: np.ndarray) -> str:
    """The given coordinates where continuation stopped, against their targets,
    in the file's units: ``A reached 173.13 deg, 26.87 deg short of the target 200 deg``."""
    parts = []
    for col in range(len(m.mech.coordinates())):
        if not gmask[col]:
            continue
        label, unit, factor, _ = coordinate_words(m, col)
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


def _within_resolution(
    polisher: MpPolisher,
    tolerance: Any,
    m: ClosureModel,
    cfg: Configuration,
    q: np.ndarray,
    target: np.ndarray,
    fold: Fold | None,
    gmask: np.ndarray,
) -> tuple[np.ndarray, Any, str, bool] | None:
    """Given values beyond a limit of travel (``fold``) by no more than the resolution
    of the value the fold is most sensitive to (a configuration drawn at a fold to its
    data's digits): the nearest closed configuration, every coordinate free (Newton's
    least-norm steps from ``q``), polished at the model's digits (and deeper at a
    multiple root, as joint values are), and placed on the fold near it when there is one
    (:func:`~mechsing.kinematics.polish.fold_mp`): the configuration, its residual, the
    note that says so, and whether it is on the fold; None otherwise."""
    if fold is None or m.precision.mode != "mp":
        return None
    coords = m.mech.coordinates()
    if fold.col >= len(coords):  # a pose model's own coordinates follow the joints'
        return _pose_within_resolution(polisher, tolerance, m, cfg, q, target, gmask)
    joint, index = coords[fold.col]
    written = cfg.resolution.get(joint)
    label = m.mech.coordinate_label(joint, index)
    if not written or index >= len(written):
        return None
    resolution, digits = written[index]
    if not resolution or fold.beyond > resolution:
        return None
    # the nearest closed configuration (every coordinate free), then the fold near it
    qf, rf = polisher.polish(m, q, target, np.zeros(m.n, dtype=bool), cfg)
    if rf > tolerance:
        return None
    located = fold_mp(m, qf, fold.col)
    unit = "m" if m.length_columns[fold.col] else "rad"
    digits_here = m.precision.digits
    on_fold = located is not None and located.residual <= tolerance
    if located is not None and on_fold:
        qf, rf = located.q, located.residual
        with m.precision.context():
            moved = abs(to_float(qf[fold.col]) - to_float(target[fold.col]))
        if moved > resolution:
            return None
        where = f"the limit itself ({label} moved by {moved:.2g} {unit} onto it)"
    else:
        # not a fold of this value (a bifurcation, where the whole closure loses rank)
        with m.precision.context():
            moved = abs(to_float(qf[fold.col]) - to_float(target[fold.col]))
        where = f"the nearest closed configuration ({label} moved by {moved:.2g} {unit})"
    note = (
        f"at {digits_here} digits the written decimals do not close ({label} is "
        f"{fold.beyond:.2g} {unit} beyond where the unknown joints lose a direction), "
        f"within the resolution of its {digits}-digit data ({resolution:.2g} {unit}): "
        f"analysed at {where}, polished at {digits_here} digits; give more digits or "
        "exact values to decide the written decimals"
    )
    return qf, rf, note, on_fold


#: the turns (rad; times L for a length) tried along a singularity's self-motion
_SELF_MOTION_TURNS = tuple(k * math.pi / 4 for k in (1, -1, 2, -2, 3, -3, 4))


def _across_self_motion(
    polisher: MpPolisher,
    tolerance: Any,
    m: ClosureModel,
    cfg: Configuration,
    q: np.ndarray,
    target: np.ndarray,
    gmask: np.ndarray,
) -> tuple[np.ndarray, Any, str, bool] | None:
    """Given values that do close, a hair off a singularity where continuation stopped
    (a Z-Y-Z wrist given a rotation 5.8e-18 rad off its axis): at the singularity the
    unknown joints have a self-motion (their Jacobian's kernel; the wrist's first and
    last joints turning against each other), along which the direction the given values
    ask for, out of reach at the stop, comes into reach (the wrist's middle axis turned
    to it).  Newton at the model's digits from points a turn along the kernel that keep
    the residual (a self-motion; a fold's kernel direction does not): the closed
    configuration nearest the stop, with its note; None when none closes."""
    free = ~np.asarray(gmask, dtype=bool)
    if m.precision.mode != "mp" or not np.any(free):
        return None

    def residual(x: np.ndarray) -> float:
        with m.precision.context():
            return float(np.linalg.norm(np.asarray(to_float(scaled_system(m, x, False)[1]))))

    with m.precision.context():
        Js = scaled_jacobian(m, q, False)
        Js = Js.toarray() if hasattr(Js, "toarray") else Js
        A = np.asarray(to_float(m.precision.asarray(Js)[:, free]), dtype=float)
    here = residual(q)
    _u, s, vt = np.linalg.svd(A)
    if not s.size or not s[0]:
        return None
    kernel = [
        vt[i]
        for i in range(vt.shape[0])
        if i >= s.size or s[i] <= CONTINUATION_SINGULAR_RTOL * s[0]
    ]
    best = None
    for k in kernel:
        k = k / np.abs(k).max()
        for turn in _SELF_MOTION_TURNS:
            with m.precision.context():
                start = m.update(q, increment(m, free, m.precision.asarray(turn * k)))
            # a self-motion keeps the residual (a fold's kernel direction does not: its
            # values beyond the fold have no configuration to turn to)
            if residual(start) > 2 * here:
                continue
            qf, rf = polisher.polish(m, start, target, gmask, cfg)
            if rf > tolerance:
                continue
            with m.precision.context():
                moved = max(abs(float(to_float(x))) for x in m.difference(qf, q))
            if best is None or moved < best[2]:
                best = (qf, rf, moved)
    if best is None:
        return None
    qf, rf, moved = best
    digits = m.precision.digits
    note = (
        f"at {digits} digits continuation stopped at a singularity a hair from the given "
        "values (the unknown joints lose a direction there, the one the given values ask "
        "for); they are reached by a turn along the singularity's self-motion (joints "
        f"moved by up to {moved:.3g}), closed by Newton at {digits} digits: the "
        "configuration analysed is the given one, near the singularity, not on it; give "
        "values at the singularity itself to analyse it there"
    )
    return qf, rf, note, False


def _pose_within_resolution(
    polisher: MpPolisher,
    tolerance: Any,
    m: ClosureModel,
    cfg: Configuration,
    q: np.ndarray,
    target: np.ndarray,
    gmask: np.ndarray,
) -> tuple[np.ndarray, Any, str, bool] | None:
    """:func:`_within_resolution` for a pose given with digits to spare
    (:attr:`~mechsing.model.OutputPose.resolution`; a wrist drawn at its singularity,
    where the written rotation lies a rounding off it): the nearest closed configuration
    (the unknown joints and the pose coordinates written with digits to spare free,
    polished at the model's digits) when it moves the written
    pose by no more than its decimals resolve (the rotation by at most the rotation's
    bound: two rotation vectors ``d`` apart differ by a rotation of angle at most
    ``|d|``; each position coordinate by its own; an exact pose coordinate or a given
    joint value by no more than the closure tolerance).  Not placed on a fold: the
    configuration, its residual, the note that says so, False; None otherwise."""
    written = () if cfg.pose is None else cfg.pose.resolution
    if not written or not isinstance(m, PoseModel):
        return None
    nb, L = m.nb, m.length_scale
    # free: the unknown joints and the pose coordinates written with digits to spare (an
    # exact one, a given joint value, stays: least-norm steps would move it too)
    held = np.array(gmask, dtype=bool)
    for i in range(6):
        held[nb + i] = held[nb + i] and not written[i][0]
    qf, rf = polisher.polish(m, q, target, held, cfg)
    if rf > tolerance:
        return None
    with m.precision.context():
        step = m.difference(np.asarray(qf), np.asarray(target))
        moved = [abs(float(to_float(x))) for x in step]
        exact = [float(to_float(tolerance)) / float(to_float(L)), float(to_float(tolerance))]
    # a given joint value stays (the pose is what was written with digits to spare)
    for c in np.flatnonzero(np.asarray(gmask[:nb], dtype=bool)):
        if moved[c] > exact[int(bool(m.length_columns[c]))]:
            return None
    turned = math.hypot(*moved[nb : nb + 3])
    rot_res = written[0][0]
    if turned > (rot_res or exact[0]):
        return None
    for i in range(3, 6):
        if moved[nb + i] > (written[i][0] or exact[1]):
            return None
    # the pose coordinate moved most (lengths over L), to name in the note
    i = max(range(6), key=lambda k: moved[nb + k] / (float(to_float(L)) if k >= 3 else 1.0))
    unit = "m" if i >= 3 else "rad"
    digits = min(d for res, d in written if res)
    parts = ([f"its rotation to {rot_res:.2g} rad"] if rot_res else []) + [
        f"{POSE_COORDINATES[3 + k]} to {written[3 + k][0]:.2g} m"
        for k in range(3)
        if written[3 + k][0]
    ]
    digits_here = m.precision.digits
    note = (
        f"at {digits_here} digits continuation does not close the written pose (it stops "
        f"where the unknown joints lose a direction), within the resolution of its {digits}-digit "
        f"data ({', '.join(parts)}): analysed at the nearest closed configuration "
        f"({POSE_COORDINATES[i]} moved by {moved[nb + i]:.2g} {unit}), polished at "
        f"{digits_here} digits; give more digits or exact values to decide the written "
        "decimals"
    )
    return qf, rf, note, False
