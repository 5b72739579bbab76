"""Configuration-space singularities: the kinematic tangent cone (local mobility and the kinematic tangent cone, c-space singularities).

Loop closure along a loop with bodies B0 .. Bn = B0: the relative twist across
joint k is ``zeta_k = s_k S_k u_k`` (current screws ``S_k = Ad(g_a) e``,
trivialised rates ``u_k``, orientation sign ``s_k``).  With ``V_k = sum_{j<k}
zeta_j`` the twist of the body before joint k relative to B0, and
``dS/dt = [V_a, S]``:

* order 1: ``sum_k zeta_k = 0``;
* order 2: ``sum_k s_k S_k w_k + sum_k [V_k, zeta_k] = 0`` (``w = du/dt``);
* order 3: ``sum_k s_k S_k a_k + sum_k ([V_k, A_k] + [dV_k, zeta_k] + [V_k, dzeta_k]) = 0``
  with ``A_k = s_k S_k w_k``, ``dzeta_k = A_k + [V_k, zeta_k]``,
  ``dV_k = sum_{j<k} dzeta_j``.

Within one multi-dof joint no bracket appears (its velocity is trivialised); a U
joint is two revolutes in sequence.  Everything is computed in the
commensurate metric (an automorphism of se(3), so brackets commute with it)
and projected on each loop's reduced orthonormal coordinates, like the
stacked closure matrix M.  A tangent x in ker M extends to order 2 iff the
quadratic part lies in range M, i.e. ``p^T Q(x) = 0`` for every left-null
vector p: these are the quadratic forms of the second-order test.

One code path for every numerical precision: the screws, loop bases, kernels,
forms, eigen-decompositions and third-order residuals are numpy float arrays
in float and object arrays of N-digit ``mpf`` at mp:N (run inside
``Precision.context()``), decided with that mode's thresholds
(:func:`mechsing.numeric.decide_rank`, :func:`~mechsing.numeric.decide_definiteness`
and the tolerances placed relative to its ``tau_hi``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.numeric import (
    Precision,
    RankDecision,
    backend_of,
    decide_definiteness,
    decide_rank,
    order3_residual_rtol,
    subspace_containment_atol,
    subspace_rank_rtol,
)
from mechsing.numeric.backend import holds_objects
from mechsing.numeric.linalg import eigh, lstsq, max_abs, norm, pinv_truncated, svd
from mechsing.screws import loop_basis

#: directions sampled on a candidate subspace for the order-3 test
_ORDER3_SAMPLES = 6
#: combinations of two forms scanned for a definite one
_PENCIL_ANGLES = 90
#: most subspaces a product of the loop groups' cones is written out as (beyond,
#: the cone is reported as not a finite union of subspaces worth listing)
MAX_CONE_PIECES = 256


@dataclass
class LoopChain:
    """A loop as a sequence of elements (coordinate columns, sign) and the
    orthonormal commensurate basis Q (6 x k) of its subalgebra."""

    elements: list[tuple[list[int], int]]
    Q: np.ndarray


def loop_chains(model: Any, cs: Any, prec: Precision | None = None) -> list[LoopChain]:
    """The elements of every canonical loop, in loop order, with the loop's basis
    at ``prec`` (float by default; call inside ``prec.context()`` at mp:N)."""
    prec = prec or Precision("float")
    out = []
    for ls in cs.loops:
        elems: list[tuple[list[int], int]] = []
        for name, sign in zip(ls.loop.joints, ls.loop.signs, strict=True):
            jk = model.joint(name)
            cols = list(range(jk.columns.start, jk.columns.stop))
            if jk.type == "U":
                parts = [([cols[0]], sign), ([cols[1]], sign)]
                elems.extend(parts if sign > 0 else parts[::-1])
            else:
                elems.append((cols, sign))
        rows = ls.basis_rows
        if prec.mode == "float":
            Q = ls.basis_float  # the closure system's: the same QR of the same float rows
        else:
            Q = loop_basis(None if rows is None else prec.asarray(rows))
        out.append(LoopChain(elems, Q))
    return out


class Expansion:
    """Higher-order closure terms at one configuration (commensurate), in the
    backend of the screws ``Ss`` (float, or mp at the working precision)."""

    def __init__(self, chains: list[LoopChain], Ss: np.ndarray) -> None:
        self.chains = chains
        arr = np.asarray(Ss)
        self.Ss = arr if holds_objects(arr) else np.asarray(arr, dtype=float)
        self.bk = backend_of(self.Ss)

    def _zetas(self, chain: LoopChain, u: np.ndarray) -> list[np.ndarray]:
        return [s * (self.Ss[:, cols] @ u[cols]) for cols, s in chain.elements]

    def bilinear(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Stacked reduced ``sum_{j<k} [zeta_j(x), zeta_k(y)]`` per loop."""
        out = []
        for ch in self.chains:
            zx, zy = self._zetas(ch, x), self._zetas(ch, y)
            acc = self.bk.zeros(6)
            V = self.bk.zeros(6)
            for k in range(len(zy)):
                acc += lie.bracket(V, zy[k])
                V = V + zx[k]
            out.append(ch.Q.T @ acc)
        return np.concatenate(out) if out else self.bk.zeros(0)

    def quadratic(self, x: np.ndarray) -> np.ndarray:
        return self.bilinear(x, x)

    def third(self, u: np.ndarray, w: np.ndarray) -> np.ndarray:
        """Stacked reduced third-order terms for tangent u and second-order rates w."""
        out = []
        for ch in self.chains:
            z = self._zetas(ch, u)
            A = self._zetas(ch, w)
            n = len(z)
            V = [self.bk.zeros(6)]
            for k in range(n - 1):
                V.append(V[-1] + z[k])
            dz = [A[k] + lie.bracket(V[k], z[k]) for k in range(n)]
            dV = [self.bk.zeros(6)]
            for k in range(n - 1):
                dV.append(dV[-1] + dz[k])
            acc = self.bk.zeros(6)
            for k in range(n):
                acc += lie.bracket(V[k], A[k]) + lie.bracket(dV[k], z[k]) + lie.bracket(V[k], dz[k])
            out.append(ch.Q.T @ acc)
        return np.concatenate(out) if out else self.bk.zeros(0)


def closure_expansion(model: Any, cs: Any, prec: Precision) -> tuple[Expansion, np.ndarray]:
    """The expansion and the stacked reduced closure matrix M at the configuration
    of the closure system ``cs``, in the numbers of ``prec`` (float or mp:N).

    Built from the closure system's commensurate screws and each loop's basis
    rows (computed at the analysis precision, exact ones included), with the
    same QR as the loops' reduced coordinates, so that the brackets and M share
    their coordinates; at the analysis precision M is the closure matrix itself.
    """
    with prec.context():
        bk = prec.backend
        Ss0 = cs.scaled_screws
        if Ss0 is None:
            Ss0 = model.frame.screws(cs.screws)
        Ss = prec.asarray(Ss0)
        chains = loop_chains(model, cs, prec)
        rows = []
        for ls, ch in zip(cs.loops, chains, strict=True):
            signs = np.zeros(model.n)
            for name, sign in zip(ls.loop.joints, ls.loop.signs, strict=True):
                signs[model.joint(name).columns] = sign
            rows.append(ch.Q.T @ (Ss * signs[None, :]))
        if model.couplings:
            # a coupling's row (the closure system's last rows) is exactly linear in the
            # coordinates (R, P, H: additive): a chain of its two columns whose elements
            # carry sign 0 and a zero basis, so its higher-order terms are zero
            C = prec.asarray(model.coupling_block(model.frame)[3::6].tolist())
            for i, ck in enumerate(model.couplings):
                chains.append(LoopChain([([ck.follower], 0), ([ck.leader], 0)], bk.zeros((6, 1))))
                rows.append(C[i : i + 1])
        M = np.concatenate(rows, axis=0) if rows else bk.zeros((0, model.n))
        return Expansion(chains, Ss), M


@dataclass
class Cone:
    """The tangent cone found by the higher-order test.

    ``subspaces``: list of orthonormal bases (n x d, commensurate joint rates,
    in the numbers of the test precision) whose union is the cone (empty list:
    the cone is {0}); ``kind``: ``"subspaces"``, ``"zero"`` (cone {0}) or
    ``"inconclusive"`` (not a finite union of subspaces, or undecided at every
    order tried); ``order``: the highest order used; ``eig_margin``: the
    eigenvalue margin of the deciding forms; ``undecided``: a definiteness fell
    between the thresholds; ``precision``: the precision of the test (``float``
    or ``mp:N``).
    """

    kind: str
    subspaces: list[np.ndarray]
    order: int
    eig_margin: float | None = None
    undecided: bool = False
    notes: list[str] = field(default_factory=list)
    precision: str = "float"


def _orth(A: np.ndarray, prec: Precision) -> np.ndarray:
    if A.shape[1] == 0:
        return A
    U, s, _ = svd(A, full_matrices=False)
    keep = np.array([x > subspace_rank_rtol(prec) * s[0] for x in s], dtype=bool)
    return U[:, keep]


def _forms(exp: Expansion, N: np.ndarray, P: np.ndarray) -> list[np.ndarray]:
    """Symmetric m x m matrices p_k^T Q(N y) for each left-null vector p_k."""
    m = N.shape[1]
    c = P.shape[1]
    F = exp.bk.zeros((c, m, m))
    for a in range(m):
        for b in range(a, m):
            v = exp.bilinear(N[:, a], N[:, b]) + exp.bilinear(N[:, b], N[:, a])
            val = P.T @ v / 2
            F[:, a, b] = val
            F[:, b, a] = val
    return [F[k] for k in range(c)]


def _form_basis(forms: list[np.ndarray], prec: Precision) -> list[np.ndarray]:
    """A basis of the span of the forms (as vectors), decided with the rank rule."""
    if not forms:
        return []
    m = forms[0].shape[0]
    bk = backend_of(*forms)
    iu = np.triu_indices(m)
    A = np.array([f[iu] for f in forms]).T
    if max_abs(A) == 0:
        return []
    U, s, _ = svd(A, full_matrices=False)
    r = sum(1 for x in s if x > prec.tolerances.tau_hi * s[0])
    out = []
    for k in range(r):
        f = bk.zeros((m, m))
        f[iu] = U[:, k] * s[k]
        f = f + f.T - np.diag(np.diag(f))
        out.append(f)
    return out


def _restrict(forms: list[np.ndarray], B: np.ndarray) -> list[np.ndarray]:
    return [B.T @ f @ B for f in forms]


def _zero_set(
    forms: list[np.ndarray], prec: Precision, depth: int = 0
) -> tuple[str, list[np.ndarray], list[bool], list[float], bool]:
    """Common zero set of quadratic forms on R^m as a union of subspaces.

    Returns (kind, subspaces as bases in R^m, silent flags, eigenvalue margins,
    undecided).  kind: "subspaces" (an empty list is the cone {0}) or "cone"
    (an indefinite form of rank >= 3: no finite union of subspaces).  A
    subspace is *silent* when order 2 says nothing transversal about it (every
    form vanishes there identically, or it is the kernel of a semidefinite
    form: a double root, where branches may be tangential); order 3 decides
    those.  The forms are float or mp arrays; ``prec`` (float or mp:N, whose
    context must be active) decides them.
    """
    if not forms:
        return "subspaces", [], [], [], False
    m = forms[0].shape[0]
    if m == 0:
        return "subspaces", [], [], [], False
    bk = backend_of(*forms)
    basis = _form_basis(forms, prec)
    if not basis:
        return "subspaces", [bk.eye(m)], [True], [], False
    decisions = [decide_definiteness(f, prec) for f in basis]
    if any(d.kind is None for d in decisions):
        return "subspaces", [], [], [], True
    # a definite combination: the cone is {0}
    for d in decisions:
        if d.kind == "definite":
            return "subspaces", [], [], [d.eig_margin or 0.0], False
    if len(basis) >= 2:
        for t in np.linspace(0, math.pi, _PENCIL_ANGLES, endpoint=False):
            d = decide_definiteness(math.cos(t) * basis[0] + math.sin(t) * basis[1], prec)
            if d.kind == "definite":
                return "subspaces", [], [], [d.eig_margin or 0.0], False
    # split on the form of lowest rank
    ranked = sorted(zip(basis, decisions, strict=True), key=lambda fd: fd[1].n_pos + fd[1].n_neg)
    f, d = ranked[0]
    rest = [g for g, _ in ranked[1:]]
    margins: list[float] = [d.eig_margin or 0.0]
    w, V = eigh(f)
    tau = prec.tolerances.tau_hi * max_abs(w)
    pos = [i for i in range(m) if w[i] > tau]
    neg = [i for i in range(m) if w[i] < -tau]
    zero = [i for i in range(m) if abs(w[i]) <= tau]
    pieces: list[tuple[np.ndarray, bool]] = []
    if not pos or not neg:
        # semidefinite: the zero set is the kernel, reached as a double root
        pieces.append((V[:, zero], True))
    elif len(pos) == 1 and len(neg) == 1:
        # rank-2 indefinite: two hyperplanes (sqrt|a| v_p . y = +- sqrt|b| v_n . y), crossing transversally
        vp = bk.sqrt(w[pos[0]]) * V[:, pos[0]]
        vn = bk.sqrt(-w[neg[0]]) * V[:, neg[0]]
        for normal in (vp - vn, vp + vn):
            pieces.append((_null_of_row(normal), False))
    else:
        return "cone", [], [], margins, False
    out: list[np.ndarray] = []
    flags: list[bool] = []
    undecided = False
    for B, silent in pieces:
        if B.shape[1] == 0:
            continue
        if rest:
            kind, subs, fl, mg, und = _zero_set(_restrict(rest, B), prec, depth + 1)
        else:
            kind, subs, fl, mg, und = "subspaces", [bk.eye(B.shape[1])], [False], [], False
        undecided = undecided or und
        margins.extend(mg)
        if kind == "cone":
            return "cone", [], [], margins, undecided
        for S, sflag in zip(subs, fl, strict=True):
            out.append(B @ S)
            flags.append(silent or sflag)
    spaces, keep_flags = _distinct_flagged(out, flags, prec)
    return "subspaces", spaces, keep_flags, margins, undecided


def _null_of_row(r: np.ndarray) -> np.ndarray:
    _, _, Vt = svd(r[None, :])
    return Vt[1:].T


def _distinct_flagged(
    spaces: list[np.ndarray], flags: list[bool], prec: Precision
) -> tuple[list[np.ndarray], list[bool]]:
    """Remove zero-dimensional, repeated and contained subspaces (a kept space is
    silent only if every space merged into it was)."""
    items = [(_orth(S, prec), f) for S, f in zip(spaces, flags, strict=True) if S.shape[1] > 0]
    items = [(S, f) for S, f in items if S.shape[1] > 0]
    atol = subspace_containment_atol(prec)
    keep: list[tuple[np.ndarray, bool]] = []
    for S, f in sorted(items, key=lambda sf: -sf[0].shape[1]):
        for i, (K, kf) in enumerate(keep):
            if norm(S - K @ (K.T @ S)) < atol:
                keep[i] = (K, kf and f)
                break
        else:
            keep.append((S, f))
    return [S for S, _ in keep], [f for _, f in keep]


def _distinct(spaces: list[np.ndarray], prec: Precision) -> list[np.ndarray]:
    return _distinct_flagged(spaces, [False] * len(spaces), prec)[0]


def tangent_cone(
    exp: Expansion,
    M: np.ndarray,
    prec: Precision,
    max_order: int = 3,
    rank: RankDecision | None = None,
) -> Cone:
    """The kinematic tangent cone at a configuration (orders 2 and 3).

    ``M``: the stacked commensurate closure matrix, in the numbers of ``exp``
    (see :func:`closure_expansion`); ``prec``: float or mp:N, the precision
    every rank, definiteness and residual of the test is computed and decided
    at (its working precision is set here); ``rank``: M's decision at ``prec``
    with its native spaces, when already made.
    """
    with prec.context():
        dec = rank or decide_rank(M, prec, 1.0, want_spaces=True, native_spaces=True)
        return _tangent_cone(exp, M, dec, prec, max_order)


def _tangent_cone(
    exp: Expansion, M: np.ndarray, dec: RankDecision, prec: Precision, max_order: int
) -> Cone:
    tp = str(prec)
    N = dec.null_space
    P = dec.left_null_space
    r = dec.rank if dec.rank is not None else dec.rank_bounds[0]
    m = N.shape[1]
    if m == 0:
        return Cone("zero", [], 1, precision=tp)
    if P.shape[1] == 0:
        return Cone("subspaces", [N], 1, precision=tp)
    grouped = _grouped_zero_set(exp, N, P, prec)
    if grouped is not None:
        kind, subs, silent, margins, undecided = grouped
    else:
        N, active = _localised_kernel(exp, N, P, prec)
        forms = _forms(exp, N[:, :active], P)
        kind, subs, silent, margins, undecided = _zero_set(forms, prec)
        if active < m:
            kind, subs, silent = _with_free_directions(kind, subs, silent, active, m, exp.bk)
    eig = min(margins) if margins else None
    if undecided:
        return Cone("inconclusive", [], 2, eig, True, ["a second-order form is undecided"], tp)
    if kind == "cone":
        return Cone(
            "inconclusive",
            [],
            2,
            eig,
            False,
            ["the second-order cone is not a finite union of subspaces"],
            tp,
        )
    spaces = [N @ S for S in subs]
    if not spaces:
        return Cone("zero", [], 2, eig, precision=tp)
    # order 3 only where order 2 is silent (forms vanish identically, or a double root)
    order = 2
    if max_order >= 3 and any(silent):
        kept: list[np.ndarray] = []
        for W, quiet in zip(spaces, silent, strict=True):
            if not quiet:
                kept.append(W)
                continue
            order = 3
            verdict = _order3(exp, M, r, N, P, W, prec)
            if verdict == "keep":
                kept.append(W)
            elif verdict == "mixed":
                return Cone(
                    "inconclusive",
                    [],
                    3,
                    eig,
                    False,
                    [
                        "the third-order test keeps some directions of a candidate branch and not others"
                    ],
                    tp,
                )
        spaces = kept
        if not spaces:
            return Cone("zero", [], order, eig, precision=tp)
    elif any(silent):
        return Cone(
            "inconclusive", [], 2, eig, False, ["order 2 is silent on a candidate branch"], tp
        )
    return Cone("subspaces", _distinct(spaces, prec), order, eig, precision=tp)


def _grouped_zero_set(
    exp: Expansion, N: np.ndarray, P: np.ndarray, prec: Precision
) -> tuple[str, list[np.ndarray], list[bool], list[float], bool] | None:
    """The second-order zero set group by group, when the closure system splits.

    Loops that share no joint (directly or through other loops) form independent
    groups: a kernel vector or a left-null vector of a block-diagonal closure matrix
    (as :func:`~mechsing.numeric.blocks.block_svd` gives them) lives in one group,
    the forms of a group's left-null vectors involve only its own loops and kernel
    vectors, and the zero set is the product of the groups' zero sets (a group
    without left-null vector is regular: its whole kernel).  So a mechanism of a
    thousand loops costs a thousand small tests, not one test on the whole kernel.
    Returns None when the kernel or the left-null vectors mix groups (a dense
    factorisation, or one group): the caller then works on the whole kernel.
    """
    if exp.bk.name != "float" or len(exp.chains) < 2:
        return None
    rows, starts = 0, []
    for ch in exp.chains:
        starts.append(rows)
        rows += ch.Q.shape[1]
    # the groups: chains linked by a shared joint column
    parent = list(range(len(exp.chains)))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owner: dict[int, int] = {}
    for i, ch in enumerate(exp.chains):
        for cols, _ in ch.elements:
            for c in cols:
                if c in owner:
                    parent[find(i)] = find(owner[c])
                else:
                    owner[c] = i
    group_of_chain = [find(i) for i in range(len(exp.chains))]
    groups = sorted(set(group_of_chain))
    if len(groups) < 2:
        return None
    col_group = np.full(N.shape[0], -1)
    for c, i in owner.items():
        col_group[c] = group_of_chain[i]
    row_group = np.empty(rows, dtype=int)
    for i, ch in enumerate(exp.chains):
        row_group[starts[i] : starts[i] + ch.Q.shape[1]] = group_of_chain[i]
    Nf, Pf = np.asarray(N, dtype=float), np.asarray(P, dtype=float)

    def owner_group(vec: np.ndarray, where: np.ndarray) -> int | None:
        hit = np.unique(where[vec != 0.0])
        return int(hit[0]) if len(hit) == 1 else (-1 if len(hit) == 0 else None)

    kgroup = [owner_group(Nf[:, j], col_group) for j in range(Nf.shape[1])]
    pgroup = [owner_group(Pf[:, j], row_group) for j in range(Pf.shape[1])]
    if any(g is None for g in kgroup + pgroup) or -1 in pgroup:
        return None
    m = N.shape[1]
    factors: list[tuple[list[int], list[np.ndarray], list[bool]]] = []
    margins: list[float] = []
    undecided = False
    for g in groups:
        pcols = [j for j, h in enumerate(pgroup) if h == g]
        kcols = [j for j, h in enumerate(kgroup) if h == g]
        if not pcols or not kcols:
            continue
        chains = [i for i, h in enumerate(group_of_chain) if h == g]
        grows = np.concatenate(
            [np.arange(starts[i], starts[i] + exp.chains[i].Q.shape[1]) for i in chains]
        )
        sub = Expansion([exp.chains[i] for i in chains], exp.Ss)
        forms = _forms(sub, N[:, kcols], P[np.ix_(grows, pcols)])
        kind, subs, silent, mg, und = _zero_set(forms, prec)
        margins.extend(mg)
        undecided = undecided or und
        if kind == "cone":
            return "cone", [], [], margins, undecided
        factors.append((kcols, subs or [exp.bk.zeros((len(kcols), 0))], silent or [False]))
    if undecided:
        return "subspaces", [], [], margins, True
    count = 1
    for _, subs, _ in factors:
        count *= len(subs)
    if count > MAX_CONE_PIECES:
        return "cone", [], [], margins, False
    tested = {j for kcols, _, _ in factors for j in kcols}
    free = [j for j in range(m) if j not in tested]
    pieces: list[tuple[list[tuple[list[int], np.ndarray]], bool]] = [([], False)]
    for kcols, subs, flags in factors:
        pieces = [
            (done + [(kcols, S)], quiet or flag)
            for done, quiet in pieces
            for S, flag in zip(subs, flags, strict=True)
        ]
    out, out_flags = [], []
    for parts, quiet in pieces:
        width = sum(S.shape[1] for _, S in parts) + len(free)
        B = exp.bk.zeros((m, width))
        at = 0
        for kcols, S in parts:
            B[np.ix_(kcols, range(at, at + S.shape[1]))] = S
            at += S.shape[1]
        for j in free:
            B[j, at] = 1.0
            at += 1
        out.append(B)
        out_flags.append(quiet)
    if all(B.shape[1] == 0 for B in out):
        return "subspaces", [], [], margins, False
    return "subspaces", out, out_flags, margins, False


def _localised_kernel(
    exp: Expansion, N: np.ndarray, P: np.ndarray, prec: Precision
) -> tuple[np.ndarray, int]:
    """The kernel in a basis whose first ``active`` columns are the only ones that
    move a joint of a loop the left-null vectors P see.

    The second-order forms ``P^T Q(x, y)`` involve only those loops (a loop's
    term is made of its own joints' rates), so they vanish whenever x or y is
    one of the other columns, which are zero on every such joint (exactly, when
    the closure matrix splits into blocks; to the precision otherwise).  A
    mechanism of many loops in which one loop is singular thus gets forms of
    that loop's size, not of the whole kernel's.  Returns (N, m) unchanged when
    no column can be set aside.
    """
    m = N.shape[1]
    rows = 0
    touched: list[int] = []
    seen = P.shape[0] and max_abs(P)
    for ch in exp.chains:
        k = ch.Q.shape[1]
        if seen and max_abs(P[rows : rows + k]) > subspace_rank_rtol(prec) * seen:
            touched.extend(c for cols, _ in ch.elements for c in cols)
        rows += k
    cols = sorted(set(touched))
    if not cols or len(cols) >= N.shape[0]:
        return N, m
    _, s, Vt = svd(N[cols], full_matrices=True)
    top = s[0] if len(s) else 0
    active = sum(1 for x in s if top and x > subspace_rank_rtol(prec) * top)
    if active == 0 or active == m:
        return N, m
    return N @ Vt.T, active


def _with_free_directions(
    kind: str, subs: list[np.ndarray], silent: list[bool], active: int, m: int, bk: Any
) -> tuple[str, list[np.ndarray], list[bool]]:
    """The zero set of forms that vanish on the last ``m - active`` coordinates:
    each subspace of the first ``active`` ones times all of the others (the cone
    {0} of the active part gives the others alone)."""
    if kind != "subspaces":
        return kind, subs, silent
    free = m - active
    pieces = subs or [bk.zeros((active, 0))]
    flags = silent or [False]
    out = []
    for S in pieces:
        B = bk.zeros((m, S.shape[1] + free))
        B[:active, : S.shape[1]] = S
        B[active:, S.shape[1] :] = bk.eye(free)
        out.append(B)
    return kind, out, list(flags)


def _order3(
    exp: Expansion,
    M: np.ndarray,
    r: int,
    N: np.ndarray,
    P: np.ndarray,
    W: np.ndarray,
    prec: Precision,
) -> str:
    """Does every direction of W extend to order 3 ("keep"), none ("drop"), or mixed?

    The second-order rates solve ``M w = -Q(x)`` with the pseudo-inverse of M's
    decided rank-``r`` part (its dropped singular values are zero to the
    precision, never inverted)."""
    rng = np.random.default_rng(1)
    U, s, Vt = svd(M)
    Mp = pinv_truncated(U, s, Vt, r)
    tol = order3_residual_rtol(prec)
    ok = 0
    bad = 0
    for _ in range(_ORDER3_SAMPLES):
        x = W @ rng.normal(size=W.shape[1])
        x = x / norm(x)
        wp = -Mp @ exp.quadratic(x)
        t0 = exp.third(x, wp)
        base = P.T @ t0
        Lz = np.stack(
            [P.T @ (exp.third(x, wp + N[:, j]) - t0) for j in range(N.shape[1])],
            axis=1,
        )
        scale = max(1.0, max_abs(Lz))
        resid = base + Lz @ lstsq(Lz, -base) if Lz.size else base
        if max_abs(resid) <= tol * scale:
            ok += 1
        else:
            bad += 1
    if bad == 0:
        return "keep"
    if ok == 0:
        return "drop"
    return "mixed"
