"""``mechsing exercise``: variants of the bundled exercises with answer keys, and grading.

The keys are computed by mechsing; these tests check them against the exercises' closed
forms, worked here from each variant's mechanism file (the law of cosines for the
four-bar's limit positions, the slider-crank's dead centres, det J = a1 a2 sin B for the
2R arm, the 3-RPR's leg lengths and concurrent leg lines), never against mechsing.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import sympy
import yaml

from tests.cli import run_cli

ROOT = Path(__file__).resolve().parents[1]
EXERCISES = ROOT / "examples" / "exercises"
TEMPLATES = sorted(EXERCISES.glob("*/template.yaml"))


def _make(out: Path, exercise: str, n: int, seed: int, *extra: str) -> list[Path]:
    run = run_cli(
        ["exercise", "make", exercise, "--variants", n, "--seed", seed, "-o", out, *extra]
    )
    assert run.status == 0, run.err
    return sorted(out.glob("variant-*"))


def _params(folder: Path) -> dict[str, float]:
    """The variant's parameters, evaluated by sympy from the file's text (in order)."""
    doc = yaml.safe_load((folder / "mechanism.yaml").read_text(encoding="utf-8"))
    values: dict[str, sympy.Expr] = {}
    for name, text in doc["parameters"].items():
        values[name] = sympy.sympify(str(text), locals=dict(values))
    return {k: float(v) for k, v in values.items()}


def _key(folder: Path) -> dict[str, dict]:
    doc = yaml.safe_load((folder / "key.yaml").read_text(encoding="utf-8"))
    return {q["id"]: q for q in doc["questions"]}


@pytest.fixture(scope="module")
def made(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[Path]]:
    base = tmp_path_factory.mktemp("variants")
    return {
        name: _make(base / name, name, 3, 11)
        for name in ("12", "07-slider-crank-dead-centres", "15", "10-3rpr-type2", "13", "14")
    }


def test_every_template_makes_a_variant(tmp_path: Path) -> None:
    assert len(TEMPLATES) >= 7, [t.parent.name for t in TEMPLATES]
    for t in TEMPLATES:
        (folder,) = _make(tmp_path / t.parent.name, str(t.parent), 1, 0)
        names = {p.name for p in folder.iterdir()}
        assert names == {"statement.md", "mechanism.yaml", "sheet.yaml", "key.yaml", "key.md"}
        statement = (folder / "statement.md").read_text(encoding="utf-8")
        assert "{" not in statement.replace("{pose", ""), (t, statement)  # every placeholder filled
        key = _key(folder)
        sheet = yaml.safe_load((folder / "sheet.yaml").read_text(encoding="utf-8"))
        assert list(sheet["answers"]) == list(key), t


def test_the_same_seed_gives_the_same_files(tmp_path: Path) -> None:
    one = _make(tmp_path / "one", "12", 2, 42)
    two = _make(tmp_path / "two", "12", 2, 42)
    other = _make(tmp_path / "other", "12", 2, 43)
    for a, b in zip(one, two, strict=True):
        for f in sorted(a.iterdir()):
            assert f.read_bytes() == (b / f.name).read_bytes(), f
    assert (one[0] / "mechanism.yaml").read_bytes() != (other[0] / "mechanism.yaml").read_bytes()


def test_variants_differ_from_each_other(made: dict[str, list[Path]]) -> None:
    for folders in made.values():
        texts = {(f / "mechanism.yaml").read_text(encoding="utf-8") for f in folders}
        assert len(texts) == len(folders)


def test_crank_rocker_limits_by_the_law_of_cosines(made: dict[str, list[Path]]) -> None:
    for folder in made["12"]:
        p = _params(folder)
        a, b, c, d = p["a"], p["b"], p["c"], p["d"]
        s, longest = min(a, b, c, d), max(a, b, c, d)
        assert s == a and s + longest < a + b + c + d - s - longest  # Grashof, crank shortest
        stretched = math.acos(((a + b) ** 2 + d**2 - c**2) / (2 * (a + b) * d))
        folded = math.pi + math.acos(((b - a) ** 2 + d**2 - c**2) / (2 * (b - a) * d))
        key = _key(folder)
        assert key["stretched"]["unit"] == "deg"
        assert key["stretched"]["value"] == pytest.approx(math.degrees(stretched), abs=1e-6)
        assert key["folded"]["value"] == pytest.approx(math.degrees(folded), abs=1e-6)
        assert "input" in key["kind"]["value"]  # Gosselin-Angeles type I


def test_slider_crank_dead_centres_in_closed_form(made: dict[str, list[Path]]) -> None:
    for folder in made["07-slider-crank-dead-centres"]:
        p = _params(folder)
        r, l, e = p["r"], p["l"], p["e"]
        x0 = math.sqrt(l**2 - (e + r) ** 2)  # the pin at the reference, crank pointing down
        outer = math.sqrt((l + r) ** 2 - e**2) - x0
        inner = math.sqrt((l - r) ** 2 - e**2) - x0
        assert -4 < inner < 0 < outer < 4  # inside the swept stroke
        key = _key(folder)
        assert key["outer"]["value"] == pytest.approx(outer, abs=1e-7)
        assert key["inner"]["value"] == pytest.approx(inner, abs=1e-7)
        assert "output" in key["outer_classes"]["value"]  # the slider locks, the crank turns


def test_2r_condition_is_a1_a2_sin_b(made: dict[str, list[Path]]) -> None:
    a1, a2, B = sympy.symbols("a1 a2 B", real=True)
    for folder in made["15"]:
        p = _params(folder)
        key = _key(folder)
        numeric = sympy.sympify(key["condition"]["value"], locals={"B": B})
        want = sympy.Rational(str(p["a1"])) * sympy.Rational(str(p["a2"])) * sympy.sin(B)
        assert sympy.simplify(numeric - want) == 0, key["condition"]["value"]
        symbolic = sympy.sympify(key["symbolic"]["value"], locals={"a1": a1, "a2": a2, "B": B})
        assert sympy.simplify(symbolic - a1 * a2 * sympy.sin(B)) == 0
        assert key["bent_factor"]["value"] == pytest.approx(
            math.sin(math.radians(p["bend"])), abs=1e-12
        )
        assert key["folded_singular"]["value"] is True  # sin(pi) = 0


def test_3rpr_legs_and_type_ii_from_the_leg_lines(made: dict[str, list[Path]]) -> None:
    for folder in made["10-3rpr-type2"]:
        p = _params(folder)
        base = np.array([[0.0, 0.0], [p["b2x"], 0.0], [p["b3x"], p["b3y"]]])
        ref = np.array([[p["r1x"], p["r1y"]], [p["r2x"], p["r2y"]], [p["r3x"], p["r3y"]]])
        doc = yaml.safe_load((folder / "mechanism.yaml").read_text(encoding="utf-8"))
        pose = doc["configurations"]["concurrent"]["pose"]
        assert pose["angle"] == "2*atan(u)" and pose["position"] == ["gx", "gy", 0]
        phi = 2 * math.atan(p["u"])
        rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        centre = ref.mean(axis=0)  # the platform's reference point: its pivots' centroid
        moved = np.array([p["gx"], p["gy"]]) + (ref - centre) @ rot.T
        legs = np.linalg.norm(moved - base, axis=1) - np.linalg.norm(ref - base, axis=1)
        key = _key(folder)
        for i in range(3):
            assert key[f"P{i + 1}"]["value"] == pytest.approx(legs[i], abs=1e-9)
        # the leg lines n . x = n . A_i (n normal to the leg) meet in one point
        d = (moved - base) / np.linalg.norm(moved - base, axis=1)[:, None]
        lines = np.column_stack([-d[:, 1], d[:, 0], d[:, 1] * base[:, 0] - d[:, 0] * base[:, 1]])
        assert abs(np.linalg.det(lines)) < 1e-12
        assert set(key["classes"]["value"]) == {"output", "impossible-input"}


def test_double_rocker_limits_by_the_law_of_cosines(made: dict[str, list[Path]]) -> None:
    for folder in made["13"]:
        p = _params(folder)
        a, b, c, d = p["a"], p["b"], p["c"], p["d"]
        s, longest = min(a, b, c, d), max(a, b, c, d)
        assert s + longest > a + b + c + d - s - longest  # non-Grashof
        upper = math.acos((a**2 + d**2 - (b + c) ** 2) / (2 * a * d))  # B, C, D in line
        stop = math.acos(((a + b) ** 2 + d**2 - c**2) / (2 * (a + b) * d))  # A, B, C in line
        key = _key(folder)
        assert key["upper"]["value"] == pytest.approx(upper, abs=1e-7)
        assert key["lower"]["value"] == pytest.approx(-upper, abs=1e-7)
        assert key["output_stop"]["value"] == pytest.approx(stop, abs=1e-7)


def test_elbow_null_rates_from_the_lengths(made: dict[str, list[Path]]) -> None:
    """Stretched, J2, J3, J4 sit on one line at 0, a2, a2 + a3 along it: the rates with
    w2 + w3 + w4 = 0 and a2 w3 + (a2 + a3) w4 = 0 move nothing."""
    for folder in made["14"]:
        p = _params(folder)
        a2, a3 = p["a2"], p["a3"]
        key = _key(folder)
        want = np.array([0, a3 / (a2 + a3), -1, a2 / (a2 + a3), 0, 0])
        got = np.array(key["null_rates"]["value"])
        assert min(np.abs(got - want).max(), np.abs(got + want).max()) < 1e-9
        assert key["rank"]["value"] == 5 and key["regular_singular"]["value"] is False


# -- grading --------------------------------------------------------------------------


def _check(sheet: Path, key: Path, fmt: str = "json") -> tuple[int, dict | str]:
    run = run_cli(["exercise", "check", sheet, "--key", key, "--format", fmt])
    return run.status, (
        json.loads(run.out) if fmt == "json" and run.status in (0, 1) else run.out + run.err
    )


def _write(path: Path, answers: dict) -> Path:
    path.write_text(yaml.safe_dump({"student": "A. Student", "answers": answers}), encoding="utf-8")
    return path


def test_grading_a_right_a_wrong_and_an_incomplete_sheet(
    made: dict[str, list[Path]], tmp_path: Path
) -> None:
    folder = made["12"][0]
    p = _params(folder)
    a, b, c, d = p["a"], p["b"], p["c"], p["d"]
    stretched = math.acos(((a + b) ** 2 + d**2 - c**2) / (2 * (a + b) * d))
    folded = math.pi + math.acos(((b - a) ** 2 + d**2 - c**2) / (2 * (b - a) * d))
    classes = ", ".join(_key(folder)["kind"]["value"])
    right = _write(
        tmp_path / "right.yaml",
        {
            "stretched": f"{stretched:.6f} rad",
            "folded": round(math.degrees(folded), 3),
            "kind": classes,
        },
    )
    wrong = _write(
        tmp_path / "wrong.yaml",
        {"stretched": f"{math.degrees(stretched) + 1:.3f} deg", "folded": "3 m", "kind": "output"},
    )
    partial = _write(tmp_path / "partial.yaml", {"stretched": f"{math.degrees(stretched):.3f}°"})
    key = folder / "key.yaml"
    status, got = _check(right, key)
    assert status == 0 and [q["result"] for q in got["questions"]] == ["right"] * 3
    assert got["right"] == 3 and got["total"] == 3
    status, got = _check(wrong, key)
    assert status == 1 and [q["result"] for q in got["questions"]] == ["wrong"] * 3
    assert "angle" in got["questions"][1]["note"]  # a length given for an angle
    assert got["questions"][0]["expected"].startswith(f"{math.degrees(stretched):.6g} deg")
    status, got = _check(partial, key)
    assert status == 1
    assert [q["result"] for q in got["questions"]] == ["right", "missing", "missing"]
    status, text = _check(partial, key, "text")
    assert status == 1 and "missing" in text and "1 of 3 right" in text


def test_grading_formulas_written_differently(made: dict[str, list[Path]], tmp_path: Path) -> None:
    folder = made["15"][0]
    p = _params(folder)
    product = sympy.Rational(str(p["a1"])) * sympy.Rational(str(p["a2"]))
    sheet = _write(
        tmp_path / "formulas.yaml",
        {
            "condition": f"2*{product}*sin(B/2)*cos(B/2)",  # sin B as a double angle
            "symbolic": "sin(B)*a2*a1",
            "bent_factor": f"sin({p['bend']}*pi/180)",
            "folded_singular": "yes",
        },
    )
    status, got = _check(sheet, folder / "key.yaml")
    assert status == 0 and [q["result"] for q in got["questions"]] == ["right"] * 4, got
    wrong = _write(
        tmp_path / "wrongformulas.yaml",
        {"condition": f"{product}*cos(B)", "symbolic": "a1*sin(B)", "folded_singular": False},
    )
    status, got = _check(wrong, folder / "key.yaml")
    assert [q["result"] for q in got["questions"]] == ["wrong", "wrong", "missing", "wrong"]


def test_same_formula_at_random_points_and_up_to_a_factor() -> None:
    from mechsing.exercises.grade import same_formula

    # not equal as expressions (sympy says so); equal to the relative tolerance at every point
    assert same_formula("a1*a2*sin(B)", "a1*a2*sin(B)*(1 + 1e-12)", 1e-9)[0]
    assert not same_formula("a1*a2*sin(B)", "a1*a2*sin(B)*(1 + 1e-6)", 1e-9)[0]
    # the test is relative: 1e-12 is not small beside a1*a2*sin(B) at a1 = a2 = 1e-4 m
    assert not same_formula("a1*a2*sin(B)", "a1*a2*sin(B) + 1e-12", 1e-9)[0]
    assert same_formula("a1*a2*sin(B)", "-2*a1*a2*sin(B)", 1e-9, up_to_factor=True)[0]
    assert not same_formula("a1*a2*sin(B)", "a1*a2*cos(B)", 1e-9, up_to_factor=True)[0]
    ok, why = same_formula("a1*sin(B)", "a1*sin(C)", 1e-9)
    assert not ok and "C" in why


def test_unreadable_sheet_or_key_exits_2(made: dict[str, list[Path]], tmp_path: Path) -> None:
    key = made["12"][0] / "key.yaml"
    bad = tmp_path / "bad.yaml"
    bad.write_text("answers: [1, 2\n", encoding="utf-8")
    run = run_cli(["exercise", "check", bad, "--key", key])
    assert run.status == 2 and "bad.yaml" in run.err
    run = run_cli(["exercise", "check", bad, "--key", tmp_path / "nokey.yaml"])
    assert run.status == 2 and "nokey.yaml" in run.err
    run = run_cli(["exercise", "check", key, "--key", made["12"][0] / "mechanism.yaml"])
    assert run.status == 2 and "not an answer key" in run.err
    bomb = tmp_path / "bomb.yaml"
    bomb.write_text(
        "a: &a [1, 1, 1]\nb: &b [*a, *a, *a]\nanswers: {stretched: *b}\n", encoding="utf-8"
    )
    run = run_cli(["exercise", "check", bomb, "--key", key])
    assert run.status == 2 and "aliases" in run.err
    edited = yaml.safe_load(key.read_text(encoding="utf-8"))
    edited["questions"][0]["value"] = "forty"  # a key edited by hand
    (tmp_path / "edited.yaml").write_text(yaml.safe_dump(edited), encoding="utf-8")
    run = run_cli(["exercise", "check", key, "--key", tmp_path / "edited.yaml"])
    assert run.status == 2 and "'forty' is not a number" in run.err


def test_a_template_that_cannot_be_met_is_refused(tmp_path: Path) -> None:
    text = (EXERCISES / "12-crank-rocker-sweep" / "template.yaml").read_text(encoding="utf-8")
    text = text.replace('holds: "a < min(b, c, d)"', 'holds: "a > 2 * max(b, c, d)"')
    folder = tmp_path / "impossible"
    folder.mkdir()
    (folder / "template.yaml").write_text(text, encoding="utf-8")
    run = run_cli(
        ["exercise", "make", folder, "--variants", 1, "--seed", 0, "-o", tmp_path / "out"]
    )
    assert run.status == 2
    assert "the crank is the shortest link" in run.err and "failed most" in run.err
    assert not (tmp_path / "out").exists()


def test_the_exercises_own_numbers_are_never_a_variant(tmp_path: Path) -> None:
    """A variant with the bundled exercise's numbers would come with a published answer."""
    text = (EXERCISES / "15-symbolic-2r-condition" / "template.yaml").read_text(encoding="utf-8")
    doc = yaml.safe_load(text)
    own = yaml.safe_load(doc["mechanism"])["parameters"]
    for name in doc["vary"]:  # each range a single point but one: two grid points in all
        doc["vary"][name] = {"from": own[name], "to": own[name], "step": 1}
    doc["vary"]["turn"]["to"] = own["turn"] + 1
    folder = tmp_path / "own"
    folder.mkdir()
    (folder / "template.yaml").write_text(yaml.safe_dump(doc, sort_keys=False), encoding="utf-8")
    (made,) = _make(tmp_path / "out", str(folder), 1, 0)
    numbers = yaml.safe_load((made / "key.yaml").read_text(encoding="utf-8"))["numbers"]
    assert float(numbers["turn"]) == own["turn"] + 1
    doc["vary"]["turn"]["to"] = own["turn"]  # the exercise's own numbers only: refused
    (folder / "template.yaml").write_text(yaml.safe_dump(doc, sort_keys=False), encoding="utf-8")
    run = run_cli(["exercise", "make", folder, "--seed", 0, "-o", tmp_path / "o2"])
    assert run.status == 2 and "failed most: numbers other than the template's own" in run.err


def test_a_question_mechsing_cannot_answer_is_refused(tmp_path: Path) -> None:
    text = (EXERCISES / "15-symbolic-2r-condition" / "template.yaml").read_text(encoding="utf-8")
    text = text.replace("path: configurations.0.singular", "path: configurations.0.nothing")
    folder = tmp_path / "unanswered"
    folder.mkdir()
    (folder / "template.yaml").write_text(text, encoding="utf-8")
    run = run_cli(["exercise", "make", folder, "--seed", 0, "-o", tmp_path / "out"])
    assert run.status == 2
    assert "could not answer" in run.err and "folded_singular" in run.err, run.err


def test_a_non_empty_directory_needs_force(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine", encoding="utf-8")
    run = run_cli(["exercise", "make", "12", "--seed", 1, "-o", out])
    assert run.status == 2 and "--force" in run.err
    assert [p.name for p in out.iterdir()] == ["notes.txt"]
    (folder,) = _make(out, "12", 1, 1, "--force")
    assert (out / "notes.txt").read_text(encoding="utf-8") == "mine" and folder.is_dir()
    # never into the template's own folder, even with --force
    mine = tmp_path / "mine"
    mine.mkdir()
    template = (EXERCISES / "15-symbolic-2r-condition" / "template.yaml").read_bytes()
    (mine / "template.yaml").write_bytes(template)
    run = run_cli(["exercise", "make", mine, "--seed", 1, "-o", mine, "--force"])
    assert run.status == 2 and "template's folder" in run.err
    assert [p.name for p in mine.iterdir()] == ["template.yaml"]
    assert (mine / "template.yaml").read_bytes() == template


def test_list_shows_which_exercises_have_templates() -> None:
    run = run_cli(["exercise", "list", "--format", "json"])
    assert run.status == 0
    rows = {r["exercise"]: r["template"] for r in json.loads(run.out)["exercises"]}
    assert set(rows) == {p.name for p in EXERCISES.iterdir() if (p / "README.md").exists()}
    assert {n for n, t in rows.items() if t} == {t.parent.name for t in TEMPLATES}


def test_constraints_and_quantities_are_parsed_not_evaluated() -> None:
    from mechsing.errors import UserError
    from mechsing.exercises.draw import evaluate
    from mechsing.exercises.units import parse_quantity

    assert evaluate("a + max(b, 2) < 3 and not a > 1", {"a": 0.5, "b": 1.0}) is True
    assert evaluate("0 < a < 1 < b", {"a": 0.5, "b": 1.0}) is False  # chained
    for hostile in ("__import__('os')", "a.real", "[a]", "a if a else 1"):
        with pytest.raises(UserError):
            evaluate(hostile, {"a": 1.0})
    assert parse_quantity("33.1 deg") == (33.1, "deg")
    assert parse_quantity("12mm") == (12.0, "mm")
    assert parse_quantity("2*pi") == (pytest.approx(2 * math.pi), None)
    assert parse_quantity("pi/6 rad") == (pytest.approx(math.pi / 6), "rad")
    with pytest.raises(UserError, match="unknown unit"):
        parse_quantity("3 furlongs")
