"""Static diagrams of the accuracy page: work–precision (error against time) and resolution against bytes.

They take plain points, not bench.json, and draw them in the house style; `figure_svg` turns
them into byte-stable inline SVG. Point labels are placed after the layout is fixed, each at the
first free spot around its point, and dropped rather than drawn over another label or marker.
"""
from __future__ import annotations

from dataclasses import dataclass

import matplotlib.pyplot as plt
from matplotlib.ticker import LogLocator, NullFormatter

from . import style as s

GREEN, PURPLE = "#2a7a3b", "#7b3fa0"
COLOURS = (s.BLUE, s.ORANGE, GREEN, PURPLE, s.MUTED, s.INK)
MARKERS = ("o", "s", "^", "D", "v", "P")
LABEL_SIZE = 7.5
CHAR_WIDTH = 4.4  # pt per character of a point label (DejaVu Sans at 7.5 pt, digits)
CALLOUT_CHAR = 5.6  # pt per character of the bold callout
MARKER_HALF = 3.5  # pt: half the size of a marker, an obstacle for labels


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
    chosen: Point | None = None  # drawn with a ring and `chosen.text` as a callout
    exact: Point | None = None  # a method with no error to plot: a star on the floor
    floor: float = 1e-16  # errors below this are drawn on it
    ceiling: float = 10.0  # errors above this are drawn on it, as an upward triangle
    line: tuple[float, str] | None = None  # a horizontal reference line (y, label)
    xlim: tuple[float, float] | None = None  # fixed limits (shared by panels); None: fit the points
    ylim: tuple[float, float] | None = None


def work_precision_figure(panels: list[Panel], xlabel: str, ylabel: str, note: str) -> plt.Figure:
    """Log–log panels stacked vertically, one line per series, points labelled, the chosen one ringed."""
    with plt.rc_context(s.RC):
        fig, axes = plt.subplots(len(panels), 1, figsize=(s.WIDTH_IN, 0.5 + 3.6 * len(panels)), squeeze=False)
        for ax, panel in zip(axes[:, 0], panels):
            _draw_panel(ax, panel, xlabel, ylabel)
            ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=len(panel.series), fontsize=LABEL_SIZE + 1,
                      frameon=False, handlelength=1.5, columnspacing=0.9, handletextpad=0.4, borderaxespad=0.2)
        fig.text(0.01, 0.005, note, fontsize=LABEL_SIZE + 0.5, color=s.MUTED, ha="left", va="bottom")
        fig.tight_layout(rect=(0, 0.025, 1, 1), h_pad=1.4)
        for ax, panel in zip(axes[:, 0], panels):
            _annotate(ax, panel)
    return fig


def resolution_figure(panels: list[Panel], note: str) -> plt.Figure:
    """A 2-column grid of panels: interpolation error (in display digits) against bytes stored."""
    rows = (len(panels) + 1) // 2
    with plt.rc_context(s.RC):
        fig, axes = plt.subplots(rows, 2, figsize=(s.WIDTH_IN, 0.7 + 2.9 * rows), squeeze=False)
        for ax, panel in zip(axes.ravel(), panels):
            _draw_panel(ax, panel, "bytes stored (float32)", "error ÷ ½ last digit")
        for ax in axes.ravel()[len(panels):]:
            ax.set_visible(False)
        names = [series.name for series in panels[0].series]
        handles = [plt.Line2D([], [], color=COLOURS[i], marker=MARKERS[i], lw=1.5, ms=5) for i in range(len(names))]
        fig.legend(handles, names, loc="upper center", ncol=len(names), fontsize=LABEL_SIZE + 1, frameon=False,
                   handlelength=1.5, columnspacing=1.0)
        fig.text(0.01, 0.005, note, fontsize=LABEL_SIZE + 0.5, color=s.MUTED, ha="left", va="bottom")
        fig.tight_layout(rect=(0, 0.03, 1, 0.95), h_pad=1.2, w_pad=1.2)
        for ax, panel in zip(axes.ravel(), panels):
            _annotate(ax, panel)
    return fig


def _draw_panel(ax, panel: Panel, xlabel: str, ylabel: str) -> None:
    """Axes, lines and markers; labels wait for the final layout (`_annotate`)."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title(panel.title, fontsize=9.5, loc="left", color=s.INK, pad=16)
    ax.set_xlabel(xlabel, fontsize=9)
    ax.set_ylabel(ylabel, fontsize=9)
    ax.tick_params(labelsize=8)
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_minor_formatter(NullFormatter())  # "2×10²" minor labels collide on short decades
    ax.yaxis.set_major_locator(LogLocator(base=10.0, numticks=8))
    for index, series in enumerate(panel.series):
        _draw_series(ax, panel, series, COLOURS[index % len(COLOURS)], MARKERS[index % len(MARKERS)])
    if panel.exact:
        ax.plot([panel.exact.x], [panel.floor], marker="*", ms=12, color=s.INK, ls="none", zorder=5)
    if panel.line:
        ax.axhline(panel.line[0], color=s.MUTED, lw=1.0, ls=(0, (4, 3)), zorder=1)
        ax.annotate(panel.line[1], (0.99, panel.line[0]), xycoords=("axes fraction", "data"), xytext=(0, 3),
                    textcoords="offset points", ha="right", va="bottom", fontsize=LABEL_SIZE, color=s.MUTED)
    _limits(ax, panel)
    if panel.chosen:
        ax.plot([panel.chosen.x], [_clamped(panel, panel.chosen.y)], marker="o", ms=15, mfc="none", mec=s.INK, mew=1.8,
                ls="none", zorder=6)


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


def _annotate(ax, panel: Panel) -> None:
    """The chosen setting's callout, then each point's label where it collides with nothing."""
    to_pt = ax.transData.transform
    frame = ax.get_window_extent()
    bounds = (frame.x0, frame.y0, frame.x1, frame.y1)
    points = [(p, COLOURS[i % len(COLOURS)]) for i, series in enumerate(panel.series) for p in series.points]
    markers = [_square(to_pt((p.x, _clamped(panel, p.y))), MARKER_HALF) for p, _ in points]
    placed: list[tuple] = []
    if panel.chosen:
        centre = to_pt((panel.chosen.x, _clamped(panel, panel.chosen.y)))
        markers.append(_square(centre, 7.5))
        placed.append(_callout(ax, panel, centre, bounds, markers))
    for point, colour in sorted(points, key=lambda item: not item[0].major):
        if point.text:
            box = _label(ax, panel, point, colour, to_pt((point.x, _clamped(panel, point.y))), bounds, markers, placed)
            if box:
                placed.append(box)


def _square(centre, half: float) -> tuple:
    return (centre[0] - half, centre[1] - half, centre[0] + half, centre[1] + half)


def _overlaps(a: tuple, b: tuple) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def _inside(box: tuple, bounds: tuple) -> bool:
    return box[0] >= bounds[0] and box[1] >= bounds[1] and box[2] <= bounds[2] and box[3] <= bounds[3]


def _free(box: tuple, bounds: tuple, obstacles: list[tuple]) -> bool:
    return _inside(box, bounds) and not any(_overlaps(box, o) for o in obstacles)


def _label(ax, panel: Panel, point: Point, colour: str, centre, bounds, markers, placed) -> tuple | None:
    """A point's label at the first free spot right, below-right, left or below-left of it; None if none is free."""
    width, height = CHAR_WIDTH * len(point.text) + 1.0, 8.0
    gap = MARKER_HALF + 0.5  # clear of the point's own marker
    for dx, dy in ((gap, 1.0), (gap, -9.0), (-gap - width, 1.0), (-gap - width, -9.0)):
        box = (centre[0] + dx, centre[1] + dy, centre[0] + dx + width, centre[1] + dy + height)
        if _free(box, bounds, markers + placed):
            ax.annotate(point.text, (point.x, _clamped(panel, point.y)), xytext=(dx, dy), textcoords="offset points",
                        ha="left", va="bottom", fontsize=LABEL_SIZE, color=colour, zorder=4)
            return box
    return None


def _callout(ax, panel: Panel, centre, bounds, markers) -> tuple:
    """The chosen setting's name in a box, joined to its ring, at the first spot that covers no marker."""
    width, height = CALLOUT_CHAR * len(panel.chosen.text) + 8.0, 13.0
    candidates = [(18, 18), (18, -31), (-18 - width, 18), (-18 - width, -31), (24, -6), (-24 - width, -6),
                  (18, 40), (18, -53), (-18 - width, 40), (-18 - width, -53)]
    chosen = candidates[0]
    for dx, dy in candidates:
        box = (centre[0] + dx, centre[1] + dy, centre[0] + dx + width, centre[1] + dy + height)
        if _free(box, bounds, markers):
            chosen = (dx, dy)
            break
    dx, dy = chosen
    ax.annotate(panel.chosen.text, (panel.chosen.x, _clamped(panel, panel.chosen.y)), xytext=(dx + 4, dy + 3.5),
                textcoords="offset points", ha="left", va="bottom", fontsize=LABEL_SIZE + 1, color=s.INK,
                fontweight="bold", zorder=7, bbox={"boxstyle": "round,pad=0.25", "fc": "white", "ec": s.GRID, "alpha": 0.95},
                arrowprops={"arrowstyle": "-", "color": s.INK, "lw": 1.0, "shrinkA": 0, "shrinkB": 7.5})
    return (centre[0] + dx, centre[1] + dy, centre[0] + dx + width, centre[1] + dy + height)

