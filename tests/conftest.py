"""Shared fixtures: the tiny test book (tests/book/) and the project's own book, each built once per
session, and the markers that pick a fast subset (`make check` runs everything but `browser` and
`slow`).

A test that asks for `built_site` (the real book) or for a book built in another process (SLOW_FIXTURES)
is marked `slow`, as are the tests SLOW_TESTS lists; one that asks for `chromium`,
or lives in a browser module, is marked `browser`: the marks follow from what a test uses, so a
new test cannot forget them.
"""

from __future__ import annotations

import fcntl
import gc
import os
import shutil
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from sitegen.physics.compiled import CACHE_ENV

if TYPE_CHECKING:
    from sitegen.build import BuildConfig

# sitegen.build (matplotlib, the models) is imported where it is used, not here: the process that hands
# tests to pytest-xdist's workers imports this file too, and runs no test.

ROOT = Path(__file__).resolve().parents[1]
BOOK = Path(__file__).resolve().parent / "book"  # the tiny book: a few pages, one scene per model family
# Compiled code is keyed by content (kernels' sources, numba, target), so every book the tests build, in
# this process or another, shares the project's: the kernels compile once per checkout, not once per book.
COMPILED = ROOT / ".cache" / "compiled"
BROWSER_MODULES = {
    "test_browser",
    "test_accessibility",
    "test_chromium_reader",
    "test_firefox_reader",
    "test_webkit_reader",
}
SLOW_FIXTURES = {"built_site", "two_builds"}  # the real book; the tiny book built again in another process
# Tests that take seconds each on their own (node-id prefixes), left to `make test`:
SLOW_TESTS = (
    # an ODE solve per stop, with every solver or over whole grids (the bubble's tests of its hard cases)
    "tests/test_bubble_hard_cases.py::",
    "tests/test_properties.py::test_effect_vanishes_in_its_limit[bubble.",
    "tests/test_output_deps.py::test_output_ignores_parameters_outside_its_deps[bubble-",
    "tests/test_bubble_model.py::test_effect_vanishing_limit_reproduces_the_reduced_model[",
    "tests/test_hard_cases_extra.py::test_resonance_response_jumps_between_adjacent_frequencies_so_interpolation_fails",
    # exact rationals at tens of thousands of stops; 500 fuzzed scenes resolved
    "tests/test_tables_exact.py::test_every_checked_stop_is_exact_to_the_displayed_digit[collision]",
    "tests/test_tables_exact.py::test_every_checked_stop_is_exact_to_the_displayed_digit[lever]",
    "tests/test_fuzz.py::test_scene_resolution_never_crashes",
    # many builds, or builds in other processes, of small books
    "tests/test_fuzz.py::test_build_of_fuzzed_books_succeeds_or_reports_author_errors",
    "tests/test_interrupted_build.py::test_kill",
    "tests/test_build.py::test_computing_from_nothing_is_deterministic_across_hash_seeds",
    "tests/test_build.py::test_the_work_ahead_gives_the_bytes_of_work_done_here",
    "tests/test_review.py::test_review_against_a_revision_builds_it_in_a_temporary_worktree",
    "tests/test_build.py::test_builds_are_byte_identical_across_folders_and_hash_seeds",
    "tests/test_collect.py::test_a_watcher_keeps_nothing_of_its_earlier_builds",  # five rebuilds
    "tests/test_executors.py::test_dask_cluster_gives_the_serial_bytes",
    "tests/test_executors.py::test_a_process_beside_that_dies_leaves_its_pages_to_the_build",  # a book built twice
    "tests/test_executors.py::test_after_an_author_error_here_the_pages_beside_are_built_here",
    "tests/test_executors.py::test_sigterm_stops_a_build_as_ctrl_c_does",  # a book built in another process
    "tests/test_executors.py::test_a_table_on_both_sides_is_not_split_even_when_cached",  # a book built twice
    "tests/test_determinism_load.py::",  # bubble books built in other processes, beside spinning CPUs
    # pip building and installing the wheel (and a fresh venv that builds a book with it)
    "tests/test_install.py::test_installing_writes_nothing_into_build",
    "tests/test_install.py::test_the_wheel_carries",
    "tests/test_install.py::test_the_installed_wheel_builds_a_book_elsewhere",
    "tests/test_install.py::test_a_new_book_builds_and_previews_with_the_installed_tool",
)
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault(CACHE_ENV, str(COMPILED))  # the tests that call the solvers directly, and their subprocesses


# The test files that take longest in `make test`, longest first. pytest-xdist hands a process one whole file at a
# time, in the order of the collection (with --no-loadscope-reorder, as the Makefile asks; by default it orders the
# files by their number of tests), so the long files start first and the short ones fill in at the end. Left to the
# default, a file of two long tests came last and ran alone for 40 s while the other processes had nothing to do.
LONGEST_FIRST = (
    "test_webkit_reader",
    "test_firefox_reader",
    "test_browser",
    "test_accessibility",
    "test_reader_tools",
    "test_properties",
    "test_interrupted_build",
    "test_layout",
    "test_determinism_load",
    "test_figure_goldens",
    "test_install",
    "test_bubble_hard_cases",
    "test_sweep",
    "test_bubble_model",
    "test_review",
    "test_fuzz",
    "test_bubble_compiled",
    "test_build",
    "test_preview",
    "test_tables_exact",
    "test_executors",
    "test_stamp",
    "test_html_validity",
    "test_plugins",
)


COLLECTED = pytest.StashKey[list]()  # the node ids of every test collected, before -m or -k leave any out


@pytest.hookimpl(tryfirst=True)  # before -m and -k deselect: they read these marks
def pytest_collection_modifyitems(config, items) -> None:
    """Mark what builds the real book or a book in another process (or is listed in SLOW_TESTS) `slow`, and
    what drives Chromium `browser`; put the longest files first."""
    config.stash[COLLECTED] = [item.nodeid for item in items]
    rank = {name: k for k, name in enumerate(LONGEST_FIRST)}
    items.sort(key=lambda item: rank.get(item.path.stem, len(rank)))  # stable: the rest keep their order
    for item in items:
        names = set(getattr(item, "fixturenames", ()))
        if names & SLOW_FIXTURES or item.nodeid.startswith(SLOW_TESTS):
            item.add_marker(pytest.mark.slow)
        if "chromium" in names or item.module.__name__ in BROWSER_MODULES:
            item.add_marker(pytest.mark.browser)


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
    """The project's compiled code (.cache/compiled/) with the bubble's kernels complete, loaded in this process:
    compiled here, or (another test process compiling them) loaded once it is done. A build sharing it then
    loads them, and tabulates its bubble scenes ahead, whatever ran before; with them missing it would compile."""
    from sitegen.models.bubble.model import Bubble

    Bubble().prepare_kernels(COMPILED)
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


def pytest_collection_finish(session) -> None:
    """Young objects collected every 10,000 allocations, not Python's 700, as a build does (phases/collect.py):
    a test process allocates without pause, and the collector ran tens of thousands of times a run for
    little (make check: 58 s -> about 51 s). Freezing the shared objects as well gained nothing measurable:
    every build lets go of what was frozen when it ends."""
    from sitegen.phases.collect import YOUNG

    gc.set_threshold(YOUNG, *gc.get_threshold()[1:])


def pytest_terminal_summary(terminalreporter) -> None:
    """The browser engines the tests drove, as each reported its version (reader_checks.py records them)."""
    versions = {
        value
        for reports in terminalreporter.stats.values()
        for report in reports
        for name, value in getattr(report, "user_properties", ())
        if name == "browser"
    }
    if versions:
        terminalreporter.write_line("browser engines: " + ", ".join(sorted(versions)))


@pytest.hookimpl(trylast=True)
def pytest_unconfigure(config) -> None:
    """Leave the heap to the process's exit unsearched, as the `sitegen` command does (cli.run): at exit Python
    looks through every object it holds for reference cycles, a second or so in a test process that has
    imported the whole package and built books; the run waits for each of its processes to end."""
    gc.disable()
    gc.freeze()
