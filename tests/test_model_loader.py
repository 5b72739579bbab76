"""Reading valid mechanism files: units, exact numbers, U joints, inputs, output,
configurations and notes (mechsing.model.loader)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import sympy

from mechsing.cli import exit_status
from mechsing.model import (
    Displacement,
    InputRef,
    MechanismError,
    load,
    loads,
)
from tests.mechanisms import FOURBAR_JOINTS, TWO_LEAVES

DATA = Path(__file__).parent / "data"
pi = sympy.pi
R = sympy.Rational

FOURBAR = "\nmechanism: four-bar\n" + FOURBAR_JOINTS


def test_fourbar_mm_deg():
    m = load(DATA / "fourbar_deg.yaml")
    assert m.name == "four-bar-mm"
    assert m.bodies == ("ground", "crank", "coupler", "rocker")
    assert m.ground == "ground"
    assert [j.name for j in m.joints] == ["A", "B", "C", "D"]
    assert m.joint("C").params["point"] == (3, 2, 0)  # 3000 mm
    assert m.joint("A").params["axis"] == (0, 0, 1)  # normalised from [0, 0, 2]
    assert any("axis of joint 'A' normalised" in n for n in m.notes)
    assert m.joint("A").line == 6
    assert m.units.length == "mm" and m.units.angle == "deg"
    assert m.inputs == (InputRef("A"),)
    assert m.output.body == "rocker" and m.output.relative_to == "ground" and not m.output.default
    cfg = m.configurations
    assert list(cfg) == ["reference", "crank-30", "crank-200", "exact"]
    assert cfg["reference"].values == {} and cfg["reference"].start is None
    assert cfg["crank-30"].values["A"] == (pi / 6,)
    assert cfg["crank-30"].start == "reference"
    assert cfg["crank-200"].start == "crank-30"
    assert cfg["crank-200"].values["A"] == (10 * pi / 9,)
    assert cfg["exact"].values["B"] == (pi / 1800,)  # 0.1 degree, exactly
    assert m.dof == 4 and m.graph.num_loops == 1


def test_reference_always_present_and_first_when_missing():
    m = loads(FOURBAR + "configurations:\n  a: {A: 1}\n")
    assert list(m.configurations) == ["reference", "a"]
    m2 = loads(FOURBAR)
    assert list(m2.configurations) == ["reference"]


def test_reference_in_file_keeps_file_order():
    m = loads(FOURBAR + "configurations:\n  a: {A: 1}\n  reference: {A: 0}\n")
    assert list(m.configurations) == ["a", "reference"]
    assert m.configurations["reference"].start is None


def test_default_name_and_ground():
    m = loads(FOURBAR.replace("mechanism: four-bar\n", ""), default_name="thing")
    assert m.name == "thing"
    assert m.ground == "ground"


def test_explicit_ground_not_first():
    m = loads("ground: rocker\n" + FOURBAR)
    assert m.ground == "rocker"
    assert m.graph.tree_paths["rocker"] == ()


def test_exact_numbers_keep_their_text():
    text = FOURBAR.replace("point: [1, 0, 0]", "point: [0.1, 1e-3, 017]").replace(
        "point: [3, 2, 0]", 'point: ["1/3", "sqrt(2)/2", -0.25]'
    )
    m = loads(text)
    assert m.joint("B").params["point"] == (R(1, 10), R(1, 1000), 17)
    assert m.joint("C").params["point"] == (R(1, 3), sympy.sqrt(2) / 2, R(-1, 4))


def test_json_is_accepted(tmp_path):
    doc = {
        "mechanism": "arm",
        "units": {"length": "cm", "angle": "deg"},
        "bodies": ["ground", "link"],
        "joints": [
            {
                "name": "A",
                "type": "R",
                "between": ["ground", "link"],
                "axis": [0, 0, 1],
                "point": [10, 0, 0],
            },
        ],
        "configurations": {"up": {"A": 90}},
    }
    p = tmp_path / "arm.json"
    p.write_text(json.dumps(doc))
    m = load(p)
    assert m.joint("A").params["point"] == (R(1, 10), 0, 0)
    assert m.configurations["up"].values["A"] == (pi / 2,)
    assert m.output.body == "link" and m.output.default


def test_serial_mixed_units_u_joint_and_displacements():
    m = load(DATA / "serial_mixed.yaml")
    u = m.joint("U1")
    assert u.type == "U" and u.dof == 2 and u.is_composite
    assert u.hidden_body == "U1.cross"
    a1, a2 = u.params["axes"]
    assert a1 == (0, 0, 1)
    assert a2 == (sympy.sqrt(2) / 2, sympy.sqrt(2) / 2, 0)
    assert u.params["point"] == (0, 0, R(1, 10))
    h = m.joint("H1")
    assert h.params["pitch"] == R(1, 200)  # 0.5 cm per radian: degrees do not touch a pitch
    assert h.params["point"] == (R(1, 6), 0, R(1, 10))
    assert m.joint("P1").params["axis"] == (0, 0, -1)
    assert m.joint("S1").params["point"] == (R(1, 5), 0, sympy.sqrt(2) / 10)
    assert m.joint("C1").units == ("rad", "m")
    assert m.joint("W").dof == 0
    assert m.input_coordinates() == (("U1", 0), ("U1", 1), ("C1", 1), ("H1", 0), ("P1", 0))
    bent = m.configurations["bent"].values
    assert bent["U1"] == (pi / 2, -pi / 4)
    assert bent["C1"] == (pi / 6, R(1, 20))  # 30 deg, 5 cm
    assert bent["H1"] == (1,)  # "180/pi" degrees
    assert bent["P1"] == (R(1, 40),)  # 2.5 cm
    moved = m.configurations["moved"]
    assert moved.start == "bent"
    s1 = moved.values["S1"]
    assert isinstance(s1, Displacement) and s1.translation is None
    assert s1.rotation == ((1, 0, 0), (0, 0, -1), (0, 1, 0))
    c1 = moved.values["C1"]
    assert c1.translation == (R(1, 100), 0, 0)
    # a tree: no loop, the output defaults to the unique leaf
    assert m.graph.num_loops == 0
    assert m.output.body == "tool" and m.output.default and m.output.relative_to == "base"
    assert any("output defaulted" in n for n in m.notes)
    assert m.hidden_bodies == ("U1.cross",)


def test_tree_without_unique_leaf_has_no_output():
    m = loads(TWO_LEAVES)
    assert m.output is None
    assert m.legs == ()


def test_closed_mechanism_without_output_is_valid():
    m = loads(FOURBAR + "inputs: [A]\n")
    assert m.output is None and m.inputs == (InputRef("A"),)


def test_output_point_and_relative_to_and_characteristic_length():
    m = load(DATA / "ladder.yaml")
    assert m.output.body == "top" and m.output.relative_to == "middle"
    assert m.output.point == (R(1, 2), sympy.sqrt(3), 0)
    assert m.characteristic_length == R(1, 2)
    m2 = loads("units: {length: mm}\ncharacteristic_length: 250\n" + FOURBAR)
    assert m2.characteristic_length == R(1, 4)


def test_indexed_inputs():
    text = """
bodies: [ground, a, b]
joints:
  - {name: C1, type: C, between: [ground, a], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: D1, type: D, between: [a, b]}
inputs: ["C1[1]", "D1[5]", "D1 [0]"]
"""
    m = loads(text)
    assert m.inputs == (InputRef("C1", 1), InputRef("D1", 5), InputRef("D1", 0))
    assert str(m.inputs[0]) == "C1[1]"


def test_every_catalog_type_reads():
    from mechsing.subgroups import load_catalog

    values = {"direction": "[1, 2, 2]", "normal": "[0, 0, 1]", "point": "[1, 0, 0]", "pitch": "0.1"}
    for sym, t in load_catalog().items():
        geo = "".join(f", {k}: {values[kind]}" for k, kind in t.parameters)
        text = (
            "bodies: [ground, a]\njoints:\n"
            f"  - {{name: J, type: {sym}, between: [ground, a]{geo}}}\n"
        )
        m = loads(text)
        j = m.joint("J")
        assert j.dof == t.dimension
        assert set(j.params) == {k for k, _ in t.parameters}
        for k, kind in t.parameters:
            if kind == "direction":
                assert j.params[k] == (R(1, 3), R(2, 3), R(2, 3))


def test_values_in_file_units_per_coordinate_kind():
    text = """
units: {length: mm, angle: deg}
bodies: [ground, a]
joints:
  - {name: C1, type: C, between: [ground, a], axis: [0, 0, 1], point: [0, 0, 0]}
configurations:
  c: {C1: [180, 500]}
"""
    m = loads(text)
    assert m.configurations["c"].values["C1"] == (pi, R(1, 2))


def test_u_joint_graph_shape():
    m = load(DATA / "serial_mixed.yaml")
    G = m.graph.multigraph
    assert G.nodes["U1.cross"]["hidden"] is True
    assert G.has_edge("base", "U1.cross", key=("U1", 0))
    assert G.has_edge("U1.cross", "yoke", key=("U1", 1))
    assert not G.has_edge("base", "yoke")
    assert G.number_of_edges() == len(m.joints) + 1


def test_errors_are_user_errors_with_parts():
    with pytest.raises(MechanismError) as exc:
        loads(
            FOURBAR.replace(
                "axis: [0, 0, 1], point: [3, 2, 0]", "axis: [0, 0, 0], point: [3, 2, 0]"
            ),
            path="x.yaml",
        )
    e = exc.value
    assert exit_status(e) == 2 and e.path == "x.yaml" and e.line == 7 and e.item == "joint 'C'"
    assert str(e).startswith("x.yaml:7: joint 'C': ")


def test_unreadable_paths(tmp_path):
    with pytest.raises(MechanismError, match="cannot read"):
        load(tmp_path / "nope.yaml")
    with pytest.raises(MechanismError, match="directory"):
        load(tmp_path)
    p = tmp_path / "bin.yaml"
    p.write_bytes(b"\xff\xfe\x00bad")
    with pytest.raises(MechanismError, match="UTF-8"):
        load(p)


def test_near_zero_is_relative_to_the_file_scale():
    # in a mechanism 1000 units across, a direction of length 1e-7 is still refused,
    # and one of length 1e-3 is accepted (and normalised)
    big = FOURBAR.replace("point: [4, 0, 0]", "point: [4000, 0, 0]")
    with pytest.raises(MechanismError, match="too close to zero"):
        loads(
            big.replace(
                "[ground, crank],   axis: [0, 0, 1]", "[ground, crank],   axis: [0, 0, 1e-7]"
            )
        )
    m = loads(
        big.replace("[ground, crank],   axis: [0, 0, 1]", "[ground, crank],   axis: [0, 0, 0.001]")
    )
    assert m.joint("A").params["axis"] == (0, 0, 1)


def test_absurd_sizes_are_refused_quickly():
    import time

    # a ring of 1,990 bodies braced by triangles: every loop shares joints with the
    # next, so the closure system is one dense block of about 3,000 joints
    n = 1990
    bodies = ", ".join(f"b{i}" for i in range(n))
    joints = "".join(
        f"  - {{name: J{i}, type: R, between: [b{i}, b{(i + 1) % n}], axis: [0, 0, 1], "
        f"point: [{i}, 0, 0]}}\n"
        for i in range(n)
    )
    extra = "".join(
        f"  - {{name: K{i}, type: R, between: [b{i}, b{i + 2}], axis: [0, 0, 1], "
        f"point: [{i}, 1, 0]}}\n"
        for i in range(0, n - 2, 2)
    )
    t = time.perf_counter()
    with pytest.raises(MechanismError, match=r"too large a mechanism .* would take about \d+ s"):
        loads(f"bodies: [{bodies}]\njoints:\n{joints}{extra}")
    assert time.perf_counter() - t < 20
    many = ", ".join(f"b{i}" for i in range(3000))
    with pytest.raises(MechanismError, match="more than"):
        loads(f"bodies: [{many}]\njoints: []\n")
    with pytest.raises(MechanismError, match="more than"):
        loads("bodies: [a]\njoints: []\nmechanism: '" + "x" * (5 * 1024 * 1024) + "'\n")
