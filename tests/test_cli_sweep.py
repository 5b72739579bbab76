"""``mechsing sweep`` (issue 13): its JSON, CSV and text, its errors, its schema.

The answers are not the code's own: the offset slider-crank's dead centres come from its
planar geometry (crank r = 1 about the origin, rod l = 4, slider pin on the line y = e = 7/5
starting at x = 16/5, so P = x - 16/5; crank and rod are collinear where x^2 + e^2 = (l +- r)^2),
and a grid's samples are the ranges the test gives.  The streamed JSON is also compared with
the Python function's own document (the command writes it row by row, the function builds it
whole), and validated against the published schema with jsonschema.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re

import pytest

from tests.cli import ROOT, run_cli, run_cli_subprocess

SLIDER = ROOT / "examples" / "slider_crank_slider_input.yaml"
RPR = ROOT / "examples" / "planar_3rpr.yaml"
PATH = ["--vary", "P=-4:4:0.01"]

R, L, E, X0 = 1.0, 4.0, 7 / 5, 16 / 5
#: the slider's displacement P at the outer and inner dead centres (SI)
DEAD_CENTRES = sorted(math.sqrt((L + s * R) ** 2 - E**2) - X0 for s in (1, -1))


def _validator():
    jsonschema = pytest.importorskip("jsonschema")
    from mechsing.sweeps.schema import sweep_schema

    schema = sweep_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


def _ok(argv: list) -> str:
    rc, out, err = run_cli(argv)
    assert rc == 0, (argv, rc, err)
    assert "Traceback" not in err, err
    return out


@pytest.fixture(scope="module")
def slider_json() -> dict:
    return json.loads(_ok(["sweep", SLIDER, *PATH, "--format", "json"]))


def test_slider_crank_folds_at_the_closed_form_dead_centres(slider_json):
    doc = slider_json
    assert doc["units"] == {"length": "m", "angle": "rad"}
    (var,) = doc["variables"]
    assert var["name"] == "P" and var["samples"] == 801 and len(doc["points"]) == 801
    assert [p["values"][0] for p in doc["points"]] == pytest.approx(
        [-4 + 0.01 * k for k in range(801)], abs=1e-12
    )
    folds = sorted(p["values"][0] for p in doc["located"] if p["kind"] == "fold")
    assert len(folds) == 2
    for got, want in zip(folds, DEAD_CENTRES, strict=True):
        assert abs(got - want) < 1e-10, (got, want)
    for p in doc["located"]:  # classified on the path (every located point of a path is)
        assert p["classes"] and p["precision"] and p["configuration"] is not None
    # reached exactly between the dead centres (on the start's assembly mode)
    for p in doc["points"]:
        x = p["values"][0]
        if DEAD_CENTRES[0] + 1e-9 < x < DEAD_CENTRES[1] - 1e-9:
            assert p["reached"] and p["closure"]["rank"] == doc["generic"]["closure"]
        elif not DEAD_CENTRES[0] - 1e-9 < x < DEAD_CENTRES[1] + 1e-9:
            assert not p["reached"] and p["closure"] == {"rank": None, "ratio": None}


def test_slider_crank_json_validates_against_the_schema(slider_json):
    validator = _validator()
    assert not list(validator.iter_errors(slider_json))
    broken = {k: v for k, v in slider_json.items() if k != "points"}
    assert list(validator.iter_errors(broken)), "a document without points must fail"
    bad_point = json.loads(json.dumps(slider_json))
    bad_point["points"][0]["reached"] = "yes"
    assert list(validator.iter_errors(bad_point))


def test_slider_crank_csv_one_line_per_sample_then_the_located_points(slider_json):
    out = _ok(["sweep", SLIDER, *PATH, "--format", "csv"])
    rows = list(csv.reader(io.StringIO(out)))
    header, body = rows[0], rows[1:]
    assert header[:3] == ["kind", "P [m]", "reached"]
    assert all(len(r) == len(header) for r in body)
    samples = [r for r in body if r[0] == "sample"]
    located = [r for r in body if r[0] != "sample"]
    assert len(samples) == 801 and len(located) == len(slider_json["located"])
    assert len(out.splitlines()) == 1 + 801 + len(located)
    assert body[: len(samples)] == samples, "the samples come first, the located points after"
    folds = sorted(float(r[1]) for r in located if r[0] == "fold")
    for got, want in zip(folds, DEAD_CENTRES, strict=True):
        assert abs(got - want) < 1e-10
    reached = {round(float(r[1]), 9) for r in samples if r[2] == "1"}
    assert reached == {round(p["values"][0], 9) for p in slider_json["points"] if p["reached"]}


def _in_millimetres(tmp_path):
    """The slider-crank drawn in millimetres (units: {length: mm}): the same linkage."""
    text = SLIDER.read_text()
    text = text.replace(
        "mechanism: slider-crank-slider-input", "mechanism: sc-mm\nunits: {length: mm}"
    )
    text = text.replace("point: [0, -1, 0]", "point: [0, -1000, 0]")
    text = text.replace('point: ["16/5", "7/5", 0]', "point: [3200, 1400, 0]")
    text = re.sub(r"  slider-4: .*\n", "", text)
    text = re.sub(r"  dead-centre: .*\n", "", text)
    path = tmp_path / "sc_mm.yaml"
    path.write_text(text)
    return path


def test_text_shows_the_file_units_and_json_stays_si(tmp_path):
    mm = _in_millimetres(tmp_path)
    text = _ok(["sweep", mm, "--vary", "P=-4000:4000:10"])
    assert "P from -4000 to 4000 mm by 10" in text
    shown = re.findall(r"P = (\S+) mm \((\S+) m\): limit of travel", text)
    assert len(shown) == 2, text
    for (in_mm, in_m), want in zip(
        sorted(shown, key=lambda s: float(s[1])), DEAD_CENTRES, strict=True
    ):
        assert abs(float(in_mm) - 1000 * want) < 1e-5 and abs(float(in_m) - want) < 1e-8
    doc = json.loads(_ok(["sweep", mm, "--vary", "P=-4000:4000:10", "--format", "json"]))
    assert doc["file_units"]["length"] == "mm" and doc["variables"][0]["unit"] == "m"
    folds = sorted(p["values"][0] for p in doc["located"] if p["kind"] == "fold")
    for got, want in zip(folds, DEAD_CENTRES, strict=True):  # SI: metres, the same points
        assert abs(got - want) < 1e-10


def test_a_grid_streams_every_point_row_by_row_as_the_function_returns_them():
    import mechsing

    xs, ys = "pose.x=0.6:1.4:0.2", "pose.y=0.8:1.6:0.2"
    doc = json.loads(_ok(["sweep", RPR, "--vary", xs, "--vary", ys, "--format", "json"]))
    assert len(doc["points"]) == 25
    assert [v["samples"] for v in doc["variables"]] == [5, 5]
    for k, p in enumerate(doc["points"]):  # rows of the second variable, each over the first
        j, i = divmod(k, 5)
        assert p["values"] == pytest.approx([0.6 + 0.2 * i, 0.8 + 0.2 * j], abs=1e-12)
    assert not list(_validator().iter_errors(doc))
    whole = mechsing.sweep(str(RPR), [xs, ys])
    assert doc == json.loads(json.dumps(whole.to_json()))


def test_output_file_format_from_its_extension(tmp_path):
    out = tmp_path / "sweep.csv"
    rc, stdout, err = run_cli(["sweep", SLIDER, "--vary", "P=0:1:0.25", "-o", out])
    assert rc == 0, err
    assert stdout == ""
    rows = list(csv.reader(out.open()))
    assert rows[0][0] == "kind" and sum(r[0] == "sample" for r in rows) == 5
    assert not list(tmp_path.glob("*.partial"))
    js = tmp_path / "sweep.out"
    rc, _, err = run_cli(["sweep", SLIDER, "--vary", "P=0:1:0.25", "-o", js, "--format", "json"])
    assert rc == 0, err
    assert len(json.loads(js.read_text())["points"]) == 5


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--vary", "Q=0:1:0.1"], ["--vary Q", "no joint named 'Q'", "the joints are A, B, C, P"]),
        (["--vary", "P=0:1"], ["--vary 'P=0:1'", "expected NAME=START:STOP:STEP"]),
        (["--vary", "P=0:x:1"], ["--vary 'P=0:x:1'", "must be numbers"]),
        (["--vary", "P=0:1:0"], ["--vary P", "STEP must be positive"]),
        (["--vary", "P=1:0:-0.1"], ["--vary P", "STEP must be positive", "START above STOP"]),
        (
            ["--vary", "P=0:1:0.1", "--vary", "A=0:1:0.1", "--vary", "B=0:1:0.1"],
            ["--vary is given 3 times"],
        ),
        (
            ["--vary", "P=0:1:0.1", "--precision", "exact"],
            ["--precision exact", "--precision auto"],
        ),
        (["--vary", "P=0:1:0.1", "--precision", "mp:5"], ["--precision"]),
        (["--vary", "P=0:1:0.1", "--from", "nope"], ["--from 'nope'", "reference, slider-4"]),
        (["--vary", "P=0:1:0.1", "--workers", "2"], ["--workers", "two --vary"]),
        (["--vary", "pose.q=0:1:0.1"], ["--vary pose.q", "pose.x"]),
    ],
)
def test_bad_input_exits_2_naming_the_file_and_the_option(argv, words):
    rc, out, err = run_cli(["sweep", SLIDER, *argv])
    assert rc == 2, (rc, err)
    assert out == "" and "Traceback" not in err
    assert str(SLIDER) in err
    for w in words:
        assert w in err, (w, err)


def test_options_argparse_refuses_exit_2():
    for argv in (["sweep", SLIDER], ["sweep", SLIDER, *PATH, "--workers", "0"]):
        with pytest.raises(SystemExit) as exc:
            run_cli(argv)
        assert exc.value.code == 2


def test_a_sweep_that_cannot_start_exits_3_and_writes_nothing(tmp_path):
    text = SLIDER.read_text().replace('slider-4: {P: "4/5"}', "far: {P: 3}")
    path = tmp_path / "far.yaml"
    path.write_text(text)
    out = tmp_path / "far.json"
    rc, stdout, err = run_cli(["sweep", path, "--vary", "P=0:1:0.1", "--from", "far", "-o", out])
    assert rc == 3, err
    assert "'far'" in err and str(path) in err and "short of the target" in err
    assert stdout == "" and not out.exists() and not list(tmp_path.glob("*.partial"))


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_progress_bar_on_a_terminal_unless_quiet(monkeypatch):
    import contextlib

    from mechsing.cli import main

    for quiet, shown in (([], True), (["--quiet"], False)):
        err = _Terminal()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            assert main(["sweep", str(SLIDER), "--vary", "P=0:1:0.25", *quiet]) == 0
        assert ("/5" in err.getvalue()) is shown, err.getvalue()
    rc, _, err_text = run_cli(["sweep", SLIDER, "--vary", "P=0:1:0.25"])  # not a terminal
    assert rc == 0 and err_text == ""


def test_schema_command_prints_the_sweep_schema():
    from mechsing.sweeps.schema import sweep_schema

    out = _ok(["schema", "--sweep"])
    assert json.loads(out) == json.loads(json.dumps(sweep_schema()))
    assert json.loads(out)["$id"] != json.loads(_ok(["schema"]))["$id"]


def test_the_command_as_users_run_it():
    rc, out, err = run_cli_subprocess(["sweep", SLIDER, "--vary", "P=1:2:0.1"], timeout=300)
    assert rc == 0, err
    assert out.startswith("slider-crank-slider-input: sweep (path) of P from 1 to 2 m by 0.1")
    assert "limit of travel" in out and "Traceback" not in err
    assert "sweep" in run_cli_subprocess(["--help"], timeout=300).out


def test_the_summary_does_not_depend_on_the_blas_kernel():
    """A four-bar's constraint test is 1/sqrt(2) at every sample (a planar loop's wrenches:
    its rank never changes), so its lowest sample is a tie that rounding breaks either way:
    the summary says it is constant, and the same text comes out whichever OpenBLAS kernel
    rounds (the dropped singular values, rounding themselves, are masked)."""
    argv = ["sweep", str(ROOT / "examples" / "fourbar.yaml"), "--vary", "A=0:360:1"]
    outs = []
    for core in (None, "Prescott"):
        env = {} if core is None else {"OPENBLAS_CORETYPE": core}
        run = run_cli_subprocess(argv, env=env)
        assert run.status == 0, run.err
        outs.append(re.sub(r"dropped singular value [-+.e0-9]+", "dropped ...", run.out))
    assert outs[0] == outs[1]
    line = next(x for x in outs[0].splitlines() if x.strip().startswith("constraint"))
    assert f"constant {1 / math.sqrt(2):.3g} over the reached samples" in line


def test_two_swept_joints_of_a_one_dof_linkage_are_refused_by_name():
    """The slider-crank has mobility 1 (one loop of four one-dof joints, planar: 4 - 3):
    two swept joints cannot both move freely; the message names the swept coordinates,
    not the file's inputs."""
    path = ROOT / "examples" / "slider_crank_slider_input.yaml"
    rc, _, err = run_cli(["sweep", path, "--vary", "B=0:1:0.5", "--vary", "C=0:1:0.5"])
    assert rc == 2
    assert "the coordinates swept (B, C) are 2 for a mechanism of mobility 1" in err
    assert "such as the file's inputs (P)" in err


def test_a_stop_note_names_the_variable_and_its_last_sample() -> None:
    """The slider-crank's dead centres (DEAD_CENTRES, closed form): from the reference, a
    path by 0.03 m stops at the last sample before each, and the note says the swept
    value it stopped at (not a bare length, read as a distance)."""
    rc, out, err = run_cli(["sweep", str(SLIDER), "--vary", "P=-4:4:0.03"])
    assert rc == 0, err
    samples = [-4 + 0.03 * k for k in range(267)]
    bottom = min(s for s in samples if s > DEAD_CENTRES[0])
    top = max(s for s in samples if s < DEAD_CENTRES[1])
    end = samples[-1]  # the last sample short of 4 m
    assert f"towards P = {end:.10g} m: stopped after P = {top:.10g} m:" in out
    assert f"towards P = -4 m: stopped after P = {bottom:.10g} m:" in out
