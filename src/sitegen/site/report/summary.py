"""Headline figures derived from one bench run: what a digit costs, the Pareto front, the chosen setting, and
whether a faster setting is at least as accurate.

Pure functions of bench.json's data, so the accuracy page (built deterministically) and the bench's printout
quote the same numbers. Every ratio compares runs of the same bench run. A run is a dict with its "method",
the "setting" it varies ("rtol", "nodes", "step", "courant" or None) and its "value", its "error", "time_s",
"evaluations" and "status" ("ok" when it ran and has a result).
"""

from __future__ import annotations

import math

import numpy as np

FLOOR = 1e-14  # errors below this are at round-off: they say nothing about a method's order
TARGETS = (1e-3, 1e-6, 1e-9, 1e-12)  # error levels at which the cheapest run is quoted
CLEARLY_FASTER = 0.8  # a dominating setting takes at most this share of the time: more than the timing noise
SYMBOLS = {"courant": "ν =", "step": "step", "nodes": "nodes"}  # how a setting is written before its value


def usable(run: dict) -> bool:
    """A run that ran (not skipped, not failed) and has a time and a finite error."""
    return run.get("status", "ok") == "ok" and run.get("error") is not None and run.get("time_s") is not None


def per_digit_cost(runs: list[dict]) -> float | None:
    """Time multiplier per extra correct digit: 10^slope of log10(time) against −log10(error), least squares.

    None when fewer than three points lie above round-off (no trend to fit).
    """
    points = [(r["time_s"], r["error"]) for r in runs if usable(r) and r["error"] > FLOOR]
    if len(points) < 3:
        return None
    digits = -np.log10([e for _, e in points])
    seconds = np.log10([t for t, _ in points])
    if np.ptp(digits) < 1.0:  # less than one digit of spread: a slope would be noise
        return None
    return float(10.0 ** np.polyfit(digits, seconds, 1)[0])


def pareto(runs: list[dict]) -> list[dict]:
    """The runs no other run beats in both time and error, fastest first (a closed form's exact run aside)."""
    candidates = sorted((r for r in runs if usable(r) and not r.get("exact")), key=lambda r: (r["time_s"], r["error"]))
    front, best = [], math.inf
    for run in candidates:
        if run["error"] < best:
            front.append(run)
            best = run["error"]
    return front


def setting_text(run: dict) -> str:
    """A run's setting as a reader writes it: "rtol 1e-6", "ν = 0.1", "nodes 32" ("" without a setting)."""
    setting, value = run.get("setting"), run.get("value")
    if setting is None or value is None:
        return ""
    if setting == "rtol":
        return f"rtol {exponent_text(value)}"
    return f"{SYMBOLS.get(setting, setting)} {value:g}"


def label(run: dict) -> str:
    """A run as a reader names it: "DOP853 rtol 1e-6", "velocity Verlet ν = 0.1", "exact DST"."""
    return f"{run['method']} {setting_text(run)}".strip()


def exponent_text(value: float) -> str:
    """1e-06 -> "1e-6" (how tolerances are written on the page)."""
    mantissa, exponent = f"{value:.0e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def methods(runs: list[dict]) -> dict[str, list[dict]]:
    """Runs grouped by method, in the order the methods first appear."""
    groups: dict[str, list[dict]] = {}
    for run in runs:
        groups.setdefault(run["method"], []).append(run)
    return groups


def find(runs: list[dict], method: str, value=None) -> dict | None:
    """The usable run of `method` at `value` of its setting (None: the run without one), or None."""
    for run in runs:
        if run["method"] == method and usable(run) and _same(run.get("value"), value):
            return run
    return None


def _same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-9)
    return a == b


def chosen(panel: dict) -> dict | None:
    """The panel's ringed run: the scene's own settings (`own`) or the experiment's choice (`chosen`)."""
    pick = panel.get("own") or panel.get("chosen")
    return find(panel["runs"], pick["method"], pick.get("value")) if pick else None


def cheapest_within(runs: list[dict], target: float) -> dict | None:
    """The fastest usable run (not a closed form's exact one) whose error is at most `target`."""
    within = [r for r in runs if usable(r) and not r.get("exact") and r["error"] <= target]
    return min(within, key=lambda r: r["time_s"], default=None)


def digits(error: float) -> float:
    """The correct digits an error leaves: floor(−log10 error) (1.3e-13: 12), as many as round-off allows at 0."""
    return math.floor(-math.log10(max(error, FLOOR / 100)))


def dominating(panel: dict) -> dict | None:
    """A run that beats the panel's chosen one: clearly faster (CLEARLY_FASTER) with at least as many correct
    digits (the fastest such), or None."""
    own = chosen(panel)
    if own is None or own.get("exact"):
        return None
    better = [
        r
        for r in panel["runs"]
        if usable(r)
        and r is not own
        and r["time_s"] <= CLEARLY_FASTER * own["time_s"]
        and digits(r["error"]) >= digits(own["error"])
    ]
    return min(better, key=lambda r: (r["time_s"], r["error"]), default=None)


def headlines(panel: dict) -> dict:
    """For one panel: costs per digit per method, the Pareto front, the chosen run, the cheapest run per error
    level and a run that dominates the chosen one."""
    runs = panel["runs"]
    return {
        "per_digit": {m: per_digit_cost(rs) for m, rs in methods(runs).items()},
        "pareto": pareto(runs),
        "chosen": chosen(panel),
        "cheapest": {target: cheapest_within(runs, target) for target in TARGETS},
        "dominating": dominating(panel),
    }


def ratio(top: dict | None, bottom: dict | None, field: str = "time_s") -> float | None:
    """top[field]/bottom[field], or None when either run is missing or the bottom is zero."""
    if not top or not bottom or not bottom.get(field):
        return None
    return top[field] / bottom[field]


def experiments(bench: dict) -> list[tuple[str, str, dict]]:
    """Every work–precision experiment of the run as (part, title, data): each model's methods at its scenes'
    stops, then the experiments it declares of its own."""
    found = []
    for name, results in (bench or {}).get("models", {}).items():
        if results.get("methods"):
            found.append((name, results["title"], results["methods"]))
        found += [
            (part, data.get("title", part), data)
            for part, data in results.get("experiments", {}).items()
            if data.get("kind") == "work-precision"
        ]
    return found


def panel_title(panel: dict) -> str:
    """A panel's title: the experiment's own, or the scene it measured (its id: the page is named in the table)."""
    return panel.get("title") or f"{panel['scene'].split('#')[-1]} ({panel['stops']} stops)"


def dominated_lines(bench: dict) -> list[str]:
    """One line per scene whose own settings another setting beats: which, by how much (plain text)."""
    lines = []
    for results in (bench or {}).get("models", {}).values():
        for panel in (results.get("methods") or {}).get("panels", ()):
            better, own = dominating(panel), chosen(panel)
            if better:
                lines.append(
                    f"{panel['scene']}: its setting ({label(own)}: {own['time_s'] * 1e3:.3g} ms, error "
                    f"{own['error']:.1e}) is dominated by {label(better)} ({better['time_s'] * 1e3:.3g} ms, error "
                    f"{better['error']:.1e}): as accurate at the stops the build checks, in "
                    f"{better['time_s'] / own['time_s']:.0%} of the time"
                )
    return lines
