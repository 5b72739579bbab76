"""The exercises of examples/exercises/ check out: mechsing's output agrees with every answer
worked by hand, and the worked answers state the numbers that are checked.

Each exercise is a folder ``examples/exercises/NN-name/`` with a ``README.md`` (statement,
questions, worked answer), its mechanism file(s) and ``answers.yaml``::

    answers:
      - id: finite                     # a name, written in the README as `finite = 1`
        command: [analyze, mechanism.yaml, --config, reference, --format, json]
        path: configurations.name=reference.mobility.finite
        expected: "1"                  # the README's text for it
        tol: 1e-9                      # absolute, for numbers (default 1e-9)
        unit: deg                      # optional: the JSON's radians shown in degrees

* ``command`` is a mechsing command line run in the exercise's folder (``--format json``);
* ``path`` walks the JSON: a key, a list index, ``key=value`` (the first list item whose
  ``key`` is ``value``) or ``*`` (every item: the answer is then a set);
* ``expected`` is an exact expression (``8/5``, ``2*atan(1/3)``, ``sqrt(2)/2 - 1``), a word
  (``G``, ``true``) or words separated by commas (a set, e.g. ``input, serial``; a single
  word against a ``*`` path means "one of them"); with
  ``up_to_sign: true`` a vector answer is checked up to its sign (a lost twist's direction).

The worked answer writes each checked answer as a code span `` `ID = EXPECTED` ``; the test
reads those spans, so the prose and the checks cannot drift: every id must be stated in
the README, with exactly the text of ``expected``.
"""

from __future__ import annotations

import functools
import json
import math
import os
import re
from pathlib import Path
from typing import Any

import pytest
import sympy
import yaml

from mechsing.exercises.paths import walk as _walk
from tests.cli import run_cli

ROOT = Path(__file__).resolve().parents[1]
EXERCISES = ROOT / "examples" / "exercises"
FOLDERS = sorted(p for p in EXERCISES.iterdir() if p.is_dir() and (p / "README.md").exists())

_SPAN = re.compile(r"`([A-Za-z_][A-Za-z0-9_]*) = ([^`]+)`")
_NAMES = {n: getattr(sympy, n) for n in ("sqrt", "sin", "cos", "tan", "asin", "acos", "atan")}
_NAMES.update(pi=sympy.pi, atan2=sympy.atan2)


def _answers(folder: Path) -> list[dict[str, Any]]:
    return yaml.safe_load((folder / "answers.yaml").read_text(encoding="utf-8"))["answers"]


def _value(text: str) -> Any:
    """An expected answer: a float (exact expression), a bool, a word, or a set of words."""
    t = str(text).strip()
    if t in ("true", "false"):
        return t == "true"
    if t.startswith("[") and t.endswith("]"):
        return [_value(x) for x in t[1:-1].split(",")]
    if "," in t:
        return {x.strip() for x in t.split(",")}
    if re.fullmatch(r"[A-Za-z_][\w-]*", t) and t != "pi":
        return t  # a word (a class, a subgroup type): never a sympy symbol such as E or S
    try:
        return float(sympy.sympify(t, locals=_NAMES, rational=True).evalf(30))
    except (sympy.SympifyError, TypeError, ValueError, AttributeError, SyntaxError):
        return t


@functools.cache
def _run(folder: Path, argv: tuple[str, ...]) -> Any:
    here = os.getcwd()
    os.chdir(folder)
    try:
        run = run_cli(list(argv))
    finally:
        os.chdir(here)
    assert run.status == 0, (folder.name, argv, run.err)
    return json.loads(run.out)


def _agrees(expected: Any, got: Any, answer: dict[str, Any]) -> bool:
    tol = float(answer.get("tol", 1e-9))
    scale = 180 / math.pi if answer.get("unit") == "deg" else 1.0
    if isinstance(expected, bool) or isinstance(got, bool):
        return expected == got
    if isinstance(expected, float):
        if isinstance(got, list) and len(got) == 1:
            got = got[0]
        return isinstance(got, (int, float)) and abs(got * scale - expected) <= tol
    if isinstance(expected, list):
        if not isinstance(got, list) or len(got) != len(expected):
            return False
        signs = (1, -1) if answer.get("up_to_sign") else (1,)
        return any(
            all(abs(s * g * scale - e) <= tol for g, e in zip(got, expected, strict=True))
            for s in signs
        )
    if isinstance(expected, set):
        return isinstance(got, (set, list)) and {str(x) for x in got} == expected
    if isinstance(got, (set, list)):  # one word against several: it is one of them
        return expected in {str(x) for x in got}
    if str(got) != expected and isinstance(got, str) and any(c in expected for c in "*/()"):
        return _same_formula(expected, got)
    return str(got) == expected


def _same_formula(expected: str, got: str) -> bool:
    """Two formulas (a symbolic condition) equal as expressions, whatever their order."""
    try:
        a = sympy.sympify(expected, rational=True)
        b = sympy.sympify(got, rational=True)
    except (sympy.SympifyError, TypeError, SyntaxError):
        return False
    return sympy.simplify(a - b) == 0


def test_there_are_enough_exercises() -> None:
    assert len(FOLDERS) >= 12, [f.name for f in FOLDERS]


def test_the_path_language() -> None:
    data = {"c": [{"name": "a", "x": [1.5]}, {"name": "b", "s": [{"k": "u"}, {"k": "v"}]}]}
    assert _walk(data, "c.name=a.x.0") == 1.5
    assert _walk(data, "c.1.s.*.k") == {"u", "v"}
    assert _value("8/5") == pytest.approx(1.6) and _value("input, serial") == {"input", "serial"}
    assert _value("G") == "G" and _value("[0, -1, 0]") == [0.0, -1.0, 0.0]


@pytest.mark.parametrize("folder", FOLDERS, ids=[f.name for f in FOLDERS])
def test_readme_states_the_checked_answers(folder: Path) -> None:
    """Every checked answer is written in the worked answer with the text answers.yaml checks."""
    text = (folder / "README.md").read_text(encoding="utf-8")
    for part in ("## Statement", "## Questions", "## Worked answer"):
        assert part in text, f"{folder.name}: no {part!r} section"
    stated: dict[str, list[str]] = {}
    for name, value in _SPAN.findall(text):
        stated.setdefault(name, []).append(value.strip())
    for answer in _answers(folder):
        aid, want = answer["id"], str(answer["expected"]).strip()
        assert aid in stated, f"{folder.name}: `{aid} = ...` is not stated in README.md"
        assert want in stated[aid], (
            f"{folder.name}: README says {aid} = {stated[aid]}, answers.yaml {want}"
        )


@pytest.mark.parametrize("folder", FOLDERS, ids=[f.name for f in FOLDERS])
def test_mechsing_agrees_with_the_worked_answer(folder: Path) -> None:
    for answer in _answers(folder):
        data = _run(folder, tuple(str(a) for a in answer["command"]))
        got = _walk(data, answer["path"])
        want = _value(answer["expected"])
        assert _agrees(want, got, answer), (
            f"{folder.name}: {answer['id']}: expected {want}, mechsing {got}"
        )


@pytest.mark.parametrize("folder", FOLDERS, ids=[f.name for f in FOLDERS])
def test_mechanism_files_pass_the_schema(folder: Path) -> None:
    """A student's editor checks the exercise's file against the published schema."""
    jsonschema = pytest.importorskip("jsonschema")
    from mechsing.model.schema import mechanism_schema

    validator = jsonschema.Draft202012Validator(mechanism_schema())
    for path in sorted(folder.glob("*.yaml")):
        if path.name in ("answers.yaml", "template.yaml"):
            continue  # the checked answers, and the variants' template (tests/test_exercise_variants.py)
        doc = yaml.safe_load(path.read_text(encoding="utf-8"))
        assert not [e.message for e in validator.iter_errors(doc)], path.name


def test_the_index_lists_every_exercise() -> None:
    index = (EXERCISES / "README.md").read_text(encoding="utf-8")
    for folder in FOLDERS:
        assert f"]({folder.name}/README.md)" in index, folder.name
