"""Random mechanisms with exact data, for exact mode's benchmark (``_scale_exact.py``) and
its tests (``tests/test_exact_instances.py``).

usage: python benchmarks/_exact_instances.py FAMILY SEED [DEGREE]   (prints the file)

Each generator returns an :class:`Instance`: the mechanism file's text (numbers written
as exact strings, ``"3/5"``, ``"3*sqrt(2)/5"``), the degree over QQ of the number field
its data live in (computed with sympy, :func:`field_degree`), and the exact joint values
of its configurations, which :func:`closes` checks independently of mechsing (the
product of exponentials around the loop, Rodrigues' formula with exact cosines and sines).

- ``bennett``: a Bennett linkage from the Denavit-Hartenberg product
  T_i = Rz(theta_i) Tx(a_i) Rx(alpha_i) (d_i = 0), with tan(alpha/2) and tan(beta/2)
  rational and a / sin(alpha) = b / sin(beta) = c; c rational (degree 1) or a rational
  times sqrt(k) (degree 2).  The reference has tan(theta1/2) = t1 rational,
  tan(theta2/2) = K / t1 with K = sin((beta + alpha)/2) / sin((beta - alpha)/2)
  = (tan(beta/2) + tan(alpha/2)) / (tan(beta/2) - tan(alpha/2)), theta3 = -theta1,
  theta4 = -theta2; the sign of K is the one whose product closes exactly (checked
  here).  Further configurations take other rational t1; a joint value is measured from
  the reference, q = 2 atan((t - t_ref) / (1 + t t_ref)).
- ``bricard``: line-symmetric Bricard 6R: three random lines with rational unit
  directions and rational points for joints 1-3, and their images under the half-turn
  about a random rational line for joints 4-6.  ``bricard-plane``: plane-symmetric
  Bricard 6R: joints 1 and 4 lie in a rational plane, joints 6 and 5 are the mirror
  images of joints 2 and 3.  The drawn pose is the configuration.  Points rational
  (degree 1) or a + b sqrt(k) with a, b rational (``bricard-d2``, ``bricard-plane-d2``:
  degree 2); the isometries are rational, so the images stay in the field.
- ``stewart``: a 6-UPS platform in the form of ``examples/stewart_octahedral.yaml``
  (U at the base, first axis vertical; P along the leg; S at the platform): platform
  points of a rational hexagon moved by a rational pose (rotation: the Cayley transform
  of a rational vector), legs whose squared lengths are rational squares times 1, 2, 3
  or 6, so that the leg lengths and the legs' unit directions lie in QQ (degree 1),
  QQ(sqrt 2) (degree 2) or QQ(sqrt 2, sqrt 3) (degree 4).  The drawn pose is the
  configuration.
"""

from __future__ import annotations

import random
import sys
from dataclasses import dataclass, field

import sympy as sp
from sympy.polys.domains import QQ

Vec = tuple[sp.Expr, sp.Expr, sp.Expr]


@dataclass(frozen=True)
class Instance:
    """A generated mechanism: ``text`` (the YAML file), ``degree`` (of its number field over
    QQ), ``family`` and ``name``; ``joints`` (name -> (axis, point) as exact sympy vectors,
    in loop order for single-loop families) and ``configs`` (configuration name -> joint
    name -> exact angle, radians, measured from the drawn pose) for the closure check;
    ``published``: the mobility and closure rank the mechanism is known to have."""

    family: str
    name: str
    text: str
    degree: int
    joints: dict[str, tuple[Vec, Vec]] = field(default_factory=dict)
    configs: dict[str, dict[str, sp.Expr]] = field(default_factory=dict)
    published: dict[str, int] = field(default_factory=dict)


# -- exact arithmetic -------------------------------------------------------------------


def is_zero(x: sp.Expr) -> bool:
    """Exactly zero: rationalise denominators, expand (a linear combination of square roots
    of distinct square-free integers is zero only when every coefficient is)."""
    return sp.expand(sp.radsimp(sp.expand(x))) == 0


def _rat(r: random.Random, lo: int, hi: int, den: int) -> sp.Rational:
    """A random rational p/q with q in 1..den and p/q in [lo, hi]."""
    q = r.randint(1, den)
    return sp.Rational(r.randint(lo * q, hi * q), q)


def _unit(r: random.Random) -> sp.Matrix:
    """A random rational unit vector (inverse stereographic projection of a rational point)."""
    u, v = _rat(r, -2, 2, 5), _rat(r, -2, 2, 5)
    n = 1 + u**2 + v**2
    return sp.Matrix([2 * u / n, 2 * v / n, (1 - u**2 - v**2) / n])


def _hat(w: sp.Matrix) -> sp.Matrix:
    return sp.Matrix([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def cayley(v: sp.Matrix) -> sp.Matrix:
    """The rotation (I - [v])^-1 (I + [v]) of a rational vector v: a rational rotation."""
    eye = sp.eye(3)
    return sp.simplify((eye - _hat(v)).inv() * (eye + _hat(v)))


def _rotation(axis: sp.Matrix, c: sp.Expr, s: sp.Expr) -> sp.Matrix:
    """Rodrigues: the rotation by the angle with cosine c and sine s about a unit axis."""
    k = _hat(axis)
    return sp.eye(3) + s * k + (1 - c) * k * k


def cos_sin(angle: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """Exact cosine and sine of an angle +-2 atan(t) (from the half-angle tangent t), 0 or pi,
    or of anything sympy's ``expand_trig`` writes in radicals."""
    if angle == 0:
        return sp.Integer(1), sp.Integer(0)
    if angle == sp.pi:
        return sp.Integer(-1), sp.Integer(0)
    coeff, rest = sp.sympify(angle).as_coeff_Mul()
    if abs(coeff) == 2 and isinstance(rest, sp.atan):
        t = sp.sign(coeff) * rest.args[0]  # tan of half the angle
        return (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)
    return sp.expand_trig(sp.cos(angle)), sp.expand_trig(sp.sin(angle))


def closes(inst: Instance, config: str) -> bool:
    """The loop's product of exponentials at ``config`` is the identity, exactly (a single
    loop: ``inst.joints`` in loop order, each R joint turning the next body about its
    line by its value)."""
    g_r, g_t = sp.eye(3), sp.zeros(3, 1)
    values = inst.configs[config]
    for name, (axis, point) in inst.joints.items():
        w = sp.Matrix(axis)
        w = w / sp.sqrt(sum(x**2 for x in w))
        c, s = cos_sin(values.get(name, sp.Integer(0)))
        rot = _rotation(w, c, s)
        trans = (sp.eye(3) - rot) * sp.Matrix(point)
        g_r, g_t = g_r * rot, g_r * trans + g_t
    return all(is_zero(x - y) for x, y in zip(g_r, sp.eye(3), strict=True)) and all(
        is_zero(x) for x in g_t
    )


def _radicals(x: sp.Expr) -> set[sp.Expr]:
    return {
        p
        for p in sp.sympify(x).atoms(sp.Pow)
        if p.exp.is_Rational and not p.exp.is_Integer and p.base.is_Rational
    }


def field_degree(numbers: list[sp.Expr]) -> int:
    """Degree over QQ of the field generated by the radicals (rational numbers to rational
    powers) in ``numbers``: sympy's primitive element of QQ(radicals) and its minimal
    polynomial."""
    gens: set[sp.Expr] = set()
    for x in numbers:
        gens |= _radicals(x)
    if not gens:
        return 1
    k = QQ.algebraic_field(*sorted(gens, key=sp.default_sort_key))
    return int(k.ext.minpoly.degree())


def mechanism_degree(mech: object, configs: list[str]) -> int:
    """Degree of the number field of a loaded mechanism's data as mechsing holds them (axes
    normalised) and of the cosines and sines of its R joints' values (and the other joints'
    values) at ``configs``."""
    numbers: list[sp.Expr] = []
    for j in mech.joints:  # type: ignore[attr-defined]
        for v in j.params.values():
            numbers += [x for x in _flatten(v) if isinstance(x, sp.Basic)]
    for name in configs:
        c = mech.configurations.get(name)  # type: ignore[attr-defined]
        if c is None:
            continue
        types = {j.name: j.type for j in mech.joints}  # type: ignore[attr-defined]
        for joint, vals in c.values.items():
            for x in vals:
                x = sp.sympify(x)
                if types.get(joint) in ("R", "U", "H") or x.has(sp.pi, sp.atan):
                    numbers += list(cos_sin(x))
                else:
                    numbers.append(x)
    return field_degree(numbers)


def _flatten(v: object) -> list[object]:
    if isinstance(v, tuple | list):
        return [y for x in v for y in _flatten(x)]
    return [v]


def _s(x: sp.Expr) -> str:
    return f'"{sp.sstr(sp.radsimp(x))}"' if not x.is_Integer else str(x)


def _v(xs: sp.Matrix | Vec) -> str:
    return "[" + ", ".join(_s(x) for x in xs) + "]"


def _joint_line(name: str, a: str, b: str, axis: sp.Matrix, point: sp.Matrix) -> str:
    return (
        f"  - {{name: {name}, type: R, between: [{a}, {b}], axis: {_v(axis)}, point: {_v(point)}}}"
    )


# -- Bennett ------------------------------------------------------------------------------


def _dh(c: sp.Expr, s: sp.Expr, a: sp.Expr, ca: sp.Expr, sa: sp.Expr) -> sp.Matrix:
    """Rz(theta) Tx(a) Rx(alpha) as a 4 x 4 matrix (cos/sin of theta: c, s; of alpha: ca, sa)."""
    return sp.Matrix(
        [
            [c, -s * ca, s * sa, a * c],
            [s, c * ca, -c * sa, a * s],
            [0, sa, ca, 0],
            [0, 0, 0, 1],
        ]
    )


def _half(t: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    return (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)


def _relative(t: sp.Expr, t_ref: sp.Expr) -> sp.Expr:
    """theta - theta_ref for tan(theta/2) = t, tan(theta_ref/2) = t_ref (mod 2 pi)."""
    if t == t_ref:
        return sp.Integer(0)
    den = 1 + t * t_ref
    if den == 0:
        return sp.pi
    return 2 * sp.atan((t - t_ref) / den)


def bennett(seed: int, degree: int = 1, extra: int = 2) -> Instance:
    """A random Bennett linkage (degree 1: rational data; 2: lengths in QQ(sqrt k)) with its
    reference and ``extra`` further exactly closed configurations."""
    r = random.Random(f"bennett-{seed}-{degree}")
    while True:
        s_al, s_be = _rat(r, 1, 3, 6) / 3, _rat(r, 1, 3, 6) / 3
        if s_al != s_be and 0 < s_al < 1 and 0 < s_be < 1:
            break
    ca, sa = _half(s_al)
    cb, sb = _half(s_be)
    scale = _rat(r, 1, 3, 4)
    if degree == 2:
        scale = scale * sp.sqrt(r.choice((2, 3, 5, 7)))
    elif degree != 1:
        raise ValueError("bennett: degree 1 or 2")
    a, b = scale * sa, scale * sb
    k_ratio = (s_be + s_al) / (s_be - s_al)
    t_vals = []
    while len(t_vals) < 1 + extra:
        t1 = _rat(r, -3, 3, 5)
        if t1 != 0 and t1 not in t_vals:
            t_vals.append(t1)
    for sign in (1, -1):
        frames = _bennett_frames(t_vals[0], sign * k_ratio / t_vals[0], a, b, ca, sa, cb, sb)
        if frames is not None:
            break
    else:
        raise AssertionError("neither sign of K closes the Bennett loop")
    joints = {}
    for i in range(4):
        f = frames[i]
        joints[f"J{i + 1}"] = (tuple(f[:3, 2]), tuple(f[:3, 3]))
    ref = (t_vals[0], sign * k_ratio / t_vals[0])
    configs: dict[str, dict[str, sp.Expr]] = {"reference": {}}
    for n, t1 in enumerate(t_vals[1:], start=1):
        t2 = sign * k_ratio / t1
        q1, q2 = _relative(t1, ref[0]), _relative(t2, ref[1])
        # theta3 = -theta1, theta4 = -theta2: so are their differences from the reference
        configs[f"moved{n}"] = {"J1": q1, "J2": q2, "J3": -q1, "J4": -q2}
    lines = [
        f"# Bennett linkage, random instance (seed {seed}): tan(alpha/2) = {s_al}, "
        f"tan(beta/2) = {s_be}, a/sin(alpha) = b/sin(beta) = {scale}",
        f"# reference: tan(theta1/2) = {ref[0]}, tan(theta2/2) = {ref[1]}, theta3 = -theta1, "
        "theta4 = -theta2",
        f"mechanism: bennett-d{degree}-{seed}",
        "units: {angle: rad}",
        "bodies: [ground, link1, link2, link3]",
        "joints:",
    ]
    bodies = ["ground", "link1", "link2", "link3", "ground"]
    for i, (name, (axis, point)) in enumerate(joints.items()):
        lines.append(_joint_line(name, bodies[i], bodies[i + 1], axis, point))
    lines += ["inputs: [J1]", "output: {body: link2}", "configurations:", "  reference: {}"]
    for cname, vals in configs.items():
        if cname != "reference":
            lines.append(
                f"  {cname}: {{" + ", ".join(f"{j}: {_s(q)}" for j, q in vals.items()) + "}"
            )
    numbers = [x for ax, p in joints.values() for x in (*ax, *p)]
    return Instance(
        "bennett",
        f"bennett-d{degree}-{seed}",
        "\n".join(lines) + "\n",
        field_degree(numbers),
        joints,
        configs,
        {"finite": 1, "closure_rank": 3},
    )


def _bennett_frames(t1, t2, a, b, ca, sa, cb, sb):  # noqa: ANN001, ANN202
    """Frames 0..3 of the DH chain (frame 0 = ground) when T1 T2 T3 T4 = I exactly, else None."""
    ts = (t1, t2, -t1, -t2)
    params = ((a, ca, sa), (b, cb, sb), (a, ca, sa), (b, cb, sb))
    frames = [sp.eye(4)]
    for t, (length, c_al, s_al) in zip(ts, params, strict=True):
        c, s = _half(t)
        frames.append(frames[-1] * _dh(c, s, length, c_al, s_al))
    if all(is_zero(x - y) for x, y in zip(frames[4], sp.eye(4), strict=True)):
        return frames[:4]
    return None


# -- Bricard ------------------------------------------------------------------------------


def _coordinate(r: random.Random, root: sp.Expr | None) -> sp.Expr:
    """A random rational, or (``root`` given) a + b root with a, b random rationals."""
    x = _rat(r, -2, 2, 4)
    return x if root is None else x + _rat(r, -1, 1, 4) * root


def _point(r: random.Random, root: sp.Expr | None = None) -> sp.Matrix:
    return sp.Matrix([_coordinate(r, root) for _ in range(3)])


def _root(r: random.Random, degree: int) -> sp.Expr | None:
    if degree not in (1, 2):
        raise ValueError("bricard: degree 1 or 2")
    return None if degree == 1 else sp.sqrt(r.choice((2, 3, 5, 7)))


def _named(family: str, seed: int, degree: int) -> str:
    return f"{family}-{seed}" if degree == 1 else f"{family}-d2-{seed}"


def bricard(seed: int, degree: int = 1) -> Instance:
    """A random line-symmetric Bricard 6R at its drawn (symmetric) pose: points rational
    (degree 1) or in QQ(sqrt k) (degree 2); directions rational."""
    r = random.Random(f"bricard-{seed}" if degree == 1 else f"bricard-{seed}-{degree}")
    root = _root(r, degree)
    d = _unit(r)
    c = _point(r, root) / 2
    half = 2 * d * d.T - sp.eye(3)  # the half-turn's rotation (rational, involutive)
    first = [(_unit(r), _point(r, root)) for _ in range(3)]
    lines3 = first + [(half * w, c + half * (p - c)) for w, p in first]
    return _six_r(
        "bricard",
        _named("bricard", seed, degree),
        seed,
        lines3,
        f"half-turn about the line through {list(c)} along {list(d)}",
    )


def bricard_plane(seed: int, degree: int = 1) -> Instance:
    """A random plane-symmetric Bricard 6R at its drawn pose: joints 1 and 4 in the plane of
    symmetry, joints 6 and 5 the mirror images of joints 2 and 3 (points rational or in
    QQ(sqrt k), directions rational)."""
    r = random.Random(f"bricard-plane-{seed}" if degree == 1 else f"bricard-plane-{seed}-{degree}")
    root = _root(r, degree)
    q = cayley(sp.Matrix([_rat(r, -1, 1, 4) for _ in range(3)]))
    n = q[:, 2]
    c = _point(r, root) / 2
    mirror = sp.eye(3) - 2 * n * n.T

    def in_plane() -> tuple[sp.Matrix, sp.Matrix]:
        co, si = _half(_rat(r, -3, 3, 4))
        w = q * sp.Matrix([co, si, 0])
        p = c + q * sp.Matrix([_coordinate(r, root), _coordinate(r, root), 0])
        return w, p

    j1, j4 = in_plane(), in_plane()
    j2, j3 = (_unit(r), _point(r, root)), (_unit(r), _point(r, root))
    j5 = (mirror * j3[0], c + mirror * (j3[1] - c))
    j6 = (mirror * j2[0], c + mirror * (j2[1] - c))
    return _six_r(
        "bricard-plane",
        _named("bricard-plane", seed, degree),
        seed,
        [j1, j2, j3, j4, j5, j6],
        f"mirror in the plane through {list(c)} normal to {list(n)}",
    )


def _six_r(
    family: str, name: str, seed: int, axes: list[tuple[sp.Matrix, sp.Matrix]], what: str
) -> Instance:
    joints = {f"J{i + 1}": (tuple(w), tuple(p)) for i, (w, p) in enumerate(axes)}
    bodies = ["ground", "link1", "link2", "link3", "link4", "link5", "ground"]
    lines = [
        f"# {family} 6R, random instance (seed {seed}): {what}",
        f"mechanism: {name}",
        "bodies: [ground, link1, link2, link3, link4, link5]",
        "joints:",
    ]
    for i, (joint, (w, p)) in enumerate(joints.items()):
        lines.append(_joint_line(joint, bodies[i], bodies[i + 1], sp.Matrix(w), sp.Matrix(p)))
    lines += ["inputs: [J1]", "output: {body: link3}", "configurations:", "  reference: {}"]
    numbers = [x for ax, p in joints.values() for x in (*ax, *p)]
    return Instance(
        family,
        name,
        "\n".join(lines) + "\n",
        field_degree(numbers),
        joints,
        {"reference": {}},
        {"finite": 1, "closure_rank": 5},
    )


def symmetric(inst: Instance) -> bool:
    """The Bricard conditions, checked exactly on the file's lines through their invariants:
    for each pair of consecutive lines, cos^2 of their angle and their squared distance; for
    each line, the squared offset between its feet of the common normals.  Line-symmetric:
    link i + 3 and offset i + 3 repeat link i and offset i; plane-symmetric (lines 1 and 4 in
    the plane): links (1, 2), (2, 3), (3, 4) repeat as (6, 1), (5, 6), (4, 5), offsets 2 and 3
    as 6 and 5."""
    lines = [(sp.Matrix(w), sp.Matrix(p)) for w, p in inst.joints.values()]
    link = [_line_pair(lines[i], lines[(i + 1) % 6]) for i in range(6)]
    offset = [_offset2(lines[i - 1], lines[i], lines[(i + 1) % 6]) for i in range(6)]
    if inst.family == "bricard":
        links, offsets = [(i, i + 3) for i in range(3)], [(i, i + 3) for i in range(3)]
    else:
        links, offsets = [(0, 5), (1, 4), (2, 3)], [(1, 5), (2, 4)]
    same_links = all(
        is_zero(x - y) for i, j in links for x, y in zip(link[i], link[j], strict=True)
    )
    return same_links and all(is_zero(offset[i] - offset[j]) for i, j in offsets)


def _unit_line(line: tuple[sp.Matrix, sp.Matrix]) -> tuple[sp.Matrix, sp.Matrix]:
    w, p = line
    return w / sp.sqrt(w.dot(w)), p


def _line_pair(
    l1: tuple[sp.Matrix, sp.Matrix], l2: tuple[sp.Matrix, sp.Matrix]
) -> tuple[sp.Expr, sp.Expr]:
    """Invariants of two skew lines: cos^2 of their angle and their squared distance."""
    (w1, p1), (w2, p2) = _unit_line(l1), _unit_line(l2)
    cross = w1.cross(w2)
    return w1.dot(w2) ** 2, (p2 - p1).dot(cross) ** 2 / cross.dot(cross)


def _foot(l1: tuple[sp.Matrix, sp.Matrix], l2: tuple[sp.Matrix, sp.Matrix]) -> sp.Expr:
    """Parameter s of the foot p1 + s w1 of the common normal of line 1 with line 2."""
    (w1, p1), (w2, p2) = _unit_line(l1), _unit_line(l2)
    n = w1.cross(w2)
    return (p2 - p1).cross(w2).dot(n) / n.dot(n)


def _offset2(prev, line, nxt) -> sp.Expr:  # noqa: ANN001
    """Squared DH offset of ``line``: the distance between its feet of the common normals."""
    return (_foot(line, nxt) - _foot(line, prev)) ** 2


# -- Stewart ------------------------------------------------------------------------------


def _squarefree(n: int) -> int:
    k = 1
    for p in range(2, int(n**0.5) + 2):
        while n % (p * p) == 0:
            n //= p * p
        if n % p == 0:
            n //= p
            k *= p
    return k * n


def _leg_direction(r: random.Random, cls: int) -> tuple[int, int, int]:
    while True:
        x, y, z = r.randint(-4, 4), r.randint(-4, 4), r.randint(4, 9)
        if (x, y) != (0, 0) and _squarefree(x * x + y * y + z * z) == cls:
            return x, y, z


#: rational unit horizontal directions for the U joints' second axes (a, b, c: (a/c, b/c, 0))
_HORIZONTAL = [
    (sp.Rational(a, c), sp.Rational(b, c))
    for a, b, c in ((1, 0, 1), (0, 1, 1), (3, 4, 5), (4, 3, 5), (-3, 4, 5), (-4, 3, 5))
    + ((5, 12, 13), (12, 5, 13), (-5, 12, 13), (-12, 5, 13))
]


def stewart(seed: int, degree: int = 1) -> Instance:
    """A random 6-UPS platform at a rational pose whose legs' lengths lie in a field of
    degree 1, 2 or 4 (QQ, QQ(sqrt 2), QQ(sqrt 2, sqrt 3))."""
    choices = {1: (1,), 2: (1, 2), 4: (1, 2, 3, 6)}
    if degree not in choices:
        raise ValueError("stewart: degree 1, 2 or 4")
    r = random.Random(f"stewart-{seed}-{degree}")
    while True:
        classes = [r.choice(choices[degree]) for _ in range(6)]
        if field_degree([sp.sqrt(k) for k in classes]) == degree:
            break
    rot = cayley(sp.Matrix([_rat(r, -1, 1, 5) / 2 for _ in range(3)]))
    height = sp.Rational(r.randint(8, 14), 10)
    offset = sp.Matrix([_rat(r, -1, 1, 10) / 5, _rat(r, -1, 1, 10) / 5, height])
    # platform hexagon: three pairs of points near azimuths 60, 180, 300 deg (rational)
    hexagon = [(3, 4), (-4, 3), (-5, 0), (-4, -3), (3, -4), (4, -3)]
    radius = sp.Rational(r.randint(5, 8), 10)
    joints_lines = []
    numbers: list[sp.Expr] = []
    bodies = ["ground"]
    for k in range(6):
        x, y = hexagon[k]
        local = sp.Matrix([sp.Rational(x, 5) * radius, sp.Rational(y, 5) * radius, 0])
        p = rot * local + offset
        lx, ly, lz = _leg_direction(r, classes[k])
        # the leg goes from the base (z = 0) up to p: leg = lam (lx, ly, lz), lam rational
        lam = p[2] / lz
        leg = sp.Matrix([lx, ly, lz]) * lam
        base = p - leg
        length = sp.sqrt(leg.dot(leg))
        unit = sp.Matrix([sp.radsimp(e / length) for e in leg])
        # the U's second axis: the listed horizontal direction furthest from the leg's plane
        hx, hy = max(_HORIZONTAL, key=lambda h: abs(h[0] * ly - h[1] * lx))
        second = sp.Matrix([hx, hy, 0])
        i = k + 1
        bodies += [f"cyl{i}", f"pis{i}"]
        joints_lines += [
            f"  - {{name: U{i}, type: U, between: [ground, cyl{i}], axes: [[0, 0, 1], {_v(second)}], point: {_v(base)}}}",
            f"  - {{name: P{i}, type: P, between: [cyl{i}, pis{i}], axis: {_v(unit)}}}",
            f"  - {{name: S{i}, type: S, between: [pis{i}, platform], point: {_v(p)}}}",
        ]
        numbers += [*second, *unit, *base, *p]
    bodies.append("platform")
    lines = [
        f"# 6-UPS platform, random instance (seed {seed}): rotation = Cayley transform, "
        f"squared leg lengths = rational squares times {classes}",
        f"mechanism: stewart-d{degree}-{seed}",
        f"bodies: [{', '.join(bodies)}]",
        "joints:",
        *joints_lines,
        "inputs: [P1, P2, P3, P4, P5, P6]",
        "output: {body: platform}",
        "configurations:",
        "  reference: {}",
    ]
    return Instance(
        "stewart",
        f"stewart-d{degree}-{seed}",
        "\n".join(lines) + "\n",
        field_degree(numbers),
        {},
        {"reference": {}},
        {"finite": 6, "closure_rank": 30},
    )


#: family -> generator(seed) -> Instance, with the degrees the benchmark draws
FAMILIES = {
    "bennett-d1": lambda seed: bennett(seed, 1),
    "bennett-d2": lambda seed: bennett(seed, 2),
    "bricard": bricard,
    "bricard-d2": lambda seed: bricard(seed, 2),
    "bricard-plane": bricard_plane,
    "bricard-plane-d2": lambda seed: bricard_plane(seed, 2),
    "stewart-d1": lambda seed: stewart(seed, 1),
    "stewart-d2": lambda seed: stewart(seed, 2),
    "stewart-d4": lambda seed: stewart(seed, 4),
}


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 2 or args[0] not in FAMILIES:
        print(f"usage: _exact_instances.py {{{'|'.join(FAMILIES)}}} SEED", file=sys.stderr)
        return 2
    inst = FAMILIES[args[0]](int(args[1]))
    print(inst.text, end="")
    print(f"# field degree {inst.degree}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
