"""The inverse dynamics of a closed chain: the inputs' efforts for a motion of the inputs.

The mechanism's spanning tree carries the bodies (:class:`~mechsing.kinetics.tree.TreeDynamics`
on the tree's joints: a chord joint moves no body of its own); the loops close it.  The
loops' rows are the closure system's, ``A`` (:func:`mechsing.screws.closure_system`: each
loop's signed screws in coordinates of its subalgebra, independent rows; the same ``A`` the
motion test and the statics use, :func:`mechsing.statics.motion_matrices`), its length
columns divided by ``L`` so that it acts on SI rates (``A`` is commensurate):

* velocity: ``A qd = 0`` with the inputs' rates given: ``[A; E] qd = [0; u]``;
* acceleration: ``A qdd + Adot qd = 0``, where the rate of each loop's screw is the Lie
  bracket of the twist of the joint's first body with it (``s_k' = [xi_a, s_k]``: the
  closure written at acceleration level on the Lie algebra), the loop's sum of them taken
  to its rows' coordinates as its screws are (:class:`ClosureRows`);
* efforts: the tree's efforts ``tau = M qdd + bias`` (zero on the chords' coordinates) are
  balanced by the inputs' efforts and the loops' constraint wrenches (the multipliers
  ``lambda``, in the coordinates of ``A``'s rows): ``E^T tau_in + A^T lambda = tau``
  (virtual work), solved in the least-squares sense in float; a residual means the inputs
  cannot produce the motion's efforts (a Type II singularity), and its size is reported.
  In mp:N and exact the systems are solved in that arithmetic (normal equations,
  :meth:`mechsing.numeric.backend.Backend.solve`).

**The crossing condition at a Type II singularity** (Briot & Arakelian, IJRR 2008).
There ``[A; E]`` loses rank: the inputs leave twists ``v`` free (``A v = 0``, ``E v = 0``)
and the balance's matrix ``[E^T A^T]`` has a kernel.  The balance has a solution iff the
tree's efforts do no power on the free twists, ``v . tau = 0``: then the motion can cross
with bounded (not unique) efforts; otherwise they grow as one over the distance to the
singularity.  Float's least squares report the balance's residual.  In mp:N and exact the
rank is decided with the precision's margins (:meth:`ClosureRows.type_ii`), the motion and
the balance are made unique (the least-squares rates and accelerations, the inputs'
efforts of least norm: :class:`TypeII`), and the condition is decided on the residual (the
part of ``tau`` along the free twists over ``tau``) with the precision's margins, exactly
in exact mode; inputs' rates or accelerations that are not a motion of the mechanism
there (at a Type II the inputs cannot move independently) are refused with the reason.

Forward dynamics (:func:`closed_forward`): with ``N`` the passive motions of unit input
rates (``[A; E] N = [0; 1]``) and ``qdd_0`` the acceleration of zero input accelerations,
every admissible acceleration is ``qdd_0 + N udd``, and virtual work along the admissible
motions (``N^T A^T = 0``, ``N^T E^T = 1``) gives the inputs' equation
``N^T M N udd = tau_in - N^T (M qdd_0 + bias)``: the mass matrix reduced to the inputs.
At a Type II singularity (decided in mp:N and exact) it is refused with the reason.

Owns :class:`ClosureRows`, :class:`TypeII`, :func:`closed_inverse` and
:func:`closed_forward`, and their parts: a motion driven by any rows of the rates
(:func:`driven_motion`: a sweep's timed motion drives its swept coordinate) and the
effort balance with the crossing condition (:func:`balance`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import mpmath
import numpy as np

from mechsing import lie
from mechsing.errors import UserError
from mechsing.numeric import to_float

__all__ = [
    "ClosedMotion",
    "ClosureRows",
    "TypeII",
    "balance",
    "closed_forward",
    "closed_inverse",
    "driven_motion",
]


@dataclass(frozen=True)
class ClosedMotion:
    """A closed chain's motion and efforts at one configuration (SI, coordinate order):
    every coordinate's rate and acceleration, every coordinate's effort (the inputs'
    efforts on the inputs, 0 on the passive joints), the loops' multipliers (a wrench per
    loop, at the ground origin) and the relative residual of the effort balance."""

    qd: np.ndarray
    qdd: np.ndarray
    efforts: np.ndarray
    multipliers: np.ndarray
    residual: float
    tree_efforts: np.ndarray
    #: the Type II crossing condition: the inputs can produce the motion's efforts (at a
    #: Type II in mp:N and exact decided on the power of the dynamic wrench on the
    #: uncontrolled twists; elsewhere the residual below ``CROSSING_RTOL``)
    possible: bool = True


@dataclass(frozen=True)
class TypeII:
    """A Type II configuration in mp:N or exact: ``free`` the uncontrolled twists (rows,
    SI rates: ``A v = 0``, ``E v = 0``) and ``kernel`` the inputs' part of the balance's
    kernel (rows ``(z_E, 0)`` of the ``z = (z_E, z_A)`` with ``[E^T A^T] z = 0``: inputs'
    efforts that the loops balance alone).  The motion is made unique by asking it
    orthogonal to the free twists (the least-squares rates), the efforts by asking the
    inputs' orthogonal to ``z_E`` (the inputs' efforts of least norm: a choice that does
    not depend on the coordinates of the loops' rows, as the multipliers' norm does)."""

    free: np.ndarray
    kernel: np.ndarray


class ClosureRows:
    """The closure's rows at the closed ``q`` in the model's precision: :attr:`A` (r x n,
    acting on SI rates) from the one closure system, and :meth:`rate` (``Adot qd``)."""

    def __init__(self, td: Any, q: np.ndarray) -> None:
        from mechsing.screws import closure_system

        model = td.model
        self.td, self.q, self.model = td, q, model
        with model.precision.context():
            cs = closure_system(model, q)
            A = np.array(cs.matrix, copy=True)
            lengths = np.asarray(model.frame.length_columns, dtype=bool)
            if np.any(lengths):  # commensurate length columns are times L: back to SI
                A[:, lengths] = A[:, lengths] / model.length_scale
        self.A = A
        self.commensurate = cs.matrix
        self.loops = cs.loops
        self.screws = cs.screws  # SI current screws at the ground origin (6 x n)

    def _coordinates(self, ls: Any, x: np.ndarray) -> np.ndarray:
        """A twist's coordinates in the rows of the loop ``ls``, as its screws' are."""
        from mechsing.screws.systems import reduced_coordinates

        model = self.model
        xs = model.frame.twists(x[:, None])
        if ls.basis_rows is None:  # undecided subgroup: the six rows of se(3)
            return xs[:, 0]
        if model.backend.name == "float":
            return (ls.basis_float.T @ xs)[:, 0]
        return reduced_coordinates(model, ls.basis_rows, xs)[:, 0]

    def rate(self, qd: np.ndarray) -> np.ndarray:
        """``Adot qd``: each loop's ``sum_k sigma_k [xi_(a_k), s_k] qd_k`` in its rows."""
        model, td = self.model, self.td
        with model.precision.context():
            _, xi, _, _ = td.motion(self.q, qd, None, False)
            out = []
            for ls in self.loops:
                total = None
                for name, sign in zip(ls.loop.joints, ls.loop.signs, strict=True):
                    jk = model.joint(name)
                    k = jk.columns.start
                    term = lie.bracket(xi[jk.a], self.screws[:, k]) * (qd[k] * sign)
                    total = term if total is None else total + term
                out.append(self._coordinates(ls, total))
            return np.concatenate(out) if out else model.backend.zeros(0)

    def type_ii(self, inputs: list[int]) -> TypeII | None:
        """In mp:N and exact, where the inputs leave a motion free (``[A; E]`` below full
        column rank, decided with the precision's margins on the commensurate rows): the
        uncontrolled twists and the balance's kernel (:class:`TypeII`); None at a regular
        configuration, and always in float (its least squares give the same motion and
        balance).  Refused when the rank is too close to call at these digits."""
        from mechsing.numeric import decide_rank

        model = self.model
        if model.backend.name == "float":
            return None
        with model.precision.context():
            L = model.length_scale
            E = np.array(self.selector(inputs), copy=True)
            lengths = np.asarray(model.frame.length_columns, dtype=bool)
            if np.any(lengths):  # a commensurate length rate is the rate / L: its row times L
                E[:, lengths] = E[:, lengths] * L
            dec = decide_rank(
                np.vstack([self.commensurate, E]), model.precision, float(to_float(L))
            )
            if dec.rank is None:
                raise UserError(
                    "the inputs come too close to leaving a motion of the mechanism free here "
                    f"(a Type II singularity) to decide at {model.precision}: more digits "
                    "(--precision mp:N with a larger N) decide it"
                )
            if dec.rank == model.n:
                return None
            # the same spaces of the SI rows (a change of units of the columns keeps the rank)
            S = self.selector(inputs)
            K = np.vstack([self.A, S])
            free = model.backend.null_space(K, dec.rank)
            kernel = np.array(model.backend.null_space(np.vstack([S, self.A]).T, dec.rank))
            kernel[:, len(inputs) :] = 0  # the inputs' part (the multipliers' depends on A's rows)
        return TypeII(free, kernel)

    def selector(self, inputs: list[int]) -> np.ndarray:
        """The rows selecting the coordinates ``inputs`` (in the model's numbers)."""
        E = np.zeros((len(inputs), self.model.n), dtype=int)
        E[np.arange(len(inputs)), inputs] = 1
        return self.model.asarray(E)


def _solve(backend: Any, A: np.ndarray, b: np.ndarray, what: str) -> tuple[np.ndarray, float]:
    """x with ``A x = b`` (least squares) and the relative residual (float)."""
    if backend.name == "float":
        A, b = np.asarray(A, dtype=float), np.asarray(b, dtype=float)
        x, *_ = np.linalg.lstsq(A, b, rcond=None)
        scale = max(float(np.linalg.norm(b)), float(np.linalg.norm(A) * np.linalg.norm(x)), 1e-300)
        return x, float(np.linalg.norm(A @ x - b)) / scale
    try:
        x = backend.solve(A, b)
    except (ZeroDivisionError, ValueError, ArithmeticError) as exc:
        raise UserError(
            f"the {what} is singular here (a Type II singularity: the inputs' efforts are "
            "unbounded or not unique); --precision float gives the least-squares efforts and "
            "the crossing condition's residual"
        ) from exc

    r = A.dot(x) - b
    return x, _norm(r) / max(_norm(b), 1e-300)


def driven_motion(
    rows: ClosureRows,
    G: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    drift: Any = None,
    free: TypeII | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Every coordinate's rate and acceleration at the closed configuration of ``rows``
    when the rows ``G`` of the rates are driven: ``[A; G] qd = [0; v]`` and
    ``[A; G] qdd = [-Adot qd; a - drift(qd)]`` (``drift``: the part of the driven rows'
    second derivative that is not ``G qdd``, a function of the rates; None: rows of
    constant coefficients, the coordinates themselves).  At a Type II configuration
    (``free``, mp:N and exact) the rates and accelerations orthogonal to the uncontrolled
    twists, refused when the driven rows' values are not a motion of the mechanism there."""
    model = rows.model
    with model.precision.context():
        K = np.vstack([rows.A, G] + ([] if free is None else [free.free]))
        zeros = model.backend.zeros(rows.A.shape[0])
        pad = [] if free is None else [model.backend.zeros(free.free.shape[0])]
        qd, res_v = _solve(
            model.backend, K, np.concatenate([zeros, v, *pad]), "closure at velocity level"
        )
        rhs = a if drift is None else a - drift(qd)
        qdd, res_a = _solve(
            model.backend,
            K,
            np.concatenate([-rows.rate(qd), rhs, *pad]),
            "closure at acceleration level",
        )
        if free is not None:
            for what, x, b in (
                ("rates", qd, np.concatenate([zeros, v, *pad])),
                ("accelerations", qdd, np.concatenate([-rows.rate(qd), rhs, *pad])),
            ):
                res = _holds(model, K, x, b, f"the closure of the {what}")
                if res is not None:
                    raise UserError(
                        f"the {what} given are not a motion of the mechanism at this Type II "
                        f"singularity (the closure leaves a relative residual of {res:.2g}): "
                        "there the inputs cannot move independently; --precision float gives "
                        "the least-squares motion"
                    )
    return qd, qdd


def _holds(model: Any, A: np.ndarray, x: np.ndarray, b: np.ndarray, what: str) -> float | None:
    """None when ``A x = b`` holds (mp:N: the residual relative to ``|b|`` decided zero
    with the precision's margins; exact: every entry of ``A x - b`` proved zero), else
    the relative residual (float); refused when too close to call."""
    from mechsing.numeric import decide_nonzero

    r = A.dot(x) - b
    if model.backend.name == "exact":
        if all(model.backend.is_zero(e, 0) for e in r):
            return None
        return _norm(r) / max(_norm(b), 1e-300)
    with model.precision.context():
        size = mpmath.sqrt(mpmath.fsum(e**2 for e in b))
        rel = mpmath.sqrt(mpmath.fsum(e**2 for e in r)) / (size if size else 1)
    verdict = decide_nonzero(rel, model.precision)
    if verdict is None:
        raise UserError(
            f"{what} is too close to holding to decide at {model.precision} (relative "
            f"residual {float(rel):.2g}): more digits (--precision mp:N with a larger N) "
            "decide it"
        )
    return float(rel) if verdict else None


def _norm(v: np.ndarray) -> float:
    return math.sqrt(sum(float(to_float(e)) ** 2 for e in np.ravel(v)))


def balance(
    rows: ClosureRows, E: np.ndarray, tau: np.ndarray, free: TypeII | None = None
) -> tuple[np.ndarray, np.ndarray, float, bool]:
    """The inputs' efforts (every coordinate's: 0 off the inputs ``E`` selects), the
    loops' multipliers, the relative residual of ``E^T tau_in + A^T lambda = tau``
    (virtual work) for the tree's efforts ``tau`` and whether the inputs can produce
    them (the crossing condition).  At a Type II configuration (``free``, mp:N and exact)
    the condition is that ``tau`` does no power on the uncontrolled twists (Briot &
    Arakelian 2008), decided with the precision's margins (exactly in exact mode); the
    inputs' efforts are then those of least norm (they are not unique: :class:`TypeII`),
    otherwise the least-squares ones."""
    from mechsing.numeric import CROSSING_RTOL

    model = rows.model
    with model.precision.context():
        M = np.hstack([E.T, rows.A.T])
        b = tau
        if free is not None:
            M = np.vstack([M, free.kernel])
            b = np.concatenate([tau, model.backend.zeros(free.kernel.shape[0])])
        x, residual = _solve(model.backend, M, b, "balance of the efforts")
        if free is None:
            possible = residual <= CROSSING_RTOL
        else:  # the residual is |tau's part along the free twists| / |tau|
            possible = _holds(model, M, x, b, "the crossing condition (the balance)") is None
        m = E.shape[0]
        return E.T.dot(x[:m]), x[m:], residual, bool(possible)


def closed_inverse(
    td: Any, q: np.ndarray, inputs: list[int], u: np.ndarray, udd: np.ndarray
) -> ClosedMotion:
    """The motion and efforts of the closed chain of ``td`` at the closed configuration
    ``q`` (in the model's numbers) for the inputs' coordinates ``inputs`` moving with the
    rates ``u`` and the accelerations ``udd``."""
    rows = ClosureRows(td, q)
    free = rows.type_ii(inputs)
    E = rows.selector(inputs)
    qd, qdd = driven_motion(rows, E, u, udd, free=free)
    qd[inputs] = u  # the inputs' rates as given (the solve returns them to rounding)
    qdd[inputs] = udd
    tau = td.inverse(q, qd, qdd)
    efforts, multipliers, residual, possible = balance(rows, E, tau, free)
    return ClosedMotion(qd, qdd, efforts, multipliers, residual, tau, possible)


def closed_forward(
    td: Any, q: np.ndarray, inputs: list[int], u: np.ndarray, tau_in: np.ndarray
) -> np.ndarray:
    """The inputs' accelerations under the inputs' efforts ``tau_in`` at the closed
    configuration ``q`` with the inputs' rates ``u`` (the reduced equation of the module
    docstring); every coordinate's acceleration."""
    rows = ClosureRows(td, q)
    if rows.type_ii(inputs) is not None:
        raise UserError(
            "the inputs leave a motion of the mechanism free here (a Type II singularity): "
            "their efforts do not determine the accelerations (the mass matrix reduced to "
            "the inputs is singular); --accelerations gives the inverse dynamics and the "
            "crossing condition here"
        )
    E = rows.selector(inputs)
    model = rows.model
    with model.precision.context():
        K = np.vstack([rows.A, E])
        m = len(inputs)
        N = np.stack(
            [
                _solve(
                    model.backend,
                    K,
                    np.concatenate([model.backend.zeros(rows.A.shape[0]), unit]),
                    "closure at velocity level",
                )[0]
                for unit in model.backend.eye(m)
            ],
            axis=1,
        )
        still = closed_inverse(td, q, inputs, u, model.backend.zeros(m))
        M = td.mass_matrix(q)
        reduced = N.T.dot(M).dot(N)
        udd = model.backend.solve(reduced, tau_in - N.T.dot(still.tree_efforts))
        return still.qdd + N.dot(udd)
