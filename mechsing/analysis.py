"""The analysis of a mechanism at its configurations (the API behind ``mechsing analyze``).

>>> import mechsing
>>> result = mechsing.analyze("examples/fourbar.yaml")     # doctest: +SKIP
>>> result.to_json()["configurations"][1]["mobility"]       # doctest: +SKIP
{'grubler': -2, 'group': 1, 'instantaneous': 1, 'generic': 1, 'finite': 1}

Precision: ``auto`` decides in float and re-does a configuration at mp:50
when a rank is undecided there; ``float``, ``mp:N`` and ``exact`` use one mode.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mechsing.errors import working_on
from mechsing.kinematics import Closer, ClosureError, KinematicModel
from mechsing.model import Mechanism, load
from mechsing.numeric import Precision, parse_precision
from mechsing.screws import closure_system, group_mobility, grubler
from mechsing.singularity import classify_configuration, mechanism_properties

__all__ = ["AnalysisResult", "ConfigurationResult", "analyze"]


@dataclass
class ConfigurationResult:
    """Everything mechsing says about one configuration (see :meth:`to_json`)."""

    name: str
    precision: str
    joints: dict[str, list[float]] = field(default_factory=dict)
    closure_residual: float | None = None
    closure_rank: dict[str, Any] | None = None
    loops: list[dict[str, Any]] = field(default_factory=list)
    mobility: dict[str, Any] = field(default_factory=dict)
    singularities: list[dict[str, Any]] = field(default_factory=list)
    #: every rank decision made at the configuration, singular or not
    #: (:meth:`mechsing.numeric.RankDecision.record`)
    decisions: list[dict[str, Any]] = field(default_factory=list)
    underdetermined: bool = False
    error: str | None = None
    #: wall-clock seconds the configuration took (escalation included); not in the JSON
    seconds: float = field(default=0.0, compare=False)
    #: what the analysis did to the given values that a reader should know (JSON ``notes``)
    notes: list[str] = field(default_factory=list)
    internals: dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def singular(self) -> bool | None:
        if not self.singularities:
            return False
        if all(s["class"] == "undecided" for s in self.singularities):
            return None
        return True

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {"name": self.name, "precision": self.precision}
        if self.error is not None:
            out["error"] = self.error
            out["singular"] = None
            out["singularities"] = []
            return out
        out.update(
            {
                "joints": self.joints,
                "closure_residual": self.closure_residual,
                "closure_rank": self.closure_rank,
                "loops": self.loops,
                "mobility": self.mobility,
                "singular": self.singular,
                "singularities": self.singularities,
                "decisions": self.decisions,
            }
        )
        if self.underdetermined:
            out["underdetermined"] = True
        if self.notes:
            out["notes"] = list(self.notes)
        return out


@dataclass
class AnalysisResult:
    """The analysis of a mechanism; :meth:`to_json` is the JSON contract of DESIGN.md."""

    mechanism: Mechanism
    precision: Precision
    length_scale: float
    configurations: list[ConfigurationResult]
    properties: list[dict[str, Any]] = field(default_factory=list)

    @property
    def failed(self) -> bool:
        return any(c.error is not None for c in self.configurations)

    def to_json(self) -> dict[str, Any]:
        t = self.precision.tolerances
        return {
            "mechanism": self.mechanism.name,
            "precision": {
                "mode": str(self.precision),
                "tau_lo": t.tau_lo,
                "tau_hi": t.tau_hi,
                "length_scale": self.length_scale,
            },
            "properties": self.properties,
            "configurations": [c.to_json() for c in self.configurations],
        }


def analyze(
    mechanism: Mechanism | str | Path,
    configs: list[str] | None = None,
    precision: Precision | str = "auto",
) -> AnalysisResult:
    """Analyse a mechanism (or a file) at the named configurations (default: all)."""
    mech = mechanism if isinstance(mechanism, Mechanism) else load(str(mechanism))
    with working_on(file=mech.path or mech.name):
        return _analyze(mech, configs, precision)


def _analyze(
    mech: Mechanism, configs: list[str] | None, precision: Precision | str
) -> AnalysisResult:
    if isinstance(precision, str):
        prec = parse_precision(precision)
    elif isinstance(precision, Precision):
        prec = precision
    else:
        raise TypeError(
            f"precision must be 'auto', 'float', 'mp:N', 'exact' or a Precision, not {precision!r}"
        )
    if configs:
        names = list(configs)
    else:
        # the file's configurations, in file order; the implicit reference (every
        # joint at identity) only when the file lists none
        names = [
            n for n, c in mech.configurations.items() if not (n == "reference" and c.line is None)
        ]
        names = names or ["reference"]
    for n in names:
        if n not in mech.configurations:
            from mechsing.cli import UserError

            known = ", ".join(mech.configurations)
            raise UserError(
                f"{mech.path or mech.name}: no configuration named {n!r}; the file has: {known}"
            )
    models: dict[str, tuple[KinematicModel, Closer]] = {}

    def stage(mode: Precision) -> tuple[KinematicModel, Closer]:
        key = str(mode)
        if key not in models:
            km = KinematicModel(mech, mode)
            # given values are checked with the tolerance of the mode asked for (auto: float's)
            models[key] = (km, Closer(km, data_precision=first))
        return models[key]

    first = Precision("float") if prec.mode == "auto" else prec
    results = []
    for name in names:
        start = time.perf_counter()
        res = _analyze_one(mech, name, stage(first))
        if prec.mode == "auto" and res.error is None and res.internals.get("undecided"):
            res = _analyze_one(mech, name, stage(Precision("mp", 50)))
            res.internals["escalated"] = True
        res.seconds = time.perf_counter() - start
        results.append(res)
    km0 = stage(first)[0]
    props = mechanism_properties(mech, km0, results)
    return AnalysisResult(mech, prec, km0.length_scale, results, props)


def _analyze_one(
    mech: Mechanism, name: str, stage: tuple[KinematicModel, Closer]
) -> ConfigurationResult:
    # every mp:N computation must run at N digits: mpmath's precision is a context
    prec = stage[0].precision
    with working_on(configuration=name, precision=str(prec)), prec.context():
        return _analyze_one_in_context(mech, name, stage)


def _analyze_one_in_context(
    mech: Mechanism, name: str, stage: tuple[KinematicModel, Closer]
) -> ConfigurationResult:
    model, closer = stage
    prec = model.precision
    out = ConfigurationResult(name, str(prec))
    try:
        closed = closer.solve(name)
    except ClosureError as exc:
        out.error = str(exc)
        return out
    q = closed.q
    out.joints = model.values(q)
    out.closure_residual = float(closed.residual)
    out.underdetermined = closed.underdetermined
    out.notes.extend(closed.notes)
    cs = closure_system(model, q, prec)
    rank = cs.rank
    out.closure_rank = {
        "rank": rank.rank,
        "nullity": cs.nullity,
        "margin": rank.margin.to_json(),
    }
    undecided = rank.rank is None
    if mech.loops:
        out.decisions.append(rank.record("closure"))
    for ls in cs.loops:
        ident = ls.identification
        sub = ident.subgroup.to_json() if ident.ok else {"type": None, "dim": None, "params": {}}
        entry: dict[str, Any] = {
            "joints": list(ls.loop.joints),
            "subgroup": sub,
            "rank": ls.rank.rank,
            "sigma": list(ls.rank.sigma) if ls.rank.sigma is not None else None,
            "margin": ls.rank.margin.to_json(),
        }
        if not ident.ok:
            entry["subgroup_status"] = ident.status
            undecided = True
        if ls.rank.rank is None:
            undecided = True
        out.loops.append(entry)
        out.decisions.append(ls.rank.record(f"loop {'-'.join(ls.loop.joints)}"))
    inst = cs.nullity
    out.mobility = {
        "grubler": grubler(model),
        "group": group_mobility(model, cs.loops),
        "instantaneous": inst,
        "generic": inst,
        "finite": inst,
    }
    out.internals.update(
        {"model": model, "q": q, "closure": cs, "undecided": undecided, "closed": closed}
    )
    out.singularities = classify_configuration(mech, model, out)
    if any(f["class"] == "undecided" for f in out.singularities):
        out.internals["undecided"] = True  # auto re-decides the configuration at mp:50
    return out
