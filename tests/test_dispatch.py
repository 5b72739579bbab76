"""The one dispatch of fast paths (mechsing.numeric.dispatch): one parity test per table.

Every fast form registered in a table is run against the generic definition (the same
call inside ``fast_paths(False)``) on random inputs with the edge cases of the form
(angles 0, -0, tiny, at the series switch, near and at pi, beyond pi; exact half-turns;
screws on the axes, with pitch, pure translations): bit for bit where the form says so,
otherwise to rounding.  A form registered without a check here fails the listing test.
Independent references (scipy's expm, mpmath at 50 digits) check the exponential and
the logarithm themselves.  The switch: ``MECHSING_FAST=0`` (and its alias
``MECHSING_NO_COMPILED=1``) turns every fast path off in a fresh interpreter.
"""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
import scipy.linalg

import mechsing
import mechsing.assembly.certify
import mechsing.kinetics.tree
import mechsing.sweeps.scan
from mechsing import lie, load
from mechsing.kinematics import KinematicModel, forward
from mechsing.lie import _so3
from mechsing.lie._series import SWITCH_T2
from mechsing.numeric import dispatch

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

#: the Lie functions with a float64 form, each its own table
LIE_TABLES = (
    "exp",
    "exp_so3",
    "cross",
    "hat3",
    "quaternion_parts",
    "log_so3_parts",
    "pose",
    "log",
    "inverse",
    "act_screw",
)

#: the forms each table must hold (the parity checks below cover exactly these): one
#: table per formula (one signature), its forms chosen by the table from the arguments
EXPECTED = {
    **{name: {"float64"} for name in LIE_TABLES},
    "joint element": {"one-dof", "universal", "spherical"},
    "joint elements": {"stacked joints"},
    "current screws": {"one configuration", "batch"},
    "inverse dynamics": {"compiled tree"},
    "serial chain": {"batched"},
    "serial screen": {"compiled"},
    # its parity: tests/test_scale.py::test_block_svd_equals_the_dense_svd (with the
    # block-diagonal matrices of that module)
    "factorisation": {"blocks"},
    "dense factorisation": {"lapack"},
    "sweep test factors": {"values first"},
    # their parity: tests/test_dispatch_certify.py
    "krawczyk test": {"double contraction"},
    "newton start": {"double steps"},
    "newton steps": {"chord"},
    "regular root": {"double bound"},
}


@pytest.fixture(autouse=True)
def _fast_paths_on():
    """The fast forms are on in these tests whatever the environment says (CI also runs
    the mathematical modules with MECHSING_FAST=0)."""
    with dispatch.fast_paths(True):
        yield


def test_every_table_and_form_is_listed_and_checked() -> None:
    got = {name: set(t.forms) for name, t in dispatch.tables().items()}
    assert got == EXPECTED
    for t in dispatch.tables().values():
        assert t.generic
        for form in t.forms.values():
            assert callable(form.function) and form.when


def generic(f, *args):
    """f(*args) with every fast path off."""
    with dispatch.fast_paths(False):
        return f(*args)


def _same(a: np.ndarray, b: np.ndarray) -> None:
    """Equal bit for bit (zeros' signs included)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape
    assert np.array_equal(a, b, equal_nan=True)
    assert np.array_equal(np.signbit(a), np.signbit(b))


def _close(fast: np.ndarray, slow: np.ndarray, scale: np.ndarray | float = 1.0) -> None:
    """Equal to rounding: a few ulps of the entries' size (times ``scale``, the angle's
    size where rounding grows with it)."""
    size = np.maximum(1.0, np.abs(slow)) * scale
    assert fast.shape == slow.shape
    assert np.all(np.abs(fast - slow) <= 2e-15 * 8 * size)


# ------------------------------------------------------------------------ the inputs


def _angles(n: int, rng: np.random.Generator) -> np.ndarray:
    """Angles at the branch points: 0, tiny, around the series switch, generic, near pi,
    exactly pi, beyond pi."""
    s = math.sqrt(SWITCH_T2)
    fixed = [0.0, 1e-300, 1e-160, 1e-12, 1e-8, s, np.nextafter(s, 0), np.nextafter(s, 2)]
    fixed += [math.pi, np.nextafter(math.pi, 0), math.pi - 1e-9, math.pi - 1e-5, 4.0, 7.5]
    rest = np.concatenate(
        [
            10.0 ** rng.uniform(-17, 0, n),
            rng.uniform(0.5, 1.5, n),
            rng.uniform(0, math.pi, n),
            math.pi - 10.0 ** rng.uniform(-16, -1, n),
        ]
    )
    return np.concatenate([fixed, rest])


def _rotation_vectors(rng: np.random.Generator, n: int = 60) -> np.ndarray:
    th = _angles(n, rng)
    u = rng.normal(size=(len(th), 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    u[:3] = [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]  # on the axes
    return u * th[:, None]


def _twists(rng: np.random.Generator) -> np.ndarray:
    w = _rotation_vectors(rng)
    v = rng.normal(size=w.shape) * 3.0
    v[::7] = 0.0
    return np.concatenate([w, v], axis=1)


def _displacements(rng: np.random.Generator) -> np.ndarray:
    g = generic(lie.exp, _twists(rng))
    # exact half-turns and the identity, which the principal log treats apart
    g[0] = np.eye(4)
    g[1, :3, :3] = np.diag([1.0, -1.0, -1.0])
    g[2, :3, :3] = np.diag([-1.0, -1.0, 1.0])
    return g


def _joint_angles(rng: np.random.Generator) -> np.ndarray:
    """Joint values with signs: 0, -0, tiny, pi, -pi, beyond, random."""
    fixed = [0.0, -0.0, 1e-300, -1e-12, 1e-8, math.pi, -math.pi, np.nextafter(math.pi, 0)]
    fixed += [math.pi - 1e-9, 2 * math.pi, -7.0, 12.5]
    return np.concatenate([fixed, rng.uniform(-4, 4, 100), 10.0 ** rng.uniform(-17, 0, 30)])


def _one_dof_screws(rng: np.random.Generator) -> list[np.ndarray]:
    """A revolute on an axis, one off the origin with pitch, a general screw, a slider."""
    u = rng.normal(size=3)
    u /= np.linalg.norm(u)
    return [
        np.array([0.0, 0.0, 1.0, 0.0, -2.0, 0.0]),
        np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.5]),
        np.concatenate([u, np.cross(rng.normal(size=3), u) + 0.3 * u]),
        np.array([0.0, 0.0, 0.0, 0.6, 0.0, -0.8]),
    ]


# ------------------------------------------------------ the Lie functions' tables


LIE_FLOAT64 = {
    "exp": (lie.exp, "twist"),
    "exp_so3": (lambda x: lie.exp_so3(x[..., :3]), "twist"),
    "hat3": (lambda x: _so3.hat3(x[..., :3]), "twist"),
    "cross": (lambda x: _so3.cross(x[..., :3], x[..., 3:]), "twist"),
    "log": (lie.log, "displacement"),
    "log_so3_parts": (
        lambda g: np.concatenate(
            [np.stack(_so3.log_so3_parts(g[..., :3, :3])[1:], axis=-1)]
            + [_so3.log_so3_parts(g[..., :3, :3])[0]],
            axis=-1,
        ),
        "displacement",
    ),
    "quaternion_parts": (
        lambda g: np.concatenate(
            [
                lie.quaternion_parts(g[..., :3, :3])[0][..., None],
                lie.quaternion_parts(g[..., :3, :3])[1],
            ],
            axis=-1,
        ),
        "displacement",
    ),
    "inverse": (lie.inverse, "displacement"),
    "pose": (lambda g: lie.pose(g[..., :3, :3], g[..., :3, 3]), "displacement"),
    "act_screw": (
        lambda g: lie.act_screw(g, np.array([0.3, -0.2, 0.9, 1.5, -2.0, 0.25])),
        "displacement",
    ),
}


def _lie_input(kind: str, rng: np.random.Generator) -> np.ndarray:
    return _twists(rng) if kind == "twist" else _displacements(rng)


def _bit_for_bit_row_by_row(f, x: np.ndarray) -> None:
    """f's fast form is the generic code bit for bit on the batch; each row gets the
    numbers it gets alone, and stacks of stacks keep the generic shapes."""
    whole = f(x)
    _same(whole, generic(f, x))
    for i in range(0, len(x), 5):
        _same(f(x[i]), whole[i])
        _same(f(x[i]), generic(f, x[i]))
    k = len(x) // 2 * 2
    _same(
        f(x[:k].reshape((2, k // 2) + x.shape[1:])),
        whole[:k].reshape((2, k // 2) + whole.shape[1:]),
    )


@pytest.mark.parametrize("form", sorted(LIE_TABLES))
def test_lie_float64_table_parity(form: str) -> None:
    f, kind = LIE_FLOAT64[form]
    _bit_for_bit_row_by_row(f, _lie_input(kind, np.random.default_rng(11)))
    if form == "act_screw":  # broadcast of (N, 1) displacements on (3,) screws
        rng = np.random.default_rng(13)
        g = _displacements(rng)[:, None]
        basis = rng.normal(size=(3, 6))
        _same(lie.act_screw(g, basis), generic(lie.act_screw, g, basis))


# ------------------------------------------------------------------------ table exp


def _stewart_joints() -> tuple:
    model = KinematicModel(load(EXAMPLES / "stewart_octahedral.yaml"), "float")
    return model, {jk.type: jk for jk in model.joints}


def _check_one_dof(rng: np.random.Generator) -> None:
    from mechsing.lie._rodrigues import one_dof_exp

    th = _joint_angles(rng)[:40]  # below the entrywise threshold: the broadcasts
    for e in _one_dof_screws(rng):
        got = one_dof_exp(e, th)
        _close(got, generic(lie.exp, th[:, None] * e), np.maximum(1.0, np.abs(th))[:, None, None])
        assert np.array_equal(got[:2], [np.eye(4)] * 2)  # 0 and -0: the identity
    # a large batch of finite angles is filled entry by entry: the numbers of the
    # broadcast form (each angle alone) bit for bit; "always" takes it at any size
    th = _joint_angles(rng)
    for e in _one_dof_screws(rng):
        got = one_dof_exp(e, th)
        with dispatch.fast_paths("always"):
            _same(one_dof_exp(e, th[:3]), got[:3])
        for i in range(0, th.size, 13):
            _same(one_dof_exp(e, th[i : i + 1])[0], got[i])
    # the table takes it for a float batch of a one-dof joint, not for one configuration
    model, kinds = _stewart_joints()
    jk = kinds["P"]
    Q = rng.uniform(-1, 1, size=(50, model.n))
    assert dispatch.table("joint element").pick(jk, Q) is not None
    assert dispatch.table("joint element").pick(jk, Q[0]) is None
    _close(forward.batch_element(jk, Q), generic(forward.batch_element, jk, Q))
    _same(generic(forward.batch_element, jk, Q), forward.element(jk, Q))


def _check_universal(rng: np.random.Generator) -> None:
    model, kinds = _stewart_joints()
    jk = kinds["U"]
    Q = rng.uniform(-7, 7, size=(60, model.n))
    Q[:4, jk.columns] = [[0.0, 0.0], [math.pi, 0.0], [1e-12, -math.pi], [-0.0, 1e-300]]
    _close(forward.batch_element(jk, Q), forward.element(jk, Q), 8.0)


def _check_spherical(rng: np.random.Generator) -> None:
    model, kinds = _stewart_joints()
    jk = kinds["S"]
    u = rng.normal(size=(60, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    angles = np.concatenate([[0.0, 1e-12, math.pi, math.pi - 1e-9], rng.uniform(0, 7, 56)])
    Q = np.zeros((60, model.n))
    Q[:, jk.columns] = u * angles[:, None]
    _close(forward.batch_element(jk, Q), forward.element(jk, Q), 4.0)


def _scanners(path: Path) -> tuple:
    mech = load(path)
    with dispatch.fast_paths(False):
        slow = mechsing.sweeps.scan.ChainScanner(mech)
    return mechsing.sweeps.scan.ChainScanner(mech), slow


def _check_serial_chain(rng: np.random.Generator) -> None:
    for file in ("ur5.yaml", "puma560.yaml"):
        fast, slow = _scanners(EXAMPLES / file)
        Q = rng.uniform(-7, 7, size=(200, fast.n))
        Q[:20] = 0.0
        Q[20:40, 2] = math.pi
        _close(fast.matrices(Q), generic(slow.matrices, Q), 8.0)


def _check_compiled_serial_chain(rng: np.random.Generator) -> None:
    pytest.importorskip("numba")
    from mechsing.numeric import SCAN_ROUNDING_FACTOR

    fast, _slow = _scanners(EXAMPLES / "ur5.yaml")
    assert fast.compiled
    with dispatch.fast_paths(False):
        assert not fast.compiled
    Q = rng.uniform(-math.pi, math.pi, size=(3000, fast.n))
    Q[:300, 4] = 10.0 ** -rng.integers(0, 17, size=300)
    Q[300:600, 2] = 0.0
    got = fast.scan(Q)
    want = generic(fast.scan, Q)
    np.testing.assert_array_equal(got.rank, want.rank)
    # both bounds are the same formula, each lowered by the determinant's backward error
    err = SCAN_ROUNDING_FACTOR * 6 * np.finfo(float).eps
    assert np.all(np.abs(got.bound - want.bound) <= 2 * err)
    assert np.count_nonzero(got.rank < 6) > 0


def _check_stacked_joints(rng: np.random.Generator) -> None:
    # the poses of one float configuration from one exp of every joint's twist stacked:
    # each joint's element alone, bit for bit (exp is row by row)
    for name in ("stewart_octahedral", "five_bar", "tsai_3upu", "planar_3rpr"):
        model = KinematicModel(load(EXAMPLES / f"{name}.yaml"), "float")
        for q in rng.normal(size=(5, model.n)) * 1.5:
            fast = forward.poses(model, q)
            slow = generic(forward.poses, model, q)
            assert fast.keys() == slow.keys()
            for body, g in slow.items():
                _same(fast[body], g)


JOINT_CHECKS = {
    ("joint element", "one-dof"): _check_one_dof,
    ("joint element", "universal"): _check_universal,
    ("joint element", "spherical"): _check_spherical,
    ("joint elements", "stacked joints"): _check_stacked_joints,
    ("serial chain", "batched"): _check_serial_chain,
    ("serial screen", "compiled"): _check_compiled_serial_chain,
}


@pytest.mark.parametrize("table, form", sorted(JOINT_CHECKS))
def test_joint_table_parity(table: str, form: str) -> None:
    assert form in EXPECTED[table]
    JOINT_CHECKS[table, form](np.random.default_rng(21))


# --------------------------------------------------------------- table current screws


@pytest.mark.parametrize("form", sorted(EXPECTED["current screws"]))
def test_current_screws_table_parity(form: str) -> None:
    """The screws of every joint at one float configuration (stacked) or a batch (written
    in place): the joint-by-joint products of the generic definition, bit for bit."""
    rng = np.random.default_rng(22)
    for name in ("stewart_octahedral", "five_bar", "tsai_3upu", "planar_3rpr"):
        model = KinematicModel(load(EXAMPLES / f"{name}.yaml"), "float")
        Q = rng.normal(size=(80, model.n)) * 1.5
        Q[:10] *= 1e-9
        Q[10] = 0.0
        if form == "batch":
            P = forward.batch_poses(model, Q)
            _same(forward.current_screws(model, Q, P), generic(forward.current_screws, model, Q, P))
        else:
            for q in Q[::9]:
                P = forward.poses(model, q)
                _same(
                    forward.current_screws(model, q, P),
                    generic(forward.current_screws, model, q, P),
                )


def test_exp_and_log_against_independent_references() -> None:
    """exp against scipy's expm of the 4x4 hat; log as the inverse of mpmath's expm at
    50 digits (angles below pi, where log inverts exp); with fast paths on and off."""
    rng = np.random.default_rng(14)
    xi = _twists(rng)
    for on in (True, False):
        with dispatch.fast_paths(on):
            g = lie.exp(xi)
            for x, gx in zip(xi, g, strict=True):
                ref = scipy.linalg.expm(lie.hat(x))
                scale = max(1.0, np.abs(ref).max())
                assert np.abs(gx - ref).max() <= 5e-14 * scale * max(1.0, np.linalg.norm(x[:3]))
            inside = np.linalg.norm(xi[:, :3], axis=1) < math.pi - 1e-6
            with mpmath.workdps(50):
                for x in xi[inside][::3]:
                    E = mpmath.expm(mpmath.matrix(lie.hat(x).tolist()))
                    g50 = np.array([[float(E[i, j]) for j in range(4)] for i in range(4)])
                    back = lie.log(g50)
                    assert np.abs(back - x).max() <= 1e-13 * max(1.0, np.abs(x).max())


def test_mp_and_exact_arrays_keep_the_generic_code() -> None:
    """Object arrays (mp, exact) never take a float form: their results stay objects
    and agree with float to float's rounding."""
    x = np.array([0.3, -0.2, 0.5, 1.0, 2.0, -0.5])
    with mpmath.workdps(30):
        xm = np.array([mpmath.mpf(float(c)) for c in x], dtype=object)
        gm = lie.exp(xm)
        assert gm.dtype == object
        assert np.abs(np.array(gm, dtype=float) - lie.exp(x)).max() < 1e-15 * 4
        back = lie.log(gm)
        assert back.dtype == object
        assert max(abs(back[i] - xm[i]) for i in range(6)) < mpmath.mpf(10) ** -25


# ------------------------------------------------------------------------ the switch


def _probe(env: dict[str, str]) -> str:
    code = (
        "import mechsing.sweeps.scan_kernel as k; from mechsing.numeric import dispatch; "
        "print(dispatch.mode(), k.available())"
    )
    switches = ("MECHSING_FAST", "MECHSING_NO_COMPILED")
    clean = {k: v for k, v in os.environ.items() if k not in switches}
    run = subprocess.run(
        [sys.executable, "-c", code],
        env={**clean, **env},
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    )
    return run.stdout.strip()


def test_the_environment_switch_turns_every_fast_path_off() -> None:
    assert _probe({"MECHSING_FAST": "0"}) == "off False"
    assert _probe({"MECHSING_NO_COMPILED": "1"}) == "off False"  # the older alias
    assert _probe({"MECHSING_FAST": "1"}).startswith("on ")
    with dispatch.fast_paths(False):
        assert not dispatch.enabled()
        assert dispatch.table("joint element").get("one-dof") is None
        assert dispatch.table("exp").pick(np.zeros(6)) is None
        assert dispatch.threshold(64) == math.inf
        with dispatch.fast_paths("always"):
            assert dispatch.threshold(64) == 0
    joint = dispatch.table("joint element")
    with joint.disabled("one-dof"):
        assert joint.get("one-dof") is None and joint.get("spherical") is not None
    assert joint.get("one-dof") is not None
    assert dispatch.table("exp").pick(np.zeros(6)) is not None
    assert dispatch.table("exp").pick(np.zeros(6, dtype=object)) is None
    with pytest.raises(ValueError, match="fast_paths takes"):
        with dispatch.fast_paths("yes"):  # type: ignore[arg-type]
            pass


def test_no_test_chooses_a_path_by_patching_mechsing() -> None:
    """Tests choose a path through dispatch.fast_paths, never by patching the module
    constants or switches that used to choose one, nor by setting the switch's
    environment variables in-process (read once, when mechsing is imported)."""
    patched = re.compile(
        r"monkeypatch\.(setattr\([^\n]*\b(DENSE_ENTRIES|ENTRYWISE|_ENTRYWISE|pointwise|F64)\b"
        r"|(setenv|delenv)\(\s*\"MECHSING_(FAST|NO_COMPILED))"
    )
    offenders = [
        f"{p.name}:{text[: m.start()].count(chr(10)) + 1}"
        for p in sorted((ROOT / "tests").glob("*.py"))
        for text in [p.read_text(encoding="utf-8")]
        for m in patched.finditer(text)
    ]
    assert offenders == []


def test_callers_hand_their_arguments_to_the_table() -> None:
    """Outside mechsing.numeric no code names a fast form (for_float, fast=): each
    formula's generic definition hands its arguments to its table, which picks."""
    named = re.compile(r"\.for_float\(|\bfast\s*=\s*(True|False|fast)\b|\bfast: bool\b")
    offenders = [
        f"{p.relative_to(ROOT)}:{text[: m.start()].count(chr(10)) + 1}"
        for p in sorted((ROOT / "mechsing").rglob("*.py"))
        if "numeric" not in p.parts
        for text in [p.read_text(encoding="utf-8")]
        for m in named.finditer(text)
    ]
    assert offenders == []
    # the table chooses from the arguments: float64 arrays take the float64 form,
    # object arrays (mp, exact) the generic definition
    table = dispatch.table("exp")
    assert table.pick(np.zeros(6)) is table.forms["float64"].function
    assert table.pick(np.zeros(6, dtype=object)) is None
    model = KinematicModel(load(EXAMPLES / "stewart_octahedral.yaml"), "float")
    joint = dispatch.table("joint element")
    Q = np.zeros((4, model.n))
    for jk in model.joints:
        kind = {"U": "universal", "S": "spherical"}.get(jk.type, "one-dof")
        assert joint.pick(jk, Q) is joint.forms[kind].function
        assert joint.pick(jk, Q[0]) is None  # one configuration: lie.exp's numbers


# --------------------------------------------------------------- table inverse dynamics

#: a tree with a revolute, a prismatic and a helical joint, one crossed from between[1]
DYNAMICS_TREE = """\
mechanism: tree
bodies: [ground, a, b, c]
joints:
  - {name: J1, type: R, between: [ground, a], axis: [0, 0, 1], point: [0, 0, 0.1]}
  - {name: J2, type: P, between: [b, a], axis: [1, 1, 0]}
  - {name: J3, type: H, between: [a, c], axis: [0, 1, 0], point: [0.5, 0, 0], pitch: 0.1}
mass:
  a: {kg: 2, centre: [0.2, 0, 0.1], inertia: [0.02, 0.03, 0.04, 0.001, 0, 0]}
  b: {kg: 1, centre: [0.7, 0.3, 0], inertia: [0.01, 0.01, 0.015, 0, 0, 0.002]}
  c: {kg: 0.5, centre: [0.5, 0.2, 0.1], inertia: [0.005, 0.004, 0.006, 0, 0, 0]}
gravity: [0, 0, -9.81]
"""


@pytest.mark.parametrize("form", sorted(EXPECTED["inverse dynamics"]))
def test_inverse_dynamics_table_parity(form: str) -> None:
    """The compiled recursive Newton-Euler against the generic one (numpy on whole
    arrays), to rounding, on the UR5 and on a tree with R, P and H joints, one crossed
    backwards; with and without gravity."""
    pytest.importorskip("numba")
    from mechsing.kinetics.tree import TreeDynamics
    from mechsing.model import loads

    rng = np.random.default_rng(43)
    for mech in (load(EXAMPLES / "ur5.urdf"), loads(DYNAMICS_TREE, path="tree.yaml")):
        td = TreeDynamics(KinematicModel(mech, "float"), (0, 0, -9.81))
        Q, V, A = (rng.uniform(-3, 3, size=(200, td.n)) for _ in range(3))
        for gravity in (True, False):
            fast = td.inverse(Q, V, A, gravity)
            slow = generic(td.inverse, Q, V, A, gravity)
            assert np.all(np.abs(fast - slow) <= 1e-13 * np.maximum(1.0, np.abs(slow).max()))


# --------------------------------------------------------------- table sweep test factors


def test_sweep_values_first_parity() -> None:
    """A sweep test's singular values without its vectors: numpy's thin SVD's own values
    (bit for bit) at the matrices near a rank decision (the g-th value under 5% of the
    largest, or a later one neither negligible nor large), the same values to a few eps
    elsewhere; the vectors, read later, are the thin SVD's of the same matrix."""
    from mechsing.sweeps import factors

    rng = np.random.default_rng(23)
    A = rng.normal(size=(400, 6, 6))
    # rank 5 (a zero singular value), a small sixth one, a small fifth one
    A[:100, :, 5] = A[:100, :, :5] @ rng.normal(size=5)
    A[100:200, :, 5] = A[100:200, :, :5] @ rng.normal(size=5) + 1e-6 * rng.normal(size=(100, 6))
    A[200:250, :, 4] = A[200:250, :, 3] + 1e-7 * rng.normal(size=(50, 6))
    form = dispatch.table("sweep test factors").get("values first")
    for g, unit in ((5, False), (6, False), (5, True)):
        got = form(A, g, unit)
        want = np.linalg.svd(A, full_matrices=False)[1]
        rel = want / want[:, :1]
        near = rel[:, g - 1] < 0.05
        if g < 6:
            near |= (rel[:, g:] > 1e-13).any(axis=1) & (rel[:, g:] < 0.05).any(axis=1)
        if unit:
            near |= want[:, g - 1] < 0.05
        assert near[100:250].all()
        _same(got[near], want[near])
        assert np.allclose(got[~near], want[~near], rtol=1e-13, atol=1e-15 * want[~near, :1])
    # a matrix's values are the same in any batch (a grid's rows alone or together)
    _same(form(A[95:105], 5, False), form(A, 5, False)[95:105])
    # the generic definition with the fast paths off
    with dispatch.fast_paths(False):
        assert dispatch.table("sweep test factors").pick(A, 5, False) is None
    assert factors.VALUES is dispatch.table("sweep test factors")


# ------------------------------------------------------------- table dense factorisation


def test_dense_factorisation_lapack_parity() -> None:
    """A small float matrix's SVD by numpy's LAPACK gufunc called directly: numpy.linalg.svd's
    factors and values bit for bit (full and thin, with and without vectors), on matrices
    of every shape up to 12 x 12, rank-deficient, with zero columns, tiny and huge; a
    matrix with a NaN or too many entries is not taken (numpy's wrapper decides it)."""
    from mechsing.numeric import blocks

    rng = np.random.default_rng(29)
    mats = [np.zeros((6, 6)), np.ones((6, 3)), np.eye(6) * 1e-300, np.eye(4) * 1e300]
    for _ in range(300):
        m, n = rng.integers(1, 13, 2)
        A = rng.normal(size=(m, n)) * 10.0 ** rng.uniform(-30, 30)
        if n > 2:
            A[:, 0] = A[:, 1] * 10.0 ** rng.uniform(-20, 0)
            A[:, 2] = 0.0
        mats.append(A)
    table = dispatch.table("dense factorisation")
    form = table.get("lapack")
    for A in mats:
        for full in (True, False):
            assert table.pick(A, full, True) is form
            got = form(A, full, True)
            want = np.linalg.svd(A, full_matrices=full)
            for g, w in zip(got, want, strict=True):
                _same(g, w)
        _same(form(A, True, False), np.linalg.svd(A, compute_uv=False))
        # the caller's entry point takes it
        _same(blocks.dense_svd(A, False, False), np.linalg.svd(A, compute_uv=False))
    bad = np.ones((3, 3))
    bad[1, 1] = np.nan
    assert table.pick(bad, True, True) is None
    assert table.pick(np.ones((70, 70)), True, True) is None
    assert table.pick(np.ones((3, 3), dtype=np.float32), True, True) is None
    with dispatch.fast_paths(False):
        assert table.pick(mats[5], True, True) is None
