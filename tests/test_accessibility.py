"""Accessibility of every built page, opened from disk (file://) in headless Chromium.

- axe-core (WCAG 2.0/2.1/2.2 A and AA, and best practices) finds nothing, in the light and the
  dark colour scheme;
- text keeps AA contrast in both schemes (worked out here too, since axe leaves text over
  MathML and some inline boxes "incomplete");
- Tab reaches every control and link, and each shows a focus ring with 3:1 contrast;
- pointer targets are at least 24 px (or spaced as WCAG 2.2 allows), at 1280 and 360 px wide;
- readouts sit in polite live regions; sliders carry labels and aria-valuetext;
- with prefers-reduced-motion nothing moves by itself, and no CSS animation runs;
- the page reads at 360 px without sideways scrolling;
- printing shows each scene as it is now, with no controls, dark on white.

Keyboard operation of each control (arrows, Page Up/Down, Home/End) is tested in test_browser.py.
"""

from __future__ import annotations

import pytest
from a11y import (
    control_size_problems,
    describe_violations,
    focused_element_problems,
    moving_state,
    overflow_problems,
    run_axe,
    tab_stops,
    target_size_problems,
    text_contrast_problems,
)
from browser import ROOT, SETTLED, front, load, new_page

from sitegen.content.pages import discover_pages

pytestmark = pytest.mark.browser  # the whole module is about pages in Chromium

PAGES = [f"{path.stem}.html" for path in discover_pages(ROOT / "content")]
SCHEMES = ("light", "dark")
WIDTHS = {"desktop": 1280, "phone": 360}


def _page_scheme_params():
    return [pytest.param(name, scheme, id=f"{name[:-5]}-{scheme}") for name in PAGES for scheme in SCHEMES]


def _load(chromium, site, name: str, **options):
    """A new page with `options`, and `name` opened in it from disk, fonts settled."""
    options.setdefault("viewport", {"width": WIDTHS["desktop"], "height": 900})
    page = new_page(chromium, **options)
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto((site / name).as_uri(), wait_until="load")
    page.evaluate(SETTLED)
    assert not errors, errors
    return page


@pytest.fixture
def open_page(tabs, built_site):
    """open_page(name, **page options) -> the page loaded afresh, in a page no other part of the
    test uses, for a test that changes it."""
    with tabs.lending() as borrow:

        def _open(name: str, **options):
            options.setdefault("viewport", {"width": WIDTHS["desktop"], "height": 900})
            page, errors = borrow(**options)
            load(page, (site := built_site / name).as_uri())
            assert not errors, f"{site.name}: {errors}"
            return page

        yield _open


@pytest.fixture(scope="module")
def page_as_loaded(chromium, built_site):
    """page_as_loaded(name, scheme) -> the page as it loads (1280 px wide), shared by the tests that only read it."""
    pages = {}

    def _get(name: str, scheme: str):
        if (name, scheme) not in pages:
            pages[name, scheme] = _load(chromium, built_site, name, color_scheme=scheme)
        return front(pages[name, scheme])

    return _get


PHONE = {
    "viewport": {"width": WIDTHS["phone"], "height": 740},
    "device_scale_factor": 2,
    "is_mobile": True,
    "has_touch": True,
}


@pytest.fixture(scope="module")
def phone_page(chromium, built_site):
    """phone_page(name) -> the page as it loads on a phone 360 px wide (touch, two device pixels to
    the CSS pixel), shared by the tests that only read it."""
    pages = {}

    def _get(name: str):
        if name not in pages:
            pages[name] = _load(chromium, built_site, name, **PHONE)
        return front(pages[name])

    return _get


def test_every_page_is_checked(built_site):
    """The pages parametrized here are exactly the pages built."""
    assert sorted(PAGES) == sorted(p.name for p in built_site.glob("*.html"))


@pytest.mark.parametrize("name,scheme", _page_scheme_params())
def test_axe_finds_no_violations(page_as_loaded, name, scheme):
    """axe-core, WCAG 2.0/2.1/2.2 A and AA plus best practices: zero violations."""
    page = page_as_loaded(name, scheme)
    violations = run_axe(page)
    assert not violations, describe_violations(violations)


@pytest.mark.parametrize("name,scheme", _page_scheme_params())
def test_text_keeps_contrast(page_as_loaded, name, scheme):
    """Every piece of text has 4.5:1 contrast (3:1 when large) against what is behind it."""
    page = page_as_loaded(name, scheme)
    assert page.evaluate("matchMedia('(prefers-color-scheme: dark)').matches") == (scheme == "dark")
    problems = text_contrast_problems(page)
    assert not problems, "\n".join(problems[:20])


def test_dark_scheme_is_dark_and_figures_sit_on_a_light_card(page_as_loaded):
    """The dark palette really applies, and the matplotlib figures keep their white ground."""
    page = page_as_loaded("newtons-laws.html", "dark")
    colours = page.evaluate(
        """() => ({body: getComputedStyle(document.body).backgroundColor,
                   figure: getComputedStyle(document.querySelector('.scene-figure')).backgroundColor,
                   filter: getComputedStyle(document.querySelector('.scene-svg')).filter})"""
    )
    assert colours["body"] != "rgb(255, 255, 255)" and _luminance(colours["body"]) < 0.05, colours
    assert colours["figure"] == "rgb(255, 255, 255)" and colours["filter"] == "none", colours


@pytest.mark.parametrize("name,scheme", _page_scheme_params())
def test_focus_is_visible_on_every_tab_stop(open_page, name, scheme):
    """Tab walks through every link and control in order; each shows a 3:1 focus ring on screen."""
    page = open_page(name, color_scheme=scheme)
    expected = tab_stops(page)
    assert expected
    reached, problems = [], []
    for _ in range(len(expected) + 3):
        page.keyboard.press("Tab")
        focused = focused_element_problems(page)
        if focused["where"] is None or (reached and focused["where"] == reached[0]):
            break  # past the last stop: focus left the document or came round again
        reached.append(focused["where"])
        problems += [f"{focused['where']}: {p}" for p in focused["problems"]]
    assert reached == expected
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("width", WIDTHS.keys())
@pytest.mark.parametrize("name", PAGES, ids=[n[:-5] for n in PAGES])
def test_targets_are_at_least_24px(page_as_loaded, phone_page, name, width):
    """Sliders, radio labels and buttons measure 24 px or more; other small targets are spaced."""
    page = page_as_loaded(name, "light") if width == "desktop" else phone_page(name)
    problems = control_size_problems(page) + target_size_problems(page)
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("name", PAGES, ids=[n[:-5] for n in PAGES])
def test_readouts_are_announced_politely(page_as_loaded, name):
    """Each readout is inside a polite live region present at load; nothing is assertive; every
    slider has a visible label and an aria-valuetext, and every radio group a legend."""
    page = page_as_loaded(name, "light")
    problems = page.evaluate(
        r"""() => {
          const problems = [];
          for (const out of document.querySelectorAll('[data-out]')) {
            const region = out.closest('[aria-live]');
            if (!region || region.getAttribute('aria-live') !== 'polite')
              problems.push(`readout ${out.dataset.out} is not in a polite live region`);
          }
          for (const el of document.querySelectorAll('[aria-live="assertive"], [role="alert"]'))
            problems.push(`assertive region ${el.outerHTML.slice(0, 60)}`);
          for (const input of document.querySelectorAll('input[type="range"]')) {
            const label = document.querySelector(`label[for="${input.id}"]`);
            if (!label || !label.textContent.trim() || label.getBoundingClientRect().width === 0)
              problems.push(`slider ${input.id} has no visible label`);
            if (!input.getAttribute('aria-valuetext')) problems.push(`slider ${input.id} has no aria-valuetext`);
          }
          for (const group of document.querySelectorAll('fieldset')) {
            const legend = group.querySelector('legend');
            if (!legend || !legend.textContent.trim())
              problems.push(`radio group ${group.dataset.param} has no legend`);
          }
          return problems;
        }"""
    )
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("name", PAGES, ids=[n[:-5] for n in PAGES])
def test_nothing_moves_by_itself_with_reduced_motion(open_page, name):
    """With prefers-reduced-motion, no CSS animation or transition runs and no scene moves unasked,
    and a slider moved by the reader updates the scene at once (no transition)."""
    page = open_page(name, reduced_motion="reduce")
    assert page.evaluate("matchMedia('(prefers-reduced-motion: reduce)').matches")
    before = moving_state(page)
    page.wait_for_timeout(600)
    after = moving_state(page)
    assert after == before
    assert not after["animations"]
    moved = page.evaluate(
        """() => [...document.querySelectorAll('[data-scene] input[type="range"]')].map(el => {
             el.value = el.min; el.dispatchEvent(new Event('input', {bubbles: true}));
             return document.getAnimations().length; })"""
    )
    assert not any(moved)


@pytest.mark.parametrize("name", PAGES, ids=[n[:-5] for n in PAGES])
def test_page_reads_at_360px(phone_page, name):
    """At 360 px nothing sticks out sideways (wide equations scroll in their own box), text stays
    at least 14 px, and every slider is wide enough to drag (at least 120 px)."""
    page = phone_page(name)
    problems = overflow_problems(page)
    assert not problems, "\n".join(problems)
    sizes = page.evaluate(
        """() => ({text: Math.min(...[...document.querySelectorAll('p, li, dd, dt, label, figcaption')]
                     .map(e => parseFloat(getComputedStyle(e).fontSize))),
                   sliders: [...document.querySelectorAll('input[type="range"]')]
                     .map(e => e.getBoundingClientRect().width)})"""
    )
    assert sizes["text"] >= 14, sizes
    assert all(w >= 120 for w in sizes["sliders"]), sizes


A4_TEXT_WIDTH = 718  # CSS px: an A4 page (793.7 px) less Chromium's default margins of 0.4 in each side


@pytest.mark.parametrize("name", PAGES, ids=[n[:-5] for n in PAGES])
def test_print_shows_scenes_as_they_are_without_controls(open_page, name):
    """Printed (even from the dark scheme, laid out at an A4 page's width): dark text on white, no
    sliders, radio buttons, play, reset or navigation buttons, and each scene's figure (the wide one,
    not the phone's), control values and readouts in the state the reader left; nothing reaches past
    the right edge of the text, not even inside a box that would scroll on screen (paper cannot)."""
    page = open_page(name, color_scheme="dark", viewport={"width": A4_TEXT_WIDTH, "height": 1000})
    page.evaluate(
        """() => document.querySelectorAll('[data-scene] input[type="range"]').forEach(el => {
             el.value = el.max; el.dispatchEvent(new Event('input', {bubbles: true})); })"""
    )
    on_screen = page.evaluate("() => [...document.querySelectorAll('[data-out], output')].map(e => e.textContent)")
    page.emulate_media(media="print")
    printed = page.evaluate(
        r"""() => {
          const shown = el => { const b = el.getBoundingClientRect();
            return getComputedStyle(el).display !== 'none' && b.width > 0 && b.height > 0; };
          return {
            controls: [...document.querySelectorAll('input, button, ' +
              'select')].filter(shown).map(e => e.outerHTML.slice(0, 80)),
            unchosen: [...document.querySelectorAll('fieldset label')].filter(l => !l.querySelector('input:checked')
              && shown(l)).map(l => l.textContent.trim()),
            chosen: [...document.querySelectorAll('fieldset label')].filter(l => l.querySelector('input:checked') &&
              shown(l)).length,
            groups: document.querySelectorAll('fieldset').length,
            hidden: [...document.querySelectorAll('[data-out], output, ' +
              '.scene-svg.wide')].filter(e => !shown(e)).map(e => e.outerHTML.slice(0, 80)),
            phone: [...document.querySelectorAll('.scene-svg.narrow')].filter(shown).length,
            cut: [...document.querySelectorAll('main *')].filter(e => !e.closest('svg') || e.localName === 'svg')
              .filter(e => shown(e) &&
                e.getBoundingClientRect().right > document.querySelector('article').getBoundingClientRect().right + 0.5)
              .map(e => `${e.localName}.${e.className.baseVal ?? e.className}: right ` +
                `${e.getBoundingClientRect().right.toFixed(0)}`).slice(0, 10),
            article: document.querySelector('article').getBoundingClientRect().right,
            texts: [...document.querySelectorAll('[data-out], output')].map(e => e.textContent),
            ink: getComputedStyle(document.body).color,
            paper: getComputedStyle(document.body).backgroundColor,
          };
        }"""
    )
    assert printed["controls"] == [] and printed["unchosen"] == []
    assert printed["chosen"] == printed["groups"]
    assert printed["hidden"] == [] and printed["phone"] == 0
    assert printed["article"] <= A4_TEXT_WIDTH and printed["cut"] == [], printed["cut"]
    assert printed["texts"] == on_screen
    assert printed["ink"] == "rgb(0, 0, 0)" and printed["paper"] == "rgb(255, 255, 255)", printed
    assert page.pdf(format="A4")[:5] == b"%PDF-"


def test_print_opens_the_derivations_and_lets_a_scene_start_a_page(open_page):
    """Printed, a closed <details> (a derivation) shows what it holds: by the stylesheet, and opened by the
    script before printing (closed again after); only a scene's figure is kept whole on a page, so that a
    scene may start a page rather than leave half of one empty."""
    page = open_page("newtons-laws.html", viewport={"width": A4_TEXT_WIDTH, "height": 1000})
    closed = page.evaluate("() => [...document.querySelectorAll('details:not([open])')].map(d => d.textContent.length)")
    assert closed, "no closed <details> on the page"
    page.emulate_media(media="print")
    laid_out = """() => [...document.querySelectorAll('details')].map(d =>
        [...d.children].filter(c => c.localName !== 'summary')
            .reduce((h, c) => h + c.getBoundingClientRect().height, 0))"""
    assert all(height > 0 for height in page.evaluate(laid_out)), page.evaluate(laid_out)
    breaks = page.evaluate("""() => [...document.querySelectorAll('figure.scene')].map(s =>
        [getComputedStyle(s).breakInside, getComputedStyle(s.querySelector('.scene-figure')).breakInside])""")
    assert set(map(tuple, breaks)) == {("auto", "avoid")}, breaks
    page.evaluate("dispatchEvent(new Event('beforeprint'))")
    assert page.evaluate("document.querySelectorAll('details:not([open])').length") == 0
    page.evaluate("dispatchEvent(new Event('afterprint'))")
    after = page.evaluate("() => [...document.querySelectorAll('details:not([open])')].map(d => d.textContent.length)")
    assert after == closed


def _luminance(css: str) -> float:
    r, g, b = (int(v) / 255 for v in css[css.index("(") + 1 : css.index(")")].split(",")[:3])
    lin = [v / 12.92 if v <= 0.03928 else ((v + 0.055) / 1.055) ** 2.4 for v in (r, g, b)]
    return 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]
