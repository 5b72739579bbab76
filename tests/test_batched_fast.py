"""The batched float kinematics of the sweeps: its fast forms (a one-dof rotation filled
entry by entry, the current screws written in place, the spherical joints updated all at
once) give the numbers of the plain formulas bit for bit, at angles 0, tiny, near pi and
beyond, and agree with scipy's expm."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import scipy.linalg

from mechsing import lie, load
from mechsing.kinematics import KinematicModel, batched
from mechsing.kinematics.batch import BatchClosure
from mechsing.lie import exp_so3, log_so3

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _angles(rng: np.random.Generator) -> np.ndarray:
    fixed = [0.0, -0.0, 1e-300, -1e-12, 1e-8, math.pi, -math.pi, np.nextafter(math.pi, 0)]
    fixed += [math.pi - 1e-9, 2 * math.pi, -7.0, 12.5]
    return np.concatenate([fixed, rng.uniform(-4, 4, 100), 10.0 ** rng.uniform(-17, 0, 30)])


def _same(a: np.ndarray, b: np.ndarray) -> None:
    assert a.shape == b.shape
    assert np.array_equal(a, b)
    assert np.array_equal(np.signbit(a), np.signbit(b))


def _one_dof_plain(e: np.ndarray, th: np.ndarray) -> np.ndarray:
    """The Rodrigues form of exp(th e), written out with (N, 3, 3) broadcasts."""
    u, v = e[:3], e[3:]
    K = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    K2 = K @ K
    s, c1 = np.sin(th), 1.0 - np.cos(th)
    out = np.zeros(th.shape + (4, 4))
    out[..., 3, 3] = 1.0
    out[..., :3, :3] = np.eye(3) + s[..., None, None] * K + c1[..., None, None] * K2
    out[..., :3, 3] = th[..., None] * v + c1[..., None] * (K @ v) + (th - s)[..., None] * (K2 @ v)
    return out


def test_one_dof_rotation_entry_by_entry_is_the_plain_formula() -> None:
    rng = np.random.default_rng(21)
    th = _angles(rng)
    assert th.size >= batched._ENTRYWISE  # the entry-by-entry form is taken
    axes = [np.array([0.0, 0.0, 1.0, 0.0, -2.0, 0.0]), np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.5])]
    u = rng.normal(size=3)
    u /= np.linalg.norm(u)
    axes.append(np.concatenate([u, np.cross(rng.normal(size=3), u) + 0.3 * u]))
    for e in axes:
        got = batched._one_dof_exp(e, th)
        _same(got, _one_dof_plain(e, th))
        # a small batch takes the broadcast form: each angle the same numbers
        for i in range(0, th.size, 13):
            _same(batched._one_dof_exp(e, th[i : i + 1])[0], got[i])
        for t, g in zip(th[::9], got[::9], strict=True):
            ref = scipy.linalg.expm(lie.hat(t * e))
            assert np.abs(g - ref).max() <= 1e-13 * max(1.0, abs(t)) * max(1.0, np.abs(e).max())


def _screws_plain(model: KinematicModel, Q: np.ndarray, P: dict) -> np.ndarray:
    cols = []
    for jk in model.joints:
        ga = P[jk.a]
        if jk.type == "U":
            qa = Q[:, jk.columns.start, None]
            cols.append(lie.act_screw(ga, jk.basis[0]))
            cols.append(lie.act_screw(ga @ lie.exp(jk.basis[0] * qa), jk.basis[1]))
        else:
            cols.extend(np.moveaxis(lie.act_screw(ga[:, None, :, :], jk.basis), -2, 0))
    return np.stack(cols, axis=-1)


def test_batched_poses_and_screws_are_the_plain_products() -> None:
    rng = np.random.default_rng(22)
    for name in ("stewart_octahedral", "five_bar", "tsai_3upu", "planar_3rpr"):
        model = KinematicModel(load(EXAMPLES / f"{name}.yaml"), "float")
        Q = rng.normal(size=(80, model.n)) * 1.5
        Q[:10] *= 1e-9
        P = batched.poses(model, Q, fast=True)
        S = batched.current_screws(model, Q, P)
        _same(S, _screws_plain(model, Q, P))
        for i in range(0, len(Q), 17):  # one configuration alone (the analysis's path)
            one = batched.current_screws(model, Q[i], batched.poses(model, Q[i]))
            assert np.abs(one - S[i]).max() <= 1e-13 * max(1.0, np.abs(one).max())
            for body, g in batched.poses(model, Q[i]).items():
                assert np.abs(P[body][i] - g).max() <= 1e-13 * max(1.0, np.abs(g).max())


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
