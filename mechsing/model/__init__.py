"""The mechanism: reading and validating files, and the graph model.

Public API::

    from mechsing.model import load, loads
    mech = load("examples/fourbar.yaml")      # a Mechanism (or MechanismError)
    mech.joints, mech.loops, mech.legs, mech.configurations, mech.graph.tree_paths

The file is read by :mod:`mechsing.model.loader` (the top level), with
:mod:`mechsing.model.joints`, :mod:`mechsing.model.configurations` and the
reading context :mod:`mechsing.model.reading`.
See :mod:`mechsing.model.mechanism` for the data model,
:mod:`mechsing.model.graph` for loops, legs and the spanning tree,
:mod:`mechsing.model.expressions` for exact numbers and whitelisted
expressions, and :mod:`mechsing.model.schema` for the JSON Schema.
"""

from mechsing.errors import ExpressionError, MechanismError
from mechsing.model.expressions import parse_number
from mechsing.model.graph import (
    Leg,
    Loop,
    MechanismGraph,
    PathStep,
    build_graph,
    canonical_loops,
)
from mechsing.model.loader import load, loads
from mechsing.model.mechanism import (
    Configuration,
    Coupling,
    Displacement,
    InputRef,
    Joint,
    Mechanism,
    Output,
    OutputPose,
    Scene,
    Units,
)

__all__ = [
    "Configuration",
    "Coupling",
    "Displacement",
    "ExpressionError",
    "InputRef",
    "Joint",
    "Leg",
    "Loop",
    "Mechanism",
    "MechanismError",
    "MechanismGraph",
    "Output",
    "OutputPose",
    "PathStep",
    "Scene",
    "Units",
    "build_graph",
    "canonical_loops",
    "load",
    "loads",
    "parse_number",
]
