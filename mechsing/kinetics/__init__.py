"""Dynamics in the Lie form (docs/dynamics.md).

* :mod:`~mechsing.kinetics.rigid`: the rigid body -- its inertia as a map from twists to
  momenta (dual vectors), the coadjoint action, kinetic energy, the Newton-Euler law in a
  Galilean and in a moving frame (Chevallier & Lerbet, chapter 7);
* :mod:`~mechsing.kinetics.tree`: trees of bodies -- inverse dynamics (a recursive
  Newton-Euler on twists and wrenches of D), the mass matrix, the bias efforts, forward
  dynamics; float (batched), mp:N and exact (chapter 8);
* :mod:`~mechsing.kinetics.closed`: closed chains' inverse dynamics (the passive joints'
  rates and accelerations from the loop closure, the closure's rate by the Lie bracket,
  the loops' multipliers) and the Type II crossing condition;
* :mod:`~mechsing.kinetics.api`: :func:`dynamics`, the dynamics of a file's
  configurations (``mechsing dynamics``), and its result; :mod:`~mechsing.kinetics.schema`
  the schema of its JSON.

The package is named ``kinetics`` so that ``mechsing.dynamics`` stays the function
:func:`~mechsing.kinetics.api.dynamics` (a package of the same name would rebind it when
imported).
"""

from mechsing.kinetics.api import dynamics

__all__ = ["dynamics"]
