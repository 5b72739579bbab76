"""The dynamics of a tree of bodies on twists and wrenches of D (Chevallier & Lerbet,
chapter 8: the dynamic equations of tree-structured systems).

Every quantity is written in the ground frame at the ground origin, as the rest of
mechsing writes them, so that no frame is attached to a body: with ``s_k`` the current
screw of joint k (``Ad(g_a) e_k``, the joint's reference screw carried by the pose of its
``between[0]``) and ``sigma_k`` the sign of the tree's crossing of it,

* forward, from the ground out (a body b after joint k from the body p):
  ``xi_b = xi_p + sigma_k s_k qd_k`` and
  ``a_b = a_p + sigma_k s_k qdd_k + [xi_b, sigma_k s_k qd_k]`` (the rate of the current
  screw is the Lie bracket ``s_k' = [xi_p, s_k]``), the ground accelerating by ``-g``
  so that the weights come with the inertia efforts;
* each body needs the wrench ``W_b = I_b(a_b) + [xi_b, I_b(xi_b)]``
  (:func:`mechsing.kinetics.rigid.newton_euler`, ``I_b`` its inertia carried to its pose);
* backward, from the leaves in: the joint before b carries ``F_b = W_b + sum of the F of
  b's children`` and its effort is the power pairing ``tau_k = sigma_k <F_b, s_k>``.

That is the recursive Newton-Euler algorithm (Featherstone's RNEA, Luh-Walker-Paul) with
Ad and ad in place of the spatial-vector algebra.  The **mass matrix** comes from the
composite inertias (the sum of a subtree's inertia maps, all in ground coordinates):
``M_kl = sigma_k sigma_l <Ic_(b_l)(s_l), s_k>`` when joint k is on the path of joint l's
body; the **bias efforts** are the inverse dynamics at zero acceleration (Coriolis,
centrifugal and gravity); **forward dynamics** solves ``M qdd = tau - bias`` by Cholesky.

Owns :class:`TreeDynamics`.  The formulas are those of :mod:`mechsing.lie` and run in
float (numpy, batched over leading axes of the joint values: a sweep's samples at once),
mp:N and exact.  The tree's joints are joints of one coordinate (R, P, H); a joint of
several coordinates, a closed chain and coupled joints are refused with the reason.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing import lie
from mechsing.errors import UserError
from mechsing.kinematics import forward
from mechsing.kinetics.rigid import Inertia, kinetic_energy, newton_euler
from mechsing.model.loads import mass_centre
from mechsing.numeric import dispatch
from mechsing.numeric.backend import holds_objects

__all__ = ["TreeDynamics"]

#: the fast forms of the inverse dynamics (:mod:`mechsing.kinetics._compiled`)
_INVERSE = dispatch.table("inverse dynamics", "mechsing.kinetics.tree.TreeDynamics.inverse")

#: the joint types the tree dynamics takes (one coordinate each)
ONE_COORDINATE = ("R", "P", "H")


class TreeDynamics:
    """The dynamics of a mechanism whose joints form a tree from the ground.

    Parameters
    ----------
    model : KinematicModel
        The mechanism's kinematic model in the precision of the computation (float, mp:N,
        exact); its mechanism gives the masses (``mass``) and gravity.
    gravity : sequence of 3 numbers or None
        The acceleration of gravity (m/s^2, ground axes); None: the file's (none: zero).
    closed : bool
        Take a closed chain: the dynamics of its spanning tree (the chords' coordinates
        move no body: their efforts are 0), closed by :mod:`mechsing.kinetics.closed`.
    """

    def __init__(self, model: Any, gravity: Any = None, closed: bool = False) -> None:
        mech = model.mech
        self.model = model
        self.backend = model.backend
        _refuse(mech, closed)
        wt = mech.weights
        with model.precision.context():
            grav = gravity if gravity is not None else (wt.gravity if wt is not None else None)
            #: the acceleration of the ground that brings the weights: (0, -g)
            self.ground_acceleration = model.asarray(
                [0, 0, 0, *(-x for x in (grav if grav is not None else (0, 0, 0)))]
            )
            self.has_gravity = grav is not None and any(x != 0 for x in grav)
            inertias = dict(wt.inertias) if wt is not None else {}
            #: each body's inertia at the drawn pose, in the model's numbers
            self.inertia: dict[str, Inertia] = {}
            for body, kg, centre in wt.masses if wt is not None else ():
                about = inertias.get(body, ((0, 0, 0), (0, 0, 0), (0, 0, 0)))
                self.inertia[body] = Inertia(
                    model.asarray(kg),
                    model.asarray(list(mass_centre(mech, body, centre))),
                    model.asarray([list(r) for r in about]),
                )
        #: the tree, parents first: (body, the joint's model entry, the body before, sign)
        self.plan: list[tuple[str, Any, str, int]] = []
        for body, steps in sorted(mech.graph.tree_paths.items(), key=lambda kv: len(kv[1])):
            if body == mech.ground or not steps:
                continue
            last = steps[-1]
            jk = model.joint(last.joint)
            self.plan.append((body, jk, jk.a if last.sign > 0 else jk.b, last.sign))
        #: the body each tree step's first coordinate moves
        self._body_of_column = {jk.columns.start: body for body, jk, _, _ in self.plan}
        #: the plan as arrays for the compiled kernels, built when first asked
        #: (:mod:`._compiled`)
        self.compiled_tables: tuple[np.ndarray, ...] | None = None
        #: each body's coordinates on its path from the ground (the mass matrix's pattern)
        self.path_columns: dict[str, list[int]] = {
            body: [model.joint(st.joint).columns.start for st in steps]
            for body, steps in mech.graph.tree_paths.items()
        }
        self.n: int = model.n
        self.ground: str = mech.ground

    # ------------------------------------------------------------------ kinematics

    def _zero_twist(self, batch: tuple[int, ...]) -> np.ndarray:
        return np.broadcast_to(self.backend.zeros(6), batch + (6,))

    def motion(
        self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray | None, gravity: bool
    ) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray], dict[str, np.ndarray], dict]:
        """The bodies' poses, twists and accelerations (spatial, at the ground origin) and
        the joints' current screws times their signs, by the forward recursion."""
        # a batch takes the batch poses (the dispatch picks the joints' closed forms for
        # float numbers: equal to lie.exp to rounding)
        poses = forward.batch_poses(self.model, q) if q.ndim > 1 else forward.poses(self.model, q)
        batch = q.shape[:-1]
        zero = self._zero_twist(batch)
        xi = {self.ground: zero}
        acc = {
            self.ground: np.broadcast_to(self.ground_acceleration, batch + (6,))
            if gravity
            else zero
        }
        screws: dict[str, np.ndarray] = {}
        for body, jk, prev, sign in self.plan:
            k = jk.columns.start
            s = lie.act_screw(poses[jk.a], jk.basis[0])
            if sign < 0:
                s = -s
            screws[body] = s
            rate = s * qd[..., k, None]
            xi[body] = xi[prev] + rate
            if qdd is not None:
                acc[body] = acc[prev] + s * qdd[..., k, None] + lie.bracket(xi[body], rate)
        return poses, xi, acc, screws

    def inertias_at(self, poses: dict[str, np.ndarray]) -> dict[str, Inertia]:
        """Each massive body's inertia carried to its pose."""
        return {b: I0.moved(poses[b]) for b, I0 in self.inertia.items()}

    # ------------------------------------------------------------------ dynamics

    def inverse(self, q: Any, qd: Any, qdd: Any, gravity: bool = True) -> np.ndarray:
        """The joint efforts (N, N m) for the joint values ``q``, rates ``qd`` and
        accelerations ``qdd`` (each (..., n)): the recursive Newton-Euler algorithm."""
        q, qd, qdd = (self._arr(x) for x in (q, qd, qdd))
        fast = _INVERSE.pick(self, q, qd, qdd, gravity)
        got = None if fast is None else fast(self, q, qd, qdd, gravity)
        if got is not None:
            return got
        poses, xi, acc, screws = self.motion(q, qd, qdd, gravity)
        carried: dict[str, np.ndarray] = {}
        for body, I0 in self.inertia.items():
            # the law where the body's inertia is the drawn one: the twist and acceleration
            # brought back by Ad(g^-1), the wrench carried to the pose by the coadjoint
            # action (Ad(g) in the (f, m) layout); the same as newton_euler(I0.moved(g),
            # xi, acc) without moving the inertia sample by sample
            g = poses[body]
            back = lie.inverse(g)
            w0 = newton_euler(I0, lie.act_screw(back, xi[body]), lie.act_screw(back, acc[body]))
            carried[body] = lie.act_screw(g, w0)
        batch = q.shape[:-1]
        zero = self.backend.zeros(batch) if batch else self.backend.zeros(())
        tau: list[Any] = [zero] * self.n  # a chord's coordinate moves no body
        for body, jk, prev, _sign in reversed(self.plan):
            F = carried.get(body)
            if F is None:
                F = self._zero_twist(q.shape[:-1])
            tau[jk.columns.start] = lie.klein(screws[body], F)
            if prev != self.ground:
                carried[prev] = carried[prev] + F if prev in carried else F
        return np.stack(tau, axis=-1)

    def bias(self, q: Any, qd: Any, gravity: bool = True) -> np.ndarray:
        """The bias efforts: Coriolis, centrifugal and gravity (inverse dynamics at zero
        acceleration)."""
        q = self._arr(q)
        return self.inverse(q, qd, self._zeros_like(q), gravity)

    def gravity_efforts(self, q: Any) -> np.ndarray:
        """The efforts that hold the weights at rest."""
        q = self._arr(q)
        return self.inverse(q, self._zeros_like(q), self._zeros_like(q), True)

    def mass_matrix(self, q: Any) -> np.ndarray:
        """The joint-space mass matrix (..., n, n) from the composite inertias."""
        q = self._arr(q)
        batch = q.shape[:-1]
        poses, _, _, screws = self.motion(q, self._zeros_like(q), None, False)
        composite: dict[str, np.ndarray] = {
            b: I.matrix() for b, I in self.inertias_at(poses).items()
        }
        M: list[list[Any]] = [[None] * self.n for _ in range(self.n)]
        for body, jk, prev, _sign in reversed(self.plan):
            l = jk.columns.start
            Ic = composite.get(body)
            if Ic is None:
                Ic = np.broadcast_to(self.backend.zeros((6, 6)), batch + (6, 6))
            f = (Ic @ screws[body][..., None])[..., 0]
            for k in self.path_columns[body]:
                sk = screws[self._body_of_column[k]]
                M[k][l] = M[l][k] = lie.klein(sk, f)
            if prev != self.ground:
                composite[prev] = composite[prev] + Ic if prev in composite else Ic
        zero = self.backend.zeros(batch) if batch else self.backend.zeros(())
        rows = [np.stack([x if x is not None else zero for x in row], axis=-1) for row in M]
        return np.stack(rows, axis=-2)

    def forward(self, q: Any, qd: Any, tau: Any, gravity: bool = True) -> np.ndarray:
        """The joint accelerations under the efforts ``tau``: ``M qdd = tau - bias`` solved
        by Cholesky (float, batched) or by the backend's exact / mp solve."""
        q, tau = self._arr(q), self._arr(tau)
        M = self.mass_matrix(q)
        rhs = tau - self.bias(q, qd, gravity)
        if not holds_objects(M):
            try:
                L = np.linalg.cholesky(M)
            except np.linalg.LinAlgError:
                raise UserError(self._singular_message()) from None
            y = np.linalg.solve(L, rhs[..., None])
            return np.linalg.solve(np.swapaxes(L, -1, -2), y)[..., 0]
        if M.ndim != 2:
            return np.stack([self.forward(q[i], qd[i], tau[i], gravity) for i in range(len(q))])
        try:
            return self.backend.solve(M, rhs)
        except Exception as exc:  # noqa: BLE001 - a singular matrix, said for people
            raise UserError(self._singular_message()) from exc

    def kinetic_energy(self, q: Any, qd: Any) -> np.ndarray:
        """The kinetic energy (J): the sum of the bodies' ``1/2 <I(xi), xi>``."""
        q, qd = self._arr(q), self._arr(qd)
        poses, xi, _, _ = self.motion(q, qd, None, False)
        total: Any = self.backend.zeros(q.shape[:-1]) if q.ndim > 1 else self.backend.zeros(())
        for body, I in self.inertias_at(poses).items():
            total = total + kinetic_energy(I, xi[body])
        return total

    # ------------------------------------------------------------------ helpers

    def _arr(self, x: Any) -> np.ndarray:
        if isinstance(x, np.ndarray) and (x.dtype == object) == (self.backend.dtype == object):
            return x
        return self.model.asarray(x)

    def _zeros_like(self, q: np.ndarray) -> np.ndarray:
        return self.backend.zeros(q.shape)

    def _singular_message(self) -> str:
        moved = {b for b in self.inertia}
        idle = [
            jk.name
            for body, jk, _, _ in self.plan
            if not any(b in moved for b in self._subtree(body))
        ]
        why = (
            f": joint{'s' if len(idle) > 1 else ''} {', '.join(idle)} move{'' if len(idle) > 1 else 's'} no mass"
            if idle
            else " (a joint moves no inertia about its axis)"
        )
        return (
            f"the mass matrix is singular{why}; give the bodies they move a mass and an "
            "inertia (mass: in the file, <inertial> in URDF and MJCF)"
        )

    def _subtree(self, body: str) -> set[str]:
        out = {body}
        for b, _, prev, _ in self.plan:  # parents first
            if prev in out:
                out.add(b)
        return out


def _refuse(mech: Any, closed: bool = False) -> None:
    """The mechanisms the tree dynamics does not take, with the reason."""
    if mech.graph.loops and not closed:
        raise UserError(
            f"{mech.name}: the tree dynamics takes an open chain or a tree; this mechanism "
            f"has {len(mech.graph.loops)} closed loop(s)"
        )
    if mech.couplings:
        raise UserError(
            f"{mech.name}: coupled joints (couplings, a URDF <mimic>) are not taken by the "
            "dynamics; remove the coupling"
        )
    other = [j for j in mech.joints if j.type not in ONE_COORDINATE]
    if other:
        j = other[0]
        raise UserError(
            f"{mech.name}: joint {j.name!r} is {j.type}; the dynamics takes joints of one "
            f"coordinate ({', '.join(ONE_COORDINATE)}): write a joint of several as joints "
            "of one with massless bodies between them"
        )
    if mech.weights is None:
        raise UserError(
            f"{mech.name}: the file gives no masses; add mass: {{BODY: {{kg: M, centre: "
            "[x, y, z], inertia: [ixx, iyy, izz, ixy, ixz, iyz]}} (URDF and MJCF: "
            "<inertial>; mechsing does not derive an inertia from MJCF geoms)"
        )


# the compiled form registers itself in the table (when numba is installed)
from mechsing.kinetics import _compiled  # noqa: E402,F401
