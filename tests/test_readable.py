"""The readable choices of screws (mechsing.screws.readable) keep what is intrinsic.

Laws, on random spans of screws built from random axes, points and pitches by hand:
* ``echelon`` and ``readable_basis`` span the same space as their input (same rank, and
  each input row is a combination of theirs);
* ``simplest(v, rows)`` differs from ``v`` by an element of the span, and its first half
  is the least over the class (orthogonal to the span's first halves);
* pure translations of the span come out as rows with a zero first half.
And two answers derived by hand: the planar chain in line, the rotation with a
translation along its axis.
"""

from __future__ import annotations

import numpy as np
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from mechsing.screws.readable import echelon, readable_basis, simplest


def _screw(axis, point, pitch):
    w = np.asarray(axis, float)
    w = w / np.linalg.norm(w)
    return np.concatenate([w, np.cross(point, w) + pitch * w])


def _translation(direction):
    d = np.asarray(direction, float)
    return np.concatenate([np.zeros(3), d / np.linalg.norm(d)])


coords = st.floats(-3, 3, allow_nan=False)
vectors = st.tuples(coords, coords, coords).filter(lambda v: np.linalg.norm(v) > 0.1)
screws = st.one_of(
    st.builds(_screw, vectors, st.tuples(coords, coords, coords), st.floats(-1, 1)),
    st.builds(_translation, vectors),
)


def _well_posed(rows):
    """An orthonormal basis of the span's directions that are clearly in it (singular
    values above 1e-3 of the largest): a span whose rank no tolerance can dispute."""
    _, s, Vt = np.linalg.svd(np.asarray(rows))
    return Vt[: int(np.sum(s > 1e-3 * s[0]))]


spans = st.lists(screws, min_size=1, max_size=5).map(_well_posed)
scales = st.sampled_from([1e-3, 1.0, 1e3])


def _in_span(x, rows):
    """x is a combination of rows (least squares residual at rounding level)."""
    R = np.asarray(rows).T
    a = np.linalg.lstsq(R, x, rcond=None)[0]
    return np.linalg.norm(R @ a - x) <= 1e-8 * max(np.linalg.norm(x), np.linalg.norm(R))


def _rank(rows):
    return np.linalg.matrix_rank(np.asarray(rows), tol=1e-8)


@settings(max_examples=150, deadline=None)
@given(spans, scales)
@example(
    # a span with almost no rotation about x: the echelon form pivots on it (6.9e-6, above
    # ECHELON_PIVOT_RTOL), scaling its row by 1.4e5, and the readable form then drops the
    # y entries of 1e-10 of the data (SUPPORT_RTOL of the row): 1e-10 of the span in the
    # commensurate metric, 1e-7 in SI at L = 1e-3
    np.array(
        [
            [
                6.89578692e-06,
                3.71865917e-11,
                2.08416201e-01,
                -9.63636640e-01,
                -9.65636479e-03,
                -1.66954686e-01,
            ],
            [
                -3.74071749e-06,
                1.90630590e-10,
                -6.82688241e-01,
                -2.60289655e-01,
                -1.74144125e-01,
                6.60196853e-01,
            ],
        ]
    ),
    1e-3,
)
@example(
    # two rotations with moments of 1e-5 (their axes through points 1e-5 off the origin)
    # whose span's x and y entries are nearly equal: the echelon form pivots on y's 1.4e-5
    # and scales its rows by 7e4, the unit rows are then nearly parallel, and their
    # moments (1e-10 of the row, 1e-5 of the pivot's unit) must stay to span the input
    _well_posed(
        [
            _screw((0.0, 1e-5, 1.0), (0.0, 0.0, 0.0), 0.0),
            _screw((1.0, 1.0, 0.0), (0.0, 0.0, 1e-5), 0.0),
        ]
    ),
    1e-3,
)
@example(
    # a rotation about a z axis leaning 5.3e-6 towards y, the translation along that
    # axis: the echelon form pivots on the 5.3e-6 and scales by 1.9e5, and the translation's
    # row keeps a first half of 4.9e-7 (rounding beside its 1.9e5); the rotation's second
    # half made least modulo it must take that first half off with it
    _well_posed(
        [
            _screw((0.0, 5.346710167176784e-06, 1.0), (0.0, 1.0, 0.0), 0.0),
            np.array([1.0, 0.0, 0.0, 0.0, 1.0, 0.0]),
            _translation((0.0, 5.346710167176784e-06, 1.0)),
        ]
    ),
    1.0,
)
def test_echelon_and_readable_basis_span_the_same_space(rows, L):
    """The same span, judged in the commensurate metric the forms decide in (second halves
    over L): in SI a small mechanism's second halves are L times smaller, and a first-half
    entry of rounding level next to them would weigh 1/L times more than it does."""
    size = np.array([1, 1, 1, L, L, L])
    rows = rows * size  # a mechanism of another size
    for basis in (echelon(rows, L)[0], readable_basis(rows, L)):
        assert len(basis) == len(rows)
        for r in rows:
            assert _in_span(r / size, basis / size)
        for b in basis:
            assert _in_span(b / size, rows / size)


@settings(max_examples=150, deadline=None)
@given(spans, screws)
@example(
    # a rotation about y (twice) and a screw of pitch 1 whose axis leans 1.6e-9 off it:
    # the first halves' second singular value, about 1e-9, is kept, and the combination
    # of rows it takes amplifies rounding by about 1e9; the first half is the orthogonal
    # projection, taken as such
    _well_posed(
        [
            np.array([0.0, 1.0, 0.0, 0.0, 0.0, 0.0]),
            np.array([0.0, 1.0, 0.0, 0.0, 0.0, 0.0]),
            _screw((0.0, 1.0, 1.616356439661559e-09), (0.0, 0.0, 0.0), 1.0),
        ]
    ),
    _screw((0.0, 0.0, 1.0), (0.0, 0.0, 0.0), 0.0),
)
def test_simplest_stays_in_the_class_with_the_least_first_half(rows, v):
    s = simplest(v, rows)
    assert _in_span(s - v, rows) or np.linalg.norm(s - v) < 1e-9
    # least first half: no element of the span lowers it to first order
    first = rows[:, :3]
    if np.linalg.norm(first) > 1e-9:
        assert np.linalg.norm(first @ s[:3]) <= 1e-8 * max(1.0, np.linalg.norm(first))


@settings(max_examples=100, deadline=None)
@given(st.lists(vectors, min_size=1, max_size=3), st.lists(screws, max_size=2))
def test_the_translations_of_a_span_come_out_pure(directions, others):
    rows = np.array([_translation(d) for d in directions] + list(others)).reshape(-1, 6)
    # ranks no tolerance can dispute: every singular value clearly zero or clearly not
    for m in (rows, rows[:, :3]):
        s = np.linalg.svd(m, compute_uv=False)
        assume(np.all((s > 1e-3 * s[0]) | (s < 1e-12 * s[0])))
    basis = readable_basis(rows, 1.0)
    # the translations of the span (the combinations with a zero first half) have a
    # dimension of rank(rows) - rank(first halves); as many rows come out pure
    pure = [b for b in basis if np.linalg.norm(b[:3]) < 1e-12]
    assert len(pure) == _rank(rows) - _rank(rows[:, :3])


def test_a_planar_chain_in_line():
    # rotations about z through (1, 5, 0) and (4, 5, 0) (a chain in line along y = 5):
    # they span the rotation about z through (0, 5, 0) and the translation along y; modulo
    # that span, the translation along (1, 1, 0) is the translation along x, and the
    # rotation about z through the origin is the translation along x times -5.
    rows = np.array([_screw([0, 0, 1], [1, 5, 0], 0), _screw([0, 0, 1], [4, 5, 0], 0)])
    assert np.allclose(simplest(_translation([1, 1, 0]), rows), [0, 0, 0, 2**-0.5, 0, 0])
    assert np.allclose(simplest(_screw([0, 0, 1], [0, 0, 0], 0), rows), [0, 0, 0, -5, 0, 0])
    basis = readable_basis(rows, 1.0)
    assert np.allclose(basis, [_screw([0, 0, 1], [0, 5, 0], 0), [0, 0, 0, 0, 1, 0]])


def test_a_screw_motion_keeps_its_pitch_modulo_nothing_and_loses_it_modulo_its_axis():
    t = _screw([0, 0, 1], [1, 0, 0], 0.2)  # a screw of pitch 0.2 about the axis x = 1
    assert np.allclose(simplest(t, np.zeros((0, 6))), t)
    # modulo the translation along its axis, it is the pure rotation about the same axis
    assert np.allclose(simplest(t, [_translation([0, 0, 1])]), _screw([0, 0, 1], [1, 0, 0], 0))


def test_rotations_tilted_by_rounding_out_of_a_plane_keep_their_span_and_size():
    # rotations whose axes leave the (y, z) plane by 3e-8 rad, and two translations (the
    # case hypothesis found): a pivot on the tiny x column would scale its row by 3e7
    # and the readable basis would lose the span to the digits dropped; the plane's own
    # columns are the pivots instead, and no entry grows
    rows = np.array(
        [
            _screw([3e-8, 1, 0.1], [0.3, -1, 2], 0),
            _screw([-5e-8, 0.2, 1], [1, 0.5, -0.4], 0.1),
            _translation([1, 2, 0]),
            _translation([0, 1, 3]),
        ]
    )
    for basis in (echelon(rows, 1.0)[0], readable_basis(rows, 1.0)):
        assert len(basis) == 4
        assert all(_in_span(r, basis) for r in rows)
        assert all(_in_span(b, rows) for b in basis)
        assert np.max(np.abs(basis)) < 1e2
    E, pivots = echelon(rows, 1.0)
    assert pivots[:2] == [1, 2]


def test_a_non_finite_entry_propagates_through_the_echelon_form():
    """A NaN is the largest entry and the first pivot (numpy's rules): dividing by it and
    eliminating with it leaves every row NaN; the pivots still advance one per row."""
    rows = np.array([[np.nan, 0, 0, 0, 0, 0], [1.0, 2.0, 0, 0, 0, 0]])
    E, pivots = echelon(rows, 1.0)
    assert pivots == [0, 1]
    assert E.shape == (2, 6) and np.isnan(E).all()
