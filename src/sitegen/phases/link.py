"""The phase that ties the pages together once all are read: citations formatted from the book's
bibliography (each page that cites gets its list of references), every label indexed across the book and
every reference to one checked, every link and file a page names checked, and every page's text searched
for markers left unconverted. Each problem is an error at the author's line."""

from __future__ import annotations

from dataclasses import replace

from ..content import bibliography as bib
from ..content.labels import check_references, index_labels
from ..content.leftovers import leftover_markers
from ..content.links import check_links, page_anchors
from ..content.pages import Page
from ..content.prose import did_you_mean
from ..errors import AuthorError, SourceLoc
from ..site import assets, search
from ..site.assemble import TEMPLATE_IDS
from .record import Book
from .run import BuildRun

_FOOTNOTES = '<section aria-label="Footnotes" class="footnotes"'


def link_book(book: Book, run: BuildRun) -> Book:
    """The book with its citations, its labels and the files its pages name; an error for every unknown
    citation key, label, link or file, and every marker left as text."""
    pages, citations = _cite(list(book.pages), run)
    labels, errors = index_labels(pages)
    errors += check_references(pages, labels)
    anchors = {page.slug: page_anchors(page, _template_ids(page)) for page in pages}
    reserved = {"assets/sitegen.js", "assets/sitegen.css", search.SEARCH_SCRIPT, f"assets/{assets.FONT_FILE}"}
    files, problems = check_links(pages, anchors, run.config.content, reserved)
    errors += problems
    for page in pages:
        text = page.html + "".join(page.extracted.captions)
        errors += leftover_markers(text, page.extracted.prose, SourceLoc(page.source, 1))
    for error in errors:
        run.error(error)
    return replace(book, pages=tuple(pages), labels=labels, citations=citations, files=tuple(files))


def _template_ids(page: Page) -> tuple[str, ...]:
    return TEMPLATE_IDS + (("contents",) if page.slug == "index" else ())


def _cite(pages: list[Page], run: BuildRun) -> tuple[list[Page], dict]:
    """The pages, those that cite with their list of references; each page's citations as HTML."""
    cited = [page for page in pages if page.extracted.citations]
    if not cited:
        return pages, {}
    library = _bibliography(run, cited[0].extracted.citations[0].loc)
    if library is None:
        return pages, {}
    try:
        style = bib.load_style(library.style)
    except ValueError as problem:
        run.error(AuthorError(_config_line(run, "csl"), str(problem)))
        return pages, {}
    made, out = {}, []
    for page in pages:
        if page.extracted.citations and _known_keys(page, library, run):
            made[page.slug] = bib.format_page(page.extracted.citations, library, style)
            page = replace(page, html=_with_references(page.html, made[page.slug].references))
        out.append(page)
    return out, made


def _bibliography(run: BuildRun, first: SourceLoc) -> bib.Bibliography | None:
    """The book's bibliography, read (None after reporting why there is none)."""
    book = run.config.book
    if book.bibliography is None:
        run.error(
            AuthorError(
                first, 'citations need a bibliography: name a BibTeX file in book.toml, bibliography = "references.bib"'
            )
        )
        return None
    if not book.bibliography.is_file():
        run.error(
            AuthorError(
                _config_line(run, "bibliography"), f"bibliography {book.relative(book.bibliography)} does not exist"
            )
        )
        return None
    style = book.csl or bib.DEFAULT_STYLE
    library, errors = bib.read_bibliography(book.bibliography, book.relative(book.bibliography), style)
    for error in errors:
        run.error(error)
    return library


def _known_keys(page: Page, library: bib.Bibliography, run: BuildRun) -> bool:
    """Whether every key the page cites is in the bibliography (an error for each that is not)."""
    known = True
    for citation in page.extracted.citations:
        for cited in citation.keys:
            if cited.key not in library.items:
                hint = did_you_mean(cited.key, library.items)
                literal = " (an @ that cites nothing is written \\@)" if citation.in_text else ""
                message = f"unknown citation key '{cited.key}'{hint}{literal}"
                run.error(AuthorError(citation.loc, message))
                known = False
    return known


def _with_references(html: str, references: str) -> str:
    """A page's HTML with its list of references at the end, before its footnotes."""
    at = html.find(_FOOTNOTES)
    return html + "\n" + references if at < 0 else html[:at] + references + html[at:]


def _config_line(run: BuildRun, key: str) -> SourceLoc:
    """Where book.toml sets `key` (its first line when it does not)."""
    path = run.config.book.root / "book.toml"
    lines = path.read_text(encoding="utf-8").splitlines() if path.is_file() else []
    line = next((n for n, text in enumerate(lines, start=1) if text.strip().startswith(key)), 1)
    return SourceLoc("book.toml", line)
