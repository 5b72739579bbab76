"""The Pinocchio anchor of the sweep benchmark: the pipeline a user would otherwise write to
follow a mechanism along a path and watch its distance to singularity.

What it computes, at every point of a path of one held joint coordinate (or of the output
body's pose):

1. **Projection onto the loop constraints.**  The mechanism becomes a Pinocchio model: the
   spanning tree of its graph is the kinematic tree (R -> ``JointModelRevoluteUnaligned``,
   P -> ``JointModelPrismaticUnaligned``, U -> two unaligned revolutes, S ->
   ``JointModelSpherical``, a quaternion), and each chord joint a loop-closure constraint
   between two frames placed at that joint on its two bodies: the relative placement
   ``aMb = oMf_a^-1 oMf_b``, minus what the chord joint allows (R: the five components of
   ``log6(aMb)`` other than the turn about its axis; P: the five other than the slide along
   it; S: the three coordinates of the point's separation).  Newton (Gauss-Newton with the
   pseudo-inverse, ``numpy.linalg.lstsq``) solves the constraints with the held coordinates
   fixed, warm-started from the previous point of the path, until every equation is within
   ``1e-12 L`` (lengths; angles times L), L the mechanism's characteristic length, the
   closure tolerance mechsing uses in float.  A pose path adds the output's pose as a 6-D
   constraint (``log6`` of the output frame against its target) and holds nothing.  Every
   kinematic quantity is Pinocchio's own: ``computeJointJacobians``,
   ``updateFramePlacements``, ``getFrameJacobian``, ``log6``, ``Jlog6``.
2. **Distance to singularity**, from numpy's SVD at each closed point (batched over the
   path once it is followed; the projection itself is sequential, warm-started, so it
   cannot be batched): in the commensurate metric (length rows divided by L, prismatic
   columns multiplied by L),

   * ``closure_sigma``: the constraint Jacobian J (every coordinate, loops only):
     ``sigma_r / sigma_1`` with r its generic rank (its rank at the path's first point,
     singular values above ``1e-9 sigma_1``);
   * with ``N`` an orthonormal basis of ker J (its last right singular vectors), the
     output map ``T`` (the output body's twist Jacobian at its reference point, or the
     velocity of ``output.point``) and the input selection ``E`` restricted to the
     kernel, as mechsing's complete velocity equation does: ``output_sigma`` is the
     smallest singular value of ``T N`` over the largest of ``T``, ``input_sigma`` the
     smallest of ``E N`` (E is a selection, of norm 1).  ``output_sigma`` vanishes at an
     input singularity (Type I: the output stops while an input moves), ``input_sigma``
     at an output singularity (Type II: the output moves with the inputs locked).

Coordinates: :meth:`PinocchioAnchor.to_mechsing` returns mechsing's joint values (file
order, catalog basis order; a joint with ``between: [a, b]`` sets ``g_b = g_a exp(q e)``
with ``e`` its screw at the reference configuration in the ground frame), chord joints
included, so :func:`check_against_mechsing` compares them with mechsing's closure.  Every
Pinocchio joint frame has the ground's orientation at the reference configuration and sits
at its joint's point; for a joint the tree crosses from ``between[1]`` to ``between[0]``,
Pinocchio's value is minus mechsing's (R, P; S: the inverse rotation) and a U joint's two
revolutes come in the other order with opposite axes.  Scope: R, P, U and S tree joints; R, P and S chord joints; the
output relative to ground.

The benchmark's paths are :func:`cases` (the four-bar's crank turn, the slider-crank between
its dead centres, the hexapod's platform turn, a 3-RPR pose grid); :func:`prepare` builds a
case's anchor and its timed run, :func:`check` compares it with mechsing first.  Run alone,
``python benchmarks/_pinocchio_sweep.py`` prints the anchor's own figures.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

import mechsing
from mechsing.kinematics import Closer, KinematicModel
from mechsing.model import Configuration, Mechanism, OutputPose

try:  # the optional `bench` extra
    import pinocchio as pin
except ImportError:  # pragma: no cover - the benchmark says so and skips the anchor
    pin = None

__all__ = [
    "CLOSURE_RTOL",
    "AnchorPath",
    "PinocchioAnchor",
    "ProjectionError",
    "check_against_mechsing",
]

#: closure tolerance relative to the characteristic length L (mechsing's in float)
CLOSURE_RTOL = 1e-12
#: a singular value counts in the generic rank above this fraction of the largest
#: (mechsing's float tau_hi)
RANK_RTOL = 1e-9
#: Newton gives up after this many iterations at one point
MAX_ITERATIONS = 50


class ProjectionError(RuntimeError):
    """Newton did not close the constraints at a point of the path."""


@dataclass(frozen=True)
class _Coordinate:
    """A scalar coordinate of a tree joint: mechsing's column, Pinocchio's q and v index,
    and the sign between them (-1 when the tree crosses the joint from b to a)."""

    column: int
    idx_q: int
    idx_v: int
    sign: int
    length: bool


@dataclass(frozen=True)
class _Spherical:
    """An S tree joint: mechsing's three columns (rotation vector) and Pinocchio's
    quaternion (x, y, z, w) at ``idx_q``."""

    columns: slice
    idx_q: int
    sign: int


@dataclass(frozen=True)
class _Chord:
    """A chord joint's constraint: frames ``fa`` on body a and ``fb`` on body b (at the
    joint's point, z along its axis for R and P), and the equations it keeps."""

    name: str
    type: str
    column: slice
    fa: int
    fb: int
    rows: int


@dataclass
class AnchorPath:
    """What the anchor returns for one path (arrays over the path's points).

    ``values``: the swept values (held coordinate in SI, or the pose parameter);
    ``q``: Pinocchio configurations (points, nq); ``iterations``: Newton iterations per
    point (Jacobian solves; 0 when the warm start already closed); ``residual``: the
    largest constraint equation at each closed point, as a length (m);
    ``closure_sigma``, ``input_sigma``, ``output_sigma``: smallest relative singular
    values (module docstring); ``closure_rank``: the generic rank used.
    """

    values: np.ndarray
    q: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    closure_sigma: np.ndarray
    input_sigma: np.ndarray | None
    output_sigma: np.ndarray | None
    closure_rank: int


def _aligned(u: np.ndarray) -> np.ndarray:
    """A rotation whose z column is the unit vector u (x: the coordinate axis least aligned
    with u, made normal to it)."""
    a = np.eye(3)[int(np.argmin(np.abs(u)))]
    e1 = a - (a @ u) * u
    e1 /= np.linalg.norm(e1)
    return np.column_stack([e1, np.cross(u, e1), u])


def _vec(x: Sequence[Any]) -> np.ndarray:
    return np.array([float(v) for v in x])


class PinocchioAnchor:
    """A Pinocchio model of a mechanism, its loop constraints and the projection onto them.

    Parameters
    ----------
    mech : Mechanism or path of a mechanism file
    pose : bool
        Add the output body's pose as a 6-D constraint (a pose path); its target is set by
        :meth:`set_pose`.
    """

    def __init__(self, mech: Mechanism | str, pose: bool = False) -> None:
        if pin is None:
            raise ImportError("the Pinocchio anchor needs the `pin` package (the bench extra)")
        self.mech = mech if isinstance(mech, Mechanism) else mechsing.load(mech)
        mech = self.mech
        #: characteristic length L (m): the closure tolerance is CLOSURE_RTOL * L
        self.length_scale: float = KinematicModel(mech, "float").length_scale
        self.n_mechsing = mech.dof
        columns: dict[str, slice] = {}
        k = 0
        for j in mech.joints:
            columns[j.name] = slice(k, k + j.dof)
            k += j.dof
        self._columns = columns
        self.model = pin.Model()
        graph = mech.graph
        joint_of: dict[str, int] = {mech.ground: 0}  # body -> Pinocchio joint id
        point_of: dict[str, np.ndarray] = {mech.ground: np.zeros(3)}  # its frame's origin
        self._scalars: list[_Coordinate] = []
        self._spherical: list[_Spherical] = []
        pending: list[tuple[str, Any, str, int]] = []
        bodies = sorted(
            (b for b in graph.tree_paths if graph.tree_paths[b] and b in mech.bodies),
            key=lambda b: len(graph.tree_paths[b]),
        )
        for body in bodies:
            step = graph.tree_paths[body][-1]
            j = mech.joint(step.joint)
            parent = j.between[0] if step.sign == 1 else j.between[1]
            pid, pp = joint_of[parent], point_of[parent]
            s = step.sign
            if j.type == "R":
                p = _vec(j.params["point"])
                jid = self._add(
                    pid, pin.JointModelRevoluteUnaligned(_vec(j.params["axis"])), p - pp, j.name
                )
                pending.append((j.name, jid, "R", s))
            elif j.type == "P":
                p = pp
                jid = self._add(
                    pid, pin.JointModelPrismaticUnaligned(_vec(j.params["axis"])), p - pp, j.name
                )
                pending.append((j.name, jid, "P", s))
            elif j.type == "S":
                p = _vec(j.params["point"])
                jid = self._add(pid, pin.JointModelSpherical(), p - pp, j.name)
                pending.append((j.name, jid, "S", s))
            elif j.type == "U":
                p = _vec(j.params["point"])
                a1, a2 = (_vec(a) for a in j.params["axes"])
                first, second = (a1, a2) if s == 1 else (-a2, -a1)
                j1 = self._add(pid, pin.JointModelRevoluteUnaligned(first), p - pp, j.name + ".0")
                jid = self._add(
                    j1, pin.JointModelRevoluteUnaligned(second), np.zeros(3), j.name + ".1"
                )
                pending.append((j.name, (j1, jid), "U", s))
            else:
                raise ValueError(
                    f"joint {j.name!r}: the Pinocchio anchor builds R, P, U and S tree joints, not {j.type}"
                )
            joint_of[body], point_of[body] = jid, p
        for name, jid, kind, s in pending:
            col = columns[name].start
            if kind in ("R", "P"):
                jm = self.model.joints[jid]
                self._scalars.append(_Coordinate(col, jm.idx_q, jm.idx_v, s, kind == "P"))
            elif kind == "U":
                jm1, jm2 = self.model.joints[jid[0]], self.model.joints[jid[1]]
                # s = -1: the first Pinocchio revolute is mechsing's second coordinate
                c1, c2 = (col, col + 1) if s == 1 else (col + 1, col)
                self._scalars.append(_Coordinate(c1, jm1.idx_q, jm1.idx_v, 1, False))
                self._scalars.append(_Coordinate(c2, jm2.idx_q, jm2.idx_v, 1, False))
            else:
                self._spherical.append(_Spherical(columns[name], self.model.joints[jid].idx_q, s))
        self._scalar_by_column = {c.column: c for c in self._scalars}
        self._chords: list[_Chord] = []
        for name in graph.chord_joints:
            j = mech.joint(name)
            a, b = j.between
            if j.type == "R":
                p, R0, rows = _vec(j.params["point"]), _aligned(_vec(j.params["axis"])), 5
            elif j.type == "P":
                p, R0, rows = point_of[a], _aligned(_vec(j.params["axis"])), 5
            elif j.type == "S":
                p, R0, rows = _vec(j.params["point"]), np.eye(3), 3
            else:
                raise ValueError(
                    f"chord joint {name!r}: the Pinocchio anchor closes R, P and S chords, not {j.type}"
                )
            fa = self._frame(f"{name}@a", joint_of[a], point_of[a], R0, p)
            fb = self._frame(f"{name}@b", joint_of[b], point_of[b], R0, p)
            self._chords.append(_Chord(name, j.type, columns[name], fa, fb, rows))
        self.output_frame: int | None = None
        self.output_point = False
        out = mech.output
        if out is not None:
            if out.relative_to != mech.ground:
                raise ValueError("the Pinocchio anchor measures the output relative to ground only")
            self.output_point = out.point is not None
            o = _vec(mech.output_reference_point())
            self.output_frame = self._frame(
                "output", joint_of[out.body], point_of[out.body], np.eye(3), o
            )
            #: the output's reference point at the reference configuration (ground frame)
            self.output_origin = o
        self.pose = pose
        if pose and self.output_frame is None:
            raise ValueError("a pose path needs the mechanism's output")
        self._target = pin.SE3.Identity()
        if pose:
            self.set_pose(np.zeros(3), np.zeros(3))
        self.data = self.model.createData()
        nv = self.model.nv
        #: commensurate column scale: prismatic rates times L
        self.column_scale = np.ones(nv)
        for c in self._scalars:
            if c.length:
                self.column_scale[c.idx_v] = self.length_scale
        self.n_closure = sum(c.rows for c in self._chords)
        self.input_columns = self._input_columns()

    # ------------------------------------------------------------------ building

    def _add(self, parent: int, jm: Any, offset: np.ndarray, name: str) -> int:
        return self.model.addJoint(parent, jm, pin.SE3(np.eye(3), offset), name)

    def _frame(
        self, name: str, joint: int, origin: np.ndarray, R0: np.ndarray, p: np.ndarray
    ) -> int:
        """A frame on a Pinocchio joint, at ground placement (R0, p) at the reference."""
        placement = pin.SE3(R0, p - origin)
        return self.model.addFrame(pin.Frame(name, joint, placement, pin.FrameType.OP_FRAME))

    def _input_columns(self) -> list[int]:
        """Pinocchio velocity indices of the file's inputs (tree R, P or U coordinates)."""
        out = []
        for joint, index in self.mech.input_coordinates():
            out.append(self._coordinate(joint, index).idx_v)
        return out

    def _coordinate(self, joint: str, index: int = 0) -> _Coordinate:
        col = self._columns[joint].start + index
        if col not in self._scalar_by_column:
            raise ValueError(
                f"coordinate {joint}[{index}] is not a scalar coordinate of Pinocchio's tree "
                "(a chord joint or an S joint): the anchor cannot hold it"
            )
        return self._scalar_by_column[col]

    # ------------------------------------------------------------------ coordinates

    def held_coordinate(self, name: str) -> tuple[int, int]:
        """Pinocchio's q index of a mechsing coordinate (``"A"``, ``"U1[1]"``) and the sign
        from mechsing's value to Pinocchio's (``q_pin = sign * value``)."""
        joint, _, rest = name.partition("[")
        c = self._coordinate(joint, int(rest.rstrip("]")) if rest else 0)
        return c.idx_q, c.sign

    def from_mechsing(self, qm: np.ndarray) -> np.ndarray:
        """Pinocchio's q of mechsing's joint values (chord values are dropped)."""
        q = pin.neutral(self.model)
        for c in self._scalars:
            q[c.idx_q] = c.sign * qm[c.column]
        for s in self._spherical:
            R = pin.exp3(s.sign * np.asarray(qm[s.columns], dtype=float))
            q[s.idx_q : s.idx_q + 4] = pin.Quaternion(R).coeffs()
        return q

    def to_mechsing(self, q: np.ndarray) -> np.ndarray:
        """mechsing's joint values at a closed Pinocchio q, chord joints included (R: the
        turn of frame b about the axis in frame a; P: the slide; S: the rotation vector)."""
        qm = np.zeros(self.n_mechsing)
        for c in self._scalars:
            qm[c.column] = c.sign * q[c.idx_q]
        for s in self._spherical:
            R = pin.Quaternion(q[s.idx_q + 3], *q[s.idx_q : s.idx_q + 3]).toRotationMatrix()
            qm[s.columns] = s.sign * pin.log3(R)
        pin.framesForwardKinematics(self.model, self.data, q)
        for ch in self._chords:
            aMb = self.data.oMf[ch.fa].actInv(self.data.oMf[ch.fb])
            if ch.type == "R":
                qm[ch.column] = np.arctan2(aMb.rotation[1, 0], aMb.rotation[0, 0])
            elif ch.type == "P":
                qm[ch.column] = aMb.translation[2]
            else:
                qm[ch.column] = pin.log3(aMb.rotation)
        return qm

    def set_pose(self, position: np.ndarray, rotation_vector: np.ndarray) -> None:
        """Target of the pose constraint: the output's reference point moved by
        ``position`` (m, ground axes) and the output turned by ``rotation_vector`` about
        that point, from the reference configuration."""
        R = pin.exp3(np.asarray(rotation_vector, dtype=float))
        self._target = pin.SE3(R, self.output_origin + np.asarray(position, dtype=float))

    # ------------------------------------------------------------------ constraints

    def system(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Constraint residual (dimensionless: lengths over L), its Jacobian (equations, nv)
        with commensurate rows, and the output map (rows of ``T``, nv), at q.

        The loop constraints come first (``n_closure`` rows), then the pose's 6 rows when
        the anchor has a pose constraint."""
        model, data, L = self.model, self.data, self.length_scale
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        rs, Js = [], []
        local, world = pin.ReferenceFrame.LOCAL, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
        for ch in self._chords:
            oMa, oMb = data.oMf[ch.fa], data.oMf[ch.fb]
            if ch.type == "S":
                # the point's separation, ground axes
                Ja = pin.getFrameJacobian(model, data, ch.fa, world)
                Jb = pin.getFrameJacobian(model, data, ch.fb, world)
                rs.append((oMb.translation - oMa.translation) / L)
                Js.append((Jb[:3] - Ja[:3]) / L)
                continue
            aMb = oMa.actInv(oMb)
            Ja = pin.getFrameJacobian(model, data, ch.fa, local)
            Jb = pin.getFrameJacobian(model, data, ch.fb, local)
            # d log6(aMb) = Jlog6(aMb) (V_b - Ad(bMa) V_a), body twists (Pinocchio's (v, w))
            e = pin.log6(aMb).vector
            J = pin.Jlog6(aMb) @ (Jb - aMb.inverse().action @ Ja)
            keep = [0, 1, 2, 3, 4] if ch.type == "R" else [0, 1, 3, 4, 5]
            scale = np.array([1 / L] * 3 + [1.0] * 3)[keep]
            rs.append(e[keep] * scale)
            Js.append(J[keep] * scale[:, None])
        if self.pose:
            oMo = data.oMf[self.output_frame]
            tMo = self._target.actInv(oMo)
            Jo = pin.getFrameJacobian(model, data, self.output_frame, local)
            scale = np.array([1 / L] * 3 + [1.0] * 3)
            rs.append(pin.log6(tMo).vector * scale)
            Js.append((pin.Jlog6(tMo) @ Jo) * scale[:, None])
        if self.output_frame is not None:
            Jt = pin.getFrameJacobian(model, data, self.output_frame, world)
            T = Jt[:3] / L if self.output_point else np.vstack([Jt[:3] / L, Jt[3:]])
        else:
            T = np.zeros((0, model.nv))
        r = np.concatenate(rs) if rs else np.zeros(0)
        J = np.vstack(Js) if Js else np.zeros((0, model.nv))
        return r, J, T

    def project(
        self, q_guess: np.ndarray, held_indices: Sequence[int], held_values: Sequence[float]
    ) -> tuple[np.ndarray, int]:
        """Newton (Gauss-Newton, pseudo-inverse) onto the constraints with Pinocchio's
        coordinates ``q[held_indices] = held_values`` fixed, from ``q_guess``.

        Returns the closed q and the iterations (Jacobian solves) it took; stops when every
        equation is within ``CLOSURE_RTOL * L``.  The held indices are q indices of
        revolute or prismatic Pinocchio joints (:meth:`held_coordinate`).
        """
        q, _, iterations = self._project(q_guess, held_indices, held_values)
        return q, iterations

    def _project(
        self, q_guess: np.ndarray, held_indices: Sequence[int], held_values: Sequence[float]
    ) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray], int]:
        model = self.model
        q = np.array(q_guess, dtype=float)
        q[list(held_indices)] = held_values
        held_v = {model.joints[self._joint_at_q(i)].idx_v for i in held_indices}
        free = np.array([i for i in range(model.nv) if i not in held_v], dtype=int)
        scale = self.column_scale[free]
        dv = np.zeros(model.nv)
        for it in range(MAX_ITERATIONS + 1):
            r, J, T = self.system(q)
            if not r.size or np.max(np.abs(r)) <= CLOSURE_RTOL:
                return q, (r, J, T), it
            if it == MAX_ITERATIONS:
                break
            step, *_ = np.linalg.lstsq(J[:, free] * scale, -r, rcond=None)
            dv[:] = 0.0
            dv[free] = step * scale
            q = pin.integrate(model, q, dv)
        raise ProjectionError(
            f"Newton did not close the constraints in {MAX_ITERATIONS} iterations "
            f"(largest equation {np.max(np.abs(r)) * self.length_scale:.3e} m)"
        )

    def _joint_at_q(self, idx_q: int) -> int:
        for jid in range(1, self.model.njoints):
            jm = self.model.joints[jid]
            if jm.idx_q <= idx_q < jm.idx_q + jm.nq:
                return jid
        raise IndexError(idx_q)

    # ------------------------------------------------------------------ paths

    def approach(
        self, q: np.ndarray, held: Sequence[str], values: Sequence[float], steps: int = 100
    ) -> np.ndarray:
        """Continuation from a closed q to the held values (mechsing's units), in ``steps``
        equal steps of the held coordinates: the start of a path that does not begin at q."""
        idx, signs = zip(*(self.held_coordinate(n) for n in held), strict=True)
        start = np.array([q[i] for i in idx])
        goal = np.array(signs) * np.asarray(values, dtype=float)
        for t in np.linspace(0.0, 1.0, steps + 1)[1:]:
            q, _ = self.project(q, idx, start + t * (goal - start))
        return q

    def approach_pose(
        self, q: np.ndarray, position: np.ndarray, rotation_vector: np.ndarray, steps: int = 100
    ) -> np.ndarray:
        """Continuation of a pose-constrained anchor from the reference pose to a pose."""
        for t in np.linspace(0.0, 1.0, steps + 1)[1:]:
            self.set_pose(t * np.asarray(position), t * np.asarray(rotation_vector))
            q, _ = self.project(q, (), ())
        return q

    def path(
        self, held: str | Sequence[str], values: Sequence[Any], q_start: np.ndarray | None = None
    ) -> AnchorPath:
        """Follow a path of held coordinates (mechsing's names and SI units; ``values`` is
        (points,) for one coordinate, (points, k) for k), each point warm-started from the
        previous one, the first from ``q_start`` (default: the reference configuration)."""
        held = [held] if isinstance(held, str) else list(held)
        vals = np.asarray(values, dtype=float)
        step = self._held_step(held, vals.reshape(len(vals), -1))
        return self._run(vals, step, [(i, i - 1) for i in range(len(vals))], q_start)

    def grid(
        self,
        held: Sequence[str],
        values1: Sequence[float],
        values2: Sequence[float],
        q_start: np.ndarray | None = None,
    ) -> AnchorPath:
        """A grid of two held coordinates, as rows of paths: the first column (``held[0]``
        over ``values1`` at ``values2[0]``) is followed from ``q_start``, then each row
        (``held[1]`` over ``values2``) from its first column's point.  Points are in
        row-major order, ``values`` is (n1 * n2, 2)."""
        v1, v2 = np.asarray(values1, dtype=float), np.asarray(values2, dtype=float)
        vals = np.stack(np.meshgrid(v1, v2, indexing="ij"), axis=-1).reshape(-1, 2)
        return self._run(
            vals, self._held_step(list(held), vals), _grid_order(len(v1), len(v2)), q_start
        )

    def pose_path(
        self,
        positions: np.ndarray,
        rotation_vectors: np.ndarray,
        values: Sequence[Any],
        q_start: np.ndarray | None = None,
    ) -> AnchorPath:
        """Follow a path of the output's pose: one target per point, ``positions`` and
        ``rotation_vectors`` (points, 3) as in :meth:`set_pose`; ``values`` is the path
        parameter reported."""
        step = self._pose_step(
            np.reshape(positions, (-1, 3)), np.reshape(rotation_vectors, (-1, 3))
        )
        vals = np.asarray(values, dtype=float)
        return self._run(vals, step, [(i, i - 1) for i in range(len(vals))], q_start)

    def pose_grid(
        self,
        positions: np.ndarray,
        rotation_vectors: np.ndarray,
        values: np.ndarray,
        q_start: np.ndarray | None = None,
    ) -> AnchorPath:
        """A grid of output poses (targets (n1, n2, 3), values (n1, n2, 2)), followed as
        :meth:`grid` follows held coordinates: the first column, then the rows."""
        n1, n2 = np.shape(positions)[:2]
        step = self._pose_step(
            np.reshape(positions, (-1, 3)), np.reshape(rotation_vectors, (-1, 3))
        )
        vals = np.reshape(np.asarray(values, dtype=float), (n1 * n2, -1))
        return self._run(vals, step, _grid_order(n1, n2), q_start)

    def _held_step(self, held: list[str], values: np.ndarray) -> Any:
        idx, signs = zip(*(self.held_coordinate(n) for n in held), strict=True)
        target = values * np.array(signs)

        def step(i: int, q: np.ndarray) -> Any:
            return self._project(q, idx, target[i])

        return step

    def _pose_step(self, positions: np.ndarray, rotation_vectors: np.ndarray) -> Any:
        if not self.pose:
            raise ValueError("a pose path needs PinocchioAnchor(mech, pose=True)")

        def step(i: int, q: np.ndarray) -> Any:
            self.set_pose(positions[i], rotation_vectors[i])
            return self._project(q, (), ())

        return step

    def _run(
        self,
        values: np.ndarray,
        step: Any,
        order: list[tuple[int, int]],
        q_start: np.ndarray | None,
    ) -> AnchorPath:
        """Project the points in ``order``: (point, the point it is warm-started from, -1 for
        ``q_start``); then the batched SVDs."""
        n, nv = len(order), self.model.nv
        q0 = pin.neutral(self.model) if q_start is None else np.asarray(q_start, dtype=float)
        Q = np.empty((n, self.model.nq))
        its = np.empty(n, dtype=int)
        res = np.empty(n)
        Jc = np.empty((n, self.n_closure, nv))
        T = None
        for i, prev in order:
            q, (r, J, Ti), its[i] = step(i, q0 if prev < 0 else Q[prev])
            Q[i] = q
            res[i] = np.max(np.abs(r)) * self.length_scale if r.size else 0.0
            Jc[i] = J[: self.n_closure]
            if Ti.shape[0]:
                if T is None:
                    T = np.empty((n, Ti.shape[0], nv))
                T[i] = Ti
        closure, inp, outp, rank = self.sigmas(Jc, T)
        return AnchorPath(values, Q, its, res, closure, inp, outp, rank)

    def sigmas(
        self, Jc: np.ndarray, T: np.ndarray | None
    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None, int]:
        """Batched SVDs over a path (module docstring): the closure test, and the input and
        output maps on the closure kernel; the generic rank is the first point's."""
        D = self.column_scale
        A = Jc * D
        U, s, Vt = np.linalg.svd(A, full_matrices=True)
        if s.shape[1] == 0:
            rank = 0
        else:
            rank = int(np.count_nonzero(s[0] > RANK_RTOL * s[0, 0]))
        closure = s[:, rank - 1] / s[:, 0] if rank else np.ones(len(A))
        N = np.swapaxes(Vt[:, rank:, :], 1, 2)  # (points, nv, nv - rank), commensurate
        inp = outp = None
        if self.input_columns and N.shape[2]:
            EN = N[:, self.input_columns, :]
            inp = np.linalg.svd(EN, compute_uv=False)[:, -1]
        if T is not None and N.shape[2]:
            TD = T * D
            TN = TD @ N
            outp = np.linalg.svd(TN, compute_uv=False)[:, -1] / np.linalg.norm(
                TD, ord=2, axis=(1, 2)
            )
        return closure, inp, outp, rank


def _grid_order(n1: int, n2: int) -> list[tuple[int, int]]:
    """Warm starts of a row-major n1 x n2 grid: down the first column, then along each row."""
    column = [(i * n2, (i - 1) * n2 if i else -1) for i in range(n1)]
    rows = [(i * n2 + j, i * n2 + j - 1) for i in range(n1) for j in range(1, n2)]
    return column + rows


# ====================================================================== the check against mechsing


def _distance(mech: Mechanism, q1: np.ndarray, q2: np.ndarray) -> float:
    """Largest difference between two sets of mechsing joint values: angles (rad) modulo
    2 pi, lengths (m), S joints by the angle of their relative rotation (rad)."""
    worst = 0.0
    k = 0
    for j in mech.joints:
        cols = slice(k, k + j.dof)
        k += j.dof
        if j.type == "S":
            R1, R2 = pin.exp3(q1[cols]), pin.exp3(q2[cols])
            worst = max(worst, float(np.linalg.norm(pin.log3(R1.T @ R2))))
            continue
        for u, a, b in zip(j.units, q1[cols], q2[cols], strict=True):
            d = b - a
            if u == "rad":
                d = (d + np.pi) % (2 * np.pi) - np.pi
            worst = max(worst, abs(float(d)))
    return worst


def check_against_mechsing(
    anchor: PinocchioAnchor,
    path: AnchorPath,
    points: Sequence[int],
    held: str | None = None,
    poses: tuple[np.ndarray, np.ndarray] | None = None,
) -> float:
    """Largest difference (rad or m) between the joint values the anchor found at the
    path's ``points`` and those mechsing's closure finds for the same held value (``held``:
    the coordinate's name) or the same output pose (``poses``: the path's positions and
    rotation vectors), each by continuation from the reference configuration."""
    mech = anchor.mech
    configs = dict(mech.configurations)
    names = []
    for i in points:
        name = f"anchor-check-{i}"
        if held is not None:
            if mech.joint(held).dof != 1:
                raise ValueError(f"the check holds a one-coordinate joint, not {held!r}")
            configs[name] = Configuration(name, {held: (float(path.values[i]),)})
        else:
            assert poses is not None
            x = anchor.output_origin + poses[0][i]
            pose = OutputPose(position=tuple(x), rotation_vector=tuple(poses[1][i]))
            configs[name] = Configuration(name, {}, pose=pose)
        names.append(name)
    mech2 = dataclasses.replace(mech, configurations=configs)
    closer = Closer(KinematicModel(mech2, "float"))
    worst = 0.0
    for i, name in zip(points, names, strict=True):
        qm = np.asarray(closer.solve(name).q, dtype=float)
        worst = max(worst, _distance(mech, anchor.to_mechsing(path.q[i]), qm))
    return worst


# ====================================================================== the benchmark's paths


@dataclass(frozen=True)
class Case:
    """One path (or grid) of the benchmark: the file, what is held or posed, the values.

    A held path gives ``held`` and ``values`` (points,); a pose path or grid gives
    ``positions`` and ``rotation_vectors`` ((points, 3), or (n1, n2, 3) for a grid, as in
    :meth:`PinocchioAnchor.set_pose`) and ``values`` the reported parameter; ``checked``
    are the points compared with mechsing's closure.
    """

    name: str
    file: str
    values: np.ndarray
    checked: tuple[int, ...]
    held: str | None = None
    positions: np.ndarray | None = None
    rotation_vectors: np.ndarray | None = None

    @property
    def points(self) -> int:
        return len(self.values) if self.held else int(np.prod(np.shape(self.positions)[:-1]))


def cases(density: int = 1) -> list[Case]:
    """The benchmark's paths: the four-bar's crank A over a turn in 0.1 deg steps (3600
    points); the slider-crank's slider P over its reachable range, between the dead centres
    x = 4 sqrt(11)/5 and 24/5 (the slider at x = 16/5 + P), at the midpoints of 2000 equal
    cells; the hexapod's platform turned about the vertical through its centre from -100 to
    100 deg (1000 points, through the Type II poses at +-90 deg); the 3-RPR's reference point
    over a 50 x 50 grid of +-0.3 m at the reference orientation (a 2-variable case).
    ``density`` multiplies the points of each path (and of each grid by about as much)."""
    side = 50 * max(1, round(density**0.5))
    lo, hi = 4 * np.sqrt(11) / 5 - 16 / 5, 8 / 5
    slider = lo + (np.arange(2000 * density) + 0.5) * (hi - lo) / (2000 * density)
    turn = np.zeros((1000 * density, 3))
    turn[:, 2] = np.deg2rad(np.linspace(-100, 100, 1000 * density))
    steps = np.linspace(-0.3, 0.3, side)
    X, Y = np.meshgrid(steps, steps, indexing="ij")
    grid = np.stack([X, Y, np.zeros_like(X)], axis=-1)
    return [
        Case(
            "four-bar, crank A 0-360 deg",
            "fourbar.yaml",
            np.deg2rad(np.arange(3600 * density) * 0.1 / density),
            (300, 1800, 3500),
            held="A",
        ),
        Case(
            "slider-crank, slider P dead centre to dead centre",
            "slider_crank_slider_input.yaml",
            slider,
            (10, 1000, 1990),
            held="P",
        ),
        Case(
            "6-UPS hexapod, platform turn -100..100 deg",
            "stewart_octahedral.yaml",
            np.rad2deg(turn[:, 2]),
            (0, 500, 999),
            positions=np.zeros((1000 * density, 3)),
            rotation_vectors=turn,
        ),
        Case(
            f"3-RPR, platform (x, y) {side} x {side} grid",
            "planar_3rpr.yaml",
            np.stack([X, Y], axis=-1).reshape(-1, 2),
            (0, side * side // 2 + side // 2, side * side - 1),
            positions=grid,
            rotation_vectors=np.zeros_like(grid),
        ),
    ]


def prepare(case: Case, root: Any) -> tuple[PinocchioAnchor, Any]:
    """The anchor of a case and a function that follows its path from a closed start (the
    start is reached by continuation from the reference once, here, outside any timing)."""
    pose = case.held is None
    anchor = PinocchioAnchor(mechsing.load(f"{root}/examples/{case.file}"), pose=pose)
    q = pin.neutral(anchor.model)
    if case.held is not None:
        q0 = anchor.approach(q, [case.held], [case.values[0]])
        return anchor, lambda: anchor.path(case.held, case.values, q0)
    assert case.positions is not None and case.rotation_vectors is not None
    x, r = case.positions, case.rotation_vectors
    first = (0, 0) if x.ndim == 3 else 0
    q0 = anchor.approach_pose(q, x[first], r[first])
    if x.ndim == 3:
        return anchor, lambda: anchor.pose_grid(x, r, case.values, q0)
    return anchor, lambda: anchor.pose_path(x, r, case.values, q0)


def check(case: Case, anchor: PinocchioAnchor, path: AnchorPath) -> float:
    """:func:`check_against_mechsing` at the case's checked points."""
    if case.held is not None:
        return check_against_mechsing(anchor, path, case.checked, held=case.held)
    assert case.positions is not None and case.rotation_vectors is not None
    flat = np.reshape(case.positions, (-1, 3)), np.reshape(case.rotation_vectors, (-1, 3))
    return check_against_mechsing(anchor, path, case.checked, poses=flat)


def main(argv: Sequence[str] | None = None) -> int:
    """The anchor alone, for its own figures (benchmarks/sweep.py runs it beside mechsing):
    ``python benchmarks/_pinocchio_sweep.py [--repeat 5]``, one core."""
    import argparse
    import os
    from pathlib import Path

    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        if os.environ.get(var) != "1":
            print(f"note: {var} is not 1; numpy may use several cores")
    from _timing import timed_median

    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args(argv)
    root = Path(__file__).resolve().parents[1]
    print(f"Pinocchio {pin.__version__} anchor: Newton to {CLOSURE_RTOL:g} L, numpy SVD")
    for case in cases():
        anchor, run = prepare(case, root)
        deviation = check(case, anchor, run())
        t, p = timed_median(run, args.repeat)
        its = p.iterations
        print(
            f"  {case.name}: {case.points} points, {case.points / t:,.0f} points/s "
            f"(median of {args.repeat}); Newton iterations mean {its.mean():.2f}, "
            f"max {its.max()}, total {its.sum()}; largest residual {p.residual.max():.1e} m; "
            f"joint values vs mechsing's closure {deviation:.1e}"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
