"""The statics of a configuration (what :mod:`mechsing.statics` offers): the record
:class:`Kinetostatics` with its JSON and text, the statics at a closed configuration
(:func:`kinetostatics`, :func:`kinetostatics_at`, with the bodies' weights), the load a
configuration is analysed under (:func:`load_of`), and an analysis result with its
configurations' statics attached (:func:`with_kinetostatics`)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.analysis.display import floor_for
from mechsing.model.loads import mass_centre
from mechsing.numeric import Precision, floored, to_float
from mechsing.statics.efforts import EffortMap, Equilibrium, effort_map, equilibrium, load_wrench
from mechsing.statics.matrices import MotionMatrices, float_configuration, motion_matrices
from mechsing.statics.transmission import Transmission, transmission
from mechsing.statics.units import UnitEfforts, unit_efforts

__all__ = [
    "Kinetostatics",
    "kinetostatics",
    "kinetostatics_at",
    "load_of",
    "with_kinetostatics",
]


@dataclass(frozen=True)
class Kinetostatics:
    """The statics of one configuration: ``equilibrium`` for its load (None without one),
    the largest unit efforts and the transmission indices."""

    equilibrium: Equilibrium | None
    units: UnitEfforts
    transmission: Transmission
    inputs: tuple[str, ...]
    input_lengths: tuple[bool, ...]
    #: the bodies whose weights the efforts hold too (the file's mass and gravity)
    weighed: tuple[str, ...] = ()
    #: the characteristic length L (m): a force times L compares with a torque
    length_scale: float = 1.0

    def to_json(self) -> dict[str, Any]:
        """The configuration's JSON keys: ``efforts`` (null when unbounded) and
        ``kinetostatics`` (docs/json.md)."""
        eq = self.equilibrium
        body: dict[str, Any] = {
            "effort_units": {
                n: ("N" if ln else "N m")
                for n, ln in zip(self.inputs, self.input_lengths, strict=True)
            },
            "largest_unit_efforts": self.units.to_json(),
            "transmission": self.transmission.to_json(),
        }
        out: dict[str, Any] = {}
        if eq is not None:
            out["efforts"] = eq.efforts
            body["load"] = {
                "wrench": [float(x) for x in eq.wrench],
                "point": [float(x) for x in eq.point],
            }
            body["weighed_bodies"] = list(self.weighed)
            body["bounded"] = eq.bounded
            body["uncontrolled_twists"] = eq.uncontrolled
            body["load_power"] = eq.powers
            body["non_unique"] = list(eq.non_unique)
            body["joint_wrenches"] = eq.joint_wrenches
            body["indeterminate_loops"] = [list(j) for j in eq.indeterminate_loops]
            body["loop_wrenches"] = eq.loop_wrenches
        out["kinetostatics"] = body
        return out

    def text_lines(self) -> list[str]:
        """Sentences for the text and Markdown reports (one bullet each)."""
        lines: list[str] = []
        eq = self.equilibrium
        unit = {
            n: ("N" if ln else "N m") for n, ln in zip(self.inputs, self.input_lengths, strict=True)
        }
        if eq is not None:
            f, m0 = eq.wrench[:3], eq.wrench[3:]
            m = m0 - np.cross(eq.point, f)
            load = (
                f"load on the output: force ({_v(f)}) N and moment ({_v(m)}) N m at "
                f"({_v(eq.point)}) m"
            )
            if self.weighed:
                load += f", with the weights of {', '.join(self.weighed)}"
            if eq.bounded is False:
                tw = "; ".join(
                    f"twist ({_v(t)}) takes {p:.4g} W per unit rate"
                    for t, p in zip(eq.uncontrolled, eq.powers, strict=True)
                )
                lines.append(
                    f"{load}: the efforts are unbounded (Type II): the inputs do not "
                    f"control an output twist the load does power on ({tw})"
                )
            else:
                assert eq.efforts is not None
                # shown as 0 below float's display floor relative to the largest effort
                # (commensurate: a force times L), as lengths are (the JSON keeps them)
                comm = {
                    n: abs(v) * (self.length_scale if unit[n] == "N" else 1.0)
                    for n, v in eq.efforts.items()
                }
                rel = floor_for(Precision("float"), 1.0) * max(comm.values(), default=0.0)
                eff = ", ".join(
                    f"{n} {floored(v, rel / (self.length_scale if unit[n] == 'N' else 1.0)):.6g} "
                    f"{unit[n]}"
                    for n, v in eq.efforts.items()
                )
                lines.append(f"{load}: actuator efforts {eff}")
                if eq.bounded is None:
                    lines.append("whether the efforts are bounded is undecided at float")
                if eq.non_unique:
                    lines.append(
                        f"efforts not unique ({', '.join(eq.non_unique)}): the least-norm ones "
                        "are given"
                    )
                if eq.uncontrolled:
                    lines.append(
                        "the inputs do not control an output twist, but the load does no "
                        "power on it: bounded, not unique"
                    )
                if eq.indeterminate_loops:
                    loops = "; ".join("-".join(j) for j in eq.indeterminate_loops)
                    lines.append(
                        f"constraint wrenches statically indeterminate in loop(s) {loops} "
                        "(overconstrained)"
                    )
        lines += self.units.text_lines(self.length_scale)
        lines += self.transmission.text_lines()
        return lines


def _v(x: Any) -> str:
    return ", ".join(f"{float(a):.4g}" for a in x)


def load_of(mech: Any, name: str, override: Any = None) -> Any:
    """The load of configuration ``name``: ``override`` (``--load``) or the file's."""
    if override is not None:
        return override
    c = mech.configurations.get(name)
    return None if c is None else c.load


def kinetostatics(
    mech: Any, joints: Any, load: Any = None, model: Any = None
) -> Kinetostatics | None:
    """The statics at the closed configuration of joint values ``joints`` (by name, SI),
    under ``load`` (a :class:`~mechsing.model.loads.Load` or None); None for a mechanism
    without inputs or output."""
    if not mech.inputs or mech.output is None:
        return None
    from mechsing.kinematics import KinematicModel

    fm = model if model is not None else KinematicModel(mech, "float")
    return kinetostatics_at(mech, float_configuration(fm, joints), load, fm)


def kinetostatics_at(mech: Any, q: np.ndarray, load: Any, model: Any) -> Kinetostatics:
    """:func:`kinetostatics` at the coordinate vector ``q`` of the float ``model``."""
    mm = motion_matrices(mech, q, model)
    emap = effort_map(mm)
    x0 = mech.output_reference_point() if load is None or load.point is None else load.point
    p = mm.point_now(np.array(to_float(np.array(x0, dtype=object)), dtype=float))
    eq = None
    weights = _weights(mech, mm)
    if load is not None or weights:
        force = np.zeros(3) if load is None else to_float(np.array(load.force, dtype=object))
        moment = np.zeros(3) if load is None else to_float(np.array(load.moment, dtype=object))
        eq = equilibrium(mm, emap, load_wrench(force, moment, p), p, weights)
    return Kinetostatics(
        eq,
        unit_efforts(mm, emap, p),
        transmission(mech, mm),
        mm.inputs,
        mm.input_lengths,
        tuple(b for b, _ in weights),
        mm.L,
    )


def _weights(mech: Any, mm: MotionMatrices) -> list[tuple[str, np.ndarray]]:
    """Each weighed body's weight (SI wrench at the ground origin) at ``mm``'s
    configuration: m g through its centre of mass (default: the centroid of its joints'
    points in the drawn pose), which moves with it."""
    wt = mech.weights
    if wt is None or not wt.weighs:  # no gravity: masses for the dynamics only
        return []
    g = np.asarray(to_float(np.array(wt.gravity, dtype=object)), dtype=float)
    out = []
    for body, kg, centre in wt.masses:
        x0 = np.asarray(
            to_float(np.array(mass_centre(mech, body, centre), dtype=object)), dtype=float
        )
        c = mm.body_point_now(body, x0)
        out.append((body, load_wrench(float(to_float(kg)) * g, np.zeros(3), c)))
    return out


def with_kinetostatics(result: Any, mech: Any, override: Any = None) -> Any:
    """``result`` (an :class:`~mechsing.analysis.results.AnalysisResult`) with the statics
    of each analysed configuration that has a load (the file's, or ``override``)."""
    if not mech.inputs or mech.output is None:
        return result
    from mechsing.kinematics import KinematicModel

    fm = None
    configs = []
    for c in result.configurations:
        load = load_of(mech, c.name, override)
        if c.error is None and (
            load is not None or (mech.weights is not None and mech.weights.weighs)
        ):
            fm = fm or KinematicModel(mech, "float")
            c = dataclasses.replace(c, kinetostatics=kinetostatics(mech, c.joints, load, fm))
        configs.append(c)
    return dataclasses.replace(result, configurations=tuple(configs))


__all__ += ["EffortMap", "MotionMatrices"]
