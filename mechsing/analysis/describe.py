"""What a report tells a person about a mechanism's structure and its output's motion.

Owns :class:`LegDescription` (a leg of a parallel mechanism: its joints in order from the
base, ``output.relative_to``, to the output body) with :func:`describe_legs`, and
:class:`OutputMotion` (the space of twists the output body can make at a configuration,
the subgroup type it spans, or "not a subgroup" with its dimension) with
:func:`output_motion`.

Conventions: twists are (omega, v) in SI at the ground origin (rad/s, m/s per unit rate),
the output body's twist relative to ``output.relative_to`` whether or not the output has a
point.  The output twist space at a configuration is ``T K``: the output map ``T`` (the
tree path from ``relative_to`` to the output body) applied to the joint rates ``K`` that
keep every loop closed (all rates for an open chain).  Its rank is decided at the
analysis precision, in the commensurate metric with the precision's two thresholds; the
span is a subgroup when the subgroup it generates (:func:`mechsing.subgroups.identify`)
has the span's dimension.  Exact mode works in the number field of the data: ``K`` the
closure matrix's exact kernel, ``T K`` its exact product, the rank decided exactly, the
span's exact basis (pivot columns) identified exactly (Lie closure by exact echelon
forms); where the data have no number field it decides at mp:50 from the exact data.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from mechsing.kinematics import KinematicModel
from mechsing.model import Mechanism
from mechsing.numeric import Margin, Precision, decide_rank, to_float
from mechsing.numeric.field import field_floats, field_product
from mechsing.numeric.lazy import sympy
from mechsing.numeric.linalg import spectral_norm, svd
from mechsing.screws import ClosureSystem
from mechsing.screws.readable import readable_basis
from mechsing.singularity.zfb import output_chain
from mechsing.subgroups import Subgroup, identify

__all__ = ["LegDescription", "OutputMotion", "PointMotion", "describe_legs", "output_motion"]

Floats = tuple[float, ...]


@dataclass(frozen=True)
class LegDescription:
    """Leg ``number`` (from 1, numbered by its first joint in file order, as findings name
    legs) between ``base`` and ``body``: ``joints`` on its path from the base to the
    output body in that order, ``other_joints`` the rest of the leg (joints of loops
    inside the leg, e.g. a parallelogram, file order), ``bodies`` its intermediate bodies
    (file order)."""

    number: int
    base: str
    body: str
    joints: tuple[str, ...]
    other_joints: tuple[str, ...] = ()
    bodies: tuple[str, ...] = ()


def describe_legs(mech: Mechanism) -> tuple[LegDescription, ...]:
    """The legs between ``output.relative_to`` and the output body, each with its joints
    from the base to the output (empty without an output, or with fewer than two legs:
    a mechanism with one leg is a chain, not a parallel mechanism)."""
    from mechsing.singularity.criteria import leg_path

    out = mech.output
    if out is None or len(mech.legs) < 2:
        return ()
    legs = []
    for i, leg in enumerate(mech.legs, start=1):
        path = tuple(j for j, _sign in leg_path(mech, leg, out.relative_to, out.body))
        rest = tuple(j for j in leg.joints if j not in path)
        legs.append(LegDescription(i, out.relative_to, out.body, path, rest, tuple(leg.bodies)))
    return tuple(legs)


@dataclass(frozen=True)
class PointMotion:
    """The velocities the output's point can have (an output with ``point``): its
    ``position`` (m, ground frame) at the configuration, ``dim`` of its velocity space
    (None: undecided), an orthonormal basis ``velocities`` (unit directions) and the
    rank decision's ``margin``."""

    position: Floats
    dim: int | None
    velocities: tuple[Floats, ...]
    margin: Margin


@dataclass(frozen=True)
class OutputMotion:
    """The twists the output body can make (relative to ``relative_to``) at
    ``configuration``.

    ``dim``: the dimension of the output twist space (None: undecided at this precision);
    ``subgroup``: the subgroup type it spans when it is one; ``is_subgroup``: whether the
    span is closed under the Lie bracket (None: undecided, or not identified: ``note``
    says why); ``twists``: an orthonormal (commensurate metric) basis of the span as SI
    twists (omega, v) at the ground origin; ``margin`` of the rank decision; ``precision``
    it was decided at; ``generated``: the subgroup the twists generate (the span's own
    subgroup, or the smallest one that holds a span that is not a subgroup: G for a
    five-bar's distal link, D for an arm at a singularity; None when not identified)."""

    configuration: str
    body: str
    relative_to: str
    dim: int | None
    subgroup: Subgroup | None
    is_subgroup: bool | None
    twists: tuple[Floats, ...]
    margin: Margin
    precision: str
    note: str | None = None
    generated: Subgroup | None = None
    #: the output point's velocities (None: the output has no point)
    point: PointMotion | None = None
    #: the identification's status when it gave no type (``undecided``,
    #: ``ill-conditioned``); None when it gave one or was not run
    status: str | None = None

    @property
    def instantaneous_screw(self) -> bool:
        """Is the span one twist (a one-degree-of-freedom output)?  Its subgroup (R, P or
        H) is then the output's instantaneous screw, the screw it turns about at this
        instant, and not a motion type: a motion type is a subgroup the output's motions
        stay in, and the screw moves as the mechanism does."""
        return self.dim == 1

    @property
    def undecided(self) -> bool:
        """Did the precision leave the motion open: the rank of the output twists, or the
        subgroup they generate (auto re-decides both at mp:50)?"""
        return self.dim is None or self.status == "undecided"

    @property
    def type(self) -> str | None:
        """The subgroup's symbol (``T`` with dimension 3 for a translational robot)."""
        return None if self.subgroup is None else self.subgroup.symbol

    @property
    def summary(self) -> str:
        """The twist space in a few words (the JSON ``summary``): ``T (dimension 3)`` or
        ``not a subgroup: dim 2`` (``R (dimension 1)``: one twist, the instantaneous
        screw)."""
        if self.dim is None:
            return "undecided"
        if self.is_subgroup and self.subgroup is not None:
            return f"{self.subgroup.symbol} (dimension {self.dim})"
        if self.is_subgroup is False:
            return f"not a subgroup: dim {self.dim}"
        return f"dim {self.dim} ({self.note or 'type not identified'})"


def _mode(model: KinematicModel) -> Precision:
    prec: Precision = model.precision
    # policy: exact mode decides a rank of a product with a kernel at mp:50 from the exact
    # data when they have no number field (see _exact_kernel)
    return Precision("mp", 50) if prec.mode == "exact" else prec


def _exact_kernel(model: KinematicModel, cs: ClosureSystem) -> np.ndarray | None:
    """Exact mode: the closure matrix's exact kernel basis (columns, sympy numbers; the
    identity without loops), or None (not exact mode, or no exact basis)."""
    if model.precision.mode != "exact":
        return None
    n = cs.matrix.shape[1]
    if cs.matrix.shape[0] == 0:
        eye = np.empty((n, n), dtype=object)
        for i in range(n):
            for j in range(n):
                eye[i, j] = sympy.S.One if i == j else sympy.S.Zero
        return eye
    return cs.rank.exact_null_space


def _exact_span(
    model: KinematicModel, cs: ClosureSystem, A: Any, Z: np.ndarray
) -> tuple[Any, np.ndarray] | None:
    """The exact product ``A Z`` (A exact, Z the exact kernel), its exact rank decision
    (with its exact range basis), and an orthonormal float basis of its span (columns,
    in the order of the left singular vectors of ``A N``, N the kernel's orthonormal
    basis, as the numerical modes give them); None when the product has no number field."""
    # without loops the kernel is the identity: A itself
    AZ = field_product(A, Z) if cs.matrix.shape[0] else np.asarray(A, dtype=object)
    if AZ is None:
        return None
    dec = decide_rank(AZ, model.precision, model.length_scale, want_spaces=True)
    r = dec.rank
    if r == 0:
        return dec, np.zeros((AZ.shape[0], 0))
    N = cs.rank.null_space if cs.matrix.shape[0] else np.eye(cs.matrix.shape[1])
    Af = field_floats(A)
    if Af is None:
        Af = np.asarray(to_float(A), dtype=float)
    # the exact span's orthonormal float basis (dec.range_space: of its pivot columns),
    # rotated to the singular vectors of A N
    Y = dec.range_space
    u, _s, _vt = svd(Y.T @ (Af @ N))
    return dec, Y @ u


def output_motion(
    mech: Mechanism, model: KinematicModel, q: Any, cs: ClosureSystem, configuration: str
) -> OutputMotion | None:
    """The output twist space at the closed configuration ``q`` (``cs``: the closure
    system there; None without an output), and its point's velocity space when the
    output has a point."""
    if mech.output is None:
        return None
    Z = _exact_kernel(model, cs)
    if Z is not None:
        motion = _exact_output_motion(mech, model, q, cs, configuration, Z)
        if motion is not None:
            if mech.output.point is None:
                return motion
            point = _exact_point_motion(mech, model, q, cs, Z)
            if point is not None:
                return replace(motion, point=point)
    prec = _mode(model)
    with model.precision.context():
        A = cs.matrix
    with prec.context():
        A = prec.asarray(A)
        if A.shape[0] and prec.mode == "float" and cs.rank.precision == "float":
            # the joint rates that keep every loop closed: in float, the closure system's
            # own decision already holds them (the same decision of the same matrix)
            N = cs.rank.null_space
        elif A.shape[0]:
            N = decide_rank(A, prec, model.length_scale, want_spaces=True, native_spaces=True)
            N = N.null_space
        else:
            N = prec.backend.eye(A.shape[1])
    motion = _output_motion(mech, model, q, cs, configuration, N)
    if mech.output.point is None:
        return motion
    return replace(motion, point=_point_motion(mech, model, q, cs, N))


def _point_motion(
    mech: Mechanism, model: KinematicModel, q: Any, cs: ClosureSystem, N: Any
) -> PointMotion:
    """The velocity space of the output point over the closure's kernel ``N``."""
    prec = _mode(model)
    L = model.length_scale
    V, x = output_chain(mech, model, q, cs, True)
    with prec.context():
        V = prec.asarray(V)
        dec = decide_rank(
            V @ N, prec, L, want_spaces=True, reference=spectral_norm(V), native_spaces=True
        )
        r = dec.rank
        basis = [] if r is None else [dec.range_space[:, k] for k in range(r)]
        vel = tuple(
            tuple(float(c) + 0.0 for c in np.asarray(to_float(b), dtype=float)) for b in basis
        )
    pos = tuple(float(c) + 0.0 for c in np.asarray(to_float(x), dtype=float))
    return PointMotion(pos, r, vel, dec.margin)


def _exact_point_motion(
    mech: Mechanism, model: KinematicModel, q: Any, cs: ClosureSystem, Z: np.ndarray
) -> PointMotion | None:
    """:func:`_point_motion` in exact mode: the rank of ``V K`` exactly, in the number
    field of the data (None: no field)."""
    V, x = output_chain(mech, model, q, cs, True)
    span = _exact_span(model, cs, V, Z)
    if span is None:
        return None
    dec, basis = span
    vel = tuple(tuple(float(c) + 0.0 for c in basis[:, k]) for k in range(basis.shape[1]))
    pos = tuple(float(c) + 0.0 for c in np.asarray(to_float(x), dtype=float))
    return PointMotion(pos, dec.rank, vel, dec.margin)


def _exact_output_motion(
    mech: Mechanism,
    model: KinematicModel,
    q: Any,
    cs: ClosureSystem,
    configuration: str,
    Z: np.ndarray,
) -> OutputMotion | None:
    """:func:`_output_motion` in exact mode: ``T K`` and its rank exactly, its span's
    exact twists identified exactly (None: the data have no number field)."""
    T, _ = output_chain(mech, model, q, cs, False)
    span = _exact_span(model, cs, T, Z)
    if span is None:
        return None
    dec, basis = span
    fr = model.frame
    r = dec.rank
    si = [model.frame.as_float().twist_back(basis[:, k]) for k in range(r)]
    with model.precision.context():
        E = dec.exact_range_space
        # the span's exact twists in SI at the ground origin: v_0 = L v_c + c x omega
        X = np.array([fr.twist_back(E[:, k]) for k in range(r)], dtype=object).reshape(r, 6)
    return _motion_of_span(mech, model, configuration, dec, si, X, model.precision, fr.c)


def _output_motion(
    mech: Mechanism, model: KinematicModel, q: Any, cs: ClosureSystem, configuration: str, N: Any
) -> OutputMotion:
    out = mech.output
    prec = _mode(model)
    L = model.length_scale
    T, _ = output_chain(mech, model, q, cs, False)
    with prec.context():
        T = prec.asarray(T)
        TN = T @ N
        dec = decide_rank(
            TN, prec, L, want_spaces=True, reference=spectral_norm(T), native_spaces=True
        )
        r = dec.rank
        fr = model.frame.as_float()
        if r is None:
            return OutputMotion(
                configuration,
                out.body,
                out.relative_to,
                None,
                None,
                None,
                (),
                dec.margin,
                str(prec),
                note="the rank of the output twists lies between the two thresholds",
            )
        basis = dec.range_space[:, :r] if r else prec.backend.zeros((6, 0))
        si = [fr.twist_back(np.asarray(to_float(basis[:, k]), dtype=float)) for k in range(r)]
        if prec.mode == "mp":
            # the N-digit twists, for the identification at N digits
            c = prec.asarray(fr.c_float)
            native = []
            for k in range(r):
                w, v = basis[0:3, k], basis[3:6, k] * model.length_scale
                native.append(np.concatenate([w, v + np.cross(c, w)]))
            X = np.array(native, dtype=object).reshape(r, 6)
        else:
            X = np.array(si, dtype=float).reshape(r, 6)
    # the mechanism's centroid: identify's default centre (the mean axis point of the
    # rotating screws) is thrown far off by a translation with a rounding-level rotation
    centre = prec.asarray(np.asarray(fr.c_float, dtype=float)) if prec.mode == "mp" else fr.c_float
    return _motion_of_span(mech, model, configuration, dec, si, X, prec, centre)


def _motion_of_span(
    mech: Mechanism,
    model: KinematicModel,
    configuration: str,
    dec: Any,
    si: list[Any],
    X: np.ndarray,
    prec: Precision,
    centre: Any,
) -> OutputMotion:
    """The output motion of a decided span of rank ``dec.rank``: its SI ``si`` twists
    (orthonormal, float) and ``X`` (SI twists in ``prec``'s numbers) identified about
    ``centre``."""
    out = mech.output
    L = model.length_scale
    r = dec.rank
    # the basis shown: rotations in echelon form with their axes as near the origin as the
    # span's translations allow, then those (the span itself is what the numbers decided)
    shown = readable_basis(np.array(si, dtype=float).reshape(-1, 6), float(to_float(L)))
    twists = tuple(tuple(float(x) + 0.0 for x in t) for t in shown)
    if r == 0:
        return OutputMotion(
            configuration,
            out.body,
            out.relative_to,
            0,
            None,
            True,
            (),
            dec.margin,
            str(prec),
            note="the output cannot move",
        )
    if r == 6:  # the twists span se(3): all displacements, nothing to identify
        return OutputMotion(
            configuration,
            out.body,
            out.relative_to,
            6,
            Subgroup("D"),
            True,
            twists,
            dec.margin,
            str(prec),
            generated=Subgroup("D"),
        )
    ident = identify(X, L, prec, centre=centre)
    if not ident.ok or ident.dim is None:
        return OutputMotion(
            configuration,
            out.body,
            out.relative_to,
            r,
            None,
            None,
            twists,
            dec.margin,
            str(prec),
            note=f"the subgroup the twists generate is {ident.status}",
            status=ident.status,
        )
    if ident.dim == r:
        return OutputMotion(
            configuration,
            out.body,
            out.relative_to,
            r,
            ident.subgroup,
            True,
            twists,
            dec.margin,
            str(prec),
            generated=ident.subgroup,
        )
    return OutputMotion(
        configuration,
        out.body,
        out.relative_to,
        r,
        None,
        False,
        twists,
        dec.margin,
        str(prec),
        note=f"the twists generate {ident.subgroup.symbol if ident.subgroup else '?'} "
        f"(dimension {ident.dim}), larger than their span",
        generated=ident.subgroup,
    )
