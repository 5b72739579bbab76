"""Big mechanisms: the cycle basis, block factorisations and grouped tangent cones.

The answers are checked against networkx (an independent minimum cycle basis),
numpy's dense SVD, and the mathematics of ladders of parallelograms and chains
of Bennett linkages (each loop keeps its own single degree of freedom; a
parallelogram folded flat is a change point where its two branches cross).
"""

from __future__ import annotations

import random

import networkx as nx
import numpy as np
import pytest
from scipy.sparse import csc_matrix

from mechsing.kinematics.closure import Closer
from mechsing.kinematics.jacobians import chord_signs
from mechsing.kinematics.model import KinematicModel
from mechsing.kinematics.newton import damped_least_squares, truncated_least_squares
from mechsing.model import load
from mechsing.model.graph import NETWORKX_LOOP_WORK, canonical_loops, short_cycle_basis
from mechsing.numeric import decide_rank, dispatch
from mechsing.numeric.blocks import block_factors, block_svd, blocks_of
from tests.cli import run_cli


class _J:
    def __init__(self, name: str, a: str, b: str) -> None:
        self.name = name
        self.between = (a, b)


def _random_graph(rng: random.Random) -> tuple[list[str], list[_J]]:
    n = rng.randint(2, 16)
    bodies = [f"b{i}" for i in range(n)]
    joints = [_J(f"j{i}", bodies[rng.randrange(i)], bodies[i]) for i in range(1, n)]
    for _ in range(rng.randint(0, 14)):
        x, y = rng.sample(range(n), 2)
        joints.append(_J(f"j{len(joints) + 1}", bodies[x], bodies[y]))
    rng.shuffle(joints)
    return bodies, joints


def _networkx_total(bodies: list[str], joints: list[_J]) -> int:
    """Total joints of networkx's minimum cycle basis of the body/joint graph."""
    H = nx.Graph()
    H.add_nodes_from(bodies)
    for j in joints:
        H.add_edge(("joint", j.name), j.between[0])
        H.add_edge(("joint", j.name), j.between[1])
    return sum(len(c) // 2 for c in nx.minimum_cycle_basis(H))


def test_short_cycle_basis_is_a_minimum_cycle_basis():
    rng = random.Random(3)
    for _ in range(150):
        bodies, joints = _random_graph(rng)
        basis = short_cycle_basis(bodies, [j.between for j in joints])
        assert len(basis) == len(joints) - len(bodies) + 1
        # every element is a cycle: each body meets an even number of its joints
        for cycle in basis:
            degree: dict[str, int] = {}
            for k in cycle:
                for body in joints[k].between:
                    degree[body] = degree.get(body, 0) + 1
            assert all(d % 2 == 0 for d in degree.values())
        # independent over GF(2)
        rows = np.zeros((len(basis), len(joints)), dtype=np.uint8)
        for i, cycle in enumerate(basis):
            rows[i, cycle] = 1
        assert _gf2_rank(rows) == len(basis)
        # minimum: the same total length as networkx's minimum cycle basis
        assert sum(map(len, basis)) == _networkx_total(bodies, joints)


def _gf2_rank(rows: np.ndarray) -> int:
    A = rows.copy()
    rank = 0
    for col in range(A.shape[1]):
        pivot = next((r for r in range(rank, A.shape[0]) if A[r, col]), None)
        if pivot is None:
            continue
        A[[rank, pivot]] = A[[pivot, rank]]
        for r in range(A.shape[0]):
            if r != rank and A[r, col]:
                A[r] ^= A[rank]
        rank += 1
    return rank


def test_a_large_ladder_gets_its_squares_as_loops():
    n = 60  # loops x (bodies + joints)^2 is far above networkx's bound
    bodies = ["ground"] + [f"{x}{k}" for k in range(1, n + 1) for x in ("l", "r", "t")]
    joints = []
    prev = "ground"
    for k in range(1, n + 1):
        joints += [
            _J(f"A{k}", prev, f"l{k}"),
            _J(f"B{k}", prev, f"r{k}"),
            _J(f"C{k}", f"l{k}", f"t{k}"),
            _J(f"D{k}", f"r{k}", f"t{k}"),
        ]
        prev = f"t{k}"
    assert n * (len(bodies) + len(joints)) ** 2 > NETWORKX_LOOP_WORK
    loops = canonical_loops(bodies, joints)
    assert [set(lp.joints) for lp in loops] == [
        {f"A{k}", f"B{k}", f"C{k}", f"D{k}"} for k in range(1, n + 1)
    ]
    # each starts at its first joint in the file, oriented by its between
    assert all(lp.joints[0] == f"A{k}" and lp.signs[0] == 1 for k, lp in enumerate(loops, 1))


def _block_matrix(rng: np.random.Generator) -> np.ndarray:
    m, n = (int(x) for x in rng.integers(10, 60, 2))
    A = np.zeros((m, n))
    rp, cp = rng.permutation(m), rng.permutation(n)
    i = j = 0
    while i < m and j < n:
        a, b = (int(x) for x in rng.integers(1, 7, 2))
        blk = rng.normal(size=(min(a, m - i), min(b, n - j)))
        if rng.random() < 0.4:
            blk[:, 0] = blk[:, -1]  # a rank drop inside the block
        A[np.ix_(rp[i : i + a], cp[j : j + b])] = blk
        i, j = i + a + int(rng.random() < 0.15), j + b  # sometimes a zero row
    return A


@pytest.fixture
def blockwise():
    """Every float matrix factorised block by block, whatever its size (the dispatch table
    ``factorisation`` taken at every size)."""
    with dispatch.fast_paths("always"):
        yield


def test_block_svd_equals_the_dense_svd(blockwise):
    """The parity test of the dispatch table ``factorisation``: block by block, the whole
    matrix's singular values and an SVD of it."""
    rng = np.random.default_rng(5)
    for _ in range(60):
        A = _block_matrix(rng)
        s_dense = np.linalg.svd(A, compute_uv=False)
        assert np.allclose(block_svd(A, compute_uv=False), s_dense, atol=1e-13)
        for full in (True, False):
            U, s, Vt = block_svd(A, full_matrices=full)
            assert np.allclose(s, s_dense, atol=1e-13)
            S = np.zeros((U.shape[1], Vt.shape[0]))
            np.fill_diagonal(S, s)
            assert np.allclose(U @ S @ Vt, A, atol=1e-12)
            assert np.allclose(U.T @ U, np.eye(U.shape[1]), atol=1e-12)
            assert np.allclose(Vt @ Vt.T, np.eye(Vt.shape[0]), atol=1e-12)


def test_blocks_of_finds_the_components():
    A = np.zeros((4, 5))
    A[0, 1] = A[2, 1] = 1.0  # rows 0 and 2 share column 1
    A[1, 3] = 2.0
    got = sorted((tuple(r), tuple(c)) for r, c in blocks_of(A))
    assert got == [((), (0,)), ((), (2,)), ((), (4,)), ((0, 2), (1,)), ((1,), (3,)), ((3,), ())]


def _ladder(n: int, fold: int) -> str:
    bodies, joints, prev = ["ground"], [], "ground"
    for k in range(1, n + 1):
        bodies += [f"l{k}", f"r{k}", f"t{k}"]
        for name, a, b, x, y in (
            ("A", prev, f"l{k}", 0, k - 1),
            ("B", prev, f"r{k}", 1, k - 1),
            ("C", f"l{k}", f"t{k}", 0, k),
            ("D", f"r{k}", f"t{k}", 1, k),
        ):
            joints.append(
                f"  - {{name: {name}{k}, type: R, between: [{a}, {b}], axis: [0, 0, 1], "
                f"point: [{x}, {y}, 0]}}"
            )
        prev = f"t{k}"
    every = {f"{x}{k}": 0 for k in range(1, n + 1) for x in "ABCD"}
    every.update({f"A{fold}": -90, f"B{fold}": -90, f"C{fold}": 90, f"D{fold}": 90})
    flat = ", ".join(f"{k}: {v}" for k, v in every.items())
    return (
        "units: {angle: deg}\n"
        f"bodies: [{', '.join(bodies)}]\njoints:\n" + "\n".join(joints) + "\n"
        f"configurations:\n  reference: {{}}\n  flat: {{{flat}}}\n"
    )


@pytest.mark.parametrize("dense", [False, True])
def test_a_ladder_with_one_parallelogram_folded_flat(tmp_path, dense):
    """40 parallelograms: 40 degrees of freedom; the folded one is a change point
    (parallelogram and anti-parallelogram branches cross), so the kernel gains one
    direction and two branches of 40 degrees of freedom cross.  The block path and
    the dense path (every factorisation on the whole matrix) agree."""
    with dispatch.fast_paths(not dense):  # dense: every matrix factorised whole
        path = tmp_path / "ladder.yaml"
        path.write_text(_ladder(40, 17))
        run = run_cli(["analyze", str(path), "--precision", "float", "--format", "json"])
        assert run.status == 0, run.err
        import json

        reference, flat = json.loads(run.out)["configurations"]
        assert reference["mobility"]["finite"] == 40
        assert reference["mobility"]["instantaneous"] == 40
        assert not reference.get("singularities")
        assert flat["mobility"]["instantaneous"] == 41
        assert flat["mobility"]["finite"] == 40
        (bif,) = [s for s in flat["singularities"] if s["class"] == "bifurcation"]
        assert bif["branch_mobility"] == [40, 40]
        # the folded loop, and only it, loses rank
        ranks = {tuple(lp["joints"]): lp["rank"] for lp in flat["loops"]}
        assert ranks[("A17", "C17", "D17", "B17")] == 2
        assert sum(1 for r in ranks.values() if r == 3) == 39


def test_a_sparse_matrix_gets_the_dense_block_svd(blockwise):
    """A matrix given sparse has the blocks and the factorisation of the same matrix
    given dense, to the last bit (each block is the same dense sub-matrix)."""
    rng = np.random.default_rng(11)
    for _ in range(40):
        A = _block_matrix(rng)
        S = csc_matrix(A)
        assert [(r.tolist(), c.tolist()) for r, c in blocks_of(S)] == [
            (r.tolist(), c.tolist()) for r, c in blocks_of(A)
        ]
        assert np.array_equal(block_svd(S, compute_uv=False), block_svd(A, compute_uv=False))
        for full in (True, False):
            pairs = zip(
                block_svd(S, full_matrices=full), block_svd(A, full_matrices=full), strict=True
            )
            assert all(np.array_equal(x, y) for x, y in pairs)


def test_block_factors_solve_least_squares_block_by_block(blockwise):
    """The filtered pseudo-inverse applied block by block is numpy's pseudo-inverse
    (singular values kept above a floor) and Tikhonov's damped least squares
    ``(A^T A + lam^2 I)^-1 A^T b``, both computed on the whole dense matrix."""
    rng = np.random.default_rng(12)
    for _ in range(40):
        A = _block_matrix(rng)
        b = rng.normal(size=A.shape[0])
        F = block_factors(csc_matrix(A))
        assert np.allclose(F.s, np.linalg.svd(A, compute_uv=False), atol=1e-13)
        floor = 1e-9 * F.s[0]
        x = F.solve(b, lambda s, f=floor: np.where(s > f, 1 / np.where(s > f, s, 1), 0.0))
        assert np.allclose(x, np.linalg.pinv(A, rcond=1e-9) @ b, atol=1e-9)
        lam = 1e-3 * F.s[0]
        x = F.solve(b, lambda s, lam=lam: s / (s * s + lam * lam))
        tikhonov = np.linalg.solve(A.T @ A + lam * lam * np.eye(A.shape[1]), A.T @ b)
        assert np.allclose(x, tikhonov, atol=1e-8)
        # the solvers of Newton's steps take the sparse matrix and give the dense answer
        for solve in (damped_least_squares, truncated_least_squares):
            assert np.allclose(solve(csc_matrix(A), b), solve(A, b), atol=1e-9)


def _ladder_model(n: int, tmp_path):
    path = tmp_path / f"ladder-{n}.yaml"
    path.write_text(_ladder(n, (n + 1) // 2) + _FOLD_ONLY.format(k=(n + 1) // 2))
    return KinematicModel(load(path), "float")


#: the folded loop's four values alone: the other joints are solved by continuation
_FOLD_ONLY = "  flat-solved: {{A{k}: -90, B{k}: -90, C{k}: 90, D{k}: 90}}\n"


def test_a_ladder_closure_jacobian_built_sparse(tmp_path):
    """A ladder's closure rows: chord D_k closes through B_k forward and A_k, C_k back
    (the tree reaches rung k through A_k, C_k), the four joints of its own square and
    no other, however far the square is from ground; the sparse Jacobian holds the
    dense one's numbers."""
    m = _ladder_model(40, tmp_path)
    assert m.sparse_closure
    names = [jk.name for jk in m.joints]
    for k, jk in enumerate(m.chords, 1):
        assert jk.name == f"D{k}"
        signs = chord_signs(m)[k - 1]
        crossed = {names[i]: int(signs[i]) for i in np.flatnonzero(signs)}
        assert crossed == {f"A{k}": -1, f"B{k}": 1, f"C{k}": -1, f"D{k}": 1}
    rng = np.random.default_rng(3)
    for _ in range(3):
        q = rng.normal(size=m.n)
        J = m.sparse_closure_jacobian(q, m.float_frame)
        assert np.array_equal(J.toarray(), m.scaled_closure_jacobian(q, m.float_frame))


@pytest.mark.parametrize("dense", [False, True])
def test_a_ladder_folded_flat_by_continuation(tmp_path, dense):
    """Folding one square of a ladder (its verticals turned by -90 deg, its rung kept
    level) moves no other joint: the squares above ride on a rung that only
    translates.  Continuation from the reference with the four values alone finds
    every other joint at 0, on the sparse path and on the dense one."""
    with dispatch.fast_paths(not dense):  # dense: every matrix factorised whole
        m = _ladder_model(40, tmp_path)
        assert m.sparse_closure is not dense
        closed = Closer(m).solve("flat-solved")
        expected = {jk.name: 0.0 for jk in m.joints}
        expected.update({"A20": -np.pi / 2, "B20": -np.pi / 2, "C20": np.pi / 2, "D20": np.pi / 2})
        got = m.values(closed.q)
        assert max(abs(got[name][0] - v) for name, v in expected.items()) < 1e-9
        assert closed.residual <= 1e-12 * m.length_scale


_BENNETT = (
    ("J1", (0, 0, 1), ("0", "0", "0")),
    ("J2", ("12/25", "-9/25", "4/5"), ("3/5", "4/5", "0")),
    ("J3", ("-156/701", "429/701", "532/701"), ("-2353/3505", "-364/3505", "1248/3505")),
    ("J4", (0, "24/25", "7/25"), ("-8/5", "0", "0")),
)


def _bennett_chain(n: int, turned: int) -> str:
    """``n`` Bennett linkages (examples/bennett.yaml's, moved up 2 m per loop), link 2
    of each the base of the next; ``turned``: loop ``turned``'s J1 at 30 deg, the
    rest solved."""
    bodies, joints, base = ["ground"], [], "ground"
    for k in range(1, n + 1):
        names = [base, f"l1_{k}", f"l2_{k}", f"l3_{k}"]
        bodies += names[1:]
        for i, (name, axis, point) in enumerate(_BENNETT):
            p = [point[0], point[1], f"{point[2]} + {2 * k}"]
            quoted = ", ".join(f'"{x}"' if isinstance(x, str) else str(x) for x in axis)
            joints.append(
                f"  - {{name: {name}_{k}, type: R, between: [{names[i]}, {names[(i + 1) % 4]}], "
                f"axis: [{quoted}], point: [{', '.join(repr(x) for x in p)}]}}"
            )
        base = names[2]
    return (
        f"units: {{angle: deg}}\nbodies: [{', '.join(bodies)}]\njoints:\n"
        + "\n".join(joints)
        + f"\nconfigurations:\n  reference: {{}}\n  turned: {{J1_{turned}: 30}}\n"
    )


def test_a_bennett_chain_solved_sparse_moves_one_loop(tmp_path):
    """Turning one Bennett loop of a chain of 30 (spatial loops: every screw row is
    used) moves only that loop's joints, and exactly as the lone Bennett linkage
    moves (the loops above ride on its link 2, which the loop turns rigidly).  The
    chain is solved on the sparse path, the lone linkage on the dense one."""
    chain = tmp_path / "chain.yaml"
    chain.write_text(_bennett_chain(30, 12))
    lone = tmp_path / "lone.yaml"
    lone.write_text(_bennett_chain(1, 1))
    m = KinematicModel(load(chain), "float")
    m1 = KinematicModel(load(lone), "float")
    assert m.sparse_closure and not m1.sparse_closure
    got = m.values(Closer(m).solve("turned").q)
    one = m1.values(Closer(m1).solve("turned").q)
    assert abs(one["J1_1"][0] - np.pi / 6) < 1e-15
    assert min(abs(one[f"J{i}_1"][0]) for i in (2, 3, 4)) > 0.05  # the loop moved
    for name, (v,) in got.items():
        joint, loop = name.split("_")
        expected = one[f"{joint}_1"][0] if loop == "12" else 0.0
        assert abs(v - expected) < 1e-9, name


def test_a_sparse_matrix_gets_the_dense_rank_decision(blockwise):
    """decide_rank of a sparse float matrix: the rank, the singular values and the
    margin of the same matrix given dense (its spaces, when asked, from the dense one)."""
    rng = np.random.default_rng(13)
    for _ in range(20):
        A = _block_matrix(rng)
        sparse, dense = decide_rank(csc_matrix(A), "float"), decide_rank(A, "float")
        assert sparse.rank == dense.rank and sparse.rank_bounds == dense.rank_bounds
        assert sparse.sigma == dense.sigma
        assert sparse.margin.kept == dense.margin.kept
        assert np.isclose(sparse.margin.rounding, dense.margin.rounding, rtol=1e-12)
        spaces = decide_rank(csc_matrix(A), "float", want_spaces=True)
        assert np.array_equal(
            spaces.null_space, decide_rank(A, "float", want_spaces=True).null_space
        )
