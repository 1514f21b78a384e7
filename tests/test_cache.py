"""The content-addressed cache: what it reuses, what it recomputes, and why it says so."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from helpers import tree, write_book

from sitegen.build import BuildConfig, build
from sitegen.compute import cache as cache_module
from sitegen.compute import sources

ROOT = Path(__file__).resolve().parents[1]
CHAPTER = "newtons-laws.md"


PAGE = """+++
title = "Two scenes"
+++

The first law is best read as a definition; here are two scenes.

```scene
model: impulse
slider F_pk: 0..50 step 2 default 12
slider tau: 0.05..1 step 0.05 default 0.2
slider m: 0.5..10 step 0.5 default 2
```

```scene
model: collision
slider m1: 0.5..5 step 0.5 default 1
slider v1i: -5..5 step 1 default 3
slider e: 0..1 step 0.25 default 1
```
"""


@pytest.fixture
def book(tmp_path) -> BuildConfig:
    """The small book, never built: an empty cache."""
    return write_book(tmp_path, {CHAPTER.removesuffix(".md"): PAGE}, cache=True)


@pytest.fixture(scope="module")
def first_build(tmp_path_factory) -> Path:
    """The small book after its first build (from an empty cache), once for the module."""
    root = tmp_path_factory.mktemp("first")
    build(write_book(root, {CHAPTER.removesuffix(".md"): PAGE}, cache=True), progress=None)
    return root


@pytest.fixture
def built(tmp_path, first_build) -> BuildConfig:
    """A copy of the small book as its first build left it: its pages, build/ and cache (the start of
    every test of a rebuild)."""
    shutil.copytree(first_build, tmp_path, dirs_exist_ok=True)
    return BuildConfig(tmp_path, tmp_path / "content", tmp_path / "build", cache=tmp_path / ".cache")


def _edit(config: BuildConfig, old: str, new: str) -> None:
    page = config.content / CHAPTER
    text = page.read_text()
    assert old in text
    page.write_text(text.replace(old, new, 1))


def _statuses(report) -> dict[str, str]:
    """Scene name -> status, from the build's per-scene lines."""
    return {line.split()[1]: line.rsplit("s  ", 1)[1] for line in report.scene_lines if line.startswith("[")}


def test_first_build_computes_every_scene_as_new(book):
    """An empty cache: every scene is computed, and --explain says it is new."""
    report = build(book, progress=None)
    assert report.computed == report.scenes > 0 and report.cached == 0
    assert set(_statuses(report).values()) == {"computed: new"}


def test_rebuild_with_nothing_changed_evaluates_nothing(built):
    """The second build takes every scene from the cache: zero model evaluations."""
    report = build(built, progress=None)
    assert (report.computed, report.evaluations, report.cached) == (0, 0, report.scenes)


def test_prose_edit_evaluates_nothing(built):
    """Editing a sentence changes the page but no scene's key."""
    _edit(built, "The first law is best read as a definition;", "The first law is really a definition;")
    report = build(built, progress=None)
    assert report.computed == 0 and report.evaluations == 0
    assert "really a definition" in (built.out / "newtons-laws.html").read_text()


def test_one_scene_edited_only_that_scene_is_computed(built):
    """Changing one scene's slider grid recomputes that scene alone, and says why."""
    _edit(built, "slider F_pk: 0..50 step 2 default 12", "slider F_pk: 0..50 step 1 default 12")
    report = build(built, progress=None)
    statuses = _statuses(report)
    assert report.computed == 1
    assert statuses.pop("newtons-laws#impulse") == "computed: spec changed"
    assert set(statuses.values()) == {"cached"}


def test_model_code_change_is_named(built, monkeypatch):
    """When the model's source hash changes, every scene of the rebuild says 'model code changed'."""
    real = cache_module.source_digest
    monkeypatch.setattr(cache_module, "source_digest", lambda modules: "edited-" + real(modules))
    report = build(built, progress=None)
    assert set(_statuses(report).values()) == {"computed: model code changed"}


def test_source_digest_follows_the_bytes_of_the_model_file(tmp_path, monkeypatch):
    """The code part of a key is a hash of the model module's bytes (and what it imports)."""
    import sitegen.models.impulse.model as impulse

    copy = tmp_path / "impulse.py"
    copy.write_bytes(Path(impulse.__file__).read_bytes())
    monkeypatch.setattr(impulse, "__file__", str(copy))
    sources.forget_sources()
    before = sources.source_digest(frozenset({"sitegen.models.impulse.model"}))
    copy.write_text(copy.read_text() + "\n# a comment changes the bytes\n")
    sources.forget_sources()
    assert sources.source_digest(frozenset({"sitegen.models.impulse.model"})) != before
    sources.forget_sources()


def test_library_version_change_is_named(built, monkeypatch):
    """A different numpy/scipy/matplotlib makes every scene recompute, saying so."""
    monkeypatch.setattr(cache_module, "library_digest", lambda: "numpy==0.0")
    report = build(built, progress=None)
    assert set(_statuses(report).values()) == {"computed: library version changed"}


def test_damaged_entry_is_reported_and_recomputed(built):
    """A truncated cache entry fails its checksum: the build says so, recomputes it, and is correct."""
    expected = (built.out / "newtons-laws.html").read_bytes()
    entry = sorted((built.cache / "tables").rglob("*.bin"))[0]
    entry.write_bytes(entry.read_bytes()[: len(entry.read_bytes()) // 2])
    report = build(built, progress=None)
    assert report.computed == 1
    assert any("damaged" in line for line in report.scene_lines)
    assert (built.out / "newtons-laws.html").read_bytes() == expected


def test_cached_and_uncached_builds_are_byte_identical(built, tmp_path):
    """Warm cache, cold cache and no cache give the same bytes."""
    warm = BuildConfig(built.root, built.content, tmp_path / "warm", cache=built.cache)
    none = BuildConfig(built.root, built.content, tmp_path / "none", cache=None)
    build(warm, progress=None)
    build(none, progress=None)
    assert tree(warm.out) == tree(built.out) == tree(none.out)


def test_cache_writes_leave_no_temporary_files(built):
    """Entries are written to a temporary file and renamed; none is left behind."""
    assert not [p for p in built.cache.rglob(".tmp-*")]


def test_changed_default_redraws_the_figure(built, tmp_path):
    """A new default moves the figure's layers: a warm-cache build equals a build without cache."""
    _edit(built, "slider F_pk: 0..50 step 2 default 12", "slider F_pk: 0..50 step 2 default 20")
    warm = build(built, progress=None)
    assert warm.computed == 0  # the tables do not depend on the default
    fresh = BuildConfig(built.root, built.content, tmp_path / "fresh", cache=None)
    build(fresh, progress=None)
    assert (built.out / CHAPTER.replace(".md", ".html")).read_bytes() == (
        fresh.out / CHAPTER.replace(".md", ".html")
    ).read_bytes()


def test_a_scene_key_reads_its_own_model_and_not_the_others():
    """The chain's key hashes the chain's modules and what they import (base, numerics) and the tabulator
    with its imports, but not the other models: editing one model's file recomputes only that model's
    scenes (tests/test_review.py checks it on the whole book, tests/test_plugins.py for each source)."""
    from sitegen.compute.cache import TABULATOR
    from sitegen.compute.sources import source_hashes
    from sitegen.registry import builtin_registry

    chain = builtin_registry().models["chain"].__module__
    modules = set(source_hashes(frozenset({chain, TABULATOR})))
    assert {
        chain,
        "sitegen.physics.base",
        "sitegen.physics.numerics",
        "sitegen.compute.grid",
        "sitegen.compute.table",
    } <= modules
    assert not [m for m in modules for other in ("ossicles", "bubble", "collision") if other in m]
