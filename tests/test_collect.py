"""Garbage collection around builds (phases/collect.py): a build sets aside what the process held and
collects after each page, and gives the collector back as it found it; a watcher keeps nothing of the
builds it no longer uses."""

from __future__ import annotations

import gc
import threading

import pytest

from sitegen.phases.collect import collecting_per_page

PROCESS_THRESHOLDS = (700, 10, 10)  # Python's own: what a program that embeds sitegen would have


@pytest.fixture
def own_thresholds():
    """The process at Python's default thresholds, nothing frozen; the test suite's own restored after."""
    suite = gc.get_threshold()
    gc.set_threshold(*PROCESS_THRESHOLDS)
    gc.unfreeze()
    yield
    gc.set_threshold(*suite)


def test_a_build_gives_the_collector_back_as_it_found_it(tiny_book, own_thresholds):
    """During the build the process's objects are frozen and no automatic full collection runs; after it,
    even after one that failed, the thresholds are the process's and nothing stays frozen."""
    from sitegen.build import build
    from sitegen.errors import BuildFailed

    seen = {}

    def progress(line):
        seen.setdefault("frozen", gc.get_freeze_count())
        seen.setdefault("thresholds", gc.get_threshold())

    build(tiny_book, progress=progress)
    assert seen["frozen"] > 10_000 and seen["thresholds"][2] > 10**6
    assert gc.get_threshold() == PROCESS_THRESHOLDS and gc.get_freeze_count() == 0
    (tiny_book.content / "index.md").write_text("```scene\nmodel: no-such-model\n```\n")
    with pytest.raises(BuildFailed):
        build(tiny_book, progress=None)
    assert gc.get_threshold() == PROCESS_THRESHOLDS and gc.get_freeze_count() == 0


def test_builds_side_by_side_in_threads_give_it_back_when_the_last_ends(own_thresholds):
    """Build A starts, B starts, A ends, B ends: B keeps the builds' settings until it ends, then the
    process has its own again (not A's view of them, nor the builds')."""
    a_in, b_in, a_out = threading.Event(), threading.Event(), threading.Event()
    during_b = {}

    def build_a():
        with collecting_per_page():
            a_in.set()
            b_in.wait(10)
        a_out.set()

    def build_b():
        a_in.wait(10)
        with collecting_per_page():
            b_in.set()
            a_out.wait(10)
            during_b.update(thresholds=gc.get_threshold(), frozen=gc.get_freeze_count())

    threads = [threading.Thread(target=build_a), threading.Thread(target=build_b)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(20)
    assert during_b["thresholds"][2] > 10**6 and during_b["frozen"] > 0, "A's end undid B's settings"
    assert gc.get_threshold() == PROCESS_THRESHOLDS and gc.get_freeze_count() == 0


@pytest.mark.slow
def test_a_watcher_keeps_nothing_of_its_earlier_builds(tiny_book, own_thresholds):
    """Rebuild after rebuild, the watcher's process holds as many objects as after the first ones: what each
    build left in reference cycles is freed (it held a few hundred more per rebuild when it was not)."""
    from sitegen.config import read_book
    from sitegen.preview.watch import Builder

    class Pages:
        def publish(self, ok, errors):
            pass

    builder = Builder(read_book(tiny_book.root), tiny_book.out, Pages(), say=lambda *args, **kwargs: None)
    counts = []
    for _ in range(5):  # the first rebuilds fill caches; a leak showed as a few hundred objects more per rebuild after
        assert builder.rebuild(set())
        counts.append(len(gc.get_objects()))
    assert counts[-1] - counts[2] < 100, f"objects held after each rebuild: {counts}"
