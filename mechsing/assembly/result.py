"""The result of :func:`~mechsing.assembly.api.modes`: what a formulation found, each mode
classified as :func:`mechsing.analyze` classifies it (the same code: :func:`analyze_found`),
the one continuation from ``start`` reaches marked, with the distances between modes.

Owns :class:`Mode`, :class:`ModesResult` and :func:`finish`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import mpmath
import numpy as np

from mechsing.assembly.chains import Found
from mechsing.assembly.given import closure_from_start, travel_of_start
from mechsing.assembly.settings import MODE_CERTIFY_RADIUS, REACHED_DIGITS
from mechsing.kinematics.closed import FLOAT_DIGITS, ClosedValue
from mechsing.model import Mechanism
from mechsing.numeric import MODE_FOLD_MATCH_DISTANCE, MODE_MATCH_DISTANCE, Precision

__all__ = ["Mode", "ModesResult", "finish", "joint_distance"]


@dataclass(frozen=True)
class Mode:
    """One assembly mode: every joint value (``joints``: floats, SI and radians;
    ``joints_text``: at the working precision), whether the Krawczyk test certified it
    (``certified``, within ``radius`` in the formulation's unknowns), the analysis of
    the configuration (``analysis``: analyze's configuration JSON, whose ``singular``
    and ``singularities`` the mode repeats), whether continuation from the
    configuration's start reaches it, the joints outside their ``limits``, and how
    many joint-space solutions it stands for."""

    joints: dict[str, list[float]]
    joints_text: dict[str, list[str]]
    certified: bool
    radius: float
    analysis: dict[str, Any]
    reached_by_continuation: bool
    outside_limits: list[str]
    output_pose: list[list[float]] | None
    equivalent_solutions: int = 1
    #: the mode as found, a frozen value (source ``mode``, certified or not, at the digits
    #: it was refined to): what ``sweep(start=mode)`` starts from; not in the JSON
    point: ClosedValue | None = field(default=None, compare=False, repr=False)

    def to_json(self) -> dict[str, Any]:
        return {
            "joints": self.joints,
            "joints_text": self.joints_text,
            "certified": self.certified,
            "certified_radius": self.radius,
            "singular": self.analysis.get("singular"),
            "singularities": self.analysis.get("singularities", []),
            "reached_by_continuation": self.reached_by_continuation,
            "outside_limits": self.outside_limits,
            "equivalent_solutions": self.equivalent_solutions,
            "output_pose": self.output_pose,
            "analysis": self.analysis,
        }


@dataclass(frozen=True)
class ModesResult:
    """Every assembly mode of one configuration (``to_json()``: the ``modes`` JSON).

    ``count``: the number of real modes (None when the solution set is not finite);
    ``complete``: ``"proven"`` (exact elimination with certified real-root isolation),
    ``"not proven"`` or ``"infinite"`` (the given values leave a curve of closed
    configurations: no count); ``distances``: between modes, over the joint coordinates
    in the commensurate metric (angles in rad, lengths divided by L) and as the output's
    pose distance (rotation angle plus translation over L)."""

    mechanism: str
    configuration: str
    precision: dict[str, Any]
    count: int | None
    complete: str
    formulation: dict[str, Any]
    paths: dict[str, Any] | None
    modes: tuple[Mode, ...]
    distances: dict[str, list[list[float]]]
    notes: tuple[str, ...] = field(default=())

    def to_json(self) -> dict[str, Any]:
        return {
            "mechanism": self.mechanism,
            "configuration": self.configuration,
            "precision": self.precision,
            "count": self.count,
            "complete": self.complete,
            "formulation": self.formulation,
            "paths": self.paths,
            "modes": [m.to_json() for m in self.modes],
            "distances": self.distances,
            "notes": list(self.notes),
        }


def finish(mech: Mechanism, config: str, prec: Precision, found: Found, dps: int) -> ModesResult:
    """The result of what a formulation found (no mode listed when the set is infinite)."""
    if found.count is None:
        return ModesResult(
            mech.name,
            config,
            {"mode": str(prec)},
            None,
            "infinite",
            found.formulation,
            found.paths,
            (),
            {"joints": [], "pose": []},
            found.notes,
        )
    return _result(mech, config, prec, found, dps)


def _text(x: Any, prec: Precision) -> str:
    if prec.mode == "mp":
        return mpmath.nstr(x, prec.digits, strip_zeros=False)
    return repr(float(x))


def _result(mech: Mechanism, config: str, prec: Precision, found: Found, dps: int) -> ModesResult:
    from mechsing.analysis import analyze_found
    from mechsing.kinematics import KinematicModel

    km = KinematicModel(mech, "float")
    L = float(km.length_scale)
    coords = mech.coordinates()
    rows = sorted(found.rows, key=lambda row: _order(mech, row[0]))
    names = {f"{config}#mode{k + 1}": q for k, (q, _ok) in enumerate(rows)}
    carried = prec.mode in ("mp", "auto")
    with mpmath.workdps(dps):  # the modes' digits carried (mpf() rounds to the context's)
        data = {
            n: ClosedValue(
                [mpmath.mpf(x) for x in q] if carried else [float(x) for x in q],
                dps if carried else FLOAT_DIGITS,
                "mode",
                n,
                bool(ok),
            )
            for n, (q, ok) in zip(names, rows, strict=True)
        }
    # the modes are data to dps digits (not points float located): analysed as a file's
    analysed = analyze_found(mech, data, prec, located=prec.mode == "float") if data else []
    # which mode the start reaches; proven none: nothing to reach (and no note on a start
    # continuation cannot close, which is all it could say)
    nothing = not rows and found.complete == "proven"
    closure = found.closure or ((None, None) if nothing else closure_from_start(mech, config))
    qs, certified = [[float(x) for x in q] for q, _ in rows], [bool(ok) for _, ok in rows]
    reached, notes = _reached(mech, qs, certified, km, closure)
    if reached is None and qs and closure[0] is not None:
        # float's closure a hair inside a fold (1e-13 rad) lands on the fold itself,
        # between the two modes that meet there (1e-6 apart) and matching neither; at
        # REACHED_DIGITS continuation goes down its branch to its own mode
        deeper = closure_from_start(mech, config, f"mp:{REACHED_DIGITS}")
        if deeper[0] is not None:
            reached, notes = _reached(mech, qs, certified, km, deeper)
    if nothing and mech.configurations[config].values:
        # no mode: where the values given leave the start's assembly mode, if they do
        travel = travel_of_start(mech, config)
        if travel is not None:
            notes = (*notes, f"no closed configuration: {travel}")
    out_body = mech.output.body if mech.output is not None else None
    poses = [
        km.poses(np.array([float(x) for x in q]))[out_body] if out_body else None for q, _ in rows
    ]
    result_modes = []
    for k, ((q, ok), res) in enumerate(zip(rows, analysed, strict=True)):
        joints: dict[str, list[float]] = {}
        texts: dict[str, list[str]] = {}
        outside = []
        for (name, i), x in zip(coords, q, strict=True):
            joints.setdefault(name, []).append(float(x))
            texts.setdefault(name, []).append(_text(x, prec))
            lim = mech.limits.get(name)
            if lim and not (lim[i][0] <= float(x) <= lim[i][1]) and name not in outside:
                outside.append(name)
        pose = poses[k]
        result_modes.append(
            Mode(
                joints,
                texts,
                bool(ok),
                float(MODE_CERTIFY_RADIUS),
                res.to_json(),
                k == reached,
                outside,
                None if pose is None else np.asarray(pose, dtype=float).tolist(),
                found.equivalent,
                data[f"{config}#mode{k + 1}"],
            )
        )
    return ModesResult(
        mech.name,
        config,
        {"mode": str(prec), "length_scale": L, "digits": dps},
        len(result_modes),
        found.complete,
        found.formulation,
        found.paths,
        tuple(result_modes),
        _distances(mech, [q for q, _ in rows], poses, L),
        (*found.notes, *notes),
    )


def _order(mech: Mechanism, q: list[Any]) -> tuple[int, ...]:
    """A mode's place in the list: its joint values rounded to the match distance (angles
    taken in [-pi, pi), pi and -pi alike), so that noise far below it (a joint at 0 as
    1e-51 in one mode and -1e-51 in another) does not reorder the modes."""
    key = []
    for (name, i), x in zip(mech.coordinates(), q, strict=True):
        v = float(x)
        if mech.joint(name).units[i] == "rad":
            v = (v + np.pi) % (2 * np.pi) - np.pi
            if v > np.pi - MODE_MATCH_DISTANCE / 2:
                v -= 2 * np.pi
        key.append(round(v / MODE_MATCH_DISTANCE))
    return tuple(key)


def _reached(
    mech: Mechanism,
    qs: list[list[float]],
    certified: list[bool],
    km: Any,
    closure: tuple[Any, str | None],
) -> tuple[int | None, tuple[str, ...]]:
    """Which mode continuation from the configuration's start reaches (its index), from
    its closure (:func:`~mechsing.assembly.given.closure_from_start`): the nearest, within
    MODE_MATCH_DISTANCE, or MODE_FOLD_MATCH_DISTANCE of a mode not ``certified`` (a double
    root, where float's closure is known to about 1e-8 only)."""
    res, failed = closure
    if res is None and failed is None:  # no mode to reach
        return None, ()
    if res is None and not qs:
        # no mode: where continuation stopped, and its advice to add a configuration on
        # the way, would only mislead (the values are reached nowhere, or not found)
        return None, ("continuation from the start does not close the configuration either",)
    if res is None:
        return None, (f"continuation from the start does not close the configuration: {failed}",)
    q0 = [x for _, v in res.joints for x in v]
    best, where = None, None
    for k, q in enumerate(qs):
        d = joint_distance(mech, q0, q, km.length_scale)
        if best is None or d < best:
            best, where = d, k

    def within(d: float | None, k: int | None) -> bool:
        reach = MODE_MATCH_DISTANCE if k is None or certified[k] else MODE_FOLD_MATCH_DISTANCE
        return d is not None and d <= reach

    if not within(best, where) and mech.output is not None and qs:
        # a mode stands for joint vectors of one output pose (a U's flip, a rod's idle
        # spin): continuation may reach another of them; the pose tells the mode
        body, L = mech.output.body, float(km.length_scale)
        P0 = np.asarray(km.poses(np.array(q0, dtype=float))[body], dtype=float)
        dists = [
            float(np.linalg.norm(P0[:3, :3] - P[:3, :3]) + np.linalg.norm(P0[:3, 3] - P[:3, 3]) / L)
            for P in (np.asarray(km.poses(np.array(q))[body], dtype=float) for q in qs)
        ]
        best = min(dists)
        where = dists.index(best)
    if not within(best, where):
        return None, (
            "continuation from the start closes the configuration at none of the modes "
            "found: a closed configuration the count misses",
        )
    return where, ()


def closure_gap(mech: Mechanism, prec: Precision, row: list[Any], target: Any = None) -> Any:
    """How far the joint values ``row`` (the file's coordinates) leave the loops from
    closing where that is more than ``prec`` accepts (m), else 0: as a configuration
    giving every joint is checked when its mode is analysed (the kinematic model's
    residual, at mp:N in its digits, else in float; exact accepts none); ``target``, an
    arm's gap to its target pose (m), in place of the loops'."""
    from mechsing.kinematics import KinematicModel

    km = KinematicModel(mech, prec if prec.mode == "mp" else "float")
    accepted = km.precision.closure_tolerance(km.length_scale) if prec.mode != "exact" else 0
    gap = target or km.residual_norm(km.chord_residuals(km.asarray(row)), native=True)
    return gap if gap > accepted else 0


def joint_distance(mech: Mechanism, q1: list[float], q2: list[float], L: float) -> float:
    """The commensurate distance over the joint coordinates: angles modulo 2 pi (rad),
    lengths over L."""
    total = 0.0
    for (name, i), a, b in zip(mech.coordinates(), q1, q2, strict=True):
        if mech.joint(name).units[i] == "rad":
            d = (float(a) - float(b) + np.pi) % (2 * np.pi) - np.pi
        else:
            d = (float(a) - float(b)) / L
        total += d * d
    return float(np.sqrt(total))


def _distances(
    mech: Mechanism, qs: list[Any], poses: list[Any], L: float
) -> dict[str, list[list[float]]]:
    n = len(qs)
    joints = [[joint_distance(mech, qs[i], qs[k], L) for k in range(n)] for i in range(n)]
    pose = []
    if poses and poses[0] is not None:
        for i in range(n):
            row = []
            for k in range(n):
                Ri, Rk = np.asarray(poses[i])[:3, :3], np.asarray(poses[k])[:3, :3]
                Rr = Ri.T @ Rk  # its angle from both its cosine and its sine: exact at 0
                sine = (
                    np.linalg.norm([Rr[2, 1] - Rr[1, 2], Rr[0, 2] - Rr[2, 0], Rr[1, 0] - Rr[0, 1]])
                    / 2
                )
                angle = np.arctan2(sine, (np.trace(Rr) - 1) / 2)
                dp = np.linalg.norm(np.asarray(poses[i])[:3, 3] - np.asarray(poses[k])[:3, 3])
                row.append(float(angle + dp / L))
            pose.append(row)
    return {"joints": joints, "pose": pose}
