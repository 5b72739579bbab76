"""The exact part of ``benchmarks/scale.py``: exact mode's time over float's, with the verdicts.

usage: python benchmarks/_scale_exact.py [--quick] [--repeat 3]

Cases: every bundled example (``examples/*.yaml``) and random instances with exact data
(``_exact_instances.py``): Bennett linkages with rational data (degree 1) and with
lengths in QQ(sqrt k) (degree 2), line- and plane-symmetric Bricard 6R linkages
with points rational or in QQ(sqrt k) (degrees 1, 2), and 6-UPS platforms at a rational pose with leg lengths in QQ, QQ(sqrt 2)
and QQ(sqrt 2, sqrt 3) (degrees 1, 2, 4).

For each case, in this process: one run of each mode over all the file's
configurations (exact mode within its time limit), which also sorts the configurations
into those exact mode analyses, those it refuses (not exact data, or values left to
solve: an ``error`` entry) and those it stops at its time limit (60 s, --quick 10 s);
that first exact run of the whole file is reported (it pays for the primitive elements
of the number fields, cached for the process afterwards).  Then both modes are timed on
the configurations exact mode analyses (the same work for both), and, when the file has
configurations exact mode refuses or stops, on the whole file as well (a refusal is
timed as what exact mode does with it: ``mechsing.analyze`` of the file, as a user runs
it).  Times are CPU seconds of this process (the machine is shared: wall time would
count the other processes), the median of ``--repeat`` runs of each mode, the two modes
alternating run by run, with sympy's cache cleared before every run (a repeated exact
run would otherwise find the previous run's results in it).  The verdicts are compared
per configuration: classes of the singularities, closure rank, mobility and every rank
decision's rank.  The field degree is that of the data as mechsing holds them (axes
normalised) and of the cosines and sines of the joint values analysed
(:func:`_exact_instances.mechanism_degree`).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import sympy
from _exact_instances import FAMILIES, mechanism_degree

import mechsing
from mechsing.model import load

ROOT = Path(__file__).resolve().parents[1]

#: random instances per family (quick: one), and exact mode's time limit per configuration
INSTANCES = 3
TIME_LIMIT = 60.0
QUICK_TIME_LIMIT = 10.0


def verdict(conf: dict) -> tuple:
    """What must agree between exact and float at one configuration."""
    mob = conf.get("mobility") or {}
    return (
        tuple(sorted(s["class"] for s in conf.get("singularities", []))),
        (conf.get("closure_rank") or {}).get("rank"),
        tuple(sorted(mob.items())),
        tuple((d["test"], d["rank"], d.get("generic")) for d in conf.get("decisions", [])),
    )


def _kind(conf: dict) -> str:
    err = conf.get("error")
    if err is None:
        return "exact"
    return "limit" if "its time limit" in err else "refused"


def _run(path: Path, precision: str, configs: list[str] | None, limit: float) -> tuple[float, dict]:
    sympy.core.cache.clear_cache()
    t0 = time.process_time()
    res = mechsing.analyze(path, configs=configs, precision=precision, time_limit=limit)
    return time.process_time() - t0, res.to_json()


def _alternating(
    path: Path, configs: list[str] | None, repeat: int, limit: float
) -> tuple[float, float, list[dict]]:
    """Median CPU seconds of float and of exact over ``configs`` (None: the whole file),
    the modes alternating run by run; and the exact runs' results."""
    floats, exacts, results = [], [], []
    for _ in range(repeat):
        floats.append(_run(path, "float", configs, limit)[0])
        t, res = _run(path, "exact", configs, limit)
        exacts.append(t)
        results.append(res)
    return statistics.median(floats), statistics.median(exacts), results


def measure(path: Path, repeat: int, limit: float) -> dict:
    """One case: counts of configurations analysed / refused / stopped, median seconds of
    each mode on the analysed ones and on the whole file, the first exact run of the whole
    file, the verdicts' agreement and the field degree."""
    first, exact0 = _run(path, "exact", None, limit)
    _, float0 = _run(path, "float", None, limit)
    kinds = {c["name"]: _kind(c) for c in exact0["configurations"]}
    done = [n for n, k in kinds.items() if k == "exact"]
    floats = {c["name"]: c for c in float0["configurations"]}
    disagree = [
        c["name"]
        for c in exact0["configurations"]
        if c["name"] in done and verdict(c) != verdict(floats[c["name"]])
    ]
    row = {
        "degree": mechanism_degree(load(str(path)), done),
        "exact": len(done),
        "refused": sum(k == "refused" for k in kinds.values()),
        "limit": sum(k == "limit" for k in kinds.values()),
        "disagree": disagree,
        "float_s": None,
        "exact_s": None,
        "stopped": [],
        "first_s": first,
        "file_float_s": None,
        "file_exact_s": None,
    }
    if done:
        row["float_s"], row["exact_s"], runs = _alternating(path, done, repeat, limit)
        # a configuration that finished near the limit once may be stopped in a timed run
        row["stopped"] = sorted(
            {c["name"] for res in runs for c in res["configurations"] if c.get("error")}
        )
    if len(done) < len(kinds):
        row["file_float_s"], row["file_exact_s"], _ = _alternating(path, None, repeat, limit)
    else:  # the whole file is what was timed
        row["file_float_s"], row["file_exact_s"] = row["float_s"], row["exact_s"]
    return row


def cases(tmp: Path, quick: bool) -> list[tuple[str, Path]]:
    """The bundled examples, then the random instances (written to ``tmp``)."""
    out = [(p.stem, p) for p in sorted((ROOT / "examples").glob("*.yaml"))]
    for make in FAMILIES.values():
        for seed in range(1 if quick else INSTANCES):
            inst = make(seed)
            path = tmp / f"{inst.name}.yaml"
            path.write_text(inst.text)
            out.append((inst.name, path))
    return out


def part_exact(repeat: int, quick: bool) -> str:
    """The exact/float table (Markdown), the worst ratio and the median ratio per field degree."""
    limit = QUICK_TIME_LIMIT if quick else TIME_LIMIT
    repeat = 1 if quick else repeat
    lines = [
        f"Exact mode's time limit {limit:g} s per configuration; CPU seconds, medians of "
        f"{repeat} runs per mode (alternating); analysed: both modes on the configurations "
        "exact mode analyses; whole file: `mechsing.analyze` of the file (exact's refusals "
        "timed as what it does); first: exact's first whole-file run (the fields' primitive "
        "elements).",
        "",
        "| case | field degree | configurations exact / refused / time limit "
        "| analysed: float s | exact s | exact / float "
        "| whole file: float s | exact s | exact / float | first exact run s | verdicts agree |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    by_degree: dict[int, list[float]] = {}
    worst: tuple[float, str] | None = None
    limits: list[str] = []
    stopped: list[str] = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, path in cases(Path(tmp), quick):
            row = measure(path, repeat, limit)
            if row["exact_s"] is None:
                times, ratio = "| - | - | - ", None
            else:
                ratio = row["exact_s"] / row["float_s"]
                star = "*" if row["stopped"] else ""
                times = f"| {row['float_s']:.3f} | {row['exact_s']:.3f}{star} | {ratio:.1f}{star} "
                if row["stopped"]:
                    stopped.append(f"{name} ({', '.join(row['stopped'])})")
                by_degree.setdefault(row["degree"], []).append(ratio)
                if worst is None or ratio > worst[0]:
                    worst = (ratio, name)
            ff, fe = row["file_float_s"], row["file_exact_s"]
            whole = (
                f"| {ff:.3f} | {fe:.3f} | {fe / ff:.1f} "
                if ff and fe is not None
                else "| - | - | - "
            )
            if row["limit"]:
                limits.append(f"{name} ({row['limit']})")
            agree = "no: " + ", ".join(row["disagree"]) if row["disagree"] else "yes"
            if not row["exact"]:
                agree = "-"
            lines.append(
                f"| {name} | {row['degree']} | {row['exact']} / {row['refused']} / {row['limit']} "
                f"{times}{whole}| {row['first_s']:.3f} | {agree} |"
            )
            print(lines[-1], file=sys.stderr, flush=True)
    lines.append("")
    if worst is not None:
        lines.append(
            f"Worst exact / float (analysed configurations): {worst[0]:.1f} ({worst[1]}); "
            "the target is 5."
        )
    lines.append(
        "Median exact / float by field degree: "
        + "; ".join(
            f"degree {d}: {statistics.median(v):.1f} ({len(v)} cases)"
            for d, v in sorted(by_degree.items())
        )
        + "."
    )
    lines.append(
        "Time limit hit (configurations): " + (", ".join(limits) if limits else "none") + "."
    )
    if stopped:
        lines.append(
            "* a configuration exact mode finished in its untimed run was stopped at the time "
            "limit in a timed run (the time includes the limit): " + ", ".join(stopped) + "."
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--quick", action="store_true", help="one instance per family, one run")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    print(part_exact(args.repeat, args.quick))
    return 0


if __name__ == "__main__":
    sys.exit(main())
