"""Static diagrams of the accuracy page: work–precision (error against time, the Pareto front as a grey band)
and resolution against bytes.

They take plain points, not bench.json, and draw them in the house style; `figure_svg` turns
them into byte-stable inline SVG. Nothing is written over the data: each panel's legend (with the
ring that marks the chosen setting) sits above it, its title above the legend; point labels are
placed once the layout is fixed, each at the first spot around its point where its measured text
box covers no marker, line or other label, and dropped where there is none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import LogLocator

from . import style as s
from .log_axes import DECADE, minor_ticks, ticks_in_view, tight_layout_measured_once

GREEN, PURPLE, TEAL, BROWN = "#2a7a3b", "#7b3fa0", "#0f7a82", "#8a5a14"
# Eight series told apart by colour and marker (the bubble diagrams have seven solvers).
COLOURS = (s.BLUE, s.ORANGE, GREEN, PURPLE, s.MUTED, s.INK, TEAL, BROWN)
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "h")
LABEL_SIZE = 7.5
LEGEND_SIZE = LABEL_SIZE + 1
MARKER_HALF = 3.5  # pt: half the size of a marker, an obstacle for labels
LINE_HALF = 1.5  # pt: half the width of a line, an obstacle for labels
LABEL_MARGIN = (
    1.0  # pt kept clear round a label: a browser draws a text's box a little taller than matplotlib measures it
)
RING_SIZE = 15  # pt: the ring round the chosen setting
FRONT_WIDTH = 7  # pt: the band that joins the Pareto front


@dataclass(frozen=True)
class Point:
    """One run: x and y in the diagram's units, and the short text written beside it."""

    x: float
    y: float
    text: str = ""
    major: bool = True  # labelled first; a minor label is dropped sooner when space is short


@dataclass(frozen=True)
class Series:
    """One method (or one axis choice): its points in order, joined by a line."""

    name: str
    points: tuple[Point, ...]


@dataclass(frozen=True)
class Panel:
    """One axes: its title, its series, the point to ring as the chosen setting, and an exact point."""

    title: str
    series: tuple[Series, ...]
    chosen: Point | None = None  # drawn with a ring; `chosen.text` names the ring in the legend
    exact: Point | None = None  # a method with no error to plot: a star on the floor
    floor: float = 1e-16  # errors below this are drawn on it
    ceiling: float = 10.0  # errors above this are drawn on it, as an upward triangle
    line: tuple[float, str] | None = None  # a horizontal reference line (y, label)
    xlim: tuple[float, float] | None = None  # fixed limits (shared by panels); None: fit the points
    ylim: tuple[float, float] | None = None
    front: tuple[Point, ...] = ()  # the Pareto front, fastest first: drawn as a grey band under the lines


def work_precision_figure(panels: list[Panel], xlabel: str, ylabel: str, note: str, narrow: bool = False) -> plt.Figure:
    """Log–log panels stacked vertically, one line per series, points labelled, the chosen one ringed.

    `narrow`: the same panels for a phone's width (style.NARROW_WIDTH_IN), the legend in more rows.
    """
    columns = 3 if narrow else 6
    with plt.rc_context(s.RC):
        fig, axes = plt.subplots(
            len(panels), 1, figsize=(s.width(narrow), 0.5 + (4.0 if narrow else 3.6) * len(panels)), squeeze=False
        )
        for ax, panel in zip(axes[:, 0], panels):
            _draw_panel(ax, panel, xlabel, ylabel)
            _legend_and_title(ax, panel, columns)
        _note(fig, note)
        tight_layout_measured_once(fig, rect=(0, 0.025 * (1.6 if narrow else 1), 1, 1), h_pad=1.4)
        for ax, panel in zip(axes[:, 0], panels):
            _annotate(ax, panel)
    return fig


def resolution_figure(panels: list[Panel], note: str, narrow: bool = False) -> plt.Figure:
    """A 2-column grid of panels (one column when `narrow`): interpolation error (in display digits) against bytes
    stored."""
    columns = 1 if narrow else 2
    rows = (len(panels) + columns - 1) // columns
    with plt.rc_context(s.RC):
        fig, axes = plt.subplots(rows, columns, figsize=(s.width(narrow), 0.9 + 2.9 * rows), squeeze=False)
        for ax, panel in zip(axes.ravel(), panels):
            _draw_panel(ax, panel, "bytes stored (float32)", "error ÷ ½ last digit")
            ax.set_title(panel.title, fontsize=9.5, loc="left", color=s.INK)
        for ax in axes.ravel()[len(panels) :]:
            ax.set_visible(False)
        names = [series.name for series in panels[0].series]
        handles = [plt.Line2D([], [], color=COLOURS[i], marker=MARKERS[i], lw=1.5, ms=5) for i in range(len(names))]
        legend = fig.legend(
            handles,
            names,
            loc="upper center",
            ncol=2 if narrow else len(names),
            fontsize=LEGEND_SIZE,
            frameon=False,
            handlelength=1.5,
            columnspacing=1.0,
        )
        _note(fig, note)
        top = 1 - (legend.get_window_extent().height + 6) / (fig.get_figheight() * 72)
        tight_layout_measured_once(fig, rect=(0, 0.03 * (1.6 if narrow else 1), 1, top), h_pad=1.2, w_pad=1.2)
        for ax, panel in zip(axes.ravel(), panels):
            _annotate(ax, panel)
    return fig


def _note(fig, note: str) -> None:
    fig.text(0.01, 0.005, note, fontsize=LABEL_SIZE + 0.5, color=s.MUTED, ha="left", va="bottom", wrap=True)


def _legend_and_title(ax, panel: Panel, columns: int) -> None:
    """The series and the chosen setting's ring in a legend above the axes, and the title above the legend."""
    handles, labels = ax.get_legend_handles_labels()
    if panel.chosen:
        handles.append(plt.Line2D([], [], marker="o", ms=RING_SIZE * 0.7, mfc="none", mec=s.INK, mew=1.8, ls="none"))
        labels.append(panel.chosen.text)
    width = ax.get_window_extent().width
    for ncol in range(min(columns, len(handles)), 0, -1):  # as many columns as fit over the axes
        legend = ax.legend(
            handles,
            labels,
            loc="lower left",
            bbox_to_anchor=(0.0, 1.0),
            ncol=ncol,
            fontsize=LEGEND_SIZE,
            frameon=False,
            handlelength=1.5,
            columnspacing=0.9,
            handletextpad=0.4,
            borderaxespad=0.2,
        )
        if legend.get_window_extent().width <= width:
            break
    height = legend.get_window_extent().height
    ax.set_title(panel.title, fontsize=9.5, loc="left", color=s.INK, pad=height + 0.2 * LEGEND_SIZE + 3)


def _draw_panel(ax, panel: Panel, xlabel: str, ylabel: str) -> None:
    """Axes, lines and markers; labels wait for the final layout (`_annotate`)."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel, fontsize=9)
    ax.set_ylabel(ylabel, fontsize=9)
    ax.tick_params(labelsize=8)
    ax.yaxis.set_major_locator(LogLocator(base=10.0, numticks=8))
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(DECADE)
    for index, series in enumerate(panel.series):
        _draw_series(ax, panel, series, COLOURS[index % len(COLOURS)], MARKERS[index % len(MARKERS)])
    if panel.front:
        ax.plot(
            [p.x for p in panel.front],
            [_clamped(panel, p.y) for p in panel.front],
            color=s.MUTED,
            lw=FRONT_WIDTH,
            alpha=0.3,
            solid_capstyle="round",
            solid_joinstyle="round",
            label="Pareto front",
            zorder=2,
        )
    if panel.exact:
        ax.plot([panel.exact.x], [panel.floor], marker="*", ms=12, color=s.INK, ls="none", zorder=5)
    if panel.line:
        ax.axhline(panel.line[0], color=s.MUTED, lw=1.0, ls=(0, (4, 3)), zorder=1)
        ax.annotate(
            panel.line[1],
            (0.99, panel.line[0]),
            xycoords=("axes fraction", "data"),
            xytext=(0, 3),
            textcoords="offset points",
            ha="right",
            va="bottom",
            fontsize=LABEL_SIZE,
            color=s.MUTED,
        )
    _limits(ax, panel)
    minor_ticks(ax)
    ticks_in_view(ax)
    if panel.chosen:
        ax.plot(
            [panel.chosen.x],
            [_clamped(panel, panel.chosen.y)],
            marker="o",
            ms=RING_SIZE,
            mfc="none",
            mec=s.INK,
            mew=1.8,
            ls="none",
            zorder=6,
        )


def _clamped(panel: Panel, y: float) -> float:
    return min(max(y, panel.floor), panel.ceiling)


def _draw_series(ax, panel: Panel, series: Series, colour: str, marker: str) -> None:
    xs = [p.x for p in series.points]
    ys = [_clamped(panel, p.y) for p in series.points]
    ax.plot(xs, ys, color=colour, marker=marker, ms=4.5, lw=1.5, label=series.name, zorder=3)
    over = [(x, y) for x, y, p in zip(xs, ys, series.points) if p.y > panel.ceiling]
    if over:
        ax.plot(*zip(*over), ls="none", marker="^", ms=8, color=colour, zorder=4)


def _limits(ax, panel: Panel) -> None:
    xs = [p.x for series in panel.series for p in series.points] + ([panel.exact.x] if panel.exact else [])
    ys = [_clamped(panel, p.y) for series in panel.series for p in series.points]
    ys += ([panel.floor] if panel.exact else []) + ([panel.line[0]] if panel.line else [])
    ax.set_xlim(panel.xlim or (min(xs) / 2.5, max(xs) * 2.5))
    ax.set_ylim(panel.ylim or (min(ys) / 10.0, max(ys) * 10.0))


# --- labels, placed once the layout is final ------------------------------------------------------------------

# Where a label may go, in the order tried: right and up, right and down, left and up, left and down,
# over, under, right, left of its point.
_SPOTS = ((1, 1), (1, -1), (-1, 1), (-1, -1), (0, 1), (0, -1), (1, 0), (-1, 0))


def _annotate(ax, panel: Panel) -> None:
    """Each point's label (major ones first) where it covers no marker, ring, line or earlier label."""
    # One renderer measures every label: asked for none, matplotlib makes a new one (an SVG print) per question.
    renderer = ax.figure._get_renderer()
    to_pt = ax.transData.transform
    frame = ax.get_window_extent()
    bounds = (frame.x0, frame.y0, frame.x1, frame.y1)
    points = [(p, COLOURS[i % len(COLOURS)]) for i, series in enumerate(panel.series) for p in series.points]
    obstacles = [_square(to_pt((p.x, _clamped(panel, p.y))), MARKER_HALF) for p, _ in points]
    for series in panel.series:
        obstacles += _line_boxes([to_pt((p.x, _clamped(panel, p.y))) for p in series.points])
    if panel.chosen:
        obstacles.append(_square(to_pt((panel.chosen.x, _clamped(panel, panel.chosen.y))), RING_SIZE / 2 + 1))
    if panel.exact:
        obstacles.append(_square(to_pt((panel.exact.x, panel.floor)), 7))
    boxes = np.array(obstacles, dtype=float).reshape(-1, 4)  # one row (x0, y0, x1, y1) per obstacle
    for point, colour in sorted(points, key=lambda item: not item[0].major):
        if point.text:
            box = _label(ax, panel, point, colour, bounds, boxes, renderer)
            if box:
                boxes = np.vstack([boxes, box])


def _square(centre, half: float) -> tuple:
    return (centre[0] - half, centre[1] - half, centre[0] + half, centre[1] + half)


def _line_boxes(vertices) -> list[tuple]:
    """Small squares every few points along a polyline (in display points), standing for the line."""
    boxes = []
    for (x0, y0), (x1, y1) in zip(vertices, vertices[1:]):
        steps = max(1, math.ceil(math.hypot(x1 - x0, y1 - y0) / (2 * LINE_HALF)))
        boxes += [
            _square((x, y), LINE_HALF) for x, y in zip(np.linspace(x0, x1, steps + 1), np.linspace(y0, y1, steps + 1))
        ]
    return boxes


def _well_inside(xy, bounds: tuple, margin: float = 2.0) -> bool:
    """Whether a point (in display points) lies inside `bounds` by more than `margin` on every side."""
    return bounds[0] + margin < xy[0] < bounds[2] - margin and bounds[1] + margin < xy[1] < bounds[3] - margin


def _inside(box: tuple, bounds: tuple) -> bool:
    return box[0] >= bounds[0] and box[1] >= bounds[1] and box[2] <= bounds[2] and box[3] <= bounds[3]


def _free(box: tuple, bounds: tuple, obstacles: np.ndarray) -> bool:
    """Whether `box` lies within `bounds` and overlaps no obstacle (a row x0, y0, x1, y1; edges may touch)."""
    if not _inside(box, bounds):
        return False
    x0, y0, x1, y1 = box
    return not np.any((x0 < obstacles[:, 2]) & (obstacles[:, 0] < x1) & (y0 < obstacles[:, 3]) & (obstacles[:, 1] < y1))


def _label(ax, panel: Panel, point: Point, colour: str, bounds, obstacles, renderer) -> tuple | None:
    """A point's label at the first free spot around it, measured as drawn; None (and no label) if none is free."""
    xy = (point.x, _clamped(panel, point.y))
    label = ax.annotate(
        point.text,
        xy,
        xytext=(0, 0),
        textcoords="offset points",
        ha="left",
        va="bottom",
        fontsize=LABEL_SIZE,
        color=colour,
        zorder=4,
    )
    if _well_inside(ax.transData.transform(xy), bounds):
        # matplotlib draws a label only while its point is in the axes, and checks that (through the data
        # transform and the axes' outline) each time the label is measured or drawn; a point this far inside
        # stays in, so the label is drawn as it would be, unchecked.
        label.set_annotation_clip(False)
    # Measured once, with the figure's own renderer; at 72 dpi an offset in points moves it as many pixels.
    x0, y0, x1, y1 = label.get_window_extent(renderer).extents
    width, height = x1 - x0, y1 - y0
    gap = MARKER_HALF + LABEL_MARGIN + 0.5  # clear of the point's own marker
    for sx, sy in _SPOTS:
        dx = gap if sx > 0 else -gap - width if sx < 0 else -width / 2
        if sx:  # beside the point, level with its centre or just above or below it
            dy = 1.0 if sy > 0 else -height - 1.0 if sy < 0 else -height / 2
        else:  # over or under it
            dy = gap if sy > 0 else -gap - height
        box = (x0 + dx - LABEL_MARGIN, y0 + dy - LABEL_MARGIN, x1 + dx + LABEL_MARGIN, y1 + dy + LABEL_MARGIN)
        if _free(box, bounds, obstacles):
            label.xyann = (dx, dy)
            return box
    label.remove()
    return None
