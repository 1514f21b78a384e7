"""The installed tool builds any book: Temml travels in the package (the bytes npm installs from
package-lock.json), node on PATH is the one requirement outside Python, and installing the package
(pip wheel ., pip install .) writes nothing into the source tree's build/, which is the book's site."""

from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import sys
import venv
import zipfile
from pathlib import Path

import pytest
from helpers import names
from scipy.integrate import quad

from sitegen.content import math as tex
from sitegen.content.markdown_ext import MathItem
from sitegen.errors import SourceLoc

ROOT = Path(__file__).resolve().parents[1]
VENDORED = ROOT / "src" / "sitegen" / "content" / "temml"
NPM_TEMML = ROOT / "node_modules" / "temml"


@pytest.mark.parametrize(
    "vendored, installed",
    [
        ("temml.min.js", "dist/temml.min.js"),
        ("Temml-Latin-Modern.css", "dist/Temml-Latin-Modern.css"),
        ("LICENSE", "LICENSE"),
    ],
    ids=["script", "stylesheet", "licence"],
)
def test_the_vendored_temml_is_what_npm_installs_from_the_lock(vendored, installed):
    """Each vendored file equals the one `npm ci` installs, and that is the version package-lock.json pins."""
    lock = json.loads((ROOT / "package-lock.json").read_text())["packages"]["node_modules/temml"]["version"]
    assert json.loads((NPM_TEMML / "package.json").read_text())["version"] == lock
    assert f"temml](https://temml.org) {lock}" in (VENDORED / "README.md").read_text()
    assert (VENDORED / vendored).read_bytes() == (NPM_TEMML / installed).read_bytes()


FORMULAS = [
    (r"F = \frac{\mathrm{d}p}{\mathrm{d}t}", False),
    (r"\int_0^\tau F\,\mathrm{d}t = \Delta p \tag{2}", True),
    (r"\sqrt{\tfrac{k}{m}}\,\vec v_{1}^{\prime}", False),
    (r"\begin{aligned} a &= b \\ c &= d \end{aligned}", True),
]


def test_the_browser_build_run_by_node_gives_the_packages_mathml():
    """The vendored browser build, run in node, writes the MathML of the npm package's CommonJS build."""
    ours, _ = tex.convert_math([MathItem(t, d, SourceLoc("x.md", 1)) for t, d in FORMULAS])
    script = (
        "const t = require('temml'); const f = JSON.parse(require('fs').readFileSync(0, 'utf8'));"
        "process.stdout.write(JSON.stringify(f.map(([x, d]) => t.renderToString(x, "
        "{displayMode: d, throwOnError: true, annotate: false}))));"
    )
    done = subprocess.run(
        ["node", "-e", script],
        input=json.dumps(FORMULAS),
        capture_output=True,
        text=True,
        env={**os.environ, "NODE_PATH": str(ROOT / "node_modules")},
        check=True,
    )
    assert ours == json.loads(done.stdout)


def test_without_node_the_build_says_what_to_install(monkeypatch, tmp_path):
    """node missing from PATH is a set-up error that names node, not a traceback."""
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(
        tex.MathToolMissing, match="node is not on PATH: sitegen converts TeX to MathML with Temml, run by Node.js"
    ):
        tex.convert_math([MathItem("x", False, SourceLoc("x.md", 1))])


@pytest.fixture(scope="module")
def source_copy(tmp_path_factory) -> Path:
    """The repository's tracked files, with a built site in build/ (one page and a marker)."""
    copy = tmp_path_factory.mktemp("repo") / "sitegen"
    files = (
        subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout.decode().split("\0")
    )
    for name in filter(None, files):
        if (ROOT / name).is_file():
            (copy / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, copy / name)
    (copy / "build" / "assets").mkdir(parents=True)
    (copy / "build" / "index.html").write_text("<!DOCTYPE html><title>site</title>\n")
    (copy / "build" / "assets" / "sitegen.css").write_text("")
    return copy


def _listing(copy: Path) -> tuple[list[str], list[str]]:
    """Every path (files and folders) under the copy's build/, and under the whole copy."""
    return names(copy / "build", folders=True), names(copy, folders=True)


def _pip(*args: str) -> None:
    subprocess.run(
        [sys.executable, "-m", "pip", "--disable-pip-version-check", "--quiet", *args], check=True, capture_output=True
    )


@pytest.fixture(scope="module")
def wheel(source_copy, tmp_path_factory) -> dict:
    """sitegen's wheel, built once with `pip wheel .` from the source copy, and the copy's build/ and
    whole tree just before and just after."""
    out = tmp_path_factory.mktemp("wheel")
    before = _listing(source_copy)
    _pip("wheel", "--no-deps", "--no-build-isolation", "-w", str(out), str(source_copy))
    return {
        "path": next(out.glob("sitegen-*.whl")),
        "before": before,
        "after": _listing(source_copy),
    }


@pytest.mark.parametrize("command", ["wheel", "install"])
@pytest.mark.slow
def test_installing_writes_nothing_into_build(source_copy, tmp_path, request, command):
    """After a site is built into build/, `pip wheel .` and `pip install .` leave build/ as it was (and
    the source tree gains no egg-info or build folder of theirs)."""
    if command == "wheel":
        built = request.getfixturevalue("wheel")
        before, after = built["before"], built["after"]
    else:
        before = _listing(source_copy)
        _pip("install", "--no-deps", "--no-build-isolation", "--target", str(tmp_path / "target"), str(source_copy))
        after = _listing(source_copy)
    assert after[0] == before[0]
    assert after[1] == before[1]


@pytest.mark.slow
def test_the_wheel_carries_temml_templates_and_assets(wheel):
    """What a build needs besides Python code is inside the wheel."""
    names = zipfile.ZipFile(wheel["path"]).namelist()
    for needed in (
        "sitegen/content/temml/temml.min.js",
        "sitegen/content/temml/Temml-Latin-Modern.css",
        "sitegen/content/temml/LICENSE",
        "sitegen/content/tex2mathml.js",
        "sitegen/site/templates/base.html",
        "sitegen/site/static/sitegen.js",
        "sitegen/site/static/latinmodern-math.woff2",
        "sitegen/pdf/book.html",
        "sitegen/pdf/print.css",
        "sitegen/models/chain/__init__.py",
    ):
        assert needed in names
    assert not [n for n in names if "__pycache__" in n or n.startswith(("tests/", "content/", "build/"))]


@pytest.fixture(scope="module")
def installed(wheel, tmp_path_factory) -> dict:
    """A fresh venv with the wheel (its libraries taken from this one's site-packages) and the swing
    plugin's wheel: its `sitegen`, its python, its site-packages and the environment to run them in."""
    top = tmp_path_factory.mktemp("installed")
    wheels = top / "wheels"
    _pip("wheel", "--no-deps", "--no-build-isolation", "-w", str(wheels), str(ROOT / "tests" / "plugins" / "swing"))
    shutil.copy(wheel["path"], wheels)
    env_dir = top / "venv"
    venv.create(env_dir)  # without pip: this environment's pip installs into it (pip --python)
    python = env_dir / "bin" / "python"
    site = next((env_dir / "lib").glob("python3*/site-packages"))
    libraries = next(Path(p) for p in sys.path if p.endswith("site-packages") and (Path(p) / "numpy").is_dir())
    (site / "libraries.pth").write_text(
        f"{libraries}\n"
    )  # numpy, scipy, matplotlib...: not sitegen (an editable .pth is not read from there)
    _pip("--python", str(python), "install", "--no-deps", "--no-index", *map(str, wheels.glob("*.whl")))
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "NODE_PATH")} | {"OPENBLAS_NUM_THREADS": "1"}
    where = subprocess.run(
        [python, "-c", "import sitegen; print(sitegen.__file__)"], capture_output=True, text=True, env=env
    )
    assert where.stdout.startswith(str(site)), where.stdout  # the wheel's sitegen, not this checkout's
    return {"sitegen": str(env_dir / "bin" / "sitegen"), "python": str(python), "env": env}


@pytest.mark.slow
def test_the_installed_wheel_builds_a_book_elsewhere(installed, tmp_path):
    """The installed tool builds the plugin book in a folder of its own, with no node_modules anywhere
    near; an edit to the book's model changes the page and recomputes that model's scene only."""
    book = tmp_path / "elsewhere" / "swings"
    shutil.copytree(ROOT / "tests" / "plugins" / "book", book)
    sitegen, env = [installed["sitegen"], "build", "--explain"], installed["env"]
    first = subprocess.run(sitegen, cwd=book, capture_output=True, text=True, env=env)
    assert first.returncode == 0, first.stderr
    page = (book / "build" / "index.html").read_text()
    assert 'data-out="T">2.0385 s<' in page and 'data-out="period">4.443 s<' in page and "<math" in page
    model = book / "models" / "pendulum" / "model.py"
    model.write_text(model.read_text().replace("decimals=4", "decimals=5"))
    second = subprocess.run(sitegen, cwd=book, capture_output=True, text=True, env=env)
    assert second.returncode == 0, second.stderr
    assert "index#pendulum" in second.stdout and "computed: model code changed" in second.stdout
    assert [line for line in second.stdout.splitlines() if "index#swing" in line][0].endswith("cached")
    assert 'data-out="T">2.03853 s<' in (book / "build" / "index.html").read_text()
    assert not any(p.name == "node_modules" for p in book.parents) and not (book / "node_modules").exists()


@pytest.mark.slow
def test_a_new_book_builds_and_previews_with_the_installed_tool(installed, tmp_path, chromium):
    """`sitegen new mybook && cd mybook && sitegen build` with the installed wheel makes pages whose
    scene shows the book's own model; its test passes; `sitegen serve --watch` there shows a prose
    edit in the open page by itself."""
    from preview import WatchServer

    env = installed["env"]
    made = subprocess.run(
        [installed["sitegen"], "new", "mybook"], cwd=tmp_path, capture_output=True, text=True, env=env
    )
    assert made.returncode == 0, made.stderr
    book = tmp_path / "mybook"
    built = subprocess.run([installed["sitegen"], "build"], cwd=book, capture_output=True, text=True, env=env)
    assert built.returncode == 0, built.stderr
    page = (book / "build" / "pendulum.html").read_text()
    period = (
        4 * math.sqrt(1 / 9.81) * quad(lambda phi: (1 - math.sin(phi) ** 2 / 4) ** -0.5, 0, math.pi / 2)[0]
    )  # 60°, 1 m
    assert 'data-scene="pendulum"' in page and f'data-out="T">{period:.3f} s<' in page and "<math" in page
    tested = subprocess.run(
        [installed["python"], "-m", "pytest", "-q", "-p", "no:cacheprovider", "tests"],
        cwd=book,
        capture_output=True,
        text=True,
        env=env,
    )
    assert tested.returncode == 0 and " passed" in tested.stdout, tested.stdout + tested.stderr
    server = WatchServer(book, [installed["sitegen"], "serve", "--watch", "--port", "0"], env)
    try:
        view = chromium.new_page()
        view.goto(server.url("pendulum.html"))
        (book / "content" / "pendulum.md").write_text(
            (book / "content" / "pendulum.md").read_text() + "\nOne more line of prose.\n"
        )
        view.wait_for_function(
            "document.body?.innerText.includes('One more line of prose.')", timeout=10_000
        )  # a hang guard; bench/preview.py times it
        view.close()
    finally:
        assert server.stop() == 0
