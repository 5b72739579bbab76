"""The JSON Schema (draft 2020-12) of ``mechsing condition --format json``.

Written by hand next to :meth:`ConditionResult.to_json`, which it describes;
the tests validate real outputs against it.  Numbers are in SI units and
radians; formulas are sympy text (``sin(B)``, ``a1*a2``).
"""

from __future__ import annotations

from typing import Any

__all__ = ["CONDITION_SCHEMA_ID", "condition_schema"]

CONDITION_SCHEMA_ID = "urn:mechsing:schema:condition"


def condition_schema() -> dict[str, Any]:
    """The schema of the condition document (a JSON-serialisable dict)."""
    nullable_number = {"type": ["number", "null"]}
    nullable_bool = {"type": ["boolean", "null"]}
    factor = {
        "type": "object",
        "properties": {
            "expression": {"type": "string", "description": "the factor (sympy text)"},
            "latex": {"type": "string", "description": "the factor in LaTeX (sympy.latex)"},
            "power": {"type": "integer", "minimum": 1},
            "meaning": {
                "type": ["string", "null"],
                "description": "what its vanishing means, where recognised",
            },
            "value": {**nullable_number, "description": "its value at the configuration"},
            "vanishes": {**nullable_bool, "description": "zero at the configuration"},
            "name": {
                "type": ["string", "null"],
                "description": "the name people give the singularity (wrist, elbow, shoulder), "
                "where its geometry shows one",
            },
        },
        "required": ["expression", "latex", "power", "meaning", "value", "vanishes"],
        "additionalProperties": False,
    }
    condition = {
        "type": "object",
        "properties": {
            "name": {"type": "string"},
            "form": {"enum": ["determinant", "gcd of maximal minors", "eliminated"]},
            "variables": {"type": "array", "items": {"type": "string"}},
            "expression": {"type": "string", "description": "constant*(factor)*... = 0"},
            "latex": {
                "type": "string",
                "description": "the same product in LaTeX, without '= 0' (for $...$)",
            },
            "constant": {"type": "string"},
            "factors": {"type": "array", "items": factor},
            "note": {"type": "string"},
            "roots": {
                "type": "array",
                "items": {"type": "number"},
                "description": "values of the single variable of an eliminated condition "
                "where it vanishes (root_units)",
            },
            "root_units": {"type": "array", "items": {"enum": ["rad", "m"]}},
            "vanishes": nullable_bool,
        },
        "required": [
            "name",
            "form",
            "variables",
            "expression",
            "latex",
            "constant",
            "factors",
            "note",
            "roots",
            "root_units",
            "vanishes",
        ],
        "additionalProperties": False,
    }
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "$id": CONDITION_SCHEMA_ID,
        "title": "mechsing condition document",
        "description": "Singularity conditions as factored formulas in the joint variables "
        "(named by the joints, measured from the drawn pose, rad or m), the angles phi_X of "
        "the bodies of a linkage (rad), or the pose variables x, y, z (m) and phi (rad).",
        "type": "object",
        "properties": {
            "mechanism": {"type": "string"},
            "method": {
                "enum": [
                    "open chain",
                    "single loop, one input",
                    "linkage, one input",
                    "parallel robot, pose variables",
                ]
            },
            "symbolic": {"type": "array", "items": {"type": "string"}},
            "parameters": {"type": "object", "additionalProperties": {"type": "number"}},
            "configuration": {"type": ["string", "null"]},
            "values": {"type": "object", "additionalProperties": {"type": "number"}},
            "conditions": {"type": "array", "items": condition},
            "notes": {"type": "array", "items": {"type": "string"}},
        },
        "required": [
            "mechanism",
            "method",
            "symbolic",
            "parameters",
            "configuration",
            "values",
            "conditions",
            "notes",
        ],
        "additionalProperties": False,
    }
