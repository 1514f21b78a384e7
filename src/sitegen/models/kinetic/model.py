"""K2: the pressure of an ideal gas on a wall, from molecular impacts counted exactly (no time stepping).

N point molecules in a cube of side L with specular walls and no collisions between them. Only the
motion along x matters for the wall at x = L. Unfolded onto a circle of length 2L, a molecule moves
as X = x0 + v_x t and hits that wall whenever X crosses L + 2kL, so its hits in a window are
counted in closed form. Everything is computed in the units L and v_th = sqrt(k_B T/m): the
pressure ratios, hit counts and figure curves then depend only on (N, t_w, sampling), identically
for every temperature and species (common random numbers), and p_sim = ratio * p_ideal.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
from scipy.special import ndtri

from ...physics.base import Model, Output, Param
from ...physics.numerics import Measurement, Numerics

K_B = 1.380649e-23  # J/K, exact SI
ATOMIC_MASS = 1.66053906660e-27  # kg
BOX_SIDE = 100e-9  # m
SPECIES = ("He", "Ne", "N2", "O2", "Ar", "Xe")
# Molecular masses in u. N2 is 2 x 14.0067: the spec's readouts at the defaults (v_th 298.40 m/s)
# need it; the rounded 28.014 would show 298.39.
MASS_U = np.array([4.0026, 20.180, 28.0134, 31.998, 39.948, 131.29])
QUANTILE, RANDOM = 0, 1
SEED = 12345  # random mode: one fresh generator per N (the spec's measured single-seed deviations)
GOLDEN_STEP = (np.sqrt(5.0) - 1.0) / 2.0  # 1/phi: start positions s_i = {i/phi}
TRAIN_BINS = 80  # time bins of the impulse train; the running mean is sampled at their right edges
HIST_SPAN = 4.0  # the v_x histogram covers |v_x| <= 4 v_th
HIST_SIZE = 2 * int(2 * HIST_SPAN / 0.25) + 2  # vertices of the finest histogram (bins of 0.25 v_th)
CHUNK_VALUES = 200_000  # counts per pass (molecules × edge times): the arrays stay in cache, a small N takes few passes

_WINDOW = ("N", "t_w", "sampling")  # what the wall record depends on
_TRAIN_SIZE = 2 * TRAIN_BINS + 2


class Kinetic(Model):
    """Pressure on the wall x = L: exact hit counting against n k_B T and the sample's m Σv_x²/V."""

    name = "kinetic"
    title = "Kinetic-theory pressure from molecular impacts"
    params = (
        Param("N", "N", "", 1000.0, lo=1.0, hi=1e6, description="number of molecules (rounded to a whole number)"),
        Param("T", "T", "K", 300.0, lo=0.0, lo_open=True, description="temperature"),
        Param.choice("species", "gas", SPECIES, "N2", description="molecular species"),
        Param("t_w", "t<sub>w</sub>", "L/vₜₕ", 100.0, lo=0.0, lo_open=True, description="averaging window in units of L/v_th"),
        Param.choice("sampling", "sampling", ("quantile", "random"), "quantile",
                     description="how velocities and positions are drawn"),
        Param.choice("dim", "dimensions", ("1D", "2D", "3D"), "3D",
                     description="directions the molecules move in").with_effect("dimension"),
        Param("tau_c", "τ<sub>c</sub>", "L/vₜₕ", 0.0, lo=0.0,
              description="duration of one impact (a triangular pulse)").with_effect("contact_duration"),
        Param("alpha", "α", "", 0.0, lo=0.0, hi=1.0,
              description="accommodation: the fraction of impacts re-emitted diffusely at T").with_effect("wall_law"),
    )
    outputs = (
        Output("v_th", "v<sub>th</sub> = √(k<sub>B</sub>T/m)", "m/s", ("T", "species"), decimals=2),
        Output("v_rms", "v<sub>rms</sub> = √3 v<sub>th</sub>", "m/s", ("T", "species"), decimals=2),
        Output("p_ideal", "p<sub>ideal</sub> = Nk<sub>B</sub>T/V", "Pa", ("N", "T"), decimals=2, digits=4),
        Output("ratio_sample", "p<sub>sample</sub>/p<sub>ideal</sub>", "", ("N", "sampling"), decimals=6),
        Output("ratio", "p<sub>sim</sub>/p<sub>ideal</sub>", "", _WINDOW, decimals=6),
        Output("p_sim", "p<sub>sim</sub>", "Pa", ("N", "T", "t_w", "sampling"), decimals=2),
        Output("hits", "wall hits", "", _WINDOW, decimals=0),
        # Figure geometry, in units free of T and species: step-curve vertices of the force in time bins
        # (over p_ideal L^2), the running mean at the bins' right edges, and the v_x/v_th histogram.
        Output("train", "force on the wall / p<sub>ideal</sub>L²", "", _WINDOW, decimals=2, size=_TRAIN_SIZE),
        Output("running", "running mean p(t)/p<sub>ideal</sub>", "", _WINDOW, decimals=3, size=TRAIN_BINS),
        Output("hist_x", "v<sub>x</sub>/v<sub>th</sub> (histogram vertices)", "", ("N",), decimals=2,
               size=HIST_SIZE, ragged=True),
        Output("hist_y", "probability density of v<sub>x</sub>/v<sub>th</sub>", "", ("N", "sampling"), decimals=3,
               size=HIST_SIZE, ragged=True),
        # dimension: equipartition gives every direction k_B T/2, so only the totals depend on d.
        Output("v_rms_d", "v<sub>rms</sub> = √d v<sub>th</sub>", "m/s", ("T", "species", "dim"), decimals=2,
               effect="dimension"),
        Output("E_k", "⟨E<sub>k</sub>⟩ = (d/2)k<sub>B</sub>T", "zJ", ("T", "dim"), decimals=3, effect="dimension"),
        # contact_duration: each impact a triangular pulse of width tau_c centred on the point-particle hit.
        Output("train_soft", "force on the wall / p<sub>ideal</sub>L²", "", (*_WINDOW, "tau_c"), decimals=2,
               size=_TRAIN_SIZE, effect="contact_duration"),
        Output("running_soft", "running mean p(t)/p<sub>ideal</sub>", "", (*_WINDOW, "tau_c"), decimals=3,
               size=TRAIN_BINS, effect="contact_duration"),
        # wall_law: Maxwell's wall, a fraction alpha of impacts re-emitted with the flux-weighted Maxwellian at T.
        Output("ratio_wall", "p<sub>sim</sub>/p<sub>ideal</sub>", "", (*_WINDOW, "alpha"), decimals=6, effect="wall_law"),
        Output("hits_wall", "wall hits", "", (*_WINDOW, "alpha"), decimals=0, effect="wall_law"),
        Output("train_wall", "force on the wall / p<sub>ideal</sub>L²", "", (*_WINDOW, "alpha"), decimals=2,
               size=_TRAIN_SIZE, effect="wall_law"),
        Output("running_wall", "running mean p(t)/p<sub>ideal</sub>", "", (*_WINDOW, "alpha"), decimals=3,
               size=TRAIN_BINS, effect="wall_law"),
    )
    effects = ("dimension", "contact_duration", "wall_law")
    # physics.md §11.3: exact unfolded counting dominates time stepping (no trade-off to expose); the
    # build checks it against a replay of each molecule's hits, one flight after another.
    numerics = Numerics("exact-counting", tolerance=1e-12)
    methods = {"exact-counting": {}}
    error_metric = "relative error of the simulated pressure"

    def is_numerical(self, effects) -> bool:
        """The specular wall's counting is checked; Maxwell's wall re-draws velocities (its own tests)."""
        return "wall_law" not in effects

    def measure_error(self, values, effects) -> Measurement:
        """p_sim from the counted hits against the hits found by replaying each molecule's flights."""
        x = {**self.defaults(), **values}
        count, tau, sampling = max(1, int(round(x["N"]))), float(x["t_w"]), int(x["sampling"])
        counted = wall_record(count, tau, sampling).ratio
        z, s = molecules(count, sampling)
        replayed = float(np.sum(2.0 * np.abs(z) * replayed_hits(s, z, tau)) / (count * tau))
        error = abs(counted - replayed) / replayed if replayed else abs(counted)
        return Measurement(error, 0, "exact counting", "an event-by-event replay of every molecule")

    def _evaluate(self, x, wanted, effects):
        if {"contact_duration", "wall_law"} <= effects:
            raise ValueError("effects contact_duration and wall_law are not combined; enable one of them")
        count = np.maximum(1.0, np.rint(x["N"]))
        window = (count, x["t_w"], x["sampling"])
        mass = MASS_U[x["species"].astype(int)] * ATOMIC_MASS
        thermal = K_B * x["T"]
        dims = x["dim"] + 1.0  # choice index 0, 1, 2 -> 1, 2, 3 dimensions
        records = _RecordCache(np.unique(x["t_w"]))

        def per_window(read, size=(), *extra):
            return _per_case(lambda n, tau, mode, *more: read(records.get(n, tau, mode, *more)), size, *window, *extra)

        def per_soft_window(read, size):
            return _per_case(lambda *case: read(records.get_soft(*case)), size, *window, x["tau_c"])

        formulas = {
            "v_th": lambda: np.sqrt(thermal / mass),
            "v_rms": lambda: np.sqrt(3.0 * thermal / mass),
            "p_ideal": lambda: count * thermal / BOX_SIDE**3,
            "ratio_sample": lambda: _per_case(lambda n, mode: sample_ratio(*molecules(n, mode)), (), count, x["sampling"]),
            "ratio": lambda: per_window(_ratio),
            "p_sim": lambda: per_window(_ratio) * (count * thermal / BOX_SIDE**3),
            "hits": lambda: per_window(_hits),
            "train": lambda: per_window(_train, (_TRAIN_SIZE,)),
            "running": lambda: per_window(_running, (TRAIN_BINS,)),
            "hist_x": lambda: _per_case(lambda n: _padded(np.repeat(histogram_edges(n), 2)), (HIST_SIZE,), count),
            "hist_y": lambda: _per_case(_histogram, (HIST_SIZE,), count, x["sampling"]),
            "v_rms_d": lambda: np.sqrt(dims * thermal / mass),
            "E_k": lambda: 0.5 * dims * thermal * 1e21,
            "train_soft": lambda: per_soft_window(_train, (_TRAIN_SIZE,)),
            "running_soft": lambda: per_soft_window(_running, (TRAIN_BINS,)),
            "ratio_wall": lambda: per_window(_ratio, (), x["alpha"]),
            "hits_wall": lambda: per_window(_hits, (), x["alpha"]),
            "train_wall": lambda: per_window(_train, (_TRAIN_SIZE,), x["alpha"]),
            "running_wall": lambda: per_window(_running, (TRAIN_BINS,), x["alpha"]),
        }
        return {name: formulas[name]() for name in wanted}


def _histogram(count, sampling):
    return _padded(step_vertices(velocity_density(molecules(count, sampling)[0])))


def _ratio(record):
    return record.ratio


def _hits(record):
    return record.hits


def _train(record):
    return step_vertices(record.force())


def _running(record):
    return record.running_mean()


# --- the sample of molecules -----------------------------------------------------------------------------------


@lru_cache(maxsize=16)
def molecules(count: int, sampling: int, seed: int = SEED) -> tuple[np.ndarray, np.ndarray]:
    """Velocities z = v_x/v_th and start positions s = x0/L of `count` molecules (read-only arrays).

    quantile: z_i = Phi^-1((i + 1/2)/N) and s_i = {i/phi}, deterministic and independent of NumPy's
    generators; random: a fresh np.random.default_rng(seed), z first, then s.
    """
    count, sampling = int(count), int(sampling)
    if sampling == QUANTILE:
        index = np.arange(count)
        z, s = ndtri((index + 0.5) / count), np.mod(index * GOLDEN_STEP, 1.0)
    else:
        rng = np.random.default_rng(seed)
        z = rng.standard_normal(count)
        s = rng.random(count)
    z.flags.writeable = s.flags.writeable = False
    return z, s


def sample_ratio(z: np.ndarray, s: np.ndarray) -> float:
    """p_sample/p_ideal = <z^2>: the long-time pressure of this sample over n k_B T."""
    return float(np.sum(z * z) / z.size)


# --- exact hit counting ------------------------------------------------------------------------------------------


def wall_hits(s, z, tau) -> np.ndarray:
    """Hits on the wall x = L within a time tau (units L/v_th) of molecules starting at s = x0/L with z = v_x/v_th.

    The unfolded path runs from s to X = s + z tau; the wall's images sit at 1 + 2k, counted in the
    half-open interval (min(s, X), max(s, X)], so v_x = 0 gives 0 and no hit is counted twice.
    """
    end = np.multiply(z, tau, out=np.empty(np.broadcast_shapes(np.shape(s), np.shape(z), np.shape(tau))))
    end += s
    upper = _image_index(np.maximum(s, end, out=np.empty_like(end)))
    upper -= _image_index(np.minimum(s, end, out=end))
    return upper


def replayed_hits(s, z, tau: float) -> np.ndarray:
    """Hits on the wall x = L within tau, found flight by flight: the first arrival (directly, or
    after bouncing off x = 0), then one every round trip 2L/|v_x| (the second method for wall_hits)."""
    speed = np.abs(z)
    first = np.where(z > 0, 1.0 - s, 1.0 + s) / np.where(speed > 0, speed, 1.0)
    round_trip = 2.0 / np.where(speed > 0, speed, 1.0)
    later = np.floor((tau - first) / round_trip)
    return np.where((speed > 0) & (first <= tau), later + 1.0, 0.0)


def _image_index(x: np.ndarray) -> np.ndarray:
    """floor((x - 1)/2), in place: the index k of the last image 1 + 2k of the wall at or below x."""
    x -= 1.0
    x *= 0.5  # exact, as /2 is
    return np.floor(x, out=x)


def cumulative_impulse(z: np.ndarray, s: np.ndarray, times: np.ndarray) -> np.ndarray:
    """Σ_i 2|z_i| n_i(t) at each time t: the impulse delivered to the wall by then, in units m v_th."""
    weight = 2.0 * np.abs(z)
    inside = bool(np.all((s >= 0.0) & (s < 1.0)))  # as molecules() draws them
    if inside:
        halves = (0.5 * s, 0.5 * z)  # exact, and once rather than at every time
        signed = np.where(z < 0.0, -weight, weight)  # the sign of each molecule's index + 1 (see _index_after)
    impulse = np.empty(len(times))
    step = max(1, CHUNK_VALUES // max(len(z), 1))
    for k in range(0, len(times), step):
        tau = times[k : k + step, None]
        if inside:  # (index + 1)·(±weight) is |index + 1|·weight, bar the sign of a zero
            terms = _index_after(*halves, tau)
            terms *= signed
        else:
            terms = wall_hits(s, z, tau)
            terms *= weight
        impulse[k : k + step] = np.sum(terms, axis=1)  # float64 sums: the terms are ~1e-23 N·s in SI
    # A sum of zeros that were all −0.0 is −0.0, where |index + 1|·weight sums to +0.0: adding +0.0 restores
    # that sign and changes no other sum (any other term or partial sum is the same float).
    impulse += 0.0
    return impulse


def _index_after(half_s, half_z, tau) -> np.ndarray:
    """The end's image index + 1 for starts inside the box (0 ≤ s < 1), from s/2 and z/2: ± the hits of wall_hits.

    There the start's image index is −1, so the count is the end's index + 1 moving out (z ≥ 0: the end at
    or above the start) and −1 − that index moving in (z < 0: the end below 1). Halving is exact and commutes
    with rounding, so (z/2)τ + s/2 − 1/2 is the image index's (zτ + s − 1)/2 to the bit, in two passes fewer."""
    half_end = np.multiply(half_z, tau, out=np.empty(np.broadcast_shapes(np.shape(half_s), np.shape(half_z), np.shape(tau))))
    half_end += half_s
    half_end -= 0.5
    index = np.floor(half_end, out=half_end)
    index += 1.0
    return index


@dataclass(frozen=True)
class WallRecord:
    """What the wall received in one window: impulse at the bin edges and the number of hits."""

    count: int
    tau: float
    edges: np.ndarray  # bin edges in units L/v_th, 0 .. tau
    impulse: np.ndarray  # cumulative impulse at the edges, units m v_th
    hits: float

    @property
    def ratio(self) -> float:
        """p_sim/p_ideal = Σ 2|z| n / (N tau)."""
        return float(self.impulse[-1] / (self.count * self.tau))

    def force(self) -> np.ndarray:
        """Mean force in each time bin over the ideal mean force p_ideal L^2."""
        return np.diff(self.impulse) / (self.count * np.diff(self.edges))

    def running_mean(self) -> np.ndarray:
        """p(t)/p_ideal averaged from 0 to each bin's right edge (the last one is the ratio)."""
        return self.impulse[1:] / (self.count * self.edges[1:])


def wall_record(count: int, tau: float, sampling: int, seed: int = SEED) -> WallRecord:
    """Count the sample's hits on the wall in [0, tau], at TRAIN_BINS + 1 evenly spaced times."""
    z, s = molecules(count, sampling, seed)
    edges = window_edges(tau)
    impulse = cumulative_impulse(z, s, edges)
    hits = float(np.sum(wall_hits(s, z, tau)))
    return WallRecord(count, float(tau), edges, impulse, hits)


def window_edges(tau: float) -> np.ndarray:
    """The TRAIN_BINS + 1 evenly spaced bin edges of the window [0, tau]; the last is tau exactly."""
    return tau * (np.arange(TRAIN_BINS + 1) / TRAIN_BINS)


class _RecordCache:
    """Wall records of one evaluation, shared by the outputs that read them."""

    def __init__(self, windows: np.ndarray):
        self._windows = tuple(float(w) for w in windows)  # every t_w of the grid: one diffuse run serves them all
        self._records: dict[tuple, WallRecord] = {}

    def get(self, count: float, tau: float, sampling: float, alpha: float = 0.0) -> WallRecord:
        """The record of one window; alpha = 0 (specular walls) is counted exactly, never simulated."""
        key = (int(count), float(tau), int(sampling), float(alpha))
        if key not in self._records:
            if alpha == 0.0:
                self._records[key] = wall_record(*key[:3])
            else:
                runs = maxwell_wall_records(key[0], key[2], key[3], self._windows)
                self._records.update({(key[0], w, key[2], key[3]): record for w, record in runs.items()})
        return self._records[key]

    def get_soft(self, count: float, tau: float, sampling: float, width: float) -> WallRecord:
        """The record of one window with impacts spread into pulses of `width`."""
        key = ("soft", int(count), float(tau), int(sampling), float(width))
        if key not in self._records:
            self._records[key] = soft_record(*key[1:])
        return self._records[key]


# --- effect contact_duration: impacts as triangular pulses -----------------------------------------------------


def soft_record(count: float, tau: float, sampling: float, width: float, seed: int = SEED) -> WallRecord:
    """The wall record when each impact is a triangular pulse of `width` (L/v_th); width 0 is the exact count."""
    record = wall_record(int(count), tau, int(sampling), seed)
    if width == 0.0:
        return record
    z, s = molecules(int(count), int(sampling), seed)
    return replace(record, impulse=pulsed_impulse(z, s, record.edges, width))


def pulsed_impulse(z: np.ndarray, s: np.ndarray, times: np.ndarray, width: float) -> np.ndarray:
    """Impulse delivered in [0, t] at each time (units m v_th) when every impact is a triangular pulse.

    The pulses are centred on the point-particle hit times t_k, which the unfolded motion gives before
    t = 0 as well: the impulse is Σ 2|z| (G((t - t_k)/width) - G(-t_k/width)), G the pulse's cumulative share.
    """
    weight = 2.0 * np.abs(z)
    start = np.sum(weight * _smoothed_count(s, z, 0.0, width))
    return np.array([np.sum(weight * _smoothed_count(s, z, float(t), width)) for t in times]) - start


def _smoothed_count(s, z, t: float, width: float) -> np.ndarray:
    """Σ_k G((t - t_k)/width) + (a constant per molecule): hits up to t, each spread over its pulse."""
    before, after = t - 0.5 * width, t + 0.5 * width
    total = _signed_hits(s, z, before)  # pulses over by then count whole
    ends = s + z * before, s + z * after
    first = np.floor((np.minimum(*ends) - 1.0) / 2.0) + 1.0  # images 1 + 2k of the wall inside the window
    count = np.floor((np.maximum(*ends) - 1.0) / 2.0) - first + 1.0
    safe_z = np.where(z == 0.0, 1.0, z)  # v_x = 0 has no images in any window
    for j in range(int(count.max(initial=0.0))):
        hit_time = (2.0 * (first + j) + 1.0 - s) / safe_z
        total += np.where(j < count, _pulse_share((t - hit_time) / width), 0.0)
    return total


def _signed_hits(s, z, t: float) -> np.ndarray:
    """Hits in (0, t] (minus those in (t, 0] when t < 0), the same count as `wall_hits` for t > 0."""
    start, end = np.floor((s - 1.0) / 2.0), np.floor((s + z * t - 1.0) / 2.0)
    return np.sign(z) * (end - start)


def _pulse_share(u: np.ndarray) -> np.ndarray:
    """G(u): the share of a unit triangular pulse on [-1/2, 1/2] delivered by time u (in pulse widths)."""
    u = np.clip(u, -0.5, 0.5)
    return np.where(u <= 0.0, 2.0 * (u + 0.5) ** 2, 1.0 - 2.0 * (0.5 - u) ** 2)


# --- effect wall_law: Maxwell's wall (specular, or diffuse with full thermal accommodation) ---------------------


def maxwell_wall_records(count: int, sampling: int, alpha: float, windows, seed: int = SEED) -> dict[float, WallRecord]:
    """Wall records for each window when a fraction alpha of impacts (on both walls) re-emits diffusely at T.

    Event-driven and exact between events (no time step): each round moves every molecule to its
    next wall. A diffuse re-emission draws |v_x| from the flux-weighted Maxwellian (Rayleigh in
    units v_th), an impact on x = L delivers m(|v_in| + |v_out|). The draws come from a counter-based
    hash of (seed, molecule, event), so a molecule's path does not depend on the windows asked for.
    """
    z, s = molecules(count, sampling, seed)
    windows = sorted(set(float(w) for w in windows))
    horizon = windows[-1]
    binned = {w: np.zeros(TRAIN_BINS) for w in windows}
    hits = dict.fromkeys(windows, 0.0)
    moving = z != 0.0
    keys = _molecule_keys(seed, np.flatnonzero(moving))
    x, v, t = s[moving], z[moving], np.zeros(int(moving.sum()))
    event = 0
    while keys.size:
        right = v > 0.0
        arrival = t + np.where(right, 1.0 - x, x) / np.abs(v)
        alive = arrival <= horizon
        keys, x, v, right, arrival = keys[alive], x[alive], v[alive], right[alive], arrival[alive]
        speed_in = np.abs(v)
        diffuse = _uniform(keys, event, 0) < alpha if alpha < 1.0 else np.ones(keys.size, bool)
        speed_out = np.where(diffuse, np.sqrt(-2.0 * np.log(_uniform(keys, event, 1))), speed_in)
        for w in windows:
            on_wall = right & (arrival <= w)
            bins = np.minimum(np.ceil(arrival[on_wall] * (TRAIN_BINS / w)) - 1.0, TRAIN_BINS - 1).astype(int)
            binned[w] += np.bincount(bins, weights=(speed_in + speed_out)[on_wall], minlength=TRAIN_BINS)
            hits[w] += float(np.count_nonzero(on_wall))
        x, v, t = np.where(right, 1.0, 0.0), np.where(right, -speed_out, speed_out), arrival
        event += 1
    return {
        w: WallRecord(count, w, window_edges(w), np.concatenate(([0.0], np.cumsum(binned[w]))), hits[w])
        for w in windows
    }


_MIX = (np.uint64(0xBF58476D1CE4E5B9), np.uint64(0x94D049BB133111EB))
_GOLDEN64 = np.uint64(0x9E3779B97F4A7C15)


def _molecule_keys(seed: int, index: np.ndarray) -> np.ndarray:
    """One 64-bit key per molecule; the seed is hashed first, so two seeds never share a molecule's stream."""
    return _splitmix(index.astype(np.uint64) + _splitmix(np.array([seed], dtype=np.uint64)))


def _uniform(keys: np.ndarray, event: int, stream: int) -> np.ndarray:
    """Uniform numbers in (0, 1), one per molecule: splitmix64 of (molecule key, event, stream).

    Counter-based, so the same on every machine and NumPy version.
    """
    key = _splitmix(keys ^ np.uint64(4 * event + stream))
    return ((key >> np.uint64(11)).astype(float) + 0.5) * 2.0**-53


def _splitmix(x: np.ndarray) -> np.ndarray:
    x = x + _GOLDEN64
    x = (x ^ (x >> np.uint64(30))) * _MIX[0]
    x = (x ^ (x >> np.uint64(27))) * _MIX[1]
    return x ^ (x >> np.uint64(31))


# --- the velocity histogram and curve geometry -------------------------------------------------------------------


def histogram_edges(count: int) -> np.ndarray:
    """Bin edges over |z| <= 4: bins of 1, 1/2 or 1/4 v_th, so the central bin expects >= ~5 molecules."""
    width = float(np.clip(2.0 ** np.ceil(np.log2(12.5 / count)), 0.25, 1.0))
    return np.arange(-HIST_SPAN, HIST_SPAN + width / 2, width)


def velocity_density(z: np.ndarray) -> np.ndarray:
    """Histogram of z as a probability density (count / (N width)) on `histogram_edges`."""
    edges = histogram_edges(z.size)
    width = edges[1] - edges[0]
    index = np.floor((z - edges[0]) / width)
    inside = (index >= 0) & (index < len(edges) - 1)
    counts = np.bincount(index[inside].astype(int), minlength=len(edges) - 1)
    return counts / (z.size * width)


def step_vertices(values: np.ndarray) -> np.ndarray:
    """y of a step curve over consecutive bins, closed to zero: 0, v0, v0, v1, v1, ..., v_last, 0."""
    return np.concatenate(([0.0], np.repeat(values, 2), [0.0]))


def _padded(vector: np.ndarray) -> np.ndarray:
    return np.concatenate((vector, np.full(HIST_SIZE - len(vector), np.nan)))


def _per_case(compute, trailing: tuple[int, ...], *columns) -> np.ndarray:
    """Evaluate `compute` once per distinct combination of the columns and spread the results over the grid."""
    shape = np.shape(columns[0])
    # Each column's distinct values, then one integer per combination: the same cases, in the same
    # (lexicographic) order, as np.unique over rows, which sorts the rows as records (far slower).
    values, codes = zip(*(np.unique(np.ravel(c), return_inverse=True) for c in columns))
    combined = np.zeros(np.size(columns[0]), dtype=np.int64)
    for distinct, code in zip(values, codes):
        combined = combined * len(distinct) + np.ravel(code)
    used, inverse = np.unique(combined, return_inverse=True)
    digits = []
    for distinct in reversed(values):
        used, digit = np.divmod(used, len(distinct))
        digits.append(distinct[digit])
    cases = np.stack(digits[::-1], axis=-1)
    results = np.array([compute(*case) for case in cases], dtype=float).reshape((len(cases),) + trailing)
    return results[np.ravel(inverse)].reshape(shape + trailing)
