"""A JSON Schema (draft 2020-12) of the sweep document (``mechsing sweep --format json``).

Owns :func:`sweep_schema`, printed by ``mechsing schema --sweep``.  It states the shape
of the document that :meth:`~mechsing.sweeps.results.SweepResult.to_json` returns and
the command line writes point by point: the header (mechanism, file, ``from``,
precision, units, the swept variables, what is held, the tests and their generic
ranks), ``points`` (one per sample, row by row for a grid: the second variable's rows,
each over the first variable), ``located``, ``loci``, ``notes`` and
``newton_iterations``.  Conventions: every number is in SI units and radians; a value
that is not a finite number (a sample not reached) is null.  A located point's
``configuration`` is the analysis of one configuration as ``mechsing analyze``'s JSON
gives it (its own contract, checked by the analysis tests, not here).
"""

from __future__ import annotations

from typing import Any

from mechsing.kinetics.timed import TIMED_SCHEMA
from mechsing.statics.along import KINETOSTATICS_SCHEMA
from mechsing.sweeps.measures import TESTS

__all__ = ["SWEEP_SCHEMA_ID", "sweep_schema"]

SWEEP_SCHEMA_ID = "urn:mechsing:schema:sweep-document"

_NUMBER_OR_NULL = {"type": ["number", "null"]}
_STRINGS = {"type": "array", "items": {"type": "string"}}


def _values() -> dict[str, Any]:
    return {
        "type": "array",
        "items": {"type": "number"},
        "minItems": 1,
        "maxItems": 2,
        "description": "the swept variables' values (SI units, radians), in --vary order",
    }


MODE: dict[str, Any] = {
    "type": "integer",
    "minimum": 1,
    "description": "the assembly mode the sweep started on (--mode, --modes), as mechsing "
    "modes numbers them",
}


def sweep_schema() -> dict[str, Any]:
    """The JSON Schema of the sweep document (a JSON-serialisable dict)."""
    measure = {
        "type": "object",
        "properties": {
            "rank": {"type": ["integer", "null"], "minimum": 0},
            "ratio": {"type": ["number", "null"], "minimum": 0},
        },
        "required": ["rank", "ratio"],
        "additionalProperties": False,
        "description": "the test's decided rank (null: undecided or not reached) and its "
        "smallest relative singular value (null: not reached)",
    }
    point = {
        "type": "object",
        "properties": {
            "values": {"$ref": "#/$defs/values"},
            "reached": {"type": "boolean"},
            **{t: {"$ref": "#/$defs/measure"} for t in TESTS},
            "outside_limits": {
                "type": "array",
                "items": {"type": "string"},
                "description": "present when the file has joint limits: the coordinates "
                "beyond theirs at this sample (J2, or C1[1] for a joint of several)",
            },
            **KINETOSTATICS_SCHEMA["point"],
            "mode": MODE,
            **TIMED_SCHEMA["point"],
        },
        "required": ["values", "reached"],
        "additionalProperties": False,
    }
    variable = {
        "type": "object",
        "properties": {
            "name": {"type": "string"},
            "unit": {"enum": ["m", "rad"]},
            "file_unit": {"type": "string"},
            "start": {"type": "number"},
            "stop": {"type": "number"},
            "step": {"type": "number", "exclusiveMinimum": 0},
            "samples": {"type": "integer", "minimum": 1},
        },
        "required": ["name", "unit", "file_unit", "start", "stop", "step", "samples"],
        "additionalProperties": False,
        "description": "a swept variable; start, stop and step in the file's units",
    }
    located = {
        "type": "object",
        "properties": {
            "values": {"$ref": "#/$defs/values"},
            "kind": {"enum": ["fold", "crossing", "minimum", "sample"]},
            "between": {"enum": ["row", "column"]},
            "far_side": {"type": "boolean"},
            "tests": {"type": "array", "items": {"enum": list(TESTS)}},
            "ratio": {"type": "number", "minimum": 0},
            "singular": {"type": ["boolean", "null"]},
            "classes": {"type": ["array", "null"], "items": {"type": "string"}},
            "margin": {"type": ["object", "null"]},
            "precision": {"type": ["string", "null"]},
            "joints": {
                "type": "object",
                "additionalProperties": {"type": "array", "items": {"type": "number"}},
            },
            "unresolved": {"type": ["string", "null"]},
            "configuration": {"type": ["object", "null"]},
            "values_text": {
                "type": ["array", "null"],
                "items": {"type": "string"},
                "description": "at mp:N, the swept values of a point found again at N digits, "
                "as text at N digits (null otherwise, or for a pose variable's sweep)",
            },
            "joints_text": {
                "type": ["object", "null"],
                "additionalProperties": {"type": "array", "items": {"type": "string"}},
                "description": "at mp:N, every joint value of a point found again at N "
                "digits, as text at N digits (null otherwise)",
            },
            "mode": MODE,
        },
        "required": [
            "values",
            "kind",
            "between",
            "far_side",
            "tests",
            "ratio",
            "singular",
            "classes",
            "margin",
            "precision",
            "joints",
            "configuration",
        ],
        "additionalProperties": False,
        "description": "a singularity located between samples; classes, margin, precision "
        "and configuration are null when the full analysis did not classify it",
    }
    locus = {
        "type": "object",
        "properties": {
            "test": {"enum": list(TESTS)},
            "classes": _STRINGS,
            "closed": {"type": "boolean"},
            "mode": MODE,
            "vertices": {
                "type": "array",
                "items": {
                    "type": "array",
                    "items": {"type": "number"},
                    "minItems": 2,
                    "maxItems": 2,
                },
            },
        },
        "required": ["test", "classes", "closed", "vertices"],
        "additionalProperties": False,
        "description": "a polyline of a grid over its two swept variables (SI) where the "
        "test's measure vanishes",
    }
    length_angle = {
        "type": "object",
        "properties": {"length": {"type": "string"}, "angle": {"type": "string"}},
        "required": ["length", "angle"],
        "additionalProperties": False,
    }
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "$id": SWEEP_SCHEMA_ID,
        "title": "mechsing sweep document",
        "description": "mechsing sweep --format json: the measures at every sample of a path "
        "or a grid, the singularities located on it and, for a grid, their loci (SI units "
        "and radians)",
        "type": "object",
        "properties": {
            "mechanism": {"type": "string"},
            "file": {"type": ["string", "null"]},
            "from": {"type": "string"},
            "precision": {"type": "string"},
            "units": {
                "type": "object",
                "properties": {"length": {"const": "m"}, "angle": {"const": "rad"}},
                "required": ["length", "angle"],
                "additionalProperties": False,
            },
            "file_units": length_angle,
            "variables": {
                "type": "array",
                "items": {"$ref": "#/$defs/variable"},
                "minItems": 1,
                "maxItems": 2,
            },
            "held": _STRINGS,
            "tests": {"type": "array", "items": {"enum": list(TESTS)}},
            "generic": {
                "type": "object",
                "propertyNames": {"enum": list(TESTS)},
                "additionalProperties": {"type": "integer", "minimum": 0},
            },
            "points": {"type": "array", "items": {"$ref": "#/$defs/point"}},
            "located": {"type": "array", "items": {"$ref": "#/$defs/located"}},
            "loci": {"type": "array", "items": {"$ref": "#/$defs/locus"}},
            "notes": _STRINGS,
            "newton_iterations": {"type": "integer", "minimum": 0},
            **KINETOSTATICS_SCHEMA["top"],
            "mode": MODE,
            "modes": {
                "type": "array",
                "items": {"type": ["integer", "null"], "minimum": 1},
                "description": "--modes all: the assembly modes swept, one after the other",
            },
            "loops": {
                "type": "array",
                "items": {"type": "object"},
                "description": "--loop: each mode's loop around the rectangle of the two "
                "ranges (mode, end_mode, corners, closed, changed_mode, "
                "mode_change_without_singularity, distance, located, joints_start, "
                "joints_end, notes)",
            },
            "mode_changes": {
                "type": "array",
                "items": {
                    "type": "object",
                    "properties": {
                        "start_mode": {"type": ["integer", "null"]},
                        "end_mode": {"type": ["integer", "null"]},
                        "loop": {"type": "array"},
                        "path": {"type": "array"},
                        "distance": {"type": "number"},
                        "joints_start": {"type": "object"},
                        "joints_end": {"type": "object"},
                    },
                    "required": ["start_mode", "end_mode", "loop", "path"],
                },
                "description": "--loop: the loops back on another assembly mode with no "
                "singularity located on the way",
            },
            "aspects": {
                "type": "array",
                "items": {"$ref": "#/$defs/aspect"},
                "description": "a grid's connected singularity-free regions (each mode's, "
                "largest first)",
            },
            **TIMED_SCHEMA["top"],
        },
        "required": [
            "mechanism",
            "file",
            "from",
            "precision",
            "units",
            "file_units",
            "variables",
            "held",
            "tests",
            "generic",
            "points",
            "located",
            "loci",
            "notes",
            "newton_iterations",
        ],
        "additionalProperties": False,
        "$defs": {
            "values": _values(),
            "measure": measure,
            "point": point,
            "variable": variable,
            "located": located,
            "locus": locus,
            "aspect": {
                "type": "object",
                "properties": {
                    "cells": {"type": "integer", "minimum": 1},
                    "box": {
                        "type": "array",
                        "items": {"type": "array", "items": {"type": "number"}},
                        "description": "[[min, max] of the first variable, [min, max] of "
                        "the second] over the region's samples (SI)",
                    },
                    "mode": MODE,
                },
                "required": ["cells", "box"],
                "additionalProperties": False,
            },
        },
    }
