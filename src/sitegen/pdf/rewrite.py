"""One built page's article, made fit to stand in the whole book's print document.

Every page of the site was written with its own ids and links between files; in one document the ids
are made unique (each is prefixed with its page), links to pages of the book become links inside the
document, files of the site are reached where they are, and what only works on screen (scripts, the
controls' script-only parts, anchors beside headings, the pager) is left out. Everything else passes
through byte for byte: the parser re-writes only the tags it changes.
"""

from __future__ import annotations

import html
from dataclasses import dataclass
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import urlsplit

# Attributes that hold the id of another element (one id, or several separated by spaces).
ID_REFERENCES = ("for", "aria-describedby", "aria-labelledby", "aria-controls", "aria-owns", "headers", "list")
_DROP = object()  # what `_value` answers for an attribute to leave out
VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}


@dataclass(frozen=True)
class Place:
    """Where a page's article goes in the book's document, and what its links may reach."""

    slug: str  # the page (its file is SLUG.html); its ids become SLUG--ID
    pages: frozenset[str]  # the slugs of every page in the book
    site: Path  # the built site, for files that pages show or link to
    base_url: str = ""  # the book's web address: links to the site's other files, and to each scene

    def target(self, fragment: str, slug: str | None = None) -> str:
        """The id in the document of `fragment` on page `slug` (default this page's); the page itself if empty."""
        slug = slug or self.slug
        return f"{slug}--{fragment}" if fragment else slug

    def web_address(self, path: str) -> str:
        """The address of a file of the site on the web (empty when the book has no base_url)."""
        return f"{self.base_url.rstrip('/')}/{path}" if self.base_url else ""


def article(page_html: str) -> str:
    """The inside of a built page's <article> (its title, prose and scenes)."""
    start = page_html.index("<article>") + len("<article>")
    return page_html[start : page_html.rindex("</article>")]


def for_print(fragment: str, place: Place) -> str:
    """`fragment` (an article's HTML) with ids and links made right for the book's document."""
    rewriter = _Rewriter(place)
    rewriter.feed(fragment)
    rewriter.close()
    return "".join(rewriter.out)


def _is_left_out(tag: str, attrs: dict[str, str | None]) -> bool:
    """What a printed page does without: scripts and their data, the no-script notes, the anchors beside
    headings, the pager and the home page's own contents (the document has its own)."""
    classes = (attrs.get("class") or "").split()
    if tag in ("script", "noscript"):
        return True
    if tag == "a" and "anchor" in classes:
        return True
    return tag == "nav" and ("pager" in classes or attrs.get("aria-label") == "Contents")


class _Rewriter(HTMLParser):
    def __init__(self, place: Place):
        super().__init__(convert_charrefs=False)
        self.place = place
        self.out: list[str] = []
        self.skipping: list[str] = []  # the tags open inside a left-out element (its own first)
        self.figures: list[str | None] = []  # for each open <figure>: the scene's id, or None

    def handle_starttag(self, tag, attrs):
        self._start(tag, attrs, closed=False)

    def handle_startendtag(self, tag, attrs):
        self._start(tag, attrs, closed=True)

    def _start(self, tag, attrs, closed: bool):
        named = dict(attrs)
        if self.skipping or _is_left_out(tag, named):
            if not closed and tag not in VOID:
                self.skipping.append(tag)
            return
        if tag == "figure":
            is_scene = "scene" in (named.get("class") or "").split()
            self.figures.append(named.get("id") if is_scene else None)
        changed = [(name, self._value(name, value)) for name, value in attrs]
        changed = [(name, value) for name, value in changed if value is not _DROP]
        if tag == "details" and "open" not in named:
            changed.append(("open", None))  # a derivation folded away on screen is printed in full
        if changed == list(attrs):
            self.out.append(self.get_starttag_text())
            return
        text = "".join(f" {name}" if value is None else f' {name}="{html.escape(value)}"' for name, value in changed)
        self.out.append(f"<{tag}{text}{' /' if closed else ''}>")

    def handle_endtag(self, tag):
        if self.skipping:
            if tag == self.skipping[-1]:
                self.skipping.pop()
            return
        if tag == "figure" and self.figures:
            scene = self.figures.pop()
            if scene:
                self.out.append(self._scene_link(scene))
        self.out.append(f"</{tag}>")

    def _scene_link(self, scene: str) -> str:
        """The address of the scene on the web, printed small under it (nothing when the book has no base_url)."""
        address = self.place.web_address(f"{self.place.slug}.html#{scene}")
        if not address:
            return ""
        shown = html.escape(address)
        return f'<p class="scene-address">Interactive version: <a href="{shown}">{shown}</a></p>\n'

    def _value(self, name: str, value: str | None):
        if value is None:
            return None
        if name == "id":
            return self.place.target(value)
        if name in ID_REFERENCES:
            return " ".join(self.place.target(part) for part in value.split())
        if name in ("href", "xlink:href"):
            return self._link(value)
        if name == "src":
            return self._file(value)
        return value

    def _link(self, href: str):
        """A link of the page as it reads in the document: inside it for the book's pages, to the web for the
        site's other files (no link when the book has no web address), unchanged for addresses elsewhere."""
        parts = urlsplit(href)
        if parts.scheme or parts.netloc:
            return href
        if not parts.path:
            return f"#{self.place.target(parts.fragment)}"
        slug = parts.path[: -len(".html")] if parts.path.endswith(".html") else None
        if slug in self.place.pages:
            return f"#{self.place.target(parts.fragment, slug)}"
        return self.place.web_address(href) or _DROP

    def _file(self, src: str) -> str:
        """A file of the site (an image, say), reached where the built site has it."""
        parts = urlsplit(src)
        if parts.scheme or parts.netloc or not parts.path:
            return src
        return (self.place.site / parts.path).resolve().as_uri()

    def handle_data(self, data):
        if not self.skipping:
            self.out.append(data)

    def handle_entityref(self, name):
        if not self.skipping:
            self.out.append(f"&{name};")

    def handle_charref(self, name):
        if not self.skipping:
            self.out.append(f"&#{name};")

    def handle_comment(self, data):
        if not self.skipping:
            self.out.append(f"<!--{data}-->")
