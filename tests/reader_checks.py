"""The reader's checks, run in each of the three engines (tests/engines.py) by a test module of its own:
test_chromium_reader.py, test_firefox_reader.py and test_webkit_reader.py each name their engine (ENGINE) and
import these tests, so that pytest-xdist can give each engine to a process of its own.

On the tiny book (tests/book) and the project's own book, as the engine draws them:
- every page loads from disk and over http://127.0.0.1 with no error or warning logged, every readout
  showing a value;
- every scene's controls move it, and its controls, readouts and figure layers are the model's and the
  same as in Chromium, stop for stop;
- a link to a state opens it, the scene writes its state back into the address, Reset brings back the
  defaults; an animated scene plays and pauses;
- search finds a section, keeps its list closed after Escape, and opens the section chosen; on a chapter
  its own results link to their places;
- each scene's figure, at 390 and 1280 px, is drawn with as much of each of its layers' colours as in
  Chromium (a layer painted over the plot, as WebKit once painted dots, shows as far too much of it);
  the pictures are kept in the run's temporary folder, `engines/<engine>/`, for a person to look at;
- at 390, 320 and 1280 px the page fits: no sideways scrolling, a wide box shows that it scrolls, each
  equation number at the right margin beside its formula, a fraction in a sentence set at a script's size.

One browser per module, one tab; a page stays loaded from one test to the next when they read the same
document (each test puts its scene back on its defaults), and the tests are ordered so that the viewport
changes its width rarely (a resize of a long page costs WebKit a second or two). Chromium's states and
colours, the reference, come from a tab of their own. Each test records its engine's version as its driver
tells it (a property of the test in a JUnit XML report); conftest.py ends a run that drove a browser with a
line naming each engine and its version.
"""

from __future__ import annotations

import random
from pathlib import Path
from urllib.parse import quote

import numpy as np
import pytest
from browser import (
    BROKEN_TEXT,
    SiteServer,
    book,
    control_value,
    layer_problems,
    move,
    move_many,
    read_state,
    reset,
    scene_problems,
    spread,
)
from engines import Chromium, Firefox, WebKit, instrumented
from layout import EQUATION_NUMBERS_JS, FRACTION_SIZES_JS, OVERFLOW_JS

from sitegen.compute.grid import CHOICE

# What each engine's module takes (its fixtures, and the tests in the order they run: see above).
__all__ = [
    "engine",
    "reference",
    "sites",
    "url",
    "_engine_version",
    "test_page_loads_cleanly",
    "test_scene_moves_as_in_chromium",
    "test_a_link_opens_a_state_and_reset_leaves_it",
    "test_an_animation_plays_and_pauses",
    "test_search_finds_a_section_and_opens_it",
    "test_search_on_a_page_links_to_its_places",
    "test_figure_draws_its_layers_as_chromium_does",
    "test_page_fits",
]

ROOT = Path(__file__).resolve().parents[1]
BOOKS = {"tiny": book(ROOT / "tests" / "book"), "book": book(ROOT)}
SITES = {"tiny": "tiny_site", "book": "built_site"}  # the fixture that builds each
WIDE, HEIGHT = 1280, 1000


def _pages(transports=("file", "http"), widths=(WIDE,)):
    return [
        pytest.param(name, page.output_name, transport, width, id=f"{name}-{page.slug}-{transport}-{width}")
        for width in widths
        for name, (pages, _) in BOOKS.items()
        for page in pages
        for transport in transports
    ]


def _scenes(only=lambda scene: True, widths=(WIDE,)):
    return [
        pytest.param(name, scene, width, id=f"{name}-{scene.key}-{width}")
        for width in widths
        for name, (_, scenes) in BOOKS.items()
        for scene in scenes
        if only(scene)
    ]


# --- the engine, the sites it reads, and Chromium's reference ---------------------------------------


@pytest.fixture(scope="module")
def engine(request, chromium, tmp_path_factory):
    """The module's engine (its ENGINE), with one tab."""
    name = request.module.ENGINE
    if name == "chromium":
        made = Chromium(chromium)
    elif name == "firefox":
        made = Firefox()
    else:
        made = WebKit(tmp_path_factory.mktemp("webkit-config"))
    yield made
    made.close()


@pytest.fixture(autouse=True)
def _engine_version(request, record_property):
    """Every test carries its engine's version, as its driver tells it (a JUnit XML report shows it)."""
    record_property("browser", request.getfixturevalue("engine").version)


@pytest.fixture(scope="module")
def reference(chromium):
    """Chromium, in a tab of its own: the states and colours every engine is compared with."""
    made = Chromium(chromium)
    yield made
    made.close()


@pytest.fixture(scope="module")
def sites(request, tmp_path_factory):
    """sites(engine, book) -> (folder, server): the built book as that engine reads it (WebKit: a copy whose
    pages log their errors, see engines.instrumented), served on 127.0.0.1."""
    made, servers = {}, []

    def _get(engine, name: str):
        key = (engine.name == "webkit", name)
        if key not in made:
            folder = request.getfixturevalue(SITES[name])
            if engine.name == "webkit":
                folder = instrumented(folder, tmp_path_factory.mktemp(f"webkit-{name}") / "site")
            server = SiteServer(folder).__enter__()
            servers.append(server)
            made[key] = folder, server
        return made[key]

    yield _get
    for server in servers:
        server.__exit__(None, None, None)


@pytest.fixture(scope="module")
def url(sites):
    """url(engine, book, page name, transport="file", fragment="") -> the page's address for that engine."""

    def _url(engine, name: str, page: str, transport: str = "file", fragment: str = "") -> str:
        folder, server = sites(engine, name)
        return ((folder / page).as_uri() if transport == "file" else server.url(page)) + fragment

    return _url


def show(engine, address: str, width: int = WIDE) -> None:
    """The page at `address` in the engine's tab, `width` px wide: loaded unless it is the document shown."""
    engine.resize(width, HEIGHT)
    if engine.shown != address:
        engine.load(address)
        engine.shown = address


def open_anew(engine, address: str) -> None:
    """The page at `address` loaded as a new document (even if it is shown), at the wide width."""
    engine.shown = None
    show(engine, address)
    engine.shown = None  # the test moves on from it: navigates, or leaves a state behind


def settle(engine) -> None:
    """Two animation frames: layout and the script's resize handler done."""
    engine.run("return new Promise(done => requestAnimationFrame(() => requestAnimationFrame(() => done(true))));")


IN_VIEW_JS = (
    "const r = document.getElementById(arg).getBoundingClientRect(); return r.top >= -2 && r.top < innerHeight;"
)


def click(engine, selector: str) -> None:
    engine.run("document.querySelector(arg).click(); return true;", selector)


# --- pages ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("name,page,transport,width", _pages())
def test_page_loads_cleanly(engine, url, name, page, transport, width):
    """Loaded from disk or over http, the page logs no error or warning, and every readout shows a value."""
    engine.errors()
    show(engine, url(engine, name, page, transport), width)
    texts = engine.run("return [...document.querySelectorAll('[data-out]')].map(el => el.textContent);")
    assert all(text.strip() and not BROKEN_TEXT.search(text) for text in texts), texts
    assert (errors := engine.errors()) == [], errors


# --- scenes ---------------------------------------------------------------------------------------


def _positions(scene) -> list[dict[str, int]]:
    """Each control through its spread of stops (the others on their defaults), then random states."""
    defaults = dict(zip(scene.params, scene.defaults))
    positions = [{**defaults, a.param: k} for a in scene.axes for k in spread(a.count, 5)]
    rng = random.Random(scene.key)
    positions += [{a.param: rng.randrange(a.count) for a in scene.axes} for _ in range(12)]
    return positions


def _states(engine, address: str, scene, positions):
    show(engine, address)
    reset(engine, scene)
    states = move_many(engine, scene, positions)
    reset(engine, scene)
    return states


@pytest.mark.parametrize("name,scene,width", _scenes())
def test_scene_moves_as_in_chromium(engine, reference, url, name, scene, width):
    """Through each control's stops and random states: controls, readouts and layers are the model's and
    the same text as Chromium's."""
    positions = _positions(scene)
    expected = _states(reference, url(reference, name, scene.page.output_name), scene, positions)
    engine.errors()
    states = _states(engine, url(engine, name, scene.page.output_name), scene, positions)
    for state, want, stops in zip(states, expected, positions):
        problems = scene_problems(scene, state) + layer_problems(state)
        assert not problems, "\n".join(problems[:10])
        assert state.readouts == want.readouts, stops
        assert state.layers == want.layers, stops
        assert [c.valuetext for c in state.controls] == [c.valuetext for c in want.controls], stops
    assert (errors := engine.errors()) == [], errors


def _link(scene) -> tuple[str, dict[str, int]]:
    """A link to a state away from the defaults on every control with more than one stop, as the page writes it."""
    stops = {a.param: (d + max(1, a.count // 3)) % a.count for a, d in zip(scene.axes, scene.defaults) if a.count > 1}
    pairs = []
    for param, k in stops.items():
        axis = scene.axis(param)
        value = axis.labels[k] if axis.kind == CHOICE else repr(round(float(axis.stop(k)), 6))
        pairs.append(f"{param}={quote(value)}")
    return f"#{scene.id}:{','.join(pairs)}", stops


@pytest.mark.parametrize("name,scene,width", _scenes(lambda scene: any(a.count > 1 for a in scene.axes)))
def test_a_link_opens_a_state_and_reset_leaves_it(engine, url, name, scene, width):
    """A link "#scene:param=value,..." opened as a new document sets those stops and shows the scene; moving a
    control writes the state into the address; Reset brings back the defaults and the scene's plain link."""
    fragment, stops = _link(scene)
    engine.errors()
    open_anew(engine, url(engine, name, scene.page.output_name, fragment=fragment))
    state = read_state(engine, scene)
    want = tuple(stops.get(p, d) for p, d in zip(scene.params, scene.defaults))
    assert state.stops == want and scene_problems(scene, state) == []
    engine.wait_for(IN_VIEW_JS, scene.dom_id)  # the link shows the scene
    where, axis = next((i, a) for i, a in enumerate(scene.axes) if a.count > 1)
    move(engine, scene, {axis.param: (want[where] + 1) % axis.count})
    engine.wait_for("return location.hash !== arg[0] && location.hash.startsWith(arg[1]);", [fragment, f"#{scene.id}:"])
    click(engine, f"#{scene.dom_id} button[data-reset]")
    state = read_state(engine, scene)
    assert state.stops == scene.defaults and scene_problems(scene, state) == []
    engine.wait_for("return location.hash === '#' + arg;", scene.dom_id)
    assert (errors := engine.errors()) == [], errors


@pytest.mark.parametrize("name,scene,width", _scenes(lambda scene: scene.animate))
def test_an_animation_plays_and_pauses(engine, url, name, scene, width):
    """Play moves the animated control stop by stop (the readouts the model's at each), Pause stops it,
    Reset brings back the defaults."""
    show(engine, url(engine, name, scene.page.output_name))
    engine.errors()
    reset(engine, scene)
    button = f"#{scene.dom_id} button[data-animate]"
    engine.run("document.getElementById(arg).scrollIntoView({block: 'center'}); return true;", scene.dom_id)
    click(engine, button)
    start = control_value(scene.axis(scene.animate), scene.defaults[scene.params.index(scene.animate)])
    control = f"#{scene.dom_id} [data-param='{scene.animate}']"
    engine.wait_for("return document.querySelector(arg[0]).value !== arg[1];", [control, start])
    playing = read_state(engine, scene)
    assert playing.button["pressed"] == "true" and playing.button["text"] == "Pause", playing.button
    assert scene_problems(scene, playing) == []
    click(engine, button)
    paused = read_state(engine, scene)
    engine.run("return new Promise(done => setTimeout(() => done(true), 250));")
    assert read_state(engine, scene).stops == paused.stops and paused.button["pressed"] == "false"
    click(engine, f"#{scene.dom_id} button[data-reset]")
    assert read_state(engine, scene).stops == scene.defaults
    assert (errors := engine.errors()) == [], errors


# --- search ---------------------------------------------------------------------------------------


def _search(engine, words: str) -> list[str]:
    """Type `words` into the search box as a reader does; the results' links."""
    engine.click("#search-box")  # a click, as a reader's: a script's focus() is not a focus in a window behind
    engine.type(words)
    engine.wait_for(
        "return !document.getElementById('search-results').hidden"
        " && document.querySelector('#search-results li') !== null;"
    )
    return engine.run("return [...document.querySelectorAll('#search-results a')].map(a => a.getAttribute('href'));")


@pytest.mark.parametrize("transport", ["file", "http"])
def test_search_finds_a_section_and_opens_it(engine, url, transport):
    """Typed into the home page's box, "restitution" lists the section on collisions; Escape in a result
    closes the list and leaves it closed with the focus back in the box; Enter there opens the section."""
    open_anew(engine, url(engine, "book", "index.html", transport))
    engine.errors()
    found = _search(engine, "restitution")
    assert "newtons-laws.html#collisions-momentum-and-the-energy-ledger" in found, found
    engine.press("ArrowDown")
    assert engine.run("return document.activeElement.closest('#search-results') !== null;")
    engine.press("Escape")
    assert engine.run("return document.activeElement.id;") == "search-box"
    engine.run("return new Promise(done => setTimeout(() => done(true), 100));")
    assert engine.run("return document.getElementById('search-results').hidden;")
    page, section = found[0].split("#")
    engine.press("Enter")
    engine.wait_for(  # loaded before anything reads its layout (Firefox warns of a layout forced before its CSS)
        "return location.pathname.endsWith(arg[0]) && location.hash === '#' + arg[1]"
        " && document.readyState === 'complete';",
        [page, section],
    )
    engine.wait_for(IN_VIEW_JS, section)
    assert (errors := engine.errors()) == [], errors


def test_search_on_a_page_links_to_its_places(engine, url):
    """On a chapter, the results on the chapter itself link to their anchors, never to "" (a reload)."""
    open_anew(engine, url(engine, "book", "newtons-laws.html"))
    engine.errors()
    found = _search(engine, "newton")
    here = [href for href in found if not href.split("#")[0]]
    assert "#main-content" in here and all(len(href) > 1 for href in here), found
    assert (errors := engine.errors()) == [], errors


# --- figures as drawn -----------------------------------------------------------------------------

# The figure a scene shows, scrolled into view, where it is, and the colours its layers are drawn in (white, the
# holes of some dots, left out); a mark of MARK's colour placed just outside its top left corner, in the scene's
# padding, moving with the page: the screenshot is cut where the mark is drawn, once it is drawn.
MARK = (255, 0, 255)
FIGURE_JS = """
const scene = document.getElementById(arg);
const svg = [...scene.querySelectorAll('svg.scene-svg')].find(s => s.getBoundingClientRect().width > 0);
svg.scrollIntoView({block: 'center'});
const colours = new Set();
for (const el of svg.querySelectorAll('[data-layer]')) {
  for (const attr of ['stroke', 'fill']) {
    const c = el.getAttribute(attr);
    if (c && /^#[0-9a-f]{6}$/i.test(c) && !/^#ffffff$/i.test(c)) colours.add(c.toLowerCase());
  }
}
const r = svg.getBoundingClientRect(), s = scene.getBoundingClientRect();
const mark = document.getElementById('test-mark') || document.createElement('div');
mark.id = 'test-mark';
mark.style.cssText = `position: absolute; width: 3px; height: 3px; background: rgb(255, 0, 255); z-index: 9;
  left: ${r.left - s.left - 5}px; top: ${r.top - s.top - 5}px`;
scene.style.position = 'relative';
scene.appendChild(mark);
return {colours: [...colours].sort(), variant: svg.classList.contains('narrow') ? 'narrow' : 'wide',
        box: [r.left, r.top, r.width, r.height]};
"""
UNMARK_JS = "const m = document.getElementById('test-mark'); m.parentNode.style.position = ''; m.remove(); return true;"
_COLOURS: dict = {}  # (book, scene, width) -> Chromium's figure


def _figure(engine, scene, folder: Path):
    """The scene's shown figure as drawn: its variant and, for each colour its layers are drawn in, the share
    of the figure's pixels of that colour (the picture saved in `folder`)."""
    figure = engine.run(FIGURE_JS, scene.dom_id)
    try:
        shot, (top, left) = engine.screenshot_showing(MARK)
    finally:
        engine.run(UNMARK_JS)
    top, left = top + 5, left + 5
    width, height = figure["box"][2:]
    picture = shot.crop((left, top, left + round(width), top + round(height)))
    folder.mkdir(parents=True, exist_ok=True)
    picture.save(folder / f"{scene.key}-{figure['variant']}.png")
    pixels = np.asarray(picture, dtype=float)
    shares = {}
    for colour in figure["colours"]:
        rgb = np.array([int(colour[i : i + 2], 16) for i in (1, 3, 5)], dtype=float)
        shares[colour] = float(np.mean(np.linalg.norm(pixels - rgb, axis=2) < 40))
    return figure["variant"], shares


@pytest.mark.parametrize("name,scene,width", _scenes(widths=(WIDE, 390)))
def test_figure_draws_its_layers_as_chromium_does(engine, reference, url, tmp_path_factory, name, scene, width):
    """At its defaults, the figure shows each of its layers' colours on about as many pixels as in Chromium,
    and on no more than half of the figure: a layer painted over the plot (WebKit's dots once) fails."""
    shots = tmp_path_factory.getbasetemp() / "engines"
    key = (name, scene.key, width)
    if key not in _COLOURS:
        show(reference, url(reference, name, scene.page.output_name), width)
        reset(reference, scene)
        _COLOURS[key] = _figure(reference, scene, shots / "chromium")
    show(engine, url(engine, name, scene.page.output_name), width)
    reset(engine, scene)
    variant, shares = _figure(engine, scene, shots / engine.name)
    want_variant, want = _COLOURS[key]
    assert variant == want_variant and shares.keys() == want.keys()
    where = f"(pictures in {shots})"
    for colour, share in shares.items():
        assert share < 0.5, f"{colour} covers {share:.0%} of the figure {where}"
        assert abs(share - want[colour]) <= _slack(colour, want[colour]), (
            f"{colour}: {share:.2%} of the figure, {want[colour]:.2%} in Chromium {where}"
        )


def _slack(colour: str, share: float) -> float:
    """How far an engine's share of a colour may be from Chromium's: a grey or near-black is also the colour
    of the axes, grid and text, whose edges each engine smooths its own way (and Firefox's scroll bar makes its
    figure a little smaller); a colour proper is the layers' own."""
    rgb = [int(colour[i : i + 2], 16) for i in (1, 3, 5)]
    return 0.5 * share + 0.01 if max(rgb) - min(rgb) < 40 else 0.3 * share + 0.002


# --- the page at a phone's width and a desktop's ------------------------------------------------------


@pytest.mark.parametrize("name,page,transport,width", _pages(("file",), widths=(390, 320, WIDE)))
def test_page_fits(engine, url, name, page, transport, width):
    """At 390, 320 and 1280 px the page does not scroll sideways, a box wider than its content shows it
    scrolls, every equation number sits at the right margin beside its formula, and a fraction's parts are at
    its style's size (in a sentence, a script's: WebKit's, without math-depth, once kept the formula's)."""
    show(engine, url(engine, name, page), width)
    settle(engine)
    problems = engine.run(OVERFLOW_JS) + engine.run(EQUATION_NUMBERS_JS) + engine.run(FRACTION_SIZES_JS)
    assert not problems, "\n".join(problems[:15])
