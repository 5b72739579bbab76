"""A time limit that really interrupts a computation (exact mode's limit per configuration).

sympy can spend minutes inside a single call (``simplify``, ``is_algebraic``, an echelon
form of algebraic numbers), so a deadline checked between the steps of an analysis does not
stop it.  :class:`TimeLimit` interrupts the running Python code wherever it is:

* in the main thread with ``SIGALRM`` (:func:`signal.setitimer`): the handler raises
  :class:`TimeLimitExceeded` at the next bytecode the interpreter runs; the previous handler is
  put back afterwards, and an interval timer the caller had set is re-armed with the time it had
  left (it is postponed, not lost);
* in any other thread, where Python delivers no signals, a watchdog thread raises the same
  exception in the working thread (CPython's ``PyThreadState_SetAsyncExc``), with the same
  effect.

A call into compiled code that releases the GIL (Bertini's path tracking) runs no Python
code, so neither a time limit nor a stop signal (SIGINT, SIGTERM: the command line's) is
delivered until it returns.  :func:`interruptible` lets such a call be stopped: while it
runs, a helper thread wakes on every signal that has a Python handler and calls the
library's own stop function; once the call returns, the handler runs and raises as
usual.

A worker process would also survive a long call into C code (neither way above interrupts a
single huge integer product before it returns), but it would have to send the whole analysis
(sympy arrays, models, closures) back to the parent and pay a process start per configuration;
mechsing's exact computations are Python code (sympy, mpmath), which both ways interrupt
within microseconds.  Interrupting sympy leaves it consistent: its caches and assumptions keep
only results that were completed.

:class:`TimeLimitExceeded` derives from ``BaseException``, like ``KeyboardInterrupt``, so that
no ``except Exception`` on the way (sympy has many) swallows it; should one swallow it anyway,
it is raised again every :data:`REPEAT` seconds until the block is left.  :func:`activity`
names what the code is doing, so that the exception can say what was cut short.
"""

from __future__ import annotations

import contextlib
import ctypes
import math
import os
import select
import signal
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from types import TracebackType

from mechsing.errors import TimeLimitExceeded

__all__ = [
    "EXACT_PROGRESS_DELAY",
    "EXACT_TIME_LIMIT",
    "LONGEST_TIME_LIMIT",
    "REPEAT",
    "SHORTEST_TIME_LIMIT",
    "TimeLimit",
    "TimeLimitExceeded",
    "activity",
    "check_time_limit",
    "interruptible",
]

#: seconds exact mode may spend on one configuration (``mechsing analyze --time-limit``,
#: ``mechsing.analyze(time_limit=...)``): sympy can take hours to prove what mp:50 decides
#: in a second, so a configuration still unproved then is stopped with an error entry
EXACT_TIME_LIMIT = 60.0
#: exact mode says which configuration it works on (standard error, command line) once a
#: configuration, or the file, has taken this many seconds
EXACT_PROGRESS_DELAY = 3.0
#: seconds between repeated interruptions, should some code swallow the first one
REPEAT = 0.25
#: the range of a time limit (``--time-limit S``, ``time_limit=``), in seconds: shorter, a
#: configuration would be stopped before any work (the interruption's own latency is about
#: a millisecond); longer than about 11.6 days is no limit (and 1e308 overflows the timer)
SHORTEST_TIME_LIMIT = 0.01
LONGEST_TIME_LIMIT = 1e6


def check_time_limit(seconds: object) -> float:
    """``seconds`` as a time limit, or a ValueError that says the accepted range (the
    policy of every command's ``--time-limit`` and of the library's ``time_limit``)."""
    x = math.nan
    if isinstance(seconds, int | float) and not isinstance(seconds, bool):
        x = float(seconds)
    if not SHORTEST_TIME_LIMIT <= x <= LONGEST_TIME_LIMIT:
        raise ValueError(
            f"time_limit {seconds!r} is not a number of seconds from {SHORTEST_TIME_LIMIT:g} "
            f"to {LONGEST_TIME_LIMIT:g} (e.g. 120)"
        )
    return x


@contextmanager
def activity(text: str) -> Iterator[None]:
    """Name what the block does: a :class:`TimeLimitExceeded` raised inside it carries ``text``
    (the innermost activity wins)."""
    try:
        yield
    except TimeLimitExceeded as exc:
        if exc.activity is None:
            exc.activity = text
        raise


class TimeLimit:
    """``with TimeLimit(seconds):`` raises :class:`TimeLimitExceeded` inside the block when it
    runs longer than ``seconds`` (None: no limit).

    After the block, ``elapsed`` is its wall time in seconds and ``exceeded`` says whether the
    limit was reached.
    """

    def __init__(self, seconds: float | None) -> None:
        self.seconds = None if seconds is None else check_time_limit(seconds)
        self.exceeded = False
        self.elapsed = 0.0
        self._start = 0.0
        self._closing = False
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._watchdog: threading.Thread | None = None
        self._thread_id = 0
        self._old_handler: object = None
        self._old_timer: tuple[float, float] = (0.0, 0.0)
        self._main = False

    # ------------------------------------------------------------------ entering

    def __enter__(self) -> TimeLimit:
        self._start = time.monotonic()
        if self.seconds is None:
            return self
        self._main = threading.current_thread() is threading.main_thread() and hasattr(
            signal, "SIGALRM"
        )
        if self._main:
            try:
                self._old_handler = signal.signal(signal.SIGALRM, self._on_alarm)
            except ValueError:  # signals unavailable here (an embedded interpreter)
                self._main = False
        try:
            if self._main:
                self._old_timer = signal.setitimer(signal.ITIMER_REAL, self.seconds, REPEAT)
            else:
                self._thread_id = threading.get_ident()
                self._watchdog = threading.Thread(
                    target=self._watch, name="mechsing-time-limit", daemon=True
                )
                self._watchdog.start()
            return self
        except TimeLimitExceeded:
            # a short limit fell before the block began: no __exit__ will disarm it
            self.__exit__(None, None, None)
            raise

    def _on_alarm(self, signum: int, frame: object) -> None:
        if self._closing:
            return
        self.exceeded = True
        raise TimeLimitExceeded

    def _watch(self) -> None:
        assert self.seconds is not None
        if self._stop.wait(self.seconds):
            return
        while True:
            with self._lock:
                if self._closing:
                    return
                self.exceeded = True
                _raise_in_thread(self._thread_id, TimeLimitExceeded)
            if self._stop.wait(REPEAT):
                return

    # ------------------------------------------------------------------ leaving

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        if self.seconds is not None:
            # an interruption may arrive while we disarm: disarm again until it is done
            while True:
                try:
                    self._disarm()
                    break
                except TimeLimitExceeded:
                    continue
        self.elapsed = time.monotonic() - self._start
        if self.exceeded and exc_type is None:
            # the limit fell while leaving the block: it was still reached
            raise TimeLimitExceeded

    def _disarm(self) -> None:
        if self._main:
            self._closing = True
            signal.setitimer(signal.ITIMER_REAL, 0)
            # None: the previous handler was not set from Python; the default is put back
            old = signal.SIG_DFL if self._old_handler is None else self._old_handler
            signal.signal(signal.SIGALRM, old)  # type: ignore[arg-type]
            delay, interval = self._old_timer
            if delay > 0:
                # the caller's own timer, postponed by the block: re-armed with what it had left
                left = delay - (time.monotonic() - self._start)
                signal.setitimer(signal.ITIMER_REAL, max(left, 1e-6), interval)
                self._old_timer = (0.0, 0.0)
            self._main = False
        elif self._watchdog is not None:
            with self._lock:
                self._closing = True
                self._stop.set()
                if self.exceeded:
                    # an interruption sent but not yet delivered must not escape the block
                    _raise_in_thread(self._thread_id, None)
            self._watchdog = None


def _raise_in_thread(thread_id: int, exc: type[BaseException] | None) -> None:
    """Raise ``exc`` in the thread (None: cancel an exception not yet delivered)."""
    ctypes.pythonapi.PyThreadState_SetAsyncExc(
        ctypes.c_ulong(thread_id), ctypes.py_object(exc) if exc is not None else None
    )


#: the signals that interrupt a computation: a time limit (SIGALRM), Ctrl-C, SIGTERM
_INTERRUPTING = frozenset({signal.SIGALRM, signal.SIGINT, signal.SIGTERM})


@contextmanager
def interruptible(stop: Callable[[], None]) -> Iterator[Callable[[], bool]]:
    """Run the block, a call into compiled code that releases the GIL, so that a time
    limit (SIGALRM) or a stop signal (SIGINT, SIGTERM) stops it: on such a signal a helper
    thread calls ``stop()`` (the library's request to return early), and the signal's
    Python handler raises once the call has returned.  Yields a function that says
    whether ``stop()`` was called: a caller whose handler did not raise (a signal that
    ends nothing) runs the call again.  In a thread other than the main one (which
    receives no signals) the block runs as it is.

    It works through :func:`signal.set_wakeup_fd` (the interpreter writes each signal's
    number to a pipe when it arrives); a wake-up file the program had set gets the same
    bytes and is put back afterwards."""
    stopped = threading.Event()
    if threading.current_thread() is not threading.main_thread():
        yield stopped.is_set
        return
    r, w = os.pipe()
    os.set_blocking(w, False)
    try:
        old = signal.set_wakeup_fd(w, warn_on_full_buffer=False)
    except ValueError:  # signals unavailable here (an embedded interpreter)
        os.close(r)
        os.close(w)
        yield stopped.is_set
        return
    done = threading.Event()

    def watch() -> None:
        while not done.is_set():
            if not select.select([r], [], [], REPEAT)[0]:
                continue
            data = os.read(r, 64)
            if old >= 0:
                with contextlib.suppress(OSError):
                    os.write(old, data)
            if _INTERRUPTING.intersection(data):
                stopped.set()
                stop()

    watcher = threading.Thread(target=watch, name="mechsing-interruptible", daemon=True)
    watcher.start()
    try:
        yield stopped.is_set
    finally:
        signal.set_wakeup_fd(old)
        done.set()
        with contextlib.suppress(OSError):
            os.write(w, b"\0")  # no signal has number 0: wakes the helper to leave
        watcher.join()
        os.close(r)
        os.close(w)
