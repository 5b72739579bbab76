"""A configuration given by the output body's pose: the pose as an extra closure constraint.

Owns :class:`PoseModel`, a kinematic model whose coordinates are the mechanism's joint
coordinates followed by six coordinates of the output's pose, ``s = (r, x)``: ``x`` the
position of the output's reference point ``c0`` and ``r`` the rotation vector about it,
measured from the rotation ``R0`` of the pose continuation starts from.  The relative
displacement of the output body ``b`` from ``a = output.relative_to`` is then

    ``T(s) = (R0 exp(r), x - R0 exp(r) c0)``   (``g_b = g_a T``)

and the pose adds one closure block, ``Delta = g_a T(s) g_b^-1`` (identity when the
output is at the pose), to the loops' own: a rigid chord between ``a`` and ``b``.  The
six pose coordinates are always given, so closure by continuation
(:mod:`mechsing.kinematics.closure`) solves every joint not given with the same
predictor, Newton on the group and branch checks as for joint values; the straight
line it follows in the given coordinates is, for the pose, the geodesic from the
start's pose: the reference point on a straight line and the rotation about it by the
shortest turn ``R0 exp(t r1)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.kinematics.chains import tree_chain
from mechsing.kinematics.model import KinematicModel
from mechsing.kinematics.plans import ModelPlans
from mechsing.lie import exp_so3, left_jacobian_so3
from mechsing.model import Configuration, OutputPose
from mechsing.numeric import CommensurateFrame, to_float

__all__ = ["POSE_COORDINATES", "PoseChord", "PoseModel", "pose_problem"]

#: the six pose coordinates, after the joints'
POSE_COORDINATES = ("pose.rx", "pose.ry", "pose.rz", "pose.x", "pose.y", "pose.z")


@dataclass(frozen=True)
class PoseChord:
    """The pose constraint seen as a rigid chord from ``a`` (relative_to) to ``b`` (output)."""

    name: str
    a: str
    b: str


class PoseModel:
    """A :class:`KinematicModel` with the output's pose as six more (given) coordinates
    and one more closure block; it answers what closure and Newton ask of a model.

    Parameters
    ----------
    base : the mechanism's model (its precision is this model's)
    c0 : the output's reference point at the reference configuration (base numbers)
    R0 : the rotation the pose's rotation vector is measured from (base numbers)
    """

    #: its closure Jacobian is built and solved dense (the pose block couples the
    #: output's chain to every loop it crosses)
    sparse_closure = False

    def __init__(self, base: KinematicModel, c0: Any, R0: Any) -> None:
        out = base.mech.output
        assert out is not None
        self.base = base
        self.mech = base.mech
        #: its own plans (its singularity tests'; the joints' are the base model's)
        self.plans = ModelPlans()
        self.precision = base.precision
        self.backend = base.backend
        self.length_scale = base.length_scale
        self.centroid = base.centroid
        self.nb = base.n
        self.n = base.n + 6
        self.c0 = base.asarray(list(c0))
        self.R0 = base.asarray([list(row) for row in R0])
        self.length_columns = np.concatenate([base.length_columns, [False] * 3 + [True] * 3])
        f = base.frame
        self.frame = CommensurateFrame(f.L, f.c, self.length_columns, f.L_float, f.c_float)
        self.float_frame = self.frame.as_float()
        self.pose_chord = PoseChord("pose", out.relative_to, out.body)
        self.chords: list[Any] = [*base.chords, self.pose_chord]
        #: the closure blocks: the mechanism's (its chords' loops, its couplings), the pose
        self.couplings = base.couplings
        self.blocks: int = base.blocks + 1
        signs = np.zeros(self.n, dtype=int)
        signs[: self.nb] = tree_chain(base, out.relative_to, out.body).signs
        signs[self.nb :] = 1
        self._pose_signs = signs

    def float_twin(self) -> PoseModel:
        """The same pose problem on the mechanism's float model (itself when float)."""
        if self.backend.name == "float":
            return self
        return PoseModel(self.base.float_twin(), to_float(self.c0), to_float(self.R0))

    # -- what closure asks of a model -------------------------------------------------

    def joint(self, name: str) -> Any:
        return self.base.joint(name)

    def zeros(self) -> np.ndarray:
        return self.backend.zeros(self.n)

    def asarray(self, q: Any) -> np.ndarray:
        return self.base.asarray(q)

    def values(self, q: np.ndarray) -> dict[str, list[float]]:
        out = self.base.values(q[: self.nb])
        out["pose"] = [float(x) for x in to_float(q[self.nb :])]
        return out

    def poses(self, q: np.ndarray) -> dict[str, np.ndarray]:
        return self.base.poses(q[: self.nb])

    def target(self, q: np.ndarray) -> np.ndarray:
        """The relative displacement ``T(s)`` of the pose coordinates ``s = q[nb:]``."""
        s = q[self.nb :]
        with self.precision.context():
            R = self.R0 @ exp_so3(s[:3])
            return lie.pose(R, s[3:] - R @ self.c0)

    def current_screws(self, q: np.ndarray, poses: dict[str, np.ndarray] | None = None) -> Any:
        """The joints' current screws, then the pose coordinates' twists
        ``Ad(g_a) (dT T^-1)``: ``(R0 J_l(r) e_k, x x R0 J_l(r) e_k)`` for the rotation
        vector, ``(0, e_k)`` for the position."""
        poses = self.poses(q) if poses is None else poses
        S = self.base.current_screws(q[: self.nb], poses)
        s = q[self.nb :]
        bk = self.backend
        with self.precision.context():
            W = self.R0 @ left_jacobian_so3(s[:3])
            x = s[3:]
            cols = bk.zeros((6, 6))
            cols[0:3, 0:3] = W
            cols[3:6, 0:3] = lie.cross(x, W.T).T  # x x omega_k, column by column
            cols[3:6, 3:6] = bk.eye(3)
            cols = lie.Ad(poses[self.pose_chord.a]) @ cols
        return np.concatenate([S, cols], axis=1)

    def closure_jacobian(self, q: np.ndarray, screws: np.ndarray | None = None) -> np.ndarray:
        """The loops' rows (pose columns zero), then the pose block ``V_a - V_b + dT``."""
        S = self.current_screws(q) if screws is None else screws
        J = self.base.closure_jacobian(q[: self.nb], S[:, : self.nb])
        J = np.concatenate([J, self.backend.zeros((J.shape[0], 6))], axis=1)
        return np.concatenate([J, S * self._pose_signs[None, :]], axis=0)

    def scaled_closure_jacobian(
        self, q: np.ndarray, frame: Any, screws: np.ndarray | None = None
    ) -> np.ndarray:
        """``frame.blocks(closure_jacobian(q))``, as the mechanism's model names it."""
        return frame.blocks(self.closure_jacobian(q, screws))

    def chord_residuals(
        self, q: np.ndarray, poses: dict[str, np.ndarray] | None = None
    ) -> list[np.ndarray]:
        poses = self.poses(q) if poses is None else poses
        deltas = self.base.chord_residuals(q[: self.nb], poses)
        a, b = self.pose_chord.a, self.pose_chord.b
        with self.precision.context():
            deltas.append(poses[a] @ self.target(q) @ lie.inverse(poses[b]))
        return deltas

    def residual_norm(self, deltas: list[np.ndarray], native: bool = False) -> Any:
        return self.base.residual_norm(deltas, native)

    def chord_twists(self, deltas: list[np.ndarray]) -> np.ndarray:
        return self.base.chord_twists(deltas)

    def update(self, q: np.ndarray, delta: np.ndarray) -> np.ndarray:
        """The joints on the group; the pose coordinates add."""
        head = self.base.update(q[: self.nb], delta[: self.nb])
        return np.concatenate([head, q[self.nb :] + delta[self.nb :]])

    def difference(self, q1: np.ndarray, q0: np.ndarray) -> np.ndarray:
        head = self.base.difference(q1[: self.nb], q0[: self.nb])
        return np.concatenate([head, np.asarray(q1[self.nb :]) - np.asarray(q0[self.nb :])])

    # -- where the output is ------------------------------------------------------------

    def output_pose(self, q: np.ndarray) -> np.ndarray:
        """The output's displacement relative to ``relative_to`` at the joints ``q[:nb]``."""
        poses = self.poses(q)
        with self.precision.context():
            return lie.inverse(poses[self.pose_chord.a]) @ poses[self.pose_chord.b]

    def distance(self, q: np.ndarray, goal: np.ndarray) -> tuple[float, float]:
        """How far the output (joints ``q[:nb]``) is from the pose of the coordinates
        ``goal[nb:]``: the reference point's distance (m) and the angle between the two
        rotations (rad)."""
        g = to_float(self.output_pose(q))
        t = to_float(self.target(goal))
        c0 = to_float(self.c0)
        dx = float(np.linalg.norm(g[:3, :3] @ c0 + g[:3, 3] - (t[:3, :3] @ c0 + t[:3, 3])))
        cosang = (np.trace(g[:3, :3].T @ t[:3, :3]) - 1) / 2
        return dx, float(np.arccos(np.clip(cosang, -1.0, 1.0)))


def pose_problem(
    base: KinematicModel, cfg: Configuration, q0: np.ndarray | None, R0: Any = None
) -> tuple[PoseModel, np.ndarray | None, np.ndarray]:
    """The pose model of a configuration that gives the output's pose, continued from the
    joints ``q0`` (the start's): the model, the start's coordinates (joints, then the
    start's pose: no rotation from it, its reference point's position) and the target's
    pose coordinates (the rotation vector from the start's rotation to the given one, the
    given position).  ``R0``: the start's rotation when known (the same problem at more
    digits, whose rotation coordinates must be those of the model it refines); then
    ``q0`` may be None and no start is returned."""
    pose: OutputPose | None = cfg.pose
    assert pose is not None
    mech = base.mech
    with base.precision.context():
        bk = base.backend
        c0 = base.asarray(list(mech.output_reference_point()))
        start = None
        if R0 is None:
            assert q0 is not None
            trial = PoseModel(base, c0, bk.eye(3))
            g0 = trial.output_pose(np.concatenate([q0, bk.zeros(6)]))
            R0 = g0[:3, :3]
            x0 = R0 @ c0 + g0[:3, 3]
            start = np.concatenate([q0, bk.zeros(3), x0])
        else:
            R0 = base.asarray([list(row) for row in R0])
        if pose.rotation is not None:
            R1 = base.asarray([list(row) for row in pose.rotation])
        elif pose.rotation_vector is not None:
            R1 = exp_so3(base.asarray(list(pose.rotation_vector)))
        else:
            R1 = bk.eye(3)
        x1 = c0 if pose.position is None else base.asarray(list(pose.position))
        r1 = lie.log_so3(R0.T @ R1)
        model = PoseModel(base, c0, R0)
        goal = np.concatenate([r1, x1])
    return model, start, goal
