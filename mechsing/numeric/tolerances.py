"""Every decision tolerance of mechsing, as constants, and the two rank thresholds.

The bottom of :mod:`mechsing.numeric`: it imports nothing from mechsing.  A tolerance
that depends on the precision mode is a function of these constants, beside the
object it depends on (:meth:`mechsing.numeric.Backend.zero_rtol` for a backend's
working precision, :mod:`mechsing.numeric.precision` for a precision mode).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import Any

# ---------------------------------------------------------------------------
# Decision tolerances that are not rank thresholds.  Each is a *decision*
# (membership, identification, classification), so each lives here.
# ---------------------------------------------------------------------------

#: relative tolerance for "this screw lies in that subalgebra" / "these are equal"
#: decisions on float data, relative to the largest entry involved.
MEMBERSHIP_RTOL_FLOAT = 1e-9
#: norm below which a geometric vector given by a user (an axis, a normal) is
#: refused as near-zero (relative to the largest length of the mechanism or 1); and
#: the spread of the axis points below which they coincide (relative to the farthest
#: from the origin), so that the characteristic length is not their rounding
NEAR_ZERO_VECTOR = 1e-9
#: support threshold of a kernel vector (entries above 1e-9 of the largest)
SUPPORT_RTOL = 1e-9
#: the centre an identification moves the screws to is the mean of the axis points of
#: the screws that rotate, but not of one whose rotation is below this fraction of the
#: largest: its axis point is as far as its translation over that rotation (a
#: translation with a trace of rotation: 1e4 away for a rotation of 1e-4), and a centre
#: that far makes the commensurate rows ill-conditioned (an X axis then read to 1e-9)
CENTRE_ROTATION_RTOL = 1e-3
#: a reduced row echelon form written to be read (screws.readable.echelon) takes its
#: pivots in column order, but not one below this fraction of the largest entry still
#: to eliminate: a smaller pivot would scale its row by more than 1e6 and bring the
#: data's rounding up to the digits shown (an axis tilted by 3e-8 rad out of a plane is
#: then read in the plane's own columns; the span is unchanged)
ECHELON_PIVOT_RTOL = 1e-6
#: two unit axes are parallel when the norm of their cross product is below this (a
#: product of subgroups turning about parallel axes with their own pitches)
PARALLEL_AXES_ATOL = 1e-9
#: closure acceptance in float mode, relative to the characteristic length L
#: (mp:N accepts at 10^(15-N) L, never looser than this)
CLOSURE_RTOL_FLOAT = 1e-12
#: fewest digits of mp:N: below 20, tau_lo = 10^(10-N) exceeds tau_hi = 10^(-N/2)
MP_MIN_DIGITS = 20
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
#: largest joint value accepted in a configuration: radians, or times the
#: characteristic length L for a length; larger is an absurd size (an angle of
#: 1e6 rad is 160 000 turns)
MAX_JOINT_VALUE = 1e6
#: largest magnitude of any number a file or a command line gives (a coordinate, a
#: parameter, a joint value, a limit, a sweep range, a screw coordinate), in its own
#: units: 10^12 of them is beyond any mechanism, and squares and products of such
#: numbers stay far from float overflow (1.8e308)
MAX_NUMBER = 1e12
#: continuation accepts intermediate steps at this residual (times L); the target
#: itself is accepted at the precision's closure tolerance
CONTINUATION_STEP_RTOL = 1e-9
#: a nearby configuration found by sampling or by following a branch counts as
#: closed at this residual (times L)
SAMPLE_CLOSURE_RTOL = 1e-10
#: a sample that lands closer to q than this fraction of its step is q itself
#: (Newton fell back): not a nearby configuration
SAMPLE_DISTINCT_RATIO = 0.1
#: a branch probe follows its tangent when the cosine between the tangent and
#: the displacement found is above this (a smooth branch through the point)
BRANCH_ALIGNMENT = 0.9
#: The tolerances of the higher-order (tangent-cone) tests are placed relative to
#: the mode's ``tau_hi`` (1e-9 in float, 10^(-N/2) at mp:N), so that they keep
#: their meaning at every precision (see :func:`subspace_rank_rtol`,
#: :func:`subspace_containment_atol`, :func:`order3_residual_rtol`):
#:
#: relative singular value below which a direction is dropped from a basis of a
#: subspace (bases of cone pieces, orthonormalised): tau_hi / 10 (float: 1e-10)
SUBSPACE_RANK_FACTOR = 0.1
#: two orthonormal bases span nested subspaces when the projection residual is
#: below 10 tau_hi (float: 1e-8)
SUBSPACE_CONTAINMENT_FACTOR = 10.0
#: the third-order condition holds on a direction when its residual, relative to
#: the size of its linear part, is below tau_hi (float: 1e-9)
ORDER3_RESIDUAL_FACTOR = 1.0
#: digits of the higher-order and input/output tests of an ``exact`` analysis:
#: the configuration and its screws are exact, the tests run at mp:50 (and say so)
EXACT_TEST_DIGITS = 50
#: the reference configuration has every joint at identity: reading a file refuses a
#: value listed there when it is farther than this from the identity (radians, rotation
#: entries, or lengths relative to the file's largest coordinate); nearer values are
#: decided by the analysis in its mode (to 1e-9 in float, 10^(-N/2) at mp:N, exactly)
REFERENCE_SCREEN_RTOL = 1e-6
#: a given rotation matrix must satisfy ``|R^T R - I|`` below this in float (and det R > 0);
#: at mp:N below 10^(-N/2), exactly in exact mode (:func:`rotation_orthonormal_atol`)
ROTATION_ORTHONORMAL_ATOL = 1e-9
#: batched scans (:mod:`mechsing.sweeps.scan`) decide "full rank" without an SVD when
#: the determinant bound on sigma_min / sigma_max is at least this many times
#: float's tau_hi (room for the SVD's own rounding, which is near eps)
SCAN_SCREEN_FACTOR = 10.0
#: rounding allowance of that bound, in units of (matrix size) x eps: the
#: determinant of J (or of its Gram matrix) is the exact one of a matrix within
#: this of J (backward error of LU), so the bound is lowered by as much
SCAN_ROUNDING_FACTOR = 16.0


#: auto re-decides at mp:50 a float rank decision whose largest dropped singular value
#: exceeds this many times float's own rounding of it (:func:`float_drop_is_real`).  A
#: computed singular value is off by at most the norm of the error in the matrix (Weyl):
#: the rounding of its entries, about ``eps |M|_F`` (recorded as the margin's ``rounding``),
#: plus the SVD's backward error and the roundings that built each entry (products of
#: exponentials, Jacobians, earlier float factorisations) -- this factor -- plus the
#: effect of a configuration closed only to a residual r: ``r / L |M|``.  Singular values
#: that are exactly zero come out below 2 ``eps |M|_F`` on the examples and the
#: near-singular families, and up to about 5 ``eps |M|_F`` on matrices built from other
#: float factorisations (the legs' constraint wrenches); 10^-14 from a singularity the
#: deciding singular values of benchmarks/speed_accuracy.py's families are 5 to 20
#: ``eps |M|_F``.  A drop above the bound is a singular value that float's thresholds call
#: zero but that float itself sees is not: auto re-decides the configuration at mp:50
#: when float found it singular (at a singular configuration a zero above the bound only
#: costs that second analysis; a regular one is never re-decided).
FLOAT_ROUNDING_FACTOR = 4.0

#: sweeps (:mod:`mechsing.sweeps`).  A path is followed through nodes at most
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
#: two samples' relative singular values within this relative distance are a tie, which
#: rounding (another BLAS kernel, another machine) may break either way: a sweep's summary
#: names the first of the tied lowest samples in sweep order, and a test whose values are
#: all tied (a planar loop's constant constraint rank) is said to be constant
SWEEP_TIE_RTOL = 1e-9
#: a sampled local minimum of a test's smallest relative singular value is refined when
#: it is at most this many times the rise to its higher neighbour: a zero between the
#: neighbours makes a V (or a parabola touching 0) whose lowest sample is at most half
#: (a quarter) of that rise; a shallow minimum far from zero is left alone
SWEEP_MINIMUM_SCREEN = 2.0
#: a path through a singular point of the closure (two branches crossing) is walked
#: towards it from both sides, then fitted from points SWEEP_BRANCH_OFFSET apart on both
#: sides (radians, or lengths / L): far outside the 1e-8 that float's double root blurs,
#: close enough that a cubic is exact to rounding (offset^4 = 1e-16)
SWEEP_BRANCH_OFFSET = 1e-4
#: a sweep's sign test between neighbouring samples a and b reads ``u^T A_b v`` (u, v the
#: weakest singular pair at a); where the matrix moved less than ``sigma`` at a, that
#: product is positive by Weyl's bound, which stands for it when it clears the roundings
#: of both (the SVD's backward error and the product's, a few ``eps |A|_F`` each) by this
#: factor times ``eps |A_a|_F``
SWEEP_SCREEN_ROUNDING = 1e3
#: a sweep's closure of full row rank (its triangular factor R) has its singular values
#: from the eigenvalues of R^T R where its smallest relative one is at least this: the
#: eigenvalues are off by a few eps sigma_1^2, so sigma_i by a few eps / (2 rho_i^2), at
#: most 200 eps here (the SVD's own rounding is eps / rho, up to 20 eps: on the hexapod's
#: turn, rho 0.094 to 0.14, the two differ by 1.3e-14 relative, as the SVDs of R and of
#: the closure itself differ by 1.0e-14); nearer its singularity, the SVD of R
SWEEP_GRAM_RATIO = 0.05
#: first step (commensurate arclength) when a path is followed along its curve through a
#: fold (pseudo-arclength continuation), and the shortest step before it gives up
SWEEP_ARC_STEP = 0.02
SWEEP_ARC_MIN_STEP = 1e-10
#: at a located fold, the unknowns' closure Jacobian has the singular values of the
#: directions that reach their limit there (one per leg at its limit) below this
#: fraction of its largest: float places a fold's unknowns to about sqrt(eps) (the curve
#: is quadratic in them), so those are about 1e-8, and a chain that is not at a limit
#: keeps singular values of the order of its conditioning, far above
SWEEP_FOLD_KERNEL_RTOL = 1e-5
#: a swept sample is beyond a joint's limits when it passes one by more than this part of
#: the limits' width (float's rounding of a sample placed on a limit is not leaving it)
SWEEP_LIMIT_RTOL = 1e-9
#: a node of a path closed from its prediction is kept when Newton moved it at most this
#: fraction of the step (commensurate): a well-predicted step stays on its branch, a
#: larger correction may have jumped to another assembly mode
SWEEP_NODE_CORRECTION = 0.3
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
#: the tests a fold is listed under: those whose relative measure there is below this
#: (a fold is located on the path's curve to rounding, where the vanishing measure is
#: ~1e-12 or less; the others stay of order one)
SWEEP_FOLD_TEST_RTOL = 1e-6
#: a swept pose coordinate is refused when adding its column raises the rank of the
#: closure system in the solved joints; its singular values above this fraction of the
#: largest count
SWEEP_DETERMINED_RTOL = 1e-8
#: a start where branches cross: a direction over the kernel is tried only where the
#: swept value's share of it is at least this (a direction that hardly moves the swept
#: value does not lead along the sweep)
SWEEP_BRANCH_MIN_SWEPT = 0.05
#: points of one row located by several tests (or a fold and a test) are one point when
#: their swept values agree to SWEEP_MERGE_FACTOR times SWEEP_LOCATE_TOL plus
#: SWEEP_MERGE_RTOL (both in radians, or lengths / L): each test locates to
#: SWEEP_LOCATE_TOL, a blurred one (near a singular point of the closure) to far less
SWEEP_MERGE_FACTOR = 1e3
SWEEP_MERGE_RTOL = 1e-9
#: a path through a singular point of the closure: the six points around it, the
#: measure signed by side, make one smooth signed curve when their cubic fits them to
#: this fraction of their largest value; its roots count as real where their imaginary
#: part is below SWEEP_BRANCH_ROOT_IMAG (in offsets, of order one)
SWEEP_BRANCH_FIT_RTOL = 1e-6
SWEEP_BRANCH_ROOT_IMAG = 1e-9
#: a --vary range START:STOP:STEP holds ``floor(|STOP - START| / STEP (1 + SWEEP_RANGE_RTOL)
#: + SWEEP_RANGE_ATOL) + 1`` samples: STOP is included when the steps land on it up to the
#: rounding of the decimal numbers written (0.3 / 0.1 is 2.9999999999999996)
SWEEP_RANGE_RTOL = 1e-12
SWEEP_RANGE_ATOL = 1e-9
#: an end of a --vary range within this of a non-zero multiple of pi/2 (in the file's
#: number) looks like radians in a degree file (3.14 is pi to 0.0016): a warning
RADIAN_LOOK_ATOL = 0.01

#: data resolution (issue: verdicts below the resolution of their data).  A plain decimal
#: written with at least this many significant digits is a rounding of the value meant
#: (a float printed to 15-17 digits, a CAD export): its resolution is half a unit in its
#: last written digit.  A shorter decimal (``3``, ``0.25``, ``12.5``: a drawing's
#: dimension) is taken as exact, as an expression (``pi/3``) is: resolution 0
RESOLUTION_MIN_DIGITS = 8
#: the finite-difference step (radians, or lengths / L) over which the tests' singular
#: values are differentiated with respect to a given value, for the first-order bound
#: of what the data's resolution can move them by: far above float's rounding of the
#: differences (1e-16 / 1e-6 relative) and small enough that the first order holds
RESOLUTION_STEP = 1e-6

#: a configuration that does not close is beyond a limit of travel when, where Newton on
#: its unknown joints stops, the residual lies along the direction they cannot correct
#: (the left singular vector of their Jacobian's smallest singular value): at least this
#: fraction of it (a cosine); :mod:`mechsing.kinematics.travel`
TRAVEL_RESIDUAL_ALIGNMENT = 0.9

#: exact mode first evaluates a quantity to this many digits: clearly non-zero
#: there (above 10^-(EXACT_ZERO_DIGITS - 15) of its scale) it is not zero, and
#: only the rest is handed to sympy to prove it zero
EXACT_ZERO_DIGITS = 60


@dataclass(frozen=True)
class Tolerances:
    """The two rank thresholds of a precision mode, relative to sigma_max.

    A rank is ``r`` when ``sigma_r >= tau_hi`` and ``sigma_{r+1} <= tau_lo``
    (both relative to the largest singular value); a singular value strictly
    between the two leaves the rank undecided.  Floats in float mode; at mp:N
    mpmath numbers (10^(10-N) and 10^(-N/2) are below the float range for large N),
    compared with the mode's own numbers.
    """

    tau_lo: Any
    tau_hi: Any

    def shown(self) -> tuple[str, str]:
        """``tau_lo`` and ``tau_hi`` as text (``1e-12``, ``1e-40``, ``3.16228e-351``)."""
        return _shown(self.tau_lo), _shown(self.tau_hi)


def _shown(x: Any) -> str:
    f = float(x)
    if x == 0 or abs(f) >= sys.float_info.min:  # a normal float (not a rounded subnormal)
        return f"{f:g}"
    import mpmath  # below the float range: an mp number (mpmath's own text of one with
    # thousands of exponent digits converts an integer of as many digits, refused by Python)

    e = int(mpmath.floor(mpmath.log10(abs(x))))
    m = float(x * mpmath.mpf(10) ** (-e))
    return f"{m:g}e{e:+03d}" if m != 1 else f"1e{e:+03d}"


# -- symbolic conditions (mechsing.conditions) -----------------------------------
#: relative singular value below which a Jacobian evaluated at random joint values
#: loses a rank: the generic rank, and which rows of a subgroup's coordinates to keep
CONDITION_GENERIC_RANK_RTOL = 1e-8
#: a factor evaluated at a configuration vanishes when it is below this times the
#: sum of the absolute values of its terms (the scale of its cancellation)
CONDITION_VANISH_RTOL = 1e-9
#: two axes parallel, points collinear ... (unit vectors, lengths relative to the
#: mechanism's size) in the explanations of a factor, tested where it vanishes
CONDITION_GEOMETRY_RTOL = 1e-6
#: a root of a polynomial (numpy.roots, double precision) is real when its imaginary
#: part is below this times ``max(1, |root|)``; a value is a common zero of several
#: polynomials when each is below this times the sum of its terms' magnitudes
CONDITION_ROOT_RTOL = 1e-7
#: two roots (rad or m) closer than this are one (a double root, or two factors' roots)
CONDITION_ROOT_MERGE = 1e-9

#: the largest degree (bounded by the product of the radicals' indices) of a number field
#: exact mode builds for a configuration's data (the bundled 6-UPS and 3-UPU platforms: 32,
#: five square roots); beyond it, the primitive element and the factoring over it can take
#: longer than the general sympy path, which then serves (float mode's loop identification
#: at the drawn pose of a file with many different radicals stalled there)
EXACT_FIELD_MAX_DEGREE = 32

# -- grading exercises (mechsing.exercises) --------------------------------------
#: a student's formula agrees with the key's at a point when they differ there by at most
#: this times the larger of their values (a relative test); a key's question may set its
#: own ``tol``
EXERCISE_FORMULA_RTOL = 1e-9

# -- every assembly mode (mechsing.assembly) -------------------------------------------
#: the half-width of the box (m, rad: the formulation's unknowns) in which the Krawczyk
#: test proves each mode's one true solution; the modes are found to 50 digits or more
MODE_CERTIFY_RADIUS = 1e-30
#: the mode that continuation reaches is the one within this commensurate distance
#: (angles in rad, lengths over L) of continuation's float closure (closed to 1e-12 L)
MODE_MATCH_DISTANCE = 1e-8
#: a continuation endpoint (double precision, Bertini 2) is real when each imaginary part
#: is below this times ``max(1, |z|)``; a real one is then refined at 50 digits or more,
#: and only a refined one is a mode
MODE_IMAGINARY_RTOL = 1e-6
#: a serial arm's joint pair (c, s) is isotropic, c^2 + s^2 = 0 (no joint value: an
#: extraneous solution of the half-angle formulation), when ``abs(c^2 + s^2)`` is below
#: this times ``abs(c)^2 + abs(s)^2``; a prismatic pair's c is zero (an infinite slide)
#: likewise
MODE_ISOTROPIC_RTOL = 1e-8
#: two consecutive joints of a serial arm can carry the formulation when the Study
#: quadric restricted to the span of their displacements has every eigenvalue above this
#: (lengths over L): their lines are skew, neither parallel nor meeting
MODE_PAIR_SKEW = 1e-6
#: three consecutive revolute axes meet in a point or are parallel (Pieper's arms: at
#: most 8 solutions) when their distances (over L) and angles are below this
MODE_PIEPER_ATOL = 1e-9
#: a root refined at N digits is singular (a multiple root, or a point of a curve of
#: solutions: no interval test can certify it) when its Jacobian's least singular value
#: is below 10^(-N / this) times its largest: 1e-16 at 50 digits, where Newton stops
#: within about 10^(-N/2) of a double root (a regular root as ill-conditioned as 1e-13,
#: an arm 1e-13 rad from its wrist singularity, is refined to 37 digits and certified)
MODE_SINGULAR_DIGITS = 3
#: the local dimension test at a singular root: a step of this length (the
#: formulation's unknowns) along the Jacobian's null direction, corrected back to the
#: solutions on the hyperplane at that distance; the root lies on a curve when the
#: correction closes to the working digits (an isolated multiple root leaves a residual
#: of the order of the step squared)
MODE_CURVE_STEP = 1e-6
#: a continuation endpoint (double precision) may be a singular root -- a multiple root
#: or a point of a curve of solutions, where the count cannot be proven -- when its
#: Jacobian's least singular value is below this times its largest (a regular root of
#: the bundled arms stays above 1e-4; an endpoint on a curve is within its accuracy,
#: 1e-9); it is then refined at N digits and singular only if it is there
#: (``MODE_SINGULAR_DIGITS``)
MODE_ENDPOINT_SINGULAR_RTOL = 1e-7
#: with a pair of joints whose lines are parallel or meet, a continuation endpoint is
#: extraneous (off the pair's displacements) when the four conditions of the product in
#: their span leave a residual above this times the sum of their terms' magnitudes
MODE_EXTRANEOUS_RTOL = 1e-6
#: a singular continuation endpoint (a multiple root's: accurate to about the square root
#: of double precision, or worse after the endgame) may be a real root when its imaginary
#: parts are below this times ``max(1, |z|)``: it is polished in real arithmetic at 50
#: digits and kept only where that closes
MODE_SINGULAR_IMAGINARY_RTOL = 1e-3
#: a body's inertia (about its centre of mass) is refused when it is not symmetric, when
#: an eigenvalue is negative or when its principal moments break the triangle inequality
#: (I1 <= I2 + I3) by more than this times its trace (exact numbers written to a few digits,
#: a thin rod's I1 = I2 + I3, pass)
INERTIA_RTOL = 1e-9
#: a closed chain's motion can be produced by its inputs (the Type II crossing condition:
#: the motion's dynamic efforts are balanced by the inputs' efforts and the loops'
#: constraint wrenches) when the balance's least-squares residual is below this times the
#: size of its terms; at a Type II singularity a motion that does not satisfy the condition
#: leaves a residual of the order of the efforts themselves
CROSSING_RTOL = 1e-9
#: the general formulation: a direction of Study coordinates is in the span of a loop's
#: products (the coordinates of its own subgroup) when its singular value is above this
#: times the largest (the coefficients are known to the working digits, 50 or more; a
#: direction not in the span has an exact zero there); a serial arm's target lies in the
#: subgroup its end moves in when its part outside that span is below this times its size
MODE_SPAN_RTOL = 1e-20
#: a sweep's fold placed again by its own conditions (the closure and the vanishing rate of
#: the swept value) is kept when its swept value moved by at most this fraction of the
#: value's unit (1 rad, or L): the path placed it to about 1e-8 along the curve, so its
#: value to about 1e-16; a larger move is another fold
SWEEP_FOLD_MOVE_RTOL = 1e-6
