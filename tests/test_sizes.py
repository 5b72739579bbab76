"""No class of mechsing over :data:`CLASS_LINES` lines, no module over :data:`MODULE_LINES`.

Read with ast from the source of every module of the package (classes nested in functions
or classes included): a class that grows past the limit is split by moving a cohesive group
of its methods into a module of their own (functions taking the object, the class keeping
thin methods), a module by splitting it into modules of one idea each.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "mechsing"
MODULE_LINES = 800
CLASS_LINES = 400

MODULES = sorted(PACKAGE.rglob("*.py"))


def _faults(name: str, text: str) -> list[str]:
    """What breaks the size rules in the module ``name`` whose source is ``text``."""
    out = []
    lines = len(text.splitlines())
    if lines > MODULE_LINES:
        out.append(f"{name}: {lines} lines (at most {MODULE_LINES})")
    for node in ast.walk(ast.parse(text, name)):
        if isinstance(node, ast.ClassDef):
            size = (node.end_lineno or node.lineno) - node.lineno + 1
            if size > CLASS_LINES:
                out.append(f"{name}: class {node.name} has {size} lines (at most {CLASS_LINES})")
    return out


@pytest.mark.parametrize("path", MODULES, ids=[str(p.relative_to(PACKAGE.parent)) for p in MODULES])
def test_each_module_and_class_of_mechsing_is_small(path: Path) -> None:
    name = str(path.relative_to(PACKAGE.parent))
    assert _faults(name, path.read_text(encoding="utf-8")) == []


def test_the_rules_see_a_planted_long_class_nested_class_and_long_module() -> None:
    body = "class A:\n" + "    x = 1\n" * CLASS_LINES
    assert _faults("m.py", body) == [
        f"m.py: class A has {CLASS_LINES + 1} lines (at most {CLASS_LINES})"
    ]
    nested = "def f():\n    class B:\n" + "        x = 1\n" * CLASS_LINES
    assert _faults("m.py", nested) == [
        f"m.py: class B has {CLASS_LINES + 1} lines (at most {CLASS_LINES})"
    ]
    assert _faults("m.py", "x = 1\n" * (MODULE_LINES + 1)) == [
        f"m.py: {MODULE_LINES + 1} lines (at most {MODULE_LINES})"
    ]
    assert _faults("m.py", "class A:\n" + "    x = 1\n" * (CLASS_LINES - 1)) == []
