"""The review written out: a self-contained HTML report and a Markdown summary for a pull request."""

from __future__ import annotations

import base64
from pathlib import Path

import jinja2

from .compare import Review, SceneChange
from .figures import SCALE, percent, svg_data_uri
from .report_html import TEMPLATE

MAX_SUMMARY_ROWS = 25  # rows per Markdown table; the HTML report lists everything
MAX_DIFF_LINES = 400  # lines of a text diff shown in the HTML report

_ENV = jinja2.Environment(autoescape=True, trim_blocks=True, lstrip_blocks=True)


def write_report(review: Review, out: Path) -> tuple[Path, Path]:
    """Write out/index.html and out/summary.md; return their paths."""
    out.mkdir(parents=True, exist_ok=True)
    html, summary = out / "index.html", out / "summary.md"
    html.write_text(report_html(review), encoding="utf-8")
    summary.write_text(summary_markdown(review, html), encoding="utf-8")
    return html, summary


def headline(review: Review) -> str:
    """One line: what changed, in counts."""
    if not review.changed:
        return "no changes"
    scenes = review.scenes()
    inside = [
        _count(len(review.figures()), "figure"),
        _count(len(review.tables()), "table"),
        _count(len([s for s in scenes if s.panel]), "set of readouts", "sets of readouts"),
    ]
    inside = [part for part in inside if part]
    parts = [
        _count(len(scenes), "scene") + (f" ({', '.join(inside)})" if inside else "") if scenes else "",
        _count(
            len([p for p in review.pages if p.text or p.markup or p.status != "changed"]), "page's text", "pages' text"
        ),
        _count(len(review.files), "other file"),
    ]
    return ", ".join(part for part in parts if part) + " changed"


def _count(n: int, one: str, many: str = "") -> str:
    return f"{n} {one if n == 1 else many or one + 's'}" if n else ""


# --- HTML ---------------------------------------------------------------------------------------


def report_html(review: Review) -> str:
    """The whole report as one HTML file: images inline, no script, no external resource."""
    return _ENV.from_string(TEMPLATE).render(
        review=review,
        headline=headline(review),
        png=_png_uri,
        svg=svg_data_uri,
        percent=percent,
        anchor=scene_anchor,
        figure_notes=figure_notes,
        scale=SCALE,
        max_lines=MAX_DIFF_LINES,
        stats=_stats(review),
    )


def _png_uri(data: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(data).decode()


def scene_anchor(scene: SceneChange) -> str:
    """The id of a scene's card in the report."""
    return f"{scene.page.removesuffix('.html')}--{scene.id}"


def _stats(review: Review) -> list[tuple[str, int, int | None]]:
    scenes = review.scenes()
    return [
        ("pages", len(review.pages), review.page_count),
        ("scenes", len(scenes), review.scene_count),
        ("figures", len(review.figures()), None),
        ("tables", len(review.tables()), sum(s.table_count for s in scenes) or None),
        ("other files", len(review.files), None),
    ]


def figure_notes(scene: SceneChange) -> list[str]:
    """What changed in a figure, besides its pixels: size, static drawing, moving layers."""
    svg = scene.figure.svg if scene.figure else None
    if svg is None:
        return []
    notes = []
    if svg.size_old != svg.size_new:
        notes.append(f"size {svg.size_old[0]:g}×{svg.size_old[1]:g} → {svg.size_new[0]:g}×{svg.size_new[1]:g} pt")
    notes.append("static drawing changed" if svg.static_changed else "static drawing unchanged")
    if svg.layers_changed:
        notes.append("moving layers changed: " + ", ".join(svg.layers_changed))
    return notes


# --- Markdown -----------------------------------------------------------------------------------


def summary_markdown(review: Review, report: Path | None = None) -> str:
    """A short summary to paste into a pull-request comment."""
    lines = [
        f"## Build review: {headline(review)}",
        "",
        f"`{_md(review.old_label)}` → `{_md(review.new_label)}`: {_count(review.page_count, 'page') or '0 pages'}, "
        f"{_count(review.scene_count, 'scene') or '0 scenes'} compared.",
    ]
    if not review.changed:
        return "\n".join(lines + ["", "Every file of the two builds is byte-identical."]) + "\n"
    lines += _figure_rows(review) + _table_rows(review) + _page_rows(review) + _file_rows(review)
    if review.render_note:
        lines += ["", f"_Figures were not rendered: {_md(review.render_note)}_"]
    if report is not None:
        lines += ["", f"Full report with the figures side by side: `{report.parent.name}/{report.name}`"]
    return "\n".join(lines) + "\n"


def _figure_rows(review: Review) -> list[str]:
    scenes = review.figures() + [s for s in review.scenes() if s.status != "changed" and not s.figure]
    if not scenes:
        return []
    rows = ["", "**Figures** (at the default slider values)", "", "| page | scene | change |", "|---|---|---|"]
    for scene in scenes[:MAX_SUMMARY_ROWS]:
        rows.append(f"| {scene.page} | {scene.id} | {_md(_figure_change(scene))} |")
    return rows + _more(len(scenes), "figures")


def _figure_change(scene: SceneChange) -> str:
    if scene.status != "changed":
        return f"scene {scene.status}"
    pixels = scene.figure.pixels
    parts = [percent(pixels.fraction) + " of the figure differs" if pixels else "SVG changed"]
    svg = scene.figure.svg
    if svg and svg.layers_changed:
        parts.append(f"layer{'s' if len(svg.layers_changed) > 1 else ''} {', '.join(svg.layers_changed)} moved")
    if svg and svg.static_changed:
        parts.append("static drawing changed")
    return "; ".join(parts)


def _table_rows(review: Review) -> list[str]:
    changes = review.tables()
    if not changes:
        return []
    rows = [
        "",
        "**Numbers** (every stop of every slider)",
        "",
        "| scene | output | stops changed | largest change | largest relative change |",
        "|---|---|---|---|---|",
    ]
    for scene, table in changes[:MAX_SUMMARY_ROWS]:
        if table.status != "changed":
            rows.append(f"| {scene.id} | {table.output} | {table.status} | | |")
            continue
        stops = f"{table.changed:,} of {table.stops:,}"
        rows.append(
            f"| {scene.id} | {table.output} | {stops} | "
            f"{_md(_extreme(table.largest_abs))} | {_md(_extreme(table.largest_rel))} |"
        )
    return rows + _more(len(changes), "outputs")


def _extreme(extreme) -> str:
    if extreme is None:
        return ""
    size = f"{extreme.size} " if extreme.size else ""
    return f"{size}({extreme.old} → {extreme.new}{' at ' + extreme.where if extreme.where else ''})"


def _page_rows(review: Review) -> list[str]:
    rows = []
    for page in review.pages:
        if page.status != "changed":
            rows.append(f"- {page.name}: page {page.status}")
        elif page.text:
            changed = [line for line in page.text if line.kind in "+-"]
            rows.append(f"- {page.name}: {len(changed)} line(s) of text changed")
            rows += ["  ```diff", *(f"  {line.kind}{_excerpt(line)}" for line in changed[:6]), "  ```"]
        elif page.markup:
            rows.append(f"- {page.name}: markup changed, no visible text")
    return ["", "**Pages** (text outside the scenes)", "", *rows] if rows else []


def _excerpt(line, width: int = 150) -> str:
    """A long line cut to the part around its first changed words."""
    text = line.text
    if len(text) <= width:
        return text
    start, offset = 0, 0
    for piece, hot in line.runs:
        if hot:
            start = offset
            break
        offset += len(piece)
    start = max(0, min(start - width // 3, len(text) - width))
    return ("…" if start else "") + text[start : start + width] + ("…" if start + width < len(text) else "")


def _file_rows(review: Review) -> list[str]:
    if not review.files:
        return []
    rows = [f"- {f.name}: {f.status} ({f.old_size:,} → {f.new_size:,} bytes)" for f in review.files]
    return ["", "**Other files**", "", *rows]


def _more(count: int, what: str) -> list[str]:
    return [f"| … {count - MAX_SUMMARY_ROWS} more {what} in the full report | | |"] if count > MAX_SUMMARY_ROWS else []


def _md(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")
