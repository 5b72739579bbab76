"""The sweeps package's house: modules of one idea each, and a face that only re-exports.

Read with ast from the source: each module of ``mechsing/sweeps`` says in its docstring
what it owns (``Owns ...``), and ``sweeps/__init__.py`` holds nothing but its docstring,
imports and ``__all__``.  The size limits of modules and classes, the whole package's,
are tests/test_sizes.py's.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "mechsing" / "sweeps"

MODULES = sorted(p for p in PACKAGE.glob("*.py") if p.name != "__init__.py")


def _faults(name: str, text: str) -> list[str]:
    """What breaks the house rules in the module ``name`` whose source is ``text``."""
    doc = ast.get_docstring(ast.parse(text, name)) or ""
    return [] if "Owns " in doc else [f"{name}: its docstring does not say what it owns"]


@pytest.mark.parametrize("path", MODULES, ids=[p.name for p in MODULES])
def test_each_sweeps_module_says_what_it_owns(path: Path) -> None:
    assert _faults(path.name, path.read_text(encoding="utf-8")) == []


def test_the_rule_sees_a_silent_docstring() -> None:
    assert _faults("m.py", '"""Owns A."""\nx = 1\n') == []
    assert _faults("m.py", '"""A module."""\nx = 1\n') == [
        "m.py: its docstring does not say what it owns"
    ]


def test_the_sweeps_package_face_only_re_exports() -> None:
    path = PACKAGE / "__init__.py"
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    body = tree.body[1:] if ast.get_docstring(tree) else tree.body
    for node in body:
        is_all = isinstance(node, ast.Assign) and [
            getattr(t, "id", None) for t in node.targets
        ] == ["__all__"]
        assert isinstance(node, ast.Import | ast.ImportFrom) or is_all, (
            f"sweeps/__init__.py line {node.lineno}: code in the package face "
            "(move it into the module that owns it)"
        )
