"""What the command imports before it works: ``mechsing``, ``mechsing --version``,
``mechsing -h`` and every ``mechsing COMMAND -h`` import neither numpy nor sympy (nor scipy,
matplotlib); a command imports its layers when it runs.

Each case runs the command as ``python -m mechsing`` does (``mechsing/__main__.py`` run as
the main module, in a fresh interpreter) and reads ``sys.modules`` as the interpreter exits:
a test of what is imported, not of time (benchmarks/startup.py measures the time).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from mechsing.cli import COMMANDS
from tests.cli import ROOT

#: the libraries a command imports only when it works
HEAVY = ("numpy", "sympy", "scipy", "matplotlib")


#: ``python -m mechsing ARGV`` that writes the names in sys.modules to a file at exit
_RUN = (
    "import atexit, json, os, runpy, sys\n"
    "def _record():\n"
    "    with open(os.environ['MECHSING_TEST_MODULES'], 'w') as f:\n"
    "        json.dump(sorted(sys.modules), f)\n"
    "atexit.register(_record)\n"
    "runpy.run_module('mechsing', run_name='__main__', alter_sys=True)\n"
)


def _imported(argv: list[str], tmp_path: Path) -> tuple[int, str, set[str]]:
    """The exit status, standard output and the modules ``mechsing ARGV`` imported."""
    record = tmp_path / "modules.json"
    r = subprocess.run(
        [sys.executable, "-c", _RUN, *argv],
        cwd=ROOT,
        env={**os.environ, "MECHSING_TEST_MODULES": str(record)},
        capture_output=True,
        text=True,
        timeout=120,
    )
    return r.returncode, r.stdout, set(json.loads(record.read_text()))


@pytest.mark.parametrize(
    "argv",
    [[], ["--version"], ["-h"], *([name, "-h"] for name in COMMANDS)],
    ids=lambda argv: " ".join(argv) or "(no arguments)",
)
def test_help_and_version_import_no_numerics(argv: list[str], tmp_path: Path) -> None:
    status, out, names = _imported(argv, tmp_path)
    assert status == 0 and out, (argv, status)
    assert "mechsing.cli.main" in names and "argparse" in names
    heavy = sorted(n for n in names if n.split(".")[0] in HEAVY)
    assert not heavy, f"mechsing {' '.join(argv)} imported {heavy[:5]}"


def test_a_command_imports_what_it_uses_when_it_runs(tmp_path: Path) -> None:
    # the same record shows the layers arriving once a command works: the test above
    # reads a record that would have listed them
    status, out, names = _imported(
        ["analyze", "examples/fourbar.yaml", "--config", "crank-30", "--precision", "float"],
        tmp_path,
    )
    assert status == 0 and "four-bar" in out
    assert {"numpy", "mechsing.analysis"} <= names


def test_a_float_analysis_of_one_loop_imports_no_graph_or_plot_library(tmp_path: Path) -> None:
    # the four-bar's one loop is the unique cycle basis, found without networkx (which
    # costs a fifth of the start-up with the email and XML modules it loads); nothing of
    # a float analysis needs scipy or matplotlib either
    status, out, names = _imported(
        ["analyze", "examples/fourbar.yaml", "--config", "crank-30", "--precision", "float"],
        tmp_path,
    )
    assert status == 0 and "regular: no singularity" in out
    assert "mechsing.model.graph" in names
    heavy = sorted(n for n in names if n.split(".")[0] in ("networkx", "scipy", "matplotlib"))
    assert not heavy, heavy[:5]


def _slider_crank(tmp_path: Path) -> Path:
    """The crank-input slider-crank example without its fully given dead centre (written
    with atan: a value only sympy computes); its other configurations are plain numbers."""
    text = (ROOT / "examples" / "slider_crank_crank_input.yaml").read_text(encoding="utf-8")
    kept = [line for line in text.splitlines() if not line.lstrip().startswith("dead-centre:")]
    assert len(kept) == len(text.splitlines()) - 1
    path = tmp_path / "slider_crank.yaml"
    path.write_text("\n".join(kept) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize(
    "case",
    ["fourbar float", "fourbar auto", "slider-crank float", "slider-crank auto"],
)
def test_a_float_analysis_of_plain_numbers_imports_no_sympy(case: str, tmp_path: Path) -> None:
    # the file's numbers (decimals, degrees, pi/3) are PiRational: exact, with their float,
    # and sympy is imported only by a computation that needs it (exact, mp, a root, a
    # trigonometric value); auto's first pass is float and decides these configurations
    name, precision = case.split()
    if name == "fourbar":
        argv = ["analyze", "examples/fourbar.yaml", "--config", "crank-30"]
        regular = 1
    else:
        argv = ["analyze", str(_slider_crank(tmp_path))]
        regular = 2
    status, out, names = _imported([*argv, "--precision", precision], tmp_path)
    assert status == 0 and out.count("regular: no singularity") == regular, out
    assert "(float)" in out and "mechsing.model.expressions" in names
    heavy = sorted(n for n in names if n.split(".")[0] in ("sympy", "mpmath"))
    assert not heavy, heavy[:5]


@pytest.mark.parametrize("command", ["sweep", "solve"])
def test_a_float_sweep_or_solve_of_plain_numbers_imports_no_sympy(
    command: str, tmp_path: Path
) -> None:
    # sweep, solve and report read the file as analyze does: a float or auto run (auto's
    # first pass is float) keeps the file's plain numbers as PiRational; a path sweep
    # draws no locus either, so networkx (the grid's loci) stays out too (mpmath may come:
    # the rocker's limit the sweep locates is refined in auto's mp)
    if command == "sweep":
        argv = ["sweep", "examples/fourbar.yaml", "--vary", "A=0:60:5", "--format", "json"]
    else:
        argv = ["solve", "examples/fourbar.yaml", "--config", "crank-30", "--format", "json"]
    status, out, names = _imported(argv, tmp_path)
    assert status == 0, out
    doc = json.loads(out)
    assert doc["mechanism"] == "four-bar"
    assert "mechsing.model.expressions" in names
    if command == "sweep":
        assert len(doc["located"]) == 1  # the rocker's limit in 0..60 deg
    heavy = sorted(n for n in names if n.split(".")[0] in ("sympy", "networkx"))
    assert not heavy, heavy[:5]
