"""The bubble settings sweep (bench.json's "digits") as the accuracy page shows it: a diagram and a table."""

from __future__ import annotations

import math
from html import escape

from ...render.work_precision import Panel, Point, Series


def sweep_panel(sweep: dict) -> Panel:
    """Every scene as a line: time per solve against the largest error in units of the last shown digit."""
    series = []
    chosen = None
    for name, data in sweep.items():
        points = []
        for run in data["runs"]:
            per_solve = run["seconds"] / data["stops"] * 1e3
            exponent = f"{-math.log10(run['rtol']):.0f}"
            points.append(Point(per_solve, max(run["max_units"] or 1e3, 1e-6), exponent, major=True))
            if run["rtol"] == data["chosen"] and name.endswith("driven-map"):
                chosen = Point(per_solve, max(run["max_units"] or 1e3, 1e-6), "chosen: rtol 1e-8")
        series.append(Series(name.split("#")[1], tuple(points)))
    return Panel("bubble scenes, every stop", tuple(series), chosen=chosen, floor=1e-6, ceiling=1e3)


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
        run = next(r for r in data["runs"] if r["rtol"] == data["chosen"])
        listed = [f"wrong: {escape(s)}" for s in run["wrong_stops"]] + [
            f"near a boundary: {escape(s)}" for s in run["near_stops"]
        ]
        more = run["wrong"] + run["near"] - len(listed)
        text = "; ".join(listed) + (f"; and {more} more" if more > 0 else "") if listed else "none"
        items.append(f"<li>{escape(name.split('#')[1])} ({data['stops']:,} stops): {text}</li>")
    return '<ul class="report-findings">\n' + "\n".join(items) + "\n</ul>\n"
