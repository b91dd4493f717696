"""A minimal XML element tree that remembers line numbers (xml.etree does not)."""

from __future__ import annotations

from dataclasses import dataclass, field
from xml.parsers import expat

from .errors import BTError


@dataclass
class XmlElement:
    tag: str
    attributes: dict[str, str]
    line: int
    file: str
    children: list[XmlElement] = field(default_factory=list)

    def elements(self, tag: str) -> list[XmlElement]:
        return [child for child in self.children if child.tag == tag]


def parse_xml(text: str, file: str) -> XmlElement:
    """The root element of ``text``; a malformed document raises BTError with its line."""
    parser = expat.ParserCreate()
    stack: list[XmlElement] = []
    roots: list[XmlElement] = []

    def start(tag: str, attributes: dict[str, str]) -> None:
        element = XmlElement(tag, dict(attributes), parser.CurrentLineNumber, file)
        (stack[-1].children if stack else roots).append(element)
        stack.append(element)

    def end(tag: str) -> None:
        stack.pop()

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    try:
        parser.Parse(text, True)
    except expat.ExpatError as error:
        raise BTError(
            f"malformed XML: {expat.ErrorString(error.code)}", file=file, line=error.lineno
        ) from None
    return roots[0]
