"""The result of ``mechsing condition``: conditions, their factors, and renderings.

A :class:`ConditionResult` holds one or more :class:`Condition` (an output
Jacobian's determinant, the input and output conditions of a loop or of a
parallel robot ...), each a constant times a product of :class:`Factor`.  The
expressions are sympy expressions in the joint variables (symbols named by
the joints, values in radians or metres as the joint's coordinate, measured
from the pose drawn in the file), the pose variables ``x``, ``y`` (m) and
``phi`` (rad) of a parallel robot, and the parameters kept symbolic.

Renderings: :meth:`ConditionResult.to_json` (the JSON shape docs/conditions.md
states; every number in SI units and radians), :meth:`ConditionResult.text`
and :meth:`ConditionResult.latex` (``sympy.latex``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import sympy

from mechsing.analysis.display import floor_for, shown, with_unit

__all__ = ["Condition", "ConditionResult", "Factor"]


@dataclass(frozen=True)
class Factor:
    """One factor of a condition, raised to ``power``.

    ``meaning`` says what its vanishing means where it is recognised (None
    otherwise); ``value`` and ``vanishes`` are set when a configuration was
    given (the factor's value there, and whether it is zero to the precision
    of the evaluation); ``name`` is the name people give the singularity
    (``"wrist"``, ``"elbow"``, ``"shoulder"``: :data:`mechsing.singularity.names.NAMES`),
    where its geometry shows one.
    """

    expression: Any
    power: int = 1
    meaning: str | None = None
    value: float | None = None
    vanishes: bool | None = None
    name: str | None = None


@dataclass(frozen=True)
class Condition:
    """A singularity condition ``constant * prod(factor ** power) = 0``.

    ``name`` says which singularity (``"output Jacobian"``, ``"input (type I)"``
    ...), ``form`` how it was obtained (``"determinant"``, ``"gcd of maximal
    minors"``, ``"eliminated"``), ``variables`` the symbols it is written in,
    ``note`` a sentence for people (what the determinant is of, what it
    means when the gcd is 1, where elimination failed), ``roots`` the values
    of a single variable where it vanishes (eliminated conditions).
    """

    name: str
    form: str
    variables: tuple[str, ...]
    constant: Any
    factors: tuple[Factor, ...]
    note: str = ""
    roots: tuple[float, ...] = ()
    units: tuple[str, ...] = ()

    @property
    def expression(self) -> Any:
        """The condition as one sympy expression: the constant times the factors' powers."""
        out = self.constant
        for f in self.factors:
            out = out * f.expression**f.power
        return out

    def product_text(self) -> str:
        """``constant*(factor)*(factor)**2 ...`` as written (sympy would distribute a
        rational constant into the first factor)."""
        sign = "-" if self.constant == -1 else ""
        parts = [] if self.constant in (1, -1) else [sympy.sstr(self.constant)]
        alone = self.constant in (1, -1) and len(self.factors) == 1 and self.factors[0].power == 1
        alone = alone and (
            self.constant == 1 or not isinstance(self.factors[0].expression, sympy.Add)
        )
        for f in self.factors:
            e = sympy.sstr(f.expression)
            if isinstance(f.expression, sympy.Add) and not alone:
                e = f"({e})"
            parts.append(e if f.power == 1 else f"{e}**{f.power}")
        return sign + ("*".join(parts) if parts else "1")

    def latex(self) -> str:
        """``constant \\cdot factor \\cdot factor^{2} ...`` in LaTeX (without ``= 0``)."""
        parts = []
        for f in self.factors:
            body = sympy.latex(f.expression)
            alone = len(self.factors) == 1 and f.power == 1 and self.constant == 1
            if isinstance(f.expression, sympy.Add) and not alone:
                body = rf"\left({body}\right)"
            parts.append(body if f.power == 1 else f"{body}^{{{f.power}}}")
        const = sympy.latex(self.constant)
        if self.constant == 1 and parts:
            return r" \cdot ".join(parts)
        if self.constant == -1 and parts:
            return "-" + r" \cdot ".join(parts)
        return r" \cdot ".join([const, *parts])

    @property
    def vanishes(self) -> bool | None:
        """True when a factor vanishes at the configuration, None when one cannot be evaluated."""
        flags = [f.vanishes for f in self.factors]
        if not flags or any(v is None for v in flags):
            return None
        return any(flags)


#: the display floor of a root: the roots are float's (numpy.roots), so a root below float's
#: closure tolerance at a unit length scale is round-off of 0
_ROOT_FLOOR_PRECISION = "float"


def _roots(roots: Any, unit: str) -> str:
    """The roots of a condition with their unit (``0.5, 2.1 rad``; a bare list when the
    unit is not known), each below the display floor shown as 0."""
    floor = floor_for(_ROOT_FLOOR_PRECISION, 1.0)
    text = ", ".join(shown(r, floor) for r in roots)
    return with_unit(text, unit) if unit else text


@dataclass(frozen=True)
class ConditionResult:
    """All the conditions of one mechanism file (see the module docstring)."""

    mechanism: str
    method: str
    symbolic: tuple[str, ...]
    parameters: dict[str, Any]
    conditions: tuple[Condition, ...]
    notes: tuple[str, ...] = ()
    configuration: str | None = None
    values: dict[str, float] = field(default_factory=dict)
    #: the file's angle unit: the text also shows angles in degrees for a "deg" file
    file_angle_unit: str = "rad"

    # -- renderings ---------------------------------------------------------

    def to_json(self) -> dict[str, Any]:
        """A JSON-serialisable dict (the shape ``mechsing condition --format json`` prints)."""
        return {
            "mechanism": self.mechanism,
            "method": self.method,
            "symbolic": list(self.symbolic),
            "parameters": {k: float(sympy.N(v, 17)) for k, v in self.parameters.items()},
            "configuration": self.configuration,
            "values": dict(self.values),
            "conditions": [
                {
                    "name": c.name,
                    "form": c.form,
                    "variables": list(c.variables),
                    "expression": c.product_text(),
                    "latex": c.latex(),
                    "constant": str(c.constant),
                    "factors": [
                        {
                            "expression": str(f.expression),
                            "latex": sympy.latex(f.expression),
                            "power": int(f.power),
                            "meaning": f.meaning,
                            "value": f.value,
                            "vanishes": f.vanishes,
                            "name": f.name,
                        }
                        for f in c.factors
                    ],
                    "note": c.note,
                    "roots": [float(r) for r in c.roots],
                    "root_units": list(c.units),
                    "vanishes": c.vanishes,
                }
                for c in self.conditions
            ],
            "notes": list(self.notes),
        }

    def text(self) -> str:
        """The conditions for people."""
        lines = [f"mechsing condition: {self.mechanism} ({self.method})"]
        if self.symbolic:
            lines.append(f"Symbolic parameters: {', '.join(self.symbolic)}")
        fixed = {k: v for k, v in self.parameters.items() if k not in self.symbolic}
        if fixed:
            shown = ", ".join(f"{k} = {v}" for k, v in fixed.items())
            lines.append(f"Parameters at their values: {shown}")
        if self.configuration is not None:
            vals = ", ".join(f"{k} = {v:.6g}" for k, v in self.values.items())
            lines.append(f"At configuration {self.configuration}: {vals}")
        for c in self.conditions:
            lines.append("")
            lines.append(f"{c.name} ({c.form}):")
            if c.factors:
                lines.append(f"  {c.product_text()} = 0")
            else:  # a constant alone (a redundant chain's gcd 1): no equation to write
                lines.append(
                    f"  no equation: its product is {c.product_text()}, which never vanishes"
                )
            if c.note:
                lines.append(f"  {c.note}")
            lines.append(f"  constant: {sympy.sstr(c.constant)}")
            for i, f in enumerate(c.factors, 1):
                power = f"  (power {f.power})" if f.power != 1 else ""
                lines.append(f"  factor {i}: {sympy.sstr(f.expression)}{power}")
                if f.meaning:
                    lines.append(f"    {f.meaning}")
                if f.value is not None:
                    state = "vanishes" if f.vanishes else "does not vanish"
                    lines.append(f"    at {self.configuration}: {f.value:.6g} ({state})")
            if c.roots:
                unit = c.units[0] if c.units else ""
                text = _roots(c.roots, unit)
                if unit == "rad" and self.file_angle_unit == "deg":
                    deg = _roots([r * 180 / math.pi for r in c.roots], "deg")
                    text += f" ({deg})"
                lines.append(f"  vanishes at {c.variables[0]} = {text}".rstrip())
            if c.vanishes is not None:
                verdict = "singular" if c.vanishes else "regular"
                lines.append(f"  => {self.configuration} is {verdict} for this condition")
            elif self.configuration is not None and not c.factors:
                lines.append(
                    f"  => no equation tells whether {self.configuration} is singular; "
                    f"mechsing analyze decides it"
                )
        for n in self.notes:
            lines.append("")
            lines.append(f"Note: {n}")
        return "\n".join(lines) + "\n"

    def markdown(self) -> str:
        """The conditions as Markdown, formulas as ``$...$`` (for notes and slides)."""
        lines = [f"# {self.mechanism}: singularity conditions", "", f"Method: {self.method}."]
        if self.symbolic:
            lines.append(
                "Symbolic parameters: "
                + ", ".join(f"${sympy.latex(sympy.Symbol(n))}$" for n in self.symbolic)
                + "."
            )
        fixed = {k: v for k, v in self.parameters.items() if k not in self.symbolic}
        if fixed:
            lines.append(
                "Parameters at their values: "
                + ", ".join(f"{k} = {v}" for k, v in fixed.items())
                + "."
            )
        if self.configuration is not None:
            vals = ", ".join(f"{k} = {v:.6g}" for k, v in self.values.items())
            lines.append(f"At configuration `{self.configuration}`: {vals}.")
        for c in self.conditions:
            equation = (
                f"${c.latex()} = 0$"
                if c.factors
                else f"No equation: its product is ${c.latex()}$, which never vanishes."
            )
            lines += ["", f"## {c.name} ({c.form})", "", equation, ""]
            if c.note:
                lines += [c.note[0].upper() + c.note[1:] + ".", ""]
            for i, f in enumerate(c.factors, 1):
                power = f" (power {f.power})" if f.power != 1 else ""
                text = f"{i}. ${sympy.latex(f.expression)}${power}"
                if f.meaning:
                    text += f": {f.meaning}"
                if f.value is not None:
                    state = "vanishes" if f.vanishes else "does not vanish"
                    text += f"; at `{self.configuration}`: {f.value:.6g} ({state})"
                lines.append(text)
            if c.roots:
                unit = c.units[0] if c.units else ""
                var = sympy.latex(sympy.Symbol(c.variables[0]))
                lines += ["", f"Vanishes at ${var}$ = {_roots(c.roots, unit)}".rstrip() + "."]
            if c.vanishes is not None:
                verdict = "singular" if c.vanishes else "regular"
                lines += ["", f"`{self.configuration}` is {verdict} for this condition."]
        if self.notes:
            lines += ["", "## Notes", ""]
            lines += [f"- {n}" for n in self.notes]
        return "\n".join(lines) + "\n"

    def latex(self) -> str:
        """The conditions as LaTeX (one ``align*`` environment)."""
        rows = []
        for c in self.conditions:
            expr = c.latex()  # each condition's own form: factors that are sums in parentheses
            if c.factors:
                rows.append(rf"  &\text{{{c.name}}}: && {expr} = 0")
            else:  # a constant alone: no equation (it never vanishes)
                rows.append(
                    rf"  &\text{{{c.name}}}: && \text{{no equation ({expr} never vanishes)}}"
                )
        return "\\begin{align*}\n" + " \\\\\n".join(rows) + "\n\\end{align*}\n"
