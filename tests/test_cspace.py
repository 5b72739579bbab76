"""The tangent-cone machinery: bracket terms against BCH, zero sets of quadratic forms."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from mechsing import lie
from mechsing.numeric import Precision
from mechsing.singularity.cspace import Expansion, LoopChain, _zero_set, tangent_cone
from tests.reference.se3 import hat, vee

FLOAT = Precision("float")


@pytest.mark.parametrize("seed", range(4))
def test_second_order_term_is_the_bch_quadratic_of_the_loop_product(seed: int) -> None:
    """log(prod_k exp(t s_k S_k x_k)) = t sum + t^2/2 sum_{j<k} [zeta_j, zeta_k] + O(t^3):
    the symmetric second difference of the product's logarithm (scipy expm/logm, not
    mechsing's exp/log) equals Expansion.quadratic."""
    rng = np.random.default_rng(seed)
    n = 6
    S = rng.normal(size=(6, n))
    signs = rng.choice([-1, 1], size=n)
    chain = LoopChain([([k], int(signs[k])) for k in range(n)], np.eye(6))
    exp = Expansion([chain], S)
    x = rng.normal(size=n)
    t = 1e-3

    def logprod(tt: float) -> np.ndarray:
        g = np.eye(4)
        for k in range(n):
            g = g @ scipy.linalg.expm(hat(tt * signs[k] * S[:, k] * x[k]))
        return vee(np.real(scipy.linalg.logm(g)))

    second = (logprod(t) + logprod(-t)) / t**2
    np.testing.assert_allclose(exp.quadratic(x), second, atol=1e-5 * np.abs(second).max())
    # bilinear is the polarisation of the quadratic form
    y = rng.normal(size=n)
    q = exp.quadratic(x + y) - exp.quadratic(x) - exp.quadratic(y)
    np.testing.assert_allclose(q, exp.bilinear(x, y) + exp.bilinear(y, x), atol=1e-12)


def test_bracket_terms_use_lie_bracket_convention() -> None:
    a, b = np.array([0, 0, 1.0, 0, 0, 0]), np.array([0, 0, 1.0, 0, -1.0, 0])
    chain = LoopChain([([0], 1), ([1], 1)], np.eye(6))
    exp = Expansion([chain], np.stack([a, b], axis=1))
    np.testing.assert_allclose(
        exp.bilinear(np.array([1.0, 0]), np.array([0, 1.0])), lie.bracket(a, b)
    )


def _spaces(forms: list[np.ndarray]) -> tuple[str, list[np.ndarray], list[bool]]:
    kind, subs, silent, _m, und = _zero_set(forms, FLOAT)
    assert not und
    return kind, subs, silent


def _contains(space: np.ndarray, v: np.ndarray) -> bool:
    v = v / np.linalg.norm(v)
    return float(np.linalg.norm(v - space @ (space.T @ v))) < 1e-10


def test_indefinite_form_in_the_plane_gives_two_lines() -> None:
    kind, subs, silent = _spaces([np.array([[1.0, 0], [0, -4.0]])])  # x^2 - 4 y^2 = (x-2y)(x+2y)
    assert kind == "subspaces" and len(subs) == 2 and not any(silent)
    assert sorted(s.shape[1] for s in subs) == [1, 1]
    assert any(_contains(s, np.array([2.0, 1.0])) for s in subs)
    assert any(_contains(s, np.array([2.0, -1.0])) for s in subs)


def test_definite_form_gives_zero_cone() -> None:
    kind, subs, _ = _spaces([np.array([[2.0, 0.5], [0.5, 1.0]])])
    assert kind == "subspaces" and subs == []


def test_definite_combination_of_indefinite_forms_gives_zero_cone() -> None:
    # x^2 - y^2 and xy vanish together only at 0, but neither is definite: the pencil
    # of two forms has no definite member either, so the split decides it
    kind, subs, _ = _spaces([np.diag([1.0, -1.0]), np.array([[0, 0.5], [0.5, 0]])])
    assert kind == "subspaces" and subs == []


def test_semidefinite_form_gives_a_silent_double_line() -> None:
    kind, subs, silent = _spaces([np.diag([1.0, 0.0])])
    assert kind == "subspaces" and len(subs) == 1 and silent == [True]
    assert _contains(subs[0], np.array([0.0, 1.0]))


def test_rank_three_indefinite_form_is_not_a_union_of_subspaces() -> None:
    kind, _, _ = _spaces([np.diag([1.0, 1.0, -1.0])])  # x^2 + y^2 = z^2: a circular cone
    assert kind == "cone"


def test_plane_union_line() -> None:
    # xy = 0 and yz = 0: the plane y = 0 and the line x = z = 0
    xy = np.zeros((3, 3))
    xy[0, 1] = xy[1, 0] = 0.5
    yz = np.zeros((3, 3))
    yz[1, 2] = yz[2, 1] = 0.5
    kind, subs, _ = _spaces([xy, yz])
    assert kind == "subspaces"
    dims = sorted(s.shape[1] for s in subs)
    assert dims == [1, 2]
    plane = next(s for s in subs if s.shape[1] == 2)
    line = next(s for s in subs if s.shape[1] == 1)
    assert _contains(plane, np.array([1.0, 0, 0])) and _contains(plane, np.array([0, 0, 1.0]))
    assert _contains(line, np.array([0, 1.0, 0]))


def test_zero_forms_keep_the_kernel_as_silent() -> None:
    kind, subs, silent = _spaces([np.zeros((2, 2))])
    assert kind == "subspaces" and len(subs) == 1 and subs[0].shape[1] == 2 and silent == [True]


def test_full_rank_closure_has_zero_cone() -> None:
    M = np.eye(3)
    chain = LoopChain([([0], 1), ([1], 1), ([2], 1)], np.eye(6)[:, :3])
    exp = Expansion([chain], np.eye(6)[:, :3])
    assert tangent_cone(exp, M, FLOAT).kind == "zero"
