"""The README, CONTRIBUTING.md and docs/ name only what exists: every file path in backticks is a file or
folder of this repository (or, for a path inside a book, of the book `sitegen new` writes), every relative
link resolves from the folder of the file that holds it (as a reader's browser resolves it); every
`sitegen ...` command is a real subcommand with real options; every `make ...` is a Makefile target.
Nothing points outside the repository (`../` past its root, absolute machine paths)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from sitegen.cli import command_parser
from sitegen.newbook import STARTER

ROOT = Path(__file__).resolve().parents[1]
DOCS = [ROOT / "README.md", *ROOT.glob("CONTRIBUTING.md"), *sorted((ROOT / "docs").rglob("*.md"))]
# Where a relative path may be found: the repository, a book made by `sitegen new`, and the plugin book of the tests.
PLACES = (ROOT, STARTER, ROOT / "tests" / "plugins" / "book")
MADE_BY_TOOLS = (
    "build/",
    "build-review/",
    ".cache/",
    ".venv/",
    "node_modules/",
    "goldens/",
)  # written by a build or set-up
PLACEHOLDER = re.compile(r"[<>*{}$]|\.\.\.|…")
FILE_LIKE = re.compile(r"^[\w.~/-]+$")
CODE_SPAN = re.compile(r"(?<!`)`([^`\n]+)`(?!`)")
FENCED = re.compile(r"^(```+|~~~+)[^\n]*\n(.*?)^\1\s*$", re.S | re.M)
LINK = re.compile(r"\]\(([^)\s]+)\)")
SITEGEN = re.compile(r"(?:^|[\s/(])sitegen((?:[ \t]+[^\s`;&)#]+)*)")
MAKE = re.compile(r"(?:^|[\s(`])make\s+([a-z][\w-]*)")


def _code(text: str) -> tuple[list[str], list[str]]:
    """(inline code spans, lines of fenced blocks) of a Markdown text."""
    blocks = [line for match in FENCED.finditer(text) for line in match[2].splitlines()]
    prose = FENCED.sub("", text)
    return CODE_SPAN.findall(prose), blocks


def _path_problem(path: str) -> str | None:
    """Why a path named in the docs is wrong, or None."""
    if path.startswith(("/", "~")) or ".." in path.split("/"):
        return "points outside the repository"
    if path.startswith(MADE_BY_TOOLS) or PLACEHOLDER.search(path):
        return None
    if not any((place / path).exists() for place in PLACES):
        return "does not exist"
    return None


def _looks_like_path(span: str) -> bool:
    """A code span that names a file or folder: slashes or a file's extension, letters, no spaces."""
    if "://" in span or span.startswith("-") or not FILE_LIKE.match(span) or not re.search(r"[a-z]", span):
        return False
    return "/" in span  # a bare name (`__init__.py`, `book.toml`) names a kind of file, not one place


def _named_paths(text: str) -> list[str]:
    """The paths a text names in code spans (from the repository's root)."""
    spans, _ = _code(text)
    return [s.strip() for s in spans if _looks_like_path(s.strip()) or s.strip().startswith(("../", "/"))]


def _links(text: str) -> list[str]:
    """The relative links of a text's prose, without their #fragments."""
    prose = CODE_SPAN.sub("", FENCED.sub("", text))
    links = [link.split("#")[0] for link in LINK.findall(prose) if "://" not in link and not link.startswith("mailto:")]
    return [link for link in links if link]


def _link_problem(doc: Path, link: str) -> str | None:
    """Why a relative link in `doc` is wrong, or None."""
    target = (doc.parent / link).resolve()
    if link.startswith(("/", "~")) or not target.is_relative_to(ROOT):
        return "points outside the repository"
    return None if target.exists() else "does not exist"


def _subcommands() -> dict[str, set[str]]:
    """Each sitegen subcommand and its option strings."""
    action = next(a for a in command_parser()._actions if a.__class__.__name__ == "_SubParsersAction")
    return {name: set(sub._option_string_actions) for name, sub in action.choices.items()}


def _make_targets() -> set[str]:
    return set(re.findall(r"^([a-zA-Z][\w.-]*)\s*:(?!=)", (ROOT / "Makefile").read_text(), re.M))


def _commands(text: str) -> list[str]:
    """Every `sitegen ...` and `make ...` the text shows (in code spans and code blocks)."""
    spans, blocks = _code(text)
    return [c for c in spans + blocks if re.search(r"(?:^|[\s/(])(sitegen|make)\s", c + " ")]


def _command_problems(line: str, subcommands: dict, targets: set) -> list[str]:
    problems = []
    for match in SITEGEN.finditer(line):
        words = match[1].split()
        words = words[: words.index("|")] if "|" in words else words  # a shell pipe ends the command
        if not words or not re.fullmatch(r"[a-z][a-z-]*(\|[a-z][a-z-]*)*", words[0]):
            continue  # not a command: `sitegen.models`, `sitegen` alone, a placeholder
        for name in words[0].split("|"):  # `sitegen build|serve`: each of them
            if name not in subcommands:
                problems.append(f"'sitegen {name}' is no subcommand ({', '.join(subcommands)})")
        options = [w.split("=")[0] for w in words[1:] if w.startswith("--")]
        problems += [
            f"'sitegen {words[0]} {o}' is no option"
            for o in options
            if words[0] in subcommands and o not in subcommands[words[0]]
        ]
    for target in MAKE.findall(line):
        if target not in targets:
            problems.append(f"'make {target}' is no Makefile target ({', '.join(sorted(targets))})")
    return problems


@pytest.mark.parametrize("doc", DOCS, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_named_path_exists(doc):
    named = _named_paths(doc.read_text())
    problems = [f"{path}: {why}" for path in named if (why := _path_problem(path))]
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("doc", DOCS, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_link_resolves(doc):
    problems = [f"{link}: {why}" for link in _links(doc.read_text()) if (why := _link_problem(doc, link))]
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("doc", DOCS, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_command_is_real(doc):
    subcommands, targets = _subcommands(), _make_targets()
    problems = [
        f"{line.strip()}: {p}"
        for line in _commands(doc.read_text())
        for p in _command_problems(line, subcommands, targets)
    ]
    assert not problems, "\n".join(problems)


def test_the_checker_catches_what_it_should():
    """A wrong path, a path out of the repository, an unknown subcommand, option or target are found."""
    subcommands, targets = _subcommands(), _make_targets()
    assert _path_problem("src/sitegen/render/views.py") == "does not exist"
    assert _path_problem("../notes/physics.md") == "points outside the repository"
    assert _path_problem("/home/someone/node_modules") == "points outside the repository"
    assert _path_problem("models/pendulum/model.py") is None and _path_problem("src/sitegen/cli.py") is None
    assert _named_paths("see `docs/nothing.md` and [x](docs/gone.md)") == ["docs/nothing.md"]
    assert _links("see `[y](z.md)` and [x](docs/gone.md#part)") == ["docs/gone.md"]
    assert _link_problem(ROOT / "docs" / "physics" / "README.md", "../models.md") is None
    assert _link_problem(ROOT / "docs" / "physics" / "README.md", "models.md") == "does not exist"
    assert _link_problem(ROOT / "docs" / "architecture.md", "../../elsewhere.md") == "points outside the repository"
    assert _command_problems("sitegen preview", subcommands, targets) == [
        "'sitegen preview' is no subcommand (" + ", ".join(subcommands) + ")"
    ]
    assert _command_problems(".venv/bin/sitegen serve --watch --bind 0.0.0.0", subcommands, targets) == []
    assert _command_problems("sitegen serve --live", subcommands, targets) == ["'sitegen serve --live' is no option"]
    assert _command_problems("make preview", subcommands, targets)[0].startswith("'make preview' is no Makefile target")
    assert _command_problems("sitegen build|serve|nope", subcommands, targets)[0].startswith(
        "'sitegen nope' is no subcommand"
    )


def test_the_readme_names_two_set_up_commands():
    """A fresh machine needs `make site` and `make test`, and the README's set-up says exactly that."""
    readme = (ROOT / "README.md").read_text()
    set_up = readme.split("## Set up this repository", 1)[1].split("\n## ", 1)[0]
    block = FENCED.search(set_up)[2]
    assert [line.split("#")[0].strip() for line in block.splitlines() if line.strip()] == ["make site", "make test"]


def test_every_directive_and_math_feature_the_book_uses_is_explained():
    """Each scene directive used in content/ has its row in docs/writing-pages.md, and so has each
    piece of math markup the pages use (equation labels and references, aligned and listed equations)."""
    from sitegen.build import BuildConfig, resolve_book

    guide = (ROOT / "docs" / "writing-pages.md").read_text()
    pages = resolve_book(BuildConfig.at(ROOT)).pages
    used = {key.split()[0] for page in pages for spec in page.extracted.scenes for key, _ in spec.lines}
    assert {"slider", "choice", "animate", "caption"} <= used
    missing = [key for key in sorted(used) if f"| `{key} " not in guide and f"| `{key}:" not in guide]
    assert not missing, f"directives without a row in docs/writing-pages.md: {missing}"
    sources = "".join(path.read_text() for path in (ROOT / "content").glob("*.md"))
    listed = re.search(r"^slider \w+: [-\d.]+, ", sources, re.M)
    features = {
        "{#eq-": "`{#eq-name}`",
        "(@eq-": "`(@eq-name)`",
        r"\begin{aligned}": r"`\begin{aligned}",
        r"\qquad": r"`\qquad`",
    }
    assert listed and "`slider NAME: V1, V2, V3 ... default V`" in guide
    assert not [shown for markup, shown in features.items() if markup in sources and shown not in guide]
