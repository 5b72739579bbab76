"""Precision modes, number backends, tolerances and rank decisions (the leaf layer).

Every other layer of mechsing may import this package; it imports none of them.  Its
modules, from the bottom up (each imports only those before it):

``tolerances``
    every decision tolerance (constants) and the two rank thresholds;
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

Everything public is re-exported here: ``from mechsing.numeric import decide_rank``.
"""

from __future__ import annotations

from mechsing.numeric._mp import (
    eigsy,
    mp_svd,
    svd_r,
)
from mechsing.numeric.backend import (
    EXACT,
    FLOAT,
    Backend,
    ExactBackend,
    FloatBackend,
    MpBackend,
    backend_of,
    coarser_backend,
    exact_is_zero,
    exact_normal_form,
    screw_zero_rtol,
    to_float,
)
from mechsing.numeric.decisions import (
    DefinitenessDecision,
    Margin,
    RankDecision,
    decide_definiteness,
    decide_nonzero,
    decide_rank,
    float_drop_is_real,
    rank_bounds,
    rank_difference,
)
from mechsing.numeric.field import (
    cos_sin,
    field_echelon,
    field_null_space,
    field_row_space,
    field_solve,
    from_field,
    number_field,
)
from mechsing.numeric.linalg import (
    eigh,
    lstsq,
    max_abs,
    norm,
    orthonormal_columns,
    pinv_truncated,
    singular_values,
    spectral_norm,
    svd,
)
from mechsing.numeric.precision import (
    Precision,
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
    BRANCH_ALIGNMENT,
    CLOSURE_RTOL_FLOAT,
    CONDITION_GENERIC_RANK_RTOL,
    CONDITION_GEOMETRY_RTOL,
    CONDITION_ROOT_MERGE,
    CONDITION_ROOT_RTOL,
    CONDITION_VANISH_RTOL,
    CONTINUATION_CORRECTOR_RATIO,
    CONTINUATION_FOLD_GAP,
    CONTINUATION_FOLD_REACH,
    CONTINUATION_JUMP_FLOOR,
    CONTINUATION_RETURN_RATIO,
    CONTINUATION_REVERSE_RTOL,
    CONTINUATION_SINGULAR_RTOL,
    CONTINUATION_STEP_RTOL,
    EXACT_TEST_DIGITS,
    EXACT_ZERO_DIGITS,
    FLOAT_ROUNDING_FACTOR,
    MAX_JOINT_VALUE,
    MEMBERSHIP_RTOL_FLOAT,
    MP_MIN_DIGITS,
    NEAR_ZERO_VECTOR,
    ORDER3_RESIDUAL_FACTOR,
    PARALLEL_AXES_ATOL,
    POLISH_DIGITS_SPARE,
    POLISH_MAX_STEPS,
    POLISH_SLOW_RATIO,
    REFERENCE_SCREEN_RTOL,
    ROTATION_ORTHONORMAL_ATOL,
    SAMPLE_CLOSURE_RTOL,
    SAMPLE_DISTINCT_RATIO,
    SCAN_ROUNDING_FACTOR,
    SCAN_SCREEN_FACTOR,
    SUBSPACE_CONTAINMENT_FACTOR,
    SUBSPACE_RANK_FACTOR,
    SUPPORT_RTOL,
    SWEEP_ARC_MIN_STEP,
    SWEEP_ARC_STEP,
    SWEEP_BRANCH_OFFSET,
    SWEEP_JUMP_RATIO,
    SWEEP_LOCATE_TOL,
    SWEEP_MINIMUM_SCREEN,
    SWEEP_NODE_STEP,
    SWEEP_SCREEN_ROUNDING,
    Tolerances,
)

__all__ = [
    "cos_sin",
    "field_echelon",
    "field_null_space",
    "field_row_space",
    "field_solve",
    "from_field",
    "number_field",
    "BRANCH_ALIGNMENT",
    "CONDITION_GENERIC_RANK_RTOL",
    "CONDITION_GEOMETRY_RTOL",
    "CONDITION_ROOT_MERGE",
    "CONDITION_ROOT_RTOL",
    "CONDITION_VANISH_RTOL",
    "Backend",
    "CLOSURE_RTOL_FLOAT",
    "CONTINUATION_CORRECTOR_RATIO",
    "CONTINUATION_FOLD_GAP",
    "CONTINUATION_FOLD_REACH",
    "CONTINUATION_JUMP_FLOOR",
    "CONTINUATION_RETURN_RATIO",
    "CONTINUATION_REVERSE_RTOL",
    "CONTINUATION_SINGULAR_RTOL",
    "CONTINUATION_STEP_RTOL",
    "DefinitenessDecision",
    "EXACT",
    "EXACT_TEST_DIGITS",
    "EXACT_ZERO_DIGITS",
    "ExactBackend",
    "FLOAT",
    "FLOAT_ROUNDING_FACTOR",
    "FloatBackend",
    "MAX_JOINT_VALUE",
    "MEMBERSHIP_RTOL_FLOAT",
    "MP_MIN_DIGITS",
    "Margin",
    "MpBackend",
    "NEAR_ZERO_VECTOR",
    "ORDER3_RESIDUAL_FACTOR",
    "PARALLEL_AXES_ATOL",
    "POLISH_DIGITS_SPARE",
    "POLISH_MAX_STEPS",
    "POLISH_SLOW_RATIO",
    "Precision",
    "REFERENCE_SCREEN_RTOL",
    "ROTATION_ORTHONORMAL_ATOL",
    "RankDecision",
    "SAMPLE_CLOSURE_RTOL",
    "SAMPLE_DISTINCT_RATIO",
    "SCAN_ROUNDING_FACTOR",
    "SCAN_SCREEN_FACTOR",
    "SUBSPACE_CONTAINMENT_FACTOR",
    "SUBSPACE_RANK_FACTOR",
    "SUPPORT_RTOL",
    "SWEEP_ARC_MIN_STEP",
    "SWEEP_ARC_STEP",
    "SWEEP_BRANCH_OFFSET",
    "SWEEP_JUMP_RATIO",
    "SWEEP_LOCATE_TOL",
    "SWEEP_MINIMUM_SCREEN",
    "SWEEP_NODE_STEP",
    "SWEEP_SCREEN_ROUNDING",
    "Tolerances",
    "backend_of",
    "coarser_backend",
    "characteristic_length",
    "decide_definiteness",
    "decide_nonzero",
    "decide_rank",
    "eigh",
    "eigsy",
    "exact_is_zero",
    "exact_normal_form",
    "float_drop_is_real",
    "lstsq",
    "max_abs",
    "mp_svd",
    "norm",
    "numeric_precision",
    "order3_residual_rtol",
    "orthonormal_columns",
    "parse_precision",
    "pinv_truncated",
    "rank_bounds",
    "rank_difference",
    "rotation_orthonormal_atol",
    "scale_screws",
    "CommensurateFrame",
    "screw_zero_rtol",
    "singular_values",
    "spectral_norm",
    "subspace_containment_atol",
    "subspace_rank_rtol",
    "svd",
    "svd_r",
    "to_float",
]
