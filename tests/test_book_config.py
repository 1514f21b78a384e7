"""A book is a folder with book.toml: its keys, its mistakes, the commands that find it from inside it
or through --root, and the theme folder that overrides templates and adds CSS."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from sitegen.build import BuildConfig, build
from sitegen.cli import main
from sitegen.config import DEFAULT_FOOTER, ConfigError, read_book
from sitegen.reference import models_reference
from sitegen.registry import builtin_registry

ROOT = Path(__file__).resolve().parents[1]


def test_every_key_sets_its_part(tmp_path):
    """Folders are relative to the book's folder; texts are taken as written."""
    (tmp_path / "book.toml").write_text(
        'title = "T"\nauthor = "A"\nlanguage = "de"\nbase_url = "https://x.org/b/"\n'
        'footer = "F"\ncontent = "pages"\nmodels = "py"\ntheme = "look"\n'
        'output = "site"\ngoldens = "figs"\n'
    )
    book = read_book(tmp_path)
    assert (book.title, book.author, book.language, book.base_url, book.footer) == (
        "T",
        "A",
        "de",
        "https://x.org/b/",
        "F",
    )
    assert [getattr(book, k) for k in ("content", "models", "theme", "output", "goldens")] == [
        tmp_path.resolve() / name for name in ("pages", "py", "look", "site", "figs")
    ]


def test_an_empty_book_toml_means_every_default(tmp_path):
    """Every key is optional: content/, models/, theme/, build/, goldens/, English, the standard footer."""
    (tmp_path / "book.toml").write_text("")
    book = read_book(tmp_path)
    assert (book.content, book.output, book.language, book.footer) == (
        tmp_path.resolve() / "content",
        tmp_path.resolve() / "build",
        "en",
        DEFAULT_FOOTER,
    )


@pytest.mark.parametrize(
    "text, message",
    [
        (
            'titel = "x"\n',
            "book.toml: unknown key 'titel'; did you mean 'title'? Keys: title, author, language, base_url, "
            "footer, date, paper, content, models, theme, output, goldens, bibliography, csl, page_budget_kb",
        ),
        ("language = 2\n", "book.toml: 'language' must be a string, e.g. language = \"...\""),
        ('title = "x\n', "book.toml: Illegal character '\\n' (at line 1, column 11)"),
        ('paper = "a5"\n', 'book.toml: paper \'a5\' is not a size sitegen knows; use "a4" or "letter"'),
        (
            'date = "1 December 2026"\n',
            "book.toml: date '1 December 2026' is not a date written YYYY-MM-DD, e.g. date = \"2026-12-01\"",
        ),
        (
            'date = "2026-02-30"\n',
            "book.toml: date '2026-02-30' is not a date written YYYY-MM-DD, e.g. date = \"2026-12-01\"",
        ),
        (
            'page_budget_kb = "400"\n',
            "book.toml: 'page_budget_kb' must be a positive number, e.g. page_budget_kb = 400",
        ),
        ("page_budget_kb = 0\n", "book.toml: 'page_budget_kb' must be a positive number, e.g. page_budget_kb = 400"),
        ("page_budget_kb = true\n", "book.toml: 'page_budget_kb' must be a positive number, e.g. page_budget_kb = 400"),
        ("page_budget_kb = inf\n", "book.toml: 'page_budget_kb' must be a positive number, e.g. page_budget_kb = 400"),
    ],
    ids=[
        "unknown-key",
        "not-a-string",
        "not-toml",
        "unknown-paper",
        "date-in-words",
        "no-such-day",
        "budget-a-string",
        "budget-zero",
        "budget-a-bool",
        "budget-inf",
    ],
)
def test_a_wrong_book_toml_says_what_is_wrong(tmp_path, text, message):
    """Mistakes in book.toml name the key and what would be right."""
    (tmp_path / "book.toml").write_text(text)
    with pytest.raises(ConfigError) as problem:
        read_book(tmp_path)
    assert str(problem.value) == message


def test_commands_outside_a_book_say_what_a_book_is(tmp_path, capsys):
    """No book.toml in the folder: exit 2 and a sentence on what is missing."""
    assert main(["build", "--root", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert f"no book.toml in {tmp_path.resolve()}" in err and "--root" in err


def test_build_works_from_inside_the_book(tiny_book, monkeypatch, capsys):
    """`sitegen build` with no --root builds the book in the current folder into its output folder."""
    (tiny_book.root / "book.toml").write_text(tiny_book.root.joinpath("book.toml").read_text() + 'output = "site"\n')
    monkeypatch.chdir(tiny_book.root)
    assert main(["build"]) == 0, capsys.readouterr().err
    assert (tiny_book.root / "site" / "index.html").is_file() and not (tiny_book.root / "build").exists()


def test_a_theme_overrides_a_template_and_adds_css(tiny_book):
    """theme/templates/base.html replaces the built-in page template; theme/*.css is appended to the stylesheet."""
    theme = tiny_book.root / "theme"
    (theme / "templates").mkdir(parents=True)
    base = (ROOT / "src" / "sitegen" / "site" / "templates" / "base.html").read_text()
    (theme / "templates" / "base.html").write_text(base.replace("<main ", '<main class="themed" ', 1))
    (theme / "extra.css").write_text(".themed { max-width: 50rem; }\n")
    build(tiny_book, progress=None)
    assert '<main class="themed" ' in (tiny_book.out / "index.html").read_text()
    css = (tiny_book.out / "assets" / "sitegen.css").read_text()
    assert css.rstrip().endswith(".themed { max-width: 50rem; }") and "extra.css, from the book's theme" in css


def test_the_default_theme_reads_language_author_footer_and_base_url(tiny_book):
    """The page's lang, author, canonical address and footer come from book.toml."""
    (tiny_book.root / "book.toml").write_text(
        'language = "fr"\nauthor = "Émilie"\nfooter = "Fin."\nbase_url = "https://ex.org/livre"\n'
    )
    build(BuildConfig.at(tiny_book.root), progress=None)
    html = (tiny_book.out / "mechanics.html").read_text()
    assert '<html lang="fr">' in html and '<meta name="author" content="Émilie">' in html
    assert '<link rel="canonical" href="https://ex.org/livre/mechanics.html">' in html
    assert '<footer class="site-footer">Émilie. Fin.</footer>' in html


def test_a_page_is_described_by_its_summary(tiny_site):
    """The meta description search engines show: the page's summary from its front matter."""
    html = (tiny_site / "mechanics.html").read_text()
    summary = "Impulse, collisions, a contact in time, work along two paths and a lever."
    assert f'<meta name="description" content="{summary}">' in html


def test_a_page_without_summary_is_described_by_its_first_paragraph(tiny_site):
    """No summary: the start of the first paragraph, cut at a word within 160 characters, math as its text."""
    html = (tiny_site / "index.html").read_text()
    found = re.search(r'<meta name="description" content="([^"]*)">', html)
    assert found, "index.html has no meta description"
    text = found[1]
    assert text.startswith("The test suite&#39;s own book: one scene for each family of models") and text.endswith("…")
    assert len(text.replace("&#39;", "'")) <= 161 and "<" not in text


def test_models_prints_a_models_declarations(capsys):
    """`sitegen models NAME`: the parameters with symbol, unit, domain and default; outputs with deps."""
    assert main(["models", "collision", "--builtin"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("## collision: Collision with restitution\n")
    assert "| e | e |  | 0 <= e <= 1 (up to ∞ with explosive) | 1 | unused with contact_spring_dashpot |" in out
    assert "| v_cm | V (centre of mass) | m/s | m1, m2, v1i, v2i | 3 decimals |  |" in out


def test_the_models_reference_in_the_docs_is_up_to_date():
    """docs/models.md is what `sitegen models --builtin` prints; rewrite it with that command after a change."""
    assert (ROOT / "docs" / "models.md").read_text() == models_reference(builtin_registry()), (
        "docs/models.md is out of date: run `sitegen models --builtin > docs/models.md`"
    )
