"""Sweeps per assembly mode, and loops: :func:`sweep_modes` and :class:`ModeSweeps`.

A sweep follows one assembly mode: the one continuation reaches from its start
configuration, or the mode of the start's inputs given by ``start``
(:func:`~mechsing.sweeps.start.mode_start`).  :func:`sweep_modes` runs one sweep per mode
that ``mechsing modes`` finds at the start configuration (all of them, or those asked
for), each sample labelled with its mode; with ``loop`` each follows the closed path
around the rectangle of its two ranges (:mod:`.loop`) and says on which mode it comes
back: a loop back on another mode with no singularity located on it is **a mode change
without a singularity** (``mode_changes``).

Owns :func:`sweep_modes`, :func:`mode_runs`, :func:`mode_loops` and :class:`ModeSweeps`.
"""

from __future__ import annotations

from contextlib import ExitStack
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from mechsing.errors import UserError
from mechsing.model import Mechanism
from mechsing.numeric import Precision
from mechsing.numeric.tolerances import SWEEP_SAME_MODE_DISTANCE
from mechsing.reader import read_mechanism
from mechsing.sweeps.loop import LoopResult, follow_loop
from mechsing.sweeps.results import SweepResult
from mechsing.sweeps.run import MAX_CLASSIFIED, SweepRun
from mechsing.sweeps.start import mode_out_of_range

__all__ = ["ModeSweeps", "loops_markdown", "mode_loops", "mode_runs", "sweep_modes"]


@dataclass(frozen=True)
class ModeSweeps:
    """The sweeps of several assembly modes (``sweeps``: one
    :class:`~mechsing.sweeps.results.SweepResult` per mode, its ``mode`` its number; empty
    for loops) or their loops (``loops``), and the number of modes of the start
    configuration (``count``)."""

    sweeps: tuple[SweepResult, ...]
    loops: tuple[LoopResult, ...]
    count: int | None
    #: the JSON keys before a loop sweep's points (the sweep's header, with ``modes``)
    header: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @property
    def mode_changes(self) -> tuple[LoopResult, ...]:
        """The loops that come back on another mode without a singularity."""
        return tuple(lo for lo in self.loops if lo.mode_change)

    def to_json(self) -> dict[str, Any]:
        """The document ``mechsing sweep --modes all`` writes (``--loop``: the loops)."""
        if self.loops:
            return {**self.header, **loops_json(self.loops)}
        from mechsing.sweeps.results import json_header, json_point, json_tail

        first = self.sweeps[0]
        out = {k: v for k, v in json_header(first).items() if k != "mode"}
        out["modes"] = [r.mode for r in self.sweeps]
        out["points"] = [
            json_point(r, idx) for r in self.sweeps for idx in np.ndindex(r.reached.shape)
        ]
        out.update(merged_tail([json_tail(r) for r in self.sweeps], [r.mode for r in self.sweeps]))
        return out

    def to_text(self) -> str:
        """Each mode's sweep in words, one after the other (``--loop``: each loop)."""
        if self.loops:
            return loops_text(self.loops)
        return "\n".join(r.to_text() for r in self.sweeps)


def merged_tail(tails: list[dict[str, Any]], modes: list[int | None]) -> dict[str, Any]:
    """The JSON keys after the points of several modes' sweeps: their lists joined (each
    entry carries its ``mode``), each note prefixed with its mode, the Newton iterations
    summed."""
    out: dict[str, Any] = {}
    for key in tails[0]:
        values = [t[key] for t in tails]
        if key == "notes":
            out[key] = [f"mode {m}: {n}" for m, t in zip(modes, values, strict=True) for n in t]
        elif key == "newton_iterations":
            out[key] = int(sum(values))
        elif isinstance(values[0], list):
            out[key] = [x for v in values for x in v]
        else:
            out[key] = values[0]
    return out


def mode_runs(
    mechanism: Mechanism | str | Path,
    vary: list[Any],
    from_config: str | None = None,
    precision: Precision | str = "auto",
    modes: str | list[int] = "all",
    **options: Any,
) -> tuple[list[SweepRun], Any]:
    """One :class:`~mechsing.sweeps.run.SweepRun` per assembly mode of the start
    configuration (``modes``: "all", or their numbers, 1 to the count, as ``mechsing
    modes`` numbers them), and the modes found (:class:`~mechsing.assembly.ModesResult`).
    ``options``: the other keywords of :class:`SweepRun` (``max_classified``,
    ``time_limit``)."""
    from mechsing.assembly.api import modes as find_modes

    mech = mechanism if isinstance(mechanism, Mechanism) else read_mechanism(mechanism)
    config = from_config or "reference"
    found = find_modes(mech, config, "float") if config in mech.configurations else None
    if found is None:  # the sweep's own error names the configurations
        SweepRun(mech, vary, from_config, precision, **options)
    assert found is not None
    count = len(found.modes)
    if not count:
        raise UserError(
            f"--modes: configuration {config!r} has no real assembly mode "
            f"(mechsing modes FILE --config {config})"
        )
    numbers = list(range(1, count + 1)) if modes == "all" else list(modes)
    for k in numbers:
        if not 1 <= k <= count:
            raise mode_out_of_range(k, config, count)
    runs = [
        SweepRun(mech, vary, from_config, precision, start=k - 1, modes_found=found, **options)
        for k in numbers
    ]
    return runs, found


def mode_loops(runs: list[SweepRun], found: Any = None) -> list[LoopResult]:
    """The loop of each run (:func:`~mechsing.sweeps.loop.follow_loop`), the mode each
    comes back on named: the mode of ``found`` (the start configuration's modes) when the
    start's values are the loop's corner, or the mode whose loop left from where it came
    back."""
    from mechsing.assembly.result import joint_distance

    for v in runs[0].vars if runs else ():
        if len(v.values) < 2:  # START = STOP: the rectangle has no area, no inside
            raise UserError(
                f"--loop: --vary {v.name} has one sample ({v.shown(float(v.values[0]))}): "
                "a loop goes round a rectangle; give each --vary a START and STOP at least a STEP apart"
            )
    loops = [follow_loop(run) for run in runs]
    if not runs:
        return loops
    mech = runs[0].mechanism
    L = float(runs[0].engine.model.length_scale)
    coords = mech.coordinates()
    candidates: list[tuple[int, list[float]]] = []
    eng = runs[0].engine
    corner = [float(v.values[0]) for v in runs[0].vars]
    if found is not None and all(
        float(eng.z0[c]) == x for c, x in zip(eng.cols, corner, strict=True)
    ):
        candidates += [
            (k + 1, [float(m.joints[j][i]) for j, i in coords]) for k, m in enumerate(found.modes)
        ]
    for lo in loops:
        if lo.mode is not None:
            candidates.append(
                (lo.mode, [float(x) for j in lo.joints_start for x in lo.joints_start[j]])
            )
    out = []
    for lo in loops:
        if lo.joints_end is not None and lo.end_mode is None:
            end = [float(x) for j in lo.joints_end for x in lo.joints_end[j]]
            near = [
                k
                for k, q in candidates
                if joint_distance(mech, q, end, L) <= SWEEP_SAME_MODE_DISTANCE
            ]
            if near:
                lo = replace(lo, end_mode=near[0])
        out.append(lo)
    return out


def loop_header(runs: list[SweepRun]) -> dict[str, Any]:
    """The header of a loop sweep's JSON: the sweep's (without ``mode``), ``modes`` (the
    modes the loops started on; null entries for the one continuation reaches) and the
    Newton iterations of every loop."""
    from mechsing.sweeps.results import json_header

    head = {k: v for k, v in json_header(runs[0]).items() if k != "mode"}
    head["modes"] = [r.mode for r in runs]
    head["newton_iterations"] = int(sum(r.newton_iterations for r in runs))
    return head


def loops_json(loops: tuple[LoopResult, ...] | list[LoopResult]) -> dict[str, Any]:
    """The keys after the header of a loop sweep's JSON: ``points`` (every loop's samples,
    one loop after the other), ``located`` (their singularities, each with its loop's
    ``mode``), ``loci`` (none), ``notes``, ``newton_iterations`` (0: counted by the
    sweeps' runs), ``loops`` and ``mode_changes``."""

    def mode(lo: LoopResult) -> dict[str, Any]:
        return {} if lo.mode is None else {"mode": lo.mode}

    return {
        "points": [p for lo in loops for p in lo.points_json()],
        "located": [{**s.to_json(), **mode(lo)} for lo in loops for s in lo.singularities],
        "loci": [],
        "notes": [
            (f"mode {lo.mode}: " if lo.mode is not None else "") + f"loop not closed: {n}"
            for lo in loops
            for n in lo.notes
        ],
        "loops": [lo.to_json() for lo in loops],
        "mode_changes": [lo.change_json() for lo in loops if lo.mode_change],
    }


def loops_text(loops: tuple[LoopResult, ...] | list[LoopResult], shown: Any = None) -> str:
    """The loops in words, then the mode changes without a singularity."""
    shown = shown or (lambda v: f"({v[0]:.6g}, {v[1]:.6g})")
    lines = []
    for lo in loops:
        lines += lo.text_lines(shown)
    changes = [lo for lo in loops if lo.mode_change]
    if changes:
        lines.append(
            "  mode changes without a singularity: "
            + "; ".join(f"mode {lo.mode} -> mode {lo.end_mode}" for lo in changes)
        )
    else:
        lines.append("  no mode change without a singularity")
    return "\n".join(lines) + "\n"


def loops_markdown(title: str, loops: tuple[LoopResult, ...] | list[LoopResult], shown: Any) -> str:
    """The loops as Markdown: a table (one row per loop) and the mode changes without a
    singularity, each with its loop."""
    lines = [f"# {title}", ""]
    corners = loops[0].corners if loops else ()
    if corners:
        lines += [f"The loop: {' → '.join(shown(c) for c in corners)}.", ""]
    lines += [
        "| from mode | closed | back on | singularities located | mode change without a singularity |",
        "|---|---|---|---|---|",
    ]
    for lo in loops:
        back = (
            "-"
            if not lo.closed
            else "another mode"
            if lo.end_mode is None
            else f"mode {lo.end_mode}"
        )
        sing = sum(1 for *_, s in lo.located if s is not False)
        lines.append(
            f"| {lo.mode if lo.mode is not None else 'start'} | "
            f"{'yes' if lo.closed else 'no: ' + '; '.join(lo.notes)} | {back} | {sing} | "
            f"{'**yes**' if lo.mode_change else 'no'} |"
        )
    changes = [lo for lo in loops if lo.mode_change]
    lines += ["", "## Mode changes without a singularity", ""]
    if not changes:
        lines.append("None: no loop came back on another assembly mode without a singularity.")
    for lo in changes:
        lines.append(
            f"- mode {lo.mode} → mode {lo.end_mode}: around the loop, no singularity located "
            f"({len(lo.values)} samples; joint distance between start and end {lo.distance:.3g})"
        )
    return "\n".join(lines) + "\n"


def sweep_modes(
    mechanism: Mechanism | str | Path,
    vary: list[Any],
    from_config: str | None = None,
    precision: Precision | str = "auto",
    *,
    modes: str | list[int] | None = "all",
    loop: bool = False,
    workers: int | None = None,
    scheduler: str | None = None,
    max_classified: int = MAX_CLASSIFIED,
    time_limit: float | None = None,
) -> ModeSweeps:
    """Sweep a mechanism from every assembly mode of its start configuration.

    Parameters
    ----------
    mechanism, vary, from_config, precision
        As :func:`mechsing.sweep`.
    modes : "all", a list of mode numbers, or None
        The modes of ``from_config`` (as ``mechsing modes`` numbers them, from 1) the
        sweeps start on; None: the one continuation reaches (then only with ``loop``).
    loop : bool
        With two swept variables: follow the closed path around the rectangle of their
        ranges (from the corner START, START) instead of the grid, and say on which mode
        each comes back (``mode_changes``: back on another mode with no singularity
        located on the way).
    workers, scheduler : int, str, optional
        Distribute each mode's grid with Dask, as :func:`mechsing.sweep` does.

    Returns
    -------
    ModeSweeps
    """
    options = {"max_classified": max_classified, "time_limit": time_limit}
    if modes is None:
        runs, found = [SweepRun(mechanism, vary, from_config, precision, **options)], None
    else:
        runs, found = mode_runs(mechanism, vary, from_config, precision, modes, **options)
    if loop:
        if not runs[0].grid:
            raise UserError("--loop follows the rectangle of two ranges: give two --vary")
        loops = tuple(mode_loops(runs, found))
        return ModeSweeps((), loops, len(found.modes) if found else None, loop_header(runs))
    if modes is None:
        raise UserError("sweep_modes: give modes ('all' or their numbers), or loop=True")
    out = []
    with ExitStack() as stack:
        client = None
        if (workers or scheduler) and runs and runs[0].grid:
            # one cluster for every mode's grid (its workers keep the engine they built)
            from mechsing.sweeps.distributed import open_client

            client = stack.enter_context(open_client(workers, scheduler))
        for run in runs:
            for _ in run.rows(None, workers=workers, scheduler=scheduler, client=client):
                pass
            out.append(run.result())
    return ModeSweeps(tuple(out), (), len(found.modes) if found else None)
