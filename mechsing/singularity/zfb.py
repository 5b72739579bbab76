"""Input/output and constraint singularities: Zlatanov-Fenton-Benhabib's classes from
the complete velocity equation, and the legs' constraint wrenches.

Complete velocity equation.  With ``N`` an orthonormal basis of the solution
space K of the closure equations (commensurate joint rates), the output twist
is ``t = T u`` (the output body relative to ``relative_to``, through a tree
path; or the velocity of the output point) and the inputs ``u_a = E u``.  On
one basis of K (Zlatanov, Fenton, Benhabib 1995):

* ``input`` (RI): dim E(K cap ker T) -- input rates with the output still;
* ``output`` (RO): dim T(K cap ker E) -- output motion with the inputs locked;
* ``passive-motion`` (RPM): dim (K cap ker E cap ker T);
* ``impossible-input`` (II): rank E N below its generic value;
* ``impossible-output`` (IO): rank T N below its generic value.

Each is measured against its value at regular configurations of the branch
(the nearby samples), so what holds everywhere (an idle spin, redundancy)
is a property, not a singularity.

Every test whose ingredients the file has is run (:func:`tests_run`): with inputs and no
output, ``impossible-input`` (an input loses its independent rate, as at a toggle of
the driving joint: rank E N alone); with an output and no inputs, ``impossible-output``
(rank T N alone).  :func:`tests_not_run` says which were not, and why, in the words
every output format shows.

Constraint singularity: each leg's twist system T_i and its reciprocal
(constraint) wrench system W_i; the legs' combined constraint system
``W_c = sum W_i`` losing rank below its generic value lets the output move
outside its generic motion type (Zlatanov, Bonev, Gosselin 2002).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.kinematics.chains import tree_chain
from mechsing.numeric import (
    Precision,
    RankDecision,
    decide_rank,
    field_product,
    rank_difference,
    spectral_norm,
    svd,
)
from mechsing.screws import chain_matrix

__all__ = [
    "IO_TESTS",
    "IOQuantities",
    "io_quantities",
    "leg_constraint_rank",
    "leg_path",
    "output_chain",
    "not_run_sentences",
    "tests_not_run",
    "tests_run",
]

#: the input/output tests, in the order every output lists them
IO_TESTS = ("input", "output", "passive-motion", "impossible-input", "impossible-output")
#: the tests that need the output (the constraint test and the legs' serial test too)
_NEED_OUTPUT = ("input", "output", "passive-motion", "impossible-output", "constraint", "serial")
#: the tests that need inputs
_NEED_INPUTS = ("input", "output", "passive-motion", "impossible-input")


def tests_run(mech: Any) -> tuple[str, ...]:
    """The input/output tests (:data:`IO_TESTS`) whose ingredients the mechanism has:
    all five with inputs and an output; ``impossible-input`` with inputs alone (the rank
    of the inputs on the motion space: where an input loses its independent rate);
    ``impossible-output`` with an output alone."""
    has_in, has_out = bool(mech.inputs), mech.output is not None
    return tuple(
        t
        for t in IO_TESTS
        if (has_in or t not in _NEED_INPUTS) and (has_out or t not in _NEED_OUTPUT)
    )


def tests_not_run(mech: Any) -> tuple[tuple[tuple[str, ...], str], ...]:
    """The tests a closed chain could not run for want of inputs or an output, with the
    reason: ((tests, reason), ...), empty when the file has both (or no loop: an open
    chain's only test is its output chain's rank).  The one place these words live."""
    if not mech.loops:
        return ()
    has_in, has_out = bool(mech.inputs), mech.output is not None
    if has_in and has_out:
        return ()
    if not has_in and not has_out:
        return (
            (
                (*IO_TESTS, "constraint"),
                "no inputs and no output: the input and output tests were not run",
            ),
        )
    if not has_out:
        return ((_NEED_OUTPUT, "no output: the output tests were not run"),)
    return ((_NEED_INPUTS, "no inputs: the input tests were not run"),)


def not_run_sentences(mech: Any) -> list[str]:
    """:func:`tests_not_run` as the sentences every text format shows: ``no output: the
    output tests were not run (input, output, ...)``."""
    return [f"{why} ({', '.join(tests)})" for tests, why in tests_not_run(mech)]


_FLOAT = Precision("float")


@dataclass
class IOQuantities:
    """Dimensions of the ZFB subspaces at one configuration, decided at one
    precision (float, or mp:N with every space an N-digit object array)."""

    input_motion: RankDecision  # E applied to K cap ker T
    output_motion: RankDecision  # T applied to K cap ker E
    passive_motion: int | None  # dim K cap ker E cap ker T
    input_rank: RankDecision  # rank E N
    output_rank: RankDecision  # rank T N
    spaces: dict[str, Any]
    #: the tests these quantities answer (:func:`tests_run`: all five unless the
    #: mechanism has no output or no inputs)
    run: tuple[str, ...] = IO_TESTS

    def values(self) -> dict[str, int | None]:
        """The dimensions of the tests run; None where undecided.  K cap ker T rests on
        the decision of rank T N and K cap ker E on that of rank E N: when those are
        undecided, so are the motion spaces built on them (their kernel was taken at a
        guessed rank)."""
        out_ok = self.output_rank.rank is not None
        in_ok = self.input_rank.rank is not None
        every = {
            "input": self.input_motion.rank if out_ok else None,
            "output": self.output_motion.rank if in_ok else None,
            "passive-motion": self.passive_motion if (in_ok and out_ok) else None,
            "impossible-input": self.input_rank.rank,
            "impossible-output": self.output_rank.rank,
        }
        return {t: every[t] for t in self.run}


def output_rows(
    mech: Any, model: Any, q: np.ndarray, S: np.ndarray, poses: dict[str, np.ndarray]
) -> np.ndarray | None:
    """Commensurate output map T (6 x n twists, or 3 x n point velocities / L), in
    the model's numbers (the same L and centroid as its closure rows)."""
    out = mech.output
    if out is None:
        return None
    chain = tree_chain(model, out.body, out.relative_to)
    x = None
    if out.point is not None:
        x0 = model.point_array(out.point)
        x = lie.act_point(poses[out.body], x0)
    return chain_matrix(model, S, None, x, chain.signs)


def output_chain(mech: Any, model: Any, q: np.ndarray, cs: Any, point: bool) -> tuple[Any, Any]:
    """The output chain's commensurate rows at the closed configuration ``q`` from its
    closure system ``cs`` (in the model's numbers): its twists, or with ``point`` the
    output point's velocities (:func:`output_rows`), and that point's position (None
    without ``point``).  Built once per closure system: the input/output test and the
    output motion both ask for them."""
    key = ("output chain", point)
    got = cs.shared.get(key)
    if got is None:
        out = mech.output
        with model.precision.context():
            poses = model.poses(q) if point or cs.screws is None else None
            S = cs.screws if cs.screws is not None else model.current_screws(q, poses)
            chain = tree_chain(model, out.body, out.relative_to)
            x = lie.act_point(poses[out.body], model.point_array(out.point)) if point else None
            got = cs.shared[key] = (chain_matrix(model, S, None, x, chain.signs), x)
    return got


def input_rows(mech: Any, model: Any) -> np.ndarray | None:
    """Selection E of the actuated coordinates (rows), commensurate (lengths / L)."""
    coords = mech.input_coordinates()
    if not coords:
        return None
    E = np.zeros((len(coords), model.n))
    for i, (j, k) in enumerate(coords):
        E[i, model.joint(j).columns.start + k] = 1.0
    return E


def _null(A: np.ndarray, L: float, prec: Precision, reference: Any = None) -> np.ndarray:
    if A.shape[0] == 0:
        return prec.backend.eye(A.shape[1])
    dec = decide_rank(A, prec, L, want_spaces=True, reference=reference, native_spaces=True)
    return dec.null_space


def io_quantities(
    mech: Any,
    model: Any,
    q: np.ndarray,
    N: np.ndarray,
    prec: Precision = _FLOAT,
    screws: np.ndarray | None = None,
    kernel: RankDecision | None = None,
    cs: Any = None,
) -> IOQuantities | None:
    """ZFB quantities at q, computed and decided at ``prec`` (float or mp:N).

    ``N``: commensurate kernel basis of the closure system (n x m) in the numbers
    of ``prec``; ``screws``: the current screws at q when already known (the
    closure system's); the output map is built in the model's numbers (exact
    ones included) and then converted, so that it shares L and the centroid
    with the closure rows N was computed from.  ``kernel``: N's decision; when it
    was taken from an exact one (``N = Z C``, Z exact), the products ``T N`` and
    ``E N`` are formed as ``(T Z) C`` with ``T Z`` exact in the data's number field, so
    that what vanishes exactly is exactly zero.  ``cs``: the closure system at q whose
    screws ``screws`` are (the output rows are then shared, :func:`output_chain`).
    """
    run = tests_run(mech)
    if not run:
        return None
    if mech.output is None:
        T = None
    elif cs is not None and screws is cs.screws:
        T = output_chain(mech, model, q, cs, mech.output.point is not None)[0]
    else:
        with model.precision.context():
            poses = model.poses(q) if screws is None or mech.output.point is not None else {}
            S = model.current_screws(q, poses) if screws is None else screws
            T = output_rows(mech, model, q, S, poses)
    E = input_rows(mech, model)
    # a missing side enters as no rows: its rank is 0 and only the other side's
    # test is read (:attr:`IOQuantities.run`)
    if T is None:
        T = np.zeros((0, model.n))
    if E is None:
        E = np.zeros((0, model.n))
    products = None
    if T.shape[0] and E.shape[0] and kernel is not None and kernel.kernel_coefficients is not None:
        Z, C = kernel.exact_null_space, kernel.kernel_coefficients
        TZ = field_product(T, Z)
        EZ = field_product(E.astype(int).astype(object), Z)
        if TZ is not None and EZ is not None:
            with prec.context():
                products = (prec.asarray(TZ) @ C, prec.asarray(EZ) @ C)
    with prec.context():
        T = prec.asarray(T) if T.shape[0] else prec.backend.zeros((0, model.n))
        q_ = _io_quantities(T, E, N, model.length_scale, prec, products)
    q_.run = run
    return q_


def _io_quantities(
    T: np.ndarray,
    E: np.ndarray,
    N: np.ndarray,
    L: float,
    prec: Precision,
    products: tuple[np.ndarray, np.ndarray] | None = None,
) -> IOQuantities:
    bk = prec.backend
    m = N.shape[1]
    TN, EN = products if products is not None else (T @ N, E @ N)
    # thresholds relative to the operators T and E themselves (N and the z are
    # orthonormal), so a product that vanishes is rank 0, not rounding noise
    nT = spectral_norm(T)
    nE = 1.0
    # every dimension is a difference of ranks of TN, EN and [TN; EN], each decided on
    # its own singular values: their rounding is eps times the matrix, whereas a kernel
    # of TN (or EN) computed near a singularity at distance d is off by eps / d, and
    # E applied to it would turn that error into a false input (output) motion
    if prec.mode == "float" and m:
        # the ranks with their kernels (below): in float a decision with spaces has the
        # singular values, rank and margin of the one without
        rT = decide_rank(TN, prec, L, want_spaces=True, reference=nT)
        rE = decide_rank(EN, prec, L, want_spaces=True, reference=nE)
    else:
        rT = decide_rank(TN, prec, L, reference=nT)
        rE = decide_rank(EN, prec, L, reference=nE)
    both = np.vstack([TN / max(nT, 1e-300), EN]) if m else np.zeros((0, 0))
    if m:
        rB = decide_rank(both, prec, L, reference=1.0)
        passive = None if rB.rank is None else m - rB.rank
    else:
        rB = decide_rank(np.zeros((T.shape[0] + E.shape[0], 0)), prec, L)
        passive = 0
    # witnesses of the motions (for the joint rates of a finding): the kernels at the
    # decided (or guessed) ranks
    if prec.mode == "float" and m:
        zT, zE = rT.null_space, rE.null_space
    else:
        zT = _null(TN, L, prec, nT) if m else bk.zeros((0, 0))
        zE = _null(EN, L, prec, nE) if m else bk.zeros((0, 0))
    return IOQuantities(
        rank_difference(rB, rT),  # dim E(K cap ker T) = rank [TN; EN] - rank TN
        rank_difference(rB, rE),  # dim T(K cap ker E) = rank [TN; EN] - rank EN
        passive,
        rE,
        rT,
        {"T": T, "E": E, "N": N, "zT": zT, "zE": zE, "nT": nT},
    )


def leg_path(mech: Any, leg: Any, base: str, body: str) -> list[tuple[str, int]]:
    """A path of (joint, sign) from base to body through the leg's joints (BFS, file order)."""
    from collections import deque

    joints = [mech.joint(j) for j in leg.joints]
    prev: dict[str, tuple[str, str, int] | None] = {base: None}
    queue = deque([base])
    while queue:
        x = queue.popleft()
        if x == body:
            break
        for j in joints:
            a, b = j.between
            if x not in (a, b):
                continue
            y = b if x == a else a
            if y in prev or (y == base):
                continue
            prev[y] = (x, j.name, 1 if x == a else -1)
            queue.append(y)
    path: list[tuple[str, int]] = []
    x = body
    while prev.get(x) is not None:
        px, jn, sg = prev[x]
        path.append((jn, sg))
        x = px
    return path[::-1]


def leg_constraint_rank(
    mech: Any, model: Any, q: np.ndarray, cs: Any, prec: Precision = _FLOAT
) -> tuple[RankDecision, list[np.ndarray]] | None:
    """Rank of the legs' combined constraint wrench system W_c, and each leg's
    constraint wrenches (commensurate vectors y with y . twist = 0 for every
    twist the leg lets the output make), computed and decided at ``prec``
    (float or mp:N) from the closure system ``cs`` at q.

    A leg's twist system is ``T_path K_leg``: the output twists through a path
    of the leg's joints from the base, over the solutions ``K_leg`` of the
    leg's own inner loops (for a serial leg, simply the span of its screws).
    """
    out = mech.output
    if out is None or len(mech.legs) < 2:
        return None
    with model.precision.context():
        Ss0 = cs.scaled_screws if cs.scaled_screws is not None else model.frame.screws(cs.screws)
    L = model.length_scale
    with prec.context():
        Ss = prec.asarray(Ss0)
        wrenches = []
        for leg in mech.legs:
            legset = set(leg.joints)
            cols = [
                c
                for j in leg.joints
                for c in range(model.joint(j).columns.start, model.joint(j).columns.stop)
            ]
            inner = [ls.matrix for ls in cs.loops if set(ls.loop.joints) <= legset]
            if inner:
                Mi = prec.asarray(np.concatenate(inner, axis=0))[:, cols]
                K = _null(Mi, L, prec)
            else:
                K = prec.backend.eye(len(cols))
            coef = np.zeros(model.n)
            for jn, sg in leg_path(mech, leg, out.relative_to, out.body):
                coef[model.joint(jn).columns] = sg
            Tl = (Ss * coef[None, :])[:, cols] @ K
            dec = decide_rank(Tl, prec, L)
            r = dec.rank if dec.rank is not None else dec.rank_bounds[1]
            U, _s, _ = svd(Tl)
            wrenches.append(U[:, r:])
        Wc = np.concatenate(wrenches, axis=1) if wrenches else prec.backend.zeros((6, 0))
        return decide_rank(Wc.T if Wc.shape[1] else np.zeros((0, 6)), prec, L), wrenches
