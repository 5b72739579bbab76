"""Renderers of an analysis: JSON (the machine contract), text and Markdown."""

from mechsing.report.render import render, to_json_text

__all__ = ["render", "to_json_text"]
