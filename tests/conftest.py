"""Shared fixtures: the tiny test book (tests/book/) and the project's own book, each built once per
session, and the markers that pick a fast subset (`make check` runs everything but `browser` and
`slow`).

A test that takes seconds carries `@pytest.mark.slow` (or its module `pytestmark`, or its case
`pytest.param(..., marks=...)`); a test that asks for `built_site` (the real book) is marked `slow`
here and one that asks for `chromium` `browser`, so that a new test using them cannot forget the mark.
"""

from __future__ import annotations

import fcntl
import gc
import os
import shutil
from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

if TYPE_CHECKING:
    from sitegen.build import BuildConfig

# sitegen.build (matplotlib, the models) is imported where it is used, not here: the process that hands
# tests to pytest-xdist's workers imports this file too, and runs no test.

ROOT = Path(__file__).resolve().parents[1]
BOOK = Path(__file__).resolve().parent / "book"  # the tiny book: a few pages, one scene per model family
# Compiled code is keyed by content (kernels' sources, numba, target), so every book the tests build, in
# this process or another, shares the project's: the kernels compile once per checkout, not once per book.
# (Set before sitegen.physics.compiled is first imported, which reads it.)
COMPILED = ROOT / ".cache" / "compiled"
os.environ.setdefault("SITEGEN_COMPILED_CACHE", str(COMPILED))  # the tests' builds, solvers and subprocesses
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


COLLECTED = pytest.StashKey[list]()  # the node ids of every test collected, before -m or -k leave any out


@pytest.hookimpl(tryfirst=True)  # before -m and -k deselect: they read these marks
def pytest_collection_modifyitems(config, items) -> None:
    """Mark what builds the real book `slow` and what drives Chromium `browser`; put the files with such tests first."""
    config.stash[COLLECTED] = [item.nodeid for item in items]
    for item in items:
        names = set(getattr(item, "fixturenames", ()))
        if "built_site" in names:
            item.add_marker(pytest.mark.slow)
        if "chromium" in names:
            item.add_marker(pytest.mark.browser)
    weight = Counter()
    for item in items:
        weight[item.path] += 2 * bool(item.get_closest_marker("browser")) + bool(item.get_closest_marker("slow"))
    items.sort(key=lambda item: -weight[item.path])  # stable: each file's tests keep their order


def share_compiled(root: Path) -> None:
    """Point the book at `root` to the project's compiled code (.cache/compiled/, a link)."""
    COMPILED.mkdir(parents=True, exist_ok=True)
    (root / ".cache").mkdir(parents=True, exist_ok=True)
    (root / ".cache" / "compiled").symlink_to(COMPILED, target_is_directory=True)


def copy_book(root: Path, cache: Path | None = None) -> BuildConfig:
    """A copy of the tiny book at `root` (its book.toml, content and goldens), with a copy of `cache`
    when given; its compiled code is the project's."""
    from sitegen.build import BuildConfig

    shutil.copytree(BOOK / "content", root / "content")
    shutil.copytree(BOOK / "goldens", root / "goldens")
    shutil.copy(BOOK / "book.toml", root / "book.toml")
    if cache is not None:
        shutil.copytree(cache, root / ".cache", ignore=shutil.ignore_patterns("compiled"))
    share_compiled(root)
    return BuildConfig.at(root)


@pytest.fixture
def register(monkeypatch):
    """register(models, figures): models and figure views defined by a test, added to the registry that
    every build of the test loads (as if a plugin declared them)."""
    import sitegen.build

    added = {"models": {}, "figures": {}}
    load = sitegen.build.load_registry
    monkeypatch.setattr(
        sitegen.build,
        "load_registry",
        lambda book=None: load(book).adding(added["models"], added["figures"], "the test"),
    )

    def _register(models: dict, figures: dict) -> None:
        added["models"].update(models)
        added["figures"].update(figures)

    return _register


@pytest.fixture(scope="session")
def collected_ids(request) -> list[str]:
    """The node ids of every test this run collected, selected or not."""
    return request.config.stash[COLLECTED]


def made_once(tmp_path_factory, name: str, make: Callable[[Path], object]) -> Path:
    """The folder `name`, filled by `make(folder)` once per test run: when pytest-xdist runs the tests in
    several processes, the first to ask makes it while the others wait for it, and all read the same."""
    base = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        base = base.parent  # the workers' temporary folders sit side by side in the run's own
    folder, done = base / name, base / f"{name}.done"
    with open(base / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes, also if `make` fails
        if not done.exists():
            shutil.rmtree(folder, ignore_errors=True)  # what a failed attempt left
            folder.mkdir()
            make(folder)
            done.touch()
    return folder


@pytest.fixture(scope="session")
def bubble_kernels() -> Path:
    """The project's compiled code (.cache/compiled/) with the bubble's kernels in it, loaded in this process
    (compiled here if they were missing): a build or a worker process then loads them."""
    from sitegen.models.bubble.solve import warm_up

    warm_up()
    return COMPILED


@pytest.fixture(scope="session")
def tiny_built(tmp_path_factory) -> BuildConfig:
    """The tiny book built once from nothing (its own cache, filled by this build)."""
    from sitegen.build import BuildConfig, build

    return BuildConfig.at(made_once(tmp_path_factory, "tiny", lambda folder: build(copy_book(folder), progress=None)))


@pytest.fixture(scope="session")
def tiny_site(tiny_built) -> Path:
    """The tiny book's build/ (read it, do not change it)."""
    return tiny_built.out


@pytest.fixture
def tiny_book(tmp_path, tiny_built) -> BuildConfig:
    """A fresh copy of the tiny book for one test, with a warm copy of its cache and no build/ yet."""
    return copy_book(tmp_path / "book", tiny_built.cache)


@pytest.fixture(scope="session")
def built_site(tmp_path_factory) -> Path:
    """The book under content/, built into a temporary folder (build/ is left alone).

    It uses the project's cache (.cache/), as `make site` does: on a fresh clone this is the one
    build of the book that computes everything, and the other builds of the book in the suite
    reuse its tables.
    """
    from sitegen.build import BuildConfig, build

    folder = made_once(
        tmp_path_factory, "site", lambda folder: build(BuildConfig.at(ROOT, folder / "build"), progress=None)
    )
    return folder / "build"


# Module scope: another module may start Playwright's sync API of its own (the review's renderer),
# which cannot run while a browser's event loop is open in the same thread.
@pytest.fixture(scope="module")
def chromium():
    """Debian's Chromium, headless, for the browser tests of one module."""
    from browser import close, launch
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        browser = launch(playwright)
        yield browser
        close(browser)


@pytest.fixture(scope="module")
def tabs(chromium):
    """Pages of the module's browser kept open to load documents in, by their options (see browser.Tabs)."""
    from browser import Tabs

    return Tabs(chromium)


def engines_line(reports) -> str | None:
    """The log's line of the browser engines and their versions, when a browser test ran among `reports`."""
    if not any(isinstance(r, pytest.TestReport) and "browser" in r.keywords for r in reports):
        return None
    from engines import installed_versions

    return "browser engines: " + ", ".join(installed_versions())


def pytest_terminal_summary(terminalreporter) -> None:
    """Name each browser engine with its version at the end of a run that drove one (with pytest-xdist the
    workers' reports, marks included, come back to this process, which prints it)."""
    line = engines_line(report for reports in terminalreporter.stats.values() for report in reports)
    if line:
        terminalreporter.write_line(line)


def pytest_collection_finish(session) -> None:
    """Young objects collected every 10,000 allocations, not Python's 700, as a build does (phases/collect.py):
    a test process allocates without pause, and the collector ran tens of thousands of times a run for
    little (make check: 58 s -> about 51 s). Freezing the shared objects as well gained nothing measurable:
    every build lets go of what was frozen when it ends."""
    from sitegen.phases.collect import YOUNG

    gc.set_threshold(YOUNG, *gc.get_threshold()[1:])


@pytest.hookimpl(trylast=True)
def pytest_unconfigure(config) -> None:
    """Leave the heap to the process's exit unsearched, as the `sitegen` command does (cli.run): at exit Python
    looks through every object it holds for reference cycles, a second or so in a test process that has
    imported the whole package and built books; the run waits for each of its processes to end."""
    gc.disable()
    gc.freeze()
