"""Closed-form answers for the sweep correctness tests, written from planar geometry alone (numpy and
math; nothing from mechsing): where a four-bar's input stops and where its output stops, where a
change-point four-bar is flat, a slider-crank's dead centres, the five-bar's point and its Type I and
Type II determinants, the 3-RPR's leg-line concurrency determinant and the UR5's det J.

Conventions (those of the mechanism files, docs/closure.md, "Joint values"):

* points are planar (x, y) in SI units (metres), given at the reference configuration (the pose the
  file draws); a revolute joint's value is the turn, in radians, of its second body relative to its
  first about the joint's axis, measured from the reference (so with axis +z a crank's joint value
  is its counter-clockwise turn from where the file draws it); ``axis_z`` is the z component of the
  unit axis (+1 or -1) where a function takes it;
* a prismatic joint's value is the displacement along its unit axis from the reference, in metres;
* angles returned are wrapped into (-pi, pi];
* ``a x b`` of two planar vectors is the scalar ``a_x b_y - a_y b_x``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

Point = tuple[float, float]


def cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The planar cross product u x v = u_x v_y - u_y v_x (batched over leading axes)."""
    u, v = np.asarray(u, float), np.asarray(v, float)
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def wrap(angle: float) -> float:
    """The angle in (-pi, pi]."""
    a = math.remainder(angle, 2 * math.pi)
    return math.pi if a == -math.pi else a


def _angle(v: np.ndarray) -> float:
    return math.atan2(float(v[1]), float(v[0]))


def _pts(*points: Point) -> list[np.ndarray]:
    return [np.asarray(p, float)[:2] for p in points]


# ------------------------------------------------------------------------------------ four-bar


class Limit(NamedTuple):
    """A joint value where something happens, and which alignment causes it."""

    value: float
    kind: str  # "stretched" or "folded"


def four_bar_input_limits(
    a_pt: Point, b_pt: Point, c_pt: Point, d_pt: Point, axis_z: float = 1.0
) -> list[Limit]:
    """Joint values of the input A (ground-crank, axis +-z) at the input's limits of travel.

    Joints A, D on ground; A-B the input link (length a), B-C the coupler (b), C-D the output link
    (c), |AD| = d. With the input at B the passive chain B-C-D closes iff
    |b - c| <= |BD| <= b + c; the input stops where |BD| reaches a bound, i.e. where coupler and
    output link are aligned (stretched: |BD| = b + c; folded: |BD| = |b - c|). The law of cosines
    in the triangle ABD gives the angle BAD:

        cos(BAD) = (a^2 + d^2 - |BD|^2) / (2 a d),

    two mirror positions +-BAD about AD. The joint value is that direction of AB minus AB's direction
    at the reference (times ``axis_z``), wrapped into (-pi, pi]. Only bounds crossed transversally
    are limits (|cos| < 1); a bound touched at cos = +-1 (B on the line AD) is a flat position where
    the input passes through (:func:`four_bar_flat_positions`). Sorted by value.
    """
    A, B, C, D = _pts(a_pt, b_pt, c_pt, d_pt)
    a, b, c, d = (np.linalg.norm(v) for v in (B - A, C - B, D - C, D - A))
    ref = _angle(B - A)
    ad = _angle(D - A)
    out: list[Limit] = []
    for kind, bd in (("stretched", b + c), ("folded", abs(b - c))):
        cos_bad = (a * a + d * d - bd * bd) / (2 * a * d)
        if abs(cos_bad) >= 1.0:
            continue
        phi = math.acos(cos_bad)
        out.extend(Limit(wrap(axis_z * (ad + s * phi - ref)), kind) for s in (1.0, -1.0))
    return sorted(out)


def four_bar_flat_positions(
    a_pt: Point, b_pt: Point, c_pt: Point, d_pt: Point, axis_z: float = 1.0, rtol: float = 1e-12
) -> list[float]:
    """Joint values of the input A where A, B, C and D are collinear (the change point's flat
    configurations, where two assembly modes meet).

    B must lie on the line AD (the input along AD or opposite to it, |BD| = |d - a| or d + a) and C
    on it too, which needs |BD| = b + c or |b - c| there (lengths as in
    :func:`four_bar_input_limits`); equality is tested to ``rtol`` of the longest link. For a
    Grashof change-point linkage (s + l = p + q) one of these holds.
    """
    A, B, C, D = _pts(a_pt, b_pt, c_pt, d_pt)
    a, b, c, d = (np.linalg.norm(v) for v in (B - A, C - B, D - C, D - A))
    ref, ad = _angle(B - A), _angle(D - A)
    tol = rtol * max(a, b, c, d)
    out = []
    for turn, bd in ((0.0, abs(d - a)), (math.pi, d + a)):
        if min(abs(bd - (b + c)), abs(bd - abs(b - c))) <= tol:
            out.append(wrap(axis_z * (ad + turn - ref)))
    return sorted(out)


def four_bar_mode(a_pt: Point, b_pt: Point, c_pt: Point, d_pt: Point) -> float:
    """The assembly mode of a four-bar pose: the sign of (D - B) x (C - B) (+1: C to the left of
    B -> D). Constant along a motion except where B, C, D align (the input's limits)."""
    _, B, C, D = _pts(a_pt, b_pt, c_pt, d_pt)
    return float(np.sign(cross(D - B, C - B)))


def four_bar_output_limits(
    a_pt: Point, b_pt: Point, c_pt: Point, d_pt: Point, axis_z: float = 1.0
) -> list[Limit]:
    """Joint values of the input A where the output link C-D stops (crank and coupler aligned:
    A, B, C collinear), on the reference assembly mode (:func:`four_bar_mode`).

    There |AC| = a + b (stretched) or |a - b| (folded); C lies on the circle of radius c about D, so
    the law of cosines in ACD gives cos(CAD) = (|AC|^2 + d^2 - c^2) / (2 |AC| d), two mirror
    positions of C. B is on the line AC: B = A + a (C - A)/|AC| if stretched or if a > b (C between A
    and B), else B = A - a (C - A)/|AC|. A position counts when its mode (D - B) x (C - B) has the
    reference sign. With the input as the driven joint these are input singularities (Gosselin-
    Angeles type I): the output's rate vanishes whatever the input's.
    """
    A, B0, C0, D = _pts(a_pt, b_pt, c_pt, d_pt)
    a, b, c, d = (np.linalg.norm(v) for v in (B0 - A, C0 - B0, D - C0, D - A))
    mode0 = four_bar_mode(A, B0, C0, D)
    ref, ad = _angle(B0 - A), _angle(D - A)
    out: list[Limit] = []
    for kind, ac in (("stretched", a + b), ("folded", abs(a - b))):
        if ac == 0.0:
            continue
        cos_cad = (ac * ac + d * d - c * c) / (2 * ac * d)
        if abs(cos_cad) > 1.0:
            continue
        cad = math.acos(cos_cad)
        for s in (1.0, -1.0) if 0.0 < cad < math.pi else (1.0,):  # C on line AD: one position
            ang = ad + s * cad
            e = np.array([math.cos(ang), math.sin(ang)])
            C = A + ac * e
            B = A + a * e if (kind == "stretched" or a > b) else A - a * e
            if np.sign(cross(D - B, C - B)) == mode0:
                out.append(Limit(wrap(axis_z * (_angle(B - A) - ref)), kind))
    return sorted(out)


# -------------------------------------------------------------------------------- slider-crank


def slider_crank_dead_centres(
    a_pt: Point, b_pt: Point, c_pt: Point, slide: Point
) -> dict[str, float]:
    """Slider joint values (displacement along the unit ``slide`` direction from the reference, m) at
    the dead centres of a slider-crank: crank A-B (length r, A on ground), rod B-C (length l), slider
    pin C moving on the line through its reference position with direction ``slide``.

    Crank and rod are aligned where |AC| = l + r (outer) or l - r (inner). With C(t) = C0 + t s and
    w = C0 - A: |w + t s|^2 = L^2 gives t = -w.s +- sqrt((w.s)^2 - |w|^2 + L^2); the root kept is the
    one on the reference's side of the foot of A on the line (w.s + t of the sign of w.s), the
    branch the slider stays on. For slide = +x and A at the origin this is x = sqrt(L^2 - e^2) minus
    the reference x, e the offset. A dead centre that does not exist (L < e) is NaN.
    """
    A, B, C0 = _pts(a_pt, b_pt, c_pt)
    s = np.asarray(slide, float)[:2]
    s = s / np.linalg.norm(s)
    r, l = np.linalg.norm(B - A), np.linalg.norm(C0 - B)
    w = C0 - A
    ws = float(w @ s)
    side = 1.0 if ws >= 0 else -1.0
    out = {}
    for name, L in (("outer", l + r), ("inner", abs(l - r))):
        disc = ws * ws - float(w @ w) + L * L
        out[name] = -ws + side * math.sqrt(disc) if disc >= 0 else math.nan
    return out


# ------------------------------------------------------------------------------------ five-bar


@dataclass(frozen=True)
class FiveBar:
    """A planar 5R five-bar at its reference configuration: base pivots a1, a2, elbows b1, b2 and the
    distal links' common joint p (the output point). Inputs: the base joints (axis +z)."""

    a1: Point
    a2: Point
    b1: Point
    b2: Point
    p: Point

    def lengths(self) -> tuple[float, float, float, float]:
        """(|A1B1|, |A2B2|, |B1P|, |B2P|)."""
        A1, A2, B1, B2, P = _pts(self.a1, self.a2, self.b1, self.b2, self.p)
        return tuple(float(np.linalg.norm(v)) for v in (B1 - A1, B2 - A2, P - B1, P - B2))

    def elbows(self, theta1: np.ndarray, theta2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """B1, B2 (shape (..., 2)) for input joint values theta1, theta2 (broadcast): B_i = A_i +
        Rot(theta_i)(B_i0 - A_i)."""
        A1, A2, B1, B2 = _pts(self.a1, self.a2, self.b1, self.b2)
        out = []
        for A, B, t in ((A1, B1, theta1), (A2, B2, theta2)):
            t = np.asarray(t, float)
            c, s = np.cos(t)[..., None], np.sin(t)[..., None]
            v = B - A
            out.append(A + np.concatenate([c * v[0] - s * v[1], s * v[0] + c * v[1]], axis=-1))
        return out[0], out[1]

    def reference_mode(self) -> float:
        """The reference configuration's assembly mode: the sign of (P - B1) x (P - B2)."""
        B1, B2, P = _pts(self.b1, self.b2, self.p)
        return float(np.sign(cross(P - B1, P - B2)))


#: the five-bar of examples/five_bar.yaml: base 3, proximal 2, distal 5/2, P = (0, 4); mode +1
FIVE_BAR = FiveBar(a1=(-1.5, 0.0), a2=(1.5, 0.0), b1=(-1.5, 2.0), b2=(1.5, 2.0), p=(0.0, 4.0))


def five_bar_discriminant(
    theta1: np.ndarray, theta2: np.ndarray, geometry: FiveBar = FIVE_BAR
) -> np.ndarray:
    """16 x (area of the triangle B1 B2 P)^2 by Heron's formula, as a function of the inputs:

        D = ((l1 + l2)^2 - |B1B2|^2) (|B1B2|^2 - (l1 - l2)^2),   l_i = |B_i P|.

    Positive where the distal circles cross (two assembly modes), zero on the Type II locus (distal
    links aligned: the modes merge), negative where the five-bar cannot be assembled; a polynomial in
    the elbows, so signed and continuous over the whole input plane."""
    _, _, l1, l2 = geometry.lengths()
    B1, B2 = geometry.elbows(theta1, theta2)
    d2 = np.sum((B2 - B1) ** 2, axis=-1)
    return ((l1 + l2) ** 2 - d2) * (d2 - (l1 - l2) ** 2)


def five_bar_point(
    theta1: np.ndarray, theta2: np.ndarray, mode: float, geometry: FiveBar = FIVE_BAR
) -> np.ndarray:
    """P (shape (..., 2)) for input joint values theta1, theta2 and assembly mode +-1.

    P is where the circles |P - B_i| = l_i cross: with d = B2 - B1, the foot
    M = B1 + (l1^2 - l2^2 + |d|^2)/(2|d|^2) d and the height h = sqrt(D)/(2|d|) (D of
    :func:`five_bar_discriminant`), P = M + mode h k x d/|d| (k x d = (-d_y, d_x)): mode +1 puts P to
    the left of B1 -> B2. NaN where the five-bar cannot be assembled."""
    _, _, l1, l2 = geometry.lengths()
    B1, B2 = geometry.elbows(theta1, theta2)
    d = B2 - B1
    d2 = np.sum(d * d, axis=-1)
    disc = five_bar_discriminant(theta1, theta2, geometry)
    with np.errstate(invalid="ignore", divide="ignore"):
        h = np.where(disc >= 0, np.sqrt(np.maximum(disc, 0.0)), np.nan) / (2 * np.sqrt(d2))
        m = B1 + ((l1 * l1 - l2 * l2 + d2) / (2 * d2))[..., None] * d
        n = np.stack([-d[..., 1], d[..., 0]], axis=-1) / np.sqrt(d2)[..., None]
    return m + (mode * h)[..., None] * n


def five_bar_type1_det(
    theta1: np.ndarray, theta2: np.ndarray, mode: float, geometry: FiveBar = FIVE_BAR
) -> np.ndarray:
    """prod_i (P - B_i) x (B_i - A_i): zero iff a leg's proximal and distal links are aligned (Type I,
    input singularity).

    The loop equations F_i = |P - B_i(theta_i)|^2 - l_i^2 = 0 differentiate to
    A Pdot + B thetadot = 0 with A = 2 [(P - B1)^T; (P - B2)^T] and, since
    dB_i/dtheta_i = k x (B_i - A_i), B = diag(2 (P - B_i) x (B_i - A_i)). So det B = 4 x this
    product. Signed and continuous (smooth) on each assembly mode; NaN where not assembled."""
    A1, A2 = _pts(geometry.a1, geometry.a2)
    B1, B2 = geometry.elbows(theta1, theta2)
    P = five_bar_point(theta1, theta2, mode, geometry)
    return cross(P - B1, B1 - A1) * cross(P - B2, B2 - A2)


def five_bar_type2_det(
    theta1: np.ndarray, theta2: np.ndarray, mode: float, geometry: FiveBar = FIVE_BAR
) -> np.ndarray:
    """(P - B1) x (P - B2): zero iff the distal links are aligned (Type II, output singularity);
    det A = 4 x this (A of :func:`five_bar_type1_det`).

    It is twice the signed area of B1 B2 P, = mode |d| h = mode sqrt(D)/2 (D of
    :func:`five_bar_discriminant`): it keeps the sign of ``mode`` and reaches zero only on the
    boundary of the assembled region of the input plane (a fold of the inputs), so in the input
    plane its zero set is best found as the sign change of D. NaN where not assembled."""
    B1, B2 = geometry.elbows(theta1, theta2)
    P = five_bar_point(theta1, theta2, mode, geometry)
    return cross(P - B1, P - B2)


# ------------------------------------------------------------------------------------ 3-RPR


@dataclass(frozen=True)
class Rpr3:
    """A planar 3-RPR: base pivots a_i (ground) and platform pivots b_i at the reference."""

    a: tuple[Point, Point, Point]
    b: tuple[Point, Point, Point]

    def centre(self) -> np.ndarray:
        """The platform's reference point: the centroid of its three pivots at the reference."""
        return np.mean(np.asarray(self.b, float), axis=0)

    def platform_pivots(self, x: np.ndarray, y: np.ndarray, phi: np.ndarray) -> np.ndarray:
        """B_i (shape (..., 3, 2)) with the reference point at (x, y) and the platform turned by phi
        (counter-clockwise) from the reference: B_i = (x, y) + Rot(phi)(B_i0 - c0)."""
        x, y, phi = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, y, phi)))
        r = np.asarray(self.b, float) - self.centre()
        c, s = np.cos(phi)[..., None], np.sin(phi)[..., None]
        bx = x[..., None] + c * r[:, 0] - s * r[:, 1]
        by = y[..., None] + s * r[:, 0] + c * r[:, 1]
        return np.stack([bx, by], axis=-1)


#: the 3-RPR of examples/planar_3rpr.yaml (reference point (31/30, 37/30))
RPR3 = Rpr3(
    a=((0.0, 0.0), (4.0, 0.0), (0.0, 4.0)),
    b=((0.9, 0.3), (2.5, 1.5), (-0.3, 1.9)),
)


def rpr3_concurrency_det(
    x: np.ndarray, y: np.ndarray, phi: np.ndarray, geometry: Rpr3 = RPR3, unit: bool = True
) -> np.ndarray:
    """det [u_i,x, u_i,y, A_i x u_i] over the three legs, u_i = B_i - A_i (normalised if ``unit``),
    for the reference point at (x, y) (ground frame, m) and the platform turned by phi (rad) from
    the reference.

    Row i is leg line i in planar line (Pluecker) coordinates (direction, moment about the origin);
    three planar lines are dependent iff they are concurrent or all parallel, the Type II (output)
    singularity of the 3-RPR. With unit u_i it equals det d(rho)/d(x, y, phi) of the leg lengths
    rho_i = |B_i - A_i|: d rho_i/d(x, y) = u_i and d rho_i/d phi = (B_i - p) x u_i, which differs
    from A_i x u_i by p x u_i (B_i - A_i is along u_i), a column operation. With ``unit=False`` it
    is a polynomial of degree 2 in (x, y) at fixed phi (the conic of the Type II locus)."""
    B = geometry.platform_pivots(x, y, phi)
    A = np.asarray(geometry.a, float)
    u = B - A
    if unit:
        u = u / np.linalg.norm(u, axis=-1, keepdims=True)
    m = cross(A, u)
    return np.linalg.det(np.concatenate([u, m[..., None]], axis=-1))


# --------------------------------------------------------------------------------------- UR5

#: the UR5's standard DH lengths (m), as in examples/ur5.yaml
UR5_A2, UR5_A3, UR5_D5 = -0.425, -0.39225, 0.09465


def ur5_det_j(theta: np.ndarray) -> np.ndarray:
    """det J of the UR5 at DH angles theta (..., 6) (the file's joint values):

        det J = -a2 a3 sin(theta3) sin(theta5) (a2 cos(theta2) + a3 cos(theta2 + theta3)
                                                + d5 sin(theta2 + theta3 + theta4)),

    the published closed form (d1, d4, d6 do not appear). J maps joint rates to the end effector's
    (omega, v), angular part first, with v the velocity of any body point, in the base or the tool
    frame: a change of point or frame is a map of determinant 1, so det J is the same for all of
    them (the order (v, omega) swaps three row pairs and flips its sign). Zero at wrist (sin theta5 = 0), elbow (sin theta3 = 0) and
    shoulder (third factor) singularities."""
    t = np.asarray(theta, float)
    t2, t3, t4, t5 = t[..., 1], t[..., 2], t[..., 3], t[..., 4]
    return (
        -UR5_A2
        * UR5_A3
        * np.sin(t3)
        * np.sin(t5)
        * (UR5_A2 * np.cos(t2) + UR5_A3 * np.cos(t2 + t3) + UR5_D5 * np.sin(t2 + t3 + t4))
    )
