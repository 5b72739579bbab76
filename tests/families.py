"""Generated mechanism families for tests/test_singularity_families.py (issue 6).

Every instance is built from its geometry with exact rationals (``fractions.Fraction``, written
as ``"p/q"`` strings that the loader reads exactly) or, where a configuration off a singular one
needs irrational joint values, with closed forms evaluated by mpmath at 60 digits and written
with 40 significant digits (they close to about 1e-40, far below the float and mp:50 closure
tolerances, 1e-12 L and 1e-35 L).  The expected answers are derived here from the geometry, never
from mechsing:

* :func:`changepoint_fourbar`, :func:`parallelogram_fourbar`: planar 4R at the Grashof change
  point, folded flat (all joints collinear) at the reference; configurations off the fold by a
  crank angle phi, the coupler point C from the two circle intersections (one per motion branch),
  and the two branch tangents by a one-sided difference of that closed form at phi = 1e-30;
* :func:`stretched_fourbar`: a + b + c = g, the only configuration is the stretched one;
* :func:`rpr_concurrent`: 3-RPR with the three leg lines through one point O at the reference,
  pushed poses with the legs re-derived (angles by atan2, lengths by norms);
* :func:`bennett`: Bennett linkage from rational tan(alpha/2), tan(beta/2), a (Bennett 1903);
  every configuration from the Bennett relation with rational tan(theta1/2), closure checked
  exactly here;
* :func:`tsai_coplanar`: 3-UPU (Tsai's axis conditions) whose leg constraint couples
  n_i = s_i1 x s_i2 are coplanar at the reference; platform translations off it, the U angles
  from the leg directions in closed form;
* :func:`isosceles_slider_crank`, :func:`degenerate_triangle`: the isosceles
  slider-crank r = l, e = 0 (two branches cross) and the flat 3R triangle a + b = c (rigid);
* :func:`arm_jacobian`: spatial joint screws of UR5 / PUMA 560 from their DH tables (as in the
  example headers), for the serial checks.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction as F

import mpmath
import numpy as np

from tests.reference.se3 import rodrigues_mp, unit

mpmath.mp.dps = 60

# ----------------------------------------------------------------------------- writing numbers


def q(x: F | int) -> str:
    """An exact rational as a quoted YAML string ``"p/q"`` (or ``"p"``)."""
    x = F(x)
    s = str(x.numerator) if x.denominator == 1 else f"{x.numerator}/{x.denominator}"
    return f'"{s}"'


def d(x: mpmath.mpf | float) -> str:
    """A real with 40 significant digits as a quoted decimal (read exactly by the loader)."""
    return '"' + mpmath.nstr(mpmath.mpf(x), 40, min_fixed=-50, max_fixed=50) + '"'


def q_vec(v) -> str:
    """A vector of exact rationals as a YAML list of quoted ``"p/q"`` strings."""
    return "[" + ", ".join(q(x) for x in v) + "]"


def rand_rational(rng: np.random.Generator, lo: int, hi: int, den: int = 6) -> F:
    """A random positive rational num/den with lo <= num/den*? drawn on a small grid."""
    dd = int(rng.integers(1, den + 1))
    return F(int(rng.integers(lo * dd, hi * dd + 1)), dd)


def angle_between(u0, u) -> mpmath.mpf:
    """Signed planar angle from u0 to u."""
    return mpmath.atan2(u0[0] * u[1] - u0[1] * u[0], u0[0] * u[0] + u0[1] * u[1])


def _platform_tail(configs: dict[str, dict[str, str]]) -> list[str]:
    """The end of a three-leg parallel mechanism's file: inputs P1, P2, P3, the platform as
    output, the reference and ``configs`` (name -> {joint: value text})."""
    lines = ["inputs: [P1, P2, P3]", "output: {body: platform}", "configurations:"]
    lines.append("  reference: {}")
    for name, vals in configs.items():
        lines.append(f"  {name}: {{" + ", ".join(f"{k}: {v}" for k, v in vals.items()) + "}")
    return lines


# ----------------------------------------------------------------------------- planar 4R


@dataclass
class FourBar:
    """Planar 4R A(ground-crank) B(crank-coupler) C(coupler-rocker) D(rocker-ground).

    ``g, a, b, c``: ground AD, crank AB, coupler BC, rocker CD; ``signs``: the folded reference
    B = s1 a, C = B + s2 b, D = C + s3 c = g on the x axis.
    """

    g: F
    a: F
    b: F
    c: F
    signs: tuple[int, int, int]
    name: str = "fourbar"

    @property
    def points(self) -> tuple[F, F, F, F]:
        s1, s2, s3 = self.signs
        B = s1 * self.a
        C = B + s2 * self.b
        D = C + s3 * self.c
        assert D == self.g
        return F(0), B, C, D

    def yaml(self, configs: dict[str, dict[str, str]]) -> str:
        A, B, C, D = self.points
        lines = [
            f"mechanism: {self.name}",
            "bodies: [ground, crank, coupler, rocker]",
            "joints:",
            f"  - {{name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [{q(A)}, 0, 0]}}",
            f"  - {{name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [{q(B)}, 0, 0]}}",
            f"  - {{name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [{q(C)}, 0, 0]}}",
            f"  - {{name: D, type: R, between: [rocker, ground], axis: [0, 0, 1], point: [{q(D)}, 0, 0]}}",
            "configurations:",
            "  reference: {}",
        ]
        for name, vals in configs.items():
            lines.append(f"  {name}: {{" + ", ".join(f"{k}: {v}" for k, v in vals.items()) + "}")
        return "\n".join(lines) + "\n"

    def pushed(self, phi: mpmath.mpf, branch: int) -> list[mpmath.mpf]:
        """Joint values (A, B, C, D) with the crank turned by ``phi`` from the fold and C on
        the side ``branch`` (+1/-1) of the line BD (each side is one motion branch)."""
        A0, B0, C0, D0 = (mpmath.mpf(x.numerator) / x.denominator for x in self.points)
        a, b, c = (mpmath.mpf(x.numerator) / x.denominator for x in (self.a, self.b, self.c))
        th0 = 0 if self.signs[0] > 0 else mpmath.pi
        B = (a * mpmath.cos(th0 + phi), a * mpmath.sin(th0 + phi))
        D = (D0, mpmath.mpf(0))
        e = (D[0] - B[0], D[1] - B[1])
        dist = mpmath.sqrt(e[0] ** 2 + e[1] ** 2)
        e = (e[0] / dist, e[1] / dist)
        x = (dist**2 + b**2 - c**2) / (2 * dist)
        h = mpmath.sqrt(b**2 - x**2)
        C = (B[0] + x * e[0] - branch * h * e[1], B[1] + x * e[1] + branch * h * e[0])
        # closure of the two circles, to working precision
        assert abs(mpmath.sqrt((C[0] - B[0]) ** 2 + (C[1] - B[1]) ** 2) - b) < mpmath.mpf(10) ** -50
        assert abs(mpmath.sqrt((C[0] - D[0]) ** 2 + (C[1] - D[1]) ** 2) - c) < mpmath.mpf(10) ** -50
        phi1 = phi
        phi2 = angle_between((C0 - B0, 0), (C[0] - B[0], C[1] - B[1]))
        phi3 = angle_between((C0 - D0, 0), (C[0] - D[0], C[1] - D[1]))
        return [phi1, phi2 - phi1, phi3 - phi2, -phi3]

    def pushed_config(self, phi: mpmath.mpf, branch: int) -> dict[str, str]:
        vals = self.pushed(phi, branch)
        return {k: d(v) for k, v in zip("ABCD", vals, strict=True)}

    def branch_tangents(self) -> list[np.ndarray]:
        """The two branch tangents (A, B, C, D rates) at the fold, from the closed form."""
        out = []
        with mpmath.workdps(150):  # h**2 cancels in the circle intersection
            h = mpmath.mpf(10) ** -40
            for br in (1, -1):
                t = [v / h for v in self.pushed(h, br)]
                out.append(np.array([float(x) for x in t]))
        return out


def _distinct(*xs: F) -> bool:
    return len(set(xs)) == len(xs)


def changepoint_fourbar(rng: np.random.Generator, pairing: int) -> FourBar:
    """A random Grashof change-point four-bar (four distinct lengths, s + l = p + q) with the
    ground paired with the crank (0), the coupler (1) or the rocker (2)."""
    while True:
        g, a, b = (rand_rational(rng, 1, 6) for _ in range(3))
        # g + a = b + c, g + b = a + c, or g + c = a + b; the folded signs solve
        # s1 a + s2 b + s3 c = g
        if pairing == 0:
            c, signs = g + a - b, (-1, 1, 1)
        elif pairing == 1:
            c, signs = g + b - a, (1, -1, 1)
        else:
            c, signs = a + b - g, (1, 1, -1)
        if c <= F(1, 2) or not _distinct(g, a, b, c):
            continue
        fb = FourBar(g, a, b, c, signs, "changepoint-fourbar")
        fb.points  # noqa: B018 -- asserts the fold closes
        return fb


def parallelogram_fourbar(rng: np.random.Generator) -> FourBar:
    """A random parallelogram (a = c, b = g, a != b) at one of its two folds."""
    while True:
        a, g = rand_rational(rng, 1, 5), rand_rational(rng, 1, 6)
        if a == g:
            continue
        signs = (-1, 1, 1) if rng.integers(2) else (1, 1, -1)
        return FourBar(g, a, g, a, signs, "parallelogram")


def stretched_fourbar(rng: np.random.Generator) -> FourBar:
    """A random four-bar with a + b + c = g, at its stretched (only) configuration."""
    a, b, c = (rand_rational(rng, 1, 4) for _ in range(3))
    return FourBar(a + b + c, a, b, c, (1, 1, 1), "stretched-fourbar")


# ----------------------------------------------------------------------------- 3-RPR


def _rot_rational(t: F) -> tuple[F, F]:
    """cos, sin of 2*atan(t)."""
    return (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)


@dataclass
class RPR:
    """3-RPR with leg i: Rb_i at A_i, P_i along B_i - A_i, Rp_i at B_i (reference)."""

    A: list[tuple[F, F]]
    B: list[tuple[F, F]]
    O: tuple[F, F]  # the concurrency point of the three leg lines at the reference

    def yaml(self, configs: dict[str, dict[str, str]]) -> str:
        bodies = ["ground"] + [f"{x}{i}" for i in (1, 2, 3) for x in ("cyl", "pis")] + ["platform"]
        lines = ["mechanism: rpr-concurrent", f"bodies: [{', '.join(bodies)}]", "joints:"]
        for i in range(3):
            (ax, ay), (bx, by) = self.A[i], self.B[i]
            k = i + 1
            lines += [
                f"  - {{name: Rb{k}, type: R, between: [ground, cyl{k}], axis: [0, 0, 1], point: [{q(ax)}, {q(ay)}, 0]}}",
                f"  - {{name: P{k}, type: P, between: [cyl{k}, pis{k}], axis: [{q(bx - ax)}, {q(by - ay)}, 0]}}",
                f"  - {{name: Rp{k}, type: R, between: [pis{k}, platform], axis: [0, 0, 1], point: [{q(bx)}, {q(by)}, 0]}}",
            ]
        return "\n".join(lines + _platform_tail(configs)) + "\n"

    def moved(self, turn: mpmath.mpf, shift: tuple[mpmath.mpf, mpmath.mpf]) -> dict[str, str]:
        """Joint values with the platform turned by ``turn`` about O and moved by ``shift``."""
        O = [mpmath.mpf(x.numerator) / x.denominator for x in self.O]
        c, s = mpmath.cos(turn), mpmath.sin(turn)
        out = {}
        for i in range(3):
            A = [mpmath.mpf(x.numerator) / x.denominator for x in self.A[i]]
            B = [mpmath.mpf(x.numerator) / x.denominator for x in self.B[i]]
            r = (B[0] - O[0], B[1] - O[1])
            Bn = (O[0] + c * r[0] - s * r[1] + shift[0], O[1] + s * r[0] + c * r[1] + shift[1])
            u0 = (B[0] - A[0], B[1] - A[1])
            u = (Bn[0] - A[0], Bn[1] - A[1])
            rb = angle_between(u0, u)
            ln = mpmath.sqrt(u[0] ** 2 + u[1] ** 2) - mpmath.sqrt(u0[0] ** 2 + u0[1] ** 2)
            out[f"Rb{i + 1}"] = d(rb)
            out[f"P{i + 1}"] = d(ln)
            out[f"Rp{i + 1}"] = d(turn - rb)
        return out

    def concurrency(self, turn: mpmath.mpf, shift) -> mpmath.mpf:
        """det of the three leg lines (u_i, B_i x u_i) with unit u_i at the moved pose."""
        O = [mpmath.mpf(x.numerator) / x.denominator for x in self.O]
        c, s = mpmath.cos(turn), mpmath.sin(turn)
        rows = []
        for i in range(3):
            A = [mpmath.mpf(x.numerator) / x.denominator for x in self.A[i]]
            B = [mpmath.mpf(x.numerator) / x.denominator for x in self.B[i]]
            r = (B[0] - O[0], B[1] - O[1])
            Bn = (O[0] + c * r[0] - s * r[1] + shift[0], O[1] + s * r[0] + c * r[1] + shift[1])
            u = (Bn[0] - A[0], Bn[1] - A[1])
            n = mpmath.sqrt(u[0] ** 2 + u[1] ** 2)
            u = (u[0] / n, u[1] / n)
            rows.append([u[0], u[1], Bn[0] * u[1] - Bn[1] * u[0]])
        return mpmath.det(mpmath.matrix(rows))

    def output_motion(self) -> tuple[np.ndarray, np.ndarray]:
        """At the concurrent reference, with P locked: the platform turns about O.  Returns
        (joint rates per file order for omega = 1, platform twist (w, v) at the origin)."""
        rates = []
        for i in range(3):
            A, B = self.A[i], self.B[i]
            u = (B[0] - A[0], B[1] - A[1])
            w = (B[0] - self.O[0], B[1] - self.O[1])
            # B moves with omega x (B - O), normal to the leg; the leg turns about A at
            # |B - O| / |B - A| (signed: B - O = s (B - A))
            s = (w[0] * u[0] + w[1] * u[1]) / (u[0] ** 2 + u[1] ** 2)
            rates += [float(s), 0.0, float(1 - s)]
        Ox, Oy = float(self.O[0]), float(self.O[1])
        return np.array(rates), np.array([0.0, 0.0, 1.0, Oy, -Ox, 0.0])


def rpr_concurrent(rng: np.random.Generator) -> RPR:
    """Random platform triangle and pose, concurrency point O; A_i = O + mu_i (B_i - O)."""
    while True:
        O = (rand_rational(rng, -2, 2), rand_rational(rng, -2, 2))
        cz, sz = _rot_rational(rand_rational(rng, -1, 1, 4))
        p = (rand_rational(rng, -1, 1), rand_rational(rng, -1, 1))
        local = [(rand_rational(rng, -2, 2), rand_rational(rng, -2, 2)) for _ in range(3)]
        B = [(cz * x - sz * y + p[0], sz * x + cz * y + p[1]) for x, y in local]
        mus = [F(int(rng.choice([-3, -2, 2, 3, 4])), int(rng.integers(1, 3))) for _ in range(3)]
        A = [
            (O[0] + m * (b[0] - O[0]), O[1] + m * (b[1] - O[1]))
            for m, b in zip(mus, B, strict=True)
        ]
        # a proper triangle, legs of useful length, B_i away from O, legs not all parallel
        area = (B[1][0] - B[0][0]) * (B[2][1] - B[0][1]) - (B[1][1] - B[0][1]) * (B[2][0] - B[0][0])
        if abs(area) < 1:
            continue
        if any((b[0] - O[0]) ** 2 + (b[1] - O[1]) ** 2 < F(1, 4) for b in B):
            continue
        if any(m == 1 for m in mus):
            continue
        return RPR(A, B, O)


# ----------------------------------------------------------------------------- Bennett


def _mat_mul(X, Y):
    return [[sum(X[i][k] * Y[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def _dh(ct: F, st: F, a: F, ca: F, sa: F):
    """Rz(theta) Tx(a) Rx(alpha), exact."""
    return [
        [ct, -st * ca, st * sa, a * ct],
        [st, ct * ca, -ct * sa, a * st],
        [F(0), sa, ca, F(0)],
        [F(0), F(0), F(0), F(1)],
    ]


@dataclass
class Bennett:
    """a1 = a3 = a, a2 = a4 = b, alpha1 = alpha3 = alpha, alpha2 = alpha4 = beta, d_i = 0;
    ``ta, tb``: tan(alpha/2), tan(beta/2); ``t1``: tan(theta1/2) at the reference."""

    ta: F
    tb: F
    a: F
    t1: F
    axes: list[tuple[F, F, F]] = field(default_factory=list)
    points: list[tuple[F, F, F]] = field(default_factory=list)

    @property
    def b(self) -> F:
        sa = 2 * self.ta / (1 + self.ta**2)
        sb = 2 * self.tb / (1 + self.tb**2)
        return self.a * sb / sa

    @property
    def K(self) -> F:
        """tan(theta1/2) tan(theta2/2) = sin((beta+alpha)/2)/sin((beta-alpha)/2)."""
        return (self.tb + self.ta) / (self.tb - self.ta)

    def frames(self, t1: F):
        """The four DH frames at tan(theta1/2) = t1 (theta3 = -theta1, theta4 = -theta2)."""
        t2 = self.K / t1
        ca, sa = _rot_rational(self.ta)
        cb, sb = _rot_rational(self.tb)
        c1, s1 = _rot_rational(t1)
        c2, s2 = _rot_rational(t2)
        Ts = [
            _dh(c1, s1, self.a, ca, sa),
            _dh(c2, s2, self.b, cb, sb),
            _dh(c1, -s1, self.a, ca, sa),
            _dh(c2, -s2, self.b, cb, sb),
        ]
        frames = [[[F(int(i == j)) for j in range(4)] for i in range(4)]]
        for T in Ts:
            frames.append(_mat_mul(frames[-1], T))
        return frames

    def build(self) -> Bennett:
        fr = self.frames(self.t1)
        ident = [[F(int(i == j)) for j in range(4)] for i in range(4)]
        assert fr[4] == ident, "the Bennett relation must close the loop exactly"
        self.axes = [tuple(fr[i][r][2] for r in range(3)) for i in range(4)]
        self.points = [tuple(fr[i][r][3] for r in range(3)) for i in range(4)]
        return self

    def closes(self, t1: F) -> bool:
        fr = self.frames(t1)
        return fr[4] == [[F(int(i == j)) for j in range(4)] for i in range(4)]

    def config(self, t1: F) -> dict[str, str]:
        """Exact joint values (relative to the reference) at tan(theta1/2) = t1."""
        t2, r2 = self.K / t1, self.K / self.t1

        def at(x: F) -> str:
            return f"atan({x.numerator}/{x.denominator})"

        j1 = f"2*{at(t1)} - 2*{at(self.t1)}"
        j2 = f"2*{at(t2)} - 2*{at(r2)}"
        return {"J1": f'"{j1}"', "J2": f'"{j2}"', "J3": f'"-({j1})"', "J4": f'"-({j2})"'}

    def yaml(self, configs: dict[str, dict[str, str]]) -> str:
        lines = [
            "mechanism: bennett-family",
            "bodies: [ground, link1, link2, link3]",
            "joints:",
        ]
        between = [("ground", "link1"), ("link1", "link2"), ("link2", "link3"), ("link3", "ground")]
        for i in range(4):
            lines.append(
                f"  - {{name: J{i + 1}, type: R, between: [{between[i][0]}, {between[i][1]}], "
                f"axis: {q_vec(self.axes[i])}, point: {q_vec(self.points[i])}}}"
            )
        lines += ["inputs: [J1]", "output: {body: link2}", "configurations:", "  reference: {}"]
        for name, vals in configs.items():
            lines.append(f"  {name}: {{" + ", ".join(f"{k}: {v}" for k, v in vals.items()) + "}")
        return "\n".join(lines) + "\n"


def bennett(rng: np.random.Generator) -> Bennett:
    while True:
        ta = F(int(rng.integers(1, 6)), int(rng.integers(2, 9)))
        tb = F(int(rng.integers(1, 9)), int(rng.integers(2, 9)))
        if not (0 < ta < 1 and 0 < tb < 1) or ta == tb:
            continue
        a = F(int(rng.integers(1, 7)), int(rng.integers(1, 4)))
        t1 = F(int(rng.integers(1, 7)), int(rng.integers(1, 7)))
        return Bennett(ta, tb, a, t1).build()


# ----------------------------------------------------------------------------- Tsai 3-UPU


def _dot(u, v):
    return sum(x * y for x, y in zip(u, v, strict=True))


@dataclass
class Tsai:
    """3-UPU with Tsai's axis conditions: U_ia axes [s1, s2] at A_i, P along l_i = B_i - A_i,
    U_ib axes [s2, s1] at B_i; s2 = n x s1 with n = s1 x s2 / |s1|^2 (the leg's constraint
    couple direction) and l_i in span(s1, n)."""

    A: list[tuple[F, F, F]]
    l: list[tuple[F, F, F]]
    s1: list[tuple[F, F, F]]
    n: list[tuple[F, F, F]]
    m: tuple[F, F, F]  # normal of the plane of the n_i

    def s2(self, i: int):
        return tuple(np.cross(self.n[i], self.s1[i]))

    def yaml(self, configs: dict[str, dict[str, str]]) -> str:
        bodies = ["ground"] + [f"{x}{i}" for i in (1, 2, 3) for x in ("cyl", "pis")] + ["platform"]
        lines = ["mechanism: tsai-coplanar", f"bodies: [{', '.join(bodies)}]", "joints:"]
        for i in range(3):
            k = i + 1
            A = self.A[i]
            B = tuple(a + x for a, x in zip(A, self.l[i], strict=True))
            s1, s2 = self.s1[i], self.s2(i)
            lines += [
                f"  - {{name: U{k}a, type: U, between: [ground, cyl{k}], axes: [{q_vec(s1)}, {q_vec(s2)}], point: {q_vec(A)}}}",
                f"  - {{name: P{k}, type: P, between: [cyl{k}, pis{k}], axis: {q_vec(self.l[i])}}}",
                f"  - {{name: U{k}b, type: U, between: [pis{k}, platform], axes: [{q_vec(s2)}, {q_vec(s1)}], point: {q_vec(B)}}}",
            ]
        return "\n".join(lines + _platform_tail(configs)) + "\n"

    def _leg(self, i: int, shift):
        """U angles and stroke of leg i with the platform translated by ``shift``."""
        mp = [
            [mpmath.mpf(x.numerator) / x.denominator for x in v]
            for v in (self.s1[i], self.n[i], self.l[i])
        ]
        s1, n, l0 = mp
        e1, e2 = list(unit(np.array(s1))), list(unit(np.array(n)))
        e3 = list(np.cross(e1, e2))
        l1 = [a + b for a, b in zip(l0, shift, strict=True)]
        L0 = mpmath.sqrt(sum(x * x for x in l0))
        L1 = mpmath.sqrt(sum(x * x for x in l1))
        gamma = mpmath.atan2(
            sum(a * b for a, b in zip(l0, e2, strict=True)),
            sum(a * b for a, b in zip(l0, e1, strict=True)),
        )
        c1, c2, c3 = (sum(a * b for a, b in zip(l1, e, strict=True)) / L1 for e in (e1, e2, e3))
        sig = 1 if mpmath.sin(gamma) > 0 else -1
        rr = mpmath.sqrt(c2**2 + c3**2)
        gamma1 = mpmath.atan2(sig * rr, c1)
        q1 = mpmath.atan2(sig * c3, sig * c2)
        q2 = gamma - gamma1  # rotation about s2 = n x s1 = -e3 turns (e1, e2) by -q2
        return q1, q2, L1 - L0, (e1, e2, e3)

    def translated(self, shift) -> dict[str, str]:
        out = {}
        for i in range(3):
            q1, q2, p, _ = self._leg(i, shift)
            k = i + 1
            out[f"U{k}a"] = f"[{d(q1)}, {d(q2)}]"
            out[f"P{k}"] = d(p)
            out[f"U{k}b"] = f"[{d(-q2)}, {d(-q1)}]"
        return out

    def check_leg(self, i: int, shift) -> mpmath.mpf:
        """Closure check of the closed form: |R_cyl l_hat - l_hat'| with R_cyl = Rot(s1, q1) Rot(s2, q2)."""
        q1, q2, _, (e1, e2, e3) = self._leg(i, shift)
        s2 = [-x for x in e3]
        R = mpmath.matrix((rodrigues_mp(e1, q1) @ rodrigues_mp(s2, q2)).tolist())
        l0 = mpmath.matrix([mpmath.mpf(x.numerator) / x.denominator for x in self.l[i]])
        l1 = l0 + mpmath.matrix(list(shift))
        return mpmath.norm(R * (l0 / mpmath.norm(l0)) - l1 / mpmath.norm(l1))

    def constraint_det(self, shift) -> mpmath.mpf:
        """det[n1' n2' n3'] (unit couples s1 x R_cyl s2) with the platform translated."""
        cols = []
        for i in range(3):
            q1, q2, _, (e1, e2, e3) = self._leg(i, shift)
            s2 = [-x for x in e3]
            R = rodrigues_mp(e1, q1) @ rodrigues_mp(s2, q2)
            cols.append(list(np.cross(e1, R @ np.array(s2))))
        return mpmath.det(mpmath.matrix(cols))


def tsai_coplanar(rng: np.random.Generator) -> Tsai:
    """Random 3-UPU whose three constraint couples lie in one plane (normal m) at the reference."""

    def rv(lo=-2, hi=2):
        return tuple(F(int(rng.integers(lo, hi + 1))) for _ in range(3))

    while True:
        m = rv()
        if _dot(m, m) == 0:
            continue
        A, ls, s1s, ns = [], [], [], []
        ok = True
        for k in range(3):
            # n_k in the plane normal to m, s1_k normal to n_k, leg l_k = alpha s1 + beta n
            n = tuple(np.cross(m, rv()))
            s1 = tuple(np.cross(n, rv()))
            if _dot(n, n) == 0 or _dot(s1, s1) == 0:
                ok = False
                break
            al = F(int(rng.choice([-2, -1, 1, 2])), int(rng.integers(1, 4)))
            be = F(int(rng.choice([-2, -1, 1, 2])), int(rng.integers(1, 4)))
            l = tuple(al * x + be * y for x, y in zip(s1, n, strict=True))
            ns.append(n)
            s1s.append(s1)
            ls.append(l)
            angle = 2 * F(k, 3)  # base points spread around, rational coordinates
            A.append((F(2) * (1 - angle), F(2) * (angle * angle - 1), F(int(rng.integers(-1, 2)))))
        if not ok:
            continue
        # the n_i span the plane (rank 2): the constraint system generically has rank 3 and
        # here exactly 2
        M = [list(n) for n in ns]
        det = (
            M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
            - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
            + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])
        )
        assert det == 0
        if not any(np.cross(ns[0], ns[1])) and not any(np.cross(ns[0], ns[2])):
            continue
        if any(not any(np.cross(ns[i], ns[j])) for i in range(3) for j in range(i)):
            continue
        return Tsai(A, ls, s1s, ns, m)


# ------------------------------------------------------------ isosceles slider-crank, flat triangle


def isosceles_slider_crank(r: F) -> str:
    """r = l, e = 0, crank at 90 deg: B = (0, r), the slider pin C at the crank pivot A."""
    return (
        "\n".join(
            [
                "mechanism: isosceles-slider-crank",
                "bodies: [ground, crank, rod, slider]",
                "joints:",
                "  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}",
                f"  - {{name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [0, {q(r)}, 0]}}",
                "  - {name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: [0, 0, 0]}",
                "  - {name: P, type: P, between: [ground, slider], axis: [1, 0, 0]}",
                "configurations:",
                "  reference: {}",
            ]
        )
        + "\n"
    )


def degenerate_triangle(a: F, b: F) -> str:
    """3R triangle with sides a, b, c = a + b, flat at the reference."""
    return (
        "\n".join(
            [
                "mechanism: degenerate-triangle",
                "bodies: [ground, link1, link2]",
                "joints:",
                "  - {name: A, type: R, between: [ground, link1], axis: [0, 0, 1], point: [0, 0, 0]}",
                f"  - {{name: B, type: R, between: [link1, link2], axis: [0, 0, 1], point: [{q(a)}, 0, 0]}}",
                f"  - {{name: C, type: R, between: [link2, ground], axis: [0, 0, 1], point: [{q(a + b)}, 0, 0]}}",
                "configurations:",
                "  reference: {}",
            ]
        )
        + "\n"
    )


# ----------------------------------------------------------------------------- serial arms


def _rz(t):
    c, s = mpmath.cos(t), mpmath.sin(t)
    return mpmath.matrix([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def _rx(t):
    c, s = mpmath.cos(t), mpmath.sin(t)
    return mpmath.matrix([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])


def _tz(x):
    T = mpmath.eye(4)
    T[2, 3] = x
    return T


def _tx(x):
    T = mpmath.eye(4)
    T[0, 3] = x
    return T


UR5_DH = {
    "alpha": [mpmath.pi / 2, 0, 0, mpmath.pi / 2, -mpmath.pi / 2, 0],
    "a": [0, mpmath.mpf("-0.425"), mpmath.mpf("-0.39225"), 0, 0, 0],
    "d": [
        mpmath.mpf("0.089159"),
        0,
        0,
        mpmath.mpf("0.10915"),
        mpmath.mpf("0.09465"),
        mpmath.mpf("0.0823"),
    ],
}
PUMA_DH = {
    "alpha": [0, -mpmath.pi / 2, 0, -mpmath.pi / 2, mpmath.pi / 2, -mpmath.pi / 2],
    "a": [0, 0, mpmath.mpf("0.4318"), mpmath.mpf("0.0203"), 0, 0],
    "d": [0, 0, mpmath.mpf("0.15005"), mpmath.mpf("0.4318"), 0, 0],
}


def arm_screws(arm: str, theta) -> mpmath.matrix:
    """Spatial joint twists (w, p x w) (6 x 6, columns) at DH angles ``theta``.

    UR5 (standard DH, T_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)): joint i's axis is z of
    frame i-1.  PUMA 560 (Craig, T_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)): joint
    i's axis is z of frame i.
    """
    J = mpmath.matrix(6, 6)
    T = mpmath.eye(4)
    for i in range(6):
        if arm == "ur5":
            z = [T[r, 2] for r in range(3)]
            p = [T[r, 3] for r in range(3)]
            dh = UR5_DH
            T = T * _rz(theta[i]) * _tz(dh["d"][i]) * _tx(dh["a"][i]) * _rx(dh["alpha"][i])
        else:
            dh = PUMA_DH
            T = T * _rx(dh["alpha"][i]) * _tx(dh["a"][i]) * _rz(theta[i]) * _tz(dh["d"][i])
            z = [T[r, 2] for r in range(3)]
            p = [T[r, 3] for r in range(3)]
        v = [p[1] * z[2] - p[2] * z[1], p[2] * z[0] - p[0] * z[2], p[0] * z[1] - p[1] * z[0]]
        for r in range(3):
            J[r, i] = z[r]
            J[r + 3, i] = v[r]
    return J


def arm_factors(arm: str, th) -> dict[str, mpmath.mpf]:
    """The factors of det J (the example headers: UR5 from UR's DH table, PUMA 560 Craig's)."""
    if arm == "ur5":
        a2, a3, d5 = UR5_DH["a"][1], UR5_DH["a"][2], UR5_DH["d"][4]
        return {
            "wrist": mpmath.sin(th[4]),
            "elbow": mpmath.sin(th[2]),
            "shoulder": a2 * mpmath.cos(th[1])
            + a3 * mpmath.cos(th[1] + th[2])
            + d5 * mpmath.sin(th[1] + th[2] + th[3]),
        }
    a2, a3, d4 = PUMA_DH["a"][2], PUMA_DH["a"][3], PUMA_DH["d"][3]
    return {
        "wrist": mpmath.sin(th[4]),
        "elbow": a3 * mpmath.sin(th[2]) + d4 * mpmath.cos(th[2]),
        "shoulder": a2 * mpmath.cos(th[1])
        + a3 * mpmath.cos(th[1] + th[2])
        - d4 * mpmath.sin(th[1] + th[2]),
    }


def arm_on_factor(arm: str, factor: str, th) -> list[mpmath.mpf]:
    """``th`` with one joint solved so that ``factor`` vanishes."""
    th = [mpmath.mpf(x) for x in th]
    if factor == "wrist":
        th[4] = mpmath.mpf(0)
    elif arm == "ur5" and factor == "elbow":
        th[2] = mpmath.mpf(0)
    elif arm == "ur5":  # a2 c2 + a3 c23 + d5 s234 = 0, solved for theta2
        a2, a3, d5 = UR5_DH["a"][1], UR5_DH["a"][2], UR5_DH["d"][4]
        c3, s3 = mpmath.cos(th[2]), mpmath.sin(th[2])
        c34, s34 = mpmath.cos(th[2] + th[3]), mpmath.sin(th[2] + th[3])
        th[1] = mpmath.atan2(-(a2 + a3 * c3 + d5 * s34), -a3 * s3 + d5 * c34)
    elif factor == "elbow":  # a3 s3 + d4 c3 = 0
        a3, d4 = PUMA_DH["a"][3], PUMA_DH["d"][3]
        th[2] = -mpmath.atan(d4 / a3)
    else:  # a2 c2 + a3 c23 - d4 s23 = 0, solved for theta2
        a2, a3, d4 = PUMA_DH["a"][2], PUMA_DH["a"][3], PUMA_DH["d"][3]
        c3, s3 = mpmath.cos(th[2]), mpmath.sin(th[2])
        th[1] = mpmath.atan2(a2 + a3 * c3 - d4 * s3, a3 * s3 + d4 * c3)
    f = arm_factors(arm, th)[factor]
    assert abs(f) < mpmath.mpf(10) ** -45
    return th


def kernel_vector(J: mpmath.matrix) -> np.ndarray:
    """The (corank-1) kernel vector of J at 60 digits, largest entry 1, first non-zero positive."""
    U, S, V = mpmath.svd_r(J)
    assert S[5] < mpmath.mpf(10) ** -40 * S[0] and S[4] > mpmath.mpf(10) ** -3 * S[0]
    x = [V[5, j] for j in range(6)]
    big = max(abs(v) for v in x)
    x = [v / big for v in x]
    first = next(v for v in x if abs(v) > mpmath.mpf(10) ** -9)
    if first < 0:
        x = [-v for v in x]
    return np.array([float(v) for v in x])
