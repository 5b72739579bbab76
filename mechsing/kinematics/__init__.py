"""Poses by product of exponentials, closure residuals, closure by continuation."""

from mechsing.kinematics.closure import (
    ClosedConfiguration,
    Closer,
    ClosureError,
    ConfigurationError,
    ExactDataError,
    solve_configuration,
)
from mechsing.kinematics.model import JointKinematics, KinematicModel, axis_points

__all__ = [
    "ClosedConfiguration",
    "Closer",
    "ClosureError",
    "ConfigurationError",
    "ExactDataError",
    "JointKinematics",
    "KinematicModel",
    "axis_points",
    "solve_configuration",
]
