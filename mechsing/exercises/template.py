"""Exercise templates: which numbers of an exercise vary, in which ranges, under which
constraints, and which questions mechsing answers for each variant.

A template is ``template.yaml`` in an exercise's folder (``docs/exercises.md`` documents
the format for teachers)::

    template: 1                           # the format's version
    title: Driving a crank-rocker through its dead centres
    vary:                                 # parameters of the mechanism below
      a: {from: 0.8, to: 1.2, step: 0.05} # drawn on this grid, written as decimals
    constraints:                          # each must hold for a variant to be kept
      - {name: Grashof, holds: "a + max(b, c, d) < b + c + d - max(b, c, d)"}
    mechanism: |                          # a mechanism file with block-style parameters
      parameters:
        a: 1         # the line of each varied parameter gets the drawn value
        ...
    statement: |                          # Markdown; {a} or {a:.3f} shows a parameter
      ...
    questions:
      - id: stretched
        ask: At which crank angle ...?
        kind: number                      # number, vector, integer, boolean, word, classes,
                                          # formula
        unit: deg                         # the key's unit (mechsing answers in SI)
        tol: 0.05                         # in that unit
        compute: {sweep: {vary: "A=0:360:2"}}
        path: located.0.values.0          # the path language of answers.yaml

Conventions: a varied number is drawn on its grid and written as the decimal text of the
grid point (so the file keeps exactly that number); the other parameters follow from the
file's own expressions.  Constraints are expressions over every parameter of the file
(varied or derived), evaluated in floats.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation
from pathlib import Path
from typing import Any

import yaml

from mechsing.errors import UserError

__all__ = [
    "COMPUTE_OPERATIONS",
    "CONSTRAINT_SYNTAX",
    "KINDS",
    "TEMPLATE_FILE",
    "Constraint",
    "Question",
    "Template",
    "Varied",
    "constraint_tree",
    "load_template",
    "set_parameters",
]

#: the template's file name in an exercise's folder
TEMPLATE_FILE = "template.yaml"
#: the kinds of answer a question may have
KINDS = ("number", "vector", "integer", "boolean", "word", "classes", "formula")
#: the mechsing computations a question may ask for (the library's functions)
COMPUTE_OPERATIONS = {
    "analyze": ("config", "precision"),
    "sweep": ("vary", "from", "precision"),
    "condition": ("config", "symbolic"),
    "cusps": ("vary", "config", "points"),
}
#: largest number of grid points of one varied number
_MAX_GRID = 10**6
_TOP_KEYS = ("template", "title", "vary", "constraints", "mechanism", "statement", "questions")
_QUESTION_KEYS = (
    "id",
    "ask",
    "kind",
    "unit",
    "tol",
    "compute",
    "path",
    "up_to_factor",
    "up_to_sign",
)
_IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


@dataclass(frozen=True)
class Varied:
    """A number drawn on the grid ``start, start + step, ..., stop``."""

    name: str
    start: Decimal
    stop: Decimal
    step: Decimal

    @property
    def count(self) -> int:
        """Number of grid points."""
        return int((self.stop - self.start) / self.step) + 1

    def text(self, k: int) -> str:
        """The decimal text of grid point ``k`` (``1.25``, never ``1.2500000001``)."""
        value = self.start + k * self.step
        text = format(value.normalize(), "f")
        return "0" if text in ("-0", "") else text


@dataclass(frozen=True)
class Constraint:
    """A condition every variant must meet, as an expression over the parameters."""

    name: str
    holds: str


@dataclass(frozen=True)
class Question:
    """One question: what mechsing computes, where its answer is in the JSON, its kind."""

    id: str
    ask: str
    kind: str
    compute: tuple[str, dict[str, Any]]
    path: str
    unit: str | None = None
    tol: float | None = None
    up_to_factor: bool = False
    up_to_sign: bool = False


@dataclass(frozen=True)
class Template:
    """A template read from ``template.yaml`` (see the module's docstring)."""

    path: Path
    title: str
    vary: tuple[Varied, ...]
    constraints: tuple[Constraint, ...]
    mechanism: str
    statement: str
    questions: tuple[Question, ...]

    @property
    def exercise(self) -> str:
        """The exercise's name: its folder's."""
        return self.path.resolve().parent.name


#: what a constraint may be written with
CONSTRAINT_SYNTAX = (
    "numbers, parameters, pi, + - * / **, < <= > >=, and or not, "
    "sqrt sin cos tan asin acos atan atan2 abs min max"
)


def constraint_tree(text: str) -> ast.Expression:
    """A constraint's syntax tree, of bounded size (a UserError says why not)."""
    from mechsing.errors import ExpressionError
    from mechsing.model.expressions import syntax_tree

    try:
        return syntax_tree(text, CONSTRAINT_SYNTAX)
    except ExpressionError as exc:
        shown = text.strip() if len(text.strip()) <= 60 else text.strip()[:40] + "..."
        raise UserError(f"constraint {shown!r}: {exc}") from None


def _fail(path: Path, item: str, message: str) -> UserError:
    return UserError(f"{path}: {item}: {message}")


def _decimal(path: Path, item: str, value: Any) -> Decimal:
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise _fail(path, item, f"expected a decimal number, got {value!r}")
    try:
        d = Decimal(str(value).strip())
    except InvalidOperation:
        raise _fail(path, item, f"expected a decimal number, got {value!r}") from None
    if not d.is_finite():
        raise _fail(path, item, f"expected a finite number, got {value!r}")
    return d


def _varied(path: Path, name: str, spec: Any) -> Varied:
    item = f"vary.{name}"
    if not _IDENTIFIER.match(str(name)):
        raise _fail(path, item, "a varied number's name is a parameter name (an identifier)")
    if not isinstance(spec, dict) or set(spec) != {"from", "to", "step"}:
        raise _fail(path, item, "write {from: LOW, to: HIGH, step: STEP}")
    start, stop, step = (_decimal(path, f"{item}.{k}", spec[k]) for k in ("from", "to", "step"))
    if step <= 0 or stop < start:
        raise _fail(path, item, f"needs step > 0 and to >= from (got {start}..{stop} by {step})")
    n = (stop - start) / step
    if n != n.to_integral_value():
        raise _fail(path, item, f"the range {start}..{stop} is not a whole number of steps {step}")
    v = Varied(str(name), start, stop, step)
    if v.count > _MAX_GRID:
        raise _fail(path, item, f"{v.count} grid points, more than {_MAX_GRID}: take a larger step")
    return v


def _question(path: Path, i: int, q: Any) -> Question:
    item = f"questions[{i}]"
    if not isinstance(q, dict):
        raise _fail(path, item, "each question is a mapping with id, ask, kind, compute, path")
    unknown = sorted(set(q) - set(_QUESTION_KEYS))
    if unknown:
        raise _fail(path, item, f"unknown keys {unknown} (known: {', '.join(_QUESTION_KEYS)})")
    for key in ("id", "ask", "kind", "compute", "path"):
        if key not in q:
            raise _fail(path, item, f"has no {key!r}")
    qid = str(q["id"])
    item = f"questions[{i}] ({qid})"
    if not _IDENTIFIER.match(qid):
        raise _fail(path, item, "an id is an identifier (letters, digits, _)")
    if q["kind"] not in KINDS:
        raise _fail(path, item, f"kind {q['kind']!r} is not one of {', '.join(KINDS)}")
    compute = q["compute"]
    if not isinstance(compute, dict) or len(compute) != 1:
        raise _fail(
            path,
            item,
            "compute is one of {analyze: {...}}, {sweep: {...}}, {condition: {...}}, "
            "{cusps: {...}}",
        )
    ((op, args),) = compute.items()
    if op not in COMPUTE_OPERATIONS:
        raise _fail(path, item, f"compute {op!r} is not one of {', '.join(COMPUTE_OPERATIONS)}")
    args = args or {}
    if not isinstance(args, dict) or set(args) - set(COMPUTE_OPERATIONS[op]):
        known = ", ".join(COMPUTE_OPERATIONS[op])
        raise _fail(path, item, f"compute.{op} takes a mapping of {known}")
    if op == "cusps" and "vary" not in args:
        raise _fail(path, item, 'compute.cusps needs vary: "NAME=lo:hi,NAME=lo:hi"')
    if op == "sweep" and "vary" not in args:
        raise _fail(path, item, 'compute.sweep needs vary: "NAME=START:STOP:STEP"')
    tol = q.get("tol")
    if tol is not None:
        try:
            tol = float(tol)
        except (TypeError, ValueError):
            raise _fail(path, item, f"tol {tol!r} is not a number") from None
        if not tol >= 0:
            raise _fail(path, item, f"tol must be >= 0 (got {tol})")
    if q["kind"] in ("number", "vector") and tol is None:
        raise _fail(path, item, f"a {q['kind']} question needs tol (in the question's unit)")
    unit = q.get("unit")
    if unit is not None:
        from mechsing.exercises.units import UNITS

        if q["kind"] not in ("number", "vector"):
            raise _fail(path, item, "only a number or a vector question has a unit")
        if unit not in UNITS:
            raise _fail(path, item, f"unit {unit!r} is not one of {', '.join(UNITS)}")
    return Question(
        qid,
        str(q["ask"]).strip(),
        q["kind"],
        (op, dict(args)),
        str(q["path"]),
        unit,
        tol,
        bool(q.get("up_to_factor", False)),
        bool(q.get("up_to_sign", False)),
    )


def load_template(path: str | Path) -> Template:
    """Read and check a template file (a UserError names the file, the item and the fix)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise UserError(f"{path}: cannot read the template ({exc.strerror})") from None
    try:
        doc = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        raise UserError(f"{path}: not valid YAML ({' '.join(str(exc).split())})") from None
    if not isinstance(doc, dict) or doc.get("template") != 1:
        raise UserError(f"{path}: a template starts with 'template: 1' (the format's version)")
    unknown = sorted(set(doc) - set(_TOP_KEYS))
    if unknown:
        raise _fail(path, "top level", f"unknown keys {unknown} (known: {', '.join(_TOP_KEYS)})")
    for key in ("title", "vary", "mechanism", "statement", "questions"):
        if not doc.get(key):
            raise _fail(path, key, "is missing or empty")
    if not isinstance(doc["vary"], dict):
        raise _fail(path, "vary", "is a mapping NAME: {from, to, step}")
    vary = tuple(_varied(path, n, s) for n, s in doc["vary"].items())
    constraints = []
    for i, c in enumerate(doc.get("constraints") or []):
        if isinstance(c, str):
            c = {"name": c, "holds": c}
        if not isinstance(c, dict) or "holds" not in c:
            raise _fail(path, f"constraints[{i}]", "write {name: WHAT IT MEANS, holds: EXPRESSION}")
        constraint = Constraint(str(c.get("name", c["holds"])), str(c["holds"]))
        try:  # bounded as the mechanism file's expressions are: refused here, before a draw
            constraint_tree(constraint.holds)
        except UserError as exc:
            raise _fail(path, f"constraints[{i}]", f"{exc}; write a shorter expression") from None
        constraints.append(constraint)
    if not isinstance(doc["questions"], list):
        raise _fail(path, "questions", "is a list of questions")
    questions = tuple(_question(path, i, q) for i, q in enumerate(doc["questions"]))
    ids = [q.id for q in questions]
    if len(set(ids)) != len(ids):
        raise _fail(path, "questions", f"ids repeat: {ids}")
    template = Template(
        path,
        str(doc["title"]).strip(),
        vary,
        tuple(constraints),
        str(doc["mechanism"]),
        str(doc["statement"]),
        questions,
    )
    # every varied number must be a parameter line of the mechanism
    set_parameters(template.mechanism, {v.name: v.text(0) for v in vary}, where=str(path))
    return template


_PARAM_LINE = re.compile(
    r"^(?P<indent>[ \t]+)(?P<name>[A-Za-z_][A-Za-z0-9_]*)(?P<sep>[ \t]*:[ \t]*)"
    r"(?P<value>[^#\n]*?)(?P<rest>[ \t]*(?:#.*)?)$"
)


def set_parameters(mechanism: str, values: dict[str, str], where: str = "template") -> str:
    """The mechanism text with the named parameters' values replaced (comments and layout
    kept).  The parameters must be written in block style under ``parameters:``, one a
    line."""
    lines = mechanism.splitlines(keepends=True)
    try:
        start = next(i for i, line in enumerate(lines) if line.rstrip() == "parameters:")
    except StopIteration:
        raise UserError(
            f"{where}: mechanism: no 'parameters:' line; the varied numbers are parameters "
            "written in block style, one a line (parameters:\\n  a: 1)"
        ) from None
    done = set()
    for i in range(start + 1, len(lines)):
        line = lines[i]
        if line.strip() and not line[0].isspace():
            break  # the block ended
        m = _PARAM_LINE.match(line.rstrip("\n"))
        if m and m["name"] in values:
            newline = "\n" if line.endswith("\n") else ""
            lines[i] = f"{m['indent']}{m['name']}{m['sep']}{values[m['name']]}{m['rest']}{newline}"
            done.add(m["name"])
    missing = sorted(set(values) - done)
    if missing:
        raise UserError(
            f"{where}: mechanism: the varied numbers {missing} are not parameter lines of its "
            "'parameters:' block (write them one a line, NAME: VALUE)"
        )
    return "".join(lines)
