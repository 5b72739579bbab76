"""The settings of kinematics' algorithms: Newton's damping, polishing, continuation.

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
