"""Findings and screws in words: the one place the words a student reads are made.

* a singularity class in a few words (:data:`CLASS_WORDS`, :func:`class_words`,
  :func:`finding_label`), a finding in a sentence with its own numbers
  (:func:`explain`), a margin in a line (:func:`margin_text`);
* a twist, a wrench, a point velocity or a subgroup as a phrase ("a rotation about the
  axis through (4, 0, 0) along z"): :func:`twist_words`, :func:`wrench_words`,
  :func:`velocity_words` and :func:`subgroup_words`.

The verdict table (:mod:`mechsing.analysis.html`), the text and Markdown renderings and
the design review (:mod:`mechsing.reports`) take their words from here.  Screws:  Conventions: SI at the ground origin; a twist is (omega, v)
(rad/s, m/s: ``v`` is the velocity of the body point at the origin), a wrench (f, m)
(N, N m: ``m`` the moment about the origin).  A twist with omega != 0 is a screw about
the axis through ``p = omega x v / |omega|^2`` along omega with pitch
``h = omega . v / |omega|^2`` (m/rad): a rotation when h = 0, a translation along v when
omega = 0 (infinite pitch).  A wrench with f != 0 is a force along f through
``p = f x m / |f|^2`` with pitch ``h = f . m / |f|^2`` (m): a pure force when h = 0, a
couple along m when f = 0.  "Zero" is decided relative to the screw's own size with
:data:`mechsing.numeric.MEMBERSHIP_RTOL_FLOAT` (angular parts times the length scale L,
so the decision does not depend on the unit of length).  Directions are shown as unit
vectors (``x``, ``-z`` when along a coordinate axis), numbers to 4 significant digits.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from mechsing.analysis.contract import finding_class, subgroup_params
from mechsing.analysis.display import with_unit
from mechsing.numeric import MEMBERSHIP_RTOL_FLOAT, Margin
from mechsing.numeric.linalg import first_nonzero_positive
from mechsing.numeric.numbers import unit_vector
from mechsing.singularity.findings import (
    BranchFinding,
    ConstraintFinding,
    Finding,
    SerialFinding,
    UndecidedFinding,
)
from mechsing.singularity.names import LEG, meaning_of
from mechsing.subgroups import Subgroup

__all__ = [
    "CLASS_WORDS",
    "class_words",
    "explain",
    "finding_label",
    "joint_list",
    "margin_text",
    "number_text",
    "subgroup_words",
    "twist_words",
    "velocity_space_words",
    "velocity_words",
    "wrench_words",
]

_AXES = ("x", "y", "z")


def _num(x: float, scale: float = 1.0) -> str:
    """``x`` to 4 significant digits; rounding-level values (next to ``scale``) as 0."""
    if abs(x) <= MEMBERSHIP_RTOL_FLOAT * max(scale, 1e-300):
        return "0"
    return f"{x:.4g}"


def _direction(u: np.ndarray) -> str:
    """A direction: ``x``, ``-y``, ... along a coordinate axis, else its unit vector."""
    u = unit_vector(u)
    for i, name in enumerate(_AXES):
        rest = np.delete(u, i)
        if np.all(np.abs(rest) <= MEMBERSHIP_RTOL_FLOAT):
            return name if u[i] > 0 else f"-{name}"
    return "(" + ", ".join(_num(float(c)) for c in u) + ")"


def _point(p: np.ndarray, length_scale: float) -> str:
    return "(" + ", ".join(_num(float(c), length_scale) for c in p) + ")"


def twist_words(twist: Sequence[float], length_scale: float = 1.0) -> str:
    """A twist (omega, v) in words: a rotation, a translation or a screw with its axis."""
    t = np.asarray(twist, dtype=float)
    w, v = t[:3], t[3:6]
    nw, nv = float(np.linalg.norm(w)), float(np.linalg.norm(v))
    L = float(length_scale)
    if nw * L <= MEMBERSHIP_RTOL_FLOAT * nv:
        if nv == 0.0:
            return "no motion"
        return f"a translation along {_direction(v)}"
    p = np.cross(w, v) / nw**2
    h = float(w @ v) / nw**2
    where = f"the axis through {with_unit(_point(p, L), 'm')} along {_direction(w)}"
    if abs(h) * nw <= MEMBERSHIP_RTOL_FLOAT * max(nv, nw * L):
        return f"a rotation about {where}"
    return f"a screw motion of pitch {with_unit(f'{h:.4g}', 'm/rad')} about {where}"


def wrench_words(wrench: Sequence[float], length_scale: float = 1.0) -> str:
    """A wrench (f, m) in words: a force along a line, a couple, or a wrench with pitch."""
    x = np.asarray(wrench, dtype=float)
    f, m = x[:3], x[3:6]
    nf, nm = float(np.linalg.norm(f)), float(np.linalg.norm(m))
    L = float(length_scale)
    if nf * L <= MEMBERSHIP_RTOL_FLOAT * nm:
        if nm == 0.0:
            return "no load"
        return f"a couple about {_direction(m)}"
    p = np.cross(f, m) / nf**2
    h = float(f @ m) / nf**2
    where = f"along {_direction(f)} through {with_unit(_point(p, L), 'm')}"
    if abs(h) * nf <= MEMBERSHIP_RTOL_FLOAT * max(nm, nf * L):
        return f"a force {where}"
    pitch = with_unit(f"{h:.4g}", "m")
    return f"a force {where} with a couple along it (a wrench of pitch {pitch})"


def velocity_words(velocity: Sequence[float]) -> str:
    """A point's velocity in words (its direction)."""
    v = np.asarray(velocity, dtype=float)
    if not np.any(v):
        return "the point stays still"
    return f"the point moves along {_direction(v)}"


def velocity_space_words(velocities: Sequence[Sequence[float]]) -> str:
    """A space of point velocities (a basis) in words: still, along a line, in a plane
    (named by its normal), or in every direction."""
    V = [np.asarray(v, dtype=float) for v in velocities]
    if not V:
        return "stays still"
    if len(V) == 1:
        return f"moves along {_direction(V[0])} only"
    if len(V) == 2:
        n = np.cross(V[0], V[1])
        n = first_nonzero_positive(n)
        return f"moves in the plane normal to {_direction(n)}"
    return "moves in every direction"


def subgroup_words(sub: Subgroup) -> str:
    """A subgroup with its name and geometry: ``R (rotation about an axis (revolute)):
    axis z through (4, 0, 0) m``."""
    parts = []
    for k, val in subgroup_params(sub).items():
        kind = dict(sub.type.parameters)[k]
        if kind == "point":
            parts.append(f"{k} {with_unit(_point(np.asarray(val, dtype=float), 1.0), 'm')}")
        elif kind == "pitch":
            parts.append(f"pitch {with_unit(f'{float(val):.4g}', 'm/rad')}")
        else:
            parts.append(f"{k} {_direction(np.asarray(val, dtype=float))}")
    tail = f": {', '.join(parts)}" if parts else ""
    return f"{sub.symbol} ({sub.type.name}, dimension {sub.dim}){tail}"


def describe(x: Any, kind: str, length_scale: float = 1.0) -> str:
    """``twist``, ``wrench`` or ``velocity`` in words (a 3-vector twist is a velocity)."""
    if kind == "wrench":
        return wrench_words(x, length_scale)
    if len(x) == 3:
        return velocity_words(x)
    return twist_words(x, length_scale)


# --------------------------------------------------------------------------- findings

#: each singularity class of the JSON contract in a few words
CLASS_WORDS = {
    "serial": "serial: a chain loses a direction of motion",
    "bifurcation": "bifurcation: branches of motion cross",
    "isolated": "isolated: a rigid assembly, nothing nearby closes",
    "degenerate": "degenerate: the rank drops and the motion is not described",
    "increased-mobility": "increased instantaneous mobility",
    "input": "input (type I): an input moves while the output stays still",
    "output": "output (type II): the output moves with the inputs locked",
    "passive-motion": "passive motion with inputs and output still",
    "impossible-input": "impossible input: the inputs lose independent rates",
    "impossible-output": "impossible output: the output loses independent motions",
    "constraint": "constraint: the output gains a motion outside its type",
    "undecided": "undecided at this precision",
}


def finding_label(f: Any) -> str:
    """A finding's class, with the name people give it where it has one (``serial (elbow)``)."""
    cls, name = finding_class(f), getattr(f, "name", None)
    return f"{cls} ({name})" if name else cls


def class_words(classes: Sequence[str]) -> str:
    """The classes in words, in order, each once (``none`` when there is none)."""
    seen = list(dict.fromkeys(classes))
    return "; ".join(_words(c) for c in seen) or "none"


def _words(label: str) -> str:
    """The words of a class, or of a named finding's label (``serial (elbow)``)."""
    cls, _, name = label.partition(" (")
    if not name:
        return CLASS_WORDS.get(cls, cls)
    name = name.rstrip(")")
    head = CLASS_WORDS.get(cls, cls).split(":")[0]  # "output (type II)", or "serial"
    if head != cls:  # the class's own name kept beside the finding's (type II, a dead centre)
        return f"{head}, {name}: {meaning_of(name) or name}"
    return f"{cls} ({name}: {meaning_of(name) or name})"


def number_text(x: Any) -> str:
    """A count or value as shown (``-`` for None, floats to 4 digits)."""
    if x is None:
        return "-"
    if isinstance(x, float):
        return f"{x:.4g}"
    return str(x)


def margin_text(m: Margin | None) -> str:
    """A margin's kept and dropped singular values, its thresholds and L, in a line; the
    thresholds are relative, so the largest singular value they multiply is said beside
    them (the kept and dropped values are not relative: 4e-16 dropped of a largest 2.6 is
    1.6e-16 of it, which is what tau_lo bounds)."""
    if m is None:
        return ""
    parts = [f"kept {number_text(m.kept)}", f"dropped {number_text(m.dropped)}"]
    if m.eig_margin is not None:
        parts.append(f"eigenvalue margin {number_text(m.eig_margin)}")
    lo, hi = m.thresholds
    L = with_unit(f"{m.length_scale:.4g}", "m")
    of = f" of the largest, {number_text(m.sigma_max)}" if m.sigma_max else ""
    return ", ".join(parts) + f" (thresholds {lo}/{hi}{of}; L = {L})"


def joint_list(xs: Sequence[str]) -> str:
    """``A, B and C`` (``no joint`` when empty)."""
    if not xs:
        return "no joint"
    return ", ".join(xs[:-1]) + (" and " if len(xs) > 1 else "") + xs[-1]


def explain(f: Finding) -> str:
    """One sentence a student understands, with the finding's own numbers."""
    cls = f.cls
    if isinstance(f, UndecidedFinding):
        why = (
            f"its rank lies between {f.rank_bounds[0]} and {f.rank_bounds[1]}"
            if f.rank_bounds
            else (
                f.note if f.note is not None else "a singular value lies between the two thresholds"
            )
        )
        return (
            f"the precision used cannot decide the {f.what} ({why}); {_more_precise(f.precision)}"
        )
    j = joint_list(f.joints)
    if isinstance(f, SerialFinding):
        what = f"leg {f.leg}" if f.chain == "leg" else "the chain to the output"
        # "wrist singularity (...)", "leg fully stretched or folded (...)"
        kind = f.name if f.name == LEG else f"{f.name} singularity"
        named = f"{kind} ({meaning_of(f.name)}): " if f.name else ""
        return (
            f"{named}{what} loses {f.corank} direction(s) of motion (rank {f.rank} instead of "
            f"{f.generic_rank}): joints {j} can move while its end stays still, and it resists "
            f"{f.corank} more wrench(es) than usual with no joint effort ({len(f.wrenches)} in all)"
        )
    if isinstance(f, ConstraintFinding):
        return (
            f"the legs' constraint wrenches drop to rank {f.rank} (generically {f.generic_rank}): the output "
            "gains a motion outside its usual motion type"
        )
    if isinstance(f, BranchFinding):
        if cls == "bifurcation":
            mobs = ", ".join("?" if m is None else str(m) for m in f.branch_mobility or ())
            kin = (
                " (branches of different mobility meet: a kinematotropic point)"
                if f.kinematotropic
                else ""
            )
            return (
                f"{f.branches} branches of motion cross here (branch mobilities {mobs}){kin}: from this "
                f"configuration the mechanism can leave along different paths, decided at order {f.order}"
            )
        if cls == "isolated":
            return (
                f"the joints have {f.instantaneous} instantaneous motion(s), but none extends to a real "
                "motion: this assembly is rigid and no nearby configuration closes"
            )
        if cls == "degenerate":
            return f"the loops lose rank and the higher-order test cannot describe the motion here ({f.note or ''})"
        return (
            f"the joints have {f.instantaneous} instantaneous motion(s) where the mechanism moves with "
            f"{f.generic}: the extra ones do not extend, and one smooth branch passes through"
        )
    # "dead centre: ... leg fully stretched or folded (...)": named as a leg's would be
    named = f"{f.name} ({meaning_of(f.name)}): " if getattr(f, "name", None) else ""
    if cls == "input":
        return f"{named}an input can move while the output stays still (moving joints: {j}): the output loses a direction"
    if cls == "output":
        return (
            f"{named}with the inputs locked the output can still move (moving joints: {j}): the mechanism loses "
            "stiffness and actuator forces can grow without bound"
        )
    if cls == "passive-motion":
        return f"passive joints {j} can move while the inputs and the output stay still"
    if cls == "impossible-input":
        return f"the inputs can take only {f.rank} independent rates here instead of {f.generic}"
    return f"the output can make only {f.rank} independent motions here instead of {f.generic}"


def _more_precise(precision: str) -> str:
    """What to try after an undecided test, from the precision that left it open."""
    if precision.startswith("mp:"):
        digits = int(precision[3:])
        return (
            f"try --precision mp:{2 * digits}, or exact with exact data (the configuration may "
            f"be within 10^-{digits // 2} of a singularity)"
        )
    if precision == "exact":
        return "the test ran at mp:50 from the exact data: try a larger --precision mp:N"
    return "try --precision mp:50 or exact"
