"""K4 helpers: one bubble solved with terminal events and hard caps, or by the analytic collapse.

Every solve stops at a terminal event (collapse to εR_i, |Ṙ| = c or 0.9c, the hard core,
unbounded growth) or at its evaluation cap, and comes back as data: a `Run` with a status, never an
exception, a hang or a NaN. No cap reads a clock, so a run ends the same way on any machine at any
load. Samples on the fixed grid are taken from each accepted step's interpolant as the step is made,
so memory stays bounded whatever the solver does.

Two paths solve the same problem with the same events: the compiled one (numba: DOP853, or Radau
IIA with the analytic Jacobian where the terms are stiff), which the book's scenes use, and scipy's
solvers, kept as the reference the build checks against and for the accuracy experiments.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.integrate import BDF, DOP853, LSODA, RK45, Radau
from scipy.optimize import brentq

from .terms import (
    CORE_MARGIN,
    EPSILON,
    KELLER_MIKSIS,
    Problem,
    make_rhs,
    mach_one_radius,
    rayleigh_fraction,
    rayleigh_radius,
    rayleigh_tau,
)
from ...physics import compiled
from .kernel_march import (
    CAP_CODE, CORE_CODE, DOP853_METHOD, ENDED, FAILED_CODE, G_ACCELERATION, G_RADIUS_LEVEL, G_SPEED, G_SPEED_LEVEL, KM_CODE,
    MACH_CODE, POINT_CODE, RADAU_METHOD, UNBOUNDED_CODE, march, split_hits,
)
from . import kernel_read
from .kernel_terms import pack
from ...physics.numerics import Numerics

SOLVERS = {"RK45": RK45, "DOP853": DOP853, "Radau": Radau, "BDF": BDF, "LSODA": LSODA}
COMPILED = {"compiled-DOP853": DOP853_METHOD, "compiled-Radau": RADAU_METHOD}  # the same steppers, compiled
ANALYTIC = "analytic"
STIFF = 1e3  # 4µT/(ρR0²) above which explicit methods are stability-limited (physics.md §11.2 C)
EXPLICIT, IMPLICIT = "compiled-DOP853", "compiled-Radau"  # what `auto` picks off and on stiff terms
# rtol of `auto`: the loosest at which every readout of the book's bubble scenes shows the digits of a
# tight reference at every stop (the sweep on the accuracy page; physics.md §11.2 chose 1e-6 for 1e-3 R0).
EXPLICIT_RTOL, IMPLICIT_RTOL = 1e-8, 1e-8
AUTO = "auto"  # the method setting that lets the composed terms choose (analytic, compiled DOP853 or Radau)
REFERENCE_RTOL, REFERENCE_STIFF = 1e-12, 1e-10  # the check's tight solutions (non-stiff, stiff)
ATOL_PER_RTOL = 1e-3  # nondimensional: atol = 1e-3 rtol on r ~ 1 and ṙ ~ 1
# ... but on stiff terms, for `auto` and the references, never below 1e-11: in a quasi-static stretch of
# a stiff run ṙ ≈ 0, its round-off exceeds a smaller atol and the step size collapses (Radau at rtol 1e-10 ran into 3e6 evaluations on a 0.1 µm
# nucleus with atol 1e-13, scipy's and the compiled one alike, and at 2 stops of the Blake scene with
# 1e-12; with 1e-11 every stop of R0 ≤ 1 µm takes at most 1.3e4).
ATOL_FLOOR = 1e-11
CURVE_POINTS = 401  # samples of R(t) over the run; the middle one is t = T for a two-period drive
EPS = np.finfo(float).eps

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
STATUS_CODES = {OK: ENDED, FAILED: FAILED_CODE, CAP_NFEV: CAP_CODE, MACH: MACH_CODE, KM_STOP: KM_CODE, POINT: POINT_CODE,
                CORE: CORE_CODE, UNBOUNDED_GROWTH: UNBOUNDED_CODE}
_STATUS_OF = {code: status for status, code in STATUS_CODES.items()}
_RECORDS = {"max": 1, "min": 2, "speed": 3}  # an event table's record codes (split_hits takes them in this order)


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


class _CapHit(Exception):
    def __init__(self, status: str):
        super().__init__(status)
        self.status = status


class _Budget:
    """The right-hand side, counted: raises _CapHit past the cap."""

    def __init__(self, fun, caps: Caps):
        self.fun, self.caps, self.calls = fun, caps, 0

    def __call__(self, t, y):
        self.calls += 1
        if self.calls > self.caps.max_nfev:
            raise _CapHit(CAP_NFEV)
        return self.fun(t, y)


@dataclass(frozen=True)
class Event:
    """g(τ, y) = 0 crossed in `direction` (+1 rising, −1 falling); a terminal one ends the run."""

    g: object
    direction: int
    stop: str = ""  # the run status when terminal, "" when it only records
    records: str = ""  # "max", "min" or "speed": which extrema this event finds


def default_atol(rtol: float) -> float:
    """The absolute tolerance that goes with rtol: 1e-3 rtol."""
    return rtol * ATOL_PER_RTOL


def stiff_atol(pb: Problem, rtol: float) -> float | None:
    """The absolute tolerance `auto` and the references use: at least ATOL_FLOOR on stiff terms, else the default."""
    return max(default_atol(rtol), ATOL_FLOOR) if pb.stiffness > STIFF else None


@lru_cache(maxsize=1024)
def sample_grid(tau_end: float) -> np.ndarray:
    """The fixed sample times of a run, CURVE_POINTS over [0, τ_end] (read-only: runs of one length share it)."""
    return _frozen(np.linspace(0.0, tau_end, CURVE_POINTS))


def choose_method(pb: Problem) -> tuple[str, float]:
    """The solver and rtol the composed terms call for (physics.md §11.2 verdicts)."""
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
def solve(pb: Problem, method: str | None = None, rtol: float | None = None, caps: Caps = Caps(),
          atol: float | None = None) -> Run:
    """Solve one bubble from rest at r = 1, with the chosen (or the given) method; cached."""
    if method is None:
        method, rtol = choose_method(pb)
    if method == ANALYTIC:
        return rayleigh_run(pb)
    return integrate(pb, (1.0, 0.0), method, rtol, caps, atol=atol)


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
    codes = [(kind, level, direction, STATUS_CODES[stop] if stop else 0, _RECORDS.get(role, 0))
             for kind, level, direction, stop, role in rows]
    return np.array(codes, float)


def bubble_events(pb: Problem, fun) -> list[Event]:
    """The event table as scipy-path Events, with `fun` the (counted) right-hand side."""
    def g(kind: int, level: float):
        if kind == G_ACCELERATION:
            return lambda t, y: fun(t, y)[1]
        column = 0 if kind == G_RADIUS_LEVEL else 1
        return lambda t, y: y[column] - level

    roles = {code: role for role, code in _RECORDS.items()}
    return [Event(g(int(kind), level), int(direction), _STATUS_OF[int(stop)] if stop else "", roles.get(int(record), ""))
            for kind, level, direction, stop, record in event_table(pb)]


def integrate_compiled(pb: Problem, y0, method: str, rtol: float, caps: Caps = Caps(), atol: float | None = None) -> Run:
    """The compiled path of `integrate`: the same events, samples and statuses, no Python per step."""
    ensure_compiled()
    return _marched(pb, y0, method, rtol, caps, atol)


def _marched(pb: Problem, y0, method: str, rtol: float, caps: Caps, atol: float | None) -> Run:
    """integrate_compiled once the kernels are ready (the warm-up calls it to compile them)."""
    start = time.perf_counter()
    grid = sample_grid(pb.tau_end)
    atol = default_atol(rtol) if atol is None else atol
    if pb.compressible == KELLER_MIKSIS and abs(y0[1]) >= pb.speed_limit:
        return _make_run(KM_STOP, method, rtol, _Stepper([], grid, y0), 0, time.perf_counter() - start)
    marched = march(COMPILED[method], pack(pb), np.array(y0, float), rtol, atol, pb.tau_end, grid, event_table(pb),
                    caps.max_nfev)
    return _run_of(marched, method, rtol, grid, start)


def _run_of(marched, method: str, rtol: float, grid: np.ndarray, start: float) -> Run:
    """The Run of what `march` returned."""
    code, end, samples, hits, nfev = marched
    maxima, minima, speeds = (_frozen(rows, copy=False) for rows in split_hits(hits, *_RECORDS.values()))
    return Run(_STATUS_OF[code], method, rtol, grid, _frozen(samples[:, 0]), _frozen(samples[:, 1]),
               (float(end[0]), float(end[1]), float(end[2])), maxima, minima, speeds, int(nfev), time.perf_counter() - start)


# The kernels in two parts of about 15 and 5 s of compiling, which processes can compile side by side:
# the stepping (`march`) and the reading of a run (`read`).
KERNEL_PARTS = ("march", "read")


def ensure_compiled(part: str | None = None) -> tuple[float, bool]:
    """Compile the bubble's kernels, or load them from the cache (once per process): (seconds, compiled).

    `part` (one of KERNEL_PARTS): only those kernels, into the cache, for a process compiling beside others."""
    pb = Problem(gas=1.0, kappa=1.4, visc=0.01, drive=0.5, omega=1.0, tau_end=0.5)

    def warm_up():  # each entry point once, with the types of the build's calls
        if part in (None, "march"):
            for method in COMPILED:
                _marched(pb, (1.0, 0.0), method, 1e-6, Caps(10_000), 1e-9)
        if part in (None, "read"):
            grid = sample_grid(pb.tau_end)  # a run as `march` returns one, made up: reading it compiles no stepping
            made_up = (ENDED, (pb.tau_end, 1.0, 0.0), np.ones((grid.shape[0], 2)), np.zeros((0, 4)), 0)
            run = _run_of(made_up, EXPLICIT, 1e-6, grid, 0.0)
            q = np.ones(kernel_read.READING_SIZE)  # a reading of any point whose window is the run's
            q[kernel_read.Q_TAU_END] = q[kernel_read.Q_PART] = pb.tau_end
            kernel_read.read(q, run.tau, run.r, run.v, run.end, STATUS_CODES[run.status], run.maxima, run.minima,
                             run.speeds)

    return compiled.prepare(warm_up, part, KERNEL_PARTS)


def integrate(pb: Problem, y0, method: str, rtol: float, caps: Caps = Caps(), events=None, atol: float | None = None) -> Run:
    """Step `method` from y0 over [0, τ_end] with events and caps; always returns a Run.

    atol defaults to 1e-3 rtol: r and ṙ are of order one in these units. A compiled method takes only
    the bubble's own events.
    """
    if method in COMPILED and events is None:
        return integrate_compiled(pb, y0, method, rtol, caps, atol)
    start = time.perf_counter()
    budget = _Budget(make_rhs(pb), caps)
    stepper = _Stepper(bubble_events(pb, budget) if events is None else events, sample_grid(pb.tau_end), y0)
    atol = default_atol(rtol) if atol is None else atol
    with np.errstate(over="ignore", invalid="ignore"):  # wild trial stages may overflow; their steps are rejected
        status, solver = _run_guarded(pb, y0, method, rtol, atol, budget, stepper)
    nfev = budget.calls if solver is None else solver.nfev
    return _make_run(status, method, rtol, stepper, nfev, time.perf_counter() - start)


def _run_guarded(pb: Problem, y0, method: str, rtol: float, atol: float, budget: _Budget, stepper: "_Stepper"):
    """Create the solver and step it; a cap, an overflow or an invalid start becomes a status."""
    if pb.compressible == KELLER_MIKSIS and abs(y0[1]) >= pb.speed_limit:
        return KM_STOP, None  # already outside Keller–Miksis validity: nothing to integrate
    solver = None
    try:
        solver = SOLVERS[method](budget, 0.0, np.asarray(y0, float), pb.tau_end, rtol=rtol, atol=atol)
        return stepper.run(solver), solver
    except _CapHit as cap:
        return cap.status, solver
    except ArithmeticError:  # an overflow in a term: the run is abandoned, never a crash
        return FAILED, solver


class _Stepper:
    """The stepping loop: events located on each step's interpolant, samples taken as it goes."""

    def __init__(self, events, grid, y0):
        self.events, self.grid = events, grid
        self.hits: list[list] = [[] for _ in events]
        self.samples = np.full((len(grid), 2), np.nan)
        self.samples[0] = y0
        self.next = 1
        self.last = (0.0, float(y0[0]), float(y0[1]))

    def run(self, solver) -> str:
        """Step until the end, a terminal event or a failure; return the status."""
        g_old = [e.g(0.0, solver.y) for e in self.events]
        while True:
            if solver.step() is not None or solver.status == "failed" or not np.all(np.isfinite(solver.y)):
                return FAILED
            dense = _Lazy(solver)  # built only if an event or a sample falls in this step
            g_new = [e.g(solver.t, solver.y) for e in self.events]
            stop = self._locate(g_old, g_new, solver.t_old, solver.t, dense)
            self._sample(dense, stop[0] if stop else solver.t)
            if stop:
                self.last = stop[:3]
                return stop[3]
            self.last = (float(solver.t), float(solver.y[0]), float(solver.y[1]))
            if solver.status == "finished":
                return OK
            g_old = g_new

    def found(self, role: str) -> list:
        """(τ, r, ṙ) of every event recorded in `role` ("max", "min" or "speed")."""
        return [row for event, rows in zip(self.events, self.hits) if event.records == role for row in rows]

    def _locate(self, g_old, g_new, t_old, t_new, dense):
        """Record every event crossed in this step up to the first terminal one; return that one."""
        found = []
        for index, (event, a, b) in enumerate(zip(self.events, g_old, g_new)):
            rising, falling = a <= 0.0 <= b and a != b, a >= 0.0 >= b and a != b
            if (rising and event.direction >= 0) or (falling and event.direction <= 0):
                found.append((_root(event, dense, t_old, t_new), index))
        terminal = min(((t, i) for t, i in found if self.events[i].stop), default=None)
        for t, index in found:
            if terminal is None or t <= terminal[0]:
                y = dense(t)
                self.hits[index].append((t, float(y[0]), float(y[1])))
        if terminal is None:
            return None
        y = dense(terminal[0])
        return (terminal[0], float(y[0]), float(y[1]), self.events[terminal[1]].stop)

    def _sample(self, dense, t_stop: float) -> None:
        while self.next < len(self.grid) and self.grid[self.next] <= t_stop:
            self.samples[self.next] = dense(self.grid[self.next])
            self.next += 1


class _Lazy:
    """A step's interpolant, made on first use (DOP853 spends three evaluations on it)."""

    def __init__(self, solver):
        self.solver, self.interpolant = solver, None

    def __call__(self, t):
        if self.interpolant is None:
            self.interpolant = self.solver.dense_output()
        return self.interpolant(t)


def _root(event: Event, dense, t_old: float, t_new: float) -> float:
    """The crossing time on the step's interpolant (its end if the interpolant misses the bracket)."""
    g = lambda t: event.g(t, dense(t))  # noqa: E731
    try:
        return brentq(g, t_old, t_new, xtol=4 * EPS, rtol=4 * EPS)
    except ValueError:  # an interpolant that does not pass exactly through y_old (LSODA's history)
        return t_new


def _frozen(array, copy: bool = True) -> np.ndarray:
    array = np.array(array, float, order="C", copy=copy or None)  # one layout: the compiled reading has one signature
    array.setflags(write=False)
    return array


def _pairs(rows, column: int) -> np.ndarray:
    return _frozen([(row[0], row[column]) for row in rows]).reshape(-1, 2)


def _make_run(status: str, method: str, rtol: float, stepper: _Stepper, nfev: int, seconds: float) -> Run:
    r, v = _frozen(stepper.samples[:, 0]), _frozen(stepper.samples[:, 1])
    maxima, minima, speeds = _pairs(stepper.found("max"), 1), _pairs(stepper.found("min"), 1), _pairs(stepper.found("speed"), 2)
    return Run(status, method, rtol, _frozen(stepper.grid), r, v, tuple(stepper.last), maxima, minima, speeds, nfev, seconds)


def rayleigh_run(pb: Problem) -> Run:
    """The empty collapse in closed form: r(τ) from betaincinv up to |Ṙ| = c (or r = ε)."""
    start = time.perf_counter()
    delta = pb.p_inf - pb.vapour
    tau_c = rayleigh_tau(delta)
    r_stop = max(float(mach_one_radius(delta, pb.sound)), EPSILON)
    tau_stop = tau_c * float(rayleigh_fraction(r_stop))
    speed = lambda r: -np.sqrt(2.0 * delta / 3.0 * (np.asarray(r) ** -3 - 1.0))  # noqa: E731  Ṙ² of ref. 1
    stepper = _Stepper([Event(None, -1, records="max")], sample_grid(pb.tau_end), (1.0, 0.0))
    stepper.hits[0].append((0.0, 1.0, 0.0))  # the start at rest is the maximum; r and ṙ are monotonic after it
    reached = stepper.grid <= tau_stop
    r = rayleigh_radius(stepper.grid[reached] / tau_c)
    stepper.samples[reached] = np.stack([r, speed(r)], axis=1)
    stepper.last = (tau_stop, r_stop, float(speed(r_stop)))
    status = MACH if r_stop > EPSILON else POINT
    return _make_run(status, ANALYTIC, 0.0, stepper, 0, time.perf_counter() - start)
