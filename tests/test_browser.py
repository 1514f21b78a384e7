"""The built site in a real browser (Debian's headless Chromium through Playwright).

Pages, scenes and controls are parametrized from the build's own parse of the book (content/*.md
through `read_pages` + `resolve_scenes`), so test ids are precise: page-scene-control-transport,
e.g. "newtons-laws-examples-kinetic-species-http". `test_built_site_matches_sources` checks that
the built DOM has exactly those pages, scenes, controls, readouts and play buttons, so the
parametrization cannot drift away from what was built. Expected readouts come from the physics
models at the exact stops the controls stand on (see tests/browser.py), never from the tables
the page carries.

Every kind of control is exercised as users meet it: evenly spaced and listed range sliders by
keyboard and by value, choices (radio groups) by clicking and by arrow keys; the play buttons of
animated scenes; and the singular stops whose readouts are words rather than numbers.

Speed: one browser for the session and one loaded page per (page, transport, javascript) shared
by the tests (each test first puts its scene back on its defaults); a test that navigates or
needs its own browser settings opens a fresh page. DOM reads are batched in one page.evaluate().
Loading is tested from disk and over http; keyboard, random-state, expression, layer and animation
tests run over file:// only (the script works on the same inline tables either way).
"""

from __future__ import annotations

import json
import random
from dataclasses import dataclass, field
from decimal import Decimal
from pathlib import Path
from urllib.parse import unquote, urljoin, urlparse

import pytest
from browser import (
    BROKEN_TEXT,
    SETTLED,
    BookScene,
    SiteServer,
    book,
    describe_stop,
    expected_control_text,
    expected_readouts,
    front,
    layer_deps,
    layer_problems,
    load,
    logged_page,
    move,
    move_many,
    move_value,
    new_page,
    parse_layer,
    plain,
    read_state,
    reset,
    scene_problems,
    singular_stops,
    spread,
    stop_inputs,
)

from sitegen.compute.closed_form import verified_stops
from sitegen.compute.grid import CHOICE, RANGE
from sitegen.compute.quantize import fmt
from sitegen.compute.structure import structured_pieces

pytestmark = pytest.mark.browser  # the whole module is about pages in Chromium

PAGES, SCENES = book()
PAGE_NAMES = [p.output_name for p in PAGES]
TRANSPORTS = ("file", "http")
CONTROLS = [(scene, axis.param) for scene in SCENES for axis in scene.axes]
ANIMATED = [scene for scene in SCENES if scene.animate]
SPECIAL_SCENES = [scene for scene in SCENES if any(o.special for o in scene.scene.readouts)]


def _page_params(transports=TRANSPORTS):
    return [pytest.param(p.output_name, t, id=f"{p.slug}-{t}") for p in PAGES for t in transports]


# Each transport's tests together: consecutive tests then read the same page, and bringing another tab to the front
# of the window redraws it.
def _scene_params(scenes=SCENES, transports=TRANSPORTS):
    return [pytest.param(s, t, id=f"{s.key}-{t}") for t in transports for s in scenes]


def _control_params(transports=TRANSPORTS):
    return [pytest.param(s, param, t, id=f"{s.key}-{param}-{t}") for t in transports for s, param in CONTROLS]


# --- fixtures -----------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def site_server(built_site):
    with SiteServer(built_site) as server:
        yield server


@pytest.fixture(scope="module")
def site_url(built_site, site_server):
    def url(name: str, transport: str) -> str:
        return (built_site / name).as_uri() if transport == "file" else site_server.url(name)

    return url


@dataclass
class PageLog:
    """What happened while a page was open."""

    requests: list[str] = field(default_factory=list)
    failed: list[str] = field(default_factory=list)
    responses: list[tuple[str, int]] = field(default_factory=list)
    console: list[tuple[str, str, dict]] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)

    def mark(self) -> tuple[int, int]:
        return len(self.errors), len(self.console)

    def trouble_since(self, mark: tuple[int, int]) -> list:
        """Page errors and console errors/warnings logged after `mark`."""
        console = [
            (t, text)
            for t, text, loc in self.console[mark[1] :]
            if t in ("error", "warning") and not loc.get("url", "").endswith("/favicon.ico")
        ]
        return self.errors[mark[0] :] + console


def _open_logged(chromium, url: str, javascript: bool = True, **options):
    page = new_page(chromium, java_script_enabled=javascript, **options)
    log = PageLog()
    page.on("request", lambda r: log.requests.append(r.url))
    page.on("requestfailed", lambda r: log.failed.append(f"{r.url}: {r.failure}"))
    page.on("response", lambda r: log.responses.append((r.url, r.status)))
    page.on("console", lambda m: log.console.append((m.type, m.text, m.location)))
    page.on("pageerror", lambda e: log.errors.append(str(e)))
    page.goto(url, wait_until="load")
    page.evaluate(SETTLED)
    return page, log


@pytest.fixture(scope="module")
def loaded(chromium, site_url):
    """loaded(name, transport, javascript=True) -> (page, log): one shared, loaded page per
    (name, transport, javascript) for the module. Tests must not navigate it away."""
    cache = {}

    def _get(name: str, transport: str, javascript: bool = True):
        key = (name, transport, javascript)
        if key not in cache:
            cache[key] = _open_logged(chromium, site_url(name, transport), javascript)
        front(cache[key][0])
        return cache[key]

    return _get


@pytest.fixture
def open_page(tabs, site_url):
    """open_page(name, transport, javascript=True, **page options) -> (page, errors): the page
    loaded afresh, in a page no other part of the test uses (for tests that navigate or emulate),
    and the page and console errors logged since."""
    with tabs.lending() as borrow:

        def _open(name: str, transport: str, javascript: bool = True, **options):
            page, errors = borrow(java_script_enabled=javascript, **options)
            load(page, site_url(name, transport))
            return page, errors

        yield _open


@pytest.fixture
def scene_page(loaded):
    """scene_page(scene, transport) -> (page, log, mark): the shared page with the scene back on
    its defaults (checked), and a mark to find errors logged during the test."""

    def _get(scene: BookScene, transport: str):
        page, log = loaded(scene.page.output_name, transport)
        state = reset(page, scene)
        assert state.stops == scene.defaults, f"reset to the defaults left {state.stops}"
        return page, log, log.mark()

    return _get


def _where(scene: BookScene, stops) -> str:
    return ", ".join(f"{p}={describe_stop(scene, p, k)}" for p, k in zip(scene.params, stops))


# --- the site as built ---------------------------------------------------------------------------


def _range_attrs(axis) -> dict:
    if axis.kind == RANGE:
        return {"type": "range", "min": plain(axis.lo), "max": plain(axis.hi), "step": plain(axis.step)}
    return {"type": "range", "min": "0", "max": str(axis.count - 1), "step": "1"}


@pytest.mark.parametrize("name", PAGE_NAMES, ids=[p.slug for p in PAGES])
def test_built_site_matches_sources(built_site, loaded, name):
    """The built page (as served, before any script) has exactly the scenes, controls, readouts and
    play buttons its source declares, each control of the right kind with its stops."""
    assert sorted(p.name for p in built_site.glob("*.html")) == sorted(PAGE_NAMES)
    page, _ = loaded(name, "file", javascript=False)
    scenes = [s for s in SCENES if s.page.output_name == name]
    source = next(p for p in PAGES if p.output_name == name)
    assert len(scenes) == len(source.extracted.scenes)
    found = page.eval_on_selector_all("figure.scene", "els => els.map(e => [e.id, e.dataset.scene])")
    assert found == [[s.dom_id, s.scene.model.name] for s in scenes]
    for scene in scenes:
        state = read_state(page, scene)
        assert [c.param for c in state.controls] == scene.params, scene
        for control, axis, default in zip(state.controls, scene.axes, scene.defaults):
            where = f"{scene.key} {axis.param}"
            if axis.kind == CHOICE:
                assert control.tag == "fieldset" and "choice" in (control.attrs["class"] or "").split(), where
                assert control.label and control.label.strip(), f"{where}: choice without a <legend>"
                assert [r["value"] for r in control.radios] == [str(k) for k in range(axis.count)], where
                assert control.radio_labels == list(axis.labels), where
                assert {r["name"] for r in control.radios} == {f"{scene.dom_id}-{axis.param}"}, where
                assert [r["checked"] for r in control.radios] == [k == default for k in range(axis.count)], where
            else:
                assert control.tag == "input", where
                assert {k: control.attrs[k] for k in ("type", "min", "max", "step")} == _range_attrs(axis), where
                assert control.dom_id == f"{scene.dom_id}-{axis.param}", where
                assert control.label and control.label.strip(), f"{where}: slider without a <label for>"
                assert control.index == default, where
        assert list(state.readouts) == scene.readout_names, scene
        if scene.animate:
            assert state.button == {"animate": scene.animate, "pressed": "false", "text": "Play"}, scene
        else:
            assert state.button is None, scene
        assert page.locator(f"#{scene.dom_id}[data-src^='assets/scenes/']").count() == 1


# --- a) loading ------------------------------------------------------------------------------------


def _inside_site(url: str, transport: str, built_site: Path, origin: str | None) -> bool:
    if url.startswith("data:"):
        return True  # inline data never leaves the page
    parts = urlparse(url)
    if transport == "file":
        return parts.scheme == "file" and Path(unquote(parts.path)).resolve().is_relative_to(built_site.resolve())
    return f"{parts.scheme}://{parts.netloc}" == origin


def test_a_scene_reached_before_its_data_came_shows_the_stop_it_was_moved_to(built_site, chromium):
    """The page asks for no scene's data before it has loaded (nor, while the reader has not scrolled, for a
    second after); a slider moved by the keyboard on a scene far down asks for that scene's, and its readouts
    show the new stop once it has come, as a reader's first move anywhere does. Over http, where the browser
    times each request."""
    page, errors = logged_page(chromium)
    with SiteServer(built_site) as server:
        page.goto(server.url("newtons-laws.html"), wait_until="load")
        scene, slider = next(  # the last scene whose first control is a slider
            (s, page.locator(f'#{s.dom_id} input[type="range"][data-param="{s.params[0]}"]'))
            for s in reversed([s for s in SCENES if s.page.output_name == "newtons-laws.html"])
            if page.locator(f'#{s.dom_id} input[type="range"][data-param="{s.params[0]}"]').count()
        )
        slider.focus()
        slider.press("End")
        page.wait_for_function("id => (window.sitegenScenes || {})[id] !== undefined", arg=scene.dom_id)
        asked = page.evaluate("""() => { const loaded = performance.getEntriesByType('navigation')[0].loadEventEnd;
          return performance.getEntriesByType('resource').filter(r => r.name.includes('/assets/scenes/'))
            .map(r => r.startTime >= loaded); }""")
        state = read_state(page, scene)
    assert asked and all(asked), asked  # every data script asked for after the page had loaded
    assert state.stops[0] == scene.axes[0].count - 1 and scene_problems(scene, state) == [], state
    assert not errors
    page.close()


@pytest.mark.parametrize("name,transport", _page_params())
def test_page_loads_cleanly(built_site, loaded, site_server, name, transport):
    page, log = loaded(name, transport)
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
    bad_status = [
        (u, s) for u, s in log.responses if transport == "http" and s != 200 and not u.endswith("/favicon.ico")
    ]
    assert not bad_status, bad_status
    assert any(u.endswith("assets/sitegen.js") for u in log.requests)
    assert any(u.endswith("assets/sitegen.css") for u in log.requests)

    source = next(p for p in PAGES if p.output_name == name)
    maths = page.locator("math").count()
    if source.extracted.maths:
        assert maths >= len(source.extracted.maths), (
            f"{len(source.extracted.maths)} formulas in the source, {maths} <math> elements"
        )
        assert any(u.endswith("assets/latinmodern-math.woff2") for u in log.requests), "math font not requested"
        assert page.evaluate("""document.fonts.check('16px "Latin Modern Math"')""")
        # fonts.check() is also true when the family is installed locally (it is, on Debian with
        # texlive fonts), so also require that the page's own web font actually loaded.
        faces = page.evaluate("[...document.fonts].map(f => [f.family.replace(/\"/g, ''), f.status])")
        assert ["Latin Modern Math", "loaded"] in faces, faces
    else:
        assert maths == 0


def test_pages_declare_an_icon(loaded):
    """Every page names its icon (e.g. <link rel="icon" href="data:,">), else browsers request
    /favicon.ico from the server, which the site does not have: a 404 and a console error on
    every page view over http."""
    missing = []
    for name in PAGE_NAMES:
        page, _ = loaded(name, "file", javascript=False)
        if not page.locator('head link[rel~="icon"]').count():
            missing.append(name)
    assert not missing, f"pages without <link rel=icon>: {missing}"


# --- b) without JavaScript ------------------------------------------------------------------------


@pytest.mark.parametrize("name,transport", _page_params())
def test_readouts_without_javascript(loaded, name, transport):
    """The page as built already shows every scene complete at its defaults: controls on their
    default stops with their texts, every readout the model's value there, finite layers."""
    page, log = loaded(name, transport, javascript=False)
    assert not log.errors
    scenes = [s for s in SCENES if s.page.output_name == name]
    assert page.locator("figure.scene").count() == len(scenes)
    for scene in scenes:
        state = read_state(page, scene)
        assert state.stops == scene.defaults, scene
        assert scene_problems(scene, state) == [], scene
        assert state.layers and layer_problems(state) == [], scene


# --- c) each control, by keyboard and by value / click ---------------------------------------------


def _slider_keys(count: int):
    """(key, check(stop before, stop after)) for a range input of `count` stops."""
    last = count - 1
    return [
        ("Home", lambda b, a: a == 0),
        ("ArrowRight", lambda b, a: a == min(last, b + 1)),
        ("ArrowRight", lambda b, a: a == min(last, b + 1)),
        ("ArrowLeft", lambda b, a: a == max(0, b - 1)),
        ("PageUp", lambda b, a: a > b if b < last else a == last),
        ("End", lambda b, a: a == last),
        ("ArrowRight", lambda b, a: a == last),  # at the end: stays
        ("ArrowLeft", lambda b, a: a == max(0, b - 1)),
        ("ArrowLeft", lambda b, a: a == max(0, b - 1)),
        ("PageDown", lambda b, a: a < b if b > 0 else a == 0),
        ("PageUp", lambda b, a: a > b if b < last else a == last),
        ("Home", lambda b, a: a == 0),
        ("ArrowLeft", lambda b, a: a == 0),  # at the start: stays
        ("PageDown", lambda b, a: a == 0),
    ]


def _choice_keys(count: int):
    """Arrow keys within a radio group: next/previous option, wrapping around the ends."""
    right = lambda b, a: a == (b + 1) % count  # noqa: E731
    left = lambda b, a: a == (b - 1) % count  # noqa: E731
    return [("ArrowRight", right)] * count + [
        ("ArrowDown", right),
        ("ArrowLeft", left),
        ("ArrowUp", left),
        ("ArrowLeft", left),
    ]


@pytest.mark.parametrize("scene,param,transport", _control_params(("file",)))
def test_control_by_keyboard(scene_page, scene, param, transport):
    """Sliders: Home/End, arrows and PageUp/PageDown move by stops; choices: arrow keys move the
    checked option round the group. After every key the whole scene agrees with the model."""
    page, log, mark = scene_page(scene, transport)
    axis = scene.axis(param)
    i = scene.params.index(param)
    default = scene.defaults[i]
    if axis.kind == CHOICE:
        selector = f'#{scene.dom_id} fieldset[data-param="{param}"] input[type="radio"][value="{default}"]'
        keys = _choice_keys(axis.count)
    else:
        selector = f"#{scene.dom_id}-{param}"
        keys = _slider_keys(axis.count)
    page.focus(selector)
    problems, before = [], default
    for n, (key, as_expected) in enumerate(keys):
        page.keyboard.press(key)
        state = read_state(page, scene)
        after = state.stops[i]
        assert after is not None and as_expected(before, after), (
            f"key {n} {key}: stop {before} -> {after} of {axis.count}"
        )
        others = state.stops[:i] + state.stops[i + 1 :]
        assert others == scene.defaults[:i] + scene.defaults[i + 1 :], f"{key} moved another control: {state.stops}"
        if axis.kind == CHOICE:  # focus moves with the checked radio
            assert [r["focused"] for r in state.control(param).radios] == [k == after for k in range(axis.count)], key
        problems += [f"after {key}: {p}" for p in scene_problems(scene, state)]
        before = after
    assert not problems, "\n".join(problems[:10])
    assert not log.trouble_since(mark)


@pytest.mark.parametrize("scene,param,transport", _control_params())
def test_control_by_value(scene_page, scene, param, transport):
    """Sliders: value + `input` at the ends, the default and a spread of stops between (and an
    off-grid value, which the browser snaps to a stop); choices: a click on each radio, then on
    the default option's label. After every move the whole scene agrees with the model."""
    page, log, mark = scene_page(scene, transport)
    axis = scene.axis(param)
    i = scene.params.index(param)
    default = scene.defaults[i]
    problems = []
    if axis.kind == CHOICE:
        group = page.locator(f'#{scene.dom_id} fieldset[data-param="{param}"]')
        radios, labels = group.locator('input[type="radio"]'), group.locator("label")
        assert radios.count() == labels.count() == axis.count
        # each radio clicked (last first), then the default option's label text
        for k, target in [*((k, radios.nth(k)) for k in range(axis.count - 1, -1, -1)), (default, labels.nth(default))]:
            target.click()
            state = read_state(page, scene)
            assert state.stops[i] == k, f"clicked option {k} ({axis.labels[k]}), stop is {state.stops[i]}"
            problems += scene_problems(scene, state)
    else:
        last = axis.count - 1
        stops = [0, last, default, *(k for k in spread(axis.count) if k not in (0, last)), default]
        for k, state in zip(stops, move_many(page, scene, [{param: k} for k in stops])):
            assert state.stops[i] == k, f"set stop {k}, control reads {state.control(param).value!r}"
            problems += scene_problems(scene, state)
        if axis.kind == RANGE and axis.count > 2:
            # a value 30 % of a step above a middle stop: the input snaps it to that stop
            k = axis.count // 2
            state = move_value(page, scene, param, plain(axis.stop(k) + axis.step * 3 / 10))
            assert state.stops[i] == k, f"off-grid value snapped to {state.control(param).value!r}, not stop {k}"
            problems += scene_problems(scene, state)
    assert not problems, "\n".join(problems[:10])
    assert not log.trouble_since(mark)


# --- d) singular stops read as words -------------------------------------------------------------------


@pytest.mark.parametrize("scene,transport", _scene_params(SPECIAL_SCENES))
def test_singular_stops_show_words(scene_page, scene, transport):
    """Where the model is singular (±inf) or the quantity does not exist (NaN), an output with a
    `special` shows that phrase, without a unit: e.g. the lever's mechanical advantage with the
    pivot at the end, the intensity level in front of a perfect reflector, the potential energy
    of drag. Every such output is searched over its grid (a solved model's over a sub-grid); a few of
    its singular stops each (the first, the last and up to four more) are set on the page."""
    found = singular_stops(scene)
    if not any(found.values()):
        pytest.skip(f"no stop of {scene.key} makes {', '.join(found)} non-finite")
    page, log, mark = scene_page(scene, transport)
    rng = random.Random(scene.key)
    checks = []  # (output, stops)
    for output, stops_found in found.items():
        picks = (
            {stops_found[0], stops_found[-1], *rng.sample(stops_found, min(4, len(stops_found)))} if stops_found else ()
        )
        checks += [(output, stops) for stops in sorted(picks)]
    states = move_many(page, scene, [dict(zip(scene.params, stops)) for _, stops in checks])
    problems = []
    for (output, stops), state in zip(checks, states):
        assert state.stops == stops
        phrase = scene.scene.model.output(output).special
        if state.readouts[output] != phrase:
            problems.append(f"[{_where(scene, stops)}] {output} shows {state.readouts[output]!r}, not {phrase!r}")
        problems += scene_problems(scene, state)
    assert not problems, "\n".join(problems[:10])
    assert not log.trouble_since(mark)


def test_known_singular_stops():
    """The singular stops are where the physics says: the lever's pivot at the end (x_p = 2: the
    mechanical advantage is infinite) and a perfect reflector (R_r = 1: no net intensity, L_I is
    -inf). Guards the search of test_singular_stops_show_words against finding nothing."""
    expected = {
        ("newtons-laws-lever", "MA"): ("x_p", "2"),
        ("newtons-laws-examples-acoustic-energy", "L_I"): ("R_r", "1"),
    }
    for (key, output), (param, value) in expected.items():
        scene = next((s for s in SCENES if s.key == key), None)
        if scene is None:
            continue  # the scene left the book
        found = singular_stops(scene)[output]
        i = scene.params.index(param)
        assert found and all(plain(scene.axis(param).stop(s[i])) == value for s in found), (key, output, found[:3])


# --- e) random states of whole scenes --------------------------------------------------------------

RANDOM_STATES = 200


@pytest.mark.parametrize("scene,transport", _scene_params(transports=("file",)))
def test_random_scene_states(scene_page, scene, transport):
    """Random positions of all controls at once (sliders by value + `input`, choices by checking a
    radio + `input`/`change`): catches table indexing mistakes across axes. No readout, control
    text or layer ever shows NaN, Infinity or undefined. (From disk: once a page has loaded, its
    script reads the same inline tables over http; test_control_by_value moves every control there.)"""
    page, log, mark = scene_page(scene, transport)
    rng = random.Random(f"{scene.key}/1")
    failures = []
    wanted = [tuple(rng.randrange(a.count) for a in scene.axes) for _ in range(RANDOM_STATES)]
    states = []
    for start in range(0, len(wanted), 25):  # 25 states per round trip; each control still gets its own events
        states += move_many(page, scene, [dict(zip(scene.params, w)) for w in wanted[start : start + 25]])
    for state_wanted, state in zip(wanted, states):
        assert state.stops == state_wanted, f"set {state_wanted}, controls read {state.stops}"
        failures += scene_problems(scene, state)
        texts = [c.valuetext or "" for c in state.controls] + [c.shown or "" for c in state.controls]
        failures += [f"[{_where(scene, state_wanted)}] control text {t!r}" for t in texts if BROKEN_TEXT.search(t)]
        failures += [f"[{_where(scene, state_wanted)}] {p}" for p in layer_problems(state)]
    assert not failures, f"{len(failures)} mismatches, e.g.:\n" + "\n".join(failures[:10])
    assert not log.trouble_since(mark)


# --- e2) outputs the page computes from verified expressions -------------------------------------------

STRUCTURED_SCENES = [s for s in SCENES if structured_pieces(s.scene, s.readout_names)]


@pytest.mark.parametrize("scene,transport", _scene_params(STRUCTURED_SCENES, ("file",)))
def test_expressions_at_the_verified_stops(scene_page, scene, transport):
    """The build's sampled check of each declared structure, repeated through the real script: at the slider
    box's corners, a spread of its edge stops and seeded random stops, every readout the script
    computes from an expression equals the model's value at display precision (a tie either way)."""
    page, log, mark = scene_page(scene, transport)
    stops = verified_stops(scene.scene)
    rng = random.Random(f"{scene.key}/closed-form")
    chosen = [tuple(int(k) for k in s) for s in rng.sample(list(stops), min(300, len(stops)))]
    corners = [tuple(int(k) for k in s) for s in stops if all(k in (0, a.count - 1) for k, a in zip(s, scene.axes))]
    failures = []
    for start in range(0, len(corners + chosen), 25):
        batch = (corners + chosen)[start : start + 25]
        for state in move_many(page, scene, [dict(zip(scene.params, w)) for w in batch]):
            failures += scene_problems(scene, state)
    assert not failures, f"{len(failures)} mismatches, e.g.:\n" + "\n".join(failures[:10])
    assert not log.trouble_since(mark)


# --- f) after going back in history ------------------------------------------------------------------


@pytest.mark.parametrize(
    "name,transport",
    [pytest.param(p.output_name, "file", id=f"{p.slug}-file") for p in PAGES if any(s.page is p for s in SCENES)],
)
def test_scenes_after_history_navigation(open_page, site_url, name, transport):
    """Leave a page with moved controls and come back: whatever the browser restores (the whole
    page from the back/forward cache, or just the controls' values into a fresh page, before the
    script runs), the readouts agree with the controls."""
    scenes = [s for s in SCENES if s.page.output_name == name]
    page, errors = open_page(name, transport)
    moved = {}
    for scene in scenes:  # every control to its far end from the default
        moved[scene.key] = tuple(0 if d else a.count - 1 for a, d in zip(scene.axes, scene.defaults))
        state = move(page, scene, dict(zip(scene.params, moved[scene.key])))
        assert scene_problems(scene, state) == []
    page.goto(site_url("index.html", transport), wait_until="load")
    page.go_back(wait_until="load")
    page.evaluate(SETTLED)  # a fresh page redraws restored controls once their scene's data has arrived
    # the address may carry a moved scene's state (written in place once its controls rest)
    address, _, fragment = page.url.partition("#")
    assert address == site_url(name, transport)
    assert not fragment or fragment.split(":")[0] in {s.id for s in scenes}, fragment
    for scene in scenes:
        state = read_state(page, scene)
        assert all(k in (m, d) for k, m, d in zip(state.stops, moved[scene.key], scene.defaults)), (scene, state.stops)
        assert scene_problems(scene, state) == [], scene
    assert not errors


# --- g) the figure's moving layers ---------------------------------------------------------------

# Layers that must move when a control moves from the scene's defaults (beyond what layer_deps
# derives: a layer must never move for a control outside its dependencies).
LAYER_RESPONSES = {
    "impulse": {"F_pk": {"area", "pulse"}, "tau": {"area", "pulse"}},
    "collision": {
        "m1": {"centre-of-mass", "body-1", "body-2"},
        "m2": {"centre-of-mass", "body-1", "body-2"},
        "v1i": {"centre-of-mass", "body-1", "body-2"},
        "v2i": {"centre-of-mass", "body-1", "body-2"},
        "e": {"body-1", "body-2", "K-after", "K-lost"},
    },
    "lever": {"x_p": {"fulcrum", "pivot", "arm-left", "arm-right", "bar"}, "m_L": {"balance-line", "bar"}},
    "ossicles": {
        "ell": {"pivot", "gain"},
        "A_TM": {"eardrum", "gain"},
        "A_FP": {"footplate"},
        "load": {"T-without", "T-with"},
    },
    "euler_slab": {"phi": {"wave", "faces", "a-point"}, "dx_l": {"slab", "faces", "a-slab"}},
    "acoustic_energy": {
        "wt": {"ep", "ek", "rate", "convergence"},
        "R_r": {"ek-average", "ep-average", "I-average"},
        "x_probe": {"probe"},
    },
    "kinetic": {
        "N": {"impulse-train", "velocity-histogram"},
        "t_w": {"impulse-train", "running-mean"},
        "sampling": {"velocity-histogram"},
    },
}


def _number(text: str) -> float:
    return float(text.replace("\u2212", "-"))


def _shoelace(points) -> float:
    return abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]))) / 2


def _rounded(scene: BookScene, stops, names) -> dict[str, float]:
    """Outputs of the model at these stops, rounded to their displayed digits (as tabulated)."""
    model = scene.scene.model
    values = model.evaluate(stop_inputs(scene.scene, stops), wanted=names, effects=scene.scene.effects)
    return {n: _number(fmt(float(values[n]), model.output(n).decimals)) for n in names}


def geometry_problems(scene: BookScene, layers: dict[str, list], stops) -> list[str]:
    """Where the figure contradicts the model: the shaded impulse area is J, collision lines start
    at the initial and end at the final velocities."""
    problems = []
    name = scene.scene.model.name
    values = {**scene.scene.base_values(), **{a.param: float(a.stop(k)) for a, k in zip(scene.axes, stops)}}
    if name == "impulse" and "area" in layers:
        j = _rounded(scene, stops, ["J"])["J"]
        if abs(_shoelace(layers["area"]) - j) > 5e-4 + 1e-9:
            problems.append(f"area polygon {layers['area']} has area {_shoelace(layers['area'])}, J is {j}")
    if name == "collision":
        want = _rounded(scene, stops, ["v1f", "v2f", "v_cm"])
        for layer, out in (("body-1", "v1f"), ("body-2", "v2f"), ("centre-of-mass", "v_cm")):
            if layer in layers and abs(layers[layer][-1][1] - want[out]) > 1e-9:
                problems.append(f"{layer} ends at {layers[layer][-1]}, {out} is {want[out]}")
        for layer, param in (("body-1", "v1i"), ("body-2", "v2i")):
            if layer in layers and abs(layers[layer][0][1] - values[param]) > 1e-9:
                problems.append(f"{layer} starts at {layers[layer][0]}, {param} is {values[param]}")
    return problems


def _parsed(state):
    return {name: parse_layer(attr, text) for name, (attr, text) in state.layers.items()}


@pytest.mark.parametrize("scene,transport", _scene_params(transports=("file",)))
def test_layers_follow_controls(loaded, scene_page, scene, transport):
    """The script draws the defaults where the build drew them; every control moves the layers
    that depend on it (and no other), each vertex a finite number; back at the default the
    figure is as it was."""
    static_page, _ = loaded(scene.page.output_name, transport, javascript=False)
    built = _parsed(read_state(static_page, scene))
    page, log, mark = scene_page(scene, transport)
    start_state = read_state(page, scene)
    scripted = _parsed(start_state)
    assert built, "the figure has no moving layers"
    assert built.keys() == scripted.keys() == layer_deps(scene).keys()
    for name in built:  # the script redraws the defaults exactly where the build drew them
        assert len(built[name]) == len(scripted[name]), name
        for (x0, y0), (x1, y1) in zip(built[name], scripted[name]):
            assert abs(x0 - x1) <= 1e-5 * max(1, abs(x0)) and abs(y0 - y1) <= 1e-5 * max(1, abs(y0)), name

    deps = layer_deps(scene)
    responses = LAYER_RESPONSES.get(scene.scene.model.name, {})
    problems, moved_at_all = [], set()
    for i, axis in enumerate(scene.axes):
        changed = set()
        stops = list(range(axis.count) if axis.kind == CHOICE else spread(axis.count))
        *states, state = move_many(page, scene, [{axis.param: k} for k in [*stops, scene.defaults[i]]])
        for k, moved in zip(stops, states):
            assert moved.stops[i] == k
            layers = _parsed(moved)
            where = f"{axis.param}={describe_stop(scene, axis.param, k)}"
            problems += [f"{where}: {p}" for p in geometry_problems(scene, layers, moved.stops)]
            changed |= {n for n in layers if moved.layers[n] != start_state.layers[n]}
        assert state.layers == start_state.layers, f"layers not restored after moving {axis.param} back"
        must = responses.get(axis.param, set())
        assert must <= changed, f"moving {axis.param} left {sorted(must - changed)} still"
        wrong = {n for n in changed if axis.param not in deps[n]}
        assert not wrong, f"moving {axis.param} moved {sorted(wrong)}, which do not depend on it"
        moved_at_all |= changed
    still = sorted(n for n in deps if deps[n] and n not in moved_at_all)
    assert not still, f"layers {still} depend on controls but never moved"
    assert not problems, "\n".join(problems[:10])
    assert not log.trouble_since(mark)


# --- h) animation ------------------------------------------------------------------------------------

# Records, in the page, every frame the animated control shows: the stops of all controls and the
# readouts, taken right after the script's update (a MutationObserver on the control's text).
_RECORD_JS = """
  const slider = root.querySelector(`[data-param="${arg}"]`);
  const out = root.querySelector(`output[data-value-of="${arg}"]`) || slider;
  const frames = [];
  const snap = () => ({
    values: [...root.querySelectorAll('[data-param]')].map(el => el.tagName === 'FIELDSET'
      ? (el.querySelector('input:checked') || {}).value : el.value),
    readouts: Object.fromEntries([...root.querySelectorAll('[data-out]')].map(el => [el.dataset.out, el.textContent])),
    layers: Object.fromEntries([...root.querySelectorAll('svg [data-layer]')].map(el =>
      [el.dataset.layer, el.getAttribute(el.tagName.toLowerCase() === 'path' ? 'd' : 'points')])),
  });
  if (window.__frames && window.__frames.observer) window.__frames.observer.disconnect();
  const observer = new MutationObserver(() => frames.push(snap()));
  observer.observe(out, {attributes: true, characterData: true, childList: true, subtree: true});
  window.__frames = {frames, observer};
"""


def _frames(page) -> list[dict]:
    """The frames recorded since the last call (as one JSON string: it is large)."""
    return json.loads(page.evaluate("JSON.stringify(window.__frames.frames.splice(0))"))


def _frame_stops(scene: BookScene, frame: dict) -> tuple[int, ...]:
    stops = []
    for axis, value in zip(scene.axes, frame["values"]):
        if axis.kind == RANGE:
            stops.append(int(((Decimal(value) - axis.lo) / axis.step).to_integral_value()))
        else:
            stops.append(int(value))
    return tuple(stops)


def _button(page, scene):
    return page.locator(f'#{scene.dom_id} button[data-animate="{scene.animate}"]')


def _pressed(page, scene) -> str | None:
    return read_state(page, scene).button["pressed"]


@pytest.mark.parametrize("scene,transport", _scene_params(ANIMATED, ("file",)))
def test_animation_plays_and_pauses(scene_page, scene, transport):
    """Play steps the animated slider one stop per frame, wrapping round its range; the readouts
    and the figure's layers follow at every frame; Pause stops it where it is and Play resumes
    from there. aria-pressed and the button's label say which."""
    page, log, mark = scene_page(scene, transport)
    param, i = scene.animate, scene.params.index(scene.animate)
    axis = scene.axis(param)
    page.locator(f"#{scene.dom_id}").scroll_into_view_if_needed()
    page.evaluate(
        f"([sceneId, arg]) => {{ const root = document.getElementById(sceneId); {_RECORD_JS} }}", [scene.dom_id, param]
    )
    button = _button(page, scene)
    button.click()
    assert read_state(page, scene).button == {"animate": param, "pressed": "true", "text": "Pause"}
    # a whole cycle and a bit: every stop is shown, then it starts over
    page.wait_for_function(
        "([n]) => window.__frames.frames.length >= n", arg=[axis.count + 3], timeout=max(15_000, axis.count * 500)
    )
    button.click()
    state = read_state(page, scene)
    assert state.button == {"animate": param, "pressed": "false", "text": "Play"}
    frames = _frames(page)
    stops = [_frame_stops(scene, f) for f in frames]
    path = [s[i] for s in stops]
    steps = [(b - a) % axis.count for a, b in zip([scene.defaults[i]] + path, path)]
    assert set(steps) == {1}, f"the animated slider went {path}"
    assert set(path) == set(range(axis.count)), "the animation skipped stops"
    assert all(s[:i] + s[i + 1 :] == scene.defaults[:i] + scene.defaults[i + 1 :] for s in stops), (
        "other controls moved"
    )
    problems = []
    for frame, s in zip(frames, stops):
        want = expected_readouts(scene, s)
        if frame["readouts"] != want:
            problems.append(f"[{_where(scene, s)}] page {frame['readouts']}, model {want}")
    assert not problems, f"{len(problems)} frames disagree with the model:\n" + "\n".join(problems[:5])
    # the figure follows too: each frame's layers are those the same stops show when set by hand
    moved = move_many(page, scene, [dict(zip(scene.params, s)) for s in stops])
    for frame, s, by_hand in zip(frames, stops, moved):
        assert by_hand.stops == s
        assert frame["layers"] == {n: text for n, (_, text) in by_hand.layers.items()}, f"layers at {_where(scene, s)}"
    assert len({json.dumps(f["layers"], sort_keys=True) for f in frames}) > 1, "the figure stood still while playing"
    state = move(page, scene, dict(zip(scene.params, state.stops)))  # back where it paused
    assert scene_problems(scene, state) == []
    _frames(page)  # (the moves by hand were recorded too)
    # paused: nothing moves any more
    paused_at = state.stops
    page.wait_for_timeout(400)
    assert read_state(page, scene).stops == paused_at and _frames(page) == [], "the animation went on after Pause"
    # Play again resumes from where it stopped
    button.click()
    page.wait_for_function("() => window.__frames.frames.length >= 2", timeout=10_000)
    button.click()
    frames = _frames(page)
    assert _frame_stops(scene, frames[0])[i] == (paused_at[i] + 1) % axis.count, "Play did not resume where it paused"
    assert _pressed(page, scene) == "false"
    page.evaluate("window.__frames.observer.disconnect()")
    assert not log.trouble_since(mark)


# Installed before any page script runs: every change the page makes to a play button's
# aria-pressed or a control's aria-valuetext, from the very start.
_WATCH_MOTION_JS = """
window.__motion = [];
new MutationObserver(records => records.forEach(r => window.__motion.push(
  [r.attributeName, r.target.getAttribute(r.attributeName), r.target.dataset.param || r.target.dataset.animate || '',
   (r.target.closest('[data-scene]') || {}).id])))
  .observe(document, {subtree: true, attributes: true, attributeFilter: ['aria-pressed', 'aria-valuetext']});
"""


@pytest.fixture(scope="module")
def watched(chromium):
    """watched(motion) -> (page, errors): a page, one per reduced-motion setting, that records in
    every document it loads the changes _WATCH_MOTION_JS watches for, from before any page script
    runs; and the page errors logged from this call on."""
    pages, logs = {}, {}

    def _get(motion: str):
        if motion not in pages:
            pages[motion] = new_page(chromium, reduced_motion=motion)
            pages[motion].add_init_script(_WATCH_MOTION_JS)
            pages[motion].on("pageerror", lambda e: logs[motion].append(str(e)))
        logs[motion] = []
        return front(pages[motion]), logs[motion]

    return _get


@pytest.mark.parametrize(
    "scene,motion,transport",
    [pytest.param(s, m, "file", id=f"{s.key}-{m}-file") for s in ANIMATED for m in ("reduce", "no-preference")],
)
def test_animation_never_autoplays(watched, site_url, scene, motion, transport):
    """The page loads still (with reduced motion asked for, and without): the play button is never
    pressed and the animated slider never leaves its default, in view or not, until the reader
    presses Play."""
    page, errors = watched(motion)
    page.goto("about:blank")  # the document below loads afresh
    page.goto(site_url(scene.page.output_name, transport), wait_until="load")
    assert page.evaluate("matchMedia('(prefers-reduced-motion: reduce)').matches") == (motion == "reduce")
    page.wait_for_timeout(300)
    page.locator(f"#{scene.dom_id}").scroll_into_view_if_needed()
    page.wait_for_timeout(600)  # more than ten frames of an animation
    state = read_state(page, scene)
    assert state.button["pressed"] == "false" and state.button["text"] == "Play"
    assert state.stops == scene.defaults, "the animation started by itself"
    assert scene_problems(scene, state) == []
    i = scene.params.index(scene.animate)
    default_text = expected_control_text(scene, scene.animate, scene.defaults[i])
    changes = page.evaluate("window.__motion")
    changes = [
        c for c in changes if c[3] == scene.dom_id
    ]  # another scene on the page may animate a slider of the same name
    pressed = [c for c in changes if c[0] == "aria-pressed" and c[1] != "false"]
    assert not pressed, f"the play button was pressed by the page itself: {pressed}"
    moved = [c[1] for c in changes if c[0] == "aria-valuetext" and c[2] == scene.animate and c[1] != default_text]
    assert not moved, f"the animated slider moved by itself: {moved[:5]}"
    assert not errors


def _visible_fraction(page, scene) -> float:
    return page.evaluate(
        """(id) => { const r = document.getElementById(id).getBoundingClientRect();
          const h = Math.min(r.bottom, innerHeight) - Math.max(r.top, 0); return Math.max(0, h) / r.height; }""",
        scene.dom_id,
    )


@pytest.mark.parametrize("scene,transport", _scene_params(ANIMATED, ("file",)))
def test_animation_pauses_out_of_view(scene_page, scene, transport):
    """A playing scene that scrolls out of view pauses (and stays paused when it comes back)."""
    page, log, mark = scene_page(scene, transport)
    root = page.locator(f"#{scene.dom_id}")
    root.scroll_into_view_if_needed()
    _button(page, scene).click()
    assert _pressed(page, scene) == "true"
    page.wait_for_function(
        '([id, param, v]) => document.querySelector(`#${id} [data-param="${param}"]`).value !== v',
        arg=[scene.dom_id, scene.animate, read_state(page, scene).control(scene.animate).value],
        timeout=10_000,
    )
    # scroll the scene right out of the viewport: to whichever end of the page is further from it
    page.evaluate(
        """(id) => { const r = document.getElementById(id).getBoundingClientRect();
          const top = r.top + scrollY, bottom = r.bottom + scrollY;
          const below = document.documentElement.scrollHeight - bottom;
          scrollTo(0, below > top ? document.documentElement.scrollHeight : 0); }""",
        scene.dom_id,
    )
    assert _visible_fraction(page, scene) == 0, "could not scroll the scene out of view"
    page.wait_for_function(
        "(id) => document.querySelector(`#${id} button[data-animate]`).getAttribute('aria-pressed') === 'false'",
        arg=scene.dom_id,
        timeout=5_000,
    )
    state = read_state(page, scene)
    assert state.button["text"] == "Play"
    page.wait_for_timeout(300)
    later = read_state(page, scene)
    assert later.stops == state.stops, "the animation went on out of view"
    assert scene_problems(scene, later) == []
    root.scroll_into_view_if_needed()
    page.wait_for_timeout(300)
    back = read_state(page, scene)
    assert back.button["pressed"] == "false" and back.stops == state.stops, "the animation restarted by itself"
    assert not log.trouble_since(mark)


# --- i) links --------------------------------------------------------------------------------------


def test_home_links_to_chapters(built_site, open_page):
    """The contents on the home page link to every chapter, and the links work from disk."""
    home, _ = open_page("index.html", "file")
    hrefs = home.eval_on_selector_all(
        'article nav[aria-label="Contents"] a[href]:not(.anchor)', "els => els.map(e => e.getAttribute('href'))"
    )
    chapters = [p for p in PAGES if p.slug != "index"]
    assert "newtons-laws.html" in hrefs
    assert sorted(hrefs) == sorted(p.output_name for p in chapters)
    for chapter in chapters:
        home.goto((built_site / "index.html").as_uri())
        with home.expect_navigation():
            home.locator(f'article nav[aria-label="Contents"] a[href="{chapter.output_name}"]').click()
        assert home.url == (built_site / chapter.output_name).as_uri()
        assert home.locator("h1").inner_text() == chapter.title


@pytest.mark.parametrize("name,transport", _page_params())
def test_links_resolve_to_files(built_site, loaded, name, transport):
    """No link points to a bare directory (index.html is not implied on disk); all reach a file."""
    page, _ = loaded(name, transport, javascript=False)
    links = page.eval_on_selector_all("a[href]", "els => els.map(e => [e.getAttribute('href'), e.href])")
    assert links
    targets = {}  # over http: the file each link reaches -> a link to it
    for href, absolute in links:
        assert href and not href.endswith("/"), f"link to a directory: {href!r}"
        if href.startswith("#"):
            continue
        target = urlparse(urljoin(page.url, href))
        here = urlparse(page.url)
        if target.scheme == "https" and href.startswith("https://"):
            continue  # a source's DOI or address in a list of references: the reader's to follow, never loaded
        assert (target.scheme, target.netloc) == (here.scheme, here.netloc), f"link leaves the site: {href!r}"
        if transport == "file":
            path = Path(unquote(target.path))
            assert path.is_file() and path.resolve().is_relative_to(built_site.resolve()), href
        else:
            targets.setdefault(
                absolute.partition("#")[0], href
            )  # each file once, however many of its anchors are linked
    for absolute, href in targets.items():
        response = page.request.get(absolute)
        assert response.status == 200, (href, response.status)
