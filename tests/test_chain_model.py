"""I5 (chain of N masses): the exact modal solution against a dense matrix exponential, the continuum
string, the comparison integrators' hard cases, each effect's vanishing limit and the page's readouts."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from sitegen.compute.quantize import fmt
from sitegen.models.chain.integrators import integrate_ivp, stability_limit, velocity_verlet
from sitegen.models.chain.model import Chain
from sitegen.models.chain.modes import (
    RESOLVED,
    RIGHT_MOVING,
    SPLIT,
    UNDER_RESOLVED,
    Terms,
    mass_and_stiffness,
    mode_frequencies,
    positions,
    spacing,
)
from sitegen.models.chain.motion import chain_motion, continuum, deviation, energy, evolve, initial_state

EPS = np.finfo(float).eps
LAUNCHES = [pytest.param(RIGHT_MOVING, id="right-moving"), pytest.param(SPLIT, id="split")]


def _dense_matrix(n: int, terms: Terms) -> np.ndarray:
    """The 2N×2N first-order system d(u, v)/dt = M (u, v), written out element by element (the second method)."""
    m, kappa = mass_and_stiffness(n, terms.ends)
    stiffness = np.zeros((n, n))
    for j in range(n):
        for neighbour in (j - 1, j + 1):
            if 0 <= neighbour < n:
                stiffness[j, neighbour] += kappa / m
                stiffness[j, j] -= kappa / m
            elif terms.ends == "fixed":
                stiffness[j, j] -= kappa / m  # the spring to the wall
            elif terms.ends == "periodic" and n > 1:
                stiffness[j, neighbour % n] += kappa / m
                stiffness[j, j] -= kappa / m
    stiffness -= terms.omega0**2 * np.eye(n)
    return np.block([[np.zeros((n, n)), np.eye(n)], [stiffness, -terms.gamma * np.eye(n)]])


def _expm_state(n: int, t: float, terms: Terms, launch=RIGHT_MOVING, sigma=0.05):
    """u(t), u̇(t) from scipy.linalg.expm of the dense system, and the initial state they start from."""
    u0, v0 = initial_state(positions(n, terms.ends), sigma, launch, amplitude=1.0)
    state = scipy.linalg.expm(_dense_matrix(n, terms) * t) @ np.concatenate([u0, v0])
    return state[:n], state[n:], u0, v0


def _evaluate(wanted, effects=(), **inputs):
    """The model's outputs at the defaults changed by `inputs`."""
    return Chain().evaluate({**Chain.defaults(), **inputs}, wanted=wanted, effects=effects)


# --- the exact solution against a dense matrix exponential ------------------------------------------------------


@pytest.mark.parametrize("t", [0.37, 2.0, 1e2], ids=["t=0.37", "t=2", "t=1e2"])
@pytest.mark.parametrize("n", [1, 2, 3, 8], ids=["N=1", "N=2", "N=3", "N=8"])
def test_exact_solution_matches_dense_expm(n, t):
    """DST-I modal solution vs expm of the 2N×2N system, N ≤ 8, t ≤ 1e2: u and u̇ within 1e−11 (A = 1, |u̇0| ≤ 11 s⁻¹)."""
    terms = Terms()
    u_ref, v_ref, u0, v0 = _expm_state(n, t, terms)
    u, v = evolve(u0, v0, t, terms)
    assert np.max(np.abs(u - u_ref)) <= 1e-11 and np.max(np.abs(v - v_ref)) <= 1e-11


@pytest.mark.parametrize(
    "n, expected",
    [pytest.param(1, [np.sqrt(2)], id="N=1:sqrt2"), pytest.param(2, [1.0, np.sqrt(3)], id="N=2:1,sqrt3")],
)
def test_small_chain_frequencies(n, expected):
    """ω/√(κ/m) = √2 for N = 1 and 1, √3 for N = 2, within 4.4e−16 (the DST accepts length 1)."""
    m, kappa = mass_and_stiffness(n)
    assert np.max(np.abs(mode_frequencies(n) / np.sqrt(kappa / m) - expected)) <= 4.4e-16


def test_single_mass_moves_as_its_one_mode():
    """N = 1: u(t) = u0 cos ωt + (v0/ω) sin ωt with ω = √(2κ/m), within 4ε of the amplitude, at t = 0.37 and 1e2."""
    m, kappa = mass_and_stiffness(1)
    omega = np.sqrt(2 * kappa / m)
    u0, v0 = initial_state(positions(1), 0.05, RIGHT_MOVING, amplitude=1.0)
    t = np.array([0.37, 1e2])
    u, _ = evolve(np.repeat(u0[None], 2, 0), np.repeat(v0[None], 2, 0), t)
    exact = u0 * np.cos(omega * t[:, None]) + v0 / omega * np.sin(omega * t[:, None])
    assert np.max(np.abs(u - exact)) <= 4 * EPS * 1e2 * np.hypot(u0, v0 / omega).max()  # ωt ~ 1e2: phase rounding


@pytest.mark.parametrize("launch", LAUNCHES)
@pytest.mark.parametrize("n", [1, 16, 64, 256], ids=["N=1", "N=16", "N=64", "N=256"])
def test_exact_solution_conserves_energy(n, launch):
    """E(t)/E(0) − 1 within 1e−12 for t = 0.37, 2 and 1e2."""
    t = np.array([0.0, 0.37, 2.0, 1e2])
    u, v = chain_motion(n, 0.05, t, launch, amplitude=1.0)
    e = energy(u, v)
    assert np.max(np.abs(e / e[0] - 1)) <= 1e-12


# --- the continuum string ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("launch", LAUNCHES)
@pytest.mark.parametrize("t", [0.0, 0.37, 1.3, 2.0], ids=["t=0", "t=0.37", "t=1.3", "t=2"])
def test_continuum_is_fixed_at_the_walls(t, launch):
    """u_c(0, t) = u_c(L, t) = 0 within 2e−15 (A = 1)."""
    ends = continuum(np.array([0.0, 1.0]), t, 0.05, launch, amplitude=1.0)
    assert np.max(np.abs(ends)) <= 2e-15


@pytest.mark.parametrize("ends", ["fixed", "free", "periodic"])
@pytest.mark.parametrize("launch", LAUNCHES)
def test_continuum_repeats_after_a_round_trip(launch, ends):
    """u_c(x, t + T) = u_c(x, t), T = 2L/c (L/c on a ring), within 9e−16 (A = 1) on x = k/256, t = 0.375.

    Dyadic x and t keep x − ct exact, so only the model's own rounding counts (at t = 0.37 the
    rounding of t + T itself moves u by up to max|u0'|·ε·(t + T) ≈ 3e−15).
    """
    x = np.arange(257) / 256
    period = 1.0 if ends == "periodic" else 2.0
    later = continuum(x, 0.375 + period, 0.05, launch, ends, amplitude=1.0)
    assert np.max(np.abs(later - continuum(x, 0.375, 0.05, launch, ends, amplitude=1.0))) <= 9e-16


@pytest.mark.parametrize("launch", LAUNCHES)
def test_continuum_starts_as_the_pulse(launch):
    """u_c(x, 0) = A exp(−(x−x0)²/2σ²) within e^{−18} (the images beyond the walls), σ = 0.05."""
    x = np.linspace(0, 1, 401)
    u0, _ = initial_state(x, 0.05, launch, amplitude=1.0)
    assert np.max(np.abs(continuum(x, 0.0, 0.05, launch, amplitude=1.0) - u0)) <= 1.01 * np.exp(-18)


def test_right_moving_pulse_travels_at_c():
    """Before any reflection (t = 0.4) the right-moving string is the pulse shifted by ct, within e^{−18}."""
    x = np.linspace(0, 1, 401)
    shifted, _ = initial_state(x - 0.4, 0.05, RIGHT_MOVING, amplitude=1.0)
    assert np.max(np.abs(continuum(x, 0.4, 0.05, RIGHT_MOVING, amplitude=1.0) - shifted)) <= 1.01 * np.exp(-18)


def test_chain_converges_to_the_string_as_a_squared():
    """σ = 0.05, t = 2: dev(256)/dev(512) in [3.6, 4.4] (phase error c k³ a² t/24)."""
    ratio = deviation(256, 0.05, 2.0, RIGHT_MOVING) / deviation(512, 0.05, 2.0, RIGHT_MOVING)
    assert 3.6 <= ratio <= 4.4, f"ratio {ratio:.3f}"


@pytest.mark.parametrize(
    "n, t, measured, unit",
    [
        (16, 0.5, 0.44, 0.01),
        (32, 0.5, 0.175, 0.001),
        (64, 0.5, 0.056, 0.001),
        (128, 0.5, 0.0141, 1e-4),
        (256, 0.5, 3.5e-3, 1e-4),
        (512, 0.5, 8.9e-4, 1e-5),
        (16, 2.0, 0.33, 0.01),
        (32, 2.0, 0.49, 0.01),
        (64, 2.0, 0.21, 0.01),
        (128, 2.0, 0.058, 0.001),
        (256, 2.0, 0.0141, 1e-4),
        (512, 2.0, 3.5e-3, 1e-4),
    ],
    ids=lambda v: None,
)
def test_deviation_from_the_string_matches_measured_table(n, t, measured, unit):
    """max|u_DST − u_c|/A at σ = 0.05 equals docs/physics/chain.md to within one unit of its last printed digit."""
    assert abs(deviation(n, 0.05, t, RIGHT_MOVING) - measured) <= unit


# --- comparison integrators: the hard cases ----------------------------------------------------------------------


def _magic_step_run(n=32, sigma=0.05, t=2.0):
    """VV at c·Δt = a (ν = 1) to t, the DST state and the string at the masses."""
    a, x = spacing(n), positions(n)
    u0, v0 = initial_state(x, sigma, RIGHT_MOVING, amplitude=1.0)
    run = velocity_verlet(u0, v0, a, int(round(t / a)))
    exact, _ = chain_motion(n, sigma, t, RIGHT_MOVING, amplitude=1.0)
    return run.u[-1], exact, continuum(x, t, sigma, RIGHT_MOVING, amplitude=1.0)


def test_verlet_at_the_magic_step_reproduces_the_string():
    """ν = 1, N = 32, σ = 0.05, t = 2: VV is the string to ≤ 1.5e−8 A (dispersion gone: the misleading integrator)."""
    verlet, _, string = _magic_step_run()
    assert np.max(np.abs(verlet - string)) <= 1.5e-8


def test_exact_chain_keeps_its_dispersion_at_the_magic_step_case():
    """N = 32, σ = 0.05, t = 2: the page's engine (DST) deviates from the string by ≥ 0.4 A (measured 0.488)."""
    _, exact, string = _magic_step_run()
    assert np.max(np.abs(exact - string)) >= 0.4


def test_exact_chain_agrees_with_a_dense_reference_at_the_magic_step_case():
    """N = 32, σ = 0.05, t = 2: DST vs DOP853 (rtol 1e−12) within 1e−9 A — the dispersion is real."""
    u0, v0 = initial_state(positions(32), 0.05, RIGHT_MOVING, amplitude=1.0)
    dense = integrate_ivp(u0, v0, 2.0, "DOP853", rtol=1e-12, atol=1e-14)
    exact, _ = chain_motion(32, 0.05, 2.0, RIGHT_MOVING, amplitude=1.0)
    assert dense.status == 0 and np.max(np.abs(dense.u[-1] - exact)) <= 1e-9


@pytest.mark.parametrize("factor", [1.0, 1.01, 1.1], ids=["1.00x", "1.01x", "1.1x"])
@pytest.mark.parametrize("n", [1, 2, 64], ids=["N=1", "N=2", "N=64"])
def test_verlet_refuses_steps_at_or_past_the_stability_limit(n, factor):
    """Δt ≥ 2/ω_N raises ValueError naming the limit (it would blow up: E/E0 > 1e6 within 20 steps)."""
    u0, v0 = initial_state(positions(n), 0.05, RIGHT_MOVING, amplitude=1.0)
    with pytest.raises(ValueError, match="stability limit"):
        velocity_verlet(u0, v0, factor * stability_limit(n), 10)


@pytest.mark.parametrize("n", [1, 2, 64], ids=["N=1", "N=2", "N=64"])
def test_verlet_just_inside_the_limit_stays_bounded(n):
    """Δt = 0.99 × 2/ω_N, 4000 steps: the largest |u| of the last 2000 steps is within 1 % of the first 2000's."""
    u0, v0 = initial_state(positions(n), 0.05, RIGHT_MOVING, amplitude=1.0)
    run = velocity_verlet(u0, v0, 0.99 * stability_limit(n), 4000, every=1)
    peaks = np.max(np.abs(run.u), axis=-1)
    assert np.all(np.isfinite(peaks)) and peaks[2001:].max() <= 1.01 * peaks[:2001].max()


@pytest.mark.parametrize(
    "n, at_least", [(1, 10.0), (2, 5.0), (64, 1.005)], ids=["N=1:E/E0>10", "N=2:E/E0>5", "N=64:E/E0>1.005"]
)
def test_verlet_energy_near_the_limit_is_not_conserved(n, at_least):
    """Δt = 0.99 × 2/ω_N: the true energy of the VV state reaches ≥ `at_least` × E0 (measured 50, 24, 1.016)."""
    u0, v0 = initial_state(positions(n), 0.05, RIGHT_MOVING, amplitude=1.0)
    run = velocity_verlet(u0, v0, 0.99 * stability_limit(n), 2000, every=1)
    assert np.max(energy(run.u, run.v)) / energy(u0, v0) >= at_least


def test_verlet_error_falls_as_the_square_of_the_step():
    """N = 64, t = 2: err(ν = 0.1)/err(ν = 0.05) in [3.6, 4.4] (VV is second order; measured 4.0)."""
    n = 64
    a = spacing(n)
    u0, v0 = initial_state(positions(n), 0.05, RIGHT_MOVING, amplitude=1.0)
    exact, _ = chain_motion(n, 0.05, 2.0, RIGHT_MOVING, amplitude=1.0)
    errors = [
        np.max(np.abs(velocity_verlet(u0, v0, nu * a, int(round(2.0 / (nu * a)))).u[-1] - exact)) for nu in (0.1, 0.05)
    ]
    assert 3.6 <= errors[0] / errors[1] <= 4.4


@pytest.mark.parametrize(
    "method, rtol, bound",
    [("RK45", 1e-6, 1e-5), ("DOP853", 1e-6, 5e-6), ("DOP853", 1e-9, 5e-9)],
    ids=["RK45-rtol1e-6:err<1e-5", "DOP853-rtol1e-6:err<5e-6", "DOP853-rtol1e-9:err<5e-9"],
)
def test_ivp_integrators_reach_their_tolerance_and_count_evaluations(method, rtol, bound):
    """N = 64, t = 2: max|u − u_DST|/A below `bound` (measured 1.2e−6, 4.5e−7, 3.4e−10), with nfev reported."""
    u0, v0 = initial_state(positions(64), 0.05, RIGHT_MOVING, amplitude=1.0)
    run = integrate_ivp(u0, v0, 2.0, method, rtol=rtol)
    exact, _ = chain_motion(64, 0.05, 2.0, RIGHT_MOVING, amplitude=1.0)
    assert run.status == 0 and run.evaluations > 100
    assert np.max(np.abs(run.u[-1] - exact)) <= bound


def test_verlet_counts_one_force_evaluation_per_step():
    """VV reports steps + 1 force evaluations (the first one primes the kick)."""
    u0, v0 = initial_state(positions(8), 0.05, RIGHT_MOVING, amplitude=1.0)
    run = velocity_verlet(u0, v0, 0.5 * spacing(8), 40)
    assert (run.steps, run.evaluations) == (40, 41)


# --- effects: each against the dense exponential, and its vanishing limit ----------------------------------------

EFFECT_TERMS = [
    pytest.param(Terms(ends="free"), id="free-ends"),
    pytest.param(Terms(ends="periodic"), id="periodic"),
    pytest.param(Terms(gamma=3.0), id="damped-gamma=3"),
    pytest.param(Terms(gamma=30.0), id="damped-gamma=30-some-modes-overdamped"),
    pytest.param(Terms(omega0=5.0), id="onsite-spring-omega0=5"),
    pytest.param(Terms(ends="free", gamma=3.0, omega0=5.0), id="all-three"),
]


@pytest.mark.parametrize("launch", LAUNCHES)
@pytest.mark.parametrize("n", [1, 2, 8], ids=["N=1", "N=2", "N=8"])
@pytest.mark.parametrize("terms", EFFECT_TERMS)
def test_effects_match_dense_expm(terms, n, launch):
    """Each effect's modal solution vs expm of its dense 2N×2N system at t = 0.37 and 2: ≤ 1e−11 of max|state0|."""
    for t in (0.37, 2.0):
        u_ref, v_ref, u0, v0 = _expm_state(n, t, terms, launch)
        u, v = evolve(u0, v0, t, terms)
        scale = max(np.max(np.abs(u0)), np.max(np.abs(v0)))
        assert np.max(np.abs(u - u_ref)) <= 1e-11 * scale and np.max(np.abs(v - v_ref)) <= 1e-11 * scale


def test_free_single_mass_drifts_rigidly():
    """Free ends, N = 1: no spring acts, so u(t) = u0 + v0·t exactly (the ω = 0 mode by t·sinc)."""
    u0, v0 = np.array([[0.2]]), np.array([[-0.7]])
    u, v = evolve(u0, v0, 3.0, Terms(ends="free"))
    assert u[0, 0] == pytest.approx(0.2 - 2.1, abs=4 * EPS) and v[0, 0] == -0.7


def _critical_mode_state(gamma_factor: float):
    """N = 1 chain (ω = 2√2 c/a) with γ = factor × 2ω, at t = 0.9: u, v."""
    omega = mode_frequencies(1)[0]
    u0, v0 = np.array([[0.3]]), np.array([[1.1]])
    return evolve(u0, v0, 0.9, Terms(gamma=gamma_factor * 2 * omega))


@pytest.mark.parametrize(
    "side",
    [1 - 1e-13, 1 + 1e-13, 1 - 4 * EPS, 1 + 4 * EPS],
    ids=["below-1e-13", "above-1e-13", "below-4eps", "above-4eps"],
)
def test_damping_is_continuous_across_critical(side):
    """ω_n = γ/2: the under- and overdamped branches meet the critical value within 1e−12 rel (u and v)."""
    critical, near = _critical_mode_state(1.0), _critical_mode_state(side)
    for exact, value in zip(critical, near):
        assert abs(value[0, 0] - exact[0, 0]) <= 1e-12 * abs(exact[0, 0])


def test_critically_damped_mode_is_the_closed_form():
    """γ = 2ω: u = e^{−γt/2}[u0(1 + γt/2) + v0 t] within 4ε rel (S evaluated as t·sinc at ω_d = 0)."""
    omega = mode_frequencies(1)[0]
    gamma, t = 2 * omega, 0.9
    u, _ = _critical_mode_state(1.0)
    exact = np.exp(-gamma * t / 2) * (0.3 * (1 + gamma * t / 2) + 1.1 * t)
    assert abs(u[0, 0] - exact) <= 4 * EPS * abs(exact)


def test_heavily_overdamped_chain_stays_finite_at_long_times():
    """γ = 1e4, t = 1e3: no overflow (0·∞) — every value finite and within the initial amplitude."""
    u0, v0 = initial_state(positions(16), 0.05, RIGHT_MOVING, amplitude=1.0)
    u, v = evolve(u0, v0, 1e3, Terms(gamma=1e4))
    assert np.all(np.isfinite(u)) and np.all(np.isfinite(v)) and np.max(np.abs(u)) <= np.max(np.abs(u0))


@pytest.mark.parametrize(
    "terms, bound",
    [
        pytest.param(Terms(gamma=1e-12), 1e-11, id="gamma=1e-12:1e-11"),
        pytest.param(Terms(omega0=1e-6), 1e-11, id="omega0=1e-6:1e-11"),
    ],
)
def test_effects_vanish_in_their_limit(terms, bound):
    """γ → 0 and ω0 → 0 recover the bare chain: N = 64, t = 2, |Δu| ≤ bound × max|u0| (the change is O(γt),
    O(ω0²t²))."""
    bare, _ = chain_motion(64, 0.05, 2.0, RIGHT_MOVING, amplitude=1.0)
    with_term, _ = chain_motion(64, 0.05, 2.0, RIGHT_MOVING, terms, amplitude=1.0)
    assert np.max(np.abs(with_term - bare)) <= bound


@pytest.mark.parametrize("ends", ["free", "periodic"])
def test_other_ends_agree_with_fixed_before_the_pulse_reaches_a_wall(ends):
    """Boundary's vanishing limit: at t = 0.1, N = 512, every chain matches the unreflected pulse to ≤ 1e−3 A."""
    x = np.linspace(0.1, 0.6, 51)
    travelling, _ = initial_state(x - 0.1, 0.05, RIGHT_MOVING, amplitude=1.0)
    u, _ = chain_motion(512, 0.05, 0.1, RIGHT_MOVING, Terms(ends=ends), amplitude=1.0)
    assert np.max(np.abs(np.interp(x, positions(512, ends), u) - travelling)) <= 1e-3


@pytest.mark.parametrize("ends", ["free", "periodic"])
def test_other_ends_converge_to_their_string(ends):
    """Free ends and the ring also converge as a²: dev(256)/dev(512) in [3.6, 4.4] at σ = 0.05, t = 2."""
    terms = Terms(ends=ends)
    ratio = deviation(256, 0.05, 2.0, RIGHT_MOVING, terms) / deviation(512, 0.05, 2.0, RIGHT_MOVING, terms)
    assert 3.6 <= ratio <= 4.4, f"ratio {ratio:.3f}"


@pytest.mark.parametrize(
    "terms",
    [
        pytest.param(Terms(ends="free"), id="free"),
        pytest.param(Terms(ends="periodic"), id="periodic"),
        pytest.param(Terms(omega0=20.0), id="omega0=20"),
    ],
)
def test_conservative_effects_conserve_energy(terms):
    """Undamped effects keep E(t)/E(0) − 1 within 1e−12 for N = 64 up to t = 1e2."""
    u, v = chain_motion(64, 0.05, np.array([0.0, 0.37, 2.0, 1e2]), RIGHT_MOVING, terms, amplitude=1.0)
    e = energy(u, v, terms)
    assert np.max(np.abs(e / e[0] - 1)) <= 1e-12


def test_damped_energy_decays_monotonically():
    """γ = 2: E(t) never increases (dE/dt = −mγΣu̇² ≤ 0), sampled at 101 times to t = 2."""
    t = np.linspace(0, 2, 101)
    u, v = chain_motion(64, 0.05, t, RIGHT_MOVING, Terms(gamma=2.0), amplitude=1.0)
    assert np.all(np.diff(energy(u, v, Terms(gamma=2.0))) <= 1e-14)


# --- the model's readouts and layers ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "output, expected",
    [
        ("a", "0.015385"),
        ("m", "0.015385"),
        ("kappa", "65.000"),
        ("c", "1.000"),
        ("omega_max", "130.0"),
        ("sigma_over_a", "3.25"),
        ("dev", "0.0564"),
        ("E_chain", "17.620"),
        ("E_continuum", "17.725"),
        ("E_chain_mJ", "1.762"),
    ],
    ids=lambda v: v if isinstance(v, str) and not v[0].isdigit() else None,
)
def test_defaults_display_the_specified_readouts(output, expected):
    """At N = 64, σ = 0.05, t = 0.5 the page shows docs/physics/chain.md's values."""
    value = float(_evaluate([output])[output])
    assert fmt(value, Chain.output(output).decimals) == expected


@pytest.mark.parametrize("n", [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256])
def test_wave_speed_is_independent_of_n(n):
    """a√(κ/m) from the model's own a, m and κ equals c = 1 within 2ε at every N stop."""
    out = _evaluate(["a", "m", "kappa"], N=n)
    assert abs(out["a"] * np.sqrt(out["kappa"] / out["m"]) - 1.0) <= 2 * EPS


def test_single_mass_is_under_resolved():
    """N = 1, σ = 0.05: σ/a = 0.10, status under-resolved, and the dot starts at e^{−8} A = 3.4e−4 A (flat)."""
    out = _evaluate(["sigma_over_a", "status", "u_dots"], N=1, t=0.0)
    assert fmt(float(out["sigma_over_a"]), 2) == "0.10" and int(out["status"]) == UNDER_RESOLVED
    assert out["u_dots"][0] == pytest.approx(np.exp(-8), rel=4 * EPS) and np.all(np.isnan(out["u_dots"][1:]))


def test_default_chain_is_resolved():
    """N = 64, σ = 0.05: status resolved."""
    assert int(_evaluate(["status"])["status"]) == RESOLVED


def test_dots_layer_is_the_exact_solution():
    """u_dots equals chain_motion (per A) at the first N entries and is NaN-padded to 256."""
    out = _evaluate(["u_dots", "x_dots"], N=12, t=1.3, launch=SPLIT)
    u, _ = chain_motion(12, 0.05, 1.3, SPLIT, amplitude=1.0)
    assert np.array_equal(out["u_dots"][:12], u) and np.all(np.isnan(out["u_dots"][12:]))
    assert np.allclose(out["x_dots"][:12], np.arange(1, 13) / 13, rtol=0, atol=4 * EPS)


def test_chain_energy_approaches_the_string_energy():
    """σ = 0.05: E_chain(N = 256) is within 1e−3 rel of √π/(2σ) (the string's value)."""
    out = _evaluate(["E_chain", "E_continuum"], N=256)
    assert abs(out["E_chain"] / out["E_continuum"] - 1) <= 1e-3


def test_damping_effect_in_the_model_decays_the_energy_readout():
    """With onsite_damping at γ = 1: E_now(t = 2) = E(0)·(≤ 1) and equals the engine's damped energy."""
    out = _evaluate(["E_now", "E_chain"], effects=("onsite_damping",), gamma=1.0, t=2.0)
    u, v = chain_motion(64, 0.05, 2.0, RIGHT_MOVING, Terms(gamma=1.0), amplitude=1.0)
    assert out["E_now"] < out["E_chain"] and out["E_now"] == pytest.approx(
        float(energy(u, v, Terms(gamma=1.0))), rel=1e-14
    )


@pytest.mark.parametrize(
    "effect, inputs",
    [("onsite_damping", {"gamma": 0.0}), ("onsite_spring", {"omega0": 0.0}), ("boundary", {"ends": 0})],
    ids=["gamma=0", "omega0=0", "ends=fixed"],
)
def test_enabled_effects_at_their_neutral_value_change_nothing(effect, inputs):
    """Enabling an effect at γ = 0, ω0 = 0 or fixed ends gives bitwise the bare model's dots and dev."""
    bare = _evaluate(["u_dots", "dev"], t=1.1)
    with_effect = _evaluate(["u_dots", "dev"], effects=(effect,), t=1.1, **inputs)
    assert all(np.array_equal(bare[k], with_effect[k], equal_nan=True) for k in bare)


@pytest.mark.parametrize(
    "inputs",
    [{"N": 0.0}, {"N": 257.0}, {"sigma": 0.0}, {"sigma": 0.06}, {"t": -0.1}, {"N": float("nan")}, {"launch": 2.0}],
    ids=["N=0", "N=257", "sigma=0", "sigma>0.05", "t<0", "N=nan", "launch=2"],
)
def test_invalid_input_raises_naming_the_parameter(inputs):
    """Out-of-domain inputs raise ValueError naming the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        Chain().evaluate(inputs)


def test_unknown_ends_raise():
    """Terms refuses an unknown boundary, naming the parameter."""
    with pytest.raises(ValueError, match="`ends`"):
        Terms(ends="sticky")
