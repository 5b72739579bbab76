"""mechsing's exceptions, and what was being worked on when one escaped (a leaf module).

One family, :class:`MechsingError`: every error mechsing raises on purpose,
with a message for people (the file, the item, the line, the fix).

* :class:`UserError`: bad input (a file, an option, data a mode cannot take).
* :class:`ConfigurationError`: one configuration cannot be analysed (it does
  not close, exact mode cannot take it or stopped on it) while the others can.
* :class:`CatalogError`: the subgroup catalog's data are broken.

The layers raise these and never decide what a command does with them: only
the command line (``mechsing.cli.main``) maps them to exit statuses.
:func:`working_on` names the file and the configuration under analysis, so
that an exception that escapes everything (a defect of mechsing) can still say
where it happened (:func:`current_work`).
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from contextvars import ContextVar

__all__ = [
    "CatalogError",
    "ConfigurationError",
    "MechsingError",
    "UserError",
    "current_work",
    "forget_work",
    "work_item",
    "working_on",
]


class MechsingError(Exception):
    """Every error mechsing raises on purpose; its message is written for people."""


class UserError(MechsingError):
    """Bad input: a file, an option, or data the precision mode cannot take."""


class ConfigurationError(UserError):
    """One configuration that cannot be analysed while the others can: an analysis
    gives it an ``error`` entry and reports the others."""

    def __init__(self, message: str, configuration: str, residual: float | None = None) -> None:
        super().__init__(message)
        self.configuration = configuration
        self.residual = residual

    def __reduce__(self) -> tuple[type, tuple[str, str, float | None]]:
        # pickles whole (a sweep's row raises it on a Dask worker, the driver re-raises it)
        return (type(self), (str(self), self.configuration, self.residual))


class CatalogError(MechsingError):
    """A catalog file is missing or malformed (an installation or data defect)."""


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


def work_item(key: str) -> str | None:
    """One item of :func:`current_work` (``"file"``, ``"configuration"``), or None."""
    seen = _AT_ERROR.get()
    return dict(seen[1] if seen is not None else _WORK.get()).get(key)


def forget_work() -> None:
    """Clear the record of the last error (the command line does so before each run)."""
    _AT_ERROR.set(None)
