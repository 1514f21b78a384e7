"""What each page weighs as a reader downloads it: its HTML, raw and gzip, and with the assets it loads; a
warning for a page above the book's budget, naming its heaviest scenes and what would shrink them."""

from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass

from .sizes import gzip_bytes

HEAVIEST = 3  # scenes a warning names
TABLES = 2  # of each, the largest tables it names
LOADING = (b"href", b"src", b"data-index")  # the attributes by which a page loads an asset


@dataclass(frozen=True)
class PageWeight:
    """One page: its HTML raw and gzip, what it loads with it (raw and gzip), and its scenes' data (raw
    bytes)."""

    page: str
    raw: int
    gzip: int
    loaded_gzip: int  # the HTML and every asset it loads (script, stylesheet, math font, search), gzip
    scenes: tuple[tuple[str, int], ...]  # ("page#scene", raw bytes of its inline tables), heaviest first
    loaded_raw: int = 0  # the same, raw

    def sizes(self) -> dict[str, int]:
        """The page's bytes as the accuracy report and the benches list them."""
        return {
            "html_raw": self.raw,
            "html_gzip": self.gzip,
            "total_raw": self.loaded_raw,
            "total_gzip": self.loaded_gzip,
        }


def page_weights(files: dict[str, bytes], records, cached) -> list[PageWeight]:
    """The weight of every page among `files` (name: bytes, the built site's), with its scenes from `records`.
    Each file is compressed once, and its gzip size is cached by its digest: a rebuild compresses only what
    changed."""
    packed: dict[str, int] = {}

    def gzip_size(name: str) -> int:
        if name not in packed:
            data = files[name]
            key = hashlib.sha256(data).hexdigest()
            packed[name] = int(cached("page-gzip", key, lambda: str(gzip_bytes(data)).encode()))
        return packed[name]

    weights = []
    for name, data in sorted(files.items()):
        if name.endswith(".html") and "/" not in name:
            scenes = sorted(
                ((r.name, r.data_bytes[0]) for r in records if r.page.output_name == name), key=lambda s: -s[1]
            )
            loaded = [name, *loaded_assets(data, files)]
            weights.append(
                PageWeight(
                    name,
                    len(data),
                    gzip_size(name),
                    sum(gzip_size(n) for n in loaded),
                    tuple(scenes),
                    sum(len(files[n]) for n in loaded),
                )
            )
    return weights


def loaded_assets(html: bytes, files: dict[str, bytes]) -> list[str]:
    """The assets among `files` a page loads: what it links and its scripts (the search script by its
    data-index, loaded on first use), and the fonts its stylesheets name."""
    assets = {  # found by the literal ="assets/ (a fast scan of a page of megabytes), then the attribute's name
        m[1].decode()
        for m in re.finditer(rb'="(assets/[^"]+)"', html)
        if any(html.endswith(attribute, 0, m.start()) for attribute in LOADING)
    }
    for sheet in sorted(a for a in assets if a.endswith(".css") and a in files):
        assets |= {f"assets/{u.decode()}" for u in re.findall(rb'url\("?([^")]+)"?\)', files[sheet])}
    return sorted(a for a in assets if a in files)


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
