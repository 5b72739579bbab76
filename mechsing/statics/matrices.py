"""The one adapter between the statics and the motion tests: the matrices of the
input/output test at one closed configuration.

Everything the statics need is the motion test's: the stacked closure system ``A`` (each
loop's rows in orthonormal coordinates of its subalgebra, then the couplings), the
output body's twists ``T`` and the input selection ``E``, all commensurate
(:class:`~mechsing.numeric.scaling.CommensurateFrame`), plus the frame that carries them
back to SI.  :func:`motion_matrices` builds them from the closure system
(:func:`mechsing.screws.closure_system`), the input test's rows
(:func:`mechsing.singularity.criteria.input_rows`) and the output chain
(:func:`mechsing.singularity.zfb.output_chain`): the same matrices the singularity tests
decide on, so that the statics and the tests cannot disagree.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.kinematics import KinematicModel
from mechsing.kinematics.chains import tree_chain
from mechsing.numeric import to_float
from mechsing.screws import closure_system
from mechsing.singularity.criteria import input_rows
from mechsing.singularity.zfb import output_chain

__all__ = ["LoopRows", "MotionMatrices", "motion_matrices", "float_configuration"]


@dataclass(frozen=True)
class LoopRows:
    """One loop's rows of ``A``: its joints, the row slice and the orthonormal
    commensurate basis (6 x h) of its subalgebra (its rows' coordinates)."""

    joints: tuple[str, ...]
    rows: slice
    basis: np.ndarray
    subgroup: str | None


@dataclass(frozen=True)
class MotionMatrices:
    """The motion test's matrices at one configuration (float, commensurate).

    ``A`` (r x n): closure rows; ``T`` (6 x n): the output body's twists relative to
    ``relative_to``; ``E`` (a x n): the actuated coordinates; ``inputs``: a name per row
    of E (``J`` or ``J[i]`` for one coordinate of a multi-coordinate joint);
    ``input_lengths``: which inputs are lengths (efforts in N, the others N m);
    ``columns``: the joint of each coordinate; ``chain_signs``: the output chain's
    signs per coordinate (0 off the chain); ``S``: SI screws at the ground origin
    (6 x n); ``poses``: the bodies' poses; ``frame``: the commensurate frame."""

    model: KinematicModel
    q: np.ndarray
    A: np.ndarray
    loops: tuple[LoopRows, ...]
    T: np.ndarray
    E: np.ndarray
    inputs: tuple[str, ...]
    input_lengths: tuple[bool, ...]
    columns: tuple[str, ...]
    chain_signs: np.ndarray
    S: np.ndarray
    poses: dict[str, np.ndarray]
    frame: Any

    @property
    def L(self) -> float:
        return float(self.model.length_scale)

    def wrench_in(self, w: np.ndarray) -> np.ndarray:
        """The commensurate wrench (pairs with the commensurate twists) of an SI wrench
        (f, m) at the ground origin: the inverse of the frame's ``wrench_back``."""
        return np.linalg.solve(self._wrench_back, np.asarray(w, dtype=float))

    @property
    def _wrench_back(self) -> np.ndarray:
        return np.column_stack([self.frame.wrench_back(e) for e in np.eye(6)])

    def wrench_out(self, y: np.ndarray) -> np.ndarray:
        """The SI wrench at the ground origin of a commensurate one."""
        return self.frame.wrench_back(np.asarray(y, dtype=float))

    def twist_out(self, t: np.ndarray) -> np.ndarray:
        """The SI twist at the ground origin of a commensurate one."""
        return np.asarray(self.frame.twist_back(np.asarray(t, dtype=float)), dtype=float)

    def effort_scale(self) -> np.ndarray:
        """Commensurate efforts -> SI: a length input's effort (N) is its commensurate
        effort (power per commensurate rate, N m) divided by L."""
        return np.where(np.array(self.input_lengths, dtype=bool), 1.0 / self.L, 1.0)

    @property
    def Ss(self) -> np.ndarray:
        """The commensurate screws (6 x n) of every coordinate."""
        return np.asarray(self.frame.screws(self.S), dtype=float)

    def body_signs(self, body: str) -> np.ndarray:
        """The signs (n,) of the ground-to-``body`` tree chain (0 off it): its twists are
        the screws times them."""
        mech = self.model.mech
        return np.asarray(tree_chain(self.model, body, mech.ground).signs, dtype=float)

    def body_point_now(self, body: str, x0: Any) -> np.ndarray:
        """Where the point ``x0`` of ``body`` (given in the drawn pose) is now."""
        g = self.poses[body]
        return np.asarray(lie.act_point(g, np.asarray(to_float(x0), dtype=float)), dtype=float)

    def point_now(self, x0: Any) -> np.ndarray:
        """Where the output body's point ``x0`` (given in the reference pose) is now."""
        g = self.poses[self.model.mech.output.body]
        return np.asarray(lie.act_point(g, np.asarray(to_float(x0), dtype=float)), dtype=float)


def float_configuration(model: KinematicModel, joints: Any) -> np.ndarray:
    """The coordinate vector of joint values given by name (SI, radians)."""
    q = np.zeros(model.n)
    values = dict(joints)
    for jk in model.joints:
        q[jk.columns] = np.asarray(values[jk.name], dtype=float)
    return q


def motion_matrices(
    mech: Any, q: np.ndarray, model: KinematicModel | None = None
) -> MotionMatrices:
    """The motion test's matrices at the closed configuration ``q`` (float): the closure
    system (:func:`mechsing.screws.closure_system`), the output body's twists and the
    input rows (:mod:`mechsing.singularity.zfb`)."""
    fm = model if model is not None else KinematicModel(mech, "float")
    q = np.asarray(q, dtype=float)
    cs = closure_system(fm, q)
    T = np.asarray(output_chain(mech, fm, q, cs, False)[0], dtype=float)
    E = input_rows(mech, fm)
    E = np.zeros((0, fm.n)) if E is None else E
    loops = []
    start = 0
    for ls in cs.loops:
        h = ls.matrix.shape[0]
        sg = ls.subgroup
        loops.append(
            LoopRows(
                tuple(ls.loop.joints),
                slice(start, start + h),
                np.asarray(ls.basis_float, dtype=float),
                None if sg is None else str(getattr(sg.type, "symbol", sg.type)),
            )
        )
        start += h
    names = []
    lengths = []
    for j, k in mech.input_coordinates():
        jk = fm.joint(j)
        names.append(mech.coordinate_label(j, k))
        lengths.append(bool(fm.frame.length_columns[jk.columns.start + k]))
    columns = [""] * fm.n
    for jk in fm.joints:
        for c in range(jk.columns.start, jk.columns.stop):
            columns[c] = jk.name
    out = mech.output
    chain = tree_chain(fm, out.body, out.relative_to)
    poses = fm.poses(q)
    return MotionMatrices(
        fm,
        q,
        np.asarray(cs.matrix, dtype=float),
        tuple(loops),
        T,
        np.asarray(E, dtype=float),
        tuple(names),
        tuple(lengths),
        tuple(columns),
        np.asarray(chain.signs, dtype=float),
        np.asarray(to_float(cs.screws), dtype=float),
        poses,
        fm.float_frame,
    )
