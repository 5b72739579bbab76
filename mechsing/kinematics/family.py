"""The family of a mechanism (or of some of its joints), decided once: from the subgroup
its joints' screws generate at the reference configuration (:func:`mechsing.subgroups.identify`).

* ``planar``: the planar motions G (normal ``n``): a four-bar, a slider-crank, a planar
  arm, in whatever plane it is drawn;
* ``spherical``: the rotations S about one point (a spherical four-bar, an agile eye);
* ``schoenflies``: X, rotations about one direction and every translation (a SCARA);
* ``translational``: T, the translations;
* ``spatial``: anything else (D, or a subgroup of another type).

Owns :class:`Family`, :func:`family` and :func:`pose_words` (the family in words, and how
to give a pose in it: what ``modes`` and the closure say of a pose outside it).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.model import Mechanism

__all__ = ["Family", "family", "pose_words"]

#: the family of each subgroup type the modes and drawings tell apart
_KINDS = {"G": "planar", "S": "spherical", "X": "schoenflies", "T": "translational"}


@dataclass(frozen=True)
class Family:
    """``kind`` (``planar``, ``spherical``, ``schoenflies``, ``translational``, ``spatial``),
    the subgroup's symbol and dimension (None when undecided), the subgroup itself, and
    its parameters as floats (``normal`` of G, ``point`` of S, ``axis`` of X)."""

    kind: str
    symbol: str | None
    dim: int | None
    subgroup: Any
    params: dict[str, np.ndarray]


def family(mech: Mechanism, joints: Sequence[str] | None = None) -> Family:
    """The family of ``mech``'s joints (``joints``: of these only), from the subgroup their
    reference screws generate (decided at ``auto`` precision: float, mp:50 when undecided)."""
    from mechsing.kinematics.model import KinematicModel
    from mechsing.numeric import to_float
    from mechsing.subgroups import identify

    km = KinematicModel(mech, "float")
    names = list(joints) if joints is not None else [j.name for j in mech.joints]
    screws = np.vstack([km.joint(n).basis for n in names]) if names else np.zeros((0, 6))
    ident = identify(screws, float(km.length_scale), "auto")
    if not ident.ok or ident.subgroup is None:
        return Family("spatial", None, None, None, {})
    sub = ident.subgroup
    params = {
        k: np.asarray(to_float(np.asarray(v, dtype=object)), dtype=float)
        for k, v in sub.params.items()
    }
    return Family(_KINDS.get(sub.symbol, "spatial"), sub.symbol, ident.dim, sub, params)


#: each family in words, with how a pose in it is given (:func:`pose_words`)
_POSE_WORDS = {
    "planar": "the planar motions G across the normal {normal}: give the pose by its "
    "position in the plane through the reference and its angle about the normal",
    "schoenflies": "the Schoenflies motions X (every translation, rotations about "
    "{axis}): give the pose by its position and its angle about that axis",
    "spherical": "the rotations S about the point {point}: give the pose by its "
    "rotation only (that point stays where it is)",
    "translational": "the translations T: give the pose by its position only",
}


def pose_words(fam: Family) -> str:
    """The subgroup of ``fam`` in words, with how a pose in it is given (``the planar
    motions G across the normal [0.0, 0.0, 1.0]: give the pose by its position in the
    plane through the reference and its angle about the normal``)."""
    text = _POSE_WORDS.get(fam.kind, "the subgroup {symbol} its joints generate")
    params = {
        k: [float(f"{round(float(x), 12):.6g}") + 0.0 for x in np.ravel(v)]
        for k, v in fam.params.items()
    }
    return text.format(symbol=fam.symbol, **params)
