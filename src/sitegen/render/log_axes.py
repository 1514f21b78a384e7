"""Log axes drawn cheaply, as the accuracy page's diagrams use them: decades labelled in plain text, minor
ticks only where they help, ticks made only in view, and a tight layout that measures each axes once."""

from __future__ import annotations

import math
from contextlib import contextmanager

import matplotlib.artist as martist
import numpy as np
from matplotlib.ticker import FuncFormatter, Locator, NullFormatter, NullLocator

MINOR_DECADES = 3  # an axis spanning more decades than this has no minor ticks
_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def decade_text(value: float, _position=None) -> str:
    """A decade as 10 with its exponent in superscript digits ("10⁻³"): plain text, where matplotlib's log labels
    are math ($10^{-3}$), typeset by its math parser, the slowest part of drawing these diagrams."""
    exponent = round(math.log10(value))
    if not math.isclose(value, 10.0**exponent):  # not a decade (a log axis of these diagrams labels none)
        return f"{value:g}"
    return "10" + str(exponent).translate(_SUPERSCRIPT)


DECADE = FuncFormatter(decade_text)  # a log axis's major labels


def minor_ticks(ax) -> None:
    """Unlabelled minor ticks on an axis of a few decades; an axis of more marks its decades only.

    Minor ticks help to read a value between two decades; over many decades they are clutter (matplotlib draws
    none beyond ten) and they were half the cost of drawing these diagrams.
    """
    for axis, (low, high) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        if math.log10(high / low) > MINOR_DECADES:
            axis.set_minor_locator(NullLocator())
        else:
            axis.set_minor_formatter(NullFormatter())  # "2×10²" minor labels collide on short decades


def ticks_in_view(ax) -> None:
    """Every locator of the axes' log axes gives the locations in its view only (`InView`)."""
    for axis in (ax.xaxis, ax.yaxis):
        if axis.get_scale() != "log":  # `InView` keeps its slack as a ratio, for positive locations
            continue
        if not isinstance(axis.get_major_locator(), NullLocator):
            axis.set_major_locator(InView(axis.get_major_locator()))
        if not isinstance(axis.get_minor_locator(), NullLocator):
            axis.set_minor_locator(InView(axis.get_minor_locator()))


class InView(Locator):
    """A locator's locations, less those well outside the view.

    matplotlib makes a tick (two lines, a grid line and two labels) for every location its locator gives and draws
    those in the view; a log locator gives one decade or more beyond each end, a third of these diagrams' ticks.
    A location dropped here is one matplotlib would not draw, so the drawing is the same, for less making.
    """

    SLACK = 1.001  # a location this close beyond an end (as a ratio) is kept; matplotlib decides whether to draw it

    def __init__(self, locator: Locator):
        self.locator = locator

    def set_axis(self, axis) -> None:
        """The axis of this locator and of the one it filters."""
        super().set_axis(axis)
        self.locator.set_axis(axis)

    def __call__(self):
        return self._in_view(self.locator(), *self.axis.get_view_interval())

    def tick_values(self, vmin, vmax):
        """The filtered locator's locations between vmin and vmax (and a little beyond)."""
        return self._in_view(self.locator.tick_values(vmin, vmax), vmin, vmax)

    def nonsingular(self, v0, v1):
        """As the filtered locator."""
        return self.locator.nonsingular(v0, v1)

    def view_limits(self, vmin, vmax):
        """As the filtered locator."""
        return self.locator.view_limits(vmin, vmax)

    def _in_view(self, locations, vmin, vmax):
        low, high = min(vmin, vmax), max(vmin, vmax)
        locations = np.asarray(locations)
        return locations[(locations >= low / self.SLACK) & (locations <= high * self.SLACK)]


def tight_layout_measured_once(fig, **kwargs) -> None:
    """`fig.tight_layout(**kwargs)`, each axes measured once.

    Given a `rect`, matplotlib measures every axes (ticks, labels, legend) twice, the second time to fit the
    same boxes into the rect: nothing moves in between, so the first measurements serve again, for the same
    layout and half the measuring.
    """
    with _measured_once():
        fig.tight_layout(**kwargs)


@contextmanager
def _measured_once():
    """While laying out, an artist's layout box is measured the first time it is asked for, then reused."""
    measure = getattr(martist, "_get_tightbbox_for_layout_only", None)
    if measure is None:  # a detail of matplotlib's; without it, measure as matplotlib does
        yield
        return
    boxes = {}

    def once(artist, *args, **kwargs):
        if id(artist) not in boxes:
            boxes[id(artist)] = (artist, measure(artist, *args, **kwargs))  # the artist kept: its id stays its own
        return boxes[id(artist)][1]

    martist._get_tightbbox_for_layout_only = once
    try:
        yield
    finally:
        martist._get_tightbbox_for_layout_only = measure
