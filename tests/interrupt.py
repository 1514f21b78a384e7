"""Run `sitegen` and SIGKILL it at a chosen point of writing build/ (a helper of
test_interrupted_build.py, run as a script): `python tests/interrupt.py POINT sitegen-args...`.

POINT is one of
  file:N      after N files of the new tree are written (mid-write)
  swapped     just after the new tree is swapped in, before the old one is deleted
  cleanup     while the old tree is being deleted
  between     with no atomic exchange (as on systems without renameat2), between the two renames
  cache       while the first cache entry is being written (half of it on disk, not yet renamed)
  none        not at all
"""

from __future__ import annotations

import os
import shutil
import signal
import sys
from pathlib import Path

from sitegen import cli
from sitegen.site import writer


def die() -> None:
    """End this process the way `kill -9` does: no cleanup, no finally blocks."""
    sys.stdout.flush()
    os.kill(os.getpid(), signal.SIGKILL)


def arm(point: str) -> None:
    """Patch the writer so that the process dies at `point`."""
    kind, _, arg = point.partition(":")
    if kind == "file":
        real_write, written = Path.write_bytes, [0]

        def write_bytes(self, data):
            if ".new-" in str(self):
                if written[0] == int(arg):
                    die()
                written[0] += 1
            return real_write(self, data)

        Path.write_bytes = write_bytes
    elif kind == "swapped":
        real_swap = writer._swap_in

        def swap_in(staging, dest):
            real_swap(staging, dest)
            die()

        writer._swap_in = swap_in
    elif kind == "cleanup":
        real_rmtree = shutil.rmtree

        def rmtree(path, *args, **kwargs):
            if ".new-" in str(path) and Path(path, "index.html").exists():
                (Path(path) / "index.html").unlink()  # part of the old tree is gone, then the end
                die()
            return real_rmtree(path, *args, **kwargs)

        writer.shutil.rmtree = rmtree
    elif kind == "between":
        writer._exchange = lambda a, b: False
        real_rename, renames = Path.rename, [0]

        def rename(self, target):
            renames[0] += 1
            if renames[0] == 2:  # dest moved aside; the new tree not yet in place
                die()
            return real_rename(self, target)

        Path.rename = rename
    elif kind == "cache":
        real_replace = os.replace

        def replace(source, target, *args, **kwargs):
            if f"{os.sep}.cache{os.sep}" in str(target):
                size = os.path.getsize(source)
                os.truncate(source, size // 2)
                die()
            return real_replace(source, target, *args, **kwargs)

        os.replace = replace
    elif kind != "none":
        raise SystemExit(f"unknown point {point!r}")


if __name__ == "__main__":
    arm(sys.argv.pop(1))
    cli.run()  # the command's own end: main, then an exit that leaves the heap unsearched
