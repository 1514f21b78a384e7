"""A book's config: `book.toml` in the book's folder (title, author, language, base URL, footer and
the folders of its parts). Every key is optional; a folder is relative to the book's folder.

    title = "Mechanics, interactively"   # default: the title of content/index.md
    author = "A. Author"
    language = "en"                       # the pages' lang attribute
    base_url = "https://example.org/book/" # when set, each page names its canonical address
    footer = "..."                        # the text at the foot of every page
    content = "content"                   # the pages
    models = "models"                     # the book's own models, one folder (or file) each
    theme = "theme"                       # templates that replace the built-in ones, and CSS to add
    output = "build"                      # where the site is written
    goldens = "goldens"                   # the figure goldens of `sitegen check-figures`
    date = "2026-12-01"                   # the book's date (YYYY-MM-DD): its PDF's title page and metadata
    paper = "a4"                          # the PDF's page size: "a4" or "letter"
    bibliography = "references.bib"       # the BibTeX file that [@key] citations name
    csl = "styles/nature.csl"             # the CSL style that formats them (default: American Physical Society)
    page_budget_kb = 400                  # a page above this (gzip, with its assets) is a warning
"""

from __future__ import annotations

import datetime
import difflib
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

CONFIG_FILE = "book.toml"
PLUGIN_GROUP = "sitegen.models"  # the entry-point group of installed model plugins
DEFAULT_FOOTER = "Built by sitegen. Every figure was computed when the book was built; this page works offline."
TEXTS = ("title", "author", "language", "base_url", "footer", "date", "paper")
PAPERS = ("a4", "letter")
FOLDERS = ("content", "models", "theme", "output", "goldens")
FILES = ("bibliography", "csl")  # optional files, relative to the book's folder
NUMBERS = ("page_budget_kb",)
PAGE_BUDGET_KB = 400  # what a page may weigh as a phone downloads it: gzip, with the script, stylesheet and math font


class ConfigError(ValueError):
    """book.toml is missing, unreadable or has a key or value that is wrong (a message for the author)."""


@dataclass(frozen=True)
class BookConfig:
    """Where a book's parts are (absolute paths) and what its pages say about it."""

    root: Path
    title: str = ""  # "": the home page's title
    author: str = ""
    language: str = "en"
    base_url: str = ""
    footer: str = DEFAULT_FOOTER
    date: str = ""  # "": the book has no date
    paper: str = "a4"
    content: Path | None = None
    models: Path | None = None
    theme: Path | None = None
    output: Path | None = None
    goldens: Path | None = None
    bibliography: Path | None = None  # None: the book cites nothing
    csl: Path | None = None  # None: the American Physical Society's style
    page_budget_kb: float = PAGE_BUDGET_KB

    def __post_init__(self):
        for name in FOLDERS:  # a folder left out is the one named like its key
            if getattr(self, name) is None:
                object.__setattr__(self, name, self.root / ("build" if name == "output" else name))

    def relative(self, path: Path) -> str:
        """A path as the author sees it: relative to the book's folder when inside it."""
        try:
            return path.relative_to(self.root).as_posix()
        except ValueError:
            return str(path)


def read_book(root: Path, required: bool = False) -> BookConfig:
    """The config of the book in folder `root`: its book.toml, or every default when there is none
    (ConfigError when `required` and there is none, or when it is wrong)."""
    root = root.resolve()
    path = root / CONFIG_FILE
    if not path.is_file():
        if required:
            raise ConfigError(
                f"no {CONFIG_FILE} in {root}: a book is a folder with {CONFIG_FILE} and content/ "
                f"(run sitegen inside the book's folder, or give --root)"
            )
        return BookConfig(root)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as problem:
        raise ConfigError(f"{CONFIG_FILE}: {problem}") from None
    return BookConfig(root, **_checked(data, root))


def _checked(data: dict, root: Path) -> dict:
    """The keys of book.toml as BookConfig's fields; ConfigError naming the first key that is wrong."""
    known = TEXTS + FOLDERS + FILES + NUMBERS
    values = {}
    for key, value in data.items():
        if key not in known:
            close = difflib.get_close_matches(key, known, n=1)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            raise ConfigError(f"{CONFIG_FILE}: unknown key '{key}'{hint} Keys: {', '.join(known)}")
        if key in NUMBERS:
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 < value < float("inf"):
                raise ConfigError(f"{CONFIG_FILE}: '{key}' must be a positive number, e.g. {key} = {PAGE_BUDGET_KB}")
            values[key] = float(value)
            continue
        if not isinstance(value, str):
            raise ConfigError(f"{CONFIG_FILE}: '{key}' must be a string, e.g. {key} = \"...\"")
        values[key] = (root / value).resolve() if key in FOLDERS + FILES else value
    if values.get("paper", "a4") not in PAPERS:
        raise ConfigError(
            f'{CONFIG_FILE}: paper \'{values["paper"]}\' is not a size sitegen knows; use "a4" or "letter"'
        )
    if values.get("date"):
        try:
            if not re.fullmatch(r"\d{4}-\d{2}-\d{2}", values["date"]):
                raise ValueError
            datetime.date.fromisoformat(values["date"])
        except ValueError:
            raise ConfigError(
                f"{CONFIG_FILE}: date '{values['date']}' is not a date written YYYY-MM-DD, e.g. date = \"2026-12-01\""
            ) from None
    return values
