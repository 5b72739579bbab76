"""Forward kinematics: poses and current joint screws of one configuration or a batch.

Owns the product of exponentials of a mechanism's spanning tree: the joint
elements, the body poses and the current screws (the Jacobian columns), written
once with :mod:`mechsing.lie` for a coordinate vector ``q`` of shape ``(n,)``
or an array of configurations ``(N, n)`` (every :mod:`mechsing.lie` function
broadcasts over leading axes).  :class:`~mechsing.kinematics.KinematicModel`
calls these with one configuration (in any backend), the scanner with
thousands (float).

It also owns :class:`SerialJacobian`, the fast batched Jacobian of a serial
chain of one-dof joints crossed forward from ground, built directly in the
commensurate frame (the scanner's throughput path).

Conventions: those of :mod:`mechsing.kinematics.model` (``g_b = g_a M_j``,
current screws carried by the pose of ``between[0]``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing import lie
from mechsing.lie import ANGULAR, LINEAR
from mechsing.lie._rodrigues import one_dof_exp, spherical_exp
from mechsing.numeric import dispatch
from mechsing.numeric.backend import holds_objects

#: the fast forms of :func:`element` (a float batch: by the joint's kind)
_ELEMENT = dispatch.table("joint element", "mechsing.kinematics.forward.element")
#: the fast forms of every joint's element at once (one float configuration)
_ELEMENTS = dispatch.table("joint elements", "mechsing.kinematics.forward.element, joint by joint")
#: the fast forms of :func:`current_screws` (float configurations), by q's dimensions
_SCREWS = dispatch.table("current screws", "mechsing.kinematics.forward.current_screws")


def _float_batch(jk: Any, q: Any) -> bool:
    """A float joint at float configurations (N, n)?"""
    return (
        isinstance(q, np.ndarray)
        and q.dtype == np.float64
        and q.ndim == 2
        and jk.basis.dtype == np.float64
    )


@_ELEMENT.register(
    "one-dof",
    "a one-dof float joint at a float batch: the Rodrigues closed form (to rounding)",
    accepts=lambda jk, q: _float_batch(jk, q) and jk.type != "U" and jk.basis.shape[0] == 1,
)
def _one_dof_element(jk: Any, q: np.ndarray) -> np.ndarray:
    return one_dof_exp(jk.basis[0], q[..., jk.columns.start])


@_ELEMENT.register(
    "universal",
    "a float U joint at a float batch: the product of its two turns' closed forms",
    accepts=lambda jk, q: _float_batch(jk, q) and jk.type == "U",
)
def _universal_element(jk: Any, q: np.ndarray) -> np.ndarray:
    c = jk.columns.start
    return one_dof_exp(jk.basis[0], q[..., c]) @ one_dof_exp(jk.basis[1], q[..., c + 1])


@_ELEMENT.register(
    "spherical",
    "a float S joint at a float batch: the turn about its centre (to rounding)",
    accepts=lambda jk, q: _float_batch(jk, q) and jk.type == "S",
)
def _spherical_element(jk: Any, q: np.ndarray) -> np.ndarray:
    return spherical_exp(jk.basis, q[..., jk.columns])


__all__ = [
    "SerialJacobian",
    "batch_element",
    "batch_poses",
    "current_screws",
    "element",
    "poses",
]


def element(jk: Any, q: np.ndarray) -> np.ndarray:
    """The joint's relative displacement M (``g_b = g_a M``): (..., 4, 4) for q of shape
    (..., n); each configuration's bitwise as alone (:func:`mechsing.lie.exp`)."""
    qj = q[..., jk.columns]
    if jk.type == "U":
        return lie.exp(jk.basis[0] * qj[..., 0, None]) @ lie.exp(jk.basis[1] * qj[..., 1, None])
    return lie.exp(qj @ jk.basis)


def batch_element(jk: Any, q: np.ndarray) -> np.ndarray:
    """:func:`element` at a batch of configurations (N, n), to rounding: the dispatch
    table ``joint element`` picks a closed form from the joint's kind and the numbers'
    dtype (Rodrigues, for a float joint at float values: equal to :func:`element` to
    rounding, not bit for bit); the sweeps' batched Newton and measures."""
    fast = _ELEMENT.pick(jk, q)
    return fast(jk, q) if fast is not None else element(jk, q)


def poses(model: Any, q: np.ndarray, bodies: Any = None) -> dict[str, np.ndarray]:
    """The pose of every user body (ground = identity) from the spanning tree, or only of
    ``bodies`` and those on their tree paths: (..., 4, 4) for q of shape (..., n), each
    configuration's bitwise as alone (the joints' elements: :func:`element`)."""
    return _poses(model, q, bodies, element)


def batch_poses(model: Any, q: np.ndarray, bodies: Any = None) -> dict[str, np.ndarray]:
    """:func:`poses` of a batch of configurations (N, n), to rounding (the joints'
    elements: :func:`batch_element`): the sweeps' batches."""
    return _poses(model, q, bodies, batch_element)


def _poses(model: Any, q: np.ndarray, bodies: Any, of: Any) -> dict[str, np.ndarray]:
    mech = model.mech
    eye = model.backend.eye(4)
    batch = q.shape[:-1]
    if batch:
        eye = np.broadcast_to(eye, batch + (4, 4))
    out: dict[str, np.ndarray] = {mech.ground: eye}
    elements: dict[str, np.ndarray] = {}
    paths = mech.graph.tree_paths
    if bodies is None:
        wanted = None
    else:
        wanted = set()
        for body in bodies:
            here = mech.ground
            for st in paths[body]:
                jk = model.joint(st.joint)
                here = jk.b if st.sign > 0 else jk.a
                wanted.add(here)
    at_once = _ELEMENTS.pick(model, q) if wanted is None else None
    if at_once is not None:
        elements.update(at_once(model, q))
    for body, jk, prev, sign in _pose_plan(model):
        if wanted is not None and body not in wanted:
            continue
        if jk.name not in elements:
            elements[jk.name] = of(jk, q)
        M = elements[jk.name]
        if sign > 0 and prev == mech.ground and of is batch_element and not holds_objects(M):
            # a float body after a joint from ground: its element (the identity's product
            # is exact)
            out[body] = M
            continue
        out[body] = out[prev] @ (M if sign > 0 else lie.inverse(M))
    return out


def _pose_plan(model: Any) -> list[tuple[str, Any, str, int]]:
    """The order in which :func:`poses` composes the tree (built once per model): each
    user body (shorter tree paths first) with the joint of its path's last step, the
    body before that step and the step's sign (hidden cross bodies: see
    :func:`current_screws`)."""
    plan = model.plans.pose_order
    if plan is None:
        mech = model.mech
        plan = []
        for body, steps in sorted(mech.graph.tree_paths.items(), key=lambda kv: len(kv[1])):
            if body == mech.ground or not steps or steps[-1].part is not None:
                continue
            last = steps[-1]
            jk = model.joint(last.joint)
            plan.append((body, jk, jk.a if last.sign > 0 else jk.b, last.sign))
        model.plans.pose_order = plan
    return plan


def _float_rows(q: Any, ndim: int) -> bool:
    return isinstance(q, np.ndarray) and q.dtype == np.float64 and q.ndim == ndim


@_SCREWS.register(
    "one configuration",
    "one float configuration: every joint's screws by one act_screw on the stacked poses",
    accepts=lambda model, q, body_poses: _float_rows(q, 1),
)
def _screws_at_once(model: Any, q: np.ndarray, body_poses: dict[str, np.ndarray]) -> np.ndarray:
    """:func:`current_screws` of every joint at one float configuration, by one call of
    :func:`mechsing.lie.act_screw` on the stacked poses and basis screws (a U joint's
    second screw is carried by ``g_a exp(q1 e1)``, its cross body's pose)."""
    carriers, E, crosses = _screw_plan(model)
    if not carriers:
        return model.backend.zeros((6, 0))
    G = [body_poses[a] for a in carriers]
    for jk in crosses:
        c = jk.columns.start
        G[c + 1] = G[c] @ lie.exp(jk.basis[0] * q[c, None])
    return lie.act_screw(np.stack(G), E).T


@_SCREWS.register(
    "batch",
    "a float batch (N, n): each joint's screws written into the (N, 6, n) array",
    accepts=lambda model, q, body_poses: _float_rows(q, 2),
)
def _screws_of_batch(model: Any, q: np.ndarray, body_poses: dict[str, np.ndarray]) -> np.ndarray:
    """:func:`current_screws` of every joint at a float batch of configurations q (N, n):
    the same :func:`mechsing.lie.act_screw` of each joint's basis screws (a U joint's
    second screw carried by ``g_a exp(q1 e1)``), written into the (N, 6, n) array in
    place instead of stacked."""
    out = np.empty((q.shape[0], 6, model.n))
    for jk in model.joints:
        ga = body_poses[jk.a]
        c = jk.columns.start
        if jk.type == "U":
            out[:, :, c] = lie.act_screw(ga, jk.basis[0])
            turned = ga @ lie.exp(jk.basis[0] * q[:, c, None])
            out[:, :, c + 1] = lie.act_screw(turned, jk.basis[1])
        else:
            out[:, :, jk.columns] = np.swapaxes(lie.act_screw(ga[:, None, :, :], jk.basis), 1, 2)
    return out


def _screw_plan(model: Any) -> tuple[list[str], Any, list[Any]]:
    """What :func:`_screws_at_once` stacks (built once per model): the body whose pose
    carries each coordinate's screw (``between[0]``; a U joint's second screw is fixed
    up from its first), the basis screws stacked, and the U joints."""
    plan = model.plans.screws
    if plan is None:
        carriers, E = [], []
        for jk in model.joints:
            for e in jk.basis:
                carriers.append(jk.a)
                E.append(e)
        crosses = [jk for jk in model.joints if jk.type == "U"]
        plan = (carriers, np.stack(E) if E else None, crosses)
        model.plans.screws = plan
    return plan


@_ELEMENTS.register(
    "stacked joints",
    "one float configuration: every joint's element (but U) by one exp of the stacked twists",
    accepts=lambda model, q, joints=None: (
        isinstance(q, np.ndarray) and q.dtype == np.float64 and q.ndim == 1
    ),
)
def elements_at_once(model: Any, q: np.ndarray, joints: Any = None) -> dict[str, np.ndarray]:
    """The elements of every joint (or of ``joints``) but the U joints at one float
    configuration, by one call of :func:`mechsing.lie.exp` on the stacked twists
    ``q_j @ basis_j`` (the same formula as :func:`element`, evaluated joint by joint
    in numpy's batch)."""
    joints, rows, cols, basis, others = _element_plan(model, joints)
    if not joints:
        return {}
    if holds_objects(joints[0].basis):  # a model in mp or exact numbers
        Ms = lie.exp(np.stack([q[jk.columns] @ jk.basis for jk in joints]))
        return {jk.name: Ms[i] for i, jk in enumerate(joints)}
    twists = np.empty((len(joints), 6))
    # a one-dof twist q e: the product matmul forms (q e + 0.0, as its sum from zero)
    twists[rows] = q[cols][:, None] * basis + 0.0
    for i in others:
        twists[i] = q[joints[i].columns] @ joints[i].basis
    Ms = lie.exp(twists)
    return dict(zip([jk.name for jk in joints], Ms, strict=True))


def _element_plan(
    model: Any, joints: Any
) -> tuple[list[Any], np.ndarray, np.ndarray, np.ndarray, list[int]]:
    """What :func:`elements_at_once` stacks for these joints (built once per model and
    set of joints): the joints but U, the rows of the one-dof joints with their
    coordinates and basis screws stacked, and the rows of the others."""
    cache = model.plans.elements
    key = None if joints is None else tuple(jk.name for jk in joints)
    plan = cache.get(key)
    if plan is None:
        kept = [jk for jk in (model.joints if joints is None else joints) if jk.type != "U"]
        one = [i for i, jk in enumerate(kept) if jk.basis.shape[0] == 1]
        plan = (
            kept,
            np.array(one, dtype=np.intp),
            np.array([kept[i].columns.start for i in one], dtype=np.intp),
            np.array([kept[i].basis[0] for i in one]).reshape(len(one), 6),
            [i for i, jk in enumerate(kept) if jk.basis.shape[0] != 1],
        )
        cache[key] = plan
    return plan


def current_screws(
    model: Any,
    q: np.ndarray,
    body_poses: dict[str, np.ndarray] | None = None,
    joints: list[Any] | None = None,
) -> np.ndarray:
    """The current screw of every joint coordinate: (..., 6, n), columns in file order.

    With ``joints``, only theirs (the other columns zero; ``body_poses`` then needs only
    the poses of their ``between[0]`` bodies)."""
    body_poses = poses(model, q) if body_poses is None else body_poses
    if joints is None:
        fast = _SCREWS.pick(model, q, body_poses)
        if fast is not None:
            return fast(model, q, body_poses)
    cols = []
    for jk in model.joints if joints is None else joints:
        ga = body_poses[jk.a]
        if jk.type == "U":
            qa = q[..., jk.columns.start, None]
            cols.append(lie.act_screw(ga, jk.basis[0]))
            cols.append(lie.act_screw(ga @ lie.exp(jk.basis[0] * qa), jk.basis[1]))
        elif ga.ndim == 2:  # one configuration: (k, 6)
            cols.extend(lie.act_screw(ga, jk.basis))
        else:  # a batch: (N, k, 6), one current screw per basis screw of the joint
            cols.extend(np.moveaxis(lie.act_screw(ga[..., None, :, :], jk.basis), -2, 0))
    if joints is not None:
        out = model.backend.zeros(q.shape[:-1] + (6, model.n))
        where = [c for jk in joints for c in range(jk.columns.start, jk.columns.stop)]
        if cols:
            out[..., where] = np.stack(cols, axis=-1)
        return out
    if not cols:
        return model.backend.zeros(q.shape[:-1] + (6, 0))
    return np.stack(cols, axis=-1)


class SerialJacobian:
    """Commensurate Jacobians of a serial chain of one-dof joints, batched.

    The chain: the tree path from ground to one body, every joint crossed forward
    (``sign > 0``) and of one degree of freedom.  The pose (R, P) is carried in the
    commensurate frame (origin at the centroid, lengths / L: an automorphism of D,
    so exp and Ad commute with it).  For each joint with unit screw ``(u, v)`` (or
    ``u = 0``), one product ``R @ [K, K^2, K a, K^2 a, u, v]`` (``K = u^``, axis
    point ``a = u x v``, pitch ``h = u . v``) gives its current screw
    ``(R u, R v + P x R u)`` and the next pose by the Rodrigues form of
    :func:`mechsing.lie.exp` composed on the right: ``R + sin R K + (1 - cos) R K^2``,
    ``P - sin R K a - (1 - cos) R K^2 a + h theta R u``.

    Parameters
    ----------
    model : KinematicModel (float)
    joints : the chain's joints, ground first
    order : the chain's coordinate columns (the matrix's column order)
    point : an output point on the last body (m), or None for its twist
    """

    def __init__(
        self, model: Any, joints: list[Any], order: list[int], point: np.ndarray | None
    ) -> None:
        self.frame = model.float_frame
        self.order = list(order)
        self.columns = len(order)
        #: the output point's commensurate position (x - c) / L, or None
        self.point = None if point is None else self.frame.point(np.asarray(point, dtype=float))
        self._table = []
        for jk in joints:
            e = self.frame.twists(np.asarray(jk.basis, dtype=float)[0][:, None])[:, 0]
            u, v = e[ANGULAR], e[LINEAR]
            K = lie.hat(np.concatenate([u, np.zeros(3)]))[:3, :3]
            K2 = K @ K
            a = np.cross(u, v)
            h = float(u @ v)
            # columns: K, K^2 (rotation update), K a, K^2 a (translation update), u, v
            T = np.concatenate(
                [K, K2, (K @ a)[:, None], (K2 @ a)[:, None], u[:, None], v[:, None]], axis=1
            )
            start = jk.columns.start
            self._table.append((start, order.index(start), T, h, bool(np.any(u))))

    @property
    def table(self) -> tuple[tuple[int, int, np.ndarray, float, bool], ...]:
        """Per joint, ground first: its column, its position in the matrix, its table
        ``[K, K^2, K a, K^2 a, u, v]`` (3 x 12), its pitch and whether it rotates (what a
        compiled form of this product reads)."""
        return tuple(self._table)

    @staticmethod
    def applies(model: Any, body: str, joints: list[Any]) -> bool:
        """Is the chain ``joints`` the forward tree path from ground to ``body`` of one-dof joints?"""
        steps = model.mech.graph.tree_paths[body]
        if any(st.sign < 0 or st.part is not None for st in steps):
            return False
        path = [model.joint(st.joint) for st in steps]
        return all(jk.basis.shape[0] == 1 and jk.type != "U" for jk in path) and {
            jk.name for jk in path
        } == {jk.name for jk in joints}

    def __call__(self, Q: np.ndarray) -> np.ndarray:
        """The commensurate matrices (N, 6 or 3, columns) at the rows of Q."""
        n = Q.shape[0]
        J = np.empty((n, 6, self.columns))
        R = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
        P = np.zeros((n, 3))
        last = len(self._table) - 1
        for i, (col, pos, T, h, rotates) in enumerate(self._table):
            RT = (R.reshape(-1, 3) @ T).reshape(n, 3, T.shape[1])
            w = RT[:, :, 8]
            J[:, :3, pos] = w
            J[:, 3:, pos] = RT[:, :, 9] + _cross(P, w)
            if i == last and self.point is None:
                break
            th = Q[:, col]
            if rotates:
                s = np.sin(th)
                c1 = 1.0 - np.cos(th)
                R = R + s[:, None, None] * RT[:, :, 0:3] + c1[:, None, None] * RT[:, :, 3:6]
                P = P - s[:, None] * RT[:, :, 6] - c1[:, None] * RT[:, :, 7]
                if h:
                    P = P + (h * th)[:, None] * w
            else:
                P = P + th[:, None] * RT[:, :, 9]
        if self.point is not None:
            X = R @ self.point + P
            w = J[:, :3, :]
            vel = J[:, 3:, :] + np.cross(w, X[:, :, None], axis=1)
            J = np.ascontiguousarray(vel)
        return self.frame.columns_in_place(J, self.order)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b for (N, 3) arrays (faster than np.cross or lie.cross on small rows)."""
    out = np.empty_like(b)
    out[:, 0] = a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]
    out[:, 1] = a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2]
    out[:, 2] = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    return out


dispatch.table(
    "serial chain", "the scanner's matrices from mechsing.kinematics.forward.current_screws"
).register(
    "batched",
    "a serial chain of one-dof joints from ground, batched: the Rodrigues update in the "
    "commensurate frame (the scanner's matrices, to rounding)",
    accepts=None,  # the scanner builds it where SerialJacobian.applies
)(SerialJacobian)
