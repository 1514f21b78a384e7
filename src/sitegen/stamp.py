"""A build's stamp: a digest of everything a build reads and of every file it wrote, kept in the book's
.cache/stamps/. When neither has changed since the last complete build, that build's output is what a
new build would write, byte for byte, so `sitegen build` says so and stops before loading numpy,
matplotlib or any model (a rebuild with nothing changed costs a fraction of a second, whatever the
size of the book).

What a build reads: the book's config, pages (with every file next to them), bibliography, citation
style, models and theme; sitegen's own files; the source of
every plugin declared by an entry point; the Python version and every installed package's version
(numpy's, scipy's, matplotlib's, numba's and the plugins'); the compile target. Anything else a
build could depend on is not an input: the clock, the load and the machine's speed never change
its output.
"""

from __future__ import annotations

import hashlib
import importlib.metadata
import importlib.util
import json
import os
import platform
import sys
from pathlib import Path

from .config import CONFIG_FILE, PLUGIN_GROUP, BookConfig

PACKAGE = Path(__file__).resolve().parent
STAMPS = "stamps"  # the folder under the book's .cache/


def inputs_digest(book: BookConfig) -> str | None:
    """One digest of everything a build of `book` reads (None when a plugin's source cannot be found)."""
    plugins = _plugin_folders()
    if plugins is None:
        return None
    sha = hashlib.sha256()
    sha.update(f"python {sys.version} {sys.platform} {platform.machine()}\n".encode())
    sha.update(f"target {os.environ.get('SITEGEN_COMPILE_TARGET', 'generic')}\n".encode())
    versions = sorted({(d.metadata["Name"] or "", d.version) for d in importlib.metadata.distributions()})
    sha.update(json.dumps(versions).encode())
    for label, folder in [
        ("sitegen", PACKAGE),
        *plugins,
        ("content", book.content),
        ("models", book.models),
        ("theme", book.theme),
    ]:
        _add_files(sha, label, folder)
    _add_files(sha, "config", book.root / CONFIG_FILE)
    for label, path in (("bibliography", book.bibliography), ("csl", book.csl)):
        if path is not None:  # wherever book.toml puts them, inside the content folder or not
            _add_files(sha, label, path)
    return sha.hexdigest()


def outputs_digest(out: Path) -> str:
    """One digest of every file under `out`, with its path (a missing or edited file changes it)."""
    sha = hashlib.sha256()
    _add_files(sha, "out", out)
    return sha.hexdigest()


def up_to_date(book: BookConfig, out: Path, inputs: str | None) -> dict | None:
    """The last build's counts (pages, scenes) when its stamp matches `inputs` (the digest of the inputs as they
    are now) and `out` as it is now, else None."""
    try:
        stamp = json.loads(_stamp_path(book, out).read_text())
    except (OSError, ValueError):
        return None
    if inputs is None or stamp.get("inputs") != inputs or stamp.get("outputs") != outputs_digest(out):
        return None
    return stamp.get("counts", {})


def write_stamp(book: BookConfig, out: Path, inputs: str | None, counts: dict) -> None:
    """Record a complete build of `out` made from `inputs` (the digest taken before it started)."""
    if inputs is None:
        return
    path = _stamp_path(book, out)
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_suffix(".new")
    partial.write_text(json.dumps({"inputs": inputs, "outputs": outputs_digest(out), "counts": counts}))
    partial.replace(path)


def _stamp_path(book: BookConfig, out: Path) -> Path:
    name = hashlib.sha256(str(out.resolve()).encode()).hexdigest()[:24]
    return book.root / ".cache" / STAMPS / f"{name}.json"


def _plugin_folders() -> list[tuple[str, Path]] | None:
    """(name, source folder or file) of each installed plugin's top-level package, found without importing it."""
    found = []
    for entry in sorted(importlib.metadata.entry_points(group=PLUGIN_GROUP), key=lambda e: (e.name, e.value)):
        top = entry.value.split(":")[0].split(".")[0]
        try:
            spec = importlib.util.find_spec(top)
        except (ImportError, ValueError):
            return None
        if spec is None or not (spec.submodule_search_locations or spec.origin):
            return None
        places = list(spec.submodule_search_locations or [spec.origin])
        found += [(f"plugin {entry.name}", Path(place)) for place in places]
    return found


def _add_files(sha, label: str, place: Path) -> None:
    """Feed the path and bytes of `place` (a file, or every file under a folder but compiled bytecode)."""
    files = [place] if place.is_file() else sorted(p for p in place.rglob("*") if p.is_file()) if place.is_dir() else []
    sha.update(f"{label} {place.is_dir()}\n".encode())
    for path in files:
        if "__pycache__" in path.parts:
            continue
        relative = path.relative_to(place).as_posix() if place.is_dir() else path.name
        sha.update(f"{relative}\0{hashlib.sha256(path.read_bytes()).hexdigest()}\n".encode())
