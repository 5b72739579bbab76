"""High precision (mp:N) on every valid file: the right answer or a clear message, never a traceback.

Every expected answer is derived here from the mathematics, not read from the program:

1. Newton at N digits closes loops with every joint type that can sit in a loop (R, P, H, C, S,
   U, and G, Y, X, T2, T3, D): at mp:30 and mp:50 the closed configuration satisfies the loop
   equation (the product of the joints' exponentials around the loop is the identity, recomputed
   here with ``mpmath.expm`` at N + 20 digits from the catalog's bases by tests/reference) to
   10^(5-N) L, and the residual reported in the JSON of ``mechsing solve`` / ``analyze`` is below
   that too.  The RSSR is also taken 1e-10 rad from its input (rocker dead-centre) singularity,
   where ``auto`` re-decides at mp:50 and must still close.
2. The high-precision SVD never fails: a matrix with repeated rows and a zero column (the
   constraint wrenches of a screw jack), whose singular values follow from its Gram matrix, and
   the screw jack itself (R ground-screw, H screw-nut of pitch 1 mm/rad, P nut-ground) in every
   mode: mobility 1, the nut slides by the pitch times the screw's turn.
3. A serial T3-S chain with the S joint turned by pi/2 about its middle axis (where Euler angles
   would lock) is regular at mp:50: its output screws have rank 6 at every pose.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import mpmath
import numpy as np
import pytest
import yaml

from mechsing.numeric import decide_definiteness, decide_rank, parse_precision
from mechsing.numeric.linalg import eigh, spectral_norm, svd
from tests.cli import cli_json
from tests.mechanisms import EXAMPLES, by_name, classes, write
from tests.reference.expressions import mp_num
from tests.reference.kinematics import J, joint_from_entry, length_scale, mismatch
from tests.reference.se3 import expm_mp, inv

# ============================================================================ helpers


# ============================================================================ 2. robust SVD

#: the constraint wrenches of the screw jack, as stacked at mp:50 (9 x 6): every row has one
#: non-zero entry, so the columns are orthogonal and the Gram matrix is diag(2, 2, 1, 2, 2, 0)
JACK_WRENCHES = [
    [-1, 0, 0, 0, 0, 0],
    [0, 0, 0, 1, 0, 0],
    [0, 0, 0, 0, 1, 0],
    [0, 1, 0, 0, 0, 0],
    [0, 1, 0, 0, 0, 0],
    [0, 0, 1, 0, 0, 0],
    [0, 0, 0, 1, 0, 0],
    [0, 0, 0, 0, 1, 0],
    [1, 0, 0, 0, 0, 0],
]


def _max_abs(M: np.ndarray) -> mpmath.mpf:
    return max((abs(x) for x in np.asarray(M).flat), default=mpmath.mpf(0))


@pytest.mark.parametrize("digits", [20, 30, 50, 80])
@pytest.mark.parametrize("transpose", [False, True])
def test_mp_svd_of_repeated_rows_and_a_zero_column(digits: int, transpose: bool) -> None:
    """Singular values sqrt(2) (four times), 1 and 0, from A^T A = diag(2, 2, 1, 2, 2, 0); U and V
    orthogonal and U S V^T = A at the working precision; the spectral norm is sqrt(2), the rank 5,
    the Gram matrix's eigenvalues 0, 1, 2, 2, 2, 2 (positive semidefinite)."""
    prec = parse_precision(f"mp:{digits}")
    with prec.context():
        A = prec.asarray(JACK_WRENCHES)
        if transpose:
            A = A.T.copy()
        m, n = A.shape
        U, s, Vt = svd(A)
        tol = mpmath.mpf(10) ** (5 - digits)
        expected = [mpmath.sqrt(2)] * 4 + [mpmath.mpf(1), mpmath.mpf(0)]
        assert len(s) == 6
        assert max(abs(a - b) for a, b in zip(s, expected, strict=True)) <= tol
        assert _max_abs(U.T @ U - prec.backend.eye(m)) <= tol
        assert _max_abs(Vt @ Vt.T - prec.backend.eye(n)) <= tol
        S = prec.backend.zeros((m, n))
        for i in range(6):
            S[i, i] = s[i]
        assert _max_abs(U @ S @ Vt - A) <= tol
        assert abs(spectral_norm(A) - mpmath.sqrt(2)) <= tol
        w, Q = eigh(A.T @ A if not transpose else A @ A.T)
        assert max(abs(a - b) for a, b in zip(w, [0, 1, 2, 2, 2, 2], strict=True)) <= tol
    dec = decide_rank(A, prec, want_spaces=True, native_spaces=True)
    assert dec.rank == 5
    assert decide_definiteness(A.T @ A if not transpose else A @ A.T, prec).kind == "semidefinite"


def _gave_up(*args: object, **kwargs: object) -> None:
    raise RuntimeError("svd: no convergence to an eigenvalue after 150 iterations")


@pytest.mark.parametrize("shape", [(6, 6), (9, 6), (6, 9), (1, 4), (4, 1), (18, 12)])
@pytest.mark.parametrize("rank_deficit", [0, 2])
def test_svd_when_mpmath_gives_up(
    monkeypatch: pytest.MonkeyPatch, shape: tuple[int, int], rank_deficit: int
) -> None:
    """Where mpmath's iteration gives up, the SVD still holds: singular values are the square
    roots of the eigenvalues of the Gram matrix (computed here by mpmath's eigsy at 70 digits, an
    independent route), U and V are orthogonal, U S V^T = A, in full and thin form."""
    m, n = shape
    rng = np.random.default_rng(m * 100 + n + rank_deficit)
    r = max(0, min(m, n) - rank_deficit)
    with mpmath.workdps(50):
        A = mpmath.zeros(m, n)
        if r:  # a product of m x r and r x n integer matrices (over 7 and 5): rank r
            X = mpmath.matrix([[int(v) for v in rng.integers(-9, 10, r)] for _ in range(m)]) / 7
            Y = mpmath.matrix([[int(v) for v in rng.integers(-9, 10, n)] for _ in range(r)]) / 5
            A = X * Y
    with mpmath.workdps(70):
        G = A.T * A if m >= n else A * A.T
        ev = sorted(mpmath.eigsy(G, eigvals_only=True), reverse=True)
        # rank r: the other singular values are exactly 0
        expected = [mpmath.sqrt(e) for e in ev[:r]] + [mpmath.mpf(0)] * (min(m, n) - r)
    monkeypatch.setattr(mpmath, "svd_r", _gave_up)
    prec = parse_precision("mp:50")
    tol = mpmath.mpf(10) ** -45 * max(1, max(expected))
    with prec.context():
        Aa = np.array(A.tolist(), dtype=object)
        for full in (True, False):
            U, s, Vt = svd(Aa, full_matrices=full)
            k = min(m, n)
            assert U.shape == ((m, m) if full else (m, k)) and Vt.shape == (
                (n, n) if full else (k, n)
            )
            assert max(abs(a - b) for a, b in zip(s, expected, strict=True)) <= tol
            assert _max_abs(U.T @ U - prec.backend.eye(U.shape[1])) <= tol
            assert _max_abs(Vt @ Vt.T - prec.backend.eye(Vt.shape[0])) <= tol
            S = prec.backend.zeros((U.shape[1], Vt.shape[0]))
            for i in range(k):
                S[i, i] = s[i]
            assert _max_abs(U @ S @ Vt - Aa) <= tol
        assert abs(spectral_norm(Aa) - expected[0]) <= tol
    assert decide_rank(Aa, prec).rank == r


def test_eigh_when_mpmath_gives_up(monkeypatch: pytest.MonkeyPatch) -> None:
    """Where mpmath's QL iteration gives up, the Jacobi eigenvalue method gives the spectrum of a
    symmetric matrix built with known eigenvalues (Q diag(d) Q^T, Q a Householder reflection) and
    orthonormal eigenvectors, and the definiteness decision still stands."""
    d = [-2, 0, 0, 1, 1, 3]
    prec = parse_precision("mp:50")
    with prec.context():
        v = [mpmath.mpf(x) for x in (1, 2, -1, 3, 0, 1)]
        nv2 = mpmath.fsum(x * x for x in v)
        Q = np.array(
            [[(1 if i == j else 0) - 2 * v[i] * v[j] / nv2 for j in range(6)] for i in range(6)]
        )
        D = prec.backend.zeros((6, 6))
        for i, x in enumerate(d):
            D[i, i] = mpmath.mpf(x)
        M = Q @ D @ Q.T
        monkeypatch.setattr(mpmath, "eigsy", _gave_up)
        w, V = eigh(M)
        tol = mpmath.mpf(10) ** -45
        assert max(abs(a - b) for a, b in zip(w, d, strict=True)) <= tol
        assert _max_abs(V.T @ V - prec.backend.eye(6)) <= tol
        assert _max_abs(M @ V - V * w[None, :]) <= tol
    assert decide_definiteness(M, prec).kind == "indefinite"


#: a screw jack: the screw turns in the ground (R), the nut rides on it (H, pitch 1 mm per radian)
#: and slides in the ground without turning (P); the screw's turn is the input, the nut the output
SCREW_JACK = """mechanism: screw-jack
units: {length: mm}
bodies: [ground, screw, nut]
joints:
  - {name: R1, type: R, between: [ground, screw], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: H1, type: H, between: [screw, nut], axis: [0, 0, 1], point: [0, 0, 0], pitch: 1}
  - {name: P1, type: P, between: [nut, ground], axis: [0, 0, 1]}
inputs: [R1]
output: {body: nut}
configurations:
  reference: {}
  turned: {R1: 0.7}
  turned-back: {R1: "-3/2"}
"""
#: pitch of the jack (m per radian)
JACK_PITCH = 1e-3


@pytest.mark.parametrize("mode", ["float", "mp:30", "mp:50", "auto"])
def test_screw_jack_in_every_mode(tmp_path: Path, mode: str) -> None:
    """All three joints lie on one axis, so their screws (z, 0), (z, h z), (0, z) span the
    cylindrical subgroup C (dim 2): closure rank 2, one degree of freedom (3 - 2) everywhere,
    no singularity.  Turning the screw by theta with the nut kept from turning (H1 = -theta)
    moves the nut by h theta along the axis: P1 = h R1 (g_nut = exp(-P1 (0, z)) and
    exp(theta (z, 0)) exp(-theta (z, h z)) = exp(-h theta (0, z))), so the nut's slide rate is the
    pitch times the input rate."""
    path = write(tmp_path, "screw_jack", SCREW_JACK)
    res = cli_json(["analyze", str(path), "--precision", mode, "--format", "json"])
    assert set(by_name(res)) == {"reference", "turned", "turned-back"}
    for c in res["configurations"]:
        where = (mode, c["name"])
        assert "error" not in c, where
        assert (c["closure_rank"]["rank"], c["closure_rank"]["nullity"]) == (2, 1), where
        assert c["mobility"]["instantaneous"] == c["mobility"]["generic"] == 1, where
        assert c["mobility"]["finite"] == 1, where
        (lp,) = c["loops"]
        assert (lp["subgroup"]["type"], lp["subgroup"]["dim"]) == ("C", 2), where
        assert c["singular"] is False and classes(c) == [], where
        (r1,), (h1,), (p1,) = c["joints"]["R1"], c["joints"]["H1"], c["joints"]["P1"]
        assert h1 == pytest.approx(-r1, abs=1e-15), where
        assert p1 == pytest.approx(JACK_PITCH * r1, rel=1e-14, abs=1e-18), where


#: the screw jack with a pitch of 1e-13 m/rad (in metres), every joint value given exactly
FINE_JACK = """mechanism: fine-screw-jack
bodies: [ground, screw, nut]
joints:
  - {name: R1, type: R, between: [ground, screw], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: H1, type: H, between: [screw, nut], axis: [0, 0, 1], point: [0, 0, 0], pitch: 1e-13}
  - {name: P1, type: P, between: [nut, ground], axis: [0, 0, 1]}
inputs: [R1]
output: {body: nut}
configurations:
  turned: {R1: "pi/4", H1: "-pi/4", P1: "pi/4*1e-13"}
"""


@pytest.mark.parametrize("mode", ["float", "mp:50", "exact", "auto"])
def test_a_fine_pitch_gives_no_constraint_singularity_in_any_mode(tmp_path: Path, mode) -> None:
    """Issue 44: a helical joint of pitch 1e-13 m/rad.  For any pitch h != 0 the legs are
    R1-H1 (twists (z, 0) and (z, h z): the cylindrical subgroup C, constraint wrenches the
    forces along x, y and the couples about x, y) and P1 (constraint wrenches the forces
    along x, y and the couples about x, y, z): together rank 5 at every configuration, so
    no constraint singularity anywhere.  float does not resolve the pitch (1e-13 is below
    its thresholds: the screw turns like a revolute joint there, and the combined rank is
    6 at every configuration, again regular); mp:50 and exact resolve it, and their
    generic rank must be theirs, not float's 6 (which made the configuration a false
    constraint singularity, rank 5 'generically 6')."""
    path = write(tmp_path, "fine_jack", FINE_JACK)
    res = cli_json(["analyze", str(path), "--precision", mode, "--format", "json"])
    (c,) = res["configurations"]
    assert "error" not in c, c
    assert c["singular"] is False and classes(c) == [], (mode, classes(c))
    assert (c["closure_rank"]["rank"], c["mobility"]["generic"]) == (2, 1)


# ============================================================================ 1. Newton at N digits

#: digits of the independent recomputation beyond the mode's
GUARD = 20


def _joints(entries: list[dict]) -> list[J]:
    """The reference joints of file entries, their numbers at the working precision (so build
    them inside the ``mpmath.workdps`` block that uses them)."""
    return [joint_from_entry(e, mp_num, mpmath.mpf(1)) for e in entries]


def _product(joints: list[J], q: dict[str, list]) -> np.ndarray:
    """The product of the joints' exponentials in their order (mpmath.expm at the working
    precision; a U joint exp(q1 R1) exp(q2 R2))."""
    g = np.eye(4)
    for j in joints:
        g = g @ j.element([mpmath.mpf(x) for x in q[j.name]], expm_mp)
    return g


def _mechanism(name: str, joints: list[dict], inputs: list[str], config: dict) -> str:
    bodies = []
    for j in joints:
        for b in j["between"]:
            if b not in bodies:
                bodies.append(b)
    lines = [f"mechanism: {name}", f"bodies: [{', '.join(bodies)}]", "joints:"]
    lines += [f"  - {json.dumps(j)}" for j in joints]
    lines += [f"inputs: [{', '.join(inputs)}]", "configurations:", "  reference: {}"]
    lines.append(f"  moved: {json.dumps(config)}")
    return "\n".join(lines) + "\n"


def _R(name: str, a: str, b: str, axis: list, point: list) -> dict:
    return {"name": name, "type": "R", "between": [a, b], "axis": axis, "point": point}


def _S(name: str, a: str, b: str, point: list) -> dict:
    return {"name": name, "type": "S", "between": [a, b], "point": point}


#: a spatial RSSR: crank (radius 1/2) about z through the origin, coupler from (1/2, 0, 0) to
#: (0, 3, 2), rocker (radius 1) about x through (0, 3, 1); the coupler spins idly about its line
RSSR = [
    _R("A", "ground", "crank", [0, 0, 1], [0, 0, 0]),
    _S("B", "crank", "coupler", ["1/2", 0, 0]),
    _S("C", "coupler", "rocker", [0, 3, 2]),
    _R("D", "rocker", "ground", [1, 0, 0], [0, 3, 1]),
]

#: loops in chain order (each joint between the previous body and the next), the input and its
#: value; every joint type that can sit in a loop appears in at least one
LOOPS: dict[str, tuple[list[dict], dict]] = {
    "RSSR": (RSSR, {"A": 0.1}),
    "RSSP": (
        [*RSSR[:3], {"name": "D", "type": "P", "between": ["rocker", "ground"], "axis": [0, 1, 0]}],
        {"A": 0.4},
    ),
    "HSSR": (
        [{**RSSR[0], "type": "H", "pitch": "1/10"}, *RSSR[1:]],
        {"A": 0.3},
    ),
    "CSSR": (
        [{**RSSR[0], "type": "C"}, *RSSR[1:]],
        {"A": [0.3, "1/20"]},
    ),
    "RUSR": (
        [
            RSSR[0],
            {
                "name": "B",
                "type": "U",
                "between": ["crank", "coupler"],
                "axes": [[0, 0, 1], [1, 0, 0]],
                "point": ["1/2", 0, 0],
            },
            *RSSR[2:],
        ],
        {"A": 0.3},
    ),
    "R+G": (
        [
            _R("J1", "ground", "body", [1, 2, 2], [1, 0, 3]),
            {"name": "J2", "type": "G", "between": ["body", "ground"], "normal": [1, 2, 2]},
        ],
        {"J1": 0.7},
    ),
    "H+Y": (
        [
            {**_R("J1", "ground", "body", [0, 1, 1], [1, 2, 0]), "type": "H", "pitch": "1/10"},
            {
                "name": "J2",
                "type": "Y",
                "between": ["body", "ground"],
                "normal": [0, 1, 1],
                "pitch": "1/10",
            },
        ],
        {"J1": 0.7},
    ),
    "R+X": (
        [
            _R("J1", "ground", "body", [0, 0, 1], [1, 2, 0]),
            {"name": "J2", "type": "X", "between": ["body", "ground"], "axis": [0, 0, 1]},
        ],
        {"J1": 0.7},
    ),
    "P+T2": (
        [
            {"name": "J1", "type": "P", "between": ["ground", "body"], "axis": [1, 1, 0]},
            {"name": "J2", "type": "T2", "between": ["body", "ground"], "normal": [0, 0, 1]},
        ],
        {"J1": 0.3},
    ),
    "P+T3": (
        [
            {"name": "J1", "type": "P", "between": ["ground", "body"], "axis": [1, 2, 2]},
            {"name": "J2", "type": "T3", "between": ["body", "ground"]},
        ],
        {"J1": 0.3},
    ),
    "R+D": (
        [
            _R("J1", "ground", "body", [1, 2, 2], [1, 0, 3]),
            {"name": "J2", "type": "D", "between": ["body", "ground"]},
        ],
        {"J1": 0.7},
    ),
}


def _closed_values(path: Path, mode: str) -> tuple[dict, dict[str, list[mpmath.mpf]]]:
    """The JSON of ``mechsing solve`` and the joint values of the closed configuration at the
    mode's digits (Python API: the JSON rounds them to float)."""
    from mechsing.kinematics import solve_configuration
    from mechsing.model import load

    out = cli_json(
        ["solve", str(path), "--config", "moved", "--precision", mode, "--format", "json"]
    )
    model, closed = solve_configuration(load(str(path)), "moved", mode)
    q = {jk.name: list(closed.q[jk.columns]) for jk in model.joints}
    return out, q


@pytest.mark.parametrize("digits", [30, 50])
@pytest.mark.parametrize("loop", sorted(LOOPS))
def test_newton_at_n_digits_closes_every_joint_type(tmp_path: Path, loop: str, digits: int) -> None:
    """Moved by its input, the loop is closed by continuation and Newton at N digits: the product
    of the joints' exponentials around the loop (recomputed with mpmath.expm at N + 20 digits) is
    the identity to 10^(5-N) L, and the JSON's residual is below 10^(5-N) L."""
    joints, config = LOOPS[loop]
    inputs = list(config)
    path = write(
        tmp_path, f"loop_{loop.replace('+', '_')}", _mechanism(loop, joints, inputs, config)
    )
    out, q = _closed_values(path, f"mp:{digits}")
    with mpmath.workdps(digits + GUARD):
        ref = _joints(joints)
        L, c = length_scale(ref)
        goal = mpmath.mpf(10) ** (5 - digits) * L
        assert out["closure_residual"] <= goal, (loop, out["closure_residual"], float(goal))
        g = _product(ref, q)
        assert mismatch(g, L, c) <= goal, (loop, float(mismatch(g, L, c)))
        # the given value is the file's, to N digits
        given = q[inputs[0]]
        want = config[inputs[0]] if isinstance(config[inputs[0]], list) else [config[inputs[0]]]
        assert max(abs(a - mp_num(b)) for a, b in zip(given, want, strict=True)) <= goal


def _stewart_with_strokes() -> tuple[str, list[dict]]:
    """The octahedral Stewart platform of the examples with one more configuration: the six
    strokes given (inputs), the U and S joints solved by continuation from the centred pose."""
    text = (EXAMPLES / "stewart_octahedral.yaml").read_text()
    strokes = "{P1: 0.05, P2: -0.03, P3: 0.02, P4: 0.04, P5: -0.01, P6: 0.03}"
    text = text.replace("configurations:\n", f"configurations:\n  moved: {strokes}\n", 1)
    return text, yaml.safe_load(text)["joints"]


@pytest.mark.parametrize("digits", [30, 50])
def test_newton_at_n_digits_closes_the_stewart_platform(tmp_path: Path, digits: int) -> None:
    """Six U-P-S legs with given strokes: every leg carries the platform to the same pose (the
    product U_k P_k S_k of the leg's exponentials, recomputed at N + 20 digits, is the same for
    the six legs) to 10^(5-N) L, and the JSON's residual is below 10^(5-N) L."""
    text, joints = _stewart_with_strokes()
    path = write(tmp_path, "stewart_strokes", text)
    out, q = _closed_values(path, f"mp:{digits}")
    with mpmath.workdps(digits + GUARD):
        ref = _joints(joints)
        by = {j.name: j for j in ref}
        L, c = length_scale(ref)
        goal = mpmath.mpf(10) ** (5 - digits) * L
        assert out["closure_residual"] <= goal, out["closure_residual"]
        legs = [_product([by[f"U{k}"], by[f"P{k}"], by[f"S{k}"]], q) for k in range(1, 7)]
        for k, g in enumerate(legs[1:], start=2):
            d = inv(legs[0]) @ g
            assert mismatch(d, L, c) <= goal, (k, float(mismatch(d, L, c)))
        for k in range(1, 7):
            assert abs(q[f"P{k}"][0] - mp_num(out["joints"][f"P{k}"][0])) <= mpmath.mpf(10) ** -15


def test_rssr_at_400_digits(tmp_path: Path) -> None:
    """Beyond float's exponent range (eps = 10^-400 underflows in float) mp:N still closes the
    RSSR to 10^(5-N) L; the series of the Lie formulas take their number of terms from N."""
    joints, config = LOOPS["RSSR"]
    path = write(tmp_path, "rssr400", _mechanism("rssr", joints, ["A"], config))
    out, q = _closed_values(path, "mp:400")
    with mpmath.workdps(400 + GUARD):
        ref = _joints(joints)
        L, c = length_scale(ref)
        assert mismatch(_product(ref, q), L, c) <= mpmath.mpf(10) ** (5 - 400) * L
    assert out["closure_residual"] <= 1e-300  # the residual underflows float's range


def test_auto_near_the_rssr_rocker_dead_centre(tmp_path: Path) -> None:
    """The RSSR's loop equation |C(psi) - B(theta)|^2 = |C0 - B0|^2 with B(theta) = (cos theta,
    sin theta, 0) / 2 and C(psi) = (0, 3 - sin psi, 1 + cos psi) has d/dtheta = -cos theta
    (3 - sin psi), zero only at theta = +-pi/2: there the rocker stops while the crank turns (an
    input singularity, and the rocker cannot move at all: impossible output).  At
    theta = pi/2 - 1e-10 every rank is full, but float's thresholds cannot tell (auto re-decides
    at mp:50): the configuration must be closed at 50 digits and found regular."""
    joints, _ = LOOPS["RSSR"]
    text = _mechanism("rssr", joints, ["A"], {"A": "pi/2 - 1e-10"})
    text = text.replace("inputs: [A]\n", "inputs: [A]\noutput: {body: rocker}\n")
    text += '  dead: {A: "pi/2"}\n'
    path = write(tmp_path, "rssr_dead_centre", text)
    res = by_name(cli_json(["analyze", str(path), "--format", "json"]))
    c = res["moved"]
    assert c["precision"] == "mp:50" and "error" not in c, c.get("error")
    with mpmath.workdps(60):
        L, _c = length_scale(_joints(joints))
        assert c["closure_residual"] <= mpmath.mpf(10) ** -45 * L
    assert (c["closure_rank"]["rank"], c["closure_rank"]["nullity"]) == (6, 2)  # crank + idle spin
    assert c["singular"] is False, classes(c)
    dead = cli_json(
        ["analyze", str(path), "--config", "dead", "--precision", "mp:50", "--format", "json"]
    )
    (d,) = dead["configurations"]
    assert {"input", "impossible-output"} <= set(classes(d)), classes(d)


@pytest.mark.parametrize(
    ("precision", "k"),
    [
        ("float", 4),
        ("float", 6),
        ("float", 8),
        ("float", 9),
        ("mp:50", 11),
        ("mp:50", 15),
        ("mp:50", 20),
    ],
)
def test_input_test_near_the_rssr_dead_centre_is_never_falsely_singular(
    tmp_path: Path, precision: str, k: int
) -> None:
    """10^-k before the dead centre (theta = pi/2, see above) every rank is full. The input
    test must say so or leave it undecided, never report a singularity: its dimension is
    rank [TN; EN] - rank TN, decided on those matrices' own singular values (rounding eps),
    not E applied to a kernel of TN computed 10^-k from a singularity (error eps / 10^-k,
    which float used to take for an input motion at k = 9)."""
    joints, _ = LOOPS["RSSR"]
    text = _mechanism("rssr", joints, ["A"], {"A": f"pi/2 - 1e-{k}"})
    text = text.replace("inputs: [A]\n", "inputs: [A]\noutput: {body: rocker}\n")
    path = write(tmp_path, "rssr_near", text)
    (c,) = cli_json(
        ["analyze", str(path), "--config", "moved", "--precision", precision, "--format", "json"]
    )["configurations"]
    assert "error" not in c, c["error"]
    assert c["singular"] is not True, classes(c)
    inputs = [d for d in c["decisions"] if d["test"] == "input"]
    assert inputs and all(d["rank"] in (None, d.get("generic")) for d in inputs), inputs
    if precision == "mp:50" or k <= 8:  # decided where the precision can see 10^-k
        assert c["singular"] is False, classes(c)


# ============================================================================ 3. T3-S chain at mp:50

#: also in the matrix test (tests/data) and benchmarks/mp_cost.py
T3_S_CHAIN = (EXAMPLES.parent / "tests" / "data" / "t3_s_chain.yaml").read_text()


def test_t3_s_chain_is_regular_where_charts_are_singular(tmp_path: Path) -> None:
    """A T3 joint then an S joint: the translations and the rotations about the S centre span
    all of se(3) at every pose, so the output screw system has rank 6 everywhere; where Euler
    angles would lock (pi/2 about the middle axis) or the rotation-vector chart is singular
    (2 pi) the verdict is regular.  Independently: L = |c| = 1 with c = (0, 0, 1) the only axis
    point; the S screws are carried by b1's pose (the translation t) and seen from c they are
    (e_i, t x e_i), the T3 screws (0, e_i): the commensurate matrix is [[0, I], [I, t^]] at every
    S value, whose extreme singular values the margin reports."""
    path = write(tmp_path, "t3_s_chain", T3_S_CHAIN)
    res = cli_json(["analyze", str(path), "--precision", "mp:50", "--format", "json"])
    with mpmath.workdps(60):
        t = [mpmath.mpf(x) / 10 for x in (1, 2, 3)]
        M = mpmath.zeros(6, 6)
        for i in range(3):
            M[i, 3 + i] = 1
            M[3 + i, i] = 1
        M[3, 4], M[3, 5], M[4, 3], M[4, 5], M[5, 3], M[5, 4] = -t[2], t[1], t[2], -t[0], -t[1], t[0]
        sig = sorted(mpmath.svd_r(M, compute_uv=False), reverse=True)
    assert len(res["configurations"]) == 3
    for c in res["configurations"]:
        assert c["precision"] == "mp:50" and "error" not in c, c["name"]
        assert c["singular"] is False and classes(c) == [], (c["name"], classes(c))
        (d,) = [x for x in c["decisions"] if x["test"] == "output chain"]
        assert (d["rank"], d["generic"]) == (6, 6), c["name"]
        assert d["margin"]["kept"] == pytest.approx(float(sig[-1]), rel=1e-14)
        assert d["margin"]["sigma_max"] == pytest.approx(float(sig[0]), rel=1e-14)
        assert d["margin"]["dropped"] is None


def test_mp_analysis_never_converts_arrays_through_repr(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """For ``mpf * x`` mpmath first tries to make x an mpf; a numpy array fails only after its
    repr (every entry printed to N digits) has been built, then numpy does the product.  An mp:50
    analysis (a serial chain, and an RSSR through closure, polish and every test) keeps an array
    on the left of each mixed operation, so that path is never taken."""
    calls: list[str] = []
    original = mpmath.mp.npconvert

    def spy(x: object) -> object:
        calls.append(type(x).__name__)
        return original(x)

    monkeypatch.setattr(mpmath.mp, "npconvert", spy)
    chain = write(tmp_path, "t3_s_chain", T3_S_CHAIN)
    joints, config = LOOPS["RSSR"]
    rssr = write(tmp_path, "rssr", _mechanism("rssr", joints, ["A"], config))
    for path in (chain, rssr):
        cli_json(["analyze", str(path), "--precision", "mp:50", "--format", "json"])
    assert calls == []


# ============================================================================ singular targets


@pytest.mark.parametrize("precision", ["mp:30", "mp:50", "auto"])
def test_a_singular_target_reached_from_its_input_is_classified_as_when_fully_given(
    tmp_path: Path, precision: str
) -> None:
    """The parallelogram's flat configuration (A = -pi/2, a change point where the
    parallelogram and anti-parallelogram branches cross) reached from its input alone: the
    passive joints solve a multiple root, whose residual is quadratic in the distance along
    the kernel.  N digits of residual then place it only to 10^(-N/2), where the rank could
    not be decided (mp:30 used to call it regular, mp:50 and auto to stall at 5.7e-32 m); it
    must close to 10^(5-N) L and get the classes of the fully given flat configuration,
    decided exactly.  Independently: on that branch B = -A, C = A, D = -A (a parallelogram
    keeps its links parallel), so the solved values are pi/2, -pi/2, pi/2."""
    src = (EXAMPLES / "parallelogram.yaml").read_text()
    text = src.replace('crank-30: {A: "-pi/6"}', 'flat-solved: {A: "-pi/2"}')
    path = write(tmp_path, "para", text)
    (c,) = cli_json(
        [
            "analyze",
            str(path),
            "--config",
            "flat-solved",
            "--precision",
            precision,
            "--format",
            "json",
        ]
    )["configurations"]
    (exact,) = cli_json(
        ["analyze", str(path), "--config", "flat", "--precision", "exact", "--format", "json"]
    )["configurations"]
    assert "error" not in c, c["error"]
    digits = 50 if precision == "auto" else int(precision[3:])
    assert c["precision"] == f"mp:{digits}"
    assert c["closure_residual"] <= 10.0 ** (5 - digits) * 2
    for name, value in {"B": math.pi / 2, "C": -math.pi / 2, "D": math.pi / 2}.items():
        assert abs(c["joints"][name][0] - value) < 1e-15
    assert classes(c) == classes(exact) and "bifurcation" in classes(c)
