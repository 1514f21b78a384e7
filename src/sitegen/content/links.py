"""Every link and image a page names, checked against the book when it is built: a page, a heading, an
equation, a figure, a table, a scene (or a scene's state, `#collision:m1=2`), a file next to the pages.
Links outside the book are not followed (no network); a page loads nothing from outside it.

The files the pages name (images, data, documents under the content folder) are the ones copied into
the site, byte for byte, at the same place relative to the pages.
"""

from __future__ import annotations

import posixpath
import re
from html import unescape
from pathlib import Path
from urllib.parse import unquote, urlsplit

from ..errors import AuthorError
from .pages import Page
from .prose import Link, did_you_mean

_ID = re.compile(r'\sid="([^"]+)"')


def page_anchors(page: Page, extra: tuple[str, ...] = ()) -> set[str]:
    """The ids a link can name on `page`: those in its HTML, those its placeholders become, and `extra`
    (the template's)."""
    return (
        {unescape(i) for i in _ID.findall(page.html)} | {label.anchor for label in page.extracted.labels} | set(extra)
    )


def check_links(
    pages: list[Page], anchors: dict[str, set[str]], content: Path, reserved: set[str]
) -> tuple[list[str], list[AuthorError]]:
    """The files under `content` the pages name (sorted, relative), and an error for every link or image that
    does not resolve, or an image without alt text. `reserved`: the names of files the build writes itself."""
    files, errors = set(), []
    slugs = {page.slug for page in pages}
    existing = sorted(p.relative_to(content).as_posix() for p in content.rglob("*") if p.is_file())
    for page in pages:
        for link in page.extracted.links:
            problem, file = _problem(link, page, slugs, anchors, content, existing, reserved)
            if problem:
                errors.append(AuthorError(link.loc, problem))
            elif file:
                files.add(file)
    return sorted(files), errors


def _problem(link: Link, page: Page, slugs, anchors, content: Path, existing, reserved):
    """(what is wrong with `link` or None, the file it names under `content` or None)."""
    if link.image and link.alt is not None and not link.alt.strip():
        return (
            f"image '{link.target}' has no alt text: write what it shows between the brackets, ![…]({link.target})",
            None,
        )
    parts = urlsplit(link.target)
    if parts.scheme or parts.netloc:
        if link.image:
            return (
                f"image '{link.target}' is outside the book: a page "
                "loads nothing from the web; save it next to the page",
                None,
            )
        return None, None
    path, fragment = unquote(parts.path), unquote(parts.fragment)
    if not path:
        return _fragment_problem(fragment, page.slug, anchors), None
    if path.startswith("/"):
        return f"link '{link.target}' is an absolute path, which breaks from disk; write it relative to the page", None
    if path.endswith("/") or (content / path).is_dir():
        return f"link '{link.target}' names a folder; name a page or a file in it", None
    name = posixpath.normpath(path)
    if name.startswith("../"):
        return f"link '{link.target}' points outside the book's content folder", None
    if name.endswith(".md") and name[:-3] in slugs:
        return f"link '{link.target}' names the page's source; link to the page, '{name[:-3]}.html'", None
    if name.endswith(".html") and name[:-5] in slugs:
        return (_fragment_problem(fragment, name[:-5], anchors, name) if fragment else None), None
    if name in reserved:
        return f"file '{name}' has the name of a file the build writes; rename it", None
    if name not in existing:
        pages = [f"{slug}.html" for slug in sorted(slugs)]
        hint = did_you_mean(name, pages if name.endswith(".html") else existing)
        kind = "page" if name.endswith(".html") else "file"
        return f"link '{link.target}' names no {kind} of the book (content/{name}){hint}", None
    if fragment:
        return f"link '{link.target}' has a #fragment on a file that is not a page", None
    return None, name


def _fragment_problem(fragment: str, slug: str, anchors, page_name: str = "") -> str | None:
    ids = anchors[slug]
    scene, colon, _ = fragment.partition(":")
    if fragment in ids or (colon and f"scene-{scene}" in ids):
        return None
    where = f"{page_name}#" if page_name else "#"
    hint = did_you_mean(fragment, sorted(ids), where)
    return f"link '{where}{fragment}' names no place on {page_name or 'this page'}{hint}"
