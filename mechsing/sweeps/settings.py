"""Owns the settings of the sweeps' algorithms: locating and merging tolerances, the sign
test's screens, the --vary range's rounding (the path engine's are in
:mod:`mechsing.kinematics.settings`).

They choose how a path is followed and where its singular points are placed -- not what a
verdict decides (those thresholds are in :mod:`mechsing.numeric.tolerances`).  Lengths are
commensurate (radians, or lengths over the characteristic length L).  Imports nothing.
"""

from __future__ import annotations

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
#: the closure itself differ by 1.0e-14); nearer its singularity, the SVD of R (the same
#: rule as ``mechsing.numeric.linalg.CLEAR_RANK_RATIO``'s, which this module, importing
#: nothing, does not import: tests/test_criteria.py checks they agree)
SWEEP_GRAM_RATIO = 0.05

#: at a located fold, the unknowns' closure Jacobian has the singular values of the
#: directions that reach their limit there (one per leg at its limit) below this
#: fraction of its largest: float places a fold's unknowns to about sqrt(eps) (the curve
#: is quadratic in them), so those are about 1e-8, and a chain that is not at a limit
#: keeps singular values of the order of its conditioning, far above
SWEEP_FOLD_KERNEL_RTOL = 1e-5

#: a swept sample is beyond a joint's limits when it passes one by more than this part of
#: the limits' width (float's rounding of a sample placed on a limit is not leaving it)
SWEEP_LIMIT_RTOL = 1e-9

#: the tests a fold is listed under: those whose relative measure there is below this
#: (a fold is located on the path's curve to rounding, where the vanishing measure is
#: ~1e-12 or less; the others stay of order one)
SWEEP_FOLD_TEST_RTOL = 1e-6

#: a swept pose coordinate is refused when adding its column raises the rank of the
#: closure system in the solved joints; its singular values above this fraction of the
#: largest count
SWEEP_DETERMINED_RTOL = 1e-8

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

#: a sweep's fold placed again by its own conditions (the closure and the vanishing rate of
#: the swept value) is kept when its swept value moved by at most this fraction of the
#: value's unit (1 rad, or L): the path placed it to about 1e-8 along the curve, so its
#: value to about 1e-16; a larger move is another fold
SWEEP_FOLD_MOVE_RTOL = 1e-6
