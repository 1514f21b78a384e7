"""Time-stepping integrators for the chain, kept only to compare against its exact modal solution.

The page never uses them: the exact solution is cheaper by 25–4000× and has no step error, and
velocity Verlet at the "magic" step c·Δt = a would silently replace the chain's dispersion by the
continuum's exact transport (docs/physics/chain.md, hard cases).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
from scipy.integrate import solve_ivp

from .modes import BARE, Terms, mass_and_stiffness, mode_frequencies


@dataclass(frozen=True)
class Integration:
    """An integrator's answer: the state at the final time(s), the work it took and how it ended."""

    t: np.ndarray  # times of the rows of u and v
    u: np.ndarray  # displacements, one row per time
    v: np.ndarray  # velocities, one row per time
    evaluations: int  # force (right-hand-side) evaluations
    steps: int
    status: int = 0  # 0 success, as solve_ivp reports it
    message: str = ""


def stability_limit(n: int, terms: Terms = BARE) -> float:
    """The largest stable explicit step, 2/ω_N with ω_N the chain's highest mode frequency."""
    return 2.0 / float(np.max(mode_frequencies(n, terms)))


def acceleration(u: np.ndarray, terms: Terms = BARE) -> np.ndarray:
    """ü_j = (κ/m)(u_{j+1} − 2u_j + u_{j−1}) − ω0² u_j, with the chain's ends as `terms` says."""
    m, kappa = mass_and_stiffness(u.shape[-1], terms.ends)
    if terms.ends == "fixed":
        padded = np.pad(u, [(0, 0)] * (u.ndim - 1) + [(1, 1)])
    elif terms.ends == "free":
        padded = np.pad(u, [(0, 0)] * (u.ndim - 1) + [(1, 1)], mode="edge")  # a missing spring: no force
    else:
        padded = np.pad(u, [(0, 0)] * (u.ndim - 1) + [(1, 1)], mode="wrap")
    laplacian = padded[..., 2:] - 2 * u + padded[..., :-2]
    return kappa / m * laplacian - terms.omega0**2 * u


def velocity_verlet(u0, v0, dt: float, steps: int, terms: Terms = BARE, every: int = 0) -> Integration:
    """Kick–drift–kick velocity Verlet; refuses Δt ≥ 2/ω_N, where it grows without bound.

    `every` > 0 keeps every `every`-th step (for energy histories); otherwise only the last.
    """
    if terms.gamma:
        raise ValueError("velocity Verlet here integrates the undamped chain only; use `integrate_ivp` with `gamma`")
    u, v = np.array(u0, float), np.array(v0, float)
    limit = stability_limit(u.shape[-1], terms)
    if not (0 < dt < limit):
        raise ValueError(
            f"`dt` = {dt:.6g} s must lie in (0, 2/ω_N) = (0, {limit:.6g} s): the stability limit of explicit steps"
        )
    accel = acceleration(u, terms)
    rows_t, rows_u, rows_v = [0.0], [u.copy()], [v.copy()]
    for step in range(1, steps + 1):
        v = v + 0.5 * dt * accel
        u = u + dt * v
        accel = acceleration(u, terms)
        v = v + 0.5 * dt * accel
        if every and step % every == 0:
            rows_t.append(step * dt), rows_u.append(u), rows_v.append(v)
    if not every:
        rows_t, rows_u, rows_v = [steps * dt], [u], [v]
    return Integration(np.array(rows_t), np.array(rows_u), np.array(rows_v), steps + 1, steps)


def integrate_ivp(
    u0, v0, t_end: float, method: str = "DOP853", rtol: float = 1e-9, atol: float | None = None, terms: Terms = BARE
) -> Integration:
    """The chain as a first-order system through scipy's solve_ivp (RK45, DOP853, ...), state at t_end.

    atol defaults to rtol × max|u0|, so the error control is relative to the pulse, not to 1 m.
    """
    u0, v0 = np.asarray(u0, float), np.asarray(v0, float)
    n = u0.shape[-1]
    scale = max(float(np.max(np.abs(u0))), 1e-300)

    def rhs(_, state):
        u, v = state[:n], state[n:]
        return np.concatenate([v, acceleration(u, terms) - terms.gamma * v])

    solution = solve_ivp(
        rhs,
        (0.0, t_end),
        np.concatenate([u0, v0]),
        method=method,
        rtol=rtol,
        atol=rtol * scale if atol is None else atol,
    )
    final = solution.y[:, -1]
    return Integration(
        np.array([solution.t[-1]]),
        final[None, :n],
        final[None, n:],
        solution.nfev,
        len(solution.t) - 1,
        solution.status,
        solution.message,
    )


def dense_motion(u0, v0, t: float, terms: Terms = BARE) -> tuple[np.ndarray, np.ndarray]:
    """u(t), u̇(t) of one chain from its dense N×N force matrix (the second method, O(N³), for checks).

    The matrix is assembled by applying the force law to each unit displacement, so it shares no
    code with the transforms of the modal solution. Undamped: its eigendecomposition (numpy eigh);
    damped: scipy.linalg.expm of the 2N×2N first-order system.
    """
    u0, v0 = np.asarray(u0, float), np.asarray(v0, float)
    n = u0.shape[-1]
    force = acceleration(np.eye(n), terms).T  # column j: the accelerations when mass j alone moves by 1
    if terms.gamma:
        system = np.block([[np.zeros((n, n)), np.eye(n)], [force, -terms.gamma * np.eye(n)]])
        state = scipy.linalg.expm(system * t) @ np.concatenate([u0, v0])
        return state[:n], state[n:]
    squared, modes = np.linalg.eigh(-force)
    omega = np.sqrt(np.maximum(squared, 0.0))  # a rigid mode's ω² may come out as −1e−13
    a, b = modes.T @ u0, modes.T @ v0
    phase = omega * t
    sine = np.where(omega > 0, np.sin(phase) / np.where(omega > 0, omega, 1.0), t)
    return modes @ (a * np.cos(phase) + b * sine), modes @ (b * np.cos(phase) - a * omega * np.sin(phase))
