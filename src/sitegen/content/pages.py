"""Pages: discovery under content/, TOML front matter, and Markdown with slots."""

from __future__ import annotations

import difflib
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..errors import AuthorError, SourceLoc
from .markdown_ext import Extracted, markdown_to_html

FRONT_MATTER = "+++"
FRONT_MATTER_KEYS = ("title", "order", "parent", "summary")
_TOML_LINE = re.compile(r"at line (\d+),")


@dataclass(frozen=True)
class Page:
    """One parsed page: metadata, prose HTML with slots, and what was lifted out of it."""

    slug: str  # output name without '.html'; 'index' is the book home
    source: str  # path relative to the project, for messages
    title: str
    order: int
    parent: str | None
    summary: str
    html: str
    extracted: Extracted

    @property
    def output_name(self) -> str:
        """The file this page becomes under build/."""
        return f"{self.slug}.html"


def discover_pages(content_dir: Path) -> list[Path]:
    """Every Markdown page under `content_dir`, in a fixed order."""
    return sorted(content_dir.glob("*.md"))


def read_page(path: Path, root: Path) -> tuple[Page | None, list[AuthorError]]:
    """Parse one page file; return the page (None if unusable) and every error in it."""
    source = path.relative_to(root).as_posix()
    data = path.read_bytes()
    try:
        lines = data.decode("utf-8-sig").split("\n")  # -sig: a byte-order mark some editors add is dropped
    except UnicodeDecodeError as error:
        where = SourceLoc(source, data.count(b"\n", 0, error.start) + 1)
        return None, [
            AuthorError(where, f"the file is not UTF-8 text (byte 0x{data[error.start]:02x}); save it as UTF-8")
        ]
    meta, body_start, errors = _front_matter(lines, source)
    if body_start is None:  # a front matter that never closes leaves no way to tell where the body starts
        return None, errors
    # Otherwise the body is read even when the front matter is broken, and the page stands in with
    # its file name as title, so that one run reports the errors of its prose and scenes too.
    extracted = Extracted()
    html = markdown_to_html("\n".join(lines[body_start:]), source, body_start + 1, extracted)
    meta = meta or {"title": path.stem}
    page = Page(
        slug=path.stem,
        source=source,
        title=str(meta["title"]),
        order=int(meta.get("order", 0)),
        parent=meta.get("parent"),
        summary=str(meta.get("summary", "")),
        html=html,
        extracted=extracted,
    )
    return page, errors + extracted.errors


def _front_matter(lines: list[str], source: str) -> tuple[dict | None, int | None, list[AuthorError]]:
    """(metadata or None if unusable, the line where the body starts or None if unknown, errors)."""
    top = SourceLoc(source, 1)
    if not lines or lines[0].strip() != FRONT_MATTER:
        return (
            None,
            0,
            [
                AuthorError(
                    top,
                    "a page starts with TOML front matter between "
                    f"'{FRONT_MATTER}' lines, e.g. title = \"Newton's laws\"",
                )
            ],
        )
    end = next((i for i in range(1, len(lines)) if lines[i].strip() == FRONT_MATTER), None)
    if end is None:
        return None, None, [AuthorError(top, f"front matter is not closed; add a line '{FRONT_MATTER}' after it")]
    try:
        meta = tomllib.loads("\n".join(lines[1:end]))
    except tomllib.TOMLDecodeError as error:
        found = _TOML_LINE.search(str(error))
        line = 1 + int(found[1]) if found else 1
        message = _TOML_LINE.sub("at", str(error))  # the line is in the location already
        return None, end + 1, [AuthorError(SourceLoc(source, line), f"front matter is not valid TOML: {message}")]
    problems = _unknown_keys(meta, lines[1:end], source)
    if not isinstance(meta.get("title"), str) or not meta["title"].strip():
        problems.append(AuthorError(top, 'front matter needs a title, e.g. title = "Newton\'s laws"'))
    if not isinstance(meta.get("order", 0), int):
        problems.append(AuthorError(top, "front matter 'order' must be a whole number"))
    if "parent" in meta and not isinstance(meta["parent"], str):
        problems.append(
            AuthorError(top, "front matter 'parent' must be the name of another page, e.g. \"newtons-laws\"")
        )
    return (None if problems else meta), end + 1, problems


def _unknown_keys(meta: dict, lines: list[str], source: str) -> list[AuthorError]:
    """An error at its line for each key a page cannot have, with the key it most looks like."""
    problems = []
    for key in meta:
        if key in FRONT_MATTER_KEYS:
            continue
        line = next((n for n, text in enumerate(lines, start=2) if re.match(rf"\s*{re.escape(key)}\s*=", text)), 1)
        close = difflib.get_close_matches(key, FRONT_MATTER_KEYS, n=1)
        hint = f"did you mean '{close[0]}'? " if close else ""
        problems.append(
            AuthorError(
                SourceLoc(source, line),
                f"unknown front matter key '{key}'; {hint}a page takes {', '.join(FRONT_MATTER_KEYS)}",
            )
        )
    return problems
