"""`sitegen pdf`: the tiny book printed as one PDF by headless Chromium, read back with pypdf.

The book is a copy of the tiny book with a web address, a date and Letter paper in its book.toml;
it is built and printed twice, and everything below reads those two files.
"""

from __future__ import annotations

import html
import re
import subprocess
import sys
import unicodedata
from pathlib import Path

import pytest
from conftest import copy_book
from pypdf import PdfReader

from sitegen.config import read_book
from sitegen.pdf import ChromiumMissing, make_pdf
from sitegen.pdf.chromium import find_chromium
from sitegen.pdf.compose import document_html, read_site
from sitegen.pdf.finish import broken_links, links

BASE_URL = "https://example.org/tiny/"
TEXT_WIDTH_PX = (8.5 * 25.4 - 2 * 20) / 25.4 * 96  # Letter, less the side margins of print.css (20 mm each)
_READOUT = re.compile(r'<dd data-out="[^"]+"[^>]*>(.*?)</dd>', re.S)
_HEADING = re.compile(r'<h([12])(?: id="[^"]*")?>(.*?)</h\1>', re.S)
_TAG = re.compile(r"<[^>]+>")


def _squeezed(text: str) -> str:
    """Text without white space, which PDF text extraction places differently from HTML, and with the
    ligatures and mathematical letters of the fonts read as plain letters."""
    return re.sub(r"\s+", "", unicodedata.normalize("NFKC", text))


def _plain(fragment: str) -> str:
    return html.unescape(_TAG.sub("", re.sub(r'<a class="anchor".*?</a>', "", fragment, flags=re.S)))


@pytest.fixture(scope="module")
def printed(tmp_path_factory, tiny_built):
    """The tiny book (with base_url, date and paper = "letter"), built, and printed twice."""
    from sitegen.build import BuildConfig, build

    root = tmp_path_factory.mktemp("pdf-book")
    copy_book(root, tiny_built.cache)
    with open(root / "book.toml", "a", encoding="utf-8") as toml:
        toml.write(f'base_url = "{BASE_URL}"\ndate = "2026-11-30"\npaper = "letter"\n')
    book = read_book(root)
    build(BuildConfig.at(root), progress=None)
    first = make_pdf(book, book.output, root / "first.pdf")
    second = make_pdf(book, book.output, root / "second.pdf")
    return book, first, second


pytestmark = pytest.mark.browser  # Chromium prints every PDF of this module


def test_two_prints_of_the_same_sources_are_the_same_bytes(printed):
    _, first, second = printed
    assert first.path.read_bytes() == second.path.read_bytes()


def test_the_pdf_has_a_page_count_in_the_expected_range(printed):
    _, first, _ = printed
    # A title page, the contents, five pages of which four have scenes that fill most of a page each.
    assert 12 <= first.pages <= 40
    assert len(PdfReader(first.path).pages) == first.pages


def test_every_page_is_letter_sized(printed):
    _, first, _ = printed
    sizes = {(round(float(p.mediabox.width)), round(float(p.mediabox.height))) for p in PdfReader(first.path).pages}
    assert sizes == {(612, 792)}


def test_its_text_holds_every_title_and_section_title(printed):
    book, first, _ = printed
    text = _squeezed(" ".join(page.extract_text() for page in PdfReader(first.path).pages))
    titles = []
    for built in sorted(book.output.glob("*.html")):
        article = built.read_text(encoding="utf-8").split("<article>", 1)[1]
        titles += [_plain(inner) for _, inner in _HEADING.findall(article) if _plain(inner).strip() != "Contents"]
    assert titles
    assert [t for t in titles if _squeezed(t) not in text] == []


def test_its_text_holds_every_scenes_default_readouts(printed):
    book, first, _ = printed
    text = _squeezed(" ".join(page.extract_text() for page in PdfReader(first.path).pages))
    readouts = []
    for built in sorted(book.output.glob("*.html")):
        readouts += [_plain(value) for value in _READOUT.findall(built.read_text(encoding="utf-8"))]
    assert len(readouts) > 20
    assert [r for r in readouts if _squeezed(r) not in text] == []


def test_every_internal_link_leads_to_a_place_in_the_pdf(printed):
    book, first, _ = printed
    reader = PdfReader(first.path)
    internal = [target for _, kind, target in links(reader) if kind == "dest"]
    document = read_site(book.output, book)
    assert set(internal) >= {line.target for line in document.contents}  # the contents link to every part
    assert broken_links(reader) == []


def test_the_contents_show_the_page_each_part_starts_on(printed):
    book, first, _ = printed
    reader = PdfReader(first.path)
    page = reader.get_destination_page_number(reader.named_destinations["/mechanics"])
    text = reader.pages[1].extract_text()
    assert re.search(rf"Mechanics\W*{page + 1}\b", text)
    assert f"Mechanics{page + 1}" in _squeezed(reader.pages[page].extract_text())  # the running header


def test_each_scene_links_to_its_interactive_version(printed):
    book, first, _ = printed
    reader = PdfReader(first.path)
    addresses = {target for _, kind, target in links(reader) if kind == "uri"}
    built = (book.output / "mechanics.html").read_text(encoding="utf-8")
    scenes = re.findall(r'<figure class="scene" id="([^"]+)"', built)
    assert scenes
    assert {f"{BASE_URL}mechanics.html#{scene}" for scene in scenes} <= addresses
    text = _squeezed(" ".join(page.extract_text() for page in reader.pages))
    assert _squeezed(f"{BASE_URL}mechanics.html#{scenes[0]}") in text


def test_its_metadata_come_from_the_book_not_the_clock(printed):
    _, first, _ = printed
    metadata = PdfReader(first.path).metadata
    assert metadata["/Title"] == "A tiny book"
    assert metadata["/Author"] == "The sitegen tests"
    assert metadata["/CreationDate"] == metadata["/ModDate"] == "D:20261130000000Z"


def test_nothing_is_wider_than_the_text_block(printed, chromium):
    book, _, _ = printed
    page = chromium.new_page(viewport={"width": round(TEXT_WIDTH_PX), "height": 1000})
    document = Path(book.root) / "print.html"
    document.write_text(document_html(read_site(book.output, book), book, book.output, {}), encoding="utf-8")
    page.emulate_media(media="print")
    page.goto(document.as_uri())
    wider = page.evaluate(
        """width => [...document.querySelectorAll('body *:not(svg *)')]
             .filter(e => e.getBoundingClientRect().width > 0 && e.getBoundingClientRect().right > width + 0.5)
             .map(e => e.tagName + ' ' + (e.id || e.className.baseVal || e.className))""",
        page.evaluate("document.body.clientWidth"),
    )
    page.close()
    assert wider == []


def test_without_a_chromium_the_error_says_how_to_get_one():
    with pytest.raises(ChromiumMissing, match="apt install chromium"):
        find_chromium_with_no_path()


def find_chromium_with_no_path():
    """find_chromium as on a machine whose PATH has no browser and whose Playwright has none installed."""
    code = (
        "import os, sys; os.environ['PATH'] = ''; os.environ['PLAYWRIGHT_BROWSERS_PATH'] = '/nonexistent';"
        "from sitegen.pdf.chromium import find_chromium, ChromiumMissing\n"
        "try:\n    find_chromium()\nexcept ChromiumMissing as e:\n    print(e); sys.exit(7)"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    if done.returncode == 7:
        raise ChromiumMissing(done.stdout)
    raise AssertionError(f"found a Chromium with an empty PATH: {done.stdout} {done.stderr}")


@pytest.mark.parametrize("given", ["/nonexistent/chromium"])
def test_a_chromium_named_but_missing_is_an_error(given):
    with pytest.raises(ChromiumMissing, match="no Chromium at"):
        find_chromium(given)


@pytest.fixture(scope="module")
def furniture_pdf(tmp_path_factory, printed) -> PdfReader:
    """The small book of every piece of a page's furniture (tests/furniture/), built and printed."""
    import shutil

    from sitegen.build import BuildConfig, build

    root = tmp_path_factory.mktemp("pdf-furniture")
    shutil.copytree(Path(__file__).parent / "furniture", root, dirs_exist_ok=True)
    build(BuildConfig.at(root, cache=None), progress=None)
    book = read_book(root)
    return PdfReader(make_pdf(book, book.output, root / "book.pdf").path)


@pytest.mark.parametrize(
    "words",
    [
        "Greenwood [2] fitted with a single formula",  # a citation
        "Its stiffness falls by about a hundredfold",  # the footnote, at the end of its chapter
        "Why a single oscillator is not the whole story",  # a callout's title
        "The travelling wave peaks where the local resonance",  # a collapsible callout, printed open
        "def best_frequency(",  # fenced code
        "an indented block",  # indented code
        "Figure 1 Greenwood's map",  # a numbered picture's caption
        "Table 1 Best frequencies",  # a numbered table's caption
        "equation (1) in Hearing, as physics",  # a reference to an equation on another page
        "D. D. Greenwood, A cochlear frequency-position function",  # the references list
    ],
    ids=[
        "citation",
        "footnote",
        "callout",
        "collapsed-callout",
        "fenced",
        "indented",
        "figure",
        "table",
        "reference",
        "bibliography",
    ],
)
def test_the_furniture_of_every_page_is_printed(furniture_pdf, words):
    text = _squeezed(" ".join(page.extract_text() for page in furniture_pdf.pages))
    assert _squeezed(words) in text


def test_a_picture_of_a_page_is_in_the_pdf_and_its_notes_link_both_ways(furniture_pdf):
    assert sum(len(page.images) for page in furniture_pdf.pages) == 1
    internal = {target for _, kind, target in links(furniture_pdf) if kind == "dest"}
    assert {
        "cochlea--fn:stiff",
        "cochlea--fnref:stiff",
        "cochlea--ref-greenwood1990",
        "index--eq-oscillator",
    } <= internal
    assert broken_links(furniture_pdf) == []
