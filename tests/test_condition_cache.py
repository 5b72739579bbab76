"""The derivations a process remembers (``mechsing.conditions.derive._derived``): by the
content of the mechanism, never by a file's name or an object's identity."""

from __future__ import annotations

from pathlib import Path

import sympy

from mechsing.conditions import condition, derive

FOURBAR = """\
mechanism: four-bar
bodies: [ground, crank, coupler, rocker]
joints:
  - {{name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [1, 0, 0]}}
  - {{name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [{cx}, 2, 0]}}
  - {{name: D, type: R, between: [rocker, ground], axis: [0, 0, 1], point: [4, 0, 0]}}
inputs: [A]
output: {{body: rocker}}
configurations:
  reference: {{}}
"""


def _fresh(path: Path, **kw: object) -> object:
    kept = dict(derive._DERIVED)
    derive._DERIVED.clear()
    try:
        return condition(path, **kw)  # type: ignore[arg-type]
    finally:
        derive._DERIVED.clear()
        derive._DERIVED.update(kept)


def test_the_same_file_rewritten_is_derived_again(tmp_path: Path) -> None:
    path = tmp_path / "fourbar.yaml"
    path.write_text(FOURBAR.format(cx=3), encoding="utf-8")
    first = condition(path)
    path.write_text(FOURBAR.format(cx="7/2"), encoding="utf-8")
    second = condition(path)
    assert second != first
    assert second == _fresh(path)


def test_the_same_content_is_derived_once(tmp_path: Path) -> None:
    path = tmp_path / "fourbar.yaml"
    path.write_text(FOURBAR.format(cx=3), encoding="utf-8")
    first = condition(path)
    size = len(derive._DERIVED)
    again = condition(path)
    evaluated = condition(path, config="reference")
    assert len(derive._DERIVED) == size
    assert again == first == _fresh(path)
    assert evaluated == _fresh(path, config="reference")
    assert [f.expression for c in evaluated.conditions for f in c.factors] == [
        f.expression for c in first.conditions for f in c.factors
    ]


def test_the_key_tells_apart_what_prints_alike() -> None:
    key = derive._content_key
    assert key(sympy.Float("0.1", 15)) != key(sympy.Float("0.1", 30))
    assert key(sympy.Symbol("a", real=True)) != key(sympy.Symbol("a"))
    assert key(sympy.Dummy("a")) != key(sympy.Dummy("a"))
    assert key((1, 2)) != key(((1, 2),))
    assert key({"a": 1}) == key({"a": 1})
    assert key(object()) is None
