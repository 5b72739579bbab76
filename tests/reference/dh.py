"""Denavit-Hartenberg products and URDF texts written from DH tables, independently of mechsing.

Imports nothing from mechsing.  Tables are lists of rows ``(theta_offset, d, a, alpha)``
(radians, metres) for revolute joints.  Standard convention (Denavit-Hartenberg; Spong):
``T_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)``; modified (Craig):
``T_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)`` with a row holding
``(theta_offset_i, d_i, a_{i-1}, alpha_{i-1})``.  ``theta_i = q_i + theta_offset_i``.

Published tables (sources in each constant's comment).
"""

from __future__ import annotations

import math

import numpy as np

PI = math.pi

#: UR5, standard DH (Universal Robots, "DH parameters for calculations of kinematics and
#: dynamics", UR3/UR5/UR10 table)
UR5 = [
    (0.0, 0.089159, 0.0, PI / 2),
    (0.0, 0.0, -0.425, 0.0),
    (0.0, 0.0, -0.39225, 0.0),
    (0.0, 0.10915, 0.0, PI / 2),
    (0.0, 0.09465, 0.0, -PI / 2),
    (0.0, 0.0823, 0.0, 0.0),
]
#: PUMA 560, standard DH (P. Corke, "Robotics, Vision and Control", puma560 model after
#: Armstrong, Khatib and Burdick 1986): a2 = 0.4318, a3 = 0.0203, d3 = 0.15005, d4 = 0.4318
PUMA560 = [
    (0.0, 0.0, 0.0, PI / 2),
    (0.0, 0.0, 0.4318, 0.0),
    (0.0, 0.15005, 0.0203, -PI / 2),
    (0.0, 0.4318, 0.0, PI / 2),
    (0.0, 0.0, 0.0, -PI / 2),
    (0.0, 0.0, 0.0, 0.0),
]
#: KUKA LBR iiwa 14 R820, standard DH (KUKA data sheet link lengths 0.36, 0.42, 0.40, 0.126 m;
#: the DH table of e.g. Faria et al., "Position-based kinematics for 7-DoF serial manipulators",
#: 2018)
IIWA14 = [
    (0.0, 0.36, 0.0, -PI / 2),
    (0.0, 0.0, 0.0, PI / 2),
    (0.0, 0.42, 0.0, PI / 2),
    (0.0, 0.0, 0.0, -PI / 2),
    (0.0, 0.40, 0.0, -PI / 2),
    (0.0, 0.0, 0.0, PI / 2),
    (0.0, 0.126, 0.0, 0.0),
]
#: Franka Emika Panda, modified (Craig) DH (Franka Control Interface documentation, "Robot and
#: interface specifications"); rows (theta_offset, d_i, a_{i-1}, alpha_{i-1}); the flange adds
#: d = 0.107
PANDA = [
    (0.0, 0.333, 0.0, 0.0),
    (0.0, 0.0, 0.0, -PI / 2),
    (0.0, 0.316, 0.0, PI / 2),
    (0.0, 0.0, 0.0825, PI / 2),
    (0.0, 0.384, -0.0825, -PI / 2),
    (0.0, 0.0, 0.0, PI / 2),
    (0.0, 0.0, 0.088, PI / 2),
]
PANDA_FLANGE = 0.107


def _rz(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _rx(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _tr(x: float, y: float, z: float) -> np.ndarray:
    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t


def dh_product(rows: list, q: np.ndarray, convention: str = "standard", flange: float = 0.0):
    """The tool frame (4x4) of the table at joint values q (flange: a final Tz)."""
    t = np.eye(4)
    for (off, d, a, alpha), qi in zip(rows, q, strict=True):
        th = qi + off
        if convention == "standard":
            t = t @ _rz(th) @ _tr(0, 0, d) @ _tr(a, 0, 0) @ _rx(alpha)
        else:
            t = t @ _rx(alpha) @ _tr(a, 0, 0) @ _rz(th) @ _tr(0, 0, d)
    return t @ _tr(0, 0, flange)


def urdf_from_dh(
    name: str,
    rows: list,
    convention: str = "standard",
    flange: float = 0.0,
    limits: float | None = None,
) -> str:
    """A URDF text whose links are the DH frames (link_i = frame i; tool0 the tool frame).

    Standard: joint i turns link_{i-1}'s copy of frame i-1 about its z, and the fixed part
    ``Tz(d) Tx(a) Rx(alpha)`` of row i is the origin of the next joint (xyz = a 0 d,
    rpy = alpha 0 0).  Modified: joint i's origin is ``Rx(alpha) Tx(a)`` followed by
    ``Tz(d)`` (which commutes with the joint's Rz): xyz = (a, -d sin alpha, d cos alpha).
    Tables with a non-zero theta offset are not written (URDF's rpy would put the offset's
    Rz before the roll)."""
    assert all(row[0] == 0 for row in rows), "theta offsets are not written as URDF"

    out = ['<?xml version="1.0"?>', f'<robot name="{name}">', '  <link name="base_link"/>']
    n = len(rows)
    for i in range(n + 1):
        if i:
            out.append(f'  <link name="link{i}"/>')
    out.append('  <link name="tool0"/>')
    prev_fixed = (0.0, 0.0, 0.0, 0.0)  # the fixed part carried to the next joint: (d, a, alpha)
    for i, (_off, d, a, alpha) in enumerate(rows, start=1):
        if convention == "standard":
            pd, pa, palpha = prev_fixed[1:]
            xyz = (pa, 0.0, pd)
            rpy = (palpha, 0.0, 0.0)
            prev_fixed = (0.0, d, a, alpha)
        else:
            xyz = (a, -d * math.sin(alpha), d * math.cos(alpha))
            rpy = (alpha, 0.0, 0.0)
        lim = (
            f'    <limit lower="{-limits!r}" upper="{limits!r}" effort="1" velocity="1"/>\n'
            if limits
            else ""
        )
        parent = "base_link" if i == 1 else f"link{i - 1}"
        # a constant theta offset: a fixed joint turning about z before the moving joint
        out.append(
            f'  <joint name="joint{i}" type="revolute">\n'
            f'    <parent link="{parent}"/>\n    <child link="link{i}"/>\n'
            f'    <origin xyz="{xyz[0]!r} {xyz[1]!r} {xyz[2]!r}" '
            f'rpy="{rpy[0]!r} {rpy[1]!r} {rpy[2]!r}"/>\n'
            f'    <axis xyz="0 0 1"/>\n{lim}  </joint>'
        )
    if convention == "standard":
        _, d, a, alpha = prev_fixed
        xyz, rpy = (a, 0.0, d), (alpha, 0.0, 0.0)
    else:
        xyz, rpy = (0.0, 0.0, flange), (0.0, 0.0, 0.0)
    out.append(
        f'  <joint name="flange" type="fixed">\n    <parent link="link{n}"/>\n'
        f'    <child link="tool0"/>\n'
        f'    <origin xyz="{xyz[0]!r} {xyz[1]!r} {xyz[2]!r}" rpy="{rpy[0]!r} {rpy[1]!r} {rpy[2]!r}"/>\n'
        "  </joint>"
    )
    out.append("</robot>")
    return "\n".join(out) + "\n"
