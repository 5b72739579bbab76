"""Files from and to anywhere: the hostile or careless kinds of input and output path.

Every command reads its file with :func:`mechsing.files.read_input` and writes with
:func:`mechsing.files.open_output`; each test runs the command as a user does (a child
process under hard caps: 1 GB of address space and a wall clock) in a temporary directory,
and checks the exit status, the message and that nothing but the asked output changed.

* an output that is an input (the same path, a hard link, a symbolic link; a report's
  default name; a Markdown report's figures) is refused, exit 2, naming both;
* outputs are written atomically through a unique temporary file: a link planted at the
  old fixed ``OUT.partial`` is never followed, two sweeps onto one OUT both succeed, an
  interrupted sweep leaves OUT as it was and no temporary file;
* a missing directory is refused by every command, naming it; a directory as OUT too;
* devices, sockets and directories as FILE are "not a regular file"; pipes and FIFOs are
  read with the files' size cap, and a FIFO nobody writes to is an error after a wait;
* no command leaves a file in the working directory, the home folder or the temporary
  folder, but the output it was asked for.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import socket
import stat
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from tests.cli import ROOT, WALL_CLOCK, run_cli_capped

FOURBAR = ROOT / "examples" / "fourbar.yaml"
URDF = ROOT / "examples" / "ur5.urdf"
MJCF = ROOT / "examples" / "fourbar_mjcf.xml"
SWEEP = ["--vary", "A=0:360:90", "--quiet", "--precision", "float"]
QUICK = ["--config", "crank-30", "--precision", "float"]


def _tree(folder: Path) -> dict[str, tuple[int, bytes | str]]:
    """Every entry under ``folder``: its kind and content (a link's target)."""
    out: dict[str, tuple[int, bytes | str]] = {}
    for p in sorted(folder.rglob("*")):
        st = p.lstat()
        if stat.S_ISLNK(st.st_mode):
            out[str(p.relative_to(folder))] = (stat.S_IFLNK, os.readlink(p))
        elif stat.S_ISREG(st.st_mode):
            out[str(p.relative_to(folder))] = (stat.S_IFREG, p.read_bytes())
        else:
            out[str(p.relative_to(folder))] = (stat.S_IFMT(st.st_mode), "")
    return out


def _refused(r, *words: str) -> None:
    assert r.status == 2, (r.status, r.err)
    assert r.out == "" and "Traceback" not in r.err, r.err
    assert r.err.startswith("mechsing: error: ") and r.err.count("\n") == 1, r.err
    for w in words:
        assert w in r.err, (w, r.err)


# --------------------------------------------------------------------------- item 1


def _copy(folder: Path, source: Path, name: str) -> Path:
    path = folder / name
    shutil.copyfile(source, path)
    return path


ONTO_ITSELF = {
    "analyze": (FOURBAR, "in.yaml", ["analyze", "in.yaml", "-o", "in.yaml"]),
    "sweep": (FOURBAR, "in.yaml", ["sweep", "in.yaml", *SWEEP, "-o", "in.yaml"]),
    "sweep-json": (FOURBAR, "in.json", ["sweep", "in.json", *SWEEP, "-o", "./in.json"]),
    "convert-urdf": (URDF, "in.urdf", ["convert", "in.urdf", "-o", "in.urdf"]),
    "convert-mjcf": (MJCF, "in.xml", ["convert", "in.xml", "-o", "in.xml"]),
    "report-md": (FOURBAR, "in.md", ["report", "in.md", "-o", "in.md"]),
    "report-default": (FOURBAR, "in.html", ["report", "in.html"]),
}


@pytest.mark.parametrize("case", list(ONTO_ITSELF))
def test_an_output_onto_its_input_is_refused_naming_both(case, tmp_path):
    source, name, argv = ONTO_ITSELF[case]
    _copy(tmp_path, source, name)
    before = _tree(tmp_path)
    r = run_cli_capped(argv, cwd=tmp_path)
    _refused(r, f"is the input file {name}", "(the same file)")
    assert argv[-1] in r.err or case == "report-default"
    assert _tree(tmp_path) == before


@pytest.mark.parametrize("link", ["hard", "symbolic-output", "symbolic-input"])
def test_a_link_to_the_input_is_the_input(link, tmp_path):
    path = _copy(tmp_path, FOURBAR, "in.yaml")
    if link == "hard":
        os.link(path, tmp_path / "other.yaml")
        argv = ["analyze", "in.yaml", "-o", "other.yaml"]
    elif link == "symbolic-output":
        (tmp_path / "other.yaml").symlink_to("in.yaml")
        argv = ["analyze", "in.yaml", "-o", "other.yaml"]
    else:  # the input given through a link, the output its target
        (tmp_path / "other.yaml").symlink_to(path)
        argv = ["sweep", "other.yaml", *SWEEP, "-o", "in.yaml"]
    before = _tree(tmp_path)
    r = run_cli_capped(argv, cwd=tmp_path)
    _refused(r, f"-o {argv[-1]}", "is the input file", "(the same file)")
    assert _tree(tmp_path) == before


def test_a_markdown_reports_figures_never_replace_the_input(tmp_path):
    # the input is a YAML file that sits where the report's first figure goes
    (tmp_path / "r_files").mkdir()
    _copy(tmp_path / "r_files", FOURBAR, "graph.svg")
    before = _tree(tmp_path)
    r = run_cli_capped(["report", "r_files/graph.svg", *QUICK, "-o", "r.md"], cwd=tmp_path)
    _refused(r, "graph.svg", "is the input file r_files/graph.svg")
    assert _tree(tmp_path) == before
    # a file where the figures' folder goes is not replaced either
    shutil.rmtree(tmp_path / "r_files")
    _copy(tmp_path, FOURBAR, "r_files")
    before = _tree(tmp_path)
    r = run_cli_capped(["report", "r_files", "-o", "r.md"], cwd=tmp_path)
    _refused(r, "r_files", "is the input")
    assert _tree(tmp_path) == before


# --------------------------------------------------------------------------- item 2


def test_a_link_planted_at_the_old_partial_name_is_never_followed(tmp_path):
    _copy(tmp_path, FOURBAR, "in.yaml")
    victim = tmp_path / "victim.txt"
    victim.write_text("the user's data\n")
    (tmp_path / "out.json.partial").symlink_to(victim)
    r = run_cli_capped(["sweep", "in.yaml", *SWEEP, "-o", "out.json"], cwd=tmp_path)
    assert r.status == 0, r.err
    assert victim.read_text() == "the user's data\n"
    assert len(json.loads((tmp_path / "out.json").read_text())["points"]) == 5
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "in.yaml",
        "out.json",
        "out.json.partial",
        "victim.txt",
    ]


def test_two_sweeps_onto_one_output_both_succeed(tmp_path):
    _copy(tmp_path, FOURBAR, "in.yaml")
    argv = ["sweep", "in.yaml", "--vary", "A=0:360:30", "--quiet", "-o", "out.json"]
    cmd = [sys.executable, "-m", "mechsing", *argv]
    procs = [
        subprocess.Popen(cmd, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        for _ in range(2)
    ]
    for p in procs:
        _, err = p.communicate(timeout=WALL_CLOCK)
        assert p.returncode == 0, err
    assert len(json.loads((tmp_path / "out.json").read_text())["points"]) == 13
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.yaml", "out.json"]


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_an_interrupted_sweep_leaves_the_output_as_it_was(sig, tmp_path):
    _copy(tmp_path, FOURBAR, "in.yaml")
    out = tmp_path / "out.json"
    out.write_text("the previous sweep\n")
    argv = ["sweep", "in.yaml", "--vary", "A=0:360:0.01", "--quiet", "-o", "out.json"]
    p = subprocess.Popen(
        [sys.executable, "-m", "mechsing", *argv],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        deadline = time.monotonic() + WALL_CLOCK
        while not [q for q in tmp_path.iterdir() if q.name.endswith(".partial")]:
            assert p.poll() is None and time.monotonic() < deadline, "no temporary file"
            time.sleep(0.05)
        p.send_signal(sig)
        p.communicate(timeout=WALL_CLOCK)
    finally:
        p.kill()
    assert p.returncode != 0
    assert out.read_text() == "the previous sweep\n"
    assert sorted(q.name for q in tmp_path.iterdir()) == ["in.yaml", "out.json"]


def test_an_output_keeps_its_permissions_and_links_and_devices_are_written_through(tmp_path):
    _copy(tmp_path, FOURBAR, "in.yaml")
    kept = tmp_path / "kept.txt"
    kept.write_text("old\n")
    kept.chmod(0o640)
    assert (
        run_cli_capped(["analyze", "in.yaml", *QUICK, "-o", "kept.txt"], cwd=tmp_path).status == 0
    )
    assert stat.S_IMODE(kept.stat().st_mode) == 0o640 and "four-bar" in kept.read_text()
    # a new file gets the usual permissions: 0666 less the umask
    mask = os.umask(0)
    os.umask(mask)
    assert run_cli_capped(["analyze", "in.yaml", *QUICK, "-o", "new.txt"], cwd=tmp_path).status == 0
    assert stat.S_IMODE((tmp_path / "new.txt").stat().st_mode) == 0o666 & ~mask
    # an output that is a link is written to the link's target; the link stays
    (tmp_path / "link.txt").symlink_to("new.txt")
    (tmp_path / "new.txt").write_text("")
    assert (
        run_cli_capped(["analyze", "in.yaml", *QUICK, "-o", "link.txt"], cwd=tmp_path).status == 0
    )
    assert (tmp_path / "link.txt").is_symlink() and "four-bar" in (tmp_path / "new.txt").read_text()
    # /dev/null is written to, never replaced by a regular file
    r = run_cli_capped(["analyze", "in.yaml", *QUICK, "-o", os.devnull], cwd=tmp_path)
    assert r.status == 0, r.err
    assert stat.S_ISCHR(os.stat(os.devnull).st_mode)
    # /dev/stdout that is a pipe (the runner's) is written to as a stream
    r = run_cli_capped(["analyze", "in.yaml", *QUICK, "-o", "/dev/stdout"], cwd=tmp_path)
    assert r.status == 0 and r.out.startswith("mechsing analysis: four-bar"), r.err
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "in.yaml",
        "kept.txt",
        "link.txt",
        "new.txt",
    ]


# --------------------------------------------------------------------------- item 3

MISSING = {
    "analyze": ["analyze", "in.yaml", "-o", "no/such/dir/out.txt"],
    "sweep": ["sweep", "in.yaml", *SWEEP, "-o", "no/such/dir/out.json"],
    "report-html": ["report", "in.yaml", "-o", "no/such/dir/r.html"],
    "report-md": ["report", "in.yaml", "-o", "no/such/dir/r.md"],
    "convert": ["convert", "in.urdf", "-o", "no/such/dir/out.yaml"],
}


@pytest.mark.parametrize("case", list(MISSING))
def test_a_missing_directory_is_refused_by_every_command(case, tmp_path):
    _copy(tmp_path, FOURBAR, "in.yaml")
    _copy(tmp_path, URDF, "in.urdf")
    before = _tree(tmp_path)
    r = run_cli_capped(MISSING[case], cwd=tmp_path)
    _refused(r, "the directory no/such/dir does not exist", "mechsing creates no directories")
    assert _tree(tmp_path) == before


@pytest.mark.parametrize("command", [["analyze"], ["sweep", *SWEEP], ["report"]])
def test_a_directory_as_the_output_is_refused(command, tmp_path):
    _copy(tmp_path, FOURBAR, "in.yaml")
    (tmp_path / "sub").mkdir()
    before = _tree(tmp_path)
    out = "sub.md" if command == ["report"] else "."
    if out == "sub.md":  # a directory with a report's name
        (tmp_path / "sub.md").mkdir()
        before = _tree(tmp_path)
    r = run_cli_capped([command[0], "in.yaml", *command[1:], "-o", out], cwd=tmp_path)
    _refused(r, f"-o {out}: is a directory")
    assert _tree(tmp_path) == before


# --------------------------------------------------------------------------- item 4

#: every kind of special file through analyze, and the endless device through every command
NOT_REGULAR = [
    *[(k, ["analyze"]) for k in ("/dev/zero", "/dev/urandom", "directory", "socket")],
    ("/dev/zero", ["solve", "--config", "reference"]),
    ("/dev/zero", ["sweep", *SWEEP]),
    ("/dev/zero", ["report", "-o", "r.html"]),
    ("/dev/zero", ["condition"]),
    ("/dev/urandom", ["convert"]),
]


@pytest.mark.parametrize(
    ("special", "command"), NOT_REGULAR, ids=[f"{c[0]}-{k}" for k, c in NOT_REGULAR]
)
def test_a_file_that_is_not_regular_is_refused_before_it_is_read(special, command, tmp_path):
    work = tmp_path / "w"
    work.mkdir()
    if special == "directory":
        path = str(tmp_path)
    elif special == "socket":
        path = str(tmp_path / "s")
        server = socket.socket(socket.AF_UNIX)
        server.bind(path)
    else:
        path = special
    try:
        r = run_cli_capped([command[0], path, *command[1:]], cwd=work, timeout=60)
    finally:
        if special == "socket":
            server.close()
    kind = {"directory": "a directory", "socket": "a socket"}.get(special, "a character device")
    _refused(r, path, f"not a regular file ({kind})")
    assert list(work.iterdir()) == []


def _pipe_writing(data: bytes, forever: bool = False) -> int:
    """The read end of a pipe a thread writes ``data`` into (over and over with
    ``forever``, until the reader goes); the caller passes it to the child."""
    r, w = os.pipe()

    def write() -> None:
        try:
            with os.fdopen(w, "wb") as f:
                f.write(data)
                while forever:
                    f.write(data)
        except (BrokenPipeError, OSError):
            pass

    threading.Thread(target=write, daemon=True).start()
    return r


def test_a_pipe_is_read_like_a_file(tmp_path):
    r_end = _pipe_writing(FOURBAR.read_bytes())
    try:
        r = run_cli_capped(
            ["analyze", f"/dev/fd/{r_end}", "--config", "crank-30"], cwd=tmp_path, pass_fds=(r_end,)
        )
    finally:
        os.close(r_end)
    assert r.status == 0, r.err
    assert "four-bar" in r.out and "regular: no singularity" in r.out
    assert list(tmp_path.iterdir()) == []


def test_an_endless_pipe_stops_at_the_size_cap(tmp_path):
    r_end = _pipe_writing(b"a" * 65536, forever=True)
    try:
        r = run_cli_capped(["analyze", f"/dev/fd/{r_end}"], cwd=tmp_path, pass_fds=(r_end,))
    finally:
        os.close(r_end)
    from mechsing.reader import LARGEST_FILE

    _refused(r, f"/dev/fd/{r_end}", f"more than {LARGEST_FILE:,} bytes")


def test_a_fifo_nobody_writes_to_is_an_error_not_a_hang(tmp_path):
    fifo = tmp_path / "in.yaml"
    os.mkfifo(fifo)
    started = time.monotonic()
    r = run_cli_capped(
        ["analyze", "in.yaml"],
        cwd=tmp_path,
        timeout=60,
        setup="import mechsing.files\nmechsing.files.PIPE_WAIT_SECONDS = 1.0",
    )
    _refused(r, "in.yaml", "no data arrived for 1 s", "no program writes to")
    assert time.monotonic() - started < 60


def test_a_fifo_whose_writer_comes_later_is_read(tmp_path):
    fifo = tmp_path / "in.yaml"
    os.mkfifo(fifo)

    def write() -> None:
        time.sleep(1.0)
        with open(fifo, "wb") as f:  # blocks until mechsing has opened it
            f.write(FOURBAR.read_bytes())

    writer = threading.Thread(target=write, daemon=True)
    writer.start()
    r = run_cli_capped(["analyze", "in.yaml", "--config", "crank-30"], cwd=tmp_path, timeout=60)
    writer.join(5)
    assert r.status == 0, r.err
    assert "regular: no singularity" in r.out


# --------------------------------------------------------------------------- item 14

EVERY_COMMAND = {
    "analyze": (["analyze", "{FOURBAR}", "--config", "crank-30"], None),
    "analyze-o": (["analyze", "{FOURBAR}", "--config", "crank-30", "-o", "a.json"], "a.json"),
    "solve": (["solve", "{FOURBAR}", "--config", "crank-30"], None),
    "sweep": (["sweep", "{FOURBAR}", *SWEEP, "-o", "s.csv"], "s.csv"),
    "report-html": (["report", "{FOURBAR}", "--config", "crank-30"], "fourbar.html"),
    "report-md": (["report", "{FOURBAR}", "--config", "crank-30", "-o", "r.md"], "r.md"),
    "condition": (["condition", "{FOURBAR}"], None),
    "convert": (["convert", "{URDF}", "-o", "ur5.yaml"], "ur5.yaml"),
    "catalog": (["catalog", "S"], None),
    "identify": (["identify", "--", "0,0,1,0,0,0"], None),
    "schema": (["schema"], None),
}


@pytest.mark.parametrize("case", list(EVERY_COMMAND))
def test_a_command_writes_nothing_but_its_output(case, tmp_path):
    """In an empty working directory, with an empty home and temporary folder (and no
    MPLCONFIGDIR): afterwards only the asked output is there."""
    argv, output = EVERY_COMMAND[case]
    argv = [a.format(FOURBAR=FOURBAR, URDF=URDF) for a in argv]
    work, home, tmp = (tmp_path / n for n in ("work", "home", "tmp"))
    for d in (work, home, tmp):
        d.mkdir()
    env = {
        "HOME": str(home),
        "TMPDIR": str(tmp),
        "MPLCONFIGDIR": "",
        "XDG_CACHE_HOME": "",
        "XDG_CONFIG_HOME": "",
        "DASK_TEMPORARY_DIRECTORY": "",
    }
    r = run_cli_capped(argv, cwd=work, env=env)
    assert r.status == 0, r.err
    expected = {output} if output else set()
    if output and output.endswith(".md"):
        expected.add(output[:-3] + "_files")
    assert {p.name for p in work.iterdir()} == expected
    assert list(home.iterdir()) == [] and list(tmp.iterdir()) == []
