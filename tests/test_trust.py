"""Valid input gets a right answer or a clear message, never a traceback: regressions of the
new-user trial (renderers, identify, catalog, unreachable inputs, internal defects) and the
packaging of the catalog."""

from __future__ import annotations

import importlib.resources
import json
import math
import tomllib

import pytest

from mechsing.errors import current_work, forget_work, working_on
from tests.cli import run_cli
from tests.mechanisms import NON_GRASHOF_ROCKER, ROOT, write

SLIDER_CRANK = (ROOT / "examples" / "slider_crank_crank_input.yaml").read_text()


# --------------------------------------------------------------------------- renderers


@pytest.mark.parametrize("fmt", ["text", "md"])
def test_text_and_markdown_render_a_test_left_undecided_in_float(tmp_path, fmt):
    """Offset slider-crank, crank 1e-10 before its outer dead centre (A = 2 atan(4/3)): float
    cannot decide the input test there; the report says so instead of crashing."""
    text = SLIDER_CRANK.replace('crank-60: {A: "pi/3"}', 'near: {A: "2*atan(4/3) - 1e-10"}')
    path = write(tmp_path, "near", text)
    rc, out, err = run_cli(
        ["analyze", str(path), "--config", "near", "--precision", "float", "--format", fmt]
    )
    assert rc == 0, err
    rc_j, out_j, _ = run_cli(
        ["analyze", str(path), "--config", "near", "--precision", "float", "--format", "json"]
    )
    undecided = [
        f
        for f in json.loads(out_j)["configurations"][0]["singularities"]
        if f["class"] == "undecided"
    ]
    assert undecided, "1e-10 from the dead centre, float must leave a test undecided"
    for f in undecided:
        assert f"cannot decide the {f['what']}" in out
        assert f["rank_bounds"] is not None or "note" in f
    assert "tested in float" in out and "decided in float" not in out


def test_text_labels_the_grubler_count_as_spatial():
    rc, out, _ = run_cli(
        [
            "analyze",
            str(ROOT / "examples" / "fourbar.yaml"),
            "--config",
            "crank-30",
            "--precision",
            "float",
        ]
    )
    assert rc == 0
    assert "spatial Grubler-Kutzbach count -2" in out


# --------------------------------------------------------------------------- identify, catalog


@pytest.mark.parametrize("fmt", ["text", "json"])
def test_identify_without_a_screw_gives_the_identity_subgroup(fmt):
    """No screw generates the trivial subgroup E, of dimension 0 (as the API answers)."""
    rc, out, err = run_cli(["identify", "--format", fmt, "--"])
    assert rc == 0, err
    if fmt == "json":
        d = json.loads(out)
        assert (d["type"], d["dim"], d["params"], d["status"]) == ("E", 0, {}, "ok")
    else:
        assert out.startswith("E (dimension 0)") and "None" not in out


def test_identify_text_in_exact_mode_shows_exact_parameters():
    """R through (1/6, -1/6, 0) along (1, 1, 0)/sqrt 2: its Plücker coordinates are
    w = (1, 1, 0), v = p x w = (0, 0, 1/3)."""
    rc, out, _ = run_cli(["identify", "--", "1,1,0,0,0,1/3"])
    assert rc == 0
    assert "R (dimension 1)" in out
    assert "axis: sqrt(2)/2, sqrt(2)/2, 0" in out
    assert "point: 1/6, -1/6, 0" in out
    assert "precision: exact" in out and "None" not in out


def test_identify_text_in_float_never_prints_none():
    unit = [
        "1,0,0,0,0,0",
        "0,1,0,0,0,0",
        "0,0,1,0,0,0",
        "0,0,0,1,0,0",
        "0,0,0,0,1,0",
        "0,0,0,0,0,1",
    ]
    rc, out, _ = run_cli(["identify", "--precision", "float", "--", *unit])
    assert rc == 0 and "None" not in out and "nothing dropped" in out


@pytest.mark.parametrize("fmt", ["text", "json"])
def test_catalog_explains_the_universal_joint(fmt):
    rc, out, err = run_cli(["catalog", "U", "--format", fmt])
    assert rc == 0, err
    if fmt == "json":
        (u,) = json.loads(out)
        assert u["symbol"] == "U" and u["composite"] is True and u["of"] == ["R", "R"]
    else:
        assert "composite" in out and "two R joints" in out and "unknown" not in out


# --------------------------------------------------------------------------- unreachable input

ROCKER = NON_GRASHOF_ROCKER + "configurations:\n  far: {A: 120}\n"


def test_an_unreachable_input_reports_the_value_reached_in_the_file_units(tmp_path):
    """Non-Grashof four-bar (2 + 4 > 3 + sqrt 5): the crank AB stops where B, C, D line up,
    |BD| = 3 + sqrt 5; by the law of cosines the angle of AB from AD is then
    acos((4 + 16 - |BD|^2) / 16), and A (measured from AB's reference angle, 90 deg) stops there."""
    bd = 3 + math.sqrt(5)
    limit = math.degrees(math.acos((4 + 16 - bd**2) / 16)) - 90
    rc, out, err = run_cli(
        ["analyze", str(write(tmp_path, "rocker", ROCKER)), "--precision", "float"]
    )
    assert rc == 3
    reached = float(err.split("A reached ")[1].split(" deg")[0])
    assert limit - 0.05 < reached <= limit + 1e-6
    assert f"{120 - reached:.3g} deg short of the target 120 deg" in err
    assert "of the way" not in err


# --------------------------------------------------------------------------- internal defects


def test_an_escaping_exception_is_one_line_exit_4_naming_file_and_configuration(monkeypatch):
    import mechsing.analysis.run

    def broken(*args, **kwargs):
        raise RuntimeError("svd: no convergence")

    monkeypatch.setattr(mechsing.analysis.run, "classify", broken)
    path = str(ROOT / "examples" / "fourbar.yaml")
    rc, out, err = run_cli(["analyze", path, "--config", "crank-30", "--precision", "float"])
    assert rc == 4
    assert err.count("\n") == 1 and "Traceback" not in err
    assert path in err and "'crank-30'" in err and "defect" in err and "-T" in err
    with pytest.raises(RuntimeError, match="no convergence"):
        run_cli(["-T", "analyze", path, "--config", "crank-30", "--precision", "float"])


def test_the_work_record_names_the_innermost_context_of_the_error_only():
    forget_work()
    with pytest.raises(ValueError), working_on(file="a.yaml"), working_on(configuration="c1"):
        raise ValueError
    assert current_work() == "file 'a.yaml', configuration 'c1'"
    forget_work()
    with working_on(file="b.yaml"):
        assert current_work() == "file 'b.yaml'"
    assert current_work() == ""


# --------------------------------------------------------------------------- packaging


def test_the_installed_catalog_is_the_catalog_folder():
    """The package data mechsing.catalog (what a wheel ships) holds catalog/'s files, byte for byte."""
    installed = importlib.resources.files("mechsing.catalog")
    source = ROOT / "catalog"
    names = {f.name for f in installed.iterdir() if f.name.endswith(".toml")}
    assert names == {p.name for p in source.glob("*.toml")} and names
    for name in names:
        assert installed.joinpath(name).read_bytes() == (source / name).read_bytes()


def test_the_build_lists_every_package():
    """pyproject lists the packages explicitly (to map catalog/ into mechsing.catalog): every
    folder of mechsing/ with an __init__.py must be in the list, or a wheel would lack it."""
    conf = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    on_disk = {
        ".".join(p.parent.relative_to(ROOT).parts)
        for p in (ROOT / "mechsing").rglob("__init__.py")
        if "__pycache__" not in p.parts
    }
    assert on_disk | {"mechsing.catalog"} == set(conf["packages"])
    assert conf["package-dir"] == {"mechsing.catalog": "catalog"}


def test_docs_show_exit_status_4():
    text = " ".join((ROOT / "README.md").read_text().split())
    assert "4 an internal defect" in text


# --------------------------------------------------------------------------- auto on float data


def _slider_crank_near_dead_centre(distance: str) -> dict[str, str]:
    """Every joint value of the offset slider-crank (crank r = 1 at the origin, B at (0, -1),
    rod 4 to C = (16/5, 7/5), slider on y = 7/5) a given distance before its outer dead centre
    A = 2 atan(4/3), from the planar geometry at 40 digits, written with float's 17 digits:
    B = (sin A, -cos A), C = (x, 7/5) with |C - B| = 4; the rod turns by phi - phi0, the slider
    not at all."""
    import mpmath

    with mpmath.workdps(40):
        a = 2 * mpmath.atan(mpmath.mpf(4) / 3) - mpmath.mpf(distance)
        bx, by = mpmath.sin(a), -mpmath.cos(a)
        cy = mpmath.mpf(7) / 5
        x = bx + mpmath.sqrt(16 - (cy - by) ** 2)
        phi0 = mpmath.atan2(mpmath.mpf(12) / 5, mpmath.mpf(16) / 5)
        phi = mpmath.atan2(cy - by, x - bx)
        vals = {"A": a, "B": phi - phi0 - a, "C": phi0 - phi, "P": x - mpmath.mpf(16) / 5}
    return {k: repr(float(v)) for k, v in vals.items()}


def test_auto_re_decides_fully_given_float_values_instead_of_refusing_them(tmp_path):
    """Every value given with float's digits 1e-10 before the dead centre: float cannot decide
    the input test, so auto re-decides at mp:50, where those digits close only to 1e-16 m.
    The default mode must not turn a valid file into 'does not close': it projects the values
    onto closure (a change far below their own digits) and decides there (regular: the dead
    centre is 1e-10 away)."""
    vals = _slider_crank_near_dead_centre("1e-10")
    given = ", ".join(f"{k}: {v}" for k, v in vals.items())
    path = write(
        tmp_path, "near", SLIDER_CRANK.replace('crank-60: {A: "pi/3"}', f"near: {{{given}}}")
    )
    rc, out, err = run_cli(["analyze", str(path), "--config", "near", "--format", "json"])
    assert rc == 0, err
    (c,) = json.loads(out)["configurations"]
    assert c["precision"] == "mp:50" and c["closure_residual"] < 1e-40
    assert c["singular"] is False
    for k, v in vals.items():
        assert abs(c["joints"][k][0] - float(v)) < 1e-14
    assert any("projected onto closure" in n for n in c["notes"])
    # asked for explicitly, mp:50 still holds the file to its digits (the contract)
    rc, _out, err = run_cli(["analyze", str(path), "--config", "near", "--precision", "mp:50"])
    assert rc == 3 and "give more digits" in err


def test_errors_raised_while_solving_name_the_file(tmp_path):
    """A displacement outside its joint's subgroup is found while closing, not while reading:
    the message still names the file (and the configuration, joint and line)."""
    path = write(
        tmp_path,
        "bad",
        """mechanism: s-bad
bodies: [g, b]
joints:
  - {name: S1, type: S, between: [g, b], point: [0, 1, 2]}
configurations:
  c1:
    S1: {rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]], translation: [0, 3, 1.001]}
""",
    )
    rc, _out, err = run_cli(["analyze", str(path)])
    assert rc == 2
    assert err.startswith(f"mechsing: error: {path}: configuration 'c1', joint 'S1' (line 7)")
    rc, _out, err = run_cli(["analyze", str(write(tmp_path, "rocker", ROCKER))])
    assert rc == 3 and err.startswith(f"mechsing: {tmp_path / 'rocker.yaml'}: configuration 'far'")


@pytest.mark.parametrize("k", [5, 6, 7])
def test_an_undecided_rank_whose_bounds_give_one_verdict_is_no_finding(tmp_path, k):
    """10^-k before the slider-crank's dead centre the legs' constraint rank is undecided in
    float between 5 and 6 (rounding over a leg's small singular value), and its generic value
    is 5: a constraint singularity is a rank below 5, so either rank is regular and no
    'undecided' finding may make the configuration's verdict null."""
    text = SLIDER_CRANK.replace('crank-60: {A: "pi/3"}', f'near: {{A: "2*atan(4/3) - 1e-{k}"}}')
    rc, out, err = run_cli(
        [
            "analyze",
            str(write(tmp_path, "sc", text)),
            "--config",
            "near",
            "--precision",
            "float",
            "--format",
            "json",
        ]
    )
    assert rc == 0, err
    (c,) = json.loads(out)["configurations"]
    assert c["singular"] is False, c["singularities"]
    for d in c["decisions"]:
        if d["rank"] is None and d.get("generic") is not None and d["test"] == "constraint":
            assert d["rank_bounds"][0] >= d["generic"]


def test_an_undecided_finding_at_mp_suggests_more_digits_not_the_same_mode():
    from mechsing.analysis.words import explain
    from mechsing.singularity.findings import UndecidedFinding

    f = UndecidedFinding("input test", (0, 1), None, "mp:50")
    assert "mp:100" in explain(f) and "mp:50 or" not in explain(f)


# --------------------------------------------------------------------------- folds as targets

SLIDER_INPUT = (ROOT / "examples" / "slider_crank_slider_input.yaml").read_text()


def _with_config(text: str, line: str) -> str:
    head, _sep, _rest = text.partition("configurations:")
    return f"{head}configurations:\n  reference: {{}}\n  {line}\n"


def test_a_fold_given_by_its_input_is_reached_and_classified_as_when_fully_given(tmp_path):
    """The slider-crank driven by its slider, at the outer dead centre given by the slider
    alone (P = 8/5: the slider pin at x = sqrt((l + r)^2 - e^2) = 24/5).  The slider cannot go
    further: a fold, where the crank and the rod move like the square root of the slider, so
    continuation cannot step onto it and Newton only halves the distance there.  The target is
    reached; float, which places a fold's unknown joints only to about 1e-8, says it cannot
    decide; auto decides at mp:50 and gives the classes of the fully given dead centre
    (decided exactly); the solved joints are the dead centre's closed form."""
    path = write(tmp_path, "dead", _with_config(SLIDER_INPUT, 'dead: {P: "8/5"}'))
    full = write(
        tmp_path,
        "full",
        _with_config(
            SLIDER_INPUT, 'dead: {A: "2*atan(4/3)", B: "-2*atan(2)", C: "2*atan(2/11)", P: "8/5"}'
        ),
    )
    closed_form = {"A": 2 * math.atan(4 / 3), "B": -2 * math.atan(2), "C": 2 * math.atan(2 / 11)}
    rc, out, err = run_cli(
        ["analyze", str(path), "--config", "dead", "--precision", "float", "--format", "json"]
    )
    assert rc == 0, err
    (c,) = json.loads(out)["configurations"]
    assert c["singular"] is None and any("fold" in f["what"] for f in c["singularities"])
    assert any("fold" in n for n in c["notes"])
    for k, v in closed_form.items():
        assert abs(c["joints"][k][0] - v) < 1e-6
    rc, out, err = run_cli(["analyze", str(path), "--config", "dead", "--format", "json"])
    assert rc == 0, err
    (a,) = json.loads(out)["configurations"]
    rc, out, _ = run_cli(
        ["analyze", str(full), "--config", "dead", "--precision", "exact", "--format", "json"]
    )
    (e,) = json.loads(out)["configurations"]
    assert a["precision"] == "mp:50" and a["singular"] is True
    assert sorted(f["class"] for f in a["singularities"]) == sorted(
        f["class"] for f in e["singularities"]
    )
    for k, v in closed_form.items():
        assert abs(a["joints"][k][0] - v) < 1e-14


def test_a_target_beyond_the_fold_is_still_refused(tmp_path):
    path = write(tmp_path, "beyond", _with_config(SLIDER_INPUT, 'beyond: {P: "8/5 + 1/1000"}'))
    rc, _out, err = run_cli(["analyze", str(path), "--config", "beyond", "--precision", "float"])
    assert rc == 3 and "short of the target" in err
