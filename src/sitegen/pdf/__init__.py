"""`sitegen pdf`: the whole book as one PDF, from the built site.

Every page of the site goes into one print document (compose.py), in the contents' order, after a title
page and the contents; headless Chromium prints it (chromium.py). The contents' page numbers are only
known once it is printed, so it is printed again with them, until the pages no longer move (the second
print, in practice). Last, the PDF's metadata are set from the book (finish.py).
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass
from pathlib import Path

from ..config import BookConfig
from .chromium import ChromiumMissing, PrintFailed, find_chromium, print_pdf
from .compose import document_html, read_site, targets
from .finish import BrokenLinks, finished, target_pages

__all__ = ["BrokenLinks", "ChromiumMissing", "PdfMade", "PrintFailed", "make_pdf"]
MAX_PRINTS = 4  # numbers in the contents that keep moving pages after this many prints are a bug


@dataclass(frozen=True)
class PdfMade:
    """What `make_pdf` wrote: where, its pages and bytes, and how many prints the page numbers took."""

    path: Path
    pages: int
    size: int
    prints: int


def make_pdf(book: BookConfig, site: Path, out: Path, chromium: str | None = None) -> PdfMade:
    """Print the site built in `site` as one PDF at `out`."""
    browser = find_chromium(chromium)
    document = read_site(site, book)
    title = document.title
    wanted = targets(document)
    numbers: dict[str, int] = {}
    prints = 0
    with tempfile.TemporaryDirectory(prefix="sitegen-pdf-") as work:
        page, printed = Path(work) / "book.html", Path(work) / "book.pdf"
        while True:
            prints += 1
            page.write_text(document_html(document, book, site, numbers), encoding="utf-8")
            print_pdf(browser, page, printed)
            landed = target_pages(printed)
            missing = [target for target in wanted if target not in landed]
            if missing:
                raise PrintFailed(f"the contents link to places the PDF does not have: {', '.join(missing)}")
            now = {target: landed[target] for target in wanted}
            if now == numbers:
                break
            if prints == MAX_PRINTS:
                raise PrintFailed(f"the contents' page numbers still moved after {MAX_PRINTS} prints")
            numbers = now
        data, pages = finished(printed, book, title)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(data)
    return PdfMade(out, pages, len(data), prints)
