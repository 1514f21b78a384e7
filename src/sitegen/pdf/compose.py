"""The book's print document: a title page, the contents, and every page of the built site in the
contents' order, each a chapter with its own running header."""

from __future__ import annotations

import datetime
import html
import re
from dataclasses import dataclass
from html.parser import HTMLParser
from pathlib import Path

import jinja2

from ..config import BookConfig
from ..site.navigation import sections
from .rewrite import Place, article, for_print

HERE = Path(__file__).resolve().parent
_TITLE = re.compile(r"<h1>(.*?)</h1>", re.S)
_PAGE_TITLE = re.compile(r"<title>(.*?)</title>", re.S)
_TAG = re.compile(r"<[^>]+>")
PAPER_SIZES = {"a4": "A4", "letter": "letter"}


@dataclass(frozen=True)
class Chapter:
    """One page of the site in the document: its slug, title, depth in the contents and printable HTML."""

    slug: str
    title: str
    depth: int
    html: str


@dataclass(frozen=True)
class ContentsLine:
    """A line of the document's contents: a chapter (level 1) or one of its sections (level 2)."""

    level: int
    depth: int
    text: str
    target: str  # the id it links to


@dataclass(frozen=True)
class Document:
    """The print document's parts, before the page numbers are known."""

    title: str  # the book's, as its home page names it
    chapters: tuple[Chapter, ...]
    contents: tuple[ContentsLine, ...]


def read_site(site: Path, book: BookConfig) -> Document:
    """The built site's pages, in the order of its contents, made into the document's chapters."""
    home = (site / "index.html").read_text(encoding="utf-8")
    order = reading_order(home)
    slugs = frozenset(slug for _, slug in order)
    chapters, contents = [], []
    for depth, slug in order:
        page = (site / f"{slug}.html").read_text(encoding="utf-8")
        inside = article(page)
        title = _plain(_TITLE.search(inside)[1])
        place = Place(slug, slugs, site, book.base_url)
        printable = for_print(inside, place)
        chapters.append(Chapter(slug, title, depth, printable))
        contents.append(ContentsLine(1, depth, title, slug))
        contents += [ContentsLine(2, depth, s.text, s.id) for s in sections(printable) if s.level == 2]
    return Document(_plain(_PAGE_TITLE.search(home)[1]), tuple(chapters), tuple(contents))


def document_html(document: Document, book: BookConfig, site: Path, numbers: dict[str, int]) -> str:
    """The whole document as one HTML file, its contents showing `numbers` (target id -> page)."""
    environment = jinja2.Environment(
        loader=jinja2.FileSystemLoader(HERE), autoescape=True, trim_blocks=True, lstrip_blocks=True
    )
    template = environment.get_template("book.html")
    marker = "<!-- sitegen: chapters -->"
    text = template.render(
        book=book,
        title=document.title,
        date=_long_date(book.date),
        paper=PAPER_SIZES[book.paper],
        stylesheet=(site / "assets" / "sitegen.css").resolve().as_uri(),
        print_css=(HERE / "print.css").read_text(encoding="utf-8"),
        chapters=document.chapters,
        header_css=_running_headers(document.chapters),
        contents=document.contents,
        numbers=numbers,
        marker=marker,
    )
    # The chapters are large trusted HTML: they go in after rendering, not through jinja2.
    body = "".join(
        f'<section class="chapter" id="{c.slug}" style="page: chapter-{i}">\n{c.html}</section>\n'
        for i, c in enumerate(document.chapters, 1)
    )
    return text.replace(marker, body, 1)


def targets(document: Document) -> list[str]:
    """The ids the contents link to, whose pages it shows."""
    return [line.target for line in document.contents]


def _running_headers(chapters) -> str:
    """A named page per chapter, whose header carries the chapter's title."""
    return "\n".join(
        f"@page chapter-{i} {{ @top-left {{ content: {_css_string(c.title)}; }} }}" for i, c in enumerate(chapters, 1)
    )


def _css_string(text: str) -> str:
    """`text` as a CSS string inside <style> (quotes, backslashes, line ends and "<" escaped)."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ").replace("<", "\\3c ")
    return f'"{escaped}"'


def _plain(fragment: str) -> str:
    """The text of an HTML fragment, its tags dropped and spaces collapsed."""
    return " ".join(html.unescape(_TAG.sub("", fragment)).split())


def _long_date(date: str) -> str:
    """A YYYY-MM-DD date as it reads on a title page ("1 December 2026"), or ""."""
    if not date:
        return ""
    day = datetime.date.fromisoformat(date)
    return f"{day.day} {day:%B} {day.year}"


def reading_order(index_html: str) -> list[tuple[int, str]]:
    """The pages of the book's contents (the home page's contents panel), as (depth, slug) in order."""
    parser = _ContentsReader()
    parser.feed(index_html)
    parser.close()
    return parser.pages


class _ContentsReader(HTMLParser):
    """Reads the page links of the contents panel (`nav.book-contents`): lists of pages nest, and a page's
    own list of sections (`ol.sections`) holds no page."""

    def __init__(self):
        super().__init__()
        self.pages: list[tuple[int, str]] = []
        self.inside = False
        self.lists: list[bool] = []  # for each open <ol>: whether it lists sections

    def handle_starttag(self, tag, attrs):
        named = dict(attrs)
        classes = (named.get("class") or "").split()
        if tag == "nav" and "book-contents" in classes:
            self.inside = True
        elif self.inside and tag == "ol":
            self.lists.append("sections" in classes)
        elif self.inside and tag == "a" and self.lists and not any(self.lists):
            href = named.get("href") or ""
            if href.endswith(".html") and "#" not in href:
                self.pages.append((len(self.lists) - 1, href[: -len(".html")]))

    def handle_endtag(self, tag):
        if tag == "nav" and self.inside:
            self.inside = False
        elif self.inside and tag == "ol" and self.lists:
            self.lists.pop()
