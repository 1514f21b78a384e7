"""The book's search index: the prose and captions of every page, section by section, shipped with the
code that searches it as one classic script (assets/search.js), so that search works from disk."""

from __future__ import annotations

import hashlib
import json
import re
from html.parser import HTMLParser

from ..content.pages import Page
from . import assets
from .assemble import SEARCH_SCRIPT  # noqa: F401 - where the index goes, named beside the search box that loads it
from .navigation import reading_order

# Not prose: code and drawings, navigation, controls and readouts, a table's cells (its caption is prose).
_SKIPPED = frozenset(
    {"script", "style", "svg", "nav", "noscript", "thead", "tbody", "tfoot", "button", "output", "template"}
)
_SKIPPED_CLASSES = frozenset({"scene-panel", "report-data", "anchor"})
_SECTION = frozenset({"h1", "h2", "h3"})
_BREAKS = frozenset({"p", "li", "figcaption", "caption", "div", "summary", "br", "dd", "dt", "td", "th", "math"})
# Scripts (a scene's inline tables) and drawings hold most of a page's bytes and no prose: cut before parsing,
# with comments first (one may mention a tag) and innermost drawings first (an <svg> may hold another).
_NO_PROSE = re.compile(r"<!--.*?-->|<script\b.*?</script>|<svg\b(?:(?!<svg\b).)*?</svg>", re.S)
_VOID = frozenset(
    {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}
)


class _Sections(HTMLParser):
    """Text of an <article>, cut at its headings: [(heading id, heading text, text under it)]."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.sections: list[list] = []
        self.depth = 0  # inside <article>
        self.skipping = 0  # inside an element whose text is not prose (figures, controls, navigation)
        self.heading: list | None = None

    def handle_starttag(self, tag, attrs):
        names = dict(attrs)
        if tag == "article":
            self.depth += 1
        if not self.depth or tag in _VOID:
            return
        if self.skipping or tag in _SKIPPED or _SKIPPED_CLASSES & set((names.get("class") or "").split()):
            self.skipping += 1
        elif tag in _SECTION:
            self.heading = [names.get("id", ""), []]
        elif tag in _BREAKS:
            self._text(" ")

    def handle_endtag(self, tag):
        if not self.depth or tag in _VOID:
            return
        if tag == "article":
            self.depth -= 1
        elif self.skipping:
            self.skipping -= 1
        elif tag in _SECTION and self.heading is not None:
            anchor, words = self.heading
            self.sections.append([anchor, " ".join("".join(words).split()), []])
            self.heading = None
        elif tag in _BREAKS:
            self._text(" ")

    def handle_data(self, data):
        if self.depth and not self.skipping:
            self._text(data)

    def _text(self, text: str) -> None:
        if self.heading is not None:
            self.heading[1].append(text)
        elif self.sections:
            self.sections[-1][2].append(text)


# A rebuild in a long-lived process (serve --watch) parses only the pages that changed. Keyed by a digest, not
# by the page: a page's HTML is megabytes, and a shelf's pages held as keys would grow the build's memory with
# every chapter.
_PARSED: dict[bytes, tuple] = {}
PARSED_PAGES = 64


def page_sections(html: str) -> tuple[tuple[str, str, str], ...]:
    """A page's sections as (heading id, heading, text): the h1's section has no id."""
    key = hashlib.sha256(html.encode()).digest()
    if key not in _PARSED:
        if len(_PARSED) >= PARSED_PAGES:
            _PARSED.clear()
        _PARSED[key] = _sections(html)
    return _PARSED[key]


def _sections(html: str) -> tuple[tuple[str, str, str], ...]:
    parser = _Sections()
    parser.feed(_NO_PROSE.sub("", html))
    parser.close()
    return tuple(
        (anchor if index else "", title, " ".join("".join(words).split()))
        for index, (anchor, title, words) in enumerate(parser.sections)
    )


def search_script(sections: dict[str, list], pages: list[Page]) -> bytes:
    """assets/search.js: the index of every page (in reading order), from each page's `page_sections` by its
    file name, and the code that searches it."""
    order = reading_order(pages)
    index = {
        "pages": [[page.output_name, page.title] for page in order],
        "sections": [
            [number, anchor, title, text]
            for number, page in enumerate(order)
            for anchor, title, text in sections.get(page.output_name, [])
        ],
    }
    data = json.dumps(index, ensure_ascii=False, separators=(",", ":"))
    return f"window.sitegenSearchIndex = {data};\n".encode() + assets.search_code()
