"""Sweeps: where, along a path or over a grid, a mechanism meets its singularities.

>>> import mechsing
>>> r = mechsing.sweep("examples/slider_crank_slider_input.yaml", ["P=-3:3:0.01"])  # doctest: +SKIP
>>> [(p.kind, p.values, p.classes) for p in r.located]                                # doctest: +SKIP

:func:`sweep` varies one swept variable (a path) or two (a grid) in the file's units
(:class:`~mechsing.sweeps.spec.Vary`: ``"A=0:360:1"``, ``"C1[1]=0:0.5:0.01"``,
``"pose.x=-0.1:0.1:0.01"``), follows the mechanism along it from the ``from_config``
configuration on its assembly mode (:mod:`.path`), measures every sample in float
(:mod:`.measures`), locates the singularities between the samples (:mod:`.engine`),
classifies each at ``precision`` (:mod:`.classify`), and returns a
:class:`~.results.SweepResult` (:mod:`.run`).  This package only re-exports.

:class:`SweepRun` is the same sweep row by row, for a caller that writes rows as they
come (the command line streams its CSV and JSON that way, in bounded memory) or
distributes them (``workers``/``scheduler``: Dask, see :mod:`.distributed`).
"""

from mechsing.sweeps.permode import ModeSweeps, sweep_modes
from mechsing.sweeps.results import (
    LocatedSingularity,
    Locus,
    SweepResult,
    SweptVariable,
)
from mechsing.sweeps.run import SweepRun, sweep
from mechsing.sweeps.spec import Vary

__all__ = [
    "LocatedSingularity",
    "Locus",
    "ModeSweeps",
    "SweepResult",
    "SweepRun",
    "SweptVariable",
    "Vary",
    "sweep",
    "sweep_modes",
]
