"""Helpers for the layout tests: what sticks out of its box, text outside or too small in a figure,
labels over controls, legends over data. Each check is one `page.evaluate` returning a list of
problems (empty when all is well), so that a failing test says what is wrong and where."""

from __future__ import annotations

from a11y import _COLOUR_JS

MIN_FIGURE_TEXT_PX = 8.0  # the smallest text a figure may show, in CSS px, at any width from 320 px
SCRIPT_RATIO = 0.7  # a sub- or superscript may be this much smaller than its line (TeX's is 0.7)

# where(el) and the colour helpers of a11y.py, and two of our own.
_WHERE_JS = (
    _COLOUR_JS
    + r"""
const shown = el => { const b = el.getBoundingClientRect(); return b.width > 0 && b.height > 0 && getComputedStyle(el).visibility !== 'hidden'; };
const overlap = (a, b) => Math.max(0, Math.min(a.right, b.right) - Math.max(a.left, b.left)) * Math.max(0, Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top));
"""
)


# The checks that every engine runs (test_engines.py): function bodies that return their problems.
OVERFLOW_JS = (
    _WHERE_JS
    + r"""
    const problems = [], width = document.documentElement.clientWidth;
    if (document.documentElement.scrollWidth > width) problems.push(`the page scrolls sideways: ${document.documentElement.scrollWidth} > ${width} px`);
    for (const el of document.body.querySelectorAll('*')) {
      if (el.closest('svg') || el.clientWidth <= 1 || !shown(el)) continue;
      const x = getComputedStyle(el).overflowX;
      if (el.scrollWidth <= el.clientWidth + 1 || x === 'visible') continue;
      if (/hidden|clip/.test(x)) problems.push(`${where(el)}: ${el.scrollWidth} px of content cut to ${el.clientWidth} px`);
      else if (!el.classList.contains('scrolls')) problems.push(`${where(el)}: ${el.scrollWidth} px in ${el.clientWidth} px, scrolling without showing it`);
    }
    return problems;
"""
)
# A numbered display (one equation or a list) has its number beside its last line, flush with the right edge
# of its box, clear of the formula. (A display too wide for its box scrolls, its number at the end of the line.)
EQUATION_NUMBERS_JS = (
    _WHERE_JS
    + r"""
    const problems = [];
    for (const box of [...document.querySelectorAll('.equation[id^="eq-"], .equation.numbered')].filter(shown)) {
      const number = box.querySelector(':scope > .eqno');
      if (!number) { problems.push(`${where(box)}: no number of its own beside the formula`); continue; }
      if (box.scrollWidth > box.clientWidth + 1) continue;
      const text = document.createRange();  // the number as drawn (its box grows to fill the margin)
      text.selectNodeContents(number);
      const b = box.getBoundingClientRect(), n = text.getBoundingClientRect();
      const margin = b.right - parseFloat(getComputedStyle(box).paddingRight) - box.clientLeft;
      if (Math.abs(n.right - margin) > 1) problems.push(`${where(box)}: its number ends at ${n.right.toFixed(1)} px, the right margin is at ${margin.toFixed(1)}`);
      const maths = [...box.querySelectorAll('math')].map(m => m.getBoundingClientRect()), last = maths[maths.length - 1];
      if (n.bottom <= last.top || n.top >= last.bottom) problems.push(`${where(box)}: its number (${n.top.toFixed(0)}..${n.bottom.toFixed(0)} px) is not beside the last line (${last.top.toFixed(0)}..${last.bottom.toFixed(0)})`);
      const beside = maths.filter(m => m.bottom > n.top && m.top < n.bottom);
      if (beside.some(m => m.right > n.left - 4)) problems.push(`${where(box)}: its number runs into the formula`);
    }
    return problems;
"""
)

# A fraction in text style (in a sentence, \tfrac, within another fraction's part) has its parts at a script's
# size, about 0.7 of the fraction's own; in display style (a displayed formula, \dfrac, an aligned display) at
# its size. The nearest ancestor that sets a style decides, as MathML Core's math-style does.
FRACTION_SIZES_JS = r"""
    const problems = [], size = el => parseFloat(getComputedStyle(el).fontSize);
    const compact = fraction => {
      for (let el = fraction.parentElement; el; el = el.parentElement) {
        if (el.localName === 'mfrac') return true;
        if (el.hasAttribute('displaystyle')) return el.getAttribute('displaystyle') === 'false';
        if (el.localName === 'math') return el.getAttribute('display') !== 'block';
      }
      return true;
    };
    for (const fraction of document.querySelectorAll('mfrac')) {
      const small = compact(fraction), [low, high] = small ? [0.6, 0.75] : [0.95, 1.05];
      for (const part of fraction.children) {
        const ratio = size(part) / size(fraction);
        if (ratio < low || ratio > high) problems.push(`a fraction in ${small ? 'text' : 'display'} style ("${fraction.textContent.slice(0, 30)}"): a part at ${ratio.toFixed(2)} of its size`);
      }
    }
    return problems;
"""


def overflow_problems(page) -> list[str]:
    """The page scrolling sideways, and any box whose content is wider than it without showing that it
    scrolls (the `scrolls` class the script sets draws a shadow at each edge that hides more)."""
    return page.evaluate("() => {" + OVERFLOW_JS + "}")


def equation_number_problems(page) -> list[str]:
    """Numbered equations whose number is missing, off the right margin, off the last line or on the formula."""
    return page.evaluate("() => {" + EQUATION_NUMBERS_JS + "}")


def figure_problems(page) -> list[str]:
    """Each scene shows exactly one of its figures, whole: inside the scene and the viewport, never in a
    box that scrolls."""
    return page.evaluate(
        "() => {"
        + _WHERE_JS
        + r"""
        const problems = [], width = document.documentElement.clientWidth;
        for (const scene of document.querySelectorAll('figure.scene')) {
          const figures = [...scene.querySelectorAll('svg.scene-svg')].filter(shown);
          if (figures.length !== 1) { problems.push(`${scene.id}: ${figures.length} figures shown`); continue; }
          const r = figures[0].getBoundingClientRect(), s = scene.getBoundingClientRect();
          if (r.left < Math.max(0, s.left) - 0.5 || r.right > Math.min(width, s.right) + 0.5) {
            problems.push(`${scene.id}: figure spans ${r.left.toFixed(0)}..${r.right.toFixed(0)} px, scene ${s.left.toFixed(0)}..${s.right.toFixed(0)}, screen 0..${width}`);
          }
          for (let box = figures[0].parentElement; box !== scene; box = box.parentElement) {
            if (box.scrollWidth > box.clientWidth + 1) problems.push(`${scene.id}: ${where(box)} scrolls sideways`);
          }
        }
        return problems;
      }"""
    )


def svg_text_problems(page, minimum: float = MIN_FIGURE_TEXT_PX) -> list[str]:
    """Text of a shown figure (scenes and diagrams) that reaches outside its SVG, or is drawn smaller
    than `minimum` CSS px (a sub- or superscript: than SCRIPT_RATIO of that)."""
    return page.evaluate(
        "([minimum, ratio]) => {"
        + _WHERE_JS
        + r"""
        const problems = [];
        for (const svg of [...document.querySelectorAll('svg.scene-svg')].filter(shown)) {
          const box = svg.getBoundingClientRect(), scale = box.width / svg.viewBox.baseVal.width;
          const name = (svg.closest('[id]') || svg).id + (svg.classList.contains('narrow') ? ' (narrow)' : '');
          for (const text of svg.querySelectorAll('text')) {
            const r = text.getBoundingClientRect();
            if (!r.width) continue;
            const out = Math.max(box.left - r.left, r.right - box.right, box.top - r.top, r.bottom - box.bottom);
            if (out > 0.5) problems.push(`${name}: "${text.textContent.trim().slice(0, 30)}" reaches ${out.toFixed(1)} px outside the figure`);
            const pieces = [text, ...text.querySelectorAll('tspan')]
              .filter(piece => [...piece.childNodes].some(n => n.nodeType === 3 && n.textContent.trim()))
              .map(piece => [piece.textContent.trim(), parseFloat(getComputedStyle(piece).fontSize) * scale]);
            const line = Math.max(...pieces.map(([, size]) => size));
            if (line < minimum - 0.01) problems.push(`${name}: "${text.textContent.trim().slice(0, 30)}" drawn at ${line.toFixed(1)} px`);
            for (const [words, size] of pieces) {
              if (size < ratio * minimum - 0.01) problems.push(`${name}: "${words.slice(0, 30)}" (in "${text.textContent.trim().slice(0, 30)}") drawn at ${size.toFixed(1)} px`);
            }
          }
        }
        return problems;
      }""",
        [minimum, SCRIPT_RATIO],
    )


def text_collision_problems(page) -> list[str]:
    """Pieces of text of a shown figure that overlap one another (point labels, titles, legends, ticks).

    A text's box is its glyphs' box: the browser's box less the top 0.2 em, which holds no glyph but
    an accent (DejaVu Sans: ascent 0.93 em, capitals 0.73 em), on whichever side is up for the text.
    """
    return page.evaluate(
        "() => {"
        + _WHERE_JS
        + r"""
        const problems = [];
        const glyphs = text => {
          const r = text.getBoundingClientRect(), m = text.getScreenCTM();
          const sizes = [text, ...text.querySelectorAll('tspan')].map(t => parseFloat(getComputedStyle(t).fontSize));
          const cut = 0.2 * Math.max(...sizes) * Math.hypot(m.c, m.d);
          const box = {left: r.left, right: r.right, top: r.top, bottom: r.bottom};
          if (Math.abs(m.d) >= Math.abs(m.c)) { if (m.d > 0) box.top += cut; else box.bottom -= cut; }
          else if (m.c > 0) box.left += cut; else box.right -= cut;
          return box;
        };
        for (const svg of [...document.querySelectorAll('svg.scene-svg')].filter(shown)) {
          const name = (svg.closest('[id]') || svg).id + (svg.classList.contains('narrow') ? ' (narrow)' : '');
          const texts = [...svg.querySelectorAll('text')].filter(t => t.textContent.trim() && t.getBoundingClientRect().width)
            .map(t => [t.textContent.trim(), glyphs(t)]);
          for (let i = 0; i < texts.length; i++) for (let j = i + 1; j < texts.length; j++) {
            const covered = overlap(texts[i][1], texts[j][1]);
            if (covered > 2) problems.push(`${name}: "${texts[i][0].slice(0, 20)}" and "${texts[j][0].slice(0, 20)}" overlap by ${covered.toFixed(0)} px²`);
          }
        }
        return problems;
      }"""
    )


def legend_problems(page) -> list[str]:
    """Legends of a shown figure that cover a panel's plotting area (where data is drawn)."""
    return page.evaluate(
        "() => {"
        + _WHERE_JS
        + r"""
        const problems = [];
        for (const svg of [...document.querySelectorAll('svg.scene-svg')].filter(shown)) {
          const name = (svg.closest('[id]') || svg).id + (svg.classList.contains('narrow') ? ' (narrow)' : '');
          const panels = [...svg.querySelectorAll('g[id*="-axes_"]')].map(g => g.querySelector('path')).filter(Boolean);
          for (const legend of svg.querySelectorAll('g[id*="-legend_"]')) {
            const r = legend.getBoundingClientRect();
            for (const panel of panels) {
              const covered = overlap(r, panel.getBoundingClientRect());
              if (covered > 2) problems.push(`${name}: a legend ("${legend.textContent.trim().slice(0, 30)}") covers ${covered.toFixed(0)} px² of a panel`);
            }
          }
        }
        return problems;
      }"""
    )


def control_label_problems(page) -> list[str]:
    """A slider's label, the slider and its value text that overlap one another (text measured where
    it is drawn, which may be beyond its element's box)."""
    return page.evaluate(
        "() => {"
        + _WHERE_JS
        + r"""
        const problems = [];
        const extent = el => {
          if (el.localName === 'input') return el.getBoundingClientRect();
          const range = document.createRange();
          range.selectNodeContents(el);
          return range.getBoundingClientRect();
        };
        for (const control of document.querySelectorAll('[data-scene] .control')) {
          const parts = [...control.querySelectorAll(':scope > label, :scope > input, :scope > output, :scope > legend, :scope > .options')].filter(shown);
          for (let i = 0; i < parts.length; i++) for (let j = i + 1; j < parts.length; j++) {
            const covered = overlap(extent(parts[i]), extent(parts[j]));
            if (covered > 1) problems.push(`${where(control)}: ${parts[i].localName} "${parts[i].textContent.trim()}" overlaps ${parts[j].localName} by ${covered.toFixed(0)} px²`);
          }
        }
        return problems;
      }"""
    )
