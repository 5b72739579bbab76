"""Every assembly mode of a configuration: :func:`modes` and its typed result.

For a configuration's given values (the inputs), every real closed configuration with
those values: found by a formulation (:mod:`.planar`) and a method (exact elimination,
:mod:`.exact`), each certified (:mod:`.certify`), classified as
:func:`mechsing.analyze` classifies it (the same code: :func:`analyze_found`), the one
continuation from ``start`` reaches marked, with the distances between modes.

Owns :class:`Mode`, :class:`ModesResult` and :func:`modes`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.assembly.certify import krawczyk
from mechsing.assembly.chains import Found, closure_from_start, loop_found, serial_found
from mechsing.errors import ConfigurationError, FormulationError, UserError
from mechsing.model import Mechanism
from mechsing.numeric import (
    MODE_CERTIFY_RADIUS,
    MODE_MATCH_DISTANCE,
    Precision,
    parse_precision,
    rotation_orthonormal_atol,
)

__all__ = ["Mode", "ModesResult", "modes"]

#: the mechanism's extra that brings the continuation engine (named in messages)
EXTRA = "pip install 'mechsing[modes]'"


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


def _given(mech: Mechanism, config: str) -> dict[str, tuple[Any, ...]]:
    from mechsing.model.mechanism import Displacement

    where = f"{mech.path or mech.name}: "
    cfg = mech.configurations[config]
    if cfg.pose is not None:
        raise UserError(
            f"{where}configuration {config!r} gives the output's pose: modes takes given joint "
            "values (the inputs); give them with --set JOINT=VALUE"
        )
    out = {}
    for name, v in cfg.values.items():
        if isinstance(v, Displacement):
            raise UserError(
                f"{where}configuration {config!r}: joint {name} is given as a displacement; "
                "modes takes joint values"
            )
        out[name] = tuple(
            sympy.nsimplify(x) if isinstance(x, float) else sympy.sympify(x) for x in v
        )
    inputs = {ref.joint for ref in mech.inputs}
    if inputs and inputs <= set(out) and set(out) - inputs:
        # every value given: the modes share the inputs' values (the rest is one of them)
        out = {name: v for name, v in out.items() if name in inputs}
    if not out:
        raise UserError(
            f"{where}configuration {config!r} gives no joint value: the closed configurations form "
            "the whole configuration space, not a finite set of modes; give the inputs "
            "(--set JOINT=VALUE)"
        )
    return out


def modes(
    mechanism: Mechanism | str,
    config: str,
    precision: Precision | str = "auto",
    time_limit: float | None = None,
    start: str | None = None,
) -> ModesResult:
    """Every real assembly mode of configuration ``config`` (its given joint values).

    Parameters
    ----------
    mechanism : Mechanism or str
        A mechanism (:func:`mechsing.load`) or a file's path.
    config : str
        The configuration whose given values (the inputs) every mode shares; the one
        continuation from its ``start`` reaches is marked.
    precision : Precision or str
        How each mode is classified (``"auto"``, ``"float"``, ``"mp:N"``); the modes are
        found at max(50, N + 10) digits whatever it is.
    time_limit : float or None
        The most seconds (None: no limit).
    start : str or None
        The configuration continuation starts from to mark the mode it reaches (None: the
        configuration's own ``start``).

    Returns
    -------
    ModesResult

    Raises
    ------
    UserError
        No built-in formulation applies (the message names the reason and the extra).
    """
    from mechsing.reader import read_mechanism
    from mechsing.timelimit import TimeLimit

    mech = mechanism if isinstance(mechanism, Mechanism) else read_mechanism(mechanism)
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    if prec.mode == "exact":
        raise UserError(
            "modes classifies modes found numerically (certified, not exact "
            "values): use --precision auto, float or mp:N"
        )
    if config not in mech.configurations:
        raise UserError(
            f"{mech.path or mech.name}: no configuration named {config!r}; the "
            f"file has: {', '.join(mech.configurations)}"
        )
    if start is not None:
        mech = _started_from(mech, config, start)
    dps = max(50, (prec.digits or 0) + 10)
    where = f"{mech.path or mech.name}: configuration {config!r}"
    # one time limit for the whole: the solving, the certification and the classification
    if not mech.loops:  # a serial arm: the output's pose (given, or reached) is what is given
        with TimeLimit(time_limit):
            with mpmath.workdps(dps):
                try:
                    found = serial_found(mech, config, dps, rotation_orthonormal_atol(prec))
                except FormulationError as reason:
                    raise UserError(
                        f"{where}: no method applies (a mechanism without loops is solved as "
                        f"a serial arm for the output's pose, and that formulation does not "
                        f"apply: {reason})"
                    ) from None
            return _finish(mech, config, prec, found, dps)
    given = _given(mech, config)
    with TimeLimit(time_limit):
        with mpmath.workdps(dps):
            _check_values(mech, config)
            try:
                found = _planar(mech, given, dps)
            except FormulationError as planar_reason:
                try:
                    found = _spatial(mech, given, dps)
                except FormulationError as spatial_reason:
                    try:
                        found = loop_found(mech, config, given, dps)
                    except FormulationError as loop_reason:
                        raise UserError(
                            f"{where}: no method applies (the planar exact method does not "
                            f"apply: {planar_reason}; the spatial platform in Study "
                            f"coordinates does not apply: {spatial_reason}; the single loop "
                            f"of six unknown joints does not apply: {loop_reason})"
                        ) from None
        return _finish(mech, config, prec, found, dps)


def _check_values(mech: Mechanism, config: str) -> None:
    """The given values are finite and of a sensible size (the analysis's bound, its
    message naming the configuration and the joint): refused before any solving."""
    from mechsing.kinematics import KinematicModel
    from mechsing.kinematics.given import GivenValues

    try:
        GivenValues(KinematicModel(mech, "float")).of(mech.configurations[config])
    except UserError as exc:
        raise UserError(f"{mech.path or mech.name}: {exc}") from None


def _started_from(mech: Mechanism, config: str, start: str) -> Mechanism:
    """``mech`` with configuration ``config`` continued from ``start``."""
    import dataclasses

    where = mech.path or mech.name
    if start not in mech.configurations:
        raise UserError(
            f"{where}: --from {start!r}: no such configuration; the file has: "
            f"{', '.join(mech.configurations)}"
        )
    cur: str | None = start
    while cur is not None:
        if cur == config:
            raise UserError(
                f"{where}: --from {start!r}: it starts from {config!r} itself (a cycle); "
                "choose a configuration that does not"
            )
        cur = mech.configurations[cur].start
    cfg = dataclasses.replace(mech.configurations[config], start=start)
    return dataclasses.replace(mech, configurations={**mech.configurations, config: cfg})


def _finish(mech: Mechanism, config: str, prec: Precision, found: Found, dps: int) -> ModesResult:
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


def _planar(mech: Mechanism, given: dict, dps: int) -> Found:
    from mechsing.assembly.exact import eliminate_stages
    from mechsing.assembly.planar import joint_values, planar_stages, stages_system

    stages = planar_stages(mech, given)
    found = eliminate_stages(stages, dps)
    square, unknowns = stages_system(stages)
    rows = []
    for platforms in found.branches:
        coords = joint_values(mech, stages, given, list(platforms))
        z = [v for c, s, x, y in platforms for v in (x, y, mpmath.atan2(s, c))]
        rows.append((coords, krawczyk(square, unknowns, z, mpmath.mpf(MODE_CERTIFY_RADIUS))))
    system = stages[0]
    formulation = {
        "name": "planar platform pose",
        "method": "exact elimination",
        "platform": system.platform,
        "unknowns": ["x", "y", "theta"],
        "legs": [{"kind": leg.kind, "joints": list(leg.joints)} for leg in system.legs],
        "polynomial_degree": found.degrees[0],
        "offset": str(2 * sympy.atan(found.offset)),
    }
    if len(stages) > 1:
        formulation["stages"] = [
            {
                "platform": st.platform,
                "legs": [{"kind": leg.kind, "joints": list(leg.joints)} for leg in st.legs],
                "polynomial_degree": degree,
            }
            for st, degree in zip(stages, found.degrees, strict=True)
        ]
    if not found.finite:
        return Found(formulation, [], None, "infinite", None, found.notes)
    complete = "proven" if found.proven else "not proven"
    return Found(formulation, rows, len(rows), complete, None, found.notes)


def _spatial(mech: Mechanism, given: dict, dps: int) -> Found:
    from mechsing.assembly.spatial import (
        GENERIC_COUNT,
        XS,
        YS,
        joint_values_spatial,
        out_of_reach,
        patch_equation,
        pose_of,
        solve_study,
        spatial_system,
    )

    system = spatial_system(mech, given)
    formulation = {
        "name": "Study coordinates",
        "method": "homotopy continuation (Bertini 2), Newton refinement",
        "platform": system.platform,
        "unknowns": [str(v) for v in (*XS, *YS)],
        "legs": [{"kind": "distance", "joints": list(n)} for n, *_ in system.legs],
        "polynomial_degree": 2,
        "bezout": 2**7,
        "generic_count": GENERIC_COUNT,
    }
    reason = out_of_reach(system)
    if reason is not None:  # proved without tracking: no real (or complex) pose
        return Found(formulation, [], 0, "proven", None, (reason,))
    try:
        studies, paths = solve_study(system, dps)
    except ConfigurationError as exc:
        raise ConfigurationError(f"{mech.path or mech.name}: {exc}", exc.configuration) from None
    # one mode per platform pose (the Study coordinates' sign is fixed by the patch)
    kept: list[list[Any]] = []
    for z in studies:
        R, t = pose_of(z)
        if all(
            mpmath.norm(R - pose_of(k)[0]) + mpmath.norm(t - pose_of(k)[1]) > MODE_MATCH_DISTANCE
            for k in kept
        ):
            kept.append(z)
    eqs = [*system.equations, patch_equation()]
    rows = []
    for z in kept:
        ok = krawczyk(eqs, [*XS, *YS], z, mpmath.mpf(MODE_CERTIFY_RADIUS))
        rows.append((joint_values_spatial(mech, system, given, z), ok))
    paths["duplicates"] = len(studies) - len(kept)
    distinct = all(ok for _, ok in rows)
    complete = "maximal" if len(rows) == GENERIC_COUNT and distinct else "not proven"
    equivalent = 2 ** sum(1 for n, *_ in system.legs if mech.joint(n[0]).type == "U")
    return Found(formulation, rows, len(rows), complete, paths, (), equivalent)


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
    with mpmath.workdps(dps):  # the modes' digits carried (mpf() rounds to the context's)
        data = {
            n: (
                [mpmath.mpf(x) for x in q] if prec.mode in ("mp", "auto") else [float(x) for x in q]
            )
            for n, q in names.items()
        }
    # the modes are data to dps digits (not points float located): analysed as a file's
    analysed = analyze_found(mech, data, prec, located=prec.mode == "float") if data else []
    closure = found.closure or closure_from_start(mech, config)
    reached, notes = _reached(mech, [[float(x) for x in q] for q, _ in rows], km, closure)
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
    mech: Mechanism, qs: list[list[float]], km: Any, closure: tuple[Any, str | None]
) -> tuple[int | None, tuple[str, ...]]:
    """Which mode continuation from the configuration's start reaches (its index), from
    its closure (:func:`~mechsing.assembly.chains.closure_from_start`)."""
    res, failed = closure
    if res is None:
        return None, (f"continuation from the start does not close the configuration: {failed}",)
    q0 = [x for _, v in res.joints for x in v]
    best, where = None, None
    for k, q in enumerate(qs):
        d = _joint_distance(mech, q0, q, km.length_scale)
        if best is None or d < best:
            best, where = d, k
    if best is None or best > MODE_MATCH_DISTANCE:
        return None, ("continuation closes the configuration at none of the modes",)
    return where, ()


def _joint_distance(mech: Mechanism, q1: list[float], q2: list[float], L: float) -> float:
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
    joints = [[_joint_distance(mech, qs[i], qs[k], L) for k in range(n)] for i in range(n)]
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
