"""What the command costs before it works: the CPU time of ``mechsing --version``, ``-h``,
``analyze -h`` and ``analyze`` of the four-bar, and what each imports.

usage:
    python benchmarks/startup.py [--tree [LABEL=]PATH ...] [--repeat 7]

Each run is a fresh ``python -m mechsing ARGS`` with ``PYTHONPATH`` set to one tree (default:
this checkout), started in an empty folder (so that only ``PYTHONPATH`` decides which
mechsing is imported) with one BLAS thread; its CPU time (user and system, the child's own
from ``wait4``) is what is compared, on a shared machine.  Several trees (``--tree``
repeated: before and after a change) are run in turn, command by command and round by
round, so that a change of the machine's load falls on all alike; medians over ``--repeat``
rounds after one untimed round.  The bytecode is cached as an installed package has it (in a
temporary ``PYTHONPYCACHEPREFIX``, written by the untimed round), whatever
``PYTHONDONTWRITEBYTECODE`` says.

Then, for each command and tree, one run under ``python -X importtime``: how many modules
it imported, and the import time (wall, microseconds, the interpreter's own record) of the
heavy libraries it loaded (numpy, sympy, scipy, matplotlib, networkx), by package.

Prints a Markdown table: median CPU seconds per tree, the ratio of each tree to the first,
and the heavy imports.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FOURBAR = ROOT / "examples" / "fourbar.yaml"
COMMANDS = {
    "--version": ["--version"],
    "-h": ["-h"],
    "analyze -h": ["analyze", "-h"],
    "analyze fourbar --config crank-30": ["analyze", str(FOURBAR), "--config", "crank-30"],
}
HEAVY = ("numpy", "sympy", "scipy", "matplotlib", "networkx")


def _env(tree: Path, pycache: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env.update(
        PYTHONPATH=str(tree),
        PYTHONPYCACHEPREFIX=str(pycache),
        OPENBLAS_NUM_THREADS="1",
        OMP_NUM_THREADS="1",
    )
    return env


def cpu_seconds(argv: list[str], env: dict[str, str], cwd: Path) -> float:
    """The CPU seconds (user and system) of one ``python -m mechsing ARGV`` run."""
    p = subprocess.Popen(
        [sys.executable, "-m", "mechsing", *argv],
        env=env,
        cwd=cwd,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        raise SystemExit(f"mechsing {' '.join(argv)} exited {p.returncode}")
    return usage.ru_utime + usage.ru_stime


def imports(argv: list[str], env: dict[str, str], cwd: Path) -> tuple[int, dict[str, int]]:
    """The number of modules ``mechsing ARGV`` imports and the import time (microseconds,
    self, summed by package) of the heavy libraries among them."""
    r = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "mechsing", *argv],
        env=env,
        cwd=cwd,
        capture_output=True,
        text=True,
        check=True,
    )
    count, heavy = 0, dict.fromkeys(HEAVY, 0)
    for line in r.stderr.splitlines():
        if not line.startswith("import time:") or line.count("|") != 2:
            continue
        self_us, _, name = line.removeprefix("import time:").split("|")
        if not self_us.strip().isdigit():
            continue  # the header line
        count += 1
        top = name.strip().split(".")[0]
        if top in heavy:
            heavy[top] += int(self_us)
    return count, {k: v for k, v in heavy.items() if v}


def _where(tree: Path, env: dict[str, str], cwd: Path) -> str:
    return subprocess.run(
        [sys.executable, "-c", "import mechsing; print(mechsing.__file__)"],
        env=env,
        cwd=cwd,
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument(
        "--tree",
        action="append",
        metavar="[LABEL=]PATH",
        help="a checkout of mechsing to measure (repeat: before, after); default this one",
    )
    ap.add_argument("--repeat", type=int, default=7, help="timed rounds (default 7)")
    args = ap.parse_args()
    trees: list[tuple[str, Path]] = []
    for text in args.tree or [f"this={ROOT}"]:
        label, _, path = text.rpartition("=")
        tree = Path(path).resolve()
        trees.append((label or tree.name, tree))
    with tempfile.TemporaryDirectory(prefix="mechsing-startup-") as tmp:
        cwd = Path(tmp) / "run"
        cwd.mkdir()
        envs = [_env(tree, Path(tmp) / f"pycache{i}") for i, (_, tree) in enumerate(trees)]
        for (label, tree), env in zip(trees, envs, strict=True):
            where = _where(tree, env, cwd)
            if not where.startswith(str(tree)):
                raise SystemExit(f"{label}: mechsing imported from {where}, not from {tree}")
        times: dict[str, list[list[float]]] = {c: [[] for _ in trees] for c in COMMANDS}
        for rnd in range(args.repeat + 1):  # round 0 writes the bytecode and is not counted
            for name, argv in COMMANDS.items():
                for i, env in enumerate(envs):
                    t = cpu_seconds(argv, env, cwd)
                    if rnd:
                        times[name][i].append(t)
        found = {name: [imports(argv, env, cwd) for env in envs] for name, argv in COMMANDS.items()}
    load = os.getloadavg()[0]
    print(
        f"CPU seconds per run, median of {args.repeat} (after one untimed round), trees in "
        f"turn; load average {load:.1f}; {time.strftime('%Y-%m-%d %H:%M')}\n"
    )
    labels = [label for label, _ in trees]
    head = ["command", *(f"{lb} CPU s" for lb in labels)]
    head += [f"{lb} / {labels[0]}" for lb in labels[1:]]
    head += [f"{lb}: modules, heavy imports (ms)" for lb in labels]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for name in COMMANDS:
        med = [statistics.median(ts) for ts in times[name]]
        row = [f"`mechsing {name}`", *(f"{m:.3f}" for m in med)]
        row += [f"{m / med[0]:.2f}" for m in med[1:]]
        for count, heavy in found[name]:
            libs = ", ".join(f"{k} {v / 1000:.0f}" for k, v in heavy.items()) or "none"
            row.append(f"{count}: {libs}")
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
