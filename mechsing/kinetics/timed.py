"""A timed motion along a sweep's path (``mechsing sweep --duration T``): each sample's
rates, accelerations and efforts, and the Type II crossing condition at the located
Type II points.

The swept value ``s`` follows the quintic time law of a rest-to-rest motion over ``T``
seconds from the path's first sample to its last (:class:`TimeLaw`):
``s(t) = s0 + (s1 - s0) h(t / T)`` with ``h(x) = 10 x^3 - 15 x^4 + 6 x^5`` (zero rate and
acceleration at both ends, zero acceleration half way).  At a sample the sweep closed,
the motion of every coordinate follows from the path's own parameterisation: the
coordinates the sweep gives (the swept one and those it holds) are driven,

* a joint coordinate by its row of the identity: rate ``s'`` (swept) or 0 (held);
* a coordinate of the output's pose (``pose.x`` ...) by the output body's twist: its
  reference point ``P`` moves with ``v_P = v + w x P`` and accelerates with
  ``a_P = a + alpha x P + w x v_P`` (``(w, v)`` the body's twist and ``(alpha, a)`` its
  rate, at the ground origin); a held rotation has ``w = 0`` and ``alpha = 0``, a
  turned one (``pose.rx`` ...: the rotation ``R0 exp(r)``, one component of ``r``
  swept) ``w = R0 J_l(r) r'`` and its rate (:func:`turn_rates`),

and the closure gives the rest (:func:`mechsing.kinetics.closed.driven_motion`).  The
tree's efforts (:class:`~mechsing.kinetics.tree.TreeDynamics`) are every joint's for an
open chain and, balanced by the loops' multipliers, the inputs' for a closed chain
(:func:`~mechsing.kinetics.closed.balance`).

**The crossing condition along the path.**  At a Type II point the inputs leave a twist
``v`` of the mechanism uncontrolled (``[C; E] v = 0``); the motion can pass with bounded
efforts only when the dynamic wrench does no power on it: ``v . tau = 0`` for the tree's
efforts ``tau`` (Briot & Arakelian, IJRR 2008).  At every located point the full analysis
classed as Type II (class ``output``), :meth:`TimedSweep.locate` reports the relative
residual ``|v . tau| / max |tau|`` of the motion law (``v`` of unit norm, the largest tree
effort over the path's samples: the motion's own scale, which does not vanish where the
motion happens to be at rest) and whether it is below
:data:`mechsing.numeric.tolerances.CROSSING_RTOL` (``possible``); elsewhere the efforts
grow as one over the distance to the point.

Owns :class:`TimeLaw`, :class:`TimedSweep`, :func:`turn_rates` and :func:`attach`; the report's figure is
:mod:`mechsing.reports.dynamics`'.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.errors import UserError
from mechsing.numeric import CROSSING_RTOL

__all__ = ["TIMED_SCHEMA", "TimeLaw", "TimedSweep", "attach", "turn_rates"]

#: bisection steps inverting the time law (each halves the bracket of t / T in [0, 1])
_INVERSION_STEPS = 60


def _h(x: np.ndarray) -> np.ndarray:
    """The quintic rest-to-rest law on [0, 1]: ``10 x^3 - 15 x^4 + 6 x^5``."""
    return x**3 * (10 - 15 * x + 6 * x**2)


@dataclass(frozen=True)
class TimeLaw:
    """The quintic rest-to-rest law from ``start`` to ``stop`` (SI) over ``duration`` s."""

    start: float
    stop: float
    duration: float

    def position(self, t: Any) -> np.ndarray:
        """The swept value (SI) at the times ``t`` (s; clipped to [0, duration])."""
        x = np.clip(np.asarray(t, dtype=float) / self.duration, 0.0, 1.0)
        return self.start + (self.stop - self.start) * _h(x)

    def time(self, s: Any) -> np.ndarray:
        """The times (s) at which the law is at the swept values ``s`` (between start
        and stop): ``h`` inverted by bisection (it increases on [0, 1]) from the nearer
        end (``h(1 - x) = 1 - h(x)``: near either end ``h`` is flat, and its small values
        keep their relative precision where values near 1 would round to 1)."""
        span = self.stop - self.start
        u = np.clip((np.asarray(s, dtype=float) - self.start) / span, 0.0, 1.0)
        w = np.minimum(u, 1.0 - u)
        lo, hi = np.zeros_like(w), np.full_like(w, 0.5)
        for _ in range(_INVERSION_STEPS):
            mid = 0.5 * (lo + hi)
            below = _h(mid) < w
            lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
        x = np.where(w == 0, 0.0, 0.5 * (lo + hi))  # the ends exactly
        return np.where(u > 0.5, 1.0 - x, x) * self.duration

    def rates(self, s: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The time, the rate ``s'`` and the acceleration ``s''`` at the swept values ``s``."""
        t = self.time(s)
        x = t / self.duration
        span = self.stop - self.start
        sd = span / self.duration * 30 * x**2 * (1 - x) ** 2
        sdd = span / self.duration**2 * 60 * x * (1 - x) * (1 - 2 * x)
        return t, sd, sdd


@dataclass(frozen=True)
class Crossing:
    """The crossing condition at a located Type II point: where (the swept ``values``,
    the ``time``), the relative residual ``|v . tau| / max |tau|`` and the verdict."""

    values: tuple[float, ...]
    time: float
    possible: bool
    residual: float

    def to_json(self) -> dict[str, Any]:
        return {
            "values": list(self.values),
            "time": self.time,
            "possible": self.possible,
            "residual": self.residual,
        }


class TimedSweep:
    """The timed motion along the path of the sweep ``run`` (a
    :class:`~mechsing.sweeps.SweepRun` before its rows) over ``duration`` seconds, under
    ``gravity`` (None: the file's); filled row by row (:meth:`store`)."""

    def __init__(self, run: Any, duration: float, gravity: Any = None) -> None:
        from mechsing.kinetics.tree import TreeDynamics

        mech = run.mechanism
        if run.grid:
            raise UserError(
                "--duration times a motion along a path: give one --vary (a grid of two "
                "swept values is a region, not one motion in time: no order of its samples "
                "is the motion, and its efforts would depend on the order chosen)"
            )
        if not (isinstance(duration, int | float) and math.isfinite(duration) and duration > 0):
            raise UserError(f"--duration {duration!r}: give a positive number of seconds")
        pb = run.engine.problem
        self.model = model = pb.model
        self.loops = bool(mech.graph.loops)
        self.td = TreeDynamics(model, gravity, closed=self.loops)
        n = model.n
        self.col = int(run.engine.cols[0])
        self.given = [int(c) for c in np.flatnonzero(pb.given)]
        self.pose = pb.cm is not pb.model
        if self.pose:
            out = mech.output
            from mechsing.numeric import to_float

            #: the start's rotation vector and the rotation it is measured from (a turn)
            self.rotation = np.asarray(to_float(run.engine.z0[n : n + 3]), dtype=float)
            self.R0 = np.asarray(to_float(pb.cm.R0), dtype=float)
            if out.relative_to not in (None, mech.ground):
                raise UserError(
                    f"--duration: the output {out.body!r} is relative to {out.relative_to!r}; "
                    "a timed sweep of its pose takes an output relative to the ground"
                )
            self.out_body = out.body
            self.point = np.asarray([float(x) for x in mech.output_reference_point()], dtype=float)
        if self.loops:
            if not mech.inputs:
                raise UserError(
                    f"{mech.name}: --duration on a closed chain needs its inputs (inputs: "
                    "[...]): their efforts are what the motion costs"
                )
            self.inputs = [model.joint(j).columns.start + k for j, k in mech.input_coordinates()]
            names = [mech.coordinate_label(j, k) for j, k in mech.input_coordinates()]
        else:
            self.inputs = list(range(n))
            names = [jk.name for jk in model.joints]
        self.names = tuple(names)
        self.units = {
            nm: ("N" if model.frame.length_columns[c] else "N m")
            for nm, c in zip(names, self.inputs, strict=True)
        }
        values = np.asarray(run.vars[0].values, dtype=float)
        self.law = TimeLaw(float(values[0]), float(values[-1]), float(duration))
        self.values = values
        self.times = self.law.time(values)
        shape = run.reached.shape
        self.efforts = np.full((*shape, len(names)), np.nan)
        #: each sample's joint values (SI, the model's coordinates; NaN where not reached)
        self.joints = np.full((*shape, n), np.nan)
        self.residual = np.full(shape, np.nan)
        #: the largest norm of the tree's efforts over the samples (the crossings' scale)
        self.scale = 0.0
        self.crossings: list[Crossing] = []
        self.gravity = self.td.has_gravity

    # -- one configuration --------------------------------------------------------------

    def _driven(self, q: np.ndarray, s: float) -> tuple[np.ndarray, np.ndarray, Any]:
        """The driven rows ``G``, their rates and accelerations (``drift`` for a pose)."""
        _, sd, sdd = self.law.rates(s)
        n = self.model.n
        v = np.array([float(sd) if c == self.col else 0.0 for c in self.given])
        a = np.array([float(sdd) if c == self.col else 0.0 for c in self.given])
        if not self.pose:
            G = np.zeros((len(self.given), n))
            G[np.arange(len(self.given)), self.given] = 1.0
            return G, (v, a), None
        pick = [c - n for c in self.given]
        if self.col < n + 3:  # a turn: the output's angular velocity and acceleration
            w, dw = turn_rates(self.R0, self.rotation, self.col - n, s)
            v6, a6 = np.zeros(6), np.zeros(6)
            v6[:3], a6[:3] = w * float(sd), w * float(sdd) + dw * float(sd) ** 2
            v, a = v6[pick], a6[pick]
        td = self.td
        poses, _, _, screws = td.motion(q, np.zeros(n), None, False)
        T = np.zeros((6, n))
        for k in td.path_columns[self.out_body]:
            T[:, k] = screws[td._body_of_column[k]]
        P = lie.act_point(poses[self.out_body], self.point)
        rows = np.vstack(
            [T[:3], -lie.hat3(P) @ T[:3] + T[3:]]
        )  # (w, v_P) of the coordinates' rates

        def drift(qd: np.ndarray) -> np.ndarray:
            _, xi, acc, _ = td.motion(q, qd, np.zeros(n), False)
            w, vo = xi[self.out_body][:3], xi[self.out_body][3:]
            al, ao = acc[self.out_body][:3], acc[self.out_body][3:]
            vp = vo + np.cross(w, P)
            return np.concatenate([al, ao + np.cross(al, P) + np.cross(w, vp)])[pick]

        return rows[pick], (v, a), drift

    def motion(self, q: np.ndarray, s: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, Any]:
        """At the closed ``q`` (float) where the swept value is ``s``: every coordinate's
        rate and acceleration, the tree's efforts and the closure's rows."""
        from mechsing.kinetics.closed import ClosureRows, driven_motion

        q = np.asarray(q, dtype=float)
        G, (v, a), drift = self._driven(q, s)
        rows = ClosureRows(self.td, q)
        qd, qdd = driven_motion(rows, G, v, a, drift)
        tau = np.asarray(self.td.inverse(q, qd, qdd), dtype=float)
        self.scale = max(self.scale, float(np.linalg.norm(tau)))
        return qd, qdd, tau, rows

    def at(self, q: np.ndarray, s: float) -> tuple[np.ndarray, float]:
        """The efforts of :attr:`names` at the closed ``q`` where the swept value is ``s``
        and the effort balance's relative residual (0 for an open chain)."""
        from mechsing.kinetics.closed import balance

        _, _, tau, rows = self.motion(q, s)
        if not self.loops:
            return tau, 0.0
        efforts, _, residual, _ = balance(rows, self._selector(), tau)
        return efforts[self.inputs], residual

    def _selector(self) -> np.ndarray:
        E = np.zeros((len(self.inputs), self.model.n))
        E[np.arange(len(self.inputs)), self.inputs] = 1.0
        return E

    # -- along the sweep ------------------------------------------------------------------

    def store(self, at: Any, row: Any) -> None:
        """The efforts of a finished row's reached samples (a path: ``at`` is the whole)."""
        if row.Z is None:
            return
        n = self.model.n
        for k in np.flatnonzero(row.reached):
            eff, res = self.at(row.Z[k][:n], float(self.values[k]))
            self.joints[k] = row.Z[k][:n]
            self.efforts[k] = eff
            self.residual[k] = res

    def locate(self, located: Any) -> None:
        """The crossing condition at each located point classed Type II (``output``)."""
        if not self.loops:
            return
        for p in located:
            if "output" not in (p.classes or ()):
                continue
            q = np.zeros(self.model.n)
            joints = dict(p.joints)
            for jk in self.model.joints:
                q[jk.columns] = np.asarray(joints[jk.name], dtype=float)
            s = float(p.values[0])
            _, _, tau, rows = self.motion(q, s)
            # the uncontrolled twist: the kernel of [A; E] (its last right singular vector)
            _, _, Vt = np.linalg.svd(np.vstack([rows.A, self._selector()]))
            power = abs(float(Vt[-1] @ tau))
            residual = 0.0 if power == 0 else power / max(self.scale, float(np.linalg.norm(tau)))
            self.crossings.append(
                Crossing(
                    tuple(float(x) for x in p.values),
                    float(self.law.time(s)),
                    residual <= CROSSING_RTOL,
                    residual,
                )
            )

    # -- output -------------------------------------------------------------------------

    def header_json(self) -> dict[str, Any]:
        return {
            "timed": {
                "duration": self.law.duration,
                "law": "quintic",
                "start": self.law.start,
                "stop": self.law.stop,
                "efforts_of": list(self.names),
                "effort_units": self.units,
            }
        }

    def point_json(self, idx: tuple[int, ...]) -> dict[str, Any]:
        k = idx[0]
        if np.isnan(self.residual[k]):
            return {"time": float(self.times[k]), "dynamic_efforts": None}
        return {
            "time": float(self.times[k]),
            "dynamic_efforts": {
                nm: float(x) for nm, x in zip(self.names, self.efforts[k], strict=True)
            },
        }

    def tail_json(self) -> dict[str, Any]:
        return {"type_ii_crossings": [c.to_json() for c in self.crossings]}

    def text_lines(self, where: Any, shown: Any) -> list[str]:
        """The text report's lines; ``where(index)`` words a sample's swept values and
        ``shown(values)`` swept values (SI)."""
        lines = [
            f"  timed motion over {self.law.duration:g} s (quintic law, at rest at both ends)"
            + ("" if self.gravity else ", no gravity")
            + ":"
        ]
        for i, nm in enumerate(self.names):
            col = self.efforts[:, i]
            ok = np.isfinite(col)
            if not np.any(ok):
                continue
            k = int(np.nanargmax(np.where(ok, np.abs(col), -1)))
            lines.append(
                f"    largest |effort| of {nm}: {abs(float(col[k])):.4g} {self.units[nm]} at "
                f"{where((k,))} (t = {self.times[k]:.4g} s)"
            )
        for c in self.crossings:
            verdict = "possible" if c.possible else "not possible (unbounded efforts)"
            lines.append(
                f"    Type II crossing at {shown(c.values)} (t = {c.time:.4g} s): {verdict}, "
                f"residual {c.residual:.2g}"
            )
        return lines


def turn_rates(R0: np.ndarray, r0: np.ndarray, k: int, s: float) -> tuple[np.ndarray, np.ndarray]:
    """The output's angular velocity per unit rate of its rotation vector's component
    ``k`` and its rate per unit rate squared, where the rotation is ``R0 exp(r)`` with
    ``r`` the start's ``r0`` but ``r_k = s`` (ground axes, SI).

    ``w(s) = R0 J_l(r) e_k`` (``J_l`` the left Jacobian of SO(3)) and, with
    ``J_l(r) = int_0^1 exp(tau r) dtau``, ``dw/ds = R0 int_0^1 [tau J_l(tau r) e_k]^
    exp(tau r) e_k dtau``: the angular acceleration is ``w s'' + dw/ds s'^2``.  The
    integrand is analytic in ``tau``: Gauss-Legendre nodes integrate it to rounding for
    any rotation (:data:`_TURN_NODES`)."""
    r = np.array(r0, dtype=float)
    r[k] = s
    e = np.zeros(3)
    e[k] = 1.0
    w = R0 @ (lie.left_jacobian_so3(r) @ e)
    x, wt = np.polynomial.legendre.leggauss(_TURN_NODES)
    tau = (x + 1) / 2
    terms = [np.cross(t * (lie.left_jacobian_so3(t * r) @ e), lie.exp_so3(t * r) @ e) for t in tau]
    dw = R0 @ (np.asarray(wt) @ np.asarray(terms) / 2)
    return w, dw


#: Gauss-Legendre nodes of :func:`turn_rates` (exact for polynomials of degree 47 in tau;
#: the integrand's Taylor terms in tau fall as |r|^j / j!, below rounding by j = 48 for
#: |r| <= pi)
_TURN_NODES = 24


def attach(run: Any, duration: float | None, gravity: Any = None) -> None:
    """Give the sweep ``run`` (before its rows) the timed motion over ``duration`` seconds
    (None: none)."""
    if duration is None:
        return
    run.dynamics = TimedSweep(run, duration, gravity)


#: the sweep document's keys this module adds (:func:`mechsing.sweeps.schema.sweep_schema`)
TIMED_SCHEMA: dict[str, Any] = {
    "point": {
        "time": {
            "type": "number",
            "description": "with --duration: the time (s) the timed motion is at this sample",
        },
        "dynamic_efforts": {
            "type": ["object", "null"],
            "additionalProperties": {"type": "number"},
            "description": "with --duration: each effort (N or N m) the timed motion needs "
            "here (every joint of an open chain, the inputs of a closed one); null where "
            "not reached",
        },
    },
    "top": {
        "timed": {
            "type": "object",
            "description": "with --duration: the motion law (quintic, rest to rest), its "
            "duration, start and stop, the efforts' names and units",
        },
        "type_ii_crossings": {
            "type": "array",
            "items": {"type": "object"},
            "description": "with --duration: the Type II crossing condition at each located "
            "Type II point (values, time, possible, residual)",
        },
    },
}
