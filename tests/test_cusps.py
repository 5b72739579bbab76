"""``mechsing cusps``: singular curves and cusps of a section, cuspidal or not.

Checked against tests/reference/cusps_reference.py, which imports nothing from mechsing:
the cusps of the mechanism's forward map (Whitney's cusp: det dF = 0 and its derivative
along the kernel = 0), solved from its own formulas, no eliminant; and, for the arm, the
inverse-kinematics quartic built by a resultant and its triple root.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import sympy

from tests.cli import run_cli
from tests.mechanisms import (
    CUSPIDAL_3RPR,
    CUSPIDAL_3RPR_BASE,
    CUSPIDAL_3RPR_PLATFORM,
    CUSPIDAL_3RPR_REST,
    ORTHOGONAL_3R,
)
from tests.reference.cusps_reference import (
    arm_cusps,
    ik_quartic,
    rpr_cusps,
    triple_root_residual,
)

#: a 3-RPR whose platform is the base triangle halved (similar triangles, same
#: orientation): a design known not to be cuspidal
SIMILAR_3RPR = """\
mechanism: planar-3rpr-similar
bodies: [ground, cyl1, pis1, cyl2, pis2, cyl3, pis3, platform]
joints:
  - {name: Rb1, type: R, between: [ground, cyl1],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: P1, type: P, between: [cyl1, pis1],     axis: [1, 1, 0]}
  - {name: Rp1, type: R, between: [pis1, platform], axis: [0, 0, 1], point: [1, 1, 0]}
  - {name: Rb2, type: R, between: [ground, cyl2],   axis: [0, 0, 1], point: [4, 0, 0]}
  - {name: P2, type: P, between: [cyl2, pis2],     axis: [-1, 1, 0]}
  - {name: Rp2, type: R, between: [pis2, platform], axis: [0, 0, 1], point: [3, 1, 0]}
  - {name: Rb3, type: R, between: [ground, cyl3],   axis: [0, 0, 1], point: [0, 4, 0]}
  - {name: P3, type: P, between: [cyl3, pis3],     axis: [1, -1, 0]}
  - {name: Rp3, type: R, between: [pis3, platform], axis: [0, 0, 1], point: [1, 3, 0]}
inputs: [P1, P2, P3]
output: {body: platform}
configurations:
  section: {P1: 1}
"""

#: an orthogonal 3R arm (Baili, Wenger & Chablat, ICRA 2004: modified DH d2 = 1, r2 =
#: 3/2, d3 = 2, alpha2 = -90 deg, alpha3 = 90 deg, the point at d4 = 3/2 on x3): cuspidal
ORTHOGONAL_DH = [(0, 0, 0), (1, -sympy.pi / 2, sympy.Rational(3, 2)), (2, sympy.pi / 2, 0)]
ORTHOGONAL_TOOL = (sympy.Rational(3, 2), 0, 0)
#: a PUMA-like 3R arm: the first two axes meet, the last two parallel
PUMA_DH = [(0, 0, 0), (0, -sympy.pi / 2, 0), (2, 0, 0)]
PUMA_3R = """\
mechanism: puma-like-3r
bodies: [base, link1, link2, link3]
joints:
  - {name: J1, type: R, between: [base, link1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [link1, link2], axis: [0, 1, 0], point: [0, 0, 0]}
  - {name: J3, type: R, between: [link2, link3], axis: [0, 1, 0], point: [2, 0, 0]}
inputs: [J1, J2, J3]
output: {body: link3, point: ["7/2", 0, 0]}
"""


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _cusps(path: Path, vary: str, *more: str) -> dict:
    run = run_cli(["cusps", str(path), "--vary", vary, "--format", "json", *more])
    assert run.status == 0, run.err
    return json.loads(run.out)


def _follows_the_schema(doc: dict) -> None:
    """The document validates against ``mechsing schema --cusps``."""
    jsonschema = pytest.importorskip("jsonschema")
    run = run_cli(["schema", "--cusps"])
    assert run.status == 0, run.err
    jsonschema.Draft202012Validator(json.loads(run.out)).validate(doc)


def test_cuspidal_3rpr_cusps_match_the_forward_map(tmp_path: Path) -> None:
    rest = [float(sympy.sympify(r)) for r in CUSPIDAL_3RPR_REST]
    path = _write(tmp_path, "zwc.yaml", CUSPIDAL_3RPR)
    vary = f"P2={-rest[1]!r}:{32 - rest[1]!r},P3={-rest[2]!r}:{32 - rest[2]!r}"
    doc = _cusps(path, vary)
    assert doc["cuspidal"] is True and doc["evidence"]["kind"] == "cusps"
    assert doc["section"]["fixed"]["P1"] == pytest.approx(14.98 - rest[0], abs=1e-12)
    got = sorted(
        ((c["inputs"]["P2"] + rest[1], c["inputs"]["P3"] + rest[2]) for c in doc["cusps"]),
        key=lambda p: (round(p[0], 6), round(p[1], 6)),
    )
    base = [[float(sympy.sympify(x)) for x in p] for p in CUSPIDAL_3RPR_BASE]
    plat = [[float(sympy.sympify(x)) for x in p] for p in CUSPIDAL_3RPR_PLATFORM]
    want = sorted(
        rpr_cusps(base, plat, 14.98, ((0, 32), (0, 32))),
        key=lambda p: (round(p[0], 6), round(p[1], 6)),
    )
    assert len(want) >= 2  # a cuspidal design
    assert len(got) == len(want)
    for (g2, g3), (w2, w3, _theta) in zip(got, want, strict=True):
        assert g2 == pytest.approx(w2, abs=1e-9) and g3 == pytest.approx(w3, abs=1e-9)
    for c in doc["cusps"]:
        assert c["certified"] and c["multiplicity"] == 3 and c["radius"] <= 1e-20
    # the modes meet where the reference says: the platform angle at each cusp
    thetas = sorted(round(c["modes"]["platform"]["theta"], 6) for c in doc["cusps"])
    assert thetas == sorted(round(w[2], 6) for w in want)
    _follows_the_schema(doc)


def test_similar_3rpr_is_not_cuspidal(tmp_path: Path) -> None:
    path = _write(tmp_path, "similar.yaml", SIMILAR_3RPR)
    doc = _cusps(path, "P2=-1:5,P3=-1:5", "--points", "41")
    assert doc["cuspidal"] is False and doc["cusps"] == []
    assert doc["evidence"]["kind"] == "no-triple-root"
    assert doc["evidence"]["singular_points"] > 0  # it has singular curves, no cusp
    # what the search covers, said precisely: the curves crossing the grid's lines (its
    # steps, (5 - (-1)) / 40), not a proof for the whole box
    assert doc["evidence"]["covers"] == "grid"
    reason = doc["evidence"]["reason"]
    assert "41 x 41 grid, steps P2 0.15 and P3 0.15" in reason
    assert "not a proof for the whole box" in reason
    _follows_the_schema(doc)
    rest = np.sqrt(2)  # every leg's length in the drawing
    want = rpr_cusps(
        [(0, 0), (4, 0), (0, 4)],
        [(0, 0), (2, 0), (0, 2)],
        1 + rest,
        ((rest - 1, rest + 5), (rest - 1, rest + 5)),
    )
    # the platform parallel to the base (theta = 0) is singular at every leg length, its
    # kernel along that curve of the map: every point of it solves the reference's
    # system (a curve, not three modes meeting); off it, no cusp
    assert [w for w in want if abs(np.sin(w[2])) > 1e-3] == []


def test_orthogonal_3r_arm_is_cuspidal(tmp_path: Path) -> None:
    path = _write(tmp_path, "orth.yaml", ORTHOGONAL_3R)
    doc = _cusps(path, "rho=0:6,z=-5:5")
    assert doc["cuspidal"] is True and doc["problem"] == "inverse kinematics"
    got = sorted(
        ((c["inputs"]["rho"], c["inputs"]["z"]) for c in doc["cusps"]),
        key=lambda p: (round(p[0], 6), round(p[1], 6)),
    )
    want = sorted(
        arm_cusps(ORTHOGONAL_DH, ORTHOGONAL_TOOL, ((0, 6), (-5, 5))),
        key=lambda p: (round(p[0], 6), round(p[1], 6)),
    )
    assert len(got) == len(want) == 4
    for (gr, gz), (wr, wz) in zip(got, want, strict=True):
        assert gr == pytest.approx(wr, abs=1e-9) and gz == pytest.approx(wz, abs=1e-9)
    quartic, t3, target = ik_quartic(ORTHOGONAL_DH, ORTHOGONAL_TOOL)
    assert sympy.Poly(quartic, t3).degree() == 4
    for c in doc["cusps"]:
        assert c["certified"]
        residual, _q3 = triple_root_residual(quartic, t3, target, *c["inputs"].values())
        assert residual < 1e-8


def test_puma_like_arm_is_not_cuspidal(tmp_path: Path) -> None:
    path = _write(tmp_path, "puma3.yaml", PUMA_3R)
    doc = _cusps(path, "rho=0:6,z=-5:5")
    assert doc["cuspidal"] is False and doc["cusps"] == []
    assert doc["evidence"]["kind"] == "decoupled"
    assert arm_cusps(PUMA_DH, ORTHOGONAL_TOOL, ((1e-3, 6), (-5, 5))) == []
    _follows_the_schema(doc)


def _orthogonal_3r_in_mm() -> str:
    mm = ORTHOGONAL_3R.replace("mechanism: orthogonal-3r", "units: {length: mm}\nmechanism: x")
    for a, b in (('[1, "3/2", 0]', "[1000, 1500, 0]"), ('[3, "3/2", 0]', "[3000, 1500, 0]")):
        mm = mm.replace(a, b)
    mm = mm.replace('["9/2", "3/2", 0]', "[4500, 1500, 0]")
    assert "3/2" not in mm
    return mm


def test_vary_is_read_in_the_files_units(tmp_path: Path) -> None:
    """The orthogonal 3R arm drawn in mm, its section given in mm (--vary in the file's
    units, as sweep's): the same four cusps as the arm in m, in SI in the document, at
    the inverse-kinematics quartic's triple roots (the reference, in m).  Before, --vary
    was read in m: rho = 0..6000 m, beyond the arm's reach but for its first 6 m."""
    path = _write(tmp_path, "orth_mm.yaml", _orthogonal_3r_in_mm())
    doc = _cusps(path, "rho=0:6000,z=-5000:5000")
    assert doc["section"]["vary"] == {"rho": [0.0, 6.0], "z": [-5.0, 5.0]}

    def key(p):
        return (round(p[0], 6), round(p[1], 6))

    got = sorted(((c["inputs"]["rho"], c["inputs"]["z"]) for c in doc["cusps"]), key=key)
    want = sorted(arm_cusps(ORTHOGONAL_DH, ORTHOGONAL_TOOL, ((0, 6), (-5, 5))), key=key)
    assert doc["cuspidal"] is True and len(got) == len(want) == 4
    for (gr, gz), (wr, wz) in zip(got, want, strict=True):
        assert gr == pytest.approx(wr, abs=1e-9) and gz == pytest.approx(wz, abs=1e-9)


def test_a_section_beyond_the_reach_says_so(tmp_path: Path) -> None:
    """The orthogonal 3R arm drawn in mm, a section from 100 m out (its links and tool
    sum to under 6.5 m): no point of the grid has a real posture, and the evidence says
    the section missed the arm and in which units --vary was read."""
    path = _write(tmp_path, "orth_mm.yaml", _orthogonal_3r_in_mm())
    doc = _cusps(path, "rho=100000:6000000,z=-5000:5000", "--points", "9")
    assert doc["formulation"]["modes_counts"] == [0] and doc["cuspidal"] is False
    assert "no real mode anywhere on the grid" in doc["evidence"]["reason"]
    assert "read in the file's units, mm and rad" in doc["evidence"]["reason"]


def test_cusps_output_format_follows_its_extension(tmp_path: Path) -> None:
    """-o NAME.json writes the JSON document (as sweep's -o does), -o NAME.md Markdown;
    --plot of a name that is neither .png nor .svg is refused before the work. The PUMA-like
    arm's first two axes meet: not cuspidal (its inverse kinematics decouples)."""
    path = _write(tmp_path, "puma3.yaml", PUMA_3R)
    for name, first in (("c.json", "{"), ("c.md", "## puma-like-3r")):
        run = run_cli(["cusps", str(path), "--vary", "rho=0:6,z=-5:5", "-o", str(tmp_path / name)])
        assert run.status == 0, run.err
        assert (tmp_path / name).read_text().startswith(first)
    assert json.loads((tmp_path / "c.json").read_text())["cuspidal"] is False
    run = run_cli(
        ["cusps", str(path), "--vary", "rho=0:6,z=-5:5", "--plot", str(tmp_path / "c.jpg")]
    )
    assert run.status == 2 and "name it .png or .svg" in run.err
    assert not (tmp_path / "c.jpg").exists()


def test_schema_prints_one_document_at_a_time(capsys: pytest.CaptureFixture[str]) -> None:
    from mechsing.cli import main

    with pytest.raises(SystemExit) as exc:
        main(["schema", "--sweep", "--cusps"])
    assert exc.value.code == 2 and "not allowed with argument" in capsys.readouterr().err
    assert json.loads(run_cli(["schema", "--cusps"]).out)["title"] == "mechsing cusps document"


def test_the_schema_rejects_a_document_without_its_verdict(tmp_path: Path) -> None:
    """The schema is no blank cheque: a document missing ``cuspidal``, or with a cusp of
    multiplicity 2 (two modes meeting is a singular curve, not a cusp), fails it."""
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads(run_cli(["schema", "--cusps"]).out)
    doc = _cusps(_write(tmp_path, "puma3.yaml", PUMA_3R), "rho=0:6,z=-5:5")
    del doc["cuspidal"]
    with pytest.raises(jsonschema.ValidationError, match="cuspidal"):
        jsonschema.Draft202012Validator(schema).validate(doc)
    doc["cuspidal"] = False
    doc["cusps"] = [
        {
            "inputs": {"rho": 1.0, "z": 0.0},
            "multiplicity": 2,
            "certified": False,
            "radius": None,
            "t": 0.0,
            "modes": {"real_modes_at_cusp": 2, "coalescing": 3},
        }
    ]
    with pytest.raises(jsonschema.ValidationError, match="3 was expected"):
        jsonschema.Draft202012Validator(schema).validate(doc)


def test_cusps_text_and_plot(tmp_path: Path) -> None:
    path = _write(tmp_path, "orth.yaml", ORTHOGONAL_3R)
    png = tmp_path / "section.png"
    run = run_cli(
        ["cusps", str(path), "--vary", "rho=0:6,z=-5:5", "--points", "41", "--plot", str(png)]
    )
    assert run.status == 0, run.err
    assert "cuspidal" in run.out and "three modes meet" in run.out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # Markdown keeps the grid's lines: an orthogonal 3R arm reaches a point of its
    # workspace in 0, 2 or 4 postures (Baili, Wenger & Chablat, ICRA 2004)
    md = run_cli(
        ["cusps", str(path), "--vary", "rho=0:6,z=-5:5", "--points", "41", "--format", "md"]
    )
    assert md.status == 0 and "- real modes on the grid: 0, 2, 4\n" in md.out
    assert "- singular curves: " in md.out and "| 4 |" in md.out


def test_the_figure_has_one_colour_band_per_count_and_its_legend_off_the_section() -> None:
    """A hand-written section (counts 0, 2 and 4 on a 3 x 3 grid, one cusp at the
    centre): the colour bar reads 0, 2, 4, one colour each, nothing between; the
    legend lies below the axes, so no cusp is under it."""
    from mechsing.reports.cusps import cusps_figure

    doc = {
        "mechanism": "hand-made",
        "section": {"vary": {"a": [0.0, 2.0], "b": [0.0, 2.0]}, "fixed": {}},
        "modes_grid": {"a": [0, 1, 2], "b": [0, 1, 2], "modes": [[0, 0, 2], [0, 2, 4], [2, 4, 4]]},
        "singular_curves": {"points": [[0.5, 1.0], [1.0, 0.5]]},
        "cusps": [{"inputs": {"a": 1.0, "b": 1.0}, "certified": True}],
        "cuspidal": True,
    }
    fig = cusps_figure(doc)
    ax, bar = fig.axes
    image = ax.images[0]
    assert [t.get_text() for t in bar.get_yticklabels()] == ["0", "2", "4"]
    assert image.cmap.N == 3  # three colours, one per count
    colours = [tuple(image.cmap(image.norm(i))) for i in range(3)]
    assert len(set(colours)) == 3
    fig.canvas.draw()
    legend = ax.get_legend().get_window_extent()
    assert legend.y1 < ax.get_window_extent().y0


def test_the_figure_of_a_decoupled_arm_says_why_it_is_empty(tmp_path: Path) -> None:
    """The PUMA-like arm (first two axes meet: its inverse kinematics decouples, no cusp
    anywhere) is decided without a grid: the figure says so, its axes in metres."""
    from mechsing.reports.cusps import cusps_figure

    doc = _cusps(_write(tmp_path, "puma3.yaml", PUMA_3R), "rho=0:6,z=-5:5")
    assert doc["evidence"]["kind"] == "decoupled"
    ax = cusps_figure(doc).axes[0]
    assert any("no cusp anywhere" in t.get_text() for t in ax.texts)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("rho (m)", "z (m)")


@pytest.mark.parametrize(
    ("vary", "words"),
    [
        ("rho=0:6", "two coordinates"),
        ("rho=6:0,z=-1:1", "lo < hi"),
        ("x=0:1,z=0:1", "rho=lo:hi,z=lo:hi"),
    ],
)
def test_cusps_bad_vary_exits_2(tmp_path: Path, vary: str, words: str) -> None:
    path = _write(tmp_path, "orth.yaml", ORTHOGONAL_3R)
    run = run_cli(["cusps", str(path), "--vary", vary])
    assert run.status == 2 and words in run.err


#: a planar 2R arm (unit links): two joints, no cusp to look for
ARM_2R = """\
mechanism: arm-2r
bodies: [base, link1, link2]
joints:
  - {name: J1, type: R, between: [base, link1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [link1, link2], axis: [0, 0, 1], point: [1, 0, 0]}
inputs: [J1, J2]
output: {body: link2, point: [2, 0, 0]}
"""


@pytest.mark.parametrize(
    ("text", "vary", "words"),
    [
        (ARM_2R, "J1=0:1,J2=-3:3", "three revolute joints"),
        (ARM_2R, "rho=0:2,z=-1:1", "it has J1 (R), J2 (R)"),
        (SIMILAR_3RPR, "Rb1=0:1,P3=0:1", "--vary Rb1: not an input"),
        (SIMILAR_3RPR, "P2=5:-1,P3=-1:5", "(write P2=-1:5)"),
        (SIMILAR_3RPR, "P2=0:1,P2=0:2", "P2 is given twice"),
    ],
)
def test_cusps_bad_input_names_the_item_and_the_fix(
    tmp_path: Path, text: str, vary: str, words: str
) -> None:
    run = run_cli(["cusps", str(_write(tmp_path, "m.yaml", text)), "--vary", vary])
    assert run.status == 2 and words in run.err and "Traceback" not in run.err


def test_exercise_variants_key_matches_the_reference(tmp_path: Path) -> None:
    """Exercise 17's variants: the key mechsing writes (cuspidal, how many cusps) is the
    reference's count for the variant's drawn r2 and d4."""
    import yaml

    out = tmp_path / "variants"
    run = run_cli(["exercise", "make", "17", "--variants", "1", "--seed", "5", "-o", str(out)])
    assert run.status == 0, run.err
    key = yaml.safe_load((out / "variant-01" / "key.yaml").read_text(encoding="utf-8"))
    r2, d4 = (sympy.Rational(key["numbers"][n]) for n in ("r2", "d4"))
    want = arm_cusps(
        [(0, 0, 0), (1, -sympy.pi / 2, r2), (2, sympy.pi / 2, 0)], (d4, 0, 0), ((0, 6), (-5, 5))
    )
    answers = {q["id"]: q["value"] for q in key["questions"]}
    assert answers["cusps"] == len(want)
    assert answers["cuspidal"] is (len(want) > 0)


def test_report_has_a_cusps_section(tmp_path: Path) -> None:
    path = _write(tmp_path, "orth.yaml", ORTHOGONAL_3R)
    out = tmp_path / "review.html"
    run = run_cli(["report", str(path), "--cusps", "rho=0:6,z=-5:5", "-o", str(out)])
    assert run.status == 0, run.err
    html = out.read_text(encoding="utf-8")
    section = html[html.index(">Cusps<") :]
    assert "orthogonal-3r (inverse kinematics): cuspidal" in section
    assert "data:image/svg+xml" in section  # the section's figure
    assert section.count("three modes meet") == 4


def test_a_degenerate_cusp_is_listed_with_why_it_is_not_certified() -> None:
    """P = t^3 - a^2 t + b: three real roots where 4 a^6 > 27 b^2 (two horns meeting at
    the origin), all three meet at t = 0 at (a, b) = (0, 0), but there d(P_t)/da = -2a = 0:
    the triple-root system's Jacobian is singular (the singular curve b = +-2 |a|^3 /
    sqrt 27 is itself singular there), so the Krawczyk test cannot certify it, and the
    cusp says so; the ordinary cusp of t^3 - a t + b is certified and regular (the
    planar_3rpr_six example at its reference's P1 = 0, P2, P3 in [-20, 20], lists such
    a degenerate cusp near P2 = 9.93, P3 = -12.17)."""
    from mechsing.assembly.cusps import DEGENERATE, Cusp
    from mechsing.assembly.discriminant import Family, section

    t, a, b = sympy.symbols("t a b")
    (horn,) = section(Family.of(t**3 - a**2 * t + b, t, a, b), (-1.0, 1.1), (-0.5, 0.6), 41).cusps
    assert (float(horn.a), float(horn.b), float(horn.t)) == pytest.approx((0, 0, 0), abs=1e-12)
    assert not horn.certified and horn.degenerate
    # three real roots beside it (inside a horn), one alone outside
    assert len([r for r in np.roots([1, 0, -(0.1**2), 1e-4]) if abs(r.imag) < 1e-12]) == 3
    (plain,) = section(Family.of(t**3 - a * t + b, t, a, b), (-1.0, 1.1), (-0.5, 0.6), 41).cusps
    assert plain.certified and not plain.degenerate
    doc = Cusp({"a": 0.0, "b": 0.0}, 0.0, False, 1e-30, {}, DEGENERATE).to_json()
    assert doc["radius"] is None and "degenerate cusp" in doc["not_certified"]


def test_a_pose_configuration_fixes_the_input_it_closes_at(tmp_path: Path) -> None:
    """The bundled 3-RPR with a configuration that gives the platform's pose, not the
    legs: the fixed input P1 is the first leg's length at that pose less its drawn
    length (the platform pivot (9/10, 3/10) turned by 0.1 rad about the centroid of the
    three platform pivots, which moves to (1.1, 1.2); the base pivot at the origin and the
    leg along the pivot's direction), not its reference value 0."""
    root = Path(__file__).resolve().parents[1]
    text = (root / "examples" / "planar_3rpr.yaml").read_text()
    path = _write(
        tmp_path,
        "posed.yaml",
        text + "  posed: {pose: {position: [1.1, 1.2, 0], rotation_vector: [0, 0, 0.1]}}\n",
    )
    pivots = np.array([[0.9, 0.3], [2.5, 1.5], [-0.3, 1.9]])
    c = pivots.mean(axis=0)
    t = 0.1
    turn = np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    moved = np.array([1.1, 1.2]) + turn @ (pivots[0] - c)
    want = float(np.linalg.norm(moved) - np.linalg.norm(pivots[0]))
    doc = _cusps(path, "P2=0:1,P3=0:1", "--config", "posed", "--points", "21")
    assert doc["section"]["fixed"]["P1"] == pytest.approx(want, abs=1e-12)
    assert abs(want) > 0.05  # not the reference value it took before
