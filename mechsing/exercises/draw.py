"""Drawing the numbers of a variant: a grid point of every varied number, kept when every
constraint of the template holds.

The draws come from ``numpy.random.default_rng(seed)`` in a fixed order (one integer per
varied number, in the template's order), so a seed gives the same variants on every
machine.  A template whose constraints no draw meets in :data:`MAX_DRAWS` draws is refused
with the constraint that failed most.
"""

from __future__ import annotations

import ast
import math
from collections import Counter
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation
from typing import Any

import numpy as np
import yaml

from mechsing.errors import ParameterError, UserError
from mechsing.exercises.template import (
    CONSTRAINT_SYNTAX,
    Template,
    constraint_tree,
    set_parameters,
)

__all__ = ["MAX_DRAWS", "Draw", "check_constraints", "draws", "evaluate", "parameter_values"]

#: draws tried for one variant before the template is refused
MAX_DRAWS = 2000
#: the name under which a draw is counted when mechsing cannot answer its questions
ANSWERED = "mechsing answers every question"
#: the name under which a draw is counted when it repeats an earlier variant
DISTINCT = "a variant not drawn before"
#: ... and when it has the template's own numbers (those of the exercise, whose worked
#: answer is published)
NOT_OWN = "numbers other than the template's own (the exercise's worked answer)"

_FUNCTIONS: dict[str, Callable[..., float]] = {
    "sqrt": math.sqrt,
    "sin": math.sin,
    "cos": math.cos,
    "tan": math.tan,
    "asin": math.asin,
    "acos": math.acos,
    "atan": math.atan,
    "atan2": math.atan2,
    "abs": abs,
    "min": min,
    "max": max,
}
_COMPARE = {
    ast.Lt: lambda a, b: a < b,
    ast.LtE: lambda a, b: a <= b,
    ast.Gt: lambda a, b: a > b,
    ast.GtE: lambda a, b: a >= b,
}
_ARITHMETIC = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.Pow: lambda a, b: a**b,
}


@dataclass(frozen=True)
class Draw:
    """One kept draw: the varied numbers' texts, the mechanism file with them, and every
    parameter's value (float)."""

    texts: dict[str, str]
    mechanism: str
    values: dict[str, float]


def parameter_values(mechanism: str, where: str = "mechanism") -> dict[str, float]:
    """Every parameter of a mechanism file's text, in floats, read as the file format does
    (exact, each from the earlier ones)."""
    from mechsing.errors import ExpressionError
    from mechsing.model.expressions import parse_number

    doc = yaml.safe_load(mechanism)
    params = doc.get("parameters") if isinstance(doc, dict) else None
    if not isinstance(params, dict):
        raise UserError(f"{where}: no parameters mapping")
    exact: dict[str, Any] = {}
    for name, value in params.items():
        try:
            exact[str(name)] = parse_number(str(value), names=exact)
        except ExpressionError as exc:
            raise ParameterError(f"{where}: parameter {name}: {exc}", _floats(exact)) from None
    return _floats(exact)


def _floats(exact: dict[str, Any]) -> dict[str, float]:
    return {k: float(v) for k, v in exact.items()}


def evaluate(text: str, values: dict[str, float]) -> Any:
    """A constraint's expression in floats: numbers, names of ``values``, ``pi``, ``+ - *
    / **``, comparisons (chained too), ``and``, ``or``, ``not`` and the functions sqrt,
    sin, cos, tan, asin, acos, atan, atan2, abs, min, max.  Never ``eval``; bounded as a
    mechanism file's expressions are (:func:`mechsing.model.expressions.syntax_tree`)."""
    tree = constraint_tree(text)

    def build(node: ast.AST) -> Any:
        if isinstance(node, ast.Expression):
            return build(node.body)
        if isinstance(node, ast.Constant) and type(node.value) in (int, float):
            return float(node.value)
        if isinstance(node, ast.Name):
            if node.id == "pi":
                return math.pi
            if node.id in values:
                return values[node.id]
            raise UserError(f"constraint {text!r}: {node.id!r} is not a parameter")
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd | ast.Not):
            v = build(node.operand)
            return (
                (not v)
                if isinstance(node.op, ast.Not)
                else (-v if isinstance(node.op, ast.USub) else v)
            )
        if isinstance(node, ast.BinOp) and type(node.op) in _ARITHMETIC:
            return _ARITHMETIC[type(node.op)](build(node.left), build(node.right))
        if isinstance(node, ast.BoolOp):
            parts = [bool(build(v)) for v in node.values]
            return all(parts) if isinstance(node.op, ast.And) else any(parts)
        if isinstance(node, ast.Compare) and all(type(o) in _COMPARE for o in node.ops):
            left = build(node.left)
            for op, right_node in zip(node.ops, node.comparators, strict=True):
                right = build(right_node)
                if not _COMPARE[type(op)](left, right):
                    return False
                left = right
            return True
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Name)
            and node.func.id in _FUNCTIONS
            and not node.keywords
        ):
            return _FUNCTIONS[node.func.id](*(build(a) for a in node.args))
        what = ast.get_source_segment(text.strip(), node) or type(node).__name__
        raise UserError(f"constraint {text!r}: {what!r} is not allowed ({CONSTRAINT_SYNTAX})")

    return build(tree)


def check_constraints(
    template: Template, values: dict[str, float], partial: bool = False
) -> list[str]:
    """The names of the template's constraints that ``values`` break (a constraint whose
    expression cannot be evaluated there, e.g. the root of a negative number, is broken).
    With ``partial``, ``values`` may lack parameters: a constraint that uses one is
    skipped."""
    broken = []
    for c in template.constraints:
        if partial and not _uses_only(c.holds, values):
            continue
        try:
            ok = bool(evaluate(c.holds, values))
        except (ValueError, ZeroDivisionError, OverflowError, TypeError):
            ok = False
        except UserError as exc:
            raise UserError(f"{template.path}: constraints ({c.name}): {exc}") from None
        if not ok:
            broken.append(c.name)
    return broken


def _uses_only(text: str, values: dict[str, float]) -> bool:
    try:
        tree = constraint_tree(text)
    except UserError:
        return True  # evaluate() says what is wrong
    names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
    return names <= set(values) | set(_FUNCTIONS) | {"pi"}


def _own_numbers(template: Template) -> tuple[Decimal | None, ...]:
    """The varied numbers as the template's mechanism writes them (None: not a decimal)."""
    doc = yaml.safe_load(template.mechanism)
    params = doc.get("parameters") if isinstance(doc, dict) else None
    out = []
    for v in template.vary:
        text = str(params.get(v.name)) if isinstance(params, dict) else ""
        try:
            out.append(Decimal(text.strip()))
        except InvalidOperation:
            out.append(None)
    return tuple(out)


def draws(template: Template, seed: int, failures: Counter[str]) -> Iterator[Draw]:
    """Draws that meet every constraint, forever (the caller stops).  ``failures`` counts
    the broken constraints; once :data:`MAX_DRAWS` draws in a row are refused, a UserError
    names the constraint that failed most.  The caller may add to ``failures`` (a draw it
    refuses for another reason) and the count of refused draws goes on."""
    rng = np.random.default_rng(seed)
    seen: set[tuple[str, ...]] = set()
    own = _own_numbers(template)
    refused = 0
    while True:
        if refused >= MAX_DRAWS:
            name, times = failures.most_common(1)[0]
            holds = next((c.holds for c in template.constraints if c.name == name), None)
            said = f"{name} ({holds})" if holds and holds != name else name
            raise UserError(
                f"{template.path}: no draw met the constraints in {MAX_DRAWS} draws; the one "
                f"that failed most: {said}, in {times} draws. Widen the ranges of 'vary' or "
                "relax that constraint"
            )
        ks = [int(rng.integers(0, v.count)) for v in template.vary]
        texts = {v.name: v.text(k) for v, k in zip(template.vary, ks, strict=True)}
        key = tuple(texts.values())
        if key in seen or tuple(Decimal(t) for t in key) == own:
            failures[DISTINCT if key in seen else NOT_OWN] += 1
            refused += 1
            continue
        # the constraints over the varied numbers alone first: no file to evaluate
        broken = check_constraints(template, {k: float(v) for k, v in texts.items()}, True)
        if broken:
            failures.update(broken)
            refused += 1
            continue
        mechanism = set_parameters(template.mechanism, texts, where=str(template.path))
        try:
            values = parameter_values(mechanism, where=f"{template.path}: mechanism")
            broken = check_constraints(template, values)
        except ParameterError as exc:  # a derived parameter is not a real number here
            broken = check_constraints(template, exc.values, partial=True)
            broken = broken or ["the mechanism's parameters are real numbers"]
        if broken:
            failures.update(broken)
            refused += 1
            continue
        seen.add(key)
        before = sum(failures.values())
        yield Draw(texts, mechanism, values)
        refused = refused + 1 if sum(failures.values()) > before else 0
