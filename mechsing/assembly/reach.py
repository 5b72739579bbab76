"""A six-leg platform hung far from its base: no real pose, proven before tracking.

Owns :func:`far_out_of_reach`.

Write the pose ``x -> R x + p``, a leg from the base point ``a_i`` to the platform point
``b_i`` (at the reference pose) of length ``L_i``, ``c_i = R b_i - a_i`` (so
``|c_i| <= r_i = |a_i| + |b_i|``) and ``D = |p|``, ``u = p / D``, ``v = R^T u``.  Then
``L_i^2 = D^2 + 2 D u.c_i + |c_i|^2`` and, subtracting leg 1's,

    v.(b_i - b_1) - u.(a_i - a_1) = (L_i^2 - L_1^2) / (2 D) - (|c_i|^2 - |c_1|^2) / (2 D),

five equations linear in ``x = (u, v)``, two unit vectors of R^3.  ``|D - L_i| <= r_i``
bounds ``D`` to ``[D_lo, D_hi]``, so each right side lies in a known interval, narrow when
the legs are long (its width is about ``r^2 / L``).  With ``M`` the 5 x 6 matrix of the
left sides (rank 5 for a general platform), ``x = x_c + t n + w`` where ``x_c`` is the
least-norm solution at the intervals' centres, ``n`` the unit null vector of ``M``,
``|t| <= |x| = sqrt(2)`` and ``|w| <= omega = |half-widths| / sigma_min(M)``.  A real pose
needs a ``t`` with both ``| |u_c + t n_u| - 1 |`` and ``| |v_c + t n_v| - 1 |`` at most
``omega``; bisection of ``[-sqrt(2), sqrt(2)]`` with the Lipschitz bounds ``|n_u|``,
``|n_v|`` shows there is none (a proof) or stops at its depth (nothing said).  As the legs
grow with fixed differences the five equations in the four freedoms of two unit vectors
become overdetermined: no real pose hangs that far, and this says so at once.
"""

from __future__ import annotations

from typing import Any

import mpmath
import sympy

from mechsing.numeric._mp import svd_r
from mechsing.numeric.tolerances import REACH_PROOF_MARGIN

__all__ = ["far_out_of_reach"]

#: working digits of the proof (its rounding, about 1e-35, far below REACH_PROOF_MARGIN)
DIGITS = 40
#: halvings of [-sqrt(2), sqrt(2)] before the proof gives up (pieces of 3e-6 at the end)
DEPTH = 20
#: pieces examined at most (the bisection's work bound)
MAX_PIECES = 20000


def far_out_of_reach(legs: Any) -> str | None:
    """Why no real pose closes six distance legs hung far from the base (see the module's
    proof), or None when the proof does not conclude.  ``legs``: (names, a, b, L^2) each,
    sympy data as :class:`~mechsing.assembly.spatial.SpatialSystem` holds them."""
    with mpmath.workdps(DIGITS):
        a = [mpmath.matrix([sympy.N(c, DIGITS) for c in leg[1]]) for leg in legs]
        b = [mpmath.matrix([sympy.N(c, DIGITS) for c in leg[2]]) for leg in legs]
        L = [mpmath.sqrt(mpmath.mpf(sympy.N(leg[3], DIGITS))) for leg in legs]
        r = [mpmath.norm(a[i]) + mpmath.norm(b[i]) for i in range(len(legs))]
        d_lo = max(L[i] - r[i] for i in range(len(legs)))
        d_hi = min(L[i] + r[i] for i in range(len(legs)))
        if d_lo <= 0 or d_hi < d_lo:
            return None  # near the base (or out of reach, which out_of_reach says)
        rows, centre, half = [], [], []
        for i in range(1, len(legs)):
            rows.append([*(-(a[i] - a[0])), *(b[i] - b[0])])
            g = sorted([(L[i] ** 2 - L[0] ** 2) / (2 * d) for d in (d_lo, d_hi)])
            eta = max(r[i] ** 2, r[0] ** 2) / (2 * d_lo)
            lo, hi = g[0] - eta, g[1] + eta
            centre.append((lo + hi) / 2)
            half.append((hi - lo) / 2 + REACH_PROOF_MARGIN)
        M = mpmath.matrix(rows)
        _U, S, V = svd_r(M, full_matrices=True)
        if S[len(S) - 1] <= REACH_PROOF_MARGIN * S[0]:
            return None  # a special platform: the five equations are dependent
        n = [V[V.rows - 1, j] for j in range(6)]
        x_c = M.T * mpmath.lu_solve(M * M.T, mpmath.matrix(centre))
        omega = mpmath.norm(mpmath.matrix(half)) / S[len(S) - 1] + REACH_PROOF_MARGIN
        if omega >= mpmath.mpf(1) / 2:
            return None  # too near to conclude

        def off(t: Any, k: int) -> Any:  # | |x_c + t n| (u or v) - 1 |
            return abs(
                mpmath.sqrt(sum((x_c[3 * k + j] + t * n[3 * k + j]) ** 2 for j in range(3))) - 1
            )

        lip = [mpmath.sqrt(sum(n[3 * k + j] ** 2 for j in range(3))) for k in (0, 1)]
        top = mpmath.sqrt(2)
        pieces, examined = [(-top, top, 0)], 0
        while pieces:
            lo_t, hi_t, depth = pieces.pop()
            examined += 1
            mid, rad = (lo_t + hi_t) / 2, (hi_t - lo_t) / 2
            if any(off(mid, k) - lip[k] * rad > omega for k in (0, 1)):
                continue  # no unit u (or v) over this piece
            if depth >= DEPTH or examined >= MAX_PIECES:
                return None
            pieces += [(lo_t, mid, depth + 1), (mid, hi_t, depth + 1)]
        return (
            f"the legs ({float(min(L)):.6g} to {float(max(L)):.6g} m) hang the platform "
            f"{float(d_lo):.6g} to {float(d_hi):.6g} m from the origin, where the legs' "
            "lengths leave no real direction and orientation for it (a bound proved from the "
            "base and platform points: no real pose)"
        )
