"""The book's print document: a built page's article rewritten to stand in one document with the others,
and the contents' order read from the home page (no browser)."""

from __future__ import annotations

from pathlib import Path

import pytest

from sitegen.pdf.compose import reading_order
from sitegen.pdf.rewrite import Place, for_print

BASE_URL = "https://example.org/tiny/"

PLACE = Place("mechanics", frozenset({"index", "mechanics", "waves"}), Path("/site"), BASE_URL)


@pytest.mark.parametrize(
    ("fragment", "expected"),
    [
        ('<h2 id="impulse">I</h2>', '<h2 id="mechanics--impulse">I</h2>'),
        ('<a href="#eq-j">(1)</a>', '<a href="#mechanics--eq-j">(1)</a>'),
        ('<a href="waves.html#eq-k">(2)</a>', '<a href="#waves--eq-k">(2)</a>'),
        ('<a href="index.html">home</a>', '<a href="#index">home</a>'),
        ('<a href="https://doi.org/10.1/x">doi</a>', '<a href="https://doi.org/10.1/x">doi</a>'),
        ('<a href="data/table.csv">data</a>', f'<a href="{BASE_URL}data/table.csv">data</a>'),
        ('<label for="s-m">m</label>', '<label for="mechanics--s-m">m</label>'),
        ('<dd aria-describedby="a b">x</dd>', '<dd aria-describedby="mechanics--a mechanics--b">x</dd>'),
        ("<details><summary>D</summary>x</details>", "<details open><summary>D</summary>x</details>"),
        ('<p>a<script type="application/json">{"x": "<\\/p>"}</script>b</p>', "<p>ab</p>"),
        ("<noscript><p>JavaScript is off</p></noscript><p>kept</p>", "<p>kept</p>"),
        ('<h2 id="x">X <a class="anchor" href="#x"><span>#</span></a></h2>', '<h2 id="mechanics--x">X </h2>'),
        ('<img src="images/map.png" alt="A map">', '<img src="file:///site/images/map.png" alt="A map">'),
        ("<p>&amp; &lt;x&gt; &#955;</p>", "<p>&amp; &lt;x&gt; &#955;</p>"),
    ],
    ids=[
        "id",
        "same-page",
        "other-page",
        "page",
        "outside",
        "site-file",
        "label",
        "id-list",
        "details",
        "script",
        "noscript",
        "anchor",
        "image",
        "entities",
    ],
)
def test_an_article_is_made_fit_for_the_books_document(fragment, expected):
    assert for_print(fragment, PLACE) == expected


def test_a_scene_gets_its_web_address_under_its_caption():
    fragment = '<figure class="scene" id="scene-lever" data-scene="lever"><figcaption>A lever.</figcaption></figure>'
    printed = for_print(fragment, PLACE)
    assert printed.endswith(
        f'<figcaption>A lever.</figcaption><p class="scene-address">Interactive version: '
        f'<a href="{BASE_URL}mechanics.html#scene-lever">{BASE_URL}mechanics.html#scene-lever</a></p>\n</figure>'
    )


def test_without_a_web_address_a_link_to_a_file_of_the_site_is_left_as_text():
    place = Place("mechanics", frozenset({"mechanics"}), Path("/site"))
    assert for_print('<a href="data/table.csv">data</a>', place) == "<a>data</a>"
    assert (
        for_print('<figure class="scene" id="s"></figure>', place)
        == '<figure class="scene" id="mechanics--s"></figure>'
    )


def test_the_contents_order_is_read_from_the_home_pages_panel():
    index = (
        '<nav class="book-contents" id="book-contents"><ol><li><a href="index.html">Home</a></li>'
        '<li><a href="a.html">A</a><ol class="sections"><li><a href="#s">S</a></li></ol>'
        '<ol><li><a href="b.html">B</a></li></ol></li><li><a href="c.html">C</a></li></ol></nav>'
    )
    assert reading_order(index) == [(0, "index"), (0, "a"), (1, "b"), (0, "c")]


def test_sitegen_pdf_without_its_browser_says_so_and_keeps_the_site(tiny_book, capsys, monkeypatch):
    from sitegen.cli import main

    monkeypatch.chdir(tiny_book.root)
    assert main(["pdf", "--chromium", "/nonexistent/chromium"]) == 2
    assert "sitegen: no Chromium at /nonexistent/chromium" in capsys.readouterr().err
    assert (tiny_book.out / "index.html").is_file()  # built first, as `sitegen build` would
    assert not (tiny_book.root / "book.pdf").exists()
