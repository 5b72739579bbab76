"""The Lie group D = SE(3), its Lie algebra of screws, SO(3) and related algebras.

Conventions, stated once for the whole package (the README's "Conventions"):

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

# _float registers itself as the fast forms of the functions above; _rodrigues holds the
# joints' closed forms (mechsing.kinematics.forward registers them)
# (their float64 kernels and the joints' Rodrigues forms: mechsing.numeric.dispatch)
from mechsing.lie import _float, _rodrigues, cayley, dual, quaternion  # noqa: E402,F401
from mechsing.lie.cayley import *  # noqa: E402,F403
from mechsing.lie.cayley import __all__ as _cayley_all  # noqa: E402
from mechsing.lie.dual import *  # noqa: E402,F403
from mechsing.lie.dual import __all__ as _dual_all  # noqa: E402
from mechsing.lie.quaternion import *  # noqa: E402,F403
from mechsing.lie.quaternion import __all__ as _quat_all  # noqa: E402

__all__ += [*_cayley_all, *_dual_all, *_quat_all, "cayley", "dual", "quaternion"]
