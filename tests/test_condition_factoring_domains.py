"""A joint's factors are split in one of two domains (a polynomial ring over the
rationals, or sympy's expressions where the ring cannot hold the condition); both must
give the same factors, and the factors times the cofactor must be the condition on the
circle c**2 + s**2 = 1."""

from __future__ import annotations

import sympy

from mechsing.conditions.factoring import _split_in_expressions, _split_in_ring, factor_condition
from mechsing.conditions.symbolic import JointSymbols

q, c, s = sympy.symbols("q c s")
c2, s2 = sympy.symbols("c2 s2")
a, b = sympy.symbols("a b", positive=True)
J = JointSymbols(q, c, s)


def _on_circle(expr):
    """expr with s**2 -> 1 - c**2, s2**2 -> 1 - c2**2 (its normal form on the torus)."""
    p = sympy.Poly(sympy.expand(expr), s, s2)
    out = sympy.Integer(0)
    for (i, j), coeff in p.terms():
        out += (
            coeff * s ** (i % 2) * (1 - c**2) ** (i // 2) * s2 ** (j % 2) * (1 - c2**2) ** (j // 2)
        )
    return sympy.expand(out)


CASES = [
    # a factor a*cos + b*sin + e of the joint alone, times one of another joint
    (2 * c + 3 * s - 1) * (c2 + s2),
    # sin(J) = 0 (roots t = 0 and t = oo: one degree-1 factor and one root at infinity)
    s * (c2 - 2 * s2 + 1),
    # 1 + cos(J) squared: a double root at J = pi, from the degree deficit alone
    (1 + c) ** 2 * (c2 + 3),
    # a repeated factor, and a factor with symbolic parameters
    (c - s) ** 2 * (a * c + b * s + a),
    # nothing in the joint alone
    c * c2 + s * s2 + 1,
    # a factor in the joint with a cofactor that mixes both joints
    (3 * c + 4 * s) * (c * c2 - s * s2 + 2),
]


def test_the_two_domains_split_the_same_factors():
    params = {a, b}
    for expr in CASES:
        expr = sympy.expand(expr)
        ring_found, ring_rest = _split_in_ring(expr, J, params)
        expr_found, expr_rest = _split_in_expressions(expr, J, params)
        assert [(sympy.expand(f), p) for f, p in ring_found] == [
            (sympy.expand(f), p) for f, p in expr_found
        ], expr
        assert _on_circle(ring_rest - expr_rest) == 0, expr
        product = ring_rest
        for f, p in ring_found:
            product *= f**p
        assert _on_circle(product - expr) == 0, expr


def test_a_factor_whose_half_angle_roots_are_rational_is_found():
    # 3*cos(J) + 4*sin(J) is (3t + 1)(t - 3) / (1 + t**2) in t = tan(J/2): two factors of
    # degree 1 and no root at infinity; on the circle (s**2 -> 1 - c**2) ordinary
    # factoring no longer sees it
    q2 = sympy.Symbol("q2")
    J2 = JointSymbols(q2, c2, s2)
    other = c * c2 - s * s2 + 2
    for joint_alone, power in ((3 * c + 4 * s, 1), (3 * c + 4 * s + 5, 1), (3 * c + 4 * s, 2)):
        expr = _on_circle(joint_alone**power * other)
        const, factors = factor_condition(expr, [J, J2], set())
        assert (joint_alone, power) in factors, factors
        assert (other, 1) in factors, factors
        product = const
        for f, p in factors:
            product *= f**p
        assert _on_circle(product - expr) == 0


def test_cos_and_sin_of_the_joint_are_found():
    expr = sympy.expand((2 * c + 3 * s - 1) * (1 + c) * (c2 + s2))
    found, rest = _split_in_ring(expr, J, set())
    assert {sympy.expand(f) for f, _ in found} == {1 - 2 * c - 3 * s, 1 + c}
    assert sympy.expand(rest) == -c2 - s2
