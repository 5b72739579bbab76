"""The guard: every valid file, every precision mode, every format gives an answer or a clear
message, never a traceback.

Each bundled example and each valid file of tests/data/ is analysed once per mode (float, mp:30,
mp:50, auto, exact); the one result is rendered as text, JSON and Markdown.  The outcome must be
what the command line would turn into exit status 0 (all analysed), 2 (bad input, e.g. exact mode
refusing decimal data) or 3 (some configuration could not be analysed, with its ``error``); any
other exception is a defect.  Each configuration must finish within its mode's bound (exact mode:
its own time limit, which stops a configuration with an ``error``).  One file per mode also runs
through the command line itself.

Every command that reads a mechanism (analyze, condition, sweep, report) also reads one file of
each format (mechsing YAML, a DH table, URDF, MJCF) through the command line, with Python's
warnings turned into errors: a numpy RuntimeWarning there is a defect, as an exit status 4 is.
"""

from __future__ import annotations

import json
import time
import warnings
from pathlib import Path

import pytest

from mechsing.analysis import analyze
from mechsing.cli import exit_status
from mechsing.errors import UserError
from mechsing.reports import render
from tests.cli import run_cli
from tests.mechanisms import ROOT

FILES = (
    sorted((ROOT / "examples").glob("*.yaml"))
    + sorted((ROOT / "tests" / "data").glob("*.yaml"))
    + [ROOT / "examples" / "ur5.urdf", ROOT / "examples" / "fourbar_mjcf.xml"]
    # the exercises' mechanisms (not their answers, nor the variants' templates)
    + sorted(
        p
        for p in (ROOT / "examples" / "exercises").glob("*/*.yaml")
        if p.name not in ("answers.yaml", "template.yaml")
    )
)
MODES = ("float", "mp:30", "mp:50", "auto", "exact")
#: the seconds a configuration may take: a hang, not a speed, is what this catches
BOUND = {"exact": 60.0, "float": 20.0, "mp:30": 20.0, "mp:50": 20.0, "auto": 20.0}
#: exact mode's own time limit here, so that a configuration it stops ends within the bound
EXACT_LIMIT = 55.0
#: one file per mode also goes through the command line (in-process, so its exit status is seen)
THROUGH_CLI = {
    "float": ("fourbar.yaml", "text"),
    "mp:30": ("bennett.yaml", "json"),
    "mp:50": ("planar_3rpr.yaml", "md"),
    "auto": ("ur5.yaml", "text"),
    "exact": ("slider_crank_crank_input.yaml", "json"),
}


def _status(mode: str, path: Path) -> tuple[int, object]:
    try:
        result = analyze(path, precision=mode, time_limit=EXACT_LIMIT)
    except UserError as exc:
        assert exit_status(exc) == 2, exc
        assert str(exc) and "Traceback" not in str(exc)
        return 2, exc
    return (3 if result.failed else 0), result


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("path", FILES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_every_file_every_mode_every_format(path: Path, mode: str) -> None:
    start = time.perf_counter()
    status, outcome = _status(mode, path)
    elapsed = time.perf_counter() - start
    if status == 2:
        # only exact mode may refuse a valid file whole (its data are not exact)
        assert mode == "exact", outcome
        assert "exact" in str(outcome)
        return
    result = outcome
    configs = result.configurations
    assert configs
    for c in configs:
        assert c.seconds <= BOUND[mode], (c.name, c.seconds)
        if c.error is not None:
            assert c.error.strip() and c.name in c.error
    assert elapsed <= BOUND[mode] * len(configs) + 30.0
    data = json.loads(render(result, "json"))
    assert data == json.loads(json.dumps(data))
    assert [c["name"] for c in data["configurations"]] == [c.name for c in configs]
    for c in data["configurations"]:
        assert ("error" in c) or c["precision"] and c["decisions"] is not None
    text, md = render(result, "text"), render(result, "md")
    for c in configs:
        assert f"Configuration {c.name}" in text and f"Configuration {c.name}" in md
    assert md.startswith("# mechsing analysis")


@pytest.mark.parametrize("mode", MODES)
def test_the_command_line_in_every_mode(mode: str) -> None:
    name, fmt = THROUGH_CLI[mode]
    rc, out, err = run_cli(
        [
            "analyze",
            str(ROOT / "examples" / name),
            "--precision",
            mode,
            "--format",
            fmt,
            "--time-limit",
            str(EXACT_LIMIT),
        ]
    )
    assert rc in (0, 3), err
    assert "Traceback" not in err and out
    if fmt == "json":
        assert json.loads(out)["precision"]["mode"] == mode


#: one file per format, and what a sweep of it varies
FORMATS = {
    "yaml": (ROOT / "examples" / "fourbar.yaml", "A=0:360:10"),
    "dh": (ROOT / "tests" / "data" / "scara_dh.yaml", "J2"),  # over its limits
    "urdf": (ROOT / "examples" / "ur5.urdf", "joint3=-3:3:0.25"),
    "mjcf": (ROOT / "examples" / "fourbar_mjcf.xml", "A=0:360:10"),
}
COMMANDS = ("analyze", "condition", "sweep", "report", "modes", "cusps", "dynamics")
#: the commands that only take mechanisms of some kinds: a refusal (2) must say what they need
NEEDS = {
    "cusps": ("three inputs", "positional task"),
    "dynamics": ("gives no masses", "joints of one coordinate"),
}


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("fmt", FORMATS)
def test_every_command_reads_every_format(fmt: str, command: str, tmp_path: Path) -> None:
    """Each command on a file of each format: an answer (0), a clear refusal (2: the MJCF
    file names no output, which condition needs) or a configuration not analysed (3), never
    a defect (4) or a warning of Python's."""
    path, vary = FORMATS[fmt]
    argv = [command, str(path)]
    if command in ("sweep", "report"):
        argv += ["--vary", vary, "--precision", "float"]
    if command == "sweep":
        argv += ["--quiet", "--format", "json"]
    if command == "report":
        argv += ["-o", str(tmp_path / "review.md")]
    if command == "cusps":  # the section of the file's first two joints
        from mechsing import load

        first, second = (j.name for j in load(path).joints[:2])
        argv += ["--vary", f"{first}=0:1,{second}=0:1", "--points", "5"]
    if command == "modes":  # the file's first configuration after the reference
        from mechsing import load

        argv += [
            "--config",
            [*(c for c in load(path).configurations if c != "reference"), "reference"][0],
        ]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rc, out, err = run_cli(argv)
    assert "Traceback" not in err and "internal error" not in err, err
    if fmt == "mjcf" and command == "condition":
        assert rc == 2 and "no output" in err, err
        return
    if command == "modes" and fmt == "dh":  # a four-joint SCARA: the general formulation
        assert rc == 0 and "joint displacements in Study coordinates" in out, err
    if command == "modes" and fmt == "mjcf":  # a loop and only a reference: no given value
        assert rc == 2 and "gives no joint value" in err, err
        return
    if command in NEEDS and rc == 2:  # a mechanism of another kind, refused with what it needs
        assert str(path) in err and any(n in err for n in NEEDS[command]), err
        return
    assert rc in (0, 3), err
    if command == "sweep":
        assert json.loads(out)["points"]
    elif command == "report":
        assert (tmp_path / "review.md").read_text().startswith("#")
    else:
        assert out


#: the sweep's options of the newer commands, on the four-bar (its crank-30 has two modes)
SWEEP_OPTIONS = {
    "mode": ["--from", "crank-30", "--mode", "2"],
    "modes-all": ["--from", "crank-30", "--modes", "all"],
    "json-by-extension": ["--from", "crank-30"],
}


@pytest.mark.parametrize("option", SWEEP_OPTIONS)
def test_the_sweeps_newer_options(option: str, tmp_path: Path) -> None:
    """A sweep per assembly mode, every mode, and the format read from -o's extension: an
    answer without a warning of Python's, each sample labelled with the mode it follows."""
    out_file = tmp_path / "sweep.json"
    argv = ["sweep", str(ROOT / "examples" / "fourbar.yaml"), "--vary", "A=0:360:10"]
    argv += ["--quiet", "-o", str(out_file), *SWEEP_OPTIONS[option]]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rc, _, err = run_cli(argv)
    assert rc == 0 and "Traceback" not in err, err
    document = json.loads(out_file.read_text())
    runs = document if isinstance(document, list) else [document]
    assert runs and all(run["points"] for run in runs)
    if option == "mode":
        assert {p["mode"] for run in runs for p in run["points"]} == {2}
    if option == "modes-all":
        assert {p["mode"] for run in runs for p in run["points"]} == {1, 2}
