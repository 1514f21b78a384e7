"""A digit sweep (an experiment of kind "digit-sweep") as the accuracy page shows it: every stop of each scene
at several rtols, the largest error in units of the last shown digit against the time a solve takes."""

from __future__ import annotations

import math
from html import escape

from ...render.work_precision import Panel, Point, Series, work_precision_figure
from .html import MISSING, figure, figure_html, table


def sweep_part(name: str, data: dict | None, context) -> str:
    """The sweep's diagram, its table, and every value that is wrong or near a rounding boundary at the chosen rtol."""
    if not data:
        return MISSING
    scenes, label = data["scenes"], data["label"]

    def draw(narrow):
        return work_precision_figure(
            [sweep_panel(scenes, data["ringed"], data["title"])],
            "time per solve, all stops (ms)",
            "largest error (last shown digits)",
            "labels: rtol = 10⁻ⁿ; below 0.5 every shown digit can be right",
            narrow,
        )

    rows = table(
        ["scene", "rtol", "ms per solve", "wrong values", "near a boundary", "largest error (digits)"],
        sweep_rows(scenes),
        "Every stop of every scene against the tight reference",
        text=(0,),
    )
    caption = (
        f"{label} Reference: {escape(next(iter(scenes.values()))['reference'])}. The number beside a point is n in "
        "rtol = 10⁻ⁿ; the ringed point is the setting the scenes use."
    )
    return figure_html(name, figure(context, name, scenes, label, draw), label, caption, rows) + near_listing(scenes)


def sweep_panel(sweep: dict, ringed: str, title: str) -> Panel:
    """Every scene as a line: time per solve against the largest error in units of the last shown digit."""
    series = []
    chosen = None
    for name, data in sweep.items():
        points = []
        for run in data["runs"]:
            per_solve = run["seconds"] / data["stops"] * 1e3
            exponent = f"{-math.log10(run['rtol']):.0f}"
            points.append(Point(per_solve, max(run["max_units"] or 1e3, 1e-6), exponent, major=True))
            if run["rtol"] == data["chosen"] and name == ringed:
                text = f"chosen: rtol 1e-{exponent}"
                chosen = Point(per_solve, max(run["max_units"] or 1e3, 1e-6), text)
        series.append(Series(name.split("#")[1], tuple(points)))
    return Panel(title, tuple(series), chosen=chosen, floor=1e-6, ceiling=1e3)


def sweep_rows(sweep: dict) -> list[list[str]]:
    """Table rows: scene, rtol, ms per solve, wrong values, values near a rounding boundary, largest error."""
    rows = []
    for name, data in sweep.items():
        for run in data["runs"]:
            mark = " (chosen)" if run["rtol"] == data["chosen"] else ""
            units = "—" if run["max_units"] is None else f"{run['max_units']:.2g}"
            rows.append(
                [
                    name.split("#")[1],
                    f"1e−{-math.log10(run['rtol']):.0f}{mark}",
                    f"{run['seconds'] / data['stops'] * 1e3:.2f}",
                    f"{run['wrong']:,}",
                    f"{run['near']:,}",
                    units,
                ]
            )
    return rows


def near_listing(sweep: dict) -> str:
    """At the chosen rtol: every value that is wrong, and every one near a rounding boundary, by stop (HTML)."""
    items = []
    for name, data in sweep.items():
        run = next((r for r in data["runs"] if r["rtol"] == data["chosen"]), None)
        if run is None:
            continue
        listed = [f"wrong: {escape(s)}" for s in run["wrong_stops"]] + [
            f"near a boundary: {escape(s)}" for s in run["near_stops"]
        ]
        more = run["wrong"] + run["near"] - len(listed)
        text = "; ".join(listed) + (f"; and {more} more" if more > 0 else "") if listed else "none"
        items.append(f"<li>{escape(name.split('#')[1])} ({data['stops']:,} stops): {text}</li>")
    return '<ul class="report-findings">\n' + "\n".join(items) + "\n</ul>\n"
