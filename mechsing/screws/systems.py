"""Screw systems at a configuration: loops, the stacked closure system, mobility, and
the one builder of a chain's screw system (:func:`chain_matrix`: output, leg and
scanned chains).

"Model only what the scene requires" (Chevallier & Lerbet): each loop's
joint screws are expressed in reduced, orthonormal coordinates of the loop's
generated subalgebra h (a planar loop in its g, a spherical loop in its s), so
the loop matrix is ``dim h x n`` with no spurious zero rows, and its singular
values are those of the commensurate screws themselves.

Commensurate metric (the characteristic length L): screws are moved to
the centroid c of the joints' axis points, their v rows divided by L, and the
columns of length coordinates multiplied by L, before any rank decision; the maps
are the model's :class:`~mechsing.numeric.CommensurateFrame` (``model.frame``).
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.kinematics import KinematicModel
from mechsing.kinematics.protocol import ClosureModel
from mechsing.lie import ANGULAR, LINEAR
from mechsing.model import Loop, Mechanism
from mechsing.numeric import Precision, RankDecision, decide_rank, to_float
from mechsing.numeric.field import field_solve
from mechsing.numeric.lazy import sympy
from mechsing.numeric.linalg import orthonormal_columns
from mechsing.subgroups import Identification, Subgroup, generate

__all__ = [
    "ClosureSystem",
    "chain_matrix",
    "LoopSystem",
    "closure_system",
    "fixed_loop_basis",
    "grubler",
    "group_mobility",
    "loop_basis",
    "reduced_coordinates",
    "reference_loop_identification",
    "share_loop_identifications",
]


@dataclass
class LoopSystem:
    """One loop at a configuration.

    ``matrix``: the loop's closure rows in reduced orthonormal coordinates of
    its subalgebra, ``dim h x n`` (all coordinates of the mechanism as columns,
    zero outside the loop, signed by the loop's orientation); ``rank``: its
    decision (relative to h); ``subgroup``: the generated subgroup.
    """

    loop: Loop
    identification: Identification
    matrix: np.ndarray
    rank: RankDecision
    #: orthonormal commensurate basis (6 x dim h, float) of the loop's subalgebra
    basis_float: np.ndarray = field(default_factory=lambda: np.eye(6), repr=False)
    #: the commensurate basis rows (dim h x 6) of the subalgebra in the analysis
    #: backend, whose QR (:func:`loop_basis`) gives the reduced coordinates of
    #: ``matrix``; None when the subgroup is undecided (the 6 rows of se(3))
    basis_rows: np.ndarray | None = field(default=None, repr=False)

    @property
    def subgroup(self) -> Subgroup | None:
        return self.identification.subgroup

    @property
    def dim(self) -> int:
        return self.matrix.shape[0]


@dataclass
class ClosureSystem:
    """The stacked closure system of all loops at one configuration."""

    loops: list[LoopSystem]
    #: the loops' rows, then one row per coupling of joint values (the last
    #: ``couplings`` rows: ``dq_f - m dq_l``, commensurate)
    matrix: np.ndarray
    rank: RankDecision
    screws: np.ndarray = field(repr=False)
    #: the commensurate screws (``model.frame.screws``) the loop rows are built from
    scaled_screws: np.ndarray | None = field(default=None, repr=False)
    #: matrices the tests at this configuration share, built once by the first that
    #: asks (:func:`mechsing.singularity.zfb.output_chain`: the output chain's rows)
    shared: dict[tuple[str, bool], tuple[np.ndarray, np.ndarray | None]] = field(
        default_factory=dict, repr=False, compare=False
    )
    #: how many couplings of joint values the system's last rows are
    couplings: int = 0

    @property
    def nullity(self) -> int | None:
        r = self.rank.rank
        return None if r is None else self.matrix.shape[1] - r


def chain_matrix(
    model: ClosureModel,
    S: np.ndarray,
    columns: Sequence[int] | None,
    point: np.ndarray | None = None,
    signs: np.ndarray | None = None,
) -> np.ndarray:
    """The commensurate screw system of a chain: the one builder of output, leg and
    scanned chain matrices.

    ``S``: current screws (..., 6, n), one configuration or a batch, in any backend;
    ``columns``: the chain's coordinates in the matrix's column order (None: all n);
    ``signs``: (n,) integers (a :class:`~mechsing.kinematics.chains.Chain`'s), +1 or -1
    for a coordinate crossed forward or backward and 0 off the chain, so that the
    columns are relative twists of the chain's last body (None: the joints' own
    screws); ``point``: the current position (m) of a point of the last body, (..., 3),
    for a positioning task.  Returns the twists (..., 6, k) or the point's velocity
    rows ``v + omega x x`` (..., 3, k), commensurate (moved to the centroid, v / L,
    length columns times L), in the numbers of ``S``.
    """
    M = S if signs is None else S * signs  # integer signs: exact in every backend
    if columns is not None:
        M = M[..., list(columns)]
    fr = model.frame
    T = fr.screws(M, columns)
    if point is None:
        return T
    # velocity of the body point x: v + omega x x, from twists moved to the centroid:
    # v_x = v_c + omega x (x - c); in commensurate units divide by L
    w, vc = T[..., ANGULAR, :], T[..., LINEAR, :]
    d = fr.point(point)
    return vc + np.swapaxes(lie.cross(np.swapaxes(w, -1, -2), d[..., None, :]), -1, -2)


def reduced_coordinates(
    model: KinematicModel, basis_rows: np.ndarray, Ss: np.ndarray
) -> np.ndarray:
    """Coordinates of commensurate screws ``Ss`` (6 x n) in an orthonormal basis of
    the span of ``basis_rows`` (k x 6, commensurate): (k x n).

    float: numpy QR; mp: mpmath QR at the working precision; exact: the
    (non-orthonormal) basis itself, solved exactly (ranks are what matter there).
    """
    k = basis_rows.shape[0]
    if k == 0:
        return model.backend.zeros((0, Ss.shape[1]))
    name = model.backend.name
    if name in ("float", "mp"):
        with model.precision.context():
            return loop_basis(basis_rows).T @ Ss
    # each row divided by its largest entry (exactly): a translation row (0, u / L)
    # would otherwise carry 1/L into every coordinate, and the margin (a pivot)
    # would change with the unit of length
    rows = []
    for row in basis_rows.tolist():
        big = max(row, key=lambda x: abs(float(x)))
        rows.append([sympy.sympify(x) / abs(sympy.sympify(big)) for x in row])
    fast = field_solve(np.array(rows, dtype=object).T, Ss)
    if fast is not None:  # in the number field of the entries
        return fast
    B = sympy.Matrix(rows).T
    C = (B.T * B).inv() * B.T * sympy.Matrix(Ss.tolist())
    return np.array(C.applyfunc(sympy.simplify).tolist(), dtype=object)


def loop_basis(basis_rows: np.ndarray | None) -> np.ndarray:
    """Orthonormal commensurate basis (6 x k) of a loop's subalgebra from its basis
    rows (k x 6, float or mp; the identity of se(3) when None), by the same QR
    as the loop's reduced coordinates, in the rows' backend (call inside the
    precision's context at mp:N)."""
    if basis_rows is None:
        return np.eye(6)
    return orthonormal_columns(np.asarray(basis_rows).T)


#: the loop identifications decided for each mechanism (by its loops' joints), kept
#: beside it while it lives (not in it: a mechanism pickles without them)
_LOOP_IDENTIFICATIONS: weakref.WeakKeyDictionary[
    Mechanism, dict[tuple[str, ...], Identification]
] = weakref.WeakKeyDictionary()


def reference_loop_identification(model: KinematicModel, loop: Loop) -> Identification:
    """The subgroup generated by the loop's joints at the reference configuration.

    Decided once per loop and kind of model.  A float model (``float``, and auto's first
    pass) decides it from float screws, with the rank rule and margins of every other
    float decision; the other models, and a float model whose decision is undecided or
    ill-conditioned, decide it exactly from the file's values (falling back to ``auto``
    when the exact decision fails).  By the invariance lemma (the structure of the
    subgroups of D, item 7) the loop moves inside this subgroup carried by the pose of
    the loop's first body, at every configuration.  Kept on the mechanism (immutable; it
    depends on the file's values and the characteristic length alone): the analyses of
    one mechanism (a sweep's start and its located points) decide it once.
    """
    cache = _LOOP_IDENTIFICATIONS.setdefault(model.mech, {})
    in_float = model.backend.name == "float"
    key = (*loop.joints, "float" if in_float else "exact")
    if key in cache:
        return cache[key]

    def joint_subgroups(number: Callable[[Any], Any]) -> list[Subgroup]:
        subs: list[Subgroup] = []
        for name in loop.joints:
            j = model.mech.joint(name)
            if j.type == "U":
                a1, a2 = (number(a) for a in j.params["axes"])
                pt = number(j.params["point"])
                subs.append(Subgroup("R", axis=a1, point=pt))
                subs.append(Subgroup("R", axis=a2, point=pt))
            else:
                subs.append(Subgroup(j.type, {k: number(v) for k, v in j.params.items()}))
        return subs

    ident = None
    if in_float:
        subs = joint_subgroups(lambda v: to_float(np.asarray(v, dtype=object)))
        ident = generate(subs, length_scale=model.length_scale, precision="float")
        if not ident.ok:  # undecided in float: decided exactly below
            ident = None
    if ident is None:
        exact_key = (*loop.joints, "exact")
        ident = cache.get(exact_key)
        if ident is None:
            subs = joint_subgroups(lambda v: v)
            try:
                ident = generate(subs, length_scale=model.length_scale, precision="exact")
                if not ident.ok:
                    raise ValueError(ident.status)
            except (ValueError, TypeError, ZeroDivisionError):
                ident = generate(subs, length_scale=model.length_scale, precision="auto")
            cache[exact_key] = ident
    cache[key] = ident
    return ident


def share_loop_identifications(source: Mechanism, target: Mechanism) -> None:
    """``target`` (the same joints as ``source``, other configurations: a copy with
    configurations added) shares the loop identifications decided for ``source``."""
    _LOOP_IDENTIFICATIONS[target] = _LOOP_IDENTIFICATIONS.setdefault(source, {})


def _loop_subgroup(
    model: KinematicModel, loop: Loop, poses: dict[str, np.ndarray]
) -> Identification:
    """The loop's generated subgroup at this configuration (reference one, conjugated)."""
    ref = reference_loop_identification(model, loop)
    if not ref.ok or ref.subgroup is None:
        return ref
    g = poses[loop.bodies[0]]
    gf = to_float(g)
    # policy: a float model keeps the reference parameters of a loop at rest
    if model.backend.name == "float" and np.array_equal(gf, np.eye(4)):
        return ref  # the loop's first body is at rest: parameters stay exact
    if model.backend.name == "exact":
        # policy: exact mode keeps the exact subgroup; the numeric modes move its float
        # parameters (the loop's rows are rebuilt at the model's precision from them)
        moved = ref.subgroup.conjugate(g)
    else:
        with model.precision.context():
            moved = Subgroup(
                ref.subgroup.type, {k: to_float(v) for k, v in ref.subgroup.params.items()}
            ).conjugate(gf)
    return replace(ref, subgroup=moved)


def _loop_rows(
    model: KinematicModel, loop: Loop, ident: Identification, prec: Precision
) -> tuple[np.ndarray, np.ndarray]:
    """The loop's commensurate basis rows (in the model's numbers) and their orthonormal
    float basis (:func:`loop_basis`); a float model keeps those of a loop whose subgroup is
    its reference one (its first body at rest: the same at every configuration)."""
    key = (loop.joints, str(prec))
    kept = model._loop_rows.get(key)
    if kept is not None and kept[0] is ident:
        return kept[1], kept[2]
    B = ident.subgroup.basis(prec if prec.mode != "auto" else "float")
    with model.precision.context():
        Bb = model.asarray(B)
        Bs = model.frame.rows(Bb)
    Qf = loop_basis(to_float(Bs))
    if model.backend.name == "float" and ident is reference_loop_identification(model, loop):
        model._loop_rows[key] = (ident, Bs, Qf)
    return Bs, Qf


def fixed_loop_basis(model: KinematicModel, loop: Loop) -> np.ndarray | None:
    """The orthonormal commensurate basis (6 x dim h, float) of a float model's loop
    subalgebra h that serves every configuration: the loop's first body is the ground,
    so its subgroup is its reference one wherever the mechanism moves (as in
    :func:`closure_system`).  None where the rows cannot be reduced that way: the
    loop's first body moves (its subgroup is carried by its pose), its subgroup is
    undecided, or it is all of D (nothing to reduce)."""
    if loop.bodies[0] != model.mech.ground:
        return None
    ident = reference_loop_identification(model, loop)
    if not ident.ok or ident.subgroup is None or ident.dim is None or ident.dim >= 6:
        return None
    _, Qf = _loop_rows(model, loop, ident, model.precision)
    return np.asarray(Qf, dtype=float)


def closure_system(
    model: KinematicModel, q: np.ndarray, precision: Precision | None = None
) -> ClosureSystem:
    """Loop systems and the stacked closure system at ``q`` (closed)."""
    prec = precision or model.precision
    poses = model.poses(q)
    S = model.current_screws(q, poses)
    Ss = model.frame.screws(S)
    L = model.length_scale
    loops: list[LoopSystem] = []
    blocks = []
    for loop in model.mech.loops:
        ident = _loop_subgroup(model, loop, poses)
        cols = np.zeros(model.n, dtype=int)
        for name, sign in zip(loop.joints, loop.signs, strict=True):
            cols[model.joint(name).columns] = sign
        Sl = Ss * cols[None, :]
        if ident.ok and ident.subgroup is not None:
            Bs, Qf = _loop_rows(model, loop, ident, prec)
            if model.backend.name == "float" and Bs.shape[0]:
                R = Qf.T @ Sl  # reduced_coordinates: the same QR of the same rows
            else:
                R = reduced_coordinates(model, Bs, Sl)
        else:
            R = Sl  # undecided subgroup: the full 6 rows (reported as such)
            Bs = None
            Qf = np.eye(6)
        with model.precision.context():
            dec = decide_rank(R[:, cols != 0], prec, L)
        loops.append(LoopSystem(loop, ident, R, dec, Qf, Bs))
        blocks.append(R)
    if model.couplings:
        # each coupling's row dq_f - m dq_l = 0, commensurate: the linear x row of its
        # closure block (mechsing.kinematics.couplings), after the loops' rows
        with model.precision.context():
            blocks.append(model.coupling_block(model.frame)[3::6])
    if blocks:
        M = np.concatenate(blocks, axis=0)
    else:
        M = model.backend.zeros((0, model.n))
    with model.precision.context():
        dec = decide_rank(M, prec, L, want_spaces=True)
    return ClosureSystem(loops, M, dec, S, Ss, couplings=len(model.couplings))


def grubler(model: KinematicModel) -> int:
    """Spatial Grubler-Kutzbach (lambda = 6): 6 (bodies - 1 - joints) + sum of dof, minus
    one per coupling of joint values (each is one more constraint)."""
    mech = model.mech
    return 6 * (len(mech.bodies) - 1 - len(mech.joints)) + mech.dof - len(model.couplings)


def group_mobility(model: KinematicModel, loops: list[LoopSystem]) -> int | None:
    """Total joint dof minus the sum of the loops' generated-subgroup dimensions, minus one
    per coupling of joint values (wrong for exceptional and paradoxical linkages such as
    Sarrus and Bennett)."""
    dims = []
    for ls in loops:
        if ls.identification.dim is None:
            return None
        dims.append(ls.identification.dim)
    return model.mech.dof - sum(dims) - len(model.couplings)
