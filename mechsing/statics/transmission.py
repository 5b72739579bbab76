"""Motion/force transmission indices (Wang, Wu & Liu, Mech. Mach. Theory 45(10), 2010).

Their setting: a parallel mechanism whose every leg has one actuated coordinate and a
unique transmission wrench: the wrench reciprocal to the leg's passive joints (and, for
an output point, to the output body's rotations about it) within the motion space of
the mechanism (the span of its joint screws), and not reciprocal to its actuated joint.
Elsewhere the indices are null, with the reason.

For a transmission force ``f`` entering a body at the point X (the leg's joint after the
actuator for the input; the leg's joint on the output body, or the output point, for the
output) the index is the power coefficient relative to its largest value,
``|f . v_X| / (|f| |v_X|)``: the cosine of the pressure angle (for a crank, the sine of
the transmission angle).  For a pure couple ``m`` it is ``|m . omega| / (|m| |omega|)``.
The input twist is the actuated joint's screw; the output twist of leg i is the output's
when every other input is locked.  ``input`` and ``output`` are each leg's; ``local`` is
the least of all.  They are ratios of powers of unit screws: frame- and unit-invariant.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.numeric import MEMBERSHIP_RTOL_FLOAT, Precision, decide_rank, to_float
from mechsing.singularity.criteria import leg_path
from mechsing.statics.matrices import MotionMatrices

__all__ = ["Transmission", "transmission"]

_FLOAT = Precision("float")
_POINT_TYPES = ("R", "H", "C", "S", "U")


@dataclass(frozen=True)
class Transmission:
    """``input`` / ``output``: one index per leg (legs numbered from 1 in file order),
    ``local`` the least; all None with ``reason`` outside the setting."""

    input: list[float] | None = None
    output: list[float] | None = None
    local: float | None = None
    reason: str | None = None
    legs: list[dict[str, Any]] = field(default_factory=list)

    def to_json(self) -> dict[str, Any]:
        return {
            "input": self.input,
            "output": self.output,
            "local": self.local,
            "reason": self.reason,
            "legs": self.legs,
        }

    def text_lines(self) -> list[str]:
        if self.local is None:
            return [f"transmission indices: none ({self.reason})"]
        assert self.input is not None and self.output is not None
        return [
            "transmission indices (Wang et al. 2010): input "
            + ", ".join(f"{x:.4g}" for x in self.input)
            + "; output "
            + ", ".join(f"{x:.4g}" for x in self.output)
            + f"; local {self.local:.4g}"
        ]


def _none(reason: str) -> Transmission:
    return Transmission(reason=reason)


def _joint_point(mech: Any, mm: MotionMatrices, name: str) -> np.ndarray | None:
    j = mech.joint(name)
    if j.type not in _POINT_TYPES:
        return None
    x0 = np.asarray(to_float(np.array(j.params["point"], dtype=object)), dtype=float)
    return np.asarray(lie.act_point(mm.poses[j.between[0]], x0), dtype=float)


def _index(w: np.ndarray, t: np.ndarray, x: np.ndarray | None, L: float) -> float | None:
    """The power coefficient of the SI wrench ``w`` on the SI twist ``t`` over its
    largest (a pure force entering at ``x``, or a pure couple); None for neither."""
    f, m0 = w[:3], w[3:]
    om, v0 = t[:3], t[3:]
    nf = float(np.linalg.norm(f))
    if nf * L > MEMBERSHIP_RTOL_FLOAT * float(np.linalg.norm(m0)):
        if x is None:
            return None
        mx = m0 - np.cross(x, f)
        if float(np.linalg.norm(mx)) > MEMBERSHIP_RTOL_FLOAT * nf * L:
            return None  # not a force through x
        vx = v0 + np.cross(om, x)
        nv = float(np.linalg.norm(vx))
        return 0.0 if nv == 0 else abs(float(f @ vx)) / (nf * nv)
    nm, no = float(np.linalg.norm(m0)), float(np.linalg.norm(om))
    return 0.0 if no == 0 or nm == 0 else abs(float(m0 @ om)) / (nm * no)


def transmission(mech: Any, mm: MotionMatrices) -> Transmission:
    """The transmission indices at ``mm``'s configuration (see the module)."""
    legs = mech.legs
    if len(legs) < 2:
        return _none("not a parallel mechanism: the indices need two legs or more")
    inputs = mech.input_coordinates()
    fm = mm.model
    L = mm.L
    Ss = np.asarray(mm.frame.screws(mm.S), dtype=float)  # commensurate screws
    out = mech.output
    span = decide_rank(Ss, _FLOAT, L, want_spaces=True)
    if span.rank is None:
        return _none("the motion space's dimension is undecided at float")
    Q = span.range_space  # 6 x d, commensurate motion space
    # a positioning task (an output point) when the inputs are fewer than the motion
    # space's dimension: the output body's rotations about its point do no task work;
    # with as many inputs the inputs fix the body, whose twist is the output
    xP = None
    if out.point is not None and len(inputs) < Q.shape[1]:
        xP = mm.point_now(out.point)
    extra = np.zeros((6, 0))
    if xP is not None:
        # rotations about x_P: (e_i, x_P x e_i) as columns
        rot = np.vstack([np.eye(3), np.cross(xP[None, :], np.eye(3)).T])
        extra = np.asarray(mm.frame.twists(rot), dtype=float)
    if extra.shape[1]:  # only the rotations about the point that lie in the motion space
        inside = decide_rank(extra - Q @ (Q.T @ extra), _FLOAT, L, want_spaces=True)
        C = inside.null_space if inside.null_space is not None else np.zeros((3, 0))
        extra = extra @ C
    AE = np.vstack([mm.A, mm.E])
    # at a Type II configuration (the output moves with the inputs locked) an input's
    # output twist is unbounded along a twist no transmission wrench does power on: the
    # output indices are 0 (their limit)
    locked = decide_rank(AE, _FLOAT, L, want_spaces=True)
    Z = locked.null_space if locked.null_space is not None else np.zeros((AE.shape[1], 0))
    type2 = bool(Z.shape[1]) and decide_rank(mm.T @ Z, _FLOAT, L).rank != 0
    ins, outs, per = [], [], []
    for k, leg in enumerate(legs, start=1):
        acts = [(j, i) for (j, i) in inputs if j in leg.joints]
        if len(acts) != 1:
            return _none(
                f"leg {k} ({', '.join(leg.joints)}) has {len(acts)} actuated coordinates; the "
                "indices need exactly one per leg"
            )
        aj, ai = acts[0]
        acol = fm.joint(aj).columns.start + ai
        cols = [
            c
            for j in leg.joints
            for c in range(fm.joint(j).columns.start, fm.joint(j).columns.stop)
        ]
        passive = [c for c in cols if c != acol]
        Pm = np.hstack([Ss[:, passive], extra])
        R = Q.T @ Pm  # passive screws in the motion space
        dec = decide_rank(R.T if R.size else np.zeros((0, Q.shape[1])), _FLOAT, L, want_spaces=True)
        if dec.rank is None:
            return _none(f"leg {k}: the rank of its passive joints is undecided at float")
        Y = dec.null_space  # d x s: wrenches reciprocal to the passive screws (in Q coordinates)
        if Y is None or Y.shape[1] == 0:
            return _none(f"leg {k} transmits no wrench: its passive joints span the motion space")
        full = decide_rank((Q.T @ np.hstack([Ss[:, cols], extra])).T, _FLOAT, L, want_spaces=True)
        Yc = full.null_space if full.null_space is not None else np.zeros((Q.shape[1], 0))
        # the leg at an input singularity: its one transmission wrench is reciprocal to
        # the actuated joint too (the input index is 0)
        at_input = Y.shape[1] == 1 and Yc.shape[1] == 1
        if at_input:
            Yc = np.zeros((Y.shape[0], 0))
        if Y.shape[1] - Yc.shape[1] != 1:
            return _none(
                f"leg {k}: its transmission wrench is not unique ({Y.shape[1] - Yc.shape[1]} "
                "independent ones)"
            )
        # the transmission wrench: reciprocal to the passive joints, orthogonal to the
        # leg's constraint wrenches
        if Yc.shape[1]:
            Y = Y - Yc @ (Yc.T @ Y)
        u, s, _ = np.linalg.svd(Y, full_matrices=False)
        y = Q @ u[:, 0]
        w = mm.wrench_out(y)
        path = leg_path(mech, leg, out.relative_to, out.body)
        names = [jn for jn, _ in path]
        if aj not in names:
            return _none(f"leg {k}: its actuated joint {aj} is not on its path to the output")
        after = names[names.index(aj) + 1] if names.index(aj) + 1 < len(names) else None
        x_in = None if after is None else _joint_point(mech, mm, after)
        t_in = mm.S[:, acol]
        lam = 0.0 if at_input else _index(w, t_in, x_in, L)
        # the output twist with every other input locked
        rhs = np.zeros(AE.shape[0])
        rhs[mm.A.shape[0] + inputs.index((aj, ai))] = 1.0
        z = np.linalg.lstsq(AE, rhs, rcond=None)[0]
        t_out = mm.twist_out(mm.T @ z)
        x_out = xP if xP is not None else _joint_point(mech, mm, names[-1])
        eta = 0.0 if type2 else _index(w, t_out, x_out, L)
        if lam is None or eta is None:
            return _none(
                f"leg {k}: its transmission wrench is neither a pure force through a joint "
                "point nor a pure couple"
            )
        ins.append(lam)
        outs.append(eta)
        scale = float(np.linalg.norm(w[:3])) or float(np.linalg.norm(w[3:])) or 1.0
        per.append(
            {
                "leg": k,
                "input": mm.inputs[inputs.index((aj, ai))],
                "wrench": [float(a) for a in w / scale],
                "input_index": lam,
                "output_index": eta,
            }
        )
    return Transmission(ins, outs, float(min(ins + outs)), None, per)
