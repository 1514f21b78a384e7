"""The generic parts of the accuracy report: a model's methods at its scenes' stops, and an experiment a model
declares of its own, each drawn from bench.json alone as a work–precision diagram with its table of runs.

A diagram has a panel per scene (or per problem of the experiment), a line per method, the Pareto front
marked and the scene's own settings (or the experiment's choice) ringed. Nothing here names a model.
"""

from __future__ import annotations

import re
from html import escape

from ...compute.accuracy import methods_anchor
from ...render.work_precision import Panel, Point, Series, work_precision_figure
from . import summary
from .html import MISSING, duration, factor, figure, figure_html, run_point, sci, table


def model_part(name: str, context) -> str:
    """A model's methods over their ladders at the accuracy stops of each of its scenes."""
    results = ((context.bench or {}).get("models") or {}).get(name)
    if not results or not results.get("methods"):
        return _wrapped(name, MISSING if not context.bench or results else _no_scenes(name))
    data = results["methods"]
    label = f"Work–precision diagram of the model {name}: error against time for each method, one panel per scene."
    if _worth_drawing(data):
        body = _diagram(context, name, data, label, _methods_caption(data))
    else:
        body = _runs_table(name, data)
    return _wrapped(name, body + _digits_table(data) + _findings(data))


def experiment_part(name: str, data: dict | None, context) -> str:
    """An experiment a model declares of its own, drawn like the generic one."""
    if not data:
        return MISSING
    caption = f"{escape(_sentence(data['title']))}. Error: {escape(data.get('error', data['metric']))}; reference: "
    caption += f"{escape(data['reference'])}{_agreement(data)}. {powers(data.get('caption', ''))}"
    return _diagram(context, name, data, data.get("label", f"Work–precision diagram: {data['title']}."), caption)


def _wrapped(name: str, body: str) -> str:
    return f'<div class="report-part" id="{methods_anchor(name)}">\n{body}</div>\n'


def _no_scenes(name: str) -> str:
    return f'<p class="report-missing">No numerically computed scene of this book uses the model {escape(name)}.</p>\n'


def _worth_drawing(data: dict) -> bool:
    """Whether some panel has a line to draw: two usable runs or more (one method at one setting is a table row)."""
    return any(sum(summary.usable(r) for r in panel["runs"]) > 1 for panel in data["panels"])


def _diagram(context, name: str, data: dict, label: str, caption: str) -> str:
    def draw(narrow):
        return work_precision_figure(
            [_panel(panel, data) for panel in data["panels"]],
            data.get("work", "median time, checked stops (ms)"),
            data["metric"].split(" over")[0],
            data.get("note", "labels: rtol = 10⁻ⁿ, or the value of the method's setting; ▲: error above the plot"),
            narrow,
        )

    svg = figure(context, name, data, label, draw)
    return figure_html(name, svg, label, caption, _runs_table(name, data))


def _panel(panel: dict, data: dict) -> Panel:
    runs = [r for r in panel["runs"] if summary.usable(r)]
    series = [
        Series(method, tuple(run_point(r) for r in _ordered(group)))
        for method, group in summary.methods(runs).items()
        if not all(r.get("exact") for r in group)
    ]
    picked, exact = summary.chosen(panel), next((r for r in runs if r.get("exact")), None)
    ring = None
    if picked:
        text = "scene's setting" if panel.get("own") else "chosen"
        ring = Point(picked["time_s"] * 1e3, picked["error"], f"{text}: {summary.label(picked)}" + _exact(picked))
    front = tuple(Point(r["time_s"] * 1e3, r["error"]) for r in summary.pareto(runs))
    return Panel(
        summary.panel_title(panel),
        tuple(series),
        chosen=ring,
        exact=Point(exact["time_s"] * 1e3, 0.0, "") if exact else None,
        floor=data.get("floor", 1e-16),
        ceiling=data.get("ceiling", 10.0),
        front=front if len(front) > 1 else (),
    )


def _ordered(runs: list[dict]) -> list[dict]:
    """A method's runs from its loosest setting to its tightest (by error where one has no value: its own rule)."""
    if any(r.get("value") is None for r in runs):
        return sorted(runs, key=lambda r: -r["error"])
    finer_when_smaller = runs[0].get("setting") != "nodes"
    return sorted(runs, key=lambda r: -r["value"] if finer_when_smaller else r["value"])


def _exact(run: dict) -> str:
    return " (exact)" if run.get("exact") else ""


def _methods_caption(data: dict) -> str:
    only = data.get("only_own") or []
    skipped = f" Measured only at the scenes' own settings: {escape(', '.join(only))}." if only else ""
    return (
        f"Each panel is one scene: every method the model offers over a ladder of its setting, measured at the stops "
        f"the build checks. Error: {escape(data['metric'])}, the largest over the stops, against "
        f"{powers(escape(data['reference']))}; time: the median of repeated computations of the scene's outputs at "
        f"all those stops. The number beside a point is n in rtol = 10⁻ⁿ (or the method's setting); the grey band "
        f"joins the Pareto front; the ringed point is the scene's own setting.{skipped}"
    )


def _runs_table(name: str, data: dict) -> str:
    rows = []
    several = len(data["panels"]) > 1
    for panel in data["panels"]:
        front, picked = {id(r) for r in summary.pareto(panel["runs"])}, summary.chosen(panel)
        for r in panel["runs"]:
            cells = [escape(panel.get("title") or panel["scene"])] if several else []
            cells += [escape(r["method"]), escape(summary.setting_text(r) or "—")]
            if r.get("status", "ok") != "ok" or r.get("time_s") is None:
                reason = r.get("skipped") or r.get("status", "")
                rows.append(cells + ["—", "—", "—", "", f"not run: {escape(reason)}"])
                continue
            notes = [f"{r.get('repeats', 1)} run(s)"]
            notes += ["the scene's setting" if panel.get("own") else "chosen"] if r is picked else []
            if r.get("ended") and r["ended"] != data.get("expected_status", r["ended"]):
                notes.append(f"ended: {escape(r['ended'])}")
            rows.append(
                cells
                + [
                    f"{r.get('evaluations', 0):,}",
                    sci(r["error"]),
                    duration(r["time_s"]),
                    "yes" if id(r) in front else "",
                    "; ".join(notes),
                ]
            )
    head = (["problem"] if several else []) + ["method", "setting", "evaluations", "error", "median time"]
    return table(head + ["Pareto front", "notes"], rows, f"Every run of {escape(name)}", text=(len(head) + 1,))


def _digits_table(data: dict) -> str:
    """What one more correct digit costs, per method and panel."""
    costs = [(summary.panel_title(p), summary.headlines(p)["per_digit"]) for p in data["panels"]]
    methods = list(dict.fromkeys(m for _, per in costs for m, f in per.items() if f))
    if not methods:
        return ""
    return table(
        ["problem", *map(escape, methods)],
        [[escape(title)] + [factor(per.get(m)) for m in methods] for title, per in costs],
        "What one more correct digit costs: the time multiplier per extra digit (least-squares slope of log time "
        "against −log error)",
    )


def _findings(data: dict) -> str:
    items = [finding(panel) for panel in data["panels"]]
    return '<ul class="report-findings">\n' + "\n".join(f"<li>{i}</li>" for i in items if i) + "\n</ul>\n"


def finding(panel: dict) -> str:
    """One panel's headline as a sentence (HTML): its chosen setting, what beats it, the cheapest runs."""
    head = summary.headlines(panel)
    parts = [f"<strong>{escape(summary.panel_title(panel))}.</strong>"]
    if head["chosen"]:
        c = head["chosen"]
        whose = "The scene's setting" if panel.get("own") else "The chosen setting"
        parts.append(
            f"{whose}, {run_html(c)}, takes {duration(c['time_s'])} "
            + ("and is exact." if c.get("exact") else f"with error {sci(c['error'])}{_evaluations(c)}.")
        )
    if head["dominating"]:
        d = head["dominating"]
        parts.append(
            f"It is dominated: {run_html(d)} is as accurate ({sci(d['error'])}) in {duration(d['time_s'])}, "
            f"{summary.ratio(d, head['chosen']):.0%} of its time."
        )
    cheapest = [
        f"within {sci(target)}, {run_html(run)} ({duration(run['time_s'])})"
        for target, run in head["cheapest"].items()
        if run
    ]
    if cheapest and sum(summary.usable(r) for r in panel["runs"]) > 1:  # with one run, nothing to choose from
        parts.append("Cheapest run " + "; ".join(cheapest) + ".")
    return " ".join(parts)


def _evaluations(run: dict) -> str:
    return f" ({run['evaluations']:,} evaluations)" if run.get("evaluations") else ""


def run_html(run: dict) -> str:
    """A run as the page's prose names it: "DOP853 at rtol 10<sup>−6</sup>", "velocity Verlet at ν = 0.1"."""
    text = summary.setting_text(run)
    if run.get("setting") == "rtol":
        return f"{escape(run['method'])} at rtol {sci(run['value'])}"
    return f"{escape(run['method'])} at {escape(text)}" if text else escape(run["method"])


def _agreement(data: dict) -> str:
    check = data.get("reference_check") or {}
    return f" (they agree to {sci(check['agreement'])})" if check.get("agreement") is not None else ""


def _sentence(text: str) -> str:
    return text[:1].upper() + text[1:]


def powers(text: str) -> str:
    """Numbers like 1e-12 in (escaped) text written as 10<sup>−12</sup>, as the page writes them."""

    def power(match: re.Match) -> str:
        shown = f"10<sup>{int(match[2])}</sup>".replace("-", "−")
        return shown if match[1] in ("1", "1.0") else f"{match[1]}\u00a0×\u00a0{shown}"

    return re.sub(r"\b(\d+(?:\.\d+)?)e([-+]?\d+)\b", power, text)
