"""mechsing's errors, and what was being worked on when an error escaped (a leaf module).

* :class:`UserError`: bad input (or a configuration that cannot be analysed):
  printed without a traceback; the command exits with its ``status``.
* :func:`working_on`: a context naming the file and the configuration under
  analysis, so that an exception that escapes everything (a defect of
  mechsing, exit status 4) can still say where it happened
  (:func:`current_work`).
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from contextvars import ContextVar

__all__ = ["UserError", "current_work", "forget_work", "working_on"]


class UserError(Exception):
    """Bad input: printed without a traceback, exit status 2 (or ``status``)."""

    def __init__(self, message: str, status: int = 2) -> None:
        super().__init__(message)
        self.status = status


_WORK: ContextVar[tuple[tuple[str, str], ...]] = ContextVar("mechsing_work", default=())
#: what was being worked on where the last exception was raised (innermost context)
_AT_ERROR: ContextVar[tuple[BaseException, tuple[tuple[str, str], ...]] | None] = ContextVar(
    "mechsing_work_at_error", default=None
)


@contextlib.contextmanager
def working_on(**what: str | None) -> Iterator[None]:
    """Name what the enclosed code works on (``file=...``, ``configuration=...``);
    nested contexts add to the outer ones.  When an exception leaves the
    innermost block, what it named is kept for :func:`current_work`."""
    before = _WORK.get()
    items = tuple((k, str(v)) for k, v in what.items() if v is not None)
    token = _WORK.set(tuple(kv for kv in before if kv[0] not in what) + items)
    try:
        yield
    except BaseException as exc:
        seen = _AT_ERROR.get()
        if seen is None or seen[0] is not exc:  # the innermost block sees it first
            _AT_ERROR.set((exc, _WORK.get()))
        raise
    finally:
        _WORK.reset(token)


def current_work() -> str:
    """What was being worked on where an exception escaped (else now), as
    ``file 'x.yaml', configuration 'crank-30'``; empty when nothing is named."""
    seen = _AT_ERROR.get()
    work = seen[1] if seen is not None else _WORK.get()
    return ", ".join(f"{k} {v!r}" for k, v in work)


def forget_work() -> None:
    """Clear the record of the last error (the command line does so before each run)."""
    _AT_ERROR.set(None)
