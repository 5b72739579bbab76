"""The batched closure of the sweeps updates the spherical joints all at once, with the
numbers of the joint-by-joint composition bit for bit, at angles 0, tiny, near pi and
beyond, and agrees with scipy's expm.  (The fast forms of the exponential and of the
current screws: their parity tests in tests/test_dispatch.py.)"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import scipy.linalg

from mechsing import lie, load
from mechsing.kinematics import KinematicModel
from mechsing.kinematics.batch_newton import BatchClosure
from mechsing.lie import exp_so3, log_so3

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _same(a: np.ndarray, b: np.ndarray) -> None:
    assert a.shape == b.shape
    assert np.array_equal(a, b)
    assert np.array_equal(np.signbit(a), np.signbit(b))


def test_spherical_joints_updated_all_at_once_joint_by_joint_numbers() -> None:
    """BatchClosure.update and difference of the hexapod's six S joints: one Lie call for
    all of them, the numbers of the joint-by-joint composition exp(d W) exp(q W)."""
    model = KinematicModel(load(EXAMPLES / "stewart_octahedral.yaml"), "float")
    bc = BatchClosure(model)
    rng = np.random.default_rng(23)
    N = 60
    Q = rng.normal(size=(N, model.n))
    D = rng.normal(size=(N, model.n)) * 0.1
    for jk in model.joints:
        if jk.type == "S":
            u = rng.normal(size=(N, 3))
            u /= np.linalg.norm(u, axis=1)[:, None]
            Q[:, jk.columns] = (
                u
                * np.concatenate(
                    [[0.0, 1e-12, math.pi, math.pi - 1e-9], rng.uniform(0, 3.1, N - 4)]
                )[:, None]
            )
            D[:5, jk.columns] = [
                [0, 0, 0],
                [1e-15, 0, 0],
                [0, -1e-9, 0],
                [0.5, 0.5, 0.5],
                [3.0, 0, 0],
            ]
    up = bc.update(Q, D)
    diff = bc.difference(Q, Q[::-1])
    for jk in model.joints:
        if jk.type != "S":
            continue
        W = np.asarray(jk.basis, dtype=float)[:, :3]
        Wi = np.linalg.inv(W)
        R = exp_so3(D[:, jk.columns] @ W) @ exp_so3(Q[:, jk.columns] @ W)
        _same(up[:, jk.columns], log_so3(R) @ Wi)
        R = exp_so3(Q[:, jk.columns] @ W) @ np.swapaxes(exp_so3(Q[::-1, jk.columns] @ W), -1, -2)
        _same(diff[:, jk.columns], log_so3(R) @ Wi)
        # and the rotation reached is exp(d W) exp(q W) (scipy's expm, independent)
        for i in range(0, N, 11):
            want = scipy.linalg.expm(lie.hat(np.concatenate([D[i, jk.columns] @ W, [0, 0, 0]])))
            want = (
                want[:3, :3]
                @ scipy.linalg.expm(lie.hat(np.concatenate([Q[i, jk.columns] @ W, [0, 0, 0]])))[
                    :3, :3
                ]
            )
            assert np.abs(exp_so3(up[i, jk.columns] @ W) - want).max() < 1e-12
