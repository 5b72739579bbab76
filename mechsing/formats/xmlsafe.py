"""Safe reading of XML robot descriptions (URDF, MJCF) into located elements.

Owns :func:`parse`, the one way mechsing reads XML.  It uses the standard
library's expat parser configured so that nothing outside the text is ever
read: a document type declaration (``<!DOCTYPE``), and so every entity
definition (the "billion laughs" expansion, external entities such as
``file:///etc/passwd`` or ``http://...``), is refused before it is processed;
parameter entities are never parsed.  The text is bounded in size
(:data:`MAX_XML_BYTES`), in the length of each attribute, in the number of
elements and in nesting depth.  Every element keeps its 1-based line, so every
message can name the element and its line.  Errors are
:class:`~mechsing.errors.MechanismError` (bad input, exit 2).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from xml.parsers import expat

from mechsing.errors import MechanismError
from mechsing.numeric.numbers import decimal_float, is_decimal_text

__all__ = [
    "MAX_ATTRIBUTE_CHARS",
    "MAX_DEPTH",
    "MAX_ELEMENTS",
    "MAX_XML_BYTES",
    "Element",
    "parse",
    "root_tag",
]

#: largest XML description accepted, in bytes
MAX_XML_BYTES = 10 * 1024 * 1024
#: longest attribute value accepted, in characters
MAX_ATTRIBUTE_CHARS = 10_000
#: most elements in one description
MAX_ELEMENTS = 200_000
#: deepest nesting of elements
MAX_DEPTH = 500


@dataclass
class Element:
    """An XML element: its tag, attributes, children in document order and its line."""

    tag: str
    attrib: dict[str, str]
    line: int
    children: list[Element] = field(default_factory=list)

    def get(self, key: str, default: str | None = None) -> str | None:
        return self.attrib.get(key, default)

    def find(self, tag: str) -> Element | None:
        for c in self.children:
            if c.tag == tag:
                return c
        return None

    def findall(self, tag: str) -> list[Element]:
        return [c for c in self.children if c.tag == tag]

    def where(self) -> str:
        """How a message names the element: ``<joint name="J1">``."""
        name = self.attrib.get("name")
        if name and not name.isprintable():  # control characters shown as escapes
            name = name.encode("unicode_escape").decode("ascii")
        return f'<{self.tag} name="{name}">' if name else f"<{self.tag}>"


class _Refused(Exception):
    def __init__(self, message: str, line: int | None) -> None:
        super().__init__(message)
        self.message = message
        self.line = line


def root_tag(text: str) -> str | None:
    """The tag of the root element when ``text`` looks like XML (starts with ``<``), else
    None; read from the first characters only (for recognising a format by content)."""
    head = text.lstrip("\ufeff \t\r\n")[:4096]
    if not head.startswith("<"):
        return None
    i = 0
    while i < len(head):
        j = head.find("<", i)
        if j < 0:
            return ""
        if head.startswith("<?", j):
            i = head.find("?>", j) + 2 if head.find("?>", j) >= 0 else len(head)
        elif head.startswith("<!--", j):
            i = head.find("-->", j) + 3 if head.find("-->", j) >= 0 else len(head)
        elif head.startswith("<!", j):
            return "!DOCTYPE"
        else:
            k = j + 1
            while k < len(head) and not head[k].isspace() and head[k] not in "/>":
                k += 1
            return head[j + 1 : k]
        if i <= j:
            break
    return ""


def parse(text: str, path: str, kind: str) -> Element:
    """Parse ``text`` (the file ``path``, a description of format ``kind`` for messages) into
    its root :class:`Element`.

    Raises
    ------
    MechanismError
        malformed XML (with its line), a DOCTYPE or entity declaration, a text, an
        attribute or a tree beyond the bounds.
    """
    if len(text.encode("utf-8", "surrogatepass")) > MAX_XML_BYTES:
        raise MechanismError(
            f"the {kind} file is larger than {MAX_XML_BYTES // (1024 * 1024)} MB, more than "
            "mechsing reads; remove the meshes or other large parts from it",
            path=path,
        )
    parser = expat.ParserCreate()
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    stack: list[Element] = []
    roots: list[Element] = []
    count = [0]

    def refuse_doctype(*_: object) -> None:
        raise _Refused(
            "the file has a <!DOCTYPE> declaration; mechsing does not read document type "
            "declarations or entities (they can expand without bound or read other files); "
            "remove the declaration and write the entities out",
            parser.CurrentLineNumber,
        )

    def refuse_entity(*_: object) -> None:
        raise _Refused(
            "the file declares or refers to an external entity; mechsing reads nothing "
            "outside the file; write the content out",
            parser.CurrentLineNumber,
        )

    def start(tag: str, attrs: dict[str, str]) -> None:
        line = parser.CurrentLineNumber
        count[0] += 1
        if count[0] > MAX_ELEMENTS:
            raise _Refused(f"more than {MAX_ELEMENTS} elements; that is not a robot", line)
        if len(stack) >= MAX_DEPTH:
            raise _Refused(f"<{tag}> is nested more than {MAX_DEPTH} levels deep", line)
        for k, v in attrs.items():
            if len(v) > MAX_ATTRIBUTE_CHARS:
                raise _Refused(
                    f"<{tag}>: attribute {k!r} has {len(v)} characters, more than the "
                    f"{MAX_ATTRIBUTE_CHARS} mechsing reads; shorten it",
                    line,
                )
        el = Element(tag, dict(attrs), line)
        if stack:
            stack[-1].children.append(el)
        else:
            roots.append(el)
        stack.append(el)

    def end(_tag: str) -> None:
        stack.pop()

    parser.StartDoctypeDeclHandler = refuse_doctype
    parser.EntityDeclHandler = refuse_entity
    parser.UnparsedEntityDeclHandler = refuse_entity
    parser.ExternalEntityRefHandler = refuse_entity
    parser.StartElementHandler = start
    parser.EndElementHandler = end
    try:
        parser.Parse(text, True)
    except _Refused as exc:
        raise MechanismError(exc.message, path=path, line=exc.line) from None
    except expat.ExpatError as exc:
        raise MechanismError(
            f"malformed XML: {expat.ErrorString(exc.code)} (column {exc.offset + 1}); "
            "fix the syntax",
            path=path,
            line=exc.lineno,
        ) from None
    except RecursionError:  # pragma: no cover - bounded by MAX_DEPTH
        raise MechanismError("the XML is nested too deeply", path=path) from None
    if not roots:
        raise MechanismError("the XML file has no element", path=path)
    return roots[0]


def required(el: Element, path: str, rule: str, *ways: tuple[str, ...]) -> tuple[str, ...]:
    """The one way of ``ways`` (sets of attribute names) that ``el`` gives whole; a
    MechanismError naming the element, its line and the format's ``rule`` when it gives
    none whole, or parts of two (its reference requires one set, complete)."""
    given = [w for w in ways if any(el.get(k) is not None for k in w)]
    whole = [w for w in given if all(el.get(k) is not None for k in w)]
    if len(given) == 1 and whole:
        return whole[0]
    options = " or ".join("+".join(w) for w in ways)
    if not given and len(ways) == 1:
        problem = f"lacks {', '.join(repr(k) for k in ways[0])}"
    elif not given:
        problem = f"gives none of {options}"
    elif len(given) > 1:
        problem = f"mixes {' and '.join('+'.join(w) for w in given)}"
    else:
        missing = [k for k in given[0] if el.get(k) is None]
        problem = f"lacks {', '.join(repr(k) for k in missing)}"
    raise MechanismError(f"{el.where()} {problem}: {rule}; give {options}", path=path, line=el.line)


def floats(
    el: Element, key: str, n: int | None, path: str, default: list[float] | None = None
) -> list[float]:
    """The attribute ``key`` of ``el`` as ``n`` finite numbers (any count when ``n`` is
    None), or ``default`` when absent; a MechanismError naming the element and line."""
    text = el.get(key)
    if text is None:
        if default is None:
            raise MechanismError(
                f"{el.where()} needs the attribute {key!r}; add it", path=path, line=el.line
            )
        return list(default)
    words = text.split()
    if all(is_decimal_text(t) for t in words) and (n is None or len(words) == n):
        try:
            return [decimal_float(t) for t in words]
        except ValueError as exc:
            raise MechanismError(
                f"{el.where()}: attribute {key}: {exc} (in the file's units); check the "
                "value and its unit",
                path=path,
                line=el.line,
            ) from None
    count = f"{n} numbers" if n is not None else "numbers"
    raise MechanismError(
        f"{el.where()}: attribute {key}={text[:60]!r} must be {count} separated by "
        'spaces (ASCII decimal digits, finite, e.g. "0 0 1")',
        path=path,
        line=el.line,
    )
