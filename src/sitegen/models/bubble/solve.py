"""K4 helpers: one bubble solved with terminal events and hard caps, or by the analytic collapse.

Every solve stops at a terminal event (collapse to εR_i, |Ṙ| = c or 0.9c, the hard core,
unbounded growth) or at its evaluation cap, and comes back as data: a `Run` (run.py) with a status,
never an exception, a hang or a NaN. No cap reads a clock, so a run ends the same way on any machine
at any load. Samples on the fixed grid are taken from each accepted step's interpolant as the step is
made, so memory stays bounded whatever the solver does.

Two paths solve the same problem with the same events: the compiled one (numba: DOP853, or Radau
IIA with the analytic Jacobian where the terms are stiff), which the book's scenes use, and scipy's
solvers (scipy_path.py), kept as the reference the build checks against and for the accuracy
experiments. This module chooses the method and its tolerances and runs the compiled path and the
analytic collapse.
"""

from __future__ import annotations

import time
from functools import lru_cache

import numpy as np

from ...physics.numerics import Numerics
from . import kernel_read
from .kernel_march import DOP853_METHOD, ENDED, RADAU_METHOD, march, split_hits
from .kernel_terms import pack
from .run import (
    KM_STOP,
    MACH,
    POINT,
    RECORDS,
    STATUS_CODES,
    STATUS_OF,
    Caps,
    Run,
    event_table,
    frozen,
    run_from,
    sample_grid,
    unreached,
)
from .scipy_path import integrate_scipy
from .terms import (
    EPSILON,
    KELLER_MIKSIS,
    Problem,
    mach_one_radius,
    rayleigh_fraction,
    rayleigh_radius,
    rayleigh_tau,
)

COMPILED = {"compiled-DOP853": DOP853_METHOD, "compiled-Radau": RADAU_METHOD}  # the same steppers, compiled
ANALYTIC = "analytic"
STIFF = 1e3  # 4µT/(ρR0²) above which explicit methods are stability-limited (docs/physics/bubble.md)
EXPLICIT, IMPLICIT = "compiled-DOP853", "compiled-Radau"  # what `auto` picks off and on stiff terms
# rtol of `auto`: the loosest at which every readout of the book's bubble scenes shows the digits of a
# tight reference at every stop (the sweep on the accuracy page; DOP853 at 1e-6 gives 1e-3 R0 on the driven bubble).
EXPLICIT_RTOL, IMPLICIT_RTOL = 1e-8, 1e-8
AUTO = "auto"  # the method setting that lets the composed terms choose (analytic, compiled DOP853 or Radau)
REFERENCE_RTOL, REFERENCE_STIFF = 1e-12, 1e-10  # the accuracy measurement's tight solutions (non-stiff, stiff)
ATOL_PER_RTOL = 1e-3  # nondimensional: atol = 1e-3 rtol on r ~ 1 and ṙ ~ 1
# ... but on stiff terms, for `auto` and the references, never below 1e-11: in a quasi-static stretch of
# a stiff run ṙ ≈ 0, its round-off exceeds a smaller atol and the step size collapses (Radau at rtol 1e-10 ran into 3e6
# evaluations on a 0.1 µm
# nucleus with atol 1e-13, scipy's and the compiled one alike, and at 2 stops of the Blake scene with
# 1e-12; with 1e-11 every stop of R0 ≤ 1 µm takes at most 1.3e4).
ATOL_FLOOR = 1e-11


def default_atol(rtol: float) -> float:
    """The absolute tolerance that goes with rtol: 1e-3 rtol."""
    return rtol * ATOL_PER_RTOL


def stiff_atol(pb: Problem, rtol: float) -> float | None:
    """The absolute tolerance `auto` and the references use: at least ATOL_FLOOR on stiff terms, else the default."""
    return max(default_atol(rtol), ATOL_FLOOR) if pb.stiffness > STIFF else None


def choose_method(pb: Problem) -> tuple[str, float]:
    """The solver and rtol the composed terms call for (the verdicts of docs/physics/bubble.md)."""
    if pb.is_rayleigh:
        return ANALYTIC, 0.0
    if pb.stiffness > STIFF:
        return IMPLICIT, IMPLICIT_RTOL
    return EXPLICIT, EXPLICIT_RTOL


def method_for(pb: Problem, settings: Numerics) -> tuple[str, float, float | None]:
    """(method, rtol, atol) of a scene's settings at one problem: `auto` picks by the composed terms."""
    if settings.method != AUTO:
        return settings.method, settings.rtol, settings.atol
    method, rtol = choose_method(pb)
    if method == ANALYTIC:
        return ANALYTIC, 0.0, None
    rtol = settings.rtol or rtol
    return method, rtol, settings.atol if settings.atol is not None else stiff_atol(pb, rtol)


def reference_for(pb: Problem, method: str) -> tuple[str, float, float | None]:
    """The tight solution a point solved by `method` is checked against in the build.

    The compiled solvers at tight tolerances: DOP853 at rtol 1e-12, or, on stiff terms (where explicit
    methods are stability-limited), Radau at rtol 1e-10; a point solved by one of scipy's methods gets
    scipy's DOP853 at 1e-12 (LSODA at 1e-12 where stiff). scipy's solvers at the same settings cost
    0.7–2.5 s a point (measured: LSODA 1e-12 on a 0.1 µm nucleus, DOP853 1e-12 on preset B), 20–200 times
    the compiled ones, so the compiled references are themselves checked against scipy's in the tests
    (tests/test_bubble_compiled.py) and by `sitegen bench`.
    """
    stiff = pb.stiffness > STIFF
    if method in COMPILED or method == AUTO:
        found = (IMPLICIT, REFERENCE_STIFF) if stiff else (EXPLICIT, REFERENCE_RTOL)
    else:
        found = ("LSODA", REFERENCE_RTOL) if stiff else ("DOP853", REFERENCE_RTOL)
    return (*found, stiff_atol(pb, found[1]))


@lru_cache(maxsize=4096)
def solve(
    pb: Problem, method: str | None = None, rtol: float | None = None, caps: Caps = Caps(), atol: float | None = None
) -> Run:
    """Solve one bubble from rest at r = 1, with the chosen (or the given) method; cached."""
    if method is None:
        method, rtol = choose_method(pb)
    if method == ANALYTIC:
        return rayleigh_run(pb)
    return integrate(pb, (1.0, 0.0), method, rtol, caps, atol=atol)


def integrate_compiled(
    pb: Problem, y0, method: str, rtol: float, caps: Caps = Caps(), atol: float | None = None
) -> Run:
    """The compiled path of `integrate`: the same events, samples and statuses, no Python per step."""
    start = time.perf_counter()
    grid = sample_grid(pb.tau_end)
    atol = default_atol(rtol) if atol is None else atol
    if pb.compressible == KELLER_MIKSIS and abs(y0[1]) >= pb.speed_limit:
        return run_from(
            KM_STOP,
            method,
            rtol,
            grid,
            unreached(grid, y0),
            (0.0, float(y0[0]), float(y0[1])),
            seconds=time.perf_counter() - start,
        )
    marched = march(
        COMPILED[method], pack(pb), np.array(y0, float), rtol, atol, pb.tau_end, grid, event_table(pb), caps.max_nfev
    )
    return _run_of(marched, method, rtol, grid, start)


def _run_of(marched, method: str, rtol: float, grid: np.ndarray, start: float) -> Run:
    """The Run of what `march` returned."""
    code, end, samples, hits, nfev = marched
    maxima, minima, speeds = (frozen(rows, copy=False) for rows in split_hits(hits, *RECORDS.values()))
    return Run(
        STATUS_OF[code],
        method,
        rtol,
        grid,
        frozen(samples[:, 0]),
        frozen(samples[:, 1]),
        (float(end[0]), float(end[1]), float(end[2])),
        maxima,
        minima,
        speeds,
        int(nfev),
        time.perf_counter() - start,
    )


def warm_up() -> None:
    """Call every compiled entry point once, with the types of the build's calls: each is compiled, or loaded
    from the cache, now (for timings that should leave that out)."""
    pb = Problem(gas=1.0, kappa=1.4, visc=0.01, drive=0.5, omega=1.0, tau_end=0.5)
    for method in COMPILED:
        integrate_compiled(pb, (1.0, 0.0), method, 1e-6, Caps(10_000), 1e-9)
    grid = sample_grid(pb.tau_end)  # a run as `march` returns one, made up: reading it compiles no stepping
    made_up = (ENDED, (pb.tau_end, 1.0, 0.0), np.ones((grid.shape[0], 2)), np.zeros((0, 4)), 0)
    run = _run_of(made_up, EXPLICIT, 1e-6, grid, 0.0)
    q = np.ones(kernel_read.READING_SIZE)  # a reading of any point whose window is the run's
    q[kernel_read.Q_TAU_END] = q[kernel_read.Q_PART] = pb.tau_end
    kernel_read.read(q, run.tau, run.r, run.v, run.end, STATUS_CODES[run.status], run.maxima, run.minima, run.speeds)


def integrate(
    pb: Problem, y0, method: str, rtol: float, caps: Caps = Caps(), events=None, atol: float | None = None
) -> Run:
    """Step `method` from y0 over [0, τ_end] with events and caps; always returns a Run.

    atol defaults to 1e-3 rtol: r and ṙ are of order one in these units. A compiled method takes only
    the bubble's own events.
    """
    if method in COMPILED and events is None:
        return integrate_compiled(pb, y0, method, rtol, caps, atol)
    return integrate_scipy(pb, y0, method, rtol, default_atol(rtol) if atol is None else atol, caps, events)


def rayleigh_run(pb: Problem) -> Run:
    """The empty collapse in closed form: r(τ) from betaincinv up to |Ṙ| = c (or r = ε)."""
    start = time.perf_counter()
    delta = pb.p_inf - pb.vapour
    tau_c = rayleigh_tau(delta)
    r_stop = max(float(mach_one_radius(delta, pb.sound)), EPSILON)
    tau_stop = tau_c * float(rayleigh_fraction(r_stop))
    speed = lambda r: -np.sqrt(2.0 * delta / 3.0 * (np.asarray(r) ** -3 - 1.0))  # noqa: E731  Ṙ² of ref. 1
    grid = sample_grid(pb.tau_end)
    samples = unreached(grid, (1.0, 0.0))
    reached = grid <= tau_stop
    r = rayleigh_radius(grid[reached] / tau_c)
    samples[reached] = np.stack([r, speed(r)], axis=1)
    status = MACH if r_stop > EPSILON else POINT
    # the start at rest is the maximum; r and ṙ are monotonic after it
    return run_from(
        status,
        ANALYTIC,
        0.0,
        grid,
        samples,
        (tau_stop, r_stop, float(speed(r_stop))),
        maxima=[(0.0, 1.0, 0.0)],
        seconds=time.perf_counter() - start,
    )
