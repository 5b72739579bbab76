"""Named parameters of a mechanism file (``parameters:``): values, expressions of
earlier parameters, units, symbolic parameters, and the errors people meet."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import sympy

from mechsing.model.loader import load, loads
from mechsing.model.mechanism import MechanismError
from mechsing.model.parameters import ParameterSymbol
from tests.cli import run_cli

TWO_R = """\
mechanism: planar-2r
parameters: {{{params}}}
bodies: [ground, link1, link2]
joints:
  - {{name: A, type: R, between: [ground, link1], axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: B, type: R, between: [link1, link2], axis: [0, 0, 1], point: [{b}, 0, 0]}}
inputs: [A, B]
output: {{body: link2, point: [{p}, 0, 0]}}
configurations:
  bent: {{A: 0.3, B: {angle}}}
"""


def two_r(params: str, b: str = "a1", p: str = "a1 + a2", angle: str = "1") -> str:
    return TWO_R.format(params=params, b=b, p=p, angle=angle)


def test_values_are_exact_and_used_everywhere() -> None:
    m = loads(two_r('a1: 0.425, a2: "a1 - 0.033", bend: "pi/3"', angle="bend"))
    assert m.joint("B").params["point"][0] == sympy.Rational(17, 40)
    assert m.output.point[0] == sympy.Rational(17, 40) * 2 - sympy.Rational(33, 1000)
    assert m.configurations["bent"].values["B"] == (sympy.pi / 3,)


def test_a_parameter_takes_the_unit_of_the_place_it_is_used() -> None:
    text = two_r("a1: 425, a2: 392, bend: 90", angle="bend").replace(
        "bodies:", "units: {length: mm, angle: deg}\nbodies:"
    )
    m = loads(text)
    assert m.joint("B").params["point"][0] == sympy.Rational(17, 40)  # 425 mm in metres
    assert m.configurations["bent"].values["B"] == (sympy.pi / 2,)  # 90 degrees in radians


def test_analysis_is_the_same_as_with_the_numbers_written_out(tmp_path: Path) -> None:
    with_names = tmp_path / "named.yaml"
    with_names.write_text(two_r("a1: 0.425, a2: 0.392"))
    written = tmp_path / "written.yaml"
    written.write_text(two_r("", b="0.425", p="0.817").replace("parameters: {}\n", ""))
    a = run_cli(["analyze", with_names, "--format", "json"])
    b = run_cli(["analyze", written, "--format", "json"])
    assert a.status == b.status == 0
    ja, jb = json.loads(a.out), json.loads(b.out)
    assert ja["configurations"] == jb["configurations"]


def test_symbolic_parameters_stay_symbols_that_know_their_value() -> None:
    m = loads(two_r('a1: 0.5, a2: "2*a1"'), symbolic=["a1"])
    x = m.output.point[0]
    (s,) = x.atoms(ParameterSymbol)
    assert s.name == "a1" and s.is_positive
    assert sympy.simplify(x - 3 * s) == 0  # a2 = 2*a1 follows the symbol
    assert float(sympy.N(x)) == pytest.approx(1.5)


@pytest.mark.parametrize(
    ("params", "where", "says"),
    [
        ('a1: 1, a2: "a3 + 1", a3: 2', "parameter 'a2'", "move 'a3' (line 2) above 'a2'"),
        ('a1: "a1 + 1", a2: 1', "parameter 'a1'", "cannot be defined by itself"),
        ('a1: 1, a2: "b2 * 2"', "parameter 'a2'", "the name 'b2'"),
        ("A: 1, a1: 1, a2: 1", "parameter 'A'", "clashes with the joint 'A'"),
        ("link1: 1, a1: 1, a2: 1", "parameter 'link1'", "clashes with the body 'link1'"),
        ("pi: 3, a1: 1, a2: 1", "parameter 'pi'", "the constant pi"),
        ("sqrt: 3, a1: 1, a2: 1", "parameter 'sqrt'", "a function of expressions"),
        ("a1: 1, a2: [1, 2]", "parameter 'a2'", "must be a number or an expression"),
    ],
)
def test_errors_name_the_parameter_the_line_and_the_fix(
    tmp_path: Path, params: str, where: str, says: str
) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(two_r(params))
    with pytest.raises(MechanismError) as info:
        load(path)
    assert info.value.line == 2
    assert info.value.item == where
    assert says in str(info.value)
    run = run_cli(["analyze", path])
    assert run.status == 2
    assert f"bad.yaml:2: {where}" in run.err


def test_an_unknown_name_in_a_joint_lists_the_parameters(tmp_path: Path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(two_r("a1: 1, a2: 1", b="a9"))
    run = run_cli(["analyze", path])
    assert run.status == 2
    assert "bad.yaml:6: joint 'B'" in run.err
    assert "the name 'a9' (not a parameter; parameters: a1, a2)" in run.err


def test_the_schema_describes_parameters() -> None:
    jsonschema = pytest.importorskip("jsonschema")
    import yaml

    from mechsing.model.schema import mechanism_schema

    schema = mechanism_schema()
    assert "parameters" in schema["properties"]
    doc = yaml.safe_load(two_r('a1: 0.425, a2: "a1/2"'))
    jsonschema.validate(doc, schema)
    doc["parameters"]["2bad"] = 1
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(doc, schema)
    run = run_cli(["schema"])
    assert run.status == 0 and '"parameters"' in run.out
