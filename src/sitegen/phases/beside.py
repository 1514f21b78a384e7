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

from ..compute.executors import Beside
from ..site.writer import StagedTree
from ..content.pages import Page
from .record import Book
from .run import BuildRun, Handed

MIN_SCENES = 2  # scenes to compute on each side, below which a fork costs more than it saves
_FORK_STATE: dict = {}  # the book and the run, as the process beside starts with them (set just before the fork)


@dataclass(frozen=True)
class PagesBuilt:
    """What the process beside made of its pages, beyond their files in the staging folder."""

    facts: tuple  # per scene: (page slug, index, status, accuracy, data bytes, stored values)
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
    if run.config.jobs > 1 or run.config.scheduler or run.beside is not None:
        return
    late = book.pages_with(run.late_models())
    uncached = {p.slug: 0 for p in order}
    for record in book.scenes:
        uncached[record.page.slug] += not (run.cache and run.cache.has(record.key))
    cost = {slug: cost_of(count) for slug, count in uncached.items()}
    block, share = [], 0
    for page in reversed([p for p in order if not p.found.reports and p.slug not in late]):
        if block and 2 * (share + cost[page.slug]) > sum(cost.values()) + cost[page.slug]:
            break  # the middle of this page's work would lie past the half of the book's
        block.insert(0, page)
        share += cost[page.slug]
    here = sum(cost.values()) - share
    if sum(uncached[p.slug] for p in block) < MIN_SCENES or here < cost_of(MIN_SCENES):  # a fork to wait on
        return
    _FORK_STATE.update(book=book, run=run)
    try:
        run.beside = Beside.start()
        if run.beside is None:
            return
        slugs = tuple(p.slug for p in block)
        earlier = {p.slug for p in order[:order.index(block[0])]}
        before = sum(r.page.slug in earlier for r in book.scenes)
        future = run.beside.submit(build_pages, slugs, str(run.tree.folder), phases, before, run.report.scenes)
    finally:
        _FORK_STATE.clear()  # the process beside has its copy (forked in `start`'s first submit)
    run.pages_beside = Handed(slugs, future)
    names = slugs[0] if len(slugs) == 1 else f"{slugs[0]} to {slugs[-1]}"
    run.say(f"beside    {len(slugs)} page{'s' * (len(slugs) != 1)} ({names}): built in a process beside the build")


def cost_of(scenes: int) -> int:
    """The work of a page with `scenes` scenes to compute, in quarters of a scene's (a page's own is about one)."""
    return 1 + 4 * scenes


def build_pages(slugs: tuple[str, ...], staging: str, phases, before: int, scenes: int) -> PagesBuilt | None:
    """In the process beside the build: build the pages `slugs` into the staging folder; None if an author
    error or any exception came up (the build then builds them itself, and reports it there)."""
    book, run = _FORK_STATE["book"], _FORK_STATE["run"]
    lines: list[str] = []
    # What the build's process holds of its other work is not this process's to use.
    run.progress, run.beside, run.ahead, run.drawn_ahead, run.compiling = lines.append, None, {}, None, {}
    run.tree, run.math_characters, run.searchable = StagedTree(Path(staging)), set(), {}
    # Counted from the scenes before the block, so its lines are numbered as in a build without the fork.
    report = run.report
    report.scenes, report.cached, report.computed, report.evaluations, report.scene_lines = scenes, 0, before, 0, []
    problems = len(run.cache.problems) if run.cache else 0
    start = time.perf_counter()
    try:
        for slug in slugs:
            page = next(p for p in book.pages if p.slug == slug)
            for name, phase in phases:
                book = run.phase(name, phase, book.at(page))
    except Exception:
        return None
    if run.failed:
        return None
    facts = tuple((r.page.slug, r.index, r.status, r.accuracy, r.data_bytes, r.stored_values)
                  for r in book.scenes if r.page.slug in slugs)
    return PagesBuilt(facts, tuple(lines), tuple(report.scene_lines), (report.cached, report.computed - before, report.evaluations),
                      tuple(run.cache.problems[problems:]) if run.cache else (), frozenset(run.math_characters),
                      run.searchable, run.tree.sizes, time.perf_counter() - start)


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
    if built is None:
        run.say("beside    the pages were not built beside the build: building them here")
        return book
    for line in built.lines:
        run.say(line)
    report = run.report
    report.scene_lines += built.scene_lines
    report.cached, report.computed, report.evaluations = (a + b for a, b in zip(
        (report.cached, report.computed, report.evaluations), built.counts))
    if run.cache:
        run.cache.problems += built.problems
    run.math_characters |= built.math_characters
    run.searchable.update(built.searchable)
    run.tree.sizes.update(built.sizes)
    run.built_beside = set(handed.slugs)
    facts = {(slug, index): rest for slug, index, *rest in built.facts}
    records = []
    for record in book.scenes:
        if (record.page.slug, record.index) in facts:
            status, accuracy, data_bytes, stored = facts[record.page.slug, record.index]
            records.append(replace(record.finished(), status=status, accuracy=accuracy, data_bytes=data_bytes,
                                   stored_values=stored))
    run.say(f"beside    {len(handed.slugs)} page{'s' * (len(handed.slugs) != 1)} built beside the build in "
            f"{built.seconds:.2f} s; waited {waited:.2f} s for them")
    return book.with_records(records)
