"""One run of the build: its configuration and its log (errors, progress lines, the phase clock)."""

from __future__ import annotations

import signal
import threading
import time
from collections.abc import Callable
from concurrent.futures import Executor
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from ..compute.accuracy import SceneAccuracy
from ..compute.cache import TableCache
from ..compute.executors import InProcess
from ..config import BookConfig, read_book
from ..errors import AuthorError, ErrorLog, SceneCrashed
from ..registry import Registry, raising_line
from ..site.writer import StagedTree


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in a build as Ctrl-C is: it stops as after Ctrl-C, its staging folder removed and the
    processes it started ended (killed without a word, they would outlive it)."""


# Set by `stop_on_sigterm`'s handler. The handler raises Terminated where the main thread is, but compiled code
# that calls back into Python (numba's) can swallow it there; every phase then raises it again at its end.
_termination_requested = threading.Event()


@contextmanager
def stop_on_sigterm():
    """While the block runs, SIGTERM raises Terminated (only the main thread can catch a signal)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def terminated(signum, frame):
        _termination_requested.set()
        raise Terminated

    _termination_requested.clear()
    previous = signal.signal(signal.SIGTERM, terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
        _termination_requested.clear()


PROGRESS_EVERY = 2.0  # seconds: long work (a heavy scene, compiling) says how far it got at least this often


@dataclass(frozen=True)
class BuildConfig:
    """Where the sources are, where the site goes, the cache, and where the work runs."""

    root: Path
    content: Path
    out: Path
    cache: Path | None = None  # None: compute everything, keep nothing
    jobs: int | str = 1  # local worker processes, or "auto" (one per core); 1: everything in this process
    scheduler: str | None = None  # address of a Dask scheduler, e.g. tcp://127.0.0.1:8786
    book: BookConfig | None = None  # the rest of book.toml (None: its defaults, for a book at `root`)

    def __post_init__(self):
        if self.book is None:
            object.__setattr__(self, "book", BookConfig(self.root, content=self.content, output=self.out))

    @classmethod
    def at(cls, root: Path, out: Path | None = None, **options) -> BuildConfig:
        """The book in folder `root` as its book.toml lays it out (cache in ROOT/.cache)."""
        book = read_book(root)
        options.setdefault("cache", book.root / ".cache")
        return cls(book.root, book.content, (out or book.output).resolve(), book=book, **options)


@dataclass(frozen=True)
class BuildReport:
    """What a build did: pages, scenes, values stored, and seconds per phase."""

    pages: int = 0
    scenes: int = 0
    stored_values: int = 0
    computed: int = 0  # scenes evaluated by their models in this build
    cached: int = 0  # scenes taken from the cache
    evaluations: int = 0  # work units run (model evaluations over blocks of stops)
    phases: dict[str, float] = field(default_factory=dict)
    files: dict[str, int] = field(default_factory=dict)
    scene_lines: list[str] = field(default_factory=list)  # one line per scene: cached or computed and why
    weights: list = field(default_factory=list)  # a site.weight.PageWeight per page
    warnings: list[str] = field(default_factory=list)  # pages above the book's budget, and what would shrink them
    accuracy: list[SceneAccuracy] = field(default_factory=list)  # numerically computed scenes, in page/scene order
    data_bytes: dict[str, tuple[int, int]] = field(default_factory=dict)  # "page#scene" -> raw, gzip bytes of its data

    @property
    def notes(self) -> list[str]:
        """What an author may want to change, short of an error (a dep that changes nothing; among the scene lines)."""
        return [line for line in self.scene_lines if line.startswith("note: ")]


@dataclass(frozen=True)
class BuildRun:
    """What every phase gets besides the book: the run's configuration (the settings, the models and figures
    it may use, the cache, the executor the work runs on, the staging folder the write phases fill, where
    progress lines go) and its log (the author errors found, and the seconds of each phase). What a phase
    makes goes into the book it returns."""

    config: BuildConfig
    registry: Registry
    progress: Callable[[str], None] | None = None
    executor: Executor = field(default_factory=InProcess)  # where the work runs (compute.executors)
    cache: TableCache | None = None
    tree: StagedTree | None = None  # the page phases' only: where the site's files go
    log: ErrorLog = field(default_factory=ErrorLog)
    seconds: dict[str, float] = field(default_factory=dict)  # phase -> seconds, summed over its runs

    @classmethod
    def of(cls, config: BuildConfig, registry: Registry, progress=None, executor: Executor | None = None) -> BuildRun:
        """A run of `config` (its cache, if it names one) with `registry`'s models and figures."""
        cache = TableCache(config.cache) if config.cache else None
        return cls(config, registry, progress, executor or InProcess(), cache)

    def cached(self, kind: str, key: str, compute) -> bytes:
        """The value stored under (`kind`, `key`), else `compute()` (stored for next time when there is a cache)."""
        return self.cache.cached(kind, key, compute) if self.cache else compute()

    def phase(self, name: str, function, book):
        """Run one phase over the book, adding its seconds to the phase's total."""
        start = time.perf_counter()
        try:
            made = function(book, self)
        finally:
            self.seconds[name] = self.seconds.get(name, 0.0) + time.perf_counter() - start
        if _termination_requested.is_set():
            raise Terminated
        return made

    def say(self, line: str) -> None:
        """One line of the build's log (nothing when the run is quiet)."""
        if self.progress:
            self.progress(line)

    def error(self, error: AuthorError) -> None:
        """Record an author error; the build goes on to find the others."""
        self.log.add(error)

    @property
    def failed(self) -> bool:
        """Whether an author error has been found (pages are then no longer assembled)."""
        return bool(self.log.errors)

    @contextmanager
    def scene(self, record, doing: str):
        """Work on one scene: an author error is logged; any other exception is raised with the scene's
        page, line and name and the line of code that raised it (the model's or figure's own if the
        traceback passes through their plugin)."""
        try:
            yield
        except AuthorError as error:
            self.error(error)
        except (KeyboardInterrupt, SystemExit, MemoryError):
            raise
        except Exception as error:
            code = raising_line(error, [type(record.scene.model), type(record.view)], self.config.book)
            raise SceneCrashed(record.scene.spec.loc, record.scene.spec.id, doing, error, code) from error
