"""Screw systems at a configuration: loops, the stacked closure system, mobility, and
the one builder of a chain's screw system (:func:`chain_matrix`: output, leg and
scanned chains) are :mod:`mechsing.screws.systems`'; the generic mobility (the
nullity at nearby regular samples) :mod:`mechsing.screws.mobility`'; screws written
to be read :mod:`mechsing.screws.readable`'.
"""

from mechsing.screws.systems import (
    ClosureSystem,
    LoopSystem,
    chain_matrix,
    closure_system,
    fixed_loop_basis,
    group_mobility,
    grubler,
    loop_basis,
    reduced_coordinates,
    reference_loop_identification,
    share_loop_identifications,
)

__all__ = [
    "ClosureSystem",
    "chain_matrix",
    "LoopSystem",
    "closure_system",
    "fixed_loop_basis",
    "grubler",
    "group_mobility",
    "loop_basis",
    "reduced_coordinates",
    "reference_loop_identification",
    "share_loop_identifications",
]
