"""Every malformed or hostile file through ``mechsing analyze FILE --format json``:
exit status 2, one message on stderr naming the file (and what its header
says the message must contain), nothing on stdout, never a traceback, never
code execution."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.cli import run_cli, run_cli_subprocess

ROOT = Path(__file__).resolve().parents[1]
BAD = ROOT / "tests" / "bad_files"
FILES = sorted(BAD.glob("*.yaml"))
#: run for real, in a new interpreter: a YAML error, a hostile tag, a hostile expression
SUBPROCESS = ["malformed_yaml", "python_tag", "expression_code_execution"]


def expected_words(path: Path) -> list[str]:
    return re.findall(r"^# expect: (.*)$", path.read_text(), re.M)


def check_message(path: Path, status: int, out: str, err: str) -> None:
    assert status == 2, err
    assert out == ""
    assert "Traceback" not in err and "Traceback" not in out
    assert err.startswith("mechsing: error: ")
    assert str(path) in err
    for word in expected_words(path):
        assert word.lower() in err.lower(), f"{word!r} not in {err!r}"


def test_the_corpus_is_there():
    assert len(FILES) >= 30
    assert all(expected_words(p) for p in FILES)


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_bad_file_gives_exit_2_and_a_message_naming_it(path):
    status, out, err = run_cli(["analyze", path, "--format", "json"])
    check_message(path, status, out, err)


@pytest.mark.parametrize("name", SUBPROCESS)
def test_bad_file_as_a_subprocess(name, tmp_path):
    path = BAD / f"{name}.yaml"
    proc = run_cli_subprocess(["analyze", path, "--format", "json"], cwd=tmp_path)
    check_message(path, proc.status, proc.out, proc.err)
    assert proc.err.count("\n") == 1  # one message, one line


FOURBAR = """\
bodies: [ground, crank, coupler, rocker]
joints:
  - {{name: A, type: R, between: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: B, type: R, between: [crank, coupler],  axis: [0, 0, 1], point: [{b}, 0, 0]}}
  - {{name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, 2, 0]}}
  - {{name: D, type: R, between: [rocker, ground],  axis: [0, 0, 1], point: [4, 0, 0]}}
{extra}configurations:
  reference: {{}}
  moved: {{A: {a}}}
"""


def hostile_files(marker: Path) -> dict[str, str]:
    """Ways an expression or a tag could try to run ``touch MARKER``."""
    sh = f"touch {marker}"
    exprs = {
        "import": f"__import__('os').system('{sh}')",
        "eval": f"eval(\"__import__('os').system('{sh}')\")",
        "exec": f"exec(\"import os; os.system('{sh}')\")",
        "lambda": f"(lambda: __import__('os').system('{sh}'))()",
        "dunder": "().__class__.__base__.__subclasses__()",
        "sympy-call": f"Function('system')('{sh}')",
        "getattr": f"getattr(__import__('os'), 'system')('{sh}')",
    }
    out = {}
    for key, e in exprs.items():
        q = '"' + e.replace('"', '\\"') + '"'
        out[f"point-{key}"] = FOURBAR.format(b=q, a="0.1", extra="")
        out[f"value-{key}"] = FOURBAR.format(b="1", a=q, extra="")
        out[f"length-{key}"] = FOURBAR.format(b="1", a="0.1", extra=f"characteristic_length: {q}\n")
    out["python-tag"] = FOURBAR.format(
        b="1", a="0.1", extra=f"mechanism: !!python/object/apply:os.system ['{sh}']\n"
    )
    out["python-name-tag"] = FOURBAR.format(b="1", a="!!python/name:os.system ''", extra="")
    return out


def test_expressions_and_tags_never_run_code(tmp_path):
    marker = tmp_path / "pwned"
    for key, text in hostile_files(marker).items():
        f = tmp_path / f"{key}.yaml"
        f.write_text(text)
        status, out, err = run_cli(["analyze", f, "--format", "json"])
        assert status == 2, (key, err)
        assert out == "" and str(f) in err and "Traceback" not in err, (key, err)
        assert "not allowed" in err, (key, err)
        assert not marker.exists(), key
    # and the corpus's own hostile files, which aim at /tmp/mechsing_pwned
    shared = Path("/tmp/mechsing_pwned")

    def stamp():  # touch creates the file or updates its modification time
        return shared.stat().st_mtime_ns if shared.exists() else None

    before = stamp()
    for name in ("expression_code_execution", "python_tag", "expression_dunder_attribute"):
        assert run_cli(["analyze", BAD / f"{name}.yaml", "--format", "json"]).status == 2
    assert stamp() == before
