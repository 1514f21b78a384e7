"""Shared fixtures: the project's own book built once per test session."""
from __future__ import annotations

import os
from pathlib import Path

import pytest

from sitegen.build import BuildConfig, build

ROOT = Path(__file__).resolve().parents[1]
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


@pytest.fixture(scope="session")
def built_site(tmp_path_factory) -> Path:
    """The book under content/, built into a temporary folder (build/ is left alone).

    It uses the project's cache (.cache/), as `make site` does: on a fresh clone this is the one
    build of the book that computes everything (the bubble scenes take minutes), and the other
    builds of the book in the suite reuse its tables. tests/test_build.py checks computing from
    nothing separately.
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
