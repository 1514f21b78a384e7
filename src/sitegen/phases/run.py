"""One run of the build: its settings, errors, cache, progress lines and counters, and the phase clock."""

from __future__ import annotations

import time
from concurrent.futures import Future
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from ..compute.accuracy import SceneAccuracy
from ..compute.cache import TableCache, compute_now
from ..compute.executors import Background, BackgroundFailed, Beside
from ..config import BookConfig, read_book
from ..errors import AuthorError, ErrorLog, SceneCrashed
from ..registry import Registry, raising_line

PROGRESS_EVERY = 2.0  # seconds: long work (a heavy scene, compiling) says how far it got at least this often


@dataclass(frozen=True)
class BuildConfig:
    """Where the sources are, where the site goes, the cache, and where the work runs."""

    root: Path
    content: Path
    out: Path
    cache: Path | None = None  # None: compute everything, remember nothing
    jobs: int = 1
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
class Ahead:
    """A scene tabulating beside the build: its model, its units of work and their futures, in plan order."""

    model: str
    units: tuple
    futures: tuple

    def stops_done(self) -> tuple[int, int, bool]:
        """Stops done, stops in all, and whether any work on it has started."""
        done = sum(u.stops() for u, f in zip(self.units, self.futures) if f.done())
        started = any(f.running() or f.done() for f in self.futures)
        return done, sum(u.stops() for u in self.units), started


@dataclass(frozen=True)
class Handed:
    """Pages handed to the process beside the build (phases.beside), by slug in writing order, the scenes before
    them, and the future of what it made of them."""

    slugs: tuple[str, ...]
    before: int
    future: Future


@dataclass
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
    data_bytes: dict[str, tuple[int, int]] = field(
        default_factory=dict
    )  # "page#scene" -> raw, gzip bytes of its inline tables

    @property
    def notes(self) -> list[str]:
        """What an author may want to change, short of an error (a dep that changes nothing; among the scene lines)."""
        return [line for line in self.scene_lines if line.startswith("note: ")]


class BuildRun:
    """What every phase is handed besides the book: the config, the registry of models and figures it
    may use, the error log, the cache (`remember`), the progress callback and the report being filled."""

    def __init__(self, config: BuildConfig, progress, registry: Registry):
        self.config, self.progress, self.registry = config, progress, registry
        self.models, self.figures = registry.models, registry.figures
        self.log, self.report = ErrorLog(), BuildReport()
        self.cache = TableCache(config.cache) if config.cache else None
        self.remember = self.cache.remember if self.cache else compute_now
        self.tree = None  # the staging folder the pages are written into (site.writer.StagedTree)
        self.math_characters: set[str] = set()  # what the pages' formulas show: the math font's subset
        self.searchable: dict[str, list] = {}  # each written page's sections: the search index
        self.compiling: dict[str, list[Background]] = {}  # models whose kernels compile beside the build, by name
        self.kernels_loaded: set[str] = set()  # models whose compiled code this process has loaded
        self.beside: Beside | None = None  # the process that tabulates scenes ahead, beside the build
        self.ahead: dict[str, Ahead] = {}  # scenes tabulating in it, by name
        self.drawn_ahead: Future | None = None  # the report's diagrams drawn in it (report.bench_figures)
        self.pages_beside: Handed | None = None  # pages being built in it, until taken
        self.built_beside: set[str] = set()  # the pages it built, once taken (by slug)
        self._ahead_seen: dict[str, tuple[float, float]] = {}  # scene -> when first seen started, when last said
        self._phase = ""  # the phase running now

    def phase(self, name: str, function, book):
        """Run one phase over the book, adding its seconds to the phase's total."""
        self.say_ahead_progress()
        start, self._phase = time.perf_counter(), name
        try:
            return function(book, self)
        finally:
            self.report.phases[name] = self.report.phases.get(name, 0.0) + time.perf_counter() - start

    @property
    def may_fork(self) -> bool:
        """Whether work may go to a process forked beside the build: not with --jobs or a scheduler, which spread
        the tabulating already (see `Beside.start` for where a fork is unsafe)."""
        return self.config.jobs == 1 and not self.config.scheduler

    @property
    def compiled_cache(self) -> Path:
        """The folder of compiled code (kept even when the build keeps no tables)."""
        return self.config.root / ".cache" / "compiled"

    def await_kernels(self, model) -> None:
        """If `model`'s kernels are compiling beside the build, wait for them and load them into this process
        (or compile them here if that failed). The seconds spent are booked to the compile phase."""
        parts = self.compiling.get(model.name)
        if parts is None:
            return
        start = time.perf_counter()
        for part in parts:
            while not part.finished(PROGRESS_EVERY):  # a log that says nothing for many seconds looks stuck
                self.say(
                    f"  {model.name}'s kernels still compiling beside the build, {time.perf_counter() - start:.0f} s waited"
                )
        outcomes = [_outcome(part) for part in parts]
        del self.compiling[model.name]  # only now: until every part has answered, a stopped build ends them
        failed = [o for o in outcomes if isinstance(o, BackgroundFailed)]
        if failed:  # compiled again here, where an error names the scene that needs it
            beside = f"compiling beside the build failed ({failed[0]})"
        else:
            any_fresh = any(compiled for _, compiled in outcomes)
            beside = f"{'compiled' if any_fresh else 'loaded'} in {max(s for s, _ in outcomes):.2f} s beside the build"
        seconds, fresh = model.prepare_kernels(
            self.compiled_cache
        )  # a model compiling beside the build has compiled code
        waited = time.perf_counter() - start
        self.report.phases["compile"] = self.report.phases.get("compile", 0.0) + waited
        self.report.phases[self._phase] = self.report.phases.get(self._phase, 0.0) - waited  # the phase adds them too
        self.say(
            f"compile   {model.name}: {beside}, waited for {waited:.2f} s; "
            f"then {'compiled' if fresh else 'loaded'} in {seconds:.2f} s"
        )

    def late_models(self) -> set[str]:
        """The models whose work runs beside the build: the pages with their scenes are built last."""
        return set(self.compiling) | {ahead.model for ahead in self.ahead.values()}

    def say_ahead_progress(self) -> None:
        """For each scene tabulating beside the build, once it has run PROGRESS_EVERY seconds since it started
        or since its last line: stops done, total and rate (a finished scene's own line comes with its page)."""
        now = time.perf_counter()
        for name, ahead in self.ahead.items():
            done, total, started = ahead.stops_done()
            if not started or done >= total:
                continue
            first, last = self._ahead_seen.setdefault(name, (now, now))
            if now - last >= PROGRESS_EVERY and now > first:
                self._ahead_seen[name] = (first, now)
                self.say(
                    f"  {name:<40} {done:>12,} of {total:,} stops, {done / (now - first):,.0f} stops/s, beside the build"
                )

    def figures_drawn_ahead(self) -> dict[str, bytes]:
        """The report's diagrams drawn beside the build, by key (once; none if they were not, or failed there:
        then each is drawn here, where an error says where it happened)."""
        drawn, self.drawn_ahead = self.drawn_ahead, None
        try:
            return drawn.result() if drawn is not None else {}
        except Exception:
            return {}

    def stop_background(self) -> None:
        """End work still running beside the build (all done, or a build that stopped early)."""
        for parts in self.compiling.values():
            for part in parts:
                part.stop()
        self.compiling.clear()
        if self.beside is not None:
            self.beside.stop()
            self.beside = None
        self.ahead.clear()
        self.drawn_ahead = self.pages_beside = None

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
            code = raising_line(
                error, [type(record.scene.model), type(record.view)] if record.scene else [], self.config.book
            )
            raise SceneCrashed(record.spec.loc, record.spec.id, doing, error, code) from error


def _outcome(part: Background):
    """A part's answer, or the BackgroundFailed that says why there is none."""
    try:
        return part.result()
    except BackgroundFailed as failure:
        return failure
