"""What a line of prose names, lifted out where the author wrote it: citations, cross-references, links and
images. Each is recorded with its line (the book-wide checks of phases/link.py report there) and replaced by
a placeholder that `fill_slots` swaps for the final HTML; inline code spans are left alone.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass

from ..errors import AuthorError, SourceLoc

LABEL = r"[a-z0-9][a-z0-9-]*"
_CODE_SPAN = re.compile(r"(`+)(?!`).+?(?<!`)\1(?!`)")
_REFERENCE = re.compile(rf"\(@(?P<label>{LABEL})\)")
_KEY = r"[A-Za-z0-9_](?:[\w:.+/-]*[A-Za-z0-9_])?"
_BRACKETED = re.compile(r"(?<![\\!])\[(?P<body>[^\[\]^]*?@[^\[\]]*)\](?![(\[])")
_CITE_PART = re.compile(rf"^\s*(?P<prefix>[^@]*?)\s*-?@(?P<key>{_KEY})\s*(?:,\s*(?P<locator>.*?))?\s*$")
_IN_TEXT = re.compile(rf"(?<![\w@.\\`/:=\"'\[])@(?P<key>{_KEY})")
_LINK = re.compile(
    r"(?P<bang>!?)\[(?P<text>(?:[^\[\]]|\[[^\[\]]*\])*)\]\(\s*(?P<target><[^>]*>|[^)\s]+)(?:\s+\"[^\"]*\")?\s*\)"
)
_LINK_DEFINITION = re.compile(r"^ {0,3}\[(?P<name>[^\]^]+)\]:\s*(?P<target>\S+)")
_HTML_TARGET = re.compile(
    r"<(?P<tag>a|img|source|video|audio)\b[^>]*?\b(?:href|src)\s*=\s*\"(?P<target>[^\"]*)\"", re.I
)
_HTML_IMG = re.compile(r"<img\b[^>]*>", re.I)
_DOLLAR = re.compile(r"(?<!\\)\$")
_LOCATORS = {
    "p.": "page", "pp.": "page", "page": "page", "pages": "page",
    "chap.": "chapter", "ch.": "chapter", "chapter": "chapter",
    "sec.": "section", "§": "section", "section": "section",
    "fig.": "figure", "figure": "figure", "vol.": "volume", "volume": "volume",
    "para.": "paragraph", "n.": "note", "note": "note", "l.": "line", "line": "line",
}  # fmt: skip
_LOCATOR = re.compile(r"^(?P<term>[^\d\s]+)\s*(?P<value>\S.*)$")
_BARE_PAGES = re.compile(r"^\d+(?:\s*[-–]\s*\d+)?$")


@dataclass(frozen=True)
class CiteKey:
    """One source named in a citation: its key, a locator (kind, value) and words before it ("see")."""

    key: str
    locator: tuple[str, str] | None = None
    prefix: str = ""


@dataclass(frozen=True)
class Citation:
    """`[@a, p. 3; @b]` (in brackets) or `@a` (in the text), where the author wrote it."""

    keys: tuple[CiteKey, ...]
    in_text: bool
    loc: SourceLoc


@dataclass(frozen=True)
class Link:
    """A link or an image the page names: its target as written, and for an image its alt text."""

    target: str
    loc: SourceLoc
    image: bool = False
    alt: str | None = None


def outside_code(line: str, change) -> str:
    """`line` with `change` applied to each stretch outside inline code spans."""
    out, start = [], 0
    for span in _CODE_SPAN.finditer(line):
        out += [change(line[start : span.start()]), span[0]]
        start = span.end()
    out.append(change(line[start:]))
    return "".join(out)


def reference_slots(text: str, loc: SourceLoc, extracted) -> str:
    """`(@label)` as a placeholder link, recorded for the book-wide check."""

    def slot(match: re.Match) -> str:
        extracted.references.append((match["label"], loc))
        return f'<a data-ref="{match["label"]}"></a>'

    return _REFERENCE.sub(slot, text)


def citation_slots(text: str, loc: SourceLoc, extracted) -> str:
    """Bracketed and in-text citations as placeholders, recorded for the book-wide check."""

    def record(citation: Citation) -> str:
        extracted.citations.append(citation)
        return f'<span data-cite-slot="{len(extracted.citations) - 1}"></span>'

    def bracketed(match: re.Match) -> str:
        parts = [_CITE_PART.match(part) for part in match["body"].split(";")]
        if not all(parts):
            return match[0]  # not a citation; the check for leftover markers names it
        keys = tuple(CiteKey(p["key"], _locator(p["locator"]), p["prefix"]) for p in parts)
        return record(Citation(keys, False, loc))

    text = _BRACKETED.sub(bracketed, text)
    return _IN_TEXT.sub(lambda m: record(Citation((CiteKey(m["key"]),), True, loc)), text)


def _locator(text: str | None) -> tuple[str, str] | None:
    """`p. 33` as ("page", "33"); a bare number or range is a page; other words as ("", words), shown as written."""
    if not text:
        return None
    if _BARE_PAGES.match(text):
        return ("page", text)
    locator = _LOCATOR.match(text)
    if locator and locator["term"].lower() in _LOCATORS:
        return (_LOCATORS[locator["term"].lower()], locator["value"])
    return ("", text)


def record_links(text: str, loc: SourceLoc, extracted) -> None:
    """Every link and image target of a stretch of prose (Markdown and raw HTML), for the book-wide check."""
    for match in _LINK.finditer(text):
        target = match["target"].strip("<>")
        image = bool(match["bang"])
        extracted.links.append(Link(target, loc, image, match["text"] if image else None))
    definition = _LINK_DEFINITION.match(text)
    if definition:
        extracted.links.append(Link(definition["target"].strip("<>"), loc))
    for match in _HTML_TARGET.finditer(text):
        extracted.links.append(Link(match["target"], loc, match["tag"].lower() == "img"))
    for tag in _HTML_IMG.finditer(text):
        if not re.search(r"\balt\s*=", tag[0]):
            extracted.errors.append(AuthorError(loc, 'an <img> needs alt text: alt="what the image shows"'))


def unconverted_dollar(text: str, loc: SourceLoc) -> AuthorError | None:
    """An error for a '$' that no formula took (what is left of a line once its math is lifted out)."""
    if not _DOLLAR.search(text):
        return None
    return AuthorError(
        loc,
        "a '$' here starts no formula: inline math is $...$ with no space just inside the dollars, display math "
        "starts with '$$' at the beginning of a line; write \\$ for a dollar sign",
    )


def did_you_mean(name: str, known, prefix: str = "", suffix: str = "") -> str:
    """'; did you mean 'x'?' for the closest of `known` (written between `prefix` and `suffix`), or ''."""
    close = difflib.get_close_matches(name, list(known), n=1, cutoff=0.6)
    return f"; did you mean '{prefix}{close[0]}{suffix}'?" if close else ""
