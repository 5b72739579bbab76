"""Renderers of an analysis: JSON (the machine contract), text and Markdown; and the
design-review report (:func:`report`: one self-contained HTML file, or Markdown with its
figures beside it).

``mechsing.report`` names both this package and the function :func:`report` (the public
API): once the package is imported, Python binds the name ``mechsing.report`` to the
package, so the package is made callable and calling it calls :func:`report`.
"""

import sys
import types
from typing import Any

from mechsing.report.render import render, to_json_text
from mechsing.report.review import Report, report

__all__ = ["Report", "render", "report", "to_json_text"]


class _CallablePackage(types.ModuleType):
    """This package, callable as :func:`report` (see the module docstring)."""

    def __call__(self, *args: Any, **kwargs: Any) -> Report:
        return report(*args, **kwargs)


sys.modules[__name__].__class__ = _CallablePackage
