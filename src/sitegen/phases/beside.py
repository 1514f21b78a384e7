"""Pages built beside the build: when the process forked beside it has nothing else to do (no compiled scenes,
no report diagrams ahead), a block of the pages goes to it, and this process builds the others meanwhile.

Each page's work (tabulate, check, render, assemble, write) needs nothing of the pages before it, and drawing
figures, the heaviest of it, keeps one core busy: on a book of many chapters the machine's other core would
otherwise be idle. The block is the last pages of those with neither report parts nor late scenes, so that the
build's log and its records come out in the order of a build without it: this process takes what the other made
(the pages' files are already in the staging folder) where that block would have been built. If anything went
wrong there (an author error, a crash, the process gone), the block is built here, where errors name their
place as usual.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from pathlib import Path
from typing import NamedTuple

from ..compute.accuracy import SceneAccuracy
from ..compute.executors import Beside
from ..content.pages import Page
from ..errors import AuthorError
from ..site.writer import StagedTree
from .record import Book, SceneRecord
from .run import BuildRun, Handed

MIN_SCENES = 2  # scenes to compute on each side, below which a fork costs more than it saves
_FORK_STATE: dict = {}  # the book and the run, as the process beside starts with them (set just before the fork)


class Facts(NamedTuple):
    """What a scene's record keeps once its page is written (SceneRecord.finished), as the process beside found it."""

    slug: str
    index: int
    status: str
    accuracy: SceneAccuracy | None
    data_bytes: tuple[int, int]
    stored_values: int

    @classmethod
    def of(cls, record: SceneRecord) -> Facts:
        """The facts of a written page's scene."""
        return cls(
            record.page.slug, record.index, record.status, record.accuracy, record.data_bytes, record.stored_values
        )

    def onto(self, record: SceneRecord) -> SceneRecord:
        """`record` as it is once its page is written."""
        return replace(
            record.finished(),
            status=self.status,
            accuracy=self.accuracy,
            data_bytes=self.data_bytes,
            stored_values=self.stored_values,
        )


@dataclass(frozen=True)
class PagesBuilt:
    """What the process beside made of its pages, beyond their files in the staging folder."""

    facts: tuple[Facts, ...]
    errors: tuple[AuthorError, ...]  # found there, reported here with the build's own
    lines: tuple[str, ...]  # its log, said here when the pages are taken
    scene_lines: tuple[str, ...]
    counts: tuple[int, int, int]  # scenes cached, scenes computed, work units run
    problems: tuple[str, ...]  # damaged cache entries it found
    math_characters: frozenset
    searchable: dict
    sizes: dict
    seconds: float


def hand_over_pages(book: Book, run: BuildRun, order: list[Page], phases) -> None:
    """Hand the last free pages of `order` (about half the work) to a process forked beside the build, which
    builds them with `phases`; only where nothing else runs there and it is worth a fork."""
    if not run.may_fork or run.beside is not None:
        return
    late = book.pages_with(run.late_models())
    keys = {p.slug: set() for p in order}  # the keys of each page's tables
    uncached = {p.slug: set() for p in order}  # those it computes
    for record in book.scenes:
        keys[record.page.slug].add(record.key.digest)
        if not (run.cache and run.cache.has(record.key)):
            uncached[record.page.slug].add(record.key.digest)
    free = [p for p in order if not p.found.reports and p.slug not in late]
    cost = {p.slug: cost_of(len(uncached[p.slug])) for p in free}
    total = sum(cost.values())
    # The block and the free pages before it take about as long, so that neither side waits for the other;
    # the pages after the take point (late, with report parts) are this process's alone anyway.
    block, share = [], 0
    for page in reversed(free):
        if block and 2 * (share + cost[page.slug]) > total + cost[page.slug]:
            break  # the middle of this page's work would lie past the half
        block.insert(0, page)
        share += cost[page.slug]
    earlier = order[: order.index(block[0])] if block else []
    shared = set().union(*(keys[p.slug] for p in earlier)) & set().union(*(keys[p.slug] for p in block))
    if (
        sum(len(uncached[p.slug]) for p in block) < MIN_SCENES
        or total - share < cost_of(MIN_SCENES)
        or (run.cache and shared)
    ):
        # A fork to wait on; or a table on both sides, which a serial build computes once and then takes from the
        # cache (or, its entry damaged, computes and caches again): two processes would do it at once.
        return
    before = sum(1 for r in book.scenes if r.page in earlier)
    slugs = tuple(p.slug for p in block)
    _FORK_STATE.update(book=book, run=run)
    try:
        run.beside = Beside.start()
    finally:
        _FORK_STATE.clear()  # the process beside has its copy
    if run.beside is None:
        return
    future = run.beside.submit(build_pages, slugs, str(run.tree.folder), phases, before, run.report.scenes)
    run.pages_beside = Handed(slugs, before, future)
    names = slugs[0] if len(slugs) == 1 else f"{slugs[0]} to {slugs[-1]}"
    run.say(f"beside    {len(slugs)} page{'s' * (len(slugs) != 1)} ({names}): built in a process beside the build")


def cost_of(scenes: int) -> int:
    """The work of a page with `scenes` scenes to compute, in quarters of a scene's (a page's own is about one)."""
    return 1 + 4 * scenes


def build_pages(slugs: tuple[str, ...], staging: str, phases, before: int, scenes: int) -> PagesBuilt | None:
    """In the process beside the build: build the pages `slugs` into the staging folder, as the build would
    from the block on; None if an exception came up (the build then builds them itself, and says where)."""
    book, run = _FORK_STATE["book"], _FORK_STATE["run"]
    lines = _working_beside(run, staging, scenes, before)
    problems = len(run.cache.problems) if run.cache else 0
    start = time.perf_counter()
    try:
        for slug in slugs:
            page = next(p for p in book.pages if p.slug == slug)
            for name, phase in phases:
                book = run.phase(name, phase, book.at(page))
    except Exception:
        return None
    report = run.report
    facts = tuple(Facts.of(r) for r in book.scenes if r.page.slug in slugs)
    return PagesBuilt(
        facts,
        tuple(run.log.errors),
        tuple(lines),
        tuple(report.scene_lines),
        (report.cached, report.computed - before, report.evaluations),
        tuple(run.cache.problems[problems:]) if run.cache else (),
        frozenset(run.math_characters),
        run.searchable,
        run.tree.sizes,
        time.perf_counter() - start,
    )


def _working_beside(run: BuildRun, staging: str, scenes: int, before: int) -> list[str]:
    """Set up the run as the process beside works with it: its log kept (said by the build when it takes the
    pages), its files into the build's staging folder, and what it makes counted from nothing but the scenes
    before the block (so that its lines are numbered as in a build without the fork)."""
    lines: list[str] = []
    run.progress = lines.append
    run.compiling = {}  # the build's processes compiling kernels, not this one's to wait for
    run.tree, run.math_characters, run.searchable = StagedTree(Path(staging)), set(), {}
    report = run.report
    report.scenes, report.cached, report.computed, report.evaluations, report.scene_lines = scenes, 0, before, 0, []
    return lines


def take_pages(book: Book, run: BuildRun) -> Book:
    """The pages built beside the build, taken into this one's log, records and tree (or, if that failed,
    left to be built here: `run.built_beside` stays empty)."""
    handed, run.pages_beside = run.pages_beside, None
    start = time.perf_counter()
    try:
        built = handed.future.result()
    except Exception:  # the process died, or was ended
        built = None
    waited = time.perf_counter() - start
    report = run.report
    # After an author error a build tabulates and checks on, but no longer draws, assembles or writes: the pages
    # are then built here, where that holds (the process beside did not know of the error).
    if built is None or run.failed or report.cached + report.computed != handed.before:
        run.say("beside    the pages were not built beside the build: building them here")
        return book
    for line in built.lines:
        run.say(line)
    for error in built.errors:
        run.error(error)
    report.scene_lines += built.scene_lines
    report.cached, report.computed, report.evaluations = (
        a + b for a, b in zip((report.cached, report.computed, report.evaluations), built.counts)
    )
    if run.cache:
        run.cache.problems += built.problems
    run.math_characters |= built.math_characters
    run.searchable.update(built.searchable)
    run.tree.sizes.update(built.sizes)
    run.built_beside = set(handed.slugs)
    facts = {(f.slug, f.index): f for f in built.facts}
    records = [facts[r.page.slug, r.index].onto(r) for r in book.scenes if (r.page.slug, r.index) in facts]
    run.say(
        f"beside    {len(handed.slugs)} page{'s' * (len(handed.slugs) != 1)} built beside the build in "
        f"{built.seconds:.2f} s; waited {waited:.2f} s for them"
    )
    return book.with_records(records)
