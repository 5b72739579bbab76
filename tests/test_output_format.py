"""-o OUT chooses the format by its extension, for every command that writes to -o
(one table and one rule: :mod:`mechsing.cli.output`): the file written is what
``--format`` of that format prints, --format wins over the extension, an unknown
extension writes text, and an extension naming a format the command does not write is
refused (exit 2) before the work, nothing written."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.cli import run_cli

FOURBAR = str(Path(__file__).resolve().parents[1] / "examples" / "fourbar.yaml")

#: each command writing to -o, on the README's four-bar
COMMANDS = {
    "analyze": ["analyze", FOURBAR, "--config", "crank-30"],
    "modes": ["modes", FOURBAR, "--config", "crank-30"],
    "condition": ["condition", FOURBAR],
    "sweep": ["sweep", FOURBAR, "--vary", "A=0:1:0.5"],
}


def _printed(argv: list[str], fmt: str) -> str:
    run = run_cli([*argv, "--format", fmt])
    assert run.status == 0, run.err
    return run.out


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_the_extension_of_o_chooses_the_format(name: str, tmp_path: Path) -> None:
    argv = COMMANDS[name]
    out = tmp_path / "x.json"
    run = run_cli([*argv, "-o", out])
    assert run.status == 0, run.err
    written = out.read_text(encoding="utf-8")
    assert json.loads(written)  # JSON, not text
    assert written == _printed(argv, "json")
    # --format wins over the extension; an extension the table does not know is text
    run = run_cli([*argv, "--format", "text", "-o", tmp_path / "t.json"])
    assert run.status == 0, run.err
    text = _printed(argv, "text")
    assert (tmp_path / "t.json").read_text(encoding="utf-8") == text
    assert run_cli([*argv, "-o", tmp_path / "t.out"]).status == 0
    assert (tmp_path / "t.out").read_text(encoding="utf-8") == text


def test_markdown_and_latex_follow_their_extensions(tmp_path: Path) -> None:
    for name, ext, fmt in (("analyze", ".md", "md"), ("condition", ".tex", "latex")):
        out = tmp_path / f"x{ext}"
        run = run_cli([*COMMANDS[name], "-o", out])
        assert run.status == 0, run.err
        assert out.read_text(encoding="utf-8") == _printed(COMMANDS[name], fmt), name


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["modes", FOURBAR, "--config", "crank-30"], "modes writes text, json or md, not csv"),
        (["analyze", FOURBAR], "analyze writes text, json or md, not csv"),
        (["cusps", FOURBAR, "--vary", "A=0:1,B=0:1"], "cusps writes text, json or md, not csv"),
        (["condition", FOURBAR], "condition writes text, json, latex or md, not csv"),
    ],
)
def test_an_extension_naming_a_format_the_command_does_not_write_is_refused(
    argv: list[str], words: str, tmp_path: Path
) -> None:
    out = tmp_path / "x.csv"
    run = run_cli([*argv, "-o", out])
    assert run.status == 2 and words in run.err, run.err
    assert "give --format" in run.err
    assert not out.exists()
