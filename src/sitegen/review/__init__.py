"""Review two builds: which pages, figures, tables and files changed, as an HTML report and a
Markdown summary. `review_builds` compares two build folders; `git.revision_build` makes the old
one from a git revision."""

from __future__ import annotations

from pathlib import Path

from .compare import Review, compare_trees
from .figures import Rasterizer, RasterUnavailable, pixel_diff
from .report import headline, write_report
from .tree import read_tree

__all__ = ["Review", "review_builds", "render_figures", "headline"]


def review_builds(
    old: Path, new: Path, out: Path, old_label: str | None = None, new_label: str | None = None, render: bool = True
) -> Review:
    """Compare build folders `old` and `new`, render the changed figures and write the report to `out`."""
    review = compare_trees(read_tree(old), read_tree(new), old_label or str(old), new_label or str(new))
    if render:
        render_figures(review)
    elif any(s.figure.old_svg and s.figure.new_svg for s in review.figures()):
        review.render_note = "rendering was turned off (--no-render)"
    write_report(review, out)
    return review


def render_figures(review: Review) -> None:
    """Render old and new of every changed figure and measure the difference (needs Chromium)."""
    pairs = [s.figure for s in review.figures() if s.figure.old_svg and s.figure.new_svg]
    if not pairs:
        return
    try:
        with Rasterizer() as raster:
            for figure in pairs:
                figure.pixels = pixel_diff(raster.png(figure.old_svg), raster.png(figure.new_svg))
    except RasterUnavailable as problem:
        review.render_note = str(problem)
