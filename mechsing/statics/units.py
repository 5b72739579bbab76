"""The largest actuator effort over unit pure forces and over unit pure couples.

A unit force ``f`` (|f| = 1 N) through the load point ``p`` is the wrench
``(f, p x f)``; a unit couple is ``(0, m)`` with |m| = 1 N m.  The efforts are linear in
the wrench (``tau = G w``, :class:`~mechsing.statics.efforts.EffortMap`), so the largest
|effort| of actuator i over unit forces is the norm of row i of ``G [I; hat(p)]``, and over
unit couples that of ``G [0; I]``.  The largest is taken per actuator kind (N for a
prismatic input, N m for a rotation), never mixing units.  At a Type II configuration the
largest effort over unit forces is unbounded when some force does power on an
uncontrolled output twist (and likewise for couples): it is then null.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.analysis.display import floor_for
from mechsing.numeric import Precision, decide_rank, floored
from mechsing.statics.efforts import EffortMap
from mechsing.statics.matrices import MotionMatrices

__all__ = ["UnitEfforts", "unit_efforts"]

_FLOAT = Precision("float")


def _hat(p: np.ndarray) -> np.ndarray:
    return np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]], dtype=float)


@dataclass(frozen=True)
class UnitEfforts:
    """``force`` / ``couple``: per effort unit ("N", "N m"), the largest |effort| per
    unit pure force (per newton) / unit pure couple (per newton-metre) and the input that
    takes it; None when unbounded."""

    force: dict[str, tuple[float, str] | None]
    couple: dict[str, tuple[float, str] | None]

    def to_json(self) -> dict[str, Any]:
        def one(d: dict[str, tuple[float, str] | None]) -> dict[str, Any]:
            return {
                k: (None if v is None else {"value": v[0], "input": v[1]}) for k, v in d.items()
            }

        return {"force": one(self.force), "couple": one(self.couple)}

    def text_lines(self, L: float = 1.0) -> list[str]:
        """Sentences; a value below float's display floor relative to the largest (per
        newton, a couple's times 1/L and a torque's times 1/L: commensurate) shows as 0."""
        out = []

        def comm(d: dict[str, tuple[float, str] | None], per_length: float) -> list[float]:
            return [
                v[0] * (L if unit == "N" else 1.0) * per_length
                for unit, v in d.items()
                if v is not None
            ]

        big = max([*comm(self.force, 1.0 / L), *comm(self.couple, 1.0)], default=0.0)
        rel = floor_for(Precision("float"), 1.0) * big
        for what, d, per, pl in (
            ("unit force", self.force, "N", 1.0 / L),
            ("unit couple", self.couple, "N m", 1.0),
        ):
            parts = []
            for unit, v in d.items():
                if v is None:
                    parts.append(f"unbounded for the {_INPUT_KIND[unit]} inputs ({unit})")
                else:
                    floor = rel / ((L if unit == "N" else 1.0) * pl)
                    parts.append(f"{floored(v[0], floor):.4g} {unit} per {per} ({v[1]})")
            if parts:
                out.append(f"largest effort over a {what} on the output: {', '.join(parts)}")
        return out


#: the inputs whose efforts are in a unit, by that unit (a force drives a slide)
_INPUT_KIND = {"N": "prismatic", "N m": "revolute"}


def unit_efforts(mm: MotionMatrices, emap: EffortMap, point: np.ndarray) -> UnitEfforts:
    """The largest efforts at ``mm``'s configuration over unit forces through ``point``
    (current position, SI) and over unit couples."""
    P_f = np.vstack([np.eye(3), _hat(np.asarray(point, dtype=float))])
    P_m = np.vstack([np.zeros((3, 3)), np.eye(3)])
    W_in = np.linalg.inv(np.column_stack([mm.frame.wrench_back(e) for e in np.eye(6)]))
    kinds = {"N": [i for i, ln in enumerate(mm.input_lengths) if ln]}
    kinds["N m"] = [i for i, ln in enumerate(mm.input_lengths) if not ln]
    kinds = {k: v for k, v in kinds.items() if v}

    def largest(P: np.ndarray) -> dict[str, tuple[float, str] | None]:
        bounded = True
        if emap.Tz_rows.size:
            powers = emap.Tz_rows @ (mm.T.T @ (W_in @ P))  # k x 3
            ref = float(np.linalg.norm(mm.T.T @ (W_in @ P), 2))
            d = decide_rank(powers, _FLOAT, mm.L, reference=max(ref, 1e-300))
            bounded = d.rank == 0
        out: dict[str, tuple[float, str] | None] = {}
        GP = emap.G @ P
        norms = np.linalg.norm(GP, axis=1)
        for unit, idx in kinds.items():
            if not bounded:
                out[unit] = None
                continue
            i = max(idx, key=lambda k: norms[k])
            out[unit] = (float(norms[i]), mm.inputs[i])
        return out

    return UnitEfforts(largest(P_f), largest(P_m))
