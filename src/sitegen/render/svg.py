"""The static SVG of a figure (matplotlib, byte-stable) with its moving layers spliced in."""

from __future__ import annotations

import io
import math
import re
from dataclasses import dataclass
from decimal import Decimal
from html import escape

import matplotlib.pyplot as plt

from .layers import Layer
from .style import RC

_ID_ATTR = re.compile(r'\bid="([^"]+)"')
_ID_REF = re.compile(r'(url\(#|xlink:href="#|href="#)([^")]+)')
_GROUP_ID = re.compile(r'<g id="([^"]+)"')
_KEPT_GROUP = re.compile(r"(axes|legend)_\d+$")  # tests find a figure's panels and legends by them
_BETWEEN_TAGS = re.compile(r">\s+<")
_TEXT = re.compile(r"<text\b.*?</text>", re.S)
_GEOMETRY = re.compile(r'\b(d|x|y|width|height|transform)="([^"]*)"')
_LONG_NUMBER = re.compile(r"-?\d+\.\d{3,}")
VARIANTS = ("wide", "narrow")  # the figure for a text column, and for a phone (panels stacked)


@dataclass(frozen=True)
class AxesFrame:
    """How data coordinates of one axes map to SVG user units, and its clipping box."""

    matrix: tuple[float, float, float, float]  # (a, d, e, f) of matrix(a 0 0 d e f)
    box: tuple[float, float, float, float]  # x, y, width, height in SVG units


def figure_svg(
    fig, layers: list[Layer], points: list[list[tuple[float, float]]], prefix: str, label: str, variant: str = "wide"
) -> str:
    """Save `fig` as inline SVG, add the layers at the given vertices, and make its ids unique.

    `variant` ("wide" or "narrow") becomes a class, by which the stylesheet shows the one that suits the screen.
    """
    frames = [_frame(fig, ax) for ax in fig.axes]
    buffer = io.StringIO()
    with plt.rc_context(RC):
        fig.savefig(buffer, format="svg", metadata={"Date": None, "Creator": None, "Format": None, "Type": None})
    plt.close(fig)
    svg = buffer.getvalue()
    svg = svg[svg.index("<svg") :]
    svg = re.sub(r"<metadata>.*?</metadata>\s*", "", svg, flags=re.S)
    svg = re.sub(r"\s*<!--.*?-->", "", svg, flags=re.S)  # matplotlib's comments repeat the label TeX
    svg = _compact(svg)
    head = f'class="scene-svg {variant}" role="img" aria-label="{escape(label)}"'
    svg = re.sub(
        r'<svg[^>]*?(viewBox="[^"]+")[^>]*>',
        lambda m: f'<svg xmlns="http://www.w3.org/2000/svg" {m[1]} {head}>',
        svg,
        count=1,
    )
    svg = svg.replace("</svg>", _layers_svg(layers, points, frames) + "</svg>")
    svg = _ID_ATTR.sub(lambda m: f'id="{prefix}-{m[1]}"', svg)
    return _ID_REF.sub(lambda m: f"{m[1]}{prefix}-{m[2]}", svg).strip() + "\n"


def _compact(svg: str) -> str:
    """matplotlib's SVG made smaller and exact to the browser's text layout: one tag a line without indentation
    (lines keep a figure's diff readable), nothing between the <tspan>s of a <text> (there a line break is laid
    out as a space and widens the text's box beyond its glyphs), no ids on groups that nothing refers to (but
    panels and legends), and coordinates to 0.01 pt (a figure is never drawn above 2 px per pt)."""
    svg = _BETWEEN_TAGS.sub(">\n<", svg)
    svg = _TEXT.sub(lambda m: m[0].replace(">\n<", "><"), svg)
    used = {m[2] for m in _ID_REF.finditer(svg)}
    svg = _GROUP_ID.sub(lambda m: f'<g id="{m[1]}"' if m[1] in used or _KEPT_GROUP.match(m[1]) else "<g", svg)
    return _GEOMETRY.sub(lambda m: f'{m[1]}="{_LONG_NUMBER.sub(_rounded, m[2])}"', svg)


def _rounded(match: re.Match) -> str:
    text = f"{float(match[0]):.2f}".rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def _frame(fig, ax) -> AxesFrame:
    height = fig.get_figheight() * 72.0
    (x0, y0), (x1, y1) = ax.transData.transform([(0.0, 0.0), (1.0, 1.0)])
    bbox = ax.get_window_extent()
    matrix = (x1 - x0, -(y1 - y0), x0, height - y0)
    return AxesFrame(
        tuple(round(v, 4) for v in matrix),
        tuple(round(v, 3) for v in (bbox.x0, height - bbox.y1, bbox.width, bbox.height)),
    )


def _layers_svg(layers: list[Layer], points: list[list[tuple[float, float]]], frames: list[AxesFrame]) -> str:
    parts = ['<g class="layers">']
    for index, frame in enumerate(frames):
        members = [(layer, pts) for layer, pts in zip(layers, points) if layer.axes == index]
        if not members:
            continue
        x, y, w, h = frame.box
        a, d, e, f = frame.matrix
        parts.append(f'<clipPath id="layers-clip-{index}"><rect x="{x}" y="{y}" width="{w}" height="{h}"/></clipPath>')
        parts.append(f'<g clip-path="url(#layers-clip-{index})"><g transform="matrix({a} 0 0 {d} {e} {f})">')
        for layer, pts in members:
            attributes = (
                {"fill": "none", **layer.style} if layer.kind == "polyline" else dict(layer.style)
            )  # SVG fills by default
            if layer.kind == "dots":  # a very short stroke with round caps is a dot
                # inline style: matplotlib's stylesheet sets stroke-linecap: butt on every element
                # (merged into the layer's own style: an element may carry one style attribute)
                own = attributes.get("style", "")
                attributes["style"] = (
                    own if "stroke-linecap" in own else "; ".join(filter(None, ["stroke-linecap: round", own]))
                )
                step = dot_step(a)
                shape = f'path data-layer="{layer.name}" data-dot="{step}" d="{format_dots(pts, step)}"'
            else:
                shape = f'{layer.kind} data-layer="{layer.name}" points="{format_points(pts)}" stroke-linejoin="round"'
            style = " ".join(f'{k}="{v}"' for k, v in sorted(attributes.items()))
            parts.append(f'<{shape} {style} vector-effect="non-scaling-stroke"/>')
        parts.append("</g></g>")
    parts.append("</g>")
    return "\n".join(parts)


def format_points(points: list[tuple[float, float]]) -> str:
    """SVG points text with short, stable numbers (the page's script writes the same form)."""
    return " ".join(f"{_short(x)},{_short(y)}" for x, y in points)


def format_dots(points: list[tuple[float, float]], step: str) -> str:
    """SVG path text drawing a dot at every point: a stroke `step` long (see `dot_step`)."""
    return " ".join(f"M{_short(x)},{_short(y)}h{step}" for x, y in points)


def dot_step(scale: float) -> str:
    """The length of a dot's stroke in data units, for an axes of `scale` SVG units per data unit: a power of
    ten between 0.005 and 0.05 SVG units long, too short to see, long enough to stay a stroke in single
    precision. A zero-length stroke (`M x,y h0`) draws a dot in Chromium and Firefox, but WebKit paints
    it, with a non-scaling stroke, as a block over the whole axes."""
    return format(Decimal(1).scaleb(math.floor(math.log10(0.05 / abs(scale)))), "f")


def _short(value: float) -> str:
    text = f"{value:.6g}"
    return "0" if text == "-0" else text
