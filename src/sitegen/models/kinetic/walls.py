"""The kinetic model's wall record: a sample of molecules, their hits on the wall x = L counted exactly
(unfolded onto a circle of length 2L, no time stepping), the force and running mean they make, and the
records of two effects: contact_duration (each impact a triangular pulse) and wall_law (Maxwell's wall)."""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
from scipy.special import ndtri

QUANTILE, RANDOM = 0, 1
SEED = 12345  # random mode: one fresh generator per N (the spec's measured single-seed deviations)
GOLDEN_STEP = (np.sqrt(5.0) - 1.0) / 2.0  # 1/phi: start positions s_i = {i/phi}
TRAIN_BINS = 80  # time bins of the impulse train; the running mean is sampled at their right edges
CHUNK_VALUES = 200_000  # counts per pass (molecules × edge times): the arrays stay in cache, a small N takes few passes


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
    half_end = np.multiply(
        half_z, tau, out=np.empty(np.broadcast_shapes(np.shape(half_s), np.shape(half_z), np.shape(tau)))
    )
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


class RecordCache:
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
