"""The markup that makes pages draw alike in every engine, checked in the HTML the build writes (no browser):

- a numbered display, one equation or a list, carries its number outside the math, in a box of its own
  after the formula (Temml's \\tag is a table cell that Chromium, Firefox and WebKit each put elsewhere);
- inline math may break after a top-level relation (no browser breaks a line inside a <math>), never before
  the punctuation that follows it;
- a dot of a figure is a stroke too short to see but not of zero length (WebKit paints `M x,y h0` with a
  non-scaling stroke as a block over the whole plot).

How they look in each engine is checked in test_engines.py.
"""

from __future__ import annotations

import math
import re
from decimal import Decimal

import pytest

from sitegen.content.markdown_ext import Extracted, fill_slots, markdown_to_html
from sitegen.content.math import convert_math
from sitegen.content.mathml import breakable
from sitegen.render.svg import dot_step, format_dots


def _html(text: str) -> str:
    extracted = Extracted()
    html = markdown_to_html(text, "page.md", 1, extracted)
    mathml, errors = convert_math(extracted.maths)
    assert not errors, errors
    return fill_slots(html, extracted, mathml, scenes=[])


def _number_box(html: str) -> re.Match:
    match = re.search(r'<div class="(equation[^"]*)"( id="[^"]+")?>(.*?)<span class="eqno">([^<]*)</span></div>', html)
    assert match, html
    return match


def test_a_numbered_equation_has_its_number_after_the_math():
    box = _number_box(_html("$$\nF = m a\n$$ {#eq-second}\n"))
    assert box[1] == "equation numbered" and box[2] == ' id="eq-second"' and box[4] == "(1)"
    assert box[3].startswith("<math") and box[3].endswith("</math>") and box[3].count("<math") == 1
    assert "tml-tag" not in box[0] and "<mtable" not in box[0]


def test_a_numbered_list_has_its_number_after_its_items():
    html = _html("$$\nx = 1\n$$ {#eq-first}\n\n$$\na = b, \\qquad c = d\n$$ {#eq-pair}\n")
    box = re.search(r'<div class="equation list numbered" id="eq-pair"><span class="items">(.*?)</span>', html)
    assert box and box[1].count("<math") == 2, html
    assert _number_box(html[box.start() :])[4] == "(2)"


@pytest.mark.parametrize("tag,shown", [("\\tag{2a}", "(2a)"), ("\\tag*{A}", "A")], ids=["tag", "tag-star"])
def test_a_hand_written_tag_is_shown_as_a_number_is(tag, shown):
    box = _number_box(_html(f"$$\nE = m c^2 {tag}\n$$\n"))
    assert box[1] == "equation numbered" and box[2] is None and box[4] == shown
    assert "tml-tag" not in box[0] and "<mtable" not in box[0]


def test_an_unnumbered_display_has_no_number_box():
    html = _html("$$\nF = m a\n$$\n")
    assert '<div class="equation"><math' in html and "eqno" not in html and "numbered" not in html


def test_inline_math_breaks_after_its_relations():
    html = _html("so $\\Delta K = \\tfrac12 \\mu\\,(1-e)(1+e) \\le K$ is lost.\n")
    pieces = re.findall(r"<math>.*?</math>", html)
    assert len(pieces) == 3 and html.count("<wbr>") == 2, html
    assert pieces[0].endswith("<mo>=</mo></mrow></math>") and pieces[1].endswith("<mo>≤</mo></mrow></math>")


@pytest.mark.parametrize(
    "text,kept",
    [
        ("the restitution $e$. The", '<span class="nobreak"><math><mi>e</mi></math>.</span> The'),
        ("with $e$), then", '<span class="nobreak"><math><mi>e</mi></math>),</span> then'),
        ("so $a = b$; then", '<wbr><span class="nobreak"><math><mrow><mi>b</mi></mrow></math>;</span> then'),
    ],
    ids=["full-stop", "bracket-comma", "broken-formula"],
)
def test_inline_math_keeps_the_punctuation_after_it_on_its_line(text, kept):
    """Every engine may break a line between a <math> and a full stop: the formula's last piece and the
    punctuation after it are one unbreakable run."""
    assert kept in _html(text + "\n")


def test_inline_math_before_a_word_is_left_as_it_is():
    assert "nobreak" not in _html("the restitution $e$ and the mass $m$\n")


@pytest.mark.parametrize(
    "mathml",
    [
        "<math><mi>x</mi></math>",  # nothing to break after
        "<math><mrow><msub><mi>a</mi><mrow><mi>i</mi><mo>=</mo><mn>1</mn></mrow></msub><mi>b</mi></mrow></math>",
        "<math><mrow><mi>a</mi><mo>+</mo><mi>b</mi><mo>=</mo></mrow></math>",  # a relation last
        "<math><mrow><mi>a</mi><mo>=</mo></mrow><mrow><mi>b</mi></mrow></math>",  # not one row
    ],
    ids=["one-symbol", "nested-relation", "relation-last", "two-rows"],
)
def test_inline_math_without_a_top_level_relation_is_left_whole(mathml):
    assert breakable(mathml) == mathml


@pytest.mark.parametrize("scale", [1e-5, 0.0695, 0.6825, 1.0, 4.4778, 20.0, 375.2637, 5e4, 3e7])
def test_a_dot_is_a_short_stroke_in_any_axes(scale):
    """Between 0.005 and 0.05 SVG units long whatever the axes' scale, written without an exponent."""
    step = dot_step(scale)
    assert re.fullmatch(r"0\.0*1|10*", step), step
    length = float(step) * scale
    assert 0.005 <= length < 0.05 + 1e-12, (step, length)
    assert math.log10(float(step)) == int(Decimal(step).log10())  # a power of ten


def test_the_dots_of_a_layer_are_strokes_of_that_step():
    assert format_dots([(0.5, -1.25), (2.0, 0.0)], "0.001") == "M0.5,-1.25h0.001 M2,0h0.001"
