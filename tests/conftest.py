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
    """The book under content/, built into a temporary folder (build/ is left alone)."""
    folder = tmp_path_factory.mktemp("site")
    build(BuildConfig.at(ROOT, folder / "build", cache=folder / ".cache"), progress=None)
    return folder / "build"
