"""U, C and S joints as their one-dof factors, for the symbolic conditions.

The symbolic kinematics (:mod:`mechsing.conditions.symbolic`) has one coordinate per joint
(R, P, H).  A joint of several is written as the one-dof joints it is made of, through
hidden bodies, each named as the command line names the coordinate (``U1[0]``):

* ``U``: its two revolutes, the first (``[0]``) about ``axes[0]`` fixed in the first body,
  the second about ``axes[1]`` (the file's convention: the same motion, the same values);
* ``C``: a revolute about its axis (``[0]``, the angle) and a prismatic along it (``[1]``,
  the slide); they commute, so the values are the joint's;
* ``S``: three revolutes about x, y and z of the ground through its centre
  (``[0]``, ``[1]``, ``[2]``: the angles of ``Rx Ry Rz``).  Unlike U and C this is not the
  joint's own coordinates (a rotation vector), and it has a singularity of its own where
  the middle axis has turned a right angle (cos of ``[1]`` is zero: the first and last
  axes coincide); a factor that is only that is the parametrisation's, not the
  mechanism's, and is left out with a note.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import sympy

from mechsing.model import Mechanism, build_graph
from mechsing.model.mechanism import InputRef, Joint

__all__ = ["SPLIT_TYPES", "gimbal_factor", "split_joints", "split_values"]

#: the joint types written as one-dof joints
SPLIT_TYPES = ("U", "C", "S")
_GROUND_AXES = ((1, 0, 0), (0, 1, 0), (0, 0, 1))


def _label(mech: Mechanism, name: str, index: int) -> str:
    return mech.coordinate_label(name, index)


def split_joints(mech: Mechanism) -> tuple[Mechanism, list[str]]:
    """``mech`` with its U, C and S joints written as R and P joints (and a note for each
    kind split); ``mech`` itself when it has none."""
    if not any(j.type in SPLIT_TYPES for j in mech.joints):
        return mech, []
    bodies = list(mech.bodies)
    joints: list[Joint] = []
    split: dict[str, list[str]] = {}
    for j in mech.joints:
        if j.type not in SPLIT_TYPES:
            joints.append(j)
            continue
        a, b = j.between
        point = j.params["point"]
        if j.type == "U":
            parts = [("R", {"axis": ax, "point": point}) for ax in j.params["axes"]]
        elif j.type == "C":
            axis = j.params["axis"]
            parts = [("R", {"axis": axis, "point": point}), ("P", {"axis": axis})]
        else:
            parts = [("R", {"axis": ax, "point": point}) for ax in _GROUND_AXES]
        names = [_label(mech, j.name, i) for i in range(len(parts))]
        chain = [a, *(f"{j.name}.part{i}" for i in range(1, len(parts))), b]
        bodies.extend(chain[1:-1])
        for i, ((jtype, params), name) in enumerate(zip(parts, names, strict=True)):
            units = ("m",) if jtype == "P" else ("rad",)
            joints.append(Joint(name, jtype, (chain[i], chain[i + 1]), params, j.line, 1, units))
        split.setdefault(j.type, []).append(f"{j.name} ({', '.join(names)})")
    notes = []
    words = {
        "U": "its two revolutes",
        "C": "a revolute and a prismatic joint along its axis",
        "S": "three revolutes about x, y and z through its centre (the angles of Rx Ry Rz)",
    }
    for jtype, which in split.items():
        notes.append(
            f"{jtype} joint{'s' if len(which) > 1 else ''} {', '.join(which)} written as "
            f"{words[jtype]}"
        )
    inputs = []
    for ref in mech.inputs:
        j = mech.joint(ref.joint)
        if j.type not in SPLIT_TYPES:
            inputs.append(ref)
            continue
        which = range(j.dof) if ref.index is None else (ref.index,)
        inputs.extend(InputRef(_label(mech, j.name, i)) for i in which)
    graph = build_graph(bodies, mech.ground, joints)
    out = dataclasses.replace(
        mech, bodies=tuple(bodies), joints=tuple(joints), inputs=tuple(inputs), graph=graph
    )
    return out, notes


def split_values(mech: Mechanism, values: dict[str, Any]) -> dict[str, float]:
    """The values of the split coordinates (``U1[0]`` ...) of the joint values ``values``
    (joint name -> its coordinates) of ``mech`` (the mechanism before the split)."""
    out: dict[str, float] = {}
    for j in mech.joints:
        if j.name not in values:
            continue
        v = [float(x) for x in values[j.name]]
        if j.type not in SPLIT_TYPES:
            out[j.name] = v[0]
            continue
        if j.type == "S":
            v = list(_xyz_angles(np.array(v)))
        for i, x in enumerate(v):
            out[_label(mech, j.name, i)] = x
    return out


def _xyz_angles(w: np.ndarray) -> tuple[float, float, float]:
    """The angles (a, b, c) of ``Rx(a) Ry(b) Rz(c)`` equal to the rotation of vector ``w``."""
    theta = float(np.linalg.norm(w))
    K = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    if theta == 0:
        R = np.eye(3)
    else:
        K = K / theta
        R = np.eye(3) + math.sin(theta) * K + (1 - math.cos(theta)) * K @ K
    b = math.asin(max(-1.0, min(1.0, R[0, 2])))
    a = math.atan2(-R[1, 2], R[2, 2])
    c = math.atan2(-R[0, 1], R[0, 0])
    return a, b, c


def gimbal_factor(mech: Mechanism, expression: Any) -> bool:
    """Whether a factor is only the three-revolute parametrisation's own singularity: a
    function of one split S joint's middle angle alone that vanishes at a right angle."""
    names = {str(s) for s in sympy.sympify(expression).free_symbols}
    for j in mech.joints:
        if j.type != "S":
            continue
        middle = _label(mech, j.name, 1)
        if names == {middle}:
            at_right_angle = sympy.sympify(expression).subs(
                sympy.Symbol(middle, real=True), sympy.pi / 2
            )
            return sympy.simplify(at_right_angle) == 0
    return False
