"""Helpers for the browser tests: Chromium, a local web server, the book's scenes and their controls.

The scenes come from the build's own parse (`read_pages` + `resolve_scenes`): each is a
`ResolvedScene` with its axes (range, listed or choice controls), default stops, fixed values,
effects and readouts. Expected texts are computed here independently of the page: the scene's
model is evaluated at the exact stops the DOM's controls stand on (choices as the model's codes),
with the scene's fixed values and effects, and formatted with `sitegen.compute.quantize.fmt` and
`sitegen.site.assemble.with_unit` (or the output's labels, or its `special` phrase where the
value is not finite).
Nothing is read from the scene's inline tables.

Every DOM helper is one `page.evaluate()`: resolving a Playwright locator costs several
milliseconds on the chapters' large DOMs, an evaluate about one.
"""

from __future__ import annotations

import functools
import http.server
import json
import math
import re
import threading
from collections.abc import Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import numpy as np

from sitegen.build import BuildConfig, resolve_book
from sitegen.compute.grid import CHOICE, LIST, RANGE
from sitegen.compute.quantize import MINUS, fmt, format_quantum, quantize, significant_text
from sitegen.compute.scenes import ResolvedScene
from sitegen.content.pages import Page
from sitegen.registry import builtin_registry
from sitegen.review.figures import CHROMIUM, LAUNCH_ARGS  # one place for Chromium's settings
from sitegen.site.assemble import with_unit

FIGURES = builtin_registry().figures

ROOT = Path(__file__).resolve().parents[1]


# What a readout or a control's text must never show: a number the script failed to look up.
BROKEN_TEXT = re.compile(r"NaN|Infinity|undefined|\bnull\b|\[object")


def launch(playwright, **options):
    """Debian's Chromium, headless (Playwright cannot download its own browsers here)."""
    return playwright.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS, **options)


def close(browser) -> None:
    """Close `browser` with every page the module's fixtures opened in it (a page lives as long as the module's
    browser), and forget its contexts and their tabs in front (kept, they would keep every closed browser of the
    test process)."""
    for context in _CONTEXTS.pop(browser, {}).values():
        _IN_FRONT.pop(context, None)
    browser.close()


class Tabs:
    """Pages kept open for a test module, by their options, to load documents in.

    A new page costs a renderer process (about 0.4 s of CPU beyond loading a document). A new document
    loaded in a page that is already open costs far less, and the site's script keeps nothing beyond its
    document (no storage), so a test that needs a page as it loads borrows one and loads its document
    afresh (`load`).
    """

    def __init__(self, browser):
        self.browser = browser
        self.idle: dict[str, list] = {}
        self.logs: dict = {}  # page -> the list its errors go to

    def _open(self, options: dict):
        page, errors = logged_page(self.browser, **options)
        self.logs[page] = errors
        return page

    @contextmanager
    def lending(self):
        """borrow(**context options) -> (page, errors): a page no one else holds, for the `with` block,
        and the page errors and console errors or warnings it logs from then on. Returned afterwards
        with print emulation off."""
        taken = []

        def borrow(**options):
            pool = self.idle.setdefault(json.dumps(options, sort_keys=True), [])
            page = pool.pop() if pool else self._open(options)
            taken.append((pool, page))
            self.logs[page].clear()  # what it logged for an earlier test
            return front(page), self.logs[page]

        try:
            yield borrow
        finally:
            for pool, page in taken:
                page.emulate_media(media="null")
                pool.append(page)


# What Playwright emulates for one page as well as for a whole context: pages that differ only in these share one.
PAGE_OPTIONS = ("viewport", "color_scheme", "reduced_motion")
_CONTEXTS: dict = {}  # browser -> {its contexts' options: context}, until `close`
_IN_FRONT: dict = {}  # context -> its tab in front, until `close`


def new_page(browser, **options):
    """A new page with `options`, in the browser's one context for the options a page cannot take by itself
    (JavaScript off, a phone's touch and pixel ratio).

    A context's pages are tabs of one window: a new context opens a window, which costs about 1.2 s of CPU
    more than a tab, and the site leaves nothing in a context (no cookies, no storage) that one page could
    find of another's. They share the HTTP cache: over http a later page may take the assets from it (Playwright
    still reports each request, and its status as 200). Only the tab in front is drawn (`front`).
    """
    on_page = {name: options.pop(name) for name in PAGE_OPTIONS if name in options}
    if options.get("java_script_enabled") is True:  # the default: the same context as without the option
        del options["java_script_enabled"]
    contexts = _CONTEXTS.setdefault(browser, {})
    key = json.dumps(options, sort_keys=True)
    if key not in contexts:
        contexts[key] = browser.new_context(**options)
    page = contexts[key].new_page()
    _IN_FRONT[contexts[key]] = page  # a new tab opens in front
    if "viewport" in on_page:
        page.set_viewport_size(on_page["viewport"])
    media = {name: on_page[name] for name in ("color_scheme", "reduced_motion") if name in on_page}
    if media:
        page.emulate_media(**media)
    return page


def front(page):
    """`page`, brought to the front of its window: a tab behind another gets about one animation frame a second,
    so its transitions, observers and Playwright's own waits for a steady element crawl."""
    if _IN_FRONT.get(page.context) is not page:  # bringing forward the tab in front still redraws it
        page.bring_to_front()
        _IN_FRONT[page.context] = page
    return page


def logged_page(browser, **options):
    """(page, errors): a new page with `options` (`new_page`), and the list that collects its errors and its
    console errors and warnings."""
    page = new_page(browser, **options)
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("console", lambda m: errors.append(f"{m.type}: {m.text}") if m.type in ("error", "warning") else None)
    return page, errors


# A page asks for its scenes' data at the reader's first scroll (or a second after it loads): settled when the
# fonts are, a scroll has asked for the data, every scene's has arrived and the boxes the script measures after
# the first frame are marked. With scripts off (the <noscript> in every page's head then holds elements) no
# timer or frame callback runs, so only the fonts are waited for. For every engine.
SETTLED = """(function () {
  var off = [].some.call(document.querySelectorAll("noscript"), function (n) { return n.children.length > 0; });
  if (off) return document.fonts.ready.then(function () { return true; });
  return Promise.all([document.fonts.ready, new Promise(function (done, fail) {
    var until = Date.now() + 20000;
    window.dispatchEvent(new Event("scroll"));
    (function check() {
      var scenes = window.sitegenScenes || {}, roots = [].slice.call(document.querySelectorAll("[data-scene]"));
      var waiting = roots.filter(function (root) { return scenes[root.id] === undefined; });
      if (!waiting.length) done();
      else if (Date.now() > until) fail(new Error("no data came for " + waiting.map(function (r) { return r.id; })));
      else setTimeout(check, 10);
    })();
  })]).then(function () {
    return new Promise(function (done) { requestAnimationFrame(function () { setTimeout(done, 0); }); });
  }).then(function () { return true; });
})()"""


def load(page, url: str) -> None:
    """Load `url` in `page` as a new document (even if only its fragment differs from the one open), settled."""
    page.goto("about:blank")
    page.goto(url, wait_until="load")
    page.evaluate(SETTLED)


# --- the book, as the build parses it (used to parametrize at collection time) -------------------


@dataclass(frozen=True)
class BookScene:
    """A resolved scene and the page it sits on."""

    page: Page
    scene: ResolvedScene

    @property
    def id(self) -> str:
        return self.scene.id

    @property
    def dom_id(self) -> str:
        return f"scene-{self.scene.id}"

    @property
    def key(self) -> str:
        """Unique in the book: 'newtons-laws-lever' (page slug, scene id)."""
        return f"{self.page.slug}-{self.scene.id}"

    @property
    def axes(self):
        return self.scene.axes

    @property
    def params(self) -> list[str]:
        return [a.param for a in self.scene.axes]

    @property
    def defaults(self) -> tuple[int, ...]:
        return tuple(self.scene.default_stops)

    @property
    def readout_names(self) -> list[str]:
        return [o.name for o in self.scene.readouts]

    @property
    def animate(self) -> str | None:
        return self.scene.spec.animate

    def axis(self, param: str):
        return self.scene.axes[self.params.index(param)]

    def __repr__(self) -> str:  # short, for assertion messages
        return f"<scene {self.key}>"


@functools.cache  # read once per process, by every module that parametrizes over the book
def book(root: Path = ROOT) -> tuple[list[Page], list[BookScene]]:
    """Every page of the book at `root` (the project's, or tests/book) and every scene on it, read and resolved
    as the build does (do not change them)."""
    resolved = resolve_book(BuildConfig.at(root))
    pages = list(resolved.pages)
    scenes = [BookScene(item.page, item.scene) for item in resolved.scenes]
    declared = sum(len(p.extracted.scenes) for p in pages)
    assert len(scenes) == declared, f"{declared} scene blocks, {len(scenes)} resolved"
    return pages, scenes


# --- a local web server -------------------------------------------------------------------------


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):
        pass


class SiteServer:
    """Serve a folder on 127.0.0.1 at a free port from a daemon thread."""

    def __init__(self, directory: Path):
        handler = functools.partial(_QuietHandler, directory=str(directory))
        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
        self.httpd.daemon_threads = True
        self.port = self.httpd.server_address[1]
        self.origin = f"http://127.0.0.1:{self.port}"
        self.thread = threading.Thread(target=self.httpd.serve_forever, name="site-server", daemon=True)

    def __enter__(self) -> SiteServer:
        self.thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self.httpd.shutdown()
        self.httpd.server_close()
        self.thread.join(timeout=5)

    def url(self, name: str) -> str:
        return f"{self.origin}/{name}"


# --- numbers as text ------------------------------------------------------------------------------


def plain(value: Decimal) -> str:
    """A decimal as a plain string, as an <input> value would hold it ('10', '0.25', '-5')."""
    text = format(value.normalize(), "f")
    return "0" if text == "-0" else text


def control_value(axis, index: int) -> str:
    """What a slider's `value` holds at stop `index`: the physical value for an evenly spaced
    slider, the index of the stop for a listed one (a choice's checked radio holds the index too)."""
    return plain(axis.stop(index)) if axis.kind == RANGE else str(index)


# --- controls, readouts and layers as found in the DOM --------------------------------------------


@dataclass(frozen=True)
class Control:
    """One control of a scene as the DOM has it: a range input (evenly spaced or listed) or a
    fieldset of radios (a choice)."""

    param: str
    axis: object  # the scene's Axis for this control
    tag: str  # "input" or "fieldset"
    dom_id: str
    attrs: Mapping[str, str | None]  # type, min, max, step, class, name of the radios
    value: str | None  # an input's .value
    valuetext: str | None  # aria-valuetext
    shown: str | None  # text of <output data-value-of=param>, if any
    label: str | None  # text of <label for=dom_id> (slider) or the <legend> (choice)
    radios: tuple[Mapping, ...]  # a choice's radios: value, checked, name, id, label text

    @property
    def kind(self) -> str:
        return self.axis.kind

    @property
    def count(self) -> int:
        return self.axis.count

    @property
    def index(self) -> int | None:
        """The stop the control stands on, or None if its value is no stop at all."""
        if self.kind == CHOICE:
            checked = [r for r in self.radios if r["checked"]]
            if len(checked) != 1 or not re.fullmatch(r"\d+", checked[0]["value"] or ""):
                return None
            k = int(checked[0]["value"])
        elif self.kind == LIST:
            if not re.fullmatch(r"\d+", self.value or ""):
                return None
            k = int(self.value)
        else:
            try:
                offset = (Decimal(self.value) - self.axis.lo) / self.axis.step
            except Exception:
                return None
            k = int(offset.to_integral_value())
            # a range input's value is always on its step (to float precision)
            if abs(offset - k) > Decimal("1e-9"):
                return None
        return k if 0 <= k < self.count else None

    @property
    def radio_labels(self) -> list[str]:
        return [(r["label"] or "").strip() for r in self.radios]


@dataclass(frozen=True)
class SceneState:
    """Everything a scene shows at one moment, read in one round trip."""

    controls: tuple[Control, ...]
    readouts: Mapping[str, str]  # data-out name -> text, in DOM order
    layers: Mapping[str, tuple[str, str | None]]  # data-layer name -> (attribute name, its value)
    button: Mapping | None  # the play button: data-animate, aria-pressed, text

    @property
    def stops(self) -> tuple[int | None, ...]:
        return tuple(c.index for c in self.controls)

    def control(self, param: str) -> Control:
        return next(c for c in self.controls if c.param == param)


_ROOT_JS = "const root = document.getElementById(sceneId); if (!root) throw new Error('no scene ' + sceneId);"
_STATE_JS = """const readState = () => {
  const text = el => el ? el.textContent : null;
  const controls = [...root.querySelectorAll('[data-param]')].map(el => {
    const param = el.dataset.param;
    const label = el.labels && el.labels.length ? el.labels[0] : null;  // <label for=id> (or wrapping)
    return {
      param, tag: el.tagName.toLowerCase(), id: el.id,
      attrs: {type: el.getAttribute('type'), min: el.getAttribute('min'), max: el.getAttribute('max'),
              step: el.getAttribute('step'), class: el.getAttribute('class'), value: el.getAttribute('value')},
      value: el.tagName === 'INPUT' ? el.value : null,
      valuetext: el.getAttribute('aria-valuetext'),
      shown: text(root.querySelector(`output[data-value-of="${param}"]`)),
      label: el.tagName === 'FIELDSET' ? text(el.querySelector('legend')) : text(label),
      radios: [...el.querySelectorAll('input[type="radio"]')].map(r => ({
        value: r.value, checked: r.checked, name: r.name, id: r.id, label: text(r.closest('label')),
        focused: document.activeElement === r,
      })),
    };
  });
  const readouts = Object.fromEntries([...root.querySelectorAll('[data-out]')].map(el => [el.dataset.out,
    el.textContent]));
  const layers = Object.fromEntries([...root.querySelectorAll('svg [data-layer]')].map(el => {
    const attr = el.tagName.toLowerCase() === 'path' ? 'd' : 'points';
    return [el.dataset.layer, [attr, el.getAttribute(attr)]];
  }));
  const b = root.querySelector('button[data-animate]');
  const button = b ? {animate: b.dataset.animate, pressed: b.getAttribute('aria-pressed'),
    text: b.textContent.trim()} : null;
  return {controls, readouts, layers, button};
};"""

# Move controls: [param, value] pairs. A slider gets its value and an `input` event (as a user's
# drag does); a choice's radio with that value is checked and gets `input` and `change` (as a click).
_MOVE_JS = """const moveTo = pairs => pairs.forEach(([param, v]) => {
  const el = root.querySelector(`[data-param="${param}"]`);
  if (!el) throw new Error('no control ' + param);
  if (el.tagName === 'FIELDSET') {
    const radio = el.querySelector(`input[type="radio"][value="${v}"]`);
    if (!radio) throw new Error('no option ' + v + ' of ' + param);
    radio.checked = true;
    radio.dispatchEvent(new Event('input', {bubbles: true}));
    radio.dispatchEvent(new Event('change', {bubbles: true}));
  } else {
    el.value = v;
    el.dispatchEvent(new Event('input', {bubbles: true}));
  }
});"""


def _in_scene(page, scene: BookScene, body: str, arg=None):
    """Evaluate `body` (statements over `root`, the scene element, and `arg`) in the page.

    The result comes back as one JSON string: Playwright checks a structured result value by
    value, which costs far more than the evaluation itself for a few hundred vertices.
    """
    text = page.evaluate(f"([sceneId, arg]) => JSON.stringify((() => {{ {_ROOT_JS} {body} }})())", [scene.dom_id, arg])
    return None if text is None else json.loads(text)


def _state(scene: BookScene, raw: dict) -> SceneState:
    axes = {a.param: a for a in scene.axes}
    controls = []
    for r in raw["controls"]:
        if r["param"] not in axes:  # a control the scene does not declare: reported by the caller
            axes[r["param"]] = _UnknownAxis()
        controls.append(
            Control(
                param=r["param"],
                axis=axes[r["param"]],
                tag=r["tag"],
                dom_id=r["id"],
                attrs=r["attrs"],
                value=r["value"],
                valuetext=r["valuetext"],
                shown=r["shown"],
                label=r["label"],
                radios=tuple(r["radios"]),
            )
        )
    layers = {k: tuple(v) for k, v in raw["layers"].items()}
    return SceneState(tuple(controls), raw["readouts"], layers, raw["button"])


class _UnknownAxis:
    kind, count, lo, step = "unknown", 0, Decimal(0), Decimal(1)


def read_state(page, scene: BookScene) -> SceneState:
    """The scene's controls, readouts, layers and play button, read together."""
    return _state(scene, _in_scene(page, scene, f"{_STATE_JS} return readState();"))


def move(page, scene: BookScene, stops: Mapping[str, int]) -> SceneState:
    """Put controls on stops ({param: stop index}, in that order) and read the scene back."""
    return move_many(page, scene, [stops])[0]


def move_many(page, scene: BookScene, positions: list[Mapping[str, int]]) -> list[SceneState]:
    """move() through several positions in one round trip, reading the scene after each.

    The page's script updates a scene synchronously in its `input`/`change` handlers, so what is
    read right after the events is what a reader sees in the next frame.
    """
    moves = [[[param, control_value(scene.axis(param), k)] for param, k in stops.items()] for stops in positions]
    raws = _in_scene(
        page, scene, f"{_STATE_JS} {_MOVE_JS} return arg.map(pairs => {{ moveTo(pairs); return readState(); }});", moves
    )
    return [_state(scene, raw) for raw in raws]


def move_value(page, scene: BookScene, param: str, value: str) -> SceneState:
    """Write a raw value into one control (e.g. an off-grid number) and read the scene back."""
    return _state(
        scene, _in_scene(page, scene, f"{_STATE_JS} {_MOVE_JS} moveTo(arg); return readState();", [[param, value]])
    )


def reset(page, scene: BookScene) -> SceneState:
    """Pause the scene's animation if it plays and put every control back on its default."""
    _in_scene(
        page,
        scene,
        "const b = root.querySelector('button[data-animate]'); "
        "if (b && b.getAttribute('aria-pressed') === 'true') b.click();",
    )
    return move(page, scene, dict(zip(scene.params, scene.defaults)))


# --- expected texts -------------------------------------------------------------------------------


def stop_inputs(scene: ResolvedScene, stops) -> dict[str, float]:
    """Every model parameter at a slider position: the scene's fixed values, the model defaults,
    and each control's exact stop (a choice's stop is the model's code of the option)."""
    values = {**scene.model.defaults(), **dict(scene.fixed)}
    for axis, k in zip(scene.axes, stops):
        values[axis.param] = float(axis.stop(k))
    return values


_EXPECTED: dict[tuple[int, tuple[int, ...]], dict[str, tuple[str, ...]]] = {}


def _expected(scene: ResolvedScene, stops: tuple[int, ...]) -> dict[str, tuple[str, ...]]:
    """The readout texts at a full slider position (memoised: the http run repeats the file run's states)."""
    key = (id(scene), stops)
    if key not in _EXPECTED:
        _EXPECTED[key] = _evaluate_texts(scene, stops)
    return _EXPECTED[key]


def _evaluate_texts(scene: ResolvedScene, stops: tuple[int, ...]) -> dict[str, tuple[str, ...]]:
    names = [o.name for o in scene.readouts]
    values = scene.model.evaluate(stop_inputs(scene, stops), wanted=names, effects=scene.effects)
    texts = {}
    for output in scene.readouts:
        value = float(np.asarray(values[output.name]))
        if not math.isfinite(value) and output.special:
            # singular (±inf) or not defined here (NaN): shown in words, without a unit
            texts[output.name] = (output.special,)
            continue
        if not math.isfinite(value):
            raise ValueError(f"output {output.name!r} of scene {scene.id} is {value} at {stops}")
        if output.labels:
            texts[output.name] = (output.labels[int(value)],)
        elif output.digits:  # significant digits: one correct text (ties are not singled out)
            texts[output.name] = (
                significant_text(0.0 if abs(value) < output.floor else value, output.digits, output.unit),
            )
        else:
            texts[output.name] = tuple(with_unit(t, output.unit) for t in _roundings(value, output.decimals))
    return texts


def _roundings(value: float, decimals: int) -> list[str]:
    """The correct displays of a value: its rounding, and where the value sits on a rounding tie
    (to its own float error, e.g. K = 0.005 J at 2 decimals) also the neighbour on the other side.
    An output the page computes from a verified expression may land on either side of a tie."""
    shown = fmt(value, decimals)
    scaled = value * 10.0**decimals
    if abs(abs(scaled - math.floor(scaled)) - 0.5) > 1e-9 * max(1.0, abs(scaled)):
        return [shown]
    quantum = int(quantize(value, decimals))
    other = quantum - 1 if quantum > scaled else quantum + 1  # the neighbour on the tie's other side
    return [shown, format_quantum(other, decimals)]


def expected_readouts(scene: BookScene, stops) -> dict[str, str]:
    """The readout texts the page must show at these stops, computed from the model itself (the
    first of the correct displays; see `accepted_readouts`)."""
    return {name: texts[0] for name, texts in _expected(scene.scene, tuple(stops)).items()}


def accepted_readouts(scene: BookScene, stops) -> dict[str, tuple[str, ...]]:
    """Every correct text of each readout at these stops (two where the exact value is a rounding tie)."""
    return dict(_expected(scene.scene, tuple(stops)))


def expected_control_text(scene: BookScene, param: str, index: int) -> str:
    """A control's value as the page must announce it (aria-valuetext) and show it beside it:
    an evenly spaced slider's stop with the decimals every stop needs (rounded when a step such
    as 1/60 has no finite decimal), a listed stop as the author wrote it, a choice's option name;
    numbers with the parameter's unit."""
    axis = scene.axis(param)
    if axis.kind == CHOICE:
        return axis.labels[index]
    unit = scene.scene.model.param(param).unit
    value = axis.stop(index)
    if axis.kind == RANGE:
        text = fmt(float(value), axis.decimals)
        # fmt goes through a float; make sure that cannot have changed the exact decimal written.
        assert Decimal(text.replace(MINUS, "-")) == value, (text, value)
    elif axis.has_fractions:
        text = fmt(float(value), axis.decimals)
        # the shown text is the exact stop to within half its last digit
        assert abs(Fraction(Decimal(text.replace(MINUS, "-"))) - Fraction(value)) <= Fraction(
            1, 2 * 10**axis.decimals
        ), (text, value)
    else:
        text = plain(value).replace("-", MINUS)
    return with_unit(text, unit)


def scene_problems(scene: BookScene, state: SceneState) -> list[str]:
    """Every way the scene's controls or readouts differ from the model at the controls' stops."""
    problems = []
    params = [c.param for c in state.controls]
    if params != scene.params:
        return [f"controls {params} != declared {scene.params}"]
    stops = state.stops
    for c, k in zip(state.controls, stops):
        if k is None:
            problems.append(
                f"control {c.param}: value {c.value!r} / radios {[r['checked'] for r in c.radios]} is no stop"
            )
            continue
        want = expected_control_text(scene, c.param, k)
        if c.kind == CHOICE:
            shown = c.radio_labels[k] if k < len(c.radios) else None
            if shown != want:
                problems.append(f"choice {c.param}: checked option {shown!r}, expected {want!r}")
            continue
        if c.valuetext != want:
            problems.append(f"slider {c.param}: aria-valuetext {c.valuetext!r}, expected {want!r}")
        if c.shown is not None and c.shown != want:
            problems.append(f"slider {c.param}: shown value {c.shown!r}, expected {want!r}")
    if list(state.readouts) != scene.readout_names:
        problems.append(f"readouts {list(state.readouts)} != declared {scene.readout_names}")
    for name, text in state.readouts.items():
        if BROKEN_TEXT.search(text or ""):
            problems.append(f"readout {name} shows {text!r}")
    if all(k is not None for k in stops):
        for name, texts in accepted_readouts(scene, stops).items():
            if state.readouts.get(name) not in texts:
                problems.append(
                    f"readout {name}: page {state.readouts.get(name)!r}, model {' or '.join(map(repr, texts))}"
                )
    if problems:
        where = ", ".join(f"{c.param}={describe_stop(scene, c.param, k)}" for c, k in zip(state.controls, stops))
        problems = [f"[{where}] {p}" for p in problems]
    return problems


def describe_stop(scene: BookScene, param: str, k: int | None) -> str:
    if k is None:
        return "?"
    axis = scene.axis(param)
    if axis.kind == CHOICE:
        return axis.labels[k]
    stop = axis.stop(k)
    return plain(stop) if isinstance(stop, Decimal) else str(stop)  # a fraction such as 13/60 as itself


# --- layers -----------------------------------------------------------------------------------------

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:e[-+]?\d+)?"
_PAIR = re.compile(rf"^({_NUMBER}),({_NUMBER})$", re.I)
_DOT = re.compile(rf"^M({_NUMBER}),({_NUMBER})h(?:0\.0*1|10*)$", re.I)  # a dot: a stroke 10^k long


def parse_layer(attr: str, text: str | None) -> list[tuple[float, float]]:
    """A layer's vertices: SVG `points` ("x,y x,y") or, for dots, a path `d` ("Mx,yh0.01 Mx,yh0.01");
    fails on anything that is not a finite number. An empty attribute is a layer with no vertices
    at this stop (a ragged vector output of length 0, e.g. the arc when the chord is chosen)."""
    assert text is not None, f"layer without its {attr} attribute"
    pattern = _DOT if attr == "d" else _PAIR
    points = []
    for item in text.split():
        match = pattern.match(item)
        assert match, f"bad vertex {item!r} in {attr}={text[:200]!r}"
        x, y = float(match[1]), float(match[2])
        assert math.isfinite(x) and math.isfinite(y), text
        points.append((x, y))
    return points


def layer_problems(state: SceneState) -> list[str]:
    """Layers whose vertices are not all finite numbers."""
    problems = []
    for name, (attr, text) in state.layers.items():
        try:
            parse_layer(attr, text)
        except AssertionError as error:
            problems.append(f"layer {name}: {error}")
    return problems


def layer_deps(scene: BookScene) -> dict[str, set[str]]:
    """For each moving layer, the scene's controls it may depend on (from its references: an
    `in:` parameter, or the declared deps of an `out:` output)."""
    model = scene.scene.model
    deps = {}
    for layer in FIGURES[scene.scene.spec.figure or model.name].layers(scene.scene):
        if layer.kind == "text":  # a note under the figure, not drawn in it
            continue
        params = set()
        for ref in layer.refs():
            if isinstance(ref, str) and ref.startswith("in:"):
                params.add(ref[3:])
            elif isinstance(ref, str) and ref.startswith("out:"):
                params |= set(model.deps_of(ref[4:], scene.scene.effects))
        deps[layer.name] = params & set(scene.params)
    return deps


# --- stops to visit ---------------------------------------------------------------------------------


def spread(count: int, n: int = 8) -> list[int]:
    """Stop indices to visit: first, last and `n` spread between them."""
    last = count - 1
    return sorted({0, last, *(round(i * last / (n + 1)) for i in range(1, n + 1))})


_SINGULAR: dict[str, dict[str, list[tuple[int, ...]]]] = {}
# A model solved per point (an ODE per stop) is searched on a sub-grid of at most about this many
# points: every k-th stop of each axis, and its last. Closed forms are searched at every stop.
SOLVED_SEARCH_POINTS = 500


def _search_stops(counts: tuple[int, ...], limit: int | None) -> list[list[int]]:
    """The stops of each axis to search: all of them, or the coarsest every-k-th (with the last) within `limit`
    points."""
    step = 1
    while limit and math.prod(len(range(0, c - 1, step)) + 1 for c in counts) > limit:
        step += 1
    return [sorted({*range(0, c, step), c - 1}) for c in counts]


def singular_stops(scene: BookScene) -> dict[str, list[tuple[int, ...]]]:
    """For each readout with a `special` phrase, the full slider positions (the other controls at
    their defaults) where the model's value is not finite: ±inf where the physics is singular,
    NaN where the quantity does not exist. Each group of outputs with the same dependencies is
    searched over its whole grid in one vectorised evaluation (a model that solves an equation per
    point, over a sub-grid; memoised per scene)."""
    if scene.key in _SINGULAR:
        return _SINGULAR[scene.key]
    sc = scene.scene
    groups: dict[tuple[int, ...], list[str]] = {}
    for output in sc.readouts:
        if output.special:
            dep_axes = tuple(i for i, a in enumerate(sc.axes) if a.param in sc.model.deps_of(output.name, sc.effects))
            groups.setdefault(dep_axes, []).append(output.name)
    found: dict[str, list[tuple[int, ...]]] = {}
    solved = sc.model.is_numerical(sc.effects)
    for dep_axes, names in groups.items():
        searched = _search_stops(tuple(sc.axes[i].count for i in dep_axes), SOLVED_SEARCH_POINTS if solved else None)
        shape = tuple(len(ks) for ks in searched)
        if math.prod(shape) > 2_000_000:
            raise NotImplementedError(f"{names}: {math.prod(shape)} points is too many to search")
        grids = np.meshgrid(*(sc.axes[i].values()[ks] for i, ks in zip(dep_axes, searched)), indexing="ij")
        inputs = {k: np.full(shape, v) for k, v in stop_inputs(sc, sc.default_stops).items()}
        for i, grid in zip(dep_axes, grids):
            inputs[sc.axes[i].param] = grid
        values = sc.model.evaluate(inputs, wanted=names, effects=sc.effects)
        for name in names:
            bad = ~np.isfinite(np.broadcast_to(np.asarray(values[name], float), shape))
            found[name] = []
            for where in zip(*np.nonzero(bad)):
                stops = list(sc.default_stops)
                for i, ks, k in zip(dep_axes, searched, where):
                    stops[i] = ks[k]
                found[name].append(tuple(stops))
    _SINGULAR[scene.key] = found
    return found
