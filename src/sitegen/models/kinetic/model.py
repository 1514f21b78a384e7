"""K2: the pressure of an ideal gas on a wall, from molecular impacts counted exactly (no time stepping).

N point molecules in a cube of side L with specular walls and no collisions between them. Only the
motion along x matters for the wall at x = L. Unfolded onto a circle of length 2L, a molecule moves
as X = x0 + v_x t and hits that wall whenever X crosses L + 2kL, so its hits in a window are
counted in closed form (walls.py). Everything is computed in the units L and v_th = sqrt(k_B T/m): the
pressure ratios, hit counts and figure curves then depend only on (N, t_w, sampling), identically
for every temperature and species (common random numbers), and p_sim = ratio * p_ideal.
"""

from __future__ import annotations

import numpy as np

from ...physics.base import Model, Output, Param
from ...physics.numerics import Measurement, Numerics
from .walls import TRAIN_BINS, RecordCache, molecules, replayed_hits, sample_ratio, wall_record

K_B = 1.380649e-23  # J/K, exact SI
ATOMIC_MASS = 1.66053906660e-27  # kg
BOX_SIDE = 100e-9  # m
SPECIES = ("He", "Ne", "N2", "O2", "Ar", "Xe")
# Molecular masses in u. N2 is 2 x 14.0067: the spec's readouts at the defaults (v_th 298.40 m/s)
# need it; the rounded 28.014 would show 298.39.
MASS_U = np.array([4.0026, 20.180, 28.0134, 31.998, 39.948, 131.29])
HIST_SPAN = 4.0  # the v_x histogram covers |v_x| <= 4 v_th
HIST_SIZE = 2 * int(2 * HIST_SPAN / 0.25) + 2  # vertices of the finest histogram (bins of 0.25 v_th)

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
        Param(
            "t_w",
            "t<sub>w</sub>",
            "L/vₜₕ",
            100.0,
            lo=0.0,
            lo_open=True,
            description="averaging window in units of L/v_th",
        ),
        Param.choice(
            "sampling",
            "sampling",
            ("quantile", "random"),
            "quantile",
            description="how velocities and positions are drawn",
        ),
        Param.choice(
            "dim", "dimensions", ("1D", "2D", "3D"), "3D", description="directions the molecules move in"
        ).with_effect("dimension"),
        Param(
            "tau_c", "τ<sub>c</sub>", "L/vₜₕ", 0.0, lo=0.0, description="duration of one impact (a triangular pulse)"
        ).with_effect("contact_duration"),
        Param(
            "alpha",
            "α",
            "",
            0.0,
            lo=0.0,
            hi=1.0,
            description="accommodation: the fraction of impacts re-emitted diffusely at T",
        ).with_effect("wall_law"),
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
        Output(
            "hist_x",
            "v<sub>x</sub>/v<sub>th</sub> (histogram vertices)",
            "",
            ("N",),
            decimals=2,
            size=HIST_SIZE,
            ragged=True,
        ),
        Output(
            "hist_y",
            "probability density of v<sub>x</sub>/v<sub>th</sub>",
            "",
            ("N", "sampling"),
            decimals=3,
            size=HIST_SIZE,
            ragged=True,
        ),
        # dimension: equipartition gives every direction k_B T/2, so only the totals depend on d.
        Output(
            "v_rms_d",
            "v<sub>rms</sub> = √d v<sub>th</sub>",
            "m/s",
            ("T", "species", "dim"),
            decimals=2,
            effect="dimension",
        ),
        Output("E_k", "⟨E<sub>k</sub>⟩ = (d/2)k<sub>B</sub>T", "zJ", ("T", "dim"), decimals=3, effect="dimension"),
        # contact_duration: each impact a triangular pulse of width tau_c centred on the point-particle hit.
        Output(
            "train_soft",
            "force on the wall / p<sub>ideal</sub>L²",
            "",
            (*_WINDOW, "tau_c"),
            decimals=2,
            size=_TRAIN_SIZE,
            effect="contact_duration",
        ),
        Output(
            "running_soft",
            "running mean p(t)/p<sub>ideal</sub>",
            "",
            (*_WINDOW, "tau_c"),
            decimals=3,
            size=TRAIN_BINS,
            effect="contact_duration",
        ),
        # wall_law: Maxwell's wall, a fraction alpha of impacts re-emitted with the flux-weighted Maxwellian at T.
        Output(
            "ratio_wall", "p<sub>sim</sub>/p<sub>ideal</sub>", "", (*_WINDOW, "alpha"), decimals=6, effect="wall_law"
        ),
        Output("hits_wall", "wall hits", "", (*_WINDOW, "alpha"), decimals=0, effect="wall_law"),
        Output(
            "train_wall",
            "force on the wall / p<sub>ideal</sub>L²",
            "",
            (*_WINDOW, "alpha"),
            decimals=2,
            size=_TRAIN_SIZE,
            effect="wall_law",
        ),
        Output(
            "running_wall",
            "running mean p(t)/p<sub>ideal</sub>",
            "",
            (*_WINDOW, "alpha"),
            decimals=3,
            size=TRAIN_BINS,
            effect="wall_law",
        ),
    )
    effects = ("dimension", "contact_duration", "wall_law")
    # docs/physics/kinetic.md: exact unfolded counting dominates time stepping (no trade-off to expose); the
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
        records = RecordCache(np.unique(x["t_w"]))

        def per_window(read, size=(), *extra):
            return _per_case(lambda n, tau, mode, *more: read(records.get(n, tau, mode, *more)), size, *window, *extra)

        def per_soft_window(read, size):
            return _per_case(lambda *case: read(records.get_soft(*case)), size, *window, x["tau_c"])

        formulas = {
            "v_th": lambda: np.sqrt(thermal / mass),
            "v_rms": lambda: np.sqrt(3.0 * thermal / mass),
            "p_ideal": lambda: count * thermal / BOX_SIDE**3,
            "ratio_sample": lambda: _per_case(
                lambda n, mode: sample_ratio(*molecules(n, mode)), (), count, x["sampling"]
            ),
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
