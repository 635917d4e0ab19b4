"""Where each element of an XML text starts and ends, so that an edit keeps the file's layout.

The URDF is parsed by `sw2sim.xmlsafe` (safely, and to learn it is well-formed); this module
only finds, in the same text, the characters each element spans, by scanning its tags in
document order. Carrying a hand edit from one URDF into another then inserts or replaces
whole lines of text, and everything else in the new file stays exactly as the exporter
wrote it: one attribute per line, its line endings, its number formats.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

# Comments, processing instructions, CDATA and declarations are skipped; a tag's attribute
# values may hold '>' inside quotes.
_TOKEN = re.compile(
    r"<!--.*?-->|<\?.*?\?>|<!\[CDATA\[.*?\]\]>|<![^>]*>"
    r"|<(/?)([^\s/>!?]+)((?:[^>\"']|\"[^\"]*\"|'[^']*')*?)(/?)>", re.S)


@dataclass
class Span:
    """One element's place in the text: text[start:end] is the element, tags included."""

    tag: str
    start: int
    end: int = -1
    children: list["Span"] = field(default_factory=list)


def element_spans(text: str) -> list[Span]:
    """Every element's span, in document order (the order of lxml's `iter()` over elements)."""
    order: list[Span] = []
    stack: list[Span] = []
    for match in _TOKEN.finditer(text):
        closing, tag, _, empty = match.groups()
        if tag is None:
            continue
        if closing:
            if not stack or stack[-1].tag != tag:
                raise ValueError(f"</{tag}> at character {match.start()} closes no open <{tag}>")
            stack.pop().end = match.end()
            continue
        span = Span(tag, match.start())
        if stack:
            stack[-1].children.append(span)
        order.append(span)
        if empty:
            span.end = match.end()
        else:
            stack.append(span)
    if stack:
        raise ValueError(f"<{stack[-1].tag}> is never closed")
    return order


def spans_by_element(root, text: str) -> dict:
    """Each element of the lxml tree `root` (parsed from `text`) to its span. The keys are
    the elements themselves: holding them keeps lxml handing out the same Python object for
    each, so later lookups find them."""
    elements = [e for e in root.iter() if isinstance(e.tag, str)]
    spans = element_spans(text)
    if len(spans) != len(elements) or any(s.tag != e.tag for s, e in zip(spans, elements)):
        raise ValueError("the file's tags could not be matched to its elements")
    return dict(zip(elements, spans))


def line_start(text: str, position: int) -> int:
    return text.rfind("\n", 0, position) + 1


def line_end(text: str, position: int) -> int:
    """Just past the newline ending the line `position` is on (or the text's end)."""
    found = text.find("\n", position)
    return len(text) if found < 0 else found + 1


def block(text: str, span: Span) -> tuple[int, int]:
    """The whole lines an element occupies, when it has them to itself (the exporter's layout
    and the usual hand-edited one); else just its own characters."""
    start, end = line_start(text, span.start), line_end(text, span.end)
    if text[start:span.start].strip() or text[span.end:end].strip():
        return span.start, span.end
    return start, end
