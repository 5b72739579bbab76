"""Poses and loop closure checked against an independent computation.

Everything mechsing computes here is checked by the tests' reference
implementation (tests/reference, no mechsing inside), written from the rules alone (joint-value semantics, catalog bases, in-plane
convention, U joints): its own hat/exp (``scipy.linalg.expm`` of 4x4
matrices; for the many products of the closed chains a closed-form Rodrigues
exponential, itself checked against expm), its own bases, its own spanning
tree and its own cycles (networkx), its own closed-form four-bar, its own path
tracker (Newton with finite differences).  No test trusts the solver's
residual.

* random trees (serial arms and branching trees, every joint type): body poses;
* random closed chains taken from the reference (planar 4R/5R/6R, spatial
  6R/7R, Watt and Stephenson six-bars, an R-U-P-S loop): closure by
  continuation, the product around every cycle, the assembly mode;
* every example: every named configuration closes.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

from mechsing import lie
from mechsing.cli import exit_status
from mechsing.kinematics import Closer, ClosureError, KinematicModel
from mechsing.model import load, loads
from mechsing.numeric import MAX_JOINT_VALUE
from tests.mechanisms import FOURBAR_JOINTS
from tests.reference.files import Spec
from tests.reference.kinematics import (
    KINDS,
    J,
    assert_closes,
    closure_error,
    cycle_products,
    cycles,
    fourbar_closed_form,
    rot2,
    track,
)
from tests.reference.kinematics import joints_from_model as joints_of
from tests.reference.kinematics import poses as my_poses
from tests.reference.se3 import exp_rodrigues, expt, in_plane, unit, wrap
from tests.strategies import deltas, finite, planar_frame, plane_xy, rotation_vectors, trees
from tests.strategies import file_axes as axes
from tests.strategies import file_lengths as lengths
from tests.strategies import file_points as points

PI = math.pi
EXAMPLES = sorted((Path(__file__).resolve().parents[1] / "examples").glob("*.yaml"))

SETTINGS = settings(
    max_examples=30,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
#: closed chains cost a continuation and an independent path tracking each
LOOP_SETTINGS = settings(SETTINGS, max_examples=12)


def mech_values(model: KinematicModel, q: np.ndarray) -> dict[str, np.ndarray]:
    return {k: np.array(v) for k, v in model.values(q).items()}


def flat(mech, values: dict[str, np.ndarray]) -> np.ndarray:
    """The flat coordinate vector in mechsing's order (file order, basis order)."""
    parts = [np.asarray(values[j.name], float).reshape(-1) for j in mech.joints if j.dof]
    return np.concatenate(parts) if parts else np.zeros(0)


# ---------------------------------------------------------------------------
# 1. random trees: poses against the independent product of exponentials


@SETTINGS
@given(trees())
def test_tree_poses_match_independent_product_of_exponentials(spec):
    text, written = spec.to_file()
    # a drawn tree whose every joint point lies within 1e-12 m of the origin (the floats
    # strategy reaches 1e-165) has no size and is refused as too small a mechanism: that
    # refusal is the loader's (tests/test_hostile_numbers.py), outside what this test is about
    points = [j.prm["point"] for j in spec.joints if "point" in j.prm]
    assume(not points or max(float(np.max(np.abs(p))) for p in points) >= 1e-9)
    mech = loads(text)
    values = {j.name: written["given"].get(j.name, np.zeros(0)) for j in spec.joints}
    model = KinematicModel(mech)
    q = flat(mech, values)
    # lengths beyond MAX_JOINT_VALUE x L are refused as absurd (tests/test_cli_regressions.py);
    # a drawn mechanism of size 1e-7 m with a 1 m stroke is outside what this test is about
    assume(np.all(np.abs(q[model.length_columns]) <= MAX_JOINT_VALUE * model.length_scale))
    closed = Closer(model).solve("given")
    # a configuration that gives every value is checked, not solved: values as given
    assert closed.steps == 0 and not closed.underdetermined
    np.testing.assert_allclose(closed.q, q, rtol=1e-15, atol=0)
    theirs = model.poses(closed.q)
    mine = my_poses(spec.joints, spec.ground, values)
    assert set(theirs) == set(spec.bodies)
    scale = 1.0 + max(float(np.linalg.norm(g[:3, 3])) for g in mine.values())
    for body in spec.bodies:
        R_err = np.max(np.abs(theirs[body][:3, :3] - mine[body][:3, :3]))
        p_err = np.max(np.abs(theirs[body][:3, 3] - mine[body][:3, 3]))
        assert R_err <= 1e-12, (body, R_err)
        assert p_err <= 1e-12 * scale, (body, p_err, scale)
        np.testing.assert_array_equal(theirs[body][3], [0, 0, 0, 1])


def test_tree_with_every_joint_type_in_mm_and_deg():
    """A fixed serial arm through every type (a readable regression of the property)."""
    rng = np.random.default_rng(7)
    types = ["R", "P", "H", "C", "S", "U", "T2", "T3", "G", "X", "D", "Y", "E"]
    names = [f"b{k}" for k in range(len(types) + 1)]
    joints, values = [], {}
    for k, t in enumerate(types):
        prm = {
            "R": {"axis": [0, 0, 1], "point": [1, 2, 0]},
            "P": {"axis": [1, 1, 0]},
            "H": {"axis": [0, 1, 0], "point": [0.5, 0, 1], "pitch": 0.2},
            "C": {"axis": [1, 0, 0], "point": [0, 1, 1]},
            "S": {"point": [1, 1, 1]},
            "U": {"axes": ([0, 0, 1], [1, -1, 0]), "point": [2, 0, 1]},
            "T2": {"normal": [1, 1, 1]},
            "T3": {},
            "G": {"normal": [0, 1, 0]},
            "X": {"axis": [1, 2, 3]},
            "D": {},
            "Y": {"normal": [0, 0, -1], "pitch": -0.3},
            "E": {},
        }[t]
        for key, val in list(prm.items()):
            if key == "axes":
                prm[key] = tuple(np.asarray(v, float) for v in val)
            elif key != "pitch":
                prm[key] = np.asarray(val, float)
        joints.append(J(f"J{t}", t, names[k], names[k + 1], prm))
        values[f"J{t}"] = rng.uniform(-3, 3, len(KINDS[t]))
    spec = Spec(
        names,
        names[0],
        joints,
        {"given": {k: v for k, v in values.items() if len(v)}},
        output=names[-1],
        length="mm",
        angle="deg",
    )
    text, written = spec.to_file()
    mech = loads(text)
    model = KinematicModel(mech)
    vals = {j.name: written["given"].get(j.name, np.zeros(0)) for j in joints}
    poses = model.poses(Closer(model).solve("given").q)
    mine = my_poses(joints, names[0], vals)
    for b in names:
        np.testing.assert_allclose(poses[b], mine[b], rtol=0, atol=1e-11)


def test_this_files_conventions_by_hand():
    """The independent oracle itself, on values worked out by hand from the README's conventions."""
    z = np.array([0.0, 0, 1])
    # R about z through (1, 0, 0) by pi/2 takes the origin to (1, -1, 0)
    g = J("R", "R", "a", "b", {"axis": z, "point": np.array([1.0, 0, 0])}).element([PI / 2])
    np.testing.assert_allclose(g[:3, 3], [1, -1, 0], atol=1e-15)
    np.testing.assert_allclose(g[:3, :3], [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-15)
    # H: slide = pitch x angle along the axis
    g = J("H", "H", "a", "b", {"axis": 2 * z, "point": np.zeros(3), "pitch": 0.5}).element([PI])
    np.testing.assert_allclose(g[:3, 3], [0, 0, 0.5 * PI], atol=1e-15)
    # in-plane directions: w = z gives x, y; ties go to the first coordinate axis
    for w, e1, e2 in (
        ([0, 0, 1], [1, 0, 0], [0, 1, 0]),
        ([0, 0, -3], [1, 0, 0], [0, -1, 0]),
        ([1, 1, 0], [0, 0, 1], [1 / math.sqrt(2), -1 / math.sqrt(2), 0]),
        ([1, 1, 1], [2 / math.sqrt(6), -1 / math.sqrt(6), -1 / math.sqrt(6)], None),
    ):
        f1, f2 = in_plane(w)
        np.testing.assert_allclose(f1, e1, atol=1e-15)
        np.testing.assert_allclose(f2, np.cross(unit(w), f1) if e2 is None else e2, atol=1e-15)
    # U: first about a1 (fixed in between[0]), then about a2 carried by it
    u = J("U", "U", "a", "b", {"axes": (z, np.array([1.0, 0, 0])), "point": np.zeros(3)})
    g = u.element([PI / 2, PI / 2])
    np.testing.assert_allclose(g[:3, :3] @ [0, 1, 0], [0, 0, 1], atol=1e-15)
    # G rotates about its normal through the origin, then e1 = x, e2 = y slides
    G = J("G", "G", "a", "b", {"normal": z})
    np.testing.assert_allclose(G.element([0, 2, 3])[:3, 3], [2, 3, 0], atol=1e-15)
    # D: the value is the twist itself; S: a rotation vector about the point
    S = J("S", "S", "a", "b", {"point": np.array([1.0, 2, 3])}).element([0, 0, PI])
    np.testing.assert_allclose(S @ [1, 2, 3, 1], [1, 2, 3, 1], atol=1e-14)
    np.testing.assert_allclose(S @ [1, 3, 3, 1], [1, 1, 3, 1], atol=1e-14)
    D = J("D", "D", "a", "b").element([0, 0, 0, 1, 2, 3])
    np.testing.assert_allclose(D[:3, 3], [1, 2, 3], atol=1e-15)
    # a path crossed from b to a uses the inverse
    joints = [J("A", "R", "b", "a", {"axis": z, "point": np.array([1.0, 0, 0])})]
    poses = my_poses(joints, "a", {"A": [PI / 2]})
    np.testing.assert_allclose(poses["b"] @ [0, 0, 0, 1], [1, 1, 0, 1], atol=1e-15)


@SETTINGS
@given(rotation_vectors(), st.tuples(lengths, lengths, lengths))
def test_closed_form_exponential_of_this_file_agrees_with_expm(w, v):
    xi = np.concatenate([w, v])
    np.testing.assert_allclose(exp_rodrigues(xi), expt(xi), rtol=0, atol=1e-13)


def loop_joints(pts, axs, types=None, flips=None, prefix="J") -> tuple[list[str], list[J]]:
    """A single loop ground -> l1 -> ... -> ground through the given joints."""
    n = len(pts)
    bodies = ["ground"] + [f"l{k}" for k in range(1, n)]
    joints = []
    for k in range(n):
        a, b = bodies[k], bodies[(k + 1) % n]
        if flips is not None and flips[k]:
            a, b = b, a
        t = "R" if types is None else types[k]
        joints.append(J(f"{prefix}{k}", t, a, b, {"axis": axs[k], "point": pts[k]}))
    return bodies, joints


def char_length(joints: list[J]) -> float:
    pts = [np.asarray(j.prm["point"], float) for j in joints if "point" in j.prm]
    return max(1.0, max(float(np.linalg.norm(p)) for p in pts))


def solve_file(spec: Spec):
    text, written = spec.to_file()
    mech = loads(text)
    model = KinematicModel(mech)
    return mech, model, Closer(model), written


def spread(pts2) -> bool:
    """Points of a planar linkage that are not bunched (every pair at least 0.3 apart)."""
    P = np.asarray(pts2)
    return all(np.linalg.norm(P[i] - P[k]) > 0.3 for i in range(len(P)) for k in range(i))


def spread_off_a_line(pts2) -> bool:
    """Points that are :func:`spread` and not nearly on one line (off their best line by
    0.1 or more): a planar loop whose joints are all in line is singular (its closure's
    columns (1, y_i, -x_i) span a plane only)."""
    P = np.asarray(pts2)
    return spread(P) and np.linalg.svd(P - P.mean(axis=0), compute_uv=False)[-1] > 0.1


# ---------------------------------------------------------------------------
# 2a. planar four-bar: against the closed-form solution and its assembly mode


@LOOP_SETTINGS
@given(
    planar_frame(),
    st.lists(plane_xy, min_size=4, max_size=4).filter(spread),
    st.lists(st.floats(-1, 1, **finite), min_size=4, max_size=4),
    st.lists(st.booleans(), min_size=4, max_size=4),
    deltas,
    deltas,
)
def test_planar_fourbar_matches_closed_form(frame, xy, heights, flips, d1, d2):
    """Random planar 4R (parallel axes, some reversed, points at random heights
    along them), crank moved in two chained configurations: the solution is the
    closed-form one on the reference's assembly mode; a crank that cannot turn
    that far gives a ClosureError."""
    w, e1, e2, c0 = frame
    P2 = [np.array(p) for p in xy]
    pts = [c0 + p[0] * e1 + p[1] * e2 + h * w for p, h in zip(P2, heights, strict=True)]
    # the axes are parallel: w, or -w for some joints (the same line, opposite sense)
    signs = [1 if (k % 2 == 0) else -1 for k in range(4)]
    bodies, joints = loop_joints(pts, [s * w for s in signs], flips=flips)
    A2, B2, C2, D2 = P2
    # absolute crank angle (about w) per unit value of J0
    sA = signs[0] * (-1 if flips[0] else 1)
    first, second = d1, d1 + d2
    spec = Spec(
        bodies,
        "ground",
        joints,
        {"first": {"J0": [first]}, "second": {"J0": [second], "start": "first"}},
        inputs=["J0"],
        output="l2",
    )
    mech, model, closer, _ = solve_file(spec)
    L = char_length(joints)
    status = "regular"  # of the path so far: regular, blocked or unclear
    for cname, t0, t1 in (("first", 0.0, first), ("second", first, second)):
        path = [fourbar_closed_form(A2, B2, C2, D2, sA * t) for t in np.linspace(t0, t1, 300)]
        sols = [x for x, _ in path]
        miss = max(m for _, m in path)
        if status == "regular" and not (None not in sols and min(x[2] for x in sols) > 0.05):
            status = "blocked" if miss > 1e-3 * L else "unclear"
        if status == "regular":
            closed = closer.solve(cname)
            assert not closed.underdetermined
            (psi, phi, _), _ = fourbar_closed_form(A2, B2, C2, D2, sA * t1)
            angle = {"ground": 0.0, "l1": sA * t1, "l2": psi, "l3": phi}
            vals = mech_values(model, closed.q)
            assert vals["J0"][0] == t1
            for j, s in zip(joints, signs, strict=True):
                # planar rotations about parallel axes: absolute angles add
                expected = s * (angle[j.b] - angle[j.a])
                assert abs(wrap(vals[j.name][0] - expected)) < 1e-9, (
                    j.name,
                    vals[j.name],
                    expected,
                )
            assert_closes(joints, vals, L, exp_rodrigues)
        elif status == "blocked":
            # somewhere on the way the crank cannot turn further: no closure
            with pytest.raises(ClosureError) as exc:
                closer.solve(cname)
            assert exit_status(exc.value) == 3
        else:
            try:
                closed = closer.solve(cname)
            except ClosureError:
                continue
            assert_closes(joints, mech_values(model, closed.q), L, exp_rodrigues)


def test_fourbar_example_values():
    """examples/fourbar.yaml at crank 30 deg: B ~ -0.712, C ~ 0.0881, D ~ 0.1003."""
    mech = load(EXAMPLES[0].parent / "fourbar.yaml")
    model = KinematicModel(mech)
    vals = mech_values(model, Closer(model).solve("crank-30").q)
    A, B, C, D = (np.array(p, float) for p in ([0, 0], [1, 0], [3, 2], [4, 0]))
    (psi, phi, _), _ = fourbar_closed_form(A, B, C, D, PI / 6)
    assert vals["A"][0] == pytest.approx(PI / 6, abs=1e-15)
    assert vals["B"][0] == pytest.approx(psi - PI / 6, abs=1e-10)
    assert vals["C"][0] == pytest.approx(phi - psi, abs=1e-10)
    assert vals["D"][0] == pytest.approx(-phi, abs=1e-10)
    assert (round(vals["B"][0], 3), round(vals["C"][0], 4), round(vals["D"][0], 4)) == (
        -0.712,
        0.0881,
        0.1003,
    )


# ---------------------------------------------------------------------------
# 2b. general closed chains against an independent tracker


def check_against_tracker(spec: Spec, configs: list[tuple[str, str | None]], L: float):
    """Solve each configuration with mechsing and with my tracker (from its
    start), compare poses; regular paths must close, singular ones may fail."""
    mech, model, closer, written = solve_file(spec)
    zero = {j.name: np.zeros(len(KINDS[j.type])) for j in spec.joints}
    mine_prev: dict[str, dict] = {"reference": zero}
    ok_prev = {"reference": True}
    for cname, start in configs:
        start = start or "reference"
        target = written[cname]
        if not ok_prev[start]:
            ok_prev[cname] = False
            continue
        mine, worst = track(spec.joints, mine_prev[start], target, L)
        if mine is not None and worst > 2e-3:
            closed = closer.solve(cname)
            vals = mech_values(model, closed.q)
            assert not closed.underdetermined
            for jn, v in target.items():
                np.testing.assert_allclose(vals[jn], v, rtol=1e-15, atol=1e-300)
            assert_closes(spec.joints, vals, L, exp_rodrigues)
            # the same assembly mode as my path: the same body poses
            theirs = my_poses(spec.joints, spec.ground, vals, exp_rodrigues)
            ref = my_poses(spec.joints, spec.ground, mine, exp_rodrigues)
            for b in spec.bodies:
                np.testing.assert_allclose(theirs[b], ref[b], rtol=0, atol=1e-8 * L)
            mine_prev[cname] = mine
            ok_prev[cname] = True
        else:
            # near a singularity: either closed correctly, or a ClosureError
            try:
                closed = closer.solve(cname)
            except ClosureError:
                ok_prev[cname] = False
                continue
            assert_closes(spec.joints, mech_values(model, closed.q), L, exp_rodrigues)
            ok_prev[cname] = False


@LOOP_SETTINGS
@given(
    planar_frame(),
    st.integers(5, 6),
    st.data(),
)
def test_planar_5r_6r_loops_close_on_their_assembly_mode(frame, n, data):
    w, e1, e2, c0 = frame
    xy = data.draw(st.lists(plane_xy, min_size=n, max_size=n).filter(spread))
    flips = data.draw(st.lists(st.booleans(), min_size=n, max_size=n))
    pts = [c0 + p[0] * e1 + p[1] * e2 for p in xy]
    bodies, joints = loop_joints(pts, [w] * n, flips=flips)
    ins = sorted(data.draw(st.sets(st.integers(0, n - 1), min_size=n - 3, max_size=n - 3)))
    first = {f"J{k}": [data.draw(deltas)] for k in ins}
    second = {f"J{k}": [v[0] + data.draw(deltas)] for k, v in zip(ins, first.values(), strict=True)}
    spec = Spec(
        bodies,
        "ground",
        joints,
        {"first": first, "second": {**second, "start": "first"}},
        inputs=[f"J{k}" for k in ins],
        output="l2",
    )
    check_against_tracker(spec, [("first", None), ("second", "first")], char_length(joints))


@LOOP_SETTINGS
@given(
    st.lists(points, min_size=7, max_size=7),
    st.lists(axes(), min_size=7, max_size=7),
    st.lists(st.booleans(), min_size=7, max_size=7),
    deltas,
)
def test_spatial_7r_loop_closes_on_its_assembly_mode(pts, axs, flips, delta):
    bodies, joints = loop_joints(pts, axs, flips=flips)
    spec = Spec(bodies, "ground", joints, {"moved": {"J0": [delta]}}, inputs=["J0"], output="l3")
    check_against_tracker(spec, [("moved", None)], char_length(joints))


def test_spatial_7r_direct_continuation_keeps_the_assembly_mode():
    """Found by the property above: a regular path (smallest relative singular
    value of my closure Jacobian >= 7e-3 all the way) where the passive joints
    move about three times as fast as the input.  Reaching J0 = 0.25 in one
    configuration or through J0 = 0.125 must give the same pose, the one my
    tracker follows (12, 50 or 200 steps agree)."""
    pts = [
        [1, 0, 0],
        [0, 0, 2],
        [-2.8593773267436347, 0, 3],
        [0.75, 1, 0],
        [0, 0, 0],
        [4.25, -4.5, 0],
        [0, 0, 0],
    ]
    axs = [
        [-0.25, -1.9375, 0.75],
        [0, 1, 0],
        [0.109375, 0, 0.5625],
        [0, 3, 4],
        [0, 1, 0],
        [0, 0, 1],
        [1, 2, 3],
    ]
    bodies, joints = loop_joints(
        [np.array(p, float) for p in pts], [np.array(a, float) for a in axs]
    )
    L = char_length(joints)
    cfg = {
        "direct": {"J0": [0.25]},
        "half": {"J0": [0.125]},
        "chained": {"J0": [0.25], "start": "half"},
    }
    spec = Spec(bodies, "ground", joints, cfg, inputs=["J0"], output="l3")
    mech, model, closer, _ = solve_file(spec)
    zero = {j.name: np.zeros(1) for j in joints}
    mine, worst = track(joints, zero, {"J0": np.array([0.25])}, L, nsteps=50)
    assert mine is not None and worst > 5e-3
    for name in ("chained", "direct"):
        vals = mech_values(model, closer.solve(name).q)
        assert_closes(joints, vals, L, exp_rodrigues)
        for jn in vals:
            np.testing.assert_allclose(vals[jn], mine[jn], atol=1e-8, err_msg=f"{name}: {jn}")


def closure_jacobian_at_reference(joints: list[J], L: float) -> np.ndarray:
    """My closure Jacobian in every coordinate at the reference (finite
    differences of the cycle products)."""
    zero = {j.name: np.zeros(len(KINDS[j.type])) for j in joints}
    cols = []
    h = 1e-6
    for j in joints:
        for i in range(len(KINDS[j.type])):
            plus = dict(zero)
            minus = dict(zero)
            plus[j.name] = zero[j.name].copy()
            plus[j.name][i] = h
            minus[j.name] = zero[j.name].copy()
            minus[j.name][i] = -h
            fp = np.concatenate(
                [
                    np.concatenate([L * P[:3, :3].ravel(), P[:3, 3]])
                    for P in cycle_products(joints, plus, exp_rodrigues)
                ]
            )
            fm = np.concatenate(
                [
                    np.concatenate([L * P[:3, :3].ravel(), P[:3, 3]])
                    for P in cycle_products(joints, minus, exp_rodrigues)
                ]
            )
            cols.append((fp - fm) / (2 * h))
    return np.stack(cols, axis=1)


@settings(LOOP_SETTINGS, max_examples=5)  # each failure costs mechsing ~0.5 s
@given(
    st.lists(points, min_size=6, max_size=6),
    st.lists(axes(), min_size=6, max_size=6),
    deltas.filter(lambda d: abs(d) > 0.05),
)
def test_generic_spatial_6r_is_rigid(pts, axs, delta):
    """A generic 6R loop is a structure: its reference is isolated, so moving one
    joint cannot be closed."""
    bodies, joints = loop_joints(pts, axs)
    L = char_length(joints)
    s = np.linalg.svd(closure_jacobian_at_reference(joints, L), compute_uv=False)
    assume(s[5] / s[0] > 1e-3)  # a generic 6R (not a Bennett-like exception)
    spec = Spec(bodies, "ground", joints, {"moved": {"J0": [delta]}}, inputs=["J0"], output="l3")
    mech, model, closer, _ = solve_file(spec)
    with pytest.raises(ClosureError) as exc:
        closer.solve("moved")
    assert "moved" in str(exc.value)
    assert exit_status(exc.value) == 3


# Watt and Stephenson six-bars: links and the joints between them (ternary links T1, T2)
SIX_BARS = {
    "watt": [
        ("T1", "T2"),
        ("T1", "b1"),
        ("T1", "b2"),
        ("T2", "b3"),
        ("T2", "b4"),
        ("b1", "b3"),
        ("b2", "b4"),
    ],
    "stephenson": [
        ("T1", "b1"),
        ("T1", "b2"),
        ("T1", "b3"),
        ("b1", "T2"),
        ("b2", "b4"),
        ("b4", "T2"),
        ("b3", "T2"),
    ],
}


@LOOP_SETTINGS
@given(
    st.sampled_from(sorted(SIX_BARS)),
    planar_frame(),
    st.lists(plane_xy, min_size=7, max_size=7).filter(spread),
    st.sampled_from(["T1", "T2", "b1", "b2", "b3", "b4"]),
    st.data(),
)
def test_watt_and_stephenson_six_bars(kind, frame, xy, ground, data):
    w, e1, e2, c0 = frame
    links = SIX_BARS[kind]
    joints = []
    for k, (a, b) in enumerate(links):
        if data.draw(st.booleans()):
            a, b = b, a
        p = c0 + xy[k][0] * e1 + xy[k][1] * e2
        joints.append(J(f"J{k}", "R", a, b, {"axis": w, "point": p}))
    at_ground = [j.name for j in joints if ground in (j.a, j.b)]
    inp = data.draw(st.sampled_from(at_ground))
    d1, d2 = data.draw(deltas), data.draw(deltas)
    bodies = data.draw(st.permutations(["T1", "T2", "b1", "b2", "b3", "b4"]))
    spec = Spec(
        list(bodies),
        ground,
        joints,
        {"first": {inp: [d1]}, "second": {inp: [d1 + d2], "start": "first"}},
        inputs=[inp],
        output=next(b for b in bodies if b != ground),
    )
    assert len(cycles(joints)) == 2
    check_against_tracker(spec, [("first", None), ("second", "first")], char_length(joints))


@LOOP_SETTINGS
@given(
    st.lists(points, min_size=3, max_size=3),
    axes(),
    st.tuples(axes(), axes()),
    axes(),
    deltas,
)
# the S joint's rotation passes a half-turn on the way (its principal rotation vector
# jumps by 2 pi): continuation must measure its steps on the group, not in coordinates
@example(
    pts=[
        np.array([0.0, 4.101443082788057, 0.0]),
        np.array([0.0, 0.0, 2.0]),
        np.array([0.0, -1.37727729, -1.65426486]),
    ],
    r_axis=np.array([0.0, 0.0, 1.0]),
    u_axes=(np.array([0.0, 0.25, 0.875]), np.array([1.0, 2.0, 3.0])),
    p_axis=np.array([0.3, -0.4, 0.5]),
    delta=0.25,
)
# the R, U and S joints at one point: the S joint can turn without end while the loop stays
# closed; continuation ran its rotation vector to 1e119, where the Jacobian's series overflow
# (an SVD that did not converge escaped as a traceback): now that is no step
@example(
    pts=[np.array([-1.32792144e-182, 1.02275976e-136, 3.36721595])] * 3,
    r_axis=np.array([1.06073415, 1.32350293, -7.91831284e-287]),
    u_axes=(
        np.array([1.96625492, 1.95465712, -0.19535562]),
        np.array([-1.43403705, 1.0, -7.23649228e-236]),
    ),
    p_axis=np.array([1.73752718e-105, -5.96046448e-008, -4.57111262e-001]),
    delta=-0.1281259931364724,
)
# the reference configuration is 0.0015 rad of R1 short of a fold, where it meets a second
# assembly mode (U1 = 0.15 rad at R1 = 0): the tracker's first step of 0.0078 rad, Gauss-Newton
# from the reference without a predictor, converged on that other mode, and the test blamed
# mechsing, whose continuation stays on the reference's mode; now the tracker's steps must be
# reversible, and it halves its first step
@example(
    pts=[np.array([0.0, 0.0, 1.0]), np.array([4.25, 0.0, -2.5]), np.array([-1.0, -0.5, 4.0])],
    r_axis=np.array([0.0, 1.0, 0.0]),
    u_axes=(np.array([-2.0, -0.203125, 1.5]), np.array([-1.0, 0.0, 1.0])),
    p_axis=np.array([0.0, 0.0, 1.0]),
    delta=-0.09375,
)
def test_loop_with_u_and_p_joints(pts, r_axis, u_axes, p_axis, delta):
    """ground -R- l1 -U- l2 -P- l3 -S- ground: 7 dof, mobility 1."""
    a1, a2 = u_axes
    if np.linalg.norm(np.cross(unit(a1), unit(a2))) < 0.2:
        a2 = np.cross(a1, [1.0, 0, 0] if abs(unit(a1)[0]) < 0.7 else [0, 1.0, 0])
    joints = [
        J("R1", "R", "ground", "l1", {"axis": r_axis, "point": pts[0]}),
        J("U1", "U", "l1", "l2", {"axes": (a1, a2), "point": pts[1]}),
        J("P1", "P", "l2", "l3", {"axis": p_axis}),
        J("S1", "S", "l3", "ground", {"point": pts[2]}),
    ]
    spec = Spec(
        ["ground", "l1", "l2", "l3"],
        "ground",
        joints,
        {"moved": {"R1": [delta]}, "further": {"R1": [2 * delta], "start": "moved"}},
        inputs=["R1"],
        output="l3",
    )
    check_against_tracker(spec, [("moved", None), ("further", "moved")], char_length(joints))


def test_tracker_keeps_the_start_mode_beside_a_fold():
    """My tracker's steps from a point just short of a fold of the given joint (where a
    second assembly mode comes close) stay on the start's mode: a coarse path ends where a
    fine one does.  Gauss-Newton without a predictor, in steps five times the distance to
    the fold, converged on the other mode and made test_loop_with_u_and_p_joints blame
    mechsing; a step is now taken only when it is reversible."""
    joints = [
        J(
            "R1",
            "R",
            "ground",
            "l1",
            {"axis": np.array([0.0, 1, 0]), "point": np.array([0.0, 0, 1])},
        ),
        J(
            "U1",
            "U",
            "l1",
            "l2",
            {
                "axes": (np.array([-2.0, -0.203125, 1.5]), np.array([-1.5, 0.0, -2.0])),
                "point": np.array([4.25, 0.0, -2.5]),
            },
        ),
        J("P1", "P", "l2", "l3", {"axis": np.array([0.0, 0, 1])}),
        J("S1", "S", "l3", "ground", {"point": np.array([-1.0, -0.5, 4.0])}),
    ]
    L = char_length(joints)
    zero = {j.name: np.zeros(len(KINDS[j.type])) for j in joints}
    # the fold: R1 turns from the reference up to between 0.0016 and 0.002 rad, no further
    near, _ = track(joints, zero, {"R1": np.array([0.0016])}, L, nsteps=20)
    assert near is not None
    assert track(joints, zero, {"R1": np.array([0.002])}, L, nsteps=20)[0] is None
    target = {"R1": np.array([-0.09375])}
    fine, _ = track(joints, zero, target, L, nsteps=192)
    assert fine is not None
    assert_closes(joints, fine, L, exp_rodrigues)
    for nsteps in (1, 12):
        coarse, worst = track(joints, zero, target, L, nsteps=nsteps)
        # a path the property test calls regular, and it ends on the fine path's mode
        assert coarse is not None and worst > 2e-3
        for jn in fine:
            np.testing.assert_allclose(coarse[jn], fine[jn], rtol=0, atol=1e-9, err_msg=jn)


def test_tracker_keeps_its_mode_past_a_near_singular_point():
    """A planar 6R loop whose path, from ``first`` to ``second``, passes close to a singular
    point (smallest relative singular value 0.004), where two assembly modes come close:
    my tracker's 12 steps end where its 192 steps do (each step checked against two half
    steps), not on the other mode, which made test_planar_5r_6r_loops_close_on_their_assembly_mode
    blame mechsing (found by hypothesis)."""
    w = np.array([0.42426407, -0.56568542, 0.70710678])
    e1 = np.array([0.90553851, 0.26503566, -0.33129458])
    e2 = np.array([2.77555756e-17, 7.80868809e-01, 6.24695048e-01])
    xy = [
        (1.7838318746575865, 0.25612188532054336),
        (-1.097202974807479, 2.2796627684985147),
        (-0.7489851332061965, -0.3327716191373984),
        (1.753498138462131, -0.6051395507922148),
        (-2.368945802410985, -0.2288118786708413),
        (0.25, -2.25),
    ]
    _, joints = loop_joints([x * e1 + y * e2 for x, y in xy], [w] * 6)
    L = char_length(joints)
    zero = {j.name: np.zeros(1) for j in joints}
    first = {"J1": -0.056640625, "J2": 0.125, "J4": -0.14364424968351908}
    moved = {"J1": 0.24609375, "J2": 0.25, "J4": -0.1953125}
    second = {jn: np.array([v + moved[jn]]) for jn, v in first.items()}
    first = {jn: np.array([v]) for jn, v in first.items()}
    ends = {}
    for nsteps in (12, 192):
        mid, _ = track(joints, zero, first, L, nsteps=nsteps)
        assert mid is not None
        ends[nsteps], worst = track(joints, mid, second, L, nsteps=nsteps)
        assert ends[nsteps] is not None and worst > 2e-3
    assert_closes(joints, ends[192], L, exp_rodrigues)
    for jn in ends[192]:
        np.testing.assert_allclose(ends[12][jn], ends[192][jn], rtol=0, atol=1e-9, err_msg=jn)


def test_finer_steps_reach_the_same_solution():
    """Continuation in one configuration or in a chain of four gives the same pose."""
    pts = [
        np.array(p, float)
        for p in (
            [0, 0, 0],
            [1, 0, 0.5],
            [2, 1.5, 0],
            [1, 2.5, 1],
            [-0.5, 2, 0],
            [-1, 1, 0.5],
            [-0.5, 0.3, 1],
        )
    ]
    rng = np.random.default_rng(3)
    axs = [unit(rng.normal(size=3)) for _ in pts]
    bodies, joints = loop_joints(pts, axs)
    cfg = {"direct": {"J0": [0.28]}}
    prev = None
    for k in range(1, 5):
        name = f"step{k}"
        cfg[name] = {"J0": [0.07 * k]} | ({"start": prev} if prev else {})
        prev = name
    spec = Spec(bodies, "ground", joints, cfg, inputs=["J0"], output="l3")
    mech, model, closer, _ = solve_file(spec)
    L = char_length(joints)
    direct = mech_values(model, closer.solve("direct").q)
    chained = mech_values(model, closer.solve("step4").q)
    assert_closes(joints, direct, L, exp_rodrigues)
    assert_closes(joints, chained, L, exp_rodrigues)
    for jn in direct:
        np.testing.assert_allclose(direct[jn], chained[jn], atol=1e-9)
    mine, worst = track(joints, {j.name: np.zeros(1) for j in joints}, {"J0": np.array([0.28])}, L)
    assert mine is not None and worst > 1e-2
    for jn in direct:
        np.testing.assert_allclose(direct[jn], mine[jn], atol=1e-8)


# ---------------------------------------------------------------------------
# 2c. fully given non-closing configurations, underdetermined configurations

FOURBAR_NOT_CLOSING = (
    "mechanism: four-bar\n"
    + FOURBAR_JOINTS
    + """\
inputs: [A]
output: {body: rocker}
configurations:
  reference: {}
  crank-30: {A: 0.5235987755982988}
  wrong: {A: 0.5, B: -0.7, C: 0.1, D: 0.1}
"""
)


def test_fully_given_configuration_that_does_not_close_is_an_error():
    mech = loads(FOURBAR_NOT_CLOSING)
    joints = [
        J(
            j.name,
            "R",
            *j.between,
            {
                "axis": np.array(j.params["axis"], float),
                "point": np.array(j.params["point"], float),
            },
        )
        for j in mech.joints
    ]
    vals = {"A": [0.5], "B": [-0.7], "C": [0.1], "D": [0.1]}
    # independently: the loop is open by much more than the tolerance
    (P,) = cycle_products(joints, vals)
    assert closure_error(P, 1.0) > 1e-3
    model = KinematicModel(mech)
    with pytest.raises(ClosureError) as exc:
        Closer(model).solve("wrong")
    assert exit_status(exc.value) == 3
    assert "wrong" in str(exc.value)
    assert exc.value.residual is not None and exc.value.residual > 1e-4
    # the other configuration still closes
    assert_closes(joints, mech_values(model, Closer(model).solve("crank-30").q), 1.0)


def test_analyze_exits_3_on_a_configuration_that_does_not_close(tmp_path, capsys):
    from mechsing.cli import main

    f = tmp_path / "open.yaml"
    f.write_text(FOURBAR_NOT_CLOSING)
    status = main(["analyze", str(f), "--format", "json", "--precision", "float"])
    out, err = capsys.readouterr()
    assert status == 3
    assert "wrong" in err and "Traceback" not in err
    import json

    doc = json.loads(out)
    by = {c["name"]: c for c in doc["configurations"]}
    assert by["wrong"].get("error")
    assert not by["crank-30"].get("error")


@LOOP_SETTINGS
@given(
    planar_frame(),
    st.lists(plane_xy, min_size=5, max_size=5).filter(spread_off_a_line),
    st.integers(0, 4),
    deltas,
)
def test_five_bar_with_one_input_is_underdetermined(frame, xy, k, delta):
    """A planar 5R (2 dof) with one input: minimum-norm continuation, and the
    result says ``underdetermined``.  With joint k held, its two bodies are one
    and the rest is a four-bar whose fourth side d changes with the input: it
    can be followed exactly when no side exceeds the sum of the others on the
    way, and it never passes a flat (singular) shape when d stays away from
    every |s1 +- s2 +- s3|."""
    w, e1, e2, c0 = frame
    pts = [c0 + p[0] * e1 + p[1] * e2 for p in xy]
    bodies, joints = loop_joints(pts, [w] * 5)
    spec = Spec(
        bodies, "ground", joints, {"one": {f"J{k}": [delta]}}, inputs=[f"J{k}"], output="l2"
    )
    mech, model, closer, _ = solve_file(spec)
    L = char_length(joints)
    # independently: 2 dof at the reference (rank 3 of 5 in the plane)
    s = np.linalg.svd(closure_jacobian_at_reference(joints, L), compute_uv=False)
    assert s[2] / s[0] > 1e-6 and s[3] / s[0] < 1e-8
    P = [np.array(p) for p in xy]
    prev, here, nxt = P[(k - 1) % 5], P[k], P[(k + 1) % 5]
    sides = [np.linalg.norm(P[(k + 1 + i) % 5] - P[(k + 2 + i) % 5]) for i in range(3)]
    flat = [abs(sides[0] + a * sides[1] + b * sides[2]) for a in (1, -1) for b in (1, -1)]
    # joint k turns body k+1 about P_k relative to body k, which holds P_{k-1}
    d = np.array(
        [np.linalg.norm(prev - here - rot2(t) @ (nxt - here)) for t in np.linspace(0, delta, 300)]
    )
    stuck = np.max(np.maximum(d - sum(sides), [2 * max(sides) - sum(sides) - x for x in d]))
    margin = min(float(np.min(np.abs(d - f))) for f in flat)
    if margin > 1e-2 * L:
        closed = closer.solve("one")
        assert closed.underdetermined
        vals = mech_values(model, closed.q)
        assert vals[f"J{k}"][0] == delta
        assert_closes(joints, vals, L, exp_rodrigues)
    elif stuck > 1e-3 * L:
        # the four-bar cannot be assembled somewhere on the way
        with pytest.raises(ClosureError):
            closer.solve("one")
    else:
        try:
            closed = closer.solve("one")
        except ClosureError:
            return
        assert closed.underdetermined
        assert_closes(joints, mech_values(model, closed.q), L, exp_rodrigues)


# ---------------------------------------------------------------------------
# 3. every example: every named configuration closes


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_every_example_configuration_closes(path):
    mech = load(path)
    joints = joints_of(mech)
    model = KinematicModel(mech)
    closer = Closer(model)
    L = max([1.0] + [float(np.linalg.norm(j.prm["point"])) for j in joints if "point" in j.prm])
    assert len(cycles(joints)) == len(mech.loops)
    for name, cfg in mech.configurations.items():
        closed = closer.solve(name)
        vals = mech_values(model, closed.q)
        for jn, v in cfg.values.items():
            if isinstance(v, tuple):
                np.testing.assert_allclose(vals[jn], [float(x) for x in v], rtol=1e-15, atol=1e-300)
        assert_closes(joints, vals, L)
        theirs = model.poses(closed.q)
        mine = my_poses(joints, mech.ground, vals)
        for b in mech.bodies:
            np.testing.assert_allclose(theirs[b], mine[b], rtol=0, atol=1e-10 * L)


def test_pose_cache_keeps_the_poses_of_the_last_configurations_and_stays_bounded():
    """A float model keeps the poses of the configurations it was last asked for (a sweep's
    located points are closed, then classified): the poses asked again, after more
    configurations than it keeps, are those a fresh model computes, and it keeps at most
    its bound of body poses."""
    mech = load(Path(__file__).resolve().parents[1] / "examples" / "five_bar.yaml")
    model = KinematicModel(mech, "float")
    rng = np.random.default_rng(3)
    qs = rng.uniform(-math.pi, math.pi, size=(model._pose_cache_size + 50, model.n))
    first = [model.poses(q) for q in qs]
    assert len(model._pose_cache) == model._pose_cache_size
    assert model._pose_cache_size * len(mech.bodies) <= 4096
    fresh = KinematicModel(mech, "float")
    for q, got in zip([qs[0], qs[-1], qs[0]], [first[0], first[-1], first[0]], strict=True):
        again = model.poses(q)
        want = fresh.poses(q.copy())
        for body in mech.bodies:
            np.testing.assert_array_equal(again[body], want[body])
            np.testing.assert_array_equal(got[body], want[body])


def test_spherical_joints_updated_together_step_on_the_group():
    """A float model updates its non-abelian joints (the hexapod's six S joints) all at once:
    each joint's new element is exp(d B) times its old one (scipy's expm, independent of
    mechsing), difference undoes update, and the numbers are those of the joint-by-joint
    formula (exp, then coordinates_in of each joint)."""
    mech = load(Path(__file__).resolve().parents[1] / "examples" / "stewart_octahedral.yaml")
    model = KinematicModel(mech, "float")
    spherical = [jk for jk in model.joints if not jk.abelian]
    assert [jk.type for jk in spherical] == ["S"] * 6
    rng = np.random.default_rng(5)
    for scale in (1e-6, 1e-3, 0.2):
        q = rng.normal(size=model.n) * 0.5
        d = rng.normal(size=model.n) * scale
        d[spherical[2].columns] = 0.0  # a joint that does not move
        q1 = model.update(q, d)
        for jk in spherical:
            want = expt(d[jk.columns] @ jk.basis) @ expt(q[jk.columns] @ jk.basis)
            np.testing.assert_allclose(model.element(jk, q1), want, rtol=0, atol=1e-13)
            M = lie.exp(d[jk.columns] @ jk.basis) @ model.element(jk, q)
            if np.any(d[jk.columns]):
                np.testing.assert_array_equal(q1[jk.columns], model.coordinates_in(jk, M))
        np.testing.assert_allclose(model.difference(q1, q), d, rtol=0, atol=1e-13)


@pytest.mark.parametrize("name", ["five_bar.yaml", "tsai_3upu.yaml", "planar_3rpr.yaml"])
def test_configurations_closed_together_are_those_closed_one_by_one(name):
    """Closer.solve_many checks every configuration that gives all joint values in one
    batch: each closed configuration, residual and pose is bitwise that of solve alone;
    one that does not close is left to solve, which refuses it with the same error."""
    from dataclasses import replace

    from mechsing.model import Configuration

    mech = load(Path(__file__).resolve().parents[1] / "examples" / name)
    solo = Closer(KinematicModel(mech, "float"))
    qs = {n: solo.solve(n).q for n in mech.configurations}
    cfgs = dict(mech.configurations)
    for n, q in qs.items():
        values: dict[str, list[float]] = {}
        for (j, _i), x in zip(mech.coordinates(), q, strict=True):
            values.setdefault(j, []).append(float(x))
        cfgs["given-" + n] = Configuration("given-" + n, {j: tuple(v) for j, v in values.items()})
    # the last one moved off closure by a millimetre-sized error in its first joint
    j0, v0 = next(iter(cfgs["given-" + n].values.items()))
    bad = dict(cfgs["given-" + n].values)
    bad[j0] = (v0[0] + 1e-3, *v0[1:])
    cfgs["open"] = Configuration("open", bad)
    mech2 = replace(mech, configurations=cfgs)
    names = [*("given-" + n for n in qs), "open"]
    one, many = Closer(KinematicModel(mech2, "float")), Closer(KinematicModel(mech2, "float"))
    many.solve_many(names)
    for n in names[:-1]:
        a, b = one.solve(n), many.solve(n)
        assert np.array_equal(a.q, b.q) and a.residual == b.residual and a.given == b.given
        pa, pb = one.model.poses(a.q), many.model.poses(b.q)
        assert pa.keys() == pb.keys() and all(np.array_equal(pa[k], pb[k]) for k in pa)
    with pytest.raises(ClosureError) as e1:
        one.solve("open")
    with pytest.raises(ClosureError) as e2:
        many.solve("open")
    assert str(e1.value) == str(e2.value)
