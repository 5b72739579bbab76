"""The tests' one way to run the command line: in-process (``mechsing.cli.main``, stdout and
stderr captured) or as the installed command in a child process (``python -m mechsing``), both
giving the exit status, stdout and stderr; and the parsed JSON of a successful run."""

from __future__ import annotations

import contextlib
import io
import json
import os
import subprocess
import sys
import warnings
from pathlib import Path
from typing import NamedTuple

ROOT = Path(__file__).resolve().parents[1]


class CliRun(NamedTuple):
    """One run of the command line."""

    status: int
    out: str
    err: str


def run_cli(argv: list[str]) -> CliRun:
    """``mechsing.cli.main(argv)`` in-process: (exit status, stdout, stderr)."""
    from mechsing.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main([str(a) for a in argv])
    return CliRun(rc, out.getvalue(), err.getvalue())


def runtime_warnings(argv: list[str]) -> list[str]:
    """The RuntimeWarnings (numpy's overflow, invalid value ...) an in-process run raises,
    every time one is raised: pytest would swallow them from stderr, so they are recorded."""
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        run_cli(argv)
    return [f"{w.filename}:{w.lineno}: {w.message}" for w in seen if w.category is RuntimeWarning]


def run_cli_subprocess(
    argv: list[str],
    timeout: float = 120,
    cwd: Path | str = ROOT,
    env: dict[str, str] | None = None,
) -> CliRun:
    """``python -m mechsing ARGV`` in a child process (the command as users run it: a fresh
    interpreter, main thread); raises subprocess.TimeoutExpired after ``timeout`` seconds;
    ``env`` adds to (or overrides) this process's environment."""
    r = subprocess.run(
        [sys.executable, "-m", "mechsing", *map(str, argv)],
        cwd=cwd,
        env=None if env is None else {**os.environ, **env},
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    return CliRun(r.returncode, r.stdout, r.stderr)


#: the hard caps of a test about resources: address space (bytes) and wall clock (seconds)
ADDRESS_SPACE = 1 << 30
WALL_CLOCK = 120.0


def _capped() -> None:  # in the child, before it runs anything
    import resource

    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


def run_cli_capped(
    argv: list[str],
    cwd: Path | str,
    timeout: float = WALL_CLOCK,
    env: dict[str, str] | None = None,
    setup: str = "",
    pass_fds: tuple[int, ...] = (),
) -> CliRun:
    """``python -m mechsing ARGV`` in a child process under hard caps: at most
    :data:`ADDRESS_SPACE` bytes of address space, killed after ``timeout`` seconds
    (subprocess.TimeoutExpired).  ``env`` replaces the environment's variables it names
    (a value of "" removes one); ``setup`` is Python run in the child before the command
    (e.g. a shorter wait of mechsing's); ``pass_fds`` are inherited (a pipe as /dev/fd/N)."""
    import os

    child_env = dict(os.environ)
    for k, v in (env or {}).items():
        if v:
            child_env[k] = v
        else:
            child_env.pop(k, None)
    if setup:
        code = f"import sys\n{setup}\nfrom mechsing.cli import main\nsys.exit(main(sys.argv[1:]))"
        cmd = [sys.executable, "-c", code, *map(str, argv)]
    else:
        cmd = [sys.executable, "-m", "mechsing", *map(str, argv)]
    r = subprocess.run(
        cmd,
        cwd=cwd,
        env=child_env,
        capture_output=True,
        text=True,
        timeout=timeout,
        preexec_fn=_capped,
        pass_fds=pass_fds,
    )
    return CliRun(r.returncode, r.stdout, r.stderr)


def cli_json(argv: list[str]) -> dict:
    """The parsed JSON stdout of an in-process run, which must exit 0 without a traceback."""
    rc, out, err = run_cli(argv)
    assert rc == 0, (argv, rc, err)
    assert "Traceback" not in err, err
    return json.loads(out)
