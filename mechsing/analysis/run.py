"""Running the analysis of a mechanism at its configurations: :func:`analyze` (named
configurations, at a precision mode, ``auto`` re-deciding at mp:50) and
:func:`analyze_found` (configurations a sweep located), each configuration's closure,
mobility, findings and words gathered into a :class:`ConfigurationResult`.

The package's docstring (:mod:`mechsing.analysis`) says what the modes do.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from mechsing.analysis.describe import describe_legs, output_motion
from mechsing.analysis.exact_run import ExactRun
from mechsing.analysis.properties import mechanism_properties
from mechsing.analysis.resolution import resolution_check
from mechsing.analysis.results import (
    AnalysisResult,
    ClosureRank,
    ConfigurationResult,
    GivenPose,
    LoopEntry,
    Mobility,
)
from mechsing.errors import TimeLimitExceeded, UserError, working_on
from mechsing.kinematics import Closer, ConfigurationError, KinematicModel
from mechsing.kinematics.closed import ClosedValue, digits_of
from mechsing.model import Mechanism
from mechsing.numeric import Precision, float_drop_is_real, parse_precision, to_float
from mechsing.reader import read_mechanism
from mechsing.screws import closure_system, group_mobility, grubler
from mechsing.screws.mobility import NearbySample, nearby_samples_many
from mechsing.singularity import classify
from mechsing.singularity.findings import Decision, UndecidedFinding, decision
from mechsing.singularity.generic import SampleValues, sample_values
from mechsing.singularity.local import float_model
from mechsing.timelimit import (
    EXACT_TIME_LIMIT,
    TimeLimit,
    activity,
    check_time_limit,
)

__all__ = ["AnalysisResult", "ConfigurationResult", "analyze", "analyze_found"]


def analyze(
    mechanism: Mechanism | str | Path,
    configs: list[str] | None = None,
    precision: Precision | str = "auto",
    time_limit: float | None = None,
    progress: Callable[[str], None] | None = None,
) -> AnalysisResult:
    """Analyse a mechanism (or a file of any format) at the named configurations (default:
    all).

    Parameters
    ----------
    mechanism : Mechanism, str or Path
        A mechanism (:func:`mechsing.load`) or the path of a mechanism file of any format
        (YAML or JSON, a ``dh`` table, URDF, MJCF).
    configs : list of str, optional
        The configurations to analyse, by name; default: every configuration of the file.
    precision : Precision or str
        ``"auto"`` (float, then mp:50 where float cannot decide), ``"float"``, ``"mp:N"``
        or ``"exact"``.
    time_limit : float or None
        The most seconds one configuration may take, in every precision mode (None:
        :data:`~mechsing.timelimit.EXACT_TIME_LIMIT` in exact mode, no limit in the
        others); a configuration stopped there gets an ``error`` entry that says so.
    progress : callable, optional
        Called with a line of text when exact mode takes long (which configuration it
        works on); the command line prints these lines on standard error.

    Returns
    -------
    AnalysisResult
        One :class:`~mechsing.analysis.results.ConfigurationResult` per configuration,
        the mechanism's properties; ``to_json()`` is the JSON contract.

    Raises
    ------
    UserError
        For a file or an option that is not valid (the message names the file, the line
        and the fix).  A configuration that cannot be analysed is not raised: it carries
        ``error`` in the result.
    """
    if time_limit is not None:
        check_time_limit(time_limit)
    mech = (
        mechanism
        if isinstance(mechanism, Mechanism)
        else read_mechanism(mechanism, precision=precision)
    )
    with working_on(file=mech.path or mech.name):
        return _analyze(mech, configs, precision, time_limit, progress)


def analyze_found(
    mechanism: Mechanism,
    found: dict[str, Any],
    precision: Precision | str = "auto",
    time_limit: float | None = None,
    located: bool = True,
) -> list[ConfigurationResult]:
    """The analysis of configurations found numerically in float (a sweep's located
    singularities): ``found`` maps a name to every joint coordinate (SI, radians, the
    mechanism's coordinate order), closed to float's tolerance, or to a
    :class:`~mechsing.kinematics.closed.ClosedValue` (whose ``source`` and ``certified``
    each result's ``point`` keeps).  ``located=False``: the values are data known to
    their digits (mpmath numbers, every assembly mode refined to 50 digits or more),
    analysed as a file's values are.

    Their values are float data: at mp:N (and when auto re-decides an undecided rank at
    mp:50) each is first projected onto closure at N digits (the inputs kept), as a
    file's decimal values are; the point is then where float located it, about 1e-13
    from the singularity, which N digits can tell apart.  For the same reason auto does
    not re-decide a singular float verdict whose dropped singular value is above
    float's rounding: that drop is the distance float located the point to.  Exact mode
    cannot take them (they are not exact data).  ``time_limit``: as for :func:`analyze`."""
    import mpmath

    from mechsing.model import Configuration

    prec = parse_precision(precision) if isinstance(precision, str) else precision
    if prec.mode == "exact":  # policy: exact mode takes exact data only
        raise UserError(
            "exact precision cannot classify configurations found numerically (their values "
            "are float data, not exact ones); use --precision auto or mp:N"
        )
    coords = mechanism.coordinates()
    configurations = dict(mechanism.configurations)
    for name, q in found.items():
        values: dict[str, list[float]] = {}
        numbers = q.q if isinstance(q, ClosedValue) else q
        for (joint, _i), x in zip(coords, numbers, strict=True):
            # N-digit values stay as they are (a point located again at mp:N)
            values.setdefault(joint, []).append(x if isinstance(x, mpmath.mpf) else float(x))
        configurations[name] = Configuration(
            name, {j: tuple(v) for j, v in values.items()}, start="reference"
        )
    mech = replace(mechanism, configurations=configurations)
    from mechsing.screws import share_loop_identifications

    share_loop_identifications(mechanism, mech)  # the same joints: the same loops
    with working_on(file=mech.path or mech.name):
        data = Precision("float") if located else None
        res = _analyze(mech, list(found), prec, time_limit, None, data, located=located)
    return [_handed_on(r, found.get(r.name)) for r in res.configurations]


def _handed_on(res: ConfigurationResult, given: Any) -> ConfigurationResult:
    """The result of a configuration handed to :func:`analyze_found` as a
    :class:`ClosedValue`: its ``point`` (the coordinates analysed, at their digits)
    keeps the value's source and certification (an error entry: the value itself)."""
    if not isinstance(given, ClosedValue):
        return res
    if res.point is None:
        return replace(res, point=given)
    return replace(res, point=given.at(res.point.q, res.point.digits, res.name))


def _analyze(
    mech: Mechanism,
    configs: list[str] | None,
    precision: Precision | str,
    time_limit: float | None,
    progress: Callable[[str], None] | None,
    data_precision: Precision | None = None,
    located: bool = False,
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
            models[key] = (km, Closer(km, data_precision=data_precision or first))
        return models[key]

    first = Precision("float") if prec.mode == "auto" else prec
    if prec.mode == "exact":  # policy: exact proofs run under a time limit, one at a time
        exact = ExactRun(
            mech, names, EXACT_TIME_LIMIT if time_limit is None else time_limit, progress
        )
        exact.prepare(lambda: stage(first))
    results = []
    # configurations found numerically (a sweep's located points) come many at a time:
    # their nearby samples are closed together
    prepared = _prepare_found(mech, names, stage(first)) if located else {}

    def _one(name: str) -> ConfigurationResult:
        return _analyze_one(mech, name, stage(first), prepared.get(name))

    for name in names:
        start = time.perf_counter()
        if prec.mode == "exact":  # policy: see ExactRun
            res = exact.run(name, lambda name=name: _analyze_one(mech, name, stage(first)))
            res = _with_resolution(mech, res, stage(first)[0])
            results.append(replace(res, seconds=time.perf_counter() - start))
            continue
        res = _within(time_limit, name, str(prec), lambda name=name: _one(name))
        # a point located in float is as near its singularity as float places it: the drop
        # float sees above its own rounding is that distance, so auto keeps the verdict
        doubtful = res.doubtful and not located
        # an output motion left undecided (its rank, or the subgroup its twists generate)
        # is re-decided too; at a located point, where the twists are those of a
        # singularity and the sweep shows no motion type, it is not worth an mp:50 pass
        motion = res.output_motion is not None and res.output_motion.undecided and not located
        if prec.mode == "auto" and res.error is None and (res.undecided or doubtful or motion):
            why = res.doubtful or ("undecided",)
            in_float = res
            res = _within(
                time_limit,
                name,
                "mp:50",
                lambda name=name: _analyze_one(mech, name, stage(Precision("mp", 50))),
            )
            res = replace(res, escalated_for=why)
            if res.error is not None and not located:
                res = _float_when_written_digits_fail(mech, in_float, res)
            elif doubtful and not in_float.undecided and not located:
                res = _kept_within_resolution(mech, in_float, res, stage(first)[0])
        if not located and res.data_resolution is None:
            # a located point is float data, placed as near as float can
            res = _with_resolution(mech, res, stage(first)[0])
        results.append(replace(res, seconds=time.perf_counter() - start))
    km0 = stage(first)[0]
    props = mechanism_properties(mech, results)
    return AnalysisResult(
        mech,
        prec,
        km0.length_scale,
        tuple(results),
        props,
        legs=describe_legs(mech),
        output_motion=_generic_motion(results),
    )


def _with_resolution(
    mech: Mechanism, res: ConfigurationResult, model: KinematicModel
) -> ConfigurationResult:
    """``res`` with its verdict checked against the resolution of its given values
    (:func:`mechsing.analysis.resolution.resolution_check`): when it rests on less, the
    result says so (``data_resolution``) and so do its notes."""
    with working_on(configuration=res.name):
        found = resolution_check(mech, res, model)
    if found is None:
        return res
    return replace(res, data_resolution=found, notes=(*res.notes, found.note))


def _float_when_written_digits_fail(
    mech: Mechanism, in_float: ConfigurationResult, written: ConfigurationResult
) -> ConfigurationResult:
    """Auto's result when float analysed a configuration and its re-decision at mp:50 did
    not (the written decimals do not close at 50 digits, or the time ran out).

    Given values written with digits to spare (a change point drawn to 15 digits) are
    roundings of the values meant: at 50 digits the written decimals may lie just beyond
    a limit of travel, by less than their resolution, where float closes them to its own
    tolerance.  Auto then keeps float's analysis, decided in float, and says what 50 digits
    found.  Values without such a resolution (exact expressions, short decimals) keep the
    refusal: their digits are the data."""
    cfg = mech.configurations.get(in_float.name)
    posed = cfg is not None and cfg.pose is not None and bool(cfg.pose.resolution)
    if cfg is None or not (cfg.resolution or posed):
        return written
    what = "did not close" if "does not close" in (written.error or "") else "were not analysed"
    note = (
        f"at 50 digits the written decimals {what} ({written.error}); they are roundings "
        "of the values meant, and float closes them within its tolerance: the analysis is "
        "float's; give more digits or exact values to decide at 50 digits"
    )
    return replace(in_float, escalated_for=written.escalated_for, notes=(*in_float.notes, note))


def _kept_within_resolution(
    mech: Mechanism,
    in_float: ConfigurationResult,
    written: ConfigurationResult,
    model: KinematicModel,
) -> ConfigurationResult:
    """Auto's verdict on a configuration float found singular on a drop above its own
    rounding (``in_float``) and mp:50 re-decided (``written``).

    When mp:50 finds the written decimals regular by less than the resolution of the given
    values can move its tests (a dead centre drawn to 15 digits), the data cannot tell the
    configuration from the singular one float finds: auto keeps float's verdict, decided
    in float with float's margins, and says that the written decimals are regular below
    the data's resolution.  Otherwise mp:50's verdict stands."""
    if written.error is not None or written.singular is not False or in_float.singular is not True:
        return written
    with working_on(configuration=written.name):
        below = resolution_check(mech, written, model)
    if below is None:
        return written
    kept = replace(below, verdict_from=in_float.precision)
    return replace(
        in_float,
        escalated_for=written.escalated_for,
        data_resolution=kept,
        notes=(*in_float.notes, kept.note),
    )


def _generic_motion(results: list[ConfigurationResult]) -> Any:
    """The output's motion type at the first regular configuration analysed (the one
    that speaks for the mechanism, as for its properties); None when none is regular."""
    for r in results:
        # a verdict below the data's resolution does not speak for the mechanism
        regular = r.error is None and r.singular is False and r.data_resolution is None
        if regular and r.output_motion is not None:
            return r.output_motion
    return None


def _doubtful_drops(
    singular: bool | None,
    decisions: tuple[Decision, ...],
    closure_residual: float,
    length_scale: float,
) -> tuple[str, ...]:
    """The float decisions of a configuration found singular that dropped a singular value
    above float's rounding of it (closure residual included): auto re-decides them at mp:50.

    Only a singular verdict can rest on such a drop (a rank decided too low makes a finding,
    never removes one), so a regular configuration is not re-decided: far from singular,
    auto costs what float costs."""
    if singular is not True:
        return ()
    data_error = closure_residual / length_scale
    return tuple(
        d.test
        for d in decisions
        # policy: only a float verdict can be an artefact of the data's rounding
        if d.precision == "float" and float_drop_is_real(d.margin, data_error)
    )


def _within(
    limit: float | None, name: str, mode: str, work: Callable[[], ConfigurationResult]
) -> ConfigurationResult:
    """``work()`` (the analysis of configuration ``name``) within ``limit`` seconds (None: no
    limit); stopped there, an error entry that says so."""
    if limit is None:
        return work()
    try:
        with TimeLimit(limit):
            return work()
    except TimeLimitExceeded as exc:
        doing = exc.activity or "analysing it"
        return ConfigurationResult(
            name,
            mode,
            error=f"configuration {name!r}: stopped by the time limit after {limit:g} s while "
            f"{doing}; allow more time with --time-limit S (time_limit=)",
        )


@dataclass(frozen=True)
class _Prepared:
    """What the analysis of one configuration starts from, computed before it: the
    closed configuration, its closure system and its nearby samples (None: not needed)."""

    closed: Any
    closure: Any
    samples: list[NearbySample] | None
    #: the tests' values at each sample (:func:`mechsing.singularity.generic.sample_values`)
    values: list[SampleValues] | None = None


def _prepare_found(
    mech: Mechanism, names: list[str], stage: tuple[KinematicModel, Closer]
) -> dict[str, _Prepared]:
    """Each configuration closed and its closure system decided, as its analysis does
    first, and the nearby samples its classification measures the generic values
    against (:func:`mechsing.screws.mobility.nearby_samples`), all configurations'
    samples closed by one batched Newton.  A configuration that does not close is left
    out (its analysis says why)."""
    model, closer = stage
    prec = model.precision
    out: dict[str, tuple[Any, Any]] = {}
    # the points' closure checked together (float: the same residuals, one batch)
    closer.solve_many(names)
    for name in names:
        with working_on(configuration=name, precision=str(prec)), prec.context():
            try:
                closed = closer.solve(name)
            except ConfigurationError:
                continue
            out[name] = (closed, closure_system(model, closed.q, prec))
    # the classification samples a configuration of nullity above 0 whose closure rank
    # is decided (mechsing.singularity.local)
    want = [
        n for n, (_, cs) in out.items() if mech.loops and cs.rank.rank is not None and cs.nullity
    ]
    fm = float_model(model)
    with prec.context():
        qs = [to_float(out[n][0].q) for n in want]
        kernels = [
            np.zeros((model.n, 0))
            if out[n][1].rank.null_space is None
            else to_float(out[n][1].rank.null_space)
            for n in want
        ]
    many = nearby_samples_many(fm, qs, kernels)
    # the tests' values at every sample of every configuration, computed together
    flat = sample_values(mech, fm, [s for ss in many for s in ss])
    values: dict[str, list[SampleValues]] = {}
    at = 0
    for n, ss in zip(want, many, strict=True):
        values[n] = flat[at : at + len(ss)]
        at += len(ss)
    samples = dict(zip(want, many, strict=True))
    return {n: _Prepared(c, cs, samples.get(n), values.get(n)) for n, (c, cs) in out.items()}


def _analyze_one(
    mech: Mechanism,
    name: str,
    stage: tuple[KinematicModel, Closer],
    prepared: _Prepared | None = None,
) -> ConfigurationResult:
    # every mp:N computation must run at N digits: mpmath's precision is a context
    prec = stage[0].precision
    with working_on(configuration=name, precision=str(prec)), prec.context():
        return _analyze_one_in_context(mech, name, stage, prepared)


def _analyze_one_in_context(
    mech: Mechanism,
    name: str,
    stage: tuple[KinematicModel, Closer],
    prepared: _Prepared | None = None,
) -> ConfigurationResult:
    model, closer = stage
    prec = model.precision
    if prepared is not None:
        closed = prepared.closed
    else:
        try:
            with activity("closing the configuration"):
                closed = closer.solve(name)
        except ConfigurationError as exc:
            return ConfigurationResult(name, str(prec), error=str(exc))
    q = closed.q
    with activity("deciding the ranks of the closure system, of its loops and their subgroups"):
        cs = closure_system(model, q, prec) if prepared is None else prepared.closure
        closure_rank = ClosureRank(cs.rank.rank, cs.nullity, cs.rank.margin)
        loops, decisions, undecided = _closure_entries(mech, cs)
        inst = cs.nullity
        grubler_count, group = grubler(model), group_mobility(model, cs.loops)
    with activity("classifying the singularities (output chain, input/output and cone tests)"):
        found = (
            classify(mech, model, q, cs)
            if prepared is None
            else classify(mech, model, q, cs, prepared.samples, prepared.values)
        )
    findings = list(found.findings)
    if closed.at_fold and prec.mode == "float":
        # float locates a fold's unknown joints only to sqrt(eps): a kernel singular value
        # of 1e-8 there says nothing, so no float verdict stands (auto re-decides at mp:50)
        findings.append(
            UndecidedFinding(
                "configuration at a fold of the given values",
                None,
                closure_rank.margin,
                str(prec),
                note=FOLD_NOTE,
                subject="configuration",
            )
        )
    decisions.extend(found.decisions)
    motion = output_motion(mech, model, q, cs, name)
    res = ConfigurationResult(
        name,
        str(prec),
        joints=tuple((k, tuple(v)) for k, v in model.values(q).items()),
        closure_residual=float(closed.residual),
        closure_rank=closure_rank,
        loops=loops,
        mobility=Mobility(grubler_count, group, inst, found.generic, found.finite),
        singularities=tuple(findings),
        decisions=tuple(decisions),
        underdetermined=closed.underdetermined,
        notes=tuple(closed.notes),
        # auto re-decides the configuration at mp:50 (and an output motion whose rank or
        # subgroup the precision left open: see _analyze)
        undecided=undecided
        or found.undecided
        or any(isinstance(f, UndecidedFinding) for f in findings),
        classification=found,
        pose=given_pose(mech, name),
        output_motion=motion,
        point=ClosedValue(tuple(q), digits_of(prec), "given", name),
    )
    doubtful = _doubtful_drops(
        res.singular, res.decisions, res.closure_residual or 0.0, model.length_scale
    )
    return replace(res, doubtful=doubtful) if doubtful else res


def given_pose(mech: Mechanism, name: str) -> GivenPose | None:
    """The output's pose configuration ``name`` gives, completed (an omitted position is
    the reference point's, an omitted rotation the identity) and in float (SI, radians)."""
    from mechsing import lie
    from mechsing.numeric import to_float

    pose = mech.configurations[name].pose
    if pose is None or mech.output is None:
        return None
    point = np.asarray(to_float(np.array(mech.output_reference_point(), dtype=object)), float)
    position = (
        point
        if pose.position is None
        else np.asarray(to_float(np.array(pose.position, dtype=object)), float)
    )
    if pose.rotation is not None:
        R = np.asarray(to_float(np.array(pose.rotation, dtype=object)), float)
        rvec = lie.log_so3(R)
    else:
        rv = (0, 0, 0) if pose.rotation_vector is None else pose.rotation_vector
        rvec = np.asarray(to_float(np.array(rv, dtype=object)), float)
        R = lie.exp(np.concatenate([rvec, np.zeros(3)]))[:3, :3]

    def vec(x: Any) -> tuple[float, float, float]:
        return (float(x[0]), float(x[1]), float(x[2]))

    return GivenPose(
        mech.output.body,
        mech.output.relative_to,
        vec(point),
        vec(position),
        tuple(vec(row) for row in R),
        vec(rvec),
    )


#: why float gives no verdict at a fold of the given values
FOLD_NOTE = "float places a fold's unknown joints only to about 1e-8"


def _closure_entries(
    mech: Mechanism, cs: Any
) -> tuple[tuple[LoopEntry, ...], list[Decision], bool]:
    """The loops of a configuration (their entries) and the closure and loop decisions;
    True when one of them is undecided."""
    rank = cs.rank
    undecided = rank.rank is None
    decisions = [decision("closure", rank)] if mech.loops else []
    loops = []
    for ls in cs.loops:
        ident = ls.identification
        entry = LoopEntry(
            joints=tuple(ls.loop.joints),
            subgroup=ident.subgroup if ident.ok else None,
            rank=ls.rank.rank,
            sigma=tuple(ls.rank.sigma) if ls.rank.sigma is not None else None,
            margin=ls.rank.margin,
            status=None if ident.ok else ident.status,
        )
        if not ident.ok or ls.rank.rank is None:
            undecided = True
        loops.append(entry)
        decisions.append(decision(f"loop {'-'.join(ls.loop.joints)}", ls.rank))
    return tuple(loops), decisions, undecided
