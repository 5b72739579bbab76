"""``mechsing exercise`` at its edges, through the command line: a sheet that agrees with the
key only near zero is wrong, the exit status says whether every answer is right, ``make``
writes nowhere but its own files (no link followed, never into the exercise's folder,
never over its template), and a template's expressions are bounded.

The expected grades come from the 2R arm's closed form det J = a1 a2 sin(B) (exercise 15),
never from mechsing: the hostile sheets add a term that is zero on part of the domain only
(``sqrt(u**2) + u`` is 0 where u < 0 and 2u where u > 0).
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
import yaml

from tests.cli import run_cli, run_cli_subprocess

ROOT = Path(__file__).resolve().parents[1]
EXERCISE_15 = ROOT / "examples" / "exercises" / "15-symbolic-2r-condition"


@pytest.fixture(scope="module")
def arm(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Exercise 15's variant for seed 3 (a1 = 0.7, a2 = 0.2: a1 a2 = 7/50)."""
    out = tmp_path_factory.mktemp("arm") / "arm"
    run = run_cli(["exercise", "make", "15", "--seed", 3, "-o", out, "--quiet"])
    assert run.status == 0, run.err
    numbers = yaml.safe_load((out / "variant-01" / "key.yaml").read_text(encoding="utf-8"))
    assert numbers["numbers"]["a1"] == "0.7" and numbers["numbers"]["a2"] == "0.2"
    return out / "variant-01"


def _check(tmp_path: Path, key: Path, answers: dict) -> tuple[int, dict]:
    sheet = tmp_path / "sheet.yaml"
    sheet.write_text(yaml.safe_dump({"answers": answers}), encoding="utf-8")
    run = run_cli(["exercise", "check", sheet, "--key", key, "--format", "json"])
    return run.status, json.loads(run.out)


def _results(got: dict) -> dict[str, str]:
    return {q["id"]: q["result"] for q in got["questions"]}


def test_a_formula_that_agrees_near_zero_only_is_wrong(arm: Path, tmp_path: Path) -> None:
    # B over a period: the extra term is 2*(B**2 - 6) for |B| > sqrt(6) = 2.449 (< pi)
    # a1 a positive length: the extra term is 2*(a1 - 3) for a1 > 3 m
    status, got = _check(
        tmp_path,
        arm / "key.yaml",
        {
            "condition": "0.14*sin(B) + sqrt((B**2 - 6)**2) + (B**2 - 6)",
            "symbolic": "a1*a2*sin(B) + sqrt((a1 - 3)**2) + (a1 - 3)",
        },
    )
    assert _results(got)["condition"] == "wrong" and _results(got)["symbolic"] == "wrong"
    notes = {q["id"]: q["note"] for q in got["questions"]}
    assert "differs from the expected formula at" in notes["condition"]
    assert status == 1
    # the same formula written otherwise is still right: a double angle, the lengths
    # through sqrt of their squares (they are positive), a decimal for 7/50
    status, got = _check(
        tmp_path,
        arm / "key.yaml",
        {
            "condition": "0.28*sin(B/2)*cos(B/2)",
            "symbolic": "sqrt(a1**2)*a2*(sin(B)*cos(B)**2 + sin(B)**3)",
            "bent_factor": "sin(2*pi/9)",
            "folded_singular": "yes",
        },
    )
    assert set(_results(got).values()) == {"right"}, got
    assert status == 0


def test_the_relative_test_sees_small_differences_of_small_formulas(
    arm: Path, tmp_path: Path
) -> None:
    """a1*a2*sin(B) is 1e-8 at a1 = a2 = 1e-4 m: adding 1e-10 changes it by 1 %."""
    _, got = _check(tmp_path, arm / "key.yaml", {"symbolic": "a1*a2*sin(B) + 1e-10"})
    assert _results(got)["symbolic"] == "wrong"
    _, got = _check(tmp_path, arm / "key.yaml", {"symbolic": "a1*a2*sin(B)*(1 + 1e-13)"})
    assert _results(got)["symbolic"] == "right"


def test_a_condition_up_to_a_factor(tmp_path: Path) -> None:
    """With up_to_factor, a constant multiple (either sign) is right, as the docs say; a
    multiple by a factor that is not constant is not, nor is a formula that is zero where
    the key is not."""
    folder = tmp_path / "factor"
    folder.mkdir()
    text = (EXERCISE_15 / "template.yaml").read_text(encoding="utf-8")
    text = text.replace(
        "    compute: {condition: {symbolic: [a1, a2]}}",
        "    up_to_factor: true\n    compute: {condition: {symbolic: [a1, a2]}}",
    )
    (folder / "template.yaml").write_text(text, encoding="utf-8")
    run = run_cli(["exercise", "make", folder, "--seed", 3, "-o", tmp_path / "out", "--quiet"])
    assert run.status == 0, run.err
    key = tmp_path / "out" / "variant-01" / "key.yaml"
    for sheet, want in (
        ("-3*a2*a1*sin(B)", "right"),
        ("a1*a2*2*sin(B/2)*cos(B/2)/5", "right"),
        ("a1*a2*sin(B)*(2 + cos(B))", "wrong"),
        ("a1*a2*sin(B) + sqrt((a2 - 2)**2) + (a2 - 2)", "wrong"),
        ("a1*a2*sin(B)*cos(B)", "wrong"),
    ):
        _, got = _check(tmp_path, key, {"symbolic": sheet})
        assert _results(got)["symbolic"] == want, (sheet, got)


def test_check_exits_0_only_when_every_answer_is_right(arm: Path, tmp_path: Path) -> None:
    right = {
        "condition": "7/50*sin(B)",
        "symbolic": "a1*a2*sin(B)",
        "bent_factor": "0.6428",  # sin(40 deg)
        "folded_singular": "true",
    }
    status, got = _check(tmp_path, arm / "key.yaml", right)
    assert status == 0 and got["right"] == 4
    status, got = _check(tmp_path, arm / "key.yaml", {**right, "folded_singular": "false"})
    assert status == 1 and got["wrong"] == 1
    status, got = _check(tmp_path, arm / "key.yaml", {**right, "bent_factor": None})
    assert status == 1 and got["missing"] == 1
    run = run_cli_subprocess(["exercise", "check", "--help"])
    assert "0 when every answer is right, 1 when one is wrong or missing" in " ".join(
        run.out.split()
    )


def _make(exercise: Path, out: Path, *extra: str) -> int:
    run = run_cli(["exercise", "make", exercise, "--seed", 3, "-o", out, "--quiet", *extra])
    return run.status


def test_make_follows_no_link_planted_in_the_output(tmp_path: Path) -> None:
    victim = tmp_path / "victim.txt"
    victim.write_text("mine\n", encoding="utf-8")
    victims = tmp_path / "victims"
    victims.mkdir()
    # a variant folder that is a link to another folder
    out = tmp_path / "o1"
    out.mkdir()
    (out / "variant-01").symlink_to(victims)
    assert _make(EXERCISE_15, out, "--force") == 2
    assert list(victims.iterdir()) == []
    # a key.yaml that is a link to a file: the link is replaced, the file is not
    out = tmp_path / "o2"
    (out / "variant-01").mkdir(parents=True)
    (out / "variant-01" / "key.yaml").symlink_to(victim)
    assert _make(EXERCISE_15, out, "--force") == 0
    assert victim.read_text(encoding="utf-8") == "mine\n"
    key = out / "variant-01" / "key.yaml"
    assert not key.is_symlink() and yaml.safe_load(key.read_text(encoding="utf-8"))["key"] == 1


def test_make_never_writes_over_the_template(tmp_path: Path) -> None:
    mine = tmp_path / "mine"
    mine.mkdir()
    template = (EXERCISE_15 / "template.yaml").read_bytes()
    (mine / "template.yaml").write_bytes(template)
    # a hard link to the template where a statement goes
    out = tmp_path / "out"
    (out / "variant-01").mkdir(parents=True)
    os.link(mine / "template.yaml", out / "variant-01" / "statement.md")
    assert _make(mine, out, "--force") == 2
    assert (mine / "template.yaml").read_bytes() == template
    # -o inside the exercise's folder (the docs: its folder is never written to)
    run = run_cli(["exercise", "make", mine, "--seed", 3, "-o", mine / "class"])
    assert run.status == 2 and "template's folder" in run.err
    assert sorted(p.name for p in mine.iterdir()) == ["template.yaml"]
    link = tmp_path / "into"
    link.symlink_to(mine)
    assert _make(mine, link / "class") == 2
    assert sorted(p.name for p in mine.iterdir()) == ["template.yaml"]


def test_a_template_with_a_huge_constraint_is_refused(tmp_path: Path) -> None:
    folder = tmp_path / "big"
    folder.mkdir()
    huge = " + ".join(["a1"] * 5000)
    text = (EXERCISE_15 / "template.yaml").read_text(encoding="utf-8")
    text = text.replace('holds: "a1 >= a2"', f'holds: "{huge} >= a2"')
    (folder / "template.yaml").write_text(text, encoding="utf-8")
    run = run_cli(["exercise", "make", folder, "--seed", 1, "-o", tmp_path / "out"])
    assert run.status == 2, run.err
    assert "constraints[0]" in run.err and "too long" in run.err
    assert not (tmp_path / "out").exists()
