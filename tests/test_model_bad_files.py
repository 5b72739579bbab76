"""The corpus of malformed and hostile files: each gives a MechanismError (exit
status 2) whose message names the item; none runs code or hangs."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mechsing.cli import UserError, exit_status
from mechsing.model import MechanismError, load

BAD = Path(__file__).parent / "bad_files"
FILES = sorted(BAD.glob("*.yaml"))


def test_corpus_is_large_enough():
    assert len(FILES) >= 30


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_bad_file_is_refused_with_a_clear_message(path):
    text = path.read_text()
    assert re.search(r"^# wrong: ", text, re.M), "each bad file says what is wrong"
    expected = re.findall(r"^# expect: (.*)$", text, re.M)
    assert expected, "each bad file names a keyword its message must contain"
    with pytest.raises(MechanismError) as exc:
        load(path)
    err = exc.value
    assert isinstance(err, UserError) and exit_status(err) == 2
    msg = str(err)
    assert msg.startswith(str(path))
    for word in expected:
        assert word.lower() in msg.lower(), f"{word!r} not in {msg!r}"
    assert "Traceback" not in msg


def test_hostile_files_run_no_code(tmp_path):
    marker = Path("/tmp/mechsing_pwned")
    marker.unlink(missing_ok=True)
    for name in ("expression_code_execution", "python_tag", "expression_dunder_attribute"):
        with pytest.raises(MechanismError):
            load(BAD / f"{name}.yaml")
    assert not marker.exists()


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_bad_file_through_the_cli_exits_2(path, capsys):
    from mechsing.cli import main

    assert main(["analyze", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechsing: error: ") and "Traceback" not in err
