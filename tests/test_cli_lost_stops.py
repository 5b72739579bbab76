"""A stop that Python itself loses still stops the command.

A signal's exception is raised wherever the main thread is when the signal arrives.  If
that is a weak reference's callback run by the garbage collector, Python only prints
"Exception ignored in ..." and goes on; a library's ``except BaseException`` loses it too.
The command line raises a lost stop again, and whatever swallowed it, the command neither
replaces its ``-o`` file nor ends with success (tests/test_cli_interrupts.py sends real
signals to a running command; these tests lose the stop on purpose, in process).
"""

from __future__ import annotations

import signal
import time
import weakref
from pathlib import Path

import pytest

import mechsing.cli.convert
from mechsing.cli.main import _StopOnSignal, main
from mechsing.errors import Interrupted
from mechsing.files import write_output
from tests.cli import ROOT

PREVIOUS = "the previous output\n"
URDF = ROOT / "examples" / "ur5.urdf"


class _Body:
    pass


def _lose(sig: int) -> None:
    """Send ``sig`` from inside a weak reference's callback, where its exception is lost."""
    body = _Body()
    ref = weakref.ref(body, lambda _: signal.raise_signal(sig))
    del body  # the callback runs here, and its exception is lost
    assert ref() is None


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_stop_lost_in_a_callback_is_raised_again(
    sig: int, capsys: pytest.CaptureFixture[str]
) -> None:
    start = time.monotonic()
    with pytest.raises(Interrupted) as caught, _StopOnSignal():
        _lose(sig)
        while time.monotonic() - start < 5.0:  # some work after the callback
            pass
    assert caught.value.signum == sig
    assert time.monotonic() - start < 1.0  # raised again soon, not at the end of the work
    assert "Exception ignored" not in capsys.readouterr().err  # not reported as lost


def _swallowing_run(sig: int, write: bool):
    """A command whose code swallows the stop (a bare ``except``), then goes on."""

    def run(args) -> int:
        try:
            signal.raise_signal(sig)
        except BaseException:  # noqa: BLE001, S110 - the defect this test plays
            pass
        if write:
            write_output(args.output, "the new output\n")
        return 0

    return run


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
@pytest.mark.parametrize("write", [True, False])
def test_a_swallowed_stop_keeps_the_output_and_is_no_success(
    sig: int,
    write: bool,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    out = tmp_path / "out.yaml"
    out.write_text(PREVIOUS)
    monkeypatch.setattr(mechsing.cli.convert, "run", _swallowing_run(sig, write))
    status = main(["convert", str(URDF), "-o", str(out)])
    assert status == 128 + sig
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("mechsing: stopped by SIG"), err
    assert str(out) in err[0]  # "... was left as it was"
    assert out.read_text() == PREVIOUS
    assert not [q.name for q in tmp_path.iterdir() if q.name != out.name]


def test_the_next_command_starts_unstopped(tmp_path: Path) -> None:
    # the record of a stop ends with its command
    with pytest.raises(Interrupted), _StopOnSignal():
        signal.raise_signal(signal.SIGINT)
    out = tmp_path / "out.yaml"
    assert main(["convert", str(URDF), "-o", str(out)]) == 0
    assert "joints:" in out.read_text()
