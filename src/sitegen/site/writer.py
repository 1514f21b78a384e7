"""Writing build/ all at once: into a temporary sibling, then swapped in whole.

The build writes each page into the staging folder as soon as it is finished (so it never holds
the whole site in memory), and the folder replaces build/ only when every page is written.

Whoever looks at build/ — a reader, a server, the next build — sees the old tree or the new
one, never a mix, even if the build is killed: the new tree is written under a temporary name
and exchanged with the old one by one atomic rename (Linux renameat2 RENAME_EXCHANGE). Where
that call is missing, two renames are used, and a build killed between them leaves the old
tree aside as `.build.old`, which the next build puts back. Temporary folders of builds that
died are removed by the next build; those of builds still running are left alone.
"""

from __future__ import annotations

import ctypes
import errno
import os
import shutil
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

_AT_FDCWD = -100
_RENAME_EXCHANGE = 2
_LEGACY_STALE_SECONDS = 3600  # staging folders named without a pid (older sitegen) count as dead after this


def _load_renameat2():
    try:
        return getattr(ctypes.CDLL(None, use_errno=True), "renameat2", None)
    except (OSError, TypeError):  # no C library to ask (not Linux)
        return None


_renameat2 = _load_renameat2()


class StagedTree:
    """The new tree while it is being written: files go into a staging folder beside the destination."""

    def __init__(self, folder: Path):
        self.folder = folder

    def write(self, name: str, data: bytes) -> None:
        """Write one file of the new tree (a relative path with forward slashes)."""
        path = self.folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)


@contextmanager
def staged_tree(dest: Path) -> Iterator[StagedTree]:
    """A staging folder for the tree that replaces `dest` when the block ends without an exception;
    if anything fails, or the process dies, `dest` stays as it was (or, once the swap is done, is
    wholly the new tree)."""
    dest.parent.mkdir(parents=True, exist_ok=True)
    recover(dest)
    staging = Path(tempfile.mkdtemp(prefix=f"{_staging_prefix(dest)}{os.getpid()}-", dir=dest.parent))
    staging.chmod(0o755)  # mkdtemp makes it private; the site is meant to be read
    try:
        yield StagedTree(staging)
        _swap_in(staging, dest)
    finally:
        shutil.rmtree(staging, ignore_errors=True)  # the old tree after a swap; the new one after a failure


def write_tree(files: dict[str, bytes], dest: Path) -> None:
    """Replace `dest` with exactly `files`, atomically (see `staged_tree`)."""
    with staged_tree(dest) as tree:
        for name in sorted(files):
            tree.write(name, files[name])


def recover(dest: Path) -> None:
    """Undo what an interrupted earlier build left beside `dest`: put back a tree it had moved
    aside, and remove the temporary folders of builds no longer running."""
    retired = _retired(dest)
    if retired.is_dir() and not dest.exists():
        retired.rename(dest)  # killed between the two renames of the fallback swap
    shutil.rmtree(retired, ignore_errors=True)
    for leftover in dest.parent.glob(f"{_staging_prefix(dest)}*"):
        if leftover.is_dir() and not _owner_alive(leftover.name[len(_staging_prefix(dest)) :], leftover):
            shutil.rmtree(leftover, ignore_errors=True)


def _swap_in(staging: Path, dest: Path) -> None:
    """Make `staging` the tree at `dest`; afterwards `staging` holds the old tree, if there was one."""
    if not dest.exists() and not dest.is_symlink():
        staging.rename(dest)
    elif not _exchange(staging, dest):
        retired = _retired(dest)
        dest.rename(retired)
        staging.rename(dest)
        retired.rename(staging)


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths in one atomic step; False where the system cannot."""
    if _renameat2 is None:
        return False
    if _renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(code, os.strerror(code), str(b))


def _owner_alive(suffix: str, folder: Path) -> bool:
    """Whether the build that made a staging folder (named PID-random) may still be writing it."""
    pid, dash, _ = suffix.partition("-")
    if not dash or not pid.isdigit():
        try:
            return time.time() - folder.stat().st_mtime < _LEGACY_STALE_SECONDS
        except FileNotFoundError:
            return False
    if int(pid) == os.getpid():
        return False  # this process is not writing it: a folder left by an earlier build in this process
    try:
        os.kill(int(pid), 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # someone else's live process
    return True


def _staging_prefix(dest: Path) -> str:
    return f".{dest.name}.new-"


def _retired(dest: Path) -> Path:
    return dest.parent / f".{dest.name}.old"
