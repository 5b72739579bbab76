"""Helpers for the analysis tests (tests/test_analyze.py).

* :data:`PUBLISHED`: the published facts of every example, copied from the comment block at the top
  of each examples/*.yaml file (mobility, spatial Gruebler-Kutzbach,
  configurations that are regular points of the configuration space, published closure ranks).
* :func:`run_cli`: ``mechsing.cli.main`` in-process with standard output captured.
* :func:`scaled_text`: a mechanism file with every length multiplied by a factor, written from the
  file's own text (numbers keep the text they were written with; lengths become exact expressions);
  :func:`scaled_file` writes it once per example and scale (:data:`SCALES`).
* :func:`changepoint_family`: a Grashof change-point four-bar and configurations approaching its flat
  (singular) configuration along both motion branches, joint values derived here in closed form with
  mpmath, plus the closure-system singular values computed independently of mechsing in the
  commensurate metric (characteristic length, centroid, planar reduced coordinates).
* :data:`CENTRED_SLIDER_CRANK_MM`: a centred slider-crank in millimetres whose pivots are not
  on a coordinate line in the drawn pose (the condition and serial-finding tests).
* :data:`NON_GRASHOF_ROCKER`, :data:`PLANAR_3R_POINT`: mechanisms several test modules use
  (one text each, a test adding its own configurations).
* :data:`FOURBAR_JOINTS`, :data:`PARALLELOGRAM_JOINTS`, :data:`ARM_2R_JOINTS`,
  :data:`TWO_LEAVES`: bodies and joints several test modules use, each module adding its
  name, inputs, masses and configurations.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import mpmath
import numpy as np
import yaml

from tests.cli import run_cli

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

#: crank 10 mm drawn straight down from A = (0, 0), rod 20 mm to the pin C = (10*sqrt(3), 0)
#: mm on the slide along x (no configurations: a test adds its own)
#: an orthogonal 3R arm (Baili, Wenger & Chablat, ICRA 2004: modified DH d2 = 1, r2 =
#: 3/2, d3 = 2, alpha2 = -90 deg, alpha3 = 90 deg, the point at d4 = 3/2 on x3): cuspidal
ORTHOGONAL_3R = """\
mechanism: orthogonal-3r
bodies: [base, link1, link2, link3]
joints:
  - {name: J1, type: R, between: [base, link1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [link1, link2], axis: [0, 1, 0], point: [1, "3/2", 0]}
  - {name: J3, type: R, between: [link2, link3], axis: [0, 0, 1], point: [3, "3/2", 0]}
inputs: [J1, J2, J3]
output: {body: link3, point: ["9/2", "3/2", 0]}
"""

CENTRED_SLIDER_CRANK_MM = """\
mechanism: centred-slider-crank
units: {length: mm, angle: deg}
bodies: [ground, crank, rod, slider]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [0, -10, 0]}
  - {name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: ["10*sqrt(3)", 0, 0]}
  - {name: S, type: P, between: [ground, slider], axis: [1, 0, 0]}
inputs: [A]
output: {body: slider}
"""

# ----------------------------------------------------------------------------- published facts


@dataclass(frozen=True)
class Published:
    """Facts stated in an example's header comment."""

    mobility: int
    grubler: int
    #: configurations the header calls regular points of the configuration space (generic rank)
    regular: tuple[str, ...]
    #: loop joint sets -> (subgroup type, dim); None when the header says nothing about the loops
    loops: dict[frozenset[str], tuple[str, int]] | None = None
    #: configuration -> published closure rank (stacked system)
    ranks: dict[str, int] = field(default_factory=dict)
    #: configuration -> published rank of the single loop's screws (relative to its subgroup)
    loop_ranks: dict[str, int] = field(default_factory=dict)
    overconstrained: bool = False
    serial: bool = False


def _loop(joints: str, typ: str, dim: int) -> dict[frozenset[str], tuple[str, int]]:
    return {frozenset(joints.split()): (typ, dim)}


PUBLISHED: dict[str, Published] = {
    # crank-rocker, Grashof; all three configurations regular; planar loop in G(z)
    "fourbar.yaml": Published(
        1, -2, ("reference", "crank-30", "crank-200"), _loop("A B C D", "G", 3)
    ),
    # change point: flat reference is rank 2 (bifurcation), the others regular
    "fourbar_changepoint.yaml": Published(
        1,
        -2,
        ("crank-up", "crank-120"),
        _loop("A B C D", "G", 3),
        ranks={"reference": 2},
    ),
    # non-Grashof double rocker: the c-space is smooth, also at the input's and the output's limits
    "double_rocker.yaml": Published(
        1,
        -2,
        ("reference", "input-60", "limit", "output-limit"),
        _loop("A B C D", "G", 3),
        ranks={"limit": 3, "output-limit": 3},
    ),
    # 5R five-bar: mobility 2, spatial Gruebler -1; Type I and Type II poses are c-space regular
    "five_bar.yaml": Published(
        2,
        -1,
        ("reference", "inputs", "type1", "type2"),
        _loop("A1 B1 P B2 A2", "G", 3),
        ranks={"type1": 3, "type2": 3},
    ),
    # parallelogram: flat configuration rank 2, elsewhere regular
    "parallelogram.yaml": Published(
        1,
        -2,
        ("reference", "crank-30", "anti-parallelogram"),
        _loop("A B C D", "G", 3),
        ranks={"flat": 2},
    ),
    # dead centres are regular points of the c-space (closure rank 3)
    "slider_crank_crank_input.yaml": Published(
        1,
        -2,
        ("reference", "crank-60", "dead-centre"),
        _loop("A B C P", "G", 3),
        ranks={"dead-centre": 3},
    ),
    "slider_crank_slider_input.yaml": Published(
        1,
        -2,
        ("reference", "slider-4", "dead-centre"),
        _loop("A B C P", "G", 3),
        ranks={"dead-centre": 3},
    ),
    # spherical crank-rocker: loop in S(O), rank 3 at regular configurations
    "spherical_4r.yaml": Published(
        1,
        -2,
        ("reference", "crank-60", "crank-200"),
        _loop("A B C D", "S", 3),
        loop_ranks={"reference": 3, "crank-60": 3, "crank-200": 3},
    ),
    # Bennett: joints generate all of D, rank 3 at EVERY configuration, Gruebler -2
    "bennett.yaml": Published(
        1,
        -2,
        ("reference", "theta1-90", "q1-half", "q1-1rad"),
        _loop("J1 J2 J3 J4", "D", 6),
        loop_ranks={"reference": 3, "theta1-90": 3, "q1-half": 3, "q1-1rad": 3},
        overconstrained=True,
    ),
    # Bricard: joints generate all of D, generic rank 5, Gruebler 0
    "bricard.yaml": Published(
        1,
        0,
        ("reference", "q1-0.4"),
        _loop("J1 J2 J3 J4 J5 J6", "D", 6),
        loop_ranks={"reference": 5, "q1-0.4": 5},
        overconstrained=True,
    ),
    # Sarrus: rank 5 at regular poses, 4 at the stretched pose; closure of the screws is se(3)
    # (so the group formula gives 6 - 6 = 0, one less than the truth), Gruebler 0
    "sarrus.yaml": Published(
        1,
        0,
        ("reference", "raised", "lowered"),
        _loop("J1 J2 J3 J4 J5 J6", "D", 6),
        ranks={"stretched": 4},
        loop_ranks={"reference": 5, "raised": 5, "lowered": 5, "stretched": 4},
        overconstrained=True,
    ),
    # 3-RPR: mobility 3, Gruebler -3; its two loops (two of the three leg pairs: which two is a
    # tie of the minimum cycle basis) are checked in test_planar_3rpr_loops
    "planar_3rpr.yaml": Published(3, -3, ("reference", "stroke")),
    # the 3-RPR of six real assembly modes: mobility 3, spatial Gruebler 6(8-1-9)+9 = -3;
    # its configuration space is smooth wherever no leg has zero length
    "planar_3rpr_six.yaml": Published(3, -3, ("reference", "six")),
    # Tsai 3-UPU: mobility 3, Gruebler 3; the flat pose is constraint-singular
    "tsai_3upu.yaml": Published(3, 3, ("reference", "raised", "lateral")),
    # octahedral hexapod: mobility 6, Gruebler 6; centred pose regular
    "stewart_octahedral.yaml": Published(6, 6, ("reference",)),
    # general 6-6 platform (Dietmaier's geometry): mobility 6
    "stewart_dietmaier.yaml": Published(6, 6, ("reference", "longer")),
    # quick return (crank and slotted lever): a planar single loop, regular where drawn
    "quick_return.yaml": Published(1, -2, ("reference", "crank-60"), _loop("A B S C", "G", 3)),
    # Watt II and Stephenson III six-bars: mobility 1, spatial Grubler 6(6-1-7)+7 = -5
    "watt_ii.yaml": Published(1, -5, ("reference", "crank-20")),
    "stephenson_iii.yaml": Published(1, -5, ("reference", "crank-20")),
    # serial arms: mobility 6, no loops (every configuration is a regular point of the c-space,
    # which is the whole joint space)
    "ur5.yaml": Published(
        6, 6, ("reference", "regular", "wrist", "elbow", "shoulder"), {}, serial=True
    ),
    "puma560.yaml": Published(
        6, 6, ("reference", "regular", "wrist", "elbow", "shoulder"), {}, serial=True
    ),
    # a general 6R (every two consecutive axes skew): mobility 6, no loops
    "general_6r.yaml": Published(6, 6, ("reference", "generic"), {}, serial=True),
    # a general 7R loop: mobility 1, its screws span D at the reference
    "general_7r.yaml": Published(1, 1, ("reference",), _loop("J1 J2 J3 J4 J5 J6 J7", "D", 6)),
}

#: degrees of freedom of each joint type (a U joint has two)
DOF = {"R": 1, "P": 1, "H": 1, "C": 2, "U": 2, "T2": 2, "S": 3, "T3": 3, "G": 3, "Y": 3}
DOF |= {"X": 4, "D": 6}


def total_dof(path: Path) -> int:
    data = yaml.safe_load(path.read_text())
    return sum(DOF[j["type"]] for j in data["joints"])


def all_axis_points_at_origin(path: Path) -> bool:
    """Every joint's point is the origin (then L falls back to 1, at every scale)."""
    joints = yaml.safe_load(path.read_text())["joints"]
    return all(x == 0 for j in joints for x in j.get("point", [0, 0, 0]))


def joint_types(path: Path) -> dict[str, str]:
    """Joint name -> type, as written in the file."""
    return {j["name"]: j["type"] for j in yaml.safe_load(path.read_text())["joints"]}


def configuration_names(path: Path) -> list[str]:
    return list(yaml.safe_load(path.read_text())["configurations"])


# ----------------------------------------------------------------------------- running the CLI


_ANALYSES: dict[tuple[str, ...], tuple[str, dict]] = {}


def analyze_text(path: Path | str, *options: str) -> tuple[str, dict]:
    """``mechsing analyze PATH --format json OPTIONS``: its text and parsed JSON, which must
    come with exit status 0 and no traceback (cached for the session: do not mutate)."""
    key = (str(path), *options)
    if key not in _ANALYSES:
        rc, out, err = run_cli(["analyze", str(path), "--format", "json", *options])
        assert rc == 0, f"exit status {rc} for {key}: {err}"
        assert "Traceback" not in err
        _ANALYSES[key] = (out, json.loads(out))
    return _ANALYSES[key]


def analyze_json(path: Path | str, *options: str) -> dict:
    """The parsed JSON of ``mechsing analyze PATH --format json OPTIONS`` (cached)."""
    return analyze_text(path, *options)[1]


# ----------------------------------------------------------------------------- scaling a file

#: coordinates of a joint value that are lengths, in the catalog basis order (docs/closure.md,
#: "Joint values")
LENGTH_COORDS: dict[str, tuple[bool, ...]] = {
    "R": (False,),
    "P": (True,),
    "H": (False,),
    "C": (False, True),
    "U": (False, False),
    "T2": (True, True),
    "S": (False, False, False),
    "T3": (True, True, True),
    "G": (False, True, True),
    "Y": (False, True, True),
    "X": (False, True, True, True),
    "D": (False, False, False, True, True, True),
}


class _Num(str):
    """A plain YAML number kept as its text."""


class _KeepNumbers(yaml.SafeLoader):
    pass


def _keep(loader: yaml.SafeLoader, node: yaml.ScalarNode) -> _Num:
    return _Num(loader.construct_scalar(node))


_KeepNumbers.add_constructor("tag:yaml.org,2002:int", _keep)
_KeepNumbers.add_constructor("tag:yaml.org,2002:float", _keep)


class _Dumper(yaml.SafeDumper):
    pass


def _num_repr(dumper: yaml.SafeDumper, value: _Num) -> yaml.ScalarNode:
    tag = dumper.resolve(yaml.ScalarNode, str(value), (True, False))  # int or float, as read
    return dumper.represent_scalar(tag, str(value), style="")


_Dumper.add_representer(_Num, _num_repr)


def _scale(x: object, factor: str) -> object:
    """A file number/expression times ``factor`` (an exact expression such as ``*1000000``)."""
    if isinstance(x, list):
        return [_scale(v, factor) for v in x]
    assert isinstance(x, str), x
    return f"({x}){factor}"


def scaled_text(path: Path, factor: str) -> str:
    """The mechanism file at ``path`` with every length (points, pitches, characteristic length,
    output point, length coordinates of joint values and translations) followed by ``factor``
    (e.g. ``"*1000000"`` or ``"/1000000"``); angles, axes and normals unchanged."""
    data = yaml.load(path.read_text(), Loader=_KeepNumbers)  # noqa: S506 (SafeLoader subclass)
    types = {}
    for j in data["joints"]:
        types[j["name"]] = j["type"]
        for key in ("point", "pitch"):
            if key in j:
                j[key] = _scale(j[key], factor)
    if "characteristic_length" in data:
        data["characteristic_length"] = _scale(data["characteristic_length"], factor)
    out = data.get("output")
    if isinstance(out, dict) and "point" in out:
        out["point"] = _scale(out["point"], factor)
    for cfg in (data.get("configurations") or {}).values():
        for name, value in list(cfg.items()):
            if name == "start":
                continue
            if isinstance(value, dict):  # {rotation, translation}
                if "translation" in value:
                    value["translation"] = _scale(value["translation"], factor)
                continue
            lengths = LENGTH_COORDS[types[name]]
            if isinstance(value, list):
                cfg[name] = [
                    _scale(v, factor) if is_len else v
                    for v, is_len in zip(value, lengths, strict=True)
                ]
            elif lengths[0]:
                cfg[name] = _scale(value, factor)
    return yaml.dump(data, Dumper=_Dumper, sort_keys=False, width=10_000)


#: the scales of the scale-invariance tests: name -> (k, the factor written after each length)
SCALES = {"1e-6": (1e-6, "/1000000"), "1e6": (1e6, "*1000000")}


def scaled_file(directory: Path, name: str, scale: str) -> Path:
    """The example ``name`` with every length times ``SCALES[scale]`` in ``directory`` (the
    session's ``scaled_dir``), written on first use."""
    path = directory / f"{Path(name).stem}_{scale}.yaml"
    if not path.exists():
        path.write_text(scaled_text(EXAMPLES / name, SCALES[scale][1]))
    return path


# ----------------------------------------------------------------------------- transversal family

#: change-point four-bar: crank a, coupler b, rocker c, ground g with a + b = g + c (Grashof s + l =
#: p + q); flat configuration: A = (0, 0), B = (a, 0), C = (a + b, 0), D = (g, 0), where the circles
#: of radius b about B and c about D are internally tangent (|BD| = g - a = b - c).
CP_A, CP_B, CP_C, CP_G = 2, 7, 3, 6
assert CP_A + CP_B == CP_G + CP_C


def _changepoint_pose(d: mpmath.mpf, branch: int) -> tuple[list, list]:
    """Joint points B, C and joint values (A, B, C, D) at crank angle d on a branch (+1: C above
    the line BD, -1: below), with mpmath at the working precision.

    Joint values follow the README's conventions (g_b = g_a exp(q xi), reference = the flat
    configuration): the crank turns by d, the coupler's absolute angle is phi2 = angle of C - B,
    the rocker's is phi3 = angle of C - D (both 0 at the flat reference), so
    q = (d, phi2 - d, phi3 - phi2, -phi3).
    """
    a, b, c, g = (mpmath.mpf(v) for v in (CP_A, CP_B, CP_C, CP_G))
    B = mpmath.matrix([a * mpmath.cos(d), a * mpmath.sin(d)])
    D = mpmath.matrix([g, 0])
    r = mpmath.norm(D - B)
    e = (D - B) / r
    x = (b**2 - c**2 + r**2) / (2 * r)  # foot of C on the line BD, measured from B
    h = mpmath.sqrt(b**2 - x**2)  # distance of C from that line
    C = B + x * e + branch * h * mpmath.matrix([-e[1], e[0]])
    phi2 = mpmath.atan2(C[1] - B[1], C[0] - B[0])
    phi3 = mpmath.atan2(C[1], C[0] - g)
    return [B, C], [d, phi2 - d, phi3 - phi2, -phi3]


def _reduced_planar_sigma(points: np.ndarray) -> np.ndarray:
    """Singular values of the four-bar's closure system, independently of mechsing.

    The commensurate metric: L = RMS distance of the axis points from their centroid c at the
    reference (flat) configuration; screws moved to c, v rows divided by L. For an R joint with
    axis z through p, the twist seen from c is (z, z x (c - p)), whose in-plane velocity is
    ((p - c)_y, -(p - c)_x); G's subalgebra is spanned by the coordinate directions omega_z, v_x,
    v_y, so any orthonormal reduced basis gives the singular values of the 3 x 4 matrix with
    columns (1, (p - c)_y / L, -(p - c)_x / L).
    """
    ref = np.array([[0.0, 0.0], [CP_A, 0.0], [CP_A + CP_B, 0.0], [CP_G, 0.0]])
    cen = ref.mean(axis=0)
    L = float(np.sqrt(((ref - cen) ** 2).sum(axis=1).mean()))
    rel = points - cen
    M = np.vstack([np.ones(len(points)), rel[:, 1] / L, -rel[:, 0] / L])
    return np.linalg.svd(M, compute_uv=False)


def changepoint_length_scale() -> float:
    ref = np.array([[0.0, 0.0], [CP_A, 0.0], [CP_A + CP_B, 0.0], [CP_G, 0.0]])
    cen = ref.mean(axis=0)
    return float(np.sqrt(((ref - cen) ** 2).sum(axis=1).mean()))


@dataclass(frozen=True)
class FamilyPoint:
    name: str
    d: float
    branch: int
    sigma: np.ndarray  # independent singular values (largest first)


def _digits(x: mpmath.mpf) -> str:
    return mpmath.nstr(x, 45, min_fixed=-5, max_fixed=5)


def changepoint_family(exponents: list[float]) -> tuple[str, list[FamilyPoint]]:
    """(YAML text, family points): the flat configuration as ``reference`` plus, for each crank
    angle d = 10**-e (e in ``exponents``) and each branch, a fully given configuration (45
    significant digits)."""
    lines = [
        "# Grashof change-point four-bar (a + b = g + c), generated by tests/mechanisms.py",
        "mechanism: changepoint-family",
        "bodies: [ground, crank, coupler, rocker]",
        "joints:",
        "  - {name: A, type: R, between: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}",
        f"  - {{name: B, type: R, between: [crank, coupler],  axis: [0, 0, 1], point: [{CP_A}, 0, 0]}}",
        f"  - {{name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [{CP_A + CP_B}, 0, 0]}}",
        f"  - {{name: D, type: R, between: [rocker, ground],  axis: [0, 0, 1], point: [{CP_G}, 0, 0]}}",
        "inputs: [A]",
        "output: {body: rocker}",
        "configurations:",
        "  reference: {}  # the flat configuration (d = 0): the change point",
    ]
    points = []
    with mpmath.workdps(60):
        for i, e in enumerate(exponents):
            d = mpmath.power(10, -mpmath.mpf(e))
            for branch, tag in ((1, "up"), (-1, "down")):
                (B, C), q = _changepoint_pose(d, branch)
                name = f"{tag}-{i:02d}"
                vals = ", ".join(f'{j}: "{_digits(v)}"' for j, v in zip("ABCD", q, strict=True))
                lines.append(f"  {name}: {{{vals}}}")
                pts = np.array(
                    [
                        [0.0, 0.0],
                        [float(B[0]), float(B[1])],
                        [float(C[0]), float(C[1])],
                        [CP_G, 0.0],
                    ]
                )
                points.append(FamilyPoint(name, float(d), branch, _reduced_planar_sigma(pts)))
    return "\n".join(lines) + "\n", points


# ----------------------------------------------------------------------------- JSON and files


def write(tmp_path: Path, name: str, text: str) -> Path:
    """``text`` as ``tmp_path/name.yaml``."""
    p = tmp_path / f"{name}.yaml"
    p.write_text(text)
    return p


def by_name(result: dict) -> dict[str, dict]:
    """The configurations of an analysis JSON, by name."""
    return {c["name"]: c for c in result["configurations"]}


def classes(config: dict) -> list[str]:
    """The classes of a configuration's findings, in order."""
    return [f["class"] for f in config["singularities"]]


def finding(config: dict, cls: str) -> dict:
    """The one finding of class ``cls`` (asserts there is exactly one)."""
    found = [f for f in config["singularities"] if f["class"] == cls]
    assert len(found) == 1, (config["name"], classes(config))
    return found[0]


# ----------------------------------------------------------------------------- directions


def normalised(v: object) -> np.ndarray:
    """Largest entry 1 in magnitude, first entry above 1e-9 of it positive (the JSON's
    normalisation of directions)."""
    v = np.asarray(v, dtype=float)
    v = v / np.max(np.abs(v))
    first = v[np.flatnonzero(np.abs(v) > 1e-9)[0]]
    return v if first > 0 else -v


def assert_same_lines(got: list, expected: list, tol: float = 1e-8, contract: bool = False) -> None:
    """Two sets of directions (each up to scale) are equal; with ``contract``, each of ``got``
    must also come normalised as the JSON contract says."""
    assert len(got) == len(expected), (got, expected)
    if contract:
        for x in got:
            assert abs(np.max(np.abs(x)) - 1) < 1e-12
            assert np.asarray(x)[np.flatnonzero(np.abs(x) > 1e-9)[0]] > 0
    e = [normalised(x) for x in expected]
    unmatched = list(range(len(e)))
    for x in got:
        g = normalised(x)
        hit = [i for i in unmatched if np.max(np.abs(g - e[i])) < tol]
        assert hit, (got, expected)
        unmatched.remove(hit[0])


# ------------------------------------------------------------------- a cuspidal 3-RPR

#: A cuspidal 3-RPR (Innocenti & Parenti-Castelli, ASME J. Mech. Des. 1998; the design of
#: Zein, Wenger & Chablat, Mech. Mach. Theory 43, 2008): base A1 = (0, 0), A2 = (15.91, 0),
#: A3 = (0, 10); platform sides d1 = |B1B2| = 17.04, d2 = |B2B3| = 16.54, d3 = |B3B1| =
#: 20.84 (B3's height rounded to 16.0967085: the sides hold to 1e-7), drawn with B1 = (4, 6)
#: and the platform angle 0.  Input P_i is the leg's length less its length in the drawing
#: (:data:`CUSPIDAL_3RPR_REST`); configuration ``section`` fixes rho1 = 14.98.  Its section
#: rho2, rho3 in [0, 32] holds six cusps (tests/test_cusps.py, against
#: tests/reference/cusps_reference.py), among them one at rho2 = 13.8514600894, rho3 =
#: 6.2601004357 where three modes meet at the platform angle -0.0453759 rad.
CUSPIDAL_3RPR = """\
mechanism: planar-3rpr-cuspidal
bodies: [ground, cyl1, pis1, cyl2, pis2, cyl3, pis3, platform]
joints:
  - {name: Rb1, type: R, between: [ground, cyl1],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: P1, type: P, between: [cyl1, pis1],     axis: [4, 6, 0]}
  - {name: Rp1, type: R, between: [pis1, platform], axis: [0, 0, 1], point: [4, 6, 0]}
  - {name: Rb2, type: R, between: [ground, cyl2],   axis: [0, 0, 1], point: ["1591/100", 0, 0]}
  - {name: P2, type: P, between: [cyl2, pis2],     axis: ["513/100", 6, 0]}
  - {name: Rp2, type: R, between: [pis2, platform], axis: [0, 0, 1], point: ["526/25", 6, 0]}
  - {name: Rb3, type: R, between: [ground, cyl3],   axis: [0, 0, 1], point: [0, 10, 0]}
  - {name: P3, type: P, between: [cyl3, pis3],     axis: ["489513/28400", "120967085/10000000", 0]}
  - {name: Rp3, type: R, between: [pis3, platform], axis: [0, 0, 1], point: ["489513/28400", "220967085/10000000", 0]}
inputs: [P1, P2, P3]
output: {body: platform}
configurations:
  section: {P1: "749/50 - 2*sqrt(13)"}
"""
#: the legs' lengths in the drawing of :data:`CUSPIDAL_3RPR` (rho_i = P_i + these)
CUSPIDAL_3RPR_REST = ("2*sqrt(13)", "3*sqrt(69241)/100", "sqrt(8941179738376016449)/142000000")
#: base and platform points (the platform's in its own frame, B1 at its origin)
CUSPIDAL_3RPR_BASE = ((0, 0), ("1591/100", 0), (0, 10))
CUSPIDAL_3RPR_PLATFORM = ((0, 0), ("426/25", 0), ("375913/28400", "160967085/10000000"))

#: a non-Grashof four-bar in degrees (2 + 4 > 3 + sqrt 5): the crank AB (2, drawn along y)
#: stops where B, C and D line up; input A (no configurations: a test adds its own)
NON_GRASHOF_ROCKER = """\
mechanism: rocker
units: {angle: deg}
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [0, 2, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, 2, 0]}
  - {name: D, type: R, between: [rocker, ground], axis: [0, 0, 1], point: [4, 0, 0]}
inputs: [A]
"""

#: a planar 3R arm whose output is the point at the end of its last link (unit links)
PLANAR_3R_POINT = """\
mechanism: planar-3r-point
bodies: [base, l1, l2, l3]
joints:
  - {name: R1, type: R, between: [base, l1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: R2, type: R, between: [l1, l2], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: R3, type: R, between: [l2, l3], axis: [0, 0, 1], point: [2, 0, 0]}
output: {body: l3, point: [3, 0, 0]}
"""

#: a planar 2R arm (links 1 and 0.5, the output at the tip) under a tip load at ``bent``;
#: ``straight`` is its stretched singularity
PLANAR_2R_LOADED = """\
mechanism: planar-2r
bodies: [ground, l1, l2]
joints:
  - {name: A, type: R, between: [ground, l1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [l1, l2], axis: [0, 0, 1], point: [1, 0, 0]}
inputs: [A, B]
output: {body: l2, point: [1.5, 0, 0]}
configurations:
  bent: {A: 0.3, B: 0.9, load: {force: [1, -2, 0]}}
  straight: {A: 0.3, B: 0}
"""

#: the README's four-bar (examples/fourbar.yaml, in metres): its bodies and joints only, a
#: test adding its name, inputs, output, masses and configurations
FOURBAR_JOINTS = """\
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler],  axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, 2, 0]}
  - {name: D, type: R, between: [rocker, ground],  axis: [0, 0, 1], point: [4, 0, 0]}
"""

#: examples/parallelogram.yaml's bodies and joints (A (0, 0), B (0, 1), C (2, 1), D (2, 0))
PARALLELOGRAM_JOINTS = """\
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler],  axis: [0, 0, 1], point: [0, 1, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [2, 1, 0]}
  - {name: D, type: R, between: [rocker, ground],  axis: [0, 0, 1], point: [2, 0, 0]}
"""

#: a planar 2R arm about z (shoulder A at the origin, elbow B at (1, 0, 0)): bodies and
#: joints only (the dynamics tests add the masses)
ARM_2R_JOINTS = """\
bodies: [ground, upper, fore]
joints:
  - {name: A, type: R, between: [ground, upper], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [upper, fore], axis: [0, 0, 1], point: [1, 0, 0]}
"""

#: a tree of two links hinged on the ground (no loop, two leaves: no output by default)
TWO_LEAVES = """\
bodies: [ground, a, b]
joints:
  - {name: A, type: R, between: [ground, a], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [ground, b], axis: [0, 0, 1], point: [1, 0, 0]}
"""
