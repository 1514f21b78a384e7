"""A build collects its cyclic garbage once per page, not whenever allocations pile up."""
from __future__ import annotations

import gc
from contextlib import contextmanager

_YOUNG = 10_000  # allocations between young collections (Python's default, 700, ran a thousand times a build)
_NEVER = 1 << 30  # a full-collection threshold that is never reached: the build collects fully itself


@contextmanager
def collecting_per_page():
    """While the build runs, what outlives it is set aside and full collections are the build's own
    (`collect_garbage`, after each page).

    Python's automatic full collections rescan every live object, and a build's process holds hundreds of
    thousands that outlive it (numpy, scipy, numba and matplotlib, the registry): on a cold build of the
    book, collecting took 1.3 s, most of it rescanning them. `gc.freeze` sets them aside until the build
    ends, and a full collection after each page keeps the build's garbage bounded by a page, as its memory is.
    """
    thresholds = gc.get_threshold()
    gc.freeze()  # no collection first: in a long-lived process (tests, a watcher) that would rescan its whole heap
    gc.set_threshold(_YOUNG, thresholds[1], _NEVER)
    try:
        yield
    finally:
        gc.set_threshold(*thresholds)
        gc.unfreeze()


def collect_garbage(book, run):
    """The last phase of a page: free what its work left in reference cycles (figures, mostly)."""
    gc.collect()
    return book
