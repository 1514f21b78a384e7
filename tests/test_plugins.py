"""Models and figures as plugins, from the three sources the registry reads: the built-ins, an installed
package's entry point (tests/plugins/swing, installed into a folder on sys.path as pip installs it) and
the book's models/ folder (tests/plugins/book/models/pendulum). What the cache recomputes when one of
them changes, and where an author's code is blamed when it fails."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from sitegen.build import BuildConfig, build
from sitegen.compute.sources import source_hashes
from sitegen.errors import BuildFailed, SceneCrashed
from sitegen.registry import builtin_registry, load_registry

HERE = Path(__file__).resolve().parent
PLUGINS = HERE / "plugins"
PENDULUM_SCENE_LINE = (
    8  # content/index.md of the plugin book: the pendulum scene's `model:` line (its fence is the line before)
)


@pytest.fixture(scope="session")
def swing_installed(tmp_path_factory) -> Path:
    """tests/plugins/swing installed by pip into a folder (with its dist-info and entry point)."""
    target = tmp_path_factory.mktemp("swing") / "site"
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "install",
            "--quiet",
            "--no-deps",
            "--no-build-isolation",
            "--no-compile",
            "--disable-pip-version-check",
            "--target",
            str(target),
            str(PLUGINS / "swing"),
        ],
        check=True,
    )
    return target


@pytest.fixture
def swing(swing_installed, tmp_path, monkeypatch) -> Path:
    """A fresh copy of the installed swing package on sys.path for one test; its module folder."""
    site = tmp_path / "site"
    shutil.copytree(swing_installed, site)
    monkeypatch.syspath_prepend(str(site))
    _forget("sitegen_swing")
    yield site / "sitegen_swing"
    _forget("sitegen_swing")


@pytest.fixture
def book(tmp_path, swing) -> BuildConfig:
    """A copy of the plugin book (its own pendulum model; the swing model from the package)."""
    shutil.copytree(PLUGINS / "book", tmp_path / "book")
    return BuildConfig.at(tmp_path / "book")


def _forget(package: str) -> None:
    for name in [n for n in sys.modules if n == package or n.startswith(package + ".")]:
        del sys.modules[name]


def _readout(config: BuildConfig, output: str) -> str:
    html = (config.out / "index.html").read_text()
    start = html.index(f'data-out="{output}">') + len(f'data-out="{output}">')
    return html[start : html.index("<", start)]


def _statuses(report) -> dict[str, str]:
    """{"index#pendulum": "cached" | "computed: ...", ...} from the build's scene lines."""
    return {line.split()[1]: line.split("  ")[-1].strip() for line in report.scene_lines if line.startswith("[")}


# --- the three sources ---------------------------------------------------------------------------------------


def test_the_registry_finds_each_model_in_its_source(book):
    """Built-ins, the entry point and the book's folder, each named as the author would look for it."""
    registry = load_registry(book.book)
    assert not registry.problems
    assert registry.origins["model collision"] == "built-in sitegen.models.collision"
    assert registry.origins["model swing"] == "package sitegen-swing 0.1.0 (entry point 'swing = sitegen_swing')"
    assert registry.origins["model pendulum"] == "models/pendulum (the book)"
    assert set(builtin_registry().models) < set(registry.models)


def test_a_book_builds_with_its_own_model_and_an_installed_one(book):
    """The page shows both plugins' readouts at their defaults, and the book's config in its HTML."""
    build(book, progress=None)
    assert _readout(book, "T") == "2.0385 s"  # 2π √(1/9.5)
    assert _readout(book, "period") == "4.443 s"  # 2π √(m/k) = 2π √(2/4)
    html = (book.out / "index.html").read_text()
    assert '<html lang="en-GB">' in html and '<meta name="author" content="A. Author">' in html
    assert "A. Author. Written with sitegen.</footer>" in html


# --- the cache sees the plugins' code --------------------------------------------------------------------------


def test_editing_the_book_model_changes_the_page_and_recomputes_only_its_scenes(book):
    """One more decimal in the pendulum's period: its scene is computed again and shows it; the swing is cached."""
    build(book, progress=None)
    model = book.root / "models" / "pendulum" / "model.py"
    model.write_text(model.read_text().replace("decimals=4", "decimals=5"))
    report = build(book, progress=None)
    assert _statuses(report) == {"index#pendulum": "computed: model code changed", "index#swing": "cached"}
    assert _readout(book, "T") == "2.03853 s"


def test_editing_a_helper_of_the_book_model_recomputes_its_scenes(book):
    """The key follows the model's imports into its plugin folder (swing_time.py), not only model.py."""
    build(book, progress=None)
    helper = book.root / "models" / "pendulum" / "swing_time.py"
    helper.write_text(helper.read_text().replace("2 * np.pi", "2.0 * np.pi"))
    assert _statuses(build(book, progress=None)) == {
        "index#pendulum": "computed: model code changed",
        "index#swing": "cached",
    }


def test_editing_the_installed_model_recomputes_only_its_scenes(book, swing):
    """An edit to the package's module recomputes the swing's scene (the pendulum's stays cached)."""
    build(book, progress=None)
    module = swing / "__init__.py"
    module.write_text(
        module.read_text().replace('("m", "k"), decimals=3),\n    )', '("m", "k"), decimals=4),\n    )') + "# edited\n"
    )
    _forget("sitegen_swing")
    report = build(book, progress=None)
    assert _statuses(report) == {"index#pendulum": "cached", "index#swing": "computed: model code changed"}
    assert _readout(book, "period") == "4.4429 s"


def test_adding_a_model_recomputes_nothing(book):
    """A new model in the book's folder is one more plugin: no other scene's key changes."""
    build(book, progress=None)
    shutil.copytree(book.root / "models" / "pendulum", book.root / "models" / "pendulum2")
    for path in (book.root / "models" / "pendulum2").glob("*.py"):
        path.write_text(
            path.read_text().replace('"pendulum"', '"pendulum2"').replace("class Pendulum(", "class Pendulum2(")
        )
    (book.root / "models" / "pendulum2" / "__init__.py").write_text(
        "from .figure import PendulumFigure\nfrom .model import Pendulum2\n\n"
        'MODELS = {"pendulum2": Pendulum2}\nFIGURES = {"pendulum2": PendulumFigure()}\n'
    )
    report = build(book, progress=None)
    assert report.computed == 0 and _statuses(report) == {"index#pendulum": "cached", "index#swing": "cached"}


@pytest.mark.parametrize(
    "model, own, others",
    [
        ("collision", "sitegen.models.collision.model", ("chain", "bubble", "impulse")),
        ("chain", "sitegen.models.chain.integrators", ("collision", "bubble")),  # the chain's accuracy reference
        ("bubble", "sitegen.models.bubble.kernel_march", ("chain", "collision")),
    ],
    ids=["collision", "chain", "bubble"],
)
def test_a_built_in_model_key_covers_its_own_files_and_no_other_model(model, own, others):
    """The built-in model's key is made of the modules it imports: its plugin's, the framework's, never another
    model's."""
    modules = source_hashes(frozenset({builtin_registry().models[model].__module__}))
    assert own in modules and "sitegen.physics.base" in modules, sorted(modules)
    assert not [name for name in modules for other in others if f".{other}." in f"{name}."], sorted(modules)


# --- errors in an author's plugin --------------------------------------------------------------------------------


def test_a_name_defined_twice_is_an_error_naming_both(book):
    """A book model and figure called 'collision' clash with the built-in ones: each error names both sources."""
    folder = book.root / "models" / "collision"
    shutil.copytree(book.root / "models" / "pendulum", folder)
    (folder / "__init__.py").write_text((folder / "__init__.py").read_text().replace('"pendulum"', '"collision"'))
    (folder / "model.py").write_text(
        (folder / "model.py").read_text().replace('name = "pendulum"', 'name = "collision"')
    )
    with pytest.raises(BuildFailed) as failure:
        build(book, progress=None)
    assert [str(e) for e in failure.value.errors] == [
        "models/collision/figure.py:6: figure 'collision' is defined twice: by built-in sitegen.models.collision "
        "and by models/collision (the book)",
        "models/collision/model.py:7: model 'collision' is defined twice: by built-in sitegen.models.collision "
        "and by models/collision (the book)",
    ]


def test_an_import_error_in_a_book_model_is_reported_at_its_line_and_at_the_scene(book):
    """A model that fails to import: the error points at its line, and the scene that uses it says so."""
    model = book.root / "models" / "pendulum" / "model.py"
    model.write_text(model.read_text().replace("from .swing_time import period", "from .swing_time import periodd"))
    with pytest.raises(BuildFailed) as failure:
        build(book, progress=None)
    assert [str(e) for e in failure.value.errors] == [
        f"content/index.md:{PENDULUM_SCENE_LINE}: scene 'pendulum': "
        "model 'pendulum' could not be loaded: see the error "
        "at models/pendulum/model.py:4",
        "models/pendulum/model.py:4: models/pendulum (the book) cannot be loaded: ImportError: cannot import name "
        f"'periodd' from 'sitegen_book_models.pendulum.swing_time' ({model.parent / 'swing_time.py'})",
    ]


def test_a_syntax_error_in_a_book_model_is_reported_at_its_line(book):
    """Python's own complaint, at the author's line."""
    helper = book.root / "models" / "pendulum" / "swing_time.py"
    helper.write_text(helper.read_text().replace("return 2 * np.pi", "return 2 * * np.pi"))
    with pytest.raises(BuildFailed) as failure:
        build(book, progress=None)
    assert (
        "models/pendulum/swing_time.py:7: models/pendulum (the book) cannot be loaded: SyntaxError: invalid syntax"
        in [str(e) for e in failure.value.errors]
    )


def test_a_model_missing_a_declaration_is_an_error_at_its_class(book):
    """A model class without outputs is reported where the class is defined."""
    model = book.root / "models" / "pendulum" / "model.py"
    text = model.read_text()
    model.write_text(text[: text.index("    outputs = (")] + text[text.index("    def _evaluate") :])
    with pytest.raises(BuildFailed) as failure:
        build(book, progress=None)
    assert (
        "models/pendulum/model.py:7: models/pendulum (the book): "
        "model Pendulum declares no outputs (see the Model class)" in [str(e) for e in failure.value.errors]
    )


@pytest.mark.parametrize("jobs", [1, 2], ids=["serial", "worker-processes"])
def test_an_exception_in_a_book_model_names_its_line_and_the_scene(book, jobs):
    """A bug in the author's helper: the message names the helper's line and the scene, not "internal error"."""
    helper = book.root / "models" / "pendulum" / "swing_time.py"
    helper.write_text(
        helper.read_text().replace(
            '    """T = 2π √(L/g)."""\n', '    """T = 2π √(L/g)."""\n    raise RuntimeError("the bob fell off")\n'
        )
    )
    config = BuildConfig(book.root, book.content, book.out, cache=None, jobs=jobs, book=book.book)
    with pytest.raises(SceneCrashed) as crash:
        build(config, progress=None)
    assert str(crash.value) == (
        f"content/index.md:{PENDULUM_SCENE_LINE - 1}: scene 'pendulum': models/pendulum/swing_time.py:7: "
        "RuntimeError: the bob fell off (while tabulating)"
    )


def test_a_figure_named_unlike_its_model_is_pointed_out(book):
    """FIGURES names the pendulum's figure 'pendulm': the scene's error says what the plugin declares instead."""
    plugin = book.root / "models" / "pendulum" / "__init__.py"
    plugin.write_text(plugin.read_text().replace('FIGURES = {"pendulum"', 'FIGURES = {"pendulm"'))
    with pytest.raises(BuildFailed) as failure:
        build(book, progress=None)
    figures = ", ".join(sorted({*builtin_registry().figures, "pendulm", "swing"}))
    assert [str(e) for e in failure.value.errors] == [
        f"content/index.md:{PENDULUM_SCENE_LINE - 1}: scene 'pendulum': unknown figure 'pendulum' — did you mean "
        "'pendulm'? models/pendulum (the book) defines model 'pendulum' but no figure of that name (its FIGURES: "
        f"pendulm): name the figure after the model, or add 'figure: pendulm' to the scene. Figures: {figures}"
    ]
