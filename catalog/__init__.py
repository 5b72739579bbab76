"""The subgroup catalog of mechsing as package data: ``mechsing.catalog``.

The build maps this folder into the package (``pyproject.toml``), so the
TOML files here are read with :mod:`importlib.resources` in editable and wheel
installs alike.  There is no code here; see ``README.md`` for the format.
"""
