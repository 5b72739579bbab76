"""The JSON Schema of the file format (``mechsing schema``)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

from mechsing.cli import main
from mechsing.model.schema import mechanism_schema

ROOT = Path(__file__).parent.parent
VALID = sorted(
    list((ROOT / "examples").glob("*.yaml"))
    + list((ROOT / "examples").glob("*.json"))
    + list((ROOT / "tests" / "data").glob("*.yaml"))
)


def test_cli_prints_the_schema(capsys):
    assert main(["schema"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out == json.loads(json.dumps(mechanism_schema()))
    assert out["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert main(["schema", "--compact"]) == 0
    assert "\n" not in capsys.readouterr().out.strip()


def test_schema_lists_every_joint_type():
    from mechsing.subgroups import load_catalog

    variants = mechanism_schema()["$defs"]["joint"]["oneOf"]
    types = {v["properties"]["type"]["const"] for v in variants}
    assert types == set(load_catalog()) | {"U"}


def _validator():
    jsonschema = pytest.importorskip("jsonschema")
    schema = mechanism_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


@pytest.mark.parametrize("path", VALID, ids=[p.name for p in VALID])
def test_valid_files_pass_the_schema(path):
    v = _validator()
    doc = yaml.safe_load(path.read_text())
    errors = [e.message for e in v.iter_errors(doc)]
    assert not errors


BASE = {
    "bodies": ["ground", "a"],
    "joints": [
        {
            "name": "A",
            "type": "R",
            "between": ["ground", "a"],
            "axis": [0, 0, 1],
            "point": [0, 0, 0],
        }
    ],
}


@pytest.mark.parametrize(
    "change",
    [
        {"joint": []},
        {"units": {"length": "inch"}},
        {"joints": [{"name": "A", "type": "R", "between": ["ground", "a"], "axis": [0, 0, 1]}]},
        {
            "joints": [
                {
                    "name": "A",
                    "type": "P",
                    "between": ["ground", "a"],
                    "axis": [0, 0, 1],
                    "point": [0, 0, 0],
                }
            ]
        },
        {"joints": [{"name": "A", "type": "Q", "between": ["ground", "a"]}]},
        {
            "joints": [
                {
                    "name": "A",
                    "type": "R",
                    "between": ["ground"],
                    "axis": [0, 0, 1],
                    "point": [0, 0, 0],
                }
            ]
        },
        {"inputs": ["A[x]"]},
        {"output": {"relative_to": "ground"}},
        {"configurations": {"c": {"A": {"rotation": [[1, 0, 0]]}}}},
    ],
)
def test_bad_files_fail_the_schema(change):
    v = _validator()
    doc = dict(BASE, **change)
    assert list(v.iter_errors(doc))
