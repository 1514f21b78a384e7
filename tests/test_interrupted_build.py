"""Nothing is lost when a build dies: killed mid-way (SIGKILL) or failed, it leaves the previous
build/ byte-for-byte as it was, or — once the swap is done — the complete new tree; never a mix.
The next build cleans up what the dead one left and succeeds, with a consistent cache.

Kills come two ways: at exact points of the write (a helper, tests/interrupt.py, arms the
writer or the cache to kill its own process), and from outside, early and at increasing delays
after the build's staging folder appears. Each runs `sitegen build` in a subprocess on a copy of
a small book (many pages, so writing takes a while; every page and one scene change between the
two versions, so the new build computes and caches a table).
"""

from __future__ import annotations

import contextlib
import io
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from helpers import tree, write_book

from sitegen import cli
from sitegen.site import writer

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CHAPTERS = 24


def _book(title: str, masses: str) -> dict[str, str]:
    """A small book: a home page with math, a page with two cheap scenes, and many short pages.
    The book's title is in every page's header, so every file but the assets changes with it."""
    pages = {
        "index": f'+++\ntitle = "{title}"\n+++\n\nA book with $F = ma$ in it.\n',
        "scenes": '+++\ntitle = "Scenes"\norder = 1\n+++\n\n```scene\nmodel: impulse\n'
        f"slider F_pk: 0..10 step 2 default 4\nslider m: {masses} step 1 default 2\n```\n\n"
        "```scene\nmodel: collision\nslider m1: 0.5..2 step 0.5 default 1\nslider e: 0..1 step 0.5 default 1\n```\n",
    }
    for n in range(CHAPTERS):
        pages[f"chapter-{n:02d}"] = (
            f'+++\ntitle = "Chapter {n}"\norder = {n + 2}\n+++\n\n' + f"Paragraph {n}. " * 400 + "\n"
        )
    return pages


OLD, NEW = _book("Old title", "1..3"), _book("New title", "1..4")


def sitegen(root: Path, point: str = "none", output=subprocess.PIPE) -> subprocess.Popen:
    """`sitegen build --root ROOT` in a subprocess, armed to die at `point` (see interrupt.py)."""
    env = {**os.environ, "PYTHONUNBUFFERED": "1", "OPENBLAS_NUM_THREADS": "1"}
    command = [sys.executable, str(HERE / "interrupt.py"), point, "build", "--root", str(root)]
    return subprocess.Popen(command, env=env, text=True, stdout=output, stderr=output)


def run(root: Path, point: str = "none") -> subprocess.CompletedProcess:
    """The build in a subprocess, to its end (or its death at `point`)."""
    process = sitegen(root, point)
    out, err = process.communicate(timeout=300)
    return subprocess.CompletedProcess(process.args, process.returncode, out, err)


def build_here(root: Path) -> subprocess.CompletedProcess:
    """`sitegen build --root ROOT` in this process (the same command, without a second start-up)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = cli.main(["build", "--root", str(root)])
    return subprocess.CompletedProcess(["sitegen", "build"], code, out.getvalue(), err.getvalue())


def which(found: dict[str, bytes], old: dict[str, bytes], new: dict[str, bytes]) -> str:
    """'old' or 'new' when `found` is exactly one of them, else what is wrong with it."""
    if found == old:
        return "old"
    if found == new:
        return "new"
    mixed = sorted(
        n for n in set(found) | set(new) if found.get(n) not in (old.get(n), new.get(n)) or (n in found) != (n in new)
    )
    return f"a mix: {len(found)} files, differing in {mixed[:5]}"


def leftovers(root: Path) -> list[str]:
    """Temporary folders a build left beside build/."""
    return sorted(p.name for p in root.iterdir() if p.name.startswith(".build."))


@pytest.fixture(scope="module")
def projects(tmp_path_factory) -> dict[str, Path]:
    """Two projects, the old book and the new one, each built once, undisturbed (caches warm)."""
    roots = {}
    for name, pages in (("old", OLD), ("new", NEW)):
        roots[name] = tmp_path_factory.mktemp(f"reference-{name}")
        write_book(roots[name], pages)
        done = build_here(roots[name])
        assert done.returncode == 0, done.stderr
    return roots


@pytest.fixture(scope="module")
def versions(projects) -> dict[str, dict[str, bytes]]:
    """The trees the old and the new book build into."""
    trees = {name: tree(root / "build") for name, root in projects.items()}
    assert trees["old"] != trees["new"] and len(trees["new"]) >= CHAPTERS + 4
    differing = [n for n in trees["new"] if trees["old"].get(n) != trees["new"][n]]
    assert len(differing) >= CHAPTERS + 2  # every page, so that a mix would show
    return trees


@pytest.fixture
def book(tmp_path, projects, versions) -> Path:
    """A project holding the old book's build (and its warm cache), with the new book's sources."""
    root = tmp_path / "project"
    shutil.copytree(projects["old"], root, symlinks=True)
    write_book(root, NEW)
    assert tree(root / "build") == versions["old"]
    return root


def restore_old_build(root: Path, projects) -> None:
    """Put the old book's build back in place (as if the new one had never been built)."""
    shutil.rmtree(root / "build")
    shutil.copytree(projects["old"] / "build", root / "build")


def assert_next_build_recovers(root: Path, versions) -> None:
    """A build after the kill succeeds, cleans up, reports no damaged cache entry, and gives
    exactly the tree a clean build of the new book gives."""
    done = build_here(root)
    assert done.returncode == 0, done.stderr
    assert "damaged" not in done.stdout + done.stderr
    assert "Traceback" not in done.stderr
    assert leftovers(root) == []
    assert tree(root / "build") == versions["new"]


# --- killed at exact points of the write ---------------------------------------------------------


@pytest.mark.parametrize(
    "point,expected",
    [(f"file:{CHAPTERS // 2}", "old"), ("swapped", "new"), ("cleanup", "new")],
    ids=["mid-write", "just-swapped", "deleting-the-old-tree"],
)
@pytest.mark.slow  # builds a book in another process and kills it
def test_kill_during_write_leaves_old_or_new_tree(book, versions, point, expected):
    """SIGKILL at a point of the write: build/ is wholly the old tree before the swap and wholly
    the new one after it; the next build cleans up and succeeds."""
    done = run(book, point)
    assert done.returncode == -signal.SIGKILL, (done.returncode, done.stderr[-2000:])
    assert which(tree(book / "build"), versions["old"], versions["new"]) == expected
    assert_next_build_recovers(book, versions)


@pytest.mark.slow  # builds a book in another process and kills it
def test_kill_while_caching_a_table(book, versions):
    """Killed with half a cache entry on disk: build/ is the old tree, and the next build
    neither trusts nor stumbles on the broken write."""
    done = run(book, "cache")
    assert done.returncode == -signal.SIGKILL, (done.returncode, done.stderr[-2000:])
    assert which(tree(book / "build"), versions["old"], versions["new"]) == "old"
    assert_next_build_recovers(book, versions)


@pytest.mark.slow  # builds a book in another process and kills it
def test_kill_between_fallback_renames_is_repaired(book, versions):
    """Without an atomic exchange, a kill between the two renames leaves the old tree aside;
    the next build (or any writer) puts it back before doing anything else."""
    done = run(book, "between")
    assert done.returncode == -signal.SIGKILL
    assert not (book / "build").exists() and tree(book / ".build.old") == versions["old"]
    writer.recover(book / "build")
    assert tree(book / "build") == versions["old"] and not (book / ".build.old").exists()
    assert_next_build_recovers(book, versions)


@pytest.mark.slow  # builds a book in another process and kills it
def test_kills_at_increasing_delays(book, projects, versions):
    """Killed from outside: once early (while it starts and reads), then 0, 1, 5 and 20 ms
    after its staging folder appears (it is writing): each time build/ is the old tree or the new
    one. How many kills landed mid-write (debris left, old tree in place) is printed."""
    seen, mid_write = [], 0
    for delay in (None, 0.0, 0.001, 0.005, 0.02):
        process = sitegen(book, output=subprocess.DEVNULL)
        if delay is None:
            time.sleep(0.3)
        else:
            _wait_for_staging(book, process)
            time.sleep(delay)
        process.kill()
        process.wait(timeout=60)
        seen.append(which(tree(book / "build"), versions["old"], versions["new"]))
        assert seen[-1] in ("old", "new"), f"after a kill at {delay}: {seen[-1]}"
        mid_write += seen[-1] == "old" and any(n.startswith(f".build.new-{process.pid}-") for n in leftovers(book))
        if seen[-1] == "new":  # start again from the old tree
            restore_old_build(book, projects)
    print(f"\nkills: {seen}; {mid_write} landed while the new tree was being written")
    assert seen[0] == "old", seen
    assert_next_build_recovers(book, versions)


def _wait_for_staging(root: Path, process: subprocess.Popen, timeout: float = 120.0) -> None:
    """Return as soon as the build's own staging folder (named after its pid) exists, or it has ended."""
    prefix = f".build.new-{process.pid}-"
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and process.poll() is None:
        with os.scandir(root) as entries:
            if any(e.name.startswith(prefix) for e in entries):
                return
        time.sleep(0.0005)  # a poll without a pause would take a core from the build it waits for


# --- the writer on its own --------------------------------------------------------------------------


def test_failed_write_keeps_the_old_tree(tmp_path):
    """A write that fails half-way (a file where a folder must go) leaves the old tree and no debris."""
    dest = tmp_path / "build"
    writer.write_tree({"index.html": b"old", "assets/a.css": b"a"}, dest)
    with pytest.raises(OSError):
        writer.write_tree({"index.html": b"new", "x": b"file", "x/y": b"under a file"}, dest)
    assert tree(dest) == {"assets/a.css": b"a", "index.html": b"old"}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["build"]


def test_write_replaces_the_tree_exactly(tmp_path):
    """Files of the previous build that the new one lacks are gone; nothing else is left."""
    dest = tmp_path / "build"
    writer.write_tree({"index.html": b"1", "old.html": b"x"}, dest)
    writer.write_tree({"index.html": b"2", "assets/s.js": b"js"}, dest)
    assert tree(dest) == {"assets/s.js": b"js", "index.html": b"2"}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["build"]


def test_write_without_atomic_exchange(tmp_path, monkeypatch):
    """Where the system has no atomic exchange, two renames do the swap, and clean up after."""
    monkeypatch.setattr(writer, "_exchange", lambda a, b: False)
    dest = tmp_path / "build"
    writer.write_tree({"index.html": b"1"}, dest)
    writer.write_tree({"index.html": b"2"}, dest)
    assert tree(dest) == {"index.html": b"2"}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["build"]


def test_recover_removes_only_dead_builds_folders(tmp_path):
    """Staging folders of dead builds go; those of a running build (here: our parent) stay."""
    dest = tmp_path / "build"
    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True
    ).stdout.strip()
    for name in (f".build.new-{dead}-abc", f".build.new-{os.getppid()}-def", ".build.old"):
        (tmp_path / name).mkdir()
        (tmp_path / name / "index.html").write_bytes(b"x")
    writer.recover(dest)
    assert sorted(p.name for p in tmp_path.iterdir()) == [f".build.new-{os.getppid()}-def", "build"]
    assert tree(dest) == {"index.html": b"x"}  # .build.old without build/ was put back


def test_ctrl_c_before_a_command_begins_is_a_line_not_a_traceback(monkeypatch, capsys):
    """Ctrl-C while `sitegen` still loads what a command needs (before the build's own handling): one line and
    exit status 130, as during the build."""

    def interrupted(argv=None):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "main", interrupted)
    with pytest.raises(SystemExit) as ended:
        cli.run()
    assert ended.value.code == 130
    assert capsys.readouterr().err == "sitegen: interrupted\n"
