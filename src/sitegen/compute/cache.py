"""A content-addressed cache of tabulated scenes, under .cache/ (one checksummed file per entry).

The key covers everything that can change a scene's tables — the scene's request (sliders, fixed
values, effects, outputs), the source of every file its model loads (found by following the
imports of the model's module: its plugin's own modules and what they use of sitegen) and of the
tabulator, and the numpy/scipy/matplotlib versions — and nothing that cannot (prose, other scenes,
other models, file times). Freshness is never judged by modification time.
"""

from __future__ import annotations

import hashlib
import io
import json
import os
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from .scenes import ResolvedScene
from .sources import library_digest, sha, source_digest
from .structure import Structured
from .table import Table

TABULATOR = "sitegen.compute.tabulate"  # the code that turns a model's numbers into tables (with its imports)


@dataclass(frozen=True)
class CacheKey:
    """The three parts of a scene's key, kept apart so a rebuild can say which one changed."""

    spec: str
    code: str
    libraries: str

    @property
    def digest(self) -> str:
        """The entry's name in the cache."""
        return sha(f"{self.spec}:{self.code}:{self.libraries}")


def scene_key(scene: ResolvedScene, outputs: list[str]) -> CacheKey:
    """The key of a scene's tables."""
    request = {
        "model": scene.model.name,
        "axes": [[a.param, a.kind, [str(s) for s in a.stops], list(a.labels)] for a in scene.axes],
        "fixed": sorted([name, repr(value)] for name, value in scene.fixed),
        "effects": sorted(scene.effects),
        "outputs": sorted(outputs),
    }
    if scene.model.settings is not None:  # the numerical settings change the numbers; the tolerance does not
        request["numerics"] = scene.model.settings.knobs()
    modules = frozenset({type(scene.model).__module__, TABULATOR})
    return CacheKey(sha(json.dumps(request, sort_keys=True)), source_digest(modules), library_digest())


class TableCache:
    """Tables by key on disk, written atomically and checked on every read."""

    def __init__(self, root: Path):
        self.root = root
        self.problems: list[str] = []  # corrupt entries found (and recomputed)

    def load(self, key: CacheKey) -> dict[str, Table] | None:
        """The cached tables, or None when absent or damaged (a damaged entry is noted and removed)."""
        path = self._entry(key)
        try:
            data = path.read_bytes()
        except FileNotFoundError:
            return None
        checksum, _, payload = data.partition(b"\n")
        try:
            if checksum.decode() != hashlib.sha256(payload).hexdigest():
                raise ValueError("checksum mismatch")
            return _decode(payload)
        except (ValueError, KeyError, OSError, UnicodeDecodeError) as problem:
            self.problems.append(f"cache entry {path.name} is damaged ({problem}); recomputed")
            path.unlink(missing_ok=True)
            return None

    def has(self, key: CacheKey) -> bool:
        """Whether an entry exists for the key (not whether it is sound: `load` checks that)."""
        return self._entry(key).is_file()

    def store(self, key: CacheKey, tables: dict[str, Table]) -> None:
        """Write an entry: a temporary file renamed into place, so readers never see half of one."""
        payload = _encode(tables)
        self._write(self._entry(key), hashlib.sha256(payload).hexdigest().encode() + b"\n" + payload)

    def holds(self, kind: str, key: str) -> bool:
        """Whether `cached(kind, key, ...)` has an entry to read (not whether it is sound)."""
        return self._entry_path(kind, key).is_file()

    def cached(self, kind: str, key: str, compute) -> bytes:
        """Bytes derived from inputs summed up by `key` (e.g. a figure's SVG): cached, or computed once."""
        path = self._entry_path(kind, key)
        try:
            checksum, _, payload = path.read_bytes().partition(b"\n")
            if checksum.decode() == hashlib.sha256(payload).hexdigest():
                return payload
            self.problems.append(f"cache entry {kind}/{path.name} is damaged (checksum mismatch); recomputed")
        except (FileNotFoundError, UnicodeDecodeError):
            pass
        payload = compute()
        self._write(path, hashlib.sha256(payload).hexdigest().encode() + b"\n" + payload)
        return payload

    def _entry_path(self, kind: str, key: str) -> Path:
        return self.root / kind / key[:2] / f"{key}.bin"

    def explain(self, scene_name: str, key: CacheKey, cached: bool) -> str:
        """Why a scene was computed (or that it was cached), keeping its key for next time."""
        index = self.root / "index" / f"{sha(scene_name)[:24]}.json"
        try:
            before = json.loads(index.read_text())
        except (FileNotFoundError, ValueError):
            before = None
        if before != asdict(key):  # rewritten only when it changed: a rebuild of cached scenes writes nothing here
            self._write(index, json.dumps(asdict(key), sort_keys=True).encode())
        if cached:
            return "cached"
        if before is None:
            return "computed: new"
        changed = [
            what
            for field, what in (
                ("spec", "spec changed"),
                ("code", "model code changed"),
                ("libraries", "library version changed"),
            )
            if before.get(field) != getattr(key, field)
        ]
        return "computed: " + (", ".join(changed) if changed else "not in the cache")

    def _entry(self, key: CacheKey) -> Path:
        return self.root / "tables" / key.digest[:2] / f"{key.digest}.bin"

    @staticmethod
    def _write(path: Path, data: bytes) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")
        try:
            with os.fdopen(handle, "wb") as out:
                out.write(data)
            os.replace(temporary, path)
        except BaseException:
            Path(temporary).unlink(missing_ok=True)
            raise


def _encode(tables: dict) -> bytes:
    meta, arrays = [], {}
    for i, (name, t) in enumerate(sorted(tables.items())):
        if isinstance(t, Structured):
            meta.append(
                {
                    "name": name,
                    "expr": t.expr,
                    "decimals": t.decimals,
                    "labels": list(t.labels),
                    "width": t.width,
                    "special": t.special,
                    "parts": sorted(t.parts),
                    "bounds": list(t.bounds),
                    "sliders": len(t.sliders),
                }
            )
            arrays.update({f"s{i}_{k}": v for k, v in enumerate(t.sliders)})
            continue
        meta.append(
            {
                "name": name,
                "axes": list(t.axes),
                "shape": list(t.shape),
                "decimals": t.decimals,
                "labels": list(t.labels),
                "width": t.width,
                "special": t.special,
                "ragged": t.lengths is not None,
                "summed": t.summed_axes,
                "raw": t.raw,
                "digits": t.digits,
            }
        )
        arrays[f"q{i}"] = t.quanta
        if t.exponents is not None:
            arrays[f"e{i}"] = t.exponents
        if t.lengths is not None:
            arrays[f"n{i}"] = t.lengths
    buffer = io.BytesIO()
    np.savez(buffer, meta=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8), **arrays)
    return buffer.getvalue()


def _decode(payload: bytes) -> dict:
    with np.load(io.BytesIO(payload), allow_pickle=False) as archive:
        meta = json.loads(archive["meta"].tobytes().decode())
        tables = {
            m["name"]: Table(
                m["name"],
                tuple(m["axes"]),
                tuple(m["shape"]),
                archive[f"q{i}"],
                m["decimals"],
                tuple(m["labels"]),
                m["width"],
                archive[f"n{i}"] if m["ragged"] else None,
                m["special"],
                m.get("summed", False),
                m.get("raw", False),
                archive[f"e{i}"] if m.get("digits") else None,
                m.get("digits", 0),
            )
            for i, m in enumerate(meta)
            if "expr" not in m
        }
        for i, m in enumerate(meta):
            if "expr" in m:
                tables[m["name"]] = Structured(
                    m["name"],
                    m["expr"],
                    m["decimals"],
                    tuple(m["labels"]),
                    m["width"],
                    m["special"],
                    {p: tables[p] for p in m["parts"]},
                    tuple(archive[f"s{i}_{k}"] for k in range(m["sliders"])),
                    tuple(m["bounds"]),
                )
        return tables


def compute_now(kind: str, key: str, compute) -> bytes:
    """What `TableCache.cached` does when there is no cache: compute."""
    return compute()
