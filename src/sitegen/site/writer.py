"""Writing build/ all at once: into a temporary sibling, then swapped in by renames."""
from __future__ import annotations

import shutil
import tempfile
from pathlib import Path


def write_tree(files: dict[str, bytes], dest: Path) -> None:
    """Replace `dest` with exactly `files`; on any failure the previous `dest` stays as it was."""
    dest.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{dest.name}.new-", dir=dest.parent))
    staging.chmod(0o755)  # mkdtemp makes it private; the site is meant to be read
    try:
        for name in sorted(files):
            path = staging / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(files[name])
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    retired = dest.parent / f".{dest.name}.old"
    shutil.rmtree(retired, ignore_errors=True)
    if dest.exists():
        dest.rename(retired)
    staging.rename(dest)
    shutil.rmtree(retired, ignore_errors=True)
