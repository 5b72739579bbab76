"""The ``couplings`` key of a mechanism file: linear couplings of joint coordinates.

Owns :func:`read_couplings` and :func:`refuse_couplings`.  A coupling is what a URDF
``<mimic>`` element says: the value of ``joint`` is ``multiplier * (value of leader) +
offset``, both joints of one coordinate, the values in the file's units (``offset``
in the unit of ``joint``'s coordinate; ``multiplier`` the ratio of the two values as
written, so a degree file's R joint coupled to a P joint takes degrees per length
unit)::

    couplings:
      - {joint: finger_right, leader: finger_left, multiplier: -1, offset: 0}

``mechsing convert`` writes the entries of a URDF's mimic joints, with
``source_line``, the line of the ``<mimic>`` element; such an entry may name a leader the
description does not define (a broken ``<mimic>``): it is kept, so the robot is still read,
and refused when its joint is analysed (:func:`refuse_orphan_couplings`).  The analysis
models a coupling as one more constraint of the closure system
(:mod:`mechsing.kinematics.couplings`: a row ``dq_f - m dq_l = 0`` at first order, a
residual ``q_f - m q_l - c`` at finite order); a path that does not take couplings
(symbolic conditions) refuses them (:func:`refuse_couplings`, exit 2 naming the joint and
its line).  A coupling whose joint lies on a branch the scene options leave out
(``--output-body``: the fingers, another arm) is dropped with its branch
(:mod:`mechsing.model.scene`).
"""

from __future__ import annotations

from typing import Any

from mechsing.errors import MechanismError
from mechsing.model.mechanism import Coupling, Joint, Mechanism

__all__ = [
    "COUPLING_KEYS",
    "coupling_line",
    "coupling_source",
    "describe_coupling",
    "read_couplings",
    "refuse_couplings",
    "refuse_orphan_couplings",
]

#: keys of one entry of ``couplings``
COUPLING_KEYS = ("joint", "leader", "multiplier", "offset", "source_line")


def read_couplings(r: Any, v: Any, jmap: dict[str, Joint]) -> tuple[Coupling, ...]:
    """The ``couplings`` of a file (``r``: the loader's reader; ``v``: the key's node)."""
    if v is None:
        return ()
    from mechsing.yamlnodes import YScalar

    seq = r.sequence(
        v, "couplings", "couplings", "couplings: [{joint: B, leader: A, multiplier: 1}]"
    )
    out: list[Coupling] = []
    followers: dict[str, int | None] = {}
    for e in seq.items:
        m = r.mapping(e, "couplings", "each coupling")
        r.keys(m, "couplings", COUPLING_KEYS, ("joint", "leader"))
        follower = r.name(m.get("joint"), "couplings", "the coupled joint")
        item = f"coupling of {follower!r}"
        leader = r.name(m.get("leader"), item, "the leader joint")
        source_line = None
        sl = m.get("source_line")
        if sl is not None:
            if not (isinstance(sl, YScalar) and sl.kind == "int" and int(sl.text) > 0):
                raise r.error(item, m.key_line("source_line"), "source_line must be a line number")
            source_line = int(sl.text)
        # a converted description's coupling to a joint it does not define is kept, and
        # refused when its joint is analysed (refuse_orphan_couplings): the robot is still read
        orphan = leader not in jmap and source_line is not None and follower in jmap
        for name, key in ((follower, "joint"), (leader, "leader")):
            if name == leader and orphan:
                continue
            if name not in jmap:
                raise r.error(
                    item,
                    m.key_line(key),
                    f"unknown joint {name!r}; use one of {', '.join(list(jmap)[:8])}",
                )
            if jmap[name].dof != 1:
                raise r.error(
                    item,
                    m.key_line(key),
                    f"joint {name!r} ({jmap[name].type}) has {jmap[name].dof} coordinates; a "
                    "coupling ties two joints of one coordinate (R, P, H)",
                )
        if leader == follower:
            raise r.error(item, m.line, "a joint cannot be coupled to itself; name another leader")
        if follower in followers:
            raise r.error(
                item,
                m.line,
                f"joint {follower!r} is already coupled (line {followers[follower]}); "
                "couple it once",
            )
        followers[follower] = m.line
        unit_f = _factor(r, jmap[follower])
        unit_l = unit_f if orphan else _factor(r, jmap[leader])
        mult = (
            1 if m.get("multiplier") is None else r.number(m.get("multiplier"), item, "multiplier")
        )
        offset = 0 if m.get("offset") is None else r.number(m.get("offset"), item, "offset", unit_f)
        out.append(
            Coupling(
                follower, leader, mult * unit_f / unit_l, offset, m.line, source_line, not orphan
            )
        )
    return tuple(out)


def _factor(r: Any, j: Joint) -> Any:
    return r.units.angle_factor if j.units[0] == "rad" else r.units.length_factor


def describe_coupling(c: Coupling) -> str:
    """``joint = multiplier x leader + offset`` in words (SI, radians)."""
    from mechsing.numeric import to_float

    mult, off = to_float(c.multiplier), to_float(c.offset)
    tail = f" {'+' if off >= 0 else '-'} {abs(off):.6g}" if off else ""
    return f"{c.joint} = {mult:.6g} x {c.leader}{tail}"


def coupling_line(c: Coupling) -> int | None:
    """The line a reader looks at for a coupling: its ``<mimic>``'s in a converted
    description, else its entry's."""
    return c.source_line if c.source_line is not None else c.line


def coupling_source(c: Coupling) -> str:
    """Where a coupling comes from, in words: ``<mimic>, line 63`` or ``coupling, line 9``."""
    what = "<mimic>" if c.source_line is not None else "coupling"
    line = coupling_line(c)
    return what if line is None else f"{what}, line {line}"


def refuse_orphan_couplings(mech: Mechanism) -> None:
    """A MechanismError (exit 2) for a coupling of ``mech`` whose leader the robot does not
    define (a converted ``<mimic>`` naming a missing joint): it cannot be modelled; the
    message names the joint, its line and the ways out."""
    for c in mech.couplings:
        if c.leader_defined:
            continue
        raise MechanismError(
            f"joint {c.joint!r}: its {'<mimic>' if c.source_line is not None else 'coupling'} "
            f"names joint {c.leader!r}, which the robot does not define; fix the name, or "
            f"name an output on a branch that does not hold {c.joint!r} (--output-body BODY: "
            "the branches that neither lead to it nor close a loop with it are left out, "
            "couplings included)",
            path=mech.path,
            line=coupling_line(c),
        )


def refuse_couplings(mech: Mechanism, what: str) -> None:
    """A MechanismError (exit 2) for the first coupling of ``mech`` on a path that does
    not model couplings (``what``: that path, e.g. "symbolic conditions"); the message
    names the joint, its line and the ways out."""
    refuse_orphan_couplings(mech)
    if not mech.couplings:
        return
    c = mech.couplings[0]
    more = (
        f" (and {len(mech.couplings) - 1} more coupled joint"
        + ("s" if len(mech.couplings) > 2 else "")
        + ": "
        + ", ".join(repr(x.joint) for x in mech.couplings[1:4])
        + (", ..." if len(mech.couplings) > 4 else "")
        + ")"
        if len(mech.couplings) > 1
        else ""
    )
    raise MechanismError(
        f"joint {c.joint!r} is coupled to joint {c.leader!r} "
        f"({'<mimic>' if c.source_line is not None else 'coupling'}: {describe_coupling(c)})"
        f"{more}: couplings of joint values are not supported by {what} yet (analyze, "
        "solve and sweep take them). Name an output on a branch that does not hold the coupled joint "
        "(--output-body BODY: the branches that neither lead to it nor close a loop with "
        "it are left out, couplings included), or remove the coupling",
        path=mech.path,
        line=coupling_line(c),
    )
