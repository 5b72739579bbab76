"""The singularity tests, each defined once (:mod:`mechsing.singularity.criteria`), and
the one rank rule of :mod:`mechsing.numeric` they decide through.

Each test is checked against a closed form, for any leading batch shape, and a batch's
decision against the one-configuration decision of the same test object (the single
definition).  A last test reads every module's source: the rank rule is called only from
``numeric`` and the test objects.
"""

from __future__ import annotations

import ast
import math
from pathlib import Path

import mpmath
import numpy as np

import mechsing
from mechsing.kinematics import Closer, KinematicModel, forward
from mechsing.model.loader import loads
from mechsing.numeric import Precision, parse_precision, rank_bounds, to_float
from mechsing.numeric.linalg import clear_complements
from mechsing.screws import closure_system
from mechsing.singularity.criteria import ClosureTest, ConstraintTest, MotionTest, SerialTest
from tests.mechanisms import PLANAR_3R_POINT

PACKAGE = Path(__file__).resolve().parents[1] / "mechsing"
EX = PACKAGE.parent / "examples"


def test_the_rank_rule_counts_the_two_thresholds_over_any_batch_shape():
    """rank_bounds: lowest = #(sigma >= tau_hi), highest = #(sigma > tau_lo), per matrix,
    for a batch of shape (2, 2) as for one matrix (shape ())."""
    tol = Precision("float").tolerances  # tau_lo 1e-12, tau_hi 1e-9
    rel = np.array(
        [
            [[1.0, 1e-3, 0.0], [1.0, 1e-10, 0.0]],  # rank 2; undecided 1..2
            [[1.0, 1e-9, 1e-12], [0.0, 0.0, 0.0]],  # tau_hi kept, tau_lo dropped: 2; 0
        ]
    )
    lo, hi = rank_bounds(rel, tol)
    assert lo.tolist() == [[2, 1], [2, 0]]
    assert hi.tolist() == [[2, 2], [2, 0]]
    one = rank_bounds(rel[0, 1], tol)
    assert (int(one[0]), int(one[1])) == (1, 2)


def test_the_rank_rule_compares_mp_numbers_below_the_float_range():
    """At mp:400 tau_lo = 10^-390 and tau_hi = 10^-200 are below the float range: the rule
    compares the mp numbers themselves (10^-300 lies between them: undecided; 10^-395 is
    dropped), which as floats would both be 0."""
    prec = parse_precision("mp:400")
    with prec.context():
        rel = [mpmath.mpf(1), mpmath.mpf("1e-150"), mpmath.mpf("1e-300"), mpmath.mpf("1e-395")]
        lo, hi = rank_bounds(rel, prec.tolerances)
    assert (int(lo), int(hi)) == (2, 3)


def _arm():
    mech = loads(PLANAR_3R_POINT)
    return mech, KinematicModel(mech, "float")


def test_the_serial_test_of_a_planar_arm_is_its_closed_form_for_any_batch_shape():
    """The velocity of the arm's end point spans the plane (rank 2) unless every link is
    aligned (q2 = q3 = 0 mod pi: rank 1).  The serial test's matrices and ranks for a batch
    of shape (2, 2), and its one-configuration decision, all say so."""
    mech, model = _arm()
    test = SerialTest.of(mech, model)
    motion = MotionTest.of(mech, model)
    Q = np.array(
        [[[0.0, 0.0, 0.0], [0.3, 0.5, -0.2]], [[1.0, math.pi, 0.0], [-0.4, 1.2, 0.7]]]
    )  # (2, 2, 3)
    want = [[1, 2], [1, 2]]
    flat = Q.reshape(-1, 3)
    S = np.stack([model.current_screws(q) for q in flat])
    x = np.stack([motion.output_point(model.poses(q), float_point=True) for q in flat])
    M = test.matrix(S.reshape(2, 2, 6, 3), [0, 1, 2], x.reshape(2, 2, 3))[0]
    assert M.shape == (2, 2, 3, 3)
    assert test.batch_ranks(M).decided.tolist() == want
    for q, r in zip(flat, np.ravel(want), strict=True):
        one = test.decide(
            model.current_screws(q), [0, 1, 2], motion.output_point(model.poses(q)), "float"
        )
        assert one.rank.rank == r
        assert test.batch_ranks(one.matrix).decided.tolist() == r  # batch shape ()


def test_the_motion_test_of_the_five_bar_at_a_batch_is_its_one_configuration_decision():
    """The five-bar's inputs and output point both span its two-dof motion (file
    comment): T N and E N of rank 2, no input, output or passive motion, at every closed
    configuration of the file; the batch decision of the motion test equals its
    one-configuration decision (the same object)."""
    mech = mechsing.load(EX / "five_bar.yaml")
    model = KinematicModel(mech, "float")
    closer = Closer(model)
    test = MotionTest.of(mech, model)
    assert MotionTest.of(mech, model) is test  # one plan per model
    Qs, Ns, ones = [], [], []
    for name in ["reference", "inputs"]:
        q = np.asarray(to_float(closer.solve(name).q), dtype=float)
        cs = closure_system(model, q)
        N = np.asarray(to_float(cs.rank.null_space), dtype=float)
        T = test.output_rows(cs.screws, test.output_point(model.poses(q)))
        one = test.decide(T, test.E, N, Precision("float"))
        Qs.append(q)
        Ns.append(N)
        ones.append(one.values())
    Q = np.array(Qs)
    P = forward.poses(model, Q)
    S = forward.current_screws(model, Q, P)
    T, nT = test.batch_output_rows(S, P)
    many = test.batch_values(T, nT, np.array(Ns))
    want = {
        "input": 0,
        "output": 0,
        "passive-motion": 0,
        "impossible-input": 2,
        "impossible-output": 2,
    }
    assert many == ones == [want, want]


def _turned(mech, model, column, values=None):
    """The commensurate screws of the file's reference configuration with one joint
    coordinate given ``values`` (default: 121 over [-pi, pi]; no closure needed for
    the rows)."""
    values = np.linspace(-np.pi, np.pi, 121) if values is None else np.asarray(values)
    q0 = np.asarray(to_float(Closer(model).solve("reference").q), dtype=float)
    Q = np.tile(q0, (len(values), 1))
    Q[:, column] = values
    P = forward.poses(model, Q)
    return model.frame.screws(forward.current_screws(model, Q, P))


def test_the_closure_test_models_each_loop_in_its_own_subgroup():
    """A loop through the ground stays in the subgroup its joints generate at the
    reference (a planar loop in its plane's G, a spherical one in its S): its rows are
    that subalgebra's coordinates, 3 rows not 6, with the singular values of the
    six-row stacked screws at every configuration (an isometry of the span they lie
    in), also where the loop is singular.  A loop that generates all of D keeps its
    six rows."""
    eps = np.finfo(float).eps
    for name, loops, rows in [
        ("five_bar.yaml", 1, 3),
        ("planar_3rpr.yaml", 2, 6),
        ("spherical_4r.yaml", 1, 3),
        ("bennett.yaml", 1, 6),
    ]:
        mech = mechsing.load(EX / name)
        model = KinematicModel(mech, "float")
        test = ClosureTest.of(mech, model)
        assert len(mech.loops) == loops and test.rows == rows, name
        Ss = _turned(mech, model, 0)
        got = test.matrices(Ss)
        six = (Ss[:, None] * test.loop_signs[None, :, None, :]).reshape(len(Ss), -1, model.n)
        assert got.shape == (len(Ss), rows, model.n)
        s_got = np.linalg.svd(got, compute_uv=False)
        s_six = np.linalg.svd(six, compute_uv=False)
        np.testing.assert_allclose(s_got, s_six[:, :rows], rtol=0, atol=100 * eps, err_msg=name)
        # the rows left out are zero: the six-row system has no other singular value
        np.testing.assert_allclose(s_six[:, rows:], 0, rtol=0, atol=100 * eps, err_msg=name)


def test_the_constraint_test_of_the_five_bar_counts_the_planar_wrenches():
    """Each leg of the five-bar (planar) resists the three out-of-plane wrenches; leg 1
    (two joints up to the output body) also resists the force along its distal link:
    together four independent wrenches, in a batch as at one configuration."""
    mech = mechsing.load(EX / "five_bar.yaml")
    model = KinematicModel(mech, "float")
    test = ConstraintTest.of(mech, model)
    assert len(test.legs) == 2
    q = np.asarray(to_float(Closer(model).solve("reference").q), dtype=float)
    cs = closure_system(model, q)
    dec, _ = test.decide(cs, Precision("float"))
    Ss = model.frame.screws(cs.screws)[None]
    assert dec.rank == 4
    assert test.batch_values(Ss) == [4]
    rows = test.wrench_rows(Ss, np.zeros((len(mech.loops), model.n)))
    assert np.linalg.matrix_rank(rows[0]) == 4


def test_the_legs_wrenches_from_their_qr_span_the_svd_s_near_and_far_from_a_leg_singularity():
    """The five-bar's legs' wrench rows over a batch of configurations (a crank turned
    through a leg's serial singularity, where the distal links line up): leg by leg,
    the rows span the same space as the left singular vectors beyond the leg's rank (the
    same orthogonal projector to rounding), whether the leg was clearly of full rank
    (its complement from its QR) or not (the SVD's), and the legs' combined wrenches
    have the same singular values."""
    mech = mechsing.load(EX / "five_bar.yaml")
    model = KinematicModel(mech, "float")
    test = ConstraintTest.of(mech, model)
    q0 = np.asarray(to_float(Closer(model).solve("reference").q), dtype=float)
    # the chain's screws with A1 turned a full turn (no closure needed for the wrench
    # rows): the second leg's three screws pass through rank 2 and near it
    Q = np.tile(q0, (241, 1))
    Q[:, 0] = np.linspace(-np.pi, np.pi, 241)
    P = forward.poses(model, Q)
    Ss = model.frame.screws(forward.current_screws(model, Q, P))
    got = test.wrench_rows(Ss, np.zeros((len(mech.loops), model.n)))
    want, unclear = [], 0
    for leg in test.legs:
        Tl = (Ss * leg.path_signs[None, None, :])[:, :, leg.columns]
        want.append(test._wrenches_by_svd(Tl))
        unclear += int(np.sum(~clear_complements(Tl)[0]))
    assert 0 < unclear < len(Q)  # both ways of forming them are compared
    want_rows = np.concatenate(want, axis=1)
    eps = np.finfo(float).eps
    for i in range(len(test.legs)):
        A, B = got[:, 6 * i : 6 * i + 6], want_rows[:, 6 * i : 6 * i + 6]
        PA = np.swapaxes(A, 1, 2) @ A
        PB = np.swapaxes(B, 1, 2) @ B
        np.testing.assert_allclose(PA, PB, rtol=0, atol=100 * eps)
    np.testing.assert_allclose(
        np.linalg.svd(got, compute_uv=False),
        np.linalg.svd(want_rows, compute_uv=False),
        rtol=0,
        atol=100 * eps,
    )


def test_the_legs_wrenches_within_their_subalgebra_have_the_six_row_singular_values():
    """Where every leg moves in one subgroup (a planar five-bar or 3-RPR: the plane's G),
    each leg resists the three out-of-plane wrenches and, within the plane, the
    complement of its twists: the combined wrenches' singular values are sqrt(legs)
    three times beside those of the in-plane rows, at every configuration, equal to
    those of the six-row wrenches.  The five-bar's crank turns a full turn (its first
    leg, two joints, always resists the force along its distal link: one in-plane row);
    the 3-RPR's first leg is stretched through zero length, where its two revolute axes
    meet and it resists a force through them (the one configuration with an in-plane
    row).  A spatial parallel robot has no such subgroup."""
    eps = np.finfo(float).eps
    zero_length = -math.hypot(0.9, 0.3)  # P1 bringing Rp1 onto Rb1 (axis (9/10, 3/10))
    for name, column, values, rows in [
        ("five_bar.yaml", 0, np.linspace(-np.pi, np.pi, 241), 241),
        ("planar_3rpr.yaml", 1, np.append(np.linspace(-2, 2, 81), zero_length), 1),
    ]:
        mech = mechsing.load(EX / name)
        model = KinematicModel(mech, "float")
        test = ConstraintTest.of(mech, model)
        assert test.subalgebra is not None and test.subalgebra.shape == (6, 3), name
        Ss = _turned(mech, model, column, values)
        signs = ClosureTest.of(mech, model).loop_signs
        six = test.wrench_rows(Ss, signs)
        reduced = test.wrench_rows(Ss, signs, reduced=True)
        assert reduced.shape == (len(Ss), 3 * len(test.legs), 3)
        want = np.linalg.svd(six, compute_uv=False)
        got = test.combined_values(np.linalg.svd(reduced, compute_uv=False))
        # each leg's wrenches are its twists' complement, known to about eps times the
        # twists' condition number (the six-row ones' out-of-plane rows are not exactly
        # the plane's annihilator either): the values agree to that
        cond = np.ones(len(Ss))
        for leg in test.legs:
            st = np.linalg.svd(Ss[:, :, leg.columns], compute_uv=False)
            cond = np.maximum(cond, st[:, 0] / np.where(st[:, -1] > 0, st[:, -1], np.inf))
        assert np.all(np.abs(got - want) <= 100 * eps * cond[:, None]), name
        np.testing.assert_allclose(got[:, :3], math.sqrt(len(test.legs)), rtol=0, atol=0)
        # one in-plane row (a unit force) where a leg resists one, none elsewhere
        assert np.sum(np.abs(got[:, 3] - 1) < 1e-9) == rows, name
        assert np.all((np.abs(got[:, 3] - 1) < 1e-9) | (got[:, 3] < 1e-9)), name
    for name in ["stewart_octahedral.yaml", "tsai_3upu.yaml"]:
        mech = mechsing.load(EX / name)
        assert ConstraintTest.of(mech, KinematicModel(mech, "float")).subalgebra is None, name


def test_clear_row_rank_calls_clear_only_matrices_far_from_losing_rank():
    """A square or wide matrix is called clearly of full row rank exactly where its
    smallest singular value is at least CLEAR_RANK_RATIO of its largest (the SVD's
    answer), away from that ratio by more than the Gram matrix's rounding."""
    from mechsing.numeric.linalg import CLEAR_RANK_RATIO, clear_row_rank

    rng = np.random.default_rng(3)
    A = rng.standard_normal((400, 3, 4))
    # some of them brought to rank 2, and some near the ratio
    A[:100, 2] = A[:100, 0] - 2 * A[:100, 1]
    A[100:200, 2] = A[100:200, 0] + 1e-6 * A[100:200, 2]
    s = np.linalg.svd(A, compute_uv=False)
    ratio = s[:, -1] / s[:, 0]
    got = clear_row_rank(A)
    far = np.abs(ratio - CLEAR_RANK_RATIO) > 1e-6
    assert np.array_equal(got[far], (ratio >= CLEAR_RANK_RATIO)[far])
    assert not got[:200].any() and got[200:].any()
    assert not clear_row_rank(np.zeros((2, 3, 3))).any()


def test_clear_complements_are_the_svd_s_and_only_clear_matrices_are_called_clear():
    """numeric.linalg.clear_complements on random batches (N, 6, k), k = 1..5, scaled from
    1e-150 to 1e150, with zero, rank-deficient and nearly rank-deficient matrices: a
    matrix is called clear exactly when its smallest singular value is at least
    CLEAR_RANK_RATIO of its largest (never a zero or rank-deficient one), and a clear
    one's complement is orthonormal with the SVD's projector; the ratio is the sweeps'
    Gram ratio (one rule, two modules)."""
    from mechsing.numeric.linalg import CLEAR_RANK_RATIO
    from mechsing.sweeps.settings import SWEEP_GRAM_RATIO

    assert CLEAR_RANK_RATIO == SWEEP_GRAM_RATIO
    rng = np.random.default_rng(5)
    eps = np.finfo(float).eps
    for k in range(1, 6):
        A = rng.standard_normal((400, 6, k)) * 10.0 ** rng.uniform(-150, 150, (400, 1, 1))
        A[:20] = 0.0
        if k > 1:
            A[20:60, :, -1] = A[20:60, :, 0] * 3.0  # rank k - 1
            A[60:100, :, -1] = A[60:100, :, 0] + 1e-9 * A[60:100, :, 1]  # nearly
        clear, K = clear_complements(A)
        s = np.linalg.svd(A, compute_uv=False)
        ratio = s[:, -1] / np.where(s[:, 0] > 0, s[:, 0], 1.0)
        assert not clear[:20].any()
        if k > 1:
            assert not clear[20:100].any()
        far = np.abs(ratio - CLEAR_RANK_RATIO) > 1e-6
        assert np.array_equal(clear[far], (ratio >= CLEAR_RANK_RATIO)[far])
        assert clear.sum() > 200
        U = np.linalg.svd(A[clear])[0][:, :, k:]
        Kc = K[clear]
        np.testing.assert_allclose(
            Kc @ np.swapaxes(Kc, 1, 2), U @ np.swapaxes(U, 1, 2), rtol=0, atol=50 * eps
        )
        np.testing.assert_allclose(
            np.swapaxes(Kc, 1, 2) @ Kc,
            np.broadcast_to(np.eye(6 - k), (len(Kc), 6 - k, 6 - k)),
            rtol=0,
            atol=50 * eps,
        )


#: the functions that apply the rank rule: called only from numeric and the test objects
_RULE = {"rank_bounds", "batched_rank_bounds", "_split_rank"}


def test_the_rank_rule_is_called_only_from_numeric_and_the_criteria():
    """Every call of the two-threshold rank rule (by any name it is exported under) in the
    package's source stands in mechsing/numeric or mechsing/singularity/criteria."""
    allowed = (PACKAGE / "numeric", PACKAGE / "singularity" / "criteria")
    callers = set()
    for path in PACKAGE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.Call):
                continue
            f = node.func
            name = f.id if isinstance(f, ast.Name) else getattr(f, "attr", None)
            if name in _RULE:
                callers.add(path)
    assert callers, "the rule's callers were not found: the names changed"
    outside = sorted(
        str(p.relative_to(PACKAGE)) for p in callers if not any(a in p.parents for a in allowed)
    )
    assert outside == []


def test_the_scan_s_compiled_screen_is_a_backend_registered_with_the_serial_test():
    """The scan (mechsing.sweeps.scan) registers its compiled screen with the serial test;
    the screen reads the serial chain's public table, not a private attribute."""
    import mechsing.sweeps.scan  # noqa: F401 - registers the screen
    from mechsing.sweeps import scan_kernel

    want = scan_kernel if scan_kernel.available() else None
    assert SerialTest.compiled_screen() is want
    source = (PACKAGE / "sweeps" / "scan_kernel.py").read_text(encoding="utf-8")
    assert "._table" not in source


def test_a_test_s_plan_is_kept_by_its_model_and_by_no_other():
    """The plan is built once per model (the same object when asked again) and kept in
    the model's own plans: a model built after another was let go, at the same address,
    gets plans of its own (the test's and the tree's), and building plans attaches
    nothing to the model."""
    import gc
    import weakref

    from mechsing.kinematics.chains import tree_chain

    mech = loads(PLANAR_3R_POINT)
    seen: dict[int, tuple[weakref.ref[SerialTest], object]] = {}
    reused = None
    for _ in range(200):  # CPython gives a let-go model's address to a new one soon
        model = KinematicModel(mech, "float")
        fields = set(vars(model))
        plan = SerialTest.of(mech, model)
        assert SerialTest.of(mech, model) is plan and plan.model is model
        chain = tree_chain(model, "l3", "base")  # holds no model: kept alive below
        assert tree_chain(model, "l3", "base") is chain
        forward.poses(model, np.zeros(model.n))
        forward.current_screws(model, np.zeros(model.n))
        assert set(vars(model)) == fields
        if id(model) in seen:
            reused = (plan, chain, *seen[id(model)])
            break
        seen[id(model)] = (weakref.ref(plan), chain)
        del model, plan
        gc.collect()
    assert reused is not None, "no address was reused in 200 models"
    plan, chain, old_plan, old_chain = reused
    assert old_plan() is None  # let go with its model
    assert chain is not old_chain and chain.signs is not old_chain.signs


def test_threads_building_models_get_their_own_plans():
    """Eight threads, each building its models in turn and asking for their tests and
    chains at once, each get plans of their own model; threads sharing one model get
    equal plans."""
    from concurrent.futures import ThreadPoolExecutor

    from mechsing.kinematics.chains import tree_chain

    mech = loads(PLANAR_3R_POINT)
    shared = KinematicModel(mech, "float")

    def work(_: int) -> bool:
        ok = True
        for _ in range(5):
            model = KinematicModel(mech, "float")
            for cls in (SerialTest, MotionTest, ConstraintTest):
                ok &= cls.of(mech, model).model is model
            ok &= SerialTest.of(mech, shared).model is shared
            ok &= tree_chain(model, "l3", "base").joints == ["R1", "R2", "R3"]
        return ok

    with ThreadPoolExecutor(8) as pool:
        assert all(pool.map(work, range(8)))
