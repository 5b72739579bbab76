"""Every assembly mode of a configuration: :func:`modes`, which only dispatches.

What is given is read once (:func:`~mechsing.assembly.given.read_given`, its values
checked), the first formulation of the registry that applies finds the modes
(:func:`~mechsing.assembly.registry.find`), and
:func:`~mechsing.assembly.result.finish` classifies and reports them, all under one time
limit.

Owns :func:`modes` (and re-exports :class:`Mode` and :class:`ModesResult`).
"""

from __future__ import annotations

import mpmath

from mechsing.assembly.result import Mode, ModesResult, finish
from mechsing.errors import UserError
from mechsing.model import Mechanism
from mechsing.numeric import Precision, parse_precision, rotation_orthonormal_atol

__all__ = ["Mode", "ModesResult", "modes"]

#: the mechanism's extra that brings the continuation engine (named in messages)
EXTRA = "pip install 'mechsing[modes]'"


def modes(
    mechanism: Mechanism | str,
    config: str,
    precision: Precision | str = "auto",
    time_limit: float | None = None,
    start: str | None = None,
) -> ModesResult:
    """Every real assembly mode of configuration ``config`` (its given joint values).

    Parameters
    ----------
    mechanism : Mechanism or str
        A mechanism (:func:`mechsing.load`) or a file's path.
    config : str
        The configuration whose given values (the inputs) every mode shares; the one
        continuation from its ``start`` reaches is marked.
    precision : Precision or str
        How each mode is classified (``"auto"``, ``"float"``, ``"mp:N"``); the modes are
        found at max(50, N + 10) digits whatever it is.
    time_limit : float or None
        The most seconds (None: no limit).
    start : str or None
        The configuration continuation starts from to mark the mode it reaches (None: the
        configuration's own ``start``).

    Returns
    -------
    ModesResult

    Raises
    ------
    UserError
        No registered formulation applies (the message names each one's reason).
    """
    from mechsing.assembly.given import read_given
    from mechsing.assembly.registry import find
    from mechsing.reader import read_mechanism
    from mechsing.timelimit import TimeLimit

    mech = mechanism if isinstance(mechanism, Mechanism) else read_mechanism(mechanism)
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    if prec.mode == "exact":
        raise UserError(
            "modes classifies modes found numerically (certified, not exact "
            "values): use --precision auto, float or mp:N"
        )
    if config not in mech.configurations:
        raise UserError(
            f"{mech.path or mech.name}: no configuration named {config!r}; the "
            f"file has: {', '.join(mech.configurations)}"
        )
    dps = max(50, (prec.digits or 0) + 10)
    # one time limit for the whole: the solving, the certification and the classification
    with TimeLimit(time_limit):
        given = read_given(mech, config, prec, dps, rotation_orthonormal_atol(prec), start)
        if mech.loops:  # absurd given values refused before any solving
            _check_values(mech, config)
        with mpmath.workdps(dps):
            found = find(given)
        return finish(given.mech, config, prec, found, dps)


def _check_values(mech: Mechanism, config: str) -> None:
    """The given values are finite and of a sensible size (the analysis's bound, its
    message naming the configuration and the joint): refused before any solving."""
    from mechsing.kinematics import KinematicModel
    from mechsing.kinematics.given import GivenValues

    try:
        GivenValues(KinematicModel(mech, "float")).of(mech.configurations[config])
    except UserError as exc:
        raise UserError(f"{mech.path or mech.name}: {exc}") from None
