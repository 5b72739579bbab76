"""The settings of kinematics' algorithms: Newton's damping, polishing, continuation, the path engine.

Step sizes, iteration counts and ratios that choose how a configuration is closed,
polished or followed -- not what a verdict decides (those thresholds are in
:mod:`mechsing.numeric.tolerances`).  Lengths are commensurate (radians, or lengths over
the characteristic length L).  Imports nothing.
"""

from __future__ import annotations

#: continuation stops when the smallest kept singular value of the closure
#: Jacobian in the unknown joints (relative to the largest) falls below this
#: before the target while the rank drops
CONTINUATION_SINGULAR_RTOL = 1e-6

#: a continuation step is rejected (and halved) when Newton's correction is
#: larger than this fraction of the predictor step: it may have jumped to
#: another assembly mode
CONTINUATION_CORRECTOR_RATIO = 0.5

#: below this relative smallest singular value (unknown joints) a step must be
#: reversible: stepping back must return within CONTINUATION_RETURN_RATIO of
#: the step to the previous point (near a fold two modes are close)
CONTINUATION_REVERSE_RTOL = 1e-2
CONTINUATION_RETURN_RATIO = 0.1

#: corrections and returns smaller than this (commensurate: radians, or
#: lengths / L) are rounding, never a jump between assembly modes
CONTINUATION_JUMP_FLOOR = 1e-9

#: a target continuation cannot step onto is tried directly (Newton from the last point
#: reached) when what is left is at most this (commensurate); it is accepted only at a
#: fold: the unknown joints' Jacobian there has relative smallest singular value below
#: CONTINUATION_SINGULAR_RTOL, and the landing moved them at most CONTINUATION_FOLD_REACH
#: times the square root of what was left (the two branches meet like a square root)
CONTINUATION_FOLD_GAP = 1e-4

#: a target continuation cannot step onto, not a fold itself but just short of one
#: (nearer it than the shortest step reaches): each step goes half the given values' way
#: left, so the fold stays at least twice the step away, the whole way once Newton closes
#: there on the same branch; at most this many halvings, after which the target is taken
#: to lie beyond the fold
CONTINUATION_APPROACH_HALVINGS = 40

#: continuation from a start drawn at a fold of the given values (its unknown joints'
#: Jacobian one rank short: a dead centre, a toggle): the first configuration is closed at
#: CONTINUATION_LEAVE_FRACTION of the first step, from the start moved along the
#: Jacobian's kernel by each of CONTINUATION_LEAVE_SIZES times the square root of the given
#: values' move d (the two modes that meet at a fold lie about sqrt(d) away), and kept when
#: it closes at least CONTINUATION_LEAVE_OFF sqrt(d) away from the start (off the fold)
CONTINUATION_LEAVE_FRACTION = 1e-2
CONTINUATION_LEAVE_SIZES = (1.0, 0.25, 4.0)
CONTINUATION_LEAVE_OFF = 0.05
CONTINUATION_FOLD_REACH = 10.0

#: mp:N polishes a closed configuration with Newton at N digits until its
#: residual is below 10^(POLISH_DIGITS_SPARE - N) L (working precision, with a
#: few digits spare for the rounding of poses), in at most POLISH_MAX_STEPS steps
POLISH_DIGITS_SPARE = 5
POLISH_MAX_STEPS = 24

#: a polish step that lowers the residual by less than this factor is slow (Newton at a
#: multiple root lowers it by 4): the doubled step is tried too
POLISH_SLOW_RATIO = 8

#: damping of the float Newton steps on the closure (damped least squares, one
#: configuration or a batch), relative to sigma_max (or a bound of it)
NEWTON_DAMPING = 1e-7

#: continuation accepts intermediate steps at this residual (times L); the target
#: itself is accepted at the precision's closure tolerance
CONTINUATION_STEP_RTOL = 1e-9

#: a configuration that does not close is beyond a limit of travel when, where Newton on
#: its unknown joints stops, the residual lies along the direction they cannot correct
#: (the left singular vector of their Jacobian's smallest singular value): at least this
#: fraction of it (a cosine); :mod:`mechsing.kinematics.travel`
TRAVEL_RESIDUAL_ALIGNMENT = 0.9

# -- the path engine (mechsing.kinematics.paths: sweeps, effort limits, mode loops) -------
#: these keep the SWEEP_ names they had when only the sweeps followed paths

#: A path is followed through nodes at most
#: SWEEP_NODE_STEP apart (radians, or lengths / L), each closed from the tangent's
#: prediction and kept only when Newton moved it little (else the step is halved, and at
#: last the careful continuation of a named configuration takes it); the samples between
#: nodes are closed together by batched Newton from the cubic through the nodes around
#: them, and a sample whose correction exceeds SWEEP_JUMP_RATIO times the node spacing is
#: closed again by continuation (it may have jumped to another assembly mode)
SWEEP_NODE_STEP = 0.25
SWEEP_JUMP_RATIO = 0.25

#: where a path's samples are closer together than this (radians, or lengths / L), the
#: samples between two nodes are closed in two passes: first knots about this far apart
#: (from the nodes' cubic), then the samples between the knots (from the knots' cubic,
#: about (SWEEP_KNOT_STEP / SWEEP_NODE_STEP)^4 nearer: one Newton step each)
SWEEP_KNOT_STEP = 0.01

#: a located singularity (a sign change, a minimum, a fold) is refined until the swept
#: value is known to this (radians, or lengths / L): well below the 1e-10 promised
SWEEP_LOCATE_TOL = 1e-12

#: first step (commensurate arclength) when a path is followed along its curve through a
#: fold (pseudo-arclength continuation), and the shortest step before it gives up
SWEEP_ARC_STEP = 0.02
SWEEP_ARC_MIN_STEP = 1e-10

#: a node of a path closed from its prediction is kept when Newton moved it at most this
#: fraction of the step (commensurate): a well-predicted step stays on its branch, a
#: larger correction may have jumped to another assembly mode
SWEEP_NODE_CORRECTION = 0.3

#: a node of a path is predicted only this far (commensurate, passive joints included):
#: where the passive joints swing much faster than the given ones (a five-bar's distal
#: links near their closest approach) the prediction of a whole step can overshoot
#: towards another assembly mode and Newton close there within the correction allowed;
#: the step is halved instead
SWEEP_NODE_SWING = 1.0

#: the rank of a path's closure Jacobian in its unknowns and the swept coordinate (whose
#: kernel is the curve's tangent, or the branches' directions where branches cross):
#: singular values above this fraction of the largest count (a regular point of the curve
#: keeps them of the order of its conditioning; float's rounding leaves ~1e-16)
SWEEP_CURVE_RANK_RTOL = 1e-9

#: where that kernel has several directions, the one nearest the previous tangent is the
#: curve's only when it keeps at least this much of it (the norm of its projection)
SWEEP_TANGENT_KEPT = 0.5

#: a pseudo-arclength step is accepted when the tangent turns by at most this many
#: degrees over it (a longer step is halved where the curve bends)
SWEEP_ARC_MAX_TURN_DEG = 30.0

#: a pseudo-arclength corrector has converged when its last correction is at most
#: SWEEP_ARC_STEP_ATOL + SWEEP_ARC_STEP_RTOL times the step (and the residual closes)
SWEEP_ARC_STEP_ATOL = 1e-13
SWEEP_ARC_STEP_RTOL = 1e-9

#: a start where branches cross: a direction over the kernel is tried only where the
#: swept value's share of it is at least this (a direction that hardly moves the swept
#: value does not lead along the sweep)
SWEEP_BRANCH_MIN_SWEPT = 0.05
