"""Safe reading of YAML (and JSON) into located values (a leaf module).

The tree of located values is what the model reads and what the formats write
(a ``dh`` table is expanded into bodies and joints as such a tree), so it sits
below both.

``yaml.compose`` (SafeLoader) gives the node graph with line marks and never
constructs Python objects; this module converts the nodes itself into
:class:`YScalar`, :class:`YSeq` and :class:`YMap`, which keep the *text* of
every scalar (so numbers keep their decimal meaning) and the line of every
item.  Aliases are followed with a bound on the total number of items visited
(an alias bomb stops with an error instead of filling memory), recursive
aliases and unknown tags are refused, and duplicate mapping keys are errors.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import yaml

from mechsing.errors import YAMLReadError

__all__ = [
    "MAX_FILE_BYTES",
    "MAX_ITEMS",
    "YAMLReadError",
    "YMap",
    "YScalar",
    "YSeq",
    "YValue",
    "read_yaml_text",
]

#: largest mechanism file accepted, in bytes
MAX_FILE_BYTES = 4 * 1024 * 1024
#: most items (scalars, lists, mappings) in a file, counted after alias expansion
MAX_ITEMS = 200_000

_CORE = "tag:yaml.org,2002:"
_SCALAR_TAGS = {
    _CORE + "str": "str",
    _CORE + "int": "int",
    _CORE + "float": "float",
    _CORE + "bool": "bool",
    _CORE + "null": "null",
    _CORE + "timestamp": "str",  # a date-like plain scalar is read as its text
}


@dataclass(frozen=True)
class YScalar:
    """A scalar with its text as written, its resolved kind and its line."""

    text: str
    kind: str  # "str", "int", "float", "bool" or "null"
    line: int
    quoted: bool = False

    def describe(self) -> str:
        return repr(self.text) if self.quoted or self.kind == "str" else self.text


@dataclass(frozen=True)
class YSeq:
    items: tuple[YValue, ...]
    line: int

    def describe(self) -> str:
        return "a list"


@dataclass(frozen=True)
class YMap:
    """A mapping in file order; keys are the keys' texts."""

    items: tuple[tuple[YScalar, YValue], ...]
    line: int

    def keys(self) -> list[str]:
        return [k.text for k, _ in self.items]

    def get(self, key: str) -> YValue | None:
        for k, v in self.items:
            if k.text == key:
                return v
        return None

    def key_line(self, key: str) -> int:
        for k, _ in self.items:
            if k.text == key:
                return k.line
        return self.line

    def describe(self) -> str:
        return "a mapping"


YValue = YScalar | YSeq | YMap


class _Converter:
    def __init__(self, max_items: int) -> None:
        self.max_items = max_items
        self.count = 0
        self.stack: set[int] = set()

    def convert(self, node: yaml.Node) -> YValue:
        self.count += 1
        line = node.start_mark.line + 1
        if self.count > self.max_items:
            raise YAMLReadError(
                f"the file expands to more than {self.max_items} items (an alias bomb or an "
                "absurdly large file); write the mechanism without so many aliases",
                line,
            )
        if id(node) in self.stack:
            raise YAMLReadError(
                "an alias refers to a list or mapping that contains it "
                "(a recursive alias); remove the recursion",
                line,
            )
        if isinstance(node, yaml.ScalarNode):
            kind = _SCALAR_TAGS.get(node.tag)
            if kind is None:
                raise YAMLReadError(f"the tag {node.tag!r} is not allowed; remove it", line)
            return YScalar(str(node.value), kind, line, node.style not in (None, ""))
        if isinstance(node, yaml.SequenceNode):
            if node.tag != _CORE + "seq":
                raise YAMLReadError(f"the tag {node.tag!r} is not allowed; remove it", line)
            self.stack.add(id(node))
            try:
                return YSeq(tuple(self.convert(n) for n in node.value), line)
            finally:
                self.stack.discard(id(node))
        if isinstance(node, yaml.MappingNode):
            if node.tag != _CORE + "map":
                raise YAMLReadError(f"the tag {node.tag!r} is not allowed; remove it", line)
            self.stack.add(id(node))
            try:
                items = []
                seen: dict[str, int] = {}
                for kn, vn in node.value:
                    if kn.tag == _CORE + "merge":
                        raise YAMLReadError(
                            "merge keys ('<<') are not supported; write the keys out",
                            kn.start_mark.line + 1,
                        )
                    k = self.convert(kn)
                    if not isinstance(k, YScalar):
                        raise YAMLReadError("a mapping key must be a plain name", k.line)
                    if k.text in seen:
                        raise YAMLReadError(
                            f"duplicate key {k.text!r} (first at line {seen[k.text]}); "
                            "keep only one",
                            k.line,
                        )
                    seen[k.text] = k.line
                    items.append((k, self.convert(vn)))
                return YMap(tuple(items), line)
            finally:
                self.stack.discard(id(node))
        raise YAMLReadError(f"unexpected YAML node {type(node).__name__}", line)  # pragma: no cover


def _compose(text: str) -> Any:
    """The document's node tree: libyaml's composer when PyYAML has it (ten times
    faster on a file of a thousand joints), else PyYAML's own.  A document libyaml
    refuses is composed again by PyYAML, so every error message is PyYAML's."""
    fast = getattr(yaml, "CSafeLoader", None)
    if fast is not None:
        try:
            return yaml.compose(text, Loader=fast)
        except (yaml.YAMLError, RecursionError):
            pass
    return yaml.compose(text, Loader=yaml.SafeLoader)


def read_yaml_text(text: str, max_items: int = MAX_ITEMS) -> YValue:
    """Compose one YAML/JSON document safely and convert it to located values.

    Raises
    ------
    YAMLReadError
        malformed YAML (with its line), several documents, an empty file, a
        forbidden tag, a recursive alias, too many items or too deep nesting.
    """
    if len(text) > MAX_FILE_BYTES:
        raise YAMLReadError(
            f"the file has more than {MAX_FILE_BYTES} characters; that is not a mechanism"
        )
    try:
        node = _compose(text)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else None
        problem = exc.problem or "malformed YAML"
        ctx = f" ({exc.context})" if exc.context else ""
        raise YAMLReadError(f"malformed YAML: {problem}{ctx}; fix the syntax", line) from None
    except yaml.YAMLError as exc:
        raise YAMLReadError(f"malformed YAML: {exc}; fix the syntax") from None
    except RecursionError:
        raise YAMLReadError("the file is nested too deeply to be a mechanism") from None
    if node is None:
        raise YAMLReadError("the file is empty; see 'mechsing schema' or the README for the format")
    try:
        return _Converter(max_items).convert(node)
    except RecursionError:
        raise YAMLReadError("the file is nested too deeply to be a mechanism") from None


def plain(value: YValue) -> Any:
    """The located value as plain Python (texts for scalars); for messages and tests."""
    if isinstance(value, YScalar):
        return value.text
    if isinstance(value, YSeq):
        return [plain(v) for v in value.items]
    return {k.text: plain(v) for k, v in value.items}
