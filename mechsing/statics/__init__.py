"""Kinetostatics: what a configuration costs in newtons and newton-metres.

At a configuration with inputs and an output, under a load (the wrench the environment
applies to the output body: the file's ``load`` or ``--load``): the actuator efforts
that hold it (:mod:`mechsing.statics.efforts`), the wrench each joint carries, the
largest effort per unit pure force and per unit pure couple on the output, and the
motion/force transmission indices (:mod:`mechsing.statics.transmission`).  Everything is
computed from the motion test's matrices (:mod:`mechsing.statics.matrices`), in float,
SI at the ground origin.  docs/kinetostatics.md is the user's page.
"""

from mechsing.statics.configuration import (
    Kinetostatics,
    kinetostatics,
    kinetostatics_at,
    load_of,
    with_kinetostatics,
)
from mechsing.statics.matrices import motion_matrices

__all__ = [
    "Kinetostatics",
    "kinetostatics",
    "kinetostatics_at",
    "load_of",
    "motion_matrices",
    "with_kinetostatics",
]
