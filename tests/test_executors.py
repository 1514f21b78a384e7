"""Tabulation through an Executor: serial, local processes, a Dask cluster — the same bytes from each; the
scenes of models with compiled code tabulated ahead in a forked process beside the build; and one call run
beside the build in a process of its own (how a first build compiles the bubble's kernels)."""

from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from helpers import tree

from sitegen.build import BuildConfig, build
from sitegen.compute.executors import Background, BackgroundFailed, Beside
from sitegen.compute.tabulate import plan_scene
from sitegen.errors import BuildFailed
from sitegen.models.collision.model import Collision
from sitegen.physics import Model, Output, Param
from sitegen.registry import builtin_registry

ROOT = Path(__file__).resolve().parents[1]
HOME_PAGE = '+++\ntitle = "Mechanics, interactively"\n+++\n\nThe home page of a test book.\n'  # links nowhere
PAGE = """+++
title = "Scenes"
+++

```scene
model: impulse
slider F_pk: 0..50 step 2 default 12
slider tau: 0.05..1 step 0.05 default 0.2
slider m: 0.5..10 step 0.5 default 2
```

```scene
model: collision
slider m1: 0.5..5 step 0.5 default 1
slider m2: 0.5..5 step 0.5 default 2
slider v1i: -5..5 step 1 default 3
slider v2i: -5..5 step 1 default -1
slider e: 0..1 step 0.25 default 1
```
"""


def _book(tmp_path: Path, name: str, page: str = PAGE, **options) -> BuildConfig:
    """The project's home page and `page` as scenes.md, built into tmp_path/name with no cache."""
    pages = {"index.md": HOME_PAGE, "scenes.md": page}
    return _chapters(tmp_path, name, pages, cache=None, **options)


def test_process_pool_gives_the_serial_bytes(tmp_path):
    """`--jobs 2` (two local processes) builds the same tree, byte for byte, as a serial build."""
    serial = _book(tmp_path, "serial")
    pooled = _book(tmp_path, "pooled", jobs=2)
    build(serial, progress=None)
    build(pooled, progress=None)
    assert tree(serial.out) == tree(pooled.out)


@pytest.mark.slow
def test_dask_cluster_gives_the_serial_bytes(tmp_path):
    """The same build on a Dask LocalCluster on 127.0.0.1, through its executor, gives the same bytes."""
    distributed = pytest.importorskip("distributed", reason="the Dask extra is part of the test install")
    serial = _book(tmp_path, "serial")
    build(serial, progress=None)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None, processes=True
    ) as cluster:
        report = build(_book(tmp_path, "dask", scheduler=cluster.scheduler_address), progress=None)
    assert report.computed == report.scenes == 2
    assert tree(serial.out) == tree(tmp_path / "dask")


def _every_output_per_stop(monkeypatch) -> None:
    """Ignore the models' exact forms, so that every output is tabulated per stop (real work to split)."""
    monkeypatch.setattr(Output, "structure_for", lambda self, effects: None)


def test_chunked_scene_gives_the_same_tables(tmp_path, monkeypatch):
    """A model costly per point is split into blocks of rows; joined, they give the same bytes."""
    _every_output_per_stop(monkeypatch)
    serial = _book(tmp_path, "whole")
    build(serial, progress=None)
    monkeypatch.setattr(Collision, "chunk_stops", 1000)
    report = build(_book(tmp_path, "chunked", jobs=2), progress=None)
    assert report.evaluations > 10  # the collision's 60,500 stops went out in many blocks
    assert tree(serial.out) == tree(tmp_path / "chunked")


def test_plan_splits_only_heavy_models(tmp_path, monkeypatch):
    """Blocks of at most `max_stops` points (or one row) cover every row of the grid exactly once."""
    _every_output_per_stop(monkeypatch)
    from sitegen.build import needed_outputs, resolve_book

    config = _book(tmp_path, "plan")
    scene = next(s.scene for s in resolve_book(config).scenes if s.scene.model.name == "collision")
    units = plan_scene(scene, needed_outputs(scene), max_stops=5000)
    full = [u for u in units if u.axes == (0, 1, 2, 3, 4)]
    one_row = 60_500 // scene.axes[0].count  # a block is whole rows of the first slider
    assert len(full) > 1 and all(u.stops() <= max(5000, one_row) for u in full)
    rows = sorted(r for u in full for r in range(*u.rows))
    assert rows == list(range(scene.axes[0].count))  # every row once


class _Explodes(Model):
    """A model that fails at one parameter value, as a solver might."""

    name = "explodes"
    title = "Explodes"
    params = (Param("x", "x", "", 0.0),)
    outputs = (Output("y", "y", "", ("x",)),)

    def _evaluate(self, x, wanted, effects):
        if np.any(x["x"] == 0.5):
            raise ValueError("the solve failed at x = 0.5")
        return {"y": x["x"]}


def test_worker_failure_comes_back_as_an_author_error(tmp_path, register):
    """An error inside a worker process reaches the author as `file:line: scene '...': ...`."""
    register({"explodes": _Explodes}, {"explodes": type(builtin_registry().figures["impulse"])(), "bare": _Bare()})
    page = (
        '+++\ntitle = "Boom"\n+++\n\n```scene\nmodel: explodes\nslider '
        "x: 0..1 step 0.25 default 0\nreadouts: y\nfigure: bare\n```\n"
    )

    with pytest.raises(BuildFailed) as failure:
        build(_book(tmp_path, "out", page=page, jobs=2), progress=None)
    assert [str(e) for e in failure.value.errors] == [
        "content/scenes.md:5: scene 'explodes': model 'explodes' failed: the solve failed at x = 0.5"
    ]


class _ExplodesCompiled(_Explodes):
    """The failing model, as if it ran compiled code (so that its scenes are tabulated ahead, beside the build)."""

    name = "explodes_compiled"

    def prepare_kernels(self, cache, part=None):
        return 0.0, False


BUBBLE_PAGE = (
    PAGE
    + """
```scene
model: bubble
id: collapse
fix R0: 1000
slider p_inf: 1, 2 default 1
slider gas_content: 0.01, 0.1 default 0.1
effects: inertia, vapour, step, gas
fix kappa: 1.4
readouts: t_c R_mach t_mach collapse_R_min collapse_flag
numerics: method auto, rtol 1e-6, tolerance 2e-5
```
"""
)


def _no_other_thread() -> None:
    """The precondition of a fork (and so of the work ahead): this process runs no other thread (one left
    running by an earlier test of this process would be a leak to fix there)."""
    import threading

    deadline = time.monotonic() + 5  # a thread an earlier test has just ended may take a moment to finish
    while threading.active_count() > 1 and time.monotonic() < deadline:
        time.sleep(0.02)
    assert threading.active_count() == 1, f"threads left running: {[t.name for t in threading.enumerate()]}"


def test_scenes_tabulated_ahead_beside_the_build_give_the_same_bytes(tmp_path, monkeypatch, bubble_kernels):
    """The bubble's scene (compiled code) is tabulated in a forked process beside the build, which gives the
    same tree, byte for byte, as a build that tabulates it here; the forked process is gone when the build ends."""
    import multiprocessing

    from conftest import share_compiled

    share_compiled(tmp_path)  # the project's compiled code: the kernels load, and then the scene goes ahead
    _no_other_thread()
    lines: list[str] = []
    build(_book(tmp_path, "ahead", page=BUBBLE_PAGE), progress=lines.append)
    assert "ahead     bubble: 1 scene tabulating in a process beside the build; pages with them are built last" in lines
    assert multiprocessing.active_children() == []
    monkeypatch.setattr(Beside, "start", classmethod(lambda cls: None))  # as where a fork is unsafe
    here: list[str] = []
    build(_book(tmp_path, "here", page=BUBBLE_PAGE), progress=here.append)
    assert not any(line.startswith("ahead     bubble") for line in here)
    assert tree(tmp_path / "ahead") == tree(tmp_path / "here")


def test_a_table_on_two_pages_is_tabulated_ahead_once(tmp_path, bubble_kernels):
    """The same bubble scene on two pages goes ahead once: the first page to be built takes it, and the
    second takes it from the cache, as in a build without the fork."""
    from conftest import share_compiled

    share_compiled(tmp_path)
    _no_other_thread()
    bubble = BUBBLE_PAGE[BUBBLE_PAGE.index("```scene\nmodel: bubble") :]
    pages = {
        "index.md": HOME_PAGE,
        "one.md": PAGE + bubble,
        "two.md": PAGE.replace('title = "Scenes"', 'title = "Two"') + bubble,
    }
    lines: list[str] = []
    build(_chapters(tmp_path, "out", pages), progress=lines.append)
    assert "ahead     bubble: 1 scene tabulating in a process beside the build; pages with them are built last" in lines
    assert [line.rsplit("  ", 1)[-1] for line in _steady(lines) if "#collapse " in line and line.startswith("[")] == [
        "computed: new",
        "cached",
    ]


def test_a_model_failing_beside_the_build_is_reported_from_here(tmp_path, register):
    """A scene that fails in the process beside the build is computed again here, so that the author reads the
    same `file:line: scene '...': ...` as from a build without it."""
    import multiprocessing

    _no_other_thread()
    register(
        {"explodes_compiled": _ExplodesCompiled},
        {"explodes_compiled": type(builtin_registry().figures["impulse"])(), "bare": _Bare()},
    )
    page = (
        '+++\ntitle = "Boom"\n+++\n\n```scene\nmodel: explodes_compiled\nslider x: 0..1 step 0.25 default 0\n'
        "readouts: y\nfigure: bare\n```\n"
    )
    lines: list[str] = []
    with pytest.raises(BuildFailed) as failure:
        build(_book(tmp_path, "out", page=page), progress=lines.append)
    assert any(line.startswith("ahead     explodes_compiled: 1 scene") for line in lines)
    assert [str(e) for e in failure.value.errors] == [
        "content/scenes.md:5: scene 'explodes_compiled': model 'explodes_compiled' failed: the solve failed at x = 0.5"
    ]
    assert multiprocessing.active_children() == []


def test_a_scene_tabulating_beside_the_build_says_how_far_it_got(tmp_path, monkeypatch):
    """Between phases, a scene tabulating beside the build that has started and not finished gets a line of
    its stops done, its total and the rate (here at every chance: as if each phase took longer than the pace)."""
    from concurrent.futures import Future

    from sitegen.phases import run as run_module
    from sitegen.phases.run import Ahead, BuildRun

    class Unit:
        def __init__(self, stops):
            self.count = stops

        def stops(self):
            return self.count

    monkeypatch.setattr(run_module, "PROGRESS_EVERY", 0.0)
    lines: list[str] = []
    run = BuildRun(_book(tmp_path, "out"), lines.append, builtin_registry())
    futures = tuple(Future() for _ in range(3))
    run.ahead["scenes#heavy"] = Ahead("heavy", (Unit(1000), Unit(1000), Unit(500)), futures)
    run.say_ahead_progress()
    assert lines == []  # not started in the process beside
    futures[0].set_running_or_notify_cancel()
    run.say_ahead_progress()  # seen started: its first line comes at the next chance
    futures[0].set_result(None)
    futures[1].set_running_or_notify_cancel()
    time.sleep(0.01)
    run.say_ahead_progress()
    assert len(lines) == 1 and lines[0].startswith("  scenes#heavy") and " 1,000 of 2,500 stops, " in lines[0]
    assert lines[0].endswith(" stops/s, beside the build")
    futures[2].set_running_or_notify_cancel()
    for future in futures[1:]:
        future.set_result(None)
    run.say_ahead_progress()
    assert len(lines) == 1  # finished: its own line comes when its page is built


def test_no_fork_while_another_thread_runs():
    """A fork copies the locks another thread may hold, so none is made then: the scenes are tabulated here."""
    import threading

    _no_other_thread()
    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    try:
        assert Beside.start() is None
    finally:
        stop.set()
        other.join()
    beside = Beside.start()
    assert beside is not None
    try:
        assert beside.submit(math.hypot, 3.0, 4.0).result() == 5.0
    finally:
        beside.stop()


def test_stopping_the_process_beside_ends_its_running_call():
    """stop() ends the call running and drops the calls not yet made, at once, and leaves no thread behind
    (the next build may fork again)."""
    import threading

    _no_other_thread()
    beside = Beside.start()
    running = beside.submit(time.sleep, 3600)
    waiting = [beside.submit(math.hypot, 3.0, 4.0) for _ in range(3)]
    while not running.running():
        time.sleep(0.01)
    start = time.perf_counter()
    beside.stop()
    assert time.perf_counter() - start < 60
    assert running.done() and all(future.done() for future in waiting)
    assert threading.active_count() == 1
    again = Beside.start()
    assert again is not None
    again.stop()


class _Bare:
    label = "empty axes"

    def layers(self, scene):
        return []

    def draw(self, scene, tables):
        from sitegen.render.style import new_figure

        return new_figure(2.0)[0]


def test_a_long_scene_says_how_far_it_got_before_its_own_line(tmp_path, monkeypatch):
    """While a scene computes, lines give its stops done, its total and the rate (here after every
    block, as if each took longer than the pace); the scene's own line follows when it ends."""
    from sitegen.phases import scenes as scene_phases

    _every_output_per_stop(monkeypatch)
    monkeypatch.setattr(Collision, "chunk_stops", 10_000)
    monkeypatch.setattr(scene_phases, "PROGRESS_EVERY", 0.0)
    lines: list[str] = []
    build(_book(tmp_path, "paced"), progress=lines.append)
    collision = next(i for i, line in enumerate(lines) if line.startswith("[") and "#collision" in line)
    updates = [line for line in lines[:collision] if "#collision" in line and line.endswith(" stops/s")]
    assert len(updates) >= 3, lines
    done = [int(line.split()[1].replace(",", "")) for line in updates]
    totals = {line.split(" of ")[1].split()[0] for line in updates}
    assert done == sorted(done) and len(totals) == 1 and done[-1] < int(totals.pop().replace(",", ""))


def test_a_call_beside_returns_its_value_or_says_why_it_failed():
    """Background(f, *args).result() is f(*args) from another process; a raise or a dead process is BackgroundFailed."""
    beside = Background(math.hypot, 3.0, 4.0)
    assert beside.result() == 5.0
    with pytest.raises(BackgroundFailed, match="ValueError: math domain error"):
        Background(math.sqrt, -1.0).result()
    with pytest.raises(BackgroundFailed, match="ended with code 3"):
        Background(os._exit, 3).result()


def test_a_call_beside_can_be_stopped():
    """stop() ends a call that is still running: its process is ended, and it never answers."""
    beside = Background(time.sleep, 3600)
    beside.stop()
    with pytest.raises(BackgroundFailed, match="stopped .*ended with code -15"):  # SIGTERM
        beside.result()


def test_a_call_beside_does_not_run_the_callers_script_again(tmp_path):
    """The process beside is a fresh interpreter given the call: a script without a __main__ guard runs once,
    and a file in the current folder named like a module it needs does not shadow that module."""
    script = tmp_path / "script.py"
    script.write_text(
        "import math\nfrom sitegen.compute.executors import Background\n"
        "print('script ran', flush=True)\nprint(Background(math.factorial, 5).result())\n"
    )
    (work := tmp_path / "work").mkdir()
    (work / "pickle.py").write_text("raise ImportError('the folder the build was started from shadows pickle')\n")
    done = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, check=True, timeout=60, cwd=work
    )
    assert done.stdout.splitlines() == ["script ran", "120"]


def _chapters(tmp_path: Path, name: str, pages: dict[str, str], **options) -> BuildConfig:
    """A book of `pages` (file name -> text) in tmp_path/content (written once), built into tmp_path/name with
    its own cache unless `options` say otherwise."""
    content = tmp_path / "content"
    if not content.exists():
        content.mkdir(parents=True)
        for file, text in pages.items():
            (content / file).write_text(text)
    return BuildConfig(tmp_path, content, tmp_path / name, **{"cache": tmp_path / f"{name}-cache", **options})


def _steady(lines: list[str]) -> list[str]:
    """The scene lines and the scenes' check lines of a build's log, without their seconds."""
    return [re.sub(r"\d+\.\d+ s", "s", line) for line in lines if re.match(r"\[|check {5}\S", line)]


def _steady_report(report) -> dict:
    """What a build reports, without the seconds of its phases and scenes."""
    from dataclasses import asdict

    facts = asdict(report)
    del facts["phases"]
    facts["scene_lines"] = _steady(facts["scene_lines"])
    return facts


WORK = """
```scene
model: work
choice force: spring | drag default spring
choice path: direct | arc default direct
slider k: 1..2 step 1 default 1
slider h: 0..1 step 0.5 default 1
readouts: W dU W_drag verdict
```
"""
# The second chapter's scenes, each on a range of its own (a table shared by two pages is computed once).
_OWN_RANGES = (
    ("slider F_pk: 0..50 step 2", "slider F_pk: 0..48 step 2"),
    ("slider e: 0..1 step 0.25", "slider e: 0..1 step 0.5"),
    ("slider k: 1..2 step 1", "slider k: 1..3 step 1"),
)


def _chapters_of(page: str = PAGE + WORK, same: bool = False) -> dict[str, str]:
    """A home page and two chapters of `page`'s scenes (by default three, one of them checked numerically; no
    bubble scene, no report), the second's on ranges of their own unless `same`."""
    second = page.replace('title = "Scenes"', 'title = "Two"')
    for old, new in () if same else _OWN_RANGES:
        second = second.replace(old, new)
    return {
        "index.md": HOME_PAGE,
        "one.md": page.replace('title = "Scenes"', 'title = "One"'),
        "two.md": second,
    }


def _built_here(config: BuildConfig):
    """A build with nothing forked (as where a fork is unsafe): its report and its log."""
    lines: list[str] = []
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(Beside, "start", classmethod(lambda cls: None))
        report = build(config, progress=lines.append)
    assert not any(line.startswith("beside") for line in lines)
    return report, lines


@pytest.fixture(scope="module")
def chapters_here(tmp_path_factory) -> tuple[dict[str, bytes], dict, list[str]]:
    """The two chapters built with nothing forked: the tree, the report and the log."""
    config = _chapters(tmp_path_factory.mktemp("chapters"), "here", _chapters_of())
    report, lines = _built_here(config)
    return tree(config.out), _steady_report(report), lines


def test_pages_built_beside_the_build_give_the_same_bytes_and_log(tmp_path, chapters_here):
    """With nothing else to do beside the build, the process forked there builds the last chapter while the build
    builds the others: the tree is byte for byte that of a build without it, so is the report, its scene lines
    are the same lines in the same place, and the process is gone when the build ends."""
    import multiprocessing

    _no_other_thread()
    lines: list[str] = []
    report = build(_chapters(tmp_path, "beside", _chapters_of()), progress=lines.append)
    assert "beside    1 page (two): built in a process beside the build" in lines
    assert any(line.startswith("beside    1 page built beside the build in ") for line in lines)
    assert multiprocessing.active_children() == []
    files, facts, here = chapters_here
    assert _steady(lines) == _steady(here) and len(_steady(here)) == 8  # a line per scene, and the work's checks
    assert all(line.endswith("computed: new") for line in _steady(lines) if line.startswith("["))  # with a cache
    assert _steady_report(report) == facts
    assert tree(tmp_path / "beside") == files


def test_a_table_two_pages_compute_is_not_computed_on_both_sides(tmp_path):
    """A scene on a page of each side would be computed and cached twice at once (a build without the fork
    computes it once, then takes it from the cache): then nothing is forked."""
    _no_other_thread()
    lines: list[str] = []
    build(_chapters(tmp_path, "out", _chapters_of(same=True)), progress=lines.append)
    assert not any(line.startswith("beside") for line in lines)
    statuses = [line.rsplit("  ", 1)[-1] for line in _steady(lines) if line.startswith("[")]
    assert statuses == ["computed: new"] * 3 + ["cached"] * 3


@pytest.mark.slow
def test_a_table_on_both_sides_is_not_split_even_when_cached(tmp_path):
    """Nor when that table is cached: its entry may be damaged, and a build without the fork then computes it
    once (saying so) and takes it from the cache on the later page; two processes would each compute it, and
    which of them said what would depend on timing."""
    from sitegen.build import resolve_book

    _no_other_thread()
    collision = PAGE[PAGE.index("```scene\nmodel: collision") :]
    on_both = collision.replace("model: collision", "model: collision\nid: shared").replace(
        "slider e: 0..1 step 0.25", "slider e: 0..1 step 0.125"
    )  # a table of its own, on both chapters
    pages = {name: text if name == "index.md" else f"{text}\n{on_both}" for name, text in _chapters_of().items()}
    config = _chapters(tmp_path, "out", pages)
    build(config, progress=None)
    digests = {
        slug: {r.key.digest for r in resolve_book(config).scenes if r.page.slug == slug} for slug in ("one", "two")
    }
    shared = (digests["one"] & digests["two"]).pop()
    for entry in (config.cache / "tables").rglob("*.bin"):  # the shared table alone is cached, and damaged
        if entry.stem == shared:
            entry.write_bytes(bytes(b ^ 0xFF for b in entry.read_bytes()))
        else:
            entry.unlink()
    lines: list[str] = []
    report = build(config, progress=lines.append)
    assert not any(line.startswith("beside") for line in lines)
    assert [line.rsplit("  ", 1)[-1] for line in _steady(lines) if "#shared " in line and line.startswith("[")] == [
        "computed: not in the cache",
        "cached",
    ]
    assert sum("is damaged" in line for line in report.scene_lines) == 1


def test_an_author_error_in_a_page_built_beside_is_reported_from_here(tmp_path, register):
    """An author error found beside the build is reported by it: the author reads the same
    `file:line: scene '...': ...` as from a build without the fork."""
    import multiprocessing

    _no_other_thread()
    register({"explodes": _Explodes}, {"explodes": type(builtin_registry().figures["impulse"])(), "bare": _Bare()})
    boom = "```scene\nmodel: explodes\nslider x: 0..1 step 0.25 default 0\nreadouts: y\nfigure: bare\n```\n"
    pages = {**_chapters_of(), "two.md": _chapters_of()["two.md"] + "\n" + boom}
    lines: list[str] = []
    with pytest.raises(BuildFailed) as failure:
        build(_chapters(tmp_path, "out", pages), progress=lines.append)
    assert "beside    1 page (two): built in a process beside the build" in lines
    line = max(n for n, text in enumerate(pages["two.md"].splitlines(), 1) if text == "```scene")  # its fence
    assert [str(e) for e in failure.value.errors] == [
        f"content/two.md:{line}: scene 'explodes': model 'explodes' failed: the solve failed at x = 0.5"
    ]
    assert multiprocessing.active_children() == []


@pytest.mark.slow
def test_after_an_author_error_here_the_pages_beside_are_built_here(tmp_path, register):
    """Once a page of the build's own has an author error, a build no longer draws or writes, which the process
    beside did not know: its pages are built here, and the errors and the scene lines' numbers are those of a
    build without the fork."""
    _no_other_thread()
    register({"explodes": _Explodes}, {"explodes": type(builtin_registry().figures["impulse"])(), "bare": _Bare()})
    boom = "```scene\nmodel: explodes\nslider x: 0..1 step 0.25 default 0\nreadouts: y\nfigure: bare\n```\n"
    pages = {**_chapters_of(), "one.md": _chapters_of()["one.md"] + "\n" + boom}
    failures, logs = [], []
    for name in ("beside", "here"):
        logs.append([])
        with pytest.MonkeyPatch.context() as patch, pytest.raises(BuildFailed) as failure:
            if name == "here":
                patch.setattr(Beside, "start", classmethod(lambda cls: None))
            build(_chapters(tmp_path / name, "out", pages), progress=logs[-1].append)
        failures.append([str(e) for e in failure.value.errors])
    assert "beside    the pages were not built beside the build: building them here" in logs[0]
    assert failures[0] == failures[1] and len(failures[0]) == 1
    # The same lines, numbered alike; only the status may differ: the tables computed beside are in the cache by
    # then, and the lines say so ("cached").
    beside, here = ([line.rsplit("  ", 1)[0] for line in _steady(log)] for log in logs)
    assert beside == here


def _ends_at_once(*args):
    """In place of the pages' work beside the build: the process ends without a word."""
    os._exit(3)


@pytest.mark.slow
def test_a_process_beside_that_dies_leaves_its_pages_to_the_build(tmp_path, monkeypatch, chapters_here):
    """If the process beside ends without answering, the build builds the pages it was given: the same bytes,
    report and scene lines."""
    from sitegen.phases import beside

    _no_other_thread()
    monkeypatch.setattr(beside, "build_pages", _ends_at_once)
    lines: list[str] = []
    report = build(_chapters(tmp_path, "died", _chapters_of()), progress=lines.append)
    assert "beside    the pages were not built beside the build: building them here" in lines
    files, facts, here = chapters_here
    assert tree(tmp_path / "died") == files and _steady_report(report) == facts and _steady(lines) == _steady(here)


_ORPHANED = """import os, sys, time
from sitegen.compute.executors import Beside
beside = Beside.start()
print(beside.submit(os.getpid).result(), flush=True)
beside.submit(time.sleep, 60)
time.sleep(60)
"""


def _ended(pid: int) -> bool:
    """Whether process `pid` has ended (gone, or a zombie no one has reaped yet)."""
    try:
        return Path(f"/proc/{pid}/status").read_text().split("State:")[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


def _all_ended(pids: list[int], seconds: float = 10.0) -> bool:
    """Whether every process of `pids` has ended within `seconds`."""
    deadline = time.monotonic() + seconds
    while not all(_ended(p) for p in pids) and time.monotonic() < deadline:
        time.sleep(0.05)
    return all(_ended(p) for p in pids)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="only Linux tells a child that its parent died")
def test_the_process_beside_ends_when_the_build_is_killed():
    """A build killed without a word (SIGKILL: no cleanup runs) takes its process beside with it, which would
    otherwise wait for calls for ever."""
    parent = subprocess.Popen([sys.executable, "-c", _ORPHANED], stdout=subprocess.PIPE, text=True)
    beside = int(parent.stdout.readline())
    assert not _ended(beside)
    parent.kill()
    parent.wait()
    assert _all_ended([beside]), f"process {beside} outlived the build"


def test_a_call_handed_to_a_process_beside_that_died_fails_in_its_future():
    """Once the process beside has died, a call handed to it fails in its future, which every caller reads
    (and then does the work itself), rather than at the handing over, which would end the build."""
    from concurrent.futures.process import BrokenProcessPool

    _no_other_thread()
    beside = Beside.start()
    try:
        os.kill(beside.submit(os.getpid).result(), signal.SIGKILL)
        with pytest.raises(BrokenProcessPool):
            beside.submit(time.sleep, 0).result(timeout=60)
        late = beside.submit(int)  # handed over once the pool knows its process is gone
        with pytest.raises(BrokenProcessPool):
            late.result(timeout=60)
    finally:
        beside.stop()


def test_compiling_that_cannot_start_all_its_processes_starts_none(monkeypatch):
    """When the second of a model's compiling processes cannot start (too many processes), the first is
    ended and the model compiles in the build's own process, as one that cannot be handed over does."""
    from types import SimpleNamespace

    from sitegen.phases import scenes

    started = []

    class Starting:
        def __init__(self, *call):
            if started:
                raise OSError(11, "Resource temporarily unavailable")
            self.stopped = False
            started.append(self)

        def stop(self):
            self.stopped = True

    monkeypatch.setattr(scenes, "Background", Starting)
    run = SimpleNamespace(compiled_cache=Path("compiled"), compiling={})
    model = SimpleNamespace(name="bubble", kernel_parts=("march", "read"), prepare_kernels=print)
    assert scenes._compiling_beside(model, run) is False
    assert run.compiling == {} and [s.stopped for s in started] == [True]


def _children(pid: int) -> list[int]:
    """The processes whose parent is `pid`."""
    found = []
    for entry in Path("/proc").iterdir():
        try:
            if entry.name.isdigit() and int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1]) == pid:
                found.append(int(entry.name))
        except (FileNotFoundError, ProcessLookupError):
            continue
    return found


_CALLING = """import signal, sys, time
signal.signal(signal.SIGINT, signal.default_int_handler)  # ignored if the tests were started without job control
from sitegen.compute.executors import Background
call = Background(time.sleep, 60)
try:  # from the line on: a Ctrl-C that follows it at once may land before the print returns
    print("started", flush=True)
    time.sleep(60)
except KeyboardInterrupt:
    print("interrupted", flush=True)
    time.sleep(60)
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="only Linux tells a child that its parent died")
def test_a_call_beside_ends_when_its_caller_is_killed():
    """A process that compiles beside a build killed without a word (SIGKILL) ends with it, rather than
    compiling on for half a minute (and holding the caller's output open meanwhile)."""
    caller = subprocess.Popen([sys.executable, "-c", _CALLING], stdout=subprocess.PIPE, text=True)
    assert caller.stdout.readline() == "started\n"
    beside = _children(caller.pid)
    assert beside and not any(_ended(p) for p in beside)
    caller.kill()
    caller.wait()
    assert _all_ended(beside), f"processes {beside} outlived their caller"


def test_ctrl_c_at_the_terminal_reaches_the_caller_not_the_call_beside():
    """A Ctrl-C (SIGINT to the terminal's process group) interrupts the caller, which ends its calls beside;
    the call's own interpreter never sees it (at start-up it would print a traceback)."""
    caller = subprocess.Popen(
        [sys.executable, "-c", _CALLING], stdout=subprocess.PIPE, text=True, start_new_session=True
    )
    try:
        assert caller.stdout.readline() == "started\n"
        beside = _children(caller.pid)
        os.killpg(caller.pid, signal.SIGINT)
        assert caller.stdout.readline() == "interrupted\n"
        time.sleep(0.3)
        assert beside and not any(_ended(p) for p in beside), "the call beside was interrupted too"
    finally:
        caller.kill()
        caller.wait()
    assert _all_ended(beside)


_COMPILING_BOOK = {
    "index.md": '+++\ntitle = "Home"\n+++\n\nA page the build writes while the kernels compile.\n',
    "bubble.md": '+++\ntitle = "A bubble"\n+++\n\n```scene\nmodel: bubble\nid: driven\nfix R0: 4.5\n'
    "slider p_a: 0.5..1.5 step 0.5 default 1.5\nslider f: 10, 26.5 default 26.5\n"
    "effects: gas, vdw_hard_core, surface_tension, viscosity, drive, keller_miksis\n"
    "readouts: driven_R_max driven_flag\n```\n",
}


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.slow
def test_sigterm_stops_a_build_as_ctrl_c_does(tmp_path):
    """SIGTERM (a service manager, `kill`) on a build while its kernels compile beside it: the build stops as after
    Ctrl-C, with exit status 143, no staging folder left, the compiling processes ended and build/ untouched."""
    root = tmp_path / "book"
    (root / "content").mkdir(parents=True)
    for name, text in _COMPILING_BOOK.items():
        (root / "content" / name).write_text(text)
    (root / "book.toml").write_text("")
    (root / "build").mkdir()
    (root / "build" / "index.html").write_text("the last complete build")
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    env.pop("SITEGEN_COMPILED_CACHE", None)  # the book's own .cache/compiled/, empty: its kernels compile
    build_process = subprocess.Popen(
        [sys.executable, "-m", "sitegen.cli", "build", "--root", str(root)],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    seen = []
    for line in build_process.stdout:  # to the build waiting for its kernels (not in a finalizer, where a signal's
        seen.append(line)  # exception is only printed)
        if "kernels still compiling beside the build" in line:
            break
    assert any("compiling in 2 processes beside the build" in line for line in seen), seen
    compiling = _children(build_process.pid)
    assert len(compiling) >= 2, compiling
    build_process.terminate()
    out, err = build_process.communicate(timeout=60)
    assert build_process.returncode == 128 + signal.SIGTERM, err
    assert "build stopped" in err and "Traceback" not in err, err
    assert _all_ended(compiling), f"processes {compiling} outlived the build"
    assert not [p.name for p in root.iterdir() if p.name.startswith(".build")]
    assert (root / "build" / "index.html").read_text() == "the last complete build"
