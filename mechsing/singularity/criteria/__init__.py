"""The singularity tests, each defined once (:mod:`~mechsing.singularity.criteria.base`):
``closure`` (the stacked loop screw systems), ``serial`` (a chain's screw system),
``motion`` (input, output, passive motion, impossible input and output) and
``constraint`` (the legs' combined constraint wrenches).  Each has a plan built once per
model, computes its matrices for any leading batch shape, states its reference and
decides a batch through the one rank rule of :mod:`mechsing.numeric`; the analysis of one
configuration, its nearby samples, the sweeps' measures and the scans all call them."""

from mechsing.singularity.criteria.base import Criterion, RankBounds, singular_values
from mechsing.singularity.criteria.closure import ClosureTest
from mechsing.singularity.criteria.constraint import ConstraintTest, LegPlan, leg_path
from mechsing.singularity.criteria.motion import (
    IO_TESTS,
    IOQuantities,
    MotionTest,
    input_rows,
    tests_run,
)
from mechsing.singularity.criteria.serial import ChainSystem, SerialTest

__all__ = [
    "IO_TESTS",
    "ChainSystem",
    "ClosureTest",
    "ConstraintTest",
    "Criterion",
    "IOQuantities",
    "LegPlan",
    "MotionTest",
    "RankBounds",
    "SerialTest",
    "input_rows",
    "leg_path",
    "singular_values",
    "tests_run",
]
