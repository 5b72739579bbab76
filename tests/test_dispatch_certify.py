"""The dispatch tables of the assembly modes' certificates (mechsing.numeric.dispatch;
the forms in mechsing.assembly.contraction): each fast form against its generic
definition (the same call inside ``fast_paths(False)``) on random polynomial systems
with known roots, real and complex, and at double roots where a form must leave the
decision to the generic definition.  The tables and their forms are listed in
tests/test_dispatch.py (``EXPECTED``)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from mechsing.numeric import dispatch


@pytest.fixture(autouse=True)
def _fast_paths_on():
    """The fast forms are on in these tests whatever the environment says."""
    with dispatch.fast_paths(True):
        yield


def generic(f, *args):
    """f(*args) with every fast path off."""
    with dispatch.fast_paths(False):
        return f(*args)


# ------------------------------------------------- tables krawczyk test and newton start


def _polynomial_system(rng: np.random.Generator, n: int, float_coefficients: bool):
    """A square system of quadratics in n unknowns with a known real root r (rational):
    ``f_i = sum_j a_ij (x_j - r_j) + sum_jk b_ijk (x_j - r_j)(x_k - r_k)``, expanded;
    its coefficients rational, or 60-digit floats (enclosed, not exact)."""
    import sympy

    xs = sympy.symbols(f"x0:{n}")
    r = [sympy.Rational(int(v), 7) for v in rng.integers(-9, 10, n)]
    d = [x - v for x, v in zip(xs, r, strict=True)]
    eqs = []
    for _ in range(n):
        e = sum(
            sympy.Rational(int(a), 5) * t for a, t in zip(rng.integers(-9, 10, n), d, strict=True)
        )
        e += sum(
            sympy.Rational(int(b), 3) * d[j] * d[k]
            for j in range(n)
            for k in range(j, n)
            for b in [rng.integers(-4, 5)]
        )
        if float_coefficients:
            e = sympy.Float(str(rng.uniform(0.5, 2)), 60) * e
        eqs.append(sympy.expand(e))
    return eqs, list(xs), r


def test_krawczyk_double_contraction_proves_what_the_generic_test_proves() -> None:
    """The double contraction bound (f(m) and Y f(m) in mpmath intervals) against every
    operation in intervals: both prove a box about a root refined at 50 digits (real, and
    a complex root's real and imaginary parts), and the fast form proves nothing the
    generic test does not: a box shifted off the root, or about a double root, it leaves
    undecided (None) and the generic test refutes."""
    import sympy

    from mechsing.assembly import certify

    rng = np.random.default_rng(41)
    form = dispatch.table("krawczyk test").get("double contraction")
    radius = mpmath.mpf(1e-30)
    with mpmath.workdps(50):
        mpmath.iv.dps = 50
        for n, floats in ((1, False), (2, True), (4, False), (6, True)):
            eqs, xs, r = _polynomial_system(rng, n, floats)
            system = certify._interval_system(tuple(eqs), tuple(xs), 50)
            root = certify.newton(eqs, xs, [float(v) + 1e-9 for v in r], 50)
            assert root is not None
            for m, proved in ((root, True), ([v + 3 * radius for v in root], False)):
                assert form(system, m, radius) is (True if proved else None)
                assert generic(certify.krawczyk_box, system, m, radius) is proved
                assert certify.krawczyk(eqs, xs, m, radius) is proved
        # a complex root of x^2 + 1 and of a 2 x 2 system, in its real and imaginary parts
        x, y = sympy.symbols("x y")
        for eqs, gens, z in (
            ([x**2 + 1], [x], [1j]),
            ([x**2 + y**2 + 1, x - 2 * y], [x, y], [0.8944j, 0.4472j]),
        ):
            root = certify.newton(eqs, gens, z, 50)
            assert certify.krawczyk_complex(eqs, gens, root, radius)
            mid = [mpmath.re(v) for v in root] + [mpmath.im(v) for v in root]
            system = certify._realified_system(tuple(eqs), tuple(gens), 50)
            assert form(system, mid, radius) is True
            assert generic(certify.krawczyk_box, system, mid, radius) is True
        # a double root: no box is proved
        eqs, gens = [(x - 1) ** 2], [x]
        system = certify._interval_system((sympy.expand(eqs[0]),), (x,), 50)
        m = [mpmath.mpf(1)]
        assert form(system, m, radius) is None
        assert generic(certify.krawczyk_box, system, m, radius) is False
        mpmath.iv.dps = 15
    with dispatch.fast_paths(False):
        assert dispatch.table("krawczyk test").pick(system, m, radius) is None


def test_newton_double_steps_reach_the_generic_root() -> None:
    """Newton's steps in double precision first, then at 50 digits: the root the generic
    refinement (50 digits from the start) reaches, to 1e-45, from starts 1e-6 off (real
    and complex); from a start where the double steps do not shrink, the start itself."""
    from mechsing.assembly import certify

    rng = np.random.default_rng(42)
    form = dispatch.table("newton start").get("double steps")
    with mpmath.workdps(50):
        for n, floats in ((1, False), (3, True), (5, False)):
            eqs, xs, r = _polynomial_system(rng, n, floats)
            for z in (
                [float(v) + 1e-6 for v in r],
                [complex(float(v), 1e-6) for v in r],
            ):
                fast = certify.newton(eqs, xs, z, 50)
                slow = generic(certify.newton, eqs, xs, z, 50)
                assert fast is not None and slow is not None
                assert max(abs(a - b) for a, b in zip(fast, slow, strict=True)) < 1e-45
                assert max(abs(a - b) for a, b in zip(fast, r, strict=True)) < 1e-45
        import sympy

        x = sympy.Symbol("x")
        arrays = certify._double_functions((x**2 + 1,), (x,))
        assert form(arrays, [0.0]) == [0.0]  # a singular Jacobian: the start itself


# ------------------------------------------------- tables newton steps and regular root


def test_chord_steps_reach_the_generic_root() -> None:
    """Newton's steps at 50 digits by one double inverse (chord steps) against the
    generic steps (each solved by mpmath's LU): the same root to 1e-45, real and complex,
    with a residual at the working digits' rounding; at a double root (the steps do not
    contract) the generic steps start from where they would without the form."""
    import sympy

    from mechsing.assembly import certify

    rng = np.random.default_rng(43)
    form = dispatch.table("newton steps").get("chord")
    with mpmath.workdps(50):
        for n, floats in ((1, False), (3, True), (6, False)):
            eqs, xs, r = _polynomial_system(rng, n, floats)
            f, _ = certify._functions(eqs, xs)
            arrays = certify._double_functions(tuple(eqs), tuple(xs))
            for z in ([float(v) + 1e-12 for v in r], [complex(float(v), 1e-12) for v in r]):
                x, reached = form(
                    arrays, f, mpmath.matrix([certify._number(v) for v in z]), 50, 60, 10
                )
                assert reached
                slow = generic(certify.newton, eqs, xs, z, 50)
                assert max(abs(a - b) for a, b in zip(x, slow, strict=True)) < 1e-45
                assert max(abs(a - b) for a, b in zip(x, r, strict=True)) < 1e-45
                assert mpmath.norm(f(x)) < mpmath.mpf(10) ** -45
                assert certify.newton(eqs, xs, z, 50) is not None
        x = sympy.Symbol("x")
        eqs = [sympy.expand((x - 1) ** 2)]
        f, _ = certify._functions(eqs, [x])
        arrays = certify._double_functions(tuple(eqs), (x,))
        start = mpmath.matrix([mpmath.mpf(1) + mpmath.mpf(1e-9)])
        got, reached = form(arrays, f, start, 50, 60, 10)
        assert not reached and got == start  # not contracting: the generic steps go on


def test_regular_in_double_proves_only_what_the_generic_test_decides() -> None:
    """The double-precision bound answers True only where the singular values at 50
    digits say regular: at well-conditioned roots of random systems (real and complex),
    never at a double root or at roots as ill-conditioned as the floor, where it leaves
    the decision (None) to the generic test."""
    import sympy

    from mechsing.assembly import certify

    rng = np.random.default_rng(44)
    form = dispatch.table("regular root").get("double bound")
    with mpmath.workdps(50):
        floor = mpmath.mpf(10) ** -16
        for n, floats in ((1, False), (2, True), (5, False)):
            eqs, xs, r = _polynomial_system(rng, n, floats)
            root = certify.newton(eqs, xs, [float(v) + 1e-9 for v in r], 50)
            arrays = certify._double_functions(tuple(eqs), tuple(xs))
            assert form(arrays, root, floor) is True
            assert generic(certify.regular, eqs, xs, root) is True
        x, y = sympy.symbols("x y")
        eps = sympy.Rational(1, 10**17)
        for eqs, gens, point in (
            ([sympy.expand((x - 1) ** 2)], [x], [mpmath.mpf(1)]),
            # a regular root whose singular values' ratio is 1e-17: below the floor
            ([x - 1, sympy.expand(eps * (y - 2))], [x, y], [mpmath.mpf(1), mpmath.mpf(2)]),
        ):
            arrays = certify._double_functions(tuple(eqs), tuple(gens))
            assert form(arrays, point, floor) is None
            assert generic(certify.regular, eqs, gens, point) is False


def test_krawczyk_point_values_lie_in_the_interval_values() -> None:
    """The values the double contraction certifies with (at the point, widened by their
    rounding's bound) enclose the values every operation in intervals gives, and are
    narrow (1e-40 at 50 digits) at a root of a system with float coefficients."""
    from mechsing.assembly import certify
    from mechsing.assembly.contraction import _enclosed_values

    rng = np.random.default_rng(45)
    with mpmath.workdps(50):
        mpmath.iv.dps = 50
        try:
            for n, floats in ((2, True), (4, False), (6, True)):
                eqs, xs, r = _polynomial_system(rng, n, floats)
                system = certify._interval_system(tuple(eqs), tuple(xs), 50)
                for m in (
                    certify.newton(eqs, xs, [float(v) + 1e-9 for v in r], 50),
                    [mpmath.mpf(float(v)) + mpmath.mpf(0.3) for v in r],
                ):
                    xc = np.array([float(v) for v in m])
                    ball = _enclosed_values(system, m, xc)
                    boxes = system.f([mpmath.iv.mpf(v) for v in m])
                    for b, i in zip(ball, boxes, strict=True):
                        assert b.a <= i.b and i.a <= b.b  # both hold the exact value
                        width = mpmath.mpf(b.b) - mpmath.mpf(b.a)
                        assert width < mpmath.mpf(10) ** -40 * (1 + abs(mpmath.mpf(i.a)))
        finally:
            mpmath.iv.dps = 15
