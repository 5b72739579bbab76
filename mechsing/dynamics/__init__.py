"""Dynamics in the Lie form (docs/dynamics.md).

* :mod:`~mechsing.dynamics.rigid`: the rigid body -- its inertia as a map from twists to
  momenta (dual vectors), the coadjoint action, kinetic energy, the Newton-Euler law in a
  Galilean and in a moving frame (Chevallier & Lerbet, chapter 7);
* :mod:`~mechsing.dynamics.tree`: trees of bodies -- inverse dynamics (a recursive
  Newton-Euler on twists and wrenches of D), the mass matrix, the bias efforts, forward
  dynamics; float (batched), mp:N and exact (chapter 8);
* :mod:`~mechsing.dynamics.closed`: closed chains' inverse dynamics (the passive joints'
  rates and accelerations from the loop closure, the closure's rate by the Lie bracket,
  the loops' multipliers) and the Type II crossing condition;
* :mod:`~mechsing.dynamics.api`: :func:`dynamics`, the dynamics of a file's
  configurations (``mechsing dynamics``), and its result; :mod:`~mechsing.dynamics.schema`
  the schema of its JSON.

``mechsing.dynamics`` names both this package and the function :func:`dynamics` (the
public API): once the package is imported Python binds the name to the package, so the
package is callable and calling it calls :func:`dynamics` (as :mod:`mechsing.report`).
"""

from __future__ import annotations

import sys
import types
from typing import Any

__all__ = ["dynamics"]


def __getattr__(name: str) -> Any:
    if name == "dynamics":
        from mechsing.dynamics.api import dynamics

        return dynamics
    raise AttributeError(f"module 'mechsing.dynamics' has no attribute {name!r}")


class _CallablePackage(types.ModuleType):
    """This package, callable as :func:`dynamics` (see the module docstring)."""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        from mechsing.dynamics.api import dynamics

        return dynamics(*args, **kwargs)


sys.modules[__name__].__class__ = _CallablePackage
