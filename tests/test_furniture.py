"""A small book written as a new author would (tests/furniture/): citations from its .bib, a footnote, both
callout forms and a collapsible one, fenced and indented code, a labelled picture, a captioned table, and
references to an equation and a scene on another page. It builds into pages where each of them is
rendered and linked, with nothing left as raw text, the picture copied as it is; the same bytes from two
clean builds; valid HTML; and in Chromium every piece shows, every reference leads to its place, and axe
finds nothing at 390 and 1280 px in the light and the dark scheme.
"""

from __future__ import annotations

import re
import shutil
from html.parser import HTMLParser
from pathlib import Path

import pytest
from a11y import describe_violations, overflow_problems, run_axe, text_contrast_problems
from browser import front, load, new_page
from helpers import tree
from test_html_validity import _describe, _is_error, run_vnu

from sitegen.build import BuildConfig, build

BOOK = Path(__file__).parent / "furniture"
PAGES = ("index.html", "cochlea.html")
RAW = re.compile(r"\[@|@\w|\[\^|\[!\w+\]|!!!|\?\?\?|```|~~~|\$|\(@|\{#")


def _build(folder: Path) -> Path:
    shutil.copytree(BOOK, folder, dirs_exist_ok=True)
    build(BuildConfig.at(folder, cache=None), progress=None)
    return folder / "build"


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    return _build(tmp_path_factory.mktemp("furniture"))


class _Text(HTMLParser):
    """A page's visible words outside code, math and scripts, and every element's id and class."""

    SKIP = {"code", "pre", "math", "script", "style", "svg"}

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.words, self.ids, self.depth = [], set(), 0

    def handle_starttag(self, tag, attrs):
        self.ids |= {value for name, value in attrs if name == "id"}
        self.depth += tag in self.SKIP

    def handle_endtag(self, tag):
        self.depth -= tag in self.SKIP

    def handle_data(self, data):
        if not self.depth:
            self.words.append(data)


def _read(path: Path) -> _Text:
    text = _Text()
    text.feed(path.read_text(encoding="utf-8"))
    return text


def test_every_piece_is_rendered(site):
    html = (site / "cochlea.html").read_text(encoding="utf-8")
    assert html.count('<span class="citation">') == 3
    assert re.findall(r'<li id="(ref-[\w-]+)">', html) == ["ref-vonbekesy1960", "ref-greenwood1990", "ref-notes2024"]
    assert '<a href="#ref-vonbekesy1960">[1, p. 12]</a>' in html
    assert '<a href="https://doi.org/10.1121/1.399052">' in html and '<a href="https://example.org/ear-notes">' in html
    assert '<section aria-label="Footnotes" class="footnotes" role="doc-endnotes">' in html
    assert html.count('role="note"') == 2 and '<details class="callout tip">' in html
    assert '<span class="k">def</span>' in html and "an indented block\nstays code" in html
    assert re.search(
        r'<figure class="figure" id="fig-greenwood"><img alt="Greenwood\'s map[^"]*" src="images/greenwood.png"', html
    )
    assert '<table id="tbl-places">\n<caption><span class="caption-label">Table\u00a01</span> Best frequencies' in html


def test_the_picture_is_copied_byte_for_byte(site):
    assert (site / "images" / "greenwood.png").read_bytes() == (
        BOOK / "content" / "images" / "greenwood.png"
    ).read_bytes()


@pytest.mark.parametrize("name", PAGES)
def test_no_marker_is_left_as_text(site, name):
    words = " ".join(_read(site / name).words)
    assert not RAW.findall(words.replace("$ and an at sign @", "")), RAW.findall(words)


REFERENCES = [
    ("cochlea.html", "index.html#eq-oscillator", "(1) in Hearing, as physics"),
    ("cochlea.html", "index.html#scene-carts", "Figure\u00a01 in Hearing, as physics"),
    ("cochlea.html", "#fig-greenwood", "Figure\u00a01"),
    ("cochlea.html", "#tbl-places", "Table\u00a01"),
    ("cochlea.html", "#sec-place", "Place and frequency"),
    ("index.html", "#eq-oscillator", "(1)"),
]


@pytest.mark.parametrize("page,href,text", REFERENCES, ids=[h for _, h, _ in REFERENCES])
def test_each_reference_links_to_its_place_with_its_number(site, page, href, text):
    html = (site / page).read_text(encoding="utf-8")
    assert f'<a class="ref" href="{href}">{text}</a>' in html
    target, _, anchor = href.rpartition("#")
    assert anchor in _read(site / (target or page)).ids


def test_two_clean_builds_give_the_same_bytes(site, tmp_path):
    again = _build(tmp_path / "again")
    assert tree(site) == tree(again)


def test_the_pages_are_valid_html(site):
    errors = [_describe(m) for m in run_vnu(site) if _is_error(m)]
    assert not errors, "\n".join(errors)


@pytest.fixture(scope="module")
def seen(chromium, site):
    """seen(name, width, scheme) -> the page opened from disk at that width in that colour scheme."""
    pages = {}

    def _get(name: str, width: int, scheme: str):
        if (name, width, scheme) not in pages:
            page = new_page(chromium, viewport={"width": width, "height": 900}, color_scheme=scheme)
            load(page, (site / name).as_uri())
            pages[name, width, scheme] = page
        return front(pages[name, width, scheme])

    return _get


def test_chromium_shows_every_piece(seen):
    page = seen("cochlea.html", 1280, "light")
    for selector in (
        ".citation",
        ".references-list li",
        ".footnotes li",
        ".callout.note",
        ".callout.warning",
        "details.callout > summary",
        ".highlight pre",
        "#fig-greenwood figcaption",
        "#tbl-places caption",
    ):
        box = page.locator(selector).first.bounding_box()
        assert box and box["width"] > 0 and box["height"] > 0, selector
    assert page.evaluate("document.querySelector('#fig-greenwood img').naturalWidth") == 320
    text = page.evaluate("document.querySelector('article').innerText")
    assert not RAW.findall(text.replace("$ and an at sign @", "").replace("@ ", "")), RAW.findall(text)
    colours = page.evaluate(
        "['.highlight .k', '.highlight .n', '.highlight .sd'].map(s "
        "=> getComputedStyle(document.querySelector(s)).color)"
    )
    assert len(set(colours)) == 3, colours


def test_a_collapsed_callout_opens(seen):
    page = seen("cochlea.html", 1280, "light")
    body = page.locator("details.callout p")
    assert not body.is_visible()
    page.locator("details.callout > summary").click()
    assert body.is_visible()
    page.locator("details.callout > summary").click()


def test_a_reference_to_another_page_opens_it_at_the_place(chromium, site):
    page = new_page(chromium, viewport={"width": 390, "height": 700})
    load(page, (site / "cochlea.html").as_uri())
    page.locator('a.ref[href="index.html#eq-oscillator"]').click()
    page.wait_for_url("**/index.html#eq-oscillator")
    assert page.locator("#eq-oscillator").is_visible()
    assert page.evaluate("document.querySelector('#eq-oscillator').getBoundingClientRect().top") < 700


def test_a_citation_and_a_footnote_lead_to_their_notes_and_back(seen):
    page = seen("cochlea.html", 1280, "light")
    page.locator('a[href="#ref-greenwood1990"]').click()
    assert page.evaluate("location.hash") == "#ref-greenwood1990"
    page.locator("a.footnote-ref").click()
    assert page.evaluate("location.hash") == "#fn:stiff"
    page.locator("a.footnote-backref").click()
    assert page.evaluate("location.hash") == "#fnref:stiff"


CASES = [(name, width, scheme) for name in PAGES for width in (390, 1280) for scheme in ("light", "dark")]


@pytest.mark.parametrize("name,width,scheme", CASES, ids=[f"{n[:-5]}-{w}-{s}" for n, w, s in CASES])
def test_axe_finds_nothing(seen, name, width, scheme):
    page = seen(name, width, scheme)
    violations = run_axe(page)
    assert not violations, describe_violations(violations)
    assert text_contrast_problems(page) == []
    assert overflow_problems(page) == []
