"""The repository holds sources, not what they produce.

What mechsing and its tools write (reports: ``STEM.html``, or ``STEM.md`` with its figures in
``STEM_files/``; a sweep's ``OUT.partial``; the API reference built into ``docs/api/_build/``;
Python's ``__pycache__``; packaging's ``build/``, ``dist/`` and ``*.egg-info``) is ignored by
``.gitignore`` and is not in ``git ls-files``.  Run in a git checkout (CI's clone is one).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path, PurePosixPath

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: folders of test fixtures whose names end like a report's figure folder (``STEM_files``)
FIXTURE_FOLDERS = {"tests/bad_files"}
#: the first line of every Markdown report (mechsing.reports.review's title)
REPORT_TITLE = "# Design review:"


def _git(*args: str, stdin: str = "") -> subprocess.CompletedProcess[str]:
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("not a git checkout")
    return subprocess.run(
        ["git", *args], cwd=ROOT, input=stdin, capture_output=True, text=True, check=False
    )


def _tracked() -> list[PurePosixPath]:
    run = _git("ls-files", "-z")
    assert run.returncode == 0, run.stderr
    return [PurePosixPath(p) for p in run.stdout.split("\0") if p]


def generated(path: PurePosixPath, first_line: str = "") -> str | None:
    """Why ``path`` (a repository path; a Markdown file's first line) is generated output,
    or None when it is a source."""
    folders = [str(PurePosixPath(*path.parts[: i + 1])) for i in range(len(path.parts) - 1)]
    for folder in folders:
        name = folder.rsplit("/", 1)[-1]
        if name in ("__pycache__", "build", "dist", "_build") or name.endswith(".egg-info"):
            return f"a build or cache folder ({folder}/)"
        if name.endswith("_files") and folder not in FIXTURE_FOLDERS:
            return f"a report's figure folder ({folder}/)"
    if path.suffix in (".pyc", ".pyo", ".partial"):
        return f"a compiled or partial file ({path.suffix})"
    if path.suffix == ".html" and path.parts[0] != "docs":
        return "an HTML report"
    if path.suffix == ".md" and first_line.startswith(REPORT_TITLE):
        return "a Markdown report"
    return None


def test_the_rule_tells_outputs_from_sources() -> None:
    """``generated`` on paths whose answer is known, both ways."""
    outputs = [
        ("review_files/graph.svg", ""),
        ("examples/fourbar_files/config-crank-30.svg", ""),
        ("fourbar.html", ""),
        ("mechsing/__pycache__/cli.cpython-311.pyc", ""),
        ("docs/api/_build/index.html", ""),
        ("mechsing.egg-info/PKG-INFO", ""),
        ("out.csv.partial", ""),
        ("notes/review.md", "# Design review: four-bar"),
    ]
    sources = [
        ("tests/bad_files/zero_axis.yaml", ""),
        ("docs/reports.md", "# Design-review reports"),
        ("README.md", "# mechsing"),
        ("docs/images/report-fourbar.png", ""),
        ("mechsing/reports/review.py", ""),
    ]
    assert all(generated(PurePosixPath(p), f) for p, f in outputs)
    assert not any(generated(PurePosixPath(p), f) for p, f in sources)


def test_the_repository_holds_no_generated_output() -> None:
    bad = []
    for path in _tracked():
        first = ""
        if path.suffix == ".md" and (ROOT / path).is_file():
            with open(ROOT / path, encoding="utf-8") as f:
                first = f.readline()
        why = generated(path, first)
        if why:
            bad.append(f"{path}: {why}")
    assert not bad, "generated output in the repository (git rm it; .gitignore covers it):\n" + (
        "\n".join(bad)
    )


def test_what_mechsing_writes_is_ignored() -> None:
    """Each kind of output, where a user or a tool writes it, is ignored by .gitignore; the
    sources beside it (a fixture folder named like a figure folder included) are not."""
    written = [
        "fourbar.html",
        "review.md",
        "review_files/graph.svg",
        "examples/five_bar_files/sweep.svg",
        "sweep.csv",
        "sweep.csv.partial",
        "old.json",
        "docs/api/_build/index.html",
        "mechsing/__pycache__/cli.cpython-311.pyc",
        "build/lib/mechsing/__init__.py",
        "dist/mechsing-0.1.0-py3-none-any.whl",
        "mechsing.egg-info/PKG-INFO",
    ]
    kept = ["README.md", "tests/bad_files/new_case.yaml", "docs/api/index.rst", "docs/new.md"]
    run = _git("check-ignore", "--no-index", "--stdin", stdin="\n".join(written + kept) + "\n")
    assert run.returncode in (0, 1), run.stderr  # 1: nothing ignored
    ignored = set(run.stdout.split())
    assert sorted(set(written) - ignored) == [], "not ignored"
    assert sorted(set(kept) & ignored) == [], "sources ignored"


# -- running from a checkout that was never installed --------------------------------------


def _uninstalled(path: Path, *args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    """``python -m mechsing ARGS`` with the package imported from ``path``, not installed: -S
    reads no .pth file (so no editable install's finder), PYTHONPATH is ``path`` and then this
    environment's site-packages (numpy and the rest)."""
    paths = sysconfig.get_paths()
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    env["PYTHONPATH"] = os.pathsep.join([str(path), paths["purelib"], paths["platlib"]])
    return subprocess.run(
        [sys.executable, "-S", *args], cwd=cwd, env=env, capture_output=True, text=True
    )


_PROBE = (
    "import importlib.util, mechsing; "
    "print(mechsing.__file__); print(importlib.util.find_spec('mechsing.catalog'))"
)


def test_python_m_mechsing_runs_in_a_checkout_never_installed() -> None:
    """In the checkout (cwd at its root) the package is the checkout's, ``mechsing.catalog``
    does not exist, and the catalog is read from the top-level ``catalog/``: every type."""
    probe = _uninstalled(ROOT, "-c", _PROBE, cwd=ROOT)
    assert probe.returncode == 0, probe.stderr
    assert probe.stdout.split("\n")[:2] == [str(ROOT / "mechsing" / "__init__.py"), "None"]
    run = _uninstalled(ROOT, "-m", "mechsing", "analyze", "examples/fourbar.yaml", cwd=ROOT)
    assert run.returncode == 0, run.stderr
    assert "regular: no singularity" in run.stdout
    listing = _uninstalled(ROOT, "-m", "mechsing", "catalog", cwd=ROOT)
    assert listing.returncode == 0, listing.stderr
    types = len(list((ROOT / "catalog").glob("*.toml")))
    assert listing.stdout.count("  dim ") == types


def test_a_package_without_its_catalog_says_how_to_install(tmp_path: Path) -> None:
    """The package copied alone (no catalog beside it): one line on standard error naming the
    missing catalog and the install command, exit status 2."""
    shutil.copytree(
        ROOT / "mechsing", tmp_path / "mechsing", ignore=shutil.ignore_patterns("__pycache__")
    )
    run = _uninstalled(tmp_path, "-m", "mechsing", "catalog", cwd=tmp_path)
    lines = run.stderr.strip().splitlines()
    assert run.returncode == 2 and len(lines) == 1, run.stderr
    assert "catalog" in lines[0] and "pip install" in lines[0]
