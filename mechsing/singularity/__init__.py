"""Singularity classification of a closed configuration: :func:`classify`, a pure function
from (mechanism, kinematic model, configuration, closure system) to a frozen
:class:`~mechsing.singularity.findings.Classification` (the finding types live in
:mod:`mechsing.singularity.findings`).

Every test is measured against its value at generic configurations: what holds everywhere
is a property of the mechanism (decided by the analysis), never a singularity.
"""

from mechsing.singularity.classification import classify, output_chain, random_configurations
from mechsing.singularity.findings import Classification
from mechsing.singularity.serial import GENERIC_SAMPLES

__all__ = [
    "GENERIC_SAMPLES",
    "Classification",
    "classify",
    "output_chain",
    "random_configurations",
]
