"""The work–precision experiments of docs/physics/ (chain.md, bubble.md): the chain and the Rayleigh–Plesset presets.

Each experiment returns plain data (dicts of numbers and strings, ready for JSON): for every
method and setting its error against a reference, its evaluation count and the median wall
time of repeated runs. Errors are deterministic; only the times depend on the machine.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..models.bubble.presets import preset_problem
from ..models.bubble.run import MACH, OK, Caps, Run
from ..models.bubble.solve import ANALYTIC, choose_method, integrate, rayleigh_run
from ..models.bubble.terms import EPSILON, Problem, mach_one_radius, rayleigh_fraction, rayleigh_radius, rayleigh_tau
from ..models.chain.integrators import integrate_ivp, velocity_verlet
from ..models.chain.modes import LENGTH, RIGHT_MOVING, SPEED, mass_and_stiffness, positions, spacing
from ..models.chain.motion import evolve, initial_state
from .timing import time_medians

RTOLS = tuple(10.0**-k for k in range(3, 13))  # 1e-3 … 1e-12
BUBBLE_METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA", "compiled-DOP853", "compiled-Radau")
EXPLICIT = ("RK45", "DOP853")
CHAIN_T = 2.0 * LENGTH / SPEED  # one round trip
CHAIN_SIGMA = 0.05 * LENGTH
BENCH_CAPS = Caps(max_nfev=3_000_000)  # generous: the bench measures, the build guards


@dataclass(frozen=True)
class Plan:
    """Which experiments to run and how often to repeat them (FULL for `make bench`, QUICK for tests)."""

    chain_sizes: tuple[int, ...] = (64, 256)
    courant_numbers: tuple[float, ...] = (0.5, 0.2, 0.1, 0.05, 0.02)  # ν = cΔt/a of velocity Verlet
    chain_methods: tuple[str, ...] = EXPLICIT
    chain_rtols: tuple[float, ...] = RTOLS
    cases: tuple[str, ...] = ("A", "B", "C")
    bubble_methods: tuple[str, ...] = BUBBLE_METHODS
    bubble_rtols: tuple[float, ...] = RTOLS
    max_repeats: int = 5
    cross_check: bool = True  # the slow second-method check of the tight references (~20 s for B)
    scene_repeats: int = 3  # cold tabulations per scene (a scene slower than 2 s is timed once)
    sweep_rtols: tuple[float, ...] = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10)  # the bubble scenes' settings, every stop


FULL = Plan()
QUICK = Plan(
    chain_sizes=(16,),
    courant_numbers=(0.5, 0.25),
    chain_rtols=(1e-3, 1e-6),
    cases=("A",),
    bubble_methods=("DOP853", "LSODA", "compiled-DOP853"),
    bubble_rtols=(1e-3, 1e-6),
    max_repeats=1,
    cross_check=False,
    scene_repeats=1,
    sweep_rtols=(1e-6,),
)


def finite(value) -> float | None:
    """A float for JSON, or None where the value does not exist (NaN, ±inf)."""
    value = float(value)
    return value if math.isfinite(value) else None


# --- the chain (docs/physics/chain.md) --------------------------------------------------------------------


def chain_start(n: int) -> tuple[np.ndarray, np.ndarray]:
    """u(0), u̇(0) of the bench's right-moving Gaussian pulse (σ = 0.05 L, x₀ = 0.3 L, A = 1)."""
    return initial_state(positions(n), CHAIN_SIGMA, RIGHT_MOVING, amplitude=1.0)


def chain_exact(n: int) -> np.ndarray:
    """u(T) by the exact DST modal solution: the reference of every chain integrator."""
    u0, v0 = chain_start(n)
    return evolve(u0, v0, CHAIN_T)[0]


def chain_by_eigh(n: int) -> np.ndarray:
    """u(T) from a dense eigendecomposition of the stiffness matrix: a second, independent exact method."""
    m, kappa = mass_and_stiffness(n)
    stiffness = kappa / m * (2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1))
    squared, modes = np.linalg.eigh(stiffness)
    omega = np.sqrt(squared)
    u0, v0 = chain_start(n)
    return modes @ (np.cos(omega * CHAIN_T) * (modes.T @ u0) + np.sin(omega * CHAIN_T) / omega * (modes.T @ v0))


def verlet_steps(n: int, courant: float) -> int:
    """Steps of velocity Verlet over T at Courant number ν = cΔt/a (rounded to a whole number)."""
    return max(1, round(CHAIN_T * SPEED / (courant * float(spacing(n)))))


def run_verlet(n: int, courant: float):
    """Velocity Verlet over one round trip at Courant number ν: the Integration at T."""
    u0, v0 = chain_start(n)
    steps = verlet_steps(n, courant)
    return velocity_verlet(u0, v0, CHAIN_T / steps, steps)


def run_chain_ivp(n: int, method: str, rtol: float):
    """The chain through solve_ivp (atol = rtol × A): the Integration at T."""
    u0, v0 = chain_start(n)
    return integrate_ivp(u0, v0, CHAIN_T, method, rtol)


def chain_error(u: np.ndarray, exact: np.ndarray) -> float:
    """max_j |u_j − u_DST| / A (A = 1)."""
    return float(np.max(np.abs(np.asarray(u).ravel() - exact)))


def chain_experiment(plan: Plan = FULL) -> dict:
    """Velocity Verlet, RK45 and DOP853 against the exact DST solution, and DST against eigh."""
    jobs = {}
    for n in plan.chain_sizes:
        u0, v0 = chain_start(n)
        jobs[n, "exact DST", None] = lambda u0=u0, v0=v0: evolve(u0, v0, CHAIN_T)
        for nu in plan.courant_numbers:
            jobs[n, "velocity Verlet", nu] = lambda n=n, nu=nu: run_verlet(n, nu)
        for method in plan.chain_methods:
            for rtol in plan.chain_rtols:
                jobs[n, method, rtol] = lambda n=n, method=method, rtol=rtol: run_chain_ivp(n, method, rtol)
    timed = time_medians(jobs, plan.max_repeats)
    exact = {n: chain_exact(n) for n in plan.chain_sizes}
    runs = [_chain_row(key, timed[key], exact[key[0]]) for key in jobs]
    return {
        "what": "a right-moving Gaussian pulse on a fixed-end chain over one round trip",
        "T": CHAIN_T,
        "sigma": CHAIN_SIGMA,
        "x0": 0.3 * LENGTH,
        "error": "max_j |u_j − u_DST| / A at t = 2L/c",
        "reference": "exact DST-I modal solution (its own row: DST against a dense eigendecomposition)",
        "chosen": {"method": "exact DST"},
        "runs": runs,
    }


def _chain_row(key: tuple, timed, exact: np.ndarray) -> dict:
    """One chain run as JSON data: its setting, work, error against the DST and median time."""
    n, method, setting = key
    row = {"N": n, "method": method, "courant": None, "rtol": None, "time_s": timed.seconds, "repeats": timed.repeats}
    if method == "exact DST":
        return {
            **row,
            "setting": "one transform pair",
            "evaluations": 0,
            "steps": 1,
            "error": finite(chain_error(chain_by_eigh(n), exact)),
        }
    result = timed.result
    row.update(
        evaluations=int(result.evaluations), steps=int(result.steps), error=finite(chain_error(result.u[-1], exact))
    )
    if method == "velocity Verlet":
        return {**row, "setting": f"ν = {setting:g}", "courant": setting}
    row.update(setting=f"rtol {setting:.0e}".replace("e-0", "e-"), rtol=setting)
    return row if result.status == 0 else {**row, "status": result.message}


# --- Rayleigh–Plesset (docs/physics/bubble.md) -------------------------------------------------------------

# Case C is the viscous micro-bubble of docs/physics/bubble.md (the model's "stiff" preset); B and C run one
# acoustic period, as there (the page's scenes run two).
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


def bubble_problem(case: str) -> Problem:
    """The nondimensional problem of a bench case (B and C cut to one acoustic period)."""
    pb, _ = preset_problem(CASES[case]["preset"])
    periods = CASES[case]["periods"]
    return replace(pb, tau_end=periods * 2.0 * math.pi / pb.omega) if periods else pb


def solve_case(case: str, method: str, rtol: float) -> Run:
    """One case solved with `method` at `rtol` (atol = 1e-3 rtol, nondimensional), uncached."""
    if method == ANALYTIC:
        return rayleigh_run(bubble_problem(case))
    return integrate(bubble_problem(case), (1.0, 0.0), method, rtol, BENCH_CAPS)


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


def case_errors(case: str, run: Run, reference: Run | None) -> dict:
    """The error metrics of one run of a case; `curve` is the one the diagram plots."""
    pb = bubble_problem(case)
    if case == "A":
        return collapse_errors(run, pb)
    if case == "B":
        return driven_errors(run, reference, 2.0 * math.pi / pb.omega)
    return stiff_errors(run, reference)


def case_reference(case: str, cross_check: bool) -> tuple[Run | None, dict]:
    """The reference run of a case (None for A: the closed form) and how well a second method agrees."""
    if case == "A":
        r = np.linspace(0.011, 1.0, 2001)
        trip = float(np.max(np.abs(rayleigh_radius(rayleigh_fraction(r)) - r)))
        return None, {"check": "betainc ∘ betaincinv round trip over r ∈ [0.011, 1]", "agreement": trip}
    (method, rtol), (second, second_rtol) = REFERENCE[case]
    reference = solve_case(case, method, rtol)
    note = {"status": reference.status, "nfev": reference.nfev}
    if not cross_check:
        return reference, {**note, "check": "skipped (quick run)", "agreement": None}
    other = solve_case(case, second, second_rtol)
    agreement = case_errors(case, other, reference)
    measured = [v for v in agreement.values() if v is not None]
    return reference, {
        **note,
        "check": f"{second} rtol {second_rtol:.0e}",
        "agreement": max(measured, default=None),
        "check_seconds": other.seconds,
    }


def bubble_experiment(case: str, plan: Plan = FULL) -> dict:
    """Every method × rtol on one bench case (some skipped, with the reason), against its reference."""
    reference, check = case_reference(case, plan.cross_check)
    combos = [(ANALYTIC, 0.0)] if case == "A" else []
    combos += [(method, rtol) for method in plan.bubble_methods for rtol in plan.bubble_rtols]
    jobs = {(m, r): (lambda m=m, r=r: solve_case(case, m, r)) for m, r in combos if not skip_reason(case, m, r)}
    timed = time_medians(jobs, plan.max_repeats)
    runs = []
    for method, rtol in combos:
        if (method, rtol) not in jobs:
            runs.append({"method": method, "rtol": rtol, "skipped": skip_reason(case, method, rtol)})
            continue
        run = timed[method, rtol]
        errors = case_errors(case, run.result, reference)
        row = {
            "method": method,
            "rtol": rtol or None,
            "nfev": run.result.nfev,
            "status": run.result.status,
            "error": errors["curve"],
            "errors": errors,
            "time_s": run.seconds,
            "repeats": run.repeats,
        }
        runs.append({**row, "exact": True} if method == ANALYTIC else row)
    method, rtol = choose_method(preset_problem(CASES[case]["preset"])[0])
    info = {k: v for k, v in CASES[case].items() if k != "periods"}
    return {
        **info,
        "reference_check": check,
        "chosen": {"method": method, "rtol": rtol or None},
        "runs": runs,
        "expected_status": MACH if case == "A" else OK,
    }
