"""Pages: discovery under content/, TOML front matter, and Markdown with slots."""
from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..errors import AuthorError, SourceLoc
from .markdown_ext import Extracted, markdown_to_html

FRONT_MATTER = "+++"
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
    found: Extracted

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
        return None, [AuthorError(where, f"the file is not UTF-8 text (byte 0x{data[error.start]:02x}); save it as UTF-8")]
    meta, body_start, errors = _front_matter(lines, source)
    if meta is None:
        return None, errors
    found = Extracted()
    html = markdown_to_html("\n".join(lines[body_start:]), source, body_start + 1, found)
    page = Page(
        slug=path.stem,
        source=source,
        title=str(meta["title"]),
        order=int(meta.get("order", 0)),
        parent=meta.get("parent"),
        summary=str(meta.get("summary", "")),
        html=html,
        found=found,
    )
    return page, errors + found.errors


def _front_matter(lines: list[str], source: str) -> tuple[dict | None, int, list[AuthorError]]:
    top = SourceLoc(source, 1)
    if not lines or lines[0].strip() != FRONT_MATTER:
        return None, 0, [AuthorError(top, f"a page starts with TOML front matter between '{FRONT_MATTER}' lines, e.g. title = \"Newton's laws\"")]
    end = next((i for i in range(1, len(lines)) if lines[i].strip() == FRONT_MATTER), None)
    if end is None:
        return None, 0, [AuthorError(top, f"front matter is not closed; add a line '{FRONT_MATTER}' after it")]
    try:
        meta = tomllib.loads("\n".join(lines[1:end]))
    except tomllib.TOMLDecodeError as error:
        found = _TOML_LINE.search(str(error))
        line = 1 + int(found[1]) if found else 1
        message = _TOML_LINE.sub("at", str(error))  # the line is in the location already
        return None, 0, [AuthorError(SourceLoc(source, line), f"front matter is not valid TOML: {message}")]
    problems = []
    if not isinstance(meta.get("title"), str) or not meta["title"].strip():
        problems.append(AuthorError(top, 'front matter needs a title, e.g. title = "Newton\'s laws"'))
    if not isinstance(meta.get("order", 0), int):
        problems.append(AuthorError(top, "front matter 'order' must be a whole number"))
    if "parent" in meta and not isinstance(meta["parent"], str):
        problems.append(AuthorError(top, "front matter 'parent' must be the name of another page, e.g. \"newtons-laws\""))
    return (None if problems else meta), end + 1, problems
