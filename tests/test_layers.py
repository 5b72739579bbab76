"""The layers import only downwards, and no module imports itself back.

Every import of every module of ``mechsing`` is read from its source (the AST, so imports
inside functions count too).  A module may import from its own layer and the layers below
it, never from a layer above; and the graph of imports between modules has no cycle.  The
order is the README's Layout table.
"""

from __future__ import annotations

import ast
from pathlib import Path

import networkx as nx

PACKAGE = Path(__file__).resolve().parents[1] / "mechsing"

#: layers from the bottom up; a module's layer is its first dotted component below mechsing
LAYERS: list[set[str]] = [
    {"errors", "files", "numeric", "timelimit", "yamlnodes"},  # leaves
    {"lie"},
    {"subgroups"},
    {"model"},
    {"formats"},
    {"reader", "adhoc"},
    {"kinematics"},
    {"screws"},
    {"singularity"},
    {"analysis", "conditions"},
    {"assembly"},
    {"statics", "kinetics"},
    {"sweeps"},
    {"exercises"},
    {"reports"},
    {"cli", "__main__"},
]


def _modules() -> dict[str, Path]:
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        out[name] = path
    return out


def _imports(name: str, path: Path, known: set[str]) -> set[str]:
    """The mechsing modules that ``name`` imports, wherever the import stands."""
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                base = ".".join([*up, base] if base else up)
            # "from mechsing.x import y" may import the module mechsing.x.y
            targets = [
                f"{base}.{a.name}" if f"{base}.{a.name}" in known else base for a in node.names
            ]
        else:
            continue
        for t in targets:
            while t and t not in known:
                t = t.rpartition(".")[0]
            if t and t.startswith("mechsing") and t != name:
                found.add(t)
    return found


def _layer(module: str) -> int | None:
    parts = module.split(".")
    if len(parts) == 1:  # the package itself: its public API is loaded lazily, on top
        return len(LAYERS)
    for i, names in enumerate(LAYERS):
        if parts[1] in names:
            return i
    return None


def _graph() -> nx.DiGraph:
    mods = _modules()
    g = nx.DiGraph()
    for name, path in mods.items():
        g.add_node(name)
        for t in _imports(name, path, set(mods)):
            if t != "mechsing":  # "from mechsing import __version__": the package's data
                g.add_edge(name, t)
    return g


def test_every_module_has_a_layer() -> None:
    assert [m for m in _modules() if _layer(m) is None] == []


def test_no_layer_imports_one_above_it() -> None:
    g = _graph()
    upward = [
        f"{a} (layer {_layer(a)}) imports {b} (layer {_layer(b)})"
        for a, b in g.edges
        if _layer(b) > _layer(a)
    ]
    assert upward == []


def test_no_import_cycle() -> None:
    cycles = list(nx.simple_cycles(_graph()))
    assert cycles == []


def test_statics_sweeps_and_assembly_are_layers_of_their_own_without_a_cycle() -> None:
    """Issue 42: statics, sweeps and assembly each in a layer no other of the three
    shares (sweeps above both, which import no sweeps module), and no cycle between the
    packages themselves (statics.along once imported sweeps while sweeps imported statics:
    a cycle the shared layer hid)."""
    layers = {p: _layer(f"mechsing.{p}") for p in ("statics", "sweeps", "assembly")}
    assert len(set(layers.values())) == 3
    assert layers["sweeps"] > max(layers["statics"], layers["assembly"])
    g = _graph()
    packages = nx.DiGraph()
    for a, b in g.edges:
        pa, pb = (m.split(".")[1] if "." in m else m for m in (a, b))
        if pa != pb:
            packages.add_edge(pa, pb)
    assert list(nx.simple_cycles(packages)) == []
    assert not [b for b in packages.successors("statics") if b in ("sweeps", "assembly")]
    assert not [b for b in packages.successors("assembly") if b in ("sweeps", "statics")]


def test_the_reader_sees_what_the_test_reads() -> None:
    """The walk finds imports inside functions, relative imports and 'from x import module'."""
    g = _graph()
    assert g.has_edge("mechsing.cli.analyze", "mechsing.analysis")  # inside run()
    assert g.has_edge("mechsing.analysis.run", "mechsing.errors")
    assert g.has_edge("mechsing.singularity.local", "mechsing.numeric")


def test_importing_a_layer_loads_no_command_and_sets_no_thread_count() -> None:
    """Only the command line limits BLAS threads (in main); a program that imports mechsing's
    layers keeps its own settings."""
    import os
    import subprocess
    import sys

    env = {k: v for k, v in os.environ.items() if not k.endswith("_NUM_THREADS")}
    code = (
        "import os, sys, mechsing.model, mechsing.analysis;"
        "assert 'mechsing.cli' not in sys.modules, 'the CLI was loaded';"
        "assert not [k for k in os.environ if k.endswith('_NUM_THREADS')], 'threads were set'"
    )
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_the_public_api_is_discoverable() -> None:
    import mechsing

    for name in ("lie", "subgroups", "load", "analyze", "scan"):
        assert name in dir(mechsing) and getattr(mechsing, name) is not None
    assert callable(mechsing.lie.exp) and callable(mechsing.subgroups.identify)


def test_the_model_imports_no_format() -> None:
    """mechsing.model reads mechsing YAML and JSON; the other formats (URDF, MJCF, a dh table)
    are read by mechsing.reader, above both, which hands the model what it reads."""
    g = _graph()
    found = [(a, b) for a, b in g.edges if a.startswith("mechsing.model") and ".formats" in b]
    assert found == []
    assert g.has_edge("mechsing.reader", "mechsing.formats.dh")


def test_the_formats_import_no_model() -> None:
    """The formats turn URDF, MJCF and a dh table into mechsing YAML (located values of
    mechsing.yamlnodes, a leaf) and raise the errors of mechsing.errors: they need nothing
    of the model, though the layers would allow it."""
    g = _graph()
    found = [(a, b) for a, b in g.edges if ".formats" in a and b.startswith("mechsing.model")]
    assert found == []
    assert g.has_edge("mechsing.formats.dh", "mechsing.yamlnodes")
    assert g.has_edge("mechsing.formats.xmlsafe", "mechsing.errors")


def _exception_classes() -> dict[str, list[str]]:
    """Module -> the public exception classes it defines (a class whose base is a builtin
    exception or an exception class of mechsing.errors), read from the source."""
    import builtins

    bases = {
        n
        for n in dir(builtins)
        if isinstance(getattr(builtins, n), type)
        and issubclass(getattr(builtins, n), BaseException)
    }
    tree = ast.parse((PACKAGE / "errors.py").read_text(encoding="utf-8"))
    bases |= {c.name for c in tree.body if isinstance(c, ast.ClassDef)}
    out: dict[str, list[str]] = {}
    for name, path in _modules().items():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
                named = {
                    b.id if isinstance(b, ast.Name) else getattr(b, "attr", "") for b in node.bases
                }
                if named & bases:
                    out.setdefault(name, []).append(node.name)
    return out


def test_every_exception_is_defined_in_errors() -> None:
    """mechsing.errors holds every exception class, so that any layer raises or catches any
    of them without importing another layer (a private signal that never leaves its module,
    named with a leading underscore, stays there)."""
    found = _exception_classes()
    assert {m: c for m, c in found.items() if m != "mechsing.errors"} == {}
    assert {"MechanismError", "ExpressionError", "ClosureError", "ExactDataError"} <= set(
        found["mechsing.errors"]
    )
