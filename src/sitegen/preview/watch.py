"""`sitegen serve --watch`: build the book, serve it, and rebuild it whenever its pages (or the files next
to them: pictures, the bibliography), book.toml, theme or models change, telling the open pages
(server.Live) after every attempt.

Changes come from the system's file events through watchfiles (no polling loop). The rebuild runs in
this process with what is already loaded: the registry of models is kept unless a model or book.toml
changed, and the cache keeps every scene whose key did not change, so a prose edit evaluates no model
and an edit to a model recomputes only the scenes that use it.
"""

from __future__ import annotations

import gc
import queue
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from http.server import ThreadingHTTPServer
from pathlib import Path

import watchfiles

from ..build import BuildConfig, build
from ..config import CONFIG_FILE, BookConfig, ConfigError, read_book
from ..content.math import MathToolMissing
from ..errors import BuildFailed, SceneCrashed
from ..registry import Registry, load_registry, raising_line
from .server import Live

SETTLE_MS = 50  # a batch of changes ends after this long without another (one save is often several events)
LONGEST_MS = 400  # ... or after this long in all, while changes keep coming
# Files editors and tools write beside the one being saved, which the build never reads: a save rebuilds once,
# on the file itself, not on these (watchfiles' own list already has *.swp, *~, .#lock and *.py[cod]).
EDITOR_TEMPORARIES = (
    r"\.tmp$",  # a temporary written then renamed over the file, e.g. .model.py.b4bce7….tmp
    r"^sed[A-Za-z0-9]{6}$",  # sed -i's temporary copy
    r"^4913$",  # vim's test that the folder is writable
    r"^#.*#$",  # emacs's auto-save
    r"\.(bak|orig|rej|part|crdownload)$",  # backups, patches' leftovers, downloads in progress
    r"\.sw[a-p]x?$",  # vim's swap files (.swp, .swo, .swx, ...)
)


def watched(path: str) -> bool:
    """Whether a change to `path` is one the build may read (not an editor's or a tool's temporary)."""
    return BOOK_FILTER(watchfiles.Change.modified, path)


BOOK_FILTER = watchfiles.DefaultFilter(
    ignore_entity_patterns=(*watchfiles.DefaultFilter.ignore_entity_patterns, *EDITOR_TEMPORARIES)
)


def serve_watching(
    book: BookConfig, out: Path, server: ThreadingHTTPServer, live: Live, say=print, jobs: int | str = 1, scheduler=None
) -> int:
    """Build the book into `out`, serve it with `server` (which shows `live`) and rebuild on every
    change until Ctrl-C, each build's work run where `jobs` and `scheduler` say (as `sitegen build`'s); the
    exit status."""
    stop, serving = threading.Event(), threading.Thread(target=server.serve_forever, name="preview-server", daemon=True)
    try:
        watcher = BookWatcher(book, stop)
        watcher.start()  # before the first build, so that no edit made once it is served goes unseen
        builder = Builder(book, out, live, say, jobs=jobs, scheduler=scheduler)
        builder.rebuild(set())
        serving.start()
        host, port = server.server_address[:2]
        say(
            f"serving {builder.out} at http://{host}:{port}/index.html, rebuilding on changes (Ctrl-C stops)",
            flush=True,
        )
        for changed in watcher.batches():
            builder.rebuild(changed)
    except KeyboardInterrupt:
        pass
    finally:
        stop.set()
        live.close()
        if serving.is_alive():
            server.shutdown()
        server.server_close()
    return 0


@dataclass
class Builder:
    """Rebuilds one book into one folder, keeping the registry of models while neither a model nor
    book.toml changed, and publishes each attempt to the open pages."""

    book: BookConfig
    out: Path
    live: Live
    say: object = print
    registry: Registry | None = None
    jobs: int | str = 1  # where each build's work runs (BuildConfig's)
    scheduler: str | None = None

    def rebuild(self, changed: set[Path]) -> bool:
        """One attempt after `changed` (empty: the first build); whether it succeeded."""
        start = time.perf_counter()
        errors = self._refresh(changed)
        report = None
        if not errors:
            report, errors = attempt(
                BuildConfig(
                    self.book.root,
                    self.book.content,
                    self.out,
                    cache=self.book.root / ".cache",
                    jobs=self.jobs,
                    scheduler=self.scheduler,
                    book=self.book,
                ),
                self.registry,
                self._scene_line,
            )
        self.live.publish(report is not None, errors)
        seconds = time.perf_counter() - start
        what = ", ".join(sorted(self.book.relative(p) for p in changed)) or "the book"
        if report is None:
            self.say(
                f"build of {what} failed after {seconds:.2f} s ({len(errors)} error(s)); the pages show them:",
                flush=True,
            )
            for error in errors:
                self.say(f"  {error}", flush=True)
        else:
            self.say(
                f"built {what} in {seconds:.2f} s: {report.pages} pages, {report.scenes} scenes "
                f"({report.computed} computed)",
                flush=True,
            )
        # What the attempt left in reference cycles (its records, a failed build's traceback) is freed by a
        # full collection; the watcher allocates next to nothing between rebuilds, so none would come by itself.
        gc.collect()
        return report is not None

    def _refresh(self, changed: set[Path]) -> list[str]:
        """Read book.toml and load the models again when they changed; their errors, if any."""
        if self.book.root / CONFIG_FILE in changed:
            try:
                self.book = read_book(self.book.root, required=True)
            except ConfigError as problem:
                return [str(problem)]
            self.registry = None
        if any(path.is_relative_to(self.book.models) for path in changed):
            self.registry = None
        if self.registry is None:
            self.registry = load_registry(self.book)
        return []

    def _scene_line(self, line: str) -> None:
        # the scenes this edit recomputed, and what the author may want to change (notes, pages over budget)
        if line.startswith(("note: ", "warning: ")) or line.startswith("[") and not line.endswith("cached"):
            self.say(f"  {line}", flush=True)


def attempt(config: BuildConfig, registry: Registry, progress) -> tuple[object | None, list[str]]:
    """(the build's report, []) or (None, its errors as the author reads them: file:line: ...)."""
    try:
        return build(config, progress=progress, registry=registry), []
    except BuildFailed as failure:
        return None, [str(error) for error in failure.errors]
    except (MathToolMissing, SceneCrashed, OSError) as problem:
        return None, [str(problem)]
    except Exception as problem:  # a bug in a model or in sitegen: its line, as `sitegen build` names it
        return None, [f"{raising_line(problem, [], config.book)}: {type(problem).__name__}: {problem}"]


class BookWatcher:
    """Batches of the book's changed files: its content, theme and models folders (each watched with
    all it holds, where it exists) and, in the book's own folder, book.toml, the bibliography and
    citation style it names, and those folders coming or going. The book's folder itself is not watched deeply: it
    holds the output, .cache and more."""

    def __init__(self, book: BookConfig, stop: threading.Event):
        self.book, self.stop = book, stop
        self.changes: queue.Queue[set[Path]] = queue.Queue()
        self.regroup = threading.Event()  # a watched folder appeared or went: watch the folders anew
        self.started = False

    def start(self) -> None:
        """Start watching (the changes are queued until `batches` reads them)."""
        top = self._top()
        self._start(
            lambda: self._watch(
                [self.book.root], recursive=False, keep=lambda _, path: Path(path).name in top, stop=self.stop
            )
        )
        self._start(self._watch_folders)

    def _top(self) -> set[str]:
        """The names watched in the book's own folder."""
        top = {CONFIG_FILE} | {f.name for f in self._folders(existing=False) if f.parent == self.book.root}
        return top | {f.name for f in (self.book.bibliography, self.book.csl) if f and f.parent == self.book.root}

    def batches(self) -> Iterator[set[Path]]:
        """Each batch of changes, as they come (until `stop` is set); watching starts here unless `start` came first."""
        if not self.started:
            self.start()
        top = self._top()
        while not self.stop.is_set():
            try:
                batch = self.changes.get(timeout=0.5)
            except queue.Empty:
                continue
            if any(p.name in top and p.parent == self.book.root and p.name != CONFIG_FILE for p in batch):
                self.regroup.set()
            yield batch

    def _folders(self, existing: bool = True) -> list[Path]:
        folders = [self.book.content, self.book.theme, self.book.models]
        return [f for f in folders if f.is_dir() or not existing]

    def _watch_folders(self) -> None:
        while not self.stop.is_set():
            self.regroup.clear()
            folders = self._folders()
            if not folders:
                self.regroup.wait(0.5)
                continue
            self._watch(folders, recursive=True, keep=BOOK_FILTER, stop=_Either(self.stop, self.regroup))

    def _watch(self, paths: list[Path], recursive: bool, keep, stop) -> None:
        for found in watchfiles.watch(
            *paths,
            watch_filter=keep,
            debounce=LONGEST_MS,
            step=SETTLE_MS,
            stop_event=stop,
            recursive=recursive,
            rust_timeout=500,
            yield_on_timeout=False,
            raise_interrupt=False,
        ):
            self.changes.put({Path(path) for _, path in found})

    def _start(self, target) -> None:
        self.started = True
        threading.Thread(target=target, name="preview-watcher", daemon=True).start()


class _Either:
    """Set when either of two events is (what watchfiles asks of its stop_event)."""

    def __init__(self, first: threading.Event, second: threading.Event):
        self.first, self.second = first, second

    def is_set(self) -> bool:
        return self.first.is_set() or self.second.is_set()
