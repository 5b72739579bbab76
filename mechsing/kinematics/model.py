"""The kinematic model of a mechanism in one precision mode: its joints' reference
screws and coordinates, closure residuals, closure Jacobian and updates on the
group (poses and current screws are computed by :mod:`mechsing.kinematics.forward`,
the closure Jacobians by :mod:`mechsing.kinematics.jacobians`, the updates on the group
by :mod:`mechsing.kinematics.coordinates`: the model's methods call them, and the model
keeps their caches; what depends only on the model, their plans, it keeps in its
:class:`~mechsing.kinematics.plans.ModelPlans`).

Conventions (those of the mechanism file; the README states them):

* the joint values of a mechanism are one flat vector ``q`` of all joint
  coordinates in file order and catalog basis order
  (:meth:`Mechanism.coordinates`);
* a joint with ``between: [a, b]`` sets ``g_b = g_a exp(sum q_i e_i)`` with
  ``e_i`` its reference basis screws (ground frame); a U joint sets
  ``g_b = g_a exp(q1 R(a1, c)) exp(q2 R(a2, c))``;
* the *velocity* of a joint is trivialised: ``u`` with relative twist
  ``V_b - V_a = sum u_i Ad(g_a) e_i`` (``M' M^-1 = sum u_i e_i`` for the joint
  element M), so a joint's current screws are its reference basis carried by
  the pose of ``between[0]`` and no chart singularity reaches an analysis.  The
  matching update of a joint element is ``M <- exp(sum d_i e_i) M`` (additive on
  coordinates for abelian subgroups and for U joints);
* the closure residual of a chord joint j (not in the spanning tree) is
  ``Delta_j = g_a M_j g_b^-1`` with ``g_a``, ``g_b`` from the tree; it is the
  identity when the loop through j closes;
* a coupling of two one-coordinate joints (``couplings``, a URDF ``<mimic>``:
  ``q_f = m q_l + c``) is one more closure block after the chords' (:mod:`.couplings`):
  its residual is the pure translation ``(e L / s_f) x`` with ``e = q_f - m q_l - c``
  (``s_f``: L for a length coordinate, 1 for an angle), the identity exactly when the
  coupling holds, and its Jacobian block the constant row ``(dq_f - m dq_l) L / s_f`` in
  the linear x row (five zero rows): so every Newton step, rank and kernel of the stacked
  closure system, built block by block, takes the coupling as one more constraint.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from mechsing import lie
from mechsing.kinematics import coordinates, forward, jacobians
from mechsing.kinematics.couplings import (
    CouplingKinematics,
    coupling_block,
    coupling_kinematics,
    coupling_residuals,
)
from mechsing.kinematics.field import FieldKinematics
from mechsing.kinematics.plans import ModelPlans
from mechsing.model import Mechanism
from mechsing.numeric import (
    CommensurateFrame,
    Precision,
    characteristic_length,
    dispatch,
    to_float,
)
from mechsing.numeric.backend import is_float64
from mechsing.numeric.lazy import mpmath
from mechsing.numeric.pirational import PiRational
from mechsing.subgroups import Subgroup

if TYPE_CHECKING:
    from scipy.sparse import csc_matrix

    from mechsing.kinematics.field import FieldKinematics


@dataclass(frozen=True)
class JointKinematics:
    """What the kinematics needs of one joint.

    ``basis``: reference screws (dof, 6) in the model's backend; ``columns``:
    its slice of the coordinate vector; ``abelian``: coordinates add under
    updates; ``subgroup``: the reference subgroup (None for U);
    ``length_coordinates``: which coordinates are lengths.
    """

    name: str
    type: str
    a: str
    b: str
    basis: np.ndarray
    columns: slice
    abelian: bool
    subgroup: Subgroup | None
    length_coordinates: tuple[bool, ...]


def axis_points(mech: Mechanism) -> list[list[Any]]:
    """Each joint's axis point nearest the origin (R, H, C), or centre (S, U), exact."""
    pts = []
    for j in mech.joints:
        if j.type in ("R", "H", "C"):
            u, p = j.params["axis"], j.params["point"]
            if all(isinstance(x, PiRational) for x in (*u, *p)):  # the file's plain numbers
                along = sum(a * b for a, b in zip(u, p, strict=True)) / sum(a * a for a in u)
                pts.append([pk - uk * along for uk, pk in zip(u, p, strict=True)])
                continue
            import sympy

            u = sympy.Matrix(j.params["axis"])
            p = sympy.Matrix(j.params["point"])
            foot = p - u * (u.dot(p)) / u.dot(u)
            pts.append([sympy.nsimplify(x) if isinstance(x, float) else x for x in foot])
        elif j.type in ("S", "U"):
            pts.append(list(j.params["point"]))
    return pts


def _exact_centroid(pts: list[list[Any]]) -> list[Any] | None:
    """The exact mean of the axis points when their coordinates are all rational, else
    None (a centroid with radicals would carry them into every commensurate number)."""
    import sympy

    if not pts:
        return None
    vals = [sympy.sympify(x) for p in pts for x in p]
    if not all(v.is_Rational for v in vals):
        return None
    return [sum(vals[k::3], sympy.S.Zero) / len(pts) for k in range(3)]


def refuse_inexact_geometry(mech: Mechanism) -> None:
    """Exact mode needs exact data: every number of the geometry (axes, points,
    pitches, the output point, the characteristic length) must be one that sympy proves
    algebraic.  Otherwise the whole file is refused (MechanismError, exit status 2), naming
    the joint, the key and the line."""
    import sympy

    from mechsing.errors import MechanismError

    def numbers(x: Any) -> list[Any]:
        if isinstance(x, tuple | list):
            return [y for v in x for y in numbers(v)]
        return [x]

    items: list[tuple[str, str, Any, int | None]] = [
        (f"joint {j.name!r}", key, value, j.line)
        for j in mech.joints
        for key, value in j.params.items()
    ]
    if mech.output is not None and mech.output.point is not None:
        items.append(("output", "point", mech.output.point, mech.output.line))
    if mech.characteristic_length is not None:
        items.append(("characteristic_length", "value", mech.characteristic_length, None))
    for item, key, value, line in items:
        for x in numbers(value):
            if sympy.expand_trig(sympy.sympify(x)).is_algebraic is not True:
                raise MechanismError(
                    f"{key} contains {x}, which is not exact data (sympy cannot show that it is "
                    "algebraic); exact mode needs rational or algebraic lengths and axes (e.g. "
                    '"sqrt(3)/2", "cos(pi/12)"); use --precision auto, float or mp:N for this file',
                    path=mech.path,
                    line=line,
                    item=item,
                )


class KinematicModel:
    """Poses, screws and closure residuals of a mechanism in one precision mode.

    Parameters
    ----------
    mech : Mechanism
    precision : Precision or str
        ``float``/``auto`` (numpy), ``mp:N`` or ``exact``; the reference screws
        are built from the file's exact values in that mode.
    """

    def __init__(self, mech: Mechanism, precision: Precision | str = "float") -> None:
        from mechsing.model.couplings import refuse_orphan_couplings
        from mechsing.numeric import parse_precision

        refuse_orphan_couplings(mech)  # a <mimic> of a joint the robot does not define
        self.mech = mech
        #: what depends only on this model, built when first asked (:mod:`.plans`)
        self.plans = ModelPlans()
        self.precision = parse_precision(precision) if isinstance(precision, str) else precision
        if self.precision.mode == "auto":
            self.precision = Precision("float")
        if self.precision.mode == "exact":  # policy: exact mode takes exact geometry only
            refuse_inexact_geometry(mech)
        self.backend = self.precision.backend
        pts = axis_points(mech)
        override = mech.characteristic_length
        L, c = characteristic_length(
            to_float(np.array(pts, dtype=object)) if pts else np.zeros((0, 3)),
            None if override is None else float(override),
        )
        #: characteristic length L (m) and centroid c of the axis points (float)
        self.length_scale: float = L
        self.centroid: np.ndarray = c
        self.joints: list[JointKinematics] = []
        offset = 0
        with self.precision.context():
            for j in mech.joints:
                if j.type == "U":
                    a1, a2 = j.params["axes"]
                    cpt = j.params["point"]
                    r1 = Subgroup("R", axis=a1, point=cpt)
                    r2 = Subgroup("R", axis=a2, point=cpt)
                    B = np.concatenate([r1.basis(self.precision), r2.basis(self.precision)])
                    jk = JointKinematics(
                        j.name,
                        "U",
                        j.between[0],
                        j.between[1],
                        B,
                        slice(offset, offset + 2),
                        True,
                        None,
                        (False, False),
                    )
                else:
                    sg = Subgroup(j.type, dict(j.params))
                    B = sg.basis(self.precision).reshape(-1, 6)
                    lengths = tuple(u == "m" for u in j.units)
                    jk = JointKinematics(
                        j.name,
                        j.type,
                        j.between[0],
                        j.between[1],
                        B,
                        slice(offset, offset + B.shape[0]),
                        _is_abelian(B),
                        sg,
                        lengths,
                    )
                self.joints.append(jk)
                offset += jk.basis.shape[0]
        self.n: int = offset
        self._by_name = {jk.name: jk for jk in self.joints}
        self.length_columns = np.zeros(self.n, dtype=bool)
        for jk in self.joints:
            self.length_columns[jk.columns] = jk.length_coordinates
        #: the commensurate frame in the model's numbers, and its float twin: every map
        #: into the commensurate metric and back to SI goes through them
        self.frame: CommensurateFrame = CommensurateFrame.of(
            L,
            c,
            self.length_columns,
            self.backend,
            _exact_centroid(pts) if self.backend.name == "exact" else None,
        )
        self.float_frame: CommensurateFrame = self.frame.as_float()
        self.chords = [self._by_name[name] for name in mech.graph.chord_joints]
        #: the couplings of joint coordinates: closure blocks after the chords'
        self.couplings: tuple[CouplingKinematics, ...] = coupling_kinematics(self)
        #: the closure blocks: each chord's loop, then each coupling
        self.blocks: int = len(self.chords) + len(self.couplings)
        #: the commensurate coupling blocks, per frame (:meth:`coupling_block`)
        self._coupling_blocks: dict[int, tuple[Any, np.ndarray]] = {}
        self._points: dict[tuple[Any, ...], np.ndarray] = {}
        #: the elements of the non-abelian joints at the last float configuration, and
        #: each such joint's basis in the commensurate metric (:meth:`update`, kept here
        #: by :mod:`.coordinates`)
        self._last_elements: tuple[bytes, np.ndarray] | None = None
        self._basis_twists: dict[str, np.ndarray] = {}
        #: the basis rows of loops at rest (:func:`mechsing.screws.closure_system`)
        self._loop_rows: dict[tuple[Any, ...], Any] = {}
        #: the poses of the last float configurations asked for (by their bytes)
        self._pose_cache: dict[bytes, dict[str, np.ndarray]] = {}
        self._pose_cache_size = max(1, _POSE_CACHE_MATRICES // max(1, len(mech.bodies)))
        self._abelian_columns = np.zeros(self.n, dtype=bool)
        for jk in self.joints:
            self._abelian_columns[jk.columns] = jk.abelian
        self._non_abelian = [jk for jk in self.joints if not jk.abelian]
        self._float_twin: KinematicModel | None = None
        self._field_cache: dict[tuple[Any, ...], FieldKinematics | None] = {}

    # ------------------------------------------------------------------ access

    def joint(self, name: str) -> JointKinematics:
        return self._by_name[name]

    def float_twin(self) -> KinematicModel:
        """This model in float: itself when it is float, else a float model of the same
        mechanism built once (continuation and the nearby samples work in float)."""
        if self.precision.mode == "float":
            return self
        if self._float_twin is None:
            self._float_twin = KinematicModel(self.mech, "float")
        return self._float_twin

    def zeros(self) -> np.ndarray:
        return self.backend.zeros(self.n)

    def asarray(self, q: Any) -> np.ndarray:
        with self.precision.context():
            return self.backend.asarray(q)

    def point_array(self, x: Any) -> np.ndarray:
        """A fixed point of the file (its exact coordinates, a tuple) in the model's
        numbers, converted once (read only: the output point, asked for at every
        configuration)."""
        key = tuple(x)
        got = self._points.get(key)
        if got is None:
            got = self.asarray(list(key))
            got.flags.writeable = False
            self._points[key] = got
        return got

    def values(self, q: np.ndarray) -> dict[str, list[float]]:
        """Joint values by name, floats in SI units and radians."""
        qf = to_float(q)
        return {jk.name: [float(x) for x in qf[jk.columns]] for jk in self.joints}

    # ------------------------------------------------------------------ poses

    def element(self, jk: JointKinematics, q: np.ndarray) -> np.ndarray:
        """The joint's relative displacement M (g_b = g_a M)."""
        return forward.element(jk, q)

    def poses(self, q: np.ndarray) -> dict[str, np.ndarray]:
        """The pose of every user body (ground = identity) from the spanning tree;
        q may be one configuration (n,) or a batch (N, n).  An exact configuration's
        come from its number field when its data have one; the poses of the last float
        configurations are kept: Newton asks for them again for the residual and the
        Jacobian at the same point, and the analysis of many configurations (a sweep's
        located points: closed, then classified) for each again."""
        fk = self.field_kinematics(q)
        if fk is not None:
            return fk.poses()
        if q.ndim != 1 or not is_float64(q):
            return forward.poses(self, q)
        key = q.tobytes()
        got = self._pose_cache.get(key)
        if got is None:
            got = forward.poses(self, q)
            self._keep_poses(key, got)
        return dict(got)

    def keep_poses(self, qs: np.ndarray, poses: dict[str, np.ndarray]) -> None:
        """Remember the poses of a float batch ``qs`` (N, n) computed together (``poses``:
        ``poses(qs)``, each (N, 4, 4), configuration by configuration bitwise those of one
        configuration) for :meth:`poses` of each of them: configurations closed together
        and then analysed one by one."""
        if self.backend.name != "float" or qs.ndim != 2 or not is_float64(qs):
            return
        for i, q in enumerate(qs):
            self._keep_poses(q.tobytes(), {b: P[i].copy() for b, P in poses.items()})

    def _keep_poses(self, key: bytes, got: dict[str, np.ndarray]) -> None:
        cache = self._pose_cache
        if len(cache) >= self._pose_cache_size:
            # the oldest goes (another thread may have changed the cache meanwhile)
            try:
                cache.pop(next(iter(cache)), None)
            except (StopIteration, RuntimeError):
                pass
        cache[key] = got

    def field_kinematics(self, q: np.ndarray) -> FieldKinematics | None:
        """Exact mode: the kinematics of configuration ``q`` in the number field of its
        data (:class:`~mechsing.kinematics.field.FieldKinematics`), or None when ``q``
        is not one exact configuration or its data do not fit a field (the sympy path
        then serves).  Kept for the last few configurations."""
        if self.backend.name != "exact" or q.ndim != 1:
            return None
        key = tuple(q.tolist())
        cache = self._field_cache
        if key not in cache:
            if len(cache) >= _FIELD_CACHE_SIZE:
                cache.pop(next(iter(cache)))
            cache[key] = FieldKinematics.of(self, q)
        return cache[key]

    def current_screws(
        self, q: np.ndarray, poses: dict[str, np.ndarray] | None = None
    ) -> np.ndarray:
        """The current screw of every joint coordinate: (6, n) (or (N, 6, n) for a batch),
        columns in file order."""
        fk = self.field_kinematics(q)
        if fk is not None and _same_poses(fk, poses):
            return fk.current_screws()
        if poses is None and q.ndim == 1 and is_float64(q):
            poses = self.poses(q)
        return forward.current_screws(self, q, poses)

    # ------------------------------------------------------------------ closure

    def chord_residuals(
        self, q: np.ndarray, poses: dict[str, np.ndarray] | None = None
    ) -> list[np.ndarray]:
        """``Delta_j = g_a M_j g_b^-1`` for each chord joint (identity when closed), then
        each coupling's translation (:mod:`mechsing.kinematics.couplings`)."""
        fk = self.field_kinematics(q)
        if fk is not None and _same_poses(fk, poses):
            return fk.chord_residuals() + coupling_residuals(self, q)
        if self.couplings:
            chords = self._chord_residuals(q, poses)
            with self.precision.context():
                return chords + coupling_residuals(self, q)
        return self._chord_residuals(q, poses)

    def _chord_residuals(
        self, q: np.ndarray, poses: dict[str, np.ndarray] | None = None
    ) -> list[np.ndarray]:
        poses = self.poses(q) if poses is None else poses
        at_once = _ELEMENTS.pick(self, q, self.chords)
        if at_once is not None and len(self.chords) > 1:
            ms = at_once(self, q, self.chords)
            elements = [ms.get(jk.name) for jk in self.chords]
            if all(M is not None for M in elements):
                Ga = np.stack([poses[jk.a] for jk in self.chords])
                Gb = np.stack([poses[jk.b] for jk in self.chords])
                return list(Ga @ np.stack(elements) @ lie.inverse(Gb))
        else:
            elements = [None] * len(self.chords)
        return [
            poses[jk.a] @ (self.element(jk, q) if M is None else M) @ lie.inverse(poses[jk.b])
            for jk, M in zip(self.chords, elements, strict=True)
        ]

    def residual_norm(self, deltas: list[np.ndarray], native: bool = False) -> Any:
        """Closure residual as a length (m): the largest over the chords of
        ``sqrt(|p_c|^2 + L^2 |R - I|_F^2 / 2)`` with ``p_c`` the translation of
        Delta seen from the centroid (meaningful also near half-turns, where
        the logarithm is not).

        A float; with ``native`` at mp:N the model's own number (an ``mpf``: a
        residual of 1e-400 is not 0, as its float is)."""
        L = self.length_scale
        if native and self.backend.name == "mp":
            with self.precision.context():
                worst = mpmath.mpf(0)
                c = self.frame.c
                for D in deltas:
                    R = D[:3, :3]
                    p = D[:3, 3] + R @ c - c
                    E = R - self.backend.eye(3)
                    worst = max(worst, mpmath.sqrt((p * p).sum() + L * L * (E * E).sum() / 2))
                return worst
        worst = 0.0
        # policy: mp measures in its own numbers; an exact model's residual is a float
        # measure (exact closure is proved, not measured)
        mp = self.backend.name == "mp"
        c = (self.frame if mp else self.float_frame).c
        if not mp and len(deltas) > 1 and all(is_float64(D) for D in deltas):
            # float residuals of every chord in one batch (the same formula, the same numbers)
            Dm = np.stack(deltas)
            R = Dm[:, :3, :3]
            p = Dm[:, :3, 3] + R @ c - c
            E = R - np.eye(3)
            r2 = (p * p).sum(-1) + L * L * (E * E).sum((-2, -1)) / 2
            for x in r2.tolist():
                worst = max(worst, x**0.5)
            return worst
        with self.precision.context():
            for D in deltas:
                # in the model's precision: converting Delta to float first would
                # bury an mp:N residual under float rounding of R @ c
                Dm = D if mp else np.array(to_float(D))
                R = Dm[:3, :3]
                p = Dm[:3, 3] + R @ c - c
                E = R - np.eye(3)
                r2 = (p * p).sum() + L * L * (E * E).sum() / 2
                worst = max(worst, float(r2) ** 0.5)
        return worst

    def closure_jacobian(self, q: np.ndarray, screws: np.ndarray | None = None) -> np.ndarray:
        """Linearised closure (6 * blocks, n), or (N, 6 * blocks, n) for a float batch:
        :func:`.jacobians.closure_jacobian`."""
        return jacobians.closure_jacobian(self, q, screws)

    def coupling_block(self, frame: Any) -> np.ndarray:
        """The couplings' closure rows (6 * couplings, n): commensurate in ``frame``, or
        (None) raw, as :meth:`closure_jacobian` holds them (built once per frame)."""
        key = id(frame)
        got = self._coupling_blocks.get(key)
        if got is None or got[0] is not frame:
            got = (frame, coupling_block(self, frame))
            self._coupling_blocks[key] = got
        return got[1]

    def scaled_closure_jacobian(
        self, q: np.ndarray, frame: Any, screws: np.ndarray | None = None
    ) -> np.ndarray:
        """``frame.blocks(closure_jacobian(q))``: :func:`.jacobians.scaled_closure_jacobian`."""
        return jacobians.scaled_closure_jacobian(self, q, frame, screws)

    @property
    def sparse_closure(self) -> bool:
        """Whether the float closure Jacobian is built and solved sparse:
        :func:`.jacobians.sparse_closure`."""
        return jacobians.sparse_closure(self)

    def sparse_closure_jacobian(
        self, q: np.ndarray, frame: Any, screws: np.ndarray | None = None
    ) -> csc_matrix:
        """:meth:`scaled_closure_jacobian` as a sparse matrix:
        :func:`.jacobians.sparse_closure_jacobian`."""
        return jacobians.sparse_closure_jacobian(self, q, frame, screws)

    def chord_twists(self, deltas: list[np.ndarray]) -> np.ndarray:
        """log of each chord residual, stacked (6 * n_chords,): :func:`.jacobians.chord_twists`."""
        return jacobians.chord_twists(self, deltas)

    # ------------------------------------------------------------------ updates on the group

    def update(self, q: np.ndarray, delta: np.ndarray) -> np.ndarray:
        """Apply trivialised increments ``delta`` on the group: :func:`.coordinates.update`."""
        return coordinates.update(self, q, delta)

    def difference(self, q1: np.ndarray, q0: np.ndarray) -> np.ndarray:
        """The increments ``d`` with ``update(q0, d) == q1``, measured on the group:
        :func:`.coordinates.difference`."""
        return coordinates.difference(self, q1, q0)

    def coordinates_in(self, jk: JointKinematics, M: np.ndarray) -> np.ndarray:
        """First-kind coordinates of an element of the joint's subgroup:
        :func:`.coordinates.coordinates_in`."""
        return coordinates.coordinates_in(self, jk, M)


#: exact configurations whose field kinematics a model keeps
_FIELD_CACHE_SIZE = 8
#: the fast forms of the joints' elements at once (:mod:`mechsing.numeric.dispatch`)
_ELEMENTS = dispatch.table("joint elements")
#: body poses (4 x 4 matrices) the pose cache of a float model holds at most: a sweep's
#: located points of a small mechanism, a few configurations of a big one
_POSE_CACHE_MATRICES = 4096


def _same_poses(fk: FieldKinematics, poses: dict[str, np.ndarray] | None) -> bool:
    """Were ``poses`` (if given) handed out by ``fk`` (so its screws and residuals
    belong to them)?"""
    if poses is None:
        return True
    mine = fk.poses()
    return all(poses.get(b) is g for b, g in mine.items())


def _is_abelian(B: np.ndarray) -> bool:
    k = B.shape[0]
    for i in range(k):
        for j in range(i + 1, k):
            if np.any(to_float(lie.bracket(B[i], B[j])) != 0):
                return False
    return True
