"""The API reference (docs/api, Sphinx autodoc from the docstrings) builds with no warning and
documents the public API.

Sphinx is the ``docs`` extra: without it these tests are skipped, except in CI, which installs
it and sets MECHSING_REQUIRE_DOCS=1 so that they must run.  The build goes to a temporary
folder (by hand: ``python -m sphinx -W --keep-going -b html docs/api docs/api/_build``, a
git-ignored folder).
"""

from __future__ import annotations

import importlib
import os
import re
import subprocess
import sys
import types
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "docs" / "api"

#: the modules whose every public name (their ``__all__``) the reference documents: the
#: results of the functions, the findings, and the layers a script uses directly
DOCUMENTED_MODULES = (
    "mechsing.analysis.results",
    "mechsing.analysis.solve",
    "mechsing.sweeps",
    "mechsing.sweeps.scan",
    "mechsing.reports.review",
    "mechsing.conditions.results",
    "mechsing.singularity.findings",
    "mechsing.lie",
    "mechsing.subgroups",
)


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> tuple[subprocess.CompletedProcess, Path]:
    required = os.environ.get("MECHSING_REQUIRE_DOCS") == "1"
    try:
        import sphinx  # noqa: F401
    except ImportError:
        if required:
            pytest.fail("MECHSING_REQUIRE_DOCS=1 but Sphinx is not installed (the docs extra)")
        pytest.skip("Sphinx is not installed (pip install -e '.[docs]')")
    out = tmp_path_factory.mktemp("api")
    run = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html"]
        + ["-d", str(out / "doctrees"), str(SOURCE), str(out / "html")],
        capture_output=True,
        text=True,
        env=dict(os.environ, OPENBLAS_NUM_THREADS="1"),
    )
    return run, out / "html"


def _anchors(html: Path) -> set[str]:
    found: set[str] = set()
    for page in html.glob("*.html"):
        found |= set(re.findall(r'\bid="([^"]+)"', page.read_text(encoding="utf-8")))
    return found


def _anchors_of(module: types.ModuleType, name: str) -> set[str]:
    """The ids Sphinx may give the documentation of ``module.name``: ``module-X`` for a
    module, else its dotted name there, or ``mechsing.NAME`` for a function of
    ``mechsing.__all__`` (documented once, under the name a user calls it by)."""
    import mechsing

    if name in mechsing.__all__ and callable(getattr(mechsing, name)):
        return {f"{module.__name__}.{name}", f"mechsing.{name}"}
    obj = getattr(module, name)
    if isinstance(obj, types.ModuleType):
        return {f"module-{obj.__name__}"}
    return {f"{module.__name__}.{name}"}


def test_the_reference_builds_with_no_warning(built) -> None:
    run, html = built
    assert run.returncode == 0, run.stdout + run.stderr
    assert "WARNING" not in run.stderr and "ERROR" not in run.stderr, run.stderr
    assert (html / "index.html").is_file()


def test_every_public_name_of_mechsing_is_documented(built) -> None:
    """Every name of ``mechsing.__all__`` (the functions, ``__version__`` and the layers)."""
    run, html = built
    assert run.returncode == 0, run.stderr
    import mechsing

    anchors = _anchors(html)
    missing = [n for n in mechsing.__all__ if not _anchors_of(mechsing, n) & anchors]
    assert not missing, f"not in the API reference: {missing}"


@pytest.mark.parametrize("name", DOCUMENTED_MODULES)
def test_every_public_name_of_the_results_findings_and_layers_is_documented(
    built, name: str
) -> None:
    """Each of the result types, finding types, ``mechsing.lie`` and ``mechsing.subgroups``:
    every name of its ``__all__`` has its entry (a name without a docstring has none)."""
    run, html = built
    assert run.returncode == 0, run.stderr
    module = importlib.import_module(name)
    anchors = _anchors(html)
    missing = [n for n in module.__all__ if not _anchors_of(module, n) & anchors]
    assert not missing, f"{name}: not in the API reference: {missing}"
