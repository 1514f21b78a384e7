"""The chain's own bench experiment (docs/physics/chain.md): the integrators it keeps for comparison against the exact
DST solution, on a right-moving Gaussian pulse over one round trip.

The page never uses the integrators, so they are no method a scene may choose: the generic experiment measures
only the DST, and this one adds velocity Verlet over a ladder of Courant numbers and RK45 and DOP853 over the
rtol ladder, each against the DST, whose own row is its disagreement with a dense eigendecomposition.
"""

from __future__ import annotations

import numpy as np

from ...physics.numerics import BenchExperiment
from .integrators import integrate_ivp, velocity_verlet
from .modes import LENGTH, RIGHT_MOVING, SPEED, mass_and_stiffness, positions, spacing
from .motion import evolve, initial_state

ROUND_TRIP = 2.0 * LENGTH / SPEED
PULSE_SIGMA = 0.05 * LENGTH
RTOLS = tuple(10.0**-k for k in range(3, 13))  # 1e-3 … 1e-12
COURANT = (0.5, 0.2, 0.1, 0.05, 0.02)  # ν = cΔt/a of velocity Verlet
SIZES, QUICK_SIZES = (64, 256), (16,)
EXPLICIT = ("RK45", "DOP853")


def pulse_start(n: int) -> tuple[np.ndarray, np.ndarray]:
    """u(0), u̇(0) of the bench's right-moving Gaussian pulse (σ = 0.05 L, x₀ = 0.3 L, A = 1)."""
    return initial_state(positions(n), PULSE_SIGMA, RIGHT_MOVING, amplitude=1.0)


def exact_after_round_trip(n: int) -> np.ndarray:
    """u(T) by the exact DST modal solution: the reference of every chain integrator."""
    u0, v0 = pulse_start(n)
    return evolve(u0, v0, ROUND_TRIP)[0]


def by_eigh(n: int) -> np.ndarray:
    """u(T) from a dense eigendecomposition of the stiffness matrix: a second, independent exact method."""
    m, kappa = mass_and_stiffness(n)
    stiffness = kappa / m * (2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1))
    squared, modes = np.linalg.eigh(stiffness)
    omega = np.sqrt(squared)
    u0, v0 = pulse_start(n)
    return modes @ (np.cos(omega * ROUND_TRIP) * (modes.T @ u0) + np.sin(omega * ROUND_TRIP) / omega * (modes.T @ v0))


def verlet_steps(n: int, courant: float) -> int:
    """Steps of velocity Verlet over T at Courant number ν = cΔt/a (rounded to a whole number)."""
    return max(1, round(ROUND_TRIP * SPEED / (courant * float(spacing(n)))))


def run_verlet(n: int, courant: float):
    """Velocity Verlet over one round trip at Courant number ν: the Integration at T."""
    u0, v0 = pulse_start(n)
    steps = verlet_steps(n, courant)
    return velocity_verlet(u0, v0, ROUND_TRIP / steps, steps)


def run_ivp(n: int, method: str, rtol: float):
    """The chain through solve_ivp (atol = rtol × A): the Integration at T."""
    u0, v0 = pulse_start(n)
    return integrate_ivp(u0, v0, ROUND_TRIP, method, rtol)


def pulse_error(u: np.ndarray, exact: np.ndarray) -> float | None:
    """max_j |u_j − u_DST| / A (A = 1); None where a run blew up (no finite error)."""
    error = float(np.max(np.abs(np.asarray(u).ravel() - exact)))
    return error if np.isfinite(error) else None


class RoundTrip(BenchExperiment):
    """Velocity Verlet, RK45 and DOP853 against the exact DST solution, and the DST against eigh."""

    def measure(self, scenes, quick: bool, timer) -> dict:
        """One panel per chain size: every integrator's runs and the DST's, timed by `timer`."""
        sizes = QUICK_SIZES if quick else SIZES
        courants, rtols = (COURANT[::3], RTOLS[::3][:2]) if quick else (COURANT, RTOLS)
        jobs = {}
        for n in sizes:
            u0, v0 = pulse_start(n)
            jobs[n, "exact DST", None] = lambda u0=u0, v0=v0: evolve(u0, v0, ROUND_TRIP)
            for nu in courants:
                jobs[n, "velocity Verlet", nu] = lambda n=n, nu=nu: run_verlet(n, nu)
            for method in EXPLICIT:
                for rtol in rtols:
                    jobs[n, method, rtol] = lambda n=n, method=method, rtol=rtol: run_ivp(n, method, rtol)
        timed = timer(jobs)
        exact = {n: exact_after_round_trip(n) for n in sizes}
        panels = [
            {
                "title": f"chain of N = {n} masses",
                "runs": [_row(key, timed[key], exact[n]) for key in jobs if key[0] == n],
                "chosen": {"method": "exact DST", "value": None, "text": "chosen: exact DST"},
            }
            for n in sizes
        ]
        return {
            "title": "a right-moving Gaussian pulse on a fixed-end chain over one round trip",
            "metric": "max |u − u_DST| / A",
            "error": "max_j |u_j − u_DST| / A at t = 2L/c",
            "reference": "exact DST-I modal solution (its own row: DST against a dense eigendecomposition)",
            "work": "median wall time per run (ms)",
            "note": "labels: ν = cΔt/a for Verlet, rtol = 10⁻ⁿ for RK45 and DOP853",
            "label": "Work–precision diagram of the chain of masses: error against time for each method, "
            "one panel per chain size.",
            "caption": "One round trip (t = 2L/c) of the Gaussian pulse, σ = 0.05 L. Each line is a method; the "
            "number beside a point is its Courant number ν (velocity Verlet) or n in rtol = 10⁻ⁿ (RK45, DOP853). "
            "The ringed point is what the page uses: the exact DST solution, whose own error is its "
            "disagreement with a dense eigendecomposition.",
            "T": ROUND_TRIP,
            "sigma": PULSE_SIGMA,
            "x0": 0.3 * LENGTH,
            "floor": 1e-16,
            "panels": panels,
        }


def _row(key: tuple, timed, exact: np.ndarray) -> dict:
    """One run as JSON data: its setting, work, error against the DST and median time."""
    n, method, value = key
    row = {"N": n, "method": method, "time_s": timed.seconds, "repeats": timed.repeats, "status": "ok"}
    if method == "exact DST":
        error = pulse_error(by_eigh(n), exact)
        return {**row, "setting": None, "value": None, "evaluations": 0, "steps": 1, "error": error}
    result = timed.result
    row.update(
        setting="courant" if method == "velocity Verlet" else "rtol",
        value=value,
        evaluations=int(result.evaluations),
        steps=int(result.steps),
        error=pulse_error(result.u[-1], exact),
    )
    return row if result.status == 0 else {**row, "status": result.message or f"status {result.status}"}
