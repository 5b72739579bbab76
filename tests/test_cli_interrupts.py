"""A command stopped by a signal, as a user stops it (Ctrl-C, ``kill``): SIGINT ends it with
exit status 130 and SIGTERM with 143, one line on standard error and no traceback; an
``-o`` file keeps its previous content and no temporary file is left beside it.

Each test runs the command in a child process, waits until it has worked for a while (its
CPU time, read from /proc: past the start-up, inside the computation), sends the signal and
waits generously for the end.  The one measure of speed is in CPU seconds with a wide margin:
``modes`` stopped inside Bertini's path tracking uses far less than the rest of the tracking
would (it used to track every path before a SIGTERM was seen).
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.cli import ROOT, WALL_CLOCK

FOURBAR = ROOT / "examples" / "fourbar.yaml"
FIVE_BAR = ROOT / "examples" / "five_bar.yaml"
DIETMAIER = ROOT / "examples" / "stewart_dietmaier.yaml"
PREVIOUS = "the previous output\n"
STATUS = {signal.SIGINT: 130, signal.SIGTERM: 143}

pytestmark = pytest.mark.skipif(
    not Path("/proc/self/stat").exists(), reason="reads a process's CPU time from /proc"
)


def _cpu(pid: int) -> float:
    """The CPU seconds (user and system) the process has used so far."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _interrupted(argv: list[str], sig: int, cwd: Path, after_cpu: float) -> tuple[int, str, float]:
    """Run ``mechsing ARGV``, send ``sig`` once it has used ``after_cpu`` CPU seconds:
    its exit status, its standard error and the CPU seconds it used after the signal."""
    p = subprocess.Popen(
        [sys.executable, "-m", "mechsing", *argv],
        cwd=cwd,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.monotonic() + WALL_CLOCK
        while (at := _cpu(p.pid)) < after_cpu:
            assert p.poll() is None, "the command ended before the signal: give it more work"
            assert time.monotonic() < deadline, "the command did not start working"
            time.sleep(0.02)
        p.send_signal(sig)
        deadline = time.monotonic() + WALL_CLOCK
        while True:  # wait4: the child's own CPU time at its end
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            assert time.monotonic() < deadline, "the command did not stop"
            time.sleep(0.05)
        p.returncode = os.waitstatus_to_exitcode(status)
        err = p.stderr.read()
    finally:
        if p.returncode is None:
            p.kill()
            p.wait()
        p.stderr.close()
    return p.returncode, err, usage.ru_utime + usage.ru_stime - at


def _check_stopped(status: int, err: str, sig: int, out: Path) -> None:
    assert status == STATUS[sig], (status, err)
    assert "Traceback" not in err, err
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("mechsing: stopped by SIG") and out.name in lines[0], err
    assert out.read_text() == PREVIOUS
    assert not [q.name for q in out.parent.iterdir() if q.name.endswith(".partial")]


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_stopped_sweep_exits_130_or_143_and_keeps_the_output(sig: int, tmp_path: Path) -> None:
    # a five-bar grid of 90,000 samples: some 12 s of CPU, stopped after 2 (a four-bar's
    # crank turn of 72,000 samples now ends in 1.5)
    shutil.copy(FIVE_BAR, tmp_path / "in.yaml")
    out = tmp_path / "out.csv"
    out.write_text(PREVIOUS)
    grid = ["--vary", "A1=-0.6:0.6:0.004", "--vary", "A2=-0.6:0.6:0.004"]
    argv = ["sweep", "in.yaml", *grid, "--quiet", "-o", out.name]
    status, err, _ = _interrupted(argv, sig, tmp_path, after_cpu=2.0)
    _check_stopped(status, err, sig, out)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_stopped_report_exits_130_or_143_and_keeps_the_output(sig: int, tmp_path: Path) -> None:
    shutil.copy(FOURBAR, tmp_path / "in.yaml")
    out = tmp_path / "review.html"
    out.write_text(PREVIOUS)
    argv = ["report", "in.yaml", "--vary", "A=0:360:0.005", "-o", out.name]
    status, err, _ = _interrupted(argv, sig, tmp_path, after_cpu=2.0)
    _check_stopped(status, err, sig, out)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_modes_stops_inside_the_path_tracking(sig: int, tmp_path: Path) -> None:
    # Dietmaier's platform at "longer": Bertini tracks 128 paths for about 16 CPU seconds,
    # from about 1 CPU second on; the signal comes at 4 s, inside the tracking
    pytest.importorskip("bertini")
    out = tmp_path / "modes.json"
    out.write_text(PREVIOUS)
    argv = ["modes", str(DIETMAIER), "--config", "longer", "-o", out.name]
    status, err, after = _interrupted(argv, sig, tmp_path, after_cpu=4.0)
    _check_stopped(status, err, sig, out)
    assert after < 5.0, f"{after:.1f} CPU s after the signal: the tracking went on"


def test_an_uninterrupted_command_is_unchanged(tmp_path: Path) -> None:
    # the handlers are the command's own: a run that no signal reaches writes its output
    # and puts the previous handlers back (the in-process runs of the suite rely on it)
    from tests.cli import run_cli

    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    out = tmp_path / "out.json"
    r = run_cli(["sweep", FOURBAR, "--vary", "A=0:360:90", "--quiet", "-o", out])
    assert r.status == 0, r.err
    assert len(json.loads(out.read_text())["points"]) == 5
    assert (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)) == before
