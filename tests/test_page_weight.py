"""Every build's summary says what each page weighs (raw and gzip, and gzip with what it loads), and warns
about a page above the book's budget (book.toml page_budget_kb), naming its heaviest scenes and what would
shrink them. Built on the author's oscillator book (tests/authors/oscillator)."""

from __future__ import annotations

import gzip
import shutil
from pathlib import Path

import pytest

from sitegen.build import BuildConfig, build

AUTHOR = Path(__file__).resolve().parent / "authors" / "oscillator"


@pytest.fixture
def book(tmp_path) -> BuildConfig:
    shutil.copytree(AUTHOR, tmp_path / "book", ignore=shutil.ignore_patterns(".cache", "build", "__pycache__"))
    return BuildConfig.at(tmp_path / "book")


def _gzip(path: Path) -> int:
    return len(gzip.compress(path.read_bytes(), 6, mtime=0))


def test_the_summary_has_a_line_per_page_with_its_raw_and_gzip_bytes(book):
    """The sizes are those of the files written, compressed as a static host does (gzip level 6); the page's
    download adds every asset (the one page with a scene loads every scene data file); under the default budget
    of 400 KiB there is no warning."""
    lines: list[str] = []
    report = build(book, progress=lines.append)
    page = book.out / "membrane.html"
    assets = sum(_gzip(p) for p in (book.out / "assets").rglob("*") if p.is_file())  # its scene's data too
    weight = next(w for w in report.weights if w.page == "membrane.html")
    assert (weight.raw, weight.gzip, weight.loaded_gzip) == (page.stat().st_size, _gzip(page), _gzip(page) + assets)
    assert weight.scenes == (("membrane#resonance", report.data_bytes["membrane#resonance"][0]),)
    shown = [line for line in lines if line.startswith("page ")]
    assert [line.split()[1] for line in shown] == ["index.html", "membrane.html"]
    assert (
        f"{page.stat().st_size / 1024:,.1f} KiB raw" in shown[1] and f"{_gzip(page) / 1024:,.1f} KiB gzip" in shown[1]
    )
    assert report.warnings == [] and not any(line.startswith("warning") for line in lines)


def test_a_page_over_the_budget_is_a_warning_naming_its_heaviest_scene(book):
    """page_budget_kb = 60: the page (about 70 KiB with its assets) is still written, with a warning that names
    the scene, its two largest tables and the sliders they span."""
    (book.root / "book.toml").write_text((book.root / "book.toml").read_text() + "page_budget_kb = 60\n")
    config = BuildConfig.at(book.root)
    report = build(config, progress=None)
    weight = next(w for w in report.weights if w.page == "membrane.html")
    assert (config.out / "membrane.html").is_file() and len(report.warnings) == 1
    assert report.warnings[0] == (
        f"warning: membrane.html weighs {weight.loaded_gzip / 1024:,.1f} KiB gzip with its assets, above the book's "
        "page budget of 60 KiB (book.toml page_budget_kb). Its heaviest scenes: 'resonance' "
        f"({weight.scenes[0][1] / 1024:,.1f} KiB of tables: 'ring' 18,792 values over f × zeta, 'x_now' 9,512 values "
        "over f × zeta × t). Fewer stops on those sliders, fewer decimals, or an exact form (structure=) for an "
        "output that has one would shrink them; a scene split in two loads only what each shows."
    )


def test_a_rebuild_compresses_only_what_changed(book, monkeypatch):
    """The gzip sizes are kept by the files' digests: a rebuild with nothing changed compresses nothing."""
    import sitegen.site.weight as weight

    build(book, progress=None)
    compressed = []
    gzip_bytes = weight.gzip_bytes
    monkeypatch.setattr(weight, "gzip_bytes", lambda data: compressed.append(len(data)) or gzip_bytes(data))
    assert build(book, progress=None).weights and compressed == []
