"""What one solved bubble is: how a run ends (statuses and their codes), its cap, its sample grid,
its events and the `Run` it comes back as. Both solving paths, compiled and scipy's, speak it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .kernel_march import (
    CAP_CODE,
    CORE_CODE,
    ENDED,
    FAILED_CODE,
    G_ACCELERATION,
    G_RADIUS_LEVEL,
    G_SPEED,
    G_SPEED_LEVEL,
    KM_CODE,
    MACH_CODE,
    POINT_CODE,
    UNBOUNDED_CODE,
)
from .terms import CORE_MARGIN, EPSILON, Problem

CURVE_POINTS = 401  # samples of R(t) over the run; the middle one is t = T for a two-period drive

# Run statuses: how the run ended.
OK = "ok"  # reached the end of its window
MACH = "mach"  # the incompressible wall reached |Ṙ| = c
KM_STOP = "km_limit"  # |Ṙ| reached 0.9c, outside Keller–Miksis validity
POINT = "point"  # the empty collapse reached R = εR_i
CORE = "core"  # the van der Waals hard core was reached: the tolerance is too loose
UNBOUNDED_GROWTH = "unbounded"  # R reached 10 R_B
CAP_NFEV = "cap_nfev"  # the evaluation cap was hit
FAILED = "failed"  # the solver gave up (step size underflow)


# Each status's code, as the event table and the compiled march and reading name it.
STATUS_CODES = {
    OK: ENDED,
    FAILED: FAILED_CODE,
    CAP_NFEV: CAP_CODE,
    MACH: MACH_CODE,
    KM_STOP: KM_CODE,
    POINT: POINT_CODE,
    CORE: CORE_CODE,
    UNBOUNDED_GROWTH: UNBOUNDED_CODE,
}
STATUS_OF = {code: status for status, code in STATUS_CODES.items()}
RECORDS = {"max": 1, "min": 2, "speed": 3}  # an event table's record codes (split_hits takes them in this order)
ROLE_OF = {code: role for role, code in RECORDS.items()}


@dataclass(frozen=True)
class Caps:
    """Hard limit on one solve: right-hand-side evaluations (event functions included). Never seconds:
    a wall-clock cap would make a busy machine's build differ from a quiet one's."""

    max_nfev: int = 200_000


REFERENCE_CAPS = Caps(max_nfev=3_000_000)  # a reference may cost much more than the page's solve


@dataclass(frozen=True, eq=False)
class Run:
    """One solved bubble (nondimensional): samples on the grid, extrema from events, how it ended."""

    status: str
    method: str
    rtol: float
    tau: np.ndarray  # the sample grid over [0, τ_end]
    r: np.ndarray  # r on the grid, NaN after the run stopped
    v: np.ndarray  # ṙ on the grid, NaN after the run stopped
    end: tuple[float, float, float]  # (τ, r, ṙ) where the run stopped
    maxima: np.ndarray  # (τ, r) of every maximum of r (event ṙ = 0, falling)
    minima: np.ndarray  # (τ, r) of every minimum of r (event ṙ = 0, rising)
    speeds: np.ndarray  # (τ, ṙ) at every extremum of ṙ (event r̈ = 0)
    nfev: int  # the solver's right-hand-side evaluations
    seconds: float


@dataclass(frozen=True)
class Event:
    """g(τ, y) = 0 crossed in `direction` (+1 rising, −1 falling); a terminal one ends the run."""

    g: object
    direction: int
    stop: str = ""  # the run status when terminal, "" when it only records
    records: str = ""  # "max", "min" or "speed": which extrema this event finds


@lru_cache(maxsize=1024)
def sample_grid(tau_end: float) -> np.ndarray:
    """The fixed sample times of a run, CURVE_POINTS over [0, τ_end] (read-only: runs of one length share it)."""
    return frozen(np.linspace(0.0, tau_end, CURVE_POINTS))


def event_table(pb: Problem) -> np.ndarray:
    """The events of a run as rows (g's kind, level, direction, stop code, record code): the extrema of r
    and ṙ (recorded) and the terminal events the composed terms need. Both solving paths read it."""
    rows = [(G_SPEED, 0.0, -1, "", "max"), (G_SPEED, 0.0, +1, "", "min"), (G_ACCELERATION, 0.0, 0, "", "speed")]
    limit = pb.speed_limit
    if math.isfinite(limit):
        stop = MACH if limit == pb.sound else KM_STOP
        rows += [(G_SPEED_LEVEL, limit, +1, stop, ""), (G_SPEED_LEVEL, -limit, -1, stop, "")]
    if pb.singular:
        rows.append((G_RADIUS_LEVEL, EPSILON, -1, POINT, ""))
    if pb.gas and pb.eta:
        rows.append((G_RADIUS_LEVEL, pb.eta * (1.0 + CORE_MARGIN), -1, CORE, ""))
    if math.isfinite(pb.r_unbounded):
        rows.append((G_RADIUS_LEVEL, pb.r_unbounded, +1, UNBOUNDED_GROWTH, ""))
    codes = [
        (kind, level, direction, STATUS_CODES[stop] if stop else 0, RECORDS.get(role, 0))
        for kind, level, direction, stop, role in rows
    ]
    return np.array(codes, float)


def unreached(grid: np.ndarray, y0) -> np.ndarray:
    """The samples (r, ṙ) of a run at its start `y0`, NaN at every later point of `grid` until reached."""
    samples = np.full((len(grid), 2), np.nan)
    samples[0] = y0
    return samples


def run_from(
    status: str,
    method: str,
    rtol: float,
    grid: np.ndarray,
    samples: np.ndarray,
    last,
    maxima=(),
    minima=(),
    speeds=(),
    nfev: int = 0,
    seconds: float = 0.0,
) -> Run:
    """The Run of `samples` on `grid`, ended at `last` (τ, r, ṙ) with `status`; the events it recorded are rows
    (τ, r, ṙ), of which maxima and minima keep (τ, r) and speeds (τ, ṙ)."""
    maxima, minima = (frozen([(t, r) for t, r, _ in rows]).reshape(-1, 2) for rows in (maxima, minima))
    speeds = frozen([(t, v) for t, _, v in speeds]).reshape(-1, 2)
    return Run(
        status,
        method,
        rtol,
        frozen(grid),
        frozen(samples[:, 0]),
        frozen(samples[:, 1]),
        tuple(last),
        maxima,
        minima,
        speeds,
        nfev,
        seconds,
    )


def frozen(array, copy: bool = True) -> np.ndarray:
    """`array` as a read-only C-ordered float array, as a Run holds its arrays."""
    array = np.array(array, float, order="C", copy=copy or None)  # one layout: the compiled reading has one signature
    array.setflags(write=False)
    return array
