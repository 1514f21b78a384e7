"""What a reader uses besides the scenes themselves, in headless Chromium from disk (file://):

- a scene's state is a link ("#collision:m1=2,e=0.5"): moving a control writes it in place of the
  address, opening it sets the controls and shows the scene, a bad value falls back to the default;
  each scene's Reset puts it back (every scene, round trip through a newly loaded page);
- the book's contents beside the text or behind a button, anchors on headings, previous and next;
- search, which loads its index as a classic script, from disk as over http;
- without JavaScript, the controls are hidden and a line says that the figures show their defaults.
"""

from __future__ import annotations

import json
import re
from decimal import Decimal
from urllib.parse import unquote

import pytest
from browser import SiteServer, book, front, load, logged_page, move, read_state, scene_problems

from sitegen.compute.grid import CHOICE
from sitegen.site.navigation import reading_order

PAGES, SCENES = book()
ORDER = [p.output_name for p in reading_order(PAGES)]


def _open(chromium, built_site, target: str, javascript: bool = True, width: int = 1280):
    """(page, errors): `target` (a URL or a page's name) opened in a new page, fonts settled."""
    page, errors = logged_page(chromium, java_script_enabled=javascript, viewport={"width": width, "height": 844})
    load(page, target if ":" in target else (built_site / target).as_uri())
    return page, errors


@pytest.fixture
def fresh(tabs, built_site):
    """fresh(url or page name, javascript=True, width=1280) -> (page, errors): the target loaded as a new
    document in a page that no other part of the test uses."""
    with tabs.lending() as borrow:

        def _fresh(target: str, javascript: bool = True, width: int = 1280):
            page, errors = borrow(java_script_enabled=javascript, viewport={"width": width, "height": 844})
            load(page, target if ":" in target else (built_site / target).as_uri())
            return page, errors

        yield _fresh


@pytest.fixture(scope="module")
def shared(chromium, built_site):
    """shared(page name, javascript=True, width=1280) -> (page, errors): one loaded page per name and
    options for the module, for the tests that only read it or put back what they change."""
    pages = {}

    def _get(name: str, **options):
        key = (name, *sorted(options.items()))
        if key not in pages:
            pages[key] = _open(chromium, built_site, name, **options)
        page, errors = pages[key]
        return front(page), errors

    return _get


def _in_view(page, dom_id: str) -> bool:
    return page.evaluate(
        "id => { const r = document.getElementById(id).getBoundingClientRect(); "
        "return r.top >= -2 && r.top < innerHeight; }",
        dom_id,
    )


def _wait_for_hash(page, prefix: str) -> str:
    page.wait_for_function("p => location.hash.startsWith(p)", arg=prefix, timeout=5_000)
    return page.evaluate("location.hash")


# --- a scene's state as a link ---------------------------------------------------------------------


def _elsewhere(scene) -> dict[str, int]:
    """A stop away from the default on every control that has more than one."""
    return {a.param: (d + max(1, a.count // 3)) % a.count for a, d in zip(scene.axes, scene.defaults) if a.count > 1}


@pytest.mark.parametrize("scene", SCENES, ids=[s.key for s in SCENES])
def test_scene_state_round_trips_through_its_link(fresh, shared, scene):
    """Move every control; the address becomes "#<scene>:<param>=<value>,..." naming each moved
    control; that link opened in a new document sets the same stops, shows the same readouts (the
    model's) and scrolls to the scene; Reset then brings back the defaults and the plain link."""
    page, page_errors = shared(scene.page.output_name)
    seen = len(page_errors)
    assert read_state(page, scene).stops == scene.defaults  # (the page is shared: each test resets its scene)
    moved = move(page, scene, _elsewhere(scene))
    link = _wait_for_hash(page, f"#{scene.id}:")
    pairs = dict(pair.split("=", 1) for pair in link.split(":", 1)[1].split(","))
    assert set(pairs) == {p for p, k in zip(scene.params, moved.stops) if k != scene.defaults[scene.params.index(p)]}
    for param, text in pairs.items():
        axis = scene.axis(param)
        if axis.kind == CHOICE:
            assert unquote(text) == axis.labels[moved.control(param).index], (param, text)
        else:
            assert abs(Decimal(unquote(text)) - Decimal(str(float(axis.stop(moved.control(param).index))))) < Decimal(
                "1e-6"
            ), (param, text)

    opened, opened_errors = fresh(page.url)
    front(page).click(f"#{scene.dom_id} button[data-reset]")  # the shared page back on the defaults
    state = read_state(front(opened), scene)
    assert state.stops == moved.stops
    assert state.readouts == moved.readouts and scene_problems(scene, state) == []
    assert state.layers == moved.layers
    assert _in_view(opened, scene.dom_id), "the link did not show the scene"

    opened.click(f"#{scene.dom_id} button[data-reset]")
    reset = read_state(opened, scene)
    assert reset.stops == scene.defaults and scene_problems(scene, reset) == []
    assert _wait_for_hash(opened, f"#{scene.dom_id}") == f"#{scene.dom_id}"
    errors = page_errors[seen:] + opened_errors
    assert not errors, errors


def _stop_of(scene, param: str, value: str) -> int:
    axis = scene.axis(param)
    return next(k for k in range(axis.count) if Decimal(str(axis.stop(k))) == Decimal(value))


def test_a_written_link_opens_the_collision_as_asked(fresh):
    """The link a person would write, "#collision:m1=2,e=0.5", sets m1 = 2 kg and e = 0.5 and
    leaves the other controls at their defaults."""
    scene = next(s for s in SCENES if s.id == "collision")
    page, errors = fresh(scene.page.output_name)
    page.goto(page.url + "#collision:m1=2,e=0.5")  # a change of fragment only: the page applies it
    want = list(scene.defaults)
    want[scene.params.index("m1")] = _stop_of(scene, "m1", "2")
    want[scene.params.index("e")] = _stop_of(scene, "e", "0.5")
    state = read_state(page, scene)
    assert state.stops == tuple(want) and scene_problems(scene, state) == []
    assert _in_view(page, scene.dom_id)
    assert not errors


@pytest.mark.parametrize(
    "fragment",
    [
        "collision:m1=abc,e=7,v1i=,zz=1,v2i=%E0%A4",  # not a number, off the grid, empty, unknown, malformed
        "collision:m1=1.05,e=-0,m2=0x10",  # between stops, a sign, hexadecimal
        "kinetic:sampling=nonsense,species=,N=1e9",  # no such option, empty, out of range
        "nosuchscene:m1=2",
    ],
    ids=["collision-garbage", "collision-near", "kinetic-garbage", "no-scene"],
)
def test_bad_values_in_a_link_fall_back_to_the_defaults(fresh, built_site, fragment):
    """Each name that is no control and each value that is no stop of its control is ignored: the
    control keeps its default (e = −0 is the stop 0), with no error."""
    name = fragment.split(":")[0]
    scenes = [s for s in SCENES if s.id == name] or [s for s in SCENES if s.id == "collision"]
    scene = scenes[0]
    page, errors = fresh((built_site / scene.page.output_name).as_uri() + "#" + fragment)
    state = read_state(page, scene)
    want = list(scene.defaults)
    if fragment.startswith("collision:m1=1.05"):
        want[scene.params.index("e")] = _stop_of(scene, "e", "0")
    assert state.stops == tuple(want), fragment
    assert scene_problems(scene, state) == [] and not errors, errors


def test_back_still_leaves_the_page(fresh, built_site):
    """Moving a control replaces the address rather than adding to the history: Back goes to the page
    the reader came from."""
    scene = next(s for s in SCENES if s.id == "collision")
    page, errors = fresh("index.html")
    with page.expect_navigation():
        page.locator(f'article nav[aria-label="Contents"] a[href="{scene.page.output_name}"]').click()
    move(page, scene, {"m1": 0})
    _wait_for_hash(page, "#collision:")
    move(page, scene, {"m2": 0})
    page.wait_for_function("() => location.hash.includes('m2=')")
    page.go_back(wait_until="load")
    assert page.url == (built_site / "index.html").as_uri()
    assert not errors


# --- navigation --------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ORDER)
def test_every_page_links_to_its_neighbours_and_the_whole_book(shared, name):
    """Previous and next follow the contents; the contents link every page, the current one marked;
    every section heading links to itself (in the page as built: read without its script)."""
    page, errors = shared(name, javascript=False, width=390)
    at = ORDER.index(name)
    pager = page.evaluate("""() => Object.fromEntries([...document.querySelectorAll('nav.pager a')]
        .map(a => [a.getAttribute('rel'), a.getAttribute('href')]))""")
    assert pager.get("prev") == (ORDER[at - 1] if at else None)
    assert pager.get("next") == (ORDER[at + 1] if at + 1 < len(ORDER) else None)
    links = page.evaluate("""() => [...document.querySelectorAll('#book-contents a')].map(a =>
        [a.getAttribute('href'), a.getAttribute('aria-current')])""")
    assert [h for h, _ in links if "#" not in h] == ORDER
    assert [h for h, current in links if current == "page"] == [name]
    headings = page.evaluate("""() => [...document.querySelectorAll('article h2[id], article h3[id]')].map(h =>
        [h.id, (h.querySelector('a.anchor') || {}).getAttribute?.('href') ?? null])""")
    assert headings and all(href == f"#{anchor}" for anchor, href in headings), headings
    sections = {h for h, _ in links if h.startswith("#")}
    prose = page.evaluate(
        "() => [...document.querySelectorAll('article h2[id], article "
        "h3[id]')].filter(h => !h.closest('nav')).map(h => h.id)"
    )
    assert sections == {f"#{anchor}" for anchor in prose}, "the current page's sections in the contents"


@pytest.mark.parametrize("javascript", [True, False], ids=["script", "no-script"])
def test_contents_behind_a_button_on_a_phone(fresh, javascript):
    """At 390 px the contents are hidden until the Contents button opens them (with or without the
    script: a popover); at 1280 px they stand beside the text and the button is gone."""
    page, errors = fresh("newtons-laws.html", javascript=javascript, width=390)
    nav = page.locator("#book-contents")
    assert not nav.is_visible()
    page.click("button.contents-button")
    assert nav.is_visible()
    target = nav.locator('a[href^="#"]').nth(1)
    anchor = target.get_attribute("href")
    target.click()
    assert page.evaluate("location.hash") == anchor
    if javascript:  # the script closes the panel once a link is chosen
        assert not nav.is_visible()
    wide, _ = fresh("newtons-laws.html", javascript=javascript, width=1280)
    assert wide.locator("#book-contents").is_visible() and not wide.locator("button.contents-button").is_visible()
    assert not errors


# --- search --------------------------------------------------------------------------------------------


def _search(page, words: str) -> list[str]:
    page.click("#search-box")
    page.keyboard.type(words)
    page.wait_for_selector("#search-results:not([hidden]) li")
    return page.eval_on_selector_all("#search-results a", "els => els.map(a => a.getAttribute('href'))")


@pytest.mark.parametrize("width", [390, 1280])
@pytest.mark.parametrize("transport", ["file", "http"])
def test_search_finds_restitution_and_jumps_to_its_section(fresh, built_site, transport, width):
    """Typed into the box of the home page, "restitution" lists the collisions section of Newton's laws;
    Enter opens it there. The index is fetched as a classic script, which works from disk."""
    with SiteServer(built_site) as server:
        page, errors = fresh(server.url("index.html") if transport == "http" else "index.html", width=width)
        found = _search(page, "restitution")
        assert "newtons-laws.html#collisions-momentum-and-the-energy-ledger" in found, found
        with page.expect_navigation():
            page.keyboard.press("Enter")
        assert page.url.endswith(found[0])
        assert _in_view(page, found[0].split("#")[1])
        assert not errors


def test_search_index_covers_prose_and_captions(built_site):
    """Every page and every section heading of its prose is in the index (not the home page's list of
    chapters, which is navigation), and each scene's caption is searchable on its page."""
    script = (built_site / "assets" / "search.js").read_text()
    index = json.loads(re.match(r"window\.sitegenSearchIndex = (\{.*?\});\n", script, re.S)[1])
    assert [p[0] for p in index["pages"]] == ORDER
    for page in PAGES:
        html = (built_site / page.output_name).read_text()
        number = ORDER.index(page.output_name)
        ids = {s[1] for s in index["sections"] if s[0] == number}
        prose = re.sub(r"<nav\b.*?</nav>", "", html, flags=re.S)
        assert set(re.findall(r'<h[23] id="([^"]+)"', prose)) | {""} == ids, page.slug
        text = " ".join(s[3] for s in index["sections"] if s[0] == number)
        for caption in re.findall(r"<figure class=\"scene\".*?<figcaption>(.*?)</figcaption>", html, re.S):
            caption = re.sub(r'<span class="caption-label">.*?</span>', "", caption)  # "Figure 2", not the words
            words = re.sub(r"<math\b.*?</math>|<[^>]+>", " ", caption).split()[:4]
            assert " ".join(words) in " ".join(text.split()), (page.slug, words)


def test_search_says_when_nothing_is_found(fresh):
    page, errors = fresh("newtons-laws.html", width=390)
    page.click("#search-box")
    page.keyboard.type("zyzzyva")
    page.wait_for_selector("#search-results li.none")
    assert "zyzzyva" in page.text_content("#search-results") and page.text_content("#search-status") == "nothing found"
    page.keyboard.press("Escape")
    assert page.is_hidden("#search-results") and not errors


def test_escape_from_a_result_closes_the_list_for_good(fresh):
    """Escape in a result closes the list and puts the focus back in the box, which does not open it again;
    typing in the box opens it again."""
    page, errors = fresh("index.html", width=390)
    _search(page, "restitution")
    page.keyboard.press("ArrowDown")
    assert page.evaluate("document.activeElement.closest('#search-results') !== null")
    page.keyboard.press("Escape")
    assert page.evaluate("document.activeElement.id") == "search-box"
    assert page.is_hidden("#search-results")
    page.keyboard.type(" ")
    page.wait_for_selector("#search-results:not([hidden]) li")
    assert not errors


def test_a_result_on_the_page_moves_there_and_keeps_the_scenes(fresh):
    """On Newton's laws, a result on the page itself links to its place ("#section", the page's own to the
    start of its text), never to "" (which would load the page again and lose the scenes' state)."""
    scene = next(s for s in SCENES if s.id == "collision")
    page, errors = fresh(scene.page.output_name)
    moved = move(page, scene, _elsewhere(scene))
    found = _search(page, "newton")
    here = [href for href in found if not href.split("#")[0]]
    assert "#main-content" in here and len(here) > 1, found
    assert all(href.startswith("#") and len(href) > 1 for href in here), found
    assert all(re.fullmatch(r"[a-z-]+\.html(#[\w-]+)?", href) for href in found if href not in here), found
    page.evaluate("window.sameDocument = true")
    page.click(f'#search-results a[href="{here[-1]}"]')
    page.wait_for_function("h => location.hash === h", arg=here[-1])
    assert page.evaluate("window.sameDocument === true"), "the page was loaded again"
    assert read_state(page, scene).stops == moved.stops and page.is_hidden("#search-results")
    assert _in_view(page, here[-1][1:])
    assert not errors


def test_a_link_followed_while_a_scene_settles_keeps_its_address(fresh):
    """A scene writes its state into the address once its controls rest; a link the reader follows before
    that (a search result, a heading) is the newer address and stays."""
    scene = next(s for s in SCENES if s.id == "collision")
    page, errors = fresh(scene.page.output_name)
    move(page, scene, _elsewhere(scene))  # its state is written to the address 300 ms after it rests
    page.evaluate("location.hash = '#main-content'")
    page.wait_for_timeout(600)
    assert page.evaluate("location.hash") == "#main-content"
    assert not errors


# --- without JavaScript ---------------------------------------------------------------------------------


@pytest.mark.parametrize("name", [p.output_name for p in PAGES])
def test_without_javascript_controls_are_hidden_and_a_line_says_why(shared, name):
    """No slider, radio button, play or reset button or search box shows; a page with scenes says that
    its figures show their defaults (the readouts and values are there, as tests elsewhere check)."""
    page, errors = shared(name, javascript=False, width=390)
    shown = page.evaluate("""() => [...document.querySelectorAll('input, button:not(.contents-button)')]
        .filter(e => e.getBoundingClientRect().width > 0).map(e => e.outerHTML.slice(0, 60))""")
    assert shown == []
    note = page.locator(".noscript-note")
    has_scenes = any(s.page.output_name == name for s in SCENES)
    assert note.count() == (1 if has_scenes else 0)
    if has_scenes:
        assert note.is_visible() and "default" in note.inner_text()
    assert not errors
