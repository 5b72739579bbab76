"""What the command imports before it works: ``mechsing``, ``mechsing --version``,
``mechsing -h`` and every ``mechsing COMMAND -h`` import neither numpy nor sympy (nor scipy,
matplotlib); a command imports its layers when it runs.

Each case runs the installed command as a user does (``python -X importtime -m mechsing``, a
fresh interpreter) and reads the modules it imported from the interpreter's own record on
standard error: a test of what is imported, not of time (benchmarks/startup.py measures
the time).
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from mechsing.cli import COMMANDS
from tests.cli import ROOT

#: the libraries a command imports only when it works
HEAVY = ("numpy", "sympy", "scipy", "matplotlib")


def _imported(argv: list[str]) -> tuple[int, str, set[str]]:
    """The exit status, standard output and the modules ``mechsing ARGV`` imported."""
    r = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "mechsing", *argv],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
    )
    names = {
        line.rsplit("|", 1)[1].strip()
        for line in r.stderr.splitlines()
        if line.startswith("import time:") and line.count("|") == 2
    }
    return r.returncode, r.stdout, names


@pytest.mark.parametrize(
    "argv",
    [[], ["--version"], ["-h"], *([name, "-h"] for name in COMMANDS)],
    ids=lambda argv: " ".join(argv) or "(no arguments)",
)
def test_help_and_version_import_no_numerics(argv: list[str]) -> None:
    status, out, names = _imported(argv)
    assert status == 0 and out, (argv, status)
    assert "mechsing.cli.main" in names, "the record of imports was not read"
    heavy = sorted(n for n in names if n.split(".")[0] in HEAVY)
    assert not heavy, f"mechsing {' '.join(argv)} imported {heavy[:5]}"


def test_a_command_imports_what_it_uses_when_it_runs() -> None:
    # the same record shows the layers arriving once a command works: the test above
    # reads a record that would have listed them
    status, out, names = _imported(
        ["analyze", "examples/fourbar.yaml", "--config", "crank-30", "--precision", "float"]
    )
    assert status == 0 and "four-bar" in out
    assert {"numpy", "mechsing.analysis"} <= names
