"""The full classification of one closed configuration of a mechanism with loops.

Order of work (lazy: nothing second-order at a regular point):

1. nearby regular configurations of the branch (:mod:`mechsing.screws.mobility`)
   give every *generic* value the tests are measured against;
2. a rank drop of the stacked closure system below its generic value runs the
   tangent-cone test (:mod:`mechsing.singularity.cspace`) and probes each
   candidate branch by stepping along its tangent and closing again:
   ``bifurcation`` (several branches), ``isolated`` (cone {0} and nothing
   nearby), ``degenerate`` (inconclusive, not a union of subspaces, or a cone
   that disagrees with what continuation finds), ``increased-mobility`` (one
   smooth branch of the generic dimension);
3. with inputs and output: the ZFB classes and ``constraint``
   (:mod:`mechsing.singularity.zfb`), and ``serial`` for legs that lose rank.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from mechsing.lie import ANGULAR, LINEAR
from mechsing.numeric import (
    SUPPORT_RTOL,
    Margin,
    Precision,
    RankDecision,
    decide_from_exact,
    decide_rank,
    numeric_precision,
    to_float,
)
from mechsing.numeric.linalg import first_nonzero_positive, svd
from mechsing.numeric.tolerances import MOST_MOVED_RTOL
from mechsing.screws import closure_system
from mechsing.screws.mobility import (
    SAMPLE_CLOSURE_RTOL,
    SAMPLE_DISTINCT_RATIO,
    NearbySample,
    nearby_samples,
    reclose,
    stacked_jacobian,
)
from mechsing.screws.readable import reduced_echelon
from mechsing.singularity.criteria import ConstraintTest, SerialTest, tests_run
from mechsing.singularity.cspace import Cone, Expansion, closure_expansion, tangent_cone
from mechsing.singularity.findings import (
    BranchFinding,
    ConstraintFinding,
    Decision,
    DegenerateReason,
    Finding,
    MotionFinding,
    branch_finding,
    decision,
    degenerate,
)
from mechsing.singularity.generic import SampleValues, sample_values
from mechsing.singularity.serial import (
    generic_span,
    moving_name,
    named,
    serial_finding,
    wrenches_of,
)
from mechsing.singularity.zfb import io_quantities, output_chain

#: a branch probe follows its tangent when the cosine between the tangent and
#: the displacement found is above this (a smooth branch through the point)
BRANCH_ALIGNMENT = 0.9

# The higher-order forms (tangent cone) and the input/output and constraint
# ranks at q are computed and decided at the analysis precision
# (numeric.numeric_precision: float, mp:N, mp:50 for exact), from the
# configuration and screws of the analysis; each finding says which in
# ``test_precision``.  The nearby samples and the branch probes that they are
# measured against are verification by continuation and stay in float.

#: the note of a motion test whose space rests on another test's undecided rank
RESTS_ON_UNDECIDED = "rests on an undecided rank of the input or output map"

#: distances (commensurate) of the probes along a branch tangent
BRANCH_STEPS = (3e-3, 3e-2)


@dataclass(frozen=True)
class LocalAnalysis:
    """Mobility fields and findings of one configuration, built once the local analysis
    has computed them all (:func:`mechsing.singularity.classify` turns it into a
    :class:`~mechsing.singularity.findings.Classification`)."""

    generic: int | None
    finite: int | None
    findings: tuple[Finding, ...] = ()
    samples: tuple[NearbySample, ...] = ()
    cone: Cone | None = None
    regular: bool = True
    io_generic: dict[str, int | None] = field(default_factory=dict)
    #: the rank decisions at q behind the input/output, constraint and leg tests
    decisions: tuple[Decision, ...] = ()


def float_model(model: Any) -> Any:
    """The model's float twin (:meth:`KinematicModel.float_twin`); the loop
    identifications are the mechanism's (:func:`mechsing.screws.reference_loop_identification`),
    shared by both."""
    return model.float_twin()


def _si_rates(model: Any, x: np.ndarray) -> list[float]:
    """Commensurate joint rates -> SI (length coordinates times L), largest entry 1, first
    non-zero positive; entries at or below SUPPORT_RTOL (outside the support) reported as 0."""
    v = model.float_frame.rates_back(x)
    big = float(np.max(np.abs(v))) if v.size else 0.0
    if big == 0:
        return [0.0 for _ in v]
    v = first_nonzero_positive(v / big)
    v = np.where(np.abs(v) > SUPPORT_RTOL, v, 0.0)
    return [float(a) + 0.0 for a in v]


def _probe(fm: Any, q: np.ndarray, x: np.ndarray) -> tuple[int | None, float] | None:
    """Step along commensurate direction x, close again; (nullity there, alignment)."""
    L = fm.length_scale
    undecided: tuple[int | None, float] | None = None
    for step in BRANCH_STEPS:
        d = fm.float_frame.rates_back(step * x)
        q1, res = reclose(fm, fm.update(q, d))
        if res > SAMPLE_CLOSURE_RTOL * L:
            continue
        moved = fm.float_frame.rates(fm.difference(q1, q))
        dist = float(np.linalg.norm(moved))
        if dist < SAMPLE_DISTINCT_RATIO * step:
            continue
        align = float(abs(moved @ x) / (dist * np.linalg.norm(x)))
        dec = decide_rank(stacked_jacobian(fm, q1), "float", L)
        if dec.rank is None:
            # closed only to ~1e-13 L, a point of the branch can leave float's rank
            # undecided: the longer step decides it
            undecided = (None, align)
            continue
        return fm.n - dec.rank, align
    return undecided


def _joints_of(mech: Any, cs: Any) -> tuple[str, ...]:
    order = [j.name for j in mech.joints]
    return tuple(sorted({j for ls in cs.loops for j in ls.loop.joints}, key=order.index))


def local_analysis(
    mech: Any,
    model: Any,
    q: np.ndarray,
    cs: Any,
    samples: list[NearbySample] | None = None,
    values: list[SampleValues] | None = None,
) -> LocalAnalysis:
    """Generic/finite mobility and every finding at a closed configuration with loops
    (``samples``: its nearby samples when already closed, else closed here; ``values``:
    the tests' values at each of them when already computed,
    :func:`mechsing.singularity.generic.sample_values`)."""
    tprec = numeric_precision(model.precision)
    with tprec.context():
        return _local_analysis(mech, model, q, cs, tprec, samples, values)


@dataclass
class _TestSystem:
    """The closure system at q in the numbers of the test precision (built once)."""

    exp: Expansion
    M: np.ndarray
    rank: RankDecision


def _local_analysis(
    mech: Any,
    model: Any,
    q: np.ndarray,
    cs: Any,
    tprec: Precision,
    given: list[NearbySample] | None = None,
    values: list[SampleValues] | None = None,
) -> LocalAnalysis:
    inst = cs.nullity
    prec_name = cs.rank.precision
    if inst is None:
        return LocalAnalysis(None, None, regular=False)
    fm = float_model(model)
    qf = to_float(q)
    N = to_float(cs.rank.null_space) if cs.rank.null_space is not None else np.zeros((model.n, 0))
    if inst == 0:
        samples: list[NearbySample] = []
    else:
        samples = nearby_samples(fm, qf, N) if given is None else given
    null_s = [s.nullity for s in samples if s.nullity is not None]
    gen_s = min(null_s) if null_s else None
    generic: int | None = inst
    finite: int | None = inst
    cone: Cone | None = None
    regular = True
    findings: list[Finding] = []
    joints = _joints_of(mech, cs)
    margin = cs.rank.margin
    built: list[_TestSystem] = []

    def system() -> _TestSystem:
        if not built:
            exp, M = closure_expansion(model, cs, tprec)
            # exact mode, a large system: M's rank is the closure rank proved exactly, and
            # its mp spaces come from the exact kernel (the same kernel: M is the closure
            # system in orthonormal loop coordinates), without an SVD of M at 50 digits
            large = M.shape[1] >= EXACT_KERNEL_MIN_COORDINATES
            exact = model.precision.mode == "exact" and large
            dec = decide_from_exact(M, tprec, cs.rank) if exact else None
            if dec is None:
                dec = decide_rank(M, tprec, 1.0, want_spaces=True, native_spaces=True)
            built.append(_TestSystem(exp, M, dec))
        return built[0]

    def cone_of(max_order: int = 3) -> Cone:
        ts = system()
        return tangent_cone(ts.exp, ts.M, tprec, max_order=max_order, rank=ts.rank)

    if inst == 0:
        generic = finite = 0
    elif not samples:
        cone = cone_of()
        regular = False
        if cone.kind == "zero":
            generic, finite = None, 0
            findings.append(branch_finding("isolated", joints, cone, margin, prec_name, inst))
        else:
            found = _branches(fm, qf, cone) if cone.kind == "subspaces" else []
            if found and any(b[1] is not None for b in found):
                finding, mobility = _bifurcation_or_more(
                    fm, joints, cone, found, margin, prec_name, inst, None
                )
                findings.append(finding)
                if mobility is not None:
                    generic = finite = mobility
            else:
                generic, finite = None, None
                findings.append(
                    degenerate(
                        DegenerateReason.NOTHING_NEARBY, joints, cone, margin, prec_name, inst
                    )
                )
    elif gen_s is not None and inst > gen_s:
        regular = False
        cone = cone_of()
        generic = finite = gen_s
        if cone.kind == "inconclusive":
            findings.append(
                degenerate(DegenerateReason.INCONCLUSIVE, joints, cone, margin, prec_name, inst)
            )
        elif cone.kind == "zero":
            findings.append(
                degenerate(DegenerateReason.ZERO_CONE_NEARBY, joints, cone, margin, prec_name, inst)
            )
        else:
            found = _branches(fm, qf, cone)
            finding, mobility = _bifurcation_or_more(
                fm, joints, cone, found, margin, prec_name, inst, gen_s
            )
            findings.append(finding)
            if mobility is not None:
                generic = finite = mobility
    else:
        generic = gen_s if gen_s is not None else inst
        finite = generic
        # shakiness: a regular point whose second-order cone is smaller than the kernel
        if samples:
            second = cone_of(max_order=2)
            if (
                second.kind == "subspaces"
                and len(second.subspaces) == 1
                and second.subspaces[0].shape[1] < inst
            ):
                finite = second.subspaces[0].shape[1]
                cone = second
    # input / output / constraint, measured against the regular samples of the branch
    io_generic: dict[str, int | None] = {}
    decisions: list[Decision] = []
    if generic is not None and inst > 0 and samples:
        findings += _io_findings(
            mech,
            model,
            fm,
            q,
            system().rank,
            cs,
            samples,
            generic,
            io_generic,
            decisions,
            tprec,
            values if given is not None else None,
        )
    return LocalAnalysis(
        generic,
        finite,
        tuple(findings),
        tuple(samples),
        cone,
        regular,
        io_generic,
        tuple(decisions),
    )


#: exact mode takes the test system's spaces from the exact kernel (no SVD at 50 digits)
#: from this many coordinates on (a 6-UPS platform: 36); below, the SVD costs little and
#: its spaces are kept: the margin a rank difference reports is the one of its two
#: decisions nearer to flipping, which for two decisions that drop only rounding is
#: decided by that rounding, and so by the basis the kernel is given in
EXACT_KERNEL_MIN_COORDINATES = 24

#: seed of the generic directions probed along a branch of dimension 2 or more
BRANCH_PROBE_SEED = 7


def _branches(fm: Any, qf: np.ndarray, cone: Cone) -> list[tuple[np.ndarray, int | None, bool]]:
    """For each cone subspace: its tangent, the nullity found along it, smooth on both sides."""
    res = []
    rng = np.random.default_rng(BRANCH_PROBE_SEED)
    for W in cone.subspaces:
        # a generic direction of the branch: a basis vector of it may lie in a
        # special subspace (one that leaves the singular loop at rest)
        Wf = to_float(W)
        x = Wf[:, 0] if Wf.shape[1] == 1 else Wf @ rng.normal(size=Wf.shape[1])
        x = x / np.linalg.norm(x)
        fwd = _probe(fm, qf, x)
        bwd = _probe(fm, qf, -x)
        null = None
        for p in (fwd, bwd):
            if p is not None and p[0] is not None:
                null = p[0] if null is None else max(null, p[0])
        smooth = (
            fwd is not None
            and bwd is not None
            and fwd[1] > BRANCH_ALIGNMENT
            and bwd[1] > BRANCH_ALIGNMENT
        )
        res.append((x, null, smooth))
    return res


def _bifurcation_or_more(
    fm: Any,
    joints: tuple[str, ...],
    cone: Cone,
    found: list,
    margin: Margin,
    prec: str,
    inst: int,
    gen: int | None,
) -> tuple[BranchFinding, int | None]:
    """The finding of a singular point with branches, and the mobility its branches show
    (the largest of their known mobilities, at two branches or more; else None: the
    caller's stands)."""
    tangents = tuple(tuple(_si_rates(fm, x)) for x, _, _ in found)
    mobilities = tuple(n for _, n, _ in found)
    dims = tuple(W.shape[1] for W in cone.subspaces)
    if len(found) >= 2:
        known = [m for m in mobilities if m is not None]
        return branch_finding(
            "bifurcation",
            joints,
            cone,
            margin,
            prec,
            inst,
            branches=len(found),
            branch_tangents=tangents,
            branch_mobility=mobilities,
            branch_dimensions=dims,
            kinematotropic=len(set(known)) > 1 or None,
        ), (max(known) if known else None)
    x, n, smooth = found[0]
    if smooth and gen is not None and dims[0] == gen:
        return branch_finding(
            "increased-mobility",
            joints,
            cone,
            margin,
            prec,
            inst,
            generic=gen,
            branch_tangents=tangents,
        ), None
    reason = DegenerateReason.NOT_SMOOTH if not smooth else DegenerateReason.WRONG_DIMENSION
    return degenerate(
        reason, joints, cone, margin, prec, inst, branch_tangents=tangents, generic=gen
    ), None


def _io_findings(
    mech: Any,
    model: Any,
    fm: Any,
    q: np.ndarray,
    rank: RankDecision,
    cs: Any,
    samples: list[NearbySample],
    mobility: int,
    io_generic: dict[str, int | None],
    decisions: list[Decision],
    tprec: Precision,
    values: list[SampleValues] | None = None,
) -> list[Finding]:
    """ZFB and constraint findings: decided at q at the test precision ``tprec``
    (``rank``: the closure system's decision there, with its kernel), against
    the values at the regular nearby samples (float; ``values``: those of every sample
    when already computed, else computed here for the regular ones; ``mobility``: the
    generic mobility, which makes a sample regular).  The tests' generic values go into
    ``io_generic``, their rank decisions at q into ``decisions``."""
    findings: list[Finding] = []
    idx = [i for i, s in enumerate(samples) if s.nullity == mobility] or range(len(samples))
    # each regular sample's values, computed once for every test (all samples together)
    if values is None:
        regular = sample_values(mech, fm, [samples[i] for i in idx])
    else:
        regular = [values[i] for i in idx]
    if tests_run(mech):
        here = io_quantities(
            mech, model, q, rank.null_space, tprec, screws=cs.screws, kernel=rank, cs=cs
        )
        gens = [v.io for v in regular if v.io is not None]
        if here is not None and gens:
            hv = here.values()
            generic = {
                k: (min if k in ("input", "output", "passive-motion") else max)(
                    [g[k] for g in gens if g[k] is not None], default=None
                )
                for k in hv
            }
            io_generic.update(generic)
            for test, dec in (
                ("input", here.input_motion),
                ("output", here.output_motion),
                ("impossible-input", here.input_rank),
                ("impossible-output", here.output_rank),
            ):
                if test not in hv:
                    continue
                d = decision(test, dec, generic[test])
                if hv[test] is None and dec.rank is not None:
                    # a motion space built on an undecided rank (IOQuantities.values)
                    d = replace(d, rank=None, note=RESTS_ON_UNDECIDED)
                decisions.append(d)
            first = samples[idx[0]].q if len(samples) else None
            named_by = (cs.screws, first)
            findings.extend(_zfb(mech, fm, here, hv, generic, tprec, named_by))
    legs = ConstraintTest.of(mech, model).decide(cs, tprec)
    if legs is not None:
        dec, wr = legs
        gen_ranks = [v.constraint for v in regular if v.constraint is not None]
        if (
            tprec.mode != "float"
            and dec.rank is not None
            and gen_ranks
            and dec.rank < max(gen_ranks)
        ):
            gen_ranks = _constraint_ranks_at(mech, model, [samples[i].q for i in idx], tprec)
        decisions.append(decision("constraint", dec, max(gen_ranks) if gen_ranks else None))
        if dec.rank is not None and gen_ranks and dec.rank < max(gen_ranks):
            g = max(gen_ranks)
            U, _s, _ = svd(np.concatenate(wr, axis=1))
            wrenches = wrenches_of(fm.float_frame, to_float(U[:, : dec.rank]), False)
            findings.append(
                ConstraintFinding(
                    joints=tuple(j for leg in mech.legs for j in leg.joints),
                    rank=dec.rank,
                    generic_rank=g,
                    wrenches=tuple(tuple(w) for w in wrenches),
                    margin=dec.margin,
                    precision=dec.precision,
                    test_precision=dec.precision,
                )
            )
    if mech.output is not None:
        findings.extend(_leg_serial(mech, model, fm, q, cs, regular, decisions))
    return findings


def _constraint_ranks_at(mech: Any, model: Any, qs: list[Any], tprec: Precision) -> list[int]:
    """The constraint test's ranks at the regular samples ``qs`` (float configurations)
    decided again at the test precision ``tprec`` (mp:N).

    A drop at q decided at mp:N is a drop only against the generic rank decided at mp:N
    too: the samples are closed and decided in float, and float does not resolve what is
    below its thresholds (a helical joint of pitch 1e-13 m/rad turns like a revolute one
    there, while mp:50 and exact see its slide), so that a float generic rank can be one
    that no configuration has at mp:N.  Called at a candidate drop only."""
    from mechsing.kinematics import KinematicModel

    mp_model = model if model.precision.mode == "mp" else KinematicModel(mech, tprec)
    test = ConstraintTest.of(mech, mp_model)
    out = []
    with tprec.context():
        for q in qs:
            qt = tprec.backend.asarray([float(x) for x in q])
            r = test.decide(closure_system(mp_model, qt, tprec), tprec)
            if r is not None and r[0].rank is not None:
                out.append(int(r[0].rank))
    return out


def _zfb(
    mech: Any,
    fm: Any,
    here: Any,
    hv: dict[str, Any],
    generic: dict[str, Any],
    tprec: Precision,
    named_by: tuple[Any, Any] = (None, None),
) -> list[Finding]:
    """The input/output findings at q (``named_by``: the SI screws at q and a regular
    sample's coordinates, whose screws, computed only for an output finding, name an
    output singularity whose moving joints show a pattern)."""
    findings: list[Finding] = []
    names = _coordinate_names(mech, fm)
    sp = here.spaces
    N = sp["N"]
    L = fm.length_scale
    for cls in ("input", "output", "passive-motion"):
        if cls not in hv:
            continue
        v, g = hv[cls], generic[cls]
        if v is None or g is None or v <= g:
            continue
        if cls == "input":  # in K cap ker T, the direction the inputs move most
            dec = here.input_motion
            space, basis = _moved(sp["zT"], sp["E"] @ N, v)
        elif cls == "output":  # in K cap ker E, the direction the output moves most
            dec = here.output_motion
            space, basis = _moved(sp["zE"], sp["T"] @ N, v)
        else:
            both = np.vstack([sp["T"] @ N / max(sp["nT"], 1e-300), sp["E"] @ N])
            dec = decide_rank(both, tprec, L, want_spaces=True, reference=1.0, native_spaces=True)
            space = basis = dec.null_space
        # the whole motion space in its canonical basis: the same rows however an SVD
        # picked its basis (the fast paths on or off)
        rate_basis = _rates_basis(fm, to_float(N @ space) if space.size else np.zeros((fm.n, 0)))
        if basis.size:  # the most telling motion where it is decided, else the first row
            x = to_float(N @ basis[:, 0])
            rates = _si_rates(fm, x)
        else:
            rates = list(rate_basis[0]) if rate_basis else [0.0] * fm.n
        twist = None
        if cls == "output" and basis.size:
            t = to_float(sp["T"] @ (N @ basis[:, 0]))
            twist = tuple(_output_si(mech, fm, t))
        # the moving joints: the support of the whole motion space (any of its rates)
        joints = tuple(
            sorted(
                {names[i] for row in (rate_basis or [rates]) for i, r in enumerate(row) if r},
                key=[j.name for j in mech.joints].index,
            )
        )
        name = None
        if cls == "output" and named_by[0] is not None:
            # a dead centre of the output (a slider-crank driven by its slider): named as
            # the leg of a crank's is (an input singularity's leg has its serial finding)
            generic_screws = None if named_by[1] is None else fm.current_screws(named_by[1])
            base = mech.output.relative_to
            on_base = [jt.name for jt in mech.joints if base in jt.between]
            name = moving_name(joints, names, named_by[0], generic_screws, float(L), on_base)
        findings.append(
            MotionFinding(
                cls,
                joints=joints,
                generic=g,
                margin=dec.margin,
                precision=dec.precision,
                test_precision=dec.precision,
                dimension=v,
                joint_rates=tuple(rates),
                output_twist=twist,
                name=name,
                joint_rate_basis=tuple(tuple(r) for r in rate_basis),
            )
        )
    for cls in ("impossible-input", "impossible-output"):
        if cls not in hv:
            continue
        v, g = hv[cls], generic[cls]
        if v is None or g is None or v >= g:
            continue
        dec = here.input_rank if cls == "impossible-input" else here.output_rank
        findings.append(
            MotionFinding(
                cls,
                joints=tuple(r.joint for r in mech.inputs) if cls == "impossible-input" else (),
                generic=g,
                margin=dec.margin,
                precision=dec.precision,
                test_precision=dec.precision,
                rank=v,
            )
        )
    return findings


def _moved(z: np.ndarray, A: np.ndarray, v: int) -> tuple[np.ndarray, np.ndarray]:
    """The motions of the columns of ``z`` that ``A`` moves (the inputs, or the output):
    the ``v`` directions it moves (its first right singular vectors: ``z`` less its
    passive motions, which ``A`` does not move and the passive-motion finding reports),
    and the unit combination it moves most, as a one-column basis.  Both empty when
    ``z`` is; the second also when no one direction is moved most (the two largest
    singular values within MOST_MOVED_RTOL: a symmetric pair of motions, where the SVD
    picks any combination)."""
    if not z.size:
        return z, z
    _u, s, vt = svd(A @ z)
    s = np.asarray(to_float(s), dtype=float)
    space = z @ vt[: min(v, len(s))].T
    if len(s) > 1 and s[1] >= (1.0 - MOST_MOVED_RTOL) * s[0]:
        return space, z[:, :0]
    return space, z @ vt[:1].T


def _rates_basis(fm: Any, X: np.ndarray) -> list[list[float]]:
    """The span of the commensurate joint-rate columns ``X`` in one canonical basis: the
    reduced row echelon form (:func:`mechsing.screws.readable.reduced_echelon`) of an
    orthonormal basis of it, each row then in SI rates as :func:`_si_rates` gives them
    (largest entry 1, first non-zero positive, rounding-level entries 0), as a serial
    finding's ``null_joint_rate_basis`` (:func:`mechsing.singularity.serial.null_rates_basis`)."""
    X = np.asarray(X, dtype=float)
    if X.size == 0:
        return []
    Q, _r = np.linalg.qr(X)
    rows, _ = reduced_echelon(Q.T)
    return [_si_rates(fm, row) for row in rows]


def _output_si(mech: Any, fm: Any, t: np.ndarray) -> list[float]:
    """The output's SI twist (a unit rotation, else a unit translation) or its point's
    unit velocity from a commensurate twist, first non-zero component positive (its sign
    otherwise the SVD's, which rounding decides)."""
    if mech.output.point is not None:
        v = fm.float_frame.velocity_back(t)
        n = float(np.linalg.norm(v))
        return [float(a) for a in first_nonzero_positive(v / n if n else v)]
    tw = fm.float_frame.twist_back(t)
    n = float(np.linalg.norm(tw[ANGULAR])) or float(np.linalg.norm(tw[LINEAR])) or 1.0
    return [float(a) for a in first_nonzero_positive(tw / n)]


def _coordinate_names(mech: Any, fm: Any) -> list[str]:
    names = [""] * fm.n
    for jk in fm.joints:
        for c in range(jk.columns.start, jk.columns.stop):
            names[c] = jk.name
    return names


def _leg_serial(
    mech: Any,
    model: Any,
    fm: Any,
    q: np.ndarray,
    cs: Any,
    regular: list[SampleValues],
    decisions: list[Decision],
) -> list[Finding]:
    """``serial`` for a leg whose own screw system loses rank (type I per leg):
    decided at the analysis precision from the closure system's screws (as the
    output chain of an open chain), against the float ranks at the samples
    (``regular``: their values, with each leg's screw matrix); each leg's rank decision
    goes into ``decisions``."""
    findings: list[Finding] = []
    legs = ConstraintTest.of(mech, fm).legs
    serial = SerialTest.of(mech, model)
    # one rule for every leg, the output chain's: the twists of the output body, or the
    # velocities of the output point when the output names one (a leg whose last joint
    # turns about the point moves it no more than one that ends before that joint: the
    # two mirror-image legs of a five-bar are judged alike)
    x = output_chain(mech, model, q, cs, True)[1] if mech.output.point is not None else None
    xf = None if x is None else np.asarray(to_float(x), dtype=float)
    for i, leg in enumerate(legs):
        with model.precision.context():
            here = serial.decide(cs.screws, leg.columns, x, model.precision, cs.scaled_screws)
        gen = here.rank.rank or 0
        samples = []
        for v in regular:
            matrix, r = v.legs[i]
            samples.append(matrix)
            if r is not None:
                gen = max(gen, r)
        decisions.append(decision(f"leg {i + 1} chain", here.rank, gen))
        span = None
        if here.rank.rank is not None and here.rank.rank < gen:
            span = generic_span([here.matrix, *samples], gen)
        f = serial_finding(fm, here, gen, leg.names, {"chain": "leg", "leg": i + 1}, xf, span)
        if regular and xf is None:
            # the leg's SI screws at a regular sample (its matrix is commensurate twists;
            # with an output point it holds the point's velocities, which name no axes:
            # such a leg keeps the generic sentence rather than a guessed name)
            back = fm.float_frame.twist_back
            generic = np.column_stack([back(c) for c in np.asarray(regular[0].legs[i][0]).T])
            f = named(f, leg.names, cs.screws[:, leg.columns], generic, float(fm.length_scale))
        if f:
            findings.append(f)
    return findings
