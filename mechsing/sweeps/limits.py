"""Where a sweep leaves the file's joint ``limits``: per sample, and in the summary.

Owns :func:`limited_coordinates` (the coordinates of a mechanism that have limits),
:func:`outside` (which samples of a row are beyond each one's limits) and
:func:`limits_notes` (the summary, one note per coordinate left).  A revolute angle
(R, C, U) is inside its limits when some turn of it is (``q + 2 pi k`` in
``[lower, upper]``): a path that turns a crank past pi has not left limits of
``[-pi, pi]``.  SI units and radians, as the file's ``limits`` are read.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mechsing.model import Mechanism
from mechsing.sweeps.settings import SWEEP_LIMIT_RTOL

__all__ = ["LimitedCoordinate", "limited_coordinates", "limits_notes", "outside"]

#: joints whose angle coordinates are periodic (a turn more is the same pose)
_TURNING = ("R", "C", "U")


@dataclass(frozen=True)
class LimitedCoordinate:
    """A joint coordinate with limits: its name (``J2``, ``C1[1]``), its column among the
    mechanism's coordinates, its limits (SI, radians) and whether it is a turning angle."""

    name: str
    column: int
    lower: float
    upper: float
    periodic: bool
    #: the file's unit of the coordinate and its factor to SI (the notes speak the file's)
    file_unit: str = "rad"
    factor: float = 1.0


def limited_coordinates(mech: Mechanism) -> list[LimitedCoordinate]:
    """The coordinates of ``mech`` that have limits in the file, in coordinate order."""
    out = []
    for col, (jname, i) in enumerate(mech.coordinates()):
        if jname not in mech.limits:
            continue
        joint = mech.joint(jname)
        lo, hi = mech.limits[jname][i]
        name = mech.coordinate_label(jname, i)
        periodic = joint.type in _TURNING and joint.units[i] == "rad"
        angle = joint.units[i] == "rad"
        unit = mech.units.angle if angle else mech.units.length
        factor = float(mech.units.angle_factor if angle else mech.units.length_factor)
        out.append(LimitedCoordinate(name, col, lo, hi, periodic, unit, factor))
    return out


def outside(
    coords: list[LimitedCoordinate], Q: np.ndarray, reached: np.ndarray
) -> dict[str, np.ndarray]:
    """For each limited coordinate, the reached samples (rows of ``Q``, the joint
    coordinates) beyond its limits."""
    out = {}
    for c in coords:
        q = Q[:, c.column]
        slack = SWEEP_LIMIT_RTOL * (c.upper - c.lower)
        if c.periodic and c.upper - c.lower < 2 * math.pi:
            # the turn of q nearest above the lower limit (less the slack)
            low = c.lower - slack
            q = low + np.mod(q - low, 2 * math.pi)
        with np.errstate(invalid="ignore"):
            beyond = (q < c.lower - slack) | (q > c.upper + slack)
        out[c.name] = reached & beyond
    return out


def limits_notes(
    coords: list[LimitedCoordinate], beyond: dict[str, np.ndarray], reached: np.ndarray
) -> list[str]:
    """One note per coordinate the sweep leaves the limits of: at how many of the reached
    samples (each sample's JSON ``outside_limits`` and the CSV column name them)."""
    notes = []
    total = int(np.sum(reached))
    for c in coords:
        n = int(np.sum(beyond[c.name]))
        if n:
            notes.append(
                f"the sweep leaves the limits of {c.name} ([{c.lower / c.factor:.6g}, "
                f"{c.upper / c.factor:.6g}] {c.file_unit}) at {n} of its {total} reached samples (outside_limits in each "
                "sample)"
            )
    return notes
