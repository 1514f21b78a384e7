"""What many test files need: a small book written from its pages, a folder read back, a scene block resolved.

Fixtures live in conftest.py; these are plain functions, imported by name (`from helpers import tree`).
"""

from __future__ import annotations

import functools
import shutil
from collections.abc import Mapping, Sequence
from pathlib import Path

import pytest

from sitegen.build import BuildConfig, build
from sitegen.compute.scenes import resolve_scene
from sitegen.content.scenes import parse_scene_block
from sitegen.errors import BuildFailed, SourceLoc
from sitegen.registry import builtin_registry

HOME = '+++\ntitle = "Test book"\n+++\n\nA home page.\n'  # a home page that links nowhere


def write_book(
    root: Path, pages: Mapping[str, str | bytes], *, home: str | None = HOME, cache: bool = False
) -> BuildConfig:
    """Write a book at `root` and return its configuration.

    content/ holds exactly `pages` (name -> text or bytes; `name.md`) and `home` as index.md unless `pages` has
    one; book.toml is empty (every default). The site goes to root/build, the tables to root/.cache if `cache`.
    """
    content = root / "content"
    shutil.rmtree(content, ignore_errors=True)
    content.mkdir(parents=True)
    for name, text in (({"index": home} if home is not None else {}) | dict(pages)).items():
        data = text if isinstance(text, bytes) else text.encode("utf-8")
        (content / f"{name}.md").write_bytes(data)
    (root / "book.toml").write_text("")
    return BuildConfig(root, content, root / "build", cache=root / ".cache" if cache else None)


def build_errors(config: BuildConfig) -> list[str]:
    """The author errors of a build that must fail, as the author reads them."""
    with pytest.raises(BuildFailed) as failure:
        build(config, progress=None)
    return [str(e) for e in failure.value.errors]


def tree(folder: Path) -> dict[str, bytes]:
    """Every file under `folder` by its relative path, with its bytes (nothing for a missing folder)."""
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def names(folder: Path, *, folders: bool = False) -> list[str]:
    """The relative paths under `folder`, sorted: its files, and its folders too if `folders`."""
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*") if folders or p.is_file())


def resolved_scene(block: str | Sequence[str], models: Mapping | None = None, where: SourceLoc | None = None):
    """The scene a valid scene block (text or lines) resolves to against `models` (default: the built-ins).

    `where` is the block's fence (default test.md:1); a block with any error fails the test, naming them."""
    lines = block.splitlines() if isinstance(block, str) else list(block)
    spec, errors = parse_scene_block(lines, where or SourceLoc("test.md", 1))
    assert not errors, [str(e) for e in errors]
    scene, errors = resolve_scene(spec, _builtin_models() if models is None else models)
    assert not errors, [str(e) for e in errors]
    return scene


@functools.cache
def _builtin_models() -> Mapping:
    return builtin_registry().models
