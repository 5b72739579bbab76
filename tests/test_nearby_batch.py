"""The nearby samples of many configurations closed by one batched Newton
(:func:`mechsing.screws.mobility.nearby_samples_many`), and the analysis of a sweep's
located points that uses them (:func:`mechsing.analysis.analyze_found`).

Checked against answers not computed by mechsing: the five-bar's loop closure from its
planar geometry (the example file's dimensions), its regular nullity from the planar
count (5 joints, 3 constraints), the Type I class of its published ``type1`` pose; and
against the one-Newton-per-sample path the analysis of a single configuration takes.
The tests' values at many samples (:func:`mechsing.singularity.generic.sample_values`) are
checked against the planar counts of the five-bar and of a leg that holds a parallelogram,
and against the functions that decide the tests at one configuration.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import mechsing
from mechsing.analysis import analyze_found
from mechsing.kinematics import Closer, KinematicModel
from mechsing.model import Configuration
from mechsing.model.loader import loads
from mechsing.numeric import to_float
from mechsing.screws import closure_system
from mechsing.screws.mobility import SAMPLE_STEPS, nearby_samples, nearby_samples_many
from mechsing.singularity.generic import one_sample_values, sample_values

EX = Path(__file__).resolve().parents[1] / "examples"


def _rot(a: float, v: tuple[float, float]) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _five_bar_gap(q: np.ndarray) -> float:
    """The loop's closure error from the file's geometry alone: the output point P and
    the distal links' angle through leg 1 (A1, B1) and through leg 2 (A2, B2, P)."""
    a1, b1, p, b2, a2 = q
    # leg 1: A1 at (-3/2, 0), B1 2 above it, P at (3/2, 2) from B1 (reference frames)
    P1 = np.array([-1.5, 0.0]) + _rot(a1, (0.0, 2.0)) + _rot(a1 + b1, (1.5, 2.0))
    # leg 2: A2 at (3/2, 0), B2 2 above it, P at (-3/2, 2) from B2; dist2 = dist1 turned by P
    P2 = np.array([1.5, 0.0]) + _rot(a2, (0.0, 2.0)) + _rot(a2 + b2, (-1.5, 2.0))
    turn = (a1 + b1 + p) - (a2 + b2)
    return float(np.linalg.norm(P1 - P2)) + abs(math.remainder(turn, 2 * math.pi))


def _kernels(mech, names):
    model = KinematicModel(mech, "float")
    closer = Closer(model)
    qs, Ks = [], []
    for n in names:
        q = np.asarray(to_float(closer.solve(n).q), dtype=float)
        qs.append(q)
        Ks.append(to_float(closure_system(model, q).rank.null_space))
    return model, qs, Ks


def test_five_bar_samples_close_the_loop_at_their_distances_with_the_planar_nullity():
    mech = mechsing.load(EX / "five_bar.yaml")
    model, qs, Ks = _kernels(mech, ["type1", "inputs", "reference"])
    got = nearby_samples_many(model, qs, Ks)
    assert [len(s) for s in got] == [6, 6, 6]
    steps = sorted(SAMPLE_STEPS * 3)
    for q, samples in zip(qs, got, strict=True):
        for s in samples:
            # closed: the planar geometry's gap, not mechsing's residual
            assert _five_bar_gap(s.q) < 1e-12
            # a planar 5R loop: 5 joints, 3 independent constraints
            assert s.nullity == 2
            # each sample as far as its step (the kernel direction, then the closure's
            # second-order correction)
            assert s.distance == pytest.approx(np.linalg.norm(s.q - q), rel=1e-12)
        d = sorted(s.distance for s in samples)
        assert all(0.9 * h < x < 1.1 * h for x, h in zip(d, steps, strict=True))


@pytest.mark.parametrize(
    ("file", "names", "agree"),
    [
        ("five_bar.yaml", ["type1", "type2", "inputs"], 1e-6),
        ("stewart_octahedral.yaml", None, 1e-6),  # spherical joints: rotation vectors updated
        ("tsai_3upu.yaml", None, 1e-6),
        # overconstrained: its 6 x 4 closure Jacobian has rank 3 on its motion and rank 4
        # off it, the fourth singular value of the order of the distance, so where along
        # the motion a minimum-norm Newton lands amplifies the rounding of its steps
        ("bennett.yaml", None, 1e-2),
    ],
)
def test_batched_samples_are_the_one_at_a_time_samples(file, names, agree):
    """The same starting points closed together land where one Newton each lands."""
    mech = mechsing.load(EX / file)
    names = names or list(mech.configurations)
    model, qs, Ks = _kernels(mech, names)
    many = nearby_samples_many(model, qs, Ks)
    assert sum(len(s) for s in many) > 0
    for q, K, got in zip(qs, Ks, many, strict=True):
        one = nearby_samples(model, q, K)
        assert len(got) == len(one)
        for a, b in zip(got, one, strict=True):
            assert a.nullity == b.nullity
            assert model.residual_norm(model.chord_residuals(a.q)) <= 1e-12 * model.length_scale
            assert np.max(np.abs(model.difference(a.q, b.q))) < agree * b.distance
            assert abs(a.distance - b.distance) < agree * b.distance


def test_located_points_analysed_together_as_each_alone():
    """analyze_found closes the samples of all its points at once; each result is the
    analysis of that point alone (and the published class at the Type I pose)."""
    mech = mechsing.load(EX / "five_bar.yaml")
    model = KinematicModel(mech, "float")
    closer = Closer(model)
    found = {
        n: np.asarray(to_float(closer.solve(n).q), dtype=float)
        for n in ("type1", "inputs", "reference")
    }
    together = analyze_found(mech, found, "float")
    # the same float values as configurations of the file, analysed one at a time (their
    # samples closed one Newton each)
    configs = dict(mech.configurations)
    for n, q in found.items():
        values = {
            j: tuple(float(x) for x in q[model.joint(j).columns]) for j, _ in mech.coordinates()
        }
        configs[n] = Configuration(n, values, start="reference")
    plain = replace(mech, configurations=configs)
    alone = [mechsing.analyze(plain, [n], "float").configurations[0] for n in found]
    for a, b in zip(together, alone, strict=True):
        ja, jb = a.to_json(), b.to_json()
        ja.pop("seconds", None), jb.pop("seconds", None)
        assert ja == jb
    classes = [{s["class"] for s in r.to_json()["singularities"]} for r in together]
    # Type I: leg 1 stretched (file comment: Gosselin and Angeles); the others regular
    assert "input" in classes[0]
    assert classes[1] == classes[2] == set()


#: a planar linkage whose first leg holds a loop of its own (a parallelogram A B C D
#: carries the body m, which holds the output through E), the second leg F G
INNER_LOOP_LEG = """mechanism: parallelogram-leg
bodies: [ground, l1, l2, m, out, r1]
joints:
  - {name: A, type: R, between: [ground, l1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [l1, m],      axis: [0, 0, 1], point: [0, 1, 0]}
  - {name: C, type: R, between: [m, l2],      axis: [0, 0, 1], point: [1, 1, 0]}
  - {name: D, type: R, between: [l2, ground], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: E, type: R, between: [m, out],     axis: [0, 0, 1], point: ["1/2", 2, 0]}
  - {name: F, type: R, between: [out, r1],    axis: [0, 0, 1], point: [3, 2, 0]}
  - {name: G, type: R, between: [r1, ground], axis: [0, 0, 1], point: [3, 0, 0]}
inputs: [A]
output: {body: out, point: [2, 2, 0]}
configurations:
  reference: {}
"""


def _samples_of(mech, names):
    model, qs, Ks = _kernels(mech, names)
    return model, [s for ss in nearby_samples_many(model, qs, Ks) for s in ss]


@pytest.mark.parametrize(
    "file", ["five_bar.yaml", "stewart_octahedral.yaml", "tsai_3upu.yaml", "planar_3rpr.yaml"]
)
def test_the_tests_values_at_many_samples_are_those_of_one_sample_at_a_time(file):
    """sample_values (every sample's poses, screws and decisions in stacked arrays) gives the
    values one_sample_values takes from io_quantities, ConstraintTest.decide and SerialTest.decide,
    the functions that decide the tests at the configuration itself."""
    mech = mechsing.load(EX / file)
    model, samples = _samples_of(mech, list(mech.configurations))
    assert len(samples) >= 6
    many = sample_values(mech, model, samples)
    for s, got in zip(samples, many, strict=True):
        one = one_sample_values(mech, model, s)
        assert got.io == one.io
        assert got.constraint == one.constraint
        assert [r for _, r in got.legs] == [r for _, r in one.legs]
        for (a, _), (b, _) in zip(got.legs, one.legs, strict=True):
            np.testing.assert_array_equal(a, b)


def test_five_bar_sample_values_are_the_planar_counts():
    """At regular configurations of the five-bar (file comment: two legs, inputs A1 and A2,
    output point P on dist1): no input, output or passive motion; the inputs and the point's
    velocity both span the 2-dof motion; each leg is judged by the output point's velocities
    (the output chain's rule): those of leg 1 (A1, B1) and of leg 2 (A2, B2, and P, which
    turns about the point) both span the plane, 2; the legs' constraint wrenches: the 3
    out-of-plane ones, which both legs resist, and leg 1's planar force along its distal
    link."""
    mech = mechsing.load(EX / "five_bar.yaml")
    model, samples = _samples_of(mech, ["reference", "inputs"])
    for v in sample_values(mech, model, samples):
        assert v.io == {
            "input": 0,
            "output": 0,
            "passive-motion": 0,
            "impossible-input": 2,
            "impossible-output": 2,
        }
        assert [r for _, r in v.legs] == [2, 2]
        assert v.constraint == 4


def test_a_leg_with_a_loop_of_its_own_takes_its_constraint_rank_from_the_closure_system():
    """A leg that holds a parallelogram: its twists are taken over that loop's solutions (one
    sample at a time), the rest batched.  The values are the one-at-a-time ones and the
    planar counts: one dof (7 joints, 2 planar loops of 3 constraints), driven by the input
    A and moving the point; leg 1's output twists are m's translation and the turn about E,
    leg 2's the turns about F and G, so each resists the 3 out-of-plane wrenches and one
    planar force of its own (5 together); each leg's velocities of the output point (the
    output chain's rule) span the plane: 2 for leg 1 (its turn about E and the
    parallelogram's translation) and 2 for leg 2 (the turns about F and G)."""
    mech = loads(INNER_LOOP_LEG)
    model, samples = _samples_of(mech, ["reference"])
    assert len(samples) == 6
    for s, v in zip(samples, sample_values(mech, model, samples), strict=True):
        assert v.io == {
            "input": 0,
            "output": 0,
            "passive-motion": 0,
            "impossible-input": 1,
            "impossible-output": 1,
        }
        assert v.constraint == 5
        assert [r for _, r in v.legs] == [2, 2]
        one = one_sample_values(mech, model, s)
        assert (one.io, one.constraint) == (v.io, v.constraint)


def test_the_starting_draws_are_those_of_a_fresh_generator():
    """The kernel coefficients drawn once per kernel dimension are the ones a generator
    seeded afresh at each configuration draws, in the same order."""
    from mechsing.screws.mobility import SAMPLES_PER_STEP, _draws

    for d in (1, 2, 5):
        rng = np.random.default_rng(0)
        expected = [rng.normal(size=d) for _ in range(len(SAMPLE_STEPS) * SAMPLES_PER_STEP)]
        got = _draws(0, d)
        assert len(got) == len(expected)
        assert all(np.array_equal(a, b) for a, b in zip(got, expected, strict=True))
        assert got is _draws(0, d)
