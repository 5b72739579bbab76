"""The mechanism-level properties (``properties`` of the JSON contract), decided from the
typed results of the configurations analysed.

What holds at every regular configuration of a branch is a property, never a singularity:
``overconstrained`` (finite above group), ``shaky`` (instantaneous above finite at regular
points), ``idle-motion`` (a passive motion with inputs and output still, present
generically), ``redundant-actuation`` and ``underactuated`` (inputs against finite).
"""

from __future__ import annotations

from collections.abc import Sequence

from mechsing.analysis.results import (
    Actuation,
    ConfigurationResult,
    IdleMotion,
    Overconstrained,
    Property,
    Shaky,
)
from mechsing.model import Mechanism

__all__ = ["mechanism_properties"]


def mechanism_properties(
    mech: Mechanism, results: Sequence[ConfigurationResult]
) -> tuple[Property, ...]:
    """The properties the configurations ``results`` show (the first regular one speaks
    for the mechanism; all of them when every one is singular)."""
    props: list[Property] = []
    ok = [
        r
        for r in results
        if r.error is None and r.mobility is not None and r.mobility.finite is not None
    ]
    regular = [r for r in ok if not r.singularities] or ok
    if not regular:
        return ()
    r = regular[0]
    mob = r.mobility
    assert mob is not None and mob.finite is not None
    if mech.loops and mob.group is not None and mob.finite > mob.group:
        props.append(Overconstrained(mob.finite, mob.group, mob.grubler, r.name))
    shaky = [
        x
        for x in regular
        if x.mobility is not None
        and x.mobility.generic is not None
        and x.mobility.finite is not None
        and x.mobility.generic > x.mobility.finite
    ]
    if shaky:
        m0 = shaky[0].mobility
        assert m0 is not None and m0.generic is not None and m0.finite is not None
        props.append(Shaky(m0.generic, m0.finite, tuple(y.name for y in shaky)))
    idle = 0
    for x in regular:
        c = x.classification
        dim = c.io_value("passive-motion") if c is not None else None
        if dim:
            idle = dim
            props.append(IdleMotion(dim, x.name))
            break
    n_in = len(mech.input_coordinates())
    if n_in:
        # idle motions move nothing that matters: they need no actuator
        useful = mob.finite - idle
        if n_in > useful:
            props.append(Actuation("redundant-actuation", n_in, mob.finite, idle, r.name))
        elif n_in < useful:
            props.append(Actuation("underactuated", n_in, mob.finite, idle, r.name))
    return tuple(props)
