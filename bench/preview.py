"""`make bench`: the live preview. Prints, as min / median / max over several runs,

1. the rebuild that `sitegen serve --watch` runs after a prose edit — in one process, the models
   loaded, every scene cached — for the starter book of `sitegen new` and for this repository's book
   (its cache in .cache/, as `make site` leaves it);
2. in Chromium, the time from saving a prose edit of the starter book to the open page showing it
   (the watcher's events, the rebuild, the page's reload).

Usage: python bench/preview.py [RUNS]   (default 10)
"""

from __future__ import annotations

import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))  # the watch-server helper of the tests

from playwright.sync_api import sync_playwright  # noqa: E402
from preview import WatchServer  # noqa: E402

from sitegen.build import BuildConfig, build  # noqa: E402
from sitegen.newbook import new_book  # noqa: E402
from sitegen.registry import load_registry  # noqa: E402
from sitegen.review.figures import CHROMIUM, LAUNCH_ARGS  # noqa: E402


def spread(seconds: list[float]) -> str:
    return (
        f"min {min(seconds):.3f} s, median {statistics.median(seconds):.3f} "
        f"s, max {max(seconds):.3f} s ({len(seconds)} runs)"
    )


def rebuild_times(config: BuildConfig, page: Path, runs: int) -> list[float]:
    """Seconds of each in-process rebuild after appending a sentence to `page` (the first build is untimed)."""
    registry = load_registry(config.book)
    build(config, progress=None, registry=registry)
    times = []
    for run in range(runs):
        page.write_text(page.read_text() + f"\nA sentence added for run {run}.\n")
        start = time.perf_counter()
        report = build(config, progress=None, registry=registry)
        times.append(time.perf_counter() - start)
        assert report.computed == 0, "a prose edit recomputed a scene"
    return times


def browser_times(book: Path, runs: int) -> list[float]:
    """Seconds from saving a prose edit to the open page showing it, through serve --watch."""
    server = WatchServer(book)
    try:
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
            page = browser.new_page()
            page.goto(server.url("pendulum.html"))
            times = []
            for run in range(runs):
                source = book / "content" / "pendulum.md"
                marker = f"Edit number {run} of the bench."
                start = time.perf_counter()
                source.write_text(source.read_text() + f"\n{marker}\n")
                page.wait_for_function(f"document.body.innerText.includes({marker!r})", timeout=10_000)
                times.append(time.perf_counter() - start)
                page.wait_for_load_state("load")
            browser.close()
    finally:
        server.stop()
    return times


def main(runs: int) -> None:
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    with tempfile.TemporaryDirectory() as scratch:
        starter = Path(scratch) / "starter"
        new_book(starter)
        print(
            "preview: starter book, rebuild after a prose edit: "
            f"{spread(rebuild_times(BuildConfig.at(starter), starter / 'content' / 'pendulum.md', runs))}",
            flush=True,
        )
        copy = Path(scratch) / "repository-book"
        shutil.copytree(ROOT / "content", copy / "content")
        shutil.copy(ROOT / "book.toml", copy / "book.toml")
        config = BuildConfig.at(copy, cache=ROOT / ".cache")
        print(
            "preview: this repository's book, rebuild after a prose edit: "
            f"{spread(rebuild_times(config, copy / 'content' / 'newtons-laws.md', runs))}",
            flush=True,
        )
        print(f"preview: starter book, prose edit saved -> shown in Chromium: {spread(browser_times(starter, runs))}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10)
