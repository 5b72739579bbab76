"""Deriving singularity conditions as factored formulas (``mechsing condition``).

Owns the entry point :func:`condition`: reading the mechanism with the named
parameters kept as symbols, choosing the derivation, the time limit, writing the
parameters by their names, and evaluating each factor at a configuration.  The
derivations, on mechanisms of R, P and H joints
(:mod:`mechsing.conditions.symbolic`), live in their own modules:

* an open chain: :mod:`mechsing.conditions.serial`;
* a single loop with one input: :mod:`mechsing.conditions.loop`;
* a multi-loop planar linkage with one input: :mod:`mechsing.conditions.linkage`;
* a planar parallel robot of three legs of three R or P joints, one actuated in each
  (3-RPR, 3-RRR, 3-PRR ...): :mod:`mechsing.conditions.rpr`;
* a Gough-Stewart platform: :mod:`mechsing.conditions.spatial`; a translational
  3-UPU: :mod:`mechsing.conditions.translational` (both in the pose variables).

Joint values are measured from the pose drawn in the file (all zero there);
angles in radians, lengths in metres.  Parameters named in ``symbolic`` stay
symbols, the others take their exact values.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import time
from collections.abc import Callable, Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import sympy

from mechsing.conditions.jacobians import MAX_MINORS, parameter_symbols
from mechsing.conditions.linkage import linkage_conditions
from mechsing.conditions.loop import single_loop
from mechsing.conditions.results import Condition, ConditionResult, Factor
from mechsing.conditions.rpr import planar_parallel
from mechsing.conditions.serial import open_chain
from mechsing.conditions.spatial import gough_stewart
from mechsing.conditions.split import gimbal_factor, split_joints, split_values
from mechsing.conditions.symbolic import joint_symbols
from mechsing.conditions.translational import translational_3upu
from mechsing.errors import ConfigurationError, TimeLimitExceeded, UserError
from mechsing.model import Mechanism
from mechsing.model.couplings import refuse_couplings
from mechsing.model.parameters import ParameterSymbol
from mechsing.numeric import CONDITION_VANISH_RTOL
from mechsing.reader import read_mechanism
from mechsing.timelimit import SHORTEST_TIME_LIMIT, TimeLimit

__all__ = ["ELIMINATION_SECONDS", "MAX_MINORS", "condition"]

#: time allowed to eliminate the passive joints of a loop (s)
ELIMINATION_SECONDS = 60.0


def condition(
    source: str | Path | Mechanism,
    config: str | None = None,
    symbolic: str | list[str] | tuple[str, ...] = (),
    scene: Callable[[Mechanism], Mechanism] | None = None,
    time_limit: float | None = None,
) -> ConditionResult:
    """The singularity conditions of a mechanism file as factored formulas.

    Parameters
    ----------
    source : str, Path or Mechanism
        The mechanism file (any format :func:`mechsing.load` reads), or a mechanism read
        with ``symbolic`` kept as symbols.
    config : str, optional
        A configuration of the file: each factor is evaluated there.
    symbolic : str or sequence of str
        Parameters of the file to keep as symbols (a list, or ``"a2,a3"``).
    scene : callable, optional
        Applied to the mechanism as read from a file (e.g. the command line's output and
        inputs, :func:`mechsing.model.scene.choose_scene`), before anything is derived
        (a mechanism given as ``source`` is taken as it is).
    time_limit : float or None
        The most seconds the derivation may take (None: no limit); stopped there, a
        ConfigurationError (exit status 3) that says so.  The elimination of a linkage's
        passive joints gets half of it for each condition (without a limit,
        :data:`ELIMINATION_SECONDS`): past that the condition is given in the joint
        variables, with a note.

    Returns
    -------
    ConditionResult
        The conditions, each a product of factors with their meaning.

    Raises
    ------
    UserError
        For a file that cannot be read, a parameter or configuration that does
        not exist, joints other than R, P and H, or a mechanism none of the
        three derivations applies to (the message says which exist).
    """
    names = [s.strip() for s in symbolic.split(",")] if isinstance(symbolic, str) else symbolic
    names = [s for s in names if s]
    mech = _symbolic_mechanism(source, names)
    if scene is not None and not isinstance(source, Mechanism):
        mech = scene(mech)
    refuse_couplings(mech, "symbolic conditions (mechsing condition)")
    try:
        with TimeLimit(time_limit):
            # the elimination gets half the limit: past it, the joint-variable form within it
            elim = (
                ELIMINATION_SECONDS
                if time_limit is None
                else max(time_limit / 2, SHORTEST_TIME_LIMIT)
            )
            return _condition(mech, config, names, scene, elim)
    except TimeLimitExceeded:
        raise ConfigurationError(
            f"{mech.path or mech.name}: the conditions were stopped by the time limit after "
            f"{time_limit:g} s; allow more time with --time-limit S",
            config or "reference",
        ) from None


def _condition(
    mech: Mechanism,
    config: str | None,
    names: list[str],
    scene: Callable[[Mechanism], Mechanism] | None,
    time_limit: float | None,
) -> ConditionResult:
    """The conditions of ``mech``; ``time_limit``: the seconds the elimination of a
    linkage's passive joints may take for each condition."""
    source = mech.path or mech.name
    if config is not None and config not in mech.configurations:
        raise UserError(
            f"{source}: no configuration named {config!r}; the file has: "
            f"{', '.join(mech.configurations)}"
        )
    if mech.output is None:
        raise UserError(
            f"{source}: the file has no output; a condition is about the output's motion: "
            "name one with --output-body BODY (in a mechsing file, add output: {body: NAME})"
        )
    platform = gough_stewart(mech) or translational_3upu(mech)
    if platform is not None:
        if config is not None:
            raise UserError(
                f"{source}: --config: the conditions of this platform are written in the "
                "position x, y, z of its reference point at the drawn orientation; evaluate "
                "them at a pose by putting x, y, z into them, or use 'mechsing analyze --config'"
            )
        return ConditionResult(
            mechanism=mech.name,
            method="parallel robot, pose variables",
            symbolic=tuple(names),
            parameters={k: v for k, v in mech.parameters.items() if k not in names},
            conditions=tuple(platform[0]),
            notes=tuple(platform[1]),
            file_angle_unit=mech.units.angle,
        )
    original = mech
    mech, split_notes = split_joints(mech)
    params = parameter_symbols(mech)
    method, conds, notes = _derived(mech, str(source), time_limit)
    printable = {p: sympy.Symbol(p.name, real=True) for p in params}
    conds = [_printable(c, printable) for c in conds]
    if split_notes:
        conds, dropped = _without_gimbal(original, conds)
        notes = [*split_notes, *dropped, *notes]
    values: dict[str, float] = {}
    if config is not None:
        numeric = original
        if names and mech.path:  # the same file with its parameters' values
            numeric = read_mechanism(mech.path)
            if scene is not None:
                numeric = scene(numeric)
            # a configuration added to the mechanism read (mechsing condition --set)
            added = {
                k: v for k, v in mech.configurations.items() if k not in numeric.configurations
            }
            if added:
                numeric = replace(numeric, configurations={**numeric.configurations, **added})
        values = _configuration_values(numeric, config, method, bool(split_notes))
        if method.startswith("parallel"):  # the pose, and the joints the conditions hold
            used = {"x", "y", "phi"} | {v for c in conds for v in c.variables}
            values = {k: v for k, v in values.items() if k in used}
        conds = [_evaluate(c, values, params) for c in conds]
    fixed = {k: v for k, v in mech.parameters.items() if k not in names}
    return ConditionResult(
        mechanism=mech.name,
        method=method,
        symbolic=tuple(names),
        parameters=fixed,
        conditions=tuple(conds),
        notes=(*(mech.scene.notes if mech.scene else ()), *notes),
        configuration=config,
        values=values,
        file_angle_unit=mech.units.angle,
    )


#: the derivations of this process by the content of what they derive from
#: (:func:`_derived`): a test, a notebook or a sweep that derives one mechanism again
#: pays once
_DERIVED: dict[str, tuple[str, tuple[Condition, ...], tuple[str, ...]]] = {}


def _derived(
    mech: Mechanism, source: str, time_limit: float | None
) -> tuple[str, list[Condition], list[str]]:
    """The method, conditions and notes of ``mech`` (its U, C and S joints split),
    remembered by its content (:func:`_content_key`) and the elimination's time limit.
    A derivation that ran as long as that limit may have been stopped by it (its result
    depends on the machine's speed): it is not remembered."""
    key = _content_key((mech, source, time_limit))
    if key is not None and key in _DERIVED:
        method, conds, notes = _DERIVED[key]
        return method, list(conds), list(notes)
    start = time.monotonic()
    method, conds, notes = _derive(mech, source, time_limit)
    if key is not None and (time_limit is None or time.monotonic() - start < time_limit):
        _DERIVED[key] = (method, tuple(conds), tuple(notes))
    return method, list(conds), list(notes)


def _derive(
    mech: Mechanism, source: str, time_limit: float | None
) -> tuple[str, list[Condition], list[str]]:
    S = joint_symbols(mech)
    if mech.graph.num_loops == 0:
        method, conds, notes = "open chain", *open_chain(mech, S)
    elif mech.graph.num_loops == 1 and len(mech.input_coordinates()) == 1:
        method, conds, notes = "single loop, one input", *single_loop(mech, S, time_limit)
    elif len(mech.input_coordinates()) == 1:
        ((in_joint, _),) = mech.input_coordinates()
        found = linkage_conditions(
            mech, S[in_joint], set(parameter_symbols(mech)), time_limit, True
        )
        if isinstance(found, str):
            raise UserError(
                f"{source}: a linkage of {mech.graph.num_loops} loops with one input: symbolic "
                "conditions of multi-loop linkages cover planar linkages of R and P joints "
                "with the input on the ground (Watt and Stephenson six-bars ...); this one is "
                f"not: {found}; use 'mechsing analyze' for its singularities"
            )
        method, conds, notes = "linkage, one input", *found
    else:
        method, conds, notes = (
            "parallel robot, pose variables",
            *planar_parallel(mech, S, str(source)),
        )
    return method, conds, notes


def _content_key(value: Any) -> str | None:
    """A hash of the content of ``value`` (a mechanism, its joints, sympy values: their
    ``srepr``, which names each symbol with its assumptions and each float with its
    precision), never of an object's identity; None when it holds a value of a kind
    this does not know (nothing is remembered then).  A mechanism's graph (made from its
    bodies and joints) and its configurations (no derivation reads them) are left out."""
    parts: list[str] = []

    def walk(v: Any) -> None:
        if isinstance(v, sympy.Basic):
            parts.append("S" + sympy.srepr(v))
        elif v is None or isinstance(v, (str, int, float, bool, Path)):
            parts.append(f"{type(v).__name__}:{v!r}")
        elif dataclasses.is_dataclass(v) and not isinstance(v, type):
            parts.append(f"D{type(v).__qualname__}(")
            for f in dataclasses.fields(v):
                if isinstance(v, Mechanism) and f.name in ("graph", "configurations"):
                    continue
                parts.append(f.name + "=")
                walk(getattr(v, f.name))
            parts.append(")")
        elif isinstance(v, Mapping):
            parts.append("M{")
            for k in sorted(v, key=repr):
                walk(k)
                walk(v[k])
            parts.append("}")
        elif isinstance(v, (tuple, list)):
            parts.append(f"T{len(v)}(")
            for x in v:
                walk(x)
            parts.append(")")
        else:
            raise TypeError(type(v).__name__)

    try:
        walk(value)
    except TypeError:
        return None
    return hashlib.sha256("\x1f".join(parts).encode()).hexdigest()


def _without_gimbal(mech: Mechanism, conds: list[Condition]) -> tuple[list[Condition], list[str]]:
    """The conditions without the factors that are the three-revolute parametrisation's
    of an S joint (:func:`.split.gimbal_factor`), and a note for those left out."""
    out, dropped = [], []
    for c in conds:
        kept = tuple(f for f in c.factors if not gimbal_factor(mech, f.expression))
        dropped += [sympy.sstr(f.expression) for f in c.factors if f not in kept]
        out.append(replace(c, factors=kept) if len(kept) != len(c.factors) else c)
    notes = []
    if dropped:
        notes.append(
            f"left out: {', '.join(dict.fromkeys(dropped))}, which vanishes where the middle of "
            "the three revolutes an S joint is written as has turned a right angle (a "
            "singularity of those angles, not of the mechanism)"
        )
    return out, notes


def _symbolic_mechanism(source: str | Path | Mechanism, names: list[str]) -> Mechanism:
    """The mechanism with the parameters ``names`` kept as symbols: read from the file,
    or ``source`` itself when it was read so."""
    if not isinstance(source, Mechanism):
        return read_mechanism(source, symbolic=names, exact_tables=True)
    kept = {k for k, v in source.parameters.items() if isinstance(v, ParameterSymbol)}
    if kept == set(names):
        return source
    if source.path is None or not Path(source.path).is_file():
        raise UserError(
            f"{source.name}: the mechanism keeps {', '.join(sorted(kept)) or 'no parameter'} "
            f"as symbols, not {', '.join(names) or 'none'}; read it with "
            "mechsing.load(path, symbolic=...) or pass its path"
        )
    return read_mechanism(source.path, symbolic=names, exact_tables=True)


def _printable(c: Condition, printable: dict[Any, Any]) -> Condition:
    factors = tuple(
        Factor(f.expression.xreplace(printable), f.power, f.meaning, name=f.name) for f in c.factors
    )
    return Condition(
        c.name,
        c.form,
        c.variables,
        sympy.sympify(c.constant).xreplace(printable),
        factors,
        c.note,
        c.roots,
        c.units,
    )


def _configuration_values(
    numeric: Mechanism, config: str, method: str, split: bool = False
) -> dict[str, float]:
    """The joint (or pose) variables of a configuration of ``numeric`` (no symbols);
    ``split``: its U, C and S joints' as their one-dof factors' (:mod:`.split`)."""
    from mechsing.kinematics import solve_configuration

    model, closed = solve_configuration(numeric, config, "float")
    joint_values = {k: v for k, v in model.values(closed.q).items() if k in numeric.joint_names}
    if split:
        vals = split_values(numeric, joint_values)
    else:
        vals = {k: float(v[0]) for k, v in joint_values.items()}
    if method.startswith("parallel"):
        assert numeric.output is not None
        g = np.array(model.poses(closed.q)[numeric.output.body], dtype=float)
        c0 = np.array([float(sympy.N(v)) for v in numeric.output_reference_point()])
        pos = g[:3, :3] @ c0 + g[:3, 3]
        # the joints' too: the conditions of legs other than R-P-R also hold a variable
        # of each leg's first joint
        phi = math.atan2(g[1, 0], g[0, 0])
        return {**vals, "x": float(pos[0]), "y": float(pos[1]), "phi": phi}
    return vals


def _evaluate(c: Condition, values: dict[str, float], params: list[Any]) -> Condition:
    sub: dict[Any, Any] = {}
    for f in c.factors:
        for s in f.expression.free_symbols:
            if s.name in values:
                sub[s] = sympy.Float(values[s.name], 30)
    for p in params:
        sub[sympy.Symbol(p.name, real=True)] = p.parameter_value
    out = []
    for f in c.factors:
        e = f.expression.xreplace(sub)
        val = complex(sympy.N(e, 30))
        # the scale of the factor: its terms with every sine and cosine at its largest, 1
        terms = sympy.Add.make_args(sympy.expand(f.expression))
        bound = [
            t.replace(sympy.sin, lambda *_: sympy.Integer(1)).replace(
                sympy.cos, lambda *_: sympy.Integer(1)
            )
            for t in terms
        ]
        scale = sum(abs(complex(sympy.N(t.xreplace(sub), 30))) for t in bound) or 1.0
        vanishes = abs(val) <= CONDITION_VANISH_RTOL * scale if not e.free_symbols else None
        out.append(Factor(f.expression, f.power, f.meaning, float(val.real), vanishes, f.name))
    return Condition(c.name, c.form, c.variables, c.constant, tuple(out), c.note, c.roots, c.units)
