"""Kinematics of a mechanism: poses, current screws, chains, closure.

* :mod:`~mechsing.kinematics.model`: the kinematic model (reference screws of the
  joints in one precision mode, coordinates, closure residuals and Jacobian, updates
  on the group);
* :mod:`~mechsing.kinematics.jacobians`: the model's closure Jacobians (raw,
  commensurate, sparse) and the chords' closure chains under them;
* :mod:`~mechsing.kinematics.coordinates`: the model's coordinate updates on the group
  (update, difference, first-kind coordinates of a joint's element);
* :mod:`~mechsing.kinematics.protocol`: :class:`ClosureModel`, what closure and Newton
  ask of a model (a :class:`KinematicModel`, or a pose model,
  :mod:`~mechsing.kinematics.pose`);
* :mod:`~mechsing.kinematics.plans`: :class:`~.plans.ModelPlans`, what depends only on a
  model (its tree's order, chains, the singularity tests' plans), one object per model,
  made with it;
* :mod:`~mechsing.kinematics.forward`: the forward kinematics (product of exponentials):
  poses and current screws of one configuration or a batch (the analysis and the
  scanner), the serial fast Jacobian;
* :mod:`~mechsing.kinematics.batch_newton`: closure of many float configurations at
  once, by one batched Gauss-Newton on the group (the sweeps, the nearby samples);
* :mod:`~mechsing.kinematics.chains`: the coordinates a chain between two bodies
  crosses, with their signs (tree-path sign sums);
* :mod:`~mechsing.kinematics.newton`: Newton on the group;
* :mod:`~mechsing.kinematics.closure`: closure of named configurations (:class:`Closer`),
  from their given values (:mod:`~mechsing.kinematics.given`) by continuation
  (:mod:`~mechsing.kinematics.continuation`), polished at N digits in mp
  (:mod:`~mechsing.kinematics.polish`).
"""

from mechsing.errors import ClosureError, ConfigurationError, ExactDataError
from mechsing.kinematics.chains import Chain, path_chain, tree_chain
from mechsing.kinematics.closed import ClosedValue
from mechsing.kinematics.closure import ClosedConfiguration, Closer, solve_configuration
from mechsing.kinematics.model import JointKinematics, KinematicModel, axis_points
from mechsing.kinematics.newton import NewtonResult, newton_on_group
from mechsing.kinematics.protocol import ClosureModel

__all__ = [
    "Chain",
    "ClosedConfiguration",
    "ClosedValue",
    "ClosureModel",
    "Closer",
    "ClosureError",
    "ConfigurationError",
    "ExactDataError",
    "JointKinematics",
    "KinematicModel",
    "NewtonResult",
    "axis_points",
    "newton_on_group",
    "path_chain",
    "solve_configuration",
    "tree_chain",
]
