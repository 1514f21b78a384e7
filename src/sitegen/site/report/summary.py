"""Headline figures derived from one bench run: what a digit costs, the Pareto front, key ratios.

Pure functions of bench.json's data, so the accuracy page (built deterministically) and the
bench's printout quote the same numbers. Every ratio compares runs of the same bench run.
"""

from __future__ import annotations

import math

import numpy as np

FLOOR = 1e-14  # errors below this are at round-off: they say nothing about a method's order
EXACT = ("exact DST", "analytic")


def usable(run: dict) -> bool:
    """A run that ran (not skipped, not failed) and has a time and a finite error."""
    return (
        "skipped" not in run
        and run.get("error") is not None
        and run.get("time_s") is not None
        and run.get("status", "ok") in ("ok", "mach", "")
    )


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
    """The runs no other run beats in both time and error, fastest first."""
    candidates = sorted((r for r in runs if usable(r)), key=lambda r: (r["time_s"], r["error"]))
    front, best = [], math.inf
    for run in candidates:
        if run["error"] < best:
            front.append(run)
            best = run["error"]
    return front


def label(run: dict) -> str:
    """A run as a reader names it: "DOP853 rtol 1e-6", "velocity Verlet ν = 0.1", "exact DST"."""
    if run["method"] in EXACT:
        return run["method"]
    if run.get("rtol") is not None:
        return f"{run['method']} rtol {exponent_text(run['rtol'])}"
    return f"{run['method']} {run.get('setting', '')}".strip()


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


def find(runs: list[dict], method: str, **where) -> dict | None:
    """The usable run of `method` whose fields match `where` (e.g. rtol=1e-6, N=64), or None."""
    for run in runs:
        if run["method"] == method and usable(run) and all(_same(run.get(k), v) for k, v in where.items()):
            return run
    return None


def _same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-9)
    return a == b


def ratio(top: dict | None, bottom: dict | None, field: str = "time_s") -> float | None:
    """top[field]/bottom[field], or None when either run is missing or the bottom is zero."""
    if not top or not bottom or not bottom.get(field):
        return None
    return top[field] / bottom[field]


def chain_headlines(chain: dict, n: int) -> dict:
    """For one chain size: the DST point, Verlet per halving of ν, costs per digit, the cheapest 1e-6 run."""
    runs = [r for r in chain["runs"] if r["N"] == n]
    dst = find(runs, "exact DST")
    verlet = {r["courant"]: r for r in runs if r["method"] == "velocity Verlet" and usable(r)}
    halvings = [(nu, verlet[nu / 2]) for nu in sorted(verlet) if nu / 2 in verlet]
    halving = None
    if halvings:
        nu, fine = halvings[-1]
        halving = {
            "from": nu,
            "to": nu / 2,
            "error": verlet[nu]["error"] / fine["error"],
            "time": ratio(fine, verlet[nu]),
        }
    integrators = [r for r in runs if r["method"] not in EXACT and usable(r) and r["error"] <= 1e-6]
    cheapest = min(integrators, key=lambda r: r["time_s"], default=None)
    return {
        "N": n,
        "dst": dst,
        "halving": halving,
        "cheapest_1e-6": cheapest,
        "dst_advantage": ratio(cheapest, dst),
        "per_digit": {m: per_digit_cost(rs) for m, rs in methods(runs).items() if m not in EXACT},
        "pareto": pareto(runs),
    }


TARGETS = (1e-3, 1e-6, 1e-9, 1e-12)  # error levels at which the cheapest run is quoted


def cheapest_within(runs: list[dict], target: float) -> dict | None:
    """The fastest usable solver run (not a closed form) whose error is at most `target`."""
    within = [r for r in runs if usable(r) and r["method"] not in EXACT and r["error"] <= target]
    return min(within, key=lambda r: r["time_s"], default=None)


def bubble_headlines(case: dict) -> dict:
    """For one bubble case: costs per digit per method, the Pareto front, the cheapest run per error level, the chosen
    run."""
    runs = case["runs"]
    chosen = case["chosen"]
    picked = find(runs, chosen["method"], **({"rtol": chosen["rtol"]} if chosen.get("rtol") else {}))
    return {
        "per_digit": {m: per_digit_cost(rs) for m, rs in methods(runs).items() if m not in EXACT},
        "pareto": pareto([r for r in runs if r["method"] not in EXACT]),
        "chosen": picked,
        "cheapest": {target: cheapest_within(runs, target) for target in TARGETS},
    }


def tighter(runs: list[dict], method: str, loose: float, tight: float) -> dict | None:
    """What going from rtol `loose` to `tight` with one method costs and buys: time and error ratios."""
    a, b = find(runs, method, rtol=loose), find(runs, method, rtol=tight)
    if not a or not b or not b["error"]:
        return None
    return {
        "method": method,
        "loose": loose,
        "tight": tight,
        "time": ratio(b, a),
        "digits": math.log10(a["error"] / b["error"]) if a["error"] > 0 else None,
    }
