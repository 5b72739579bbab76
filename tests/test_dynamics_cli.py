"""``mechsing dynamics`` and ``mechsing.dynamics(...)`` (issue 43): a planar 2R arm's
efforts, accelerations, mass matrix and kinetic energy against its Lagrangian
(tests/reference/lagrangian.py), the JSON against ``mechsing schema --dynamics``, the
forward problem inverting the inverse one, and the refusals (exit 2, the file named)."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import mpmath
import numpy as np
import pytest

from tests.cli import ROOT, run_cli
from tests.mechanisms import ARM_2R_JOINTS
from tests.reference.lagrangian import PlanarArm

ARM = (
    "mechanism: planar-2r\n"
    + ARM_2R_JOINTS
    + """\
inputs: [A, B]
mass:
  upper: {kg: 2, centre: [0.5, 0, 0], inertia: [0.01, 0.17, 0.17, 0, 0, 0]}
  fore: {kg: 1, centre: [1.25, 0, 0], inertia: [0.005, 0.02, 0.02, 0, 0, 0]}
gravity: [0, -9.81, 0]
configurations:
  bent: {A: 0.3, B: 0.9}
"""
)
REFERENCE = PlanarArm([1, 0.5], [2, 1], [0.5, 0.25], [0.17, 0.02], gravity=(0, -9.81))


def _file(tmp_path: Path) -> Path:
    f = tmp_path / "arm.yaml"
    f.write_text(ARM)
    return f


def _json(argv: list[str]) -> dict:
    r = run_cli(["dynamics", *map(str, argv), "--format", "json"])
    assert r.status == 0, r.err
    doc = json.loads(r.out)
    schema = json.loads(run_cli(["schema", "--dynamics"]).out)
    jsonschema.validate(doc, schema)
    return doc


def test_inverse_dynamics_of_a_2r_arm_is_its_lagrangian(tmp_path: Path) -> None:
    doc = _json(
        [
            _file(tmp_path),
            "--config",
            "bent",
            "--rates",
            "A=1",
            "B=-2",
            "--accelerations",
            "A=0.5",
            "B=3",
        ]
    )
    c = doc["configurations"][0]
    assert doc["problem"] == "inverse" and doc["gravity"] == [0, -9.81, 0]
    want = REFERENCE.efforts([0.3, 0.9], [1, -2], [0.5, 3])
    assert np.allclose([c["efforts"]["A"], c["efforts"]["B"]], [float(x) for x in want], rtol=1e-12)
    bias = REFERENCE.efforts([0.3, 0.9], [1, -2], [0, 0])
    assert np.allclose(list(c["bias_efforts"].values()), [float(x) for x in bias], rtol=1e-12)
    M = REFERENCE.mass_matrix([0.3, 0.9])
    assert c["mass_matrix"]["joints"] == ["A", "B"]
    assert np.allclose(
        c["mass_matrix"]["matrix"],
        [[float(M[i, j]) for j in range(2)] for i in range(2)],
        rtol=1e-12,
    )
    assert np.isclose(
        c["kinetic_energy"], float(REFERENCE.kinetic_energy([0.3, 0.9], [1, -2])), rtol=1e-12
    )
    assert c["crossing"] is None  # a tree has no Type II singularity


def test_forward_dynamics_returns_the_accelerations_the_efforts_were_computed_for(
    tmp_path: Path,
) -> None:
    want = [float(x) for x in REFERENCE.efforts([0.3, 0.9], [1, -2], [0.5, 3])]
    doc = _json(
        [
            _file(tmp_path),
            "--config",
            "bent",
            "--rates",
            "A=1",
            "B=-2",
            "--efforts",
            f"A={want[0]!r}",
            f"B={want[1]!r}",
        ]
    )
    c = doc["configurations"][0]
    assert doc["problem"] == "forward"
    assert np.allclose([c["accelerations"]["A"], c["accelerations"]["B"]], [0.5, 3], rtol=1e-10)


def test_at_50_digits_the_python_api_agrees_with_the_lagrangian(tmp_path: Path) -> None:
    import mechsing

    res = mechsing.dynamics(
        _file(tmp_path), "bent", rates={"A": "1"}, accelerations={"B": "-1/3"}, precision="mp:50"
    )
    with mpmath.workdps(50):
        ref = PlanarArm([1, "0.5"], [2, 1], ["0.5", "0.25"], ["0.17", "0.02"], gravity=(0, "-9.81"))
        want = ref.efforts(
            [mpmath.mpf(3) / 10, mpmath.mpf(9) / 10], [1, 0], [0, -mpmath.mpf(1) / 3]
        )
    got = res.configurations[0].efforts
    assert abs(got["A"] - float(want[0])) <= 1e-15 * abs(float(want[0]))
    assert res.precision == "mp:50"


def test_text_and_markdown_show_the_efforts(tmp_path: Path) -> None:
    f = _file(tmp_path)
    text = run_cli(["dynamics", str(f), "--accelerations", "A=1"]).out
    assert "inverse dynamics" in text and "kinetic energy" in text and "N m" in text
    md = run_cli(["dynamics", str(f), "--format", "md"]).out
    assert md.startswith("# planar-2r: inverse dynamics") and "| A |" in md


def test_a_urdf_takes_gravity_from_the_command_line() -> None:
    doc = _json([ROOT / "examples" / "ur5.urdf", "--gravity", "0,0,-9.81"])
    assert doc["gravity"] == [0, 0, -9.81]
    c = doc["configurations"][0]
    assert abs(c["efforts"]["joint2"]) > 1  # the arm's weight on the shoulder
    still = _json([ROOT / "examples" / "ur5.urdf"])
    assert still["gravity"] is None and all(
        v == 0 for v in still["configurations"][0]["efforts"].values()
    )


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--accelerations", "A=1", "--efforts", "A=1"], "not both"),
        (["--rates", "C=1"], "'C' is not a joint"),
        (["--rates", "A"], "write JOINT=VALUE"),
        (["--gravity", "0,1"], "three numbers"),
        (["--config", "nowhere"], "no configuration named 'nowhere'"),
    ],
)
def test_bad_options_exit_2_with_the_reason(tmp_path: Path, argv: list[str], words: str) -> None:
    r = run_cli(["dynamics", str(_file(tmp_path)), *argv])
    assert r.status == 2 and words in r.err


def test_a_file_without_masses_is_refused_naming_the_file() -> None:
    r = run_cli(["dynamics", str(ROOT / "examples" / "fourbar.yaml")])
    assert r.status == 2 and "fourbar.yaml" in r.err and "gives no masses" in r.err


def test_the_function_stays_the_function_once_the_package_is_imported() -> None:
    """``mechsing.dynamics`` is the function; its code lives in :mod:`mechsing.kinetics`
    (another name, so importing the package does not rebind the function's name)."""
    import mechsing
    import mechsing.kinetics.tree  # noqa: F401
    from mechsing.kinetics.api import dynamics

    assert mechsing.dynamics is dynamics


def test_the_exercise_torques_are_the_closed_form_and_the_statics(tmp_path: Path) -> None:
    """docs/dynamics.md's exercise: a 2R arm at rest under gravity; the efforts are the
    moments of the weights beyond each joint, and the statics (with an output) agree."""
    f = _file(tmp_path)
    c = _json([f, "--config", "bent"])["configurations"][0]
    g, A, B = 9.81, 0.3, 0.9
    tau_b = 1 * g * 0.25 * np.cos(A + B)
    tau_a = (2 * 0.5 + 1 * 1.0) * g * np.cos(A) + tau_b
    assert np.allclose([c["efforts"]["A"], c["efforts"]["B"]], [tau_a, tau_b], rtol=1e-12)
    f.write_text(ARM.replace("inputs: [A, B]", "inputs: [A, B]\noutput: {body: fore}"))
    r = run_cli(["analyze", str(f), "--config", "bent", "--precision", "float", "--format", "json"])
    statics = json.loads(r.out)["configurations"][0]["efforts"]
    assert np.allclose([statics["A"], statics["B"]], [tau_a, tau_b], rtol=1e-10)
