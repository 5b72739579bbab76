"""The typed, immutable results of classifying one configuration.

Owns one frozen dataclass per finding kind (the JSON contract's classes):

- :class:`SerialFinding` -- ``serial`` (an open chain, the output chain or a leg, loses rank);
- :class:`BranchFinding` -- the configuration-space classes ``bifurcation``, ``isolated``,
  ``degenerate`` (built by :func:`degenerate` only, its note a function of a
  :class:`DegenerateReason`) and ``increased-mobility``;
- :class:`MotionFinding` -- the input/output (ZFB) classes ``input``, ``output``,
  ``passive-motion``, ``impossible-input`` and ``impossible-output``;
- :class:`ConstraintFinding` -- ``constraint``;
- :class:`UndecidedFinding` -- ``undecided``;

the rank-decision record :class:`Decision` (an entry of ``decisions``) and the result of the
classification, :class:`Classification`.  Nothing here renders JSON or text: the analysis
layer's serializer (``mechsing.analysis.contract``) reads these fields.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import TYPE_CHECKING

from mechsing.numeric import Margin, RankDecision

if TYPE_CHECKING:
    from mechsing.singularity.cspace import Cone

__all__ = [
    "BRANCH_CLASSES",
    "MOTION_CLASSES",
    "RISING_TESTS",
    "BranchFinding",
    "Classification",
    "ConstraintFinding",
    "Decision",
    "DegenerateReason",
    "Finding",
    "MotionFinding",
    "SerialFinding",
    "UndecidedFinding",
    "branch_finding",
    "decision",
    "degenerate",
    "undecided_rank",
]

#: the configuration-space classes (:class:`BranchFinding`)
BRANCH_CLASSES = ("bifurcation", "isolated", "degenerate", "increased-mobility")
#: the ZFB classes (:class:`MotionFinding`): a motion space above its generic dimension ...
MOTION_CLASSES = ("input", "output", "passive-motion")
#: ... or a rank below its generic value
IMPOSSIBLE_CLASSES = ("impossible-input", "impossible-output")
#: tests whose singularity is a dimension above its generic value (the others: a rank below)
RISING_TESTS = MOTION_CLASSES

Floats = tuple[float, ...]


@dataclass(frozen=True)
class Decision:
    """One rank decision made at a configuration (an entry of the JSON ``decisions``).

    ``test``: ``closure``, ``loop A-B-C-D``, ``output chain``, ``leg k chain``, ``input``,
    ``output``, ``impossible-input``, ``impossible-output`` or ``constraint``; ``rank``
    (None when undecided, or when it rests on another test's undecided rank: ``note``
    says so and there are no ``rank_bounds``); ``generic``: the value it is measured
    against, where there is one."""

    test: str
    rank: int | None
    margin: Margin
    precision: str
    rank_bounds: tuple[int, int] | None = None
    generic: int | None = None
    note: str | None = None

    @property
    def verdict_open(self) -> bool:
        """Does this undecided rank leave the verdict open?  Not when every rank its bounds
        allow gives the same verdict: a rank test is singular below its generic value (a
        constraint rank undecided between 5 and 6 with generic 5 is regular either way), a
        motion test above it."""
        if self.rank is not None:
            return False
        if self.rank_bounds is None or self.generic is None:
            return True
        lo, hi = self.rank_bounds
        if self.test in RISING_TESTS:
            return lo <= self.generic < hi
        return lo < self.generic <= hi


def decision(test: str, dec: RankDecision, generic: int | None = None) -> Decision:
    """The record of ``dec`` as the decision of ``test`` (bounds only when undecided)."""
    bounds = (int(dec.rank_bounds[0]), int(dec.rank_bounds[1])) if dec.rank is None else None
    return Decision(test, dec.rank, dec.margin, dec.precision, bounds, generic)


@dataclass(frozen=True)
class SerialFinding:
    """``serial``: an open chain's screw system below its generic rank.

    ``chain`` is ``"output"`` (with ``body`` and ``relative_to``) or ``"leg"`` (with
    ``leg``, from 1); SI vectors as in :mod:`mechsing.singularity.serial`; ``name``: the
    name people give it (``"wrist"``, ``"elbow"``, ``"shoulder"``, ``"leg fully stretched or
    folded"``: :data:`mechsing.singularity.names.NAMES`) where the chain's axes show the
    pattern, else None."""

    chain: str
    joints: tuple[str, ...]
    rank: int
    generic_rank: int
    wrenches: tuple[Floats, ...]
    twist: Floats
    null_joint_rates: Floats
    margin: Margin
    precision: str
    body: str | None = None
    relative_to: str | None = None
    leg: int | None = None
    name: str | None = None
    #: the whole kernel, one row per vector, in its canonical basis (reduced row echelon
    #: form; ``null_joint_rates`` is its first row)
    null_joint_rate_basis: tuple[Floats, ...] = ()

    cls = "serial"

    @property
    def corank(self) -> int:
        """How much rank is lost: the generic rank minus the rank here."""
        return self.generic_rank - self.rank


@dataclass(frozen=True)
class BranchFinding:
    """A configuration-space class: the closure system loses rank and the tangent cone
    (decided at ``order``, at ``test_precision``) with continuation says what passes.

    ``margin``: the closure rank's, with the cone's eigenvalue margin."""

    cls: str
    joints: tuple[str, ...]
    order: int
    instantaneous: int
    margin: Margin
    precision: str
    test_precision: str
    branches: int | None = None
    branch_tangents: tuple[Floats, ...] | None = None
    branch_mobility: tuple[int | None, ...] | None = None
    branch_dimensions: tuple[int, ...] | None = None
    generic: int | None = None
    kinematotropic: bool | None = None
    note: str | None = None

    def __post_init__(self) -> None:
        if self.cls not in BRANCH_CLASSES:
            raise ValueError(f"not a configuration-space class: {self.cls!r}")


def branch_finding(
    cls: str,
    joints: tuple[str, ...],
    cone: Cone,
    margin: Margin,
    precision: str,
    instantaneous: int,
    **fields: object,
) -> BranchFinding:
    """A configuration-space finding decided by ``cone`` (its order, precision and
    eigenvalue margin) on the closure rank's ``margin``."""
    if cone.eig_margin is not None:
        margin = _with_eig_margin(margin, cone.eig_margin)
    return BranchFinding(
        cls,
        tuple(joints),
        cone.order,
        instantaneous,
        margin,
        precision,
        cone.precision,
        **fields,  # type: ignore[arg-type]
    )


def _with_eig_margin(margin: Margin, eig: float) -> Margin:
    from dataclasses import replace

    return replace(margin, eig_margin=eig)


class DegenerateReason(Enum):
    """Why a rank drop is ``degenerate`` (the finding's ``note`` is a function of it)."""

    #: no nearby closed configuration, but the tangent cone is not {0}
    NOTHING_NEARBY = "nothing-nearby"
    #: the higher-order test could not describe the cone (its own notes say why)
    INCONCLUSIVE = "inconclusive"
    #: the cone is {0} although nearby closed configurations exist
    ZERO_CONE_NEARBY = "zero-cone-nearby"
    #: one candidate branch, along which continuation finds no smooth curve
    NOT_SMOOTH = "not-smooth"
    #: one candidate branch whose dimension is not the branch dimension
    WRONG_DIMENSION = "wrong-dimension"


def degenerate_note(
    reason: DegenerateReason,
    cone: Cone,
    dimension: int | None = None,
    generic: int | None = None,
) -> str:
    """The ``note`` of a ``degenerate`` finding, from its reason."""
    if reason is DegenerateReason.NOTHING_NEARBY:
        return (
            "rank drops, no nearby closed configuration was found, but the tangent cone is not {0}"
        )
    if reason is DegenerateReason.INCONCLUSIVE:
        return "; ".join(cone.notes)
    if reason is DegenerateReason.ZERO_CONE_NEARBY:
        return "the tangent cone is {0} but nearby closed configurations exist (a cusp?)"
    if reason is DegenerateReason.NOT_SMOOTH:
        return (
            "one candidate branch, but continuation along it does not find a smooth curve through "
            "the point (a cusp or tangential branches)"
        )
    return f"the tangent cone is one space of dimension {dimension}, not the branch dimension {generic}"


def degenerate(
    reason: DegenerateReason,
    joints: tuple[str, ...],
    cone: Cone,
    margin: Margin,
    precision: str,
    instantaneous: int,
    branch_tangents: tuple[Floats, ...] | None = None,
    generic: int | None = None,
) -> BranchFinding:
    """The one constructor of a ``degenerate`` finding."""
    dimension = cone.subspaces[0].shape[1] if cone.subspaces else None
    return branch_finding(
        "degenerate",
        joints,
        cone,
        margin,
        precision,
        instantaneous,
        branch_tangents=branch_tangents,
        note=degenerate_note(reason, cone, dimension, generic),
    )


@dataclass(frozen=True)
class MotionFinding:
    """An input/output (ZFB) class decided at ``test_precision``.

    ``input``, ``output``, ``passive-motion``: a motion space of ``dimension`` above its
    ``generic`` one, with the ``joint_rates`` of its most telling motion (and the
    ``output_twist`` for ``output``); ``impossible-input``, ``impossible-output``: a
    ``rank`` below its ``generic`` one."""

    cls: str
    joints: tuple[str, ...]
    generic: int
    margin: Margin
    precision: str
    test_precision: str
    dimension: int | None = None
    rank: int | None = None
    joint_rates: Floats | None = None
    output_twist: Floats | None = None
    #: the name people give it where its moving joints show one (a dead centre: "leg fully
    #: stretched or folded", as a crank's leg is named), :func:`mechsing.singularity.serial.moving_name`
    name: str | None = None
    #: the whole motion space, one row per vector, in its canonical basis (reduced row
    #: echelon form of an orthonormal basis, rows in SI rates, largest entry 1, first
    #: non-zero positive); ``joints`` is its support
    joint_rate_basis: tuple[Floats, ...] | None = None

    def __post_init__(self) -> None:
        if self.cls in MOTION_CLASSES:
            ok = self.dimension is not None and self.joint_rates is not None
        elif self.cls in IMPOSSIBLE_CLASSES:
            ok = self.rank is not None
        else:
            ok = False
        if not ok:
            raise ValueError(f"not a well-formed input/output finding: {self.cls!r}")


@dataclass(frozen=True)
class ConstraintFinding:
    """``constraint``: the legs' constraint wrenches below their generic rank."""

    joints: tuple[str, ...]
    rank: int
    generic_rank: int
    wrenches: tuple[Floats, ...]
    margin: Margin
    precision: str
    test_precision: str

    cls = "constraint"

    @property
    def corank(self) -> int:
        """How much rank is lost: the generic rank minus the rank here."""
        return self.generic_rank - self.rank


@dataclass(frozen=True)
class UndecidedFinding:
    """``undecided``: the precision used left a verdict open.

    ``what`` was undecided; ``rank_bounds`` (None when the test rests on another test's
    undecided rank, or when no rank is in question); ``subject``: ``"rank"`` (a rank
    between the thresholds) or ``"configuration"`` (the configuration itself is known
    too coarsely for any verdict, ``note`` says why)."""

    what: str
    rank_bounds: tuple[int, int] | None
    margin: Margin | None
    precision: str
    note: str | None = None
    subject: str = "rank"

    cls = "undecided"


def undecided_rank(what: str, dec: RankDecision) -> UndecidedFinding:
    """The finding of a rank decision left undecided."""
    lo, hi = dec.rank_bounds
    return UndecidedFinding(what, (int(lo), int(hi)), dec.margin, dec.precision)


#: a finding: one of the five frozen types above, told apart by their ``kind``
Finding = SerialFinding | BranchFinding | MotionFinding | ConstraintFinding | UndecidedFinding


@dataclass(frozen=True)
class Classification:
    """What the classification of one closed configuration found (writes into nothing).

    ``generic``/``finite``: the mobility fields it decides (None: could not be decided);
    ``io_generic``: the generic values of the input/output tests, as (test, value) pairs;
    ``undecided_form``: a second-order form fell between the thresholds."""

    findings: tuple[Finding, ...]
    decisions: tuple[Decision, ...]
    generic: int | None
    finite: int | None
    io_generic: tuple[tuple[str, int | None], ...] = ()
    undecided_form: bool = False

    def io_value(self, test: str) -> int | None:
        """The generic value of an input/output test (None when not measured)."""
        return dict(self.io_generic).get(test)

    @property
    def undecided(self) -> bool:
        """Is any verdict left open here (an undecided finding or second-order form)?"""
        return self.undecided_form or any(isinstance(f, UndecidedFinding) for f in self.findings)
