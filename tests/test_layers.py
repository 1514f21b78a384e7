"""The package's imports point one way: content → compute → render → site → the built-in models
(plugins written on the framework below) → the registry that finds them → the build, and the tools
on top (the bench, the review, the command) use the build from outside. A short walk over
every module's imports (all of them, those inside functions too) fails when one runs backwards or
two modules import each other, however far round."""

from __future__ import annotations

import ast
import functools
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "sitegen"

# Lowest first: a module may import its own layer and the layers below it, never one above.
LAYERS = (
    ("sitegen.errors", "sitegen.config"),  # author errors; the book's config file
    ("sitegen.physics",),  # the models' framework: numpy and scipy only
    ("sitegen.content",),  # the author's sources: pages, scene and report blocks, Markdown, TeX
    ("sitegen.compute",),  # resolving scenes, tabulating, the cache, the numerical check
    ("sitegen.render",),  # figures (the only layer with matplotlib)
    ("sitegen.site",),  # HTML: scenes, pages, the accuracy report's parts, assets, the writer
    ("sitegen.models",),  # the built-in plugins: a model, its figure and helpers per folder
    ("sitegen.registry", "sitegen.reference"),  # finds the plugins (built-in, installed, the book's); lists them
    ("sitegen.phases", "sitegen.build", "sitegen.stamp"),  # the build: its phases, the script that runs them, its stamp
    (
        "sitegen.accuracy",
        "sitegen.review",
        "sitegen.preview",
        "sitegen.newbook",
        "sitegen.pdf",
        "sitegen.testing",
    ),  # tools that use the build and the layers below it (sitegen.testing: checks a book's tests call)
    ("sitegen.cli", "sitegen.progress"),  # the command, and how it shows a build's progress on a terminal
)
# Who may import the built-in models by name: their own plugins and the registry (which lists them). The build
# and the bench get them from the registry only (the bench reads what each model declares).
MODEL_USERS = ("sitegen.models", "sitegen.registry")


def _modules() -> dict[str, Path]:
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        if path.relative_to(PACKAGE).parts[0] == "starter":
            continue  # the book `sitegen new` copies: its models and test are a book's, imported as the book's
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        found[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return found


MODULES = _modules()


def imports_of(name: str) -> set[str]:
    """The sitegen modules `name` imports, anywhere in its body (relative imports resolved)."""
    path = MODULES[name]
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            base = package
            for _ in range(max(node.level - 1, 0)):
                base = base.rpartition(".")[0]
            target = (f"{base}.{node.module}" if node.module else base) if node.level else node.module
            found |= {f"{target}.{a.name}" if f"{target}.{a.name}" in MODULES else target for a in node.names}
        elif isinstance(node, ast.Import):
            found |= {a.name for a in node.names}
    return {f for f in found if f in MODULES and f != name}


def layer_of(name: str) -> int:
    """The index of the layer a module belongs to."""
    return next(i for i, layer in enumerate(LAYERS) for top in layer if name == top or name.startswith(top + "."))


NAMES = sorted(name for name in MODULES if name != "sitegen")


@functools.cache  # read when a test needs it, not while every process collects the tests
def graph() -> dict[str, set[str]]:
    """Each module's sitegen imports."""
    return {name: imports_of(name) for name in NAMES}


@pytest.mark.parametrize("name", NAMES)
def test_imports_point_down_the_layers(name):
    """Every import of the module goes to its own layer or one below."""
    upward = sorted(t for t in graph()[name] if layer_of(t) > layer_of(name))
    assert not upward, f"{name} imports {', '.join(upward)}, which sit above it"


@pytest.mark.parametrize("name", NAMES)
def test_only_the_registry_imports_the_built_in_models(name):
    """No phase, no framework module reaches a model by importing it: the build is given the registry."""
    models = sorted(t for t in graph()[name] if t.startswith("sitegen.models."))
    assert not models or name.startswith(MODEL_USERS), f"{name} imports {', '.join(models)}"


def test_no_circles():
    """No module reaches itself through its imports."""
    state, circles = {}, []

    def visit(name: str, trail: list[str]) -> None:
        state[name] = "open"
        for target in sorted(graph().get(name, ())):
            if state.get(target) == "open":
                circles.append(trail[trail.index(target) :] + [target])
            elif target not in state:
                visit(target, trail + [target])
        state[name] = "done"

    for name in NAMES:
        if name not in state:
            visit(name, [name])
    assert not circles, "\n".join(" -> ".join(c) for c in circles)


def test_the_walk_sees_backward_imports():
    """The walk itself: a module of the site layer importing the build would be found."""
    assert layer_of("sitegen.site.assemble") < layer_of("sitegen.build")
    assert "sitegen.compute.cache" in graph()["sitegen.build"] | graph()["sitegen.phases.run"]
    assert "sitegen.review.command" in graph()["sitegen.cli"]  # imports inside functions count too
