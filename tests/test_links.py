"""Every internal link, anchor and asset reference of the built site resolves.

The checker reads the built files (no browser): in HTML every `href`, `src`, the search box's
`data-index` (the script it loads when first used) and SVG `url(#…)` reference, in CSS every `url(…)`. A reference must
name a file inside the site (not a folder:
from file:// a folder shows a listing, not its index.html), and a `#fragment` must be an id
in the target page. Pages make no request outside the site; only links a reader follows
(`<a href>`) may point to the web, and those are not fetched.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest
from browser import ROOT

from sitegen.content.pages import discover_pages

PAGES = [f"{path.stem}.html" for path in discover_pages(ROOT / "content")]
_CSS_URL = re.compile(r"""url\(\s*(?:"(?P<dq>[^"]*)"|'(?P<sq>[^']*)'|(?P<bare>[^'"()\s]+))\s*\)""")
# data-index, data-src: the search index and a scene's data, scripts loaded when first used
_LINK_ATTRIBUTES = {"href", "src", "xlink:href", "poster", "data", "data-index", "data-src"}
_WEB = ("http", "https", "mailto")


@dataclass
class Document:
    """What one HTML file holds: its ids, and its references as (tag, attribute, value, line)."""

    ids: set[str] = field(default_factory=set)
    references: list[tuple[str, str, str, int]] = field(default_factory=list)
    duplicate_ids: list[str] = field(default_factory=list)


class _Collector(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.document = Document()

    def handle_starttag(self, tag, attrs):
        line = self.getpos()[0]
        for name, value in attrs:
            if value is None:
                continue
            if name == "id" or (tag == "a" and name == "name"):
                if value in self.document.ids:
                    self.document.duplicate_ids.append(value)
                self.document.ids.add(value)
            elif name in _LINK_ATTRIBUTES:
                self.document.references.append((tag, name, value, line))
            elif name == "srcset":
                for part in value.split(","):
                    self.document.references.append((tag, name, part.split()[0], line))
            elif "url(" in value:  # SVG presentation attributes and inline styles
                self.document.references += [(tag, name, _url(m), line) for m in _CSS_URL.finditer(value)]

    handle_startendtag = handle_starttag


def _url(match: re.Match) -> str:
    return next(v for v in match.group("dq", "sq", "bare") if v is not None)


def read_document(path: Path) -> Document:
    """The ids and references of one HTML file."""
    collector = _Collector()
    collector.feed(path.read_text(encoding="utf-8"))
    collector.close()
    return collector.document


def link_problems(site: Path, name: str) -> list[str]:
    """Every reference of `name` (an HTML or CSS file under `site`) that does not resolve."""
    site = site.resolve()
    source = site / name
    if name.endswith(".css"):
        text = source.read_text(encoding="utf-8")
        references = [("css", "url", _url(m), text.count("\n", 0, m.start()) + 1) for m in _CSS_URL.finditer(text)]
    else:
        references = read_document(source).references
    problems, documents = [], {}
    for tag, attribute, value, line in references:
        where = f"{name}:{line}: <{tag} {attribute}={value!r}>"
        problem = _reference_problem(site, source, tag, value.strip(), documents)
        if problem:
            problems.append(f"{where}: {problem}")
    return problems


def _reference_problem(site: Path, source: Path, tag: str, value: str, documents: dict) -> str | None:
    if not value:
        return "empty reference"
    parts = urlsplit(value)
    if parts.scheme == "data":
        return None
    if parts.scheme or parts.netloc:
        if tag == "a" and parts.scheme in _WEB:
            return None  # a link for the reader to follow; the page does not load it
        return "the page would load something from outside the site"
    if parts.query:
        return "a query string means nothing to a file"
    if not parts.path:  # "#fragment": in this document
        target = source
    else:
        if parts.path.startswith("/"):
            return "an absolute path breaks from file://; use a relative one"
        if parts.path.endswith("/"):
            return "a link to a folder; link to its index.html"
        target = (source.parent / unquote(parts.path)).resolve()
        if not target.is_relative_to(site):
            return "points outside the site"
        if target.is_dir():
            return "a link to a folder; link to its index.html"
        if not target.is_file():
            return f"no file {target.relative_to(site)}"
    if parts.fragment:
        if target.suffix != ".html":
            return f"a #fragment on {target.name}, which is not a page"
        if target not in documents:
            documents[target] = read_document(target)
        if unquote(parts.fragment) not in documents[target].ids:
            return f"no id '{unquote(parts.fragment)}' in {target.relative_to(site)}"
    return None


def test_every_page_is_checked(built_site):
    """The pages parametrized here are exactly the pages built."""
    assert sorted(PAGES) == sorted(p.name for p in built_site.glob("*.html"))


@pytest.mark.parametrize("name", PAGES, ids=[n[:-5] for n in PAGES])
def test_page_links_and_anchors_resolve(built_site, name):
    """Every href, src and url(#…) of the page reaches a file of the site and an existing id."""
    document = read_document(built_site / name)
    assert document.references
    assert not document.duplicate_ids, f"ids used twice: {sorted(set(document.duplicate_ids))}"
    problems = link_problems(built_site, name)
    assert not problems, "\n".join(problems)


def test_stylesheet_references_resolve(built_site):
    """The stylesheet's url(…)s (the math font) are files of the site."""
    assert _CSS_URL.search((built_site / "assets" / "sitegen.css").read_text(encoding="utf-8"))
    assert link_problems(built_site, "assets/sitegen.css") == []


def test_every_file_is_reachable(built_site):
    """Nothing in the site is an orphan: each file is linked from a page or the stylesheet."""
    reached = set()
    for name in [*PAGES, "assets/sitegen.css"]:
        source = (built_site / name).resolve()
        if name.endswith(".css"):
            values = [_url(m) for m in _CSS_URL.finditer(source.read_text(encoding="utf-8"))]
        else:
            values = [v for _, _, v, _ in read_document(source).references]
        for value in values:
            parts = urlsplit(value)
            if parts.path and not parts.scheme:
                reached.add((source.parent / unquote(parts.path)).resolve())
    files = {p.resolve() for p in built_site.rglob("*") if p.is_file()}
    orphans = sorted(str(p.relative_to(built_site.resolve())) for p in files - reached if p.name != "index.html")
    assert orphans == []


def test_checker_finds_each_kind_of_broken_link(tmp_path):
    """The checker itself: a missing file, a missing anchor, a folder, an escape, an absolute
    path and an outside resource are each reported; good links are not."""
    (tmp_path / "assets").mkdir()
    (tmp_path / "assets" / "x.css").write_text(
        "a { background: url(missing.png); } b { background: url('../ok.html'); }"
    )
    (tmp_path / "ok.html").write_text('<p id="here">ok</p>')
    (tmp_path / "page.html").write_text(
        '<a href="ok.html#here">fine</a>\n<a href="#top" id="top">fine</a>\n<a href="https://example.org/">web</a>\n'
        '<a href="gone.html">1</a>\n<a href="ok.html#nowhere">2</a>\n<a href="assets/">3</a>\n<a href="assets">4</a>\n'
        '<a href="../outside.html">5</a>\n<a href="/ok.html">6</a>\n<script src="https://cdn.example.org/x.js"></script>\n'
        '<svg><g clip-path="url(#clip)"></g></svg>\n'
    )
    problems = link_problems(tmp_path, "page.html")
    assert [p.split(": ", 1)[0] for p in problems] == [f"page.html:{n}" for n in (4, 5, 6, 7, 8, 9, 10, 11)]
    assert "no file gone.html" in problems[0] and "no id 'nowhere'" in problems[1]
    assert "folder" in problems[2] and "folder" in problems[3] and "outside the site" in problems[4]
    assert "absolute path" in problems[5] and "from outside the site" in problems[6] and "no id 'clip'" in problems[7]
    css = link_problems(tmp_path, "assets/x.css")
    assert len(css) == 1 and "no file assets/missing.png" in css[0]
