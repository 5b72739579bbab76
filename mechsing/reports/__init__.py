"""Renderers of an analysis: JSON (the machine contract), text and Markdown; and the
design-review report (:func:`report`: one self-contained HTML file, or Markdown with its
figures beside it).

The public API calls the review ``mechsing.report(...)`` (:func:`mechsing.report`, loaded
lazily by the package ``mechsing``); this package is named ``reports`` so that the
function and the package never share a name.
"""

from __future__ import annotations

from typing import Any

from mechsing.reports.render import render, to_json_text

__all__ = ["Report", "render", "report", "to_json_text"]


def __getattr__(name: str) -> Any:
    # the review (and matplotlib, which its figures need) is loaded on first use: the
    # text and JSON renderers, which every analysis uses, start without it
    if name in ("Report", "report"):
        from mechsing.reports import review

        return getattr(review, name)
    raise AttributeError(f"module 'mechsing.reports' has no attribute {name!r}")
