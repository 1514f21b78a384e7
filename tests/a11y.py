"""Helpers for the accessibility tests: axe-core in the page, and the measurements axe leaves out
(focus rings, target sizes, overflow at 360 px, colour contrast worked out from computed styles).

Everything here runs inside the page through one `page.evaluate` per check and returns plain
lists of problems, so that a failing test prints what is wrong and where.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
AXE = ROOT / "node_modules" / "axe-core" / "axe.min.js"
# WCAG 2.0, 2.1 and 2.2 at levels A and AA, and axe's best practices.
AXE_TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "wcag22aa", "best-practice"]

MIN_TARGET = 24  # CSS px, WCAG 2.2 SC 2.5.8 (target size, minimum)
TEXT_CONTRAST = 4.5  # SC 1.4.3 for normal text; 3 for large text
LARGE_TEXT_CONTRAST = 3.0
FOCUS_CONTRAST = 3.0  # SC 1.4.11: a focus indicator is a non-text user-interface part


def run_axe(page) -> list[dict]:
    """axe-core's violations on the page as it is now (WCAG 2.x A/AA and best practices)."""
    page.add_script_tag(path=str(AXE))
    return page.evaluate(
        """tags => axe.run(document, {runOnly: {type: 'tag', values: tags}, resultTypes: ['violations']})
                   .then(result => result.violations.map(v => ({
                       id: v.id, impact: v.impact, help: v.help,
                       nodes: v.nodes.slice(0, 5).map(n => ({target: n.target.join(' '), summary: n.failureSummary})),
                       count: v.nodes.length})))""",
        AXE_TAGS,
    )


def describe_violations(violations: list[dict]) -> str:
    """axe's findings as readable lines: rule, impact, how many nodes, and the first few."""
    lines = []
    for v in violations:
        lines.append(f"{v['id']} ({v['impact']}, {v['count']} nodes): {v['help']}")
        lines += [f"    {n['target']}: {' '.join(n['summary'].split())}" for n in v["nodes"]]
    return "\n".join(lines)


# Shared JavaScript: relative luminance, contrast, and the opaque colour behind an element
# (its own and its ancestors' background colours composited, the page's canvas last).
_COLOUR_JS = r"""
const parse = text => {
  const m = text.match(/rgba?\(([^)]+)\)/);
  if (!m) return null;
  const p = m[1].split(/[ ,/]+/).filter(Boolean).map(Number);
  return [p[0], p[1], p[2], p.length > 3 ? p[3] : 1];
};
const over = (top, bottom) => {
  const a = top[3] + bottom[3] * (1 - top[3]);
  if (!a) return [0, 0, 0, 0];
  return [0, 1, 2].map(i => (top[i] * top[3] + bottom[i] * bottom[3] * (1 - top[3])) / a).concat([a]);
};
const luminance = c => {
  const [r, g, b] = c.slice(0, 3).map(v => { v /= 255; return v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055)
    ** 2.4; });
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
};
const contrast = (a, b) => {
  const [hi, lo] = [luminance(a), luminance(b)].sort((x, y) => y - x);
  return (hi + 0.05) / (lo + 0.05);
};
const canvas = () => {
  const root = parse(getComputedStyle(document.documentElement).backgroundColor);
  const body = parse(getComputedStyle(document.body).backgroundColor);
  if (body && body[3] > 0) return over(body, [255, 255, 255, 1]);
  return root && root[3] > 0 ? over(root, [255, 255, 255, 1]) : [255, 255, 255, 1];
};
const backgroundOf = el => {
  const layers = [];
  for (let node = el; node && node.nodeType === 1; node = node.parentElement) {
    const c = parse(getComputedStyle(node).backgroundColor);
    if (c && c[3] > 0) layers.push(c);
    if (c && c[3] === 1) break;
  }
  let colour = canvas();
  for (const layer of layers.reverse()) colour = over(layer, colour);
  return colour;
};
const where = el => {
  const parts = [];
  for (let node = el; node && node.nodeType === 1 && parts.length < 4; node = node.parentElement) {
    let part = node.localName;
    if (node.id) { parts.unshift(part + '#' + node.id); break; }
    // the root's classes are the page script's state (the first Tab lays every block out), not where
    if (node.classList.length && node !== document.documentElement) part += '.' + [...node.classList].join('.');
    parts.unshift(part);
  }
  return parts.join(' > ');
};
const visible = el => {
  // The content of a closed <details> keeps its boxes in Chromium but is neither shown nor focusable.
  if (el.closest('details:not([open]) > :not(summary)')) return false;
  const style = getComputedStyle(el);
  const box = el.getBoundingClientRect();
  return style.visibility !== 'hidden' && style.display !== 'none' && box.width > 0 && box.height > 0;
};
"""


def text_contrast_problems(page) -> list[str]:
    """Every visible piece of text (outside the SVG figures) whose colour misses WCAG AA contrast
    against the colour behind it. The figures are checked by axe and sit on a light card."""
    return page.evaluate(
        "([normal, large]) => {"
        + _COLOUR_JS
        + r"""
        const problems = [];
        const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
        const seen = new Set();
        for (let text = walker.nextNode(); text; text = walker.nextNode()) {
          const el = text.parentElement;
          if (!text.textContent.trim() || seen.has(el) || el.closest('svg, script, style') || !visible(el)) continue;
          seen.add(el);
          const style = getComputedStyle(el);
          const colour = parse(style.color);
          const size = parseFloat(style.fontSize), bold = parseInt(style.fontWeight, 10) >= 700;
          const needed = size >= 24 || (bold && size >= 18.66) ? large : normal;
          const ratio = contrast(over(colour, backgroundOf(el)), backgroundOf(el));
          if (ratio < needed)
            problems.push(`${where(el)} "${text.textContent.trim().slice(0, 30)}": ${ratio.toFixed(2)} < ${needed} ` +
              `(${style.color} on rgb(${backgroundOf(el).slice(0, 3).map(Math.round)}))`);
        }
        return problems;
      }""",
        [TEXT_CONTRAST, LARGE_TEXT_CONTRAST],
    )


def tab_stops(page) -> list[str]:
    """Descriptions of the elements the Tab key should reach, in document order (one per radio group)."""
    return page.evaluate(
        "() => {"
        + _COLOUR_JS
        + r"""
        const stops = [], groups = new Set();
        for (const el of document.querySelectorAll('a[href], input, button, select, textarea, summary, [tabindex]')) {
          if (el.disabled || el.tabIndex < 0 || !visible(el)) continue;
          if (el.type === 'radio') {
            if (groups.has(el.name)) continue;
            groups.add(el.name);
          }
          stops.push(where(el.type === 'radio' ? el.closest('fieldset') || el : el));
        }
        return stops;
      }"""
    )


def focused_element_problems(page, focus_contrast: float = FOCUS_CONTRAST) -> dict:
    """The focused element: where it is, and what is wrong with how its focus is shown."""
    return page.evaluate(
        "minimum => {"
        + _COLOUR_JS
        + r"""
        const el = document.activeElement;
        if (!el || el === document.body) return {where: null, problems: []};
        const name = where(el.type === 'radio' ? el.closest('fieldset') || el : el);
        const style = getComputedStyle(el), problems = [];
        if (!el.matches(':focus-visible')) problems.push('does not match :focus-visible');
        const width = parseFloat(style.outlineWidth);
        if (style.outlineStyle === 'none' || width < 2) {
          problems.push(`focus outline ${style.outlineStyle} ${style.outlineWidth}: not a visible ring`);
        } else {
          const ring = parse(style.outlineColor), behind = backgroundOf(el.parentElement || el);
          const ratio = contrast(over(ring, behind), behind);
          if (ratio < minimum)
            problems.push(`focus ring ${style.outlineColor} has contrast ${ratio.toFixed(2)} < ${minimum}`);
        }
        const box = el.getBoundingClientRect();
        if (box.bottom < 0 || box.top > innerHeight || box.right < 0 || box.left > innerWidth)
          problems.push('focused but off screen');
        return {where: name, problems};
      }""",
        focus_contrast,
    )


def target_size_problems(page, minimum: int = MIN_TARGET) -> list[str]:
    """Pointer targets under `minimum` px that are not spaced as SC 2.5.8 allows. The target of a
    radio button is its label; links inside running text are exempt (SC 2.5.8, 'inline')."""
    return page.evaluate(
        "minimum => {"
        + _COLOUR_JS
        + r"""
        const inline = a => !a.closest('nav, header, footer') && a.closest('p, li, dd, td, figcaption');
        const targets = [];
        for (const el of document.querySelectorAll('a[href], input, button, select, summary')) {
          if (!visible(el) && el.type !== 'radio') continue;
          if (el.localName === 'a' && inline(el)) continue;
          const target = el.type === 'radio' ? el.closest('label') || el : el;
          const box = target.getBoundingClientRect();
          targets.push({name: where(target), box, small: box.width < minimum - 0.01 || box.height < minimum - 0.01});
        }
        const centre = b => [b.left + b.width / 2, b.top + b.height / 2];
        const distanceToBox = ([x, y], b) => Math.hypot(Math.max(b.left - x, 0, x - b.right), Math.max(b.top - y, 0,
          y - b.bottom));
        const problems = [];
        for (const t of targets.filter(t => t.small)) {
          const c = centre(t.box);
          const crowded = targets.filter(u => u !== t && (u.small
            ? Math.hypot(centre(u.box)[0] - c[0], centre(u.box)[1] - c[1]) < minimum
            : distanceToBox(c, u.box) < minimum / 2));
          if (crowded.length) {
            problems.push(`${t.name} is ${t.box.width.toFixed(1)}x${t.box.height.toFixed(1)} px, closer than ` +
              `${minimum} px to ${crowded.map(u => u.name).join(', ')}`);
          }
        }
        return problems;
      }""",
        minimum,
    )


def control_size_problems(page, minimum: int = MIN_TARGET) -> list[str]:
    """Scene controls (sliders, radio labels, play buttons) smaller than `minimum` px either way."""
    return page.evaluate(
        "minimum => {"
        + _COLOUR_JS
        + r"""
        const problems = [];
        for (const el of document.querySelectorAll('[data-scene] input[type="range"], [data-scene] button, ' +
          '[data-scene] input[type="radio"]')) {
          const target = el.type === 'radio' ? el.closest('label') : el;
          const box = target.getBoundingClientRect();
          if (box.width < minimum || box.height < minimum)
            problems.push(`${where(target)}: ${box.width.toFixed(1)}x${box.height.toFixed(1)} px`);
        }
        return problems;
      }""",
        minimum,
    )


def overflow_problems(page) -> list[str]:
    """Elements that stick out of the viewport sideways, unless a scrolling box holds them."""
    return page.evaluate(
        "() => {"
        + _COLOUR_JS
        + r"""
        const problems = [];
        const width = document.documentElement.clientWidth;
        if (document.documentElement.scrollWidth > width)
          problems.push(`the page scrolls sideways: ${document.documentElement.scrollWidth} px > ${width} px`);
        const scrolls = el => { for (let n = el.parentElement; n; n = n.parentElement) {
          if (/auto|scroll|hidden|clip/.test(getComputedStyle(n).overflowX)) return true; } return false; };
        for (const el of document.body.querySelectorAll('*')) {
          if (el.closest('svg') && el.localName !== 'svg') continue;
          const box = el.getBoundingClientRect();
          if (!box.width || (box.right <= width + 0.5 && box.left >= -0.5)) continue;
          if (scrolls(el)) continue;
          problems.push(`${where(el)}: ${box.left.toFixed(0)}..${box.right.toFixed(0)} px outside 0..${width}`);
        }
        return problems.slice(0, 20);
      }"""
    )


def moving_state(page) -> dict:
    """What could move on its own: every layer's geometry, every readout and control value."""
    return page.evaluate(
        r"""() => ({
          layers: [...document.querySelectorAll('svg [data-layer]')].map(e => (e.getAttribute('points') || '')
            + (e.getAttribute('d') || '')),
          readouts: [...document.querySelectorAll('[data-out]')].map(e => e.textContent),
          controls: [...document.querySelectorAll('[data-scene] input')]
            .map(e => e.type === 'radio' ? String(e.checked) : e.value),
          animations: document.getAnimations().map(a => a.animationName || a.transitionProperty || a.constructor.name),
        })"""
    )
