"""mechsing's exceptions, and what was being worked on when one escaped (a leaf module).

One family, :class:`MechsingError`: every error mechsing raises on purpose,
with a message for people (the file, the item, the line, the fix).

* :class:`UserError`: bad input (a file, an option, data a mode cannot take).
* :class:`ConfigurationError`: one configuration cannot be analysed (it does
  not close, exact mode cannot take it or stopped on it) while the others can.
* :class:`CatalogError`: the subgroup catalog's data are broken.

Every exception class of mechsing is defined here, so that any layer can raise
or catch any of them without importing another layer (the old homes re-export
them):

* bad input, with the parts of the message as attributes:
  :class:`MechanismError` (a mechanism file: path, line, item),
  :class:`ExpressionError` (a number or expression), :class:`InputError` (a file
  that cannot be read), :class:`ParameterError` (an exercise's parameter);
* configurations not analysed: :class:`ClosureError` (it does not close) and
  :class:`ExactDataError` (exact mode cannot take it);
* signals caught inside mechsing and turned into one of the above:
  :class:`YAMLReadError` (text that is not YAML mechsing accepts),
  :class:`InputRefError` (an input that names no actuable coordinate),
  :class:`EliminationTooLarge` (an elimination of passive joints not attempted),
  :class:`TooManyModes` (assembly modes too many to analyse, said with the file's name);
* :class:`TimeLimitExceeded`, a :class:`BaseException` (so that no ``except
  Exception`` swallows it) raised by :class:`mechsing.timelimit.TimeLimit`.

The layers raise these and never decide what a command does with them: only
the command line (``mechsing.cli.main``) maps them to exit statuses.
:func:`working_on` names the file and the configuration under analysis, so
that an exception that escapes everything (a defect of mechsing) can still say
where it happened (:func:`current_work`).  :func:`note_stop` records the signal that
asked the running command to stop, and :func:`raise_if_stopped` raises it again where a
stop must not be lost (code that swallowed the first :class:`Interrupted`).
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from contextvars import ContextVar

__all__ = [
    "BeyondTravelError",
    "CatalogError",
    "ClosureError",
    "ConfigurationError",
    "EliminationTooLarge",
    "ExactDataError",
    "ExpressionError",
    "FormulationError",
    "InputError",
    "InputRefError",
    "Interrupted",
    "MechanismError",
    "MechsingError",
    "ParameterError",
    "TimeLimitExceeded",
    "TooManyModes",
    "UserError",
    "YAMLReadError",
    "current_work",
    "forget_work",
    "note_stop",
    "raise_if_stopped",
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


class MechanismError(UserError):
    """A mechanism file that mechsing cannot accept (bad input).

    The message names the file, the line where it can, the item and the fix;
    the parts are also attributes for programs and tests.
    """

    def __init__(
        self,
        message: str,
        *,
        path: str | None = None,
        line: int | None = None,
        item: str | None = None,
    ) -> None:
        where = ""
        if path is not None:
            where = f"{path}:{line}: " if line is not None else f"{path}: "
        elif line is not None:
            where = f"line {line}: "
        lead = f"{item}: " if item else ""
        super().__init__(f"{where}{lead}{message}")
        self.path = path
        self.line = line
        self.item = item
        self.problem = message


class ExpressionError(UserError, ValueError):
    """A number or expression that cannot be read (exit status 2).

    The message says what is wrong and what is allowed; callers that know the
    file and line (the mechanism loader) prefix them.
    """


class InputError(UserError):
    """A file that cannot be read: ``path`` and ``problem`` (the message without the path)."""

    def __init__(self, path: str, problem: str) -> None:
        super().__init__(f"{path}: {problem}")
        self.path = path
        self.problem = problem


class ParameterError(UserError):
    """A parameter that is not a real number; ``values`` holds the ones before it."""

    def __init__(self, message: str, values: dict[str, float]) -> None:
        super().__init__(message)
        self.values = values


class ClosureError(ConfigurationError):
    """A configuration that cannot be closed."""


class BeyondTravelError(ClosureError):
    """A configuration whose given values lie beyond a limit of travel of the assembly
    mode continuation follows from its start; ``travel`` is the sentence that says which
    value, by how much, and where its limit is."""

    def __init__(
        self, message: str, configuration: str, residual: float | None, travel: str
    ) -> None:
        super().__init__(message, configuration, residual)
        self.travel = travel

    def __reduce__(self) -> tuple[type, tuple[str, str, float | None, str]]:  # type: ignore[override]
        return (type(self), (str(self), self.configuration, self.residual, self.travel))


class FormulationError(UserError):
    """A formulation of every assembly mode (``mechsing modes``) does not apply to the
    mechanism or its given values: the reason, which the command completes."""


class TooManyModes(UserError):
    """The solutions of the parts of an assembly-mode problem, solved apart, combine into
    more modes than are analysed: the message gives each part's count; the formulation
    adds the file and the configuration."""


class ExactDataError(ConfigurationError):
    """Exact mode cannot take a configuration: a joint value is missing (it would be solved
    numerically), is not exact data, or sympy cannot prove that the loops close exactly."""


class YAMLReadError(Exception):
    """The text is not YAML that mechsing accepts; ``line`` is 1-based or None."""

    def __init__(self, message: str, line: int | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.line = line


class InputRefError(ValueError):
    """An input that names no actuable coordinate: ``item`` (e.g. ``input 'A[3]'``) and
    ``problem`` (what is wrong and what to write) for the caller's message."""

    def __init__(self, item: str, problem: str) -> None:
        super().__init__(f"{item}: {problem}")
        self.item = item
        self.problem = problem


class EliminationTooLarge(Exception):
    """An elimination step of :mod:`mechsing.conditions.elimination` past its bounds
    (``RESULTANT_MAX_WORK``, ``ELIMINATION_MAX_TERMS``): not attempted; the message says
    which bound and by how much."""


class TimeLimitExceeded(BaseException):
    """The block of a :class:`~mechsing.timelimit.TimeLimit` ran longer than its limit.

    ``activity``: the innermost :func:`~mechsing.timelimit.activity` the code was in when
    it was interrupted (None when it was in none).
    """

    activity: str | None = None


class Interrupted(KeyboardInterrupt):
    """A command stopped by a signal (SIGTERM as Ctrl-C is): ``signum`` is its number.
    A KeyboardInterrupt, so that what cleans up after Ctrl-C does so after SIGTERM too."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


#: the signal that asked the running command to stop, while it runs (one process, one
#: command: a signal is the process's, so this is not per context)
_STOP: dict[str, int | None] = {"signum": None}


def note_stop(signum: int | None) -> None:
    """Record that ``signum`` asked the running command to stop (None: clear the record,
    as a command starts and ends).  Set by the command line's signal handler."""
    _STOP["signum"] = signum


def raise_if_stopped() -> None:
    """Raise :class:`Interrupted` if a signal asked the command to stop: the stop is
    raised where the signal arrived, but code that swallows exceptions (a weak
    reference's callback, a library's bare ``except``) can lose it there, so what must not
    happen after a stop (an output file replaced, a success status) asks again."""
    signum = _STOP["signum"]
    if signum is not None:
        raise Interrupted(signum)


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
