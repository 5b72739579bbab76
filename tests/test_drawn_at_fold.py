"""A configuration drawn at a fold to its data's digits, at an explicit mp:N (issue 44).

The double rocker of examples/double_rocker.yaml has its input's limits at A = +-2 pi/3
(law of cosines in the file's comment: B, C, D aligned, |BD| = 7): there the output can
move with the input locked (Gosselin-Angeles type II).  Written to 15 digits, 2 pi/3 rounds
up to 2.09439510239320, 4.5e-15 rad beyond the limit and within the value's resolution
(5e-15): mp:50 analyses the limit itself, placed at 50 digits, and says so, instead of
refusing "beyond a limit of travel".  The flat parallelogram given by its input at 15 digits
(-1.57079632679490, 3.2e-15 from -pi/2, where the parallelogram and anti-parallelogram
branches cross) is analysed at the nearest closed configuration, not refused."""

from __future__ import annotations

import json
import math
from pathlib import Path

from tests.cli import run_cli

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
ROOT_DATA = Path(__file__).resolve().parent / "data"


def _with_configuration(tmp_path: Path, example: str, line: str) -> Path:
    text = (EXAMPLES / example).read_text()
    head = text[: text.index("configurations:")]
    out = tmp_path / example
    out.write_text(head + "configurations:\n  reference: {}\n" + line + "\n")
    return out


def test_double_rocker_drawn_at_its_limit_is_analysed_at_the_limit_at_mp50(tmp_path):
    path = _with_configuration(tmp_path, "double_rocker.yaml", "  limit: {A: 2.09439510239320}")
    run = run_cli(
        ["analyze", path, "--precision", "mp:50", "--config", "limit", "--format", "json"]
    )
    assert run.status in (0, 1), run.err
    assert "beyond a limit of travel" not in run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert "error" not in conf
    # the limit in closed form: A = 2 pi/3
    assert math.isclose(conf["joints"]["A"][0], 2 * math.pi / 3, abs_tol=1e-15)
    classes = {s["class"] for s in conf["singularities"]}
    assert "output" in classes  # type II at a limit of the input (Gosselin-Angeles 1990)
    out = next(d for d in conf["decisions"] if d["test"] == "output")
    assert out["margin"]["dropped"] is not None and out["margin"]["dropped"] < 1e-40
    assert any("within the resolution of its 15-digit data" in n for n in conf["notes"])
    assert not any("float places them only" in n for n in conf["notes"])


def test_flat_parallelogram_given_by_its_input_to_15_digits_is_not_refused_at_mp50(tmp_path):
    path = _with_configuration(tmp_path, "parallelogram.yaml", "  flat: {A: -1.57079632679490}")
    run = run_cli(["analyze", path, "--precision", "mp:50", "--config", "flat", "--format", "json"])
    assert run.status in (0, 1), run.err
    assert "beyond" not in run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert "error" not in conf
    assert abs(conf["joints"]["A"][0] + math.pi / 2) < 5e-15  # within the data's resolution
    assert any("nearest closed configuration" in n for n in conf["notes"])


WRIST_AT_A_POSE = """\
mechanism: zyz-wrist
bodies: [g, a, b, c]
joints:
  - {name: W1, type: R, between: [g, a], axis: [0, 0, 1], point: [0, 0, 1]}
  - {name: W2, type: R, between: [a, b], axis: [0, 1, 0], point: [0, 0, 1]}
  - {name: W3, type: R, between: [b, c], axis: [0, 0, 1], point: [0, 0, 1]}
output: {body: c}
configurations:
  reference: {}
  drawn: {pose: {rotation_vector: [5.8e-18, 0, 0.500000000000000]}}
"""


def test_a_wrist_given_by_a_pose_drawn_at_its_singularity_is_analysed_there_at_mp50(tmp_path):
    """A Z-Y-Z spherical wrist given the output's rotation vector (5.8e-18, 0, 0.5), its
    rotation written to 15 digits (known to 5e-16 rad): within that, the rotation is the
    turn by 0.5 rad about z, where the Z-Y-Z angles are W2 = 0, W1 + W3 = 0.5 (the wrist's
    singularity: axes W1 and W3 aligned, the chain of rank 2).  Continuation at 50 digits
    from the reference (W2 = 0 already) stops there, the lost direction being the one the
    5.8e-18 asks for; the analysis is of the nearest closed configuration, with a note, not
    a refusal "beyond a limit of travel"."""
    path = tmp_path / "wrist.yaml"
    path.write_text(WRIST_AT_A_POSE)
    run = run_cli(
        ["analyze", path, "--precision", "mp:50", "--config", "drawn", "--format", "json"]
    )
    assert run.status in (0, 1), run.err
    assert "beyond a limit of travel" not in run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert "error" not in conf
    joints = conf["joints"]
    assert abs(joints["W2"][0]) < 1e-40  # the Z-Y-Z middle angle of a turn about z
    assert math.isclose(joints["W1"][0] + joints["W3"][0], 0.5, abs_tol=1e-15)
    assert conf["singular"] is True
    assert {s["class"] for s in conf["singularities"]} == {"serial"}
    (serial,) = conf["singularities"]
    assert serial["corank"] == 1 and serial["margin"]["dropped"] < 1e-40
    (note,) = [n for n in conf["notes"] if "written pose" in n]
    assert "within the resolution of its 15-digit data (its rotation to 5e-16 rad)" in note
    assert "pose.rx moved by 5.8e-18 rad" in note


def test_a_wrist_given_a_pose_a_hair_off_its_singularity_in_short_decimals_at_mp50(tmp_path):
    """The same wrist given (5.8e-18, 0, 0.5), short decimals: exact data, 5.8e-18 rad off
    the singularity (not within a resolution of it).  The pose is reachable (a Z-Y-Z
    wrist reaches every rotation), but only by turning W1 and W3 along the singularity's
    self-motion until W2's axis lies along the tilt asked for; continuation at 50 digits
    stopped at the singularity and refused it "beyond a limit of travel".  Now the given
    pose itself is analysed, regular at 50 digits.  Against the Z-Y-Z angles of the
    rotation, worked here with mpmath (Rodrigues' formula at 60 digits): |W2| is the tilt
    of the rotated z axis, W1 its direction (up to pi with the sign of W2), W1 + W3 = 0.5."""
    import mpmath

    path = tmp_path / "wrist.yaml"
    path.write_text(WRIST_AT_A_POSE.replace("0.500000000000000", "0.5"))
    run = run_cli(
        ["analyze", path, "--precision", "mp:50", "--config", "drawn", "--format", "json"]
    )
    assert run.status == 0, run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert "error" not in conf and conf["singular"] is False
    with mpmath.workdps(60):
        w = mpmath.matrix([mpmath.mpf("5.8e-18"), 0, mpmath.mpf("0.5")])
        th = mpmath.norm(w)
        k = w / th
        K = mpmath.matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        R = mpmath.eye(3) + mpmath.sin(th) * K + (1 - mpmath.cos(th)) * K * K
        tilt = mpmath.atan2(mpmath.hypot(R[0, 2], R[1, 2]), R[2, 2])
        direction = float(mpmath.atan2(R[1, 2], R[0, 2]))
    j = conf["joints"]
    w1, w2, w3 = j["W1"][0], j["W2"][0], j["W3"][0]
    assert math.isclose(abs(w2), float(tilt), rel_tol=1e-9)
    turned = w1 if w2 > 0 else w1 + math.pi
    assert abs(math.remainder(turned - direction, 2 * math.pi)) < 1e-12
    assert math.isclose(w1 + w3, 0.5, abs_tol=1e-15)
    assert any("self-motion" in n for n in conf["notes"])


def test_a_3rrr_given_a_pose_at_its_fold_to_15_digits(tmp_path):
    """tests/data/planar_3rrr.yaml: its platform turned by rz about its centre (held at
    the origin) stretches the three legs at once at cos(rz) = 1/8 (the file's comment:
    |A_i C_i|^2 = 17/4 - 2 cos(rz), legs of 1 + 1), a limit of travel of rz.  Given
    rz = 1.44546849562683, acos(1/8) to 15 digits (5e-15 rad), the position exact: mp:50
    refused it "beyond a limit of travel" (the nearest closed configuration moved the
    exact position, not the rotation written with digits to spare), and auto, which
    re-decides at mp:50, refused it too.  Now mp:50 analyses the nearest closed
    configuration, the rotation moved within its resolution, with a note; auto keeps
    float's analysis and says so."""
    path = tmp_path / "rrr.yaml"
    text = (ROOT_DATA / "planar_3rrr.yaml").read_text()
    path.write_text(
        text.replace(
            "  reference: {}",
            "  reference: {}\n  fold: {pose: {position: [0, 0, 0], rotation_vector: [0, 0, "
            "1.44546849562683]}}",
        )
    )
    run = run_cli(["analyze", path, "--precision", "mp:50", "--config", "fold", "--format", "json"])
    assert run.status in (0, 1), run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert "error" not in conf
    assert abs(conf["pose"]["rotation"][0][0] - 1 / 8) < 5e-15
    assert conf["pose"]["position"] == [0.0, 0.0, 0.0]
    (note,) = [n for n in conf["notes"] if "nearest closed configuration" in n]
    assert "within the resolution of its 15-digit data (its rotation to 5e-15 rad)" in note
    run = run_cli(["analyze", path, "--config", "fold", "--format", "json"])
    assert run.status in (0, 1), run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert "error" not in conf
    assert any("float closes them within its tolerance" in n for n in conf["notes"])
