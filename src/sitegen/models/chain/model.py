"""I5: a chain of N masses between walls, solved exactly mode by mode, against the continuum string.

The linear chain m ü_j = κ(u_{j+1} − 2u_j + u_{j−1}) is diagonalised by a sine transform (fixed
ends, DST-I), a cosine transform (free ends, DCT-II) or an FFT (a ring), so any time t is reached
in O(N log N) with no time-step error. The dashed reference is d'Alembert's solution of the wave
equation with the matching reflections. Units: L = 1 m, c = 1 m/s, μ = 1 kg/m.
"""
from __future__ import annotations

import numpy as np
import scipy.fft

from ...physics.base import Model, Output, Param
from .integrators import dense_motion
from .modes import (  # noqa: F401 (the figure, the bench and the tests import these names from here)
    AMPLITUDE, BARE, CENTRE, CONTINUUM_POINTS, DENSITY, DRAWN_WALL, ENDS, LAUNCHES, LENGTH, MAX_N, PULSE_WAVENUMBERS,
    RESOLVED, RIGHT_MOVING, SPEED, SPLIT, UNDER_RESOLVED, Terms, cutoff_frequency, mass_and_stiffness, mode_frequencies,
    positions, spacing, wavenumbers,
)
from ...physics.numerics import Measurement, Numerics


# --- initial state, the transforms and the exact evolution -----------------------------------------------------


def initial_state(x, sigma, launch, amplitude: float = AMPLITUDE):
    """u(0) = A exp(−(x−x0)²/2σ²); u̇(0) = −c u0'(x) for a right-moving pulse, 0 for the split launch."""
    x, sigma, launch = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, sigma, launch)))
    u = amplitude * np.exp(-((x - CENTRE) ** 2) / (2 * sigma**2))
    v = np.where(launch == RIGHT_MOVING, SPEED * (x - CENTRE) / sigma**2 * u, 0.0)
    return u, v


def _forward(values: np.ndarray, ends: str) -> np.ndarray:
    if ends == "fixed":
        return scipy.fft.dst(values, type=1, axis=-1)
    if ends == "free":
        return scipy.fft.dct(values, type=2, axis=-1)
    return scipy.fft.fft(values, axis=-1)


def _inverse(coefficients: np.ndarray, ends: str) -> np.ndarray:
    if ends == "fixed":
        return scipy.fft.idst(coefficients, type=1, axis=-1)
    if ends == "free":
        return scipy.fft.idct(coefficients, type=2, axis=-1)
    return scipy.fft.ifft(coefficients, axis=-1).real  # ω(k) = ω(−k), so the result is real


def _oscillation(omega: np.ndarray, gamma: float, t: np.ndarray):
    """The decaying C(t) and S(t) of each mode: e^{−γt/2}·cos ω_d t and e^{−γt/2}·sin(ω_d t)/ω_d, ω_d² = ω² − γ²/4.

    S is sin(ω_d t)/ω_d, and t where ω_d = 0 (a rigid or critically damped mode); sin and cos of the
    same rounded phase keep each mode's energy exact at any t (t·sinc would round it differently). An overdamped
    mode (ω_d² < 0, rate r = |ω_d|) takes e^{−γt/2}·cosh rt and e^{−γt/2}·sinh(rt)/r, written with
    e^{(r − γ/2)t} so that they neither overflow nor lose digits; both join the others continuously.
    """
    if not gamma:
        phase = omega * t
        return np.cos(phase), _sine_over(phase, omega, t)
    return _damped_oscillation(omega, gamma, t)


def _damped_oscillation(omega: np.ndarray, gamma: float, t: np.ndarray):
    """C(t) and S(t) of `_oscillation` for γ > 0: the on-site damping term, composed only when enabled."""
    squared = omega**2 - gamma**2 / 4
    rate = np.sqrt(np.abs(squared))
    decay = np.exp(-gamma * t / 2)
    phase = rate * t
    under_c, under_s = decay * np.cos(phase), decay * _sine_over(phase, rate, t)
    over = squared < 0
    if not np.any(over):
        return under_c, under_s
    slowest = np.exp(-omega**2 / (gamma / 2 + rate) * t)  # e^{(r − γ/2)t}, with r − γ/2 = −ω²/(γ/2 + r)
    twice = 2 * np.where(over, phase, 0.0)
    shrink = np.divide(-np.expm1(-twice), twice, out=np.ones_like(twice), where=twice > 0)  # (1 − e^{−2rt})/(2rt)
    over_c, over_s = slowest * (1 + np.exp(-twice)) / 2, slowest * t * shrink
    return np.where(over, over_c, under_c), np.where(over, over_s, under_s)


def _sine_over(phase, frequency, t):
    """sin(phase)/frequency, or t where the frequency is 0 (its limit)."""
    phase, frequency = np.broadcast_arrays(phase, frequency)
    still = frequency == 0
    return np.where(still, t, np.sin(phase) / np.where(still, 1.0, frequency))


def evolve(u0: np.ndarray, v0: np.ndarray, t, terms: Terms = BARE, velocity: bool = True):
    """The exact u(t), u̇(t) of chains (last axis: the masses) from u(0), u̇(0), at times t (one per chain);
    u̇(t) is None unless `velocity` (it costs a transform)."""
    n = u0.shape[-1]
    t = np.asarray(t, float)[..., None]
    a, b = _forward(u0, terms.ends), _forward(v0, terms.ends)
    omega = mode_frequencies(n, terms)
    cos, sine = _oscillation(omega, terms.gamma, t)
    # Each mode obeys ä + γȧ + ω²a = 0: a C + (b + γa/2) S, and its velocity, from C' = −(γ/2)C − ω_d²S, S' = C − (γ/2)S.
    half = terms.gamma / 2
    u = a * cos + (b + half * a) * sine
    if not velocity:
        return _inverse(u, terms.ends), None
    v = b * cos - (omega**2 * a + half * b) * sine
    return _inverse(u, terms.ends), _inverse(v, terms.ends)


def chain_motion(n: int, sigma, t, launch, terms: Terms = BARE, amplitude: float = AMPLITUDE, velocity: bool = True):
    """u_j(t) and u̇_j(t) (None unless `velocity`) of an N-mass chain released as the Gaussian pulse, for arrays of (σ, t, launch)."""
    sigma, t, launch = np.broadcast_arrays(*(np.asarray(v, float) for v in (sigma, t, launch)))
    u0, v0 = initial_state(positions(n, terms.ends), sigma[..., None], launch[..., None], amplitude)
    return evolve(u0, v0, t, terms, velocity)


def energy(u: np.ndarray, v: np.ndarray, terms: Terms = BARE) -> np.ndarray:
    """E = ½m Σu̇² + ½κ Σ(u_{j+1} − u_j)² (+ ½mω0² Σu²), with the springs to the walls when the ends are fixed."""
    n = u.shape[-1]
    m, kappa = mass_and_stiffness(n, terms.ends)
    if terms.ends == "fixed":
        stretch = np.diff(u, axis=-1, prepend=0.0, append=0.0)
    elif terms.ends == "free":
        stretch = np.diff(u, axis=-1)
    else:
        stretch = np.roll(u, -1, axis=-1) - u
    kinetic = 0.5 * m * np.sum(v**2, axis=-1)
    potential = 0.5 * kappa * np.sum(stretch**2, axis=-1)
    onsite = 0.5 * m * terms.omega0**2 * np.sum(u**2, axis=-1) if terms.omega0 else 0.0
    return kinetic + potential + onsite


# --- the continuum string --------------------------------------------------------------------------------------


def _pulse_images(s, sigma, period: float, amplitude: float):
    """Σ_k u0(s − k·period): the initial pulse repeated with the period (three images suffice for σ ≤ 0.05 L)."""
    # Reduce s first (np.mod is exact), then measure from x0: s and s ± P then round identically.
    shifted = np.mod(s, period) - CENTRE
    shifted = np.where(shifted >= period / 2, shifted - period, shifted)  # the image of x0 nearest s
    spread = -2 * sigma**2  # x/(−2σ²) is −(x/2σ²) exactly: one pass fewer than negating
    total = None
    for k in (-1, 0, 1):  # u0 of each image, in place: the same floats as A exp(−(s − kP)²/2σ²)
        image = shifted - k * period if k else shifted * shifted
        if k:
            image *= image
        image /= spread
        np.exp(image, out=image)
        if amplitude != 1.0:
            image *= amplitude
        if total is None:  # the images add in order, −P first
            total = image
        else:
            total += image
    return total


def continuum(x, t, sigma, launch, ends: str = "fixed", amplitude: float = AMPLITUDE):
    """d'Alembert's u_c(x, t) for the same launch: odd reflections at fixed ends, even at free ends, or a ring."""
    x, t, sigma, launch = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, t, sigma, launch)))
    period = LENGTH if ends == "periodic" else 2 * LENGTH
    sign = {"fixed": -1.0, "free": 1.0, "periodic": 0.0}[ends]

    splits = launch != RIGHT_MOVING  # only the split launch needs the images moving left

    def images(s, where=...):
        return _pulse_images(s, sigma[where], period, amplitude)

    # The launches share their images: x − ct, and −x − ct = −(x + ct) exactly (rounding is symmetric).
    behind, ahead = x - SPEED * t, x + SPEED * t
    moving = images(behind)
    if not sign:  # a ring needs no reflections
        right, split = moving, 0.5 * (moving[splits] + images(ahead[splits], splits))
    else:  # the extension of u0 beyond [0, L] that the ends impose, for each travelling half
        mirrored = images(-ahead)
        right = moving + sign * mirrored
        split = 0.5 * ((moving[splits] + sign * images(-behind[splits], splits))
                       + (images(ahead[splits], splits) + sign * mirrored[splits]))
    right[splits] = split
    return right


def continuum_energy(sigma, launch):
    """The string's energy per μc²A²: √π/(2σ) for the right-moving pulse, half of that (all potential) when split."""
    sigma, launch = np.broadcast_arrays(np.asarray(sigma, float), np.asarray(launch, float))
    return np.sqrt(np.pi) / (2 * sigma) * np.where(launch == RIGHT_MOVING, 1.0, 0.5)


def deviation(n: int, sigma, t, launch, terms: Terms = BARE):
    """max_j |u_j − u_c(x_j)| / A: how far the chain is from the continuum string (the physics error)."""
    return _deviation(chain_motion(n, sigma, t, launch, terms, amplitude=1.0, velocity=False)[0], n, sigma, t, launch, terms)


def _deviation(u: np.ndarray, n: int, sigma, t, launch, terms: Terms):
    """`deviation` of displacements u/A already computed by chain_motion."""
    x = positions(n, terms.ends)
    sigma, t, launch = np.broadcast_arrays(*(np.asarray(v, float) for v in (sigma, t, launch)))
    reference = continuum(x, t[..., None], sigma[..., None], launch[..., None], terms.ends, amplitude=1.0)
    return np.max(np.abs(u - reference), axis=-1)


# --- the model the page tabulates -------------------------------------------------------------------------------


def _per_chain(groups, compute, width: int = 0) -> np.ndarray:
    """compute(n, terms, where) on the points of each distinct chain, filling an array (+ width) over the points."""
    counts, terms_of, shape = groups
    out = np.full(shape + ((width,) if width else ()), np.nan)
    for (n, *key), where in _distinct(counts, terms_of):
        out[where] = compute(n, Terms(ENDS[key[0]], key[1], key[2]), where)
    return out


def _distinct(counts: np.ndarray, terms_of: np.ndarray):
    """((N, ends, γ, ω0), mask) for each distinct chain among the points."""
    keys = np.column_stack([counts.ravel(), terms_of.reshape(-1, 3)])
    unique, inverse = np.unique(keys, axis=0, return_inverse=True)
    for index, key in enumerate(unique):
        yield (int(key[0]), int(key[1]), float(key[2]), float(key[3])), (inverse.ravel() == index).reshape(counts.shape)


def _padded(values: np.ndarray) -> np.ndarray:
    return np.concatenate([values, np.full(values.shape[:-1] + (MAX_N - values.shape[-1],), np.nan)], axis=-1)


class Chain(Model):
    """N masses on springs between walls, released as a Gaussian pulse; exact modal solution vs the string."""

    name = "chain"
    title = "The continuum limit: chain of N masses"
    params = (
        Param("N", "N", "", 64.0, lo=1.0, hi=float(MAX_N), description="number of masses (a whole number; fractions round)"),
        Param("sigma", "σ", "m", 0.05, lo=0.0, hi=0.05, lo_open=True, description="pulse width (≤ L/20 keeps it off the walls)"),
        Param("t", "t", "s", 0.5, lo=0.0, description="time since release"),
        Param.choice("launch", "launch", LAUNCHES, "right-moving", description="pulse moving right, or released at rest (splits in two)"),
        Param.choice("ends", "ends", ENDS, "fixed", description="how the chain's ends are held").with_effect("boundary"),
        Param("gamma", "γ", "1/s", 0.0, lo=0.0, description="on-site damping rate").with_effect("onsite_damping"),
        Param("omega0", "ω<sub>0</sub>", "rad/s", 0.0, lo=0.0, description="on-site spring frequency").with_effect("onsite_spring"),
    )
    # Effect parameters count only when the scene enables their effect (the build never varies them otherwise).
    _motion = ("N", "sigma", "t", "launch", "ends", "gamma", "omega0")
    _energy = ("N", "sigma", "launch", "ends", "omega0")
    outputs = (
        Output("a", "spacing a", "m", ("N", "ends"), decimals=6),
        Output("m", "mass m = μa", "kg", ("N", "ends"), decimals=6),
        Output("kappa", "spring κ = μc²/a", "N/m", ("N", "ends"), decimals=3),
        Output("c", "c = a√(κ/m)", "m/s", (), decimals=3),
        Output("omega_max", "cutoff ω<sub>max</sub> = 2√(κ/m)", "rad/s", ("N", "ends", "omega0"), decimals=1),
        Output("sigma_over_a", "σ/a", "", ("N", "sigma", "ends"), decimals=2),
        # Both span decades (a one-mass chain holds 10⁻⁴ of the energy; at t = 0 the deviation is 10⁻⁸):
        # four significant digits; below the solve's tolerance of 1e-9 a value is zero.
        Output("dev", "max |u<sub>j</sub> − u<sub>c</sub>|/A", "", _motion, decimals=4, digits=4, floor=1e-9),
        Output("E_chain", "E<sub>chain</sub> (conserved)", "μc²A²", _energy, decimals=3, digits=4, floor=1e-9),
        Output("E_continuum", "E<sub>string</sub>", "μc²A²", ("sigma", "launch"), decimals=3),
        Output("E_chain_mJ", "E<sub>chain</sub> at A = 1 cm", "mJ", _energy, decimals=3),
        Output("E_now", "E<sub>chain</sub>(t), damped", "μc²A²", _motion, decimals=3, effect="onsite_damping"),
        Output("status", "status", "", ("N", "sigma", "ends"), labels=("resolved (σ/a ≥ 1)", "pulse under-resolved (σ/a < 1)")),
        # Layer geometry: the dots in units of A (= cm at A = 1 cm), 1/100 A at about a pixel.
        Output("x_dots", "x<sub>j</sub>", "m", ("N", "ends"), decimals=3, size=MAX_N, ragged=True),
        Output("u_dots", "u<sub>j</sub>/A", "", _motion, decimals=2, size=MAX_N, ragged=True),
        Output("u_continuum", "u<sub>c</sub>/A", "", ("sigma", "t", "launch", "ends"), decimals=2, size=CONTINUUM_POINTS),
        # The dispersion inset is log–log, so its vertices are log10 k and log10 ω (0.01 decade ≈ 0.5 px).
        Output("log_k", "log<sub>10</sub> k<sub>n</sub>", "", ("N", "ends"), decimals=2, size=MAX_N, ragged=True),
        Output("log_omega", "log<sub>10</sub> ω<sub>n</sub>", "", ("N", "ends", "omega0"), decimals=2, size=MAX_N, ragged=True),
        Output("log_k_pulse", "log<sub>10</sub>(3/σ)", "", ("sigma",), decimals=2),
        # The walls as drawn when the ends can change: DRAWN_WALL thick when fixed, nothing otherwise.
        Output("wall_left", "figure: outer face of the left wall", "m", ("ends",), decimals=3, effect="boundary"),
        Output("wall_right", "figure: outer face of the right wall", "m", ("ends",), decimals=3, effect="boundary"),
    )
    effects = ("boundary", "onsite_damping", "onsite_spring")
    # physics.md §11.1: the exact modal solution beats every integrator by 25–4000×; time steppers are
    # kept for comparison only (integrators.py). Its error is the rounding of the transforms.
    numerics = Numerics("DST", tolerance=1e-9)
    methods = {"DST": {}}
    error_metric = "max |Δuⱼ|/A at the frame"
    reports = {"chain": "the chain's work–precision diagram"}

    def measure_error(self, values, effects) -> Measurement:
        """The modal solution at one stop against the dense eigendecomposition (or expm when damped)."""
        x = {k: np.asarray(v, float) for k, v in {**self.defaults(), **values}.items()}
        (n,), terms_of, _ = _groups({k: v[None] for k, v in x.items()}, frozenset(effects))
        terms = Terms(ENDS[int(terms_of[0, 0])], float(terms_of[0, 1]), float(terms_of[0, 2]))
        u, _ = chain_motion(int(n), x["sigma"], x["t"], x["launch"], terms, amplitude=1.0, velocity=False)
        u0, v0 = initial_state(positions(int(n), terms.ends), x["sigma"], x["launch"], amplitude=1.0)
        reference, _ = dense_motion(u0, v0, float(x["t"]), terms)
        name = "the dense chain's eigenmodes (numpy eigh)" if not terms.gamma else "the dense chain's matrix exponential (scipy expm)"
        return Measurement(float(np.max(np.abs(u - reference))), 0, "exact DST", name)

    def _evaluate(self, x, wanted, effects):
        N, sigma, t, launch = (x[k] for k in self._motion[:4])
        groups = _groups(x, effects)
        ends = groups[1][..., 0]
        a = np.where(ends == ENDS.index("fixed"), spacing(np.rint(N), "fixed"), spacing(np.rint(N), "free"))

        motions = {}  # the deviation and the drawn dots read the same motion of each chain: solved once
        velocity = "E_now" in wanted  # the only output that reads u̇(t)

        def motion(n, terms, w):
            if (n, terms) not in motions:
                motions[n, terms] = chain_motion(n, sigma[w], t[w], launch[w], terms, 1.0, velocity)
            return motions[n, terms]

        def modes(pick):
            return lambda: _per_chain(groups, lambda n, terms, w: _padded(np.log10(_sorted_modes(n, terms)[pick])), MAX_N)

        formulas = {
            "a": lambda: a,
            "m": lambda: DENSITY * a,
            "kappa": lambda: DENSITY * SPEED**2 / a,
            "c": lambda: np.full(N.shape, SPEED),  # a√(κ/m) = c by construction (tested separately)
            "omega_max": lambda: np.hypot(2 * SPEED / a, groups[1][..., 2]),
            "sigma_over_a": lambda: sigma / a,
            "dev": lambda: _per_chain(groups, lambda n, terms, w: _deviation(motion(n, terms, w)[0], n, sigma[w], t[w], launch[w], terms)),
            "E_chain": lambda: _per_chain(groups, lambda n, terms, w: _initial_energy(n, sigma[w], launch[w], terms, 1.0)),
            "E_continuum": lambda: continuum_energy(sigma, launch),
            "E_chain_mJ": lambda: 1e3 * _per_chain(groups, lambda n, terms, w: _initial_energy(n, sigma[w], launch[w], terms, AMPLITUDE)),
            "E_now": lambda: _per_chain(groups, lambda n, terms, w: energy(*motion(n, terms, w), terms)),
            "status": lambda: np.where(sigma / a < 1, UNDER_RESOLVED, RESOLVED),
            "x_dots": lambda: _per_chain(groups, lambda n, terms, w: _padded(positions(n, terms.ends)), MAX_N),
            "u_dots": lambda: _per_chain(groups, lambda n, terms, w: _padded(motion(n, terms, w)[0]), MAX_N),
            "u_continuum": lambda: _continuum_curves(t, sigma, launch, ends),
            "log_k": modes(0),
            "log_omega": modes(1),
            "log_k_pulse": lambda: np.log10(PULSE_WAVENUMBERS / sigma),
            "wall_left": lambda: np.where(ends == ENDS.index("fixed"), -DRAWN_WALL, 0.0),
            "wall_right": lambda: np.where(ends == ENDS.index("fixed"), LENGTH + DRAWN_WALL, LENGTH),
        }
        return {name: formulas[name]() for name in wanted}


def _groups(x, effects: frozenset[str]):
    """Each point's N and its (ends, γ, ω0), with a term that is not enabled held at its neutral value."""
    N = x["N"]
    zero = np.zeros(N.shape)
    terms_of = np.stack([
        x["ends"] if "boundary" in effects else zero,
        x["gamma"] if "onsite_damping" in effects else zero,
        x["omega0"] if "onsite_spring" in effects else zero,
    ], axis=-1)
    return np.rint(N).astype(int), terms_of, N.shape


def _initial_energy(n: int, sigma, launch, terms: Terms, amplitude: float):
    """The chain's energy at release, per μc²A² when amplitude = 1 (the exact motion keeps it when undamped)."""
    u, v = initial_state(positions(n, terms.ends), sigma[..., None], launch[..., None], amplitude)
    return energy(u, v, terms)


def _continuum_curves(t, sigma, launch, ends):
    """The string u_c/A on the fixed x points, for each point's time, width, launch and ends."""
    out = np.empty(t.shape + (CONTINUUM_POINTS,))
    for code in np.unique(ends):
        where = ends == code
        out[where] = continuum(continuum_grid(), t[where][..., None], sigma[where][..., None], launch[where][..., None], ENDS[int(code)], 1.0)
    return out


def continuum_grid() -> np.ndarray:
    """The fixed x points on which the dashed continuum curve is drawn."""
    return np.linspace(0.0, LENGTH, CONTINUUM_POINTS)


def _sorted_modes(n: int, terms: Terms):
    """(k, ω) of the modes with k > 0, by increasing k (the dispersion relation's points; no rigid mode)."""
    k, omega = wavenumbers(n, terms.ends), mode_frequencies(n, terms)
    keep = k > 0
    order = np.argsort(k[keep], kind="stable")
    return k[keep][order], omega[keep][order]
