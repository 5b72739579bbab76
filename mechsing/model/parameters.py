"""Named parameters of a mechanism file (the ``parameters:`` mapping).

A file may declare ``parameters: {a2: 0.425, a3: "a2 - 0.033"}`` and use the
names in every number it takes (points, axes, pitches, the output point,
configuration values, poses, ``characteristic_length``).  This module owns
reading that mapping and the :class:`ParameterSymbol` that keeps a parameter
symbolic for ``mechsing condition --symbolic``.

Conventions:

* a parameter's value is a plain number or an expression (the whitelist of
  :mod:`mechsing.model.expressions`) of *earlier* parameters, read exactly
  (``0.425`` is 17/40) as every number of the file;
* a parameter is a pure number: where it is used, the unit of that place
  applies (a point's coordinates are lengths in ``units.length``, a joint
  angle is in ``units.angle``), exactly as if its value were written there;
* a name is an identifier (letters, digits, ``_``, not starting with a
  digit) that is not ``pi``, not a whitelisted function name, not a Python
  keyword, and not the name of a body or joint of the file.

Errors are :class:`~mechsing.errors.MechanismError` (exit status 2)
naming the file, the line, the parameter and the fix.
"""

from __future__ import annotations

import keyword
import re
from collections.abc import Collection, Mapping
from typing import Any

from mechsing.errors import ExpressionError
from mechsing.model.expressions import ALLOWED_FUNCTIONS, parse_number
from mechsing.yamlnodes import YMap, YScalar, YSeq

__all__ = [
    "MAX_PARAMETERS",
    "ParameterSymbol",  # noqa: F822 - defined on first use (module __getattr__)
    "check_names",
    "read_parameters",
    "symbolic_values",
]

#: most parameters in one file
MAX_PARAMETERS = 1000

_IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def __getattr__(name: str) -> Any:
    # ParameterSymbol is a sympy class: defined (and sympy imported) when first asked for
    if name == "ParameterSymbol":
        from mechsing.model.symbols import ParameterSymbol

        return ParameterSymbol
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def symbolic_values(expr: Any) -> dict[Any, Any]:
    """The :class:`ParameterSymbol` atoms of ``expr`` mapped to their values."""
    import sympy

    from mechsing.model.symbols import ParameterSymbol

    return {s: s.parameter_value for s in sympy.sympify(expr).atoms(ParameterSymbol)}


def _file_names(top: YMap) -> dict[str, str]:
    """Names of bodies and joints as written (name -> "body"/"joint"), for the clash test."""
    out: dict[str, str] = {}
    bodies = top.get("bodies")
    if isinstance(bodies, YSeq):
        for e in bodies.items:
            if isinstance(e, YScalar):
                out[e.text.strip()] = "body"
    joints = top.get("joints")
    if isinstance(joints, YSeq):
        for e in joints.items:
            if isinstance(e, YMap) and isinstance(e.get("name"), YScalar):
                out[e.get("name").text.strip()] = "joint"  # type: ignore[union-attr]
    return out


def check_names(reader: Any, top: YMap) -> None:
    """No parameter of ``top`` has the name of one of its bodies or joints (called again
    once a ``dh`` table has given the file its bodies and joints)."""
    v = top.get("parameters")
    if not isinstance(v, YMap):
        return
    names = _file_names(top)
    for k, _ in v.items:
        name = k.text.strip()
        if name in names:
            raise reader.error(
                f"parameter {name!r}",
                k.line,
                f"clashes with the {names[name]} {name!r}; give the parameter another name "
                f"(e.g. {name}_length)",
            )


def read_parameters(reader: Any, top: YMap, symbolic: Collection[str] = ()) -> dict[str, Any]:
    """The file's parameters, name -> exact value (or :class:`ParameterSymbol` for
    the names in ``symbolic``), in the order written.

    ``reader`` is the loader's reader (its ``error`` builds the messages).  Every
    name of ``symbolic`` must be a parameter of the file.
    """
    v = top.get("parameters")
    wanted = list(symbolic)
    if v is None:
        if wanted:
            raise reader.error(
                "parameters",
                None,
                f"--symbolic names {', '.join(wanted)}, but the file declares no parameters; "
                "add parameters: {NAME: value} and use the names in the file",
            )
        return {}
    m = reader.mapping(v, "parameters", "parameters (e.g. parameters: {a2: 0.425, a3: 0.392})")
    if len(m.items) > MAX_PARAMETERS:
        raise reader.error(
            "parameters", m.line, f"{len(m.items)} parameters, more than {MAX_PARAMETERS}"
        )
    check_names(reader, top)
    order = {k.text.strip(): k.line for k, _ in m.items}
    values: dict[str, Any] = {}
    for k, pv in m.items:
        name = k.text.strip()
        item = f"parameter {name!r}"
        if not _IDENTIFIER.match(name) or k.kind != "str":
            raise reader.error(
                item,
                k.line,
                "a parameter name is an identifier (letters, digits and _, not starting with "
                "a digit), such as a2 or link_length; rename it",
            )
        if name == "pi" or name in ALLOWED_FUNCTIONS or keyword.iskeyword(name):
            what = (
                "the constant pi"
                if name == "pi"
                else ("a function of expressions" if name in ALLOWED_FUNCTIONS else "a keyword")
            )
            raise reader.error(item, k.line, f"{name!r} is {what}; give the parameter another name")
        if name in values:
            raise reader.error(
                item, k.line, "declared twice; give each parameter one value and one name"
            )
        if not isinstance(pv, YScalar) or pv.kind in ("bool", "null"):
            got = pv.describe() if pv is not None else "nothing"
            raise reader.error(
                item,
                getattr(pv, "line", k.line),
                f"the value must be a number or an expression of earlier parameters, got {got}",
            )
        try:
            value = parse_number(pv.text, values, plain=getattr(reader, "plain", False))
        except ExpressionError as exc:
            later = _later_name(pv.text, order, values)
            if later is not None:
                ref, line = later
                fix = (
                    "a parameter cannot be defined by itself; give it a value"
                    if ref == name
                    else f"move {ref!r} (line {line}) above {name!r}"
                )
                raise reader.error(
                    item,
                    pv.line,
                    f"uses {ref!r}, which is not defined before it (a parameter may use only "
                    f"the parameters above it, so there are no cycles); {fix}",
                ) from None
            unknown = "the name" in str(exc)
            hint = " (no parameter is defined above it)" if unknown and not values else ""
            raise reader.error(item, pv.line, f"{exc}{hint}") from None
        values[name] = value
    missing = [s for s in wanted if s not in values]
    if missing:
        raise reader.error(
            "parameters",
            m.line,
            f"--symbolic names {', '.join(repr(s) for s in missing)}, which "
            f"{'is' if len(missing) == 1 else 'are'} not a parameter of the file; use "
            f"{', '.join(values) if values else 'a declared parameter'}",
        )
    if not wanted:
        return values
    # keep the symbolic ones as symbols: later parameters built from them too
    out: dict[str, Any] = {}
    for k, pv in m.items:
        name = k.text.strip()
        if name in wanted:
            from mechsing.model.symbols import ParameterSymbol

            out[name] = ParameterSymbol(name, values[name])
        else:
            assert isinstance(pv, YScalar)
            out[name] = parse_number(pv.text, out, plain=getattr(reader, "plain", False))
    return out


def _later_name(
    text: str, order: Mapping[str, int], defined: Mapping[str, Any]
) -> tuple[str, int] | None:
    """A parameter name used in ``text`` that is not defined yet (declared later)."""
    for word in re.findall(r"[A-Za-z_][A-Za-z0-9_]*", text):
        if word in order and word not in defined:
            return word, order[word]
    return None
