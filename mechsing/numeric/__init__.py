"""Precision modes, number backends, tolerances and rank decisions (the leaf layer).

Every other layer of mechsing may import this package; it imports none of them.  Its
modules, from the bottom up (each imports only those before it):

``tolerances``
    the decision thresholds (rank, equality, data resolution: constants, each with its
    margin rule) and the two rank thresholds;
``dispatch``
    the one place that chooses fast paths (tables of fast forms, ``MECHSING_FAST``);
``numbers``
    the one syntax of a written number, its sensible size, and directions made unit
    without overflow;
``lazy``
    sympy and mpmath imported when first used (the one place that defers them);
``pirational``
    :class:`~mechsing.numeric.pirational.PiRational`, the exact number of a file's plain
    numbers (a rational times a power of pi) that needs no sympy;
``_mp``
    the mpmath kernels: the one mp SVD and eigensolver (always converging);
``backend``
    :class:`Backend` and the float, mp and exact backends, which answer the questions
    formulas ask (``is_zero``, ``null_space``, ``row_space``, ``solve``, ``simplify``,
    series switch points) so that formulas never branch on the mode;
``precision``
    :class:`Precision`, :func:`parse_precision`, :func:`numeric_precision` and the
    tolerances that follow from a precision;
``linalg``
    SVD, eigenproblems, norms and least squares on the numerical backends;
``scaling``
    the characteristic length and :class:`CommensurateFrame` (the commensurate maps
    and their inverses);
``decisions``
    rank and definiteness decisions with their margins.

The decision API is re-exported here: ``from mechsing.numeric import decide_rank`` (the
precision modes and backends, the rank, definiteness and resolution decisions with their
margins, the thresholds, the commensurate scaling).  The tools beneath it are imported
from their modules: linear algebra from ``linalg``, number fields from ``field``, the
syntax of numbers from ``numbers``, the backends' helpers from ``backend``.
"""

from __future__ import annotations

from typing import Any

from mechsing.numeric._mp import (
    eigsy,
    mp_svd,
    svd_r,
)
from mechsing.numeric.backend import (
    FLOAT,
    Backend,
    ExactBackend,
    FloatBackend,
    MpBackend,
    backend_of,
    coarser_backend,
    screw_zero_rtol,
    to_float,
)
from mechsing.numeric.decisions import (
    DefinitenessDecision,
    Margin,
    RankDecision,
    batched_kernels,
    batched_rank_bounds,
    data_resolution,
    decide_definiteness,
    decide_from_exact,
    decide_nonzero,
    decide_rank,
    flips_within,
    float_drop_is_real,
    rank_bounds,
    rank_difference,
    relative_singular_values,
    resolution_spread,
)
from mechsing.numeric.precision import (
    Precision,
    display_floor,
    floored,
    numeric_precision,
    order3_residual_rtol,
    parse_precision,
    rotation_orthonormal_atol,
    subspace_containment_atol,
    subspace_rank_rtol,
)
from mechsing.numeric.scaling import (
    CommensurateFrame,
    characteristic_length,
    scale_screws,
)
from mechsing.numeric.tolerances import (
    CLOSURE_RTOL_FLOAT,
    CONDITION_GENERIC_RANK_RTOL,
    CONDITION_GEOMETRY_RTOL,
    CONDITION_ROOT_RTOL,
    CONDITION_VANISH_RTOL,
    CROSSING_RTOL,
    EXACT_TEST_DIGITS,
    EXACT_ZERO_DIGITS,
    FLOAT_ROUNDING_FACTOR,
    INERTIA_RTOL,
    MAX_JOINT_VALUE,
    MAX_NUMBER,
    MEMBERSHIP_RTOL_FLOAT,
    MODE_FOLD_MATCH_DISTANCE,
    MODE_MATCH_DISTANCE,
    MODE_SPAN_RTOL,
    MP_MIN_DIGITS,
    NEAR_ZERO_VECTOR,
    ORDER3_RESIDUAL_FACTOR,
    PARALLEL_AXES_ATOL,
    REFERENCE_SCREEN_RTOL,
    RESOLUTION_MIN_DIGITS,
    ROTATION_ORTHONORMAL_ATOL,
    SCAN_ROUNDING_FACTOR,
    SCAN_SCREEN_FACTOR,
    SUBSPACE_CONTAINMENT_FACTOR,
    SUBSPACE_RANK_FACTOR,
    SUPPORT_RTOL,
    Tolerances,
)


def __getattr__(name: str) -> Any:
    # the exact backend is made, and sympy imported, when first asked for
    if name == "EXACT":
        from mechsing.numeric.backend import _exact_backend

        return _exact_backend()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "MODE_FOLD_MATCH_DISTANCE",
    "MODE_MATCH_DISTANCE",
    "INERTIA_RTOL",
    "MODE_SPAN_RTOL",
    "CONDITION_GENERIC_RANK_RTOL",
    "CONDITION_GEOMETRY_RTOL",
    "CONDITION_ROOT_RTOL",
    "CONDITION_VANISH_RTOL",
    "Backend",
    "CLOSURE_RTOL_FLOAT",
    "CROSSING_RTOL",
    "DefinitenessDecision",
    "EXACT",
    "EXACT_TEST_DIGITS",
    "EXACT_ZERO_DIGITS",
    "ExactBackend",
    "FLOAT",
    "FLOAT_ROUNDING_FACTOR",
    "FloatBackend",
    "MAX_JOINT_VALUE",
    "MAX_NUMBER",
    "MEMBERSHIP_RTOL_FLOAT",
    "MP_MIN_DIGITS",
    "Margin",
    "MpBackend",
    "NEAR_ZERO_VECTOR",
    "ORDER3_RESIDUAL_FACTOR",
    "PARALLEL_AXES_ATOL",
    "Precision",
    "REFERENCE_SCREEN_RTOL",
    "RESOLUTION_MIN_DIGITS",
    "ROTATION_ORTHONORMAL_ATOL",
    "RankDecision",
    "SCAN_ROUNDING_FACTOR",
    "SCAN_SCREEN_FACTOR",
    "SUBSPACE_CONTAINMENT_FACTOR",
    "SUBSPACE_RANK_FACTOR",
    "SUPPORT_RTOL",
    "Tolerances",
    "backend_of",
    "coarser_backend",
    "characteristic_length",
    "data_resolution",
    "decide_definiteness",
    "flips_within",
    "decide_from_exact",
    "decide_nonzero",
    "decide_rank",
    "eigsy",
    "float_drop_is_real",
    "mp_svd",
    "numeric_precision",
    "display_floor",
    "floored",
    "order3_residual_rtol",
    "parse_precision",
    "batched_kernels",
    "batched_rank_bounds",
    "rank_bounds",
    "relative_singular_values",
    "rank_difference",
    "resolution_spread",
    "rotation_orthonormal_atol",
    "scale_screws",
    "CommensurateFrame",
    "screw_zero_rtol",
    "subspace_containment_atol",
    "subspace_rank_rtol",
    "svd_r",
    "to_float",
]
