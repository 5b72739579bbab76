"""The Lie group D = SE(3), its Lie algebra of screws, SO(3) and related algebras.

Conventions, stated once for the whole package (DESIGN.md "Conventions"):

* twist ``xi = (omega, v)``, shape (..., 6), angular first (:data:`ANGULAR`,
  :data:`LINEAR`); ``v`` is the velocity of the body point at the ground origin;
* wrench ``(f, m)``: force, then moment about the ground origin; the power of a
  wrench on a twist is the Klein form ``f.v + m.w``;
* displacement ``g``, shape (..., 4, 4), ``x -> R x + p``;
* ``[x, y]`` = matrix commutator; ``Ad(R, p) = [[R, 0], [p^ R, R]]``.

All functions are batched over leading axes and run unchanged on float64
arrays, on object arrays of mpmath numbers (mp:N) and on object arrays of sympy
numbers (exact); see :mod:`mechsing.numeric`.
"""

from mechsing.lie._se3 import *  # noqa: F403
from mechsing.lie._se3 import __all__ as _se3_all
from mechsing.lie._so3 import log_so3, quaternion_parts, vee3

__all__ = [*_se3_all, "log_so3", "quaternion_parts", "vee3"]
