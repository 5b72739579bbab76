"""Exact mode in the number field of the data (issue 17, "Exact mode").

An exact configuration's poses, current screws and chord residuals are computed in the
algebraic number field K that its geometry and the cosines and sines of its angles
generate (:class:`mechsing.kinematics.field.FieldKinematics`).  What is checked, and where
the expected answers come from:

* the field: QQ for rational data and angles ``2*atan(rational)`` (cos = (1 - t^2)/(1 + t^2),
  sin = 2t/(1 + t^2)); Q(sqrt 3) for ``acos(13/14)`` (sin = sqrt(1 - 169/196) = 3 sqrt(3)/14);
  Q(sqrt 2, sqrt 5) of degree 4 (its four embeddings +-sqrt 2, +-sqrt 5);
* closure: Bennett configurations from the closed form of its motion (the example's header:
  tan(theta1/2) tan(theta2/2) = 13/5, theta3 = -theta1, theta4 = -theta2, values relative to the
  reference theta1 = 2 atan(1/2), theta2 = 2 atan(26/5)) close exactly (residual zero in K) and
  have closure rank 3 (Bennett 1903: rank 3 at every configuration); one angle moved off the
  closed form leaves a non-zero residual, and the configuration is refused;
* the field path agrees with the sympy path (poses, current screws) number by number;
* published ranks: a planar four-bar (the double rocker, data in Q(sqrt 3, sqrt 15), degree 4)
  closes with loop rank 3 in G; the 3-RPR's concurrent configuration is output (type II)
  singular (its header: the three leg lines meet in one point);
* an S joint's rotation vector (angle and unit axis in radicals) in the field, equal to the
  sympy path;
* fallback: an H joint (translation pitch * angle, not algebraic) keeps the sympy path and
  gives the same verdict.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy

import mechsing
from mechsing.kinematics import forward
from mechsing.kinematics.given import GivenValues
from mechsing.kinematics.model import KinematicModel
from mechsing.model.loader import load
from mechsing.numeric.field import (
    cos_sin,
    field_echelon,
    field_null_space,
    field_row_space,
    field_solve,
    number_field,
)
from tests.mechanisms import EXAMPLES, by_name, classes, write


def _degree(K: object) -> int:
    return 1 if K.is_QQ else int(K.mod.degree())  # type: ignore[attr-defined]


def _configuration(path: Path, name: str) -> tuple[KinematicModel, np.ndarray]:
    mech = load(path)
    model = KinematicModel(mech, "exact")
    q = GivenValues(model).of(mech.configurations[name]).target
    return model, q


# ============================================================================ the field


def test_rational_angles_give_qq() -> None:
    c, s = cos_sin(sympy.S("2*atan(1/3)"))
    assert (c, s) == (sympy.Rational(4, 5), sympy.Rational(3, 5))
    K, els = number_field([c, s, sympy.Rational(-156, 701)])
    assert K.is_QQ and [K.to_sympy(e) for e in els] == [c, s, sympy.Rational(-156, 701)]


def test_acos_angle_gives_q_sqrt3() -> None:
    c, s = cos_sin(sympy.acos(sympy.Rational(13, 14)))
    assert c == sympy.Rational(13, 14)
    assert sympy.simplify(s - 3 * sympy.sqrt(3) / 14) == 0
    K, _els = number_field([c, s])
    assert _degree(K) == 2
    K.from_sympy(sympy.sqrt(3))  # sqrt(3) is in K (raises otherwise)


def test_two_square_roots_give_degree_four() -> None:
    K, els = number_field([sympy.sqrt(2), sympy.sqrt(5), sympy.Rational(1, 3)])
    assert _degree(K) == 4
    # exact arithmetic: (sqrt 2)^2 = 2, sqrt 2 sqrt 5 = sqrt 10
    assert els[0] * els[0] == K.from_sympy(sympy.Integer(2))
    assert sympy.simplify(K.to_sympy(els[0] * els[1]) - sympy.sqrt(10)) == 0


@pytest.mark.parametrize("angle", ["1", "pi/7", "pi*sqrt(2)"])
def test_angles_without_radical_sines_have_no_field(angle: str) -> None:
    assert cos_sin(sympy.S(angle)) is None


def test_field_spaces_are_those_of_the_matrix() -> None:
    """Null and row spaces over Q(sqrt 2): A N^T = 0, and the rows span A's rows (same rank)."""
    r2 = sympy.sqrt(2)
    A = np.array([[1, r2, 0], [r2, 2, 0], [0, 0, 1]], dtype=object)  # rank 2: row 2 = sqrt2 row 1
    N = field_null_space(A)
    assert N.shape == (1, 3)
    assert all(sympy.simplify(x) == 0 for x in (sympy.Matrix(A) * sympy.Matrix(N).T))
    R = field_row_space(A)
    assert R.shape == (2, 3)
    assert sympy.Matrix(np.concatenate([A, R]).tolist()).rank(simplify=True) == 2


def test_field_echelon_is_sympys() -> None:
    """The pivots, pivot values (the margin's numbers) and null-space basis from the field
    are those of sympy's own echelon_form and nullspace, on matrices over Q(sqrt 2, sqrt 3)
    with dependent rows."""
    import random

    rng = random.Random(1)
    r2, r3 = sympy.sqrt(2), sympy.sqrt(3)
    pool = [0, 0, 0, 1, -2, sympy.Rational(1, 3), r2, r3 / 2, 1 + r2, r2 * r3]
    for trial in range(20):
        m, n = rng.randint(2, 5), rng.randint(2, 5)
        rows = [[rng.choice(pool) for _ in range(n)] for _ in range(m)]
        if trial % 3 == 0:
            rows[-1] = [a * r2 + b for a, b in zip(rows[0], rows[1], strict=True)]
        M = sympy.Matrix(rows)
        E, piv = M.echelon_form(with_pivots=True, simplify=True)
        pivots, values, ker = field_echelon(np.array(rows, dtype=object))
        assert pivots == list(piv)
        assert all(
            sympy.simplify(E[i, c] - v) == 0
            for (i, c), v in zip(enumerate(piv), values, strict=True)
        )
        ns = M.nullspace(simplify=True)
        assert len(ns) == len(ker)
        for u, v in zip(ns, ker, strict=True):
            assert all(sympy.simplify(a - b) == 0 for a, b in zip(u, v, strict=True))


@pytest.mark.parametrize(
    "gens",
    [
        # degree 8, a minimal polynomial with integer coefficients
        (sympy.sqrt(2), sympy.sqrt(3), sympy.sqrt(5)),
        # primitive element sqrt(7)/3: minimal polynomial x^2 - 7/9 (the table's denominator)
        (sympy.sqrt(7) / 3,),
        (sympy.cbrt(2),),
    ],
)
def test_integer_vectors_eliminate_as_the_field(gens) -> None:
    """The elimination on integer coefficient vectors gives the pivots, pivot values and
    rows of the elimination on the field's own elements, element for element; and a
    product, an inverse and ``x - f y`` are the field's."""
    import random

    from sympy.polys.domains import QQ

    from mechsing.numeric._field_arithmetic import DomainArithmetic, IntegerArithmetic
    from mechsing.numeric.field import _eliminate, domain_matrix

    K = QQ.algebraic_field(*gens)
    ints = IntegerArithmetic(K)
    rng = random.Random(2)
    terms = [1, *gens, gens[0] ** 2, sympy.prod(gens)]

    def element() -> object:
        if rng.random() < 0.3:
            return 0
        return sum(sympy.Rational(rng.randint(-9, 9), rng.randint(1, 6)) * t for t in terms)

    A = np.array([[element() for _ in range(7)] for _ in range(6)], dtype=object)
    A[4] = A[0] * gens[0] + A[1] * sympy.Rational(3, 7)  # a dependent row
    A[:, 2] = 0  # a zero column
    D = domain_matrix(A).convert_to(K)
    rows = [list(r) for r in D.to_list()]
    want = _eliminate(DomainArithmetic(K), [list(r) for r in rows], *D.shape)
    pivots, values, kept = _eliminate(ints, [[ints.vector(x) for x in r] for r in rows], *D.shape)
    assert pivots == want[0] and len(pivots) == 5
    assert [ints.element(v) for v in values] == want[1]
    assert [[ints.element(v) for v in r] for r in kept] == want[2]
    x, f, y = rows[0][0], rows[1][1], rows[3][3]
    vx, vf, vy = ints.vector(x), ints.vector(f), ints.vector(y)
    assert ints.element(ints.mul(vf, vy)) == f * y
    assert ints.element(ints.revert(vf)) == K.one / f
    assert ints.element(ints.sub_mul(vx, vf, vy)) == x - f * y
    assert ints.element(ints.sub_mul(vx, ints.one, vx)) == K.zero


@pytest.mark.parametrize("gens", [(sympy.sqrt(2), sympy.sqrt(3)), (sympy.sqrt(7) / 3,)])
def test_field_solve_is_lu_solve(gens) -> None:
    """The solve on integer vectors is ``DomainMatrix.lu_solve``'s solution element for
    element, and raises as it does on a singular matrix."""
    import random

    from sympy.polys.matrices.exceptions import DMNonInvertibleMatrixError

    from mechsing.numeric.field import _solve, domain_matrix

    rng = random.Random(3)
    terms = [1, *gens, sympy.prod(gens)]

    def element() -> object:
        if rng.random() < 0.3:
            return 0
        return sum(sympy.Rational(rng.randint(-9, 9), rng.randint(1, 6)) * t for t in terms)

    A = np.array([[element() for _ in range(8)] for _ in range(8)], dtype=object)
    B = np.array([[element() for _ in range(2)] for _ in range(8)], dtype=object)
    D = domain_matrix(np.concatenate([A, B], axis=1))
    Am, Bm = D[:, :8], D[:, 8:]
    assert _solve(Am, Bm) == Am.lu_solve(Bm).to_list()
    A[5] = A[1] * gens[0]
    D = domain_matrix(np.concatenate([A, B], axis=1))
    with pytest.raises(DMNonInvertibleMatrixError):
        _solve(D[:, :8], D[:, 8:])


# ============================================================================ Bennett closure


def _bennett_values(t1: str, t2_offset: str = "0") -> str:
    """Joint values (relative to the reference) at tan(theta1/2) = t1 on the closed form."""
    t2 = f"13/(5*({t1})) + {t2_offset}"
    q1 = f"2*atan({t1}) - 2*atan(1/2)"
    q2 = f"2*atan({t2}) - 2*atan(26/5)"
    return f'{{J1: "{q1}", J2: "{q2}", J3: "-({q1})", J4: "-({q2})"}}'


def _bennett(tmp_path: Path, configs: dict[str, str]) -> Path:
    text = (EXAMPLES / "bennett.yaml").read_text()
    head = text[: text.index("configurations:")]
    lines = [head + "configurations:", "  reference: {}"]
    lines += [f"  {name}: {vals}" for name, vals in configs.items()]
    return write(tmp_path, "bennett_field", "\n".join(lines) + "\n")


def test_bennett_closes_exactly_in_its_field(tmp_path: Path) -> None:
    path = _bennett(
        tmp_path,
        {
            "quarter": _bennett_values("1"),
            "third": _bennett_values("3"),
            "root2": _bennett_values("sqrt(2)"),
        },
    )
    degrees = {"quarter": 1, "third": 1, "root2": 2}
    for name, degree in degrees.items():
        model, q = _configuration(path, name)
        fk = model.field_kinematics(q)
        assert fk is not None and fk.degree == degree, name
        assert fk.closes() == [True]
        eye = np.eye(4, dtype=int)
        assert all(np.all(D == eye) for D in fk.chord_residuals())
    res = mechsing.analyze(str(path), precision="exact")
    for name, c in by_name(res.to_json()).items():
        assert c["closure_residual"] == 0, name
        # Bennett: the four screws have rank 3 at every configuration of the motion
        assert (c["closure_rank"]["rank"], c["closure_rank"]["nullity"]) == (3, 1), name


def test_bennett_off_the_motion_has_a_residual(tmp_path: Path) -> None:
    path = _bennett(tmp_path, {"off": _bennett_values("1", "1/1000")})
    model, q = _configuration(path, "off")
    fk = model.field_kinematics(q)
    assert fk is not None and fk.closes() == [False]
    res = mechsing.analyze(str(path), precision="exact")
    c = by_name(res.to_json())["off"]
    assert "does not close exactly" in c["error"], c


def test_field_path_equals_the_sympy_path() -> None:
    """The poses and current screws from K are the sympy path's numbers (60 digits)."""
    for file, name in [
        ("bennett.yaml", "q1-half"),
        ("double_rocker.yaml", "limit"),
        ("tsai_3upu.yaml", "raised"),
    ]:
        model, q = _configuration(EXAMPLES / file, name)
        fk = model.field_kinematics(q)
        assert fk is not None, file
        slow = forward.poses(model, q)
        fast = fk.poses()
        for body, g in slow.items():
            diff = [sympy.N(a - b, 60) for a, b in zip(g.flat, fast[body].flat, strict=True)]
            assert all(abs(d) < 1e-50 for d in diff), (file, body)
        S_slow = forward.current_screws(model, q, slow)
        S_fast = fk.current_screws()
        diff = [sympy.N(a - b, 60) for a, b in zip(S_slow.flat, S_fast.flat, strict=True)]
        assert all(abs(d) < 1e-50 for d in diff), file


RS_CHAIN = """mechanism: r-s
bodies: [ground, arm, hand]
joints:
  - {name: R1, type: R, between: [ground, arm], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: S1, type: S, between: [arm, hand], point: [1, "1/2", 0]}
inputs: [R1, S1]
output: {body: hand}
configurations:
  reference: {}
  about-z: {R1: "2*atan(1/2)", S1: [0, 0, "pi/3"]}
  oblique: {R1: "pi/6", S1: ["2*acos(1/3)/3", "2*acos(1/3)/3", "acos(1/3)/3"]}
"""


def test_spherical_joint_in_the_field_equals_the_sympy_path(tmp_path: Path) -> None:
    """An S joint's rotation vector: angle acos(1/3) about the unit axis (2, 2, 1)/3 (cos 1/3,
    sin 2 sqrt(2)/3) and pi/3 about z; the field's poses and screws are the sympy path's."""
    path = write(tmp_path, "rs", RS_CHAIN)
    for name, degree in (("about-z", 2), ("oblique", 4)):
        model, q = _configuration(path, name)
        fk = model.field_kinematics(q)
        assert fk is not None and fk.degree == degree, name
        slow = forward.poses(model, q)
        fast = fk.poses()
        for body, g in slow.items():
            assert all(
                abs(sympy.N(a - b, 60)) < 1e-50
                for a, b in zip(g.flat, fast[body].flat, strict=True)
            ), (name, body)
        S_slow = forward.current_screws(model, q, slow)
        S_fast = fk.current_screws()
        assert all(
            abs(sympy.N(a - b, 60)) < 1e-50 for a, b in zip(S_slow.flat, S_fast.flat, strict=True)
        ), name


# ============================================================================ published ranks


def test_double_rocker_limits_close_with_loop_rank_3_in_g() -> None:
    model, q = _configuration(EXAMPLES / "double_rocker.yaml", "limit")
    fk = model.field_kinematics(q)
    assert fk is not None and fk.degree == 4  # Q(sqrt 3, sqrt 15)
    res = mechsing.analyze(str(EXAMPLES / "double_rocker.yaml"), precision="exact")
    configs = by_name(res.to_json())
    for name in ("limit", "output-limit"):
        c = configs[name]
        assert c["closure_residual"] == 0
        loop = c["loops"][0]
        assert loop["subgroup"]["type"] == "G" and loop["rank"] == 3, loop


def test_3rpr_concurrent_is_type_ii() -> None:
    res = mechsing.analyze(str(EXAMPLES / "planar_3rpr.yaml"), precision="exact")
    c = by_name(res.to_json())["concurrent"]
    assert c["closure_residual"] == 0
    assert "output" in classes(c), classes(c)


# ============================================================================ fallback

SCREW = """mechanism: screw-pair
bodies: [ground, nut, arm]
joints:
  - {name: H1, type: H, between: [ground, nut], axis: [0, 0, 1], point: [0, 0, 0], pitch: "1/10"}
  - {name: R1, type: R, between: [nut, arm], axis: [1, 0, 0], point: [0, 0, 1]}
inputs: [H1, R1]
output: {body: arm}
configurations:
  turned: {H1: "pi/2", R1: "2*atan(1/2)"}
  flat: {H1: "pi/3", R1: 0}
"""


def test_h_joint_keeps_the_sympy_path(tmp_path: Path) -> None:
    path = write(tmp_path, "screw", SCREW)
    model, q = _configuration(path, "turned")
    assert model.field_kinematics(q) is None  # pitch * pi/2 is not algebraic
    exact = by_name(mechsing.analyze(str(path), precision="exact").to_json())
    floats = by_name(mechsing.analyze(str(path), precision="float").to_json())
    for name in ("turned", "flat"):
        assert exact[name]["precision"] == "exact"
        assert exact[name]["singular"] == floats[name]["singular"]
        assert classes(exact[name]) == classes(floats[name])


def test_a_configuration_that_gives_nothing_is_its_start_in_exact_mode(tmp_path: Path) -> None:
    # A configuration with no joint values is its start configuration (nothing moves):
    # exact mode takes it as it is -- the reference's drawn pose, or a start that gives
    # every value exactly (the file's Type I pose) -- where it used to refuse it as
    # "values left to solve numerically".
    text = (EXAMPLES / "five_bar.yaml").read_text()
    path = write(tmp_path, "five_bar", text + "  drawn: {}\n  again: {start: type1}\n")
    res = by_name(
        mechsing.analyze(
            str(path), configs=["reference", "drawn", "type1", "again"], precision="exact"
        ).to_json()
    )
    for copy, original in (("drawn", "reference"), ("again", "type1")):
        c, o = res[copy], res[original]
        assert "error" not in c, c.get("error")
        assert c["precision"] == "exact" and c["closure_residual"] == 0
        assert c["joints"] == o["joints"]
        assert classes(c) == classes(o)
        assert c["closure_rank"] == o["closure_rank"] and c["mobility"] == o["mobility"]
        assert "underdetermined" not in c
    assert "input" in classes(res["again"])  # the file's type1 pose: a Type I singularity


def test_field_solve_square_tall_and_zero_columns_against_sympy() -> None:
    # the solution in Q(sqrt 2, sqrt 3) against sympy's own elimination (Matrix.LUsolve,
    # then radsimp): a square system, whose zero right-hand column has the zero solution,
    # and a tall one whose right-hand side is in the range (the least-squares solution is
    # the exact one)
    r2, r3 = sympy.sqrt(2), sympy.sqrt(3)
    A = sympy.Matrix([[1, r2, 0], [r3, 2, 1], [0, sympy.Rational(1, 3), r2 + r3]])
    b = sympy.Matrix([[r3, 0, 1], [1, 0, r2], [r2 * r3, 0, 0]])
    got = field_solve(np.array(A.tolist(), dtype=object), np.array(b.tolist(), dtype=object))
    want = A.LUsolve(b)
    assert got.shape == (3, 3)
    for i in range(3):
        for j in range(3):
            assert sympy.expand(sympy.radsimp(got[i, j] - want[i, j])) == 0, (i, j)
        assert got[i, 1] == 0
    T = A.col_join(sympy.Matrix([[1, 1, r2]]))
    x = sympy.Matrix([r2, sympy.Rational(-2, 7), 1 + r3])
    tall = field_solve(np.array(T.tolist(), dtype=object), np.array(list(T * x), dtype=object))
    assert [sympy.expand(sympy.radsimp(t - w)) for t, w in zip(tall, x, strict=True)] == [0, 0, 0]
