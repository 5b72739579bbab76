"""A JSON Schema (draft 2020-12) of the cusps document (``mechsing cusps --format json``).

Owns :func:`cusps_schema`, printed by ``mechsing schema --cusps``.  Every number is in SI
units and radians; ``rho`` and ``z`` (an arm's section) are lengths.  The document is
:meth:`mechsing.assembly.cusps.CuspsResult.to_json`.
"""

from __future__ import annotations

from typing import Any

__all__ = ["CUSPS_SCHEMA_ID", "cusps_schema"]

CUSPS_SCHEMA_ID = "urn:mechsing:schema:cusps-document"

_BY_NAME = {"type": "object", "additionalProperties": {"type": "number"}}
_RANGE = {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2}


def _cusp() -> dict[str, Any]:
    return {
        "type": "object",
        "required": ["inputs", "multiplicity", "certified", "radius", "t", "modes"],
        "properties": {
            "inputs": {
                **_BY_NAME,
                "description": "the varied coordinates' values at the cusp (two inputs, or "
                "rho and z of an arm)",
            },
            "multiplicity": {"const": 3, "description": "three modes meet: a triple root"},
            "certified": {
                "type": "boolean",
                "description": "a Krawczyk proof that exactly one true triple root lies "
                "within radius",
            },
            "radius": {
                "type": ["number", "null"],
                "description": "the half-width of the proven box (in t and the inputs, or "
                "in -1/t for a root with abs(t) > 1); null when not certified",
            },
            "t": {"type": "number", "description": "the triple root of the eliminant"},
            "not_certified": {
                "type": "string",
                "description": "why a listed cusp is not certified (a degenerate cusp: "
                "its triple-root system's Jacobian singular there)",
            },
            "modes": {
                "type": "object",
                "required": ["real_modes_at_cusp", "coalescing"],
                "description": "where the three modes meet",
                "properties": {
                    "platform": {
                        "type": "object",
                        "required": ["x", "y", "theta"],
                        "properties": {
                            "x": {"type": "number"},
                            "y": {"type": "number"},
                            "theta": {"type": "number"},
                        },
                        "description": "a planar mechanism: the platform's displacement "
                        "from the drawing",
                    },
                    "joints": {
                        **_BY_NAME,
                        "description": "every joint's value (a planar mechanism), or an "
                        "arm's second and third joints",
                    },
                    "real_modes_at_cusp": {
                        "type": "integer",
                        "minimum": 0,
                        "description": "the distinct real modes at the cusp's inputs",
                    },
                    "coalescing": {"const": 3},
                },
            },
        },
    }


def cusps_schema() -> dict[str, Any]:
    """The JSON Schema of the cusps document (a JSON-serialisable dict)."""
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "$id": CUSPS_SCHEMA_ID,
        "title": "mechsing cusps document",
        "type": "object",
        "required": [
            "mechanism",
            "problem",
            "section",
            "formulation",
            "cusps",
            "cuspidal",
            "evidence",
            "singular_curves",
            "modes_grid",
        ],
        "properties": {
            "mechanism": {"type": "string"},
            "problem": {"enum": ["direct kinematics", "inverse kinematics"]},
            "section": {
                "type": "object",
                "required": ["vary", "fixed"],
                "properties": {
                    "vary": {
                        "type": "object",
                        "additionalProperties": _RANGE,
                        "minProperties": 2,
                        "maxProperties": 2,
                        "description": "each varied coordinate's [lo, hi]",
                    },
                    "fixed": {
                        **_BY_NAME,
                        "description": "the fixed input's value (a planar mechanism; empty "
                        "for an arm)",
                    },
                },
            },
            "formulation": {
                "type": "object",
                "required": ["name", "t"],
                "properties": {
                    "name": {"type": "string"},
                    "t": {"type": "string", "description": "what the eliminant's unknown is"},
                    "platform": {"type": "string"},
                    "joints": {"type": "array", "items": {"type": "string"}},
                    "eliminant_degree": {"type": "integer", "minimum": 0},
                    "theta0": {"type": "number"},
                    "modes_counts": {
                        "type": "array",
                        "items": {"type": "integer", "minimum": 0},
                        "description": "the numbers of real modes seen on the grid",
                    },
                },
            },
            "cusps": {"type": "array", "items": _cusp()},
            "cuspidal": {
                "type": "boolean",
                "description": "true when a certified cusp lies in the section",
            },
            "evidence": {
                "type": "object",
                "required": ["kind", "reason", "cusps"],
                "properties": {
                    "kind": {"enum": ["cusps", "no-triple-root", "decoupled"]},
                    "reason": {"type": "string"},
                    "cusps": {"type": "integer", "minimum": 0},
                    "grid": {"type": "integer", "description": "grid points along each side"},
                    "singular_points": {"type": "integer", "minimum": 0},
                    "covers": {
                        "enum": ["grid"],
                        "description": "what the search for cusps covers: the singular "
                        "curves that cross the grid's lines (no proof over the whole box)",
                    },
                },
            },
            "singular_curves": {
                "type": "object",
                "required": ["points"],
                "properties": {
                    "points": {
                        "type": "array",
                        "items": _RANGE,
                        "description": "the located points of the singular curves: "
                        "[first varied, second varied]",
                    }
                },
            },
            "modes_grid": {
                "type": "object",
                "description": "each varied coordinate's grid values and modes[i][j], the "
                "number of real modes at (first[i], second[j]); empty when decoupled",
                "properties": {
                    "modes": {
                        "type": "array",
                        "items": {"type": "array", "items": {"type": "integer", "minimum": 0}},
                    }
                },
                "additionalProperties": {"type": "array"},
            },
        },
    }
