"""Figure goldens: every scene's figure at its defaults, kept as SVG files for tests to compare with.

A mismatch leaves NAME-changed.svg (and NAME-changed.png: golden, new and difference side by
side) next to the golden for a person to look at. Goldens are rewritten only on purpose
(`sitegen accept-figures`), never by a test and never in CI.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from .figures import Rasterizer, RasterUnavailable, pixel_diff, side_by_side_png
from .tree import page_figures


@dataclass
class Accepted:
    """What accept_figures did to the goldens folder."""

    new: list[str] = field(default_factory=list)
    changed: list[str] = field(default_factory=list)
    removed: list[str] = field(default_factory=list)
    unchanged: int = 0


def in_ci() -> bool:
    """Whether we run under CI (CI=true or 1), where goldens must never be rewritten."""
    return os.environ.get("CI", "").lower() in ("true", "1", "yes")


def golden_path(goldens: Path, name: str) -> Path:
    """The golden of figure "<page>/<scene id>"."""
    return goldens / f"{name}.svg"


def changed_paths(goldens: Path, name: str) -> tuple[Path, Path]:
    """Where a mismatch leaves the new figure and its comparison image."""
    return goldens / f"{name}-changed.svg", goldens / f"{name}-changed.png"


def golden_names(goldens: Path) -> list[str]:
    """Every figure that has a golden."""
    return sorted(
        p.relative_to(goldens).as_posix().removesuffix(".svg")
        for p in goldens.rglob("*.svg")
        if not p.name.endswith("-changed.svg")
    )


def accept_figures(build: Path, goldens: Path) -> Accepted:
    """Make the goldens exactly the figures of `build`: write new and changed ones, remove stale ones."""
    if in_ci():
        raise PermissionError("goldens are never rewritten in CI (CI is set); run `sitegen accept-figures` locally")
    figures, done = page_figures(build), Accepted()
    if not figures:
        raise FileNotFoundError(f"no scene figures in {build}; build the site first (make site)")
    for name, svg in figures.items():
        path = golden_path(goldens, name)
        old = path.read_text(encoding="utf-8") if path.exists() else None
        if old == svg:
            done.unchanged += 1
        else:
            (done.new if old is None else done.changed).append(name)
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(svg, encoding="utf-8")
        _remove_changed(goldens, name)
    for name in golden_names(goldens):
        if name not in figures:
            golden_path(goldens, name).unlink()
            _remove_changed(goldens, name)
            done.removed.append(name)
    for folder in sorted(goldens.rglob("*"), reverse=True):
        if folder.is_dir() and not any(folder.iterdir()):
            folder.rmdir()
    return done


def check_figure(goldens: Path, name: str, svg: str) -> str | None:
    """Compare a figure with its golden; on a mismatch write the -changed files and say what differs."""
    path = golden_path(goldens, name)
    if not path.exists():
        return f"figure '{name}' has no golden ({path}); run `sitegen accept-figures` to add it"
    golden = path.read_text(encoding="utf-8")
    if golden == svg:
        _remove_changed(goldens, name)
        return None
    changed_svg, changed_png = changed_paths(goldens, name)
    changed_svg.write_text(svg, encoding="utf-8")
    try:
        with Rasterizer() as raster:
            diff = pixel_diff(raster.png(golden), raster.png(svg))
        changed_png.write_bytes(side_by_side_png(diff))
        size = f"{diff.describe()}; see {changed_svg} and {changed_png}"
    except RasterUnavailable as problem:
        size = f"see {changed_svg} (no PNG: {problem})"
    return (
        f"figure '{name}' differs from its golden {path}: {size}. "
        "If the change is intended, run `sitegen accept-figures`."
    )


def _remove_changed(goldens: Path, name: str) -> None:
    for path in changed_paths(goldens, name):
        path.unlink(missing_ok=True)
