"""The built site in a real browser (Debian's headless Chromium through Playwright).

Pages, scenes and sliders are parametrized from the book's sources (content/*.md) so that test
ids are precise ("collision-m1-http"); `test_built_site_matches_sources` checks that the built
DOM has exactly those pages, scenes, sliders and readouts, so the parametrization cannot drift
away from what was built. Expected readouts come from the physics models (see tests/browser.py),
never from the tables the page carries.

Only evenly spaced range sliders (`slider NAME: MIN..MAX step STEP`) are moved; listed sliders
and choices would be held at their defaults (the book has none yet).
"""
from __future__ import annotations

import math
import random
import re
from dataclasses import dataclass, field
from decimal import Decimal
from pathlib import Path
from urllib.parse import unquote, urljoin, urlparse

import pytest
from playwright.sync_api import sync_playwright

from browser import (
    SiteServer,
    expected_readouts,
    expected_slider_text,
    launch,
    layer_points,
    plain,
    readouts,
    scene_sliders,
    scene_state,
    set_slider,
    set_sliders,
    source_pages,
)
from sitegen.physics import MODELS

PAGES = source_pages()
PAGE_NAMES = [p.output_name for p in PAGES]
TRANSPORTS = ("file", "http")
SCENES = [(page, spec) for page in PAGES for spec in page.found.scenes]


def is_range_slider(control) -> bool:
    """A `slider NAME: MIN..MAX step STEP` line (not a listed slider or a choice)."""
    return hasattr(control, "step") and not getattr(control, "listed", ())


def _scene_id(page, spec) -> str:
    """'collision', or 'newtons-laws-collision' if another page has a scene with the same id."""
    clash = sum(s.id == spec.id for _, s in SCENES) > 1
    return f"{page.slug}-{spec.id}" if clash else spec.id


# Evenly spaced range sliders only: the DOM contract these tests know. Listed sliders and choices
# (none in the book yet) are checked to exist and are held at their defaults, not exercised.
SLIDERS = [(page, spec, c.param) for page, spec in SCENES for c in spec.sliders if is_range_slider(c)]


def _page_params():
    return [pytest.param(p.output_name, t, id=f"{p.slug}-{t}") for p in PAGES for t in TRANSPORTS]


def _scene_params(transports=TRANSPORTS):
    # (scenes with no range slider have nothing to move here)
    return [
        pytest.param(page, spec, t, id=f"{_scene_id(page, spec)}-{t}")
        for page, spec in SCENES
        for t in transports
        if any(is_range_slider(c) for c in spec.sliders)
    ]


def _slider_params(transports=TRANSPORTS):
    return [
        pytest.param(page, spec, param, t, id=f"{_scene_id(page, spec)}-{param}" + (f"-{t}" if len(transports) > 1 else ""))
        for page, spec, param in SLIDERS
        for t in transports
    ]


def readout_names(spec) -> list[str]:
    """The outputs a scene shows: its `readouts:` line, or every output of its model."""
    return list(spec.readouts) if spec.readouts else [o.name for o in MODELS[spec.model].outputs]


def range_params(spec) -> list[str]:
    return [c.param for c in spec.sliders if is_range_slider(c)]


def fixed_values(spec) -> dict[str, Decimal]:
    """Parameter values that these tests never move: the scene's `fix` lines (none in the book
    today) and the defaults of its other controls (listed sliders, choices: none today either)."""
    values = {f.param: f.value for f in spec.fixed}
    model = MODELS[spec.model]
    for control in spec.sliders:
        if is_range_slider(control):
            continue
        if hasattr(control, "options"):  # a choice: the model's code of the default option
            values[control.param] = Decimal(model.param(control.param).choices.index(control.default))
        else:
            values[control.param] = control.default
    return values


# --- fixtures -----------------------------------------------------------------------------------


@pytest.fixture(scope="session")
def chromium():
    with sync_playwright() as playwright:
        browser = launch(playwright)
        yield browser
        browser.close()


@pytest.fixture(scope="session")
def site_server(built_site):
    with SiteServer(built_site) as server:
        yield server


@pytest.fixture
def site_url(built_site, request):
    def url(name: str, transport: str) -> str:
        if transport == "file":
            return (built_site / name).as_uri()
        return request.getfixturevalue("site_server").url(name)

    return url


@dataclass
class PageLog:
    """What happened while a page was open."""

    requests: list[str] = field(default_factory=list)
    failed: list[str] = field(default_factory=list)
    responses: list[tuple[str, int]] = field(default_factory=list)
    console: list[tuple[str, str, dict]] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)


@pytest.fixture
def open_page(chromium, site_url):
    """open_page(name, transport, javascript=True) -> (page, log), loaded, fonts settled."""
    contexts = []

    def _open(name: str, transport: str, javascript: bool = True):
        context = chromium.new_context(java_script_enabled=javascript)
        contexts.append(context)
        log = PageLog()
        context.on("request", lambda r: log.requests.append(r.url))
        context.on("requestfailed", lambda r: log.failed.append(f"{r.url}: {r.failure}"))
        context.on("response", lambda r: log.responses.append((r.url, r.status)))
        page = context.new_page()
        page.on("console", lambda m: log.console.append((m.type, m.text, m.location)))
        page.on("pageerror", lambda e: log.errors.append(str(e)))
        page.goto(site_url(name, transport), wait_until="load")
        page.evaluate("document.fonts.ready.then(() => true)")
        return page, log

    yield _open
    for context in contexts:
        context.close()


# --- checking a scene against the model ----------------------------------------------------------


def scene_problems(page, spec) -> list[str]:
    """Every way the scene's readouts or slider texts differ from the model's values."""
    sliders, got = scene_state(page, spec.id)
    sliders = [s for s in sliders if s.param in range_params(spec)]
    values = {s.param: s.exact for s in sliders}
    problems = []
    if sorted(got) != sorted(readout_names(spec)):
        problems.append(f"readouts {sorted(got)} != declared {sorted(readout_names(spec))}")
    want = expected_readouts(spec.model, values, names=[n for n in got if n in readout_names(spec)], fixed=fixed_values(spec))
    for name, text in want.items():
        if got[name] != text:
            problems.append(f"readout {name}: page {got[name]!r}, model {text!r}")
    for s in sliders:
        if not s.on_grid():
            problems.append(f"slider {s.param}: value {s.value!r} is not a stop")
        text = expected_slider_text(spec.model, s)
        if s.valuetext != text:
            problems.append(f"slider {s.param}: aria-valuetext {s.valuetext!r}, expected {text!r}")
        if s.shown is not None and s.shown != text:
            problems.append(f"slider {s.param}: shown value {s.shown!r}, expected {text!r}")
    if problems:
        state = ", ".join(f"{p}={plain(v)}" for p, v in values.items())
        problems = [f"[{state}] {p}" for p in problems]
    return problems


def range_sliders(page, spec):
    return [s for s in scene_sliders(page, spec.id) if s.param in range_params(spec)]


def slider_of(page, spec, param):
    return next(s for s in scene_sliders(page, spec.id) if s.param == param)


def default_index(spec, slider) -> int:
    source = next(s for s in spec.sliders if s.param == slider.param)
    return slider.index_of(source.default)


# --- the site as built ---------------------------------------------------------------------------


@pytest.mark.parametrize("name", PAGE_NAMES, ids=[p.slug for p in PAGES])
def test_built_site_matches_sources(built_site, open_page, name):
    """The built page has exactly the scenes, sliders and readouts its source declares."""
    assert sorted(p.name for p in built_site.glob("*.html")) == sorted(PAGE_NAMES)
    page, _ = open_page(name, "file")
    source = next(p for p in PAGES if p.output_name == name)
    scenes = page.eval_on_selector_all("figure.scene", "els => els.map(e => [e.id, e.dataset.scene])")
    assert scenes == [[f"scene-{s.id}", s.model] for s in source.found.scenes]
    for spec in source.found.scenes:
        # Listed sliders and choices are only checked to exist; the tests hold them at their defaults.
        for control in spec.sliders:
            assert page.locator(f'#scene-{spec.id} [data-param="{control.param}"]').count() == 1, control.param
        sliders = range_sliders(page, spec)
        declared_sliders = [c for c in spec.sliders if is_range_slider(c)]
        assert [s.param for s in sliders] == [c.param for c in declared_sliders]
        for slider, declared in zip(sliders, declared_sliders):
            assert (slider.lo, slider.hi, slider.step) == (declared.lo, declared.hi, declared.step)
            assert slider.exact == declared.default and slider.on_grid()
            assert slider.label and slider.label.strip(), f"slider {slider.param} has no <label for>"
        assert list(readouts(page, spec.id)) == readout_names(spec)
        assert page.locator(f"#scene-{spec.id} script.scene-data[type='application/json']").count() == 1


# --- a) loading ------------------------------------------------------------------------------------


def _inside_site(url: str, transport: str, built_site: Path, origin: str | None) -> bool:
    if url.startswith("data:"):
        return True  # inline data never leaves the page
    parts = urlparse(url)
    if transport == "file":
        return parts.scheme == "file" and Path(unquote(parts.path)).resolve().is_relative_to(built_site.resolve())
    return f"{parts.scheme}://{parts.netloc}" == origin


@pytest.mark.parametrize("name,transport", _page_params())
def test_page_loads_cleanly(built_site, open_page, site_server, name, transport):
    page, log = open_page(name, transport)
    page.wait_for_load_state("networkidle")
    # Over http Chromium probes /favicon.ico on its own (sometimes after "networkidle"); that is
    # the browser, not the page, and is covered deterministically by test_pages_declare_an_icon.
    noisy = [
        (t, text, loc)
        for t, text, loc in log.console
        if t in ("error", "warning") and not loc.get("url", "").endswith("/favicon.ico")
    ]
    assert not noisy, f"console errors/warnings: {noisy}"
    assert not log.errors, f"page errors: {log.errors}"
    assert not log.failed, f"failed requests: {log.failed}"
    origin = site_server.origin if transport == "http" else None
    outside = [u for u in log.requests if not _inside_site(u, transport, built_site, origin)]
    assert not outside, f"requests leaving the site: {outside}"
    bad_status = [(u, s) for u, s in log.responses if transport == "http" and s != 200 and not u.endswith("/favicon.ico")]
    assert not bad_status, bad_status
    assert any(u.endswith("assets/sitegen.js") for u in log.requests)
    assert any(u.endswith("assets/sitegen.css") for u in log.requests)

    source = next(p for p in PAGES if p.output_name == name)
    maths = page.locator("math").count()
    if source.found.maths:
        assert maths >= len(source.found.maths), f"{len(source.found.maths)} formulas in the source, {maths} <math> elements"
        assert any(u.endswith("assets/latinmodern-math.woff2") for u in log.requests), "math font not requested"
        assert page.evaluate("""document.fonts.check('16px "Latin Modern Math"')""")
        # fonts.check() is also true when the family is installed locally (it is, on Debian with
        # texlive fonts), so also require that the page's own web font actually loaded.
        faces = page.evaluate("[...document.fonts].map(f => [f.family.replace(/\"/g, ''), f.status])")
        assert ["Latin Modern Math", "loaded"] in faces, faces
    else:
        assert maths == 0


def test_pages_declare_an_icon(open_page):
    """Every page names its icon (e.g. <link rel="icon" href="data:,">), else browsers request
    /favicon.ico from the server, which the site does not have: a 404 and a console error on
    every page view over http."""
    missing = []
    for name in PAGE_NAMES:
        page, _ = open_page(name, "file", javascript=False)
        if not page.locator('head link[rel~="icon"]').count():
            missing.append(name)
    assert not missing, f"pages without <link rel=icon>: {missing}"


# --- b) without JavaScript ------------------------------------------------------------------------


@pytest.mark.parametrize("name,transport", _page_params())
def test_readouts_without_javascript(open_page, name, transport):
    """The page as built already shows the model's values at the default slider positions."""
    page, log = open_page(name, transport, javascript=False)
    assert not log.errors
    source = next(p for p in PAGES if p.output_name == name)
    assert page.locator("figure.scene").count() == len(source.found.scenes)
    for spec in source.found.scenes:
        sliders = range_sliders(page, spec)
        assert all(s.index == default_index(spec, s) for s in sliders)
        assert scene_problems(page, spec) == []


# --- c) each slider, by keyboard and by value ----------------------------------------------------


def _keyboard_moves(count: int):
    """(key, check(before, after)) pairs: Home, End, ArrowLeft x3, PageDown."""
    moves = [("Home", lambda b, a: a == 0), ("End", lambda b, a: a == count - 1)]
    moves += [("ArrowLeft", lambda b, a: a == max(0, b - 1))] * 3
    moves += [("PageDown", lambda b, a: a < b if b > 0 else a == 0)]
    return moves


@pytest.mark.parametrize("page_source,spec,param,transport", _slider_params(("file",)))
def test_slider_by_keyboard(open_page, page_source, spec, param, transport):
    page, log = open_page(page_source.output_name, transport)
    slider = slider_of(page, spec, param)
    control = page.locator(slider.selector)
    control.focus()
    assert page.evaluate("document.activeElement.id") == slider.dom_id
    for key, moved_right in _keyboard_moves(slider.count):
        before = slider_of(page, spec, param).index
        page.keyboard.press(key)
        after = slider_of(page, spec, param).index
        assert moved_right(before, after), f"{key}: stop {before} -> {after} of {slider.count}"
        assert scene_problems(page, spec) == [], f"after {key}"
    assert not log.errors


@pytest.mark.parametrize("page_source,spec,param,transport", _slider_params())
def test_slider_by_value(open_page, page_source, spec, param, transport):
    page, log = open_page(page_source.output_name, transport)
    slider = slider_of(page, spec, param)
    control = page.locator(slider.selector).element_handle()
    last = slider.count - 1
    stops = [0, last, default_index(spec, slider)] + [i for i in slider.spread(8) if i not in (0, last)]
    for index in stops:
        set_slider(page, control, slider.stop(index))
        assert slider_of(page, spec, param).index == index
        assert scene_problems(page, spec) == [], f"{param} at stop {index}"
    assert not log.errors


@pytest.mark.parametrize("page_source,spec,transport", _scene_params(("file",)))
def test_scene_after_history_navigation(open_page, site_url, page_source, spec, transport):
    """Leave a page with moved sliders and come back: whatever the browser restores (the whole
    page from the back/forward cache, or just the sliders' values into a fresh page, before the
    script runs), the readouts agree with the sliders."""
    page, log = open_page(page_source.output_name, transport)
    sliders = range_sliders(page, spec)
    moved = {s.param: s.stop(0 if default_index(spec, s) else s.count - 1) for s in sliders}
    set_sliders(page, spec.id, moved)
    assert scene_problems(page, spec) == []
    page.goto(site_url("index.html", transport), wait_until="load")
    page.go_back(wait_until="load")
    assert page.url == site_url(page_source.output_name, transport)
    now = {s.param: s.exact for s in range_sliders(page, spec)}
    defaults = {s.param: s.stop(default_index(spec, s)) for s in sliders}
    assert now in (moved, defaults), now
    assert scene_problems(page, spec) == []
    assert not log.errors


# --- d) random states of whole scenes -------------------------------------------------------------

RANDOM_STATES = 200


@pytest.mark.parametrize("page_source,spec,transport", _scene_params())
def test_random_scene_states(open_page, page_source, spec, transport):
    """Random positions of all sliders at once: catches table indexing mistakes across axes."""
    page, log = open_page(page_source.output_name, transport)
    sliders = range_sliders(page, spec)
    rng = random.Random(f"{page_source.slug}/{spec.id}/1")
    failures = []
    for _ in range(RANDOM_STATES):
        state = [rng.randrange(s.count) for s in sliders]
        # one round trip per state; each slider still gets its own value + `input` event
        set_sliders(page, spec.id, {s.param: s.stop(index) for s, index in zip(sliders, state)})
        problems = scene_problems(page, spec)
        assert [s.index for s in range_sliders(page, spec)] == state
        failures += problems
    assert not failures, f"{len(failures)} mismatches, e.g.:\n" + "\n".join(failures[:10])
    assert not log.errors


# --- e) the figure's moving layers ---------------------------------------------------------------

# Which layers must move (and which must not) when a slider moves from the scene's defaults.
LAYER_RESPONSES = {
    "impulse": {
        "F_pk": ({"area", "pulse"}, set()),
        "tau": ({"area", "pulse"}, set()),
        "m": (set(), {"area", "pulse"}),  # the force pulse does not depend on the mass
    },
    "collision": {
        "m1": ({"centre-of-mass", "body-1", "body-2"}, set()),
        "m2": ({"centre-of-mass", "body-1", "body-2"}, set()),
        "v1i": ({"centre-of-mass", "body-1", "body-2"}, set()),
        "v2i": ({"centre-of-mass", "body-1", "body-2"}, set()),
        "e": ({"body-1", "body-2", "K-after", "K-lost"}, {"centre-of-mass"}),  # V does not depend on e
    },
}
_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)(e[-+]?\d+)?$", re.I)


def parse_points(text: str | None) -> list[tuple[float, float]]:
    """SVG points as numbers; fails on anything that is not a finite number."""
    assert text and text.strip(), f"empty points {text!r}"
    points = []
    for pair in text.split():
        xy = pair.split(",")
        assert len(xy) == 2 and all(_NUMBER.match(v) for v in xy), f"bad point {pair!r} in {text!r}"
        x, y = map(float, xy)
        assert math.isfinite(x) and math.isfinite(y), text
        points.append((x, y))
    return points


def _number(readout: str) -> float:
    return float(readout.split()[0].replace("\u2212", "-"))


def _shoelace(points) -> float:
    return abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]))) / 2


def geometry_problems(spec, layers: dict[str, list], values: dict[str, Decimal]) -> list[str]:
    """Where the figure contradicts the readouts: the shaded area is J, the lines end at v_f."""
    problems = []
    model = spec.model
    if model == "impulse" and "area" in layers:
        j = expected_readouts(model, values, names=["J"], fixed=fixed_values(spec))["J"]
        if abs(_shoelace(layers["area"]) - _number(j)) > 5e-4 + 1e-9:
            problems.append(f"area polygon {layers['area']} has area {_shoelace(layers['area'])}, J is {j}")
    if model == "collision":
        want = expected_readouts(model, values, names=["v1f", "v2f", "v_cm"], fixed=fixed_values(spec))
        for layer, out in (("body-1", "v1f"), ("body-2", "v2f"), ("centre-of-mass", "v_cm")):
            if layer in layers and abs(layers[layer][-1][1] - _number(want[out])) > 1e-9:
                problems.append(f"{layer} ends at {layers[layer][-1]}, {out} is {want[out]}")
        for layer, param in (("body-1", "v1i"), ("body-2", "v2i")):
            if layer in layers and abs(layers[layer][0][1] - float(values[param])) > 1e-9:
                problems.append(f"{layer} starts at {layers[layer][0]}, {param} is {values[param]}")
    return problems


@pytest.mark.parametrize("page_source,spec,transport", _scene_params(("file",)))
def test_layers_follow_sliders(open_page, page_source, spec, transport):
    static_page, _ = open_page(page_source.output_name, transport, javascript=False)
    built = {k: parse_points(v) for k, v in layer_points(static_page, spec.id).items()}
    page, log = open_page(page_source.output_name, transport)
    scripted = {k: parse_points(v) for k, v in layer_points(page, spec.id).items()}
    assert built, "the figure has no moving layers"
    assert built.keys() == scripted.keys()
    for name in built:  # the script redraws the defaults exactly where the build drew them
        assert len(built[name]) == len(scripted[name])
        for (x0, y0), (x1, y1) in zip(built[name], scripted[name]):
            assert math.isclose(x0, x1, rel_tol=1e-5, abs_tol=1e-6) and math.isclose(y0, y1, rel_tol=1e-5, abs_tol=1e-6), name

    responses = LAYER_RESPONSES.get(spec.model, {})
    problems = []
    for slider in range_sliders(page, spec):
        control = page.locator(slider.selector).element_handle()
        start = layer_points(page, spec.id)
        changed = set()
        for index in slider.spread(8):
            set_slider(page, control, slider.stop(index))
            now = layer_points(page, spec.id)
            layers = {k: parse_points(v) for k, v in now.items()}
            values = {s.param: s.exact for s in range_sliders(page, spec)}
            problems += [f"{slider.param}={plain(values[slider.param])}: {p}" for p in geometry_problems(spec, layers, values)]
            changed |= {k for k in now if now[k] != start[k]}
        set_slider(page, control, slider.stop(default_index(spec, slider)))
        assert layer_points(page, spec.id) == start, f"layers not restored after moving {slider.param} back"
        must, must_not = responses.get(slider.param, (set(), set()))
        assert must <= changed, f"moving {slider.param} left {sorted(must - changed)} still"
        assert not (must_not & changed), f"moving {slider.param} moved {sorted(must_not & changed)}"
    assert not problems, "\n".join(problems[:10])
    assert not log.errors


# --- f) links --------------------------------------------------------------------------------------


def test_home_links_to_chapters(built_site, open_page):
    """The contents on the home page link to every chapter, and the links work from disk."""
    home, _ = open_page("index.html", "file")
    hrefs = home.eval_on_selector_all("nav a[href]", "els => els.map(e => e.getAttribute('href'))")
    chapters = [p for p in PAGES if p.slug != "index"]
    assert "newtons-laws.html" in hrefs
    assert sorted(hrefs) == sorted(p.output_name for p in chapters)
    for chapter in chapters:
        home.goto((built_site / "index.html").as_uri())
        with home.expect_navigation():
            home.locator(f'nav a[href="{chapter.output_name}"]').click()
        assert home.url == (built_site / chapter.output_name).as_uri()
        assert home.locator("h1").inner_text() == chapter.title


@pytest.mark.parametrize("name,transport", _page_params())
def test_links_resolve_to_files(built_site, open_page, name, transport):
    """No link points to a bare directory (index.html is not implied on disk); all reach a file."""
    page, _ = open_page(name, transport)
    links = page.eval_on_selector_all("a[href]", "els => els.map(e => [e.getAttribute('href'), e.href])")
    assert links
    for href, absolute in links:
        assert href and not href.endswith("/"), f"link to a directory: {href!r}"
        if href.startswith("#"):
            continue
        target = urlparse(urljoin(page.url, href))
        here = urlparse(page.url)
        assert (target.scheme, target.netloc) == (here.scheme, here.netloc), f"link leaves the site: {href!r}"
        if transport == "file":
            path = Path(unquote(target.path))
            assert path.is_file() and path.resolve().is_relative_to(built_site.resolve()), href
        else:
            response = page.request.get(absolute)
            assert response.status == 200, (href, response.status)
