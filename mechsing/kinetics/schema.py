"""The JSON Schema of ``mechsing dynamics --format json`` (``mechsing schema --dynamics``)."""

from __future__ import annotations

from typing import Any

__all__ = ["dynamics_schema"]


def _by_joint(description: str) -> dict[str, Any]:
    return {
        "type": "object",
        "description": description,
        "additionalProperties": {"type": "number"},
    }


def dynamics_schema() -> dict[str, Any]:
    """The schema of :meth:`mechsing.kinetics.api.DynamicsResult.to_json`."""
    config = {
        "type": "object",
        "required": [
            "name",
            "joints",
            "rates",
            "efforts",
            "accelerations",
            "mass_matrix",
            "bias_efforts",
            "kinetic_energy",
            "crossing",
        ],
        "properties": {
            "name": {"type": "string"},
            "joints": _by_joint("the joint values (rad, m) of the closed configuration"),
            "rates": _by_joint("the joint rates (rad/s, m/s)"),
            "efforts": _by_joint(
                "the joint efforts (N m, N), positive along the joint's coordinate: given "
                "(forward dynamics) or computed (inverse dynamics)"
            ),
            "accelerations": _by_joint(
                "the joint accelerations (rad/s^2, m/s^2): given (inverse) or computed (forward)"
            ),
            "mass_matrix": {
                "type": "object",
                "description": "the joint-space mass matrix, rows and columns in the order of joints",
                "required": ["joints", "matrix"],
                "properties": {
                    "joints": {"type": "array", "items": {"type": "string"}},
                    "matrix": {
                        "type": "array",
                        "items": {"type": "array", "items": {"type": "number"}},
                    },
                },
            },
            "bias_efforts": _by_joint(
                "the efforts at zero acceleration: Coriolis, centrifugal and gravity (N m, N)"
            ),
            "kinetic_energy": {"type": "number", "description": "J"},
            "crossing": {
                "description": "the Type II crossing condition of a closed chain "
                "(Briot & Arakelian 2008): null for a tree, which has no Type II singularity",
                "oneOf": [
                    {"type": "null"},
                    {
                        "type": "object",
                        "properties": {
                            "possible": {"type": "boolean"},
                            "residual": {"type": ["number", "null"]},
                        },
                    },
                ],
            },
        },
    }
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "mechsing dynamics --format json",
        "type": "object",
        "required": ["mechanism", "precision", "problem", "gravity", "configurations"],
        "properties": {
            "mechanism": {"type": "string"},
            "precision": {"type": "string"},
            "problem": {
                "enum": ["inverse", "forward"],
                "description": "inverse: efforts from accelerations; forward: accelerations "
                "from efforts",
            },
            "gravity": {
                "description": "the acceleration of gravity (m/s^2, ground axes), null: none",
                "oneOf": [
                    {"type": "null"},
                    {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3},
                ],
            },
            "configurations": {"type": "array", "items": config},
        },
    }
