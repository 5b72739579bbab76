"""Sweep a mechanism along a path or over a grid and locate its singularities.

One --vary NAME=START:STOP:STEP is a path, two are a grid (rows in the first
variable, one per sample of the second).  NAME is a joint coordinate (A, C1[1])
or a coordinate of the output's pose (pose.x, pose.y, pose.z of its reference
point; pose.rx, pose.ry, pose.rz, its rotation vector), and the range is in the
file's units.  Every sample gets each test's rank and smallest relative singular
value in float; every singularity met on the way is located between the samples
and classified by the full analysis at --precision (default auto).

JSON and CSV are in SI units and radians; they are written as the rows are done
(memory bounded by a row).  The text, written at the end, also shows the file's
units.  With -o OUT and no --format, the format follows OUT's extension (.json,
.csv; anything else is text); OUT appears only once the sweep is complete.

A progress bar is shown on standard error when it is a terminal (not with
--quiet).  Exit status: 0 success, 2 bad input, 3 the sweep cannot start (its
--from configuration does not close, or the first sample cannot be reached).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

if TYPE_CHECKING:  # the command's layers load when it runs: `mechsing --help` stays fast
    from mechsing.sweeps import SweepRun

NAME = "sweep"
HELP = "locate singularities along a path or over a grid of joint values or poses"

#: the formats, and the extensions of -o that choose them when --format is not given
FORMATS = ("text", "json", "csv")
_BY_EXTENSION = {".json": "json", ".csv": "csv", ".txt": "text"}


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE", help="mechanism file (YAML or JSON), URDF or MJCF")
    p.add_argument(
        "--vary",
        action="append",
        required=True,
        metavar="NAME=START:STOP:STEP",
        help="a swept variable in the file's units: once for a path, twice for a grid "
        "(e.g. --vary A=0:360:1, --vary C1[1]=0:0.5:0.01, --vary pose.x=-0.1:0.1:0.01); a "
        "joint given without a range (--vary J2) is swept over its limits in 200 steps",
    )
    p.add_argument(
        "--from",
        dest="from_config",
        metavar="CONFIG",
        help="the configuration the sweep starts from (its assembly mode is kept; "
        "default reference; with --set, the one the configuration cli is solved from, and the "
        "sweep starts from cli)",
    )
    from mechsing.cli.options import add_scene_options, add_set_option

    add_set_option(p, from_option=False)
    add_scene_options(p)
    p.add_argument(
        "--precision",
        default="auto",
        metavar="MODE",
        help="precision of the classification of the located points: auto (default), "
        "float or mp:N (the measures are always float)",
    )
    p.add_argument(
        "--format",
        choices=FORMATS,
        default=None,
        help="text (default), json or csv; with -o and no --format, from OUT's extension",
    )
    p.add_argument("-o", "--output", metavar="OUT", help="write to OUT instead of standard output")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument(
        "--workers",
        type=_positive_int("--workers"),
        metavar="N",
        help="distribute the rows of a grid over a local Dask cluster of N processes",
    )
    p.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="distribute the rows of a grid with the Dask scheduler at ADDRESS",
    )
    p.add_argument(
        "--max-classified",
        type=_positive_int("--max-classified"),
        default=None,
        metavar="N",
        help="most located points of a grid classified by the full analysis (default 200)",
    )
    p.add_argument(
        "-v", "--verbose", action="store_true", help="also print what mechsing did silently"
    )


def _positive_int(option: str) -> Callable[[str], int]:
    def parse(text: str) -> int:
        try:
            n = int(text)
        except ValueError:
            n = 0
        if n < 1:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not a positive whole number (e.g. {option} 4)"
            )
        return n

    return parse


def output_format(fmt: str | None, out: str | None) -> str:
    """The format asked for, else the one OUT's extension names, else text."""
    if fmt:
        return fmt
    if out:
        return _BY_EXTENSION.get(Path(out).suffix.lower(), "text")
    return "text"


def run(args: argparse.Namespace) -> int:
    from mechsing.cli import load_mechanism, precision_option
    from mechsing.errors import UserError, working_on
    from mechsing.sweeps import MAX_CLASSIFIED, SweepRun
    from mechsing.sweeps.spec import Vary

    with working_on(file=args.file):
        if len(args.vary) > 2:
            raise UserError(
                f"--vary is given {len(args.vary)} times: a sweep varies one variable (a path) "
                "or two (a grid); give --vary once or twice"
            )
        varies = [Vary.parse(text) for text in args.vary]
        for v in varies:
            if v.ranged:
                v.count()  # the range's own errors (STEP <= 0, not finite) before the file is read
        prec = precision_option(args.precision)
        if prec.mode == "exact":
            raise UserError(
                "--precision exact: a sweep locates its singularities numerically, so their "
                "values are not exact data; use --precision auto (the default) or mp:N"
            )
        if (args.workers or args.scheduler) and len(varies) != 2:
            raise UserError(
                "--workers and --scheduler distribute the rows of a grid: give two --vary"
            )
        fmt = output_format(args.format, args.output)
        from mechsing.cli.options import apply_scene, apply_set
        from mechsing.model.adhoc import set_start

        mech = apply_set(
            apply_scene(load_mechanism(args.file, args.verbose), args, args.file),
            args.set_values,
            args.from_config if args.set_values else None,  # without --set: the sweep's start
            args.file,
        )
        sweep_run = SweepRun(
            mech,
            list(varies),
            set_start(mech, args.set_values, "a sweep") or args.from_config,
            prec,
            max_classified=args.max_classified or MAX_CLASSIFIED,
        )
        with _destination(args.output) as out, _progress_bar(sweep_run, args.quiet) as progress:
            rows = sweep_run.rows(progress, workers=args.workers, scheduler=args.scheduler)
            if fmt == "json":
                write_json(sweep_run, rows, out)
            elif fmt == "csv":
                write_csv(sweep_run, rows, out)
            else:
                for _ in rows:
                    pass
                out.write(sweep_run.result().to_text())
    return 0


# --------------------------------------------------------------------------- writers


def _json_text(value: Any) -> str:
    """One JSON value on one line (non-finite floats as null, like every mechsing JSON)."""
    from mechsing.report.render import _clean

    return json.dumps(_clean(value), allow_nan=False)


def write_json(sweep_run: SweepRun, rows: Iterator[int], out: IO[str]) -> None:
    """The sweep's JSON document, written row by row: the header keys, ``points`` (one
    line per sample, in the order of the result's ``to_json()``: row by row), then
    ``located``, ``loci``, ``notes`` and ``newton_iterations``.  Nothing is written
    before the first row is done, so a sweep that cannot start writes nothing."""
    from mechsing.sweeps.results import json_header, json_point, json_tail

    started = False

    def start() -> None:
        out.write("{\n")
        for key, value in json_header(sweep_run).items():
            out.write(f'  "{key}": {_json_text(value)},\n')
        out.write('  "points": [')

    sep = "\n    "
    for j in rows:
        if not started:
            start()
            started = True
        for idx in _row_indices(sweep_run, j):
            out.write(sep + _json_text(json_point(sweep_run, idx)))
            sep = ",\n    "
    if not started:
        start()
    out.write("\n  ]")
    for key, value in json_tail(sweep_run.result()).items():
        out.write(f',\n  "{key}": {_json_text(value)}')
    out.write("\n}\n")


def write_csv(sweep_run: SweepRun, rows: Iterator[int], out: IO[str]) -> None:
    """The sweep's CSV: the header line, one ``sample`` line per sample written as each
    row is done, then one line per located singularity (its kind in the first column)."""
    from mechsing.sweeps.results import csv_header, csv_located, csv_rows

    header = False
    for j in rows:
        if not header:
            out.write(csv_header(sweep_run))
            header = True
        out.writelines(csv_rows(sweep_run, [j]))
    out.writelines(csv_located(sweep_run.result()))


def _row_indices(sweep_run: SweepRun, j: int) -> list[tuple[int, ...]]:
    shape = sweep_run.reached.shape
    if len(shape) == 1:  # a path: its one row is the whole path
        return [(i,) for i in range(shape[0])]
    return [(j, i) for i in range(shape[1])]


# --------------------------------------------------------------------------- plumbing


@contextmanager
def _destination(path: str | None) -> Iterator[IO[str]]:
    """Standard output, or OUT: written as ``OUT.partial`` beside it and renamed when the
    sweep is complete, so a sweep that stops leaves no half-written OUT."""
    from mechsing.errors import UserError

    if not path:
        yield sys.stdout
        sys.stdout.flush()
        return
    target = Path(path)
    partial = target.with_name(target.name + ".partial")
    try:
        f = open(partial, "w", encoding="utf-8", newline="")
    except OSError as exc:
        raise UserError(
            f"-o {path}: cannot write it ({exc.strerror}); choose a writable path"
        ) from None
    try:
        with f:
            yield f
        os.replace(partial, target)
    except BaseException:
        partial.unlink(missing_ok=True)
        raise


@contextmanager
def _progress_bar(sweep_run: SweepRun, quiet: bool) -> Iterator[Callable[[int], None] | None]:
    """A tqdm bar on standard error counting samples (each finished row adds its own),
    or None when standard error is not a terminal or with --quiet."""
    if quiet or not sys.stderr.isatty():
        yield None
        return
    from tqdm import tqdm

    with tqdm(
        total=int(sweep_run.reached.size), unit="sample", file=sys.stderr, leave=False
    ) as bar:
        yield bar.update
