"""The book's labels: every equation, figure (image or scene), table and section that `(@name)` can refer to,
from any page.

Numbers are per page: a page's equations are (1), (2), …, its figures (pictures and scenes alike) Figure 1,
Figure 2, …, its labelled tables Table 1, …, each in the order the page shows them. A reference on the same
page shows the number; a reference from another page adds that page's title, where the number alone would
name something else. Sections are referred to by their heading, as headings carry no numbers.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from html import escape, unescape

from ..errors import AuthorError, SourceLoc
from .markdown_ext import Label
from .pages import Page
from .prose import did_you_mean

_TAG = re.compile(r"<[^>]+>")
NAMES = {"figure": "Figure", "table": "Table"}


@dataclass(frozen=True)
class Target:
    """A label with the page it is on and, for a section, its heading's text."""

    label: Label
    page: Page
    title: str = ""


def index_labels(pages: list[Page]) -> tuple[dict[str, Target], list[AuthorError]]:
    """Every label of the book by name, and an error for each label given twice (a scene's id twice is
    no error: it is one only when a reference names it)."""
    index, errors, scene_ids = {}, [], {}
    for page in pages:
        for label in page.extracted.labels:
            if label.anchor != label.name:  # a scene: referred to by its id
                scene_ids.setdefault(label.name, []).append(Target(label, page))
                continue
            if label.name in index:
                first = index[label.name].label.loc
                errors.append(AuthorError(label.loc, f"label '{label.name}' is used twice; it labels {first} too"))
                continue
            index[label.name] = Target(label, page, _heading(page.html, label) if label.kind == "section" else "")
    for name, targets in scene_ids.items():
        if name not in index and len(targets) == 1:
            index[name] = targets[0]
    return index, errors


def scene_places(pages: list[Page]) -> dict[str, list[SourceLoc]]:
    """Where each scene id is, for the error of a reference that names one used more than once."""
    places: dict[str, list[SourceLoc]] = {}
    for page in pages:
        for label in page.extracted.labels:
            if label.anchor != label.name:
                places.setdefault(label.name, []).append(label.loc)
    return places


def check_references(pages: list[Page], index: dict[str, Target]) -> list[AuthorError]:
    """An error for each `(@name)` that names no label, with the closest label."""
    places, errors = scene_places(pages), []
    for page in pages:
        for name, loc in page.extracted.references:
            if name in index:
                continue
            if len(places.get(name, [])) > 1:
                where = ", ".join(str(p) for p in places[name])
                message = (
                    f"reference (@{name}) is ambiguous: scenes with id "
                    f"'{name}' are at {where}; give them ids of their own"
                )
            else:
                hint = did_you_mean(name, index, "(@", ")")
                message = (
                    f"reference (@{name}) names no label{hint}; labels are "
                    "{#eq-…}, {#fig-…}, {#tbl-…}, {#sec-…} or a scene's id"
                )
            errors.append(AuthorError(loc, message))
    return errors


def reference_html(target: Target, page: Page) -> str:
    """The link a reference on `page` becomes: to its target, showing the number (and the page, when it is
    another)."""
    label, there = target.label, target.page
    href = f"#{label.anchor}" if there.slug == page.slug else f"{there.output_name}#{label.anchor}"
    if label.kind == "equation":
        text = f"({label.number})"
    elif label.kind == "section":
        text = escape(target.title)
    else:
        text = f"{NAMES[label.kind]}\u00a0{label.number}"
    if there.slug != page.slug:
        text = f"{text} in {escape(there.title)}"
    return f'<a class="ref" href="{href}">{text}</a>'


def _heading(html: str, label: Label) -> str:
    found = re.search(rf'<h[1-6] id="{re.escape(label.anchor)}">(.*?)</h[1-6]>', html, re.S)
    return " ".join(unescape(_TAG.sub("", found[1])).split()) if found else label.name
