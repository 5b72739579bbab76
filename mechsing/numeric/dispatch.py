"""The one place that chooses fast paths.

Some formulas have a faster form for some inputs: the float64 kernels of the Lie
layer, the Rodrigues closed form of a one-dof joint's exponential (filled entry by
entry on large batches), the block-by-block factorisations of big sparse matrices,
the compiled screen of the scanner, the sweeps' measures of several rows in one
batch.  Each such formula has ONE generic definition (the code that runs on every
backend) and ONE :class:`Table`, named after the formula (one signature per table);
its faster forms register themselves there, each with the inputs it accepts (a
predicate on the formula's own arguments: their dtype, their shape, the joint's
kind).  The generic code hands its arguments to its table (:meth:`Table.pick`), which
answers the first registered form that accepts them, or None (the generic definition
then runs): the caller never names a form nor the fast module.  As
:mod:`scipy.spatial.transform` picks its backend once, the switch is read once, from
the environment, when mechsing is imported:

``MECHSING_FAST=0``
    every fast path off: each table answers ``None`` and every size threshold is
    infinite, so each formula runs its generic definition (the same mathematics, to
    rounding; the analysis's decisions carry margins that absorb it).
    ``MECHSING_NO_COMPILED=1`` (the older switch of the compiled screen alone) is an
    alias of ``MECHSING_FAST=0``.

Tests and benchmarks choose a path through :func:`fast_paths` (a context manager),
never by changing a module's attribute: ``fast_paths(False)`` is the generic code,
``fast_paths(True)`` the default (fast forms above their thresholds),
``fast_paths("always")`` takes every fast form whatever the input's size (its
thresholds zero), so that a small test input reaches the form a big mechanism takes;
``table(name).disabled(form)`` turns one form off.
:func:`tables` lists every table and its forms; one parity test per table runs every
registered form against the generic definition (and fails on a form it does not know).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

__all__ = [
    "ENVIRONMENT",
    "Form",
    "Table",
    "enabled",
    "fast_paths",
    "float64_arrays",
    "mode",
    "table",
    "tables",
    "threshold",
]

#: the environment variable of the switch, and its older alias (compiled screen)
ENVIRONMENT = "MECHSING_FAST"
_ALIAS = "MECHSING_NO_COMPILED"

_F64 = np.dtype(np.float64)

Mode = Literal["off", "on", "always"]


def _from_environment(environ: Mapping[str, str]) -> Mode:
    value = environ.get(ENVIRONMENT)
    if value is not None:
        return "off" if value.strip().lower() in ("0", "false", "no", "off") else "on"
    return "off" if environ.get(_ALIAS) else "on"


#: the mode stack: the environment's at the bottom, :func:`fast_paths` pushes
_MODE: list[Mode] = [_from_environment(os.environ)]


def mode() -> Mode:
    """The current mode: ``"off"``, ``"on"`` or ``"always"`` (module docstring)."""
    return _MODE[-1]


def enabled() -> bool:
    """Are fast paths on (``MECHSING_FAST`` not 0, and no ``fast_paths(False)``)?"""
    return _MODE[-1] != "off"


def threshold(size: float) -> float:
    """A fast form's size threshold as the mode has it: ``size`` when on, 0 with
    ``fast_paths("always")``, infinity when off (no input is big enough)."""
    m = _MODE[-1]
    if m == "on":
        return size
    return 0 if m == "always" else math.inf


@contextmanager
def fast_paths(on: bool | Literal["always"]) -> Iterator[None]:
    """Within the block, fast paths on (True), off (False: the generic definitions) or
    taken at every size (``"always"``)."""
    if on not in (True, False, "always"):
        raise ValueError(f"fast_paths takes True, False or 'always', not {on!r}")
    _MODE.append("always" if on == "always" else "on" if on else "off")
    try:
        yield
    finally:
        _MODE.pop()


def float64_arrays(*args: Any) -> bool:
    """Whether every one of ``args`` is a float64 ndarray (the default predicate of a form
    for float numbers: mp and exact arrays, objects, take the generic definition)."""
    for a in args:
        if not isinstance(a, np.ndarray) or a.dtype != _F64:
            return False
    return True


@dataclass(frozen=True)
class Form:
    """A fast form of a table's formula.

    ``function``: the form itself (the formula's signature, or, for a form that serves
    another form of its table, its own); ``when``: in words, the inputs it serves, what
    it saves and how close it is to the generic definition (bit for bit, or to
    rounding); ``accepts``: the predicate on the formula's arguments that chooses it
    (None: a form :meth:`Table.pick` never answers, which another form of the table
    calls, as the entrywise one-dof exponential)."""

    name: str
    function: Callable[..., Any]
    when: str
    accepts: Callable[..., bool] | None = float64_arrays


@dataclass
class Table:
    """The fast forms of one formula (``generic``: where its generic definition is)."""

    name: str
    generic: str
    forms: dict[str, Form] = field(default_factory=dict)

    def register(
        self,
        name: str,
        when: str,
        accepts: Callable[..., bool] | None = float64_arrays,
    ) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
        """Decorator: register the decorated function as the form ``name``, taken for the
        arguments ``accepts`` (a predicate on the formula's arguments) returns True for
        (forms are asked in the order they were registered)."""

        def add(function: Callable[..., Any]) -> Callable[..., Any]:
            if name in self.forms and self.forms[name].function is not function:
                raise ValueError(f"dispatch table {self.name!r} has a form {name!r} already")
            self.forms[name] = Form(name, function, when, accepts)
            return function

        return add

    def pick(self, *args: Any) -> Callable[..., Any] | None:
        """The form for these arguments of the formula: the first registered form that
        accepts them, when fast paths are on; else None (the caller then runs the
        generic definition)."""
        if _MODE[-1] == "off":
            return None
        for form in self.forms.values():
            accepts = form.accepts
            if accepts is not None and accepts(*args):
                return form.function
        return None

    @contextmanager
    def disabled(self, name: str) -> Iterator[None]:
        """Within the block, the form ``name`` alone is off (a benchmark's or a test's
        comparison of one form with the rest of the fast paths kept)."""
        form = self.forms.pop(name)
        try:
            yield
        finally:
            self.forms[name] = form

    def get(self, name: str) -> Callable[..., Any] | None:
        """The form ``name`` when fast paths are on and it is registered, else None (a
        parity test's or a benchmark's access to one form; the code asks :meth:`pick`)."""
        if _MODE[-1] == "off":
            return None
        form = self.forms.get(name)
        return None if form is None else form.function


_TABLES: dict[str, Table] = {}


def table(name: str, generic: str = "") -> Table:
    """The table of the formula ``name`` (created on first use); ``generic`` names its
    generic definition (for the listing; given by the module that holds it)."""
    t = _TABLES.get(name)
    if t is None:
        t = _TABLES[name] = Table(name, generic)
    elif generic and not t.generic:
        t.generic = generic
    return t


def tables() -> dict[str, Table]:
    """Every table by name, with its forms (the modules that register forms are those
    mechsing imports; :mod:`mechsing.numeric.dispatch` lists what they registered)."""
    return dict(_TABLES)
