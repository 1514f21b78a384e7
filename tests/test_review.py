"""`sitegen review`: tables decoded and compared stop by stop, text diffs, and the whole review end to
end — a changed model constant shows up as exactly that scene's figure and numbers, identical builds
exit 0, and `--base REV` builds a git revision in a temporary worktree."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from helpers import write_book

from sitegen.cli import main
from sitegen.review import review_builds
from sitegen.review.compare import text_diff
from sitegen.review.decode import decode
from sitegen.review.figures import CHROMIUM
from sitegen.review.tables import compare_table
from sitegen.review.tree import parse_page, text_lines

ROOT = Path(__file__).resolve().parents[1]
# The constant the end-to-end test changes, and every output of its scene that depends on it.
MODEL_FILE = "src/sitegen/models/ossicles/model.py"
CONSTANT = ("Z_AIR = 1.204 * 343.2", "Z_AIR = 1.293 * 331.3")  # air at 20 °C -> air at 0 °C
# The outputs the cochlea's impedance enters, and the two coordinate tables ("~…") the page's
# expressions for T1, T1_dB and ell_match read it through.
AFFECTED = {"T0", "T0_dB", "T1", "T1_dB", "ell_match", "~load_per_Z_air", "~sqrt_load_per_Z_air"}


def _can_render() -> bool:
    try:
        import playwright  # noqa: F401
    except ImportError:
        return False
    return Path(CHROMIUM).exists()


# --- decoding the inline tables -----------------------------------------------------------------

SLIDERS = [
    {"param": "a", "kind": "range", "count": 3, "unit": "kg", "lo": 5, "step": 5, "d": 1},  # 0.5, 1.0, 1.5
    {"param": "b", "kind": "choice", "count": 2, "unit": "", "values": [0, 1], "texts": ["water", "air"]},
]


def _data(tables: dict, sliders=SLIDERS) -> dict:
    return {"sliders": sliders, "tables": tables, "readouts": [], "layers": []}


@pytest.mark.parametrize(
    "entry, expected",
    [
        (
            {"axes": [0, 1], "shape": [3, 2], "d": 2, "q": [100, 200, 300, 400, 500, 600]},
            [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]],
        ),
        (
            {"axes": [0, 1], "shape": [3, 2], "d": 2, "q": [100, 100, 100, 100, 100, 100], "enc": "delta"},
            [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]],
        ),
        ({"axes": [0], "shape": [3], "d": 0, "q": [1, None, 3], "special": "∞"}, [1.0, np.inf, 3.0]),
        ({"axes": [], "shape": [], "d": 3, "q": [1234]}, 1.234),
    ],
    ids=["plain", "delta", "special", "no-slider"],
)
def test_scalar_tables_decode_to_values(entry, expected):
    """Integers of the last digit become values; differences are summed; null is the special value."""
    assert np.array_equal(decode(_data({"x": entry}), "x").values, np.array(expected))


def test_vector_deltas_are_summed_within_each_vector_and_short_vectors_padded():
    """A ragged vector table: each row's differences summed on their own, padding is NaN."""
    entry = {"axes": [0], "shape": [3], "d": 1, "q": [[10, 10], [20, 0, 5], []], "enc": "delta"}
    values = decode(_data({"v": entry}), "v").values
    assert values.shape == (3, 3)
    assert np.array_equal(values, [[1.0, 2.0, np.nan], [2.0, 2.0, 2.5], [np.nan] * 3], equal_nan=True)


def test_alias_and_labels_decode():
    """`same` follows the alias; a text output decodes to its phrases."""
    tables = {"p": {"axes": [1], "shape": [2], "d": 0, "q": [1, 0], "labels": ["calm", "rough"]}, "q": {"same": "p"}}
    assert decode(_data(tables), "q").values.tolist() == ["rough", "calm"]


# --- comparing a table ---------------------------------------------------------------------------


def _grid(values) -> dict:
    return {"axes": [0, 1], "shape": [3, 2], "d": 2, "q": list(values)}


def test_one_changed_stop_is_counted_located_and_sized():
    """Stops changed, the largest absolute and relative change, and where they are."""
    old = _data({"x": _grid([100, 200, 300, 400, 500, 600])})
    new = _data({"x": _grid([100, 200, 300, 440, 500, 600])})
    change = compare_table("x", "N", old, new)
    assert (change.status, change.changed, change.stops) == ("changed", 1, 6)
    assert (change.largest_abs.size, change.largest_abs.old, change.largest_abs.new) == ("0.40 N", "4.00", "4.40")
    assert change.largest_abs.where == "a = 1.0 kg, b = air"
    assert change.largest_rel.size == "10 %"
    assert change.where == "a = 1.0 kg, b = air"


def test_unchanged_values_in_a_new_encoding_are_no_change():
    """Delta-encoded or plain, equal values compare equal."""
    old = _data({"x": _grid([100, 200, 300, 400, 500, 600])})
    new = _data({"x": {**_grid([100, 100, 100, 100, 100, 100]), "enc": "delta"}})
    assert compare_table("x", "", old, new) is None


def test_a_longer_slider_is_compared_at_the_stops_both_builds_share():
    """Stops added to a slider are noted; values are compared where both grids have a stop."""
    longer = [{**SLIDERS[0], "count": 4}, SLIDERS[1]]
    old = _data({"x": _grid([100, 200, 300, 400, 500, 600])})
    new = _data({"x": {"axes": [0, 1], "shape": [4, 2], "d": 2, "q": [100, 200, 300, 400, 500, 600, 700, 800]}}, longer)
    change = compare_table("x", "", old, new)
    assert (change.changed, change.stops) == (0, 6)
    assert change.notes == ("stops of a changed (3 → 4); compared at the 3 both have",)


def test_a_table_that_lost_a_slider_is_compared_along_it():
    """A table constant along a slider drops that axis; the comparison broadcasts it back."""
    old = _data({"x": _grid([100, 100, 300, 300, 500, 500])})
    new = _data({"x": {"axes": [0], "shape": [3], "d": 2, "q": [100, 300, 600]}})
    change = compare_table("x", "", old, new)
    assert (change.changed, change.stops) == (2, 6)
    assert change.where == "a = 1.5 kg, b = water; a = 1.5 kg, b = air"
    assert "depends on a (was a, b)" in change.notes


def test_changed_phrases_are_reported_with_an_example():
    """A text output: how many stops read differently, and one of them."""
    old = _data({"s": {"axes": [1], "shape": [2], "d": 0, "q": [0, 0], "labels": ["balanced", "tips"]}})
    new = _data({"s": {"axes": [1], "shape": [2], "d": 0, "q": [0, 1], "labels": ["balanced", "tips"]}})
    change = compare_table("s", "", old, new)
    assert change.changed == 1
    assert (change.largest_abs.old, change.largest_abs.new, change.largest_abs.where) == ("balanced", "tips", "b = air")


# --- text -----------------------------------------------------------------------------------------


def test_text_diff_marks_the_changed_words():
    """A replaced line shows as old and new with only the changed words marked."""
    lines = text_diff(["a", "impulse J: 1.200 N·s", "b"], ["a", "impulse J: 1.300 N·s", "b"])
    assert [line.kind for line in lines] == [" ", "-", "+", " "]
    assert [piece for piece, hot in lines[2].runs if hot] == ["1.300"]


def test_page_text_keeps_scenes_as_markers_and_readouts_on_one_line(tiny_site):
    """The page outside its scenes reads as text with a marker per scene; a readout is 'label: value'."""
    page = parse_page("mechanics.html", (tiny_site / "mechanics.html").read_text())
    rest = text_lines(page.rest)
    assert [line for line in rest if line.startswith("[scene: ")] == [f"[scene: {s.id}]" for s in page.scenes]
    assert "impulse J: 1.200 N·s" in text_lines(page.scenes[0].panel)


# --- end to end -----------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def two_builds(tmp_path_factory, tiny_built) -> tuple[Path, Path]:
    """The tiny book as the session built it, and built again (in another process) from a copy of the
    sources with one model constant changed."""
    root = tmp_path_factory.mktemp("book")
    shutil.copytree(tiny_built.content, root / "content")
    shutil.copy(tiny_built.root / "book.toml", root / "book.toml")
    # with its compiled bytecode, if any: checked against each source's time and size, so the changed
    # model's is compiled again and the other modules are not compiled once more in the build below
    shutil.copytree(ROOT / "src" / "sitegen", root / "src" / "sitegen")
    # a warm start: only the changed scene is recomputed (the compiled code, a link to the project's, is not needed)
    shutil.copytree(tiny_built.cache, root / ".cache", ignore=shutil.ignore_patterns("compiled"))
    model = root / MODEL_FILE
    text = model.read_text()
    assert CONSTANT[0] in text, f"update CONSTANT: {MODEL_FILE} no longer has {CONSTANT[0]!r}"
    model.write_text(text.replace(CONSTANT[0], CONSTANT[1], 1))
    new = _build_copy(root, root / "new")
    # Editing one model's file recomputes that model's scenes only (here the one ossicles scene).
    assert (root / "new.log").read_text().count(" computed\n") == 1, (root / "new.log").read_text()
    return tiny_built.out, new


def _build_copy(root: Path, out: Path) -> Path:
    env = {**os.environ, "PYTHONPATH": str(root / "src"), "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run(
        [sys.executable, "-m", "sitegen.cli", "build", "--root", str(root), "--out", str(out)],
        cwd=root,
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    out.with_suffix(".log").write_text(done.stdout)
    return out


@pytest.fixture(scope="module")
def constant_review(two_builds, tmp_path_factory):
    """The review of the changed constant (figures compared as SVG, not rendered), and where its report went."""
    out = tmp_path_factory.mktemp("review") / "build-review"
    return review_builds(*two_builds, out, "before", "after", render=False), out


@pytest.mark.slow  # the tiny book built again in another process (two_builds)
def test_changed_constant_changes_exactly_that_scene(constant_review):
    """Only the ossicles scene changed: no other scene, no page text, no other file."""
    review, _ = constant_review
    assert review.changed
    assert [(s.page, s.id, s.status) for s in review.scenes()] == [("waves.html", "ossicles", "changed")]
    assert [p.name for p in review.pages] == ["waves.html"]
    examples = review.pages[0]
    assert not examples.text and not examples.markup
    assert review.files == []


@pytest.mark.slow  # the tiny book built again in another process (two_builds)
def test_changed_constant_changes_the_outputs_that_depend_on_it(constant_review):
    """Exactly the outputs computed from the constant changed, each with its size and place."""
    (scene,) = constant_review[0].scenes()
    assert {t.output for t in scene.tables} == AFFECTED
    for table in scene.tables:
        assert table.status == "changed" and 0 < table.changed <= table.stops
        assert table.largest_abs and table.largest_abs.old != table.largest_abs.new and table.largest_abs.where
    assert not scene.controls and not scene.markup
    changed_readouts = {line.text.split(":")[0] for line in scene.panel if line.kind == "+"}
    assert "power in, no transformer T0" in changed_readouts


@pytest.mark.slow  # the tiny book built again in another process (two_builds)
def test_changed_constant_changes_the_figure(constant_review):
    """The figure differs in its moving bars."""
    (scene,) = constant_review[0].scenes()
    assert {"T-with", "T-without"} <= set(scene.figure.svg.layers_changed)


@pytest.mark.browser
@pytest.mark.slow  # the tiny book built again in another process (two_builds)
def test_changed_figure_rendered_differs_in_some_but_few_pixels(two_builds, tmp_path):
    """Rendered by Chromium, the changed figure differs in some but few pixels."""
    review = review_builds(*two_builds, tmp_path, "before", "after")
    if not _can_render():
        assert "Playwright" in review.render_note or "Chromium" in review.render_note
        return
    (scene,) = review.scenes()
    pixels = scene.figure.pixels
    assert pixels is not None and 0 < pixels.fraction < 0.1
    assert pixels.old_png != pixels.new_png


@pytest.mark.slow  # the tiny book built again in another process (two_builds)
def test_report_lists_that_scene_and_nothing_else(constant_review):
    """The HTML report has one scene card, with its images inline; the summary names the outputs."""
    review, out = constant_review
    html = (out / "index.html").read_text()
    assert re.findall(r'<article class="card" id="([^"]+)"', html) == ["waves--ossicles"]
    assert not re.search(r'(?:src|href)="(?!data:|#)', html), "the report must be self-contained"
    summary = (out / "summary.md").read_text()
    assert summary.startswith("## Build review: 1 scene (1 figure, 7 tables, 1 set of readouts) changed")
    for name in AFFECTED:
        assert f"| ossicles | {name} |" in summary
    for other in ("impulse", "collision", "lever", "kinetic", "euler-slab", "acoustic-energy"):
        assert f"| {other} |" not in summary and f'id="mechanics--{other}"' not in html


@pytest.mark.slow  # the tiny book built again in another process (two_builds)
def test_cli_exits_1_on_changes_and_0_on_identical_trees(two_builds, tmp_path, capsys):
    """The exit status gates CI: 1 when anything changed, 0 for byte-identical trees."""
    old, new = two_builds
    assert main(["review", str(old), str(new), "--out", str(tmp_path / "a"), "--no-render"]) == 1
    same = tmp_path / "same"
    shutil.copytree(old, same)
    assert main(["review", str(old), str(same), "--out", str(tmp_path / "b")]) == 0
    assert "no changes" in capsys.readouterr().out
    assert "byte-identical" in (tmp_path / "b" / "summary.md").read_text()


def test_cli_says_what_is_wrong_with_its_arguments(tmp_path, capsys):
    """One folder, or a folder that is not a build: exit 2 with a message, no traceback."""
    assert main(["review", str(tmp_path)]) == 2
    assert "give two build folders" in capsys.readouterr().err
    assert main(["review", str(tmp_path / "nope"), str(tmp_path), "--out", str(tmp_path / "r")]) == 2
    assert "is not a built site" in capsys.readouterr().err


@pytest.mark.slow  # the tiny book built again in another process (two_builds)
def test_without_rendering_the_report_shows_the_svgs(two_builds, tmp_path):
    """--no-render: no pixels, the old and new figures shown as SVG images, and the reason said."""
    review = review_builds(*two_builds, tmp_path, render=False)
    assert review.figures()[0].figure.pixels is None
    html = (tmp_path / "index.html").read_text()
    assert html.count('src="data:image/svg+xml;base64,') == 2 and "Figures were not rendered" in html


# --- review against a git revision ------------------------------------------------------------------

TINY_PAGE = """+++
title = "Tiny"
+++

A pulse.

```scene
model: impulse
slider F_pk: 0..10 step 2 default 4
slider tau: 0.1..0.5 step 0.1 default 0.2
slider m: 1..2 step 0.5 default 1
caption: A pulse.
```
"""


def _git(repo: Path, *args: str) -> str:
    done = subprocess.run(
        ["git", "-c", "user.name=t", "-c", "user.email=t@example.org", *args],
        cwd=repo,
        capture_output=True,
        text=True,
        check=True,
    )
    return done.stdout


@pytest.mark.slow
def test_review_against_a_revision_builds_it_in_a_temporary_worktree(tmp_path, capsys):
    """`review --base HEAD`: identical when nothing changed, the changed scene when a default moved,
    and no worktree left behind."""
    repo = tmp_path / "repo"
    write_book(repo, {"index": TINY_PAGE})
    (repo / ".gitignore").write_text("/build/\n/.cache/\n")
    _git(repo, "init", "-q", "-b", "main")
    _git(repo, "add", "-A")
    _git(repo, "commit", "-q", "-m", "tiny book")
    assert main(["build", "--root", str(repo)]) == 0
    assert main(["review", "--base", "main", "--root", str(repo), "--out", str(tmp_path / "same"), "--no-render"]) == 0
    page = repo / "content" / "index.md"
    page.write_text(page.read_text().replace("default 4", "default 6"))
    assert main(["build", "--root", str(repo)]) == 0
    assert main(["review", "--base", "main", "--root", str(repo), "--out", str(tmp_path / "diff"), "--no-render"]) == 1
    summary = (tmp_path / "diff" / "summary.md").read_text()
    assert "`main (" in summary and "working tree (main at " in summary and "uncommitted changes" in summary
    assert summary.startswith("## Build review: 1 scene (") and "set of readouts" in summary
    assert _git(repo, "worktree", "list").count("\n") == 1
    assert "is not a commit" not in capsys.readouterr().err
