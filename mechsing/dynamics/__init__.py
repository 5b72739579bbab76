"""Dynamics in the Lie form (docs/dynamics.md).

* :mod:`~mechsing.dynamics.rigid`: the rigid body -- its inertia as a map from twists to
  momenta (dual vectors), the coadjoint action, kinetic energy, the Newton-Euler law in a
  Galilean and in a moving frame (Chevallier & Lerbet, chapter 7);
* :mod:`~mechsing.dynamics.tree`: trees of bodies -- inverse dynamics (a recursive
  Newton-Euler on twists and wrenches of D), the mass matrix, the bias efforts, forward
  dynamics; float (batched), mp:N and exact (chapter 8).
"""
