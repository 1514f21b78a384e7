"""`sitegen review`, `sitegen accept-figures` and `sitegen check-figures`: argument checks, progress lines and exit
codes."""

from __future__ import annotations

import sys
from contextlib import nullcontext
from pathlib import Path

from . import review_builds
from .git import ReviewError, revision_build, working_tree_label
from .goldens import accept_figures, check_figure, golden_names
from .report import headline
from .tree import page_figures

CHANGED, SAME, TROUBLE = 1, 0, 2


def run_review(
    trees: list[Path], base: str | None, root: Path, out: Path | None, render: bool = True, new: Path | None = None
) -> int:
    """Compare OLD NEW (or revision BASE with NEW, default `new`: the book's output, else ROOT/build);
    exit 0 if identical, 1 if not."""
    if base is None and len(trees) != 2:
        return _fail("give two build folders, OLD NEW, or --base REV [NEW]")
    if base is not None and len(trees) > 1:
        return _fail("with --base give at most one build folder, NEW (default ROOT/build)")
    out = out or Path("build-review")
    if base is None:
        new, new_label, source = trees[1], None, nullcontext((trees[0], None))
    else:
        new = trees[0] if trees else new or root / "build"
        new_label = None if trees else working_tree_label(root)
        source = revision_build(root, base, _say)
    try:
        _require_build(new, "run `make site` first" if base is not None else "")
        with source as (old, old_label):
            _require_build(old, "")
            review = review_builds(old, new, out, old_label, new_label, render)
    except (ReviewError, FileNotFoundError) as problem:
        return _fail(str(problem))
    if review.render_note:
        _say(f"figures not rendered: {review.render_note}")
    _say(f"{headline(review)}; report: {out / 'index.html'}, summary: {out / 'summary.md'}")
    return CHANGED if review.changed else SAME


def _require_build(folder: Path, hint: str) -> None:
    if not (folder / "index.html").is_file():
        raise FileNotFoundError(f"{folder} is not a built site (no index.html){'; ' + hint if hint else ''}")


def run_accept(build: Path, goldens: Path) -> int:
    """Rewrite the figure goldens from `build`; refuse in CI."""
    try:
        done = accept_figures(build, goldens)
    except (PermissionError, FileNotFoundError) as problem:
        return _fail(str(problem))
    for word, names in (("new", done.new), ("changed", done.changed), ("removed", done.removed)):
        for name in names:
            _say(f"{word:<8} {goldens / name}.svg")
    _say(
        f"goldens: {len(done.new)} new, {len(done.changed)} changed, "
        f"{len(done.removed)} removed, {done.unchanged} unchanged"
    )
    return 0


def run_check(build: Path, goldens: Path) -> int:
    """Compare every scene figure of `build` with its golden; exit 0 when all match, 1 when any differs,
    is new, or a golden has no scene (each said on a line of its own)."""
    figures = page_figures(build) if (build / "index.html").is_file() else {}
    if not figures:
        return _fail(f"no scene figures in {build}; build the book first (sitegen build)")
    problems = [p for name, svg in figures.items() if (p := check_figure(goldens, name, svg))]
    problems += [
        f"golden '{name}' has no scene in {build}; run `sitegen accept-figures` to remove it"
        for name in golden_names(goldens)
        if name not in figures
    ]
    for problem in problems:
        _say(problem)
    _say(f"figures: {len(figures)} checked against {goldens}, {len(problems)} problem(s)")
    return CHANGED if problems else SAME


def _say(text: str) -> None:
    print(text, flush=True)


def _fail(text: str) -> int:
    print(f"sitegen: {text}", file=sys.stderr)
    return TROUBLE
