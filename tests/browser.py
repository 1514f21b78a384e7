"""Helpers for the browser tests: Chromium, a local web server, and scene readouts.

Expected values are computed here independently of the page: from the model registry
(`sitegen.physics.MODELS`) and the slider values read from the DOM, formatted with
`sitegen.compute.quantize.fmt`. Nothing is read from the scene's inline tables.
"""
from __future__ import annotations

import functools
import http.server
import threading
from dataclasses import dataclass
from decimal import ROUND_HALF_EVEN, Decimal
from pathlib import Path
from typing import Iterable, Mapping

import numpy as np

from sitegen.compute.quantize import fmt
from sitegen.site.assemble import with_unit
from sitegen.content.pages import Page, discover_pages, read_page
from sitegen.physics import MODELS

ROOT = Path(__file__).resolve().parents[1]

CHROMIUM = "/usr/bin/chromium"
# We run as root (no sandbox); without the networking flags Chromium phones Google hosts.
LAUNCH_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--no-first-run",
    "--disable-sync",
]


def launch(playwright, **options):
    """Debian's Chromium, headless (Playwright cannot download its own browsers here)."""
    return playwright.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS, **options)


# --- the book's pages, from the sources (used to parametrize at collection time) ---------------


def source_pages() -> list[Page]:
    """Every page of the book as read from content/ (the built site is checked against these)."""
    pages = []
    for path in discover_pages(ROOT / "content"):
        page, errors = read_page(path, ROOT)
        assert page is not None and not errors, errors
        pages.append(page)
    return pages


# --- a local web server -------------------------------------------------------------------------


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):  # noqa: A002 - signature fixed by the base class
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

    def __enter__(self) -> "SiteServer":
        self.thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self.httpd.shutdown()
        self.httpd.server_close()
        self.thread.join(timeout=5)

    def url(self, name: str) -> str:
        return f"{self.origin}/{name}"


# --- sliders ------------------------------------------------------------------------------------


def _decimals(value: Decimal) -> int:
    return max(0, -value.normalize().as_tuple().exponent)


def plain(value: Decimal) -> str:
    """A decimal as a plain string, as an <input> value would hold it ('10', '0.25', '-5')."""
    text = format(value.normalize(), "f")
    return "0" if text == "-0" else text


@dataclass(frozen=True)
class Slider:
    """A native range input of a scene, as found in the DOM."""

    scene_id: str  # the scene's id without the "scene-" prefix
    param: str
    dom_id: str
    lo: Decimal
    hi: Decimal
    step: Decimal
    value: str  # the input's current .value
    valuetext: str  # aria-valuetext
    shown: str | None  # text of <output data-value-of=param>, if any
    label: str | None  # text of <label for=dom_id>, if any

    @property
    def selector(self) -> str:
        return f"#{self.dom_id}"

    @property
    def count(self) -> int:
        return int((self.hi - self.lo) / self.step) + 1

    @property
    def decimals(self) -> int:
        """Digits needed to write every stop exactly (as the build writes the slider text)."""
        return max(_decimals(self.lo), _decimals(self.step))

    def stop(self, index: int) -> Decimal:
        """The exact value of stop `index`."""
        return self.lo + self.step * index

    def index_of(self, value: str | Decimal) -> int:
        """The stop nearest `value` (the value a range input holds is always on a stop)."""
        k = ((Decimal(value) - self.lo) / self.step).to_integral_value(ROUND_HALF_EVEN)
        return int(min(self.count - 1, max(0, k)))

    @property
    def index(self) -> int:
        return self.index_of(self.value)

    @property
    def exact(self) -> Decimal:
        """The current value, exactly (snapped to its stop)."""
        return self.stop(self.index)

    def on_grid(self) -> bool:
        """Whether the input's value is (to float precision) one of the stops."""
        return abs(Decimal(self.value) - self.exact) <= abs(self.step) * Decimal("1e-9")

    def spread(self, n: int = 8) -> list[int]:
        """Stop indices to visit: first, last, the default is added by callers, and `n` spread ones."""
        last = self.count - 1
        return sorted({0, last, *(round(i * last / (n + 1)) for i in range(1, n + 1))})


# The helpers below run one page.evaluate() each: resolving a Playwright locator costs several
# milliseconds on the chapter's large DOM, page.evaluate about one.
_ROOT_JS = "const root = document.getElementById('scene-' + sceneId); if (!root) throw new Error('no scene ' + sceneId);"
_SLIDERS_JS = """[...root.querySelectorAll('input[type="range"][data-param]')].map(el => {
  const out = root.querySelector(`output[data-value-of="${el.dataset.param}"]`);
  const label = el.id ? document.querySelector(`label[for="${el.id}"]`) : null;
  return {
    param: el.dataset.param, id: el.id, min: el.getAttribute('min'), max: el.getAttribute('max'),
    step: el.getAttribute('step'), value: el.value, valuetext: el.getAttribute('aria-valuetext'),
    shown: out ? out.textContent : null, label: label ? label.textContent : null,
  };
})"""
_READOUTS_JS = "Object.fromEntries([...root.querySelectorAll('[data-out]')].map(el => [el.dataset.out, el.textContent]))"
_LAYERS_JS = "Object.fromEntries([...root.querySelectorAll('svg [data-layer]')].map(el => [el.dataset.layer, el.getAttribute('points')]))"


def _in_scene(page, scene_id: str, body: str, arg=None):
    """Evaluate `body` (an expression over `root`, the scene element, and `arg`) in the page."""
    return page.evaluate(f"([sceneId, arg]) => {{ {_ROOT_JS} return {body}; }}", [scene_id, arg])


def scene_root(page, scene_id: str):
    """The scene's <figure> as a Playwright locator."""
    return page.locator(f"#scene-{scene_id}")


def scene_sliders(page, scene_id: str) -> list[Slider]:
    """The scene's sliders in DOM order, with their current values."""
    return _sliders(scene_id, _in_scene(page, scene_id, _SLIDERS_JS))


def _sliders(scene_id: str, rows: list[dict]) -> list[Slider]:
    return [
        Slider(
            scene_id=scene_id,
            param=r["param"],
            dom_id=r["id"],
            lo=Decimal(r["min"]),
            hi=Decimal(r["max"]),
            step=Decimal(r["step"]),
            value=r["value"],
            valuetext=r["valuetext"],
            shown=r["shown"],
            label=r["label"],
        )
        for r in rows
    ]


_SET_JS = "(el, v) => { el.value = v; el.dispatchEvent(new Event('input', {bubbles: true})); }"


def _value_text(value) -> str:
    return plain(value) if isinstance(value, Decimal) else str(value)


def set_slider(page, target, value) -> None:
    """Set a range input's value and fire `input` (as a user's move does).

    `target` is a Locator, an ElementHandle or a CSS selector.
    """
    if isinstance(target, str):
        page.evaluate(f"([sel, v]) => ({_SET_JS})(document.querySelector(sel), v)", [target, _value_text(value)])
    else:
        target.evaluate(_SET_JS, _value_text(value))


def set_sliders(page, scene_id: str, values: Mapping[str, object]) -> None:
    """set_slider() for several sliders of a scene ({param: value}, in that order), one round trip."""
    pairs = [[param, _value_text(v)] for param, v in values.items()]
    _in_scene(
        page,
        scene_id,
        f"""arg.forEach(([param, v]) => ({_SET_JS})(root.querySelector(`input[type="range"][data-param="${{param}}"]`), v))""",
        pairs,
    )


def readouts(page, scene_id: str) -> dict[str, str]:
    """Every readout of the scene: data-out name -> its text."""
    return _in_scene(page, scene_id, _READOUTS_JS)


def scene_state(page, scene_id: str) -> tuple[list[Slider], dict[str, str]]:
    """scene_sliders() and readouts() read together, in one round trip."""
    rows, texts = _in_scene(page, scene_id, f"[{_SLIDERS_JS}, {_READOUTS_JS}]")
    return _sliders(scene_id, rows), texts


def layer_points(page, scene_id: str) -> dict[str, str]:
    """The `points` attribute of every moving layer of the scene's figure."""
    return _in_scene(page, scene_id, _LAYERS_JS)


# --- expected values ----------------------------------------------------------------------------


def expected_readouts(
    scene_name: str,
    slider_values: Mapping[str, Decimal | str | float],
    names: Iterable[str] | None = None,
    fixed: Mapping[str, Decimal | float] | None = None,
) -> dict[str, str]:
    """The readout texts the page must show, computed from the model itself.

    `slider_values` maps every slider's parameter to its (exact) value. Parameters without a
    slider take the scene's `fixed` values, else the model defaults. (The book fixes no
    parameters today; callers pass the scene's `fix` lines from its source so that a future
    `fix` line is honoured rather than silently tested against the defaults.)
    """
    model = MODELS[scene_name]()
    inputs = {**{k: float(v) for k, v in (fixed or {}).items()}, **{k: float(Decimal(str(v))) for k, v in slider_values.items()}}
    wanted = tuple(names) if names is not None else tuple(o.name for o in model.outputs)
    values = model.evaluate(inputs, wanted=wanted)
    texts = {}
    for name in wanted:
        output = model.output(name)
        if getattr(output, "size", 0):
            raise NotImplementedError(f"output {name!r} is a vector; these helpers know scalar readouts only")
        value = float(np.asarray(values[name]))
        if np.isinf(value) and getattr(output, "special", ""):
            texts[name] = output.special  # an infinite value shown in words, without a unit
            continue
        if not np.isfinite(value):
            raise ValueError(f"output {name!r} of {scene_name} is {value} at {dict(inputs)}")
        if output.labels:
            texts[name] = output.labels[int(value)]
        else:
            texts[name] = with_unit(fmt(value, output.decimals), output.unit)
    return texts


def expected_slider_text(scene_name: str, slider: Slider, index: int | None = None) -> str:
    """A slider's value as the page must announce it (aria-valuetext) and show it beside it."""
    index = slider.index if index is None else index
    unit = MODELS[scene_name].param(slider.param).unit
    value = slider.stop(index)
    digits = slider.decimals
    text = fmt(float(value), digits)
    # fmt goes through a float; make sure that cannot have changed the exact decimal written.
    assert Decimal(text.replace("\u2212", "-")) == value, (text, value)
    return with_unit(text, unit)
