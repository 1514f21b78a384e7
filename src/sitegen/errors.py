"""Author-facing errors: where in the sources, what is wrong, and what would be right."""

from __future__ import annotations

import difflib
import functools
import os
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True, order=True)
class SourceLoc:
    """A place in the author's sources: a path relative to the project and a 1-based line."""

    path: str
    line: int

    def __str__(self) -> str:
        return f"{self.path}:{self.line}"


def did_you_mean(name: str, choices) -> str:
    """A " — did you mean 'x'?" for a near miss among `choices`, else just the end of the sentence."""
    choices = list(choices)
    close = difflib.get_close_matches(name, choices, n=1, cutoff=0.5)
    # else a name the misspelling starts with ('freq' for 'f'), the longest
    close = close or sorted((c for c in choices if name.startswith(c)), key=len)[-1:]
    return f" — did you mean '{close[0]}'?" if close else "."


def caller_line(frame, own_file: str) -> tuple[str, int] | None:
    """The file and line of the first frame from `frame` outwards that is outside `own_file` and outside
    generated code (a dataclass's `__init__`): where an author's code made the object being made."""
    while frame is not None and (frame.f_code.co_filename == own_file or frame.f_code.co_filename.startswith("<")):
        frame = frame.f_back
    return (frame.f_code.co_filename, frame.f_lineno) if frame is not None else None


def code_loc(file: str, line: int, root: Path | None = None) -> SourceLoc:
    """A line of code as the author sees it: its path relative to the book's folder `root` when inside it."""
    return SourceLoc(_shown_path(file, root, os.getcwd()), line)


@functools.lru_cache(maxsize=1024)
def _shown_path(file: str, root: Path | None, cwd: str) -> str:
    """A source file's path as `code_loc` shows it (relative paths read from `cwd`), resolved once per file and
    book: a build names the `Output(...)` line of every output it checks, most of them in a few files."""
    path = Path(file).resolve()
    if root is not None and path.is_relative_to(root.resolve()):
        path = path.relative_to(root.resolve())
    return path.as_posix()


@dataclass(eq=False)  # not frozen: the exception machinery sets attributes such as __cause__
class AuthorError(Exception):
    """One mistake in the sources, reported as `path:line: scene 'id': message`."""

    loc: SourceLoc
    message: str
    scene: str | None = None

    def __str__(self) -> str:
        where = f"scene '{self.scene}': " if self.scene else ""
        return f"{self.loc}: {where}{self.message}"

    def __reduce__(self):  # errors raised in worker processes travel back by pickling
        return (AuthorError, (self.loc, self.message, self.scene))


class BuildFailed(Exception):
    """The build found author errors; it carries all of them, sorted by place."""

    def __init__(self, errors: list[AuthorError]):
        self.errors = sorted(errors, key=lambda e: (e.loc, e.message))
        super().__init__("\n".join(str(e) for e in self.errors))


class ErrorLog:
    """Collects author errors so one run can report every one of them."""

    def __init__(self) -> None:
        self.errors: list[AuthorError] = []

    def add(self, error: AuthorError) -> None:
        """Record one error."""
        self.errors.append(error)

    def raise_if_any(self) -> None:
        """End the build with every error collected so far, if there are any."""
        if self.errors:
            raise BuildFailed(self.errors)


class SceneCrashed(Exception):
    """An exception raised by code while working on one scene (a model's, a figure's or sitegen's):
    the scene's place, the line of code that raised it (`code`, the model's own when the traceback
    passes through it), and the phase.

    The original exception is the cause (`raise SceneCrashed(...) from error`), for --debug.
    """

    def __init__(self, loc: SourceLoc, scene: str, phase: str, error: BaseException, code: SourceLoc | None = None):
        self.loc, self.scene, self.phase, self.error, self.code = loc, scene, phase, error, code
        where = f"{code}: " if code else ""
        super().__init__(f"{loc}: scene '{scene}': {where}{type(error).__name__}: {error} (while {phase})")
