"""mechsing modes: every assembly mode of a configuration (issue 34).

The counts and the modes come from an independent solver (tests/reference/
modes_independent.py: Gosselin's elimination scanned in the platform angle, and a
circle intersection), never from mechsing; each mode's classification is compared with
``mechsing analyze`` of the same joint values; the command runs as a user runs it, in
an empty directory that must stay empty.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from tests.cli import run_cli, run_cli_subprocess
from tests.mechanisms import ROOT
from tests.reference.modes_independent import circle_points, rpr_poses

SIX = ROOT / "examples" / "planar_3rpr_six.yaml"
FOURBAR = ROOT / "examples" / "fourbar.yaml"
# the 3-RPR's data as its file states them (base pivots, platform pivots in the
# platform's frame, reference offset of the platform, leg lengths of configuration six)
A = np.array([[0, 0], [8, 0], [-4, 11]], float)
B_FRAME = np.array([[0, 0], [6, 0], [11, 6]], float)
OFFSET = np.array([3, 4], float)
LENGTHS = np.array([11, 12, 8], float)


def _rot(theta: float) -> np.ndarray:
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, -s], [s, c]])


@pytest.fixture(scope="module")
def six(tmp_path_factory: pytest.TempPathFactory) -> dict:
    """The modes of the 3-RPR's configuration six, run as a user runs the command, in an
    empty working directory (listed afterwards: nothing may be written there)."""
    cwd = tmp_path_factory.mktemp("cwd")
    rc, out, err = run_cli_subprocess(
        ["modes", str(SIX), "--config", "six", "--format", "json"], timeout=300, cwd=cwd
    )
    assert rc == 0, err
    assert list(cwd.iterdir()) == [], "modes wrote into the working directory"
    return json.loads(out)


def _pivots(joints: dict) -> np.ndarray:
    """The platform pivots B_i from a mode's joint values (leg i: Rb_i at A_i, then the
    slide P_i along A_i B_i of the reference)."""
    out = []
    for i in range(3):
        ref = B_FRAME[i] + OFFSET - A[i]
        u = ref / np.linalg.norm(ref)
        out.append(A[i] + _rot(joints[f"Rb{i + 1}"][0]) @ (ref + joints[f"P{i + 1}"][0] * u))
    return np.array(out)


def test_3rpr_has_six_proven_certified_modes_matching_the_independent_solver(six: dict) -> None:
    poses = rpr_poses(A, B_FRAME, LENGTHS)
    assert len(poses) == 6  # the geometry was built to have six
    assert six["count"] == 6 and six["complete"] == "proven"
    assert all(m["certified"] for m in six["modes"])
    matched = set()
    for m in six["modes"]:
        B = _pivots(m["joints"])
        # every leg has its length to 1e-12 m
        assert np.allclose(np.linalg.norm(B - A, axis=1), LENGTHS, atol=1e-12, rtol=0)
        # the platform is rigid: the pivots are a pose of the platform's frame
        hits = [
            k
            for k, (theta, p) in enumerate(poses)
            if np.allclose(B, (_rot(theta) @ B_FRAME.T).T + p, atol=1e-8)
        ]
        assert len(hits) == 1
        matched.add(hits[0])
    assert matched == set(range(6))  # none counted twice, none missed


def test_each_mode_is_classified_as_analyze_classifies_it(six: dict) -> None:
    argv = ["analyze", str(SIX), "--format", "json"]
    for k, m in enumerate(six["modes"], 1):
        for name, values in m["joints_text"].items():
            argv += ["--set", f"m{k}:{name}={values[0]}"]
    rc, out, err = run_cli(argv)
    assert rc == 0, err
    by_name = {c["name"]: c for c in json.loads(out)["configurations"]}
    for k, m in enumerate(six["modes"], 1):
        ref = by_name[f"m{k}"]
        assert m["singular"] == ref["singular"]
        assert [s["class"] for s in m["singularities"]] == [
            s["class"] for s in ref["singularities"]
        ]


def test_continuation_reaches_one_marked_mode(six: dict) -> None:
    rc, out, err = run_cli(["solve", str(SIX), "--config", "six", "--format", "json"])
    assert rc == 0, err
    solved = json.loads(out)["joints"]
    marked = [m for m in six["modes"] if m["reached_by_continuation"]]
    assert len(marked) == 1
    for name, values in solved.items():
        assert np.allclose(marked[0]["joints"][name], values, atol=1e-9)


def test_distances_between_modes_are_a_metric(six: dict) -> None:
    for key in ("joints", "pose"):
        D = np.array(six["distances"][key])
        assert D.shape == (6, 6)
        assert np.allclose(np.diag(D), 0) and np.allclose(D, D.T)
        assert (D[~np.eye(6, dtype=bool)] > 1e-6).all()  # the modes are distinct


def test_the_document_follows_its_schema(six: dict) -> None:
    import jsonschema

    rc, out, _ = run_cli(["schema", "--modes"])
    assert rc == 0
    jsonschema.validate(six, json.loads(out))


def test_fourbar_has_two_modes_the_circles_give() -> None:
    """Crank at 30 deg (the file is in degrees): the rocker's pin C lies on the circle
    about the crank's end B of radius |BC| and the circle about the pivot D of radius
    |DC|; the two intersections are the two modes."""
    rc, out, err = run_cli(["modes", str(FOURBAR), "--set", "A=30", "--format", "json"])
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["count"] == 2 and doc["complete"] == "proven"
    b_ref, c_ref, d = np.array([1.0, 0]), np.array([3.0, 2]), np.array([4.0, 0])
    b = _rot(np.pi / 6) @ b_ref
    expected = circle_points(b, np.linalg.norm(c_ref - b_ref), d, np.linalg.norm(c_ref - d))
    got = []
    for m in doc["modes"]:
        # D is between [rocker, ground]: the rocker turns by -D about the pivot
        got.append(d + _rot(-m["joints"]["D"][0]) @ (c_ref - d))
        assert m["certified"]
    for e in expected:
        assert min(np.linalg.norm(e - g) for g in got) < 1e-12
    assert sum(m["reached_by_continuation"] for m in doc["modes"]) == 1


def test_text_and_markdown_say_the_count_and_the_marked_mode() -> None:
    for fmt, head in (("text", "four-bar"), ("md", "# four-bar")):
        rc, out, err = run_cli(["modes", str(FOURBAR), "--config", "crank-30", "--format", fmt])
        assert rc == 0, err
        assert out.startswith(head) and "2 assembly modes (complete: proven" in out
        assert out.count("reached by continuation") == 1


def test_no_method_applies_exit_2_with_the_reason(tmp_path: Path) -> None:
    # Bennett's 4R with its third joint helical: neither planar, nor a platform on distance
    # legs, nor a loop of R and P joints, nor polynomial in the general formulation
    text = (ROOT / "examples" / "bennett.yaml").read_text()
    text = text.replace("{name: J3, type: R,", "{name: J3, type: H, pitch: 0.1,")
    f = tmp_path / "helical.yaml"
    f.write_text(text)
    rc, _, err = run_cli(["modes", str(f), "--set", "J1=1"])
    assert rc == 2
    assert "does not apply" in err and "not the planar motions G" in err
    assert "not U-P-S or S-P-S" in err
    assert "joint J3 is of type H" in err and "not polynomial in its angle" in err


def test_no_given_value_is_refused_not_counted() -> None:
    rc, _, err = run_cli(["modes", str(FOURBAR), "--config", "reference"])
    assert rc == 2 and "gives no joint value" in err


CONGRUENT = """\
mechanism: 3rpr-congruent
bodies: [ground, cyl1, pis1, cyl2, pis2, cyl3, pis3, platform]
joints:
  - {name: Rb1, type: R, between: [ground, cyl1],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: P1, type: P, between: [cyl1, pis1],     axis: [1, 1, 0]}
  - {name: Rp1, type: R, between: [pis1, platform], axis: [0, 0, 1], point: [1, 1, 0]}
  - {name: Rb2, type: R, between: [ground, cyl2],   axis: [0, 0, 1], point: [4, 0, 0]}
  - {name: P2, type: P, between: [cyl2, pis2],     axis: [1, 1, 0]}
  - {name: Rp2, type: R, between: [pis2, platform], axis: [0, 0, 1], point: [5, 1, 0]}
  - {name: Rb3, type: R, between: [ground, cyl3],   axis: [0, 0, 1], point: [0, 4, 0]}
  - {name: P3, type: P, between: [cyl3, pis3],     axis: [1, 1, 0]}
  - {name: Rp3, type: R, between: [pis3, platform], axis: [0, 0, 1], point: [1, 5, 0]}
inputs: [P1, P2, P3]
output: {body: platform}
configurations:
  equal: {P1: 0, P2: 0, P3: 0}
"""


def test_a_curve_of_closed_configurations_gets_no_count(tmp_path: Path) -> None:
    """Platform congruent to the base with three parallel legs of equal length: the
    platform translates on a circle without turning (a parallelogram in each pair of
    legs), so there is no finite set of modes and no count."""
    path = tmp_path / "congruent.yaml"
    path.write_text(CONGRUENT)
    rc, out, err = run_cli(["modes", str(path), "--config", "equal", "--format", "json"])
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["count"] is None and doc["complete"] == "infinite" and doc["modes"] == []
    assert any("curve" in n for n in doc["notes"])


DIETMAIER = ROOT / "examples" / "stewart_dietmaier.yaml"
#: Dietmaier's published leg lengths (ARK 1998), which the --set slides give
DIETMAIER_LENGTHS = np.array([1, 0.645275, 1.086284, 1.503439, 1.281933, 0.771071])


def test_dietmaier_has_forty_real_postures(tmp_path: Path) -> None:
    """All 40 real postures of Dietmaier's platform by the Bertini 2 engine, in an empty
    working directory that stays empty; each posture's platform pose (from leg 1's joint
    values alone, by the tests' own kinematics) puts every leg at its published length to
    1e-12 m, and the 40 poses are distinct."""
    pytest.importorskip("bertini")
    import yaml

    from tests.reference.modes_independent import leg1_platform_pose

    joints = {j["name"]: j for j in yaml.safe_load(DIETMAIER.read_text())["joints"]}
    base = [np.array(joints[f"U{i}"]["point"], float) for i in range(1, 7)]
    plat = [np.array(joints[f"S{i}"]["point"], float) for i in range(1, 7)]
    sets = []
    for i in range(6):  # the slide that makes leg i as long as published
        u = np.array(joints[f"P{i + 1}"]["axis"], float)
        u /= np.linalg.norm(u)
        d = plat[i] - base[i]
        q = -d @ u + np.sqrt((d @ u) ** 2 - d @ d + DIETMAIER_LENGTHS[i] ** 2)
        sets += ["--set", f"dietmaier:P{i + 1}={float(q)!r}"]
    rc, out, err = run_cli_subprocess(
        [
            "modes",
            str(DIETMAIER),
            *sets,
            "--precision",
            "float",
            "--format",
            "json",
        ],
        timeout=900,
        cwd=tmp_path,
    )
    assert rc == 0, err
    assert list(tmp_path.iterdir()) == []  # no records directory, no file
    doc = json.loads(out)
    assert doc["count"] == 40 and doc["complete"] == "maximal"
    assert doc["paths"]["tracked"] == 128
    assert all(m["certified"] for m in doc["modes"])
    assert sum(m["reached_by_continuation"] for m in doc["modes"]) == 1
    poses = []
    for m in doc["modes"]:
        R, t = leg1_platform_pose(joints, m["joints"])
        lengths = [np.linalg.norm(R @ plat[i] + t - base[i]) for i in range(6)]
        assert np.allclose(lengths, DIETMAIER_LENGTHS, atol=1e-12, rtol=0)
        poses.append(np.concatenate([R.ravel(), t]))
    P = np.array(poses)
    gaps = np.linalg.norm(P[:, None] - P[None], axis=2) + np.eye(40)
    assert gaps.min() > 1e-6


def test_mp_digits_and_no_runtime_warning() -> None:
    """At mp:30 every joint value is given to 30 digits, and they agree with the float
    run; no numpy RuntimeWarning is raised on the way."""
    from tests.cli import runtime_warnings

    argv = ["modes", str(FOURBAR), "--config", "crank-30", "--format", "json"]
    assert runtime_warnings([*argv, "--precision", "mp:30"]) == []
    rc, out, err = run_cli([*argv, "--precision", "mp:30"])
    assert rc == 0, err
    mp = json.loads(out)
    flt = json.loads(run_cli(argv)[1])
    for a, b in zip(mp["modes"], flt["modes"], strict=True):
        for name, texts in a["joints_text"].items():
            assert len(texts[0].lstrip("-").replace(".", "").lstrip("0")) >= 30
            assert abs(float(texts[0]) - b["joints"][name][0]) < 1e-14


def test_a_platform_without_the_extra_names_it(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without Bertini 2 installed, a spatial platform exits 2 naming the extra."""
    import sys

    monkeypatch.setitem(sys.modules, "bertini", None)  # import bertini raises ImportError
    argv = ["modes", str(DIETMAIER)] + [f"--set=P{i}=0" for i in range(1, 7)]
    rc, _, err = run_cli(argv)
    assert rc == 2 and "mechsing[modes]" in err and "GPL-3.0-or-later" in err


def test_modes_outside_the_limits_are_flagged(tmp_path: Path) -> None:
    """The four-bar with its rocker's joint D limited to [-45, 45] deg: at crank 30 deg,
    mode 1 has D = 5.7 deg (inside) and mode 2 D = -114.5 deg (outside): only mode 2 is
    flagged, and only for D."""
    text = FOURBAR.read_text().replace("inputs: [A]", "inputs: [A]\nlimits: {D: [-45, 45]}")
    path = tmp_path / "limited.yaml"
    path.write_text(text)
    rc, out, err = run_cli(["modes", str(path), "--config", "crank-30", "--format", "json"])
    assert rc == 0, err
    flagged = [m["outside_limits"] for m in json.loads(out)["modes"]]
    inside = [abs(np.degrees(m["joints"]["D"][0])) <= 45 for m in json.loads(out)["modes"]]
    assert flagged == [[] if ok else ["D"] for ok in inside] and inside.count(False) == 1


def test_a_type_ii_configuration_is_one_singular_uncertified_mode() -> None:
    """planar_3rpr.yaml's configuration concurrent (every joint given: the modes share its
    inputs) has its three leg lines through one point: two assembly modes merge there (a
    double root, kept once), analyze calls it an output (type II) singularity, and no
    Krawczyk test can prove a double root: certified is false, honestly."""
    rc, out, err = run_cli(
        [
            "modes",
            str(ROOT / "examples" / "planar_3rpr.yaml"),
            "--config",
            "concurrent",
            "--format",
            "json",
        ]
    )
    assert rc == 0, err
    doc = json.loads(out)
    merged = [m for m in doc["modes"] if m["reached_by_continuation"]]
    assert len(merged) == 1 and merged[0]["singular"] and not merged[0]["certified"]
    assert "output" in [s["class"] for s in merged[0]["singularities"]]
    # the leg lines meet at c = (1, 1): leg 1, along (9/10, 3/10) at the reference (angle
    # atan(1/3)), is turned by Rb1 onto the line from A1 = (0, 0) through c (angle pi/4)
    assert np.isclose(np.arctan(1 / 3) + merged[0]["joints"]["Rb1"][0], np.pi / 4, atol=1e-12)


def test_the_report_has_a_section_with_every_mode_sketched(tmp_path: Path) -> None:
    out = tmp_path / "review.md"
    rc, _, err = run_cli(
        ["report", str(FOURBAR), "--config", "crank-30", "--modes", "crank-30", "-o", str(out)]
    )
    assert rc == 0, err
    text = out.read_text()
    section = text.split("## Assembly modes", 1)[1]
    assert "2 assembly modes (complete: proven" in section
    assert section.count("### Mode ") == 2
    for k in (1, 2):
        assert (tmp_path / "review_files" / f"mode-crank-30-{k}.svg").is_file()
    assert section.count("continuation from the configuration's start reaches") == 1
    # the command the report records reproduces it, --modes included
    recorded = [line for line in text.splitlines() if "command: mechsing report" in line]
    assert recorded and "--modes crank-30" in recorded[0]


def test_from_marks_the_mode_continuation_from_another_start_reaches(tmp_path: Path) -> None:
    """--from CONFIG: continuation from a configuration on the other assembly mode (every
    joint given, the crank at 30 deg) stays on it, so the crank at 60 deg marks the other
    mode than continuation from the reference does."""
    rc, out, err = run_cli(["modes", str(FOURBAR), "--config", "crank-30", "--format", "json"])
    assert rc == 0, err
    other = next(m for m in json.loads(out)["modes"] if not m["reached_by_continuation"])
    # the file's angles are in degrees; the JSON's in radians
    entry = ", ".join(f"{n}: {float(np.degrees(v[0]))!r}" for n, v in other["joints"].items())
    path = tmp_path / "fourbar.yaml"
    extra = f"  other: {{{entry}}}\n  crank-60: {{A: 60}}\n"
    path.write_text(FOURBAR.read_text().rstrip() + "\n" + extra)
    marked = {}
    for start in (None, "other"):
        argv = ["modes", str(path), "--config", "crank-60", "--format", "json"]
        rc, out, err = run_cli(argv + (["--from", start] if start else []))
        assert rc == 0, err
        doc = json.loads(out)
        assert doc["count"] == 2
        marked[start] = [k for k, m in enumerate(doc["modes"]) if m["reached_by_continuation"]]
    assert len(marked[None]) == 1 and len(marked["other"]) == 1
    assert marked[None] != marked["other"]


def test_from_refuses_an_unknown_start_and_a_cycle() -> None:
    rc, _, err = run_cli(["modes", str(FOURBAR), "--config", "crank-30", "--from", "nope"])
    assert rc == 2 and "no such configuration" in err
    rc, _, err = run_cli(["modes", str(FOURBAR), "--config", "crank-30", "--from", "crank-200"])
    assert rc == 2 and "a cycle" in err


def test_time_limit_stops_modes_with_exit_3_and_writes_nothing(tmp_path: Path) -> None:
    """--time-limit interrupts the engine (Bertini 2, inside its path tracking): exit 3
    with the reason, no output file, no traceback."""
    pytest.importorskip("bertini")
    out = tmp_path / "modes.json"
    argv = ["modes", str(ROOT / "examples" / "stewart_dietmaier.yaml"), "--config", "longer"]
    rc, _, err = run_cli_subprocess([*argv, "--time-limit", "1", "-o", str(out)], timeout=300)
    assert rc == 3, err
    assert "within --time-limit 1 s" in err and "Traceback" not in err
    assert not out.exists()
