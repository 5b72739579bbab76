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

--mode K starts on assembly mode K of --from (as `mechsing modes` numbers them),
--modes all sweeps from every one (each sample labelled with its mode); with two
--vary, --loop follows the rectangle of their ranges instead of the grid and
reports a return on another mode without a singularity (mode_changes; --format md
too).  A grid reports its singularity-free regions (aspects).

A progress bar is shown on standard error when it is a terminal (not with
--quiet).  Exit status: 0 success, 2 bad input, 3 the sweep cannot start (its
--from configuration does not close, or the first sample cannot be reached) or a
located point could not be analysed (stopped by --time-limit, say: the output is
written, its entry and standard error say why).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable, Iterator
from contextlib import ExitStack, contextmanager
from typing import IO, TYPE_CHECKING, Any

if TYPE_CHECKING:  # the command's layers load when it runs: `mechsing --help` stays fast
    from mechsing.sweeps import SweepRun

NAME = "sweep"
HELP = "locate singularities along a path or over a grid of joint values or poses"

#: the formats it writes (the first the default; -o's extension chooses one:
#: :mod:`mechsing.cli.output`)
FORMATS = ("text", "json", "csv", "md")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", metavar="FILE", help="mechanism file (YAML or JSON), URDF or MJCF")
    from mechsing.cli import options, output

    options.add_vary_option(p, True, "what the sweep varies")
    options.add_from_option(
        p,
        "the configuration the sweep starts from (its assembly mode is kept; "
        "default reference; with --set, the one the configuration cli is solved from, and the "
        "sweep starts from cli)",
    )
    options.add_set_option(p, from_option=False)
    options.add_scene_options(p)
    options.add_precision_option(
        p,
        "auto",
        "precision of the classification of the located points: auto (default), "
        "float or mp:N (the measures are always float)",
    )
    options.add_time_limit_option(p)
    output.add_output_options(p, FORMATS, "the result (md: with --loop)")
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
        "--connect-timeout",
        type=_timeout,
        default=None,
        metavar="SECONDS",
        help="with --scheduler: seconds the scheduler has to accept the connection and answer "
        "(default 5)",
    )
    p.add_argument(
        "--max-classified",
        type=_positive_int("--max-classified"),
        default=None,
        metavar="N",
        help="most located points of a grid classified by the full analysis (default 200)",
    )
    options.add_verbose_option(p)
    options.add_load_option(p)
    options.add_max_effort_option(p)
    options.add_duration_option(p)
    which = p.add_mutually_exclusive_group()
    which.add_argument(
        "--mode",
        type=_positive_int("--mode"),
        metavar="K",
        help="start on assembly mode K of the --from configuration, as `mechsing modes` numbers "
        "them (default: the mode continuation reaches); every sample is labelled with it",
    )
    which.add_argument(
        "--modes",
        choices=("all",),
        help="all: one sweep per assembly mode of the --from configuration, each sample "
        "labelled with its mode",
    )
    p.add_argument(
        "--loop",
        action="store_true",
        help="with two --vary: follow the closed path around the rectangle of their ranges "
        "(from START, START) instead of the grid, and report a return on another assembly "
        "mode without a located singularity (mode_changes)",
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


def _timeout(text: str) -> float:
    from mechsing.numeric.numbers import decimal_float
    from mechsing.sweeps.distributed import MAX_CONNECT_TIMEOUT

    try:
        x = decimal_float(text)
    except ValueError:
        x = 0.0
    if not 0 < x <= MAX_CONNECT_TIMEOUT:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a number of seconds between 0 and {MAX_CONNECT_TIMEOUT:g} "
            "(e.g. --connect-timeout 10)"
        )
    return x


def run(args: argparse.Namespace) -> int:
    from mechsing.cli import load_mechanism
    from mechsing.cli.options import check_shared, warn_varies, with_sweep_load
    from mechsing.cli.output import output_format
    from mechsing.errors import UserError, working_on
    from mechsing.sweeps.run import MAX_CLASSIFIED, SweepRun

    with working_on(file=args.file):
        check_shared(args)  # the options' own errors before the file is read
        varies = args.varies
        if args.loop and len(varies) != 2:
            raise UserError("--loop follows the rectangle of two ranges: give two --vary")
        if args.loop and (args.workers or args.scheduler):
            raise UserError("--loop is one path per mode: it is not distributed (no --workers)")
        fmt = output_format(args.format, args.output, FORMATS, NAME)
        if args.loop and fmt == "csv":
            raise UserError("--loop writes text, json or md (not csv)")
        if fmt == "md" and not args.loop:
            raise UserError(
                "--format md is the loops' (--loop); a sweep's Markdown is its design review: "
                "mechsing report FILE --vary ... -o review.md"
            )
        if (args.workers or args.scheduler) and len(varies) != 2:
            raise UserError(
                "--workers and --scheduler distribute the rows of a grid: give two --vary"
            )
        if args.workers or args.scheduler:  # before the file is read
            from mechsing.sweeps.distributed import check_workers, parse_scheduler

            if args.workers and args.scheduler:
                raise UserError(
                    "give --workers N (a local cluster) or --scheduler ADDRESS, not both"
                )
            if args.workers:
                check_workers(args.workers)
            else:
                parse_scheduler(args.scheduler)
        if args.output:  # before the work: a missing directory or the input file is refused now
            from mechsing.files import check_output

            check_output(args.output, [args.file])
        from mechsing.adhoc import set_start
        from mechsing.cli.options import apply_scene, apply_set

        mech = apply_set(
            apply_scene(
                load_mechanism(args.file, args.verbose, precision=args.prec), args, args.file
            ),
            args.set_values,
            args.from_config if args.set_values else None,  # without --set: the sweep's start
            args.file,
        )
        warn_varies(mech, varies)
        start_config = set_start(mech, args.set_values, "a sweep") or args.from_config
        if args.modes or args.mode or args.loop:
            return _run_modes(args, mech, start_config, fmt)
        sweep_run = SweepRun(
            mech,
            list(varies),
            start_config,
            args.prec,
            max_classified=args.max_classified or MAX_CLASSIFIED,
            time_limit=args.time_limit,
        )
        with_sweep_load(sweep_run, mech, args.load, args.max_effort)
        if args.duration is not None:
            from mechsing.kinetics.timed import attach

            attach(sweep_run, args.duration)
        with _destination(args.output, args.file) as out:
            _write_one(args, sweep_run, fmt, out)
    return _exit_status(args, sweep_run.result().located)


def _write_one(args: argparse.Namespace, sweep_run: SweepRun, fmt: str, out: IO[str]) -> None:
    """One sweep written as its rows are done, with its progress bar."""
    with _progress_bar(sweep_run, args.quiet) as progress:
        rows = sweep_run.rows(
            progress,
            workers=args.workers,
            scheduler=args.scheduler,
            connect_timeout=args.connect_timeout,
        )
        if fmt == "json":
            write_json(sweep_run, rows, out)
        elif fmt == "csv":
            write_csv(sweep_run, rows, out)
        else:
            for _ in rows:
                pass
            out.write(sweep_run.result().to_text())


def _exit_status(args: argparse.Namespace, located: Any) -> int:
    """3 (each error on standard error) when a located point could not be analysed."""
    from mechsing.cli import NOT_ANALYSED, with_file

    stopped = [p.configuration.error for p in located if p.configuration]
    for error in filter(None, stopped):
        print(f"mechsing: {with_file(error, args.file)}", file=sys.stderr)
    return NOT_ANALYSED if any(stopped) else 0


def _run_modes(args: argparse.Namespace, mech: Any, start_config: str | None, fmt: str) -> int:
    """``--mode K``, ``--modes all`` and ``--loop``: one sweep (or loop) per mode asked for."""
    from mechsing.errors import UserError
    from mechsing.sweeps.permode import (
        loop_header,
        loops_json,
        loops_markdown,
        loops_text,
        mode_loops,
        mode_runs,
    )
    from mechsing.sweeps.run import MAX_CLASSIFIED, SweepRun

    if args.load or args.max_effort or args.duration is not None:
        raise UserError(
            "--load, --max-effort and --duration sweep one mode: give them without "
            "--mode/--modes/--loop"
        )
    options = {
        "max_classified": args.max_classified or MAX_CLASSIFIED,
        "time_limit": args.time_limit,
    }
    wanted = "all" if args.modes else [args.mode] if args.mode else None
    if wanted is None:
        runs, found = [SweepRun(mech, list(args.varies), start_config, args.prec, **options)], None
    else:
        runs, found = mode_runs(mech, list(args.varies), start_config, args.prec, wanted, **options)
    with _destination(args.output, args.file) as out:
        if args.loop:
            loops = mode_loops(runs, found)
            variables = runs[0].variables

            def shown(v: Any) -> str:
                return "(" + ", ".join(x.shown(a) for x, a in zip(variables, v, strict=True)) + ")"

            what = (
                f"{mech.name}: loops of {', '.join(v.name for v in variables)} from "
                f"{runs[0].from_config!r}"
            )
            if fmt == "json":
                out.write(_json_text({**loop_header(runs), **loops_json(loops)}) + "\n")
            elif fmt == "md":
                out.write(loops_markdown(what, loops, shown))
            else:
                out.write(what + "\n" + loops_text(loops, shown))
            # a loop that does not close says why in its entry (exit 0)
            return _exit_status(args, [p for lo in loops for p in lo.singularities])
        if len(runs) == 1:
            _write_one(args, runs[0], fmt, out)
        else:
            _write_runs(args, runs, fmt, out)
    return _exit_status(args, [p for r in runs for p in r.result().located])


def _write_runs(args: argparse.Namespace, runs: list[Any], fmt: str, out: IO[str]) -> None:
    """Several modes' sweeps as one document: JSON (the header once with ``modes``, every
    mode's points, their located points, loci and aspects joined), CSV (one after the
    other, each line with its mode) or text."""
    with ExitStack() as stack:
        client = None
        if (args.workers or args.scheduler) and runs[0].grid:
            # one Dask cluster for every mode's grid, not one per mode
            from mechsing.sweeps.distributed import CONNECT_TIMEOUT, open_client

            timeout = CONNECT_TIMEOUT if args.connect_timeout is None else args.connect_timeout
            client = stack.enter_context(open_client(args.workers, args.scheduler, timeout))

        def rows(run: Any) -> Iterator[int]:
            with _progress_bar(run, args.quiet) as progress:
                yield from run.rows(
                    progress,
                    workers=args.workers,
                    scheduler=args.scheduler,
                    connect_timeout=args.connect_timeout,
                    client=client,
                )

        _write_runs_with(runs, fmt, out, rows)


def _write_runs_with(
    runs: list[Any], fmt: str, out: IO[str], rows: Callable[[Any], Iterator[int]]
) -> None:
    """:func:`_write_runs`'s documents, each run's rows from ``rows``."""
    from mechsing.sweeps.permode import merged_tail
    from mechsing.sweeps.results import (
        csv_header,
        csv_located,
        csv_rows,
        json_header,
        json_point,
        json_tail,
    )

    if fmt == "json":
        out.write("{\n")
        head = {k: v for k, v in json_header(runs[0]).items() if k != "mode"}
        head["modes"] = [r.mode for r in runs]
        for key, value in head.items():
            out.write(f'  "{key}": {_json_text(value)},\n')
        out.write('  "points": [')
        sep = "\n    "
        for run in runs:
            for j in rows(run):
                for idx in _row_indices(run, j):
                    out.write(sep + _json_text(json_point(run, idx)))
                    sep = ",\n    "
        out.write("\n  ]")
        tail = merged_tail([json_tail(r.result()) for r in runs], [r.mode for r in runs])
        for key, value in tail.items():
            out.write(f',\n  "{key}": {_json_text(value)}')
        out.write("\n}\n")
    elif fmt == "csv":
        out.write(csv_header(runs[0]))
        for run in runs:
            for j in rows(run):
                out.writelines(csv_rows(run, [j]))
        for run in runs:
            out.writelines(csv_located(run.result()))
    else:
        for k, run in enumerate(runs):
            for _ in rows(run):
                pass
            out.write(("\n" if k else "") + run.result().to_text())


# --------------------------------------------------------------------------- writers


def _json_text(value: Any) -> str:
    """One JSON value on one line (non-finite floats as null, like every mechsing JSON)."""
    from mechsing.reports.render import _clean

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
def _destination(path: str | None, source: str) -> Iterator[IO[str]]:
    """Standard output, or OUT: written into a temporary file beside it and renamed when
    the sweep is complete (:func:`mechsing.files.open_output`), so a sweep that stops
    leaves no half-written OUT and OUT never appears before it is whole."""
    from mechsing.files import open_output

    if not path:
        yield sys.stdout
        sys.stdout.flush()
        return
    with open_output(path, [source]) as f:
        yield f


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
