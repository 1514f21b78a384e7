"""Figure goldens: every scene's figure at its defaults, byte for byte, against the book's goldens
(this repository's book keeps them in goldens/, as its book.toml says; the tiny test book in
tests/book/goldens/).

A mismatch writes NAME-changed.svg and NAME-changed.png (golden, new and the pixel difference side
by side) next to the golden for a person to look at. Goldens are never rewritten by a test (nor in
CI); `make accept-figures` rewrites them on purpose.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from sitegen.cli import main
from sitegen.config import read_book
from sitegen.content.pages import discover_pages, read_page
from sitegen.review.goldens import accept_figures, changed_paths, check_figure, golden_names, golden_path
from sitegen.review.tree import NARROW_SUFFIX, page_figures

ROOT = Path(__file__).resolve().parents[1]
GOLDENS = read_book(ROOT).goldens
ACCEPT = "run `sitegen accept-figures`"


def _source_scenes() -> list[str]:
    """ "<page>/<scene id>" for every scene of the book, read from content/ at collection time, and
    "<page>/<scene id>.narrow" for its phone figure (every figure of the book draws one)."""
    names = []
    for path in discover_pages(ROOT / "content"):
        page, _ = read_page(path, ROOT)
        if page is not None:
            names += [
                f"{page.slug}/{spec.id}{variant}" for spec in page.extracted.scenes for variant in ("", NARROW_SUFFIX)
            ]
    return names


SCENES = _source_scenes()


@pytest.fixture(scope="module")
def figures(built_site) -> dict[str, str]:
    """Every scene figure of the built book, standalone SVG, by "<page>/<scene id>"."""
    return page_figures(built_site)


def test_the_build_has_a_figure_for_every_scene_of_the_sources(figures):
    """The scenes found in the build are exactly the scenes of content/ (so every one is checked)."""
    assert sorted(figures) == sorted(SCENES)


@pytest.mark.parametrize("name", SCENES)
def test_figure_matches_its_golden(figures, name):
    """The figure at its defaults is byte-identical to its golden."""
    problem = check_figure(GOLDENS, name, figures[name])
    if problem:
        pytest.fail(problem, pytrace=False)


def test_every_golden_belongs_to_a_scene(figures):
    """No golden is left over from a scene that was renamed or removed."""
    stale = sorted(set(golden_names(GOLDENS)) - set(figures))
    assert not stale, f"goldens without a scene: {', '.join(stale)}; {ACCEPT} to remove them"


def test_the_repository_book_keeps_its_goldens_in_its_folder():
    """The goldens are the book's (goldens/ beside content/), not the tool's tests'."""
    assert GOLDENS == ROOT / "goldens" and len(golden_names(GOLDENS)) == len(SCENES)


# --- any book: the tiny test book's goldens, by the commands ----------------------------------------


@pytest.mark.browser  # a differing figure is drawn in Chromium (the tool's own), so it is left to `make test`
def test_check_figures_passes_on_the_tiny_book_and_names_a_changed_figure(tiny_book, tiny_site, capsys, monkeypatch):
    """`sitegen check-figures` in a book's folder compares its build with its goldens/: 0 when equal,
    1 naming the figure when one differs, and `accept-figures` makes them equal again."""
    monkeypatch.delenv("CI", raising=False)
    monkeypatch.chdir(tiny_book.root)
    assert main(["check-figures", "--build", str(tiny_site)]) == 0
    name = golden_names(tiny_book.root / "goldens")[0]
    golden = golden_path(tiny_book.root / "goldens", name)
    golden.write_text(golden.read_text().replace("</svg>", "<!-- edited --></svg>"))
    capsys.readouterr()
    assert main(["check-figures", "--build", str(tiny_site)]) == 1
    assert f"figure '{name}' differs from its golden" in capsys.readouterr().out
    assert main(["accept-figures", "--build", str(tiny_site)]) == 0
    assert main(["check-figures", "--build", str(tiny_site)]) == 0


def test_the_tiny_book_has_a_golden_for_every_scene(tiny_site):
    """The tool's own tests use their own book's goldens (tests/book/goldens), complete."""
    assert sorted(page_figures(tiny_site)) == golden_names(ROOT / "tests" / "book" / "goldens")


# --- the golden mechanics, on a scratch folder ------------------------------------------------------


@pytest.fixture
def scratch(tmp_path, figures, monkeypatch) -> tuple[Path, str, str]:
    """A goldens folder holding one real figure's golden, outside CI."""
    monkeypatch.delenv("CI", raising=False)
    name = sorted(figures)[0]
    golden_path(tmp_path, name).parent.mkdir(parents=True)
    golden_path(tmp_path, name).write_text(figures[name])
    return tmp_path, name, figures[name]


def test_a_mismatch_leaves_the_new_figure_and_a_png_next_to_the_golden(scratch):
    """A changed figure fails with the size of the change and leaves -changed files; the golden stays."""
    goldens, name, svg = scratch
    moved = (
        svg.replace('stroke-width="2.2"', 'stroke-width="6"', 1)
        if 'stroke-width="2.2"' in svg
        else svg.replace("#1f63b5", "#c8541c", 1)
    )
    assert moved != svg
    problem = check_figure(goldens, name, moved)
    changed_svg, changed_png = changed_paths(goldens, name)
    assert problem and ACCEPT in problem and str(changed_svg) in problem
    assert changed_svg.read_text() == moved and golden_path(goldens, name).read_text() == svg
    if "no PNG" not in problem:
        assert changed_png.read_bytes().startswith(b"\x89PNG") and "of the figure" in problem
    assert check_figure(goldens, name, svg) is None
    assert not changed_svg.exists() and not changed_png.exists()


def test_a_scene_without_a_golden_fails_with_what_to_run(scratch):
    """A new scene is a failure that says how to add its golden; nothing is written."""
    goldens, _, svg = scratch
    problem = check_figure(goldens, "page/new-scene", svg)
    assert (
        problem
        == f"figure 'page/new-scene' has no golden ({golden_path(goldens, 'page/new-scene')}); {ACCEPT} to add it"
    )
    assert not golden_path(goldens, "page/new-scene").exists()


def test_accept_figures_writes_new_and_changed_and_removes_stale(scratch, built_site):
    """accept_figures makes the folder exactly the build's figures."""
    goldens, name, svg = scratch
    golden_path(goldens, name).write_text(svg + "<!-- old -->\n")
    golden_path(goldens, "gone/scene").parent.mkdir()
    golden_path(goldens, "gone/scene").write_text(svg)
    done = accept_figures(built_site, goldens)
    assert done.changed == [name] and done.removed == ["gone/scene"] and len(done.new) == len(SCENES) - 1
    assert golden_names(goldens) == sorted(SCENES) and not (goldens / "gone").exists()


def test_accept_figures_refuses_in_ci(scratch, built_site, monkeypatch):
    """Goldens are never rewritten in CI."""
    goldens, name, svg = scratch
    monkeypatch.setenv("CI", "true")
    with pytest.raises(PermissionError, match="never rewritten in CI"):
        accept_figures(built_site, goldens)
    assert golden_names(goldens) == [name]
