"""Cusps and cuspidality (``mechsing cusps``, :func:`mechsing.cusps`).

Two problems reduce to one polynomial ``P(t; a, b)`` whose real roots in ``t`` are the
modes at the point ``(a, b)`` of a plane section, and whose singular curves and cusps
:mod:`~mechsing.assembly.discriminant` finds:

* a planar mechanism with three inputs whose direct kinematics has finitely many
  assembly modes (a 3-RPR, 3-RRR, 3-PRR): one input fixed at the configuration's value,
  two varied; ``P`` is the planar formulation's eliminant (:func:`.exact.eliminant`,
  ``t`` the platform angle's half-angle tangent), the given values of the varied inputs
  left as symbols;
* a positional 3R arm (three revolute joints, an output point): the section is the
  workspace half-plane ``(rho, z)`` about the first axis; ``P`` the inverse kinematics'
  eliminant in the third joint's half-angle (:mod:`~mechsing.assembly.arm3r`).

A factor of ``P`` free of ``(a, b)`` (the ``1 + t^2`` of ``c^2 + s^2`` left unreduced, a
Cramer determinant of the geometry alone) is divided out; a ``P`` that is a power of a
polynomial (every root at least double: an arm whose first two axes meet, whose inverse
kinematics decouples) has no triple root of its modes, and is reported not cuspidal with
that evidence.

Owns :func:`cusps`, :class:`Cusp` and :class:`CuspsResult`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.errors import FormulationError, UserError
from mechsing.model import Mechanism

__all__ = ["Cusp", "CuspsResult", "cusps"]

#: what a cusp's certification proves, in the JSON
CERTIFIED = (
    "Krawczyk (interval arithmetic, 50 digits): one true triple root of the eliminant "
    "(P = dP/dt = d2P/dt2 = 0 in t and the two varied inputs) within the radius"
)


#: why a listed cusp is not certified: its triple-root system is singular there
DEGENERATE = (
    "the Jacobian of P = dP/dt = d2P/dt2 = 0 (in t and the two varied inputs) is singular "
    "at the triple root, to 50 digits: a degenerate cusp (P_ttt (P_a P_tb - P_b P_ta) = 0, "
    "the singular curve itself singular there), which the Krawczyk test, proving a "
    "regular root, cannot certify; three modes do meet there to 50 digits"
)
#: why a listed cusp is not certified otherwise
NOT_CONTRACTED = (
    "the Krawczyk test did not contract on the box about the triple root (it closes to "
    "50 digits, and its Jacobian is regular)"
)


@dataclass(frozen=True)
class Cusp:
    """One cusp: the varied inputs' values, the triple root's mode (the pose or joint
    values where three modes meet), certified, and the modes at and beside it."""

    inputs: dict[str, float]
    t: float
    certified: bool
    radius: float
    modes: dict[str, Any]
    #: why it is not certified (None when it is)
    why_not: str | None = None

    def to_json(self) -> dict[str, Any]:
        out = {
            "inputs": dict(self.inputs),
            "multiplicity": 3,
            "certified": self.certified,
            "radius": self.radius if self.certified else None,
            "t": self.t,
            "modes": self.modes,
        }
        if self.why_not is not None:  # added: a listed cusp that is not certified says why
            out["not_certified"] = self.why_not
        return out


@dataclass
class CuspsResult:
    """The section's singular curves (located points), the modes' counts on its grid,
    the cusps, and whether the mechanism is cuspidal (with the evidence)."""

    mechanism: str
    problem: str  # "direct kinematics" or "inverse kinematics"
    varied: tuple[str, str]
    ranges: tuple[tuple[float, float], tuple[float, float]]
    fixed: dict[str, float]
    formulation: dict[str, Any]
    cusps: list[Cusp]
    cuspidal: bool
    evidence: dict[str, Any]
    curve_points: list[tuple[float, float]] = field(default_factory=list)
    grid: dict[str, Any] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        return {
            "mechanism": self.mechanism,
            "problem": self.problem,
            "section": {
                "vary": {n: list(r) for n, r in zip(self.varied, self.ranges, strict=True)},
                "fixed": dict(self.fixed),
            },
            "formulation": self.formulation,
            "cusps": [c.to_json() for c in self.cusps],
            "cuspidal": self.cuspidal,
            "evidence": self.evidence,
            "singular_curves": {"points": [list(p) for p in self.curve_points]},
            "modes_grid": self.grid,
        }


def cusps(
    mechanism: Mechanism | str,
    vary: dict[str, tuple[float, float]] | str,
    config: str | None = None,
    points: int | None = None,
) -> CuspsResult:
    """The singular curves and the cusps of a section, and whether the mechanism is
    cuspidal.

    Parameters
    ----------
    mechanism : Mechanism or str
        A mechanism (:func:`mechsing.load`) or a file's path: a planar mechanism with
        three inputs (a 3-RPR, 3-RRR, 3-PRR) or a positional 3R arm (an output point).
    vary : dict or str
        The two varied coordinates and their ranges, ``{"P2": (lo, hi), "P3": (lo, hi)}``
        or ``"P2=lo:hi,P3=lo:hi"``: two inputs of a parallel mechanism, ``rho`` and
        ``z`` of an arm, in the file's units (``units:``, as ``sweep --vary``; the
        result is in SI units and radians).
    config : str or None
        The configuration whose value of the third input is kept (None: the first that
        gives it; none: its reference value, 0).  A configuration that does not give it
        (one that gives the output's pose) is closed first, and its closed value kept.
    points : int or None
        Grid points along each side (None: :data:`~.discriminant.GRID_POINTS`).

    Returns
    -------
    CuspsResult

    Raises
    ------
    UserError
        The mechanism is neither kind, or ``vary`` does not name two of its inputs.
    """
    from mechsing.assembly import discriminant
    from mechsing.reader import read_mechanism

    mech = mechanism if isinstance(mechanism, Mechanism) else read_mechanism(mechanism)
    where = mech.path or mech.name
    given = parse_vary(vary, where) if isinstance(vary, str) else dict(vary)
    ranges = _in_si(mech, given)
    n = points or discriminant.GRID_POINTS
    if not mech.loops:
        from mechsing.assembly.arm3r import arm_family

        built = arm_family(mech, ranges)
    else:
        built = _planar_family(mech, ranges, config)
    (a_name, b_name) = built["varied"]
    a_rng, b_rng = ranges[a_name], ranges[b_name]
    if built.get("decoupled"):
        return CuspsResult(
            mech.name,
            built["problem"],
            (a_name, b_name),
            (a_rng, b_rng),
            built["fixed"],
            built["formulation"],
            [],
            False,
            {**built["decoupled"], "cusps": 0},
        )
    fam = built["family"]
    sec = discriminant.section(fam, a_rng, b_rng, n)
    found = []
    for c in sec.cusps:
        modes = built["mode_at"](c.a, c.b, c.t)
        modes["real_modes_at_cusp"] = c.real_roots
        modes["coalescing"] = 3
        found.append(
            Cusp(
                {a_name: float(c.a), b_name: float(c.b)},
                float(c.t),
                c.certified,
                float(c.radius),
                modes,
                None if c.certified else (DEGENERATE if c.degenerate else NOT_CONTRACTED),
            )
        )
    certified = [c for c in found if c.certified]
    steps = (
        f"{n} x {n} grid, steps {a_name} {(a_rng[1] - a_rng[0]) / (n - 1):.3g} and "
        f"{b_name} {(b_rng[1] - b_rng[0]) / (n - 1):.3g}"
    )
    if certified:
        evidence = {
            "kind": "cusps",
            "reason": f"{len(certified)} cusp point(s) in the section, each certified: "
            + CERTIFIED
            + f"; the list holds the cusps on singular curves that cross the {steps}",
        }
    else:
        evidence = {
            "kind": "no-triple-root",
            "reason": (
                "no real triple root of the eliminant found in the section: Newton on "
                f"P = dP/dt = d2P/dt2 = 0 from each of its {len(sec.points)} located "
                "singular points, and from between each two neighbours on which "
                f"d2P/dt2 changes sign ({sec.seeds} starts), reached none in the section"
                + ("" if not found else " that the Krawczyk test certifies")
                + f". This covers the singular curves that cross the {steps}; it is not a "
                "proof for the whole box: a cusp whose curves cross no grid line (a wedge "
                "narrower than a cell, near its tip) is not excluded (a finer --points, or "
                "a smaller box about it, finds it)"
            ),
        }
    evidence.update({"cusps": len(certified), "grid": n, "singular_points": len(sec.points)})
    # added: what the search covers: the singular curves crossing the grid's lines (no
    # proof over the whole box is made)
    evidence["covers"] = "grid"
    counts = sorted({int(v) for v in sec.counts.ravel()})
    if counts == [0]:  # nothing searched: the section misses every assembly (or posture)
        units = mech.units
        evidence["reason"] += (
            "; but no real mode anywhere on the grid: the section misses the mechanism's "
            f"reach (--vary is read in the file's units, {units.length} and {units.angle})"
        )
    return CuspsResult(
        mech.name,
        built["problem"],
        (a_name, b_name),
        (a_rng, b_rng),
        built["fixed"],
        {**built["formulation"], "modes_counts": counts},
        found,
        bool(certified),
        evidence,
        [(p.a, p.b) for p in sec.points],
        {
            a_name: [float(v) for v in sec.a_values],
            b_name: [float(v) for v in sec.b_values],
            "modes": sec.counts.astype(int).tolist(),
        },
    )


def _in_si(
    mech: Mechanism, ranges: dict[str, tuple[float, float]]
) -> dict[str, tuple[float, float]]:
    """The section's ranges, given in the file's units (``units:``; an input's own unit,
    a length for an arm's ``rho`` and ``z``), in SI units and radians."""
    units = mech.units
    out = {}
    for name, (lo, hi) in ranges.items():
        joint = next((j for j in mech.joints if j.name == name), None)
        angle = joint is not None and bool(joint.units) and joint.units[0] == "rad"
        factor = float(units.angle_factor if angle else units.length_factor)
        out[name] = (float(lo) * factor, float(hi) * factor)
    return out


def parse_vary(text: str, where: str) -> dict[str, tuple[float, float]]:
    """``NAME=lo:hi,NAME=lo:hi`` as {name: (lo, hi)} (values may be expressions)."""
    from mechsing.model.expressions import parse_number

    out = {}
    for part in text.split(","):
        name, eq, rng = part.partition("=")
        lo, colon, hi = rng.partition(":")
        if not eq or not colon or not name.strip():
            raise UserError(
                f"{where}: --vary {text!r}: write NAME=lo:hi,NAME=lo:hi (two coordinates)"
            )
        try:
            a, b = float(parse_number(lo.strip())), float(parse_number(hi.strip()))
        except (ValueError, TypeError, UserError) as exc:
            raise UserError(f"{where}: --vary {part!r}: {exc}") from None
        if not (np.isfinite(a) and np.isfinite(b) and a < b):
            fix = f" (write {name.strip()}={hi.strip()}:{lo.strip()})" if a > b else ""
            raise UserError(f"{where}: --vary {part!r}: need finite lo < hi{fix}")
        if name.strip() in out:
            raise UserError(
                f"{where}: --vary {text!r}: {name.strip()} is given twice; a section "
                "varies two different coordinates"
            )
        out[name.strip()] = (a, b)
    if len(out) != 2:
        raise UserError(f"{where}: --vary {text!r}: a section varies two coordinates")
    return out


def _closed_value(mech: Mechanism, config: str, name: str) -> Any:
    """Joint ``name``'s value (SI) in configuration ``config``, which does not give it (it
    gives the output's pose, or other joints): closed in float, as ``mechsing solve``
    closes it, and kept as the rational of its 17 digits."""
    from mechsing.analysis.solve import solve
    from mechsing.errors import ConfigurationError

    try:
        joints = dict(solve(mech, config, "float").joints)
    except ConfigurationError as exc:
        raise UserError(
            f"{mech.path or mech.name}: configuration {config!r} does not give {name}, and "
            f"it does not close ({exc}); give {name} in it, or choose another with --config"
        ) from None
    return sympy.Rational(repr(float(joints[name][0])))


def _planar_family(
    mech: Mechanism, ranges: dict[str, tuple[float, float]], config: str | None
) -> dict[str, Any]:
    """The section's eliminant of a planar mechanism with three inputs."""
    from mechsing.assembly.discriminant import Family, without_free_factor
    from mechsing.assembly.exact import T, eliminant
    from mechsing.assembly.planar import OFFSETS, C, S, joint_values, planar_system
    from mechsing.assembly.planar_pose import turned_to_xy
    from mechsing.kinematics.family import family

    where = mech.path or mech.name
    inputs = [ref.joint for ref in mech.inputs]
    if len(inputs) == 3 and len(ranges) == 2 and set(ranges) - set(inputs):
        (stray, *_) = sorted(set(ranges) - set(inputs))
        raise UserError(
            f"{where}: --vary {stray}: not an input of the mechanism; vary two of its "
            f"inputs {', '.join(inputs)} (the third is held at the configuration's value)"
        )
    if len(inputs) != 3 or set(ranges) - set(inputs) or len(ranges) != 2:
        raise UserError(
            f"{where}: cusps of a parallel mechanism need three inputs, two of them varied "
            f"(--vary {'=lo:hi,'.join(inputs[:2]) or 'NAME'}=lo:hi); the file's inputs: "
            f"{', '.join(inputs) or 'none'}"
        )
    fam = family(mech)
    if fam.kind != "planar":
        raise UserError(
            f"{where}: cusps take a planar mechanism (3-RPR, 3-RRR, 3-PRR) or a 3R arm; "
            f"its joints generate {fam.symbol or 'no decided subgroup'}"
        )
    turned = turned_to_xy(mech, fam.params["normal"])
    a_name, b_name = (n for n in inputs if n in ranges)
    (fixed_name,) = (n for n in inputs if n not in ranges)
    if config is None:  # the first configuration that gives the fixed input
        config = next((n for n, c in mech.configurations.items() if fixed_name in c.values), None)
    if config is not None and config not in mech.configurations:
        raise UserError(
            f"{where}: no configuration named {config!r}; the file has: "
            f"{', '.join(mech.configurations)}"
        )
    value = sympy.S.Zero
    if config is not None:
        given = mech.configurations[config].values.get(fixed_name)
        if given is not None:
            v = given[0]
            value = sympy.nsimplify(v) if isinstance(v, float) else sympy.sympify(v)
        else:  # a pose, or other joints: the value the configuration closes at
            value = _closed_value(mech, config, fixed_name)
    A, B = sympy.symbols("a b", real=True)
    try:
        system = planar_system(turned, {fixed_name: (value,), a_name: (A,), b_name: (B,)})
        F, (D, Dx, Dy) = eliminant(system)
    except FormulationError as exc:
        raise UserError(f"{where}: the planar formulation does not apply: {exc}") from None
    P = without_free_factor(F, T, A, B)
    r = OFFSETS[0]
    theta0 = 2 * mpmath.atan(mpmath.mpf(r.p) / r.q)
    cramer = sympy.lambdify([C, S, A, B], [D, Dx, Dy], "mpmath")

    def mode_at(a: Any, b: Any, t: Any) -> dict[str, Any]:
        with mpmath.workdps(30):
            theta = theta0 + 2 * mpmath.atan(t)
            c, s = mpmath.cos(theta), mpmath.sin(theta)
            d, dx, dy = cramer(c, s, a, b)
            pose = (c, s, dx / d, dy / d)
            out: dict[str, Any] = {
                "platform": {"x": float(pose[2]), "y": float(pose[3]), "theta": float(theta)}
            }
            try:
                num = {
                    fixed_name: (value,),
                    a_name: (sympy.Float(a, 30),),
                    b_name: (sympy.Float(b, 30),),
                }
                coords = joint_values(turned, [planar_system(turned, num)], num, [pose])
                names = [n for n, _ in turned.coordinates()]
                out["joints"] = {n: float(v) for n, v in zip(names, coords, strict=True)}
            except (FormulationError, ZeroDivisionError):
                pass
        return out

    return {
        "problem": "direct kinematics",
        "varied": (a_name, b_name),
        "fixed": {fixed_name: float(sympy.N(value, 20))},
        "family": Family.of(P, T, A, B),
        "formulation": {
            "name": "planar platform pose",
            "platform": system.platform,
            "eliminant_degree": int(sympy.Poly(P, T).degree()),
            "t": "tan((theta - theta0) / 2)",
            "theta0": float(theta0),
        },
        "mode_at": mode_at,
    }
