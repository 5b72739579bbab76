"""Snapshot the JSON of every bundled example in several precision modes, or compare two
snapshots: the check that a restructuring changed no verdict.

usage:
    python benchmarks/json_snapshot.py dump OUT.json [--modes float mp:30 exact auto] [--sweeps]
    python benchmarks/json_snapshot.py compare OLD.json NEW.json

``dump`` runs ``mechsing analyze --format json`` on examples/*.yaml in each mode (exact
mode with its default time limit) and writes ``{mode: {file: json}}``; a file a mode
refuses is stored as its error text.  ``compare`` walks both snapshots and reports every difference beyond
these rules: keys may be added (never removed); strings, booleans, integers and None
must be equal; floats must agree to 1e-12 relative in float and auto configurations
decided in float, to 10^(5-N) relative at mp:N, and exactly in exact mode (margins are
compared with the same tolerance as the values).  It prints each difference with its
path and exits 1 when there is one.

``--sweeps`` also stores, under the mode ``sweep``, the JSON of ``mechsing sweep`` on the
sweep benchmark's paths (benchmarks/sweep.py, density 2, and its five-bar grid, coarser);
their floats are compared to 1e-9 relative.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def dump(out: Path, modes: list[str], *, text: bool = False, sweeps: bool = False) -> None:
    """Run the command line (not the Python API, which a restructuring may move) on
    every example in every mode and store its JSON, or its error text when it exits
    with status 2; ``text`` also stores the text report."""
    snap: dict[str, dict[str, Any]] = {}
    for mode in modes:
        snap[mode] = {}
        for path in sorted((ROOT / "examples").glob("*.yaml")):
            cmd = [sys.executable, "-m", "mechsing", "analyze", str(path), "--precision", mode]
            run = subprocess.run([*cmd, "--format", "json"], capture_output=True, text=True)
            if run.returncode == 2:
                snap[mode][path.name] = {"refused": run.stderr.strip()}
            else:
                snap[mode][path.name] = json.loads(run.stdout)
            if text:
                snap[mode][path.name + ".txt"] = subprocess.run(
                    cmd, capture_output=True, text=True
                ).stdout
            print(f"{mode:6s} {path.name} exit {run.returncode}", file=sys.stderr)
    if sweeps:
        dump_sweeps(snap)
    out.write_text(json.dumps(snap, indent=1, sort_keys=True))


def _sweep_cases() -> list[tuple[str, list[str]]]:
    """The sweep benchmark's paths as (label, command-line arguments after ``sweep``)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import numpy as np
    from sweep import _mechsing_cases, _spec

    out = []
    for file, specs, _ in _mechsing_cases(2):
        args = [str(ROOT / "examples" / file)]
        for spec in specs:
            args += ["--vary", spec]
        out.append((file, args))
    v = np.linspace(-0.4, 0.4, 11)
    five = [str(ROOT / "examples" / "five_bar.yaml")]
    out.append(("five_bar.yaml", [*five, "--vary", _spec("A1", v), "--vary", _spec("A2", v)]))
    return out


def dump_sweeps(snap: dict[str, dict[str, Any]]) -> None:
    """Store the sweep JSON of the benchmark's paths under ``snap["sweep"]``."""
    snap["sweep"] = {}
    for label, args in _sweep_cases():
        cmd = [sys.executable, "-m", "mechsing", "sweep", *args, "--format", "json"]
        run = subprocess.run(cmd, capture_output=True, text=True)
        if run.returncode not in (0, 1):
            snap["sweep"][label] = {"refused": run.stderr.strip()}
        else:
            snap["sweep"][label] = json.loads(run.stdout)
        print(f"sweep  {label} exit {run.returncode}", file=sys.stderr)


def _tolerance(precision: str) -> float:
    if precision.startswith("mp:"):
        return 10.0 ** (5 - int(precision[3:]))
    return 0.0 if precision == "exact" else 1e-12


def _walk(old: Any, new: Any, path: str, tol: float, out: list[str]) -> None:
    if isinstance(old, dict) and isinstance(new, dict):
        for k in old:
            if k not in new:
                out.append(f"{path}.{k}: removed")
                continue
            if k == "configurations":
                for i, (a, b) in enumerate(zip(old[k], new[k], strict=False)):
                    t = _tolerance(a.get("precision", "float"))
                    _walk(a, b, f"{path}.{k}[{i}:{a.get('name')}]", max(t, 1e-12), out)
                if len(old[k]) != len(new[k]):
                    out.append(f"{path}.{k}: {len(old[k])} -> {len(new[k])} entries")
                continue
            _walk(old[k], new[k], f"{path}.{k}", tol, out)
        return
    if isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            out.append(f"{path}: length {len(old)} -> {len(new)}")
            return
        for i, (a, b) in enumerate(zip(old, new, strict=True)):
            _walk(a, b, f"{path}[{i}]", tol, out)
        return
    if isinstance(old, float) and isinstance(new, float | int) and not isinstance(new, bool):
        scale = max(abs(old), abs(new), 1e-300)
        if abs(old - new) > tol * scale:
            out.append(f"{path}: {old!r} -> {new!r}")
        return
    if old != new:
        out.append(f"{path}: {old!r} -> {new!r}")


def compare(old_path: Path, new_path: Path) -> int:
    old, new = json.loads(old_path.read_text()), json.loads(new_path.read_text())
    diffs: list[str] = []
    for mode in old:
        if mode not in new:
            diffs.append(f"{mode}: missing")
            continue
        tol = 1e-9 if mode == "sweep" else 1e-12
        for name in old[mode]:
            _walk(old[mode][name], new[mode].get(name), f"{mode}/{name}", tol, diffs)
    for d in diffs:
        print(d)
    print(f"{len(diffs)} difference(s)")
    return 1 if diffs else 0


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("dump")
    d.add_argument("out", type=Path)
    d.add_argument("--modes", nargs="+", default=["float", "mp:30", "exact", "auto"])
    d.add_argument("--text", action="store_true", help="also store the text reports")
    d.add_argument("--sweeps", action="store_true", help="also store the benchmark's sweeps")
    c = sub.add_parser("compare")
    c.add_argument("old", type=Path)
    c.add_argument("new", type=Path)
    args = p.parse_args()
    if args.cmd == "dump":
        dump(args.out, args.modes, text=args.text, sweeps=args.sweeps)
        return 0
    return compare(args.old, args.new)


if __name__ == "__main__":
    sys.exit(main())
