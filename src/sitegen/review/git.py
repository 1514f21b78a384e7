"""The old side of a review made from a git revision: checked out in a temporary worktree and built
with this checkout's Python environment but the revision's own sources."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from ..config import read_book


class ReviewError(RuntimeError):
    """The old build could not be made (unknown revision, no git, or the build failed)."""


def _git(cwd: Path, *args: str) -> str:
    try:
        done = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, check=False)
    except FileNotFoundError:
        raise ReviewError("git is not installed") from None
    if done.returncode:
        raise ReviewError(f"git {' '.join(args)}: {done.stderr.strip() or 'failed'}")
    return done.stdout.strip()


@contextmanager
def revision_build(root: Path, rev: str, progress=print) -> Iterator[tuple[Path, str]]:
    """Build revision `rev` of the project at `root`; yield its build folder and a label.

    The worktree (and its build) is removed when the block ends.
    """
    root = root.resolve()
    sha = _git(root, "rev-parse", "--verify", "--quiet", f"{rev}^{{commit}}") if rev else ""
    if not sha:
        raise ReviewError(f"'{rev}' is not a commit in {root}")
    top = Path(_git(root, "rev-parse", "--show-toplevel"))
    with tempfile.TemporaryDirectory(prefix="sitegen-review-") as tmp:
        worktree = Path(tmp) / "base"
        _git(root, "worktree", "add", "--detach", "--quiet", str(worktree), sha)
        try:
            project = worktree / root.relative_to(top)
            label = f"{rev} ({sha[:7]})"
            progress(f"building {label} in a temporary worktree")
            _build(root, project)
            yield read_book(project).output, label
        finally:
            subprocess.run(
                ["git", "worktree", "remove", "--force", str(worktree)], cwd=root, capture_output=True, check=False
            )
            subprocess.run(["git", "worktree", "prune"], cwd=root, capture_output=True, check=False)


def _build(root: Path, project: Path) -> None:
    """`sitegen build` of the checked-out project, importing sitegen from its own src/."""
    if (root / "node_modules").is_dir() and not (project / "node_modules").exists():
        (project / "node_modules").symlink_to(root / "node_modules")
    path = [str(project / "src"), *filter(None, [os.environ.get("PYTHONPATH")])]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(path), "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run(
        [sys.executable, "-m", "sitegen.cli", "build", "--root", str(project)],
        cwd=project,
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode:
        raise ReviewError(f"the build of the old revision failed:\n{done.stderr.strip() or done.stdout.strip()}")


def working_tree_label(root: Path) -> str:
    """'working tree (main at abc1234, uncommitted changes)', or plainly 'working tree' outside git."""
    try:
        head = _git(root, "rev-parse", "--short", "HEAD")
        branch = _git(root, "rev-parse", "--abbrev-ref", "HEAD")
        dirty = _git(root, "status", "--porcelain", "--untracked-files=no")
    except ReviewError:
        return "working tree"
    where = f"{branch} at {head}" if branch != "HEAD" else f"HEAD {head}"
    return f"working tree ({where}{', uncommitted changes' if dirty else ''})"
