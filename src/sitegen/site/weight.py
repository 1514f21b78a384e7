"""What each page weighs as a reader downloads it: its HTML, raw and gzip, and with the assets it loads; a
warning for a page above the book's budget, naming its heaviest scenes and what would shrink them."""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass

from .sizes import gzip_bytes

HEAVIEST = 3  # scenes a warning names
TABLES = 2  # of each, the largest tables it names


@dataclass(frozen=True)
class PageWeight:
    """One page: its HTML raw and gzip, what it loads with it (gzip), and its scenes' inline data (raw bytes)."""

    page: str
    raw: int
    gzip: int
    loaded_gzip: int  # the HTML and every asset it loads (script, stylesheet, math font, search), gzip
    scenes: tuple[tuple[str, int], ...]  # ("page#scene", raw bytes of its inline tables), heaviest first


def page_weights(files: dict[str, bytes], records, cached) -> list[PageWeight]:
    """The weight of every page among `files` (name: bytes, the built site's), with its scenes from `records`.
    Each gzip size is cached by the file's digest: a rebuild compresses only what changed."""

    def packed(data: bytes) -> int:
        key = hashlib.sha256(data).hexdigest()
        return int(cached("page-gzip", key, lambda: str(gzip_bytes(data)).encode()))

    assets = sum(packed(data) for name, data in sorted(files.items()) if name.startswith("assets/"))
    weights = []
    for name, data in sorted(files.items()):
        if name.endswith(".html") and "/" not in name:
            scenes = sorted(
                ((r.name, r.data_bytes[0]) for r in records if r.page.output_name == name), key=lambda s: -s[1]
            )
            html = packed(data)
            weights.append(PageWeight(name, len(data), html, html + assets, tuple(scenes)))
    return weights


def weight_lines(weights: list[PageWeight]) -> list[str]:
    """A line per page for the build's summary: HTML raw and gzip, and with what it loads."""
    return [
        f"page      {w.page:<36} {_kib(w.raw):>10} raw {_kib(w.gzip):>10} gzip, {_kib(w.loaded_gzip):>10} gzip "
        "with its assets"
        for w in weights
    ]


def weight_warnings(weights: list[PageWeight], budget_kb: float, records) -> list[str]:
    """A warning for each page whose download (gzip, with its assets) exceeds `budget_kb`: its heaviest scenes
    and their largest tables, with what would shrink them."""
    scenes = {r.name: r for r in records}
    warnings = []
    for w in weights:
        if w.loaded_gzip <= budget_kb * 1024:
            continue
        heavy = [name for name, size in w.scenes[:HEAVIEST] if size]
        named = "; ".join(
            f"'{name.split('#', 1)[1]}' ({_kib(size)} of tables{_tables(scenes[name])})"
            for name, size in w.scenes[:HEAVIEST]
            if size
        )
        advice = (
            f" Its heaviest scenes: {named}. Fewer stops on those sliders, fewer decimals, or an exact form "
            "(structure=) for an output that has one would shrink "
            "them; a scene split in two loads only what each shows."
            if heavy
            else ""
        )
        warnings.append(
            f"warning: {w.page} weighs {_kib(w.loaded_gzip)} gzip with its assets, above the book's page budget of "
            f"{budget_kb:g} KiB (book.toml page_budget_kb).{advice}"
        )
    return warnings


def _tables(record) -> str:
    """The scene's largest tables by values, e.g. ": 'ring' 18,792 values over zeta × f"."""
    scene = record.scene
    sizes = []
    for name in record.outputs:
        output = type(scene.model).output(name)
        if output.structure_for(scene.effects) is not None and not output.digits:
            continue  # computed by the page from a few pieces, not tabulated per stop
        deps = scene.model.deps_of(name, scene.effects)
        axes = [a for a in scene.axes if a.param in deps]
        values = math.prod(a.count for a in axes) * max(output.size, 1)
        sizes.append((values, name, " × ".join(a.param for a in axes) or "no slider"))
    largest = sorted(sizes, key=lambda s: (-s[0], s[1]))[:TABLES]
    return ": " + ", ".join(f"'{n}' {v:,} values over {over}" for v, n, over in largest) if largest else ""


def _kib(size: int) -> str:
    return f"{size / 1024:,.1f} KiB"
