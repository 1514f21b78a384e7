"""The book's navigation: the reading order of its pages, their sections, anchor links on headings,
and each page's previous and next page."""

from __future__ import annotations

import re
from dataclasses import dataclass
from html import unescape

from ..content.pages import Page

_HEADING = re.compile(r'<h([23]) id="([^"]+)">(.*?)</h\1>', re.S)
_TAG = re.compile(r"<[^>]+>")


@dataclass(frozen=True)
class Section:
    """A heading of a page: its level (2 or 3), its id and its text."""

    level: int
    id: str
    text: str


@dataclass(frozen=True)
class Entry:
    """A page in the book's contents: its sections and the pages under it."""

    page: Page
    sections: tuple[Section, ...]
    children: tuple[Entry, ...]


def sections(html: str) -> tuple[Section, ...]:
    """The h2 and h3 headings of a page's HTML, as plain text (tags, such as a formula's, dropped)."""
    return tuple(
        Section(int(level), anchor, " ".join(unescape(_TAG.sub("", inner)).split()))
        for level, anchor, inner in _HEADING.findall(html)
    )


def outline(pages: list[Page]) -> tuple[Entry, ...]:
    """The book as a tree: the home page, then each top-level page (by order) with the pages under it.

    Every page appears once: one whose parents run in a circle is placed at the top level.
    """
    ordered = sorted(pages, key=lambda p: (p.slug != "index", p.order, p.slug))
    placed: set[str] = set()

    def entry(page: Page) -> Entry:
        placed.add(page.slug)
        below = [p for p in ordered if p.parent == page.slug and p.slug not in placed and p.slug != "index"]
        placed.update(p.slug for p in below)
        return Entry(page, sections(page.html), tuple(entry(child) for child in below))

    known = {p.slug for p in pages}
    roots = [entry(p) for p in ordered if p.slug == "index" or not p.parent or p.parent not in known]
    roots += [entry(p) for p in ordered if p.slug not in placed]
    return tuple(roots)


def reading_order(pages: list[Page]) -> list[Page]:
    """Every page in the order of the contents: a page, then the pages under it."""
    order: list[Page] = []

    def walk(entries) -> None:
        for item in entries:
            order.append(item.page)
            walk(item.children)

    walk(outline(pages))
    return order


def neighbours(page: Page, pages: list[Page]) -> tuple[Page | None, Page | None]:
    """The pages before and after `page` in reading order (None at either end)."""
    order = [p.slug for p in reading_order(pages)]
    at = order.index(page.slug)
    by_slug = {p.slug: p for p in pages}
    return (by_slug[order[at - 1]] if at > 0 else None), (by_slug[order[at + 1]] if at + 1 < len(order) else None)


def with_anchors(html: str) -> str:
    """Each h2 and h3 with a link to itself at its end, so that a reader can copy where they are."""

    def anchored(match: re.Match) -> str:
        level, anchor, inner = match[1], match[2], match[3]
        link = (
            f'<a class="anchor" href="#{anchor}"><span aria-hidden="true">#</span>'
            f'<span class="visually-hidden">Link to this section</span></a>'
        )
        return f'<h{level} id="{anchor}">{inner} {link}</h{level}>'

    return _HEADING.sub(anchored, html)
