"""The bubble's own bench experiments: the three regimes of docs/physics/bubble.md (every solver over the rtol
ladder against a closed form or a tight reference), and the sweep of the book's bubble scenes (sweep.py).

The generic experiment measures the scenes' methods at their check stops; these measure scipy's solvers
beside the compiled ones on one problem each, which is what shows why `auto` chooses as it does.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ...physics.numerics import BenchExperiment
from .point import compose
from .run import MACH, OK, Caps, Run
from .solve import ANALYTIC, choose_method, integrate, rayleigh_run
from .terms import EPSILON, Problem, mach_one_radius, rayleigh_fraction, rayleigh_radius, rayleigh_tau

RTOLS = tuple(10.0**-k for k in range(3, 13))  # 1e-3 … 1e-12
METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA", "compiled-DOP853", "compiled-Radau")
QUICK_METHODS = ("DOP853", "LSODA", "compiled-DOP853")
EXPLICIT = ("RK45", "DOP853")
BENCH_CAPS = Caps(max_nfev=3_000_000)  # generous: the bench measures, the build guards

PRESETS = {  # name: (effects, parameters that differ from the defaults), docs/physics/bubble.md
    "A": (("inertia", "vapour", "step"), {"R0": 1000.0, "p_inf": 1.0}),
    "B": (
        ("gas", "vdw_hard_core", "surface_tension", "viscosity", "drive", "keller_miksis"),
        {"R0": 4.5, "p_a": 1.3, "f": 26.5},
    ),
    "C": (("gas", "vapour", "surface_tension", "viscosity", "ramp"), {"R0": 1.0, "kappa": 1.0, "depth": 0.99}),
    "stiff": (
        ("gas", "surface_tension", "viscosity", "drive"),
        {"R0": 1.0, "mu": 1.0, "rho": 1260.0, "p_a": 0.5, "f": 20.0, "kappa": 1.4},
    ),
}


# The accuracy section's case C is the model's "stiff" preset (the viscous micro-bubble); B and C run one
# acoustic period, as docs/physics/bubble.md says (the page's scenes run two).
CASES = {
    "A": {
        "preset": "A",
        "title": "A: empty Rayleigh collapse (R_max 1 mm, p∞ 1 atm)",
        "short": "A: empty Rayleigh collapse",
        "periods": 0,
        "metric": "max |ΔR|/R₀ over the sampled curve, up to |Ṙ| = c",
        "reference": "analytic: R(t) from betaincinv",
    },
    "B": {
        "preset": "B",
        "title": "B: driven bubble with Keller–Miksis (4.5 µm, 1.3 atm, 26.5 kHz), one period",
        "short": "B: driven bubble, Keller–Miksis, one period",
        "periods": 1,
        "metric": "max |ΔR|/R_max over the sampled curve",
        "reference": "DOP853 rtol 1e-13, cross-checked with Radau rtol 1e-12",
    },
    "C": {
        "preset": "stiff",
        "title": "C: stiff viscous micro-bubble (1 µm, µ = 1 Pa·s, 20 kHz), one period",
        "short": "C: stiff viscous micro-bubble, one period",
        "periods": 1,
        "metric": "max |ΔR|/R₀ over the sampled curve",
        "reference": "Radau rtol 1e-13, cross-checked with LSODA rtol 1e-12",
    },
}
REFERENCE = {"B": (("DOP853", 1e-13), ("Radau", 1e-12)), "C": (("Radau", 1e-13), ("LSODA", 1e-12))}


def preset_of(case: str, defaults: dict) -> Problem:
    """The nondimensional problem of a case's preset, the model's `defaults` filled in."""
    effects, values = PRESETS[CASES[case]["preset"]]
    return compose({**defaults, **values}, effects)[0]


def bubble_problem(case: str, defaults: dict) -> Problem:
    """The nondimensional problem of an accuracy case (B and C cut to one acoustic period)."""
    pb = preset_of(case, defaults)
    periods = CASES[case]["periods"]
    return replace(pb, tau_end=periods * 2.0 * math.pi / pb.omega) if periods else pb


def solve_case(pb: Problem, method: str, rtol: float) -> Run:
    """One case solved with `method` at `rtol` (atol = 1e-3 rtol, nondimensional), uncached."""
    if method == ANALYTIC:
        return rayleigh_run(pb)
    return integrate(pb, (1.0, 0.0), method, rtol, BENCH_CAPS)


def skip_reason(case: str, method: str, rtol: float) -> str | None:
    """Why a combination is not run (hopeless or minutes long, docs/physics/bubble.md), or None."""
    if case == "C" and method in EXPLICIT and rtol not in (1e-3, 1e-6):
        return (
            "stability-limited: 3e5–4e5 evaluations and 3–10 s per solve at every rtol (measured at 1e-3 "
            "and 1e-6); rtol changes only the error, never the cost"
        )
    if case == "B" and method == "Radau" and rtol < 1e-10:
        return "Radau beyond rtol 1e-10 on B takes 3e5–5e5 evaluations and 7–20 s per solve"
    return None


def collapse_errors(run: Run, pb: Problem) -> dict:
    """Case A: the sampled curve and the time the wall reaches |Ṙ| = c, against the closed form."""
    delta = pb.p_inf - pb.vapour
    tau_c = rayleigh_tau(delta)
    reached = np.isfinite(run.r)
    exact = rayleigh_radius(run.tau[reached] / tau_c)
    stop = tau_c * float(rayleigh_fraction(max(float(mach_one_radius(delta, pb.sound)), EPSILON)))
    return {"curve": finite(np.max(np.abs(run.r[reached] - exact))), "t_stop": finite(abs(run.end[0] - stop) / stop)}


def extrema(run: Run, period: float) -> tuple[float, float, float]:
    """(R_max, R_min, t_min/T) of the run from its event-detected extrema (not from samples)."""
    maxima = run.maxima[run.maxima[:, 0] > 0] if len(run.maxima) else np.empty((0, 2))
    minima = run.minima[run.minima[:, 0] > 0] if len(run.minima) else np.empty((0, 2))
    if not len(maxima) or not len(minima):
        return math.nan, math.nan, math.nan
    deepest = int(np.argmin(minima[:, 1]))
    return float(np.max(maxima[:, 1])), float(minima[deepest, 1]), float(minima[deepest, 0] / period)


def driven_errors(run: Run, reference: Run, period: float) -> dict:
    """Case B: the curve relative to R_max, and the readouts R_max, R_min (relative) and t_min/T."""
    r_max, r_min, t_min = extrema(run, period)
    ref_max, ref_min, ref_t = extrema(reference, period)
    return {
        "curve": finite(_curve_gap(run, reference) / ref_max),
        "R_max": finite(abs(r_max - ref_max) / ref_max),
        "R_min": finite(abs(r_min - ref_min) / ref_min),
        "t_min": finite(abs(t_min - ref_t)),
    }


def stiff_errors(run: Run, reference: Run) -> dict:
    """Case C: the sampled curve against the tight implicit reference."""
    return {"curve": finite(_curve_gap(run, reference))}


def _curve_gap(run: Run, reference: Run) -> float:
    """max |Δr| on the shared sample grid; infinite when the run stopped before the reference did."""
    if np.isnan(run.r).sum() > np.isnan(reference.r).sum():
        return math.inf
    both = np.isfinite(run.r) & np.isfinite(reference.r)
    return float(np.max(np.abs(run.r[both] - reference.r[both])))


def case_errors(case: str, pb: Problem, run: Run, reference: Run | None) -> dict:
    """The error metrics of one run of a case; `curve` is the one the diagram plots."""
    if case == "A":
        return collapse_errors(run, pb)
    if case == "B":
        return driven_errors(run, reference, 2.0 * math.pi / pb.omega)
    return stiff_errors(run, reference)


def case_reference(case: str, pb: Problem, cross_check: bool) -> tuple[Run | None, dict]:
    """The reference run of a case (None for A: the closed form) and how well a second method agrees."""
    if case == "A":
        r = np.linspace(0.011, 1.0, 2001)
        trip = float(np.max(np.abs(rayleigh_radius(rayleigh_fraction(r)) - r)))
        return None, {"check": "betainc ∘ betaincinv round trip over r ∈ [0.011, 1]", "agreement": trip}
    (method, rtol), (second, second_rtol) = REFERENCE[case]
    reference = solve_case(pb, method, rtol)
    note = {"status": reference.status, "nfev": reference.nfev}
    if not cross_check:
        return reference, {**note, "check": "skipped (quick run)", "agreement": None}
    other = solve_case(pb, second, second_rtol)
    agreement = case_errors(case, pb, other, reference)
    measured = [v for v in agreement.values() if v is not None]
    return reference, {
        **note,
        "check": f"{second} rtol {second_rtol:.0e}",
        "agreement": max(measured, default=None),
        "check_seconds": other.seconds,
    }


def finite(value) -> float | None:
    """A float for JSON, or None where the value does not exist (NaN, ±inf)."""
    value = float(value)
    return value if math.isfinite(value) else None


class Regime(BenchExperiment):
    """Every solver × rtol on one accuracy case (some skipped, with the reason), against its reference."""

    def __init__(self, case: str):
        self.case = case

    def measure(self, scenes, quick: bool, timer) -> dict:
        """The case's runs, timed by `timer`, with its reference's cross-check and the setting `auto` picks."""
        case, info = self.case, CASES[self.case]
        methods, rtols = (QUICK_METHODS, (1e-3, 1e-6)) if quick else (METHODS, RTOLS)
        defaults = type(scenes[0].scene.model).defaults()  # the bench runs this only for a book's bubble scenes
        pb = bubble_problem(case, defaults)
        reference, check = case_reference(case, pb, cross_check=not quick)
        combos = ([(ANALYTIC, None)] if case == "A" else []) + [(m, r) for m in methods for r in rtols]
        jobs = {
            (m, r): (lambda m=m, r=r: solve_case(pb, m, r or 0.0)) for m, r in combos if not skip_reason(case, m, r)
        }
        timed = timer(jobs)
        runs = [self._row(m, r, timed.get((m, r)), pb, reference) for m, r in combos]
        method, rtol = choose_method(preset_of(case, defaults))
        expected = MACH if case == "A" else OK
        return {
            "title": info["title"],
            "metric": info["metric"],
            "reference": info["reference"],
            "reference_check": check,
            "work": "median wall time per solve (ms)",
            "note": "labels: rtol = 10⁻ⁿ; ▲: error above the plot",
            "label": f"Work–precision diagram of bubble case {case}: error against time for each solver over "
            "rtol 10⁻³ to 10⁻¹².",
            "caption": "The number beside a point is n in rtol = 10⁻ⁿ (atol = 10⁻³ rtol, nondimensional); the "
            "ringed point is the setting the model chooses for this case.",
            "expected_status": expected,
            "floor": 1e-15,
            "panels": [
                {
                    "title": info["short"],
                    "runs": runs,
                    "chosen": {"method": method, "value": rtol or None},
                }
            ],
            "findings": _findings(case, runs),
        }

    def _row(self, method: str, rtol: float | None, timed, pb: Problem, reference: Run | None) -> dict:
        row = {"method": method, "setting": "rtol" if rtol else None, "value": rtol}
        if timed is None:
            return {**row, "status": "skipped", "skipped": skip_reason(self.case, method, rtol)}
        run = timed.result
        errors = case_errors(self.case, pb, run, reference)
        row.update(
            evaluations=int(run.nfev),
            ended=run.status,
            status="ok" if run.status in (OK, MACH) else run.status,
            error=errors["curve"],
            errors=errors,
            time_s=timed.seconds,
            repeats=timed.repeats,
        )
        return {**row, "exact": True} if method == ANALYTIC else row


def _run(runs: list[dict], method: str, rtol: float | None) -> dict | None:
    found = [r for r in runs if r["method"] == method and r["value"] == rtol and r["status"] == "ok"]
    return found[0] if found and found[0].get("time_s") else None


def _findings(case: str, runs: list[dict]) -> list[str]:
    """What this case shows beyond the generic figures (plain text; numbers as 1e-6)."""
    found = []
    loose, tight = _run(runs, "DOP853", 1e-6), _run(runs, "DOP853", 1e-9)
    if case != "C" and loose and tight and loose["error"] and tight["error"]:
        found.append(
            f"Tightening DOP853 from rtol 1e-6 to 1e-9 buys {math.log10(loose['error'] / tight['error']):.1f} digits "
            f"for ×{tight['time_s'] / loose['time_s']:.2g} the time."
        )
    return found + _regime_findings(case, runs)


def _regime_findings(case: str, runs: list[dict]) -> list[str]:
    if case == "A":
        dop, exact = _run(runs, "DOP853", 1e-6), _run(runs, ANALYTIC, None)
        if dop and exact:
            return [
                f"DOP853 at rtol 1e-6 takes {dop['time_s'] / exact['time_s']:.0f} times as long as the closed form."
            ]
    if case == "C":
        fast, slow = _run(runs, "LSODA", 1e-6), _run(runs, "RK45", 1e-6)
        if fast and slow:
            return [
                f"RK45 at the same rtol needs {slow['evaluations']:,} evaluations and "
                f"{slow['time_s'] / fast['time_s']:.0f} times LSODA's time: its step is held down by stability, "
                "not accuracy."
            ]
    return []
