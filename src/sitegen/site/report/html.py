"""How the accuracy report writes numbers, tables and diagrams (shared by every part)."""

from __future__ import annotations

import json
import math
import re
from html import escape

from ...compute.sources import digest, library_version, source_digest
from ...render.style import laid_out
from ...render.svg import figure_svg
from ...render.work_precision import Point

# What a diagram's bytes depend on besides its data: the drawing code (followed through its imports).
DRAWING_CODE = frozenset({"sitegen.site.report", "sitegen.render.work_precision", "sitegen.render.svg"})
FIGURES_KIND = "report-figures"  # what `figure` caches its SVG as, by a key of its data and drawing code
MISSING = (
    '<p class="report-missing">No benchmark results yet: run <code>make bench</code> (or '
    "<code>sitegen bench</code>) to measure them.</p>"
)


# --- numbers as the page writes them ------------------------------------------------------------------------


def sci(value: float | None, digits: int = 2) -> str:
    """2.1 × 10<sup>−7</sup> as the captions write numbers; 0.083, 1.3 or 270 between 0.01 and 10⁴; "—" if none."""
    if value is None or not math.isfinite(value):
        return "—"
    if value == 0:
        return "0"
    if 0.01 <= abs(value) < 1e4:
        rounded = float(f"{value:.{digits}g}")
        return f"{rounded:.{max(0, digits - 1 - math.floor(math.log10(abs(rounded))))}f}".replace("-", "−")
    mantissa, exponent = f"{value:.{digits - 1}e}".split("e")
    power = f"10<sup>{int(exponent)}</sup>".replace("-", "−")
    return power if float(mantissa) == 1.0 else f"{mantissa} × {power}"


def duration(seconds: float | None) -> str:
    """0.052 ms, 5.6 ms, 3.2 s."""
    if seconds is None:
        return "—"
    if seconds >= 1.0:
        return f"{seconds:.1f} s" if seconds < 100 else f"{seconds:.0f} s"
    ms = seconds * 1e3
    return f"{ms:.3f} ms" if ms < 1 else f"{ms:.2g} ms" if ms < 10 else f"{ms:.0f} ms"


def kib(size: int) -> str:
    """Bytes in KiB with one decimal (or bytes under 1 KiB)."""
    return f"{size} B" if size < 1024 else f"{size / 1024:.1f} KiB"


def factor(value: float | None) -> str:
    """×3.2 (or "—")."""
    return "—" if value is None else f"×{value:.2g}" if value < 10 else f"×{value:.0f}"


def rtol_exponent(rtol: float) -> str:
    """1e-06 -> "6": the label beside a point of a work–precision line."""
    return str(-int(round(math.log10(rtol))))


# --- the figures ---------------------------------------------------------------------------------------------


def figure(context, name: str, data, label: str, draw) -> str:
    """A diagram's inline SVG, wide and narrow (`draw(narrow)`), cached by its data and the drawing code
    (same data, same bytes)."""
    key = digest(
        name,
        json.dumps(data, sort_keys=True),
        source_digest(DRAWING_CODE),
        f"matplotlib {library_version('matplotlib')}",
    )

    def both() -> bytes:
        wide = figure_svg(laid_out(draw(False)), [], [], f"acc-{name}", label)
        return (wide + figure_svg(laid_out(draw(True)), [], [], f"acc-{name}-narrow", label, "narrow")).encode()

    return context.cached(FIGURES_KIND, key, both).decode()


def figure_html(name: str, svg: str, label: str, caption: str, data_table: str) -> str:
    """The diagram on a white card (wide, or narrow on a phone), its caption, and its numbers behind a disclosure."""
    return (
        f'<figure class="report-figure" id="fig-{name}">\n<div class="report-card">\n{svg}</div>\n'
        f"<figcaption>{caption}</figcaption>\n</figure>\n"
        f'<details class="report-data">\n<summary>The numbers behind this diagram</summary>\n{data_table}</details>\n'
    )


def table(
    head: list[str],
    rows: list[list[str]],
    caption: str = "",
    row_ids: list[str] | None = None,
    text: tuple[int, ...] = (),
) -> str:
    """A table in a scrolling box (wide tables scroll sideways on a phone, not the page); `text` columns wrap."""
    ids = row_ids or [""] * len(rows)
    body = "\n".join(_row(row, row_id, text) for row, row_id in zip(rows, ids))
    cap = f"<caption>{caption}</caption>\n" if caption else ""
    label = escape(re.sub(r"<[^>]+>", "", caption) or "table")
    heads = "".join(f'<th scope="col">{h}</th>' for h in head)
    # Always marked as scrolling: its edge shadows show only where it does (so nothing measures it on the page),
    # and its row count sizes the place it holds until it nears the screen and is laid out.
    return (
        f'<div class="report-scroll scrolls" tabindex="0" role="region" aria-label="{label}" '
        f'style="--rows: {len(rows)}">\n<table class="report">\n{cap}'
        f"<thead><tr>{heads}</tr></thead>\n<tbody>\n{body}\n</tbody>\n</table>\n</div>\n"
    )


def _row(cells: list[str], row_id: str, text: tuple[int, ...]) -> str:
    attribute = f' id="{row_id}"' if row_id else ""
    return (
        f"<tr{attribute}>"
        + "".join(f'<td class="text">{c}</td>' if i in text else f"<td>{c}</td>" for i, c in enumerate(cells))
        + "</tr>"
    )


def run_point(run: dict) -> Point:
    """A run as a point (time in ms, error) labelled by n of its rtol = 10⁻ⁿ or the value of its setting."""
    value = run.get("value")
    if value is None:
        return Point(run["time_s"] * 1e3, run["error"])
    if run.get("setting") == "rtol":
        exponent = rtol_exponent(value)
        return Point(run["time_s"] * 1e3, run["error"], exponent, major=int(exponent) % 3 == 0)
    return Point(run["time_s"] * 1e3, run["error"], f"{value:g}")
