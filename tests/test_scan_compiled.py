"""The scanner's compiled screen (the ``fast`` extra) against its numpy path.

Both must give the same verdict at every configuration: random ones, ones near
the published singular sets of the UR5 (its wrist, q5 = 0, and its elbow,
q3 = 0), a 7R arm at the alignment of its joints 1, 3 and 5, and chains with a
point output (3 rows) and with prismatic joints.  The bound itself is the same
formula, so it agrees to rounding wherever it is not tiny.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import mechsing
from mechsing.numeric import SCAN_ROUNDING_FACTOR, dispatch
from mechsing.sweeps import scan_kernel
from mechsing.sweeps.scan import ChainScanner
from tests.mechanisms import EXAMPLES

pytestmark = pytest.mark.skipif(
    not scan_kernel.available(), reason="numba is not installed (the `fast` extra)"
)

PANDA = """mechanism: panda
units: {length: m, angle: deg}
dh:
  convention: modified
  rows:
    - {theta: 0, d: 0.333, a: 0, alpha: 0}
    - {theta: 0, d: 0, a: 0, alpha: -90}
    - {theta: 0, d: 0.316, a: 0, alpha: 90}
    - {theta: 0, d: 0, a: 0.0825, alpha: 90}
    - {theta: 0, d: 0.384, a: -0.0825, alpha: -90}
    - {theta: 0, d: 0, a: 0, alpha: 90}
    - {theta: 0, d: 0, a: 0.088, alpha: 90}
output: {body: L7}
"""

ARM_2R_POINT = """mechanism: arm2r
dh:
  convention: standard
  rows:
    - {theta: 0, d: 0, a: 1, alpha: 0}
    - {theta: 0, d: 0, a: 0.5, alpha: 0}
output: {body: L2, point: [1.5, 0, 0]}
"""


#: one-dof joints of every kind the fast path takes (R, P, H), with lengths in mm
RPHRRR = """mechanism: rphrrr
units: {length: mm}
bodies: [base, a, b, c, d, e, f]
joints:
  - {name: J1, type: R, between: [base, a], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: P, between: [a, b], axis: [1, 0, 0]}
  - {name: J3, type: H, between: [b, c], axis: [0, 1, 0], point: [300, 0, 200], pitch: 5}
  - {name: J4, type: R, between: [c, d], axis: [1, 0, 0], point: [300, 100, 400]}
  - {name: J5, type: R, between: [d, e], axis: [0, 1, 0], point: [300, 100, 600]}
  - {name: J6, type: R, between: [e, f], axis: [0, 0, 1], point: [300, 100, 700]}
output: {body: f}
"""


def _configurations(n: int, joints: int, special: list[tuple[int, float | None]]) -> np.ndarray:
    rng = np.random.default_rng(4)
    Q = rng.uniform(-math.pi, math.pi, size=(n, joints))
    for i, (col, value) in enumerate(special):
        rows = slice(i * n // 10, (i + 1) * n // 10)
        size = rows.stop - rows.start
        Q[rows, col] = 10.0 ** -rng.integers(0, 17, size=size) if value is None else value
    return Q


def _both(sc: ChainScanner, Q: np.ndarray) -> tuple:
    with dispatch.fast_paths(True):
        assert sc.compiled
        fast = sc.scan(Q)
        with dispatch.table("serial screen").disabled("compiled"):  # the numpy path
            assert not sc.compiled
            slow = sc.scan(Q)
    return fast, slow


def _check(fast, slow, square: bool = True, m: int = 6) -> None:
    np.testing.assert_array_equal(fast.rank, slow.rank)
    # both bounds are the same formula, each lowered by the determinant's backward error
    # (16 m eps for det J, its square root for the Gram determinant): they agree within it
    err = SCAN_ROUNDING_FACTOR * m * np.finfo(float).eps
    err = err if square else math.sqrt(err)
    assert np.all(np.abs(fast.bound - slow.bound) <= 2 * err)
    # a configuration screened by one path and not the other sits at the threshold
    differ = fast.screened != slow.screened
    assert np.all(np.abs(slow.bound[differ] / 1e-8 - 1) < 1e-6)


@pytest.mark.parametrize(
    "path, special",
    [
        (EXAMPLES / "ur5.yaml", [(4, None), (2, 0.0), (2, None)]),
        (EXAMPLES / "puma560.yaml", [(4, None), (2, None)]),
        ("rphrrr", []),
    ],
)
def test_compiled_screen_gives_the_numpy_verdicts(path, special, tmp_path):
    if path == "rphrrr":
        path = tmp_path / "rphrrr.yaml"
        path.write_text(RPHRRR)
    sc = ChainScanner(mechsing.load(path))
    Q = _configurations(4000, sc.n, special)
    fast, slow = _both(sc, Q)
    _check(fast, slow)
    if special:
        assert np.count_nonzero(fast.rank < 6) > 0  # a singular set was reached


def test_a_7r_arm_and_a_point_output(tmp_path):
    panda = tmp_path / "panda.yaml"
    panda.write_text(PANDA)
    sc = ChainScanner(mechsing.load(panda))
    Q = _configurations(3000, 7, [(1, None), (3, None), (5, None)])
    # joints 1, 3 and 5 on one line: q2 = q4 = q6 = 0 (three equal screws, rank 5)
    Q[-300:, [1, 3, 5]] = 0.0
    fast, slow = _both(sc, Q)
    _check(fast, slow, square=False)
    assert np.all(fast.rank[-300:] == 5)
    arm = tmp_path / "arm2r.yaml"
    arm.write_text(ARM_2R_POINT)
    sc = ChainScanner(mechsing.load(arm))
    Q = _configurations(2000, 2, [(1, None), (1, math.pi)])
    fast, slow = _both(sc, Q)
    _check(fast, slow, square=False, m=2)
    # the tip's velocity loses rank exactly where the arm is stretched or folded
    assert np.all(fast.rank[200:400] == 1)
