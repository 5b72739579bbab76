"""Every assembly mode of a configuration (``mechsing modes``, :func:`mechsing.modes`).

A registry of formulations (:mod:`~mechsing.assembly.registry`), one module per problem,
each with ``applies(given)`` and ``find(given)``; what is given read once
(:mod:`~mechsing.assembly.given`); :mod:`~mechsing.assembly.api` only dispatches and
:mod:`~mechsing.assembly.result` classifies and reports:

* :mod:`~mechsing.assembly.planar_pose` -- a planar mechanism (in any plane) whose unknown
  part is one body on legs, by exact elimination;
* :mod:`~mechsing.assembly.platform` -- a six-leg platform in Study coordinates;
* :mod:`~mechsing.assembly.chains` -- six unknown joints in a chain: a single loop, a
  serial arm (:mod:`~mechsing.assembly.serial`);
* :mod:`~mechsing.assembly.general` -- any mechanism of R, P, C, U, S, T2 and T3 joints,
  each loop in its subgroup's coordinates; arms of fewer than six joints at a pose;

and what they share:

* :mod:`~mechsing.assembly.planar` -- the planar platform-pose formulation (legs as
  distance, point and line constraints on one body's pose);
* :mod:`~mechsing.assembly.exact` -- exact elimination to one polynomial and certified
  isolation of its real roots (built in);
* :mod:`~mechsing.assembly.spatial` -- platforms on U-P-S / S-P-S legs in Study
  coordinates, by homotopy continuation (Bertini 2, the ``modes`` extra);
* :mod:`~mechsing.assembly.reach` -- no real pose for legs hung far from the base,
  proven before tracking;
* :mod:`~mechsing.assembly.certify` -- the Krawczyk test of each mode;
* :mod:`~mechsing.assembly.api` -- :func:`modes` and its result types;
* :mod:`~mechsing.assembly.render` -- text and Markdown;
* :mod:`~mechsing.assembly.schema` -- the JSON Schema of the document.
"""

from mechsing.assembly.api import Mode, ModesResult, modes

__all__ = ["Mode", "ModesResult", "modes"]
