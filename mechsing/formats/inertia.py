"""The links' inertia of a robot description, placed in the ground frame at the drawn pose.

Owns :class:`MassSpec` (one body's mass, centre of mass and inertia about it, as the
mechanism file's ``mass`` entry gives them: ground axes, the drawn pose) and
:func:`body_masses`, which places each link's inertial (given in the link's frame by URDF
``<inertial>`` and MJCF ``<inertial>``) in the ground frame and adds the links a rigid
joint merges into one body (the centre of the total mass, the inertias moved to it by the
parallel-axis theorem: Huygens-Steiner).  The checks of a rigid body's inertia are the
loader's (:func:`mechsing.numeric.inertia.inertia_problem`), asked here too so that the error
names the element and line of the file.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["LinkInertial", "MassSpec", "body_masses", "parallel_axis"]


@dataclass
class MassSpec:
    """A body's ``mass`` entry: kg, the centre of mass (m, ground frame, drawn pose) and
    the inertia about it (kg m^2, ground axes, 3x3)."""

    body: str
    kg: float
    centre: tuple[float, float, float]
    inertia: np.ndarray


@dataclass
class LinkInertial:
    """A link's inertial placed in the ground frame: the link, kg, the centre (m) and the
    inertia about it in ground axes."""

    link: str
    kg: float
    centre: np.ndarray
    inertia: np.ndarray


def placed(link: str, frame: np.ndarray, kg: float, local: np.ndarray) -> LinkInertial:
    """A link's inertial given in its inertial frame (``frame``: that frame in the ground
    at the drawn pose, 4x4; ``local``: the inertia about the centre in the frame's axes)."""
    R = frame[:3, :3]
    return LinkInertial(link, float(kg), frame[:3, 3].copy(), R @ local @ R.T)


def parallel_axis(kg: float, d: np.ndarray) -> np.ndarray:
    """The inertia a point mass ``kg`` at ``d`` from a point adds about it: m (|d|^2 1 - d d^T)."""
    return kg * (float(d @ d) * np.eye(3) - np.outer(d, d))


def body_masses(
    inertials: list[LinkInertial], body_of: dict[str, str], ground: str
) -> list[MassSpec]:
    """The bodies' mass entries from their links' inertials (``body_of``: each link's body);
    the ground's links and massless links are left out."""
    groups: dict[str, list[LinkInertial]] = {}
    for li in inertials:
        body = body_of[li.link]
        if body != ground and li.kg > 0:
            groups.setdefault(body, []).append(li)
    out = []
    for body, parts in groups.items():
        m = sum(p.kg for p in parts)
        c = sum(p.kg * p.centre for p in parts) / m
        inertia = sum(p.inertia + parallel_axis(p.kg, p.centre - c) for p in parts)
        out.append(
            MassSpec(body, m, (float(c[0]), float(c[1]), float(c[2])), (inertia + inertia.T) / 2)
        )
    return out
