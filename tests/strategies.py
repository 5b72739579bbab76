"""Every hypothesis strategy of the tests, in two families.

* Lie formulas (tests/test_lie.py, test_cayley.py, test_dual.py, test_quaternion.py): angles
  clustered where the formulas change branch (0 and pi), unit axes, translation magnitudes
  from 1e-9 to 1e9, twists, displacements, Gibbs vectors.
* Mechanism files (tests/test_kinematics.py, test_model_graph.py): geometry and joint values as
  a file writes them (unnormalised axes, angles beyond a turn, random units), random trees of
  every joint type, planar frames, random body graphs.
* Dynamics (tests/test_dynamics_rigid.py, test_dynamics_tree.py): rigid bodies' inertia
  (boxes turned at random), robots as URDF trees of revolute and prismatic joints with
  random inertials.
"""

from __future__ import annotations

import math

import numpy as np
import sympy
from hypothesis import strategies as st

from tests.reference.files import Spec
from tests.reference.kinematics import KINDS, J
from tests.reference.se3 import in_plane, screw_motion, unit

PI = math.pi
finite = {"allow_nan": False, "allow_infinity": False}

# ============================================================================ Lie formulas

#: rotation angles in [0, pi] clustered at 0 and pi (and a few fixed points), then anywhere
angles = st.one_of(
    st.floats(0.0, 1e-12),
    st.floats(0.0, 1e-6),
    st.floats(PI - 1e-12, PI),
    st.floats(PI - 1e-6, PI),
    st.sampled_from([0.0, 1e-16, 1e-8, 1e-4, 0.5, 1.0, PI / 2, PI - 1e-4, PI - 1e-8, PI]),
    st.floats(0.0, PI),
)

#: small exact rationals (sympy), for the exact forms of the Lie formulas
rationals = st.fractions(min_value=-20, max_value=20, max_denominator=12).map(sympy.Rational)

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
def unit_axes(draw: st.DrawFn, fixed: bool = True) -> np.ndarray:
    """Unit axes: random directions and, with ``fixed``, also coordinate and fixed
    non-coordinate axes half of the time."""
    if fixed and draw(st.booleans()):
        a = np.array(draw(st.sampled_from(_fixed_axes)))
    else:
        a = np.array(draw(st.tuples(*[st.floats(-1, 1, **finite)] * 3)))
        if np.linalg.norm(a) < 1e-3:
            a = np.array([2.0, 3.0, 6.0])  # a non-coordinate axis
    return a / np.linalg.norm(a)


#: magnitudes of translations from 1e-9 to 1e9 (log-uniform) and 0
lengths = st.one_of(st.just(0.0), st.floats(-9, 9).map(lambda e: 10.0**e))
#: five length scales from 1e-9 to 1e9
length_scales = st.sampled_from([1e-9, 1e-3, 1.0, 1e3, 1e9])


@st.composite
def frame_data(draw: st.DrawFn, n: int = 5) -> tuple[float, np.ndarray, np.ndarray]:
    """A commensurate frame's data: a length scale L, a centroid within 10 L of the origin,
    and which of ``n`` joint coordinates are lengths."""
    L = draw(length_scales)
    c = np.array(draw(st.lists(st.floats(-10.0, 10.0), min_size=3, max_size=3))) * L
    return L, c, np.array(draw(st.lists(st.booleans(), min_size=n, max_size=n)))


@st.composite
def twists(draw: st.DrawFn, max_angle: float = PI) -> np.ndarray:
    """Twists whose rotation angle is clustered at 0 and pi (<= max_angle)."""
    th = min(draw(angles), max_angle)
    u = draw(unit_axes())
    d = draw(unit_axes())
    return np.concatenate([th * u, draw(lengths) * d])


def bounded_twists(bound: float = 3.0) -> st.SearchStrategy[np.ndarray]:
    """Twists with every coordinate in [-bound, bound]."""
    return st.lists(st.floats(-bound, bound), min_size=6, max_size=6).map(np.array)


@st.composite
def displacements(draw: st.DrawFn) -> np.ndarray:
    """exp of :func:`twists` by mechsing.lie (for checks of other lie functions)."""
    from mechsing import lie

    return lie.exp(draw(twists()))


@st.composite
def rotvecs(draw: st.DrawFn) -> np.ndarray:
    """Rotation vectors: a clustered angle times a random unit axis."""
    return draw(angles) * draw(unit_axes(fixed=False))


@st.composite
def scaled_points(draw: st.DrawFn) -> np.ndarray:
    """Points in a cube of one of :data:`length_scales`."""
    return draw(length_scales) * np.array(draw(st.lists(st.floats(-1, 1), min_size=3, max_size=3)))


@st.composite
def screw_displacements(draw: st.DrawFn) -> np.ndarray:
    """Screw motions by a clustered angle about a random line (N, u), sliding d along it, built
    independently (:func:`tests.reference.se3.screw_motion`)."""
    u, N, theta = draw(unit_axes(fixed=False)), draw(scaled_points()), draw(angles)
    d = draw(length_scales) * draw(st.floats(-1, 1))
    return screw_motion(u, N, theta, d)


#: magnitudes of the Gibbs vector: tan(theta/2) near 0 (theta ~ 1e-12) and large (theta within
#: 1e-9 of pi), plus moderate ones
gibbs_norms = st.one_of(
    st.floats(0, 1e-12),
    st.floats(1e-12, 1e-4),
    st.floats(0.1, 10),
    st.floats(10, 1e9),
    st.sampled_from([0.0, 1.0, 1e3, 1e6]),
)


@st.composite
def gibbs(draw: st.DrawFn) -> np.ndarray:
    """Gibbs vectors (Cayley parameters of a rotation)."""
    return draw(gibbs_norms) * draw(unit_axes(fixed=False))


@st.composite
def gibbs_twists(draw: st.DrawFn) -> np.ndarray:
    """(Gibbs vector, translation at one of :data:`length_scales`)."""
    a = draw(gibbs())
    scale = draw(length_scales)
    v = scale * np.array(draw(st.lists(st.floats(-1, 1), min_size=3, max_size=3)))
    return np.concatenate([a, v])


# ============================================================================ mechanism files


#: joint angles as a file writes them: anywhere, at 0 and +-pi, and beyond a turn
file_angles = st.one_of(
    st.floats(-PI, PI, **finite),
    st.floats(-1e-9, 1e-9, **finite),
    st.builds(lambda e, s: s * (PI - e), st.floats(0, 1e-9, **finite), st.sampled_from([1, -1])),
    st.sampled_from([0.0, PI, -PI, PI / 2, 1e-12, -1e-300, 2 * PI, 5.0]),
)
#: joint lengths (strokes) as a file writes them
file_lengths = st.one_of(
    st.floats(-3, 3, **finite),
    st.floats(-1e-9, 1e-9, **finite),
    st.sampled_from([0.0, 1.0, -2.5]),
)
coordinate_axes = st.sampled_from(
    [
        (0, 0, 1),
        (1, 0, 0),
        (0, 1, 0),
        (0, -2, 0),
        (1, 1, 0),
        (1, 1, 1),
        (-1, 1, 1),
        (1, 2, 3),
        (0, 3, 4),
    ]
)


@st.composite
def file_axes(draw: st.DrawFn) -> np.ndarray:
    """Direction vectors as a file writes them (not normalised)."""
    if draw(st.booleans()):
        return np.array(draw(coordinate_axes), dtype=float)
    v = np.array(draw(st.tuples(*[st.floats(-2, 2, **finite)] * 3)))
    if np.linalg.norm(v) < 0.3:
        v = v + np.array([0.3, -0.4, 0.5])
    return v


file_points = st.one_of(
    st.tuples(*[st.floats(-5, 5, **finite)] * 3).map(np.array),
    st.sampled_from([(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 2.0)]).map(np.array),
)
pitches = st.builds(lambda h, s: s * h, st.floats(0.05, 2, **finite), st.sampled_from([1, -1]))


@st.composite
def rotation_vectors(draw: st.DrawFn) -> np.ndarray:
    """Rotation vectors: a file axis (normalised) times a file angle."""
    return unit(draw(file_axes())) * draw(file_angles)


@st.composite
def joint_params(draw: st.DrawFn, jtype: str) -> dict:
    """A joint's geometry as a file gives it (SI), per joint type."""
    if jtype == "R" or jtype == "C":
        return {"axis": draw(file_axes()), "point": draw(file_points)}
    if jtype in ("P", "X"):
        return {"axis": draw(file_axes())}
    if jtype == "H":
        return {"axis": draw(file_axes()), "point": draw(file_points), "pitch": draw(pitches)}
    if jtype in ("T2", "G"):
        return {"normal": draw(file_axes())}
    if jtype == "Y":
        return {"normal": draw(file_axes()), "pitch": draw(pitches)}
    if jtype == "S":
        return {"point": draw(file_points)}
    if jtype == "U":
        a1, a2 = draw(file_axes()), draw(file_axes())
        if np.linalg.norm(np.cross(unit(a1), unit(a2))) < 0.2:
            a2 = np.cross(a1, [1.0, 0, 0] if abs(unit(a1)[0]) < 0.7 else [0, 1.0, 0])
        return {"axes": (a1, a2), "point": draw(file_points)}
    return {}  # T3, D, E


@st.composite
def joint_values(draw: st.DrawFn, jtype: str) -> np.ndarray:
    """A joint's values (SI) per joint type."""
    if jtype == "S":
        return draw(rotation_vectors())
    if jtype == "D":
        return np.concatenate([draw(rotation_vectors()), [draw(file_lengths) for _ in range(3)]])
    return np.array([draw(file_angles) if k == "a" else draw(file_lengths) for k in KINDS[jtype]])


TREE_TYPES = ["R", "P", "H", "C", "S", "U", "T2", "T3", "G", "X", "D", "Y", "E"]


@st.composite
def trees(draw: st.DrawFn) -> Spec:
    """Random trees (serial or branching) of every joint type, in random units, with one
    configuration that gives every joint value."""
    n = draw(st.integers(1, 8))
    serial = draw(st.booleans())
    parent = [None] + [k - 1 if serial else draw(st.integers(0, k - 1)) for k in range(1, n + 1)]
    names = draw(st.permutations([f"body{k}" for k in range(n + 1)]))
    ground = names[draw(st.integers(0, n))]
    joints, values = [], {}
    for k in range(1, n + 1):
        jtype = draw(st.sampled_from(TREE_TYPES))
        a, b = names[parent[k]], names[k]
        if draw(st.booleans()):
            a, b = b, a
        j = J(f"J{k}", jtype, a, b, draw(joint_params(jtype)))
        joints.append(j)
        values[j.name] = draw(joint_values(jtype))
    joints = draw(st.permutations(joints))
    bodies = draw(st.permutations(names))
    length, angle = draw(
        st.sampled_from([("m", "rad"), ("mm", "deg"), ("cm", "rad"), ("m", "deg")])
    )
    output = draw(st.sampled_from([b for b in names if b != ground]))
    cfg = {j.name: values[j.name] for j in joints if j.type != "E"}
    spec = Spec(
        list(bodies),
        ground,
        list(joints),
        {"given": cfg},
        output=output,
        length=length,
        angle=angle,
    )
    return spec


@st.composite
def planar_frame(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A random plane: unit normal w and in-plane unit vectors, a random origin."""
    w = unit(draw(file_axes()))
    e1, e2 = in_plane(w)
    c0 = draw(file_points)
    return w, e1, e2, c0


plane_xy = st.tuples(st.floats(-3, 3, **finite), st.floats(-3, 3, **finite))
deltas = st.floats(-0.3, 0.3, **finite).filter(lambda d: abs(d) > 1e-3)


@st.composite
def body_graphs(draw: st.DrawFn, max_bodies: int = 8, max_extra: int = 8) -> tuple[list, list]:
    """Random connected body graphs: a random spanning tree plus extra joints
    (parallel joints allowed), random orientations, some U joints (mechsing.model joints)."""
    from mechsing.model import Joint

    n = draw(st.integers(1, max_bodies))
    bodies = [f"b{i}" for i in range(n)]
    pairs = []
    for i in range(1, n):
        pairs.append((draw(st.integers(0, i - 1)), i))
    if n >= 2:
        for _ in range(draw(st.integers(0, max_extra))):
            a = draw(st.integers(0, n - 1))
            b = draw(st.integers(0, n - 2))
            b = b if b < a else b + 1
            pairs.append((a, b))
    order = draw(st.permutations(range(len(pairs))))
    joints = []
    for k, idx in enumerate(order):
        a, b = pairs[idx]
        if draw(st.booleans()):
            a, b = b, a
        jtype = "U" if draw(st.integers(0, 4)) == 0 else "R"
        joints.append(
            Joint(f"J{k}", jtype, (bodies[a], bodies[b]), {}, None, 2 if jtype == "U" else 1)
        )
    return bodies, joints


def _box_moments(m: float, a: float, b: float, c: float) -> tuple[float, float, float]:
    """The principal moments of a solid box of mass m and sides a, b, c (they satisfy the
    triangle inequality, as every rigid body's)."""
    return (m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b))


@st.composite
def body_inertias(draw: st.DrawFn) -> tuple[float, np.ndarray, np.ndarray]:
    """A body's (mass, centre, inertia about the centre in ground axes): mass in [0.1, 10]
    kg, centre within 2 m, a box of sides in [0.05, 2] m turned by a random rotation."""
    from scipy.spatial.transform import Rotation

    m = draw(st.floats(0.1, 10))
    moments = _box_moments(m, *(draw(st.floats(0.05, 2)) for _ in range(3)))
    R = Rotation.from_rotvec([draw(st.floats(-2, 2)) for _ in range(3)]).as_matrix()
    centre = np.array([draw(st.floats(-2, 2)) for _ in range(3)])
    return m, centre, R @ np.diag(moments) @ R.T


@st.composite
def robot_trees(draw: st.DrawFn) -> tuple[str, np.ndarray]:
    """A URDF tree of 2 to 7 revolute and prismatic joints (each link's parent any earlier
    link), random origins, axes and inertials (every link massive); and 3 samples of
    (q, qd, qdd), shape (3, 3, n)."""
    n = draw(st.integers(2, 7))
    fl = st.floats(-1, 1, allow_nan=False)
    links = ['<link name="l0"/>']
    joints = []
    for i in range(1, n + 1):
        m = draw(st.floats(0.2, 5))
        ixx, iyy, izz = _box_moments(m, *(draw(st.floats(0.05, 1)) for _ in range(3)))
        com = " ".join(f"{draw(fl):.6f}" for _ in range(3))
        rot = " ".join(f"{3 * draw(fl):.6f}" for _ in range(3))
        links.append(
            f'<link name="l{i}"><inertial><origin xyz="{com}" rpy="{rot}"/>'
            f'<mass value="{m:.6f}"/><inertia ixx="{ixx:.8f}" iyy="{iyy:.8f}" '
            f'izz="{izz:.8f}" ixy="0" ixz="0" iyz="0"/></inertial></link>'
        )
        parent = draw(st.integers(0, i - 1))
        kind = draw(st.sampled_from(["revolute", "revolute", "prismatic"]))
        xyz = " ".join(f"{draw(fl):.6f}" for _ in range(3))
        rpy = " ".join(f"{3 * draw(fl):.6f}" for _ in range(3))
        axis = np.array([draw(fl) for _ in range(3)])
        if np.linalg.norm(axis) < 0.1:
            axis = np.array([0.0, 0.0, 1.0])
        ax = " ".join(f"{x:.6f}" for x in axis)
        joints.append(
            f'<joint name="j{i}" type="{kind}"><parent link="l{parent}"/><child link="l{i}"/>'
            f'<origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="{ax}"/>'
            '<limit lower="-10" upper="10" effort="1" velocity="1"/></joint>'
        )
    text = '<robot name="tree">' + "".join(links) + "".join(joints) + "</robot>"
    values = draw(st.lists(st.floats(-2, 2, allow_nan=False), min_size=9 * n, max_size=9 * n))
    return text, np.array(values).reshape(3, 3, n)
