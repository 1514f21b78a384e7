"""The models and figures a build may use, found the same way from three sources.

A *plugin* is a Python module (a folder with `__init__.py`, or one file) that defines plain dicts:
`MODELS` (name: Model subclass), and optionally `FIGURES` (name: figure view) and `REPORTS` (model
name: the view of the accuracy-report parts the model declares). Plugins come from

1. sitegen itself: the modules named in BUILTINS (src/sitegen/models/<name>/);
2. installed packages: each entry point of the group `sitegen.models` names a module;
3. the book: every folder (or .py file) in its models folder (book.toml `models`, default models/).

A name defined by two plugins is an error naming both. A plugin that cannot be imported, or that
declares something wrongly, is an author error at its own file and line; the other plugins still load.
"""

from __future__ import annotations

import difflib
import hashlib
import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import inspect
import os
import re
import shutil
import sys
import tempfile
import traceback
import types
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path

from .config import PLUGIN_GROUP, BookConfig
from .errors import AuthorError, SourceLoc, code_loc, did_you_mean
from .physics.base import Model

BUILTINS = (  # in this order: the accuracy page lists the models' report parts in it
    "sitegen.models.acoustic_energy",
    "sitegen.models.ossicles",
    "sitegen.models.lever",
    "sitegen.models.work",
    "sitegen.models.impulse",
    "sitegen.models.kinetic",
    "sitegen.models.collision",
    "sitegen.models.euler_slab",
    "sitegen.models.chain",
    "sitegen.models.bubble",
)
BOOK_PACKAGE = "sitegen_book_models"  # the book's models are imported as BOOK_PACKAGE.<name>
FIGURE_METHODS = ("layers", "draw")


@dataclass(frozen=True)
class Registry:
    """Models, figures and report views by name, where each came from, and what failed to load."""

    models: Mapping[str, type[Model]] = field(default_factory=dict)
    figures: Mapping[str, object] = field(default_factory=dict)
    reports: Mapping[str, object] = field(default_factory=dict)
    origins: Mapping[str, str] = field(default_factory=dict)  # "model x" / "figure x" -> its plugin's source
    problems: tuple[AuthorError, ...] = ()  # plugins that failed to load or declare; names defined twice
    broken: Mapping[str, SourceLoc] = field(default_factory=dict)  # plugin name -> where it failed

    def adding(self, models: Mapping = (), figures: Mapping = (), source: str = "the caller") -> Registry:
        """This registry with more models and figures (for a program that builds with models of its own)."""
        origins = {
            **self.origins,
            **{f"model {n}": source for n in dict(models)},
            **{f"figure {n}": source for n in dict(figures)},
        }
        return Registry(
            {**self.models, **dict(models)},
            {**self.figures, **dict(figures)},
            self.reports,
            origins,
            self.problems,
            self.broken,
        )


@dataclass(frozen=True)
class Plugin:
    """One loaded plugin module and how to name where it came from."""

    name: str
    source: str  # e.g. "built-in sitegen.models.chain", "models/pendulum (the book)"
    module: types.ModuleType
    where: SourceLoc  # its file, for errors that are about the plugin as a whole


def load_registry(book: BookConfig | None = None) -> Registry:
    """Every plugin: the built-ins, the installed packages' entry points, then the book's models folder."""
    plugins, problems, broken = [], [], {}
    for found in (_builtin_plugins(), _entry_point_plugins(book), _book_plugins(book)):
        for name, loaded in found:
            if isinstance(loaded, AuthorError):
                problems.append(loaded)
                broken[name] = loaded.loc
            else:
                plugins.append(loaded)
    return _gathered(plugins, problems, broken, book)


def builtin_registry() -> Registry:
    """The built-in models and figures only (what the docs' reference lists)."""
    plugins = [loaded for _, loaded in _builtin_plugins()]
    return _gathered(plugins, [], {}, None)


def _builtin_plugins():
    for name in BUILTINS:
        module = importlib.import_module(name)
        yield name, Plugin(name, f"built-in {name}", module, SourceLoc(_shown(module.__file__, None), 1))


def _entry_point_plugins(book: BookConfig | None):
    for entry in sorted(metadata.entry_points(group=PLUGIN_GROUP), key=lambda e: (e.name, e.value)):
        package = f"{entry.dist.name} {entry.dist.version}" if entry.dist else "an installed package"
        source = f"package {package} (entry point '{entry.name} = {entry.value}')"
        try:
            module = entry.load()
        except Exception as error:  # an author's code: reported at its own line, the build goes on
            yield entry.name, _load_error(error, source, None, book)
            continue
        if not isinstance(module, types.ModuleType):
            where = SourceLoc(_shown(inspect.getsourcefile(type(module)) or entry.value, book), 1)
            yield (
                entry.name,
                AuthorError(where, f"{source} must name a module (e.g. 'mypackage.pendulum'), not an object"),
            )
            continue
        yield entry.name, Plugin(entry.name, source, module, SourceLoc(_shown(module.__file__, book), 1))


def _book_plugins(book: BookConfig | None):
    if book is None or not book.models.is_dir():
        return
    use_book_models(book.models)
    for path in sorted(book.models.iterdir()):
        name = path.stem
        if name.startswith(("_", ".")) or not ((path / "__init__.py").is_file() or path.suffix == ".py"):
            continue
        source = f"{book.relative(path)} (the book)"
        try:
            module = importlib.import_module(f"{BOOK_PACKAGE}.{name}")
        except Exception as error:
            yield name, _load_error(error, source, path, book)
            continue
        yield name, Plugin(name, source, module, SourceLoc(_shown(module.__file__, book), 1))


def _gathered(plugins: list[Plugin], problems: list, broken: dict, book: BookConfig | None) -> Registry:
    """The plugins' dicts merged, with an error for each name defined twice and each wrong declaration."""
    models, figures, reports, origins = {}, {}, {}, {}
    for plugin in plugins:
        declared = {kind: getattr(plugin.module, kind, None) for kind in ("MODELS", "FIGURES", "REPORTS")}
        if declared["MODELS"] is None and declared["FIGURES"] is None:
            problems.append(
                AuthorError(
                    plugin.where,
                    f"{plugin.source} defines neither MODELS nor FIGURES "
                    "(dicts of its models and figure views by name)",
                )
            )
            broken[plugin.name] = plugin.where
            continue
        for kind, target, check in (
            ("MODELS", models, _model_problem),
            ("FIGURES", figures, _figure_problem),
            ("REPORTS", reports, None),
        ):
            for name, thing in dict(declared[kind] or {}).items():
                what = f"{kind[:-1].lower()} {name}"
                problem = check(name, thing) if check else None
                if problem:
                    problems.append(AuthorError(_defined_at(thing, plugin, book), f"{plugin.source}: {problem}"))
                elif kind == "MODELS" and (wrong := _output_problems(thing, plugin, book)):
                    problems += wrong
                    broken[name] = wrong[0].loc
                elif what in origins:
                    problems.append(
                        AuthorError(
                            _defined_at(thing, plugin, book),
                            f"{kind[:-1].lower()} '{name}' is defined twice: by {origins[what]} and by {plugin.source}",
                        )
                    )
                else:
                    target[name], origins[what] = thing, plugin.source
    return Registry(models, figures, reports, origins, tuple(problems), broken)


def _model_problem(name: str, model) -> str | None:
    """What is wrong with a MODELS entry, or None."""
    if not (isinstance(model, type) and issubclass(model, Model)):
        return f"MODELS['{name}'] must be a subclass of sitegen.physics.Model, not {type(model).__name__}"
    missing = [a for a in ("name", "title", "params", "outputs") if not hasattr(model, a)]
    if missing:
        return f"model {model.__name__} declares no {', '.join(missing)} (see the Model class)"
    if model.name != name:
        return f"MODELS['{name}'] is {model.__name__}, whose name is '{model.name}': the two must agree"
    return None


def _output_problems(model: type[Model], plugin: Plugin, book: BookConfig | None) -> list[AuthorError]:
    """An error at the `Output(...)` line of each output whose deps, effect or reason names something the
    model does not declare (the build would otherwise fail on it deep inside sitegen)."""
    params, outputs = [p.name for p in model.params], [o.name for o in model.outputs]
    errors = []
    for output in model.outputs:
        where = (
            code_loc(*output.where, book.root if book else None) if output.where else _defined_at(model, plugin, book)
        )
        named = [("dep", d) for d in output.deps] + [("dep", d) for _, extra in output.deps_with for d in extra]
        wrong = [
            f"its {what} '{d}' is no parameter{did_you_mean(d, params)} Parameters: {', '.join(params)}"
            for what, d in named
            if d not in params
        ]
        for effect in [output.effect] * bool(output.effect) + [e for e, _ in output.deps_with]:
            if effect not in model.effects:
                wrong.append(
                    f"its effect '{effect}' is not one the model offers{did_you_mean(effect, model.effects)} "
                    f"Effects: {', '.join(model.effects) or 'none'}"
                )
        if output.why_from and output.why_from not in outputs:
            wrong.append(f"its why_from '{output.why_from}' is no output{did_you_mean(output.why_from, outputs)}")
        errors += [
            AuthorError(where, f"{plugin.source}: model {model.__name__}, output '{output.name}': {w}") for w in wrong
        ]
    return errors


def _figure_problem(name: str, view) -> str | None:
    """What is wrong with a FIGURES entry (a view instance with a label, layers and draw), or None."""
    if isinstance(view, type):
        return f"FIGURES['{name}'] is the class {view.__name__}; give an instance, {view.__name__}()"
    missing = [m for m in FIGURE_METHODS if not callable(getattr(view, m, None))] + (
        [] if hasattr(view, "label") else ["label"]
    )
    return f"figure '{name}' ({type(view).__name__}) has no {', '.join(missing)}" if missing else None


def _defined_at(thing, plugin: Plugin, book: BookConfig | None) -> SourceLoc:
    """Where a model class or a figure view's class is defined (else the plugin's file)."""
    cls = thing if isinstance(thing, type) else type(thing)
    try:
        lines, first = inspect.getsourcelines(cls)
        return SourceLoc(_shown(inspect.getsourcefile(cls), book), first)
    except (OSError, TypeError):
        return plugin.where


def _load_error(error: Exception, source: str, folder: Path | None, book: BookConfig | None) -> AuthorError:
    """An import-time failure of a plugin, at the deepest line of the plugin's own code."""
    loc = author_line(error, folder, book)
    message = f"{type(error).__name__}: {error}" if not isinstance(error, SyntaxError) else f"SyntaxError: {error.msg}"
    return AuthorError(loc or SourceLoc(source, 1), f"{source} cannot be loaded: {message}")


def author_line(error: BaseException, folder: Path | None, book: BookConfig | None) -> SourceLoc | None:
    """The deepest line of the traceback inside `folder` (or, with no folder, the last line outside
    sitegen and the libraries), as the author sees it."""
    if isinstance(error, SyntaxError) and error.filename:
        return SourceLoc(_shown(error.filename, book), error.lineno or 1)
    frames = traceback.extract_tb(error.__traceback__)
    inside = [f for f in frames if folder is not None and Path(f.filename).resolve().is_relative_to(folder.resolve())]
    return SourceLoc(_shown(inside[-1].filename, book), inside[-1].lineno) if inside else None


def raising_line(error: BaseException, plugins: list[type], book: BookConfig | None) -> SourceLoc | None:
    """The line that raised `error`: the deepest one in the code of the plugins of `plugins` (classes:
    a scene's model and figure view), else the deepest of all. Read from the traceback, or from its
    text when the error came back from a worker process."""
    frames = [(f.filename, f.lineno) for f in traceback.extract_tb(error.__traceback__)]
    remote = error.__cause__
    if remote is not None and type(remote).__name__ == "_RemoteTraceback":  # concurrent.futures' worker traceback
        frames += [(file, int(line)) for file, line in re.findall(r'File "([^"]+)", line (\d+)', str(remote))]
    if not frames:
        return None
    homes = [plugin_home(cls) for cls in plugins]
    own = [f for f in frames if any(Path(f[0]).resolve().is_relative_to(home) for home in homes if home)]
    file, line = (own or frames)[-1]
    return SourceLoc(_shown(file, book), line)


def plugin_home(cls: type) -> Path | None:
    """The folder (or file) of the plugin that defines `cls`: a book model's folder, an installed
    package, or a built-in model's folder in sitegen.models."""
    parts = cls.__module__.split(".")
    depth = 2 if parts[0] == BOOK_PACKAGE else 3 if parts[:2] == ["sitegen", "models"] else 1
    if parts[:2] == ["sitegen", "physics"] or parts[:3] == ["sitegen", "render", "figures"]:
        depth = len(parts)  # a built-in model or figure still in the framework's folders: its own file
    module = sys.modules.get(".".join(parts[:depth]))
    file = getattr(module, "__file__", None)
    if not file or parts[0] == "sitegen" and depth == 1:
        return None
    path = Path(file).resolve()
    return path.parent if path.name == "__init__.py" else path


def _shown(filename: str, book: BookConfig | None) -> str:
    path = Path(filename).resolve()
    return book.relative(path) if book else str(path)


def unknown_figure_message(figure: str, model: str, registry: Registry) -> str:
    """Why a scene's figure is not found: "did you mean", and, for a figure named after its model, what the
    model's own plugin declares as FIGURES instead (a name that differs from the model's, or none)."""
    known = sorted(registry.figures)
    text = f"unknown figure '{figure}'{did_you_mean(figure, known)}"
    source = registry.origins.get(f"model {model}")
    if figure == model and source and not source.startswith("built-in"):
        own = [n for n in known if registry.origins.get(f"figure {n}") == source]
        if own:
            text += (
                f" {source} defines model '{model}' but no figure of that name (its FIGURES: {', '.join(own)}): "
                f"name the figure after the model, or add 'figure: {own[0]}' to the scene."
            )
        else:
            text += f" {source} defines model '{model}' and no FIGURES: add FIGURES = {{'{model}': ...}} beside MODELS."
    return f"{text} Figures: {', '.join(known)}"


def unknown_model_hint(name: str, registry: Registry) -> str:
    """ " — did you mean 'x'?" for a misspelt model name, else ""."""
    close = difflib.get_close_matches(name, list(registry.models), n=1)
    return f"; did you mean '{close[0]}'?" if close else ""


# --- importing the book's models ----------------------------------------------------------------------------


class _SourceOnlyLoader(importlib.machinery.SourceFileLoader):
    """Loads a book model from its source every time: no bytecode is read or written in the book (a
    cached .pyc is judged by the file's time and size, and an edit within a second can keep both)."""

    def get_code(self, fullname):
        return self.source_to_code(self.get_data(self.path), self.path)


class _BookFinder(importlib.abc.MetaPathFinder):
    """Finds BOOK_PACKAGE.<name>[.<module>...] in the book's models folder."""

    def __init__(self, folder: Path):
        self.folder = folder

    def find_spec(self, fullname, path=None, target=None):
        if not fullname.startswith(BOOK_PACKAGE + "."):
            return None
        base = self.folder.joinpath(*fullname.split(".")[1:])
        if (base / "__init__.py").is_file():
            init = base / "__init__.py"
            return importlib.util.spec_from_file_location(
                fullname, init, loader=_SourceOnlyLoader(fullname, str(init)), submodule_search_locations=[str(base)]
            )
        file = base.with_suffix(".py")
        if file.is_file():
            return importlib.util.spec_from_file_location(fullname, file, loader=_SourceOnlyLoader(fullname, str(file)))
        return None


def use_book_models(folder: Path) -> None:
    """Import BOOK_PACKAGE from `folder`: any book models imported before are forgotten (an edited one is read
    again)."""
    for name in [n for n in sys.modules if n == BOOK_PACKAGE or n.startswith(BOOK_PACKAGE + ".")]:
        del sys.modules[name]
    sys.meta_path[:] = [f for f in sys.meta_path if not isinstance(f, _BookFinder)]
    sys.meta_path.insert(0, _BookFinder(folder.resolve()))
    package = types.ModuleType(BOOK_PACKAGE, "The book's models (imported by sitegen's registry).")
    package.__path__ = [str(folder.resolve())]
    sys.modules[BOOK_PACKAGE] = package


@dataclass(frozen=True)
class BookModels:
    """A book's models folder as its files, to make its models importable in a worker process, one of a cluster
    that does not have the book included: called there, it writes them into a temporary folder named by their
    digest and imports BOOK_PACKAGE from it."""

    files: tuple[tuple[str, bytes], ...]  # (path in the folder, bytes), in path order

    @classmethod
    def of(cls, book: BookConfig | None) -> BookModels | None:
        """The book's models folder (None if it has none)."""
        if book is None or book.models is None or not book.models.is_dir():
            return None
        paths = sorted(p for p in book.models.rglob("*") if p.is_file() and "__pycache__" not in p.parts)
        return cls(tuple((p.relative_to(book.models).as_posix(), p.read_bytes()) for p in paths))

    @property
    def digest(self) -> str:
        """What the files say, as a short digest."""
        hashed = hashlib.sha256()
        for name, data in self.files:
            hashed.update(f"{name}\x00{len(data)}\x00".encode() + data)
        return hashed.hexdigest()[:16]

    def __call__(self) -> None:
        """Write the files (once per digest on this machine) and import the book's models from them."""
        folder = Path(tempfile.gettempdir()) / f"sitegen-book-models-{os.getuid()}" / self.digest
        if not folder.is_dir():
            folder.parent.mkdir(parents=True, exist_ok=True)
            staging = Path(tempfile.mkdtemp(dir=folder.parent))
            for name, data in self.files:
                (staging / name).parent.mkdir(parents=True, exist_ok=True)
                (staging / name).write_bytes(data)
            try:
                staging.rename(folder)
            except OSError:  # another worker of this machine wrote them first
                shutil.rmtree(staging, ignore_errors=True)
        use_book_models(folder)
