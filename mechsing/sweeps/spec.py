"""What a sweep varies: ``--vary NAME=START:STOP:STEP`` read and checked against a mechanism.

Owns :class:`Vary` (the user's words, in the file's units) and :class:`Variable` (what
it is in the model: a joint coordinate or an output-pose coordinate, its column, its
unit and its sample values in SI units and radians).

Names: a joint of one coordinate by its name (``A``); one coordinate of a joint of
several by its index in the joint's catalog order (``C1[1]``, ``S1[0]``); the output's
pose by ``pose.x``, ``pose.y``, ``pose.z`` (the position of the output's reference
point, ground axes) and ``pose.rx``, ``pose.ry``, ``pose.rz`` (its rotation vector from
the reference configuration, about the reference point, ground axes).  Ranges are in the
file's units (``units:``), inclusive of STOP when the steps land on it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from mechsing.errors import UserError
from mechsing.kinematics.pose import POSE_COORDINATES
from mechsing.model import Mechanism
from mechsing.numeric import Precision
from mechsing.numeric.numbers import decimal_float, is_decimal_text
from mechsing.sweeps.settings import RADIAN_LOOK_ATOL, SWEEP_RANGE_ATOL, SWEEP_RANGE_RTOL

__all__ = ["MAX_SAMPLES", "Variable", "Vary", "check_varies", "resolve", "sweep_precision"]

#: most samples of one swept variable, and of a whole grid
MAX_SAMPLES = 10_000_000

_NAME_ONLY = re.compile(r"^\s*([A-Za-z_][\w.\-]*(?:\[\d+\])?)\s*$")
#: samples of a sweep over a joint's limits (``--vary J2`` given without a range)
LIMIT_STEPS = 200
_SPEC = re.compile(r"^\s*([A-Za-z_][\w.\-]*(?:\[\d+\])?)\s*=\s*([^:]+):([^:]+):([^:]+)\s*$")


@dataclass(frozen=True)
class Vary:
    """One swept variable as the user gives it: a name and a range in the file's units."""

    name: str
    start: float
    stop: float
    step: float

    @classmethod
    def parse(cls, text: str) -> Vary:
        """``NAME=START:STOP:STEP`` (numbers in the file's units)."""
        m = _SPEC.match(text)
        bare = _NAME_ONLY.match(text)
        if bare and not bare.group(1).startswith("pose."):  # a joint: its limits are the range
            return cls(bare.group(1), math.nan, math.nan, math.nan)
        if not m:
            raise UserError(
                f"--vary {text!r}: expected NAME=START:STOP:STEP, e.g. --vary A=0:360:1 "
                "(a joint), --vary C1[1]=0:0.5:0.01 (one coordinate of a joint of several) "
                "or --vary pose.x=-0.1:0.1:0.01"
            )
        name, *nums = m.groups()
        if not all(is_decimal_text(x) for x in nums):
            raise UserError(
                f"--vary {text!r}: START, STOP and STEP must be numbers in ASCII decimal "
                "digits (in the file's units)"
            )
        try:
            start, stop, step = (decimal_float(x) for x in nums)
        except ValueError as exc:
            raise UserError(f"--vary {text!r}: {exc} (in the file's units)") from None
        return cls(name, start, stop, step)

    @property
    def ranged(self) -> bool:
        """False for a joint given without a range (swept over its limits)."""
        return not math.isnan(self.step)

    def count(self) -> int:
        """The number of samples of the range (STOP included when the steps land on it)."""
        if not self.ranged:
            raise UserError(f"--vary {self.name}: no range, and the joint's limits not read yet")
        if not all(math.isfinite(x) for x in (self.start, self.stop, self.step)):
            raise UserError(f"--vary {self.name}: the range must be finite numbers")
        if self.step <= 0:
            raise UserError(
                f"--vary {self.name}: STEP must be positive ({self.step:g}); to go down, "
                "give START above STOP"
            )
        steps = abs(self.stop - self.start) / self.step * (1 + SWEEP_RANGE_RTOL) + SWEEP_RANGE_ATOL
        if not steps < MAX_SAMPLES:  # also an infinite quotient of a tiny STEP
            raise UserError(
                f"--vary {self}: more than {MAX_SAMPLES:,} samples, more than a sweep takes; "
                "use a larger STEP"
            )
        return int(math.floor(steps)) + 1

    def values(self) -> np.ndarray:
        """The sample values in the file's units, from START towards STOP."""
        k = self.count()
        sign = 1.0 if self.stop >= self.start else -1.0
        return self.start + sign * self.step * np.arange(k)

    def __str__(self) -> str:
        return f"{self.name}={self.start:g}:{self.stop:g}:{self.step:g}"


@dataclass(frozen=True)
class Variable:
    """A swept variable in the model: ``kind`` "joint" or "pose"; ``column``: its index
    among the joint coordinates (a joint), or among the six pose coordinates
    ``(rx, ry, rz, x, y, z)``; ``unit`` "rad" or "m" (SI) and the file's unit with its
    factor to SI; ``values``: the samples in SI; ``periodic``: a revolute angle."""

    name: str
    kind: str
    column: int
    unit: str
    file_unit: str
    factor: float
    values: np.ndarray
    periodic: bool

    def shown(self, si: float) -> str:
        """A value in the file's units, with the unit."""
        return f"{si / self.factor:.10g} {self.file_unit}"


def check_varies(texts: list[str], what: str = "a sweep") -> list[Vary]:
    """The ``--vary`` values of a command read and checked before the file is read: one
    or two, each range's own errors (STEP <= 0, not finite); a joint given without a
    range is checked once its limits are read (:func:`with_limits`).  ``what``: what
    sweeps in the command ("a sweep", "a report"), for the message."""
    _one_or_two(len(texts), what)
    varies = [Vary.parse(text) for text in texts]
    for v in varies:
        if v.ranged:
            v.count()
    return varies


def _one_or_two(n: int, what: str) -> None:
    if n > 2:
        raise UserError(
            f"--vary is given {n} times: {what} varies one variable (a path) or two "
            "(a grid); give --vary once or twice"
        )


def sweep_precision(prec: Precision) -> None:
    """The precision policy of a sweep: its located points are float data, so exact mode
    cannot classify them (UserError)."""
    if prec.mode == "exact":
        raise UserError(
            "--precision exact: a sweep locates its singularities numerically, so their "
            "values are not exact data; use --precision auto (the default) or mp:N"
        )


def vary_warnings(mech: Mechanism, varies: list[Vary]) -> list[str]:
    """Likely mistakes of the swept ranges that are not errors, worded as the file's
    warnings: in a file whose angles are in degrees, an angle's range that looks like
    radians (both ends within a full turn in radians and one of them within
    :data:`~mechsing.sweeps.settings.RADIAN_LOOK_ATOL` of a multiple of pi/2: ``A=-3.14:1.5:0.01``), as a plain value
    above a full turn in a file in radians is warned about."""
    if mech.units.angle == "rad":
        return []
    out = []
    for v in varies:
        if not v.ranged or not _is_angle(mech, v.name):
            continue
        ends = (v.start, v.stop)
        near = [
            x
            for x in ends
            if x
            and abs(x / (math.pi / 2) - round(x / (math.pi / 2))) * math.pi / 2 < RADIAN_LOOK_ATOL
        ]
        if max(abs(x) for x in ends) <= 2 * math.pi + RADIAN_LOOK_ATOL and near:
            deg = [math.degrees(x) for x in (v.start, v.stop, v.step)]
            out.append(
                f"--vary {v}: the range looks like radians ({near[0]:g} is about "
                f"{near[0] / math.pi:.3g} pi), but the file's angles are in degrees "
                f"(units: {{angle: {mech.units.angle}}}), so it sweeps {abs(v.stop - v.start):g} "
                f"degrees; if it is meant in radians, write it in degrees: --vary "
                f"{v.name}={deg[0]:.6g}:{deg[1]:.6g}:{deg[2]:.6g}"
            )
    return out


def _is_angle(mech: Mechanism, name: str) -> bool:
    """Whether the swept variable ``name`` (a joint coordinate or pose.*) is an angle."""
    if name.startswith("pose."):
        return name in ("pose.rx", "pose.ry", "pose.rz")
    joint, _, rest = name.partition("[")
    if joint not in mech.joint_names:
        return False
    units = mech.joint(joint).units
    index = int(rest.rstrip("]")) if rest.rstrip("]").isdigit() else 0
    return index < len(units) and units[index] == "rad"


def with_limits(mech: Mechanism, v: Vary) -> Vary:
    """A joint given without a range (``--vary J2``) is swept over its limits (the file's
    ``limits``) in :data:`LIMIT_STEPS` steps; exit 2 when the joint has no limits."""
    if v.ranged:
        return v
    name, _, rest = v.name.partition("[")
    index = int(rest.rstrip("]")) if rest else 0
    if name not in mech.joint_names:
        raise UserError(
            f"--vary {v.name}: no joint named {name!r}; the joints are "
            f"{', '.join(mech.joint_names[:12])}"
        )
    joint = mech.joint(name)
    if name not in mech.limits:
        raise UserError(
            f"--vary {v.name}: joint {name!r} has no limits in the file, so the sweep has no "
            f"range; give one (--vary {v.name}=START:STOP:STEP) or add limits: {{{name}: "
            "[lower, upper]} to the file"
        )
    if index >= joint.dof:
        raise UserError(f"--vary {v.name}: joint {name!r} has {joint.dof} coordinate(s)")
    unit = joint.units[index]
    factor = float(mech.units.angle_factor if unit == "rad" else mech.units.length_factor)
    lo, hi = (x / factor for x in mech.limits[name][index])
    return Vary(v.name, lo, hi, (hi - lo) / LIMIT_STEPS)


def resolve(mech: Mechanism, varies: list[Vary]) -> list[Variable]:
    """The swept variables of a mechanism, checked: one (a path) or two (a grid)."""
    if not varies:
        raise UserError(
            "a sweep needs --vary NAME=START:STOP:STEP (one for a path, two for a grid)"
        )
    _one_or_two(len(varies), "a sweep")
    names = [v.name for v in varies]
    if len(set(names)) != len(names):
        raise UserError(f"--vary {names[0]} is given twice")
    units = mech.units
    af, lf = float(units.angle_factor), float(units.length_factor)
    coords = mech.coordinates()
    out = []
    total = 1
    for v in varies:
        count = v.count()
        total *= count
        if count > MAX_SAMPLES or total > MAX_SAMPLES:
            raise UserError(
                f"--vary {v}: {total:,} samples, more than a sweep takes ({MAX_SAMPLES:,}); "
                "use a larger STEP"
            )
        if v.name.startswith("pose."):
            key = v.name
            if key not in POSE_COORDINATES:
                raise UserError(
                    f"--vary {v.name}: the output's pose coordinates are "
                    f"{', '.join(POSE_COORDINATES)}"
                )
            if mech.output is None:
                raise UserError(
                    f"--vary {v.name}: the mechanism has no output, so no output pose to sweep; "
                    "add output: {body: ...} to the file"
                )
            k = POSE_COORDINATES.index(key)
            angle = k < 3
            factor = af if angle else lf
            out.append(
                Variable(
                    v.name,
                    "pose",
                    k,
                    "rad" if angle else "m",
                    units.angle if angle else units.length,
                    factor,
                    v.values() * factor,
                    False,
                )
            )
            continue
        m = re.fullmatch(r"(.+?)(?:\[(\d+)\])?", v.name)
        assert m is not None
        jname, idx = m.group(1), m.group(2)
        if jname not in mech.joint_names:
            known = ", ".join(mech.joint_names)
            raise UserError(
                f"--vary {v.name}: no joint named {jname!r}; the joints are {known} (or pose.x, "
                "pose.y, pose.z, pose.rx, pose.ry, pose.rz for the output's pose)"
            )
        joint = mech.joint(jname)
        if idx is None:
            if joint.dof != 1:
                raise UserError(
                    f"--vary {v.name}: joint {jname!r} ({joint.type}) has {joint.dof} coordinates; "
                    f"name one: {jname}[0] ... {jname}[{joint.dof - 1}] (catalog order, "
                    f"units {', '.join(joint.units)})"
                )
            i = 0
        else:
            i = int(idx)
            if joint.dof == 1 and i != 0:
                raise UserError(
                    f"--vary {v.name}: joint {jname!r} ({joint.type}) has one coordinate; "
                    f"name it {jname}"
                )
            if i >= joint.dof:
                raise UserError(
                    f"--vary {v.name}: joint {jname!r} has coordinates {jname}[0] ... "
                    f"{jname}[{joint.dof - 1}]"
                )
        col = coords.index((jname, i))
        angle = joint.units[i] == "rad"
        factor = af if angle else lf
        out.append(
            Variable(
                v.name,
                "joint",
                col,
                joint.units[i],
                units.angle if angle else units.length,
                factor,
                v.values() * factor,
                joint.type in ("R", "U"),
            )
        )
    kinds = {x.kind for x in out}
    if len(out) == 2 and kinds == {"joint", "pose"}:
        raise UserError(
            "a sweep varies joint coordinates or the output's pose, not both: the joints are "
            "solved for the pose"
        )
    return out
