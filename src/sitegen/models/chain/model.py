"""I5: a chain of N masses between walls, solved exactly mode by mode, against the continuum string.

The exact motion and d'Alembert's string are computed in motion.py; the model tabulates the chain's
readouts, its masses over the dashed string and its dispersion relation. Units: L = 1 m, c = 1 m/s, μ = 1 kg/m.
"""

from __future__ import annotations

import numpy as np

from ...physics.base import Model, Output, Param
from ...physics.numerics import Measurement, Numerics
from .bench import RoundTrip
from .integrators import dense_motion
from .modes import (
    AMPLITUDE,
    CONTINUUM_POINTS,
    DENSITY,
    DRAWN_WALL,
    ENDS,
    LAUNCHES,
    LENGTH,
    MAX_N,
    PULSE_WAVENUMBERS,
    RESOLVED,
    SPEED,
    UNDER_RESOLVED,
    Terms,
    mode_frequencies,
    positions,
    spacing,
    wavenumbers,
)
from .motion import chain_motion, continuum, continuum_energy, deviation_of, energy, initial_state

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
        Param(
            "N",
            "N",
            "",
            64.0,
            lo=1.0,
            hi=float(MAX_N),
            description="number of masses (a whole number; fractions round)",
        ),
        Param(
            "sigma",
            "σ",
            "m",
            0.05,
            lo=0.0,
            hi=0.05,
            lo_open=True,
            description="pulse width (≤ L/20 keeps it off the walls)",
        ),
        Param("t", "t", "s", 0.5, lo=0.0, description="time since release"),
        Param.choice(
            "launch",
            "launch",
            LAUNCHES,
            "right-moving",
            description="pulse moving right, or released at rest (splits in two)",
        ),
        Param.choice("ends", "ends", ENDS, "fixed", description="how the chain's ends are held").with_effect(
            "boundary"
        ),
        Param("gamma", "γ", "1/s", 0.0, lo=0.0, description="on-site damping rate").with_effect("onsite_damping"),
        Param("omega0", "ω<sub>0</sub>", "rad/s", 0.0, lo=0.0, description="on-site spring frequency").with_effect(
            "onsite_spring"
        ),
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
        Output(
            "status",
            "status",
            "",
            ("N", "sigma", "ends"),
            labels=("resolved (σ/a ≥ 1)", "pulse under-resolved (σ/a < 1)"),
        ),
        # Layer geometry: the dots in units of A (= cm at A = 1 cm), 1/100 A at about a pixel.
        Output("x_dots", "x<sub>j</sub>", "m", ("N", "ends"), decimals=3, size=MAX_N, ragged=True),
        Output("u_dots", "u<sub>j</sub>/A", "", _motion, decimals=2, size=MAX_N, ragged=True),
        Output(
            "u_continuum", "u<sub>c</sub>/A", "", ("sigma", "t", "launch", "ends"), decimals=2, size=CONTINUUM_POINTS
        ),
        # The dispersion inset is log–log, so its vertices are log10 k and log10 ω (0.01 decade ≈ 0.5 px).
        Output("log_k", "log<sub>10</sub> k<sub>n</sub>", "", ("N", "ends"), decimals=2, size=MAX_N, ragged=True),
        Output(
            "log_omega",
            "log<sub>10</sub> ω<sub>n</sub>",
            "",
            ("N", "ends", "omega0"),
            decimals=2,
            size=MAX_N,
            ragged=True,
        ),
        Output("log_k_pulse", "log<sub>10</sub>(3/σ)", "", ("sigma",), decimals=2),
        # The walls as drawn when the ends can change: DRAWN_WALL thick when fixed, nothing otherwise.
        Output("wall_left", "figure: outer face of the left wall", "m", ("ends",), decimals=3, effect="boundary"),
        Output("wall_right", "figure: outer face of the right wall", "m", ("ends",), decimals=3, effect="boundary"),
    )
    effects = ("boundary", "onsite_damping", "onsite_spring")
    # docs/physics/chain.md: the exact modal solution beats every integrator by 25–4000×; time steppers are
    # kept for comparison only (integrators.py). Its error is the rounding of the transforms.
    numerics = Numerics("DST", tolerance=1e-9)
    methods = {"DST": {}}
    error_metric = "max |Δuⱼ|/A at the frame"
    experiments = {"chain-round-trip": RoundTrip()}  # the integrators kept for comparison (bench.py)

    def measure_error(self, values, effects) -> Measurement:
        """The modal solution at one stop against the dense eigendecomposition (or expm when damped)."""
        x = {k: np.asarray(v, float) for k, v in {**self.defaults(), **values}.items()}
        (n,), terms_of, _ = _groups({k: v[None] for k, v in x.items()}, frozenset(effects))
        terms = Terms(ENDS[int(terms_of[0, 0])], float(terms_of[0, 1]), float(terms_of[0, 2]))
        u, _ = chain_motion(int(n), x["sigma"], x["t"], x["launch"], terms, amplitude=1.0, velocity=False)
        u0, v0 = initial_state(positions(int(n), terms.ends), x["sigma"], x["launch"], amplitude=1.0)
        reference, _ = dense_motion(u0, v0, float(x["t"]), terms)
        name = (
            "the dense chain's eigenmodes (numpy eigh)"
            if not terms.gamma
            else "the dense chain's matrix exponential (scipy expm)"
        )
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
            return lambda: _per_chain(
                groups, lambda n, terms, w: _padded(np.log10(_sorted_modes(n, terms)[pick])), MAX_N
            )

        formulas = {
            "a": lambda: a,
            "m": lambda: DENSITY * a,
            "kappa": lambda: DENSITY * SPEED**2 / a,
            "c": lambda: np.full(N.shape, SPEED),  # a√(κ/m) = c by construction (tested separately)
            "omega_max": lambda: np.hypot(2 * SPEED / a, groups[1][..., 2]),
            "sigma_over_a": lambda: sigma / a,
            "dev": lambda: _per_chain(
                groups, lambda n, terms, w: deviation_of(motion(n, terms, w)[0], n, sigma[w], t[w], launch[w], terms)
            ),
            "E_chain": lambda: _per_chain(
                groups, lambda n, terms, w: _initial_energy(n, sigma[w], launch[w], terms, 1.0)
            ),
            "E_continuum": lambda: continuum_energy(sigma, launch),
            "E_chain_mJ": lambda: (
                1e3 * _per_chain(groups, lambda n, terms, w: _initial_energy(n, sigma[w], launch[w], terms, AMPLITUDE))
            ),
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
    terms_of = np.stack(
        [
            x["ends"] if "boundary" in effects else zero,
            x["gamma"] if "onsite_damping" in effects else zero,
            x["omega0"] if "onsite_spring" in effects else zero,
        ],
        axis=-1,
    )
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
        out[where] = continuum(
            continuum_grid(),
            t[where][..., None],
            sigma[where][..., None],
            launch[where][..., None],
            ENDS[int(code)],
            1.0,
        )
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
