"""Denavit-Hartenberg tables in a mechanism file: the ``dh`` key.

Owns :func:`expand_dh` and :func:`dh_frames`.  ``dh: {convention: standard |
modified, rows: [{theta, d, a, alpha, type: R | P, name?, body?}, ...]}``
describes a serial chain; it stands for the file's ``bodies`` and ``joints``
(and ``output`` when the file gives none).  Conventions:

* standard (Denavit and Hartenberg; Spong): ``T_i = Rz(theta_i) Tz(d_i) Tx(a_i)
  Rx(alpha_i)``; joint i turns about / slides along z of frame i-1;
* modified (Craig): ``T_i = Rx(alpha_i) Tx(a_i) Rz(theta_i) Tz(d_i)``, the row's
  ``alpha`` and ``a`` being Craig's alpha_{i-1}, a_{i-1}; joint i turns about /
  slides along z of frame i;
* the reference configuration is the table as written (each row's theta and d):
  a joint value is the DH variable minus the row's constant (theta_i - theta for
  R, d_i - d for P);
* lengths (d, a) in the file's length unit, angles (theta, alpha) in its angle
  unit; numbers may be exact expressions (``pi/2``); frames are computed in
  floats and written with round-off below 1e-14 snapped (exactly, as expressions,
  for symbolic conditions or a row holding a parameter kept as a symbol);
* joints ``J1..Jn`` and bodies ``L0..Ln`` (``L0`` the ground) unless a row gives
  ``name`` (its joint) or ``body`` (the link after it); the default inputs are
  all the joints and the default output is the last body (its twist is the tool
  frame's).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mechsing.formats.frames import axis_angle, frame
from mechsing.formats.writer import number
from mechsing.numeric.lazy import sympy
from mechsing.yamlnodes import YMap, YScalar, YSeq, YValue

__all__ = ["CONVENTIONS", "ROW_KEYS", "dh_frames", "expand_dh"]

CONVENTIONS = ("standard", "modified")
ROW_KEYS = ("theta", "d", "a", "alpha", "type", "name", "body")
_X, _Z = np.array([1.0, 0, 0]), np.array([0, 0, 1.0])


def _rz(t: float) -> np.ndarray:
    return frame(axis_angle(_Z, t))


def _rx(t: float) -> np.ndarray:
    return frame(axis_angle(_X, t))


def _tz(d: float) -> np.ndarray:
    return frame(origin=d * _Z)


def _tx(a: float) -> np.ndarray:
    return frame(origin=a * _X)


def dh_frames(rows: list[tuple[float, float, float, float]], convention: str) -> list[np.ndarray]:
    """Frames 0..n in the base frame for rows ``(theta, d, a, alpha)`` (radians, lengths)."""
    t = np.eye(4)
    out = [t]
    for theta, d, a, alpha in rows:
        if convention == "standard":
            t = t @ _rz(theta) @ _tz(d) @ _tx(a) @ _rx(alpha)
        else:
            t = t @ _rx(alpha) @ _tx(a) @ _rz(theta) @ _tz(d)
        out.append(t)
    return out


def exact_frames(rows: list[tuple[Any, Any, Any, Any]], convention: str) -> list[Any]:
    """Frames 0..n as exact sympy matrices, for rows whose values keep symbolic parameters
    (``mechsing condition --symbolic``): the same products as :func:`dh_frames`."""

    def rot(axis: int, t: Any) -> Any:
        c, s = sympy.cos(t), sympy.sin(t)
        m = sympy.eye(4)
        i, j = (0, 1) if axis == 2 else (1, 2)
        m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
        return m

    def move(axis: int, x: Any) -> Any:
        m = sympy.eye(4)
        m[axis, 3] = x
        return m

    t = sympy.eye(4)
    out = [t]
    for theta, d, a, alpha in rows:
        if convention == "standard":
            t = t * rot(2, theta) * move(2, d) * move(0, a) * rot(0, alpha)
        else:
            t = t * rot(0, alpha) * move(0, a) * rot(2, theta) * move(2, d)
        t = t.applyfunc(sympy.expand)
        out.append(t)
    return out


def _exact_vec(v: Any, line: int) -> YSeq:
    """An exact column written as expressions of the file's parameters (by their names).

    The rows' only free symbols are the parameters kept as symbols (the loader's
    ``ParameterSymbol``: a file's numbers are otherwise constants), each written as the
    plain symbol of its name."""

    def text(x: Any) -> str:
        x = sympy.sympify(x)
        named = {p: sympy.Symbol(p.name) for p in x.free_symbols}
        return sympy.sstr(x.xreplace(named))

    return YSeq(tuple(YScalar(text(v[i]), "str", line, True) for i in range(3)), line)


def _s(text: str, line: int) -> YScalar:
    return YScalar(text, "str", line, True)


def _n(x: float, line: int) -> YScalar:
    return YScalar(number(x), "float", line)


def _vec(v: np.ndarray, line: int) -> YSeq:
    return YSeq(tuple(_n(float(c), line) for c in v), line)


def _angle_factor(top: YMap) -> Any:
    """The file's angle unit in radians (read here: the table is expanded before the
    loader reads ``units``, which checks it)."""
    units = top.get("units")
    angle = units.get("angle") if isinstance(units, YMap) else None
    if isinstance(angle, YScalar) and angle.text.strip() == "deg":
        return sympy.pi / 180
    return sympy.Integer(1)


def expand_dh(top: YMap, r: Any, keep_exact: bool = False) -> YMap:
    """``top`` with its ``dh`` table replaced by the bodies, joints (and output) it defines.

    ``r`` is the loader's reader (messages naming the file and line, numbers in the
    file's units).  The frames are computed in floats, or exactly (written as
    expressions) when a row holds a parameter kept as a symbol or ``keep_exact`` asks
    (symbolic conditions: a float frame's rounding, rationalised, hides the factors)."""
    dh = top.get("dh")
    line = top.key_line("dh")
    for clash in ("joints", "bodies"):
        if top.get(clash) is not None:
            raise r.error(
                "dh",
                top.key_line(clash),
                f"the file has both dh and {clash}: a dh table defines the bodies and joints "
                f"of a serial chain; remove {clash} (name bodies and joints in the rows with "
                "body: and name:) or remove dh",
            )
    m = r.mapping(dh, "dh", "dh (convention: standard, rows: [...])")
    r.keys(m, "dh", ("convention", "rows"), ("rows",))
    convention = "standard"
    if m.get("convention") is not None:
        convention = r.name(m.get("convention"), "dh", "dh.convention")
        if convention not in CONVENTIONS:
            raise r.error(
                "dh",
                m.key_line("convention"),
                f"convention {convention!r} is not one of {', '.join(CONVENTIONS)} "
                "(standard: Rz Tz Tx Rx; modified (Craig): Rx Tx Rz Tz)",
            )
    seq = r.sequence(
        m.get("rows"), "dh", "dh.rows", "rows: [{theta: 0, d: 0.1, a: 0, alpha: pi/2, type: R}]"
    )
    if not seq.items:
        raise r.error("dh", seq.line, "dh.rows is empty; give one row per joint")
    rows: list[tuple[float, float, float, float]] = []
    exact: list[tuple[Any, Any, Any, Any]] = []  # the rows' exact values (parameters kept)
    meta: list[tuple[str, str, str, int]] = []
    names: set[str] = set()
    bodies = ["L0"]
    for i, e in enumerate(seq.items, start=1):
        item = f"dh row {i}"
        row = r.mapping(e, item, "a dh row")
        r.keys(row, item, ROW_KEYS, ("theta", "d", "a", "alpha"), hint="a DH row")
        af = _angle_factor(top)

        def val(key: str, f: Any, row: YMap = row, item: str = item) -> Any:
            return r.number(row.get(key), item, key) * f

        # file lengths (d, a): the points are written in them
        values = (val("theta", af), val("d", 1), val("a", 1), val("alpha", af))
        exact.append(values)
        theta, d, a, alpha = (float(sympy.N(x, 20)) for x in values)
        jtype = "R"
        if row.get("type") is not None:
            jtype = r.name(row.get("type"), item, "type")
            if jtype not in ("R", "P"):
                raise r.error(item, row.key_line("type"), f"type {jtype!r}: a DH joint is R or P")
        jname = r.name(row.get("name"), item, "name") if row.get("name") is not None else f"J{i}"
        body = r.name(row.get("body"), item, "body") if row.get("body") is not None else f"L{i}"
        if jname in names:
            raise r.error(item, row.key_line("name"), f"joint name {jname!r} is used twice")
        names.add(jname)
        if body in bodies:
            raise r.error(item, row.key_line("body"), f"body name {body!r} is used twice")
        bodies.append(body)
        if not all(math.isfinite(x) for x in (theta, d, a, alpha)):
            raise r.error(item, row.line, "the row's numbers must be finite")  # pragma: no cover
        rows.append((theta, d, a, alpha))
        meta.append((jname, jtype, body, row.line))
    symbolic = any(sympy.sympify(x).free_symbols for row_values in exact for x in row_values)
    symbolic = symbolic or keep_exact
    frames = exact_frames(exact, convention) if symbolic else dh_frames(rows, convention)
    vec = _exact_vec if symbolic else _vec
    joints: list[YValue] = []
    prev = bodies[0]
    for i, (jname, jtype, body, ln) in enumerate(meta):
        f = frames[i] if convention == "standard" else frames[i + 1]
        items: list[tuple[YScalar, YValue]] = [
            (_s("name", ln), _s(jname, ln)),
            (_s("type", ln), YScalar(jtype, "str", ln)),
            (_s("between", ln), YSeq((_s(prev, ln), _s(body, ln)), ln)),
            (_s("axis", ln), vec(f[:3, 2], ln)),
        ]
        if jtype == "R":
            items.append((_s("point", ln), vec(f[:3, 3], ln)))
        joints.append(YMap(tuple(items), ln))
        prev = body
    new: list[tuple[YScalar, YValue]] = []
    for k, v in top.items:
        if k.text == "dh":
            new.append((_s("bodies", line), YSeq(tuple(_s(b, line) for b in bodies), line)))
            new.append((_s("joints", line), YSeq(tuple(joints), line)))
            if top.get("output") is None:
                out = YMap(((_s("body", line), _s(bodies[-1], line)),), line)
                new.append((_s("output", line), out))
            if top.get("inputs") is None:
                names_seq = tuple(_s(m[0], line) for m in meta)
                new.append((_s("inputs", line), YSeq(names_seq, line)))
        else:
            new.append((k, v))
    if top.get("ground") is None:
        new.insert(0, (_s("ground", line), _s(bodies[0], line)))
    return YMap(tuple(new), top.line)
