"""Numbers of a mechanism file, read without mechsing: a number, or a whitelisted expression
string (numbers, + - * / **, parentheses, pi and the functions of the file format) evaluated by
walking its AST -- never eval or sympify -- in float, mpmath or sympy arithmetic."""

from __future__ import annotations

import ast
import math
from collections.abc import Callable, Sequence

import mpmath
import numpy as np

FLOAT_FUNCTIONS: dict[str, Callable] = {
    "sqrt": math.sqrt,
    "sin": math.sin,
    "cos": math.cos,
    "tan": math.tan,
    "asin": math.asin,
    "acos": math.acos,
    "atan": math.atan,
    "atan2": math.atan2,
}

#: the same functions at mpmath's working precision
MP_FUNCTIONS: dict[str, Callable] = {name: getattr(mpmath, name) for name in FLOAT_FUNCTIONS}

_OPS = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.Pow: lambda a, b: a**b,
}


def evaluate(
    x: object,
    funcs: dict[str, Callable] | None = None,
    const: Callable = float,
    pi: object = math.pi,
) -> object:
    """A file number or a whitelisted expression string, in the arithmetic of ``const`` (the
    type of the literals), ``funcs`` and ``pi``."""
    funcs = funcs or FLOAT_FUNCTIONS
    if isinstance(x, bool):
        raise TypeError(x)
    if isinstance(x, (int, float)):
        return const(x) if const is not float else float(x)
    tree = ast.parse(str(x), mode="eval")

    def ev(n: ast.AST) -> object:
        if isinstance(n, ast.Expression):
            return ev(n.body)
        if (
            isinstance(n, ast.Constant)
            and isinstance(n.value, (int, float))
            and not isinstance(n.value, bool)
        ):
            return const(n.value)
        if isinstance(n, ast.Name) and n.id == "pi":
            return pi
        if isinstance(n, ast.UnaryOp) and isinstance(n.op, (ast.USub, ast.UAdd)):
            v = ev(n.operand)
            return -v if isinstance(n.op, ast.USub) else v
        if isinstance(n, ast.BinOp) and type(n.op) in _OPS:
            return _OPS[type(n.op)](ev(n.left), ev(n.right))
        if (
            isinstance(n, ast.Call)
            and isinstance(n.func, ast.Name)
            and n.func.id in funcs
            and not n.keywords
        ):
            return funcs[n.func.id](*[ev(a) for a in n.args])
        raise ValueError(f"expression outside the whitelist: {x!r}")

    return ev(tree)


def num(x: object) -> float:
    """A file number as a float."""
    return float(evaluate(x))


def vec(v: Sequence) -> np.ndarray:
    """A file vector as floats."""
    return np.array([num(x) for x in v], dtype=float)


def mp_num(x: object) -> mpmath.mpf:
    """A file number at mpmath's working precision, its decimals as written (``0.1`` is 1/10,
    not the float nearest it)."""
    value = evaluate(x, MP_FUNCTIONS, const=lambda c: mpmath.mpf(str(c)), pi=mpmath.pi)
    return mpmath.mpf(value)
