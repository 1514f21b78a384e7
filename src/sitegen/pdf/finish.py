"""What is read back from a printed PDF (the page each target landed on, its links) and the finished file:
metadata from the book, never from the clock, so the same sources give the same bytes."""

from __future__ import annotations

import datetime
import io
from pathlib import Path

from pypdf import PdfReader, PdfWriter

from ..config import BookConfig


class BrokenLinks(RuntimeError):
    """A link in the printed book that leads nowhere (a bug in sitegen's print document, not in the book)."""


def target_pages(pdf: Path) -> dict[str, int]:
    """The page (from 1) on which each named destination (an id that a link points to) landed."""
    reader = PdfReader(pdf)
    return {
        name.lstrip("/"): reader.get_destination_page_number(dest) + 1
        for name, dest in reader.named_destinations.items()
    }


def links(reader: PdfReader) -> list[tuple[int, str, str]]:
    """Every link of the document: (page from 1, "dest" or "uri", its destination name or address)."""
    found = []
    for number, page in enumerate(reader.pages, 1):
        for annotation in page.get("/Annots") or []:
            annotation = annotation.get_object()
            if annotation.get("/Subtype") != "/Link":
                continue
            if "/Dest" in annotation:
                found.append((number, "dest", str(annotation["/Dest"]).lstrip("/")))
            elif "/A" in annotation and annotation["/A"].get("/S") == "/URI":
                found.append((number, "uri", str(annotation["/A"]["/URI"])))
    return found


def broken_links(reader: PdfReader) -> list[str]:
    """The links that lead nowhere: to a destination the document lacks, or to a file on this machine."""
    names = {name.lstrip("/") for name in reader.named_destinations}
    return [
        f"page {page}: {kind} {target}"
        for page, kind, target in links(reader)
        if (kind == "dest" and target not in names) or (kind == "uri" and target.startswith("file:"))
    ]


def finished(printed: Path, book: BookConfig, title: str) -> tuple[bytes, int]:
    """The printed PDF with the book's metadata (its title and author, and its date or no date at all), and
    its number of pages."""
    reader = PdfReader(printed)
    problems = broken_links(reader)
    if problems:
        raise BrokenLinks("the printed book has links that lead nowhere: " + "; ".join(problems))
    writer = PdfWriter(clone_from=reader)
    metadata = {"/Title": title, "/Creator": "sitegen", "/Producer": str(reader.metadata.get("/Producer", ""))}
    if book.author:
        metadata["/Author"] = book.author
    if book.date:
        stamp = f"D:{datetime.date.fromisoformat(book.date):%Y%m%d}000000Z"
        metadata["/CreationDate"] = metadata["/ModDate"] = stamp
    writer.metadata = metadata  # replaces Chromium's, whose dates are the moment it printed
    out = io.BytesIO()
    writer.write(out)
    return out.getvalue(), len(reader.pages)
