"""Every assembly mode of a configuration (``mechsing modes``).

* :mod:`~mechsing.modes.planar` -- the planar platform-pose formulation (legs as
  distance, point and line constraints on one body's pose);
* :mod:`~mechsing.modes.exact` -- exact elimination to one polynomial and certified
  isolation of its real roots;
* :mod:`~mechsing.modes.certify` -- the Krawczyk test of each mode;
* :mod:`~mechsing.modes.api` -- :func:`modes` and its result types;
* :mod:`~mechsing.modes.schema` -- the JSON Schema of the document.
"""

from mechsing.modes.api import Mode, ModesResult, modes

__all__ = ["Mode", "ModesResult", "modes"]
