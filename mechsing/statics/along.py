"""Kinetostatics along a sweep: each reached sample's efforts under the load and its
transmission indices, and ``--max-effort NAME=VALUE``: where an actuator's |effort| first
crosses a limit, located between samples by the path engine's crossing locator on the swept value
(each trial configuration closed by the sweep's own path following), reported as an
"effort limit", never as a singularity.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.errors import UserError
from mechsing.kinematics.settings import SWEEP_LOCATE_TOL
from mechsing.statics.configuration import kinetostatics_at

__all__ = [
    "KINETOSTATICS_SCHEMA",
    "EffortLimit",
    "SweepStatics",
    "attach",
    "parse_max_effort",
]


def parse_max_effort(texts: list[str] | None, mech: Any) -> dict[str, float]:
    """``--max-effort NAME=VALUE`` (repeatable): an input's effort limit in SI (N for a
    prismatic input, N m for a rotation), by input name (``J`` or ``J[i]``)."""
    from mechsing.model.expressions import parse_number
    from mechsing.numeric import to_float

    names = [mech.coordinate_label(j, i) for j, i in mech.input_coordinates()]
    out: dict[str, float] = {}
    for text in texts or []:
        name, eq, value = text.partition("=")
        name = name.strip()
        if not eq or name not in names:
            raise UserError(
                f"--max-effort {text!r}: give INPUT=VALUE with INPUT one of "
                f"{', '.join(names) or '(the file has no inputs)'}, e.g. --max-effort "
                f"{names[0] if names else 'A'}=10"
            )
        try:
            v = float(to_float(parse_number(value.strip(), {})))
        except Exception:  # noqa: BLE001 - any parse failure is the user's text
            v = float("nan")
        if not v > 0 or not np.isfinite(v):
            raise UserError(
                f"--max-effort {text!r}: {value!r} is not a positive number (N for a "
                "prismatic input, N m for a rotation)"
            )
        out[name] = v
    return out


@dataclass(frozen=True)
class EffortLimit:
    """Where ``input``'s |effort| crosses ``limit``: the swept ``values`` (SI), whether it
    goes above (``exceeds``) or back below, and the efforts there."""

    input: str
    limit: float
    values: tuple[float, ...]
    exceeds: bool
    efforts: dict[str, float | None]
    first: bool

    def to_json(self) -> dict[str, Any]:
        return {
            "kind": "effort limit",
            "input": self.input,
            "limit": self.limit,
            "values": list(self.values),
            "exceeds": self.exceeds,
            "first": self.first,
            "efforts": self.efforts,
        }


class SweepStatics:
    """The statics of a sweep's samples under ``load`` (filled row by row: :meth:`store`)."""

    def __init__(self, mech: Any, load: Any, shape: tuple[int, ...], limits: dict[str, float]):
        from mechsing.kinematics import KinematicModel

        if not mech.inputs or mech.output is None:
            raise UserError(
                "--load and --max-effort need the file's inputs and output (the efforts are "
                "the inputs' under a load on the output)"
            )
        self.mech, self.load, self.limits = mech, load, limits
        self.model = KinematicModel(mech, "float")
        names = [mech.coordinate_label(j, i) for j, i in mech.input_coordinates()]
        self.inputs = tuple(names)
        self.units = {
            n: (
                "N"
                if bool(self.model.frame.length_columns[self.model.joint(j).columns.start + i])
                else "N m"
            )
            for n, (j, i) in zip(names, mech.input_coordinates(), strict=True)
        }
        self.efforts = np.full((*shape, len(names)), np.nan)
        self.local = np.full(shape, np.nan)
        self.input_index: dict[tuple[int, ...], list[float] | None] = {}
        self.output_index: dict[tuple[int, ...], list[float] | None] = {}
        self.bounded = np.zeros(shape, dtype=bool)
        self.Z: np.ndarray | None = None  # a path's closed samples (for the limits)
        self.rows: dict[int, np.ndarray] = {}  # a grid's, by row, with --max-effort
        self.located: list[EffortLimit] = []

    def _one(self, q: np.ndarray) -> Any:
        return kinetostatics_at(self.mech, q[: self.model.n], self.load, self.model)

    def store(self, at: Any, row: Any) -> None:
        """The statics of a finished row's reached samples (``at``: the row's index in the
        arrays, or ``slice(None)`` for a path)."""
        if row.Z is None:
            return
        if at == slice(None):
            self.Z = np.array(row.Z)
        elif self.limits:  # a grid's rows, for its effort limits along them
            self.rows[int(at)] = np.array(row.Z)
        for k in np.flatnonzero(row.reached):
            idx = (int(k),) if at == slice(None) else (int(at), int(k))
            ks = self._one(row.Z[k])
            eq = ks.equilibrium
            if eq is not None and eq.efforts is not None:
                self.efforts[idx] = [eq.efforts[n] for n in self.inputs]
                self.bounded[idx] = True
            tr = ks.transmission
            self.local[idx] = np.nan if tr.local is None else tr.local
            self.input_index[idx] = tr.input
            self.output_index[idx] = tr.output

    # -- effort limits ----------------------------------------------------------------

    def locate_limits(
        self, engine: Any, values: np.ndarray, rows: np.ndarray | None = None
    ) -> None:
        """Where each limited input's |effort| crosses its limit along a path, or along
        each row of a grid (``rows``: the second variable's samples), between consecutive
        reached samples: the path engine's crossing locator on |effort| less the limit
        (:meth:`_limit_between`)."""
        if not self.limits:
            return
        if rows is None:
            if self.Z is not None:
                self._row_limits(engine, values, self.Z, self.efforts, self.bounded, ())
            return
        for j in sorted(self.rows):
            self._row_limits(
                engine, values, self.rows[j], self.efforts[j], self.bounded[j], (float(rows[j]),)
            )

    def _row_limits(
        self,
        engine: Any,
        values: np.ndarray,
        Z: np.ndarray,
        efforts: np.ndarray,
        bounded: np.ndarray,
        other: tuple[float, ...],
    ) -> None:
        """:meth:`locate_limits` along one path or row (its closed samples Z, efforts and
        bounded flags; ``other``: the row's value of the second variable, for a grid)."""
        reached = ~np.isnan(Z[:, 0])
        for name, limit in self.limits.items():
            i = self.inputs.index(name)
            over = np.where(bounded, np.abs(efforts[:, i]) > limit, True)
            first = True
            for k in range(len(values) - 1):
                if not (reached[k] and reached[k + 1]) or over[k] == over[k + 1]:
                    continue
                v, eff = self._limit_between(
                    engine, Z[k], float(values[k]), float(values[k + 1]), name, limit
                )
                self.located.append(
                    EffortLimit(name, limit, (v, *other), bool(not over[k]), eff, first)
                )
                first = False

    def _limit_between(
        self, engine: Any, z: np.ndarray, lo: float, hi: float, name: str, limit: float
    ) -> tuple[float, dict[str, Any]]:
        """Where ``name``'s |effort| crosses ``limit`` between the closed sample z (at
        ``lo``) and ``hi``, and the efforts there: the crossing locator on |effort| less
        the limit, each trial point closed by following the path from z (an unbounded
        effort, at a Type II, reads as over the limit); ``hi`` when the path is lost on
        the way."""
        from mechsing.kinematics.paths.crossing import locate_crossing
        from mechsing.kinematics.paths.follow import follow

        pb, col = engine.problem, engine.cols[0]
        closed: dict[float, Any] = {}

        def excess(v: float) -> float | None:
            zv = z if v == lo else follow(pb, z, col, np.array([lo, v])).Z[-1]
            if np.isnan(zv[0]):
                return None
            e = closed[v] = self._one(zv).equilibrium
            if e is None or e.efforts is None:
                return 1.0  # unbounded: over any limit
            return abs(float(e.efforts[name])) - limit

        at = locate_crossing(excess, lo, hi, SWEEP_LOCATE_TOL * max(1.0, abs(hi)))
        v = hi if at is None else at
        if v not in closed:
            excess(v)
        e = closed.get(v)
        if e is None or e.efforts is None:
            return v, {n: None for n in self.inputs}
        return v, e.efforts

    # -- output ---------------------------------------------------------------------

    def header_json(self) -> dict[str, Any]:
        ld = self.load
        return {
            "kinetostatics": {
                "effort_units": self.units,
                "max_effort": self.limits,
                "load": None
                if ld is None
                else {
                    "force": [float(x) for x in np.asarray(ld.force, dtype=float)],
                    "moment": [float(x) for x in np.asarray(ld.moment, dtype=float)],
                    "point": None
                    if ld.point is None
                    else [float(x) for x in np.asarray(ld.point, dtype=float)],
                },
            }
        }

    def point_json(self, idx: tuple[int, ...]) -> dict[str, Any]:
        if idx not in self.input_index:
            return {}
        e = self.efforts[idx]
        return {
            "efforts": None
            if not self.bounded[idx]
            else {n: float(v) for n, v in zip(self.inputs, e, strict=True)},
            "transmission": {
                "input": self.input_index[idx],
                "output": self.output_index[idx],
                "local": None if np.isnan(self.local[idx]) else float(self.local[idx]),
            },
        }

    def tail_json(self) -> dict[str, Any]:
        return {"effort_limits": [p.to_json() for p in self.located]}

    def text_lines(self, where: Any, shown: Any) -> list[str]:
        """The text report's lines; ``where(index)`` words a sample's swept values and
        ``shown(values)`` swept values (SI)."""
        lines = []
        for i, n in enumerate(self.inputs):
            col = self.efforts[..., i]
            ok = np.isfinite(col)
            if not np.any(ok):
                continue
            k = np.unravel_index(int(np.nanargmax(np.where(ok, np.abs(col), -1))), col.shape)
            lines.append(
                f"  largest |effort| of {n}: {abs(float(col[k])):.4g} {self.units[n]} at "
                f"{where(tuple(int(x) for x in k))}"
            )
        ok = np.isfinite(self.local)
        if np.any(ok):
            k = np.unravel_index(
                int(np.nanargmin(np.where(ok, self.local, np.inf))), self.local.shape
            )
            lines.append(
                f"  least local transmission index: {float(self.local[k]):.4g} at "
                f"{where(tuple(int(x) for x in k))}"
            )
        for p in self.located:
            verb = "exceeds" if p.exceeds else "falls back below"
            lines.append(
                f"  effort limit: |{p.input}| {verb} {p.limit:g} {self.units[p.input]} at "
                f"{shown(p.values)}" + (" (first)" if p.first and p.exceeds else "")
            )
        return lines


def attach(run: Any, load: Any, limits: dict[str, float] | None) -> None:
    """Give the sweep ``run`` (a :class:`~mechsing.sweeps.SweepRun`, before its rows) the
    statics of its samples under ``load`` (None: the load of the configuration it starts
    from) and the effort ``limits`` by input name."""
    from mechsing.statics.configuration import load_of

    mech = run.mechanism
    if load is None and not limits and (not mech.inputs or mech.output is None):
        return  # a file load with no inputs to hold it: nothing asked
    load = load_of(mech, run.from_config, load)
    if load is None:
        if not limits:
            return
        raise UserError(
            '--max-effort needs a load: give --load "force=FX,FY,FZ ..." or a load in the '
            f"configuration {run.from_config!r} the sweep starts from"
        )
    run.statics = SweepStatics(mech, load, run.reached.shape, dict(limits or {}))


#: the sweep document's keys this module adds (:func:`mechsing.sweeps.schema.sweep_schema`)
KINETOSTATICS_SCHEMA: dict[str, Any] = {
    "point": {
        "efforts": {
            "type": ["object", "null"],
            "additionalProperties": {"type": "number"},
            "description": "with --load: each input's effort (N or N m) holding the load here; "
            "null where unbounded (a Type II)",
        },
        "transmission": {
            "type": "object",
            "description": "with --load: the input, output and local transmission indices "
            "(null outside their setting)",
        },
    },
    "top": {
        "kinetostatics": {
            "type": "object",
            "description": "with --load or --max-effort: effort units, limits and the load",
        },
        "effort_limits": {
            "type": "array",
            "items": {"type": "object"},
            "description": "with --max-effort: where an input's |effort| crosses its limit "
            "(kind 'effort limit', not a singularity)",
        },
    },
}
