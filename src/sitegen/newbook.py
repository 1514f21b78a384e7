"""`sitegen new DIR`: a new book that builds at once, copied from the starter book in starter/ (real
files in the package): book.toml, a home page, a chapter with prose, display math and a scene, the
book's own model with its figure in models/pendulum/, and a pytest test of that model."""

from __future__ import annotations

import shutil
from pathlib import Path

STARTER = Path(__file__).with_name("starter")
RENAMED = {"gitignore": ".gitignore"}  # kept without its dot in the package, where it would act on the package's files


class FolderNotEmpty(ValueError):
    """The folder for the new book already holds something (a message for the author)."""


def starter_files() -> list[Path]:
    """The starter book's files, relative to its folder, in a stable order."""
    return sorted(
        p.relative_to(STARTER)
        for p in STARTER.rglob("*")
        if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc"
    )


def new_book(folder: Path) -> list[str]:
    """Write the starter book into `folder` (made if missing, else it must be empty); the names written."""
    if folder.exists() and not folder.is_dir():
        raise FolderNotEmpty(f"{folder} is a file; sitegen new writes a book into a new or empty folder")
    if folder.is_dir():
        present = sorted(p.name for p in folder.iterdir())
        if present:
            shown = ", ".join(present[:5]) + (", ..." if len(present) > 5 else "")
            raise FolderNotEmpty(
                f"{folder} is not empty (it holds {shown}); sitegen new writes a book into a new "
                f"or empty folder, so that it overwrites nothing"
            )
    written = []
    for relative in starter_files():
        name = RENAMED.get(relative.as_posix(), relative.as_posix())
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(STARTER / relative, folder / name)
        written.append(name)
    return written
