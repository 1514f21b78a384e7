"""`sitegen new DIR`: writes the starter book (and nothing over an existing one), which builds at once
into pages with a scene of the book's own model. (The installed wheel does the same in a fresh venv:
tests/test_install.py.)"""

from __future__ import annotations

import re
import subprocess
import sys

import pytest
from helpers import names

from sitegen.build import BuildConfig, build
from sitegen.errors import SceneCrashed
from sitegen.newbook import STARTER, starter_files

NEW = [sys.executable, "-m", "sitegen.cli", "new"]


def test_new_writes_the_starter_book(tmp_path):
    """Every starter file, byte for byte (the package's gitignore as .gitignore), into a folder it makes."""
    done = subprocess.run([*NEW, "mybook"], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    book = tmp_path / "mybook"
    expected = {(".gitignore" if p.as_posix() == "gitignore" else p.as_posix()): p for p in starter_files()}
    assert names(book) == sorted(expected)
    for name, source in expected.items():
        assert (book / name).read_bytes() == (STARTER / source).read_bytes(), name
    assert {
        "book.toml",
        "content/index.md",
        "content/pendulum.md",
        "models/pendulum/model.py",
        "models/pendulum/figure.py",
        "tests/test_pendulum.py",
    } <= set(expected)
    assert "cd mybook && sitegen build" in done.stdout


def test_new_writes_into_an_empty_folder(tmp_path):
    (tmp_path / "empty").mkdir()
    done = subprocess.run([*NEW, "empty"], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and (tmp_path / "empty" / "book.toml").is_file(), done.stderr


@pytest.mark.parametrize(
    "existing", ["notes.txt", ".git/config", "content/index.md"], ids=["a-file", "a-hidden-folder", "a-book"]
)
def test_new_refuses_a_folder_that_is_not_empty(tmp_path, existing):
    """Exit 2 with a sentence naming what is there; nothing is written or changed."""
    folder = tmp_path / "book"
    (folder / existing).parent.mkdir(parents=True, exist_ok=True)
    (folder / existing).write_text("mine\n")
    done = subprocess.run([*NEW, str(folder)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert (
        f"{folder} is not empty (it holds {existing.split('/')[0]}); "
        "sitegen new writes a book into a new or empty folder" in done.stderr
    )
    assert names(folder) == [existing] and (folder / existing).read_text() == "mine\n"


def test_new_refuses_a_file(tmp_path):
    (tmp_path / "book").write_text("mine\n")
    done = subprocess.run([*NEW, "book"], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and "is a file" in done.stderr and (tmp_path / "book").read_text() == "mine\n"


def test_the_new_book_builds_with_a_scene_of_its_own_model(tmp_path):
    """The starter builds without a change: a home page linking the chapter, whose scene is the book's
    pendulum with its sliders, readouts and figure, and its equations numbered and referenced."""
    subprocess.run([*NEW, "mybook"], cwd=tmp_path, check=True, capture_output=True, timeout=60)
    config = BuildConfig.at(tmp_path / "mybook")
    report = build(config, progress=None)
    assert (report.pages, report.scenes, report.computed) == (2, 1, 1)
    home, chapter = ((config.out / name).read_text() for name in ("index.html", "pendulum.html"))
    assert 'href="pendulum.html"' in home
    assert 'data-scene="pendulum"' in chapter and 'data-param="theta0"' in chapter and 'data-param="L"' in chapter
    assert all(f'data-out="{name}"' in chapter for name in ("T", "T0", "ratio")) and 'data-layer="bob"' in chapter
    assert chapter.count("<math") >= 4 and ">(2)<" in chapter


def _starter_copy(tmp_path) -> BuildConfig:
    subprocess.run([*NEW, "mybook"], cwd=tmp_path, check=True, capture_output=True, timeout=60)
    return BuildConfig.at(tmp_path / "mybook")


def test_a_dots_layer_with_a_fill_is_an_error_at_the_figures_line(tmp_path):
    """Dots are drawn by their stroke: a fill would silently show nothing, so it fails the build at the
    figure's own line, saying what to write instead."""
    config = _starter_copy(tmp_path)
    figure = config.root / "models" / "pendulum" / "figure.py"
    text = figure.read_text()
    figure.write_text(
        text.replace('style={"stroke": s.BLUE, "stroke-width": "14"}', 'style={"fill": s.BLUE, "stroke-width": "14"}')
    )
    line = next(n for n, row in enumerate(figure.read_text().splitlines(), 1) if '"fill": s.BLUE' in row)
    with pytest.raises(SceneCrashed) as crash:
        build(config, progress=None)
    message = str(crash.value)
    fence = (config.root / "content" / "pendulum.md").read_text().splitlines().index("```scene") + 1
    assert message.startswith(
        f"content/pendulum.md:{fence}: scene 'pendulum': models/pendulum/figure.py:{line}: ValueError: "
    )
    assert (
        "layer 'bob': a dots layer draws each dot with its stroke" in message
        and "give the dots' colour as 'stroke'" in message
    )


def test_a_polyline_without_a_fill_is_not_filled(tmp_path):
    """SVG fills a shape unless told not to; a polyline layer is drawn as a line unless its style gives a fill."""
    config = _starter_copy(tmp_path)
    figure = config.root / "models" / "pendulum" / "figure.py"
    figure.write_text(
        figure.read_text().replace('style={"fill": "none", "stroke": s.MUTED,', 'style={"stroke": s.MUTED,')
    )
    build(config, progress=None)
    arcs = re.findall(r'<polyline data-layer="arc"[^>]*>', (config.out / "pendulum.html").read_text())
    assert len(arcs) == 2 and all('fill="none"' in arc for arc in arcs)  # the wide and the narrow figure
