"""Snapshot the JSON of every bundled example in several precision modes, or compare two
snapshots: the check that a restructuring changed no verdict.

usage:
    python benchmarks/json_snapshot.py dump OUT.json [--modes float mp:30 exact auto]
    python benchmarks/json_snapshot.py compare OLD.json NEW.json

``dump`` runs ``mechsing.analyze`` on examples/*.yaml in each mode (exact mode with its
default time limit) and writes ``{mode: {file: json}}``; a file a mode refuses is stored
as its error text.  ``compare`` walks both snapshots and reports every difference beyond
these rules: keys may be added (never removed); strings, booleans, integers and None
must be equal; floats must agree to 1e-12 relative in float and auto configurations
decided in float, to 10^(5-N) relative at mp:N, and exactly in exact mode (margins are
compared with the same tolerance as the values).  It prints each difference with its
path and exits 1 when there is one.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def dump(out: Path, modes: list[str]) -> None:
    from mechsing.analysis import analyze
    from mechsing.errors import UserError
    from mechsing.report.render import _clean

    snap: dict[str, dict[str, Any]] = {}
    for mode in modes:
        snap[mode] = {}
        for path in sorted((ROOT / "examples").glob("*.yaml")):
            try:
                snap[mode][path.name] = _clean(analyze(path, precision=mode).to_json())
            except UserError as exc:
                snap[mode][path.name] = {"refused": str(exc)}
            print(f"{mode:6s} {path.name}", file=sys.stderr)
    out.write_text(json.dumps(snap, indent=1, sort_keys=True))


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
        for name in old[mode]:
            _walk(old[mode][name], new[mode].get(name), f"{mode}/{name}", 1e-12, diffs)
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
    c = sub.add_parser("compare")
    c.add_argument("old", type=Path)
    c.add_argument("new", type=Path)
    args = p.parse_args()
    if args.cmd == "dump":
        dump(args.out, args.modes)
        return 0
    return compare(args.old, args.new)


if __name__ == "__main__":
    sys.exit(main())
