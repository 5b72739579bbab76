"""Hypothesis strategies concentrated where the Lie formulas change branch."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

PI = math.pi

#: rotation angles clustered at 0 and pi (and a few fixed points), then anywhere
angles = st.one_of(
    st.floats(0.0, 1e-12),
    st.floats(0.0, 1e-6),
    st.floats(PI - 1e-12, PI),
    st.floats(PI - 1e-6, PI),
    st.sampled_from([0.0, 1e-16, 1e-8, 1e-4, 0.5, 1.0, PI / 2, PI - 1e-4, PI]),
    st.floats(0.0, PI),
)

#: unit axes: coordinate axes, non-coordinate fixed axes, random directions
_fixed_axes = [
    (1.0, 0.0, 0.0),
    (0.0, 1.0, 0.0),
    (0.0, 0.0, 1.0),
    (1.0, 1.0, 0.0),
    (1.0, 2.0, 3.0),
    (-1.0, 1.0, 1.0),
    (0.3, -0.4, 0.5),
]


@st.composite
def unit_axes(draw: st.DrawFn) -> np.ndarray:
    if draw(st.booleans()):
        a = np.array(draw(st.sampled_from(_fixed_axes)))
    else:
        a = np.array(
            draw(st.tuples(*[st.floats(-1, 1, allow_nan=False, allow_infinity=False)] * 3))
        )
        if np.linalg.norm(a) < 1e-3:
            a = np.array([0.2, -0.7, 0.4])
    return a / np.linalg.norm(a)


#: magnitudes of translations from 1e-9 to 1e9 (log-uniform) and 0
lengths = st.one_of(st.just(0.0), st.floats(-9, 9).map(lambda e: 10.0**e))


@st.composite
def twists(draw: st.DrawFn, max_angle: float = PI) -> np.ndarray:
    """Twists whose rotation angle is clustered at 0 and pi (<= max_angle)."""
    th = min(draw(angles), max_angle)
    u = draw(unit_axes())
    d = draw(unit_axes())
    return np.concatenate([th * u, draw(lengths) * d])


@st.composite
def displacements(draw: st.DrawFn) -> np.ndarray:
    from mechsing import lie

    return lie.exp(draw(twists()))
