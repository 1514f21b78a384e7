"""Shared fixtures: the tiny test book (tests/book/) and the project's own book, each built once per
session, and the markers that pick a fast subset (`make check` runs everything but `browser` and
`slow`).

A test that asks for `built_site` (the real book) is marked `slow`; one that asks for `chromium`,
or lives in a browser module, is marked `browser`: the marks follow from what a test uses, so a
new test cannot forget them.
"""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

import sitegen.build
from sitegen.build import BuildConfig, build
from sitegen.registry import builtin_registry

ROOT = Path(__file__).resolve().parents[1]
BOOK = Path(__file__).resolve().parent / "book"  # the tiny book: a few pages, one scene per model family
BROWSER_MODULES = {"test_browser", "test_accessibility"}
# Tests that take seconds each on their own (node-id prefixes), left to `make test`:
SLOW_TESTS = (
    # an ODE solve per stop, with every solver or over whole grids (the bubble's tests of its hard cases)
    "tests/test_bubble_hard_cases.py::",
    "tests/test_properties.py::test_effect_vanishes_in_its_limit[bubble.",
    "tests/test_output_deps.py::test_output_ignores_parameters_outside_its_deps[bubble-",
    "tests/test_bubble_model.py::test_effect_vanishing_limit_reproduces_the_reduced_model[",
    "tests/test_hard_cases_extra.py::test_resonance_response_jumps_between_adjacent_frequencies_so_interpolation_fails",
    # many builds, or builds in other processes, of small books
    "tests/test_fuzz.py::test_build_of_fuzzed_books_succeeds_or_reports_author_errors",
    "tests/test_interrupted_build.py::test_kill",
    "tests/test_build.py::test_computing_from_nothing_is_deterministic_across_hash_seeds",
    "tests/test_review.py::test_review_against_a_revision_builds_it_in_a_temporary_worktree",
    "tests/test_executors.py::test_dask_cluster_gives_the_serial_bytes",
    # pip building and installing the wheel (and a fresh venv that builds a book with it)
    "tests/test_install.py::test_installing_writes_nothing_into_build",
    "tests/test_install.py::test_the_wheel_carries",
    "tests/test_install.py::test_the_installed_wheel_builds_a_book_elsewhere",
    "tests/test_install.py::test_a_new_book_builds_and_previews_with_the_installed_tool",
)
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def pytest_collection_modifyitems(items) -> None:
    """Mark what builds the real book (or is listed in SLOW_TESTS) `slow` and what drives Chromium `browser`."""
    for item in items:
        names = set(getattr(item, "fixturenames", ()))
        if "built_site" in names or item.nodeid.startswith(SLOW_TESTS):
            item.add_marker(pytest.mark.slow)
        if "chromium" in names or item.module.__name__ in BROWSER_MODULES:
            item.add_marker(pytest.mark.browser)


def copy_book(root: Path, cache: Path | None = None) -> BuildConfig:
    """A copy of the tiny book at `root` (its book.toml, content and goldens), with a copy of `cache` when given."""
    shutil.copytree(BOOK / "content", root / "content")
    shutil.copytree(BOOK / "goldens", root / "goldens")
    shutil.copy(BOOK / "book.toml", root / "book.toml")
    if cache is not None:
        shutil.copytree(cache, root / ".cache")
    return BuildConfig.at(root)


@pytest.fixture
def register(monkeypatch):
    """register(models, figures): models and figure views defined by a test, added to the registry that
    every build of the test loads (as if a plugin declared them)."""
    added = {"models": {}, "figures": {}}
    load = sitegen.build.load_registry
    monkeypatch.setattr(sitegen.build, "load_registry",
                        lambda book=None: load(book).adding(added["models"], added["figures"], "the test"))

    def _register(models: dict, figures: dict) -> None:
        added["models"].update(models)
        added["figures"].update(figures)

    return _register


BUILTIN = builtin_registry()  # the built-in models and figures, for tests that use them directly


@pytest.fixture(scope="session")
def tiny_built(tmp_path_factory) -> BuildConfig:
    """The tiny book built once from nothing (its own cache, filled by this build)."""
    config = copy_book(tmp_path_factory.mktemp("tiny"))
    build(config, progress=None)
    return config


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
    folder = tmp_path_factory.mktemp("site")
    build(BuildConfig.at(ROOT, folder / "build"), progress=None)
    return folder / "build"


# Module scope: another module may start Playwright's sync API of its own (the review's renderer),
# which cannot run while a browser's event loop is open in the same thread.
@pytest.fixture(scope="module")
def chromium():
    """Debian's Chromium, headless, for the browser tests of one module."""
    from playwright.sync_api import sync_playwright

    from browser import launch

    with sync_playwright() as playwright:
        browser = launch(playwright)
        yield browser
        browser.close()
