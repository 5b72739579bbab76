"""XML from anywhere: hostile or unmodellable descriptions are exit 2 with the element and its
line, never a traceback, and never a file or network access."""

from __future__ import annotations

import json
import socket

import pytest

from tests.cli import run_cli, runtime_warnings

BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE lolz [
 <!ENTITY lol "lol">
 <!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
 <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
 <!ENTITY lol9 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
]>
<robot name="&lol9;"><link name="a"/></robot>
"""
FILE_ENTITY = """<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY xxe SYSTEM "file:///etc/passwd">]>
<robot name="x"><link name="&xxe;"/></robot>
"""
HTTP_ENTITY = """<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY % ext SYSTEM "http://example.invalid/evil.dtd"> %ext;]>
<robot name="x"><link name="a"/></robot>
"""
DOCTYPE_AFTER_COMMENT = """<!-- hello -->
<!DOCTYPE mujoco SYSTEM "http://example.invalid/x.dtd">
<mujoco/>
"""
HUGE_ATTRIBUTE = '<robot name="x">\n<link name="' + "a" * 200_000 + '"/>\n</robot>\n'


def _urdf(joints: str, links: str | list[str] = "abc") -> str:
    body = "".join(f'<link name="{n}"/>\n' for n in links)
    return f'<robot name="r">\n{body}{joints}</robot>\n'


UNKNOWN_TYPE = _urdf('<joint name="J" type="screw">\n<parent link="a"/><child link="b"/></joint>\n')
CYCLE = _urdf(
    '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/></joint>\n'
    '<joint name="J2" type="revolute"><parent link="b"/><child link="c"/></joint>\n'
    '<joint name="J3" type="revolute"><parent link="c"/><child link="a"/></joint>\n'
)
TWO_PARENTS = _urdf(
    '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/></joint>\n'
    '<joint name="J2" type="revolute"><parent link="c"/><child link="b"/></joint>\n'
)
MIMIC = _urdf(
    '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/></joint>\n'
    '<joint name="J2" type="revolute"><parent link="b"/><child link="c"/>\n'
    '  <mimic joint="J1" multiplier="2"/></joint>\n'
)
MJCF_UNKNOWN = (
    '<mujoco>\n<worldbody>\n<body><joint type="screw"/></body>\n</worldbody>\n</mujoco>\n'
)
MJCF_INCLUDE = '<mujoco>\n<include file="/etc/passwd"/>\n<worldbody/>\n</mujoco>\n'
MJCF_TENDON = (
    '<mujoco><worldbody><body><joint name="a"/></body></worldbody>\n'
    '<equality>\n<joint joint1="a"/>\n</equality></mujoco>\n'
)
BAD_NAME = _urdf(
    '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/></joint>\n'
    '<joint name="q[1]" type="revolute"><parent link="b"/><child link="c"/></joint>\n'
)
MALFORMED = '<robot name="x">\n<link name="a">\n</robot>\n'
HUGE_ORIGIN = _urdf(
    '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/>\n'
    '<origin xyz="1e300 0 0"/></joint>\n',
    "ab",
)
UNDERSCORE_NUMBER = _urdf(
    '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/>\n'
    '<origin xyz="1_000 0 0"/></joint>\n',
    "ab",
)
FULLWIDTH_NUMBER = _urdf(
    '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/>\n'
    '<axis xyz="0 0 \uff11"/></joint>\n',
    "ab",
)
NAN_NUMBER = _urdf(
    '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/>\n'
    '<axis xyz="0 0 nan"/></joint>\n',
    "ab",
)
MJCF_HUGE_QUAT = (
    '<mujoco>\n<worldbody>\n<body quat="1e308 1e308 0 0"><joint/></body>\n</worldbody>\n</mujoco>\n'
)
MJCF_HUGE_ZAXIS = (
    '<mujoco>\n<worldbody>\n<body zaxis="1e308 1e308 0"><joint/></body>\n</worldbody>\n</mujoco>\n'
)
MJCF_ZERO_QUAT = (
    '<mujoco>\n<worldbody>\n<body quat="0 0 0 0"><joint/></body>\n</worldbody>\n</mujoco>\n'
)
# names YAML cannot carry (C1 controls, NEL, line separators): named at the XML element,
# not as "malformed YAML ... line 7" of a converted text the user never saw
C1_LINK_NAME = _urdf(
    '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/></joint>\n',
    ["a", "b\x85x", "b"],
)
C1_JOINT_NAME = _urdf(
    '<joint name="J\x81" type="revolute"><parent link="a"/><child link="b"/></joint>\n', "ab"
)
MJCF_NEL_BODY = (
    '<mujoco>\n<worldbody>\n<body name="arm\x85"><joint/></body>\n</worldbody>\n</mujoco>\n'
)
MJCF_SEPARATOR_MODEL = '<mujoco model="m\u2028x">\n<worldbody/>\n</mujoco>\n'
MJCF_PARALLEL_XYAXES = (
    '<mujoco>\n<worldbody>\n<body xyaxes="1 0 0 2 0 0"><joint/></body>\n</worldbody>\n</mujoco>\n'
)

CASES = {
    "billion_laughs": (BILLION_LAUGHS, "DOCTYPE", 2),
    "file_entity": (FILE_ENTITY, "DOCTYPE", 2),
    "http_entity": (HTTP_ENTITY, "DOCTYPE", 2),
    "doctype_after_comment": (DOCTYPE_AFTER_COMMENT, "DOCTYPE", 2),
    "huge_attribute": (HUGE_ATTRIBUTE, "characters", 2),
    "unknown_type": (UNKNOWN_TYPE, "unknown joint type 'screw'", 5),
    "cycle": (CYCLE, "cycle", None),
    "two_parents": (TWO_PARENTS, "already the child", 6),
    "mjcf_unknown_type": (MJCF_UNKNOWN, "unknown joint type 'screw'", 3),
    "mjcf_include": (MJCF_INCLUDE, "include", 2),
    "mjcf_joint_coupling": (MJCF_TENDON, "cannot be modelled", 3),
    "malformed": (MALFORMED, "malformed XML", 3),
    "bad_joint_name": (BAD_NAME, "holds '[' or ']'", 6),
    # numbers: ASCII decimal syntax and a sensible size (at most 1e12), as the YAML's
    "urdf_huge_origin": (HUGE_ORIGIN, "'1e300' is too large", 5),
    "urdf_underscore_number": (UNDERSCORE_NUMBER, "ASCII decimal digits", 5),
    "urdf_fullwidth_number": (FULLWIDTH_NUMBER, "ASCII decimal digits", 5),
    "urdf_nan": (NAN_NUMBER, "ASCII decimal digits", 5),
    "mjcf_huge_quat": (MJCF_HUGE_QUAT, "'1e308' is too large", 3),
    "mjcf_huge_zaxis": (MJCF_HUGE_ZAXIS, "'1e308' is too large", 3),
    "mjcf_zero_quat": (MJCF_ZERO_QUAT, "degenerate (a zero vector has no direction)", 3),
    "mjcf_parallel_xyaxes": (MJCF_PARALLEL_XYAXES, "two directions are parallel", 3),
    "urdf_c1_link_name": (C1_LINK_NAME, "the link name 'b\\x85x' holds U+0085", 3),
    "urdf_c1_joint_name": (C1_JOINT_NAME, "the joint name 'J\\x81' holds U+0081", 4),
    "mjcf_nel_body_name": (MJCF_NEL_BODY, "the body name 'arm\\x85' holds U+0085", 3),
    "mjcf_separator_model_name": (MJCF_SEPARATOR_MODEL, "holds U+2028 (a line or paragraph", 1),
}


@pytest.fixture
def no_network(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("network access attempted")

    monkeypatch.setattr(socket.socket, "connect", refuse)
    monkeypatch.setattr(socket, "create_connection", refuse)


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("command", ["analyze", "convert"])
def test_hostile_xml_is_bad_input(case: str, command: str, tmp_path, no_network) -> None:
    text, words, line = CASES[case]
    f = tmp_path / "robot.xml"
    f.write_text(text)
    r = run_cli([command, str(f)])
    assert r.status == 2, (r.status, r.err)
    assert "Traceback" not in r.err and "internal error" not in r.err
    assert words in r.err
    assert str(f) in r.err
    if line is not None:
        assert f"{f}:{line}:" in r.err
    assert "root:" not in r.err + r.out  # nothing of /etc/passwd


def test_a_mimic_is_read_as_a_coupling_and_analysed(tmp_path) -> None:
    f = tmp_path / "robot.xml"
    f.write_text(MIMIC)
    r = run_cli(["analyze", str(f)])
    assert r.status == 0 and "coupling J2 = 2 x J1 (<mimic>, line 7)" in r.out, r.err
    r = run_cli(["convert", str(f)])
    assert r.status == 0, r.err
    assert '{joint: "J2", leader: "J1", multiplier: 2.0, offset: 0.0, source_line: 7}' in r.out
    assert 'inputs: ["J1"]' in r.out  # a mimic joint is driven by its leader


@pytest.mark.parametrize(
    ("mimic", "words"),
    [
        ("<mimic/>", 'add joint="..."'),
        ('<mimic joint="J2"/>', "cannot mimic itself"),
        ('<mimic joint="F"/>', "joint 'F' is fixed"),
        ('<mimic joint="J1" multiplier="x"/>', "multiplier"),
    ],
)
def test_a_bad_mimic_is_exit_2_on_its_line(mimic: str, words: str, tmp_path) -> None:
    f = tmp_path / "robot.xml"
    f.write_text(
        _urdf(
            '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/></joint>\n'
            '<joint name="F" type="fixed"><parent link="b"/><child link="d"/></joint>\n'
            '<joint name="J2" type="revolute"><parent link="b"/><child link="c"/>\n'
            f"  {mimic}</joint>\n",
            links="abcd",
        )
    )
    r = run_cli(["convert", str(f)])
    assert r.status == 2 and words in r.err and f"{f}:9:" in r.err, r.err


def _gripper(mimic_a: str, mimic_b: str) -> str:
    """An arm J1 (a -> b) with a fixed finger F (b -> d) and a sliding finger J2 (b -> c)."""
    return _urdf(
        '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/></joint>\n'
        f'<joint name="F" type="fixed"><parent link="b"/><child link="d"/>{mimic_a}</joint>\n'
        '<joint name="J2" type="prismatic"><parent link="b"/><child link="c"/>\n'
        f"  {mimic_b}</joint>\n",
        links="abcd",
    )


def test_a_mimic_of_a_fixed_joint_couples_nothing_and_is_ignored(tmp_path) -> None:
    f = tmp_path / "robot.urdf"
    f.write_text(_gripper('<mimic joint="J1"/>', ""))
    r = run_cli(["convert", str(f)])
    assert r.status == 0 and "couplings" not in r.out.replace("# the <mimic>", ""), r.out
    assert "the <mimic> of the fixed joint 'F' (line 7) is ignored" in r.out
    assert run_cli(["analyze", str(f)]).status == 0


def test_a_mimic_of_an_undefined_joint_is_refused_only_where_analysed(tmp_path) -> None:
    f = tmp_path / "robot.urdf"
    f.write_text(_gripper("", '<mimic joint="J9"/>'))
    r = run_cli(["analyze", str(f)])
    assert r.status == 2 and f"{f}:9:" in r.err, r.err
    assert "names joint 'J9', which the robot does not define" in r.err
    # the finger left out (an output on the arm's body b): analysed
    r = run_cli(["analyze", str(f), "--output-body", "b", "--format", "json"])
    assert r.status == 0, r.err
    assert json.loads(r.out)["scene"]["dropped_couplings"] == ["J2"]


@pytest.mark.parametrize("case", CASES)
def test_no_runtime_warning_on_hostile_xml(case: str, tmp_path) -> None:
    f = tmp_path / "robot.xml"
    f.write_text(CASES[case][0])
    assert runtime_warnings(["analyze", str(f)]) == []


def test_a_yaml_file_is_not_converted(tmp_path) -> None:
    r = run_cli(["convert", "examples/fourbar.yaml"])
    assert r.status == 2 and "needs no conversion" in r.err


def test_a_huge_file_is_refused(tmp_path) -> None:
    f = tmp_path / "big.urdf"
    f.write_text('<robot name="x">\n' + "<!-- padding -->\n" * 700_000 + "</robot>\n")
    for command in ("analyze", "convert"):
        r = run_cli([command, str(f)])
        assert r.status == 2 and ("MB" in r.err or "bytes" in r.err), r.err
        assert "Traceback" not in r.err


def _nested_mjcf(depth: int) -> str:
    """A chain of ``depth`` bodies, each inside the one before, each with a hinge about z
    through its own origin, the next body 1 m further along x."""
    opening = "".join(
        f'<body name="b{i}" pos="1 0 0"><joint name="j{i}" axis="0 0 1"/>\n' for i in range(depth)
    )
    return f"<mujoco>\n<worldbody>\n{opening}{'</body>' * depth}\n</worldbody>\n</mujoco>\n"


def test_bodies_nested_up_to_the_depth_limit_are_read(tmp_path) -> None:
    # mujoco, worldbody, 497 bodies and a joint: 500 levels, the parser's limit (MAX_DEPTH);
    # 493 to 498 bodies were a RecursionError (exit 4) before
    f = tmp_path / "deep.xml"
    f.write_text(_nested_mjcf(497))
    r = run_cli(["convert", str(f)])
    assert r.status == 0, r.err
    assert r.out.count("type: R") == 497
    # the last joint's axis passes through the last body's origin, 497 m along x
    assert '{name: "j496", type: R, between: ["b495", "b496"], axis: [0, 0, 1], ' in r.out
    assert "point: [497, 0, 0]}" in r.out
    f.write_text(_nested_mjcf(498))
    r = run_cli(["convert", str(f)])
    assert r.status == 2 and "nested more than 500 levels deep" in r.err, r.err


def test_nested_default_classes_up_to_the_depth_limit(tmp_path) -> None:
    depth = 490
    classes = "".join(f'<default class="c{i}">' for i in range(depth))
    f = tmp_path / "classes.xml"
    f.write_text(
        f'<mujoco>\n<default>\n{classes}<joint axis="0 1 0"/>{"</default>" * depth}\n'
        f'</default>\n<worldbody>\n<body childclass="c{depth - 1}"><joint/></body>\n'
        "</worldbody>\n</mujoco>\n"
    )
    r = run_cli(["convert", str(f)])
    assert r.status == 0, r.err
    assert "axis: [0, 1, 0]" in r.out  # the innermost class's axis
