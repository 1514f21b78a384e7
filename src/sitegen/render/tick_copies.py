"""An axis' further ticks made as copies of its first tick, not built afresh.

matplotlib builds each tick an axis needs beyond its first from the axis' tick keywords (five artists, each
through its property setters) and then copies the first tick's properties onto it (`Axis._copy_tick_props`).
That was a fifth of a figure's drawing time, and a third for the accuracy report's log axes with their minor
ticks. A copy of the first tick has those same properties from the start; what differs from tick to tick (its
position and its label's text) `Axis._update_ticks` sets on every tick before it is measured or drawn. So the
figures keep every byte (the build's tests compare them with the goldens and across builds). Imported for its
effect by `style`.
"""
from __future__ import annotations

import copy

from matplotlib import axis as maxis
from matplotlib import cbook

_PARTS = ("tick1line", "tick2line", "gridline", "label1", "label2")  # the artists a Tick is drawn with


def copied_tick(first: maxis.Tick) -> maxis.Tick:
    """A tick with the properties of `first`, with artists of its own (callbacks, font properties)."""
    tick = _artist_copy(first)
    for name in _PARTS:
        part = _artist_copy(getattr(first, name))
        if hasattr(part, "_fontproperties"):  # a label's font properties are changed in place by its setters
            part._fontproperties = part._fontproperties.copy()
        setattr(tick, name, part)
    return tick


def _artist_copy(artist):
    """A shallow copy of `artist` that shares no observers and belongs to no container yet."""
    twin = copy.copy(artist)
    twin._callbacks = cbook.CallbackRegistry(signals=["pchanged"])
    twin._remove_method = None
    return twin


def _grown(axis: maxis.Axis, ticks: list, numticks: int, major: bool) -> list:
    """The first `numticks` of an axis' `ticks`, the list first grown by copies of its first tick."""
    if not ticks:
        ticks.append(axis._get_tick(major=major))
    while len(ticks) < numticks:
        ticks.append(copied_tick(ticks[0]))
    return ticks[:numticks]


def _copy_further_ticks() -> None:
    """Make `Axis.get_major_ticks` and `get_minor_ticks` add copies of the first tick."""
    if not hasattr(maxis.Axis, "_copy_tick_props"):  # a detail of matplotlib's: without it, build ticks as it does
        return

    def get_major_ticks(self, numticks=None):
        return _grown(self, self.majorTicks, len(self.get_majorticklocs()) if numticks is None else numticks, True)

    def get_minor_ticks(self, numticks=None):
        return _grown(self, self.minorTicks, len(self.get_minorticklocs()) if numticks is None else numticks, False)

    maxis.Axis.get_major_ticks = get_major_ticks
    maxis.Axis.get_minor_ticks = get_minor_ticks


_copy_further_ticks()
