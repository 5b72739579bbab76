"""The tests' own, independent implementation of mechanism kinematics.

It owns what the tests compare mechsing against: SE(3) and screw algebra
(:mod:`tests.reference.se3`), the whitelisted file expressions
(:mod:`tests.reference.expressions`), joint bases, joint displacements, body
poses, cycles and closure residuals, the characteristic length, spatial joint
screws and a path tracker (:mod:`tests.reference.kinematics`), and reading /
writing mechanism files (:mod:`tests.reference.files`).  Bases, displacements
and lengths keep the number type they are given (float, mpmath or sympy), so
the multiprecision and exact checks use the same code as the float ones.
Everything is written from the product's conventions with numpy, scipy,
mpmath, sympy, networkx and yaml alone: nothing under this package imports
mechsing (tests/test_house.py walks its imports to check).
"""
