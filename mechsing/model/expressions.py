"""Exact numbers and whitelisted expressions from text (never ``eval``).

A number written in a mechanism file (or on the ``identify`` command line)
keeps its meaning in every precision mode: ``0.1`` is exactly 1/10, not the
float64 nearest to it.  A quoted expression such as ``"sqrt(3)/2"`` or
``"2*atan(1/2)"`` is an exact sympy value.

The grammar is parsed with :mod:`ast` and only these nodes are accepted:

* decimal numbers (``3``, ``-0.25``, ``1.5e-3``), taken from their *text*;
* the operators ``+ - * / **``, unary ``+``/``-`` and parentheses;
* the constant ``pi`` and the names a caller passes (a file's parameters);
* the functions ``sqrt``, ``sin``, ``cos``, ``tan``, ``asin``, ``acos``,
  ``atan`` (one argument) and ``atan2(y, x)``.

Anything else (names, attributes, subscripts, calls of other functions,
keyword arguments, strings, hexadecimal or complex literals, comparisons,
lambdas ...) is refused with an :class:`ExpressionError` that names what is
not allowed.  Sizes are bounded so that no text can make sympy build a huge
number: the text length, the number of syntax nodes, the digits of a number,
decimal exponents, the exponents of ``**``, and the size of the exact value once the
parameters it names are put in (:data:`MAX_EXPRESSION_SIZE` parts, counted with
repetition: a chain of parameters that each use the one before twice doubles at each
step, and is refused when it outgrows the bound instead of taking exponential time).
A number is of a sensible size (at most :data:`~mechsing.numeric.MAX_NUMBER` in
magnitude), and a divisor that is exactly zero however it is written
(``sin(pi/7)**2 + cos(pi/7)**2 - 1``) is a division by zero.

Public API: :func:`parse_number` (text to exact value), :func:`is_finite_real`,
:func:`is_plain_decimal` (a number as opposed to an expression) and
:func:`radian_power` (does a value carry radians: the unit trap of degree files).
"""

from __future__ import annotations

import ast
from collections.abc import Mapping
from fractions import Fraction
from typing import Any

from mechsing.errors import ExpressionError
from mechsing.numeric.lazy import is_sympy, mpmath, sympy
from mechsing.numeric.numbers import DECIMAL, SIGNED_DECIMAL, is_decimal_text, is_sensible_size
from mechsing.numeric.pirational import PI, PiRational
from mechsing.numeric.tolerances import EXACT_ZERO_DIGITS, MAX_NUMBER

__all__ = [
    "ALLOWED_FUNCTIONS",
    "ExpressionError",
    "MAX_EXPRESSION_CHARS",
    "MAX_EXPRESSION_DEPTH",
    "MAX_EXPRESSION_SIZE",
    "is_finite_real",
    "is_plain_decimal",
    "parse_number",
    "radian_power",
    "syntax_tree",
    "written_digits",
]

#: longest expression text accepted
MAX_EXPRESSION_CHARS = 1000
#: most syntax nodes in one expression
MAX_EXPRESSION_NODES = 200
#: most digits of one decimal literal (mantissa)
MAX_NUMBER_DIGITS = 400
#: largest |decimal exponent| of a literal such as 1e-300
MAX_DECIMAL_EXPONENT = 400
#: largest |numerator| and denominator of the exponent of ``**``
MAX_POWER_EXPONENT = 256
#: largest bit length of an intermediate rational (numerator or denominator)
MAX_RATIONAL_BITS = 8192
#: most parts (sympy nodes, counted with repetition) of an exact value, once the
#: parameters it uses are put in, and its deepest nesting: building one costs sympy time
#: that grows with both (a sum of 2000 parts about 0.06 s, a function nested 64 deep
#: about 0.01 s), so a file of many parameters is read in bounded time per parameter
MAX_EXPRESSION_SIZE = 2000
MAX_EXPRESSION_DEPTH = 64

#: whitelisted functions (sympy's of the same name) and their number of arguments
ALLOWED_FUNCTIONS: dict[str, int] = {
    "sqrt": 1,
    "sin": 1,
    "cos": 1,
    "tan": 1,
    "asin": 1,
    "acos": 1,
    "atan": 1,
    "atan2": 2,
}

_ALLOWED_TEXT = "numbers, + - * / **, parentheses, pi, sqrt, sin, cos, tan, asin, acos, atan, atan2"


def _describe(node: ast.AST) -> str:
    names = {
        ast.Name: "the name",
        ast.Attribute: "attribute access",
        ast.Subscript: "subscripts",
        ast.Call: "this call",
        ast.Lambda: "lambda",
        ast.Compare: "comparisons",
        ast.BoolOp: "and/or",
        ast.IfExp: "if/else",
        ast.List: "lists",
        ast.Tuple: "tuples",
        ast.Dict: "dicts",
        ast.Set: "sets",
        ast.JoinedStr: "f-strings",
        ast.Starred: "starred arguments",
        ast.NamedExpr: "assignment expressions",
    }
    for cls, text in names.items():
        if isinstance(node, cls):
            return text
    return type(node).__name__


class _Builder:
    """The exact value of an expression's syntax tree: its numbers and pi as
    :class:`~mechsing.numeric.pirational.PiRational` (their sums, products and integer
    powers stay so), sympy for the rest (a function's value, a sum of two powers of pi)."""

    def __init__(self, text: str, names: Mapping[str, Any] | None = None) -> None:
        self.text = text
        self.shown = _short(text)
        self.names = names or {}
        self.sizes: dict[Any, tuple[int, int]] = {}

    def fail(self, what: str) -> ExpressionError:
        return ExpressionError(
            f"expression {self.shown!r}: {what} is not allowed (allowed: {_ALLOWED_TEXT})"
        )

    def segment(self, node: ast.AST) -> str:
        seg = ast.get_source_segment(self.text, node)
        return seg if seg is not None else ""

    def build(self, node: ast.AST) -> Any:
        if isinstance(node, ast.Expression):
            return self.check(self.build(node.body))
        if isinstance(node, ast.Constant):
            return self.number(node)
        if isinstance(node, ast.UnaryOp):
            if isinstance(node.op, ast.USub):
                return self.check(-self.build(node.operand))
            if isinstance(node.op, ast.UAdd):
                return self.build(node.operand)
            raise self.fail(f"the operator {type(node.op).__name__}")
        if isinstance(node, ast.BinOp):
            return self.binop(node)
        if isinstance(node, ast.Name):
            if node.id == "pi":
                return PI
            if node.id in self.names:
                return self.names[node.id]
            if node.id in ALLOWED_FUNCTIONS:
                raise self.fail(f"{node.id} without parentheses")
            if self.names:
                known = ", ".join(self.names)
                raise self.fail(f"the name {node.id!r} (not a parameter; parameters: {known})")
            raise self.fail(f"the name {node.id!r}")
        if isinstance(node, ast.Call):
            return self.call(node)
        if isinstance(node, ast.Attribute):
            raise self.fail(f"attribute access ({self.segment(node)!r})")
        raise self.fail(_describe(node))

    def number(self, node: ast.Constant) -> Any:
        value = node.value
        if isinstance(value, bool) or not isinstance(value, int | float):
            if isinstance(value, complex):
                raise self.fail("a complex number")
            raise self.fail(f"the constant {value!r}")
        text = self.segment(node).strip()
        if not DECIMAL.match(text):
            raise self.fail(f"the number {text!r} (write plain decimal digits)")
        return decimal_text_to_rational(text, self.text)

    def binop(self, node: ast.BinOp) -> Any:
        op = node.op
        if not isinstance(op, ast.Add | ast.Sub | ast.Mult | ast.Div | ast.Pow):
            sym = {
                ast.Mod: "%",
                ast.FloorDiv: "//",
                ast.MatMult: "@",
                ast.BitXor: "^",
                ast.BitAnd: "&",
                ast.BitOr: "|",
                ast.LShift: "<<",
                ast.RShift: ">>",
            }.get(type(op), type(op).__name__)
            hint = " (use ** for powers)" if sym == "^" else ""
            raise self.fail(f"the operator {sym}{hint}")
        left = self.build(node.left)
        right = self.build(node.right)
        if isinstance(op, ast.Add):
            return self.check(left + right)
        if isinstance(op, ast.Sub):
            return self.check(left - right)
        if isinstance(op, ast.Mult):
            return self.check(left * right)
        if isinstance(op, ast.Div):
            if _is_zero(right):
                divisor = _short(self.segment(node.right), 40)
                raise ExpressionError(
                    f"expression {self.shown!r}: division by zero (the divisor {divisor!r} "
                    f"is zero{_zero_how(right)})"
                )
            return self.check(left / right)
        return self.power(left, right)

    def power(self, base: Any, exponent: Any) -> Any:
        ratio = _rational(exponent)
        if ratio is None:
            raise ExpressionError(
                f"expression {self.shown!r}: the exponent of ** must be a rational number "
                f"such as 2, -1 or 1/2 (got {exponent})"
            )
        p, q = ratio
        if abs(p) > MAX_POWER_EXPONENT or q > MAX_POWER_EXPONENT:
            raise ExpressionError(
                f"expression {self.shown!r}: the exponent {exponent} of ** is too large "
                f"(at most {MAX_POWER_EXPONENT} in numerator and denominator)"
            )
        if exponent < 0 and _is_zero(base):
            raise ExpressionError(
                f"expression {self.shown!r}: division by zero (0 to a negative power)"
            )
        base_ratio = base.ratio if isinstance(base, PiRational) else _rational(base)
        if base_ratio is not None:
            bits = max(abs(int(n)).bit_length() for n in _pair(base_ratio))
            if bits * abs(p) > MAX_RATIONAL_BITS:
                raise ExpressionError(
                    f"expression {self.shown!r}: a power in it is too large a number"
                )
        elif sympy.count_ops(base) * abs(p) > 4 * MAX_EXPRESSION_NODES:
            raise ExpressionError(
                f"expression {self.shown!r}: the power is too large an expression"
            )
        if isinstance(base, PiRational) and q == 1:
            return self.check(base**p)
        return self.check(sympy.Pow(base, exponent))

    def call(self, node: ast.Call) -> Any:
        if not isinstance(node.func, ast.Name):
            raise self.fail(f"calling {self.segment(node.func)!r}")
        name = node.func.id
        if name not in ALLOWED_FUNCTIONS:
            raise self.fail(f"the function {name!r}")
        if node.keywords:
            raise self.fail("keyword arguments")
        nargs = ALLOWED_FUNCTIONS[name]
        if len(node.args) != nargs:
            raise ExpressionError(
                f"expression {self.shown!r}: {name} takes {nargs} argument"
                f"{'s' if nargs > 1 else ''}, got {len(node.args)}"
            )
        args = [self.build(a) for a in node.args]
        if name == "atan2" and _is_zero(args[0]) and _is_zero(args[1]):
            raise ExpressionError(f"expression {self.shown!r}: atan2(0, 0) is undefined")
        return self.check(getattr(sympy, name)(*args))

    def check(self, value: Any) -> Any:
        if isinstance(value, PiRational):
            if max(value.ratio.numerator.bit_length(), value.ratio.denominator.bit_length()) > (
                MAX_RATIONAL_BITS
            ):
                raise ExpressionError(f"expression {self.shown!r}: a number in it is too large")
            return value  # finite, and of one part (no sympy work grows with it)
        if isinstance(value, sympy.Rational):
            if max(int(value.p).bit_length(), int(value.q).bit_length()) > MAX_RATIONAL_BITS:
                raise ExpressionError(f"expression {self.shown!r}: a number in it is too large")
        if value.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo):
            raise ExpressionError(f"expression {self.shown!r} is not a finite number")
        size, depth = _tree_size(value, self.sizes)
        if size > MAX_EXPRESSION_SIZE or depth > MAX_EXPRESSION_DEPTH:
            what = (
                f"has {size} parts (at most {MAX_EXPRESSION_SIZE})"
                if size > MAX_EXPRESSION_SIZE
                else f"is nested {depth} deep (at most {MAX_EXPRESSION_DEPTH})"
            )
            raise ExpressionError(
                f"expression {self.shown!r} is too large for exact evaluation: its value "
                f"{what} once the parameters it uses are put in; write a number instead, "
                "or use each parameter fewer times"
            )
        return value


def _tree_size(value: Any, memo: dict[Any, tuple[int, int]]) -> tuple[int, int]:
    """Nodes and depth of a sympy value counted as a tree (a shared part once per use),
    computed over its distinct parts only (linear in them, without recursion)."""
    stack = [value]
    while stack:
        x = stack[-1]
        if x in memo:
            stack.pop()
            continue
        todo = [a for a in x.args if a not in memo]
        if todo:
            stack.extend(todo)
            continue
        stack.pop()
        parts = [memo[a] for a in x.args]
        memo[x] = (1 + sum(p[0] for p in parts), 1 + max((p[1] for p in parts), default=0))
    return memo[value]


def _with_values(value: Any) -> Any:
    """``value`` with its parameter symbols replaced by their values (a number)."""
    return value.xreplace(
        {a: a.parameter_value for a in value.free_symbols if hasattr(a, "parameter_value")}
    )


def _rational(x: Any) -> tuple[int, int] | None:
    """Numerator and denominator of a rational value (a PiRational without pi or a
    sympy Rational), else None."""
    if isinstance(x, PiRational):
        return (x.ratio.numerator, x.ratio.denominator) if x.pi_power == 0 else None
    if is_sympy(x) and isinstance(x, sympy.Rational):
        return int(x.p), int(x.q)
    return None


def _pair(x: Any) -> tuple[int, int]:
    return (x.numerator, x.denominator) if isinstance(x, Fraction) else x


def _is_zero(value: Any) -> bool:
    """Is an exact value zero, however it is written?  Decided exactly for a rational;
    otherwise by sympy's evaluation at EXACT_ZERO_DIGITS digits (whose error it bounds):
    a value below 10^(15 - EXACT_ZERO_DIGITS) there is zero, or too close to zero to
    divide by."""
    if isinstance(value, PiRational):
        return not value
    value = sympy.sympify(value)
    if isinstance(value, sympy.Rational):
        return bool(value == 0)
    probe = _with_values(value)
    if probe.free_symbols:
        return False
    # a value below this at EXACT_ZERO_DIGITS digits is zero for a divisor
    bound = sympy.Float(10) ** (15 - EXACT_ZERO_DIGITS)
    return bool(abs(sympy.N(probe, EXACT_ZERO_DIGITS)) <= bound)


def _zero_how(value: Any) -> str:
    if _rational(value) is not None:
        return ""
    return f" to {EXACT_ZERO_DIGITS} digits, however it is written"


def _short(text: str, n: int = 60) -> str:
    return text if len(text) <= n else text[: n - 3] + "..."


def decimal_text_to_rational(text: str, context: str | None = None) -> PiRational:
    """Exact rational of a decimal literal such as ``-1.25e-3`` (bounded sizes), a
    :class:`~mechsing.numeric.pirational.PiRational`."""
    where = _short(context if context is not None else text)
    t = text.strip()
    sign = ""
    if t[:1] in "+-":
        sign, t = t[:1], t[1:].strip()
    if not DECIMAL.match(t):
        raise ExpressionError(f"{where!r} is not a decimal number")
    mant, _, exp = t.lower().partition("e")
    if len(mant.replace(".", "")) > MAX_NUMBER_DIGITS:
        raise ExpressionError(
            f"the number {where!r} has too many digits (at most {MAX_NUMBER_DIGITS})"
        )
    if exp and abs(int(exp)) > MAX_DECIMAL_EXPONENT:
        raise ExpressionError(
            f"the number {where!r} has too large an exponent (at most {MAX_DECIMAL_EXPONENT})"
        )
    value = Fraction(mant)
    if exp:
        value = value * Fraction(10) ** int(exp)
    return PiRational(-value if sign == "-" else value)


def syntax_tree(text: str, allowed: str = _ALLOWED_TEXT) -> ast.Expression:
    """The syntax tree of an expression's text, of bounded size: at most
    :data:`MAX_EXPRESSION_CHARS` characters and :data:`MAX_EXPRESSION_NODES` nodes (an
    ExpressionError otherwise, or for text that is not Python's expression syntax;
    ``allowed`` says what may be written)."""
    t = text.strip()
    if len(t) > MAX_EXPRESSION_CHARS:
        raise ExpressionError(
            f"expression of {len(t)} characters is too long (at most {MAX_EXPRESSION_CHARS})"
        )
    try:
        tree = ast.parse(t, mode="eval")
    except (SyntaxError, ValueError) as exc:
        raise ExpressionError(
            f"expression {_short(t)!r} is not valid ({getattr(exc, 'msg', exc)}); "
            f"allowed: {allowed}"
        ) from None
    except (RecursionError, MemoryError):
        raise ExpressionError(f"expression {t[:40]!r}... is nested too deeply") from None
    count = sum(1 for _ in ast.walk(tree))
    if count > MAX_EXPRESSION_NODES:
        raise ExpressionError(
            f"expression {t[:40]!r}... has {count} parts, too many (at most {MAX_EXPRESSION_NODES})"
        )
    return tree


def parse_number(text: str, names: Mapping[str, Any] | None = None, plain: bool = False) -> Any:
    """The exact value of a number or whitelisted expression: a sympy value, or with
    ``plain`` a :class:`~mechsing.numeric.pirational.PiRational` where the value is a
    rational times a power of pi (then no sympy is imported; its sympy value is
    ``sympy.sympify(x)``).

    Parameters
    ----------
    text : str
        ``"0.1"``, ``"-3"``, ``"1/3"``, ``"pi/2"``, ``"sqrt(3)/2"``,
        ``"2*atan(1/2)"``, ``"atan2(1, 2)"`` ...
    names : mapping, optional
        Named values the expression may use (a file's parameters); a value
        may be a symbol that knows its value (``parameter_value``), which the
        finiteness test uses.
    plain : bool
        Keep a rational times a power of pi a PiRational instead of its sympy value.

    Returns
    -------
    sympy.Expr or PiRational
        An exact, real, finite value (a ``sympy.Rational`` for decimal text, a PiRational
        with ``plain``).

    Raises
    ------
    ExpressionError
        when the text is empty, too long, not valid syntax, uses anything
        outside the whitelist, or is not a finite real number.
    """
    if not isinstance(text, str):
        raise ExpressionError(
            f"expected a number or an expression as text, got {type(text).__name__}"
        )
    t = text.strip()
    if not t:
        raise ExpressionError("an empty text is not a number")
    if len(t) <= MAX_EXPRESSION_CHARS and SIGNED_DECIMAL.match(t):
        return _exact_form(_sensible(decimal_text_to_rational(t), t), plain)
    tree = syntax_tree(t)
    try:
        value = _Builder(t, names).build(tree)
    except ExpressionError:
        raise
    except RecursionError:
        raise ExpressionError(f"expression {t[:40]!r}... is nested too deeply") from None
    if isinstance(value, PiRational):
        return _exact_form(_sensible(value, t), plain)
    value = sympy.sympify(value)
    probe = _with_values(value)
    if not is_finite_real(probe):
        raise ExpressionError(
            f"expression {_short(t)!r} is not a finite real number (it is {value})"
        )
    return _sensible(value, t, probe)


def _exact_form(value: PiRational, plain: bool) -> Any:
    """A PiRational as parse_number gives it: itself (``plain``) or its sympy value."""
    return value if plain else value._sympy_()


def _sensible(value: Any, text: str, probe: Any = None) -> Any:
    """``value``, or an ExpressionError when it is larger than MAX_NUMBER in magnitude."""
    x = value if probe is None else probe
    if isinstance(x, PiRational) or isinstance(x, sympy.Rational):
        ok = is_sensible_size(x)
    else:
        ok = is_sensible_size(sympy.N(x, 20))
    if not ok:
        what = repr(_short(text))
        if not SIGNED_DECIMAL.match(text.strip()):
            what += f" (= {mpmath.nstr(mpmath.mpf(sympy.N(x, 5)._mpf_), 3)})"
        raise ExpressionError(
            f"the number {what} is too large: numbers are at most {MAX_NUMBER:g} in "
            "magnitude (in the units of the place they stand); check the value and its unit"
        )
    return value


def is_finite_real(value: Any) -> bool:
    """True when a sympy value is a finite real number (decided at 30 digits
    when sympy cannot decide symbolically)."""
    if isinstance(value, PiRational) or isinstance(value, sympy.Rational):
        return True
    if value.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo, sympy.I):
        return False
    if value.free_symbols:
        return False
    if value.is_extended_real is False:
        return False
    try:
        num = sympy.N(value, 30)
    except Exception:  # pragma: no cover - sympy internal failure
        return False
    re_, im = num.as_real_imag()
    if not (re_.is_finite and im.is_finite):
        return False
    scale = max(abs(re_), sympy.Float(1))
    return abs(im) <= sympy.Float("1e-25") * scale


def is_plain_decimal(text: str) -> bool:
    """True for a plain (signed) decimal number such as ``30`` or ``-1.5e3``, False
    for an expression such as ``"pi/6"``."""
    return is_decimal_text(text)


def written_digits(text: str) -> tuple[int, int] | None:
    """The significant digits of a plain decimal as written, and the power of ten of
    its last written digit: ``"1.85459043600322"`` gives (15, -14), ``"-0.0025"``
    (2, -4), ``"30"`` (2, 0), ``"1.5e-3"`` (2, -4).  None for an expression such as
    ``"pi/3"`` (an exact value: it has no last digit).  Half a unit in the last digit
    is the value's written resolution (:func:`mechsing.numeric.data_resolution`)."""
    t = text.strip().lstrip("+-").strip()
    if not DECIMAL.match(t):
        return None
    mant, _, exp = t.lower().partition("e")
    whole, _, frac = mant.partition(".")
    digits = (whole + frac).lstrip("0")
    last = int(exp or 0) - len(frac)
    return max(len(digits), 1), last


def radian_power(value: Any) -> Any:
    """How many times an exact value carries the radian, read from its form.

    ``pi`` and the inverse trigonometric functions (``asin``, ``acos``,
    ``atan``, ``atan2``) give angles in radians: power 1.  Numbers and the
    values of other functions (``sin``, ``cos``, ``tan``, ``sqrt`` of numbers)
    are pure numbers: power 0.  Powers add over a product, multiply under a
    rational power, and a sum takes the largest over its terms.  So ``pi/6``,
    ``2*atan(1/2)`` and ``pi/6 + 1`` have power 1 (radian values), ``sqrt(3)/2``
    and ``cos(pi/12)`` power 0, and ``asin(1/2)*180/pi`` (a radian value
    converted to degrees) power 0.
    """
    if isinstance(value, PiRational):
        return value.pi_power
    if not is_sympy(value):
        return 0
    if value == sympy.pi:
        return sympy.Integer(1)
    if isinstance(value, sympy.asin | sympy.acos | sympy.atan | sympy.atan2):
        return sympy.Integer(1)
    if isinstance(value, sympy.Mul):
        return sum((radian_power(a) for a in value.args), sympy.Integer(0))
    if isinstance(value, sympy.Add):
        return max(radian_power(a) for a in value.args)
    if isinstance(value, sympy.Pow):
        return radian_power(value.base) * value.exp
    return sympy.Integer(0)
