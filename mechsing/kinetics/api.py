"""``mechsing.dynamics(...)``: the dynamics of a mechanism's configurations, and its result.

Owns :func:`dynamics` (what ``mechsing dynamics`` runs) and :class:`DynamicsResult` with
its JSON (``mechsing schema --dynamics``), text and Markdown.  At each configuration,
closed at the precision asked for: with ``accelerations`` the **inverse dynamics** (the
efforts that give them), with ``efforts`` the **forward dynamics** (the accelerations they
give), with neither the inverse dynamics at zero acceleration; always the mass matrix, the
bias efforts (Coriolis, centrifugal, gravity) and the kinetic energy
(:class:`mechsing.kinetics.tree.TreeDynamics`).  Rates, accelerations and efforts are in
SI: rad/s, m/s, rad/s^2, m/s^2, N m and N; a joint not given has 0.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mechsing.errors import UserError
from mechsing.numeric import Precision, parse_precision, to_float

__all__ = ["ConfigurationDynamics", "DynamicsResult", "dynamics"]


@dataclass(frozen=True)
class ConfigurationDynamics:
    """The dynamics at one configuration (SI; every map keyed by joint name, in the
    model's coordinate order)."""

    name: str
    joints: dict[str, float]
    rates: dict[str, float]
    accelerations: dict[str, float]
    efforts: dict[str, float]
    bias_efforts: dict[str, float]
    mass_matrix: list[list[float]]
    kinetic_energy: float
    #: the Type II crossing condition (closed chains); None for a tree, which has no Type II
    crossing: dict[str, Any] | None = None
    #: each joint's unit kind: "rad" or "m"
    kinds: dict[str, str] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "joints": self.joints,
            "rates": self.rates,
            "efforts": self.efforts,
            "accelerations": self.accelerations,
            "mass_matrix": {"joints": list(self.joints), "matrix": self.mass_matrix},
            "bias_efforts": self.bias_efforts,
            "kinetic_energy": self.kinetic_energy,
            "crossing": self.crossing,
        }


@dataclass(frozen=True)
class DynamicsResult:
    """The dynamics of a mechanism's configurations: ``problem`` is ``"inverse"`` (efforts
    from accelerations) or ``"forward"`` (accelerations from efforts)."""

    mechanism: str
    precision: str
    problem: str
    gravity: tuple[float, float, float] | None
    configurations: tuple[ConfigurationDynamics, ...]

    def to_json(self) -> dict[str, Any]:
        """The JSON of ``mechsing dynamics --format json`` (``mechsing schema --dynamics``)."""
        return {
            "mechanism": self.mechanism,
            "precision": self.precision,
            "problem": self.problem,
            "gravity": None if self.gravity is None else list(self.gravity),
            "configurations": [c.to_json() for c in self.configurations],
        }

    def _head(self) -> str:
        g = (
            "no gravity"
            if self.gravity is None
            else f"gravity ({', '.join(f'{x:g}' for x in self.gravity)}) m/s^2"
        )
        what = "inverse dynamics" if self.problem == "inverse" else "forward dynamics"
        return f"{self.mechanism}: {what} ({self.precision}), {g}"

    def text(self) -> str:
        out = [self._head()]
        for c in self.configurations:
            out.append(f"configuration {c.name}:")
            rows = [("joint", "value", "rate", "acceleration", "effort", "bias effort")]
            for j in c.joints:
                u = c.kinds.get(j, "rad")
                f = "N m" if u == "rad" else "N"
                rows.append(
                    (
                        j,
                        f"{c.joints[j]:.6g} {u}",
                        f"{c.rates[j]:.6g} {u}/s",
                        f"{c.accelerations[j]:.6g} {u}/s^2",
                        f"{c.efforts[j]:.6g} {f}",
                        f"{c.bias_efforts[j]:.6g} {f}",
                    )
                )
            widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
            for r in rows:
                cells = (x.ljust(w) for x, w in zip(r, widths, strict=True))
                out.append(("  " + "  ".join(cells)).rstrip())
            out.append(f"  kinetic energy: {c.kinetic_energy:.6g} J")
            out.append(f"  mass matrix ({', '.join(c.joints)}):")
            for row in c.mass_matrix:
                out.append("    [" + ", ".join(f"{x:.6g}" for x in row) + "]")
            if c.crossing is not None:
                can = "possible" if c.crossing["possible"] else "not possible"
                out.append(
                    f"  Type II crossing: {can} (the effort balance's relative residual "
                    f"{c.crossing['residual']:.2g})"
                )
        return "\n".join(out) + "\n"

    def markdown(self) -> str:
        out = [f"# {self._head()}", ""]
        for c in self.configurations:
            out += [f"## Configuration {c.name}", ""]
            out.append("| joint | value | rate | acceleration | effort | bias effort |")
            out.append("| --- | --- | --- | --- | --- | --- |")
            for j in c.joints:
                out.append(
                    f"| {j} | {c.joints[j]:.6g} | {c.rates[j]:.6g} | {c.accelerations[j]:.6g} "
                    f"| {c.efforts[j]:.6g} | {c.bias_efforts[j]:.6g} |"
                )
            out += ["", f"Kinetic energy: {c.kinetic_energy:.6g} J.", ""]
            out.append("| mass matrix | " + " | ".join(c.joints) + " |")
            out.append("| --- |" + " --- |" * len(c.joints))
            for j, row in zip(c.joints, c.mass_matrix, strict=True):
                out.append(f"| {j} | " + " | ".join(f"{x:.6g}" for x in row) + " |")
            out.append("")
        return "\n".join(out)


def dynamics(
    source: Any,
    config: str | list[str] | None = None,
    *,
    rates: Mapping[str, Any] | None = None,
    accelerations: Mapping[str, Any] | None = None,
    efforts: Mapping[str, Any] | None = None,
    precision: Precision | str = "float",
    gravity: Any = None,
) -> DynamicsResult:
    """The dynamics of a mechanism at its configurations.

    Parameters
    ----------
    source : str, Path or Mechanism
        A mechanism file (any format :func:`mechsing.load` reads) or a loaded mechanism.
    config : str, list of str or None
        The configuration(s); None: every configuration of the file.
    rates, accelerations, efforts : mapping joint name -> value, optional
        SI (rad/s, m/s; rad/s^2, m/s^2; N m, N), numbers or expressions such as
        ``"pi/4"``; a joint not named has 0.  ``accelerations``: inverse dynamics;
        ``efforts``: forward dynamics (not both); neither: inverse at zero acceleration.
    precision : str
        ``float``, ``mp:N`` or ``exact`` (the closure and the dynamics in that mode).
    gravity : 3 numbers or None
        The acceleration of gravity in ground axes (m/s^2); None: the file's (none: zero).
    """
    from mechsing.kinematics import solve_configuration
    from mechsing.kinetics.tree import TreeDynamics

    if accelerations is not None and efforts is not None:
        raise UserError(
            "give accelerations (inverse dynamics: the efforts they need) or efforts "
            "(forward dynamics: the accelerations they give), not both"
        )
    mech = _mechanism(source)
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    if prec.mode == "auto":
        prec = parse_precision("float")
    names = (
        list(mech.configurations)
        if config is None
        else [config]
        if isinstance(config, str)
        else list(config)
    )
    for n in names:
        if n not in mech.configurations:
            raise UserError(
                f"{mech.name}: no configuration named {n!r}; the file has: "
                f"{', '.join(mech.configurations)}"
            )
    grav = None if gravity is None else tuple(_number(x, "gravity") for x in gravity)
    out = []
    td = None
    loops = bool(mech.graph.loops)
    for name in names:
        model, closed = solve_configuration(mech, name, prec)
        if td is None:
            td = TreeDynamics(model, grav, closed=loops)
        crossing = None
        with prec.context():
            q = closed.q
            qd = _vector(td, rates, "rates")
            if loops:
                try:
                    qd, qdd, tau, crossing = _closed(
                        td,
                        mech,
                        q,
                        qd,
                        _vector(td, accelerations, "accelerations"),
                        None if efforts is None else _vector(td, efforts, "efforts"),
                    )
                except UserError as exc:  # mp:N or exact at a Type II: say where
                    raise UserError(f"configuration {name!r}: {exc}") from None
            elif efforts is not None:
                tau = _vector(td, efforts, "efforts")
                qdd = td.forward(q, qd, tau)
            else:
                qdd = _vector(td, accelerations, "accelerations")
                tau = td.inverse(q, qd, qdd)
            M = td.mass_matrix(q)
            bias = td.bias(q, qd)
            T = td.kinetic_energy(q, qd)
        joints = [jk.name for jk in model.joints]
        kinds = {jk.name: ("m" if jk.length_coordinates[0] else "rad") for jk in model.joints}

        def named(v: Any, joints: list[str] = joints) -> dict[str, float]:
            return {j: float(x) for j, x in zip(joints, to_float(np.asarray(v)), strict=True)}

        out.append(
            ConfigurationDynamics(
                name,
                named(q),
                named(qd),
                named(qdd),
                named(tau),
                named(bias),
                [[float(x) for x in row] for row in to_float(np.asarray(M))],
                float(to_float(T)),
                crossing,
                kinds,
            )
        )
    wt = mech.weights
    shown = grav if grav is not None else (wt.gravity if wt is not None else None)
    return DynamicsResult(
        mech.name,
        str(prec),
        "forward" if efforts is not None else "inverse",
        None if shown is None else tuple(float(to_float(x)) for x in shown),  # type: ignore[arg-type]
        tuple(out),
    )


def _closed(td: Any, mech: Any, q: Any, qd: Any, qdd: Any, tau: Any) -> tuple[Any, Any, Any, dict]:
    """A closed chain's motion from its inputs' rates and accelerations (the others' given
    values are not read: the closure gives them), or under its inputs' efforts ``tau``
    (forward: the accelerations first), its inputs' efforts, and the crossing condition:
    whether the inputs can produce the efforts the motion needs (the effort balance's
    relative residual below :data:`mechsing.numeric.tolerances.CROSSING_RTOL`; at a
    Type II configuration in mp:N and exact, decided on the power of the efforts on the
    uncontrolled twists, :func:`mechsing.kinetics.closed.balance`)."""
    from mechsing.kinetics.closed import closed_forward, closed_inverse

    model = td.model
    inputs = []
    for name in mech.inputs:
        jk = model.joint(str(name))
        inputs.append(jk.columns.start)
    u = np.asarray(qd)[inputs]
    if tau is not None:
        qdd = closed_forward(td, q, inputs, u, np.asarray(tau)[inputs])
    res = closed_inverse(td, q, inputs, u, np.asarray(qdd)[inputs])
    crossing = {"possible": res.possible, "residual": float(to_float(res.residual))}
    return res.qd, res.qdd, res.efforts, crossing


def _mechanism(source: Any) -> Any:
    if isinstance(source, str | Path):
        from mechsing.reader import read_mechanism

        return read_mechanism(source)
    return source


def _number(x: Any, what: str) -> Any:
    if isinstance(x, str):
        from mechsing.errors import ExpressionError
        from mechsing.model.expressions import parse_number

        try:
            return parse_number(x)
        except ExpressionError as exc:
            raise UserError(f"{what}: {exc}") from None
    return x


def _vector(td: Any, values: Mapping[str, Any] | None, what: str) -> np.ndarray:
    """The joint vector of ``values`` by joint name (0 for a joint not named)."""
    model = td.model
    known = {jk.name: jk.columns.start for jk in model.joints}
    v: list[Any] = [0] * model.n
    for name, x in (values or {}).items():
        if name not in known:
            raise UserError(
                f"{what}: {name!r} is not a joint of the mechanism; its joints: {', '.join(known)}"
            )
        v[known[name]] = _number(x, f"{what} {name}")
    return model.asarray(v)
