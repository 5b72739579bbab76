"""Verdicts that rest on less than the resolution of their data.

A value written with digits to spare (``1.85459043600322``) is a rounding of the value
meant: its resolution is half a unit in its last written digit (the reader's
:attr:`mechsing.model.Configuration.resolution`; exact expressions and short decimals
have none).  A configuration drawn at a singular pose and written to 15-17 digits is
within that resolution of the singularity, and a precise mode (mp:50, exact, or auto
re-deciding at mp:50) may find the written decimals regular by 1e-15: true of the
decimals, misleading to the reader who drew the singular pose.

Owns :class:`DataResolution` (what a verdict rests on against the data's resolution,
with the note a reader sees) and :func:`resolution_check`: the first-order bound of how
far the given values' resolution can move the tests' relative singular values
(:func:`mechsing.singularity.resolution.value_slopes`,
:func:`mechsing.numeric.resolution_spread`), and whether a decision behind the verdict
could flip within it (:func:`mechsing.numeric.flips_within`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.model import Mechanism
from mechsing.numeric import flips_within, resolution_spread
from mechsing.singularity.findings import UndecidedFinding
from mechsing.singularity.local import float_model
from mechsing.singularity.resolution import (
    geometry_slopes,
    geometry_step,
    value_slopes,
    value_step,
)

__all__ = ["DataResolution", "resolution_check"]


@dataclass(frozen=True)
class DataResolution:
    """A verdict that rests on a margin below the resolution of the given values.

    ``digits``: the fewest significant digits of a given value with a resolution;
    ``resolution``: the largest resolution of a given value (SI, radians); ``spread``:
    the first-order bound on how far that can move a relative singular value;
    ``value``: the relative singular value the verdict rests on (the smallest kept one
    of a regular verdict, the largest dropped one of a singular verdict); ``test``:
    whose it is; ``singular``: the verdict's side."""

    digits: int
    resolution: float
    spread: float
    value: float
    test: str
    singular: bool
    #: the precision whose singular verdict ``auto`` keeps because the written decimals'
    #: verdict at mp:50 (``singular`` False) is below the data's resolution; None when the
    #: verdict reported is the written decimals' own
    verdict_from: str | None = None

    @property
    def note(self) -> str:
        """The sentence a reader sees (text, Markdown, report and JSON ``notes``)."""
        data = f"its {self.digits}-digit data"
        if self.verdict_from is not None:
            return (
                f"at 50 digits the written decimals are regular by {self.value:.1g} "
                f"({self.test} test), below the resolution of {data}, which can move it by "
                f"{self.spread:.1g}: the singular configuration {self.verdict_from} finds "
                "lies within the data's resolution, so auto keeps its verdict; give more "
                "digits or exact values to decide the written decimals"
            )
        if self.singular:
            return (
                f"singular at the written decimals (the {self.test} test's dropped singular "
                f"value is {self.value:.1g} of its largest), but the resolution of {data} can "
                f"move it by {self.spread:.1g}: a regular configuration may lie within it; "
                "give more digits or exact values"
            )
        return (
            f"within {self.value:.1g} of a singular configuration ({self.test} test): below "
            f"the resolution of {data}, which can move it by {self.spread:.1g}; give more "
            "digits, exact values, or let mechsing solve it"
        )

    @property
    def verdict(self) -> str:
        """The verdict's words: what holds of the written decimals, and that it is below
        the data's resolution."""
        if self.verdict_from is not None:
            return (
                f"singular in {self.verdict_from}, within the resolution of its "
                f"{self.digits}-digit data (the written decimals are regular by "
                f"{self.value:.1g} at 50 digits)"
            )
        side = "singular" if self.singular else "regular"
        return (
            f"{side} at the written decimals, below the resolution of its {self.digits}-digit data"
        )


def _test_of(f: Any) -> str:
    """The decision name of a finding's test."""
    if f.cls == "serial":
        return "output chain" if f.chain == "output" else f"leg {f.leg} chain"
    if f.cls in ("bifurcation", "isolated", "degenerate", "increased-mobility"):
        return "closure"
    return str(f.cls)


def resolution_check(mech: Mechanism, result: Any, model: Any) -> DataResolution | None:
    """Does the verdict of ``result`` (an analysed configuration of ``mech``; ``model``:
    a kinematic model of it, any precision) rest on a margin below the resolution of
    the values its configuration gives?  None when it does not (or has no such data)."""
    cfg = mech.configurations.get(result.name)
    if cfg is None or not (cfg.resolution or mech.resolution) or result.error is not None:
        return None
    singular = result.singular
    if singular is None:
        return None  # undecided: nothing rests on a margin
    if singular:
        margins = [
            (_test_of(f), f.margin)
            for f in result.singularities
            if not isinstance(f, UndecidedFinding) and f.margin is not None
        ]
    else:
        margins = [(d.test, d.margin) for d in result.decisions if d.rank is not None]
    if not margins or (not mech.loops and mech.output is None):
        # nothing rests on a margin, or no test whose singular values the data move (a
        # tree with no loop and no output: :func:`test_sigmas` has none)
        return None
    fm = float_model(model)
    columns: list[int] = []
    resolutions: list[float] = []
    digits: list[int] = []
    kept = set(mech.joint_names)  # the joints analysed: a scene's output leaves branches out
    for joint, entries in cfg.resolution.items():
        if joint not in kept:
            continue
        start = fm.joint(joint).columns.start
        for i, (res, ndigits) in enumerate(entries):
            if res > 0:
                columns.append(start + i)
                resolutions.append(res)
                digits.append(ndigits)
    # the geometry's resolution too (a point, a pitch, a direction written with digits
    # to spare), with the joint values held
    written = [entry for entry in mech.resolution if entry[0] in kept]
    geometry = [(j, key, i) for j, key, i, _res, _d in written]
    # within reach?  A slope is a change of a relative singular value (in [0, 1]: at most
    # 1, twice that on the safe side of rounding) over its step, so the spread is at most
    # sum(2 res / step): a verdict whose every margin is farther than that cannot flip
    # (a larger spread flips more), and needs no slope
    steps = [value_step(fm, c) for c in columns] + [
        geometry_step(fm, key) for _, key, _ in geometry
    ]
    resolutions += [res for *_, res, _d in written]
    digits += [d for *_, d in written]
    reach = resolution_spread([2 / h for h in steps], resolutions)
    if all(flips_within(m, reach, singular) is None for _, m in margins):
        return None
    values = dict(result.joints)
    q = np.array([float(values[j][i]) for j, i in mech.coordinates()], dtype=float)
    slopes = value_slopes(mech, fm, q, columns) + geometry_slopes(mech, fm, q, geometry)
    spread = resolution_spread(slopes, resolutions)
    flips = [(v, t) for t, m in margins if (v := flips_within(m, spread, singular)) is not None]
    if not flips:
        return None
    # the value the verdict rests on most weakly: the smallest kept, the largest dropped
    value, test = max(flips) if singular else min(flips)
    return DataResolution(min(digits), max(resolutions), spread, value, test, singular)
