"""An axis' new ticks made by copies (render/tick_copies.py) draw the same bytes as matplotlib's own."""

from __future__ import annotations

import re
import subprocess
import sys

# A figure with what making ticks by copies must keep: many major ticks, log axes with minor ticks, tick parameters
# changed after the first ticks exist, labels set per tick and then more ticks needed, properties that matplotlib
# does not pass from the first tick to new ones (an id, a rotation mode, a wrapped label), an rc setting that
# differs between making the axes and drawing them, a layout measured then drawn, and a polar axes.
FIGURE = r"""
import io, sys
import matplotlib
matplotlib.use("svg")
import matplotlib.pyplot as plt
import numpy as np
with plt.rc_context({"svg.hashsalt": "test", "svg.fonttype": "none", "axes.grid": True, "figure.dpi": 72,
                     "text.parse_math": False}):
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(9, 3))
a.plot(np.linspace(0, 37, 50), np.sin(np.linspace(0, 37, 50)))
a.set_xticks(range(0, 38, 2))
a.tick_params(labelsize=7, colors="#c8541c")
plt.setp(a.get_yticklabels(), rotation=30, ha="right", rotation_mode="anchor", wrap=True)
a.set_ylim(-3, 3)
b.loglog([1e-9, 1e3], [1e-2, 1e6])
b.tick_params(which="minor", length=5)
c.set_xticks([0, 1], ["one\nline", "two"])
for label in c.get_xticklabels():
    label.set_linespacing(1.5)
c.xaxis.get_major_ticks()[0].set_gid("first")
c.set_xlim(-1, 12)
c.set_xticks(range(-1, 13))
fig.tight_layout()
out = io.StringIO()
with plt.rc_context({"svg.hashsalt": "test", "svg.fonttype": "none"}):
    fig.savefig(out, format="svg", metadata={"Date": None, "Creator": None})
plt.close(fig)
with plt.rc_context({"svg.hashsalt": "test", "svg.fonttype": "none"}):  # a polar axes: its ticks are built, not copied
    fig = plt.figure(figsize=(3, 3))
    polar = fig.add_subplot(projection="polar")
    polar.plot(np.linspace(0, 6, 40), np.linspace(1, 3, 40))
    polar.set_thetagrids(range(0, 360, 30))
    fig.savefig(out, format="svg", metadata={"Date": None, "Creator": None})
plt.close(fig)
svg = out.getvalue()
"""


def test_copied_ticks_draw_the_bytes_of_ticks_built_afresh():
    """The SVG with tick copying (in this process, where sitegen's figures are drawn) is byte-for-byte that of
    matplotlib's own ticks (in a process without sitegen); the figure has minor, relabelled and restyled ticks."""
    import matplotlib.axis

    from sitegen.render import tick_copies

    assert matplotlib.axis.Axis.get_major_ticks.__code__.co_filename == tick_copies.__file__  # copying is on here
    built = subprocess.run(
        [sys.executable, "-c", FIGURE + "sys.stdout.write(svg)"], capture_output=True, text=True, check=True
    ).stdout
    drawn: dict = {}
    exec(FIGURE, drawn)
    copied = drawn["svg"]
    # every label of the first axes restyled (the 19 below it and the 7 beside it), one id set on a tick
    assert len(re.findall(r'font-size: 7px[^"]*fill: #c8541c', copied)) == 19 + 7
    assert copied.count('id="first"') == 1
    assert copied.count("<use ") > 40  # tick marks, the log axes' minor ones among them
    assert copied == built


def test_a_copied_tick_has_artists_and_font_properties_of_its_own():
    """Changing a copy's label, or its line's data in place, leaves the tick it was copied from as it was."""
    import matplotlib.pyplot as plt

    from sitegen.render.tick_copies import copied_tick

    fig, ax = plt.subplots()
    first = ax.xaxis.get_major_ticks()[0]
    first.gridline.sticky_edges.x.append(0.5)  # as _copy_tick_props leaves them on a made tick
    twin = copied_tick(first)
    twin.label1.set_fontsize(3)
    twin.label1.set_text("copy")
    twin.tick1line.get_xdata(orig=True)[0] = 7.0
    twin.gridline.sticky_edges.x.append(7.0)
    assert first.label1.get_fontsize() != 3 and first.label1.get_text() != "copy"
    assert 7.0 not in list(first.tick1line.get_xdata(orig=True)) and 7.0 not in first.gridline.sticky_edges.x
    parts = ("label1", "label2", "tick1line", "tick2line", "gridline")
    assert all(getattr(twin, name) is not getattr(first, name) for name in parts)
    plt.close(fig)


def test_a_change_to_a_copied_tick_marks_its_figure_for_redrawing():
    """As with matplotlib's own ticks, changing one (a copy) tells its axes and figure to draw again."""
    import matplotlib.pyplot as plt

    from sitegen.render import tick_copies  # noqa: F401  (imported for its effect: ticks are copied here)

    fig, ax = plt.subplots()
    ax.set_xticks(range(10))
    fig.draw_without_rendering()
    assert not fig.stale
    ax.xaxis.get_major_ticks()[4].set_visible(False)
    assert ax.stale and fig.stale
    plt.close(fig)
