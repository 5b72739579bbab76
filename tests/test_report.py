"""Design-review reports: `mechsing report`, `mechsing.report()` and the notebook views.

The verdicts are checked against the published facts the example files cite (a crank-rocker
four-bar is regular at its three configurations; the five-bar's ``type1`` is an input
singularity and ``type2`` an output singularity, Gosselin and Angeles 1990); the screw axes
against their closed forms written here; the documents against independent parsers
(html5lib in strict mode, markdown-it-py) and, in test_report_browser.py, a real browser.
"""

from __future__ import annotations

import re
import warnings
from html.parser import HTMLParser
from pathlib import Path

import html5lib
import numpy as np
import pytest
from markdown_it import MarkdownIt

import mechsing
from tests.cli import ROOT, run_cli

EXAMPLES = sorted((ROOT / "examples").glob("*.yaml"))
TIME_LINE = re.compile(r"time taken: [0-9.]+ s")


class _Tables(HTMLParser):
    """The rows of every table of an HTML page, as lists of cell texts."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: list[list[str]] = []
        self._cell: list[str] | None = None

    def handle_starttag(self, tag: str, attrs: list) -> None:
        if tag == "tr":
            self.rows.append([])
        elif tag in ("td", "th"):
            self._cell = []

    def handle_endtag(self, tag: str) -> None:
        if tag in ("td", "th") and self._cell is not None:
            self.rows[-1].append("".join(self._cell))
            self._cell = None

    def handle_data(self, data: str) -> None:
        if self._cell is not None:
            self._cell.append(data)


def _rows(html: str) -> dict[str, list[str]]:
    p = _Tables()
    p.feed(html)
    out: dict[str, list[str]] = {}
    for row in p.rows:
        if row:
            out.setdefault(row[0], row)  # the first table that names it: the verdict
    return out


def _strict_parse(html: str) -> None:
    parser = html5lib.HTMLParser(strict=True)
    parser.parse(html)  # raises ParseError on the first error
    assert not parser.errors


@pytest.fixture(scope="module")
def example_reports(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """The HTML report of every bundled example, written by the command line once."""
    folder = tmp_path_factory.mktemp("reports")
    out = {}
    for f in EXAMPLES:
        path = folder / f"{f.stem}.html"
        r = run_cli(["report", f, "-o", path])
        assert r.status in (0, 3), r.err
        assert path.exists()
        out[f.stem] = path
    return out


# --------------------------------------------------------------------------- smoke


def test_every_bundled_example_gives_a_valid_self_contained_html5_report(
    example_reports: dict[str, Path],
) -> None:
    assert set(example_reports) == {f.stem for f in EXAMPLES}
    for name, path in example_reports.items():
        html = path.read_text(encoding="utf-8")
        _strict_parse(html)
        assert "<script" not in html, name
        # nothing fetched: every src is inline data, no stylesheet or font link
        assert all(s.startswith("data:") for s in re.findall(r'src="([^"]*)"', html)), name
        assert "<link" not in html and "@import" not in html and "url(" not in html, name
        heads = re.findall(r"<h2[^>]*>([^<]*)</h2>", html)
        assert heads[:3] == ["Verdict", "The mechanism", "Configurations"], name
        assert heads[-1] == "How it was computed", name
        assert html.count("<img") >= 2, name  # the graph and at least one sketch


def test_the_verdicts_are_the_published_ones(example_reports: dict[str, Path]) -> None:
    rows = _rows(example_reports["fourbar"].read_text(encoding="utf-8"))
    for c in ("reference", "crank-30", "crank-200"):  # a crank-rocker: all regular
        assert rows[c][1:3] == ["no", "none"], rows[c]
    rows = _rows(example_reports["five_bar"].read_text(encoding="utf-8"))
    assert rows["reference"][1] == "no" and rows["inputs"][1] == "no"
    assert rows["type1"][1] == "yes" and "input (type I)" in rows["type1"][2]
    assert rows["type2"][1] == "yes" and "output (type II)" in rows["type2"][2]
    assert rows["type1"][4] in ("float", "mp:50")  # the precision that decided it


def test_the_report_is_the_same_byte_for_byte_but_the_time(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    a, b = tmp_path / "a" / "review.html", tmp_path / "b" / "review.html"
    argv = ["examples/five_bar.yaml", "--config", "type2", "--vary", "A1=-0.2:0.2:0.1"]
    for p in (a, b):
        monkeypatch.chdir(p.parent)
        assert run_cli(["report", ROOT / argv[0], *argv[1:], "-o", "review.html"]).status == 0
    ta, tb = (TIME_LINE.sub("", p.read_text(encoding="utf-8")) for p in (a, b))
    assert len(TIME_LINE.findall(a.read_text(encoding="utf-8"))) == 1
    assert ta == tb


def test_a_path_sweep_marks_the_singularities_it_located(tmp_path: Path) -> None:
    # Gosselin & Angeles: the crank-rocker's input (type I) singularities are where crank and
    # coupler are collinear: |AC| = 2*sqrt(2) - 1 or 2*sqrt(2) + 1 with A = (0,0), D = (4,0),
    # |CD| = sqrt(5), |AB| = 1; the crank angle there follows from the triangle ACD.
    out = tmp_path / "review.html"
    r = run_cli(["report", ROOT / "examples/fourbar.yaml", "--vary", "A=0:360:5", "-o", out])
    assert r.status == 0, r.err
    html = out.read_text(encoding="utf-8")
    _strict_parse(html)
    rows = [row for key, row in _rows(html).items() if key.startswith("sweep:")]
    found = sorted(float(re.search(r"A = ([0-9.]+) deg", row[0]).group(1)) for row in rows)
    expected = []
    for ac, stretched in ((2 * np.sqrt(2) - 1, False), (2 * np.sqrt(2) + 1, True)):
        # C stays above the ground line (|AC| never reaches 4 -+ sqrt(5)); B is on the ray
        # AC when the links are stretched, on the opposite ray when folded
        cx = (ac**2 + 16 - 5) / 8
        cy = np.sqrt(ac**2 - cx**2)
        angle = np.degrees(np.arctan2(cy, cx))
        expected.append(angle % 360 if stretched else (angle + 180) % 360)
    assert len(found) == 2
    assert np.allclose(found, sorted(expected), atol=1e-6)
    assert all(row[1] == "yes" and "input (type I)" in row[2] for row in rows)


def test_a_grid_sweep_draws_its_loci_and_the_start(tmp_path: Path) -> None:
    rep = mechsing.report(
        ROOT / "examples/five_bar.yaml", ["reference"], ["A1=-1:1:0.25", "A2=-1:1:0.25"]
    )
    assert rep.sweep is not None and rep.sweep.grid and rep.sweep.loci
    html = rep.to_html()
    _strict_parse(html)
    assert "singularity loci over A1 and A2" in html
    assert any(k.startswith("sweep: locus 1 of ") for k in _rows(html))


# --------------------------------------------------------------------------- Markdown


def test_markdown_links_figures_that_exist_and_renders_without_warnings(tmp_path: Path) -> None:
    out = tmp_path / "review.md"
    r = run_cli(["report", ROOT / "examples/planar_3rpr.yaml", "-o", out])
    assert r.status == 0, r.err
    text = out.read_text(encoding="utf-8")
    links = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert links and all(link.startswith("review_files/") for link in links)
    for link in links:
        svg = (out.parent / link).read_text(encoding="utf-8")
        assert svg.startswith("<svg") and svg.rstrip().endswith("</svg>")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        html = MarkdownIt("commonmark").enable("table").render(text)
    assert html.count("<table>") >= 3 and html.count("<img") == len(links)
    assert "<h2>Verdict</h2>" in html
    # the verdict (Bonev, Zlatanov, Gosselin 2003): concurrent leg lines, output singular
    assert re.search(r"<td><strong>concurrent</strong></td>\s*<td>yes</td>", html)


# --------------------------------------------------------------------------- command line


def test_the_format_follows_the_extension_and_anything_else_is_refused(tmp_path: Path) -> None:
    r = run_cli(["report", ROOT / "examples/fourbar.yaml", "-o", tmp_path / "review.pdf"])
    assert r.status == 2
    assert "review.pdf" in r.err and ".html or .md" in r.err
    assert not (tmp_path / "review.pdf").exists()


def test_the_default_output_is_the_file_stem_with_html_here(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    r = run_cli(["report", ROOT / "examples/fourbar.yaml", "--config", "crank-30"])
    assert r.status == 0, r.err
    assert (tmp_path / "fourbar.html").exists()
    html = (tmp_path / "fourbar.html").read_text(encoding="utf-8")
    assert "mechsing report " in html and "--config crank-30" in html


def test_three_vary_and_a_from_without_vary_are_refused() -> None:
    f = ROOT / "examples/five_bar.yaml"
    r = run_cli(["report", f, "--vary", "A1=0:1:1", "--vary", "A2=0:1:1", "--vary", "P=0:1:1"])
    assert r.status == 2 and "--vary is given 3 times" in r.err
    r = run_cli(["report", f, "--from", "inputs"])
    assert r.status == 2 and "give --vary or --set too" in r.err


def test_set_adds_a_configuration_to_a_robot_description(tmp_path: Path) -> None:
    """--set on a URDF arm: the configuration cli (the UR5 with its wrist joint at zero,
    so the axes of joints 4 and 6 line up: a wrist singularity) is in the verdict."""
    out = tmp_path / "ur5.md"
    r = run_cli(["report", ROOT / "examples/ur5.urdf", "--set", "joint5=0", "-o", out])
    assert r.status == 0, r.err
    rows = [line for line in out.read_text().splitlines() if line.startswith("| **cli**")]
    assert rows and "| yes |" in rows[0] and "serial" in rows[0]


# --------------------------------------------------------------------------- notebook


def test_results_and_reports_show_themselves_in_a_notebook() -> None:
    res = mechsing.analyze(ROOT / "examples/five_bar.yaml", ["type1"])
    html = res._repr_html_()
    _strict_parse(f"<!DOCTYPE html><title>t</title>{html}")
    assert _rows(html)["type1"][1] == "yes"
    sw = mechsing.sweep(ROOT / "examples/fourbar.yaml", ["A=0:360:10"])
    rows = [k for k in _rows(sw._repr_html_()) if k.startswith("sweep: A = ")]
    assert len(rows) == len(sw.located) == 2
    rep = mechsing.report(ROOT / "examples/fourbar.yaml", ["crank-30"])
    frag = rep._repr_html_()
    assert frag.startswith("<style>") and "<html" not in frag and "crank-30" in frag


# --------------------------------------------------------------------------- screw axes


def test_screw_axes_are_their_closed_forms() -> None:
    from mechsing.reports.sketch import Screw, screw_axis

    # a twist of rate 1 about the axis u through p with pitch h: omega = u,
    # v (velocity of the body point at the origin) = p x u + h u
    u = np.array([0.0, 0.6, 0.8])
    p = np.array([1.0, 2.0, -1.0])
    h = 0.25
    point, direction, pitch = screw_axis(Screw("twist", (*u, *(np.cross(p, u) + h * u)), "t"))
    assert pitch == pytest.approx(h)
    assert np.allclose(direction, u)
    assert np.allclose(np.cross(point - p, u), 0)  # on the axis
    # a force f along u through p and a couple h f: m (about the origin) = p x f + h f
    point, direction, pitch = screw_axis(
        Screw("wrench", (*(2 * u), *(np.cross(p, 2 * u) + h * 2 * u)), "w")
    )
    assert pitch == pytest.approx(h) and np.allclose(np.cross(point - p, u), 0)
    # a pure translation: no axis point, infinite pitch
    point, direction, pitch = screw_axis(Screw("twist", (0, 0, 0, 0, 0, 3), "t"))
    assert point is None and pitch is None and np.allclose(direction, [0, 0, 1])


def test_planar_mechanisms_are_seen_along_their_normal() -> None:
    from mechsing.reports.sketch import choose_view

    view = choose_view(mechsing.load(str(ROOT / "examples/fourbar.yaml")))
    assert np.allclose(np.abs(view.toward), [0, 0, 1])
    view = choose_view(mechsing.load(str(ROOT / "examples/bennett.yaml")))
    assert "oblique" in view.name and abs(view.up[2]) > 0.5


# --------------------------------------------------------------------------- a real browser

CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--no-first-run",
    "--disable-sync",
]


def _browser_or_skip():
    """Playwright's sync API with Debian's chromium, or a skip (a failure when
    MECHSING_REQUIRE_BROWSER=1, as in CI)."""
    import os

    required = os.environ.get("MECHSING_REQUIRE_BROWSER") == "1"
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        if required:
            pytest.fail("MECHSING_REQUIRE_BROWSER=1 but playwright is not installed")
        pytest.skip("playwright is not installed")
    if not CHROMIUM.exists():
        if required:
            pytest.fail(f"MECHSING_REQUIRE_BROWSER=1 but {CHROMIUM} is missing")
        pytest.skip(f"{CHROMIUM} is missing (apt-get install chromium)")
    return sync_playwright


def _not_blank(png: bytes) -> float:
    import io

    import matplotlib.image

    pixels = matplotlib.image.imread(io.BytesIO(png), format="png")[..., :3]
    return float(np.var(pixels))


def test_reports_render_in_a_real_browser(example_reports: dict[str, Path], tmp_path: Path) -> None:
    sync_playwright = _browser_or_skip()
    shots = tmp_path / "screenshots"
    shots.mkdir()
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        try:
            for name, path in example_reports.items():
                for width in (1280, 390):
                    page = browser.new_page(viewport={"width": width, "height": 900})
                    errors: list[str] = []
                    fetched: list[str] = []
                    page.on(
                        "console",
                        lambda m, e=errors: e.append(m.text) if m.type == "error" else None,
                    )
                    page.on("pageerror", lambda exc, e=errors: e.append(str(exc)))
                    page.on(
                        "request",
                        lambda req, f=fetched: (
                            None if req.url.startswith(("file:", "data:")) else f.append(req.url)
                        ),
                    )
                    page.route(
                        re.compile(r"^https?://"),
                        lambda route, f=fetched: (f.append(route.request.url), route.abort()),
                    )
                    page.goto(path.as_uri())
                    page.wait_for_load_state("load")
                    assert not errors, (name, width, errors)
                    assert not fetched, (name, width, fetched)
                    figures = page.query_selector_all("figure img, svg")
                    assert figures, name
                    for fig in figures:
                        box = fig.bounding_box()
                        assert box and box["width"] > 0 and box["height"] > 0, (name, width)
                        assert fig.evaluate(
                            "e => e.naturalWidth === undefined || e.naturalWidth > 0"
                        )
                        assert box["width"] <= width, (name, width, box)  # shrinks to the window
                    # the page itself does not scroll sideways (tables scroll in their box)
                    assert page.evaluate(
                        "document.documentElement.scrollWidth <= window.innerWidth + 1"
                    ), (name, width)
                    png = page.screenshot(full_page=width == 1280)
                    assert _not_blank(png) > 1e-4, (name, width)
                    if width == 1280:
                        (shots / f"{name}.png").write_bytes(png)
                    page.close()
        finally:
            browser.close()
    assert len(list(shots.glob("*.png"))) == len(example_reports)


def test_a_configuration_that_cannot_be_analysed_is_reported_with_exit_3(tmp_path: Path) -> None:
    # exact mode takes exact data only: crank-30 gives one of four joint values, the others
    # would be solved numerically, so it cannot be analysed exactly (the reference can)
    out = tmp_path / "review.html"
    r = run_cli(["report", ROOT / "examples/fourbar.yaml", "--precision", "exact", "-o", out])
    assert r.status == 3 and "crank-30" in r.err
    rows = _rows(out.read_text(encoding="utf-8"))
    assert rows["crank-30"][1] == "not analysed" and "exact" in rows["crank-30"][2]
    assert rows["reference"][1:3] == ["no", "none"]
    # exact mode proves the closure and loop ranks; the input/output tests ran at mp:50
    decided = rows["reference"][4]
    assert decided.startswith("exact (the ") and decided.endswith(" tests at mp:50)")
    assert "input" in decided and "closure" not in decided


def test_the_mechanism_section_says_the_published_mobility_and_loop_subgroup(
    example_reports: dict[str, Path],
) -> None:
    # the four-bar (its file's published facts): planar Grubler 1, spatial Grubler -2, one
    # loop in the planar subgroup G of normal z
    html = example_reports["fourbar"].read_text(encoding="utf-8")
    rows = _rows(html)
    assert rows["Grübler-Kutzbach (spatial)"][1] == "-2"
    assert rows["group (loop subgroups)"][1] == "1" and "by 3" in rows["group (loop subgroups)"][2]
    assert rows["finite"][1] == "1"
    assert "this loop moves in a plane (planar subgroup G, normal (0, 0, 1))" in html
    # the spherical four-bar: one loop in S about the common point of its axes
    html = example_reports["spherical_4r"].read_text(encoding="utf-8")
    assert "this loop turns about a point (spherical subgroup S" in html
    # Bennett's linkage: overconstrained, mobile although Grubler says -2
    rows = _rows(example_reports["bennett"].read_text(encoding="utf-8"))
    assert rows["Grübler-Kutzbach (spatial)"][1] == "-2" and rows["finite"][1] == "1"
    assert "overconstrained" in rows["finite"][2]


def test_legs_and_output_motion_types_are_the_published_ones(tmp_path: Path) -> None:
    # Tsai's 3-UPU (L.-W. Tsai, 1996): three U-P-U legs, a translational platform (T3);
    # the file's "flat" configuration is its constraint singularity, where the platform
    # gains a rotation: the legs' constraint couples n_i lie along the horizontal legs, so the
    # rotation they no longer resist is about z (T3 plus turns about z: Schoenflies motion X)
    out = tmp_path / "tsai.html"
    assert run_cli(["report", ROOT / "examples/tsai_3upu.yaml", "-o", out]).status == 0
    html = out.read_text(encoding="utf-8")
    rows = _rows(html)
    assert [rows[k][1] for k in ("1", "2", "3")] == [
        "U1a - P1 - U1b",
        "U2a - P2 - U2b",
        "U3a - P3 - U3b",
    ]
    assert "span T3, spatial translation (dimension 3)" in html
    assert "at flat: X, Schoenflies motion (dimension 4; axis (0, 0, 1))" in html
