"""Renderers of an analysis: JSON (the machine contract), text and Markdown; and the
design-review report (:func:`report`: one self-contained HTML file, or Markdown with its
figures beside it).

``mechsing.report`` names both this package and the function :func:`report` (the public
API): once the package is imported, Python binds the name ``mechsing.report`` to the
package, so the package is made callable and calling it calls :func:`report`.
"""

from __future__ import annotations

import sys
import types
from typing import TYPE_CHECKING, Any

from mechsing.report.render import render, to_json_text

if TYPE_CHECKING:
    from mechsing.report.review import Report

__all__ = ["Report", "render", "report", "to_json_text"]


def __getattr__(name: str) -> Any:
    # the review (and matplotlib, which its figures need) is loaded on first use: the
    # text and JSON renderers, which every analysis uses, start without it
    if name in ("Report", "report"):
        from mechsing.report import review

        return getattr(review, name)
    raise AttributeError(f"module 'mechsing.report' has no attribute {name!r}")


class _CallablePackage(types.ModuleType):
    """This package, callable as :func:`report` (see the module docstring)."""

    def __call__(self, *args: Any, **kwargs: Any) -> Report:
        from mechsing.report.review import report

        return report(*args, **kwargs)


sys.modules[__name__].__class__ = _CallablePackage
