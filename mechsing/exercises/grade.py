"""Grading a student's answer sheet against an answer key.

A sheet (YAML)::

    student: Ada Lovelace        # optional
    answers:
      stretched: 33.1 deg        # a number, with its unit or in the key's unit
      kind: input                # a word, or class names (a list, or separated by commas)
      condition: a2*a1*sin(B)    # a formula: any form equal to the key's

Each question of the key is ``right``, ``wrong`` or ``missing`` (no entry, or empty).
Numbers are converted to SI units before they are compared, within the key's tolerance
(in the key's unit); class names are compared as sets; a formula is right when sympy
proves it equal to the key's, or, failing that, when the two agree at points drawn over
the whole domain of each variable to the key's tolerance (relative; default
:data:`~mechsing.exercises.grade.EXERCISE_FORMULA_RTOL`), up to a constant factor when
the key says ``up_to_factor: true`` (a condition ``det J = 0`` is one up to a factor):
:mod:`mechsing.exercises.formulas`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from mechsing.errors import UserError
from mechsing.exercises.formulas import DOMAINS, same_formula
from mechsing.exercises.template import KINDS
from mechsing.exercises.units import UNITS, parse_quantity, to_si
from mechsing.singularity.findings import BRANCH_CLASSES, IMPOSSIBLE_CLASSES, MOTION_CLASSES

#: a student's formula agrees with the key's at a point when they differ there by at most
#: this times the larger of their values (a relative test); a key's question may set its
#: own ``tol``
EXERCISE_FORMULA_RTOL = 1e-9

__all__ = [
    "CLASSES",
    "KEY_VERSION",
    "expected_text",
    "Grade",
    "Mark",
    "grade",
    "read_key",
    "read_sheet",
    "same_formula",
]

#: the classes of a finding (the JSON contract's ``class`` values)
CLASSES = (
    "serial",
    *BRANCH_CLASSES,
    *MOTION_CLASSES,
    *IMPOSSIBLE_CLASSES,
    "constraint",
    "undecided",
)
#: the version of the key format (``key: 1``)
KEY_VERSION = 1
#: largest sheet or key read (bytes)
MAX_FILE_BYTES = 1_000_000


@dataclass(frozen=True)
class Mark:
    """The grade of one question."""

    id: str
    result: str  # right, wrong or missing
    expected: str
    given: str | None = None
    note: str = ""
    key: dict[str, Any] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "result": self.result,
            "expected": self.expected,
            "given": self.given,
            "note": self.note,
            "kind": self.key.get("kind"),
            "value": self.key.get("value"),
            "unit": self.key.get("unit"),
            "tol": self.key.get("tol"),
        }


@dataclass(frozen=True)
class Grade:
    """The grades of a sheet: one mark per question of the key, in the key's order."""

    sheet: str
    key: str
    exercise: str
    variant: Any
    marks: tuple[Mark, ...]
    extra: tuple[str, ...] = field(default=())

    def count(self, result: str) -> int:
        return sum(m.result == result for m in self.marks)

    def to_json(self) -> dict[str, Any]:
        return {
            "sheet": self.sheet,
            "key": self.key,
            "exercise": self.exercise,
            "variant": self.variant,
            "questions": [m.to_json() for m in self.marks],
            "right": self.count("right"),
            "wrong": self.count("wrong"),
            "missing": self.count("missing"),
            "total": len(self.marks),
            "not_asked": list(self.extra),
        }

    def text(self) -> str:
        lines = [f"{self.sheet} against {self.key} ({self.exercise}, variant {self.variant})"]
        width = max((len(m.id) for m in self.marks), default=2)
        for m in self.marks:
            given = f"given {m.given}; " if m.given is not None else ""
            note = f" ({m.note})" if m.note else ""
            lines.append(f"  {m.id:<{width}}  {m.result:<7}  {given}expected {m.expected}{note}")
        if self.extra:
            lines.append(f"  not questions of the key (ignored): {', '.join(self.extra)}")
        lines.append(
            f"{self.count('right')} of {len(self.marks)} right, {self.count('wrong')} wrong, "
            f"{self.count('missing')} missing"
        )
        return "\n".join(lines)


def _read_yaml(path: str | Path, what: str) -> dict[str, Any]:
    p = Path(path)
    try:
        if p.stat().st_size > MAX_FILE_BYTES:
            raise UserError(f"{p}: the {what} is larger than {MAX_FILE_BYTES} bytes")
        text = p.read_text(encoding="utf-8")
        # an alias can make a small file expand to gigabytes once printed: a sheet has none
        if any(isinstance(e, yaml.AliasEvent) for e in yaml.parse(text, Loader=yaml.SafeLoader)):
            raise UserError(f"{p}: the {what} uses YAML aliases (*name); write every answer out")
        doc = yaml.safe_load(text)
    except OSError as exc:
        raise UserError(f"{p}: cannot read the {what} ({exc.strerror})") from None
    except UnicodeDecodeError:
        raise UserError(f"{p}: the {what} is not UTF-8 text") from None
    except yaml.YAMLError as exc:
        raise UserError(
            f"{p}: the {what} is not valid YAML ({' '.join(str(exc).split())})"
        ) from None
    if not isinstance(doc, dict):
        raise UserError(f"{p}: the {what} is a YAML mapping (see docs/exercises.md)")
    return doc


def _is_number(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x)


_VALUE_CHECKS = {
    "number": _is_number,
    "vector": lambda v: isinstance(v, list) and bool(v) and all(_is_number(x) for x in v),
    "integer": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "boolean": lambda v: isinstance(v, bool),
    "word": lambda v: isinstance(v, str),
    "classes": lambda v: isinstance(v, list) and all(isinstance(x, str) for x in v),
    "formula": lambda v: isinstance(v, str),
}


def read_key(path: str | Path) -> dict[str, Any]:
    """A key written by ``mechsing exercise make`` (checked: a UserError says what is wrong)."""
    doc = _read_yaml(path, "key")
    if doc.get("key") != KEY_VERSION or not isinstance(doc.get("questions"), list):
        raise UserError(f"{path}: not an answer key ('key: 1' and a list of questions)")
    for i, q in enumerate(doc["questions"]):
        if not isinstance(q, dict) or not {"id", "kind", "value"} <= set(q):
            raise UserError(f"{path}: questions[{i}]: each question has id, kind and value")
        if q["kind"] not in KINDS:
            raise UserError(
                f"{path}: questions[{i}] ({q['id']}): kind {q['kind']!r} is not one of "
                f"{', '.join(KINDS)}"
            )
        if not _VALUE_CHECKS[q["kind"]](q["value"]):
            raise UserError(
                f"{path}: questions[{i}] ({q['id']}): the value {q['value']!r} is not a {q['kind']}"
            )
        tol = q.get("tol", 0)
        if isinstance(tol, bool) or not isinstance(tol, int | float) or not tol >= 0:
            raise UserError(f"{path}: questions[{i}] ({q['id']}): tol {tol!r} is not a number >= 0")
        domains = q.get("variables", {})
        if not isinstance(domains, dict) or not set(map(str, domains.values())) <= set(DOMAINS):
            raise UserError(
                f"{path}: questions[{i}] ({q['id']}): variables maps each variable of the "
                f"formula to its domain, one of {', '.join(DOMAINS)}"
            )
        if q["kind"] == "number" and (q.get("unit") is not None and q["unit"] not in UNITS):
            raise UserError(f"{path}: questions[{i}] ({q['id']}): unknown unit {q['unit']!r}")
    return doc


def read_sheet(path: str | Path) -> dict[str, Any]:
    """A student's sheet: its ``answers`` mapping (question id -> answer)."""
    doc = _read_yaml(path, "answer sheet")
    answers = doc.get("answers")
    if answers is None:
        return {}
    if not isinstance(answers, dict):
        raise UserError(f"{path}: answers: is a mapping, one line per question (id: answer)")
    return {str(k): v for k, v in answers.items()}


def expected_text(q: dict[str, Any]) -> str:
    """A key's answer as people read it (key.md, the grades): ``44.8017 deg ± 0.05 deg``."""
    v, kind = q["value"], q["kind"]
    if kind == "number":
        unit = f" {q['unit']}" if q.get("unit") else ""
        return f"{float(v):.6g}{unit} ± {float(q.get('tol', 0)):g}{unit}"
    if kind == "vector":
        unit = f" {q['unit']}" if q.get("unit") else ""
        sign = ", up to sign" if q.get("up_to_sign") else ""
        shown = ", ".join(f"{float(x):.6g}" for x in v)
        return f"[{shown}]{unit} ± {float(q.get('tol', 0)):g}{unit} each{sign}"
    if kind == "classes":
        return ", ".join(v)
    if kind == "boolean":
        return "true" if v else "false"
    return str(v)


def _mark(q: dict[str, Any], given: Any) -> tuple[bool, str]:
    kind, value = q["kind"], q["value"]
    if kind == "number":
        number, unit = parse_quantity(given)
        key_unit = q.get("unit")
        if unit is not None and key_unit is None:
            return False, f"a pure number is expected, not {unit}"
        if unit is not None and UNITS[unit][0] != UNITS[key_unit][0]:
            return False, f"an {UNITS[key_unit][0]} is expected, {unit} is a {UNITS[unit][0]} unit"
        got = to_si(number, unit or key_unit)
        want = to_si(float(value), key_unit)
        return abs(got - want) <= to_si(float(q.get("tol", 0)), key_unit), ""
    if kind == "vector":
        return _vector(q, given)
    if kind == "integer":
        try:
            return int(str(given).strip()) == int(value), ""
        except ValueError:
            return False, "not an integer"
    if kind == "boolean":
        words = {"true": True, "yes": True, "false": False, "no": False}
        b = given if isinstance(given, bool) else words.get(str(given).strip().lower())
        return (b == value, "") if b is not None else (False, "not true or false")
    if kind == "classes":
        items = given if isinstance(given, list) else str(given).split(",")
        names = {str(x).strip().lower() for x in items if str(x).strip()}
        odd = sorted(names - set(CLASSES))
        if odd:
            return False, f"{', '.join(odd)}: not a class (classes: {', '.join(CLASSES)})"
        return names == set(value), ""
    if kind == "formula":
        rtol = float(q.get("tol", EXERCISE_FORMULA_RTOL))
        return same_formula(
            str(value), str(given), rtol, bool(q.get("up_to_factor")), q.get("variables")
        )
    return str(given).strip() == str(value), ""


def _vector(q: dict[str, Any], given: Any) -> tuple[bool, str]:
    """A vector of numbers (a list, or numbers separated by commas, brackets optional),
    each entry in the key's unit or with its own."""
    if isinstance(given, list):
        items = given
    else:
        items = [x for x in str(given).strip().strip("[]").split(",") if x.strip()]
    want = [float(x) for x in q["value"]]
    if len(items) != len(want):
        return False, f"{len(want)} entries are expected, not {len(items)}"
    key_unit = q.get("unit")
    got = []
    for item in items:
        number, unit = parse_quantity(item)
        if unit is not None and (key_unit is None or UNITS[unit][0] != UNITS[key_unit][0]):
            return False, f"the unit {unit} does not fit"
        got.append(to_si(number, unit or key_unit))
    want_si = [to_si(x, key_unit) for x in want]
    tol = to_si(float(q.get("tol", 0)), key_unit)
    signs = (1, -1) if q.get("up_to_sign") else (1,)
    ok = any(all(abs(s * g - w) <= tol for g, w in zip(got, want_si, strict=True)) for s in signs)
    return ok, ""


def grade(sheet_path: str | Path, key_path: str | Path) -> Grade:
    """Grade a sheet against a key (UserError for a sheet or key that cannot be read)."""
    key = read_key(key_path)
    answers = read_sheet(sheet_path)
    marks = []
    for q in key["questions"]:
        qid = str(q["id"])
        expected = expected_text(q)
        given = answers.get(qid)
        if given is None or (isinstance(given, str | list) and not given):
            marks.append(Mark(qid, "missing", expected, key=q))
            continue
        if isinstance(given, bool):
            shown = "true" if given else "false"
        else:
            shown = ", ".join(map(str, given)) if isinstance(given, list) else str(given)
        try:
            ok, note = _mark(q, given)
        except UserError as exc:
            ok, note = False, str(exc)
        marks.append(Mark(qid, "right" if ok else "wrong", expected, shown, note, q))
    asked = {str(q["id"]) for q in key["questions"]}
    extra = tuple(k for k in answers if k not in asked)
    return Grade(
        str(sheet_path),
        str(key_path),
        str(key.get("exercise", "")),
        key.get("variant"),
        tuple(marks),
        extra,
    )
