"""A closed path of a sweep (``--loop``): around the rectangle of two swept ranges, and
back to its start values on the same assembly mode or on another.

Owns :func:`follow_loop` and :class:`LoopResult`.  The loop goes from the corner (START
of the first variable, START of the second) along the first variable to its STOP, along
the second to its STOP, back along the first and back along the second: four paths of
the sweep, each followed by the sweep's own path engine
(:meth:`~mechsing.sweeps.engine.Sweep.row`: measures at every sample, singularities
located between them) from where the previous one ended.  The corner is reached from the
start configuration (or the assembly mode the sweep starts on) by continuation, first
variable then second; a start whose values are the corner's is the corner.

Back at the corner, the configuration is compared with the one the loop left: the same
given values, so either the same assembly mode or another.  A loop that comes back on
another mode with no singularity located on it (none, or only points the full analysis
finds regular) is **a mode change without a singularity** (around a cusp:
Innocenti & Parenti-Castelli 1998; Zein, Wenger & Chablat 2008).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing.errors import ClosureError
from mechsing.numeric.tolerances import SWEEP_SAME_MODE_DISTANCE
from mechsing.sweeps.classify import classify_located
from mechsing.sweeps.records import Located
from mechsing.sweeps.results import LocatedSingularity
from mechsing.sweeps.words import stop_notes

__all__ = ["LoopResult", "follow_loop"]


@dataclass(frozen=True)
class LoopResult:
    """One loop: the mode it started on (``mode``, None: the one continuation reaches
    from the start configuration) and came back on (``end_mode``: None when not known or
    not closed), its ``corners`` and its samples ``values`` (K, 2) in SI, ``reached``,
    each test's ``rank`` and ``ratio`` per sample, the ``located`` singularities (each
    ``(values, kind, tests, singular)``: ``singular`` the full analysis's verdict there,
    None undecided or not analysed), whether every sample was reached (``closed``), the
    joint values it left and came back with (SI), their commensurate ``distance`` and
    ``notes`` (why the loop did not close)."""

    mode: int | None
    end_mode: int | None
    corners: tuple[tuple[float, float], ...]
    values: np.ndarray = field(repr=False, compare=False)
    reached: np.ndarray = field(repr=False, compare=False)
    rank: dict[str, np.ndarray] = field(repr=False, compare=False)
    ratio: dict[str, np.ndarray] = field(repr=False, compare=False)
    located: tuple[tuple[tuple[float, ...], str, tuple[str, ...], bool | None], ...]
    closed: bool
    joints_start: dict[str, list[float]]
    joints_end: dict[str, list[float]] | None
    distance: float | None
    notes: tuple[str, ...] = ()
    #: the located singularities as a sweep lists them (its JSON's ``located``)
    singularities: tuple[Any, ...] = field(default=(), repr=False, compare=False)

    @property
    def changed(self) -> bool:
        """Back at its start values on another assembly mode."""
        return (
            self.closed and self.distance is not None and self.distance > SWEEP_SAME_MODE_DISTANCE
        )

    @property
    def singular_on_the_way(self) -> bool:
        """A singularity located on the loop that the full analysis did not find regular."""
        return any(s is not False for *_, s in self.located)

    @property
    def mode_change(self) -> bool:
        """A mode change without a singularity: another mode, nothing singular located."""
        return self.changed and not self.singular_on_the_way

    def to_json(self) -> dict[str, Any]:
        """The loop as an entry of the sweep JSON's ``loops``."""
        return {
            "mode": self.mode,
            "end_mode": self.end_mode,
            "corners": [list(c) for c in self.corners],
            "closed": self.closed,
            "changed_mode": self.changed,
            "mode_change_without_singularity": self.mode_change,
            "distance": self.distance,
            "located": [
                {"values": list(v), "kind": k, "tests": list(t), "singular": s}
                for v, k, t, s in self.located
            ],
            "joints_start": self.joints_start,
            "joints_end": self.joints_end,
            "notes": list(self.notes),
        }

    def points_json(self) -> list[dict[str, Any]]:
        """The loop's samples as a sweep's ``points`` (each with its ``mode`` when the
        loop started on a numbered one)."""
        out = []
        for k, (a, b) in enumerate(self.values):
            p: dict[str, Any] = {"values": [float(a), float(b)], "reached": bool(self.reached[k])}
            for t in self.rank:
                rk, ra = int(self.rank[t][k]), float(self.ratio[t][k])
                p[t] = {"rank": None if rk < 0 else rk, "ratio": ra if np.isfinite(ra) else None}
            if self.mode is not None:
                p["mode"] = self.mode
            out.append(p)
        return out

    def change_json(self) -> dict[str, Any]:
        """The loop as an entry of the sweep JSON's ``mode_changes`` (a mode change
        without a singularity): the start and end modes, the loop's corners, the path
        (the swept values of its samples, SI) and the joints it left and came back with."""
        return {
            "start_mode": self.mode,
            "end_mode": self.end_mode,
            "loop": [list(c) for c in self.corners],
            "path": [[float(a), float(b)] for a, b in self.values],
            "distance": self.distance,
            "joints_start": self.joints_start,
            "joints_end": self.joints_end,
        }

    def text_lines(self, shown: Any) -> list[str]:
        """The loop in words (``shown(values)``: the swept values in the file's units)."""
        on = "the start's mode" if self.mode is None else f"mode {self.mode}"
        head = f"  loop around {' -> '.join(shown(c) for c in self.corners)} from {on}: "
        if not self.closed:
            return [head + "not closed (" + "; ".join(self.notes) + ")"]
        sing = [v for v, *_, s in self.located if s is not False]
        where = "; ".join(shown(v) for v in sing)
        if not self.changed:
            end = "back on the same assembly mode"
        else:
            end = "back on " + (
                "another mode" if self.end_mode is None else f"mode {self.end_mode}"
            )
            end += f" (joint distance {self.distance:.3g})"
        if self.mode_change:
            end += ": a mode change without a singularity"
        lines = [head + end]
        if sing:
            lines.append(f"    singularities located on the loop: {where}")
        return lines


def _corners(run: Any) -> list[tuple[float, float]]:
    (a0, a1), (b0, b1) = ((v.values[0], v.values[-1]) for v in run.vars)
    return [(a0, b0), (a1, b0), (a1, b1), (a0, b1), (a0, b0)]


def follow_loop(run: Any, match: Any = None) -> LoopResult:
    """Follow the loop of a sweep of two variables (a :class:`~mechsing.sweeps.run.SweepRun`)
    from its start (its assembly mode's configuration when it has one), and classify the
    points located on it at the sweep's precision.  ``match(z)``: the number of the mode a
    configuration at the corner is on (None: not known)."""
    eng = run.engine
    pb = eng.problem
    ca, cb = eng.cols
    va, vb = (np.asarray(v.values, dtype=float) for v in run.vars)
    corners = _corners(run)
    mech = run.mechanism
    names = mech.coordinates()
    notes: list[str] = []

    def joints(z: np.ndarray) -> dict[str, list[float]]:
        out: dict[str, list[float]] = {}
        for (j, _), x in zip(names, z, strict=False):
            out.setdefault(j, []).append(float(x))
        return out

    z = np.array(eng.z0, dtype=float)
    try:
        for col, value in ((ca, va[0]), (cb, vb[0])):
            if z[col] != value:
                z = pb.reach(z, col, float(value))
    except ClosureError as exc:
        raise ClosureError(
            f"the loop cannot start: its corner ({run.vars[0].name} = "
            f"{run.vars[0].shown(va[0])}, {run.vars[1].name} = {run.vars[1].shown(vb[0])}) "
            f"cannot be reached from the start on its assembly mode ({exc})",
            run.from_config,
            exc.residual,
        ) from None
    z_start = z.copy()
    edges = [(ca, va), (cb, vb), (ca, va[::-1]), (cb, vb[::-1])]
    values: list[np.ndarray] = []
    reached: list[np.ndarray] = []
    rank: dict[str, list[np.ndarray]] = {t: [] for t in run.tests}
    ratio: dict[str, list[np.ndarray]] = {t: [] for t in run.tests}
    located: list[Located] = []
    closed = True
    for e, (col, vals) in enumerate(edges):
        row = eng.row(e, col, vals, z)
        skip = 0 if e == 0 else 1  # the corner is the last sample of the edge before
        pts = np.empty((len(vals), 2))
        pts[:, 0 if col == ca else 1] = vals
        pts[:, 1 if col == ca else 0] = z[cb if col == ca else ca]
        values.append(pts[skip:])
        reached.append(np.asarray(row.reached[skip:], dtype=bool))
        for t in run.tests:
            rank[t].append(np.asarray(row.rank[t][skip:]))
            ratio[t].append(np.asarray(row.ratio[t][skip:]))
        located += row.located
        run.newton_iterations += row.newton
        if not bool(row.reached[-1]) or row.Z is None:
            closed = False
            notes += row.stopped or [f"edge {e + 1} of the loop not reached to its end"]
            break
        z = np.asarray(row.Z[-1], dtype=float)
    done = classify_located(eng, located, run.prec, run.time_limit)
    classified = done.results
    model = eng.model
    listed = tuple(
        LocatedSingularity(
            p.values,
            p.kind,
            p.tests,
            float(p.ratio),
            tuple((k, tuple(v)) for k, v in model.values(p.q).items()),
            c,
            p.far_side,
            p.edge,
            point=v,
        )
        for p, c, v in zip(located, classified, done.points, strict=True)
    )
    found = tuple(
        (
            tuple(float(x) for x in p.values),
            p.kind,
            tuple(p.tests),
            None if c is None or c.error is not None else c.singular,
        )
        for p, c in zip(located, classified, strict=True)
    )
    n = eng.model.n
    distance = end_mode = None
    joints_end = None
    if closed:
        from mechsing.assembly.result import joint_distance

        L = float(eng.model.length_scale)
        distance = joint_distance(mech, list(z_start[:n]), list(z[:n]), L)
        joints_end = joints(z[:n])
        end_mode = match(z) if match is not None else None
        if end_mode is None and distance <= SWEEP_SAME_MODE_DISTANCE:
            end_mode = run.mode
    return LoopResult(
        run.mode,
        end_mode,
        tuple((float(a), float(b)) for a, b in corners),
        np.concatenate(values),
        np.concatenate(reached),
        {t: np.concatenate(r) for t, r in rank.items()},
        {t: np.concatenate(r) for t, r in ratio.items()},
        found,
        closed,
        joints(z_start[:n]),
        joints_end,
        distance,
        tuple(stop_notes(mech, notes, (p.classes for p in listed if p.kind == "fold"))),
        listed,
    )
