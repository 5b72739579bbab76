"""Exact mode over a file's configurations (:class:`ExactRun`): each configuration
within the time limit (stopped wherever sympy is, :mod:`mechsing.timelimit`), with
progress lines once a configuration, or the file, takes long."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from mechsing.analysis.results import ConfigurationResult
from mechsing.errors import ConfigurationError, TimeLimitExceeded
from mechsing.model import Mechanism
from mechsing.timelimit import (
    EXACT_PROGRESS_DELAY,
    TimeLimit,
)

__all__ = ["ExactRun"]


class ExactRun:
    """Exact mode over a file's configurations: each within the time limit, with progress
    lines once a configuration (or the file) takes long."""

    def __init__(
        self,
        mech: Mechanism,
        names: list[str],
        limit: float | None,
        progress: Callable[[str], None] | None,
    ) -> None:
        self.mech = mech
        self.names = names
        self.limit = limit
        self.progress = progress
        self.start = time.monotonic()
        # "after a few seconds", and always before a short limit stops a configuration
        self.delay = EXACT_PROGRESS_DELAY if limit is None else min(EXACT_PROGRESS_DELAY, limit / 2)
        self._announced: set[str] = set()
        self._lock = threading.Lock()

    def _say(self, key: str, text: str) -> None:
        with self._lock:
            self._announced.add(key)
        if self.progress is not None:
            self.progress(f"exact: {text}")

    def _watch(self, key: str, what: str) -> threading.Timer | None:
        """A progress line about ``what`` after ``delay`` seconds, at once when the file has
        already taken that long."""
        if self.progress is None:
            return None
        limit = "no time limit" if self.limit is None else f"time limit {self.limit:g} s"
        text = f"{what}; {limit} per configuration (--time-limit S changes it)"
        if time.monotonic() - self.start >= self.delay:
            self._say(key, text)
            return None
        timer = threading.Timer(self.delay, self._say, (key, text))
        timer.daemon = True
        timer.start()
        return timer

    def prepare(self, build: Callable[[], Any]) -> None:
        """Build the exact model of the geometry (once per file) within the time limit."""
        timer = self._watch("", f"preparing the exact geometry of {self.mech.name!r}")
        try:
            with TimeLimit(self.limit):
                build()
        except TimeLimitExceeded:
            # stopped, not refused: no configuration was analysed (exit status 3)
            raise ConfigurationError(
                f"{self.mech.path or self.mech.name}: exact mode could not prepare the mechanism's "
                f"geometry within {self.limit:g} s (sympy could not simplify its exact axes, points "
                "and reference screws in time); use --precision mp:50 (or auto), or allow more time "
                "with --time-limit S",
                self.names[0],
            ) from None
        finally:
            if timer is not None:
                timer.cancel()

    def run(self, name: str, work: Callable[[], ConfigurationResult]) -> ConfigurationResult:
        """``work()`` (the analysis of configuration ``name``) within the time limit."""
        i = self.names.index(name) + 1
        timer = self._watch(name, f"working on configuration {name!r} ({i} of {len(self.names)})")
        limit = TimeLimit(self.limit)
        try:
            with limit:
                res = work()
        except TimeLimitExceeded as exc:
            doing = exc.activity or "analysing it"
            res = ConfigurationResult(
                name,
                "exact",
                error=f"configuration {name!r}: exact mode stopped after {self.limit:g} s (its time "
                f"limit) while {doing}: sympy could not finish that in time; use --precision "
                "mp:50 (or auto) for this configuration, or allow exact mode more time with "
                "--time-limit S",
            )
        finally:
            if timer is not None:
                timer.cancel()
        with self._lock:
            announced = name in self._announced
        if announced and self.progress is not None:
            outcome = "stopped" if res.error is not None and limit.exceeded else "done"
            self.progress(f"exact: configuration {name!r}: {outcome} after {limit.elapsed:.1f} s")
        return res
