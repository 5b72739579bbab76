"""Singularity classification of a configuration, and mechanism-level properties.

Every test is measured against its value at generic configurations: what holds everywhere becomes a
``properties`` entry, never a singularity.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing import lie
from mechsing.kinematics.chains import tree_chain
from mechsing.numeric import to_float
from mechsing.singularity.serial import GENERIC_SAMPLES, chain_system, serial_finding
from mechsing.timelimit import activity

__all__ = [
    "GENERIC_SAMPLES",
    "classify_configuration",
    "mechanism_properties",
    "output_chain",
    "random_configurations",
]


def output_chain(mech: Any, model: Any) -> tuple[list[str], list[int]] | None:
    """Joints and coordinate columns of the tree path from ``relative_to`` to the output body."""
    out = mech.output
    if out is None:
        return None
    chain = tree_chain(model, out.body, out.relative_to)
    return chain.joints, chain.columns


def _output_point(
    mech: Any, model: Any, q: np.ndarray, poses: dict[str, np.ndarray]
) -> np.ndarray | None:
    out = mech.output
    if out is None or out.point is None:
        return None
    g = poses[out.body]
    x0 = (
        model.asarray(list(out.point))
        if model.backend.name != "float"
        else to_float(np.array(list(out.point), dtype=object))
    )
    return lie.act_point(g, x0)


def random_configurations(model: Any, count: int, seed: int = 0) -> np.ndarray:
    """``count`` random configurations (rows): angles uniform in [-pi, pi), lengths in [-L, L)."""
    q = np.random.default_rng(seed).uniform(-np.pi, np.pi, size=(count, model.n))
    return np.where(model.length_columns[None, :], q * model.length_scale / np.pi, q)


def _tree_serial(mech: Any, model: Any, result: Any) -> list[dict[str, Any]]:
    chain = output_chain(mech, model)
    if chain is None:
        return []
    names, cols = chain
    q = result.internals["q"]
    from mechsing.singularity.classify import float_model

    fm = float_model(mech, model)
    # decided at the analysis precision (so auto can re-decide it at mp:50) ...
    with activity("deciding the rank of the output chain's screw system"):
        poses = model.poses(q)
        x = _output_point(mech, model, q, poses)
        here = chain_system(model, model.current_screws(q, poses), cols, x, model.precision)
    xf = None if x is None else np.asarray(to_float(x), dtype=float)
    # ... against the generic rank found at random configurations (float)
    generic = here.rank.rank or 0
    for qr in random_configurations(fm, GENERIC_SAMPLES):
        pr = fm.poses(qr)
        sysr = chain_system(
            fm, fm.current_screws(qr, pr), cols, _output_point(mech, fm, qr, pr), "float"
        )
        if sysr.rank.rank is not None:
            generic = max(generic, sysr.rank.rank)
    result.decisions.append(here.rank.record("output chain", generic))
    label = {"chain": "output", "body": mech.output.body, "relative_to": mech.output.relative_to}
    f = serial_finding(model, here, generic, names, label, xf)
    if f is None and here.rank.rank is None:
        return [_undecided("output screw system", here.rank)]
    return [f] if f else []


def _undecided(what: str, dec: Any) -> dict[str, Any]:
    return {
        "class": "undecided",
        "what": what,
        "rank_bounds": list(dec.rank_bounds),
        "margin": dec.margin.to_json(),
        "precision": dec.precision,
    }


#: tests whose singularity is a dimension above its generic value (the others: a rank below)
_RISING = ("input", "output", "passive-motion")


def _verdict_open(d: dict[str, Any]) -> bool:
    """Does an undecided rank leave the verdict open?  Not when every rank its bounds
    allow gives the same verdict: a rank test is singular below its generic value (a
    constraint rank undecided between 5 and 6 with generic 5 is regular either way), a
    motion test above it."""
    bounds, generic = d.get("rank_bounds"), d.get("generic")
    if bounds is None or generic is None:
        return True
    lo, hi = bounds
    if d["test"] in _RISING:
        return lo <= generic < hi
    return lo < generic <= hi


def classify_configuration(mech: Any, model: Any, result: Any) -> list[dict[str, Any]]:
    """Findings at one closed configuration (the JSON contract's classes); also sets
    ``result.mobility["generic"]`` and ``["finite"]`` for mechanisms with loops."""
    from mechsing.singularity.classify import local_analysis

    findings: list[dict[str, Any]] = []
    cs = result.internals["closure"]
    if not mech.loops:
        findings.extend(_tree_serial(mech, model, result))
        return findings
    if cs.rank.rank is None:
        findings.append(_undecided("stacked closure system", cs.rank))
        result.mobility["generic"] = result.mobility["finite"] = None
        return findings
    for ls in cs.loops:
        if ls.rank.rank is None:
            findings.append(_undecided(f"loop {'-'.join(ls.loop.joints)}", ls.rank))
    with activity("running the mobility, input/output and tangent-cone tests"):
        local = local_analysis(mech, model, result.internals["q"], cs)
    result.mobility["generic"] = local.generic
    result.mobility["finite"] = local.finite
    result.internals["local"] = local
    result.decisions.extend(local.decisions)
    findings.extend(local.findings)
    # an input/output, constraint or leg rank the precision could not decide is a
    # verdict left open: say so, and let auto re-decide the configuration at mp:50
    for d in local.decisions:
        if d["rank"] is None and _verdict_open(d):
            f = {
                "class": "undecided",
                "what": f"{d['test']} test",
                # null when the test rests on another test's undecided rank (see note)
                "rank_bounds": d.get("rank_bounds"),
                "margin": d["margin"],
                "precision": d["precision"],
            }
            if "note" in d:
                f["note"] = d["note"]
            findings.append(f)
    if local.cone is not None and local.cone.undecided:
        result.internals["undecided"] = True  # a second-order form between the thresholds
    return findings


def mechanism_properties(mech: Any, model: Any, results: list[Any]) -> list[dict[str, Any]]:
    """Mechanism-level properties (``properties`` of the JSON contract), from the configurations analysed.

    What holds at every regular configuration of a branch is a property, never
    a singularity: ``overconstrained`` (finite above group), ``shaky``
    (instantaneous above finite at regular points), ``idle-motion`` (a passive
    motion with inputs and output still, present generically),
    ``redundant-actuation`` and ``underactuated`` (inputs against finite).
    """
    props: list[dict[str, Any]] = []
    ok = [r for r in results if r.error is None and r.mobility.get("finite") is not None]
    regular = [r for r in ok if not r.singularities] or ok
    if not regular:
        return props
    r = regular[0]
    mob = r.mobility
    if mech.loops and mob.get("group") is not None and mob["finite"] > mob["group"]:
        props.append(
            {
                "kind": "overconstrained",
                "finite": mob["finite"],
                "group": mob["group"],
                "grubler": mob["grubler"],
                "configuration": r.name,
                "explanation": (
                    f"the mechanism moves with {mob['finite']} degree(s) of freedom although its loops' "
                    f"subgroups allow {mob['group']} (Grubler-Kutzbach gives {mob['grubler']}): its mobility "
                    "comes from special geometry (an intersection of subgroups or metric conditions)"
                ),
            }
        )
    shaky = [
        x
        for x in regular
        if x.mobility.get("generic") is not None
        and x.mobility["finite"] is not None
        and x.mobility["generic"] > x.mobility["finite"]
    ]
    if shaky:
        x = shaky[0]
        props.append(
            {
                "kind": "shaky",
                "instantaneous": x.mobility["generic"],
                "finite": x.mobility["finite"],
                "configurations": [y.name for y in shaky],
                "explanation": (
                    f"at regular configurations the joints have {x.mobility['generic']} instantaneous "
                    f"motion(s) but only {x.mobility['finite']} extend to finite motion (second-order test)"
                ),
            }
        )
    idle = 0
    for x in regular:
        local = x.internals.get("local")
        dim = local.io_generic.get("passive-motion") if local is not None else None
        if dim:
            idle = dim
            props.append(
                {
                    "kind": "idle-motion",
                    "dimension": dim,
                    "configuration": x.name,
                    "explanation": (
                        f"{dim} passive motion(s) exist with the inputs locked and the output still, at every "
                        "regular configuration (e.g. a link spinning about its own axis)"
                    ),
                }
            )
            break
    n_in = len(mech.input_coordinates())
    if n_in and mob["finite"] is not None:
        # idle motions move nothing that matters: they need no actuator
        useful = mob["finite"] - idle
        if n_in > useful:
            props.append(
                {
                    "kind": "redundant-actuation",
                    "inputs": n_in,
                    "finite": mob["finite"],
                    "idle": idle,
                    "configuration": r.name,
                    "explanation": f"{n_in} actuated coordinates drive {useful} degree(s) of freedom",
                }
            )
        elif n_in < useful:
            props.append(
                {
                    "kind": "underactuated",
                    "inputs": n_in,
                    "finite": mob["finite"],
                    "idle": idle,
                    "configuration": r.name,
                    "explanation": f"{n_in} actuated coordinates for {useful} degree(s) of freedom",
                }
            )
    return props
