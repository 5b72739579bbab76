"""The settings of the assembly modes' algorithms: certification radius, the realness and
singularity screens of continuation endpoints, the local dimension test's step, the
formulation's choice of a pair of joints.

They choose how the modes are found and certified -- the decision that two modes are one
(:data:`~mechsing.numeric.MODE_MATCH_DISTANCE`) and the span test
(:data:`~mechsing.numeric.MODE_SPAN_RTOL`) are in :mod:`mechsing.numeric.tolerances`.
Imports nothing.
"""

from __future__ import annotations

#: the half-width of the box (m, rad: the formulation's unknowns) in which the Krawczyk
#: test proves each mode's one true solution; the modes are found to 50 digits or more
MODE_CERTIFY_RADIUS = 1e-30

#: the digits continuation from the start closes a configuration at when its float
#: closure matches none of the modes found (a hair inside a fold it lands on the fold
#: itself, between the two modes that meet there)
REACHED_DIGITS = 30

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

#: a root refined at N digits closes a system when every equation's residual is below
#: 10^(-N / this): 1e-16 at 50 digits, where a root of the equations (regular, or a
#: multiple root's polish) is within 10^(-N/2); the real roots of an overconstrained
#: system's random combinations that leave more on the other equations (data written with
#: fewer digits than the geometry needs: a Bennett linkage's axes rounded to 10) are no
#: closed configuration
MODE_CLOSURE_DIGITS = 3

#: the local dimension test at a singular root: a step of this length (the
#: formulation's unknowns) along the Jacobian's null direction, corrected back to the
#: solutions on the hyperplane at that distance; the root lies on a curve when the
#: correction closes to the working digits (an isolated multiple root leaves a residual
#: of the order of the step squared)
MODE_CURVE_STEP = 1e-6

#: Newton's steps at the working digits reuse one double-precision inverse of the
#: Jacobian at the root rounded to double (chord steps: each gains about 16 digits less
#: the condition's) when its least singular value is at least this times its largest,
#: at least 10 digits a step; a worse-conditioned root (one that may be singular:
#: ``MODE_ENDPOINT_SINGULAR_RTOL``, a double root's Jacobian in double precision is
#: about 1e-8) is refined by steps solved at the working digits, from where it was
MODE_CHORD_RTOL = 1e-6

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
