"""The closure Jacobians of a kinematic model and the chord machinery under them.

Owns the linearised closure of a :class:`~mechsing.kinematics.model.KinematicModel`:
each chord's closure chain (its signs over the coordinates, built once and kept on the
model), the chords' rows from the current screws, the closure Jacobian (raw, commensurate
in a frame, or sparse for big float models, with the couplings' blocks after the
chords'), and the logarithms of the chord residuals.  The model's methods of the same
names call these functions; the caches stay attributes of the model.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechsing import lie
from mechsing.kinematics.chains import tree_chain
from mechsing.numeric import blocks
from mechsing.numeric.backend import holds_objects

if TYPE_CHECKING:
    from scipy.sparse import csc_matrix

#: a :class:`~mechsing.kinematics.model.KinematicModel` (which imports this module)
KinematicModel = Any

__all__ = [
    "chord_signs",
    "chord_twists",
    "closure_jacobian",
    "scaled_closure_jacobian",
    "sparse_closure",
    "sparse_closure_jacobian",
]


def closure_jacobian(
    model: KinematicModel, q: np.ndarray, screws: np.ndarray | None = None
) -> np.ndarray:
    """Linearised closure: (6 * blocks, n); row block j is ``screws(j) + V_a - V_b``
    with ``V_x`` the tree velocity of body x, then each coupling's block.  A float
    batch of configurations (N, n) gives (N, 6 * blocks, n)."""
    S = model.current_screws(q) if screws is None else screws
    J = _chord_jacobian(model, S)
    if not model.couplings:
        return J
    C = model.coupling_block(None)
    if J.ndim == 3:
        C = np.broadcast_to(C, (J.shape[0],) + C.shape)
    return np.concatenate([J, C], axis=-2)


def _chord_jacobian(model: KinematicModel, S: np.ndarray) -> np.ndarray:
    """The chords' rows of :func:`closure_jacobian` from the current screws."""
    bk = model.backend
    signs = chord_signs(model)
    if not signs:
        return bk.zeros(S.shape[:-2] + (0, model.n))
    if S.ndim == 3 and not holds_objects(S):
        # a float batch: the same products, configuration by configuration
        J = np.stack(signs)[None, :, None, :] * S[:, None, :, :]
        return J.reshape(S.shape[0], -1, model.n)
    if S.ndim == 2 and not holds_objects(S):
        # one float configuration: one broadcast product (the same products)
        return (np.stack(signs)[:, None, :] * S[None, :, :]).reshape(-1, model.n)
    rows = [S * coef[None, :] for coef in signs]
    return np.concatenate(rows, axis=0)


def scaled_closure_jacobian(
    model: KinematicModel, q: np.ndarray, frame: Any, screws: np.ndarray | None = None
) -> np.ndarray:
    """``frame.blocks(closure_jacobian(q))``: the screws are made commensurate once and
    then signed per chord (the signs are -1, 0 or 1, so the numbers are the same)."""
    S = model.current_screws(q) if screws is None else screws
    signs = chord_signs(model)
    if not signs or S.ndim != 2 or holds_objects(S):
        J = frame.blocks(_chord_jacobian(model, S))
    else:
        Ss = frame.blocks(np.asarray(S, dtype=float))
        J = (np.stack(signs)[:, None, :] * Ss[None, :, :]).reshape(-1, model.n)
    if not model.couplings:
        return J
    return np.concatenate([J, model.coupling_block(frame)], axis=0)


def sparse_closure(model: KinematicModel) -> bool:
    """Whether the float closure Jacobian is big enough to be built and solved sparse
    (:func:`sparse_closure_jacobian`, block by block): a float model whose closure
    matrix is not factorised whole (:func:`mechsing.numeric.blocks.dense`)."""
    return model.backend.name == "float" and not blocks.dense(6 * model.blocks * model.n)


def sparse_closure_jacobian(
    model: KinematicModel, q: np.ndarray, frame: Any, screws: np.ndarray | None = None
) -> csc_matrix:
    """:func:`scaled_closure_jacobian` of one float configuration as a sparse matrix
    (the same numbers): row block j holds the commensurate screws of chord j's chain
    times their signs, and only the coordinates the chain crosses are stored, so
    building it is linear in the loops' lengths, not loops x coordinates."""
    from scipy.sparse import csc_matrix  # big models only: not at every start

    S = model.current_screws(q) if screws is None else screws
    chord, col, sign = _chord_entries(model)
    Ss = frame.blocks(np.asarray(S, dtype=float))
    vals = sign[:, None] * Ss[:, col].T
    rows = 6 * chord[:, None] + np.arange(6)
    cols = np.broadcast_to(col[:, None], vals.shape)
    v, r, c = vals.ravel(), rows.ravel(), cols.ravel()
    if model.couplings:
        C = model.coupling_block(frame)
        cr, cc = np.nonzero(C)
        v = np.concatenate([v, np.asarray(C[cr, cc], dtype=float)])
        r = np.concatenate([r, 6 * len(model.chords) + cr])
        c = np.concatenate([c, cc])
    return csc_matrix((v, (r, c)), shape=(6 * model.blocks, model.n))


def _chord_entries(model: KinematicModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The non-zero chord signs (:func:`chord_signs`) as (chord, column, sign)
    arrays, chord by chord, columns ascending (built once, kept in the model's plans)."""
    if model.plans.chord_entries is None:
        signs = chord_signs(model)
        if signs:
            chord, col = np.nonzero(np.stack(signs))
            sign = np.stack(signs)[chord, col].astype(float)
        else:
            chord = col = np.zeros(0, dtype=np.intp)
            sign = np.zeros(0)
        model.plans.chord_entries = (chord, col, sign)
    return model.plans.chord_entries


def chord_signs(model: KinematicModel) -> list[np.ndarray]:
    """Each chord's closure chain (integers, n): the chord itself, then back through
    the tree from its body a to its body b (built once, kept in the model's plans)."""
    if model.plans.chord_signs is None:
        out = []
        for jk in model.chords:
            coef = tree_chain(model, jk.a, jk.b).signs.copy()
            coef[jk.columns] += 1
            out.append(coef)
        model.plans.chord_signs = out
    return model.plans.chord_signs


def chord_twists(model: KinematicModel, deltas: list[np.ndarray]) -> np.ndarray:
    """log of each chord residual, stacked (6 * n_chords,)."""
    if not deltas:
        return model.backend.zeros(0)
    if len(deltas) > 1 and all(not holds_objects(D) for D in deltas):
        return lie.log(np.stack(deltas)).reshape(-1)
    return np.concatenate([lie.log(D) for D in deltas])
