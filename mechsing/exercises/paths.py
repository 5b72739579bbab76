"""The path language of exercise answers: where an answer is in mechsing's JSON output.

A path is dotted parts, each a key, a list index, ``key=value`` (the first list item whose
``key`` is ``value``) or ``*`` (every item: the answer is then a set), e.g.
``configurations.name=reference.mobility.finite`` or ``located.0.classes``.  The bundled
exercises' ``answers.yaml`` and the templates' questions use it alike.
"""

from __future__ import annotations

from typing import Any

__all__ = ["walk"]


def walk(data: Any, path: str) -> Any:
    """The value at ``path`` in a JSON document (KeyError, IndexError or StopIteration when
    there is none)."""
    parts = path.split(".")
    for i, part in enumerate(parts):
        if part == "*":
            rest = ".".join(parts[i + 1 :])
            items = [walk(x, rest) if rest else x for x in data]
            return set(items)
        if "=" in part:
            key, want = part.split("=", 1)
            data = next(x for x in data if str(x.get(key)) == want)
        elif isinstance(data, list):
            data = data[int(part)]
        else:
            data = data[part]
    return data
