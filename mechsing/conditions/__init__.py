"""Singularity conditions as factored formulas (``mechsing condition``).

:func:`condition` reads a mechanism file and returns a
:class:`~mechsing.conditions.results.ConditionResult`: the determinant of an
open chain's output Jacobian (or the gcd of its maximal minors), the input and
output conditions of a single loop with one input (and, where sympy can
eliminate the passive joints, the input values where they hold), or the
type I and type II conditions of a planar 3-RPR-type parallel robot in its
pose variables.  Joint variables are named by their joints and measured from
the pose drawn in the file; SI units and radians.  Parameters named in
``symbolic`` stay symbols.  Layer: analysis (it reads files through the model
layer and closes configurations through the kinematics layer).
"""

from mechsing.conditions.derive import condition
from mechsing.conditions.results import Condition, ConditionResult, Factor

__all__ = ["Condition", "ConditionResult", "Factor", "condition"]
