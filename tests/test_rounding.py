"""One rounding rule wherever a number is shown: to the nearest digit, an exact tie away from zero. A book of
exact decimal ties (0.125 to two decimals, 0.5625 to three, 19.375 to two, and their negatives) shows each as a
table readout (rounded by the build) and as an expression readout (a closed form the page's script evaluates and
rounds), read in Chromium from file:// and http:// after moving the real slider; the build's digit comparison
compares digits by the same rule."""

from __future__ import annotations

import re
import textwrap
from pathlib import Path

import pytest
from browser import SiteServer, load, logged_page

from sitegen.build import BuildConfig, build
from sitegen.models.bubble.compare import shown_difference
from sitegen.physics import Output
from sitegen.site.assemble import scene_data_json

MINUS = "\u2212"
FACTORS = {"u2": (1.0, 2), "u3": (1.0, 3), "n2": (-1.0, 2), "n3": (-1.0, 3), "w2": (19.375, 2), "m2": (-19.375, 2)}
STOPS = ("0", "0.125", "0.5625", "1")  # the slider's stops: every product below is an exact double
EXPECTED = {  # at each stop, what every readout of that output shows (the table's and the expression's)
    "0": {"u2": "0.00", "u3": "0.000", "n2": "0.00", "n3": "0.000", "w2": "0.00", "m2": "0.00"},
    "0.125": {
        "u2": "0.13",
        "u3": "0.125",
        "n2": f"{MINUS}0.13",
        "n3": f"{MINUS}0.125",
        "w2": "2.42",
        "m2": f"{MINUS}2.42",
    },
    "0.5625": {
        "u2": "0.56",
        "u3": "0.563",
        "n2": f"{MINUS}0.56",
        "n3": f"{MINUS}0.563",
        "w2": "10.90",
        "m2": f"{MINUS}10.90",
    },
    "1": {
        "u2": "1.00",
        "u3": "1.000",
        "n2": f"{MINUS}1.00",
        "n3": f"{MINUS}1.000",
        "w2": "19.38",
        "m2": f"{MINUS}19.38",
    },
}

MODEL = '''
"""Exact ties: y = k·s for a few factors k, each as a table (per stop) and as a closed form (the page computes it)."""
from sitegen.physics import Model, Output, Param
from sitegen.physics.structure import Poly, param

FACTORS = {factors!r}


def _linear(k):
    return Poly(lambda c: k * c["s"], ((param("s"), 1),))


class Ties(Model):
    name = "ties"
    title = "Exact ties"
    params = (Param("s", "s", "", 0.0, 0.0, 1.0),)
    outputs = tuple(Output(n, n, "", ("s",), decimals=d) for n, (k, d) in FACTORS.items()) + tuple(
        Output(n + "_x", n + " (closed form)", "", ("s",), decimals=d, structure=_linear(k))
        for n, (k, d) in FACTORS.items()
    )

    def _evaluate(self, x, wanted, effects):
        return {{name: FACTORS[name.removesuffix("_x")][0] * x["s"] for name in wanted}}


class NoFigure:
    label = "no figure"

    def layers(self, scene):
        return []

    def draw(self, scene, tables):
        from sitegen.render.style import new_figure

        return new_figure(0.5)[0]


MODELS = {{"ties": Ties}}
FIGURES = {{"ties": NoFigure()}}
'''


@pytest.fixture(scope="module")
def ties_site(tmp_path_factory) -> Path:
    """The book of ties, built."""
    root = tmp_path_factory.mktemp("ties")
    (root / "models").mkdir()
    (root / "models" / "ties.py").write_text(textwrap.dedent(MODEL.format(factors=FACTORS)))
    (root / "content").mkdir()
    readouts = " ".join([*FACTORS, *(f"{n}_x" for n in FACTORS)])
    (root / "content" / "index.md").write_text(
        f'+++\ntitle = "Ties"\n+++\n\n```scene\nmodel: ties\nslider s: {", ".join(STOPS)} default 0.125\n'
        f"readouts: {readouts}\n```\n"
    )
    build(BuildConfig.at(root), progress=None)
    return root / "build"


def _readouts(page) -> dict[str, str]:
    return page.evaluate(
        "() => Object.fromEntries([...document.querySelectorAll('[data-out]')].map(e "
        "=> [e.dataset.out, e.textContent]))"
    )


def test_the_build_writes_the_ties_as_the_rule_says(ties_site):
    """Without script the page shows the build's texts at the default, s = 0.125; the expression readouts there
    are the build's own evaluation of the closed form, rounded by the same rule."""
    html = (ties_site / "index.html").read_text()
    for name, text in EXPECTED["0.125"].items():
        assert f'data-out="{name}">{text}<' in html and f'data-out="{name}_x">{text}<' in html
    data = scene_data_json((ties_site / re.search(r'data-src="([^"]+)"', html)[1]).read_bytes())
    assert '"expr"' in data  # the _x outputs are computed by the page, not looked up


@pytest.mark.parametrize("transport", ["file", "http"])
def test_ties_show_the_same_digits_in_both_kinds_of_readout_in_chromium(ties_site, chromium, transport):
    """The slider moved by the keyboard to its first stop, then from stop to stop: at each, the table readout and
    the expression readout of every output show the digits of the rule (0.125 → 0.13, 0.5625 → 0.563,
    −19.375 → −19.38)."""
    page, errors = logged_page(chromium)
    with SiteServer(ties_site) as server:
        load(page, server.url("index.html") if transport == "http" else (ties_site / "index.html").as_uri())
        slider = page.locator('input[data-param="s"]')
        seen = {}
        slider.press("Home")
        for k, stop in enumerate(STOPS):
            if k:
                slider.press("ArrowRight")
            shown = _readouts(page)
            seen[stop] = {n: (shown[n], shown[f"{n}_x"]) for n in FACTORS}
    page.close()
    assert seen == {stop: {n: (text, text) for n, text in texts.items()} for stop, texts in EXPECTED.items()}
    assert errors == []


@pytest.mark.parametrize(
    "run, reference, near",
    [(0.5625, 0.5625000001, False), (-0.5625, -0.5625000001, False), (0.5625, 0.5624999999, True)],
    ids=["tie-and-above", "negative-tie-and-below", "tie-and-below"],
)
def test_the_build_digit_comparison_reads_a_tie_as_the_page_shows_it(run, reference, near):
    """A run landing exactly on the tie 0.5625 shows 0.563 (away from zero), as the reference just above it does:
    no difference. Against a reference just below, the digits differ, within the error of the boundary: near."""
    outputs = (Output("p_x", "x", "", (), decimals=3),)
    assert shown_difference({"x": run}, {"x": reference}, "p", 1e-9, outputs) == ((), ("p_x",) if near else ())


def test_the_script_rounds_as_the_build_does():
    """sitegen.js's toQuantum, run by node, gives shown_integers' counts at 30,000 values on, near and far from a
    half, positive and negative, at 0 to 4 decimals: the same steps on the same doubles."""
    import json
    import re
    import subprocess

    import numpy as np

    from sitegen.compute.quantize import shown_integers
    from sitegen.site.assets import script

    source = script().decode()
    function = re.search(r"  function toQuantum\(v, d\) \{.*?\n  \}\n", source, re.S)[0]
    rng = np.random.default_rng(38)
    halves = (rng.integers(-(10**6), 10**6, 10_000) + 0.5) / 10.0 ** rng.integers(0, 5, 10_000)
    values = np.concatenate([halves, halves * (1 + 1e-15), halves * (1 - 1e-11), rng.uniform(-1e3, 1e3, 10_000)])
    decimals = rng.integers(0, 5, values.size)
    run = subprocess.run(
        [
            "node",
            "-e",
            f"{function}\nconst [v, d] = JSON.parse(require('fs').readFileSync(0, 'utf8'));"
            "process.stdout.write(JSON.stringify(v.map((x, i) => toQuantum(x, d[i]))));",
        ],
        input=json.dumps([values.tolist(), decimals.tolist()]),
        capture_output=True,
        text=True,
        check=True,
    )
    assert json.loads(run.stdout) == shown_integers(values, decimals).tolist()
