"""The double-precision parts of a certificate, from a polynomial system's terms.

:class:`TermArrays` holds polynomials (each a dictionary exponents -> real coefficient)
as numpy arrays: their values at a float or complex point, and bounds on their
rounding and on their variation over a box, in double precision.

:func:`contraction_krawczyk` is the form ``"double contraction"`` of the dispatch table
``"krawczyk test"`` (generic definition :func:`mechsing.assembly.certify.krawczyk_box`,
every operation in mpmath interval arithmetic).  In the Krawczyk operator
``K = m - Y f(m) + (I - Y f'(Z))(Z - m)`` the box's radius r (``MODE_CERTIFY_RADIUS``,
1e-30) multiplies ``I - Y f'(Z)``, which only needs an upper bound B on its magnitude,
entry by entry: B r must stay below r less ``|Y f(m)|`` (about 1e-45 at a root refined
to 50 digits), so a bound of 1e-15 or of 1e-2 proves the same box.  That bound, the n x n products of the test, is computed here in
double precision with every rounding bounded (below).  ``f(m)``, where the root's
digits matter, is evaluated at the working digits at the point m and widened by a bound
on its rounding (the same analysis with the working precision's unit roundoff) and on
the coefficients' enclosures; ``|Y f(m)|`` is bounded in double from those
enclosures' magnitudes (at a root about 1e-45, r being 1e-30), and ``K``'s containment
in the box is tested in mpmath intervals at the working digits, as the generic
definition has it.  The form answers True (proved) or None
(not proved here: the caller runs the generic definition, which decides).

The bound, for z in Z: ``|I - Y f'(z)| <= |I - Y J~| + |Y| (|J~ - f'(xc)| + |f'(z) -
f'(xc)|)``, with xc the root rounded to double, ``J~`` the Jacobian evaluated at xc in
double precision and Y a double inverse of ``J~`` (any Y serves Krawczyk's theorem); the
coefficients that are not rational are those of the interval functions' enclosures
(``v +- 10^-(N - 5) (1 + |v|)`` at N digits, their half-widths added to the bound), so
it holds for every system whose coefficients lie in them, as the generic test's proof
does.
Each term is bounded by the standard error analysis of floating-point arithmetic
(Higham, Accuracy and Stability of Numerical Algorithms, 2002, ch. 3): a product of d
factors and a sum of k terms carry a relative error at most ``gamma_{d+k}``, with
``gamma_j = j u / (1 - j u)`` and u = 2^-53; a term's variation over the box
``xc +- rho`` (which holds Z: rho is r plus xc's rounding) is at most ``|c| ((|xc| +
rho)^a - |xc|^a) <= |c| (|xc| + rho)^a sum_k a_k rho_k / (|xc_k| + rho_k)``.  The
computed bounds are sums and products of non-negative doubles, each within ``gamma``
of its exact value; the result is doubled (and 1e-300 added, for underflow), which
covers these roundings many times over.

:func:`double_newton` is the form ``"double steps"`` of the dispatch table ``"newton
start"`` (generic definition: Newton's method at the working digits from the endpoint
as it is, :func:`mechsing.assembly.certify.newton`): Newton's steps in double precision
while they shrink, so that the steps at the working digits start at double precision's
accuracy (fewer of them than from a continuation endpoint).
The root the working digits reach is the same; the digits' last places may differ.

:func:`chord_steps` is the form ``"chord"`` of the dispatch table ``"newton steps"``
(generic definition: each step's linear system solved at the working digits by
mpmath's LU, :func:`mechsing.assembly.certify.newton`): the steps at the working digits
reuse one double-precision inverse Y of the Jacobian at the root rounded to double, the
step ``Y f(x)`` computed in double from ``f(x)`` at the working digits.  Each step
multiplies the error by about ``|I - Y f'(x)|``, the Jacobian's condition times the
double rounding (1e-16 to 1e-8 where ``MODE_CHORD_RTOL`` admits the root), so four or
five steps take a root from double precision to 50 digits, with no Jacobian evaluated
and no system solved at the working digits (the chord or simplified Newton method:
Ortega and Rheinboldt, Iterative Solution of Nonlinear Equations in Several Variables,
1970, 7.1).  The root is the same; the digits' last places may differ.

:func:`regular_in_double` is the form ``"double bound"`` of the dispatch table
``"regular root"`` (generic definition: the Jacobian's singular values at the working
digits, :func:`mechsing.assembly.certify.regular`): the Jacobian at the root rounded to
double, its entries' distance to the exact Jacobian at the root bounded as above, and
the singular values moved by at most that distance's Frobenius norm (Weyl's inequality)
plus LAPACK's backward error; it answers True where even so the least singular value
stays above the floor times the largest, None (the generic definition decides)
elsewhere.

Owns :class:`TermArrays`, :func:`contraction_krawczyk`, :func:`double_newton`,
:func:`chord_steps` and :func:`regular_in_double`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import mpmath
import numpy as np

from mechsing.assembly.settings import MODE_CHORD_RTOL
from mechsing.numeric import dispatch

__all__ = [
    "TermArrays",
    "chord_steps",
    "contraction_krawczyk",
    "double_newton",
    "regular_in_double",
]

#: the most double-precision Newton steps before the working digits take over
DOUBLE_NEWTON_STEPS = 12

#: the unit roundoff of double precision
_U = 2.0**-53
#: an absolute floor added to every bound (subnormal products' absolute rounding)
_TINY = 1e-300


class TermArrays:
    """Polynomials in n unknowns as arrays: each term's coefficient (rounded to double),
    its exponents and the polynomial it belongs to."""

    def __init__(
        self, terms: Sequence[dict[tuple[int, ...], Any]], n: int, pad: float = 0.0
    ) -> None:
        coeffs, exps, rows, slack = [], [], [], []
        for i, t in enumerate(terms):
            for mono, c in t.items():
                coeffs.append(float(c))
                exps.append(mono)
                rows.append(i)
                exact = isinstance(c, int) or getattr(c, "is_Rational", False)
                slack.append(0.0 if exact else 2 * pad * (1 + abs(float(c))))
        self.n = n
        self.size = len(terms)
        self.coeffs = np.array(coeffs, dtype=float)
        #: each coefficient's enclosure's half-width, above (0 for a rational one): the
        #: interval functions enclose a coefficient that is not rational (a float standing
        #: for an algebraic number) as ``v +- pad (1 + |v|)``, and so does the bound
        self.slack = np.array(slack, dtype=float)
        self.exps = np.array(exps, dtype=np.int64).reshape(len(coeffs), n)
        self.rows = np.array(rows, dtype=np.int64)
        counts = np.bincount(self.rows, minlength=self.size) if coeffs else np.zeros(1)
        degree = int(self.exps.sum(axis=1).max()) if coeffs else 0
        # a term: its coefficient's rounding (to 2 u: mpmath rounds towards zero), 2 d
        # products (powers, then the monomial), the product by its coefficient; the sum
        # of a polynomial's k terms
        j = 2 * degree + 4 + int(counts.max())
        #: the roundings a polynomial's value carries, each term's and the sum's (gamma's j)
        self.ops = j
        self.gamma = j * _U / (1 - j * _U)

    def jacobian(self) -> TermArrays:
        """The Jacobian's entries row by row (entry ``(i, k)`` the polynomial ``i n + k``),
        each term's coefficient ``c a_k`` rounded once more (in :attr:`gamma`)."""
        out = TermArrays([], self.n)
        keep = [self.exps[:, k] > 0 for k in range(self.n)]
        out.coeffs = np.concatenate([self.coeffs[t] * self.exps[t, k] for k, t in enumerate(keep)])
        out.exps = np.concatenate(
            [self.exps[t] - np.eye(self.n, dtype=np.int64)[k] for k, t in enumerate(keep)]
        )
        out.rows = np.concatenate([self.rows[t] * self.n + k for k, t in enumerate(keep)])
        out.slack = np.concatenate([self.slack[t] * self.exps[t, k] for k, t in enumerate(keep)])
        out.size = self.size * self.n
        counts = np.bincount(out.rows, minlength=out.size) if len(out.rows) else np.zeros(1)
        degree = int(out.exps.sum(axis=1).max()) if len(out.rows) else 0
        j = 2 * degree + 5 + int(counts.max())
        out.ops = j
        out.gamma = j * _U / (1 - j * _U)
        return out

    def _monomials(self, x: np.ndarray) -> np.ndarray:
        """Every term's monomial at ``x`` (repeated products, no ``pow``)."""
        out = np.ones(len(self.coeffs), dtype=x.dtype)
        for k in range(self.n):
            e = self.exps[:, k]
            p = np.ones(len(self.coeffs), dtype=x.dtype)
            for _ in range(int(e.max()) if len(e) else 0):
                p = np.where(e > 0, p * x[k], p)
                e = e - 1
            out = out * p
        return out

    def values(self, x: np.ndarray) -> np.ndarray:
        """The polynomials at ``x`` (float or complex)."""
        terms = self.coeffs * self._monomials(x)
        if np.iscomplexobj(terms):
            return np.bincount(self.rows, terms.real, self.size) + 1j * np.bincount(
                self.rows, terms.imag, self.size
            )
        return np.bincount(self.rows, terms, self.size)

    def magnitudes(self, a: np.ndarray, coeffs: np.ndarray | None = None) -> np.ndarray:
        """``sum |c| a^e`` for each polynomial (``a`` non-negative; ``coeffs``: other
        coefficients than the polynomials' own)."""
        c = np.abs(self.coeffs if coeffs is None else coeffs)
        return np.bincount(self.rows, c * self._monomials(a), self.size)

    def variation(self, x: np.ndarray, rho: np.ndarray) -> np.ndarray:
        """For each polynomial, a bound on ``|p(z) - p(x)|`` over ``|z - x| <= rho``
        (entrywise, rho > 0): ``sum |c| (|x| + rho)^a sum_k a_k rho_k / (|x_k| + rho_k)``."""
        w = np.abs(x) + rho
        share = self.exps @ (rho / w)
        return np.bincount(self.rows, np.abs(self.coeffs) * self._monomials(w) * share, self.size)


def _bound(jac: TermArrays, xc: np.ndarray, rho: np.ndarray) -> tuple[Any, Any] | None:
    """(Y, B): a double inverse of the Jacobian at ``xc`` and an upper bound on
    ``|I - Y f'(z)|`` for every ``|z - xc| <= rho`` (None: the Jacobian is singular in
    double precision or a bound is not finite)."""
    n = len(xc)
    Jt = jac.values(xc).reshape(n, n)
    try:
        Y = np.linalg.inv(Jt)
    except np.linalg.LinAlgError:
        return None
    eye = np.eye(n)
    # |J~ - f'(xc)|: the evaluation's rounding; |f'(z) - f'(xc)|: the box's variation;
    # the coefficients' enclosures over the box
    err = jac.gamma * jac.magnitudes(np.abs(xc)).reshape(n, n)
    err += jac.magnitudes(np.abs(xc) + rho, jac.slack).reshape(n, n) * (1 + jac.gamma)
    var = jac.variation(xc, rho).reshape(n, n) * (1 + jac.gamma)
    absY = np.abs(Y)
    g = (n + 2) * _U / (1 - (n + 2) * _U)  # I - Y J~ in double: n products and sums
    B = np.abs(eye - Y @ Jt) + g * (eye + absY @ np.abs(Jt)) + absY @ (err + var)
    B = 2 * B + _TINY
    if not np.all(np.isfinite(B)) or not np.all(np.isfinite(Y)):
        return None
    return Y, B


@dispatch.table("krawczyk test", "mechsing.assembly.certify.krawczyk_box").register(
    "double contraction",
    "a polynomial system given by its terms (every system the formulations certify): "
    "the contraction term's bound and |Y f(m)|'s in double precision with their rounding "
    "bounded, f(m) enclosed at the working digits; proves what the generic test proves, or answers "
    "None and the generic test decides",
    accepts=lambda system, m, radius: system.arrays is not None,
)
def contraction_krawczyk(system: Any, m: Sequence[Any], radius: Any) -> bool | None:
    """True when the box ``m +- radius`` provably holds exactly one root of the system
    (an :class:`~mechsing.assembly.certify.IntervalSystem` with its term arrays; the
    interval context's digits set); None when this test does not prove it."""
    iv = mpmath.iv
    n = len(m)
    Z = [iv.mpf([x - radius, x + radius]) for x in m]  # the box the generic test proves
    xc = np.array([float(x) for x in m])
    # upper bounds (in double) of |Z - m| and of |Z - xc|, from outward-rounded intervals
    w = np.array([_magnitude(Zk - iv.mpf(x)) for Zk, x in zip(Z, m, strict=True)])
    rho = np.array([_magnitude(Zk - iv.mpf(float(x))) for Zk, x in zip(Z, xc, strict=True)])
    got = _bound(system.arrays, xc, rho)
    if got is None:
        return None
    Y, B = got
    spread = 2 * (B @ w) * (1 + (n + 2) * _U) + _TINY  # |(I - Y f'(Z))(Z - m)|, above
    fm = _enclosed_values(system, m, xc)
    # |Y f(m)| above, in double: f(m)'s enclosures' magnitudes (f(m) is of the working
    # digits' rounding at a root, 1e-45, far below r); n products and sums of non-negative
    # doubles, doubled as the spread is.  Then K_i lies in m_i +- (|Y f(m)|_i + spread_i)
    phi = np.array([_magnitude(v) for v in fm])
    reach = (2 * (np.abs(Y) @ phi) * (1 + (n + 2) * _U) + spread) * (1 + 4 * _U) + _TINY
    if not np.all(np.isfinite(reach)):
        return None
    for i, mi in enumerate(m):
        t = float(reach[i])
        acc = iv.mpf(mi) + iv.mpf([-t, t])
        if not (acc.a > Z[i].a and acc.b < Z[i].b):
            return None
    return True


def _enclosed_values(system: Any, m: Sequence[Any], xc: np.ndarray) -> list[Any]:
    """Intervals that hold the system's values at ``m`` (``xc``: m rounded to double):
    evaluated at the working digits at the point, each widened by a bound on that
    evaluation's rounding (``gamma`` of the working precision's unit roundoff, with
    the roundings the term arrays count) and on the coefficients' enclosures (their
    slack, as the interval functions enclose them); the interval functions where the
    system has no point form."""
    iv = mpmath.iv
    if system.point is None:
        return list(system.f([iv.mpf(x) for x in m]))
    values, arrays = system.point
    v = values(list(m))
    u = 2.0 ** (1 - mpmath.mp.prec)  # a rounding at the working digits, towards zero
    gamma = arrays.ops * u / (1 - arrays.ops * u)
    a = np.abs(xc) * (1 + 2 * _U) + _TINY  # above |m|
    e = 2 * (gamma * arrays.magnitudes(a) + arrays.magnitudes(a, arrays.slack)) + _TINY
    return [iv.mpf(x) + iv.mpf([-float(r), float(r)]) for x, r in zip(v, e, strict=True)]


def _magnitude(d: Any) -> float:
    """An upper bound, in double, of the largest absolute value of the interval ``d``."""
    a, b = (abs(mpmath.mp.make_mpf(e)) for e in d._mpi_)
    return float(max(a, b)) * (1 + 4 * _U) + _TINY  # (float() rounds to within 1 ulp)


@dispatch.table(
    "newton start", "mechsing.assembly.certify.newton (from the endpoint as it is)"
).register(
    "double steps",
    "a square polynomial system given by its terms: Newton's steps in double precision "
    "while they shrink, before those at the working digits (the same root; its last "
    "digits may differ)",
    accepts=lambda arrays, z: arrays is not None,
)
def double_newton(arrays: tuple[TermArrays, TermArrays], z: Sequence[Any]) -> list[Any]:
    """``z`` refined by Newton's steps in double precision (float, or complex where an
    entry is complex) while each shrinks the last (by half at least); ``z`` itself where
    the first does not."""
    f, J = arrays
    cplx = any(isinstance(v, (complex, mpmath.mpc)) for v in z)
    x = np.array([complex(v) if cplx else float(v) for v in z])
    n = len(x)
    last = np.inf
    for _ in range(DOUBLE_NEWTON_STEPS):
        try:
            dx = np.linalg.solve(J.values(x).reshape(n, n), f.values(x))
        except np.linalg.LinAlgError:
            break
        step = float(np.max(np.abs(dx)))
        if not np.isfinite(step) or step > last / 2:
            break
        x = x - dx
        last = step
        if step <= 4 * _U * max(1.0, float(np.max(np.abs(x)))):
            break
    return list(x) if np.isfinite(last) else list(z)


@dispatch.table(
    "newton steps",
    "mechsing.assembly.certify.newton (each step solved at the working digits by mpmath's LU)",
).register(
    "chord",
    "a square polynomial system given by its terms, its Jacobian at the root rounded to "
    "double well-conditioned (MODE_CHORD_RTOL): every step at the working digits "
    "solved by one double-precision inverse (the same root; its last digits may differ)",
    accepts=lambda arrays, f, x, dps, steps, stall: arrays is not None,
)
def chord_steps(
    arrays: tuple[TermArrays, TermArrays], f: Any, x: Any, dps: int, steps: int, stall: float
) -> tuple[Any, bool]:
    """``x`` (an mpmath column) refined at ``dps`` digits by chord steps ``x - Y f(x)``,
    Y a double inverse of the Jacobian at ``x`` rounded to double: (the point reached,
    whether the steps reached ``10^-dps``, or a step that leaves less, at the rate of
    the last two, or the working digits' rounding below ``10^-(dps/2)``, as
    :func:`mechsing.assembly.certify.newton`'s do).  Not reached
    (an ill-conditioned Jacobian, a step that does not shrink the last by ``stall``
    above ``10^-(dps/2)``): ``x`` itself, for the generic steps to start from, as they
    would without this form."""
    _, J = arrays
    n = len(x)
    cplx = any(isinstance(v, mpmath.mpc) and v.imag != 0 for v in x)
    xc = np.array([complex(v) if cplx else float(v) for v in x])
    A = J.values(xc).reshape(n, n)
    if not np.all(np.isfinite(A)):
        return x, False
    s = np.linalg.svd(A, compute_uv=False)
    if not s[-1] >= MODE_CHORD_RTOL * s[0]:
        return x, False
    Y = np.linalg.inv(A)
    tiny, half = mpmath.mpf(10) ** (-dps), mpmath.mpf(10) ** (-(dps // 2))
    last, start = mpmath.inf, x
    for _ in range(steps):
        r = np.array([complex(v) if cplx else float(mpmath.re(v)) for v in f(x)])
        d = Y @ r
        step = mpmath.mpf(float(np.linalg.norm(d)))
        slow = step > last / stall
        if slow and step > half:
            return start, False  # not contracting
        x = x - mpmath.matrix([mpmath.mpc(v) if cplx else mpmath.mpf(v) for v in d])
        if step <= tiny or slow:  # there, or no longer shrinking: the digits' rounding
            return x, True
        if last < mpmath.inf and step * (step / last) <= tiny:
            # the steps shrink by step / last each (linearly): the next, the error left,
            # is below 10^-dps
            return x, True
        last = step
    return start, False


@dispatch.table(
    "regular root",
    "mechsing.assembly.certify.regular (the Jacobian's singular values at the working digits)",
).register(
    "double bound",
    "a square polynomial system given by its terms: the Jacobian's singular values in "
    "double precision, moved by a bound on the rounding (True where regular even so, "
    "None where the generic definition decides)",
    accepts=lambda arrays, x, floor: arrays is not None,
)
def regular_in_double(
    arrays: tuple[TermArrays, TermArrays], x: Sequence[Any], floor: Any
) -> bool | None:
    """True when the Jacobian at ``x`` has its least singular value above ``floor``
    times its largest, proved from the double-precision Jacobian at ``x`` rounded to
    double; None where that does not prove it."""
    _, J = arrays
    n = len(x)
    cplx = any(isinstance(v, (complex, mpmath.mpc)) and v.imag != 0 for v in x)
    xc = np.array([complex(v) if cplx else float(mpmath.re(v)) for v in x])
    Jt = J.values(xc).reshape(n, n)
    if not np.all(np.isfinite(Jt)):
        return None
    s = np.linalg.svd(Jt, compute_uv=False)
    # |J~ - f'(x)| entry by entry: the evaluation's rounding and x's rounding to double
    # (each part to half an ulp: rho), over the ball |z - xc| <= rho
    rho = 2 * _U * np.abs(xc) + _TINY
    err = J.gamma * J.magnitudes(np.abs(xc)) + J.variation(xc, rho) * (1 + J.gamma)
    # Weyl: each singular value moves by at most ||E||_2 <= ||E||_F; LAPACK's SVD is
    # backward stable (a modest multiple of u sigma_max, taken as 8 n u sigma_max)
    delta = 2 * (float(np.sqrt(np.sum(err**2))) + 8 * n * _U * float(s[0])) + _TINY
    if not np.isfinite(delta):
        return None
    if float(s[-1]) - delta > float(floor) * (float(s[0]) + delta):
        return True
    return None
