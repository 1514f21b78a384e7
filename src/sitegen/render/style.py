"""One visual language for every figure: fonts, colours, line weights, deterministic SVG."""

from __future__ import annotations

import matplotlib

matplotlib.use("svg")

import matplotlib.pyplot as plt

INK = "#1d2430"
MUTED = "#5b6472"
GRID = "#d9dde3"
BLUE = "#1f63b5"
ORANGE = "#c8541c"
FILL_BLUE = "#9cc2ea"
FILL_ORANGE = "#f2c2a6"
LOST = "#b8bec8"
WIDTH_IN = 6.0  # figure width in inches; 72 dpi so that SVG units are points
# A phone's figure: panels stacked in a column this wide. Drawn across a phone's text (about 280 to 420 px),
# its 10 pt text shows at 11 to 16 px, as the wide figure's does across a text column.
NARROW_WIDTH_IN = 3.6

RC = {
    "svg.hashsalt": "sitegen",  # fixed salt: byte-stable ids in the SVG
    "svg.fonttype": "none",  # text stays text: small, selectable, readable in diffs
    "font.family": "DejaVu Sans",
    "font.size": 10,
    "axes.edgecolor": MUTED,
    "axes.labelcolor": INK,
    "axes.linewidth": 0.8,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.grid": True,
    "grid.color": GRID,
    "grid.linewidth": 0.6,
    "xtick.color": MUTED,
    "ytick.color": MUTED,
    "xtick.labelcolor": INK,
    "ytick.labelcolor": INK,
    "lines.linewidth": 2.0,
    "figure.dpi": 72,
    "savefig.dpi": 72,
    "path.simplify": False,
}


def width(narrow: bool = False) -> float:
    """The figure width in inches: a text column's, or a phone's."""
    return NARROW_WIDTH_IN if narrow else WIDTH_IN


def new_figure(height_in: float, ncols: int = 1, narrow: bool = False, **kwargs):
    """A figure and its axes in the house style: `ncols` panels side by side, or (narrow) one above the other."""
    rows, cols = (ncols, 1) if narrow else (1, ncols)
    with plt.rc_context(RC):
        fig, axes = plt.subplots(rows, cols, figsize=(width(narrow), height_in), **kwargs)
    return fig, list(axes) if ncols > 1 else [axes]


def new_rows(height_in: float, nrows: int, narrow: bool = False, **kwargs):
    """A figure of `nrows` panels one above the other (at either width), in the house style."""
    with plt.rc_context(RC):
        fig, axes = plt.subplots(nrows, 1, figsize=(width(narrow), height_in), **kwargs)
    return fig, list(axes)


def new_mosaic(height_in: float, layout, narrow: bool = False, **kwargs):
    """A figure whose named axes follow `layout` (matplotlib's subplot_mosaic), in the house style.

    The axes are created, and so numbered in `fig.axes` (what a layer's `axes` counts), in the order
    their names first appear in `layout`, row by row; a narrow layout should keep that order.
    """
    with plt.rc_context(RC):
        fig, named = plt.subplot_mosaic(layout, figsize=(width(narrow), height_in), **kwargs)
    return fig, named


def laid_out(fig):
    """The figure as its view laid it out, without the placeholder layout engine that `tight_layout`
    leaves behind: with one, savefig draws the whole figure an extra time before printing it (the
    layout is already final, so the SVG is the same, for a third less drawing)."""
    fig.set_layout_engine(None)
    return fig
