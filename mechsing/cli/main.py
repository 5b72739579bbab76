"""The ``mechsing`` command: :func:`main` and its parser (:func:`build_parser`).

Each sub-command lives in its own module of this package and exposes
``NAME`` (the sub-command), ``HELP`` (one line), ``add_arguments(parser)`` and
``run(args) -> int``.  Building the parser imports those modules only, and they import
their layers inside ``run``: ``mechsing``, ``--version``, ``-h`` and every
``COMMAND -h`` import neither numpy nor sympy (tests/test_cli_startup.py).

Exit status: 0 success, 2 bad input, 3 some configuration could not be analysed (not
closed, or stopped by a time limit; the others are reported), 4 an internal defect (an
exception that escaped: one line on stderr, the traceback with ``-T``), 130 and 143 a
command stopped by SIGINT (Ctrl-C) and SIGTERM (one line on stderr; an ``-o`` file is
written whole or not at all, :mod:`mechsing.files`).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import math
import os
import signal
import sys
import threading
import time
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING

from mechsing import __version__
from mechsing.errors import (
    ConfigurationError,
    Interrupted,
    MechsingError,
    current_work,
    forget_work,
    note_stop,
    raise_if_stopped,
    work_item,
)

if TYPE_CHECKING:  # the commands import their layers lazily: `mechsing --version` stays fast
    from mechsing.model import Mechanism
    from mechsing.numeric import Precision
    from mechsing.reader import Source

#: exit statuses: bad input, a configuration that could not be analysed, a defect
BAD_INPUT, NOT_ANALYSED, INTERNAL_ERROR = 2, 3, 4


def exit_status(exc: BaseException) -> int:
    """The exit status of an exception that reaches the command line (the only place
    exceptions become statuses): 3 for a configuration that could not be analysed, 2
    for any other error of mechsing's (bad input), 4 for anything else (a defect)."""
    if isinstance(exc, ConfigurationError):
        return NOT_ANALYSED
    if isinstance(exc, MechsingError):
        return BAD_INPUT
    return INTERNAL_ERROR


def with_file(message: str, path: str | None = None) -> str:
    """An error message that names its file: the one given, else the one being worked on
    when the error was raised (messages from reading a file name it already)."""
    path = path or work_item("file")
    return message if not path or path in message else f"{path}: {message}"


def _few_blas_threads() -> None:
    """mechsing works on many tiny matrices: BLAS threads only add overhead there (and
    on a loaded machine make a 4x4 product hundreds of times slower).  Set before the
    commands load numpy; a user's own setting wins.  Only the command does this: a
    program that imports mechsing keeps its own threads."""
    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")


@contextlib.contextmanager
def _private_library_files() -> Iterator[None]:
    """The libraries a command uses keep their caches and records (matplotlib's font list
    and configuration folder, Dask's scratch space and locks) in one temporary folder of
    the command's, removed when it ends: a command writes no file it was not asked to,
    not in the working directory, the home folder or the shared temporary folder.  A
    user's own MPLCONFIGDIR or DASK_TEMPORARY_DIRECTORY wins."""
    import shutil
    import tempfile

    names = [v for v in ("MPLCONFIGDIR", "DASK_TEMPORARY_DIRECTORY") if v not in os.environ]
    if not names:
        yield
        return
    folder = tempfile.mkdtemp(prefix="mechsing-")
    for var in names:
        os.environ[var] = folder
    try:
        with contextlib.ExitStack() as stack:
            if "DASK_TEMPORARY_DIRECTORY" in names and "dask" in sys.modules:
                # Dask read its configuration when it was imported (an earlier command
                # of this process): set it for this command too
                import dask

                stack.enter_context(dask.config.set({"temporary-directory": folder}))
            yield
    finally:
        for var in names:
            if os.environ.get(var) == folder:
                del os.environ[var]
        dask = sys.modules.get("dask")
        if dask is not None and dask.config.get("temporary-directory", None) == folder:
            dask.config.set({"temporary-directory": None})  # imported by this command
        shutil.rmtree(folder, ignore_errors=True)


#: the signals that stop a command, and their names in its one line
STOP_SIGNALS = {signal.SIGINT: "SIGINT (Ctrl-C)", signal.SIGTERM: "SIGTERM"}
#: seconds after a stop during which a repeated signal is ignored: the command is removing
#: its temporary files; later it interrupts again (should some code have swallowed the first)
STOP_REPEAT_SECONDS = 1.0
#: seconds after a stop was lost (raised where Python cannot raise, as in a weak
#: reference's callback) before it is sent again
LOST_STOP_DELAY = 1e-3


class _StopOnSignal:
    """SIGINT and SIGTERM raise :class:`~mechsing.errors.Interrupted` (a KeyboardInterrupt
    that knows its signal) in the main thread, from Python code or from a computation in C
    that lets itself be stopped (:func:`mechsing.timelimit.interruptible`); the temporary
    files are removed on the way out, and :func:`main` prints one line.

    The exception is raised wherever the main thread is when the signal arrives, which can
    be a weak reference's callback or a ``__del__`` run by the garbage collector: Python
    only reports an exception there ("Exception ignored in ...") and goes on.  Such a lost
    stop is not reported but sent again, a millisecond later, by a thread of its own
    (:meth:`_lost`).  And the stop is recorded (:func:`mechsing.errors.note_stop`): an
    output file is not replaced after it, and the command does not end with success,
    whatever swallowed it."""

    def __init__(self) -> None:
        self.before: dict[int, object] = {}
        self.last = -math.inf
        self.hook: object = None
        self.again: list[threading.Thread] = []
        self.in_hook = False
        self.closing = False

    def __enter__(self) -> _StopOnSignal:
        note_stop(None)
        if threading.current_thread() is threading.main_thread():
            with contextlib.suppress(ValueError):  # no signals here (an embedded interpreter)
                for sig in STOP_SIGNALS:
                    self.before[sig] = signal.signal(sig, self._stop)
            if self.before and hasattr(signal, "pthread_kill"):
                self.hook = sys.unraisablehook
                sys.unraisablehook = self._lost
        return self

    def _stop(self, signum: int, frame: object) -> None:
        if self.in_hook:  # raised here, it would be lost once more: sent again instead
            self._send_again(signum)
            return
        now = time.monotonic()
        if self.closing or now - self.last < STOP_REPEAT_SECONDS:
            return
        self.last = now
        note_stop(signum)
        raise Interrupted(signum)

    def _lost(self, unraisable: object) -> None:
        """The interpreter could not raise an exception further (it runs this hook, in the
        main thread for a stop): a stop is sent again, anything else reported as before."""
        exc = getattr(unraisable, "exc_value", None)
        if not isinstance(exc, Interrupted):
            self.hook(unraisable)  # type: ignore[operator]
            return
        self.in_hook = True
        try:
            self._send_again(exc.signum)
        finally:
            self.in_hook = False

    def _send_again(self, signum: int) -> None:
        """Send ``signum`` to the main thread again in :data:`LOST_STOP_DELAY` seconds,
        from another thread: sent by the main thread itself, its handler would run at once,
        where the stop was just lost."""
        self.last = -math.inf  # not a repeated signal: the first one was lost
        main = threading.main_thread().ident
        again = threading.Thread(
            target=_send_later, args=(main, signum), name="mechsing-stop", daemon=True
        )
        self.again.append(again)
        again.start()

    def __exit__(self, *exc: object) -> None:
        self.closing = True  # a stop sent again now finds the command ending: ignored
        for again in self.again:
            again.join()
        for sig, handler in self.before.items():
            # None: the handler was not set from Python; the default is put back
            signal.signal(sig, signal.SIG_DFL if handler is None else handler)  # type: ignore[arg-type]
        if self.hook is not None:
            sys.unraisablehook = self.hook  # type: ignore[assignment]
        note_stop(None)


def _send_later(thread: int, signum: int) -> None:
    time.sleep(LOST_STOP_DELAY)
    signal.pthread_kill(thread, signum)


def _stopped_line(exc: KeyboardInterrupt, args: argparse.Namespace | None) -> tuple[str, int]:
    """The one line an interrupted command prints, and its exit status (128 + the signal)."""
    signum = getattr(exc, "signum", signal.SIGINT)
    name = STOP_SIGNALS.get(signum, f"signal {signum}")
    out = getattr(args, "output", None)
    kept = (
        f"; {out} was left as it was" if out and getattr(args, "command", "") != "exercise" else ""
    )
    return f"mechsing: stopped by {name}{kept}", 128 + int(signum)


#: sub-command modules, in the order ``--help`` lists them
COMMANDS = (
    "analyze",
    "solve",
    "modes",
    "sweep",
    "report",
    "condition",
    "convert",
    "catalog",
    "identify",
    "schema",
    "exercise",
    "dynamics",
    "cusps",
)


def load_mechanism(
    path: str | Source,
    verbose: bool = False,
    symbolic: Sequence[str] = (),
    exact_tables: bool = False,
    precision: Precision | None = None,
) -> Mechanism:
    """Read a mechanism file of any format (:func:`mechsing.reader.read_mechanism`, the
    one reader of every command); print its warnings (likely mistakes that are not
    errors), and with ``verbose`` what was done silently (axes normalised...).
    ``exact_tables``: a ``dh`` table's frames exact (``condition``).  ``precision``: the
    command's ``--precision``, which decides how the file's plain numbers are read
    (:func:`~mechsing.reader.read_mechanism`)."""
    from mechsing.errors import working_on
    from mechsing.reader import read_mechanism

    with working_on(file=path if isinstance(path, str) else path.path):
        mech = read_mechanism(
            path, symbolic=symbolic, exact_tables=exact_tables, precision=precision
        )
    for warning in mech.warnings:
        print(f"mechsing: warning: {warning}", file=sys.stderr)
    if verbose:
        for note in mech.notes:
            print(f"mechsing: {note}", file=sys.stderr)
    return mech


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # argparse exits 2 already; keep its words
        self.print_usage(sys.stderr)
        self.exit(2, f"mechsing: error: {message}\n")


def _load_commands() -> list:
    mods = []
    for name in COMMANDS:
        try:
            mods.append(importlib.import_module(f"mechsing.cli.{name}"))
        except ModuleNotFoundError as exc:  # a command not built yet
            if exc.name != f"mechsing.cli.{name}":
                raise
    return mods


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="mechsing",
        description="Find and classify the singularities of mechanisms with Lie groups.",
    )
    parser.add_argument("--version", action="version", version=f"mechsing {__version__}")
    parser.add_argument(
        "-T",
        "--traceback",
        action="store_true",
        help="show a Python traceback on errors (debugging)",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for mod in _load_commands():
        p = sub.add_parser(mod.NAME, help=mod.HELP, description=mod.__doc__)
        mod.add_arguments(p)
        p.set_defaults(_run=mod.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    # one function, no helper frame: CPython 3.11 maps and unmaps a 16 KB chunk of frames
    # on every call that crosses a chunk's edge, and one more frame here moved the imports
    # of the analysis onto an edge (12,000 mmap calls, a tenth of the four-bar's CPU time)
    args = None
    with _StopOnSignal():
        try:
            _few_blas_threads()
            parser = build_parser()
            args = parser.parse_args(argv)
            if not getattr(args, "_run", None):
                parser.print_help()
                return 0
            forget_work()
            with _private_library_files():
                status = int(args._run(args))
            raise_if_stopped()  # a stop that some code swallowed is still a stop
            return status
        except KeyboardInterrupt as exc:  # SIGINT, SIGTERM: one line, 130 / 143
            if args is not None and args.traceback:
                raise
            line, status = _stopped_line(exc, args)
            print(line, file=sys.stderr)
            return status
        except MechsingError as exc:
            if args is None or args.traceback:
                raise
            print(f"mechsing: error: {with_file(str(exc))}", file=sys.stderr)
            return exit_status(exc)
        except BrokenPipeError:
            return 0
        except Exception as exc:  # a defect: one line that says where, exit 4
            if args is None or args.traceback:
                raise
            where = current_work() or f"mechsing {args.command}"
            what = " ".join(str(exc).split())[:300]
            print(
                f"mechsing: internal error in {where}: {type(exc).__name__}: {what}. "
                "This is a defect of mechsing, not of your input: please report it with the "
                "file and the command (add -T after mechsing for the traceback)",
                file=sys.stderr,
            )
            return INTERNAL_ERROR


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
