"""The bubble's part of the accuracy report: a work–precision diagram per bench case, findings, cost per digit."""

from __future__ import annotations

from html import escape

from ...render.work_precision import Panel, Point, Series, work_precision_figure
from ...site.report import summary
from ...site.report.html import MISSING, duration, factor, figure, figure_html, label_html, run_point, sci, table
from ...site.report.sweep import near_listing, sweep_panel, sweep_rows


class BubbleReport:
    """What the accuracy report shows of the bubble's bench results (bench.json's "bubble", one entry per case)."""

    def part(self, name: str, context) -> str:
        """The part "bubble-<case>", or "settings"."""
        if name == "settings":
            return settings_part(context)
        return bubble_part(name.removeprefix("bubble-"))(context)

    def findings(self, bench: dict) -> list[str]:
        """One paragraph per case."""
        return [_bubble_sentence(case, data) for case, data in bench["bubble"].items()]

    def per_digit(self, bench: dict) -> list[tuple[str, dict]]:
        """Per case: the time multiplier per extra digit of each method."""
        return [
            (f"bubble {case}", summary.bubble_headlines(data)["per_digit"]) for case, data in bench["bubble"].items()
        ]


def bubble_part(case: str):
    """The report block of one bubble case: its work–precision diagram and its numbers."""

    def render(context) -> str:
        if not context.bench or case not in context.bench.get("bubble", {}):
            return MISSING
        data = context.bench["bubble"][case]
        label = (
            f"Work–precision diagram of bubble case {case}: error "
            "against time for five solvers over rtol 10⁻³ to 10⁻¹²."
        )

        def draw(narrow):
            return work_precision_figure(
                [_bubble_panel(data)],
                "median wall time per solve (ms)",
                data["metric"].split(" over")[0],
                "labels: rtol = 10⁻ⁿ; ▲: error above the plot",
                narrow,
            )

        svg = figure(context, f"bubble-{case}", data, label, draw)
        return figure_html(f"bubble-{case}", svg, label, _bubble_caption(data), _bubble_table(case, data))

    return render


def _bubble_panel(data: dict) -> Panel:
    runs = [r for r in data["runs"] if summary.usable(r)]
    series = [
        Series(m, tuple(run_point(r) for r in group))
        for m, group in summary.methods(runs).items()
        if m not in summary.EXACT
    ]
    chosen_run = summary.bubble_headlines(data)["chosen"]
    exact = summary.find(runs, "analytic")
    chosen = None
    if chosen_run:
        text = f"chosen: {summary.label(chosen_run)}" + (" (exact)" if chosen_run.get("exact") else "")
        chosen = Point(chosen_run["time_s"] * 1e3, chosen_run["error"], text)
    return Panel(
        data.get("short", data["title"]),
        tuple(series),
        chosen=chosen,
        floor=1e-15,
        ceiling=10.0,
        exact=Point(exact["time_s"] * 1e3, 0.0, "") if exact else None,
    )


def _bubble_caption(data: dict) -> str:
    check = data["reference_check"]
    agreement = f" (they agree to {sci(check['agreement'])})" if check.get("agreement") is not None else ""
    return (
        f"{escape(data['title'])}. Error: {escape(data['metric'])}; reference: {escape(data['reference'])}{agreement}. "
        "The number beside a point is n in rtol = 10⁻ⁿ (atol = 10⁻³ rtol, nondimensional); the ringed point is "
        "the setting the model chooses for this case."
    )


def _bubble_table(case: str, data: dict) -> str:
    front = {id(r) for r in summary.bubble_headlines(data)["pareto"]}
    rows = []
    for r in data["runs"]:
        tol = summary.exponent_text(r["rtol"]) if r.get("rtol") else "—"
        if "skipped" in r:
            rows.append([r["method"], tol, "—", "—", "—", "", f"not run: {escape(r['skipped'])}"])
        else:
            status = "" if r["status"] == data["expected_status"] else f"ended: {escape(r['status'])}"
            rows.append(
                [
                    r["method"],
                    tol,
                    f"{r['nfev']:,}",
                    sci(r["error"]),
                    duration(r["time_s"]),
                    "yes" if id(r) in front else "",
                    f"{r['repeats']} run(s) {status}".strip(),
                ]
            )
    return table(
        ["method", "rtol", "evaluations", "error", "median time", "Pareto front", "notes"],
        rows,
        f"Every run of bubble case {case}",
        text=(6,),
    )


def _bubble_sentence(case: str, data: dict) -> str:
    head = summary.bubble_headlines(data)
    runs = data["runs"]
    parts = [f"<strong>Bubble {case}.</strong>"]
    if head["chosen"]:
        c = head["chosen"]
        parts.append(
            f"The chosen setting, {label_html(c)}, takes {duration(c['time_s'])} "
            + ("and is exact." if c.get("exact") else f"with error {sci(c['error'])} ({c['nfev']:,} evaluations).")
        )
    step = summary.tighter(runs, "DOP853", 1e-6, 1e-9)
    if case != "C" and step and step["digits"] is not None:
        parts.append(
            f"Tightening DOP853 from rtol {sci(1e-6)} to {sci(1e-9)} buys {step['digits']:.1f} digits "
            f"for {factor(step['time'])} the time."
        )
    if case == "A":
        dop = summary.find(runs, "DOP853", rtol=1e-6)
        ratio = summary.ratio(dop, head["chosen"])
        if ratio:
            parts.append(f"DOP853 at rtol {sci(1e-6)} takes {ratio:.0f} times as long as the closed form.")
    if case == "C":
        fast, slow = summary.find(runs, "LSODA", rtol=1e-6), summary.find(runs, "RK45", rtol=1e-6)
        ratio = summary.ratio(slow, fast)
        if ratio:
            parts.append(
                f"RK45 at the same rtol needs {slow['nfev']:,} evaluations and {ratio:.0f} times LSODA's time: "
                "its step is held down by stability, not accuracy."
            )
    cheapest = [
        f"within {sci(target)}, {label_html(run)} ({duration(run['time_s'])})"
        for target, run in head["cheapest"].items()
        if run
    ]
    if cheapest:
        parts.append("Cheapest solver run " + "; ".join(cheapest) + ".")
    return " ".join(parts)


def settings_part(context) -> str:
    """The bubble scenes' settings, chosen: time per solve against the largest error in shown digits, every stop."""
    sweep = (context.bench or {}).get("digits")
    if not sweep:
        return MISSING
    label = (
        "Time per solve against the largest error in units of the last shown digit, every stop of each bubble scene."
    )

    def draw(narrow):
        return work_precision_figure(
            [sweep_panel(sweep)],
            "time per solve, all stops (ms)",
            "largest error (last shown digits)",
            "labels: rtol = 10⁻ⁿ; below 0.5 every shown digit can be right",
            narrow,
        )

    rows = table(
        ["scene", "rtol", "ms per solve", "wrong values", "near a boundary", "largest error (digits)"],
        sweep_rows(sweep),
        "Every stop of every bubble scene against the tight reference",
        text=(0,),
    )
    caption = (
        f"{label} Reference: {escape(next(iter(sweep.values()))['reference'])}. "
        "The number beside a point is n in rtol = 10⁻ⁿ; "
        "the ringed point is the setting the scenes use."
    )
    return figure_html(
        "settings", figure(context, "settings", sweep, label, draw), label, caption, rows
    ) + near_listing(sweep)
