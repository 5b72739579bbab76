"""Sphinx configuration of mechsing's API reference, built from the docstrings.

Build it (the ``docs`` extra installs Sphinx), warnings as errors, into a git-ignored folder:

    python -m sphinx -W --keep-going -b html docs/api docs/api/_build
"""

import sys
from pathlib import Path

# the checkout's own package, installed or not (the catalog is found beside it)
sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

import mechsing  # noqa: E402

project = "mechsing"
author = "the mechsing authors"
release = version = mechsing.__version__
extensions = ["sphinx.ext.autodoc", "sphinx.ext.napoleon"]
exclude_patterns = ["_build"]

# the docstrings are NumPy style (Parameters / Returns / Raises sections) with reST roles
napoleon_google_docstring = False
napoleon_numpy_docstring = True
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_default_options = {"members": True, "show-inheritance": True}

html_theme = "alabaster"
html_title = f"mechsing {release}: API reference"
