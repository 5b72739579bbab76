"""A JSON Schema (draft 2020-12) of the modes document (``mechsing modes --format json``).

Owns :func:`modes_schema`, printed by ``mechsing schema --modes``.  Every number is in SI
units and radians.  A mode's ``analysis`` is the analysis of one configuration as
``mechsing analyze``'s JSON gives it (its own contract, checked by the analysis tests).
"""

from __future__ import annotations

from typing import Any

__all__ = ["MODES_SCHEMA_ID", "modes_schema"]

MODES_SCHEMA_ID = "urn:mechsing:schema:modes-document"

_MATRIX = {"type": "array", "items": {"type": "array", "items": {"type": "number"}}}


def _mode() -> dict[str, Any]:
    return {
        "type": "object",
        "required": [
            "joints",
            "joints_text",
            "certified",
            "certified_radius",
            "singular",
            "singularities",
            "reached_by_continuation",
            "outside_limits",
            "equivalent_solutions",
            "analysis",
        ],
        "properties": {
            "joints": {
                "type": "object",
                "additionalProperties": {"type": "array", "items": {"type": "number"}},
                "description": "every joint's values (SI, radians), as in solve's JSON",
            },
            "joints_text": {
                "type": "object",
                "additionalProperties": {"type": "array", "items": {"type": "string"}},
                "description": "the same values as text at the precision's digits",
            },
            "certified": {
                "type": "boolean",
                "description": "a Krawczyk proof that one true solution lies within certified_radius",
            },
            "certified_radius": {
                "type": "number",
                "description": "the half-width of the proven box in the formulation's unknowns",
            },
            "singular": {"type": ["boolean", "null"], "description": "as analyze's"},
            "singularities": {
                "type": "array",
                "items": {"type": "object"},
                "description": "as analyze's findings",
            },
            "reached_by_continuation": {
                "type": "boolean",
                "description": "the mode continuation from the configuration's start closes at",
            },
            "outside_limits": {
                "type": "array",
                "items": {"type": "string"},
                "description": "the joints whose value lies outside the file's limits",
            },
            "equivalent_solutions": {
                "type": "integer",
                "minimum": 1,
                "description": "joint-space solutions this mode stands for",
            },
            "output_pose": {"type": ["array", "null"], "description": "the output body's 4x4 pose"},
            "analysis": {"type": "object", "description": "analyze's JSON of this configuration"},
        },
    }


def modes_schema() -> dict[str, Any]:
    """The JSON Schema of the modes document (a JSON-serialisable dict)."""
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "$id": MODES_SCHEMA_ID,
        "title": "mechsing modes document",
        "type": "object",
        "required": [
            "mechanism",
            "configuration",
            "precision",
            "count",
            "complete",
            "formulation",
            "paths",
            "modes",
            "distances",
            "notes",
        ],
        "properties": {
            "mechanism": {"type": "string"},
            "configuration": {"type": "string"},
            "precision": {"type": "object", "required": ["mode"]},
            "count": {
                "type": ["integer", "null"],
                "minimum": 0,
                "description": "the number of real modes; null when the set is not finite",
            },
            "complete": {"enum": ["proven", "maximal", "not proven", "infinite"]},
            "formulation": {
                "type": "object",
                "required": ["name", "method", "unknowns", "polynomial_degree"],
                "properties": {
                    "name": {"type": "string"},
                    "method": {"type": "string"},
                    "unknowns": {"type": "array", "items": {"type": "string"}},
                    "polynomial_degree": {"type": "integer", "minimum": 0},
                    "bezout": {
                        "type": "integer",
                        "description": "the start system's root count: the paths tracked",
                    },
                    "generic_count": {
                        "type": "integer",
                        "description": "the most real modes the mechanism can have here",
                    },
                    "generic_count_reason": {"type": ["string", "null"]},
                    "joints": {
                        "type": "array",
                        "items": {"type": "string"},
                        "description": "a serial arm's joints, from ground to the output",
                    },
                    "pair": {
                        "type": "array",
                        "items": {"type": "string"},
                        "description": "a serial arm's two consecutive joints whose span "
                        "carries the formulation (solved last, by factorisation)",
                    },
                    "closures": {
                        "type": "array",
                        "description": "the general formulation: each loop (or an arm's chain "
                        "to its target), the subgroup its joints generate and its closure "
                        "equations in that subgroup's coordinates",
                        "items": {
                            "type": "object",
                            "properties": {
                                "joints": {"type": "array", "items": {"type": "string"}},
                                "subgroup": {"type": ["string", "null"]},
                                "equations": {"type": "integer", "minimum": 0},
                            },
                        },
                    },
                    "eliminated": {
                        "type": "string",
                        "description": "the axis formulation: the unknown revolute "
                        "eliminated through its axis (its angle read off the others')",
                    },
                    "randomized": {
                        "type": "boolean",
                        "description": "more closure equations than unknowns (an "
                        "overconstrained mechanism): solved as random combinations",
                    },
                    "dimension": {
                        "type": "integer",
                        "minimum": 1,
                        "description": "complete infinite: the dimension of the closed "
                        "configurations with the given values (local dimension test)",
                    },
                    "parts": {
                        "type": "array",
                        "description": "the general formulation: the closure equations' "
                        "parts that share no unknown (each serial leg of a mechanism at a "
                        "pose), each solved alone; a mode is one solution of each",
                        "items": {
                            "type": "object",
                            "properties": {
                                "joints": {"type": "array", "items": {"type": "string"}},
                                "bezout": {"type": ["integer", "null"]},
                                "count": {"type": ["integer", "null"]},
                                "complete": {"enum": ["proven", "not proven", "infinite"]},
                            },
                        },
                    },
                    "working_modes": {
                        "type": "boolean",
                        "description": "the general formulation: the configuration gives "
                        "the output's pose of a mechanism with loops, and each mode is a "
                        "posture of its legs reaching it (a working mode)",
                    },
                    "proven_without_tracking": {
                        "type": "string",
                        "description": "why no mode exists, proven before any path was "
                        "tracked (then paths is null and the method was not run)",
                    },
                },
            },
            "paths": {
                "type": ["object", "null"],
                "description": "homotopy paths tracked, succeeded, failed (null: exact elimination, "
                "or formulation.proven_without_tracking)",
                "properties": {
                    k: {"type": "integer", "minimum": 0, "description": d}
                    for k, d in (
                        ("tracked", "paths tracked"),
                        ("finite", "endpoints at finite values"),
                        (
                            "extraneous",
                            "endpoints that are no solution (a serial arm: an "
                            "isotropic half-angle pair, or off the pair's span)",
                        ),
                        ("solutions", "finite solutions, real and complex (a serial arm)"),
                        ("real", "real endpoints"),
                        ("refined", "real endpoints refined at 50 digits or more"),
                        (
                            "singular",
                            "endpoints where the Jacobian is singular (a multiple "
                            "root or a curve of solutions: the count is not proven)",
                        ),
                        ("failed_or_infinite", "paths that ended at infinity or failed"),
                        ("duplicates", "refined endpoints that repeat a mode"),
                    )
                },
            },
            "modes": {"type": "array", "items": _mode()},
            "distances": {
                "type": "object",
                "required": ["joints", "pose"],
                "properties": {"joints": _MATRIX, "pose": _MATRIX},
            },
            "notes": {"type": "array", "items": {"type": "string"}},
        },
    }
