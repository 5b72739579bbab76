"""The JSON of the values the lower layers hand up: margins, rank decisions, findings,
subgroups, identifications, intersections, products and catalog types.

Owns :func:`to_json` for those values (plain dicts and lists, keys in the contract's order),
:func:`subgroup_json` (a subgroup, or none identified) and :func:`subgroup_params`, the
canonical float parameters of a subgroup that the JSON and the renderers show.  The lower layers build no JSON: their types carry the fields, this
module reads them.  :func:`mechsing.analysis.results.to_json`, the one entry of the JSON
contract, serializes the analysis results and hands every other value to :func:`to_json`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.numeric import Margin, to_float
from mechsing.singularity.findings import (
    BranchFinding,
    ConstraintFinding,
    Decision,
    MotionFinding,
    SerialFinding,
    UndecidedFinding,
)
from mechsing.subgroups import Identification, Intersection, Product, Subgroup, SubgroupType

__all__ = ["finding_class", "finding_margin", "subgroup_json", "subgroup_params", "to_json"]


def to_json(x: Any) -> Any:
    """The JSON of a margin, a rank decision, a finding, a subgroup, an identification, an
    intersection, a product or a catalog type (keys in the contract's order)."""
    if isinstance(x, Margin):
        return _margin(x)
    if isinstance(x, Decision):
        return _decision(x)
    if isinstance(x, SerialFinding | BranchFinding | MotionFinding | ConstraintFinding):
        return _finding(x)
    if isinstance(x, UndecidedFinding):
        return _undecided(x)
    if isinstance(x, Subgroup):
        return subgroup_json(x)
    if isinstance(x, Identification):
        return _identification(x)
    if isinstance(x, Intersection):
        return _intersection(x)
    if isinstance(x, Product):
        return _product(x)
    if isinstance(x, SubgroupType):
        return _subgroup_type(x)
    raise TypeError(f"no JSON form for {type(x).__name__}")


def _lists(x: Any) -> Any:
    """Tuples (the types' immutable sequences) as JSON lists."""
    if isinstance(x, tuple):
        return [_lists(v) for v in x]
    return x


# --------------------------------------------------------------------------- decisions


def _margin(m: Margin | None) -> dict[str, Any] | None:
    """How far a decision was from flipping: kept, dropped, thresholds and length scale,
    then sigma_max, rounding and eig_margin where known."""
    if m is None:
        return None
    d: dict[str, Any] = {
        "kept": m.kept,
        "dropped": m.dropped,
        "tau_lo": m.tau_lo,
        "tau_hi": m.tau_hi,
        "length_scale": m.length_scale,
    }
    if m.sigma_max is not None:
        d["sigma_max"] = m.sigma_max
    if m.rounding is not None:
        d["rounding"] = m.rounding
    if m.eig_margin is not None:
        d["eig_margin"] = m.eig_margin
    return d


def _decision(d: Decision) -> dict[str, Any]:
    out: dict[str, Any] = {"test": d.test, "rank": d.rank}
    if d.rank_bounds is not None:
        out["rank_bounds"] = list(d.rank_bounds)
    if d.generic is not None:
        out["generic"] = d.generic
    out["margin"] = _margin(d.margin)
    out["precision"] = d.precision
    if d.note is not None:
        out["note"] = d.note
    return out


# --------------------------------------------------------------------------- findings


def _decided(f: Any, out: dict[str, Any]) -> dict[str, Any]:
    """The closing keys of a decided finding: margin, precision, test precision."""
    out["margin"] = _margin(f.margin)
    out["precision"] = f.precision
    if getattr(f, "test_precision", None) is not None:
        out["test_precision"] = f.test_precision
    return out


def _finding(
    f: SerialFinding | BranchFinding | MotionFinding | ConstraintFinding,
) -> dict[str, Any]:
    out: dict[str, Any] = {"class": f.cls}
    if isinstance(f, SerialFinding):
        out["chain"] = f.chain
        if f.chain == "leg":
            out["leg"] = f.leg
        else:
            out["body"] = f.body
            out["relative_to"] = f.relative_to
        out.update(
            {
                "joints": list(f.joints),
                "corank": f.corank,
                "rank": f.rank,
                "generic_rank": f.generic_rank,
                "wrenches": _lists(f.wrenches),
                "twist": list(f.twist),
                "null_joint_rates": list(f.null_joint_rates),
            }
        )
        out = _decided(f, out)
        out["name"] = f.name  # added after the contract's first keys
        # the whole kernel in its canonical basis (null_joint_rates is its first row)
        out["null_joint_rate_basis"] = _lists(f.null_joint_rate_basis)
        return out
    out["joints"] = list(f.joints)
    if isinstance(f, BranchFinding):
        out["order"] = f.order
        if f.cls == "bifurcation":
            keys = (
                "branches",
                "branch_tangents",
                "branch_mobility",
                "branch_dimensions",
                "instantaneous",
                "kinematotropic",
            )
        elif f.cls == "increased-mobility":
            keys = ("instantaneous", "generic", "branch_tangents")
        else:  # isolated, degenerate
            keys = ("instantaneous", "branch_tangents", "note")
        for k in keys:
            v = getattr(f, k)
            if v is not None:
                out[k] = _lists(v)
        return _decided(f, out)
    if isinstance(f, MotionFinding):
        if f.rank is not None:  # impossible-input, impossible-output
            out["rank"] = f.rank
            out["generic"] = f.generic
        else:
            out["dimension"] = f.dimension
            out["generic"] = f.generic
            out["joint_rates"] = _lists(f.joint_rates)
            if f.output_twist is not None:
                out["output_twist"] = list(f.output_twist)
        out = _decided(f, out)
        if f.name is not None:  # added after the contract's first keys
            out["name"] = f.name
        if f.joint_rate_basis is not None:  # the whole motion space, canonical basis
            out["joint_rate_basis"] = _lists(f.joint_rate_basis)
        return out
    out.update(
        {
            "rank": f.rank,
            "generic_rank": f.generic_rank,
            "corank": f.corank,
            "wrenches": _lists(f.wrenches),
        }
    )
    return _decided(f, out)


def finding_class(f: Any) -> str:
    """A finding's JSON ``class`` (``to_json(f)["class"]``) without building the rest of
    its JSON: a sweep reads the classes of every located point."""
    if isinstance(f, UndecidedFinding):
        return "undecided"
    if isinstance(f, SerialFinding | BranchFinding | MotionFinding | ConstraintFinding):
        return f.cls
    raise TypeError(f"not a finding: {f!r}")


def finding_margin(f: Any) -> dict[str, Any] | None:
    """A finding's JSON ``margin`` (``to_json(f)["margin"]``) alone."""
    if not isinstance(
        f, UndecidedFinding | SerialFinding | BranchFinding | MotionFinding | ConstraintFinding
    ):
        raise TypeError(f"not a finding: {f!r}")
    return _margin(f.margin)


def _undecided(f: UndecidedFinding) -> dict[str, Any]:
    out: dict[str, Any] = {
        "class": "undecided",
        "what": f.what,
        "rank_bounds": None if f.rank_bounds is None else list(f.rank_bounds),
    }
    if f.subject == "configuration":
        # no rank in question: why the configuration itself is too coarse comes first
        out["note"] = f.note
    out["margin"] = _margin(f.margin)
    out["precision"] = f.precision
    if f.subject != "configuration" and f.note is not None:
        out["note"] = f.note
    return out


# --------------------------------------------------------------------------- subgroups


def subgroup_params(sub: Subgroup) -> dict[str, float | list[float]]:
    """The canonical parameters of ``sub`` as floats (SI): a list per vector, a float per
    scalar (``+ 0.0`` turns a negative zero into zero)."""
    params: dict[str, float | list[float]] = {}
    for k, v in sub.canonical().params.items():
        f = to_float(v)
        params[k] = [float(x) + 0.0 for x in f] if np.ndim(f) else float(f) + 0.0
    return params


def subgroup_json(sub: Subgroup | None) -> dict[str, Any]:
    """``{"type", "dim", "params"}`` of a subgroup (canonical parameters), of None (a loop's
    subgroup or an identification's when no type was identified) with type and dim None."""
    if sub is None:
        return {"type": None, "dim": None, "params": {}}
    return {"type": sub.symbol, "dim": sub.dim, "params": subgroup_params(sub)}


def _identification(r: Identification) -> dict[str, Any]:
    out = subgroup_json(r.subgroup)
    out.update(
        {
            "bracket_norms": [float(x) for x in r.bracket_norms],
            "margin": _margin(r.margin),
            "status": r.status,
            "precision": r.precision,
        }
    )
    if r.message:
        out["message"] = r.message
    if r.dim_bounds is not None:
        out["dim_bounds"] = list(r.dim_bounds)
    return out


def _intersection(r: Intersection) -> dict[str, Any]:
    out = _identification(r.identification)
    out["extra_components"] = r.extra_components
    out["note"] = r.note
    return out


def _product(r: Product) -> dict[str, Any]:
    return {
        "is_subgroup": r.is_subgroup,
        "subgroup": subgroup_json(r.subgroup) if r.subgroup is not None else None,
        "generated": _identification(r.generated),
        "set_dimension": r.set_dimension,
        "note": r.note,
    }


def _subgroup_type(t: SubgroupType) -> dict[str, Any]:
    """A catalog type as ``mechsing catalog --format json`` lists it."""
    return {
        "symbol": t.symbol,
        "name": t.name,
        "dimension": t.dimension,
        "parameters": [{"name": n, "kind": k} for n, k in t.parameters],
        "basis": [{"omega": w, "v": v} for w, v in t.basis_text],
        "coordinates": [{"name": n, "unit": u} for n, u in t.coordinates],
        "normal_in_D": t.normal_in_D,
        "invariants": list(t.invariants),
        "joints": list(t.joints),
        "explanation": t.explanation.strip(),
    }
