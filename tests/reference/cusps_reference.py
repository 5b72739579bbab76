"""Cusps computed independently of mechsing (imports nothing from it; sympy and numpy).

A cusp of a section is a cusp of a map ``F: (u, v) -> (a, b)`` from two unknowns of the
mechanism to the two varied coordinates (Whitney's cusp): the Jacobian's determinant
``d = det dF`` vanishes and its derivative along the kernel of ``dF`` does too,
``g = grad(d) . (-dF[0, 1], dF[0, 0]) = 0``.  That square system is solved by Newton
from every point of a grid over the unknowns, the distinct real roots kept and mapped
by ``F``.  No eliminant, no discriminant: the mechanism's own forward formulas.

* :func:`rpr_cusps` -- a 3-RPR with the first leg's length fixed: the unknowns are the
  first leg's angle ``phi`` and the platform angle ``theta``; ``F`` gives the other two
  legs' lengths (Zein, Wenger & Chablat, Mech. Mach. Theory 43, 2008, take this view).
* :func:`arm_cusps` -- a positional 3R arm in Denavit-Hartenberg form: the unknowns are
  joints 2 and 3; ``F`` gives ``(rho, z)`` of the end point about the first axis.
* :func:`ik_quartic` -- the arm's inverse kinematics as one polynomial in tan(q3/2) by
  a resultant, and :func:`triple_root_residual` its triple-root test.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import sympy


def _cusp_system(F: Sequence[sympy.Expr], u: sympy.Symbol, v: sympy.Symbol) -> Callable:
    J = sympy.Matrix([[sympy.diff(f, w) for w in (u, v)] for f in F])
    d = sympy.expand(J.det())
    g = sympy.diff(d, u) * (-J[0, 1]) + sympy.diff(d, v) * J[0, 0]
    system = [d, g]
    jac = [[sympy.diff(e, w) for w in (u, v)] for e in system]
    f = sympy.lambdify((u, v), system, "numpy")
    fj = sympy.lambdify((u, v), jac, "numpy")
    out = sympy.lambdify((u, v), list(F), "numpy")
    # the same condition with the kernel from the second row: where the first row
    # vanishes (a rank-0 row, not a cusp) g is zero for nothing, this one is not
    g2 = sympy.diff(d, u) * (-J[1, 1]) + sympy.diff(d, v) * J[1, 0]
    check = sympy.lambdify((u, v), [g2, J[0, 0], J[0, 1], J[1, 0], J[1, 1]], "numpy")

    def f_checked(*z: float) -> list[float]:
        return f(*z)

    f_checked.check = check  # type: ignore[attr-defined]
    return f_checked, fj, out


def _solve_on_torus(f: Callable, fj: Callable, n: int) -> list[np.ndarray]:
    roots: list[np.ndarray] = []
    grid = np.linspace(-np.pi, np.pi, n, endpoint=False)
    for u0 in grid:
        for v0 in grid:
            z = np.array([u0, v0])
            for _ in range(30):
                r = np.array(f(*z), dtype=float)
                J = np.array(fj(*z), dtype=float)
                try:
                    step = np.linalg.solve(J, r)
                except np.linalg.LinAlgError:
                    break
                z = z - step
                if np.max(np.abs(step)) < 1e-14:
                    break
            r = np.array(f(*z), dtype=float)
            if not (np.all(np.isfinite(z)) and np.max(np.abs(r)) < 1e-8):
                continue
            g2, *rows = (float(x) for x in f.check(*z))
            if min(np.hypot(rows[0], rows[1]), np.hypot(rows[2], rows[3])) < 1e-9 * max(
                1.0, *map(abs, rows)
            ) or abs(g2) > 1e-6 * max(1.0, np.max(np.abs(rows)) ** 3):
                continue  # a row of dF vanishes: its kernel is the plane, not a cusp
            if True:
                z = (z + np.pi) % (2 * np.pi) - np.pi
                if not any(np.max(np.abs(np.angle(np.exp(1j * (z - w))))) < 1e-7 for w in roots):
                    roots.append(z)
    return roots


def rpr_cusps(
    base: Sequence[Sequence[float]],
    platform: Sequence[Sequence[float]],
    rho1: float,
    box: tuple[tuple[float, float], tuple[float, float]],
    n: int = 40,
) -> list[tuple[float, float, float]]:
    """The cusps (rho2, rho3, theta) of a 3-RPR's section rho1 fixed, in ``box``:
    ``base`` the points A_i, ``platform`` the points b_i in the platform's frame."""
    phi, th = sympy.symbols("phi theta", real=True)
    A = [sympy.Matrix([sympy.nsimplify(x) for x in p]) for p in base]
    b = [sympy.Matrix([sympy.nsimplify(x) for x in p]) for p in platform]
    R = sympy.Matrix([[sympy.cos(th), -sympy.sin(th)], [sympy.sin(th), sympy.cos(th)]])
    B1 = A[0] + sympy.nsimplify(rho1) * sympy.Matrix([sympy.cos(phi), sympy.sin(phi)])
    F = []
    for i in (1, 2):
        Bi = B1 + R * (b[i] - b[0])
        F.append(sympy.expand((Bi - A[i]).dot(Bi - A[i])))  # rho_i^2: same cusps where rho_i > 0
    f, fj, out = _cusp_system(F, phi, th)
    found = []
    for z in _solve_on_torus(f, fj, n):
        sq = np.array(out(*z), dtype=float)
        if np.min(sq) <= 0:
            continue
        r2, r3 = np.sqrt(sq)
        if box[0][0] <= r2 <= box[0][1] and box[1][0] <= r3 <= box[1][1] and min(r2, r3) > 1e-6:
            found.append((float(r2), float(r3), float(z[1])))
    return sorted(found)


def _dh(a: float, alpha: float, d: float, q: sympy.Expr) -> sympy.Matrix:
    """A modified (Craig) Denavit-Hartenberg transform."""
    ca, sa = sympy.cos(alpha), sympy.sin(alpha)
    cq, sq = sympy.cos(q), sympy.sin(q)
    return sympy.Matrix(
        [
            [cq, -sq, 0, a],
            [sq * ca, cq * ca, -sa, -sa * d],
            [sq * sa, cq * sa, ca, ca * d],
            [0, 0, 0, 1],
        ]
    )


def arm_point(dh: Sequence[tuple], tool: Sequence, qs: Sequence[sympy.Expr]) -> sympy.Matrix:
    """The end point of an arm: ``dh`` rows (a, alpha, d) of modified DH, ``tool`` the
    point in the last frame."""
    T = sympy.eye(4)
    for (a, alpha, d), q in zip(dh, qs, strict=True):
        T = T * _dh(sympy.nsimplify(a), alpha, sympy.nsimplify(d), q)
    return (T * sympy.Matrix([*(sympy.nsimplify(x) for x in tool), 1]))[:3, 0]


def arm_cusps(
    dh: Sequence[tuple],
    tool: Sequence,
    box: tuple[tuple[float, float], tuple[float, float]],
    n: int = 36,
) -> list[tuple[float, float]]:
    """The cusps (rho, z) of a positional 3R arm's workspace section in ``box``."""
    q1, q2, q3 = sympy.symbols("q1 q2 q3", real=True)
    p = arm_point(dh, tool, (q1, q2, q3))
    p = p.subs(q1, 0)
    F = [sympy.expand(p[0] ** 2 + p[1] ** 2), sympy.expand(p[2])]  # rho^2 and z
    f, fj, out = _cusp_system(F, q2, q3)
    found = []
    for z in _solve_on_torus(f, fj, n):
        r2, zz = np.array(out(*z), dtype=float)
        rho = np.sqrt(max(r2, 0.0))
        if rho > 1e-6 and box[0][0] <= rho <= box[0][1] and box[1][0] <= zz <= box[1][1]:
            if not any(abs(rho - r) < 1e-7 and abs(zz - w) < 1e-7 for r, w in found):
                found.append((float(rho), float(zz)))
    return sorted(found)


def ik_quartic(dh: Sequence[tuple], tool: Sequence) -> tuple[sympy.Expr, sympy.Symbol, tuple]:
    """The arm's inverse kinematics as one polynomial in t3 = tan(q3/2) with the target
    (rho, z) as symbols: the resultant in t2 = tan(q2/2) of the equations of rho^2 + z^2
    and z, cleared of denominators and of its factors free of the target."""
    q2, q3 = sympy.symbols("q2 q3", real=True)
    t2, t3, rho, zt = sympy.symbols("t2 t3 rho z", real=True)
    p = arm_point(dh, tool, (sympy.S.Zero, q2, q3))
    eqs = [sympy.expand(p.dot(p)) - rho**2 - zt**2, sympy.expand(p[2]) - zt]
    half = {
        sympy.cos(q2): (1 - t2**2) / (1 + t2**2),
        sympy.sin(q2): 2 * t2 / (1 + t2**2),
        sympy.cos(q3): (1 - t3**2) / (1 + t3**2),
        sympy.sin(q3): 2 * t3 / (1 + t3**2),
    }
    polys = [sympy.numer(sympy.together(sympy.expand(e).subs(half))) for e in eqs]
    res = sympy.resultant(polys[0], polys[1], t2)
    keep = sympy.S.One
    for fac, mult in sympy.factor_list(res)[1]:
        if fac.has(rho) or fac.has(zt):
            keep *= fac**mult
    return sympy.expand(keep), t3, (rho, zt)


def triple_root_residual(
    quartic: sympy.Expr, t3: sympy.Symbol, target: tuple, rho: float, z: float
) -> tuple[float, float]:
    """At the target (rho, z): the smallest ``max(|Q|, |Q'|, |Q''|) / max|coeff|`` over the
    real roots of Q'' (a triple root makes it zero), and that root (q3 = 2 atan t3)."""
    Q = sympy.Poly(
        quartic.subs({target[0]: sympy.nsimplify(rho), target[1]: sympy.nsimplify(z)}), t3
    )
    c = np.array([float(x) for x in Q.all_coeffs()])
    c = c / np.max(np.abs(c))
    d1, d2 = np.polyder(c), np.polyder(c, 2)
    best = (np.inf, np.nan)
    for r in np.roots(d2):
        if abs(r.imag) < 1e-6:
            x = r.real
            v = max(abs(np.polyval(c, x)), abs(np.polyval(d1, x)))
            best = min(best, (v, 2 * np.arctan(x)))
    return best
