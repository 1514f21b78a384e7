"""A build collects its cyclic garbage once per page, not whenever allocations pile up."""

from __future__ import annotations

import gc
import threading
from contextlib import contextmanager

YOUNG = 10_000  # allocations between young collections (Python's default, 700, ran a thousand times a build)
_NEVER = 1 << 30  # a full-collection threshold that is never reached: the build collects fully itself

_lock = threading.Lock()
_running = 0  # builds running in this process (one after another, or in threads side by side)
_thresholds = gc.get_threshold()  # the process's own, given back when the last running build ends


@contextmanager
def collecting_per_page():
    """While builds run, what the process held before is set aside and full collections are the builds' own
    (`collect_garbage`, after each page).

    Python's automatic full collections rescan every live object, and a build's process holds hundreds of
    thousands that outlive it (numpy, scipy, numba and matplotlib, the registry): on a cold build of the
    book, collecting took 1.3 s, most of it rescanning them. `gc.freeze` sets them aside (without a
    collection first: in a long-lived process that would rescan its whole heap at every build), and a full
    collection after each page keeps the build's garbage bounded by a page, as its memory is. When the last
    running build ends, everything is the collector's again under the process's own thresholds; what a
    build leaves in reference cycles once it has returned is freed by the process's next full collection
    (a watcher runs one after each rebuild).
    """
    global _running, _thresholds
    with _lock:
        if not _running:
            _thresholds = gc.get_threshold()
            gc.freeze()
            gc.set_threshold(YOUNG, _thresholds[1], _NEVER)
        _running += 1
    try:
        yield
    finally:
        with _lock:
            _running -= 1
            if not _running:
                gc.set_threshold(*_thresholds)
                gc.unfreeze()


def collect_garbage(book, run):
    """The last phase of a page: free what its work left in reference cycles (figures, mostly)."""
    gc.collect()
    return book
