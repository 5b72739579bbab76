"""Mechanism files without mechsing: :class:`Spec` writes one from reference joints (in any
units), :class:`MechanismFile` reads one with yaml and the whitelisted expressions, solves its
named configurations by continuation (:func:`tests.reference.kinematics.track`) and gives poses,
closure residuals and spatial joint screws on a flat coordinate vector (file order, basis
order)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import networkx as nx
import numpy as np
import yaml

from tests.reference.expressions import num, vec
from tests.reference.kinematics import (
    KINDS,
    J,
    closure_residual,
    cycle_products,
    cycles,
    poses,
    spatial_screws,
    track,
)
from tests.reference.se3 import unit

#: SI value of each unit a file may declare
UNITS = {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "rad": 1.0, "deg": math.pi / 180}


def _num_text(x: float) -> str:
    return repr(float(x))


def _vec_text(v: object) -> str:
    return "[" + ", ".join(_num_text(x) for x in v) + "]"


@dataclass
class Spec:
    """A mechanism file written by a test, and the SI geometry behind it."""

    bodies: list[str]
    ground: str
    joints: list[J]
    configurations: dict[str, dict] = field(
        default_factory=dict
    )  # name -> {joint: SI values, "start": ...}
    inputs: list[str] = field(default_factory=list)
    output: str | None = None
    length: str = "m"
    angle: str = "rad"

    def to_file(self) -> tuple[str, dict[str, dict[str, np.ndarray]]]:
        """The YAML text, and each configuration's values as the file gives them, in SI."""
        lf, af = UNITS[self.length], UNITS[self.angle]
        lines = ["mechanism: generated"]
        if (self.length, self.angle) != ("m", "rad"):
            lines.append(f"units: {{length: {self.length}, angle: {self.angle}}}")
        lines.append(f"ground: {self.ground}")
        lines.append(f"bodies: [{', '.join(self.bodies)}]")
        lines.append("joints:")
        for j in self.joints:
            geo = []
            for key, val in j.prm.items():
                if key == "point":
                    geo.append(f"point: {_vec_text(np.asarray(val) / lf)}")
                elif key == "pitch":
                    geo.append(f"pitch: {_num_text(val / lf)}")
                elif key == "axes":
                    geo.append(f"axes: [{_vec_text(val[0])}, {_vec_text(val[1])}]")
                else:
                    geo.append(f"{key}: {_vec_text(val)}")
            lines.append(
                f"  - {{name: {j.name}, type: {j.type}, between: [{j.a}, {j.b}]"
                + "".join(", " + g for g in geo)
                + "}"
            )
        if self.inputs:
            lines.append(f"inputs: [{', '.join(self.inputs)}]")
        if self.output:
            lines.append(f"output: {{body: {self.output}}}")
        lines.append("configurations:")
        lines.append("  reference: {}")
        written: dict[str, dict[str, np.ndarray]] = {}
        by = {j.name: j for j in self.joints}
        for cname, vals in self.configurations.items():
            items = []
            si: dict[str, np.ndarray] = {}
            for jn, v in vals.items():
                if jn == "start":
                    items.append(f"start: {v}")
                    continue
                kinds = KINDS[by[jn].type]
                texts = [
                    _num_text(x / (af if k == "a" else lf)) for x, k in zip(v, kinds, strict=True)
                ]
                si[jn] = np.array(
                    [float(t) * (af if k == "a" else lf) for t, k in zip(texts, kinds, strict=True)]
                )
                items.append(f"{jn}: " + (texts[0] if len(texts) == 1 else f"[{', '.join(texts)}]"))
            lines.append(f"  {cname}: {{{', '.join(items)}}}")
            written[cname] = si
        return "\n".join(lines) + "\n", written


class MechanismFile:
    """A mechanism file read with yaml alone; joint values as one flat vector ``q`` (SI)."""

    def __init__(self, path: Path):
        self.path = path
        self.data = yaml.safe_load(path.read_text())
        d = self.data
        units = d.get("units", {}) or {}
        self.lf = UNITS[units.get("length", "m")]
        self.af = UNITS[units.get("angle", "rad")]
        self.bodies = list(d["bodies"])
        self.ground = d.get("ground", self.bodies[0])
        #: the file's joint entries as written, by name
        self.raw: dict[str, dict] = {j["name"]: j for j in d["joints"]}
        self.joints = [
            J(j["name"], j["type"], j["between"][0], j["between"][1], self._params(j))
            for j in d["joints"]
        ]
        self.jidx = {j.name: i for i, j in enumerate(self.joints)}
        self.coords = [(j.name, k) for j in self.joints for k in range(len(KINDS[j.type]))]
        self.cidx = {c: i for i, c in enumerate(self.coords)}
        self.L = self._char_length()
        G = nx.MultiGraph()
        G.add_nodes_from(self.bodies)
        for j in self.joints:
            G.add_edge(j.a, j.b, key=j.name)
        assert nx.is_connected(G), path
        self._cycles = cycles(self.joints)
        self._cache: dict[str, np.ndarray] = {}

    def _params(self, j: dict) -> dict:
        prm: dict = {}
        for key in ("axis", "normal", "point", "axes", "pitch"):
            if key not in j:
                continue
            if key == "point":
                prm[key] = vec(j[key]) * self.lf
            elif key == "pitch":
                prm[key] = num(j[key]) * self.lf
            elif key == "axes":
                prm[key] = tuple(vec(a) for a in j[key])
            else:
                prm[key] = vec(j[key])
        return prm

    def _char_length(self) -> float:
        """The characteristic length: RMS distance of the joints' axis points from their
        centroid (R: the foot of the axis nearest the origin; S, U: the centre)."""
        pts = []
        for j in self.joints:
            if j.type == "R":
                u, p = unit(j.prm["axis"]), j.prm["point"]
                pts.append(p - (p @ u) * u)
            elif j.type in ("S", "U"):
                pts.append(j.prm["point"])
        if not pts:
            return 1.0
        pts = np.array(pts)
        c = pts.mean(0)
        L = float(np.sqrt(((pts - c) ** 2).sum(1).mean()))
        return L or float(np.linalg.norm(c)) or 1.0

    # ------------------------------------------------------------------ coordinates
    def values(self, name: str) -> dict:
        """A named configuration as the file writes it."""
        return self.data["configurations"][name]

    def given(self, cfg: dict) -> dict[str, np.ndarray]:
        """The joint values a configuration gives, in SI."""
        out = {}
        for jn, v in cfg.items():
            if jn == "start":
                continue
            vals = v if isinstance(v, list) else [v]
            kinds = KINDS[self.joints[self.jidx[jn]].type]
            assert len(vals) == len(kinds), (self.path, jn)
            out[jn] = np.array(
                [
                    num(x) * (self.af if k == "a" else self.lf)
                    for x, k in zip(vals, kinds, strict=True)
                ]
            )
        return out

    def split(self, q: np.ndarray) -> dict[str, np.ndarray]:
        """The flat vector as {joint: its coordinates}."""
        out, k = {}, 0
        for j in self.joints:
            n = len(KINDS[j.type])
            out[j.name] = np.asarray(q[k : k + n], float)
            k += n
        return out

    def flat(self, values: dict[str, np.ndarray]) -> np.ndarray:
        parts = [np.asarray(values[j.name], float).reshape(-1) for j in self.joints]
        return np.concatenate(parts) if parts else np.zeros(0)

    # ------------------------------------------------------------------ kinematics
    def poses(self, q: np.ndarray) -> dict[str, np.ndarray]:
        return poses(self.joints, self.ground, self.split(q))

    def loops(self) -> list:
        """A cycle basis of the body/joint graph, each cycle as [(joint, +1 or -1), ...]."""
        return self._cycles

    def loop_residual(self, q: np.ndarray) -> float:
        """The largest entry of the closure residual ((R - I), p / L around every cycle)."""
        products = cycle_products(self.joints, self.split(q), basis_cycles=self._cycles)
        res = closure_residual(products, self.L)
        return float(np.max(np.abs(res))) if len(res) else 0.0

    def current_screws(self, q: np.ndarray, names: set[str] | None = None) -> np.ndarray:
        """Spatial joint screws at q, ordered as self.coords (or for the given joints)."""
        vals = self.split(q)
        return spatial_screws(self.joints, poses(self.joints, self.ground, vals), vals, names)

    def solve(self, name: str) -> np.ndarray:
        """The flat joint values of a named configuration: as given when every value is given
        or there is no loop; else tracked from its start (the reference from zero) in steps of
        at most 0.1 rad (or 0.1 L)."""
        if name in self._cache:
            return self._cache[name]
        cfg = self.values(name) or {}
        given = self.given(cfg)
        moving = [j for j in self.joints if KINDS[j.type]]
        if len(given) == len(moving) or not self._cycles:
            vals = {j.name: given.get(j.name, np.zeros(len(KINDS[j.type]))) for j in self.joints}
            q = self.flat(vals)
        else:
            start = (
                self.split(self.solve(cfg.get("start", "reference")))
                if name != "reference"
                else self.split(np.zeros(len(self.coords)))
            )
            span = max((np.max(np.abs(v - start[jn])) for jn, v in given.items()), default=0.0)
            steps = max(8, int(math.ceil(span / min(1.0, self.L) / 0.1)))
            vals, _ = track(
                self.joints,
                start,
                given,
                self.L,
                nsteps=steps,
                iterations=30,
                refresh=1,
                rcond=1e-8,
            )
            assert vals is not None, (self.path, name, "continuation failed or jumped")
            q = self.flat(vals)
        self._cache[name] = q
        return q
