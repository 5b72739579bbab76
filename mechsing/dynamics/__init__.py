"""Dynamics in the Lie form (docs/dynamics.md).

* :mod:`~mechsing.dynamics.rigid`: the rigid body -- its inertia as a map from twists to
  momenta (dual vectors), the coadjoint action, kinetic energy, the Newton-Euler law in a
  Galilean and in a moving frame (Chevallier & Lerbet, chapter 7).
"""
