"""The work of a build through an Executor: in this process, local processes, a Dask cluster — the same bytes
from each, the same errors, and no process left behind."""

from __future__ import annotations

import json
import math
import os
import shutil
import signal
import subprocess
import sys
import time
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from helpers import tree

from sitegen.build import BuildConfig, build
from sitegen.compute.executors import InProcess, executor_for, worker_count
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
    """The project's home page and `page` as scenes.md (in tmp_path/content, written once), built into
    tmp_path/name with no cache."""
    content = tmp_path / "content"
    if not content.exists():
        content.mkdir(parents=True)
        (content / "index.md").write_text(HOME_PAGE)
        (content / "scenes.md").write_text(page)
    return BuildConfig(tmp_path, content, tmp_path / name, cache=None, **options)


@pytest.mark.parametrize("jobs", [2, "auto"])
def test_process_pool_gives_the_bytes_of_the_build_in_process(tmp_path, jobs):
    """`--jobs 2` and `--jobs auto` (local processes) build the same tree, byte for byte, as a build in this process."""
    here = _book(tmp_path, "here")
    pooled = _book(tmp_path, "pooled", jobs=jobs)
    build(here, progress=None)
    build(pooled, progress=None)
    assert tree(here.out) == tree(pooled.out)


@pytest.mark.slow
def test_the_command_with_jobs_gives_the_bytes_of_the_build_in_process(tmp_path, bubble_kernels):
    """`sitegen build --jobs 1` and `--jobs 2` in a process of their own give the tree of `build()` here, bubble
    scene (compiled code, loaded by the workers) included."""
    here = _book(tmp_path, "here", page=BUBBLE_PAGE)
    (tmp_path / "book.toml").write_text("")
    build(here, progress=None)
    for jobs in ("1", "2"):
        out = tmp_path / f"jobs-{jobs}"
        command = [sys.executable, "-m", "sitegen.cli", "build", "--root", str(tmp_path), "--out", str(out)]
        done = subprocess.run([*command, "--no-cache", "--jobs", jobs], capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, done.stderr
        assert tree(out) == tree(here.out), jobs


def test_in_process_work_runs_when_its_result_is_asked_for():
    """In this process, a call runs at its first `result()`, once; what it raised is raised to every reader."""
    calls = []
    future = InProcess().submit(calls.append, 1)
    assert calls == [] and not future.done()
    assert future.result() is None and future.result() is None and calls == [1]
    failing = InProcess().submit(math.sqrt, -1.0)
    with pytest.raises(ValueError, match="math domain error"):
        failing.result()
    assert isinstance(failing.exception(), ValueError)


def test_jobs_auto_is_a_worker_per_core():
    """`auto` asks for as many workers as this process may use cores; a number for that many."""
    assert worker_count("auto") == len(os.sched_getaffinity(0))
    assert worker_count(3) == 3


def test_a_pool_leaves_no_process_behind():
    """Once the pool is shut down, its worker processes have ended, even after a failed call."""
    import multiprocessing

    with executor_for(jobs=2) as pool:
        assert pool.submit(math.hypot, 3.0, 4.0).result() == 5.0
        with pytest.raises(ValueError):
            pool.submit(math.sqrt, -1.0).result()
    assert multiprocessing.active_children() == []


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


_COMPILING_BOOK = {
    "index.md": '+++\ntitle = "Home"\n+++\n\nA page the build writes while the kernels compile.\n',
    "bubble.md": '+++\ntitle = "A bubble"\n+++\n\n```scene\nmodel: bubble\nid: driven\nfix R0: 4.5\n'
    "slider p_a: 0.5..1.5 step 0.5 default 1.5\nslider f: 10, 26.5 default 26.5\n"
    "effects: gas, vdw_hard_core, surface_tension, viscosity, drive, keller_miksis\n"
    "readouts: driven_R_max driven_flag\n```\n",
}


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_sigterm_stops_a_build_and_its_workers(tmp_path, bubble_kernels):
    """SIGTERM (a service manager, `kill`) on a build whose workers are tabulating: the build stops as after Ctrl-C,
    with exit status 143, no staging folder left, its worker processes ended and build/ untouched."""
    root = tmp_path / "book"
    (root / "content").mkdir(parents=True)
    for name, text in _COMPILING_BOOK.items():
        (root / "content" / name).write_text(text)
    (root / "book.toml").write_text("")
    (root / "build").mkdir()
    (root / "build" / "index.html").write_text("the last complete build")
    build_process = subprocess.Popen(
        [sys.executable, "-m", "sitegen.cli", "build", "--root", str(root), "--jobs", "2"],
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    for line in build_process.stdout:  # to the work sent out (not in a finalizer, where a signal's exception
        if line.startswith("send "):  # is only printed)
            break
    workers = _children(build_process.pid)
    build_process.terminate()
    out, err = build_process.communicate(timeout=120)
    assert build_process.returncode == 128 + signal.SIGTERM, err
    assert "build stopped" in err and "Traceback" not in err, err
    assert _all_ended(workers), f"processes {workers} outlived the build"
    assert not [p.name for p in root.iterdir() if p.name.startswith(".build")]
    assert (root / "build" / "index.html").read_text() == "the last complete build"


PENDULUM_PAGE = """+++
title = "The pendulum"
+++

A scene of the book's own model.

```scene
model: pendulum
slider theta0: 5..175 step 10 default 65
slider L: 0.5..2 step 0.5 default 1
fix g: 9.81
readouts: T T0 ratio
```
"""


def _book_with_its_own_model(root: Path) -> BuildConfig:
    """The tiny book with a page of the starter book's model, in models/ (no cache: everything computed)."""
    from conftest import copy_book

    from sitegen.newbook import STARTER

    copy_book(root)
    shutil.copytree(STARTER / "models", root / "models", ignore=shutil.ignore_patterns("__pycache__"))
    (root / "content" / "pendulum.md").write_text(PENDULUM_PAGE)
    return BuildConfig.at(root, cache=None)


@contextmanager
def _cluster(folder: Path):
    """A real Dask cluster on 127.0.0.1: `dask scheduler` and two `dask worker` processes, started in a folder of
    their own (no book there), one thread each; its scheduler's address."""
    dask = str(Path(sys.executable).with_name("dask"))
    folder.mkdir()
    address_file = folder / "scheduler.json"
    common = ["--no-dashboard"]
    started = [
        subprocess.Popen(
            [dask, "scheduler", "--host", "127.0.0.1", "--port", "0", "--scheduler-file", str(address_file), *common],
            cwd=folder,
            stderr=subprocess.DEVNULL,
        )
    ]
    try:
        deadline = time.monotonic() + 120
        while not address_file.exists() and time.monotonic() < deadline:
            time.sleep(0.2)
        address = json.loads(address_file.read_text())["address"]
        for n in range(2):
            (folder / f"worker-{n}").mkdir()
            started.append(
                subprocess.Popen(
                    [dask, "worker", address, "--nthreads", "1", "--host", "127.0.0.1", *common],
                    cwd=folder / f"worker-{n}",
                    stderr=subprocess.DEVNULL,
                )
            )
        from distributed import Client

        with Client(address) as client:
            client.wait_for_workers(2, timeout=120)
        yield address
    finally:
        for process in reversed(started):
            process.terminate()
        for process in started:
            process.wait(timeout=60)


@pytest.mark.slow
def test_a_cluster_without_the_book_builds_its_own_models_to_the_local_bytes(tmp_path, bubble_kernels):
    """A real cluster (a scheduler and two workers, processes of their own) whose workers do not have the book
    builds the tiny book with a model of its own (models/) to the bytes of a build in this process."""
    pytest.importorskip("distributed", reason="the Dask extra is part of the test install")
    config = _book_with_its_own_model(tmp_path / "book")
    build(config, progress=None)
    with _cluster(tmp_path / "cluster") as address:
        report = build(replace(config, out=tmp_path / "dask", scheduler=address), progress=None)
    assert report.computed == report.scenes
    assert any("pendulum#" in line for line in report.scene_lines)
    assert tree(tmp_path / "dask") == tree(config.out)
