"""Independent checks of the bundled example mechanisms (examples/*.yaml).

Nothing here imports mechsing: the files are read with yaml.safe_load, expressions are evaluated by a
small whitelisted AST walker, joint screws and poses are built from the file geometry with numpy /
scipy.linalg.expm, passive joints are solved by continuation with scipy.optimize.least_squares, and
loops are found with networkx. Each example also gets one check of a published fact.
"""

from __future__ import annotations

import ast
import math
from pathlib import Path

import networkx as nx
import numpy as np
import pytest
import yaml
from scipy.linalg import expm
from scipy.optimize import least_squares

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
TOL = 1e-10

# ----------------------------------------------------------------------------- expressions

_FUNCS = {
    "sqrt": math.sqrt,
    "sin": math.sin,
    "cos": math.cos,
    "tan": math.tan,
    "asin": math.asin,
    "acos": math.acos,
    "atan": math.atan,
    "atan2": math.atan2,
}


def evaluate(x, funcs=None, const=float, pi=math.pi):
    """A file number or a whitelisted expression string (numbers, + - * / **, parentheses, pi and
    the functions of DESIGN.md), evaluated by walking its AST -- never eval or sympify."""
    funcs = funcs or _FUNCS
    if isinstance(x, bool):
        raise TypeError(x)
    if isinstance(x, (int, float)):
        return const(x) if const is not float else float(x)
    tree = ast.parse(str(x), mode="eval")

    def ev(n):
        if isinstance(n, ast.Expression):
            return ev(n.body)
        if (
            isinstance(n, ast.Constant)
            and isinstance(n.value, (int, float))
            and not isinstance(n.value, bool)
        ):
            return const(n.value)
        if isinstance(n, ast.Name) and n.id == "pi":
            return pi
        if isinstance(n, ast.UnaryOp) and isinstance(n.op, (ast.USub, ast.UAdd)):
            v = ev(n.operand)
            return -v if isinstance(n.op, ast.USub) else v
        if isinstance(n, ast.BinOp) and type(n.op) in _OPS:
            return _OPS[type(n.op)](ev(n.left), ev(n.right))
        if (
            isinstance(n, ast.Call)
            and isinstance(n.func, ast.Name)
            and n.func.id in funcs
            and not n.keywords
        ):
            return funcs[n.func.id](*[ev(a) for a in n.args])
        raise ValueError(f"expression outside the whitelist: {x!r}")

    return ev(tree)


_OPS = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.Pow: lambda a, b: a**b,
}


def num(x) -> float:
    return float(evaluate(x))


def vec(v) -> np.ndarray:
    return np.array([num(x) for x in v], dtype=float)


# ----------------------------------------------------------------------------- screws


def hat(xi):
    w, v = xi[:3], xi[3:]
    m = np.zeros((4, 4))
    m[:3, :3] = [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]
    m[:3, 3] = v
    return m


def Ad(g):
    R, p = g[:3, :3], g[:3, 3]
    ph = hat(np.r_[p, 0, 0, 0])[:3, :3]
    out = np.zeros((6, 6))
    out[:3, :3] = R
    out[3:, :3] = ph @ R
    out[3:, 3:] = R
    return out


def exp_fast(xi):
    """Closed-form exponential of a twist (Rodrigues), used inside the solver for speed;
    every reported closure residual uses scipy.linalg.expm instead."""
    w, v = xi[:3], xi[3:]
    K = hat(np.r_[w, 0, 0, 0])[:3, :3]
    th = float(np.linalg.norm(w))
    if th < 1e-8:
        a, b, c = 1.0, 0.5, 1.0 / 6.0
    else:
        a, b, c = math.sin(th) / th, (1 - math.cos(th)) / th**2, (th - math.sin(th)) / th**3
    K2 = K @ K
    g = np.eye(4)
    g[:3, :3] = np.eye(3) + a * K + b * K2
    g[:3, 3] = (np.eye(3) + b * K + c * K2) @ v
    return g


def rscrew(u, p):
    u = u / np.linalg.norm(u)
    return np.r_[u, np.cross(p, u)]


def unit(u):
    u = np.asarray(u, float)
    return u / np.linalg.norm(u)


def newton(f, x, iters=30):
    """Gauss-Newton with a forward-difference Jacobian, least-squares (minimum-norm) steps;
    falls back to scipy.optimize.least_squares if it does not converge."""
    x = np.array(x, float)
    for _ in range(iters):
        r = f(x)
        if np.max(np.abs(r)) < 1e-13:
            return x
        h = 1e-7
        J = np.empty((len(r), len(x)))
        for k in range(len(x)):
            xk = x.copy()
            xk[k] += h
            J[:, k] = (f(xk) - r) / h
        dx = np.linalg.lstsq(J, -r, rcond=1e-8)[0]  # drop redundant constraints
        x = x + dx
        if np.max(np.abs(dx)) < 1e-15:
            return x
    return least_squares(f, x, xtol=1e-15, ftol=1e-15, gtol=1e-15).x


class Mech:
    def __init__(self, path: Path):
        self.path = path
        self.data = yaml.safe_load(path.read_text())
        d = self.data
        units = d.get("units", {}) or {}
        self.lf = {"m": 1.0, "cm": 0.01, "mm": 0.001}[units.get("length", "m")]
        self.af = {"rad": 1.0, "deg": math.pi / 180}[units.get("angle", "rad")]
        self.bodies = list(d["bodies"])
        self.ground = d.get("ground", self.bodies[0])
        self.joints = []
        for j in d["joints"]:
            t = j["type"]
            if t == "R":
                sc, kinds = [rscrew(vec(j["axis"]), vec(j["point"]) * self.lf)], ["a"]
            elif t == "P":
                sc, kinds = [np.r_[0, 0, 0, unit(vec(j["axis"]))]], ["l"]
            elif t == "S":
                c = vec(j["point"]) * self.lf
                sc, kinds = [rscrew(e, c) for e in np.eye(3)], ["a"] * 3
            elif t == "U":
                c = vec(j["point"]) * self.lf
                sc, kinds = [rscrew(vec(a), c) for a in j["axes"]], ["a", "a"]
            else:  # pragma: no cover - the examples use only R, P, S, U
                raise NotImplementedError(t)
            self.joints.append(
                dict(
                    name=j["name"],
                    type=t,
                    a=j["between"][0],
                    b=j["between"][1],
                    screws=sc,
                    kinds=kinds,
                    raw=j,
                )
            )
        self.jidx = {j["name"]: i for i, j in enumerate(self.joints)}
        # coordinate layout
        self.coords = [(j["name"], k) for j in self.joints for k in range(len(j["screws"]))]
        self.cidx = {c: i for i, c in enumerate(self.coords)}
        self.L = self._char_length()
        self._tree()
        self._cache: dict[str, np.ndarray] = {}

    # DESIGN.md's characteristic length (RMS distance of the joints' axis points from their centroid)
    def _char_length(self):
        pts = []
        for j in self.joints:
            r = j["raw"]
            if j["type"] == "R":
                u, p = unit(vec(r["axis"])), vec(r["point"]) * self.lf
                pts.append(p - (p @ u) * u)
            elif j["type"] in ("S", "U"):
                pts.append(vec(r["point"]) * self.lf)
        if not pts:
            return 1.0
        pts = np.array(pts)
        c = pts.mean(0)
        L = float(np.sqrt(((pts - c) ** 2).sum(1).mean()))
        return L or float(np.linalg.norm(c)) or 1.0

    def _tree(self):
        G = nx.MultiGraph()
        G.add_nodes_from(self.bodies)
        for j in self.joints:
            G.add_edge(j["a"], j["b"], key=j["name"])
        assert nx.is_connected(G), self.path
        self.G = G
        self.order, self.parent = [self.ground], {self.ground: None}
        tree_joints = set()
        for body in self.order:  # BFS in file order
            for j in self.joints:
                for here, there in ((j["a"], j["b"]), (j["b"], j["a"])):
                    if here == body and there not in self.parent:
                        self.parent[there] = j["name"]
                        self.order.append(there)
                        tree_joints.add(j["name"])
        self.cotree = [j["name"] for j in self.joints if j["name"] not in tree_joints]

    # ------------------------------------------------------------------ kinematics
    def values(self, name) -> dict:
        return self.data["configurations"][name]

    def scale(self, jname, k):
        return self.af if self.joints[self.jidx[jname]]["kinds"][k] == "a" else self.lf

    def given(self, cfg: dict) -> dict:
        out = {}
        for jn, v in cfg.items():
            if jn == "start":
                continue
            vals = v if isinstance(v, list) else [v]
            assert len(vals) == len(self.joints[self.jidx[jn]]["screws"]), (self.path, jn)
            for k, x in enumerate(vals):
                out[self.cidx[(jn, k)]] = num(x) * self.scale(jn, k)
        return out

    fast = False

    def E(self, jname, q):
        j = self.joints[self.jidx[jname]]
        qs = [q[self.cidx[(jname, k)]] for k in range(len(j["screws"]))]
        ex = exp_fast if self.fast else (lambda xi: expm(hat(xi)))
        if j["type"] == "U":
            return ex(qs[0] * j["screws"][0]) @ ex(qs[1] * j["screws"][1])
        return ex(sum(x * s for x, s in zip(qs, j["screws"], strict=True)))

    def poses(self, q):
        g = {self.ground: np.eye(4)}
        for body in self.order[1:]:
            jn = self.parent[body]
            j = self.joints[self.jidx[jn]]
            if j["b"] == body:
                g[body] = g[j["a"]] @ self.E(jn, q)
            else:
                g[body] = g[j["b"]] @ np.linalg.inv(self.E(jn, q))
        return g

    def _err(self, M):
        return np.r_[(M[:3, :3] - np.eye(3)).ravel(), M[:3, 3] / self.L]

    def residual(self, q):
        g = self.poses(q)
        out = [
            self._err(
                g[self.joints[self.jidx[c]]["a"]]
                @ self.E(c, q)
                @ np.linalg.inv(g[self.joints[self.jidx[c]]["b"]])
            )
            for c in self.cotree
        ]
        return np.concatenate(out) if out else np.zeros(0)

    def solve(self, name) -> np.ndarray:
        if name in self._cache:
            return self._cache[name]
        cfg = self.values(name) or {}
        given = self.given(cfg)
        n = len(self.coords)
        if len(given) == n or not self.cotree:
            q = np.zeros(n)
            for i, x in given.items():
                q[i] = x
        else:
            q = (
                self.solve(cfg.get("start", "reference")).copy()
                if name != "reference"
                else np.zeros(n)
            )
            free = [i for i in range(n) if i not in given]
            gi = list(given)
            q0g = q[gi].copy()
            target = np.array([given[i] for i in gi])
            span = np.max(np.abs(target - q0g)) / min(1.0, self.L) if gi else 0.0
            steps = max(8, int(math.ceil(span / 0.1)))
            for s in range(1, steps + 1):
                q[gi] = q0g + (target - q0g) * s / steps

                x = newton(lambda x, q=q: self._res_free(q, free, x), q[free])
                assert np.max(np.abs(x - q[free])) < 0.5, (
                    self.path,
                    name,
                    "continuation jumped",
                    s,
                )
                q[free] = x
        self._cache[name] = q
        return q

    def _res_free(self, q, free, x):
        qq = q.copy()
        qq[free] = x
        self.fast = True
        try:
            return self.residual(qq)
        finally:
            self.fast = False

    # ------------------------------------------------------------------ loops (networkx)
    def loops(self):
        """Minimum cycle basis of the body/joint graph, each cycle as [(joint, forward?), ...]."""
        if getattr(self, "_loops", None) is not None:
            return self._loops
        S = nx.Graph()
        for b in self.bodies:
            S.add_node(("b", b))
        for j in self.joints:
            S.add_edge(("b", j["a"]), ("j", j["name"]))
            S.add_edge(("j", j["name"]), ("b", j["b"]))
        out = []
        for cyc in nx.minimum_cycle_basis(S):
            sub = S.subgraph(cyc)
            start = next(n for n in cyc if n[0] == "b")
            walk = [u for u, _ in nx.find_cycle(sub, source=start)]
            loop = []
            for i, node in enumerate(walk):
                if node[0] == "j":
                    prev_body = walk[i - 1][1]
                    j = self.joints[self.jidx[node[1]]]
                    loop.append((node[1], j["a"] == prev_body))
            out.append(loop)
        self._loops = out
        return out

    def loop_residual(self, q):
        worst = 0.0
        for loop in self.loops():
            M = np.eye(4)
            for jn, fwd in loop:
                E = self.E(jn, q)
                M = M @ (E if fwd else np.linalg.inv(E))
            worst = max(worst, float(np.max(np.abs(self._err(M)))))
        return worst

    # ------------------------------------------------------------------ current screws
    def current_screws(self, q, names=None):
        """Spatial joint screws at q, ordered as self.coords (or for the given joints)."""
        g = self.poses(q)
        cols = []
        for j in self.joints:
            if names is not None and j["name"] not in names:
                continue
            ga = g[j["a"]]
            if j["type"] == "U":
                cols.append(Ad(ga) @ j["screws"][0])
                g1 = ga @ expm(hat(q[self.cidx[(j["name"], 0)]] * j["screws"][0]))
                cols.append(Ad(g1) @ j["screws"][1])
            else:
                cols.extend(Ad(ga) @ s for s in j["screws"])
        return np.array(cols).T


ALL = sorted(p.name for p in EXAMPLES.glob("*.yaml"))
EXPECTED = {
    "fourbar.yaml",
    "fourbar_changepoint.yaml",
    "parallelogram.yaml",
    "slider_crank_crank_input.yaml",
    "slider_crank_slider_input.yaml",
    "spherical_4r.yaml",
    "bennett.yaml",
    "bricard.yaml",
    "sarrus.yaml",
    "planar_3rpr.yaml",
    "tsai_3upu.yaml",
    "stewart_octahedral.yaml",
    "ur5.yaml",
    "puma560.yaml",
}
_M: dict[str, Mech] = {}


def mech(name) -> Mech:
    if name not in _M:
        _M[name] = Mech(EXAMPLES / name)
    return _M[name]


def test_all_examples_present():
    assert EXPECTED <= set(ALL)


@pytest.mark.parametrize("name", ALL)
def test_file_header_and_references(name):
    text = (EXAMPLES / name).read_text()
    assert text.startswith("#"), "each example starts with a comment block"
    assert "Source:" in text.split("\nmechanism:")[0]
    m = mech(name)
    names = {j["name"] for j in m.joints}
    assert len(names) == len(m.joints)
    for j in m.joints:
        assert j["a"] in m.bodies and j["b"] in m.bodies and j["a"] != j["b"]
    for i in m.data.get("inputs", []):
        assert str(i).split("[")[0] in names
    assert "reference" in m.data["configurations"]
    for cname, cfg in m.data["configurations"].items():
        cfg = cfg or {}
        assert set(cfg) - {"start"} <= names, cname
        if "start" in cfg:
            assert cfg["start"] in m.data["configurations"]
    # loop count invariant E - V + 1 (a U joint counts once)
    assert len(m.loops()) == len(m.joints) - len(m.bodies) + 1


@pytest.mark.parametrize("name", ALL)
def test_every_configuration_closes(name):
    m = mech(name)
    for cname in m.data["configurations"]:
        q = m.solve(cname)
        assert m.loop_residual(q) < TOL, (name, cname, m.loop_residual(q))


# ----------------------------------------------------------------------------- published facts


def planar_pts(m, q, jn):
    """current position (x, y) of an R joint's axis point."""
    j = m.joints[m.jidx[jn]]
    g = m.poses(q)[j["a"]]
    p = vec(j["raw"]["point"]) * m.lf
    return (g[:3, :3] @ p + g[:3, 3])[:2]


def rank(A, rel=1e-9):
    s = np.linalg.svd(A, compute_uv=False)
    return int((s > rel * s[0]).sum())


def test_fourbar_grashof_crank_rocker():
    m = mech("fourbar.yaml")
    P = [vec(m.joints[i]["raw"]["point"]) for i in range(4)]
    links = sorted(np.linalg.norm(P[(i + 1) % 4] - P[i]) for i in range(4))
    assert links[0] + links[3] < links[1] + links[2]  # Grashof
    assert np.isclose(np.linalg.norm(P[1] - P[0]), links[0])  # shortest = crank (on ground)
    for c in m.data["configurations"]:
        q = m.solve(c)
        assert rank(m.current_screws(q)) == 3  # regular everywhere
        # passive joints (B, C, D) keep full rank: no toggle
        assert rank(m.current_screws(q, {"B", "C", "D"})) == 3
    assert np.isclose(m.solve("crank-200")[0], math.radians(200))


def test_changepoint_flat_is_singular():
    m = mech("fourbar_changepoint.yaml")
    P = [vec(m.joints[i]["raw"]["point"]) for i in range(4)]
    links = sorted(np.linalg.norm(P[(i + 1) % 4] - P[i]) for i in range(4))
    assert np.isclose(links[0] + links[3], links[1] + links[2])  # change point
    assert np.allclose(np.array(P)[:, 1], 0)  # the reference is flat
    assert rank(m.current_screws(m.solve("reference"))) == 2
    for c in ("crank-up", "crank-120"):
        assert rank(m.current_screws(m.solve(c))) == 3


def test_parallelogram_two_branches_cross_at_flat():
    m = mech("parallelogram.yaml")
    assert rank(m.current_screws(m.solve("flat"))) == 2
    for c, parallel in (("reference", True), ("crank-30", True), ("anti-parallelogram", False)):
        q = m.solve(c)
        assert rank(m.current_screws(q)) == 3
        B, C = planar_pts(m, q, "B"), planar_pts(m, q, "C")
        assert np.isclose(C[1] - B[1], 0) == parallel  # coupler parallel to ground?


@pytest.mark.parametrize(
    "name,inp", [("slider_crank_crank_input.yaml", "A"), ("slider_crank_slider_input.yaml", "P")]
)
def test_slider_crank_dead_centre(name, inp):
    m = mech(name)
    assert m.data["inputs"] == [inp]
    q = m.solve("dead-centre")
    A, B, C = (planar_pts(m, q, j) for j in "ABC")
    assert abs((B - A)[0] * (C - A)[1] - (B - A)[1] * (C - A)[0]) < 1e-12  # crank and rod collinear
    J = m.current_screws(q)
    assert rank(J) == 3  # c-space regular
    passive = {"B", "C", "P"} if inp == "A" else {"A", "B", "C"}
    # crank input: passive system fine, slider rate zero (type I); slider input: passive rank drops (type II)
    assert rank(m.current_screws(q, passive)) == (3 if inp == "A" else 2)
    ker = np.linalg.svd(J)[2][-1]
    assert abs(ker[m.cidx[("P", 0)]]) < 1e-12 * np.max(np.abs(ker))
    for c in m.data["configurations"]:
        if c != "dead-centre":
            assert rank(m.current_screws(m.solve(c), passive)) == 3


def test_spherical_4r_concurrent_rank3():
    m = mech("spherical_4r.yaml")
    for c in m.data["configurations"]:
        J = m.current_screws(m.solve(c))
        assert np.allclose(J[3:], 0, atol=1e-12)  # all axes through O
        assert rank(J) == 3
        assert rank(m.current_screws(m.solve(c), {"B", "C", "D"})) == 3


def test_bennett_rank3_and_relation():
    m = mech("bennett.yaml")
    tan_a, tan_b = 1 / 3, 3 / 4
    K = (tan_b + tan_a) / (tan_b - tan_a)
    th1_ref, th2_ref = 2 * math.atan(1 / 2), 2 * math.atan(26 / 5)
    for c in m.data["configurations"]:
        q = m.solve(c)
        s = np.linalg.svd(m.current_screws(q), compute_uv=False)
        assert s[2] > 1e-3 and s[3] < 1e-10  # rank 3 along the motion
        t1, t2 = math.tan((th1_ref + q[0]) / 2), math.tan((th2_ref + q[1]) / 2)
        assert math.isclose(t1 * t2, K, rel_tol=1e-9)  # Bennett relation
        assert np.allclose(
            [q[2], q[3]], [-q[0], -q[1]], atol=1e-9
        )  # theta3 = -theta1, theta4 = -theta2
    # exact metric data: b = a sin(beta)/sin(alpha), and the relation's constant 13/5
    assert math.isclose(K, 13 / 5)


def test_bennett_closes_exactly():
    sp = pytest.importorskip("sympy")
    m = mech("bennett.yaml")
    funcs = {"sqrt": sp.sqrt, "atan": sp.atan, "sin": sp.sin, "cos": sp.cos, "tan": sp.tan}

    def ex(x):  # exact value: integers and decimals as rationals
        return evaluate(x, funcs, const=lambda v: sp.Rational(str(v)), pi=sp.pi)

    for c in ("theta1-90", "q1-half"):
        M = sp.eye(4)
        for j, (jn, v) in zip(m.data["joints"], m.data["configurations"][c].items(), strict=True):
            assert j["name"] == jn
            u = sp.Matrix([ex(x) for x in j["axis"]])
            p = sp.Matrix([ex(x) for x in j["point"]])
            th = ex(v)
            cth = sp.simplify(sp.expand_trig(sp.cos(th)))
            sth = sp.simplify(sp.expand_trig(sp.sin(th)))
            Kx = sp.Matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
            R = sp.eye(3) + sth * Kx + (1 - cth) * Kx * Kx
            T = sp.eye(4)
            T[:3, :3] = R
            T[:3, 3] = (sp.eye(3) - R) * p
            M = M * T
        assert sp.simplify(M - sp.eye(4)) == sp.zeros(4)


def test_bricard_rank5_and_line_symmetry():
    m = mech("bricard.yaml")
    for c in m.data["configurations"]:
        q = m.solve(c)
        s = np.linalg.svd(m.current_screws(q), compute_uv=False)
        assert s[4] > 1e-3 and s[5] < 1e-10
        assert np.allclose(q[3:], q[:3], atol=1e-8)  # q4 = q1, q5 = q2, q6 = q3
    assert abs(m.solve("q1-0.4")[0] - 0.4) < 1e-14


def test_sarrus_translation_and_rank():
    m = mech("sarrus.yaml")
    ranks = {}
    for c in m.data["configurations"]:
        q = m.solve(c)
        g = m.poses(q)["top"]
        assert np.allclose(g[:3, :3], np.eye(3), atol=1e-10) and np.allclose(
            g[:2, 3], 0, atol=1e-10
        )
        ranks[c] = rank(m.current_screws(q))
    assert ranks == {"reference": 5, "raised": 5, "lowered": 5, "stretched": 4}
    assert np.isclose(m.poses(m.solve("stretched"))["top"][2, 3], 2 * math.sqrt(2) - 2)


def _leg_lines_3rpr(m, q):
    lines = []
    for i in (1, 2, 3):
        a, b = planar_pts(m, q, f"Rb{i}"), planar_pts(m, q, f"Rp{i}")
        lines.append(np.r_[b - a, a[0] * b[1] - a[1] * b[0]])  # planar line coordinates
    return np.array(lines)


def test_3rpr_legs_concurrent_at_output_singularity():
    m = mech("planar_3rpr.yaml")
    det = {c: np.linalg.det(_leg_lines_3rpr(m, m.solve(c))) for c in m.data["configurations"]}
    assert abs(det["concurrent"]) < 1e-12
    assert abs(det["reference"]) > 1e-2 and abs(det["stroke"]) > 1e-2
    # the platform pivots are the base halved about c = (1, 1) at the concurrent pose
    q = m.solve("concurrent")
    for i in (1, 2, 3):
        a, b = planar_pts(m, q, f"Rb{i}"), planar_pts(m, q, f"Rp{i}")
        assert np.allclose(b, (a + np.array([1.0, 1.0])) / 2)


def _tsai_det_n(m, q):
    g = m.poses(q)
    ns = []
    for i in (1, 2, 3):
        j = m.joints[m.jidx[f"U{i}a"]]
        s1 = unit(vec(j["raw"]["axes"][0]))  # fixed in ground
        s2 = g[f"cyl{i}"][:3, :3] @ unit(vec(j["raw"]["axes"][1]))  # carried by the cylinder
        ns.append(np.cross(s1, s2))
    return np.linalg.det(np.array(ns))


def test_tsai_3upu_translational_and_constraint_singularity():
    m = mech("tsai_3upu.yaml")
    for c in m.data["configurations"]:
        q = m.solve(c)
        assert np.allclose(m.poses(q)["platform"][:3, :3], np.eye(3), atol=1e-10)  # T3
        d = _tsai_det_n(m, q)
        if c == "flat":
            assert abs(d) < 1e-12
        else:
            assert abs(d) > 1e-2, (c, d)
    assert np.isclose(m.poses(m.solve("raised"))["platform"][2, 3], 1.0)


def test_stewart_octahedral_rotation_singularity():
    m = mech("stewart_octahedral.yaml")
    for c in m.data["configurations"]:
        q = m.solve(c)
        g = m.poses(q)
        lines = []
        for k in range(1, 7):
            a = g[f"cyl{k}"] @ np.r_[vec(m.joints[m.jidx[f"U{k}"]]["raw"]["point"]), 1]
            b = g[f"pis{k}"] @ np.r_[vec(m.joints[m.jidx[f"S{k}"]]["raw"]["point"]), 1]
            lines.append(rscrew(b[:3] - a[:3], a[:3]))
        s = np.linalg.svd(np.array(lines), compute_uv=False)
        if c == "reference":
            assert s[5] / s[0] > 1e-2
        else:
            R = g["platform"][:3, :3]
            phi = math.pi / 2 if c.endswith("+90") else -math.pi / 2
            assert np.allclose(
                R,
                [[math.cos(phi), -math.sin(phi), 0], [math.sin(phi), math.cos(phi), 0], [0, 0, 1]],
                atol=1e-12,
            )
            assert s[5] / s[0] < 1e-12  # leg lines dependent


def _detJ_formula_ur5(t):
    a2, a3, d5 = -0.425, -0.39225, 0.09465
    return (
        -a2
        * a3
        * math.sin(t[2])
        * math.sin(t[4])
        * (a2 * math.cos(t[1]) + a3 * math.cos(t[1] + t[2]) + d5 * math.sin(t[1] + t[2] + t[3]))
    )


def _detJ_formula_puma(t):
    a2, a3, d4 = 0.4318, 0.0203, 0.4318
    return (
        a2
        * (a3 * math.sin(t[2]) + d4 * math.cos(t[2]))
        * (a2 * math.cos(t[1]) + a3 * math.cos(t[1] + t[2]) - d4 * math.sin(t[1] + t[2]))
        * math.sin(t[4])
    )


@pytest.mark.parametrize(
    "name,formula", [("ur5.yaml", _detJ_formula_ur5), ("puma560.yaml", _detJ_formula_puma)]
)
def test_serial_arm_det_J(name, formula):
    m = mech(name)
    # the published closed form agrees with det of our spatial Jacobian (up to sign) at random poses
    rng = np.random.default_rng(0)
    for _ in range(5):
        t = rng.uniform(-math.pi, math.pi, 6)
        dj = np.linalg.det(m.current_screws(t))
        assert math.isclose(abs(dj), abs(formula(t)), rel_tol=1e-9, abs_tol=1e-14)
    for c in m.data["configurations"]:
        t = m.solve(c)
        dj, f = np.linalg.det(m.current_screws(t)), formula(t)
        if c == "regular":
            assert abs(f) > 1e-3 and abs(dj) > 1e-3
        else:  # reference and the singular poses
            assert abs(f) < 1e-12 and abs(dj) < 1e-12, (c, f, dj)
    # which factor vanishes where: the shoulder pose is not also a wrist pose
    t = m.solve("shoulder")
    assert abs(math.sin(t[4])) > 0.1
    assert abs(math.sin(m.solve("wrist")[4])) < 1e-15
