"""The accuracy page's diagrams keep their annotations off the data: measured in matplotlib as drawn.

A crowded work–precision panel (seven methods, ten tolerances each, lines crossing) is drawn wide
and narrow: many points keep their label, and no label covers another label, a marker or the ring
of the chosen setting; the legend (which names the ring) sits outside the panel and the title
above the legend; nothing is drawn outside the figure.
"""

from __future__ import annotations

import math

import pytest

from sitegen.render import work_precision as wp
from sitegen.render.work_precision import Panel, Point, Series

METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA", "compiled-DOP853", "compiled-Radau")


def _crowded_panel() -> Panel:
    """Seven lines from the upper left to the lower right, crossing and close together as real solvers are."""
    series = []
    for m, name in enumerate(METHODS):
        points = tuple(
            Point(
                10 ** (0.5 + 0.35 * m + 0.2 * k + 0.03 * math.sin(3 * k + m)),
                10 ** (-2 - 1.0 * k - 0.3 * m),
                str(3 + k),
                major=(3 + k) % 3 == 0,
            )
            for k in range(10)
        )
        series.append(Series(name, points))
    chosen = series[1].points[5]
    return Panel("a crowded panel", tuple(series), chosen=Point(chosen.x, chosen.y, "chosen: DOP853 rtol 1e-8"))


def _boxes(artists) -> list[tuple]:
    return [tuple(a.get_window_extent().extents) for a in artists]


def _overlap(a, b) -> float:
    return max(0.0, min(a[2], b[2]) - max(a[0], b[0])) * max(0.0, min(a[3], b[3]) - max(a[1], b[1]))


@pytest.fixture(scope="module", params=[False, True], ids=["wide", "narrow"])
def drawn(request):
    panel = _crowded_panel()
    fig = wp.work_precision_figure([panel], "time (ms)", "error", "labels: rtol = 10⁻ⁿ", narrow=request.param)
    fig.draw_without_rendering()  # puts the axis labels where they are drawn
    yield fig, fig.axes[0], panel
    wp.plt.close(fig)


def test_many_points_keep_their_label(drawn):
    """A label is dropped only where it has no room: on this panel, denser than any of the book's, at
    least a third of the points keep theirs (the book's diagrams keep 55 to 85 %)."""
    fig, ax, panel = drawn
    labels = [t for t in ax.texts if t.get_text().isdigit()]
    assert len(labels) >= sum(len(s.points) for s in panel.series) / 3, len(labels)


def test_no_label_covers_a_label_a_marker_or_the_ring(drawn):
    fig, ax, panel = drawn
    labels = _boxes(t for t in ax.texts if t.get_text().isdigit())
    for i, a in enumerate(labels):
        assert not any(_overlap(a, b) > 0 for b in labels[i + 1 :]), "two labels overlap"
    centres = [ax.transData.transform((p.x, p.y)) for s in panel.series for p in s.points]
    markers = [(x - wp.MARKER_HALF, y - wp.MARKER_HALF, x + wp.MARKER_HALF, y + wp.MARKER_HALF) for x, y in centres]
    rx, ry = ax.transData.transform((panel.chosen.x, panel.chosen.y))
    ring = (rx - wp.RING_SIZE / 2, ry - wp.RING_SIZE / 2, rx + wp.RING_SIZE / 2, ry + wp.RING_SIZE / 2)
    covered = [(label, box) for label in labels for box in [*markers, ring] if _overlap(label, box) > 0]
    assert not covered, covered[:3]


def test_legend_outside_the_panel_and_the_title_above_it(drawn):
    fig, ax, panel = drawn
    legend, title, frame = ax.get_legend(), ax.title, tuple(ax.get_window_extent().extents)
    legend_box = tuple(legend.get_window_extent().extents)
    assert _overlap(legend_box, frame) == 0, (legend_box, frame)
    assert _overlap(tuple(title.get_window_extent().extents), legend_box) == 0
    assert panel.chosen.text in [t.get_text() for t in legend.get_texts()], "the ring is named in the legend"
    assert not [t for t in ax.texts if t.get_text() == panel.chosen.text], "no callout over the data"


def test_nothing_outside_the_figure(drawn):
    fig, ax, panel = drawn
    width, height = fig.get_figwidth() * fig.dpi, fig.get_figheight() * fig.dpi
    for text in [*fig.texts, *ax.texts, ax.title, ax.xaxis.label, ax.yaxis.label, *ax.get_legend().get_texts()]:
        x0, y0, x1, y1 = text.get_window_extent().extents
        assert x0 >= -0.5 and y0 >= -0.5 and x1 <= width + 0.5 and y1 <= height + 0.5, text.get_text()
