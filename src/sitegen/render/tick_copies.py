"""An axis' new ticks made as copies of one tick made the matplotlib way, not each built afresh.

When an axis needs more ticks, matplotlib builds each one from the axis' tick keywords and the rc settings of
the moment (five artists, each through its property setters), then gives it the first tick's properties
(`Axis._copy_tick_props`). That was a fifth of a figure's drawing time, and a third for the accuracy report's
log axes with their minor ticks. Here, on Cartesian axes, one tick per call is made exactly that way, and the
others the call needs are copies of it, each with artists, font properties and data of its own. So no figure
changes by a byte, whatever its code sets on its ticks (a test compares a figure whose ticks carry an id, a
rotation mode and wrapped labels, and a polar axes, against matplotlib's own). Imported for its effect by `style`.
"""

from __future__ import annotations

import copy
import functools

from matplotlib import axis as maxis
from matplotlib import cbook

_PARTS = ("tick1line", "tick2line", "gridline", "label1", "label2")  # the artists a Tick is drawn with
# The axis classes whose ticks are copied, with the tick class each makes. Copies share transforms and marker
# styles, which a Cartesian tick's setters replace rather than change. A polar tick moves its label by changing
# its own translation in place, and a 3D axis moves its ticks itself: their ticks are built, one by one.
_COPIED_TICK_CLASS = {maxis.XAxis: maxis.XTick, maxis.YAxis: maxis.YTick}


def copied_tick(made: maxis.Tick) -> maxis.Tick:
    """A copy of a tick that was just made (its parts share their transforms, and its lines their marker styles
    and paths, which matplotlib's setters replace rather than change)."""
    tick = _artist_copy(made)
    for name in _PARTS:
        setattr(tick, name, _artist_copy(getattr(made, name)))
    return tick


def _artist_copy(artist):
    """A shallow copy of `artist` that keeps its stale callback, has no "pchanged" observers, is in no artist list,
    and owns what its setters change in place."""
    twin = copy.copy(artist)
    # copy.copy drops it through Artist.__getstate__ (for pickling); kept, a changed copy marks its axes stale
    twin.stale_callback = artist.stale_callback
    twin._callbacks = cbook.CallbackRegistry(signals=["pchanged"])
    twin._remove_method = None
    if getattr(artist, "_sticky_edges", None) is not None:  # update_from writes into these lists
        twin._sticky_edges = type(artist._sticky_edges)(list(artist._sticky_edges.x), list(artist._sticky_edges.y))
    if hasattr(artist, "_fontproperties"):  # a label's setters change its font properties in place
        twin._fontproperties = artist._fontproperties.copy()
    for data in ("_xorig", "_yorig"):  # code may change in place the data that get_xdata(orig=True) returns
        if hasattr(artist, data):
            setattr(twin, data, copy.copy(getattr(artist, data)))
    return twin


def grown(axis: maxis.Axis, ticks: list, numticks: int, major: bool) -> list:
    """Extend the axis' `ticks` in place to `numticks` as matplotlib would (by copies on Cartesian axes), and
    return the first `numticks`."""
    if ticks and len(ticks) < numticks and _COPIED_TICK_CLASS.get(type(axis)) is axis._tick_class:
        # What matplotlib makes of every new tick: one built with this moment's settings, given the first's properties.
        made = axis._get_tick(major=major)
        axis._copy_tick_props(ticks[0], made)
        new = []
        while len(ticks) + len(new) + 1 < numticks:
            new.append(copied_tick(made))
        ticks.extend(new + [made])
    while len(ticks) < numticks:  # other axes' ticks, and all of a call that starts with none: as matplotlib does
        ticks.append(axis._get_tick(major=major))
        axis._copy_tick_props(ticks[0], ticks[-1])
    return ticks[:numticks]


def _copy_new_ticks() -> None:
    """Make `Axis.get_major_ticks` and `get_minor_ticks` add their new ticks by `grown`."""
    if not hasattr(maxis.Axis, "_copy_tick_props"):  # a detail of matplotlib's: without it, build ticks as it does
        return

    @functools.wraps(maxis.Axis.get_major_ticks)
    def get_major_ticks(self, numticks=None):
        return grown(self, self.majorTicks, len(self.get_majorticklocs()) if numticks is None else numticks, True)

    @functools.wraps(maxis.Axis.get_minor_ticks)
    def get_minor_ticks(self, numticks=None):
        return grown(self, self.minorTicks, len(self.get_minorticklocs()) if numticks is None else numticks, False)

    maxis.Axis.get_major_ticks = get_major_ticks
    maxis.Axis.get_minor_ticks = get_minor_ticks


_copy_new_ticks()
