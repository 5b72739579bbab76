"""Given joint values -> coordinates: what a named configuration fixes.

:class:`GivenValues` turns a configuration's values (numbers, displacements) into
the model's coordinates of the joints it gives, in the model's numbers, checking
what the file claims in the analysis's own mode (:attr:`GivenValues.data_precision`):
a displacement in its joint's subgroup, a rotation orthonormal, the reference
configuration's values the identity, exact data algebraic, every value of a sensible
size; the couplings complete the values their leaders give.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from mechsing import lie
from mechsing.errors import ExactDataError, UserError
from mechsing.kinematics.couplings import couple_given, impose_couplings
from mechsing.kinematics.model import KinematicModel
from mechsing.lie import ANGULAR
from mechsing.model import Configuration, Displacement
from mechsing.numeric import (
    MAX_JOINT_VALUE,
    Precision,
    rotation_orthonormal_atol,
    screw_zero_rtol,
    to_float,
)
from mechsing.numeric.backend import exact_is_zero
from mechsing.numeric.lazy import sympy
from mechsing.timelimit import activity

__all__ = ["Given", "GivenValues", "to_the_tolerance"]


class Given(NamedTuple):
    """A configuration's given coordinates: ``target`` holds all the model's coordinates
    (zeros where not given), ``indices`` the columns given, sorted."""

    target: np.ndarray
    indices: tuple[int, ...]


class GivenValues:
    """The given values of the configurations of one kinematic model.

    ``data_precision`` is the mode whose tolerance decides whether a given value is what
    it claims to be (default: the model's); ``tolerance`` the closure tolerance the
    couplings' given values are checked to (default: the model's, at its length
    scale)."""

    def __init__(
        self,
        model: KinematicModel,
        data_precision: Precision | None = None,
        tolerance: Any = None,
    ) -> None:
        self.model = model
        self.mech = model.mech
        self.data_precision: Precision = data_precision or model.precision
        self.tolerance = (
            model.precision.closure_tolerance(model.length_scale)
            if tolerance is None
            else tolerance
        )

    def of(self, cfg: Configuration) -> Given:
        """Target coordinates (zeros where not given) and the indices given."""
        m = self.model
        target = m.zeros()
        given: list[int] = []
        if cfg.is_reference:
            # every joint at identity; the values it lists must be the identity
            if cfg.values:
                self._check_reference(cfg)
            # a coupled joint at its leader's image: its offset (identity when none)
            return Given(impose_couplings(m, target, set()), tuple(range(m.n)))
        for jname, val in cfg.values.items():
            jk = m.joint(jname)
            coords = self.coordinates_of_value(cfg, jname, val)
            fc = np.asarray(to_float(coords), dtype=float)
            # lengths are measured against the mechanism's own size L, angles in radians
            bound = m.float_frame.rates_back(
                np.full(len(fc), MAX_JOINT_VALUE), range(jk.columns.start, jk.columns.stop)
            )
            if not np.all(np.isfinite(fc)) or np.any(np.abs(fc) > bound):
                where = f"configuration {cfg.name!r}, joint {jname!r}" + (
                    f" (line {cfg.line})" if cfg.line else ""
                )
                raise UserError(
                    f"{where}: the value {[float(x) for x in fc]} (SI) is not a finite joint value of a "
                    f"sensible size (at most {MAX_JOINT_VALUE:g} rad, or {MAX_JOINT_VALUE:g} times the "
                    f"mechanism's size {m.length_scale:.3g} m for a length); check the value and the units"
                )
            if m.precision.mode == "exact":  # policy: exact mode takes exact values only
                self._refuse_transcendental(cfg, jk, coords)
            target[jk.columns] = coords
            given.extend(range(jk.columns.start, jk.columns.stop))
        if m.couplings:
            where = f"configuration {cfg.name!r}" + (f" (line {cfg.line})" if cfg.line else "")
            target, have = couple_given(m, target, set(given), self.tolerance, where)
            given = list(have)
        return Given(target, tuple(sorted(given)))

    def coordinates_of_value(self, cfg: Configuration, jname: str, val: Any) -> np.ndarray:
        """A given value's coordinates in its joint's subgroup, in the model's numbers."""
        if isinstance(val, Displacement):
            return self._coordinates_of_displacement(cfg, jname, val)
        return self.model.asarray(list(val))

    def _check_reference(self, cfg: Configuration) -> None:
        """The values the reference configuration lists must be the identity in the
        analysis's mode: zero coordinates (angles to the mode's tolerance, lengths to
        it times L; exactly in exact mode), or an identity displacement."""
        m, decide = self.model, self.data_precision
        for jname, val in cfg.values.items():
            jk = m.joint(jname)
            coords = self.coordinates_of_value(cfg, jname, val)
            # a length against L, an angle against 1 (exact: proved zero)
            scale = m.float_frame.rates_back(
                np.ones(len(coords)), range(jk.columns.start, jk.columns.stop)
            )
            with decide.context():
                zero = all(
                    decide.backend.is_zero(x, s)
                    for x, s in zip(decide.asarray(coords), scale, strict=True)
                )
            if not zero:
                line = val.line if isinstance(val, Displacement) else cfg.lines.get(jname)
                where = f"{self.mech.path}:{line}: " if self.mech.path and line else ""
                raise UserError(
                    f"{where}configuration {cfg.name!r}: joint {jname!r}: the reference "
                    "configuration has every joint at identity (value 0), and this value is not "
                    f"the identity {to_the_tolerance(decide)}; give it in a new configuration"
                )

    def _refuse_transcendental(self, cfg: Configuration, jk: Any, coords: np.ndarray) -> None:
        """Exact data: every rotation a joint value produces must have
        algebraic entries (angles that are rational multiples of pi, atan/asin/acos of
        algebraic numbers and their sums).  sympy must *prove* it (``is_algebraic``
        after expanding the trigonometric functions): 1 rad, pi*sqrt(2) or pi**2 are
        refused rather than mis-checked."""
        if jk.type in ("R", "H", "C", "U"):
            angles = list(coords) if jk.type == "U" else [coords[0]]
            entries = [f(v) for v in angles for f in (sympy.sin, sympy.cos)]
        else:
            rotates = any(any(x != 0 for x in row[ANGULAR]) for row in jk.basis.tolist())
            if not rotates:
                return
            q = self.model.zeros()
            q[jk.columns] = coords
            entries = list(self.model.element(jk, q)[:3, :3].flat)
        for x in entries:
            # the stable forms of exp write 1 - cos a as 2 sin(a/2)**2: trigsimp folds the
            # half angles back (cos(atan(4/3)) is 3/5) when expansion alone cannot tell
            with activity(f"showing that the value of joint {jk.name!r} is exact data"):
                algebraic = sympy.expand_trig(x).is_algebraic is True or (
                    sympy.expand_trig(sympy.trigsimp(x)).is_algebraic is True
                )
            if not algebraic:
                where = f"configuration {cfg.name!r}, joint {jk.name!r}" + (
                    f" (line {cfg.line})" if cfg.line else ""
                )
                shown = ", ".join(str(v) for v in coords)
                raise ExactDataError(
                    f"{where}: the value [{shown}] is not exact data (sympy cannot show that "
                    'the rotation it gives is algebraic); exact mode needs angles such as "pi/6", '
                    '"atan(1/2)" or "2*atan(1/3)"; use --precision auto, float or mp:N for this '
                    "configuration",
                    cfg.name,
                )

    def _coordinates_of_displacement(
        self, cfg: Configuration, jname: str, val: Displacement
    ) -> np.ndarray:
        """The joint's coordinates (its log in the subgroup) of a displacement value.

        The displacement is read in the model's arithmetic and its membership in
        the joint's subgroup decided with the tolerance of the analysis's mode
        (:attr:`data_precision`): 1e-9 in float, 10^(-N/2) at mp:N, exactly in
        exact mode.  An omitted rotation is the identity; an omitted translation
        is completed (:meth:`Subgroup.completing_translation`).
        """
        m = self.model
        jk = m.joint(jname)
        where = f"configuration {cfg.name!r}, joint {jname!r}" + (
            f" (line {val.line})" if val.line else ""
        )
        if jk.subgroup is None:
            raise UserError(f"{where}: a U joint takes two angles [q1, q2], not a displacement")
        prec, decide = m.precision, self.data_precision
        with prec.context():
            R = (
                m.backend.eye(3)
                if val.rotation is None
                else m.asarray([list(r) for r in val.rotation])
            )
            self.check_rotation(where, R)
            if val.translation is None:
                p = jk.subgroup.completing_translation(R, prec)
            else:
                p = m.asarray(list(val.translation))
            g = lie.pose(R, p)
            try:
                q = jk.subgroup.coordinates_of(g, prec)
            except ValueError:
                q = None
            if q is None or not jk.subgroup.contains(g, m.length_scale, decide, q):
                if val.translation is None:
                    raise UserError(
                        f"{where}: no displacement of the joint's {jk.type} subgroup has this "
                        "rotation (whatever the translation); give a rotation the joint can produce"
                    )
                raise UserError(
                    f"{where}: this displacement is not in the joint's {jk.type} subgroup "
                    f"(decided {to_the_tolerance(decide)}); give a rotation and translation the "
                    "joint can produce, or leave the translation out to have it completed"
                )
            return q

    def check_rotation(self, where: str, R: np.ndarray) -> None:
        """A given rotation must be orthonormal with det 1, to the mode's tolerance."""
        decide = self.data_precision
        Rf = to_float(R)
        if np.linalg.det(Rf) > 0:
            E = R.T @ R - self.model.backend.eye(3)
            if decide.mode == "exact":  # policy: exact entries only, with its own advice
                if all(exact_is_zero(x) is True for x in E.flat):
                    return
                raise UserError(
                    f"{where}: the rotation is not exactly a rotation matrix (R^T R = I); exact "
                    'mode needs exact entries, such as "sqrt(2)/2" or 0.6 and 0.8; use '
                    "--precision auto, float or mp:N for decimals rounded from a rotation"
                )
            atol = rotation_orthonormal_atol(decide)
            with decide.context():
                err = max(abs(x) for x in decide.asarray(E).flat)
            if err <= atol:
                return
        raise UserError(
            f"{where}: the rotation is not a rotation matrix (R^T R = I, det R = 1) "
            f"{to_the_tolerance(decide)}; give an orthonormal matrix (with more digits)"
        )


def to_the_tolerance(prec: Precision) -> str:
    """How a precision mode decides that a given value is what it claims, for messages."""
    if prec.mode == "exact":  # the wording differs, not the arithmetic
        return "exactly, in exact mode"
    with prec.context():
        tol = float(screw_zero_rtol(prec.backend))
    return f"to {tol:.0e} (relative) at {prec} precision"
