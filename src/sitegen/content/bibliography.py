"""Citations: a book's BibTeX file read by bibtexparser, each page's citations and references list formatted
by citeproc-py with a CSL style (by default the American Physical Society's, in csl/).

Citations are numbered per page, as each page has its own list of references at its end; every citation
links to its entry, and every entry's DOI and address are links.
"""

from __future__ import annotations

import logging
import re
import warnings
from dataclasses import dataclass
from html import escape
from pathlib import Path

from ..errors import AuthorError, SourceLoc
from .prose import Citation

DEFAULT_STYLE = Path(__file__).with_name("csl") / "american-physics-society.csl"
CSL_TYPES = {
    "article": "article-journal",
    "book": "book",
    "booklet": "pamphlet",
    "inbook": "chapter",
    "incollection": "chapter",
    "inproceedings": "paper-conference",
    "conference": "paper-conference",
    "proceedings": "book",
    "manual": "book",
    "mastersthesis": "thesis",
    "phdthesis": "thesis",
    "thesis": "thesis",
    "techreport": "report",
    "report": "report",
    "unpublished": "manuscript",
    "online": "webpage",
    "misc": "article",
}
_TEXT_FIELDS = {
    "title": "title",
    "journal": "container-title",
    "booktitle": "container-title",
    "publisher": "publisher",
    "school": "publisher",
    "institution": "publisher",
    "address": "publisher-place",
    "volume": "volume",
    "number": "issue",
    "pages": "page",
    "edition": "edition",
    "series": "collection-title",
    "type": "genre",
    "note": "note",
    "doi": "DOI",
    "url": "URL",
    "isbn": "ISBN",
}
_MONTHS = ("jan", "feb", "mar", "apr", "may", "jun", "jul", "aug", "sep", "oct", "nov", "dec")
_KEY_AT = re.compile(r"@\s*\w+\s*[{(]\s*([^,\s]+)")
logging.getLogger("bibtexparser").setLevel(logging.CRITICAL)  # its failures come back as blocks, reported here


@dataclass(frozen=True)
class Bibliography:
    """The entries of a book's BibTeX file as CSL-JSON items, by key, and the CSL style that formats them."""

    items: dict[str, dict]
    style: Path


def read_bibliography(path: Path, source: str, style: Path = DEFAULT_STYLE) -> tuple[Bibliography, list[AuthorError]]:
    """The entries of the BibTeX file at `path` (`source`: its name for messages), and an error naming each
    entry that cannot be read."""
    import bibtexparser
    from bibtexparser import middlewares

    text = path.read_text(encoding="utf-8")
    library = bibtexparser.parse_string(
        text,
        append_middleware=[  # names split first, where their braces still group words ({Lord Rayleigh})
            middlewares.SeparateCoAuthors(),
            middlewares.SplitNameParts(),
            middlewares.LatexDecodingMiddleware(),
        ],
    )
    errors, items = [], {}
    for block in library.failed_blocks:
        loc = SourceLoc(source, block.start_line + 1)
        key = _KEY_AT.search(block.raw or "")
        name = f"entry '{key[1]}'" if key else "an entry"
        error = getattr(block, "error", None)
        why = getattr(error, "abort_reason", None) or (error.args[0] if error and error.args else "not BibTeX")
        if type(block).__name__ == "DuplicateBlockKeyBlock":
            why = "another entry above has the same key"
        errors.append(AuthorError(loc, f"bibliography {name} cannot be read: {why.strip()}"))
    folded: dict[str, str] = {}
    for entry in library.entries:
        loc = SourceLoc(source, entry.start_line + 1)
        if entry.key.lower() in folded:
            errors.append(
                AuthorError(loc, f"bibliography entry '{entry.key}' has the key of '{folded[entry.key.lower()]}'")
            )
            continue
        folded[entry.key.lower()] = entry.key
        item, problem = csl_item(entry)
        if problem:
            errors.append(AuthorError(loc, f"bibliography entry '{entry.key}': {problem}"))
        else:
            items[entry.key] = item
    return Bibliography(items, style), errors


def csl_item(entry) -> tuple[dict, str | None]:
    """A BibTeX entry as a CSL-JSON item, or a problem that makes it unusable."""
    fields = {f.key.lower(): f.value for f in entry.fields}
    kind = CSL_TYPES.get(entry.entry_type.lower())
    if kind is None:
        return {}, f"unknown entry type '@{entry.entry_type}'; types: {', '.join(sorted(CSL_TYPES))}"
    if not fields.get("title"):
        return {}, "it needs a title"
    item: dict = {"id": entry.key.lower(), "type": kind}
    for name in ("author", "editor"):
        if name in fields:
            item[name] = [_csl_name(person) for person in fields[name]]
    if kind == "report" and "number" in fields:
        item["number"] = str(fields["number"])  # a report's own number, not an issue of a journal
    for field, variable in _TEXT_FIELDS.items():
        if field in fields and variable not in item and not (kind == "report" and field == "number"):
            item[variable] = " ".join(str(fields[field]).split())
    if "year" in fields:
        year = str(fields["year"]).strip()
        if not year.isdigit():
            return {}, f"year '{year}' is not a year"
        parts = [int(year)]
        month = str(fields.get("month", "")).strip().lower()[:3]
        if month in _MONTHS:
            parts.append(_MONTHS.index(month) + 1)
        item["issued"] = {"date-parts": [parts]}
    return item, None


def _csl_name(person) -> dict:
    from pylatexenc.latex2text import LatexNodes2Text

    def text(words: list[str]) -> str:
        return LatexNodes2Text().latex_to_text(" ".join(words)).strip()

    name = {"family": text(person.last)}
    for part, variable in ((person.first, "given"), (person.von, "non-dropping-particle"), (person.jr, "suffix")):
        if part:
            name[variable] = text(part)
    return name


def load_style(path: Path):
    """The CSL style at `path` (ValueError with a sentence when it cannot be read)."""
    from citeproc import CitationStylesStyle
    from lxml.etree import XMLSyntaxError

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # citeproc-py warns of fields it does not use
            return CitationStylesStyle(str(path), validate=False)
    except (OSError, ValueError, XMLSyntaxError) as problem:
        raise ValueError(f"the CSL style {path.name} cannot be read: {problem}") from None


@dataclass(frozen=True)
class PageCitations:
    """A page's citations as HTML (in the order of its placeholders) and its list of references."""

    citations: tuple[str, ...]
    references: str


def format_page(citations: list[Citation], bibliography: Bibliography, style) -> PageCitations:
    """Each citation of a page, linked to its entry, and the page's references list, by the CSL style."""
    from citeproc import Citation as CslCitation
    from citeproc import CitationItem, CitationStylesBibliography, Locator, formatter
    from citeproc.source.json import CiteProcJSON

    keys = {k.key for c in citations for k in c.keys}
    source = CiteProcJSON([bibliography.items[key] for key in sorted(keys)])
    book = CitationStylesBibliography(style, source, formatter.html)
    made = []
    for citation in citations:
        items = []
        for cited in citation.keys:
            extra = {"prefix": cited.prefix + " "} if cited.prefix else {}
            if cited.locator and cited.locator[0]:
                extra["locator"] = Locator(*cited.locator)
            elif cited.locator:
                extra["suffix"] = ", " + cited.locator[1]
            items.append(CitationItem(cited.key, **extra))
        made.append(CslCitation(items))
        book.register(made[-1])
    book.sort()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        texts = [str(book.cite(c, lambda item: None)).strip() for c in made]
        entries = [str(entry) for entry in book.bibliography()]
    numbers = {key: n for n, key in enumerate(book.keys, start=1)}
    original = {key.lower(): key for key in keys}
    html = [_linked(text, citation, numbers, original, bibliography.items) for text, citation in zip(texts, citations)]
    listed = [_entry(original[key], entry, bibliography.items[original[key]]) for key, entry in zip(book.keys, entries)]
    return PageCitations(tuple(html), _references_section(listed))


def _linked(text: str, citation: Citation, numbers: dict, original: dict, items: dict) -> str:
    """A formatted citation as links: each of its numbers to its entry (a numeric style), or the whole
    citation to its first entry; in the text, the authors' names before it."""
    keys = [k.key for k in citation.keys]
    if len(keys) > 1 and all(str(numbers[key.lower()]) in text for key in keys):
        by_number = {str(numbers[key.lower()]): key for key in keys}
        pattern = re.compile(r"(?<![\d.])(" + "|".join(sorted(by_number, key=len, reverse=True)) + r")(?![\d.])")
        body = pattern.sub(lambda m: f'<a href="#{ref_id(by_number[m[1]])}">{m[1]}</a>', text, count=len(keys))
    else:
        body = f'<a href="#{ref_id(keys[0])}">{text}</a>'
    if citation.in_text:
        return f'<span class="citation">{escape(_names(items[keys[0]]))}&#160;{body}</span>'
    return f'<span class="citation">{body}</span>'


def _names(item: dict) -> str:
    """The authors (or editors) of an entry as a sentence names them: "A", "A and B", "A et al."."""
    people = item.get("author") or item.get("editor") or []
    family = [" ".join(filter(None, (p.get("non-dropping-particle"), p["family"]))) for p in people]
    if not family:
        return item["title"]
    if len(family) > 2:
        return f"{family[0]} et al."
    return " and ".join(family)


def ref_id(key: str) -> str:
    """The id of a source's entry in a page's list of references."""
    return "ref-" + re.sub(r"[^A-Za-z0-9_-]", "-", key)


def _entry(key: str, text: str, item: dict) -> str:
    """One entry of the list: the style's text, its leading number apart, its DOI and address as links."""
    number = re.match(r"^(\[\d+\]|\d+\.)\s*", text)
    label = f'<span class="ref-label">{number[1]}</span> ' if number else ""
    text = text[number.end() :] if number else text
    for variable, address in (("DOI", "https://doi.org/{}"), ("URL", "{}")):
        value = item.get(variable)
        if not value:
            continue
        href, shown = escape(address.format(value)), escape(value)
        link = f'<a href="{href}">{escape(address.format(value)) if variable == "DOI" else shown}</a>'
        for written in (href, shown):
            if written in text:
                text = text.replace(written, link, 1)
                break
        else:
            text = f"{text} {link}"
    return f'<li id="{ref_id(key)}">{label}<span class="ref-text">{text}</span></li>'


def _references_section(entries: list[str]) -> str:
    items = "\n".join(entries)
    return (
        '<section class="references" aria-labelledby="references">\n'
        '<h2 id="references">References</h2>\n'
        f'<ol class="references-list">\n{items}\n</ol>\n</section>\n'
    )
