"""The furniture of a page beyond prose and math: highlighted code, footnotes, callouts, figures from images
and captioned tables, each made by a maintained Markdown extension where one exists (Python-Markdown's
footnotes, admonition and tables; pymdown-extensions' superfences, highlight and details; markdown-callouts'
GitHub alerts) and finished here by one tree processor: callouts read as notes, footnotes as endnotes,
a caption paragraph becomes its figure's or table's caption.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as etree
from dataclasses import dataclass

import markdown
from markdown.extensions import Extension
from markdown.postprocessors import Postprocessor
from markdown.treeprocessors import Treeprocessor

from ..errors import AuthorError, SourceLoc
from .prose import did_you_mean

CALLOUT_TYPES = ("note", "tip", "important", "warning", "caution")
_ALIASES = {"danger": "caution"}  # markdown-callouts writes GitHub's CAUTION as MkDocs' "danger"
_CALLOUT_LINE = re.compile(r"^(?P<mark>!!!|\?\?\?\+?)(?P<after>.*)$")
_CALLOUT_HEAD = re.compile(r'^\s+(?P<type>[a-z]+)(?:\s+"[^"]*")?\s*$')
_ALERT_LINE = re.compile(r"^ {0,3}>\s*\[!(?P<type>[^\]]*)\]\s*$")
_FIGURE_LINE = re.compile(
    r"^!\[(?P<caption>(?:[^\[\]]|\[[^\[\]]*\])*)\]\(\s*(?P<src><[^>]*>|[^)\s]+)\s*\)\s*(?:\{(?P<attrs>[^}]*)\})?\s*$"
)
_ATTR = re.compile(r'#(?P<id>\S+)|(?P<key>[a-z-]+)\s*=\s*"(?P<value>[^"]*)"|(?P<other>\S+)')
_TABLE_CAPTION = re.compile(r"^:\s+(?P<caption>.*?)\s*(?:\{#(?P<label>[^}\s]*)\})?\s*$")
MARKDOWN_EXTENSIONS = (
    "footnotes",
    "admonition",
    "pymdownx.details",
    "pymdownx.superfences",
    "pymdownx.highlight",
    "markdown_callouts.github_callouts",
)
MARKDOWN_CONFIGS = {
    "pymdownx.highlight": {"use_pygments": True, "css_class": "highlight", "guess_lang": False},
    "footnotes": {"BACKLINK_TITLE": "Back to the text of footnote %d", "SUPERSCRIPT_TEXT": "{}"},
}


@dataclass(frozen=True)
class Figure:
    """A picture on its own line: its file, caption (Markdown), alt text, label ("fig-…" or None) and number
    (None: unnumbered)."""

    src: str
    caption: str
    alt: str
    label: str | None
    number: int | None
    loc: SourceLoc


def callout_problem(line: str, loc: SourceLoc) -> AuthorError | None:
    """An error for a callout's opening line that names no known type, or is not written as one."""
    alert = _ALERT_LINE.match(line)
    if alert:
        kind = alert["type"].lower()
        if kind in CALLOUT_TYPES:
            return None
        hint = did_you_mean(kind, CALLOUT_TYPES, "[!", "]").upper().replace("; DID YOU MEAN", "; did you mean")
        return AuthorError(loc, f"unknown callout '[!{alert['type']}]'{hint}; types: {_types('[!', ']')}")
    opening = _CALLOUT_LINE.match(line)
    if not opening:
        return None
    head = _CALLOUT_HEAD.match(opening["after"])
    if head and head["type"] in CALLOUT_TYPES:
        return None
    word = (opening["after"].split() or [""])[0]
    if head or (word.isalpha() and word.islower() and len(opening["after"].split()) == 1):
        hint = did_you_mean(word, CALLOUT_TYPES)
        return AuthorError(loc, f"unknown callout type '{word}'{hint}; types: {', '.join(CALLOUT_TYPES)}")
    return AuthorError(
        loc,
        f"a callout starts '{opening['mark']} TYPE \"Title\"' (the title in double quotes, or none), its text "
        f"indented by four spaces on the lines below; types: {', '.join(CALLOUT_TYPES)}",
    )


def _types(before: str, after: str) -> str:
    return ", ".join(f"{before}{kind.upper()}{after}" for kind in CALLOUT_TYPES)


def figure_line(line: str, loc: SourceLoc, number: int, extracted) -> Figure | None:
    """The figure a line holding only an image makes (None if the line is not one); its problems go to `extracted`."""
    match = _FIGURE_LINE.match(line)
    if not match:
        return None
    label, alt = None, None
    for attr in _ATTR.finditer(match["attrs"] or ""):
        if attr["id"] and attr["id"].startswith("fig-"):
            label = attr["id"]
        elif attr["key"] == "alt":
            alt = attr["value"]
        else:
            extracted.errors.append(
                AuthorError(loc, f"an image takes {{#fig-name}} and alt=\"…\" in its braces, not '{attr[0]}'")
            )
    caption = match["caption"].strip()
    alt = caption_text(caption) if alt is None else alt
    return Figure(match["src"].strip("<>"), caption, alt, label, number if label else None, loc)


def caption_text(caption: str) -> str:
    """A caption's words as alt text: the Markdown's emphasis and code marks and math's dollars dropped."""
    return " ".join(re.sub(r"[*_`$]|\\(?=[$@])", "", caption).split())


def table_caption(line: str, previous: str) -> tuple[str, str | None] | None:
    """(caption, label or None) for a `: Caption {#tbl-name}` line right after a table's last row, else None."""
    if not previous.lstrip().startswith("|"):
        return None
    match = _TABLE_CAPTION.match(line)
    return (match["caption"], match["label"]) if match else None


class FurnitureProcessor(Treeprocessor):
    """Callouts as notes, footnotes as endnotes, caption paragraphs into their figure or table."""

    def __init__(self, md: markdown.Markdown, extracted):
        super().__init__(md)
        self.extracted = extracted

    def run(self, root: etree.Element) -> None:
        for parent in list(root.iter()):
            for child in list(parent):
                if child.tag == "p" and "data-figure" in child.attrib:
                    self._figure(parent, child)
                elif child.tag == "p" and "data-table-caption" in child.attrib:
                    self._table_caption(parent, child)
                elif child.tag == "div" and "admonition" in child.get("class", "").split():
                    _callout(child)
                elif child.tag == "details" and _kind(child):  # ??? TYPE, not a <details> the author wrote
                    _callout(child, title_tag="summary")
                elif child.tag == "div" and child.get("class") == "footnote":
                    _endnotes(child)
                elif child.tag == "sup" and child.get("id", "").startswith("fnref"):
                    for link in child.iter("a"):
                        link.set("role", "doc-noteref")
        for parent in list(root.iter()):
            for child in list(parent):
                if child.tag == "table":
                    _scrolling(parent, child)

    def _figure(self, parent: etree.Element, paragraph: etree.Element) -> None:
        figure = self.extracted.figures[int(paragraph.attrib.pop("data-figure"))]
        paragraph.tag = "figcaption"
        element = etree.Element("figure", {"class": "figure"})
        if figure.label:
            element.set("id", figure.label)
            _prepend_label(paragraph, f"Figure {figure.number}")
        etree.SubElement(element, "img", {"src": figure.src, "alt": figure.alt})
        parent.insert(list(parent).index(paragraph), element)
        parent.remove(paragraph)
        if paragraph.text or len(paragraph):
            element.append(paragraph)

    def _table_caption(self, parent: etree.Element, paragraph: etree.Element) -> None:
        number = paragraph.attrib.pop("data-table-caption")
        label = paragraph.attrib.pop("data-table-label", None)
        siblings = list(parent)
        at = siblings.index(paragraph)
        table = siblings[at - 1] if at else None
        if table is None or table.tag != "table":
            return  # the caption line follows no table: it stays a paragraph (the preprocessor saw a row)
        paragraph.tag = "caption"
        if label:
            table.set("id", label)
            _prepend_label(paragraph, f"Table {number}")
        parent.remove(paragraph)
        table.insert(0, paragraph)


def _scrolling(parent: etree.Element, table: etree.Element) -> None:
    """A table in a box of its own that scrolls sideways where the page is too narrow (and takes the
    keyboard's focus, so that it can be scrolled without a pointer)."""
    box = etree.Element("div", {"class": "table-scroll", "tabindex": "0"})
    parent.insert(list(parent).index(table), box)
    parent.remove(table)
    box.append(table)
    box.tail, table.tail = table.tail, None


class _FocusableCode(Postprocessor):
    """A code block takes the keyboard's focus, so that a long line can be scrolled to without a pointer."""

    def run(self, text: str) -> str:
        return text.replace('<div class="highlight"><pre>', '<div class="highlight"><pre tabindex="0">')


def _prepend_label(element: etree.Element, text: str) -> None:
    label = etree.Element("span", {"class": "caption-label"})
    label.text, label.tail = text.replace(" ", "\u00a0"), (" " + element.text if element.text else " ")
    element.text = None
    element.insert(0, label)


def _kind(element: etree.Element) -> str | None:
    """The callout type an element's classes name, if any."""
    classes = [_ALIASES.get(c, c) for c in element.get("class", "").split()]
    return next((c for c in classes if c in CALLOUT_TYPES), None)


def _callout(element: etree.Element, title_tag: str = "p") -> None:
    kind = _kind(element) or "note"
    element.set("class", " ".join(["callout", kind] + (["admonition"] if title_tag == "p" else [])))
    if title_tag == "p":
        element.set("role", "note")
    title = next((c for c in element if c.tag == title_tag), None)
    if title is not None and "".join(title.itertext()).strip().lower() != kind:
        hidden = etree.Element("span", {"class": "visually-hidden"})
        hidden.text, hidden.tail = f"{kind.capitalize()}: ", title.text
        title.text = None
        title.insert(0, hidden)


def _endnotes(element: etree.Element) -> None:
    element.tag = "section"
    element.set("class", "footnotes")
    element.set("role", "doc-endnotes")
    element.set("aria-label", "Footnotes")
    for link in element.iter("a"):
        if "footnote-backref" in link.get("class", ""):
            link.set("role", "doc-backlink")


class FurnitureExtension(Extension):
    """Registers the furniture's tree processor for one page."""

    def __init__(self, extracted):
        super().__init__()
        self.extracted = extracted

    def extendMarkdown(self, md: markdown.Markdown) -> None:
        md.ESCAPED_CHARS += ["$", "@"]  # \$ and \@ write the characters themselves
        # Priority 5: after the inline processor (20) and attr_list (8) have filled every element.
        md.treeprocessors.register(FurnitureProcessor(md, self.extracted), "sitegen_furniture", 5)
        md.postprocessors.register(_FocusableCode(md), "sitegen_focusable_code", 5)  # after raw HTML is put back
