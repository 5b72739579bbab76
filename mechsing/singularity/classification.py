"""Classification of one closed configuration: :func:`classify` (the open chain's output
chain by :class:`~mechsing.singularity.criteria.SerialTest`, a closed chain's by the local
analysis, :mod:`mechsing.singularity.local`), and the random configurations every generic
rank is found at.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechsing import lie
from mechsing.kinematics.chains import tree_chain
from mechsing.kinematics.couplings import impose_couplings
from mechsing.numeric import to_float
from mechsing.singularity.criteria import SerialTest
from mechsing.singularity.findings import (
    Classification,
    Decision,
    Finding,
    UndecidedFinding,
    decision,
    undecided_rank,
)
from mechsing.singularity.local import float_model, local_analysis
from mechsing.singularity.serial import (
    GENERIC_SAMPLES,
    generic_span,
    named,
    serial_finding,
)
from mechsing.timelimit import activity

if TYPE_CHECKING:
    from mechsing.kinematics import KinematicModel
    from mechsing.model import Mechanism
    from mechsing.screws import ClosureSystem
    from mechsing.screws.mobility import NearbySample
    from mechsing.singularity.generic import SampleValues

__all__ = ["classify", "output_chain", "random_configurations"]


def output_chain(mech: Mechanism, model: KinematicModel) -> tuple[list[str], list[int]] | None:
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
    x0 = model.point_array(out.point)
    return lie.act_point(g, x0)


def random_configurations(model: KinematicModel, count: int, seed: int = 0) -> np.ndarray:
    """``count`` random configurations (rows): angles uniform in [-pi, pi), lengths in [-L, L);
    a coupled joint follows its leader."""
    Q = model.float_frame.random_coordinates(np.random.default_rng(seed), count)
    return impose_couplings(model, Q, set()) if model.couplings else Q


def _tree_serial(mech: Any, model: Any, q: np.ndarray) -> tuple[list[Finding], list[Decision]]:
    """The output chain of a mechanism without loops: its ``serial`` finding (or its
    undecided rank) and its decision."""
    chain = output_chain(mech, model)
    if chain is None:
        return [], []
    names, cols = chain
    fm = float_model(model)
    # decided at the analysis precision (so auto can re-decide it at mp:50) ...
    with activity("deciding the rank of the output chain's screw system"):
        poses = model.poses(q)
        x = _output_point(mech, model, q, poses)
        screws = model.current_screws(q, poses)
        here = SerialTest.of(mech, model).decide(screws, cols, x, model.precision)
    xf = None if x is None else np.asarray(to_float(x), dtype=float)
    # ... against the generic rank found at random configurations (float)
    generic = here.rank.rank or 0
    samples = []
    first: tuple[Any, Any] | None = None  # a generic configuration's screws and point
    serial_f = SerialTest.of(mech, fm)
    for qr in random_configurations(fm, GENERIC_SAMPLES):
        pr = fm.poses(qr)
        Sr, xr = fm.current_screws(qr, pr), _output_point(mech, fm, qr, pr)
        sysr = serial_f.decide(Sr, cols, xr, "float")
        first = first or (Sr[:, cols], xr)
        samples.append(sysr.matrix)
        if sysr.rank.rank is not None:
            generic = max(generic, sysr.rank.rank)
    decisions = [decision("output chain", here.rank, generic)]
    label = {"chain": "output", "body": mech.output.body, "relative_to": mech.output.relative_to}
    span = None
    if here.rank.rank is not None and here.rank.rank < generic:
        span = generic_span([here.matrix, *samples], generic)
    f = serial_finding(model, here, generic, names, label, xf, span)
    if first is not None:
        L = float(fm.length_scale)
        f = named(f, names, screws[:, cols], first[0], L, xf, first[1])
    if f is None and here.rank.rank is None:
        return [undecided_rank("output screw system", here.rank)], decisions
    return ([f] if f else []), decisions


def _undecided_test(d: Decision) -> UndecidedFinding:
    """An input/output, constraint or leg rank the precision could not decide."""
    # rank_bounds null when the test rests on another test's undecided rank (see note)
    return UndecidedFinding(f"{d.test} test", d.rank_bounds, d.margin, d.precision, d.note)


def classify(
    mech: Mechanism,
    model: KinematicModel,
    q: np.ndarray,
    closure: ClosureSystem,
    samples: list[NearbySample] | None = None,
    values: list[SampleValues] | None = None,
) -> Classification:
    """Classify one closed configuration ``q`` of ``mech`` (kinematic ``model`` at the
    analysis precision, ``closure``: its stacked closure system there; ``samples``: its
    nearby samples when the caller closed them already, as
    :func:`mechsing.screws.mobility.nearby_samples` does for the closure's float kernel,
    else they are closed here when needed; ``values``: the tests' values at each of them
    when the caller computed them, :func:`mechsing.singularity.generic.sample_values`).

    A pure function of its inputs: the findings (the JSON contract's classes), the rank
    decisions behind them, the generic and finite mobility for mechanisms with loops
    (for open chains both are the closure nullity), the generic values of the
    input/output tests and whether a second-order form was left undecided."""
    cs = closure
    if not mech.loops:
        findings, decisions = _tree_serial(mech, model, q)
        return Classification(tuple(findings), tuple(decisions), cs.nullity, cs.nullity)
    if cs.rank.rank is None:
        return Classification((undecided_rank("stacked closure system", cs.rank),), (), None, None)
    found: list[Finding] = [
        undecided_rank(f"loop {'-'.join(ls.loop.joints)}", ls.rank)
        for ls in cs.loops
        if ls.rank.rank is None
    ]
    with activity("running the mobility, input/output and tangent-cone tests"):
        local = local_analysis(mech, model, q, cs, samples, values)
    found.extend(local.findings)
    # an input/output, constraint or leg rank the precision could not decide is a
    # verdict left open: say so, and let auto re-decide the configuration at mp:50
    found.extend(_undecided_test(d) for d in local.decisions if d.verdict_open)
    return Classification(
        findings=tuple(found),
        decisions=tuple(local.decisions),
        generic=local.generic,
        finite=local.finite,
        io_generic=tuple(local.io_generic.items()),
        # a second-order form between the thresholds
        undecided_form=local.cone is not None and local.cone.undecided,
    )
