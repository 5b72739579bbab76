"""The typed, immutable results of an analysis, and the one serializer of the JSON contract.

Owns :class:`ConfigurationResult` and :class:`AnalysisResult` with their records (the closure
rank, a loop's entry, the mobility, the mechanism-level properties) and :func:`to_json`, the
one entry of the JSON contract: it serializes these types here and hands the values they hold
(findings, rank decisions, margins, subgroups) to :mod:`mechsing.analysis.contract`, which
builds the JSON of every lower layer's value (keys in the contract's order).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from mechsing.analysis import contract
from mechsing.analysis.describe import LegDescription, OutputMotion
from mechsing.analysis.html import VERDICT_HEADERS, html_table, verdict_row
from mechsing.analysis.resolution import DataResolution
from mechsing.kinematics.closed import ClosedValue
from mechsing.model import Mechanism
from mechsing.numeric import Margin, Precision
from mechsing.singularity.findings import (
    Classification,
    Decision,
    Finding,
    UndecidedFinding,
)
from mechsing.singularity.zfb import tests_not_run
from mechsing.subgroups import Subgroup

__all__ = [
    "AnalysisResult",
    "ClosureRank",
    "ConfigurationResult",
    "GivenPose",
    "IdleMotion",
    "LegDescription",
    "LoopEntry",
    "Mobility",
    "OutputMotion",
    "Overconstrained",
    "Property",
    "Shaky",
    "Actuation",
    "to_json",
]


@dataclass(frozen=True)
class Mobility:
    """The mobility fields of a configuration: the spatial Grubler-Kutzbach count, the
    group mobility of the loops' subgroups, the instantaneous mobility (closure nullity),
    and the generic and finite mobility the classification decided (None: undecided)."""

    grubler: int | None
    group: int | None
    instantaneous: int | None
    generic: int | None
    finite: int | None


@dataclass(frozen=True)
class ClosureRank:
    """The stacked closure system's rank, nullity and margin."""

    rank: int | None
    nullity: int | None
    margin: Margin


@dataclass(frozen=True)
class LoopEntry:
    """One loop at a configuration: its joints, the subgroup its screws generate
    (None when not identified: ``status`` says why), its rank and singular values."""

    joints: tuple[str, ...]
    subgroup: Subgroup | None
    rank: int | None
    sigma: tuple[float, ...] | None
    margin: Margin
    status: str | None = None


@dataclass(frozen=True)
class Overconstrained:
    """The mechanism moves with more freedom than its loops' subgroups allow."""

    finite: int
    group: int
    grubler: int | None
    configuration: str

    kind = "overconstrained"

    @property
    def explanation(self) -> str:
        """The property in words, with its numbers."""
        if self.finite == 0:
            # a structure: nothing moves, and the count below zero is redundant constraint
            return (
                f"the mechanism does not move (a structure), and its loops' subgroups count "
                f"{self.group} (Grubler-Kutzbach gives {self.grubler}): {-self.group} of its "
                "constraints are redundant (statically indeterminate)"
            )
        return (
            f"the mechanism moves with {self.finite} degree(s) of freedom although its loops' "
            f"subgroups allow {self.group} (Grubler-Kutzbach gives {self.grubler}): its mobility "
            "comes from special geometry (an intersection of subgroups or metric conditions)"
        )


@dataclass(frozen=True)
class Shaky:
    """Instantaneous motions at regular configurations that do not extend."""

    instantaneous: int
    finite: int
    configurations: tuple[str, ...]

    kind = "shaky"

    @property
    def explanation(self) -> str:
        """The property in words, with its numbers."""
        return (
            f"at regular configurations the joints have {self.instantaneous} instantaneous "
            f"motion(s) but only {self.finite} extend to finite motion (second-order test)"
        )


@dataclass(frozen=True)
class IdleMotion:
    """Passive motions with inputs and output still, present generically."""

    dimension: int
    configuration: str

    kind = "idle-motion"

    @property
    def explanation(self) -> str:
        """The property in words, with its numbers."""
        return (
            f"{self.dimension} passive motion(s) exist with the inputs locked and the output still, "
            "at every regular configuration (e.g. a link spinning about its own axis)"
        )


@dataclass(frozen=True)
class Actuation:
    """``redundant-actuation`` or ``underactuated``: inputs against the useful freedom."""

    kind: str
    inputs: int
    finite: int
    idle: int
    configuration: str

    @property
    def explanation(self) -> str:
        """The property in words, with its numbers."""
        useful = self.finite - self.idle
        if self.kind == "redundant-actuation":
            return f"{self.inputs} actuated coordinates drive {useful} degree(s) of freedom"
        return f"{self.inputs} actuated coordinates for {useful} degree(s) of freedom"


#: a mechanism-level property: one of the four frozen types above
Property = Overconstrained | Shaky | IdleMotion | Actuation


@dataclass(frozen=True)
class GivenPose:
    """The output body's pose a configuration gave (JSON ``pose``), in SI and radians:
    ``position`` of the reference ``point`` (its place at the reference configuration),
    and the rotation about it as a matrix and a rotation vector, relative to
    ``relative_to``."""

    body: str
    relative_to: str
    point: tuple[float, float, float]
    position: tuple[float, float, float]
    rotation: tuple[tuple[float, float, float], ...]
    rotation_vector: tuple[float, float, float]


@dataclass(frozen=True)
class ConfigurationResult:
    """Everything mechsing says about one configuration (see :func:`to_json`).

    ``undecided``: a verdict was left open at this precision (auto re-decides the
    configuration at mp:50); ``doubtful``: the float decisions of a singular verdict that
    dropped a singular value above float's rounding (auto re-decides those too);
    ``escalated_for``: why auto re-decided it; ``classification``: what
    :func:`mechsing.singularity.classify` returned (the properties read it)."""

    name: str
    precision: str
    joints: tuple[tuple[str, tuple[float, ...]], ...] = ()
    closure_residual: float | None = None
    closure_rank: ClosureRank | None = None
    loops: tuple[LoopEntry, ...] = ()
    mobility: Mobility | None = None
    singularities: tuple[Finding, ...] = ()
    #: every rank decision made at the configuration, singular or not
    decisions: tuple[Decision, ...] = ()
    underdetermined: bool = False
    error: str | None = None
    #: wall-clock seconds the configuration took (escalation included); not in the JSON
    seconds: float = field(default=0.0, compare=False)
    #: what the analysis did to the given values that a reader should know (JSON ``notes``)
    notes: tuple[str, ...] = ()
    undecided: bool = False
    doubtful: tuple[str, ...] = ()
    escalated_for: tuple[str, ...] = ()
    classification: Classification | None = field(default=None, compare=False, repr=False)
    #: the output's pose the configuration gave (None: it gave joint values only)
    pose: GivenPose | None = None
    #: the twists the output can make here and their motion type (None: no output)
    output_motion: OutputMotion | None = None
    #: the verdict rests on a margin below the resolution of the given values (JSON
    #: ``data_resolution``; None: it does not, or the values are exact)
    data_resolution: DataResolution | None = None
    #: the statics under the configuration's load (:class:`mechsing.statics.Kinetostatics`;
    #: JSON ``efforts`` and ``kinetostatics``), None without a load
    kinetostatics: Any = None
    #: the configuration analysed, as a frozen value: its coordinates at the digits of the
    #: precision that decided, and where it came from (``given``: the file's; ``located``,
    #: ``mode``: a point :func:`~mechsing.analysis.analyze_found` was handed); not in the JSON
    point: ClosedValue | None = field(default=None, compare=False, repr=False)

    @property
    def singular(self) -> bool | None:
        """True when a finding is singular, None when every finding is undecided, else False."""
        if not self.singularities:
            return False
        if all(isinstance(s, UndecidedFinding) for s in self.singularities):
            return None
        return True

    def to_json(self) -> dict[str, Any]:
        """The configuration as the JSON contract has it (one entry of ``configurations``)."""
        return to_json(self)


@dataclass(frozen=True)
class AnalysisResult:
    """The analysis of a mechanism; :func:`to_json` is the JSON contract (docs/json.md)."""

    mechanism: Mechanism
    precision: Precision
    length_scale: float
    configurations: tuple[ConfigurationResult, ...]
    properties: tuple[Property, ...] = ()
    #: the legs of a parallel mechanism, joints from the base to the output
    legs: tuple[LegDescription, ...] = ()
    #: the output's generic motion type: at the first regular configuration analysed
    output_motion: OutputMotion | None = None

    @property
    def failed(self) -> bool:
        """True when some configuration could not be analysed (it carries ``error``)."""
        return any(c.error is not None for c in self.configurations)

    def to_json(self) -> dict[str, Any]:
        """The JSON contract of the analysis (what ``mechsing analyze --format json`` prints)."""
        return to_json(self)

    def _repr_html_(self) -> str:
        """The verdict table in a notebook (``mechsing.report`` draws the whole review)."""
        caption = f"{self.mechanism.name}: analysis in {self.precision}"
        rows = [verdict_row(c) for c in self.configurations]
        return html_table(VERDICT_HEADERS, rows, caption)


# --------------------------------------------------------------------------- the serializer


def to_json(x: Any) -> Any:
    """The JSON contract of a result, a configuration, a mobility or a property, and of
    every value they hold (findings, decisions, margins, subgroups: :mod:`.contract`),
    as plain dicts and lists with keys in the contract's order."""
    if isinstance(x, AnalysisResult):
        return _analysis(x)
    if isinstance(x, ConfigurationResult):
        return _configuration(x)
    if isinstance(x, Mobility):
        return _mobility(x)
    if isinstance(x, Overconstrained | Shaky | IdleMotion | Actuation):
        return _property(x)
    return contract.to_json(x)


def _analysis(r: AnalysisResult) -> dict[str, Any]:
    t = r.precision.tolerances
    return {
        "mechanism": r.mechanism.name,
        "precision": {
            "mode": str(r.precision),
            # floats: an mp:N threshold below the float range (N > 333) is 0 here
            "tau_lo": float(t.tau_lo),
            "tau_hi": float(t.tau_hi),
            "length_scale": r.length_scale,
        },
        "properties": [_property(p) for p in r.properties],
        "configurations": [_configuration(c) for c in r.configurations],
        "legs": [_leg(leg) for leg in r.legs],
        "output_motion": None if r.output_motion is None else _output_motion(r.output_motion),
        "tests_not_run": _tests_not_run(r.mechanism),
        **_limits(r.mechanism),
        **couplings_json(r.mechanism),
        **scene_json(r.mechanism),
    }


def _tests_not_run(mech: Mechanism) -> list[dict[str, Any]]:
    """The added key ``tests_not_run``: the tests the file lacks the ingredients of (no
    inputs, no output), each group with its reason (empty when every test ran)."""
    return [{"tests": list(tests), "reason": why} for tests, why in tests_not_run(mech)]


def couplings_json(mech: Mechanism) -> dict[str, Any]:
    """The added key ``couplings`` (only when the analysed part has couplings of joint
    values, a URDF's ``<mimic>``): each ``joint = multiplier * leader + offset`` (SI,
    radians), its lines, and ``rows``: the constraint rows it adds to the closure system
    (1: each lowers the mobility and the Grubler-Kutzbach and group counts by one)."""
    if not mech.couplings:
        return {}
    from mechsing.numeric import to_float

    return {
        "couplings": [
            {
                "joint": c.joint,
                "leader": c.leader,
                "multiplier": float(to_float(c.multiplier)),
                "offset": float(to_float(c.offset)),
                "line": c.line,
                "source_line": c.source_line,
                "rows": 1,
            }
            for c in mech.couplings
        ]
    }


def _limits(mech: Mechanism) -> dict[str, Any]:
    """The added key ``limits`` (only when the file has limits): joint name -> one
    [lower, upper] per coordinate, SI units and radians."""
    if not mech.limits:
        return {}
    return {"limits": {k: [list(p) for p in v] for k, v in mech.limits.items()}}


def scene_json(mech: Mechanism) -> dict[str, Any]:
    """The added key ``scene`` (only when the command line's scene options chose the output
    or inputs): the output and inputs analysed, the branches left out (each its bodies and
    joints), the couplings dropped with them, and the notes saying so."""
    if mech.scene is None:
        return {}
    out = mech.output
    return {
        "scene": {
            "output": None
            if out is None
            else {
                "body": out.body,
                "relative_to": out.relative_to,
                "point": None if out.point is None else [float(x) for x in out.point],
            },
            "inputs": [str(i) for i in mech.inputs],
            "ground": mech.ground,
            "left_out": [
                {"bodies": list(bodies), "joints": list(joints)}
                for bodies, joints in mech.scene.left_out
            ],
            "dropped_couplings": list(mech.scene.dropped_couplings),
            "notes": list(mech.scene.notes),
        }
    }


def _configuration(c: ConfigurationResult) -> dict[str, Any]:
    out: dict[str, Any] = {"name": c.name, "precision": c.precision}
    if c.error is not None:
        out["error"] = c.error
        out["singular"] = None
        out["singularities"] = []
        return out
    cr = c.closure_rank
    out.update(
        {
            "joints": {k: list(v) for k, v in c.joints},
            "closure_residual": c.closure_residual,
            "closure_rank": None
            if cr is None
            else {"rank": cr.rank, "nullity": cr.nullity, "margin": contract.to_json(cr.margin)},
            "loops": [_loop(lp) for lp in c.loops],
            "mobility": {} if c.mobility is None else _mobility(c.mobility),
            "singular": c.singular,
            "singularities": [contract.to_json(f) for f in c.singularities],
            "decisions": [contract.to_json(d) for d in c.decisions],
        }
    )
    if c.underdetermined:
        out["underdetermined"] = True
    if c.notes:
        out["notes"] = list(c.notes)
    if c.pose is not None:
        out["pose"] = {
            "body": c.pose.body,
            "relative_to": c.pose.relative_to,
            "point": list(c.pose.point),
            "position": list(c.pose.position),
            "rotation": [list(row) for row in c.pose.rotation],
            "rotation_vector": list(c.pose.rotation_vector),
        }
    if c.output_motion is not None:
        out["output_motion"] = _output_motion(c.output_motion)
    if c.data_resolution is not None:
        d = c.data_resolution
        out["data_resolution"] = {
            "below_resolution": True,
            "verdict": d.verdict,
            "digits": d.digits,
            "resolution": d.resolution,
            "spread": d.spread,
            "value": d.value,
            "test": d.test,
        }
        if d.verdict_from is not None:  # auto kept float's singular verdict (see notes)
            out["data_resolution"]["verdict_from"] = d.verdict_from
            out["data_resolution"]["written_decimals"] = "regular"
    if c.kinetostatics is not None:
        out.update(c.kinetostatics.to_json())
    return out


def _leg(leg: LegDescription) -> dict[str, Any]:
    return {
        "leg": leg.number,
        "base": leg.base,
        "body": leg.body,
        "joints": list(leg.joints),
        "other_joints": list(leg.other_joints),
        "bodies": list(leg.bodies),
    }


def _output_motion(m: OutputMotion) -> dict[str, Any]:
    sub = contract.subgroup_json(m.subgroup)
    out: dict[str, Any] = {
        "configuration": m.configuration,
        "body": m.body,
        "relative_to": m.relative_to,
        "dim": m.dim,
        "is_subgroup": m.is_subgroup,
        "type": sub["type"],
        "params": sub["params"],
        "summary": m.summary,
        "twists": [list(t) for t in m.twists],
        "margin": contract.to_json(m.margin),
        "precision": m.precision,
        "generated": contract.subgroup_json(m.generated),
    }
    if m.note is not None:
        out["note"] = m.note
    if m.instantaneous_screw and m.subgroup is not None:
        # one twist: the screw the output turns about at this instant (not a motion type,
        # a subgroup its motions stay in); ``type`` and ``params`` above are its subgroup's
        out["instantaneous_screw"] = {
            "type": sub["type"],
            "params": sub["params"],
            "twist": list(m.twists[0]),
        }
    if m.point is not None:
        out["point"] = {
            "position": list(m.point.position),
            "dim": m.point.dim,
            "velocities": [list(v) for v in m.point.velocities],
            "margin": contract.to_json(m.point.margin),
        }
    return out


def _loop(lp: LoopEntry) -> dict[str, Any]:
    entry: dict[str, Any] = {
        "joints": list(lp.joints),
        "subgroup": contract.subgroup_json(lp.subgroup),
        "rank": lp.rank,
        "sigma": list(lp.sigma) if lp.sigma is not None else None,
        "margin": contract.to_json(lp.margin),
    }
    if lp.status is not None:
        entry["subgroup_status"] = lp.status
    return entry


def _mobility(m: Mobility) -> dict[str, Any]:
    return {
        "grubler": m.grubler,
        "group": m.group,
        "instantaneous": m.instantaneous,
        "generic": m.generic,
        "finite": m.finite,
    }


def _property(p: Property) -> dict[str, Any]:
    out: dict[str, Any] = {"kind": p.kind}
    if isinstance(p, Overconstrained):
        out.update(
            {
                "finite": p.finite,
                "group": p.group,
                "grubler": p.grubler,
                "configuration": p.configuration,
            }
        )
    elif isinstance(p, Shaky):
        out.update(
            {
                "instantaneous": p.instantaneous,
                "finite": p.finite,
                "configurations": list(p.configurations),
            }
        )
    elif isinstance(p, IdleMotion):
        out.update({"dimension": p.dimension, "configuration": p.configuration})
    else:
        out.update(
            {
                "inputs": p.inputs,
                "finite": p.finite,
                "idle": p.idle,
                "configuration": p.configuration,
            }
        )
    out["explanation"] = p.explanation
    return out
