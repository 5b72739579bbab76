"""The decision thresholds of mechsing, as constants, and the two rank thresholds.

Here stand only the thresholds a verdict depends on: rank (a singular value kept or
dropped), equality (a screw in a subalgebra, two axes parallel, a factor vanishing, a
mode matched) and the data's resolution and sizes (a number read as a rounding, a size
refused).  Each states its margin rule: what is compared with it and what a value near it
means.  Algorithm settings -- step sizes, iteration counts, screens that only choose a
faster or a safer route to the same answer -- stand beside the code that uses them
(:mod:`mechsing.kinematics.settings`, :mod:`mechsing.sweeps.settings`,
:mod:`mechsing.assembly.settings`, or the one module that uses one), named and documented
there; a test (tests/test_house.py) checks that no tolerance hides as a default argument.

The bottom of :mod:`mechsing.numeric`: it imports nothing from mechsing.  A tolerance
that depends on the precision mode is a function of these constants, beside the
object it depends on (:meth:`mechsing.numeric.Backend.zero_rtol` for a backend's
working precision, :mod:`mechsing.numeric.precision` for a precision mode).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

# ---------------------------------------------------------------------------
# Decision tolerances that are not rank thresholds.  Each is a *decision*
# (membership, identification, classification), so each lives here.
# ---------------------------------------------------------------------------

#: relative tolerance for "this screw lies in that subalgebra" / "these are equal"
#: decisions on float data, relative to the largest entry involved.
#: margin: the residual's ratio to this; at mp:N and exact the backend's own zero test
#: (:meth:`Backend.zero_rtol`) replaces it
MEMBERSHIP_RTOL_FLOAT = 1e-9
#: norm below which a geometric vector given by a user (an axis, a normal) is
#: refused as near-zero (relative to the largest length of the mechanism or 1); and
#: the spread of the axis points below which they coincide (relative to the farthest
#: from the origin), so that the characteristic length is not their rounding
#: margin: a refusal names the vector's norm against this bound
NEAR_ZERO_VECTOR = 1e-9
#: support threshold of a kernel vector (entries above 1e-9 of the largest)
#: margin: an entry's ratio to the largest entry, against this (which joints move)
SUPPORT_RTOL = 1e-9
#: two unit axes are parallel when the norm of their cross product is below this (a
#: product of subgroups turning about parallel axes with their own pitches)
#: margin: the cross product's norm against this (unit axes: an angle in radians)
PARALLEL_AXES_ATOL = 1e-9
#: closure acceptance in float mode, relative to the characteristic length L
#: (mp:N accepts at 10^(15-N) L, never looser than this)
#: margin: the residual over L against this; a configuration that does not close is
#: refused with its residual
CLOSURE_RTOL_FLOAT = 1e-12
#: fewest digits of mp:N: below 20, tau_lo = 10^(10-N) exceeds tau_hi = 10^(-N/2)
#: margin: none (a refusal of the mode's syntax)
MP_MIN_DIGITS = 20


#: largest joint value accepted in a configuration: radians, or times the
#: characteristic length L for a length; larger is an absurd size (an angle of
#: 1e6 rad is 160 000 turns)
#: margin: none (a refusal, naming the value)
MAX_JOINT_VALUE = 1e6
#: largest magnitude of any number a file or a command line gives (a coordinate, a
#: parameter, a joint value, a limit, a sweep range, a screw coordinate), in its own
#: units: 10^12 of them is beyond any mechanism, and squares and products of such
#: numbers stay far from float overflow (1.8e308)
#: margin: none (a refusal, naming the number and where it stands)
MAX_NUMBER = 1e12
#: The tolerances of the higher-order (tangent-cone) tests are placed relative to
#: the mode's ``tau_hi`` (1e-9 in float, 10^(-N/2) at mp:N), so that they keep
#: their meaning at every precision (see :func:`subspace_rank_rtol`,
#: :func:`subspace_containment_atol`, :func:`order3_residual_rtol`):
#:
#: relative singular value below which a direction is dropped from a basis of a
#: subspace (bases of cone pieces, orthonormalised): tau_hi / 10 (float: 1e-10)
#: margin (these three): the ratio to tau_hi, recorded with the cone's decisions
SUBSPACE_RANK_FACTOR = 0.1
#: two orthonormal bases span nested subspaces when the projection residual is
#: below 10 tau_hi (float: 1e-8)
SUBSPACE_CONTAINMENT_FACTOR = 10.0
#: the third-order condition holds on a direction when its residual, relative to
#: the size of its linear part, is below tau_hi (float: 1e-9)
ORDER3_RESIDUAL_FACTOR = 1.0
#: digits of the higher-order and input/output tests of an ``exact`` analysis:
#: the configuration and its screws are exact, the tests run at mp:50 (and say so)
#: margin: the tests' rank margins at these digits
EXACT_TEST_DIGITS = 50
#: the reference configuration has every joint at identity: reading a file refuses a
#: value listed there when it is farther than this from the identity (radians, rotation
#: entries, or lengths relative to the file's largest coordinate); nearer values are
#: decided by the analysis in its mode (to 1e-9 in float, 10^(-N/2) at mp:N, exactly)
#: margin: none (a refusal naming the value and its distance from the identity)
REFERENCE_SCREEN_RTOL = 1e-6
#: a given rotation matrix must satisfy ``|R^T R - I|`` below this in float (and det R > 0);
#: at mp:N below 10^(-N/2), exactly in exact mode (:func:`rotation_orthonormal_atol`)
#: margin: none (a refusal naming ``|R^T R - I|``)
ROTATION_ORTHONORMAL_ATOL = 1e-9
#: batched scans (:mod:`mechsing.sweeps.scan`) decide "full rank" without an SVD when
#: the determinant bound on sigma_min / sigma_max is at least this many times
#: float's tau_hi (room for the SVD's own rounding, which is near eps)
SCAN_SCREEN_FACTOR = 10.0
#: rounding allowance of that bound, in units of (matrix size) x eps: the
#: determinant of J (or of its Gram matrix) is the exact one of a matrix within
#: this of J (backward error of LU), so the bound is lowered by as much
#: margin (these two): a bound below the screen is decided by the SVD and tau_lo / tau_hi,
#: so the screen never changes a verdict, only whether an SVD is needed
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
#: margin: recorded as the Margin's ``rounding``; the JSON's ``dropped`` over it
FLOAT_ROUNDING_FACTOR = 4.0


#: data resolution (issue: verdicts below the resolution of their data).  A plain decimal
#: written with at least this many significant digits is a rounding of the value meant
#: (a float printed to 15-17 digits, a CAD export): its resolution is half a unit in its
#: last written digit.  A shorter decimal (``3``, ``0.25``, ``12.5``: a drawing's
#: dimension) is taken as exact, as an expression (``pi/3``) is: resolution 0
#: margin: the verdict's ``resolution`` record (how far the data's rounding moves the
#: deciding singular values, against the gap to the threshold)
RESOLUTION_MIN_DIGITS = 8


#: exact mode first evaluates a quantity to this many digits: clearly non-zero
#: there (above 10^-(EXACT_ZERO_DIGITS - 15) of its scale) it is not zero, and
#: only the rest is handed to sympy to prove it zero
#: margin: none (a quantity is proven zero by sympy or shown non-zero at these digits)
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
    if type(x) is float and x != 0:  # a float threshold: a few values, each written once
        # (zero not cached: -0.0 equals 0.0 as a key, and is written "-0")
        return _shown_float(x)
    return _shown_any(x)


@lru_cache(maxsize=256)
def _shown_float(x: float) -> str:
    return _shown_any(x)


def _shown_any(x: Any) -> str:
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
#: margin: a sample's relative singular values against this
CONDITION_GENERIC_RANK_RTOL = 1e-8
#: a factor evaluated at a configuration vanishes when it is below this times the
#: sum of the absolute values of its terms (the scale of its cancellation)
#: margin: the factor's value over the scale of its terms, against this
CONDITION_VANISH_RTOL = 1e-9
#: two axes parallel, points collinear ... (unit vectors, lengths relative to the
#: mechanism's size) in the explanations of a factor, tested where it vanishes
#: margin: a relation is named only where it holds to this
CONDITION_GEOMETRY_RTOL = 1e-6
#: a root of a polynomial (numpy.roots, double precision) is real when its imaginary
#: part is below this times ``max(1, |root|)``; a value is a common zero of several
#: polynomials when each is below this times the sum of its terms' magnitudes
#: margin: the imaginary part over ``max(1, |root|)``, against this
CONDITION_ROOT_RTOL = 1e-7

# -- every assembly mode (mechsing.assembly) -------------------------------------------
#: the mode that continuation reaches is the one within this commensurate distance
#: (angles in rad, lengths over L) of continuation's float closure (closed to 1e-12 L)
#: margin: modes are certified to 1e-30 (``MODE_CERTIFY_RADIUS``): two distinct modes are
#: farther apart than this by far, a match is within 1e-12 L
MODE_MATCH_DISTANCE = 1e-8
#: the same for a mode that is not certified (a double root, such as a crank at its limit):
#: float places a fold's unknown joints only to about 1e-8 (the square root of its
#: rounding), and continuation's closure there may lie that far from the mode
MODE_FOLD_MATCH_DISTANCE = 1e-6
#: a body's inertia (about its centre of mass) is refused when it is not symmetric, when
#: an eigenvalue is negative or when its principal moments break the triangle inequality
#: (I1 <= I2 + I3) by more than this times its trace (exact numbers written to a few digits,
#: a thin rod's I1 = I2 + I3, pass)
#: margin: none (a refusal naming the broken condition and its size)
INERTIA_RTOL = 1e-9
#: a closed chain's motion can be produced by its inputs (the Type II crossing condition:
#: the motion's dynamic efforts are balanced by the inputs' efforts and the loops'
#: constraint wrenches) when the balance's least-squares residual is below this times the
#: size of its terms; at a Type II singularity a motion that does not satisfy the condition
#: leaves a residual of the order of the efforts themselves
#: margin: the residual over the size of the balance's terms, against this
CROSSING_RTOL = 1e-9
#: the general formulation: a direction of Study coordinates is in the span of a loop's
#: products (the coordinates of its own subgroup) when its singular value is above this
#: times the largest (the coefficients are known to the working digits, 50 or more; a
#: direction not in the span has an exact zero there); a serial arm's target lies in the
#: subgroup its end moves in when its part outside that span is below this times its size
#: margin: the singular values are known to the working digits (50 or more), so a kept
#: one is above 1e-20 by far or exactly zero
MODE_SPAN_RTOL = 1e-20
# -- cusps of a section of the input space (mechsing.assembly.cusps) ---------------------
#: a root of the eliminant (double precision, np.roots) counts as real on the section's
#: grid when its imaginary part is below this times ``max(1, |t|)``: two roots that leave
#: the real axis at a fold separate as the square root of the distance to it, so a grid
#: point 1e-12 of the input's span from a singular curve still counts right
#: margin: a cusp's certificate is decided apart from this (Krawczyk at 50 digits); this
#: only counts the modes drawn on the section's grid
CUSP_REAL_RTOL = 1e-7
#: two real roots closer than this times ``max(1, |t|)`` are one (a double root counted
#: once: the modes on a singular curve)
#: margin: as CUSP_REAL_RTOL, the grid's count of modes only
CUSP_DISTINCT_RTOL = 1e-6
#: a sweep's closed configuration and an assembly mode (or two closed configurations) with
#: the same given values are on one mode when their commensurate joint distance (angles in
#: rad modulo 2 pi, lengths over L) is below this: each sample is closed to 1e-12 L, and
#: distinct modes lie orders of magnitude farther apart
#: margin: the distance to the nearest mode against this; a start matching none is refused
SWEEP_SAME_MODE_DISTANCE = 1e-6
#: an input/output finding's "most telling motion" (the direction of its motion space the
#: inputs, or the output, move most) is decided when the largest singular value of that
#: map on the space exceeds the second by more than this, relatively; within it (a
#: symmetric pair of motions, which an SVD combines as rounding decides) the finding's
#: ``joint_rates`` is the first row of its canonical ``joint_rate_basis`` instead
#: margin: none needed: both choices lie in the reported space, and rounding (1e-16)
#: moves the two values far less than this
MOST_MOVED_RTOL = 1e-8
#: a six-leg platform's far-reach proof (mechsing.assembly.reach) widens each leg's bound on
#: the platform's direction, and the bound on the unit vectors' error, by this (absolute,
#: on unit vectors), and calls the legs' equations dependent below this times the largest
#: singular value
#: margin: the proof runs at 40 digits (rounding about 1e-35): a conclusion holds with
#: this to spare; within it nothing is concluded and the system is tracked
REACH_PROOF_MARGIN = 1e-12
