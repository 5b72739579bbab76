"""Every assembly mode of a configuration (``mechsing modes``, :func:`mechsing.modes`).

* :mod:`~mechsing.assembly.planar` -- the planar platform-pose formulation (legs as
  distance, point and line constraints on one body's pose);
* :mod:`~mechsing.assembly.exact` -- exact elimination to one polynomial and certified
  isolation of its real roots (built in);
* :mod:`~mechsing.assembly.spatial` -- platforms on U-P-S / S-P-S legs in Study
  coordinates, by homotopy continuation (Bertini 2, the ``modes`` extra);
* :mod:`~mechsing.assembly.certify` -- the Krawczyk test of each mode;
* :mod:`~mechsing.assembly.api` -- :func:`modes` and its result types;
* :mod:`~mechsing.assembly.render` -- text and Markdown;
* :mod:`~mechsing.assembly.schema` -- the JSON Schema of the document.
"""

from mechsing.assembly.api import Mode, ModesResult, modes

__all__ = ["Mode", "ModesResult", "modes"]
