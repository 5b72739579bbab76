"""Running a sweep: the public :func:`sweep` and :class:`SweepRun`, row by row.

Owns :func:`sweep` (a path or a grid, whole) and :class:`SweepRun` (the same sweep row by
row, for a caller that writes rows as they come or distributes them: Dask,
:mod:`.distributed`): it reads the mechanism and the swept ranges, runs the
:class:`~.engine.Sweep`'s rows (a grid's in chunks, with the crossings between rows),
then has the located points classified (:mod:`.classify`) and returns the
:class:`~.results.SweepResult`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from mechsing.analysis.display import angle_floor, floor_for
from mechsing.errors import UserError, working_on
from mechsing.kinematics.closed import FLOAT_DIGITS, ClosedValue
from mechsing.model import Mechanism
from mechsing.numeric import Precision, parse_precision
from mechsing.reader import read_mechanism
from mechsing.singularity.zfb import not_run_sentences
from mechsing.sweeps.classify import classify_located, located_texts, unresolved
from mechsing.sweeps.engine import Sweep
from mechsing.sweeps.limits import limits_notes
from mechsing.sweeps.loci import loci_of
from mechsing.sweeps.records import Located, RowResult
from mechsing.sweeps.results import (
    LocatedSingularity,
    SweepResult,
    SweptVariable,
)
from mechsing.sweeps.spec import Vary, resolve, sweep_precision, vary_warnings, with_limits
from mechsing.sweeps.words import stop_notes
from mechsing.timelimit import check_time_limit

__all__ = ["MAX_CLASSIFIED", "SweepRun", "sweep"]

#: a grid classifies at most this many located points by the full analysis (evenly
#: spread over the located points); a path classifies every one
MAX_CLASSIFIED = 200


def sweep(
    mechanism: Mechanism | str | Path,
    vary: list[str | Vary] | str | Vary,
    from_config: str | None = None,
    precision: Precision | str = "auto",
    *,
    progress: Callable[[int], None] | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    max_classified: int = MAX_CLASSIFIED,
    time_limit: float | None = None,
    connect_timeout: float | None = None,
    load: Any = None,
    max_effort: dict[str, float] | None = None,
    start: Any = None,
    duration: float | None = None,
) -> SweepResult:
    """Sweep a mechanism (or a file) over one variable (a path) or two (a grid).

    Parameters
    ----------
    mechanism : Mechanism, str or Path
        The mechanism, or the path of its file (any format mechsing reads).
    vary : str or Vary, or a list of one or two of them
        ``"NAME=START:STOP:STEP"`` in the file's units: a joint coordinate (``A``,
        ``C1[1]``) or a coordinate of the output's pose (``pose.x`` ... ``pose.rz``).
    from_config : str, optional
        The configuration the sweep starts from, whose assembly mode it keeps (default
        ``reference``).
    precision : Precision or str
        Of the classification of the located points (``auto``, ``float``, ``mp:N``); the
        measures are always float.
    progress : callable, optional
        Called with the number of samples each finished row adds.
    workers, scheduler : int, str, optional
        Distribute the rows of a grid with Dask (a local cluster of ``workers``
        processes, or the scheduler at that address); the result is the serial one.
    max_classified : int
        The most located points of a grid classified by the full analysis.
    time_limit : float or None
        The most seconds the full analysis of one located point may take (None: no
        limit); a point stopped there has an ``error`` entry that says so.
    connect_timeout : float or None
        Seconds a scheduler has to accept the connection and answer (default
        :data:`mechsing.sweeps.distributed.CONNECT_TIMEOUT`, 5 s).
    load, max_effort : Load, dict, optional
        The samples' efforts under ``load`` (default: the start configuration's file
        load, if any) and where an input's ``|effort|`` crosses ``max_effort[input]``
        (:mod:`mechsing.statics.along`).
    start : Mode or int, optional
        The assembly mode the sweep starts on: an item of ``mechsing.modes(mechanism,
        from_config).modes`` or its index in that tuple; every sample is then labelled
        with the mode's number (``mode``: the index plus 1, as ``mechsing modes``
        numbers them).  Default: the mode continuation reaches from ``from_config``.
    duration : float, optional
        A path's swept value follows a quintic rest-to-rest law over ``duration``
        seconds: each sample's efforts for that motion and the Type II crossing
        condition at the located Type II points (:mod:`mechsing.kinetics.timed`).

    Returns
    -------
    SweepResult
        The measures at every sample, the located and classified singularities and a
        grid's loci.
    """
    run = SweepRun(
        mechanism,
        vary,
        from_config,
        precision,
        max_classified=max_classified,
        time_limit=time_limit,
        start=start,
    )
    from mechsing.statics.along import attach

    attach(run, load, max_effort)
    from mechsing.kinetics.timed import attach as timed

    timed(run, duration)
    rows = run.rows(progress, workers=workers, scheduler=scheduler, connect_timeout=connect_timeout)
    for _ in rows:
        pass
    return run.result()


class SweepRun:
    """A sweep run row by row: :meth:`rows` yields each row's samples as they are done
    (the arrays of the whole sweep are filled as it goes), :meth:`result` then locates,
    classifies and returns the :class:`SweepResult`."""

    def __init__(
        self,
        mechanism: Mechanism | str | Path,
        vary: list[str | Vary] | str | Vary,
        from_config: str | None = None,
        precision: Precision | str = "auto",
        max_classified: int = MAX_CLASSIFIED,
        time_limit: float | None = None,
        start: Any = None,
        modes_found: Any = None,
    ) -> None:
        self.start_time = time.perf_counter()
        if time_limit is not None:
            check_time_limit(time_limit)
        self.time_limit = time_limit
        self._result: SweepResult | None = None
        mech = (
            mechanism
            if isinstance(mechanism, Mechanism)
            else read_mechanism(mechanism, precision=precision)
        )
        self.mechanism = mech
        prec = parse_precision(precision) if isinstance(precision, str) else precision
        sweep_precision(prec)  # policy: exact mode takes exact data only
        self.prec = prec
        self.precision = str(prec)
        if isinstance(vary, str | Vary):  # one variable given alone
            vary = [vary]
        varies = [Vary.parse(v) if isinstance(v, str) else v for v in vary]
        varies = [with_limits(mech, v) for v in varies]
        self.varies = varies
        self.max_classified = max_classified
        with working_on(file=mech.path or mech.name):
            self.vars = resolve(mech, varies)
            self.engine = Sweep(mech, self.vars, from_config)
        eng = self.engine
        self.from_config = eng.from_config
        #: the number of the assembly mode the sweep starts on (None: the one continuation
        #: reaches from the start configuration)
        self.mode: int | None = None
        #: where the sweep starts, a frozen value (:class:`~mechsing.kinematics.closed.ClosedValue`):
        #: the mode's own (source ``mode``), or the start configuration closed (``given``)
        self.start: ClosedValue = ClosedValue(
            eng.z0[: eng.model.n], FLOAT_DIGITS, "given", eng.from_config
        )
        if start is not None:
            from mechsing.sweeps.start import mode_start

            with working_on(file=mech.path or mech.name):
                self.mode, eng.z0, self.start = mode_start(mech, eng, start, modes_found)
        self.tests = eng.tests
        self.generic = {t: int(eng.measures.generic[t]) for t in self.tests}
        L = float(eng.model.length_scale)
        floor = floor_for(prec, L)
        self.variables = tuple(
            SweptVariable(
                v.name,
                v.unit,
                v.file_unit,
                v.factor,
                v.values,
                (w.start, w.stop, w.step),
                floor if v.unit == "m" else angle_floor(floor, L),
            )
            for v, w in zip(self.vars, varies, strict=True)
        )
        names = [mech.coordinate_label(j, i) for j, i in mech.coordinates()]
        pm = eng.problem
        held = [
            names[c]
            if c < len(names)
            else f"pose.{('rx', 'ry', 'rz', 'x', 'y', 'z')[c - len(names)]}"
            for c in np.flatnonzero(pm.given)
            if c not in eng.cols
        ]
        self.held = tuple(held)
        shape = tuple(len(v.values) for v in reversed(self.vars))
        self.reached = np.zeros(shape, dtype=bool)
        self.rank = {t: np.full(shape, -2, dtype=np.int16) for t in self.tests}
        self.ratio = {t: np.full(shape, np.nan) for t in self.tests}
        self.located: list[Located] = []
        #: the scene options' notes (branches left out) first, then likely mistakes of the
        #: swept ranges (:func:`~mechsing.sweeps.spec.vary_warnings`; the command line
        #: prints them on standard error)
        self.notes: list[str] = list(mech.scene.notes) if mech.scene else []
        self.notes += vary_warnings(mech, varies)
        self.outside = {c.name: np.zeros(shape, dtype=bool) for c in eng.limited}
        self.newton_iterations = 0
        #: the statics of the samples under a load (:class:`mechsing.statics.along.SweepStatics`)
        self.statics: Any = None
        #: the timed motion along a path (:class:`mechsing.kinetics.timed.TimedSweep`)
        self.dynamics: Any = None

    @property
    def grid(self) -> bool:
        """True for a grid (two swept variables), False for a path."""
        return len(self.vars) == 2

    def rows(
        self,
        progress: Callable[[int], None] | None = None,
        workers: int | None = None,
        scheduler: str | None = None,
        connect_timeout: float | None = None,
        client: Any = None,
    ) -> Iterator[int]:
        """Run the sweep; yields the index of each finished row (0 for a path) once its
        entries of :attr:`reached`, :attr:`rank` and :attr:`ratio` are filled (rows of a
        grid on Dask with ``workers`` or ``scheduler``, see
        :func:`~mechsing.sweeps.distributed.distributed_rows`; ``client``: one already
        open, shared with other sweeps)."""
        values = [v.values for v in self.vars]
        if workers or scheduler or client is not None:
            if not self.grid:
                raise UserError(
                    "--workers and --scheduler distribute the rows of a grid (two --vary)"
                )
            from mechsing.sweeps.distributed import CONNECT_TIMEOUT, distributed_rows

            timeout = CONNECT_TIMEOUT if connect_timeout is None else connect_timeout
            source: Iterator[RowResult] = distributed_rows(
                self, values, workers, scheduler, progress, timeout, client
            )
        else:
            source = self.engine.rows(values, progress)
        if not self.grid:
            with working_on(file=self.mechanism.path or self.mechanism.name):
                for row in source:
                    self._store(row)
                    yield 0
            return
        # a grid's rows in chunks: the crossings between each row and the one before are
        # refined for the whole chunk together, then its rows are stored in order (only
        # the last row's configurations are kept past its chunk)
        prev: RowResult | None = None
        chunks = iter(self.engine.row_chunks(values))
        with working_on(file=self.mechanism.path or self.mechanism.name):
            while True:
                chunk = next(chunks, None)
                if chunk is None:
                    break
                rows = [next(source) for _ in chunk]
                pairs, at = [], []
                for row in rows:
                    if prev is not None and row.Z is not None and prev.Z is not None:
                        pairs.append((prev, row))
                        at.append(row.index)
                    prev = row if row.Z is not None else None
                between = dict(
                    zip(at, self.engine.between_many(pairs, self.engine.cols[1]), strict=True)
                )
                for row in rows:
                    self._store(row)
                    self.located += between.get(row.index, [])
                    yield row.index
                for a, _ in pairs:
                    if a is not prev:
                        a.Z = None
                        a.measures = None

    def _drives(self, p: Located) -> bool:
        """Whether the coordinate that turns back at the fold p is an input or a
        coordinate of the output's pose (then some test drops rank there: the inputs',
        or the output's, rank on the motion space); a passive joint may reach its
        extreme at a regular configuration."""
        eng = self.engine
        col = eng.cols[0] if p.edge == "row" else eng.cols[-1]
        if col >= eng.model.n:  # a coordinate of the output's pose
            return True
        inputs = {
            eng.model.joint(j).columns.start + k for j, k in self.mechanism.input_coordinates()
        }
        return col in inputs

    def _store(self, row: RowResult) -> None:
        at: Any = slice(None) if not self.grid else row.index
        self.reached[at] = row.reached
        for t in self.tests:
            self.rank[t][at] = row.rank[t]
            self.ratio[t][at] = row.ratio[t]
        self.located += row.located
        self.newton_iterations += row.newton
        if self.statics is not None:
            self.statics.store(at, row)
        if self.dynamics is not None:
            self.dynamics.store(at, row)
        for name, beyond in row.outside.items():
            self.outside[name][at] = beyond
        for s in row.stopped:
            what = (
                f"row {self.vars[1].name} = {self.vars[1].shown(self.vars[1].values[row.index])}: "
                if self.grid
                else ""
            )
            self.notes.append(f"{what}{s}")

    def result(self) -> SweepResult:
        """Classify the located points and return the result (once: later calls return
        the same result)."""
        if self._result is None:
            self._result = self._classified()
        return self._result

    def _classified(self) -> SweepResult:
        eng = self.engine
        # how the sweep started (a singular start, rows started from a neighbour) first,
        # and the tests the file lacks the ingredients of
        not_run = [f"tests not run: {s}" for s in not_run_sentences(self.mechanism)]
        self.notes[:0] = [n for n in [*not_run, *eng.start_notes] if n not in self.notes]
        self.notes += limits_notes(eng.limited, self.outside, self.reached)
        located = sorted(self.located, key=lambda p: (p.edge != "row", p.values[::-1]))
        # the points found along the rows first, then those between rows (a grid)
        chosen = list(located)
        if self.grid and len(chosen) > self.max_classified:
            pick = np.linspace(0, len(chosen) - 1, self.max_classified).round().astype(int)
            chosen = [chosen[i] for i in sorted(set(pick.tolist()))]
            self.notes.append(
                f"{len(self.located)} singular points located; the full analysis classified "
                f"{len(chosen)} of them, spread over the grid (max_classified)"
            )
        with working_on(file=self.mechanism.path or self.mechanism.name):
            classified = classify_located(eng, chosen, self.prec, self.time_limit)
        analysed, moved, at = classified.results, classified.moved, classified.points
        if self.prec.mode == "mp" and chosen or self.prec.mode == "auto" and any(moved):
            self.notes.append(
                f"{sum(moved)} of the {len(chosen)} classified points were located again at "
                f"{self.prec if self.prec.mode == 'mp' else 'mp:50'} before their analysis"
                + ("" if all(moved) else "; the others keep their float values")
            )
        by_id = {id(p): a for p, a in zip(chosen, analysed, strict=True)}
        point_by_id = {id(p): v for p, v in zip(chosen, at, strict=True)}
        moved_by_id = {id(p): m for p, m in zip(chosen, moved, strict=True)}
        # the points found again at N digits: their joints as text at those digits
        texts = {
            id(p): located_texts(eng, q, a)
            for p, a, m, q in zip(chosen, analysed, moved, at, strict=True)
            if m and a.error is None and a.precision.startswith("mp:")
        }
        model = eng.model
        out = []
        for p in located:
            joints = tuple((k, tuple(v)) for k, v in model.values(p.q).items())
            unresolved_why = unresolved(
                p, by_id.get(id(p)), moved_by_id.get(id(p), False), self._drives(p)
            )
            if unresolved_why:
                self.notes.append(
                    f"the limit of travel at {', '.join(v.name for v in self.variables)} = "
                    f"{', '.join(v.shown(x) for v, x in zip(self.variables, p.values, strict=True))} "
                    f"was not resolved: {unresolved_why}"
                )
            values_text, joints_text = texts.get(id(p), (None, None))
            out.append(
                LocatedSingularity(
                    p.values,
                    p.kind,
                    p.tests,
                    float(p.ratio),
                    joints,
                    by_id.get(id(p)),
                    p.far_side,
                    p.edge,
                    unresolved_why,
                    values_text,
                    joints_text,
                    point_by_id.get(id(p), ClosedValue(p.q, FLOAT_DIGITS, "located")),
                )
            )
        loci = loci_of(self, out) if self.grid else ()
        aspects: tuple[Any, ...] = ()
        if self.grid:
            from mechsing.sweeps.aspects import aspects_of, regular_samples

            aspects = aspects_of(
                self.vars[0].values,
                self.vars[1].values,
                regular_samples(self.reached, self.rank, self.generic),
                out,
            )
        if self.statics is not None:
            rows = self.vars[1].values if self.grid else None
            self.statics.locate_limits(eng, self.vars[0].values, rows)
        if self.dynamics is not None:
            self.dynamics.locate(out)
        return SweepResult(
            self.mechanism,
            self.variables,
            self.from_config,
            self.precision,
            self.tests,
            self.generic,
            self.held,
            self.reached,
            self.rank,
            self.ratio,
            tuple(out),
            tuple(loci),
            tuple(
                stop_notes(self.mechanism, self.notes, (p.classes for p in out if p.kind == "fold"))
            ),
            self.newton_iterations,
            time.perf_counter() - self.start_time,
            self.outside,
            statics=self.statics,
            mode=self.mode,
            aspects=aspects,
            dynamics=self.dynamics,
            start=self.start,
        )
