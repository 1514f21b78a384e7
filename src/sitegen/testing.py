"""Checks a book's own tests call on its models: what every build checks, asked for by name.

    from sitegen.testing import book_model, deps_problems, scene_problems

    def test_each_output_declares_what_it_depends_on():
        assert deps_problems(book_model("pendulum", BOOK)) == []

    def test_the_scenes_fit_their_models_and_figures():
        assert scene_problems(BOOK) == []

`deps_problems` moves every parameter across the model's domain at seeded points; `scene_problems`
does what a build does before it computes a table: it reads every page, resolves each scene against
its model and figure (every `in:`/`out:` reference of the figure's layers), and checks each scene's
outputs against their deps at seeded stops of its sliders. Each problem is one line naming the
author's file and line. Run with pytest (`pip install "sitegen[test]"` brings it).
"""

from __future__ import annotations

from pathlib import Path

from .build import BuildConfig, resolve_book
from .compute.deps import probe_model, verify_scene_deps
from .config import read_book
from .errors import BuildFailed
from .phases.scenes import planned_outputs
from .physics import Model
from .registry import load_registry

__all__ = ["book_model", "deps_problems", "scene_problems"]


def book_model(name: str, book: Path | str = ".") -> Model:
    """The model called `name` as a build of the book in folder `book` finds it (its own models/, an installed
    plugin or a built-in), ready to evaluate; AssertionError naming what failed to load."""
    registry = load_registry(read_book(Path(book)))
    assert not registry.problems, "\n".join(str(p) for p in registry.problems)
    assert name in registry.models, f"no model '{name}'; models: {', '.join(sorted(registry.models))}"
    return registry.models[name]()


def deps_problems(
    model: Model,
    effects=(),
    points: int = 16,
    seed: int = 0,
    unused: bool = True,
    book: Path | str | None = None,
    moves: int = 4,
) -> list[str]:
    """What is wrong with the deps of `model`'s outputs under `effects`: each output evaluated at `points`
    seeded points of the model's domain, with each parameter moved `moves` times from each. A parameter that
    changes an output its deps leave out is a problem; so is (with `unused`) a declared dep that never
    changed it. `book`: paths are written relative to it (default: as they are)."""
    root = Path(book).resolve() if book is not None else None
    found = probe_model(model, frozenset(effects), points, seed, root, moves)
    return list(found.errors) + (list(found.notes) if unused else [])


def scene_problems(book: Path | str = ".") -> list[str]:
    """Every author error a build of the book in folder `book` finds before computing a table: its pages,
    each scene against its model and figure, and each scene's outputs against their deps."""
    config = BuildConfig.at(Path(book), cache=None)
    try:
        resolved = resolve_book(config)
    except BuildFailed as failure:
        return [str(error) for error in failure.errors]
    return [
        str(error)
        for record in resolved.scenes
        for error in verify_scene_deps(record.scene, planned_outputs(record), root=config.root)
    ]
