"""The test suite's own house rules, checked on its source with ast (lazy imports included):

* no module under tests/ imports from a test module (test_*.py): shared helpers live in helper
  modules (tests/mechanisms.py, tests/cli.py, tests/strategies.py, tests/reference/, ...);
* the reference implementation (tests/reference/) imports nothing from mechsing, directly or
  through another module of tests/;
* hypothesis strategies are defined in tests/strategies.py only;
* no mechanism (its units, bodies and joints) is pasted in two places of tests/: one home,
  tests/mechanisms.py (or a file), each test adding its own inputs and configurations;
* no file of the project (README, docs, examples, catalog, mechsing, tests, benchmarks, .ci)
  points at documents outside it: every rule a docstring or comment relies on is stated there,
  or named by the README section or the published source that states it.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent
ROOT = TESTS.parent


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {_module_name(p): p for p in sorted(TESTS.rglob("*.py"))}


def _imports(name: str) -> set[str]:
    """Every module ``name`` imports anywhere in its body (absolute names; ``from X import Y``
    gives X and X.Y)."""
    path = MODULES[name]
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            out.add(mod)
            out.update(f"{mod}.{a.name}" for a in node.names)
    return out


def _is_test_module(name: str) -> bool:
    return name.rpartition(".")[2].startswith("test_") and name in MODULES


def test_the_walker_sees_every_kind_of_import(tmp_path: Path) -> None:
    """The checks below rest on _imports: relative, lazy and ``from package import module``."""
    assert "tests.reference.se3" in _imports("tests.reference.kinematics")
    assert "tests.families" in _imports("tests.test_extremes")  # from tests import families
    assert "tests.mechanisms" in _imports("tests.test_input_values")  # from .mechanisms import
    assert "mechsing.lie" in _imports("tests.strategies")  # a lazy import inside a function
    assert _is_test_module("tests.test_house") and not _is_test_module("tests.mechanisms")


@pytest.mark.parametrize("name", sorted(MODULES))
def test_no_module_imports_from_a_test_module(name: str) -> None:
    bad = sorted(m for m in _imports(name) if _is_test_module(m) and m != name)
    assert not bad, f"{name} imports from test modules {bad}: move the helper to a helper module"


def test_the_reference_implementation_imports_nothing_from_mechsing() -> None:
    reference = [m for m in MODULES if m == "tests.reference" or m.startswith("tests.reference.")]
    assert {"tests.reference.se3", "tests.reference.kinematics"} <= set(reference)
    seen: set[str] = set()
    todo = list(reference)
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        for m in _imports(name):
            assert m != "mechsing" and not m.startswith("mechsing."), (
                f"{name} imports {m}: the reference must stay independent of mechsing"
            )
            if m in MODULES:
                todo.append(m)  # a helper module of tests/: its imports count too


def test_hypothesis_strategies_live_in_strategies_py() -> None:
    """No other module defines a composite strategy (one set of strategies, with parameters
    where tests need variants)."""
    for name, path in MODULES.items():
        if name == "tests.strategies":
            continue
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.FunctionDef):
                decorators = {ast.unparse(d) for d in node.decorator_list}
                assert "st.composite" not in decorators, f"{name}.{node.name}: a strategy"


#: what no file of the project may name: documents that are not part of it (spelt in pieces so
#: that this file does not name them itself)
OUTSIDE_DOCUMENTS = ("DESIGN" + ".md", "theory" + ".md", "../" + "shared")
#: the parts of the project, besides the files at its top level
PROJECT_PARTS = ("docs", "examples", "catalog", "mechsing", "tests", "benchmarks", ".ci")
#: what is not the project's own text: version control, environments, caches, builds
NOT_PROJECT = {".git", ".venv", "__pycache__", ".pytest_cache", ".ruff_cache", ".hypothesis"}
NOT_PROJECT |= {"build", "dist"}


def project_files(root: Path) -> list[Path]:
    """Every file of the project under ``root``: the files at its top level and those of
    PROJECT_PARTS, without NOT_PROJECT and ``*.egg-info`` folders."""

    def kept(path: Path) -> bool:
        rel = path.relative_to(root).parts
        return not any(p in NOT_PROJECT or p.endswith(".egg-info") for p in rel)

    files = [p for p in root.iterdir() if p.is_file()]
    for part in PROJECT_PARTS:
        files += [p for p in (root / part).rglob("*") if p.is_file() and kept(p)]
    return sorted(p for p in files if kept(p))


def outside_references(root: Path) -> list[str]:
    """``path: word`` for every project file under ``root`` that names an OUTSIDE_DOCUMENTS."""
    found = []
    for path in project_files(root):
        data = path.read_bytes()
        found += [f"{path.relative_to(root)}: {w}" for w in OUTSIDE_DOCUMENTS if w.encode() in data]
    return found


def test_the_outside_document_search_finds_a_planted_reference(tmp_path: Path) -> None:
    """The search below sees top-level files and every part, and skips caches and .git."""
    (tmp_path / "tests" / "__pycache__").mkdir(parents=True)
    (tmp_path / ".git").mkdir()
    (tmp_path / "examples").mkdir()
    word = OUTSIDE_DOCUMENTS[0]
    (tmp_path / "README.md").write_text(f"see {word}\n")
    (tmp_path / "examples" / "a.yaml").write_text(f"# {OUTSIDE_DOCUMENTS[2]}/x\n")
    (tmp_path / "tests" / "__pycache__" / "x.pyc").write_bytes(word.encode())
    (tmp_path / ".git" / "HEAD").write_text(word)
    assert outside_references(tmp_path) == [
        f"README.md: {word}",
        f"{Path('examples', 'a.yaml')}: {OUTSIDE_DOCUMENTS[2]}",
    ]


def test_no_project_file_points_at_documents_outside_the_project() -> None:
    files = {p.relative_to(ROOT).as_posix() for p in project_files(ROOT)}
    assert {"README.md", "tests/test_house.py", "mechsing/__init__.py"} <= files
    for part in ("examples/", "catalog/", "benchmarks/", ".ci/"):
        assert any(f.startswith(part) for f in files), part
    bad = outside_references(ROOT)
    assert not bad, "state the rule itself, or name the README section or the paper: " + str(bad)


#: the package whose modules hold the decision thresholds (mechsing.numeric.tolerances)
PACKAGE = ROOT / "mechsing"


def tolerance_defaults(source: str) -> list[str]:
    """``function(arg=default)`` for every argument of ``source`` whose name speaks of a
    tolerance (``atol``, ``rtol``, ``tol``, ``*_tol``, ``eps``) and whose default is not None:
    a tolerance hidden as a default argument, which a caller never sees."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            continue
        a = node.args
        pos = a.posonlyargs + a.args
        pairs = list(zip(pos[len(pos) - len(a.defaults) :], a.defaults, strict=True))
        pairs += [(k, d) for k, d in zip(a.kwonlyargs, a.kw_defaults, strict=True) if d]
        for arg, default in pairs:
            name = arg.arg.lower()
            if not ("tol" in name.split("_") or name.endswith("tol") or name == "eps"):
                continue
            if isinstance(default, ast.Constant) and default.value is None:
                continue
            found.append(f"{getattr(node, 'name', 'lambda')}({arg.arg}={ast.unparse(default)})")
    return found


def test_the_default_search_finds_a_planted_tolerance() -> None:
    planted = (
        "def f(x, atol=1e-9, closure=None): pass\n"
        "def g(*, rtol=TOL, tol=None): pass\n"
        "h = lambda v, eps=1e-12: v\n"
        "def k(stol_ratio=2, tolerance=None, protocol=3): pass\n"
    )
    assert tolerance_defaults(planted) == ["f(atol=1e-09)", "g(rtol=TOL)", "lambda(eps=1e-12)"]


def test_no_tolerance_is_a_default_argument_outside_numeric() -> None:
    """Every decision tolerance lives in mechsing.numeric; elsewhere a tolerance is passed
    by the caller (from numeric, or from a named setting beside its code), never a default."""
    bad = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if path.relative_to(PACKAGE).parts[0] == "numeric":
            continue
        bad += [f"{path.relative_to(ROOT)}: {d}" for d in tolerance_defaults(path.read_text())]
    assert not bad, "pass the tolerance from mechsing.numeric (or a named setting): " + str(bad)


def mechanism_texts(source: str) -> list[tuple[int, str]]:
    """(line, the bodies and joints as read) of every string in ``source`` that reads as a
    mechanism file (a YAML mapping with ``bodies`` and ``joints``); a template that does not
    read as YAML (braces to fill) is not one."""
    import json

    import yaml

    found = []
    for node in ast.walk(ast.parse(source)):
        if not (isinstance(node, ast.Constant) and isinstance(node.value, str)):
            continue
        if "bodies" not in node.value or "joints" not in node.value:
            continue
        try:
            doc = yaml.safe_load(node.value)
        except yaml.YAMLError:
            continue
        if isinstance(doc, dict) and "bodies" in doc and "joints" in doc:
            key = {k: doc.get(k) for k in ("units", "bodies", "joints")}
            found.append((node.lineno, json.dumps(key, sort_keys=True, default=str)))
    return found


def test_the_text_search_finds_a_planted_pair() -> None:
    joints = (
        "bodies: [g, a]\\njoints:\\n  - {name: A, type: R, between: [g, a], axis: [0, 0, 1]}\\n"
    )
    planted = (
        f'X = "mechanism: x\\n{joints}"\nY = "{joints}inputs: [A]\\n"\nZ = "bodies and joints"\n'
    )
    (a, ka), (b, kb) = mechanism_texts(planted)
    assert (a, b) == (1, 2) and ka == kb


def test_no_mechanism_is_pasted_twice_in_the_tests() -> None:
    """A mechanism several test modules use (its units, bodies and joints) is written once, in a
    helper module (tests/mechanisms.py) or a file (examples/, tests/data/), and each test adds
    its name, inputs, masses and configurations to it."""
    seen: dict[str, list[str]] = {}
    for path in sorted(TESTS.rglob("*.py")):
        if "reference" in path.relative_to(TESTS).parts:
            continue  # the independent code states its own
        for line, key in mechanism_texts(path.read_text(encoding="utf-8")):
            seen.setdefault(key, []).append(f"{path.relative_to(ROOT)}:{line}")
    pasted = [places for places in seen.values() if len(places) > 1]
    assert not pasted, "give these texts one home in tests/mechanisms.py: " + str(pasted)
