"""Every scene tells the truth at every stop: each scene of the book swept in Chromium, as a reader
would, at the corners of its slider box and at seeded random stops.

At each stop: no readout shows a non-zero value as zero (the model's own value decides; a quantity
that takes both signs over the sweep may round to zero near its sign change), no number readout is
longer than WIDTH_BUDGET characters or wider than its box, and every dash carries the model's reason
(a tooltip, and text that screen readers read). Over the sweep, a one-signed number readout keeps its
significant digits: their count varies by at most DIGIT_SPREAD (fixed decimals over values that span
decades give "0.179 µm" and "1438.5919 µm"; integer counts are exact at every digit and exempt, and so
are outputs the page computes from a verified expression, which keep fixed decimals). At the defaults and at a random
stop, moving any slider from its first to its last stop changes something a reader sees: a readout, a layer of the
figure, or a note under it (the scale of a normalised figure).
"""

from __future__ import annotations

import itertools
import math
import random
import re

import numpy as np
import pytest
from browser import FIGURES, BookScene, book, describe_stop, front, load, new_page, stop_inputs

from sitegen.compute.structure import structured_pieces

PAGES, SCENES = book()
WIDTH_BUDGET = 18  # characters of a number readout, value and unit ("−123.4 mJ/m³", "2.251 × 10⁻⁷ μc²A²")
DIGIT_SPREAD = 3
CORNERS = 16  # at most this many corners of the slider box per scene (a seeded choice beyond)
RANDOM_STOPS = 12
DASH = "—"
_ZERO = re.compile(r"^[−-]?0(\.0+)?(?![\d.])")

# Everything a reader sees of a scene, read in one round trip, after moving controls ([param, value]).
_SEEN_JS = """([sceneId, positions]) => {
  const root = document.getElementById(sceneId);
  const seen = () => ({
    readouts: [...root.querySelectorAll('[data-out]')].map(el => {
      const described = el.getAttribute('aria-describedby');
      const note = described ? document.getElementById(described) : null;
      return {name: el.dataset.out, text: el.textContent, title: el.getAttribute('title') || '',
              described: note ? note.textContent : '', overflows: el.scrollWidth > el.clientWidth + 1};
    }),
    panel: (el => el.scrollWidth > el.clientWidth + 1)(root.querySelector('.readouts')),
    layers: [...root.querySelectorAll('[data-layer]')].map(el =>
      el.dataset.layer + ':' + (el.getAttribute('points') || el.getAttribute('d') || el.textContent)),
  });
  return JSON.stringify(positions.map(pairs => {
    pairs.forEach(([param, v]) => {
      const el = root.querySelector(`[data-param="${param}"]`);
      if (el.tagName === 'FIELDSET') {
        const radio = el.querySelector(`input[type="radio"][value="${v}"]`);
        radio.checked = true;
        radio.dispatchEvent(new Event('change', {bubbles: true}));
      } else {
        el.value = v;
        el.dispatchEvent(new Event('input', {bubbles: true}));
      }
    });
    return seen();
  }));
}"""


def _control_value(axis, k: int) -> str:
    if axis.kind == "range":
        text = format(axis.stop(k).normalize(), "f")
        return "0" if text == "-0" else text
    return str(k)


def sweep_stops(scene: BookScene) -> list[tuple[int, ...]]:
    """The corners of the slider box (a seeded choice of CORNERS when there are more) and RANDOM_STOPS
    seeded random stops, each a full slider position."""
    rng = random.Random(scene.key)
    highest = [a.count - 1 for a in scene.axes]
    corners = [tuple(c) for c in itertools.product(*({0, h} for h in highest))]
    if len(corners) > CORNERS:
        corners = rng.sample(corners, CORNERS)
    randoms = [tuple(rng.randrange(a.count) for a in scene.axes) for _ in range(RANDOM_STOPS)]
    return list(dict.fromkeys([scene.defaults, *corners, *randoms]))


def _see(page, scene: BookScene, positions: list[tuple[int, ...]]) -> list[dict]:
    moves = [[[a.param, _control_value(a, k)] for a, k in zip(scene.axes, stops)] for stops in positions]
    return __import__("json").loads(page.evaluate(_SEEN_JS, [scene.dom_id, moves]))


def _model_values(scene: BookScene, positions) -> dict[str, np.ndarray]:
    """The model's own value of every number readout at each position (n values per output)."""
    sc = scene.scene
    names = [o.name for o in sc.readouts if not o.is_text]
    rows = [sc.model.evaluate(stop_inputs(sc, stops), wanted=names, effects=sc.effects) for stops in positions]
    return {name: np.array([float(np.asarray(row[name])) for row in rows]) for name in names}


def _where(scene: BookScene, stops) -> str:
    return ", ".join(f"{a.param}={describe_stop(scene, a.param, k)}" for a, k in zip(scene.axes, stops))


def readout_problems(scene: BookScene, stops, seen: dict, values: dict[str, float], signed: set[str]) -> list[str]:
    """What is wrong with the readouts a reader sees at one stop."""
    outputs = {o.name: o for o in scene.scene.readouts}
    problems = ["the readouts overflow their panel"] if seen["panel"] else []
    for readout in seen["readouts"]:
        name, text, output = readout["name"], readout["text"], outputs[readout["name"]]
        if text.startswith(DASH) and not (readout["title"].strip() and readout["described"].strip()):
            problems.append(
                f"{name} shows {text!r} without a reason (title {readout['title']!r}, "
                f"described {readout['described']!r})"
            )
        if output.is_text or text == output.special:
            continue
        if len(text) > WIDTH_BUDGET:
            problems.append(f"{name} shows {text!r}: {len(text)} characters, more than {WIDTH_BUDGET}")
        if readout["overflows"]:
            problems.append(f"{name} shows {text!r}, wider than its box")
        value = values[name]
        # zero to within its accuracy (`floor`, for an output shown to significant digits) is zero
        if _ZERO.match(text) and math.isfinite(value) and abs(value) > output.floor and name not in signed:
            problems.append(f"{name} shows {text!r} for the non-zero value {value:.6g}")
    return [f"[{_where(scene, stops)}] {p}" for p in problems]


@pytest.fixture(scope="module")
def scene_pages(chromium, built_site):
    """One loaded page per book page (file://), shared by the module's tests."""
    pages = {}

    def _get(scene: BookScene):
        name = scene.page.output_name
        if name not in pages:
            pages[name] = new_page(chromium)
            load(pages[name], (built_site / name).as_uri())  # with every scene's data come
        return front(pages[name])

    return _get


@pytest.mark.parametrize("scene", SCENES, ids=[s.key for s in SCENES])
def test_every_stop_tells_the_truth(scene_pages, scene):
    """At the corners and at random stops: no non-zero value shown as zero, no readout too wide, every
    dash with its reason."""
    positions = sweep_stops(scene)
    seen = _see(scene_pages(scene), scene, positions)
    values = _model_values(scene, positions)
    # A quantity that takes both signs passes through zero: near there it rounds to zero at its digits.
    signed = {name for name, v in values.items() if np.nanmin(v) < 0 < np.nanmax(v)}
    problems = []
    for k, (stops, state) in enumerate(zip(positions, seen)):
        problems += readout_problems(scene, stops, state, {n: v[k] for n, v in values.items()}, signed)
    problems += digit_spread_problems(scene, seen, signed)
    assert not problems, f"{len(problems)} problems:\n" + "\n".join(problems[:15])


def significant_digits(text: str) -> int:
    """How many significant digits a shown number has ("0.0120 m" 3, "1.234 × 10⁻⁵" 4; 0 for zero)."""
    number = re.match(r"[−-]?([\d.]+)", text)
    return len(number[1].replace(".", "").lstrip("0")) if number else 0


def digit_spread_problems(scene: BookScene, seen: list[dict], signed: set[str]) -> list[str]:
    """One-signed, non-integer number readouts whose count of significant digits varies by more than DIGIT_SPREAD."""
    problems = []
    computed = structured_pieces(scene.scene, [o.name for o in scene.scene.readouts])
    for output in scene.scene.readouts:
        if (
            output.is_text
            or output.name in signed
            or output.name in computed
            or (output.decimals == 0 and not output.digits)
        ):
            continue
        shown = {
            r["text"]
            for state in seen
            for r in state["readouts"]
            if r["name"] == output.name and r["text"] != output.special
        }
        counts = {text: significant_digits(text) for text in shown if significant_digits(text)}
        if counts and max(counts.values()) - min(counts.values()) > DIGIT_SPREAD:
            fewest, most = min(counts, key=counts.get), max(counts, key=counts.get)
            problems.append(
                f"{output.name} shows {fewest!r} and {most!r}: {counts[fewest]} and {counts[most]} significant digits"
            )
    return problems


def figure_deps(scene: BookScene) -> set[str]:
    """The sliders the scene's figure depends on: read by a layer or a note, directly or through an output."""
    model, effects = scene.scene.model, scene.scene.effects
    params = set()
    for layer in FIGURES[scene.scene.spec.figure or model.name].layers(scene.scene):
        for ref in layer.refs():
            if isinstance(ref, str) and ref.startswith("in:"):
                params.add(ref[3:])
            elif isinstance(ref, str) and ref.startswith("out:"):
                params |= set(model.deps_of(ref[4:], effects))
    return params & set(scene.params)


def _figure(state: dict) -> tuple:
    return tuple(state["layers"])


def _visible(state: dict) -> tuple:
    return tuple(r["text"] for r in state["readouts"]) + _figure(state)


@pytest.mark.parametrize("scene", SCENES, ids=[s.key for s in SCENES])
def test_every_slider_changes_what_a_reader_sees(scene_pages, scene):
    """Each slider, moved from its first to its last stop (from the defaults and from seeded random
    stops), changes what a reader sees, and the figure itself (a layer, or the note giving its scale):
    a slider that moves only numbers beside a normalised figure leaves the figure looking frozen. The
    figure must change with every slider it depends on (through its layers and notes); one it does not
    draw at all (a mass beside a force–time curve) may move only numbers. A slider may be inert at some
    stops (a drag's coefficient while the force is a spring): one stop where it acts is enough."""
    drawn = figure_deps(scene)
    rng = random.Random(f"{scene.key}-base")
    bases = [scene.defaults, *(tuple(rng.randrange(a.count) for a in scene.axes) for _ in range(3))]
    frozen, figure_frozen = [], []
    for i, axis in enumerate(scene.axes):
        seen = [
            _see(
                scene_pages(scene),
                scene,
                [tuple(k if j == i else s for j, s in enumerate(base)) for k in (0, axis.count - 1)],
            )
            for base in bases
        ]
        if all(_visible(low) == _visible(high) for low, high in seen):
            frozen.append(axis.param)
        if axis.param in drawn and all(_figure(low) == _figure(high) for low, high in seen):
            figure_frozen.append(axis.param)
    assert not frozen, f"sliders that change nothing a reader sees: {frozen}"
    assert not figure_frozen, f"sliders that leave the figure as it was: {figure_frozen}"
