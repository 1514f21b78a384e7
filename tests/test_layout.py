"""The book on a phone, a tablet and a desktop, in the light and the dark scheme, in headless Chromium.

At 320, 390, 768 and 1280 px: the page never scrolls sideways, a box whose content is wider than it
(an equation, a table) shows that it scrolls, every scene shows one figure and all of it, no text
of a figure reaches outside it or shrinks below 8 px, no legend covers a panel where data is drawn,
and no slider's label runs into the slider or its value. Print is checked in test_accessibility.py.
"""

from __future__ import annotations

from dataclasses import dataclass

import pytest
from browser import ROOT, SETTLED, front, new_page
from layout import (
    control_label_problems,
    equation_number_problems,
    figure_problems,
    legend_problems,
    overflow_problems,
    svg_text_problems,
    text_collision_problems,
)

from sitegen.content.pages import discover_pages

PAGES = [f"{path.stem}.html" for path in discover_pages(ROOT / "content")]
WIDTHS = (320, 390, 768, 1280)
SCHEMES = ("light", "dark")


def _settled(page) -> None:
    page.evaluate("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")


@pytest.fixture(scope="module")
def page_at(chromium, built_site):
    """page_at(name, width, scheme) -> the page opened from disk (one page per
    page and scheme, reused by the tests that only read it), its viewport `width` px wide. A page whose
    viewport is resized lays out as one loaded at that width: its CSS answers to the width, and its
    script decides what scrolls on every resize."""
    pages = {}

    def _get(name: str, width: int, scheme: str):
        if (name, scheme) not in pages:
            page = new_page(chromium, viewport={"width": width, "height": 844}, color_scheme=scheme)
            errors = []
            page.on("pageerror", lambda e: errors.append(str(e)))
            page.goto((built_site / name).as_uri(), wait_until="load")
            page.evaluate(SETTLED)
            _settled(page)
            assert not errors, errors
            pages[name, scheme] = page
        page = front(pages[name, scheme])
        if page.viewport_size["width"] != width:
            page.set_viewport_size({"width": width, "height": 844})
            _settled(page)
        return page

    return _get


@dataclass(frozen=True)
class Case:
    name: str
    width: int
    scheme: str


# Page, scheme, then width: each page is loaded once per scheme and widened three times.
CASES = [Case(name, width, scheme) for name in PAGES for scheme in SCHEMES for width in WIDTHS]


@pytest.fixture(scope="module", params=CASES, ids=[f"{c.name[:-5]}-{c.width}-{c.scheme}" for c in CASES])
def case(request):
    """One page at one width in one scheme; module scope, so that pytest runs every check of a case
    before it moves on to the next (and resizes each page only when the width changes)."""
    return request.param


@pytest.fixture
def page(page_at, case):
    return page_at(case.name, case.width, case.scheme)


def test_nothing_wider_than_its_box_without_a_scroller(page):
    """The page does not scroll sideways; a box that does (an equation, a table) shows it."""
    problems = overflow_problems(page)
    assert not problems, "\n".join(problems[:15])


def test_equation_numbers_keep_to_the_right_margin(page):
    """Every numbered equation, alone or a list, has its number flush right, beside its last line, clear of it."""
    problems = equation_number_problems(page)
    assert not problems, "\n".join(problems[:15])


def test_every_scene_shows_its_whole_figure(page, case):
    """One figure per scene (the phone's below 480 px), inside the scene and the screen, never scrolled."""
    problems = figure_problems(page)
    assert not problems, "\n".join(problems[:15])
    variants = page.evaluate("""() => [...document.querySelectorAll('svg.scene-svg')]
        .filter(s => s.getBoundingClientRect().width > 0)
          .map(s => s.classList.contains('narrow') ? 'narrow' : 'wide')""")
    assert set(variants) <= ({"narrow"} if case.width < 480 else {"wide"}), variants


def test_figure_text_stays_inside_and_legible(page):
    """No text of a shown figure (scenes and the accuracy page's diagrams) reaches outside its SVG,
    and none is drawn smaller than 8 px."""
    problems = svg_text_problems(page)
    assert not problems, "\n".join(problems[:15])


def test_no_two_texts_of_a_figure_collide(page):
    """Point labels, titles, legends and ticks of a shown figure never overlap one another."""
    problems = text_collision_problems(page)
    assert not problems, "\n".join(problems[:15])


def test_no_legend_covers_a_panel(page):
    """Legends sit outside the plotting areas, where the data is drawn (the accuracy diagrams too)."""
    problems = legend_problems(page)
    assert not problems, "\n".join(problems[:15])


def test_no_label_runs_into_a_control(page):
    """A slider's label, the slider and its value text never overlap (e.g. "incident SPL (dB)")."""
    problems = control_label_problems(page)
    assert not problems, "\n".join(problems[:15])


def test_a_scene_off_the_screen_holds_room_for_itself(page):
    """A scene away from the screen holds the build's guess of its height until it is laid out; the guess is
    never below the height it takes then, so its controls never lie over the text after it meanwhile."""
    guesses = page.evaluate("""() => [...document.querySelectorAll('.scene')].map(e =>
        [e.id, parseFloat(getComputedStyle(e).containIntrinsicBlockSize.split(' ').pop())])""")
    page.evaluate("document.documentElement.classList.add('laid-out')")
    try:
        heights = page.evaluate("[...document.querySelectorAll('.scene')].map(e => e.getBoundingClientRect().height)")
    finally:
        page.evaluate("document.documentElement.classList.remove('laid-out')")
    short = [
        f"{name}: guessed {guess:.0f} px, laid out {height:.0f} px"
        for (name, guess), height in zip(guesses, heights)
        if guess < height
    ]
    assert not short, "\n".join(short)


def test_the_checks_find_what_they_look_for(page_at):
    """The checks are not blind: text pushed outside a figure or onto other text, a legend moved onto a
    panel, a label widened over its slider, an equation made to overflow without its shadow, and an
    equation number moved off the margin or taken away are all reported."""
    page = page_at("newtons-laws.html", 1280, "light")
    try:
        page.evaluate("""() => {
            const svg = document.querySelector('#scene-collision svg.wide');
            svg.querySelector('text').setAttribute('x', '-40');
            const legend = svg.querySelector('g[id*="-legend_"]');
            legend.setAttribute('transform', 'translate(0 80)');
            const label = document.querySelector('#scene-collision .control label');
            label.style.whiteSpace = 'nowrap'; label.textContent = 'a very long name that runs on and on';
            const eq = document.querySelector('.equation'); eq.style.width = '40px'; eq.classList.remove('scrolls');
            const numbers = document.querySelectorAll('.equation.numbered:not(:first-of-type) > .eqno');
            numbers[1].style.marginRight = '2em'; numbers[2].remove();
        }""")
        numbers = equation_number_problems(page)
        assert any("the right margin" in p for p in numbers) and any("no number" in p for p in numbers), numbers
        assert (
            svg_text_problems(page)
            and legend_problems(page)
            and control_label_problems(page)
            and overflow_problems(page)
        )
        page.evaluate("""() => { const texts = document.querySelectorAll('#scene-collision svg.wide text');
            texts[1].setAttribute('x', texts[0].getAttribute('x'));
            texts[1].setAttribute('y', texts[0].getAttribute('y')); }""")
        assert text_collision_problems(page)
    finally:
        page.reload(wait_until="load")
        page.evaluate(SETTLED)
