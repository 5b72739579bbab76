"""Batched scans of open chains (mechsing.scan, issue 7).

The scan must give the verdicts of the one-configuration path (the output
chain's commensurate matrix decided by ``decide_rank`` in float) at every
configuration, and its determinant screen must never certify a configuration
the SVD would not.  Independent answers: UR5's published determinant
(``det J = -a2 a3 s3 s5 (a2 c2 + a3 c23 + d5 s234)``, examples/ur5.yaml), so the
singular set is known in closed form; and the SVD itself for the bound.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mechsing
from mechsing import lie
from mechsing.kinematics import KinematicModel, forward
from mechsing.kinematics.chains import tree_chain
from mechsing.model.mechanism import MechanismError
from mechsing.numeric import decide_rank, scale_screws
from mechsing.screws import chain_matrix
from mechsing.singularity import output_chain, random_configurations
from mechsing.singularity.classification import _output_point
from mechsing.sweeps.scan import ChainScanner, scan
from tests.mechanisms import EXAMPLES, PLANAR_3R_POINT, ROOT, scaled_text

SERIAL_FILES = [
    EXAMPLES / "ur5.yaml",
    EXAMPLES / "puma560.yaml",
    ROOT / "tests" / "data" / "serial_mixed.yaml",
]

#: UR5 DH lengths (examples/ur5.yaml header)
A2, A3, D5 = -0.425, -0.39225, 0.09465


REDUNDANT_7R = """\
mechanism: redundant-7r
bodies: [b0, b1, b2, b3, b4, b5, b6, b7]
joints:
  - {name: J1, type: R, between: [b0, b1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [b1, b2], axis: [0, 1, 0], point: [0, 0, "1/3"]}
  - {name: J3, type: R, between: [b2, b3], axis: [0, 0, 1], point: [0, 0, "2/3"]}
  - {name: J4, type: R, between: [b3, b4], axis: [0, 1, 0], point: [0, 0, 1]}
  - {name: J5, type: R, between: [b4, b5], axis: [0, 0, 1], point: [0, 0, "4/3"]}
  - {name: J6, type: R, between: [b5, b6], axis: [0, 1, 0], point: [0, 0, "5/3"]}
  - {name: J7, type: P, between: [b6, b7], axis: [1, 0, 0]}
"""


def _reference_matrices(mech, Q: np.ndarray) -> list[np.ndarray]:
    """The one-configuration path: KinematicModel poses and screws.chain_matrix, as
    the analysis decides the output chain (the decision the scan must reproduce)."""
    model = KinematicModel(mech, "float")
    _, cols = output_chain(mech, model)
    out = []
    for q in Q:
        poses = model.poses(q)
        x = _output_point(mech, model, q, poses)
        out.append(chain_matrix(model, model.current_screws(q, poses), cols, x))
    return out


def _write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def _ur5_near_singular() -> np.ndarray:
    """UR5 configurations 10^-k from each published singular set, k = 0 .. 15."""
    rows = []
    base = np.array([0.3, -0.7, 1.1, -0.4, 0.9, 0.2])
    for k in range(16):
        d = 10.0**-k
        wrist = base.copy()
        wrist[4] = d
        elbow = base.copy()
        elbow[2] = math.pi - d
        rows += [wrist, elbow]
    # exactly singular: wrist, elbow, and both
    for q5, q3 in ((0.0, 1.1), (0.9, 0.0), (0.0, 0.0)):
        q = base.copy()
        q[4], q[2] = q5, q3
        rows.append(q)
    return np.array(rows)


#: joint kinds of the random open trees
_RANDOM_TYPES = ("R", "P", "H", "C", "U", "S")


def _random_tree(seed: int) -> str:
    """A random open tree of 5 joints of the kinds above (each joins a new body to an
    earlier one, in either orientation), its output the last body relative to another."""
    rng = np.random.default_rng(seed)

    def vec() -> str:
        return "[" + ", ".join(f"{x:.6f}" for x in rng.normal(size=3)) + "]"

    lines = ["mechanism: random-tree", "bodies: [b0, b1, b2, b3, b4, b5]", "joints:"]
    for k in range(1, 6):
        kind = _RANDOM_TYPES[int(rng.integers(len(_RANDOM_TYPES)))]
        parent = f"b{int(rng.integers(k))}"
        a, b = (parent, f"b{k}") if rng.random() < 0.7 else (f"b{k}", parent)
        params = {
            "R": f"axis: {vec()}, point: {vec()}",
            "P": f"axis: {vec()}",
            "H": f"axis: {vec()}, point: {vec()}, pitch: {rng.uniform(-0.5, 0.5):.4f}",
            "C": f"axis: {vec()}, point: {vec()}",
            "U": f"axes: [[0, 0, 1], [1, 0, 0]], point: {vec()}",
            "S": f"point: {vec()}",
        }[kind]
        lines.append(f"  - {{name: J{k}, type: {kind}, between: [{a}, {b}], {params}}}")
    lines.append(f"output: {{body: b5, relative_to: b{int(rng.integers(1, 5))}}}")
    return "\n".join(lines) + "\n"


def _lie_pose(model, body: str, q: np.ndarray) -> np.ndarray:
    """The pose of ``body`` at one configuration: the product of lie.exp of the joint
    values along its tree path (inverted where the path crosses a joint backward)."""
    g = lie.identity()
    for step in model.mech.graph.tree_paths[body]:
        jk = model.joint(step.joint)
        qj = q[jk.columns]
        if jk.type == "U":
            M = lie.compose(lie.exp(jk.basis[0] * qj[0]), lie.exp(jk.basis[1] * qj[1]))
        else:
            M = lie.exp(qj @ jk.basis)
        g = lie.compose(g, M if step.sign > 0 else lie.inverse(M))
    return g


def _mechanisms(tmp_path: Path, open_only: bool = False) -> list:
    """The bundled arms, the point and 7R chains above, six random trees, and (unless
    ``open_only``) a closed mechanism (its spanning tree)."""
    texts = [PLANAR_3R_POINT, REDUNDANT_7R] + [_random_tree(seed) for seed in range(6)]
    files = [_write(tmp_path, f"m{i}.yaml", t) for i, t in enumerate(texts)]
    closed = [] if open_only else [EXAMPLES / "stewart_octahedral.yaml"]
    return [mechsing.load(p) for p in [*SERIAL_FILES, *closed, *files]]


def test_batched_poses_are_products_of_lie_exponentials(tmp_path: Path) -> None:
    """For random configurations of random trees (every joint kind, joints crossed both
    ways), of the bundled arms and of a closed mechanism, each row of the batched poses
    is the product of exponentials of its tree path, and so is the one-configuration pose."""
    for mech in _mechanisms(tmp_path):
        model = KinematicModel(mech, "float")
        Q = random_configurations(model, 12, seed=5)
        poses = forward.poses(model, Q)
        for i, q in enumerate(Q):
            one = model.poses(q)
            for body in mech.bodies:
                want = _lie_pose(model, body, q)
                np.testing.assert_allclose(poses[body][i], want, rtol=0, atol=1e-12)
                np.testing.assert_allclose(one[body], want, rtol=0, atol=1e-12)


def _moved(model, q: np.ndarray, col: int, h: float) -> np.ndarray:
    """q with coordinate ``col`` moved by h on the group (the model's update, whose
    velocity the current screws are)."""
    d = np.zeros(model.n)
    d[col] = h
    return model.update(q, d)


def test_current_screws_are_finite_differences_of_poses(tmp_path: Path) -> None:
    """Each current screw (batched Jacobian column) is the velocity of the joint's body b
    relative to its body a when its coordinate moves, both seen in ground:
    ``V_b - V_a`` with ``V_x = log(g_x(q + h e_i) g_x(q - h e_i)^-1) / 2h``, whichever
    of a and b the spanning tree reaches first (central differences)."""
    h = 1e-6
    for mech in _mechanisms(tmp_path, open_only=True):
        model = KinematicModel(mech, "float")
        Q = random_configurations(model, 4, seed=9)
        S = forward.current_screws(model, Q)
        for i, q in enumerate(Q):
            for jk in model.joints:
                for col in range(jk.columns.start, jk.columns.stop):
                    Pp = model.poses(_moved(model, q, col, h))
                    Pm = model.poses(_moved(model, q, col, -h))
                    fd = sum(
                        s * lie.log(lie.compose(Pp[x], lie.inverse(Pm[x]))) / (2 * h)
                        for x, s in ((jk.b, 1), (jk.a, -1))
                    )
                    np.testing.assert_allclose(
                        S[i, :, col], fd, rtol=0, atol=1e-6 * max(1.0, np.abs(fd).max())
                    )


def _rel(model, q: np.ndarray) -> np.ndarray:
    """The output body's displacement relative to ``relative_to``."""
    out = model.mech.output
    P = model.poses(q)
    return lie.compose(lie.inverse(P[out.relative_to]), P[out.body])


def test_scanned_matrices_are_finite_differences_of_the_output(tmp_path: Path) -> None:
    """The scanner's matrices (serial fast path and general path) are the commensurate
    velocities of the output when each chain coordinate moves: the twist of the output
    body relative to ``relative_to`` (times the sign of the column's joint on the chain:
    the columns are the joints' own screws) or its point's velocity, by central
    differences of the poses."""
    h = 1e-6
    for mech in _mechanisms(tmp_path, open_only=True):
        sc = ChainScanner(mech)
        model = sc.model
        out = mech.output
        Q = random_configurations(model, 4, seed=3)
        J = sc.matrices(Q)
        signs = tree_chain(model, out.body, out.relative_to).signs
        assert J.shape == (len(Q), sc.rows, len(sc.columns))
        L, c = sc.length_scale, sc.centroid
        for i, q in enumerate(Q):
            base = model.poses(q)[out.relative_to]
            for k, col in enumerate(sc.columns):
                qp, qm = _moved(model, q, col, h), _moved(model, q, col, -h)
                if sc.point is None:
                    # the relative twist, seen in ground at the reference body's pose
                    tw = lie.log(lie.compose(_rel(model, qp), lie.inverse(_rel(model, qm))))
                    fd = lie.act_screw(base, tw / (2 * h)) * signs[col]
                    want = scale_screws(fd[:, None], L, c, sc.length_columns[k : k + 1])[:, 0]
                else:
                    xp = lie.act_point(model.poses(qp)[out.body], sc.point)
                    xm = lie.act_point(model.poses(qm)[out.body], sc.point)
                    want = (xp - xm) / (2 * h) / L * (L if sc.length_columns[k] else 1.0)
                np.testing.assert_allclose(
                    J[i, :, k], want, rtol=0, atol=1e-6 * max(1.0, np.abs(want).max())
                )


@pytest.mark.parametrize("text", [PLANAR_3R_POINT, REDUNDANT_7R], ids=["point", "7R"])
def test_point_output_and_redundant_chain(text: str, tmp_path: Path) -> None:
    mech = mechsing.load(_write(tmp_path, "m.yaml", text))
    sc = ChainScanner(mech)
    Q = random_configurations(sc.model, 30, seed=2)
    Q[0] = 0.0  # stretched planar arm / 7R at home
    res = sc.scan(Q)
    want = [decide_rank(M, "float").rank for M in _reference_matrices(mech, Q)]
    assert [int(r) if r >= 0 else None for r in res.rank] == want


def test_planar_point_generic_rank_is_two(tmp_path: Path) -> None:
    """A planar arm's point moves in the plane: rank 2 generically (the z row is zero), rank 1
    when stretched (closed form), and the screen, which certifies full rank only, never fires."""
    mech = mechsing.load(_write(tmp_path, "m.yaml", PLANAR_3R_POINT))
    res = scan(mech, np.array([[0.0, 0.0, 0.0], [0.3, 0.5, -0.2]]))
    assert res.generic_rank == 2
    assert res.rank.tolist() == [1, 2]
    assert res.singular.tolist() == [True, False]
    assert not res.screened.any()


@pytest.mark.parametrize("path", SERIAL_FILES[:2], ids=lambda p: p.stem)
def test_verdicts_equal_decide_rank_near_and_at_singularities(path: Path) -> None:
    mech = mechsing.load(path)
    sc = ChainScanner(mech)
    Q = np.concatenate([random_configurations(sc.model, 200, seed=11), _ur5_near_singular()])
    res = sc.scan(Q, chunk=37)
    want = [decide_rank(M, "float") for M in _reference_matrices(mech, Q)]
    got = [int(r) if r >= 0 else None for r in res.rank]
    assert got == [w.rank for w in want]
    # where the SVD ran, the ratio is the decision's sigma_min / sigma_max
    ran = ~res.screened
    for i in np.flatnonzero(ran):
        s = want[i].sigma
        assert res.ratio[i] == pytest.approx(s[-1] / s[0], rel=1e-6, abs=1e-15)
    assert res.generic_rank == 6


def test_ur5_singular_set_matches_the_published_determinant() -> None:
    """Scan verdicts against UR5's closed-form det J (header of examples/ur5.yaml): configurations
    where |det| is large are regular; the wrist, elbow and shoulder sets are singular."""
    mech = mechsing.load(EXAMPLES / "ur5.yaml")
    rng = np.random.default_rng(5)
    Q = rng.uniform(-math.pi, math.pi, size=(2000, 6))
    t2, t3, t4, t5 = Q[:, 1], Q[:, 2], Q[:, 3], Q[:, 4]
    det = (
        -A2
        * A3
        * np.sin(t3)
        * np.sin(t5)
        * (A2 * np.cos(t2) + A3 * np.cos(t2 + t3) + D5 * np.sin(t2 + t3 + t4))
    )
    res = scan(mech, Q)
    assert not res.singular[np.abs(det) > 1e-6].any()
    # the three published singular sets, exactly
    sing = Q[:30].copy()
    sing[:10, 4] = 0.0  # wrist
    sing[10:20, 2] = math.pi  # elbow folded
    # shoulder: theta3 = pi/2 and theta234 = 0 leave a2 c2 - a3 s2 = 0
    sing[20:, 1] = math.atan(A2 / A3)
    sing[20:, 2] = math.pi / 2
    sing[20:, 3] = -sing[20:, 1] - math.pi / 2
    res = scan(mech, sing)
    assert (res.rank == 5).all(), res.rank


def test_screen_bound_is_a_lower_bound() -> None:
    mech = mechsing.load(EXAMPLES / "puma560.yaml")
    sc = ChainScanner(mech)
    Q = np.concatenate([random_configurations(sc.model, 500, seed=3), _ur5_near_singular()])
    res = sc.scan(Q, all_sigma=True)
    assert np.isfinite(res.ratio).all()
    assert (res.bound <= res.ratio * (1 + 1e-12)).all()
    assert res.screened.sum() > 400  # nearly every random configuration is screened


@settings(max_examples=40, deadline=None)
@given(
    q=st.lists(st.floats(-4.0, 4.0), min_size=6, max_size=6),
    scale=st.sampled_from(["/1000000", "*1", "*1000000"]),
)
def test_screen_never_disagrees_with_the_svd(q: list[float], scale: str) -> None:
    """Property: on any configuration of UR5, its lengths scaled by 1e-6, 1 or 1e6, the
    screened verdict is the SVD's, and the bound holds."""
    mech = _scaled_ur5(scale)
    sc = ChainScanner(mech)
    Q = np.array([q])
    a = sc.scan(Q)
    b = sc.scan(Q, all_sigma=True)
    assert a.rank.tolist() == b.rank.tolist()
    assert b.bound[0] <= b.ratio[0] * (1 + 1e-12)


@functools.cache
def _scaled_ur5(factor: str):
    return mechsing.model.loads(scaled_text(EXAMPLES / "ur5.yaml", factor))


def test_chunks_and_iterables_give_the_same_result() -> None:
    mech = mechsing.load(EXAMPLES / "ur5.yaml")
    sc = ChainScanner(mech)
    Q = np.concatenate([random_configurations(sc.model, 100, seed=1), _ur5_near_singular()])
    whole = sc.scan(Q)
    parts = sc.scan((Q[i : i + 13] for i in range(0, len(Q), 13)), chunk=5)
    assert whole.rank.tolist() == parts.rank.tolist()
    np.testing.assert_array_equal(whole.screened, parts.screened)
    np.testing.assert_array_equal(whole.bound, parts.bound)
    assert len(sc.scan(np.zeros((0, 6)))) == 0


def test_scan_agrees_with_analyze_on_the_file_configurations() -> None:
    for path in SERIAL_FILES[:2]:
        mech = mechsing.load(path)
        res = mechsing.analyze(path, precision="float").to_json()
        sc = ChainScanner(mech)
        model = sc.model
        for c in res["configurations"]:
            q = np.concatenate([np.asarray(v, dtype=float) for v in c["joints"].values()])
            assert q.shape == (model.n,)
            r = sc.scan(q[None, :])
            serial = [f for f in c["singularities"] if f["class"] == "serial"]
            assert bool(r.singular[0]) == bool(serial), (path.name, c["name"])
            if serial:
                assert int(r.rank[0]) == serial[0]["rank"]


def test_the_package_function_survives_importing_the_module() -> None:
    """`mechsing.scan` is the function, also after `mechsing.sweeps.scan` has been imported."""
    import mechsing.sweeps.scan

    assert callable(mechsing.scan)
    res = mechsing.scan(EXAMPLES / "ur5.yaml", [[0.1, -0.7, 1.1, -0.4, 0.9, 0.2]])
    assert res.rank.tolist() == [6] and mechsing.sweeps.scan.scan is mechsing.scan


def test_rows_given_as_lists_and_ragged_blocks() -> None:
    mech = mechsing.load(EXAMPLES / "ur5.yaml")
    sc = ChainScanner(mech)
    rows = [[0.1, -0.7, 1.1, -0.4, 0.9, 0.2], [0.1, -0.7, 1.1, -0.4, 0.0, 0.2]]
    assert sc.scan(rows).rank.tolist() == [6, 5]
    blocks = [np.array(rows), np.array(rows[:1])]
    assert sc.scan(blocks).rank.tolist() == [6, 5, 6]


@pytest.mark.parametrize("bad", [math.nan, math.inf, 1e20])
def test_values_analyze_refuses_are_refused(bad: float) -> None:
    """Non-finite values and values above MAX_JOINT_VALUE: a ValueError naming the row
    (numpy would fail inside the SVD, or scan an absurd configuration)."""
    sc = ChainScanner(mechsing.load(EXAMPLES / "ur5.yaml"))
    Q = np.zeros((3, 6))
    Q[2, 4] = bad
    with pytest.raises(ValueError, match="row 2"):
        sc.scan(Q)


def test_refusals(tmp_path: Path) -> None:
    with pytest.raises(MechanismError, match="open chains"):
        ChainScanner(mechsing.load(EXAMPLES / "fourbar.yaml"))
    mech = mechsing.load(EXAMPLES / "ur5.yaml")
    with pytest.raises(ValueError, match=r"shape \(N, 6\)"):
        ChainScanner(mech).matrices(np.zeros((3, 5)))
    with pytest.raises(ValueError, match="chunk"):
        ChainScanner(mech).scan(np.zeros((3, 6)), chunk=0)
