"""K2 (kinetic-theory pressure): exact hit counting against enumeration, bounds, statistics, hard cases, effects."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from sitegen.compute.quantize import fmt
from sitegen.models.kinetic.model import ATOMIC_MASS, BOX_SIDE, K_B, MASS_U, SPECIES, Kinetic
from sitegen.models.kinetic.walls import (
    QUANTILE,
    RANDOM,
    TRAIN_BINS,
    cumulative_impulse,
    maxwell_wall_records,
    molecules,
    pulsed_impulse,
    sample_ratio,
    soft_record,
    wall_hits,
    wall_record,
)

EPS = np.finfo(float).eps
SAMPLINGS = {"quantile": QUANTILE, "random": RANDOM}


def _evaluate(wanted, effects=(), **inputs):
    """The named outputs at one point (defaults elsewhere)."""
    return Kinetic().evaluate({**Kinetic.defaults(), **inputs}, wanted=wanted, effects=effects)


def _enumerated_hits(z: float, s: float, tau: float) -> int:
    """Hits on x = L in (0, tau], by walking the bounces one by one (a second method: no unfolding)."""
    if z == 0.0:
        return 0
    x, v, t, hits = Fraction(s), Fraction(z), Fraction(0), 0
    while True:
        step = (1 - x) / v if v > 0 else x / -v
        if step == 0:  # sitting on a wall and moving into it: it reflects at t = 0, which is not in (0, tau]
            v = -v
            continue
        if t + step > tau:
            return hits
        t += step
        hits += v > 0
        x, v = (Fraction(1), -v) if v > 0 else (Fraction(0), -v)


def naive_stepping_ratio(z: np.ndarray, s: np.ndarray, tau: float, dt: float) -> tuple[float, float]:
    """COMPARISON ONLY (the hard case): fixed steps, reflecting at most once per step; (p/p_ideal, share outside)."""
    x, v, impulse = s.copy(), z.copy(), 0.0
    for _ in range(int(round(tau / dt))):
        x = x + v * dt
        right = (x > 1.0) & (v > 0.0)
        impulse += np.sum(2.0 * np.abs(v[right]))
        x, v = np.where(right, 2.0 - x, x), np.where(right, -v, v)
        left = (x < 0.0) & (v < 0.0)
        x, v = np.where(left, -x, x), np.where(left, -v, v)
    return impulse / (z.size * tau), float(np.mean((x < 0.0) | (x > 1.0)))


# --- the readouts at the defaults (N = 1000, T = 300 K, N2, t_w = 100 L/v_th, quantile) ----------------------------

DEFAULT_READOUTS = {
    "v_th": "298.40",
    "v_rms": "516.84",
    "p_ideal": "4141.95",
    "ratio_sample": "0.998699",
    "ratio": "0.998976",
    "hits": "39879",
}


@pytest.mark.parametrize("output, expected", DEFAULT_READOUTS.items(), ids=list(DEFAULT_READOUTS))
def test_defaults_display_the_listed_readouts(output, expected):
    """At the defaults the page shows the values docs/physics/kinetic.md lists."""
    value = float(_evaluate([output])[output])
    assert fmt(value, Kinetic.output(output).decimals) == expected


# --- closed forms ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("species", SPECIES)
@pytest.mark.parametrize("T", [50.0, 300.0, 777.0, 1000.0], ids=["50K", "300K", "777K", "1000K"])
def test_thermal_speeds_match_exact_square_roots(species, T):
    """v_th = √(k_B T/m) and v_rms = √(3 k_B T/m) within 2ε rel of the square root of the exact rational."""
    out = _evaluate(["v_th", "v_rms"], T=T, species=SPECIES.index(species))
    mass = Fraction(float(MASS_U[SPECIES.index(species)])) * Fraction(ATOMIC_MASS)
    for name, factor in (("v_th", 1), ("v_rms", 3)):
        exact_square = factor * Fraction(K_B) * Fraction(T) / mass
        value = Fraction(float(out[name]))
        assert abs(value * value / exact_square - 1) <= 4 * EPS  # v² within 4ε ⇔ v within 2ε


@pytest.mark.parametrize("N", [10.0, 1000.0, 1e5], ids=["N=10", "N=1000", "N=1e5"])
@pytest.mark.parametrize("T", [50.0, 300.0, 1000.0], ids=["50K", "300K", "1000K"])
def test_ideal_pressure_is_n_kB_T(N, T):
    """p_ideal = N k_B T / L³ within 3ε rel of the exact rational."""
    value = Fraction(float(_evaluate(["p_ideal"], N=N, T=T)["p_ideal"]))
    exact = Fraction(N) * Fraction(K_B) * Fraction(T) / Fraction(BOX_SIDE) ** 3
    assert abs(value / exact - 1) <= 3 * EPS


def test_simulated_pressure_is_the_ratio_times_the_ideal_pressure():
    """p_sim = (p_sim/p_ideal)·p_ideal at the defaults, within 2ε rel."""
    out = _evaluate(["p_sim", "ratio", "p_ideal"])
    assert float(out["p_sim"]) == pytest.approx(float(out["ratio"] * out["p_ideal"]), rel=2 * EPS)


# --- exact counting against a second method --------------------------------------------------------------------

COUNT_CASES = [
    pytest.param(30, 1.0, "quantile", id="N=30-tw=1-quantile"),
    pytest.param(30, 10.0, "random", id="N=30-tw=10-random"),
    pytest.param(100, 30.0, "quantile", id="N=100-tw=30-quantile"),
    pytest.param(10, 300.0, "random", id="N=10-tw=300-random"),
]


@pytest.mark.parametrize("N, tau, sampling", COUNT_CASES)
def test_unfolded_count_equals_bounce_by_bounce_enumeration(N, tau, sampling):
    """n_i from the unfolded formula equals walking the bounces in exact rationals, molecule by molecule."""
    z, s = molecules(N, SAMPLINGS[sampling])
    expected = [_enumerated_hits(float(zi), float(si), Fraction(tau)) for zi, si in zip(z, s)]
    assert wall_hits(s, z, tau).tolist() == expected


@pytest.mark.parametrize("N, tau, sampling", COUNT_CASES)
def test_ratio_is_the_impulse_sum_over_N_tau(N, tau, sampling):
    """p_sim/p_ideal = Σ 2|z_i| n_i / (N t_w) within 4ε rel of the exact rational over the enumerated hits."""
    z, s = molecules(N, SAMPLINGS[sampling])
    exact = sum(
        2 * abs(Fraction(float(zi))) * _enumerated_hits(float(zi), float(si), Fraction(tau)) for zi, si in zip(z, s)
    )
    exact /= N * Fraction(tau)
    value = Fraction(float(_evaluate(["ratio"], N=N, t_w=tau, sampling=SAMPLINGS[sampling])["ratio"]))
    assert abs(value - exact) <= 4 * EPS * exact


# --- the deterministic bound and the statistics of the sample ------------------------------------------------------

BOUND_CASES = [
    pytest.param(N, tau, mode, id=f"N={N}-tw={tau:g}-{mode}")
    for N in (10, 1000, 100000)
    for tau in (1.0, 100.0)
    for mode in SAMPLINGS
]


@pytest.mark.parametrize("N, tau, sampling", BOUND_CASES)
def test_each_molecule_miscounts_by_less_than_one_hit(N, tau, sampling):
    """|n_i − |z_i| t_w/2| < 1 for every molecule (checked in exact rationals on the float inputs)."""
    z, s = molecules(N, SAMPLINGS[sampling])
    n = wall_hits(s, z, tau)
    worst = max(abs(int(ni) - abs(Fraction(float(zi))) * Fraction(tau) / 2) for zi, ni in zip(z[:2000], n[:2000]))
    assert worst < 1


@pytest.mark.parametrize("N, tau, sampling", BOUND_CASES)
def test_simulated_pressure_is_within_the_deterministic_bound_of_the_sample(N, tau, sampling):
    """|p_sim − p_sample| ≤ 2m Σ|v_x|/(L² t_w), i.e. |ratio − ratio_sample| ≤ Σ 2|z_i|/(N t_w)."""
    out = _evaluate(["ratio", "ratio_sample"], N=N, t_w=tau, sampling=SAMPLINGS[sampling])
    z, _ = molecules(N, SAMPLINGS[sampling])
    bound = np.sum(2.0 * np.abs(z)) / (N * tau)
    assert abs(float(out["ratio"] - out["ratio_sample"])) <= bound


SEEDS = range(1, 201)


@pytest.mark.parametrize("N", [10, 1000], ids=["N=10", "N=1000"])
def test_random_sample_pressure_scatters_as_sqrt_2_over_N(N):
    """Random mode over 200 seeds: the mean of p_sample/p_ideal − 1 has |z| < 5 with std √(2/N)."""
    deviations = np.array([sample_ratio(*molecules(N, RANDOM, seed)) - 1.0 for seed in SEEDS])
    sigma = math.sqrt(2.0 / N)
    assert abs(deviations.mean()) / (sigma / math.sqrt(len(SEEDS))) < 5
    assert 0.75 < deviations.std(ddof=1) / sigma < 1.25  # the std itself, ±5 standard errors


def test_random_simulated_pressure_is_unbiased():
    """Random mode over 200 seeds (N = 1000, t_w = 100): the mean of p_sim/p_ideal − 1 has |z| < 5."""
    deviations = np.array([wall_record(1000, 100.0, RANDOM, seed).ratio - 1.0 for seed in SEEDS])
    assert abs(deviations.mean()) / (deviations.std(ddof=1) / math.sqrt(len(SEEDS))) < 5


@pytest.mark.parametrize(
    "N, listed",
    [(10, -0.120), (100, -0.0127), (1000, -0.0013), (10000, -0.00013)],
    ids=["N=10-listed=-0.120", "N=100-listed=-0.0127", "N=1000-listed=-0.0013", "N=1e4-listed=-0.00013"],
)
def test_quantile_sample_falls_short_by_order_1_over_N(N, listed):
    """Quantile mode: <z²> − 1 is within a factor 2 of the listed O(1/N) values."""
    deviation = sample_ratio(*molecules(N, QUANTILE)) - 1.0
    assert 0.5 <= deviation / listed <= 2.0


# --- hard case: time stepping with reflect-once-per-step ------------------------------------------------------------

STEPPING = [
    pytest.param(0.5, -0.0005, (-0.002, 0.0), (0.001, 0.02), id="dt=0.5-listed=-0.05%"),
    pytest.param(1.0, -0.053, (-0.08, -0.03), (0.05, 0.15), id="dt=1-listed=-5.3%"),
    pytest.param(3.0, -0.52, (-0.60, -0.45), (0.4, 0.7), id="dt=3-listed=-52%"),
]


@pytest.mark.parametrize("dt, listed, error_band, outside_band", STEPPING)
def test_fixed_step_reflection_loses_pressure_but_exact_counting_does_not(dt, listed, error_band, outside_band):
    """N = 1000, t_w = 100: naive stepping errs as listed and leaves molecules outside; the engine is exact."""
    z, s = molecules(1000, QUANTILE)
    engine = float(_evaluate(["ratio"])["ratio"])
    stepped, outside = naive_stepping_ratio(z, s, 100.0, dt)
    assert error_band[0] < stepped / engine - 1.0 < error_band[1]
    assert outside_band[0] < outside < outside_band[1]
    assert engine == wall_record(1000, 100.0, QUANTILE).ratio  # the engine has no step: the same value for any dt
    assert abs(engine - sample_ratio(z, s)) < 1e-3


def test_fine_steps_reproduce_the_exact_hit_count():
    """Δt = 0.1 L/v_th (|v|Δt < L for every molecule): stepping counts the same impulse as the engine, to 1e-12."""
    z, s = molecules(1000, QUANTILE)
    stepped, outside = naive_stepping_ratio(z, s, 100.0, 0.1)
    assert stepped == pytest.approx(float(_evaluate(["ratio"])["ratio"]), rel=1e-12)
    assert outside == 0.0


# --- hard case: t_w ≲ L/v_th, few hits -------------------------------------------------------------------------------


@pytest.mark.parametrize("sampling", SAMPLINGS)
def test_short_window_is_noisy_and_reports_its_few_hits(sampling):
    """N = 10, t_w = 1 L/v_th: a handful of hits (the readout equals enumeration) and a ratio far from p_sample."""
    mode = SAMPLINGS[sampling]
    out = _evaluate(["hits", "ratio", "ratio_sample"], N=10, t_w=1.0, sampling=mode)
    z, s = molecules(10, mode)
    assert float(out["hits"]) == sum(_enumerated_hits(float(zi), float(si), Fraction(1)) for zi, si in zip(z, s)) <= 10
    long_window = _evaluate(["ratio"], N=10, t_w=1000.0, sampling=mode)["ratio"]
    assert abs(float(long_window - out["ratio_sample"])) < 0.005 < abs(float(out["ratio"] - out["ratio_sample"]))


# --- hard case: v_x = 0 and starts exactly on a wall ------------------------------------------------------------------


@pytest.mark.parametrize("s", [0.0, 0.37, 1.0], ids=["on-left-wall", "inside", "on-right-wall"])
@pytest.mark.parametrize("tau", [1.0, 1e3, 1e300], ids=["tw=1", "tw=1e3", "tw=1e300"])
def test_molecule_at_rest_never_hits(s, tau):
    """v_x = 0: n_i = 0 exactly, wherever it sits, even on a wall."""
    assert wall_hits(np.array([s]), np.array([0.0]), tau).tolist() == [0.0]


@pytest.mark.parametrize("s", [0.0, 1.0], ids=["from-left-wall", "from-right-wall"])
@pytest.mark.parametrize("z", [2.0, -2.0, 0.5, -0.5], ids=["z=2", "z=-2", "z=0.5", "z=-0.5"])
@pytest.mark.parametrize("trips", [1, 2, 7])
def test_start_on_a_wall_counts_each_round_trip_once(s, z, trips):
    """Half-open intervals: starting on a wall, k whole round trips (|X − s| = 2k) give exactly k hits."""
    tau = 2.0 * trips / abs(z)
    assert wall_hits(np.array([s]), np.array([z]), tau).tolist() == [float(trips)]


def test_no_hit_at_t_equals_zero_is_counted_twice_across_windows():
    """Counts are additive over adjacent windows (hits in (0, a] plus (a, b] = (0, b]) for starts on walls."""
    z = np.array([2.0, -2.0, 0.5, -0.5, 3.0])
    s = np.array([1.0, 1.0, 0.0, 0.0, 0.5])
    first, total = wall_hits(s, z, 1.0), wall_hits(s, z, 3.0)
    assert (first + wall_hits(s + z * 1.0, z, 2.0)).tolist() == total.tolist()


@pytest.mark.parametrize("sampling", SAMPLINGS.values(), ids=SAMPLINGS.keys())
def test_impulse_from_starts_inside_the_box_is_the_general_count_to_the_bit(sampling):
    """Starts in [0, 1) are counted in fewer passes: the impulse equals the one summed from wall_hits, bit for bit,
    with molecules at rest (z = ±0), starting on the left wall, and windows from 0 to 1e300."""
    z, s = (np.array(a) for a in molecules(3000, sampling))
    z[:3], s[3:6] = (0.0, -0.0, 0.0), 0.0
    times = np.concatenate([np.linspace(0.0, 100.0, 81), [1e3, 1e300]])
    general = np.array([np.sum(wall_hits(s, z, t) * (2.0 * np.abs(z))) for t in times])
    assert cumulative_impulse(z, s, times).tobytes() == general.tobytes()


# --- hard case: sums of ~1e-23 N·s impulses ---------------------------------------------------------------------------


def test_ratio_agrees_with_a_correctly_rounded_sum_and_float32_would_not():
    """The float64 ratio is within 1e-13 of math.fsum; summing the SI impulses in float32 is off by > 1e-6."""
    z, s = molecules(1000, QUANTILE)
    n = wall_hits(s, z, 100.0)
    reference = math.fsum(2.0 * abs(zi) * ni for zi, ni in zip(z, n)) / (1000 * 100.0)
    assert float(_evaluate(["ratio"])["ratio"]) == pytest.approx(reference, rel=1e-13)
    mass, v_th = float(MASS_U[2]) * ATOMIC_MASS, math.sqrt(K_B * 300.0 / (float(MASS_U[2]) * ATOMIC_MASS))
    impulses = np.repeat((2.0 * mass * v_th * np.abs(z)).astype(np.float32), n.astype(int))
    single = np.cumsum(impulses, dtype=np.float32)[-1]  # a running float32 total, as a naive loop would keep
    exact_si = reference * 1000 * 100.0 * mass * v_th
    assert abs(float(single) / exact_si - 1.0) > 1e-6


@pytest.mark.parametrize("output", ["ratio", "hits", "train", "running"])
def test_window_outputs_are_bitwise_independent_of_temperature_and_species(output):
    """Common random numbers in units L, v_th: the ratio, hits and curves are the same bits for every T and gas."""
    reference = _evaluate([output])[output]
    for T, species in ((50.0, 0), (1000.0, 5), (777.0, 3)):
        assert np.array_equal(_evaluate([output], T=T, species=species)[output], reference)


# --- the figure's curves ----------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "N, tau, sampling",
    [(10, 1.0, QUANTILE), (1000, 100.0, QUANTILE), (300, 1000.0, RANDOM)],
    ids=["N=10-tw=1", "defaults", "N=300-tw=1000-random"],
)
def test_running_mean_ends_at_the_ratio_and_the_train_averages_to_it(N, tau, sampling):
    """The running mean's last point is the ratio bitwise; the mean force over the bins is the ratio to 1e-12."""
    out = _evaluate(["ratio", "running", "train"], N=N, t_w=tau, sampling=sampling)
    assert out["running"][-1] == out["ratio"]
    bins = out["train"][1:-1:2]
    assert len(bins) == TRAIN_BINS and np.mean(bins) == pytest.approx(float(out["ratio"]), rel=1e-12)


@pytest.mark.parametrize("N", [10, 30, 1000, 100000], ids=["N=10", "N=30", "N=1000", "N=1e5"])
@pytest.mark.parametrize("sampling", SAMPLINGS)
def test_velocity_histogram_is_a_density_of_the_sample(N, sampling):
    """The histogram's area is the share of molecules with |z| < 4, and x and y vertices come in equal numbers."""
    out = _evaluate(["hist_x", "hist_y"], N=N, sampling=SAMPLINGS[sampling])
    x, y = out["hist_x"], out["hist_y"]
    assert np.array_equal(np.isnan(x), np.isnan(y))
    x, y = x[~np.isnan(x)], y[~np.isnan(y)]
    area = np.sum(np.diff(x)[1::2] * y[1:-1:2])
    z, _ = molecules(N, SAMPLINGS[sampling])
    assert area == pytest.approx(np.mean(np.abs(z) < 4.0), rel=1e-12)


def test_same_inputs_give_bitwise_the_same_outputs():
    """Determinism: two evaluations (the sample cache cleared between them) agree in every bit."""
    names = [o.name for o in Kinetic.outputs if not o.effect]
    grid = {"N": np.array([10.0, 1000.0]), "t_w": np.array([[1.0], [300.0]]), "sampling": np.array([[[0.0]], [[1.0]]])}
    first = Kinetic().evaluate(grid, wanted=names)
    molecules.cache_clear()
    second = Kinetic().evaluate(grid, wanted=names)
    for name in names:
        assert np.array_equal(first[name], second[name], equal_nan=True), name


# --- effects
# -----------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("dim, factor", [(0, 1), (1, 2), (2, 3)], ids=["1D", "2D", "3D"])
def test_dimension_changes_the_totals_but_not_the_pressure(dim, factor):
    """dimension: v_rms = √d v_th and ⟨E_k⟩ = (d/2)k_BT (2ε), while the wall's pressure outputs keep their bits."""
    out = _evaluate(["v_rms_d", "E_k", "v_th", "ratio", "hits"], effects=["dimension"], dim=dim)
    assert float(out["v_rms_d"]) == pytest.approx(math.sqrt(factor) * float(out["v_th"]), rel=2 * EPS)
    assert float(out["E_k"]) == pytest.approx(0.5 * factor * K_B * 300.0 * 1e21, rel=2 * EPS)
    base = _evaluate(["ratio", "hits"])
    assert out["ratio"] == base["ratio"] and out["hits"] == base["hits"]


def test_three_dimensions_is_the_base_model_bitwise():
    """dimension at d = 3 (its default) gives v_rms bit for bit as the base model."""
    assert _evaluate(["v_rms_d"], effects=["dimension"])["v_rms_d"] == _evaluate(["v_rms"])["v_rms"]


@pytest.mark.parametrize("output", ["train", "running"])
@pytest.mark.parametrize("width, tolerance", [(0.0, 0.0), (1e-9, 1e-6)], ids=["tau_c=0-bitwise", "tau_c=1e-9-1e-6"])
@pytest.mark.parametrize("N, tau", [(10, 1.0), (1000, 100.0)], ids=["N=10-tw=1", "defaults"])
def test_contact_duration_vanishes_to_instant_kicks(width, tolerance, N, tau, output):
    """contact_duration: as τ_c → 0 the pulsed impulse train and running mean become the exact-count ones."""
    out = _evaluate([f"{output}_soft", output], effects=["contact_duration"], N=N, t_w=tau, tau_c=width)
    assert np.max(np.abs(out[f"{output}_soft"] - out[output])) <= tolerance * np.max(out[output])


@pytest.mark.parametrize("width", [0.05, 0.5, 3.0], ids=["tau_c=0.05", "tau_c=0.5", "tau_c=3"])
def test_pulses_move_impulse_in_time_but_do_not_create_it(width):
    """contact_duration: over a long window the pulsed mean force equals the ratio to within one pulse per molecule."""
    N, tau = 300, 300.0
    force = soft_record(N, tau, QUANTILE, width).force()
    ratio = wall_record(N, tau, QUANTILE).ratio
    z, _ = molecules(N, QUANTILE)
    assert abs(np.mean(force) - ratio) <= np.sum(2.0 * np.abs(z)) / (N * tau)  # only the pulses cut at 0 and t_w
    assert np.all(force >= 0.0)


@pytest.mark.parametrize("width", [0.1, 0.2, 0.35], ids=["tau_c=0.1", "tau_c=0.2", "tau_c=0.35"])
def test_pulse_shape_spreads_a_lone_kick_into_a_triangle(width):
    """One molecule (s = 1/2, z = 1) hits at t = 1/2: the impulse ramps as the triangle's integral, 2 in all."""
    times = np.linspace(0.0, 1.0, 41)
    impulse = pulsed_impulse(np.array([1.0]), np.array([0.5]), times, width)
    u = np.clip((times - 0.5) / width, -0.5, 0.5)
    share = np.where(u <= 0, 2 * (u + 0.5) ** 2, 1 - 2 * (0.5 - u) ** 2)  # ∫ of the unit triangle on [-1/2, 1/2]
    assert np.max(np.abs(impulse - 2.0 * share)) <= 8 * EPS


def test_contact_duration_and_wall_law_together_are_refused():
    """The two effects are not composed: asking for both raises ValueError naming them."""
    with pytest.raises(ValueError, match="contact_duration and wall_law"):
        _evaluate(["ratio"], effects=["contact_duration", "wall_law"])


@pytest.mark.parametrize("output", ["ratio_wall", "hits_wall", "train_wall", "running_wall"])
def test_specular_limit_of_maxwell_wall_is_the_base_model_bitwise(output):
    """wall_law with α = 0 is the exact specular count, bit for bit."""
    base = output.removesuffix("_wall")
    assert np.array_equal(_evaluate([output], effects=["wall_law"], alpha=0.0)[output], _evaluate([base])[base])


@pytest.mark.parametrize(
    "N, tau, sampling", [(1000, 100.0, QUANTILE), (30, 300.0, RANDOM)], ids=["defaults", "N=30-tw=300-random"]
)
def test_event_driven_walls_reproduce_exact_counting_as_alpha_vanishes(N, tau, sampling):
    """α = 1e-12 (the event-driven path, no diffuse event): same hits, ratio within 1e-12 of exact counting."""
    record = maxwell_wall_records(N, sampling, 1e-12, [tau])[tau]
    exact = wall_record(N, tau, sampling)
    assert record.hits == exact.hits
    assert record.ratio == pytest.approx(exact.ratio, rel=1e-12)


def test_diffuse_walls_rethermalise_an_unlucky_sample():
    """α = 1: N = 10 quantile molecules (p_sample 12 % low) give p_sim → n k_B T over 16 re-emission seeds (|z| < 5)."""
    ratios = np.array([maxwell_wall_records(10, QUANTILE, 1.0, [500.0], seed)[500.0].ratio for seed in range(1, 17)])
    assert abs(ratios.mean() - 1.0) / (ratios.std(ddof=1) / math.sqrt(len(ratios))) < 5
    specular = float(_evaluate(["ratio"], N=10, t_w=500.0, sampling=QUANTILE)["ratio"])
    assert specular < 0.9 < 0.95 < ratios.mean()


def test_diffuse_walls_keep_the_ideal_gas_pressure():
    """α = 1 and α = 0.5, N = 3000 quantile, t_w = 300: p_sim/p_ideal = 1 within 5 × its statistical error (≈ 0.5 %)."""
    for alpha in (0.5, 1.0):
        ratio = maxwell_wall_records(3000, QUANTILE, alpha, [300.0])[300.0].ratio
        assert abs(ratio - 1.0) < 0.01, alpha


def test_maxwell_wall_path_does_not_depend_on_the_windows_asked_for():
    """Counter-based draws: the record of t_w = 10 is the same whether or not t_w = 1000 is simulated too."""
    alone = maxwell_wall_records(100, RANDOM, 0.7, [10.0])[10.0]
    together = maxwell_wall_records(100, RANDOM, 0.7, [10.0, 1000.0])[10.0]
    assert alone.hits == together.hits and np.array_equal(alone.impulse, together.impulse)


# --- invalid input
# -------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "inputs",
    [
        {"N": 0.5},
        {"N": 2e6},
        {"T": 0.0},
        {"T": -1.0},
        {"t_w": 0.0},
        {"species": 6.0},
        {"species": 1.5},
        {"sampling": 2.0},
        {"t_w": float("nan")},
        {"tau_c": -0.1},
        {"alpha": 1.5},
    ],
    ids=[
        "N<1",
        "N>1e6",
        "T=0",
        "T<0",
        "t_w=0",
        "species=6",
        "species=1.5",
        "sampling=2",
        "t_w=nan",
        "tau_c<0",
        "alpha>1",
    ],
)
def test_invalid_input_raises_naming_the_parameter(inputs):
    """Out-of-domain or NaN inputs raise ValueError whose message names the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        Kinetic().evaluate(inputs)
