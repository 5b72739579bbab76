"""``mechsing catalog`` and ``mechsing identify``."""

from __future__ import annotations

import json

import pytest

from mechsing.subgroups import load_catalog
from tests.cli import run_cli


def test_catalog_text_and_json():
    code, out, _ = run_cli(["catalog"])
    assert code == 0
    for sym in load_catalog():
        assert f"  {sym} " in out
    code, out, _ = run_cli(["catalog", "--format", "json"])
    data = json.loads(out)
    assert [d["symbol"] for d in data] == list(load_catalog())
    for d in data:
        assert {"symbol", "name", "dimension", "parameters", "basis"} <= set(d)
        assert len(d["basis"]) == d["dimension"]


def test_catalog_one_type():
    code, out, _ = run_cli(["catalog", "S"])
    assert code == 0 and "spherical" in out and "point x ex" in out
    code, out, _ = run_cli(["catalog", "t2", "--format", "json"])
    assert json.loads(out)[0]["symbol"] == "T2"


def test_catalog_unknown_type():
    code, _, err = run_cli(["catalog", "Q"])
    assert code == 2 and "'Q'" in err and "use one of" in err


def test_identify_json_contract():
    code, out, _ = run_cli(["identify", "--format", "json", "--", "0,0,1,0,0,0", "0,0,1,0,-1,0"])
    assert code == 0
    data = json.loads(out)
    assert (
        data["type"] == "G" and data["dim"] == 3 and data["params"] == {"normal": [0.0, 0.0, 1.0]}
    )
    assert {"bracket_norms", "margin"} <= set(data)
    assert set(data["margin"]) >= {"kept", "dropped", "tau_lo", "tau_hi", "length_scale"}


def test_identify_expressions_and_length_scale():
    code, out, _ = run_cli(
        [
            "identify",
            "--length-scale",
            "1000",
            "--format",
            "json",
            "--",
            "sqrt(2)/2,sqrt(2)/2,0,-1000*sqrt(2),1000*sqrt(2),0",
            "0,0,1,0,0,0",
            "1,0,0,0,2000,0",
        ]
    )
    data = json.loads(out)
    assert code == 0 and data["type"] == "S"
    assert data["params"]["point"] == pytest.approx([0, 0, 2000])
    assert data["margin"]["length_scale"] == 1000.0
    code, out, _ = run_cli(["identify", "--", "1/3,0,0,0,0,0"])
    assert code == 0 and out.startswith("R (dimension 1)") and "exact" in out


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["identify", "--", "1,0,0"], "6 comma-separated"),
        (["identify", "--", "1,0,0,0,0,__import__('os')"], "entry 6"),
        (["identify", "--", "1,0,0,0,0,x"], "not allowed"),
        (["identify", "--length-scale", "-1", "--", "1,0,0,0,0,0"], "positive"),
        (["identify", "--precision", "quad", "--", "1,0,0,0,0,0"], "precision"),
    ],
)
def test_identify_bad_input(argv, needle):
    code, _, err = run_cli(argv)
    assert code == 2 and needle in err and "Traceback" not in err


def test_identify_near_degenerate_is_not_a_guess():
    code, out, _ = run_cli(
        [
            "identify",
            "--precision",
            "float",
            "--format",
            "json",
            "--",
            "0,0,1,0,0,0",
            "0,1e-11,1,0,-1,0",
        ]
    )
    data = json.loads(out)
    assert code == 0 and data["status"] == "undecided" and data["type"] is None
