"""Couplings of joint coordinates in the closure system (a URDF ``<mimic>``).

Owns :class:`CouplingKinematics` and the closure block of a coupling.  A coupling
``q_f = m q_l + c`` of two one-coordinate joints (R, P, H: abelian, their coordinates
add under updates) is a closure block after the chords' loops, of the same form:

* its residual is the pure translation ``Delta = (e L / s_f) x`` with
  ``e = q_f - m q_l - c`` (SI, radians) and ``s_f`` = L when the follower's coordinate
  is a length, 1 when it is an angle: the identity exactly when the coupling holds, its
  size a length (:meth:`KinematicModel.residual_norm`: ``|e| L`` for an angle,
  ``|e|`` for a length), its logarithm ``(0, e L / s_f x)``;
* its Jacobian block is constant: the linear x row ``(dq_f - m dq_l) L / s_f``, the other
  five rows zero; commensurate (v / L, length columns times L) it is the row
  ``u_f - m (s_l / s_f) u_l`` of the commensurate rates, 1 on the follower.

So the stacked closure system (every Newton step, rank, nullity and kernel built block by
block, batched or sparse) takes each coupling as one more independent constraint: its
kernel is the joint rates that satisfy ``dq_f = m dq_l``, and each coupling lowers the
mobility by one.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.model import Coupling
from mechsing.numeric.backend import is_float64

#: a :class:`~mechsing.kinematics.model.KinematicModel` (which imports this module)
KinematicModel = Any

__all__ = [
    "CouplingKinematics",
    "coupling_block",
    "coupling_kinematics",
    "coupling_residuals",
    "coupling_rows",
    "coupling_violation",
    "couple_given",
    "expand_rates",
    "fold_columns",
    "impose_couplings",
]


@dataclass(frozen=True)
class CouplingKinematics:
    """One coupling in a model: the follower's and the leader's coordinate columns,
    ``multiplier`` and ``offset`` in the model's numbers (SI, radians), and whether each
    coordinate is a length."""

    coupling: Coupling
    follower: int
    leader: int
    multiplier: Any
    offset: Any
    follower_length: bool
    leader_length: bool


def coupling_kinematics(model: KinematicModel) -> tuple[CouplingKinematics, ...]:
    """The couplings of ``model.mech`` whose two joints the model holds (a coupling on a
    left-out branch was dropped with it)."""
    out = []
    for c in model.mech.couplings:
        f, ld = model.joint(c.joint), model.joint(c.leader)
        with model.precision.context():
            m, off = model.asarray([c.multiplier, c.offset])
        out.append(
            CouplingKinematics(
                c,
                f.columns.start,
                ld.columns.start,
                m,
                off,
                bool(f.length_coordinates[0]),
                bool(ld.length_coordinates[0]),
            )
        )
    return tuple(out)


def coupling_block(model: KinematicModel, frame: Any) -> np.ndarray:
    """The couplings' closure rows (6 * couplings, n): commensurate in ``frame`` (its
    numbers), or raw in the model's numbers when ``frame`` is None."""
    k = len(model.couplings)
    if frame is None:
        L = model.frame.L
        out = model.backend.zeros((6 * k, model.n))
        for i, ck in enumerate(model.couplings):
            s_f = L if ck.follower_length else 1
            out[6 * i + 3, ck.follower] = L / s_f
            out[6 * i + 3, ck.leader] = -ck.multiplier * L / s_f
        return out
    L = frame.L
    exact = not isinstance(L, float)
    out = np.zeros((6 * k, model.n), dtype=object if exact else float)
    if exact:
        out[...] = 0 * L
    for i, ck in enumerate(model.couplings):
        ratio = (L if ck.leader_length else 1) / (L if ck.follower_length else 1)
        m = ck.multiplier if exact else float(ck.multiplier)
        out[6 * i + 3, ck.follower] = 1 + 0 * L
        out[6 * i + 3, ck.leader] = -m * ratio
    return out


def coupling_violation(ck: CouplingKinematics, q: np.ndarray) -> Any:
    """``q_f - m q_l - c`` (SI, radians) at ``q`` (n,) or a batch (N, n)."""
    return q[..., ck.follower] - ck.multiplier * q[..., ck.leader] - ck.offset


def coupling_residuals(model: KinematicModel, q: np.ndarray) -> list[np.ndarray]:
    """Each coupling's closure residual at ``q``: the translation ``(e L / s_f) x``
    (4 x 4, or (N, 4, 4) for a float batch), in the numbers of ``q``."""
    out = []
    L = model.frame.L
    for ck in model.couplings:
        e = coupling_violation(ck, q)
        t = e * (L / (L if ck.follower_length else 1))
        if q.ndim == 2:
            D = np.broadcast_to(np.eye(4), (q.shape[0], 4, 4)).copy()
            D[:, 0, 3] = t
        else:
            D = model.backend.eye(4)
            D[0, 3] = t
        out.append(D)
    return out


def impose_couplings(model: KinematicModel, q: np.ndarray, held: set[int]) -> np.ndarray:
    """``q`` with every coupled coordinate not in ``held`` set to ``m q_l + c`` (a chain
    of couplings in its order: a follower that leads another is set first)."""
    out = np.array(q, copy=True)
    todo = [ck for ck in model.couplings if ck.follower not in held]
    for _ in range(len(todo)):
        for ck in todo:
            out[..., ck.follower] = ck.multiplier * out[..., ck.leader] + ck.offset
    return out


def fold_columns(
    model: KinematicModel, M: np.ndarray, columns: list[int]
) -> tuple[np.ndarray, list[int], list[tuple[int, int, Any]]]:
    """A chain's commensurate screw system ``M`` (..., rows, len(columns)) with each
    coupled follower's column folded into its leader's when both are in the chain: the
    leader's column becomes ``M_l + m (s_l / s_f) M_f`` (the chain's motion per unit
    leader rate, commensurate) and the follower's column is dropped.  Returns the folded
    matrix, the positions kept (in ``columns``) and, per dropped follower, (its position,
    its leader's position, the commensurate factor ``m s_l / s_f``) to expand a rate
    vector of the kept columns back (:func:`expand_rates`)."""
    pos = {c: i for i, c in enumerate(columns)}
    L = model.frame.L
    follows: list[tuple[int, int, Any]] = []
    out = M.copy() if model.couplings else M
    # a chain of couplings (a follower that leads another) folds from its far end
    for ck in reversed(model.couplings):
        if ck.follower in pos and ck.leader in pos:
            factor = (
                ck.multiplier * (L if ck.leader_length else 1) / (L if ck.follower_length else 1)
            )
            if is_float64(out):
                factor = float(factor)
            pf, pl = pos[ck.follower], pos[ck.leader]
            out[..., pl] = out[..., pl] + factor * out[..., pf]
            follows.append((pf, pl, factor))
    dropped = {pf for pf, _, _ in follows}
    kept = [i for i in range(len(columns)) if i not in dropped]
    return (out[..., kept] if dropped else out), kept, follows[::-1]


def expand_rates(
    x: np.ndarray, n: int, kept: list[int], follows: list[tuple[int, int, Any]]
) -> np.ndarray:
    """Commensurate rates of a folded chain's kept columns (:func:`fold_columns`) as
    rates of all its ``n`` columns: each dropped follower moves at factor x leader."""
    full = np.zeros(n)
    full[kept] = x
    for pf, pl, factor in follows:
        full[pf] = float(factor) * full[pl]
    return full


def couple_given(
    model: KinematicModel, target: np.ndarray, given: set[int], tolerance: Any, where: str
) -> tuple[np.ndarray, set[int]]:
    """A configuration's given coordinates completed by the couplings: a follower whose
    leader is given follows it (``m q_l + c``), a leader whose follower is given is
    ``(q_f - c) / m``; a coupling whose two joints are both given must hold, to
    ``tolerance`` (m: ``|e| L / s_f`` as its closure residual; exactly in exact mode),
    else a UserError (exit 2) naming both joints, their values and the coupling's line
    (``where``: the configuration, for the message)."""
    from mechsing.errors import UserError
    from mechsing.model.couplings import coupling_source, describe_coupling
    from mechsing.numeric import to_float
    from mechsing.numeric.backend import exact_is_zero

    out = np.array(target, copy=True)
    have = set(given)
    L = model.frame.L
    for _ in range(len(model.couplings)):
        for ck in model.couplings:
            f, ld = ck.follower in have, ck.leader in have
            if f and ld:
                continue
            if ld:
                out[ck.follower] = ck.multiplier * out[ck.leader] + ck.offset
                have.add(ck.follower)
            elif f and to_float(ck.multiplier) != 0:
                out[ck.leader] = (out[ck.follower] - ck.offset) / ck.multiplier
                have.add(ck.leader)
    for ck in model.couplings:
        if not (ck.follower in have and ck.leader in have):
            continue
        e = coupling_violation(ck, out)
        if model.backend.name == "exact":
            holds = exact_is_zero(e, model.length_scale) is True
        else:
            holds = abs(float(to_float(e * (L / (L if ck.follower_length else 1))))) <= tolerance
        if holds:
            continue
        c = ck.coupling
        unit = lambda x: "m" if x else "rad"  # noqa: E731
        raise UserError(
            f"{where}: joint {c.joint!r} = {float(to_float(out[ck.follower])):.6g} "
            f"{unit(ck.follower_length)} and joint {c.leader!r} = "
            f"{float(to_float(out[ck.leader])):.6g} {unit(ck.leader_length)} do not satisfy "
            f"their coupling {describe_coupling(c)} ({coupling_source(c)}; SI, radians): give "
            f"the value of {c.leader!r} only (the coupled joint follows it), or values that "
            "satisfy the coupling"
        )
    return out, have


def coupling_rows(model: KinematicModel, frame: Any) -> tuple[Any, Any]:
    """The couplings' commensurate rows (k, n) in a float ``frame`` (the linear x rows of
    their closure blocks) and an orthonormal basis (n, n - k) of the joint rates they
    allow; (None, None) without couplings."""
    if not model.couplings:
        return None, None
    R = np.asarray(model.coupling_block(frame)[3::6], dtype=float)
    Vt = np.linalg.svd(R, full_matrices=True)[2]
    return R, Vt[len(model.couplings) :].T.copy()
