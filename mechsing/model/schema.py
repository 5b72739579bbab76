"""A JSON Schema (draft 2020-12) of the mechanism file, for editors.

Built from the subgroup catalog (the geometric keys of each joint type) so
that it never disagrees with the loader.  The schema checks the shape of a
file; the loader checks everything else (names that must exist, geometry,
expressions) and is the authority.
"""

from __future__ import annotations

from typing import Any

from mechsing.model.configurations import (
    DISPLACEMENT_KEYS,
    POSE_KEYS,
    RESERVED_CONFIGURATION_KEYS,
)
from mechsing.model.joints import U_KEYS
from mechsing.model.loader import ANGLE_UNITS, LENGTH_UNITS
from mechsing.model.loads import LOAD_KEY, LOAD_KEYS
from mechsing.model.mechanism import POSE_KEY, U_JOINT

__all__ = ["SCHEMA_ID", "mechanism_schema"]

SCHEMA_ID = "urn:mechsing:schema:mechanism-file"

_KIND_REF = {
    "direction": "#/$defs/vector",
    "normal": "#/$defs/vector",
    "point": "#/$defs/vector",
    "pitch": "#/$defs/number",
    "axes": "#/$defs/axes",
}


def _joint_schema(symbol: str, title: str, params: list[tuple[str, str]]) -> dict[str, Any]:
    props: dict[str, Any] = {
        "name": {"$ref": "#/$defs/joint_name"},
        "type": {"const": symbol},
        "between": {
            "type": "array",
            "items": {"$ref": "#/$defs/name"},
            "minItems": 2,
            "maxItems": 2,
            "description": "[a, b]: the joint value q sets g_b = g_a . exp(q)",
        },
    }
    for key, kind in params:
        props[key] = {"$ref": _KIND_REF[kind]}
    return {
        "title": f"{symbol}: {title}",
        "type": "object",
        "properties": props,
        "required": ["name", "type", "between", *[k for k, _ in params]],
        "additionalProperties": False,
    }


def _import_properties() -> dict[str, Any]:
    """The ``limits``, ``dh`` and ``couplings`` keys (joint limits; a Denavit-Hartenberg table standing for
    the bodies and joints of a serial chain)."""
    pair = {"type": "array", "items": {"$ref": "#/$defs/number"}, "minItems": 2, "maxItems": 2}
    row = {
        "type": "object",
        "properties": {
            "theta": {"$ref": "#/$defs/number"},
            "d": {"$ref": "#/$defs/number"},
            "a": {"$ref": "#/$defs/number"},
            "alpha": {"$ref": "#/$defs/number"},
            "type": {"enum": ["R", "P"]},
            "name": {"$ref": "#/$defs/joint_name"},
            "body": {"$ref": "#/$defs/name"},
        },
        "required": ["theta", "d", "a", "alpha"],
        "additionalProperties": False,
    }
    return {
        "limits": {
            "type": "object",
            "description": "joint limits in the file's units: [lower, upper] for a joint of "
            "one coordinate, a list of such pairs (one per coordinate) for a joint of several",
            "additionalProperties": {
                "anyOf": [pair, {"type": "array", "items": pair, "minItems": 1, "maxItems": 6}]
            },
        },
        "dh": {
            "type": "object",
            "description": "a Denavit-Hartenberg table (instead of bodies and joints): "
            "standard T = Rz(theta) Tz(d) Tx(a) Rx(alpha), or modified (Craig) T = Rx(alpha) "
            "Tx(a) Rz(theta) Tz(d); joint values are measured from the table's theta (R) or "
            "d (P); joints J1..Jn and bodies L0..Ln unless the rows name them",
            "properties": {
                "convention": {"enum": ["standard", "modified"]},
                "rows": {"type": "array", "items": row, "minItems": 1},
            },
            "required": ["rows"],
            "additionalProperties": False,
        },
        "couplings": {
            "type": "array",
            "description": "linear couplings of two joints of one coordinate (a URDF mimic): "
            "joint = multiplier * leader + offset, in the file's units; read, and dropped "
            "with a branch the scene options leave out; in the analysed part, each is one "
            "constraint row of the closure system (dq_joint = multiplier dq_leader)",
            "items": {
                "type": "object",
                "properties": {
                    "joint": {"$ref": "#/$defs/joint_name"},
                    "leader": {"$ref": "#/$defs/joint_name"},
                    "multiplier": {"$ref": "#/$defs/number"},
                    "offset": {"$ref": "#/$defs/number"},
                    "source_line": {"type": "integer", "minimum": 1},
                },
                "required": ["joint", "leader"],
                "additionalProperties": False,
            },
        },
    }


def mechanism_schema() -> dict[str, Any]:
    """The JSON Schema of the mechanism file format (a JSON-serialisable dict)."""
    from mechsing.subgroups import load_catalog

    catalog = load_catalog()
    joint_variants = [_joint_schema(sym, t.name, list(t.parameters)) for sym, t in catalog.items()]
    joint_variants.append(
        _joint_schema(
            U_JOINT, "universal joint (a1 fixed in between[0], a2 in between[1])", list(U_KEYS)
        )
    )
    number = {
        "description": "a number, or a quoted exact expression: numbers, + - * / **, "
        "parentheses, pi, sqrt, sin, cos, tan, asin, acos, atan, atan2 and the file's "
        "parameters",
        "anyOf": [
            {"type": "number"},
            {"type": "string", "minLength": 1, "maxLength": 1000},
        ],
    }
    vector = {"type": "array", "items": {"$ref": "#/$defs/number"}, "minItems": 3, "maxItems": 3}
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "$id": SCHEMA_ID,
        "title": "mechsing mechanism file",
        "description": "Bodies, joints (Lie subgroups of SE(3) or U), inputs, output and named "
        "configurations. Lengths in metres and angles in radians unless units says otherwise; "
        "pitch in length per radian.",
        "type": "object",
        "properties": {
            "mechanism": {"type": "string", "description": "the mechanism's name"},
            "units": {
                "type": "object",
                "description": "angle: deg writes every joint angle in degrees; an angle "
                "written with pi, asin, acos, atan or atan2 is a radian value and is refused "
                "there. In radians (the default) a plain angle above a full turn is warned "
                "about (degrees meant?).",
                "properties": {
                    "length": {"enum": list(LENGTH_UNITS)},
                    "angle": {"enum": list(ANGLE_UNITS)},
                },
                "additionalProperties": False,
            },
            "parameters": {
                "type": "object",
                "description": "named numbers used in any number or expression of the file "
                "(e.g. point: [a2, 0, 0]); a value is a number or an expression of earlier "
                "parameters; names are identifiers, not pi, a function name, or a body or "
                "joint name; the unit of the place where a parameter is used applies",
                "propertyNames": {"pattern": r"^[A-Za-z_][A-Za-z0-9_]*$"},
                "additionalProperties": {"$ref": "#/$defs/number"},
            },
            "ground": {"$ref": "#/$defs/name", "description": "default: the first body"},
            "bodies": {
                "type": "array",
                "items": {"$ref": "#/$defs/name"},
                "minItems": 1,
                "uniqueItems": True,
            },
            "joints": {"type": "array", "items": {"$ref": "#/$defs/joint"}},
            "inputs": {
                "type": "array",
                "items": {"type": "string", "pattern": r"^[^\[\]]+(\[[0-9]+\])?$"},
                "description": 'joint names, or "NAME[i]" for one coordinate (0-based)',
            },
            "output": {
                "type": "object",
                "properties": {
                    "body": {"$ref": "#/$defs/name"},
                    "relative_to": {"$ref": "#/$defs/name"},
                    "point": {"$ref": "#/$defs/vector"},
                },
                "required": ["body"],
                "additionalProperties": False,
            },
            "characteristic_length": {"$ref": "#/$defs/number"},
            "mass": {
                "type": "object",
                "description": "the bodies' masses for their weights under gravity "
                "(docs/kinetostatics.md): kg, and the centre of mass where it is in the drawn "
                "pose (the file's lengths; default the centroid of the body's joint points)",
                "additionalProperties": {
                    "type": "object",
                    "properties": {
                        "kg": {"$ref": "#/$defs/number"},
                        "centre": {"$ref": "#/$defs/vector"},
                        "inertia": {
                            "description": "the inertia about the centre of mass in ground "
                            "axes at the drawn pose (docs/dynamics.md): [ixx, iyy, izz, ixy, "
                            "ixz, iyz] or a 3x3 matrix, kg times the file's length squared",
                            "type": "array",
                        },
                    },
                    "required": ["kg"],
                    "additionalProperties": False,
                },
            },
            "gravity": {
                "$ref": "#/$defs/vector",
                "description": "the acceleration of gravity in ground axes (the file's length "
                "unit per s^2), with mass",
            },
            "configurations": {
                "type": "object",
                "additionalProperties": {"$ref": "#/$defs/configuration"},
            },
            **_import_properties(),
        },
        "anyOf": [
            {"required": ["bodies", "joints"]},
            {
                "required": ["dh"],
                "not": {"anyOf": [{"required": ["joints"]}, {"required": ["bodies"]}]},
            },
        ],
        "additionalProperties": False,
        "$defs": {
            "name": {"type": "string", "minLength": 1, "maxLength": 200},
            "joint_name": {
                "type": "string",
                "minLength": 1,
                "maxLength": 200,
                "pattern": r"^[^\[\]]+$",
                "not": {"enum": list(RESERVED_CONFIGURATION_KEYS)},
            },
            "number": number,
            "vector": vector,
            "axes": {
                "type": "array",
                "items": {"$ref": "#/$defs/vector"},
                "minItems": 2,
                "maxItems": 2,
            },
            "joint": {"oneOf": joint_variants},
            "rotation_matrix": {
                "type": "array",
                "description": "a rotation as a 3x3 matrix, three rows of three numbers",
                "items": {"$ref": "#/$defs/vector"},
                "minItems": 3,
                "maxItems": 3,
            },
            "displacement": {
                "type": "object",
                "description": "a multi-dof joint value as the relative displacement it "
                "produces; an omitted key is completed (identity rotation, or the translation "
                "that puts the rotation in the joint's subgroup); membership is decided to the "
                "analysis precision's tolerance",
                "properties": {
                    "rotation": {"$ref": "#/$defs/rotation_matrix"},
                    "translation": {"$ref": "#/$defs/vector"},
                },
                "minProperties": 1,
                "additionalProperties": False,
                "propertyNames": {"enum": list(DISPLACEMENT_KEYS)},
            },
            "pose": {
                "type": "object",
                "description": "the output body's pose (relative to output.relative_to, "
                "default the ground); the joints not given are solved by closure. position: "
                "where the output's reference point is (output.point, else the centroid of the "
                "output body's joint points at the reference configuration), in the file's "
                "lengths; the rotation about that point relative to the reference "
                "configuration, written one way: rotation (3x3 matrix), rotation_vector, or "
                "axis and angle (the file's angles). An omitted position or rotation is the "
                "reference configuration's.",
                "properties": {
                    "position": {"$ref": "#/$defs/vector"},
                    "rotation": {"$ref": "#/$defs/rotation_matrix"},
                    "rotation_vector": {"$ref": "#/$defs/vector"},
                    "axis": {"$ref": "#/$defs/vector"},
                    "angle": {"$ref": "#/$defs/number"},
                },
                "minProperties": 1,
                "additionalProperties": False,
                "propertyNames": {"enum": list(POSE_KEYS)},
                "dependentRequired": {"axis": ["angle"], "angle": ["axis"]},
                "not": {
                    "anyOf": [
                        {"required": ["rotation", "rotation_vector"]},
                        {"required": ["rotation", "axis"]},
                        {"required": ["rotation_vector", "axis"]},
                    ]
                },
            },
            "load": {
                "type": "object",
                "description": "the wrench the environment applies to the output body "
                "(mechsing analyze/sweep/report give the actuator efforts that hold it): force "
                "(N) and moment (N times the file's length unit, about point) in ground axes; "
                "point: a point of the output body where it is in the drawn pose (the file's "
                "lengths; it moves with the body), default the output's reference point",
                "properties": {
                    "force": {"$ref": "#/$defs/vector"},
                    "moment": {"$ref": "#/$defs/vector"},
                    "point": {"$ref": "#/$defs/vector"},
                },
                "minProperties": 1,
                "additionalProperties": False,
                "propertyNames": {"enum": list(LOAD_KEYS)},
                "anyOf": [{"required": ["force"]}, {"required": ["moment"]}],
            },
            "joint_value": {
                "anyOf": [
                    {"$ref": "#/$defs/number"},
                    {"type": "array", "items": {"$ref": "#/$defs/number"}, "maxItems": 6},
                    {"$ref": "#/$defs/displacement"},
                ]
            },
            "configuration": {
                "description": "joint values by joint name (the others are solved by "
                f"closure), start, the output body's {POSE_KEY} and the {LOAD_KEY} on it; the configuration named "
                "reference has every joint at identity and may list only identity values",
                "anyOf": [
                    {"type": "null"},
                    {
                        "type": "object",
                        "properties": {
                            "start": {"$ref": "#/$defs/name"},
                            POSE_KEY: {"$ref": "#/$defs/pose"},
                            LOAD_KEY: {"$ref": "#/$defs/load"},
                        },
                        "additionalProperties": {"$ref": "#/$defs/joint_value"},
                    },
                ],
            },
        },
    }
