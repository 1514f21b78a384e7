"""The scipy path of `solve.integrate`: scipy's solvers stepped in Python, with the events of the
compiled path located on each accepted step's interpolant and the samples taken as it goes.

It is the reference the compiled solvers are checked against in the tests and the bench, and the
path of the accuracy experiments. A cap, an overflow or a failed step becomes the Run's status.
"""

from __future__ import annotations

import time

import numpy as np
from scipy.integrate import BDF, DOP853, LSODA, RK45, Radau
from scipy.optimize import brentq

from .kernel_march import G_ACCELERATION, G_RADIUS_LEVEL
from .run import (
    CAP_NFEV,
    FAILED,
    KM_STOP,
    OK,
    ROLE_OF,
    STATUS_OF,
    Caps,
    Event,
    Run,
    event_table,
    run_from,
    sample_grid,
    unreached,
)
from .terms import KELLER_MIKSIS, Problem, make_rhs

SOLVERS = {"RK45": RK45, "DOP853": DOP853, "Radau": Radau, "BDF": BDF, "LSODA": LSODA}
EPS = np.finfo(float).eps


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


def bubble_events(pb: Problem, fun) -> list[Event]:
    """The event table as scipy-path Events, with `fun` the (counted) right-hand side."""

    def g(kind: int, level: float):
        if kind == G_ACCELERATION:
            return lambda t, y: fun(t, y)[1]
        column = 0 if kind == G_RADIUS_LEVEL else 1
        return lambda t, y: y[column] - level

    return [
        Event(g(int(kind), level), int(direction), STATUS_OF[int(stop)] if stop else "", ROLE_OF.get(int(record), ""))
        for kind, level, direction, stop, record in event_table(pb)
    ]


def integrate_scipy(pb: Problem, y0, method: str, rtol: float, atol: float, caps: Caps, events=None) -> Run:
    """Step scipy's `method` from y0 over [0, τ_end] with `events` (the bubble's own by default) and caps."""
    start = time.perf_counter()
    budget = _Budget(make_rhs(pb), caps)
    stepper = Stepper(bubble_events(pb, budget) if events is None else events, sample_grid(pb.tau_end), y0)
    with np.errstate(over="ignore", invalid="ignore"):  # wild trial stages may overflow; their steps are rejected
        status, solver = _run_guarded(pb, y0, method, rtol, atol, budget, stepper)
    nfev = budget.calls if solver is None else solver.nfev
    return _stepped_run(status, method, rtol, stepper, nfev, time.perf_counter() - start)


def _run_guarded(pb: Problem, y0, method: str, rtol: float, atol: float, budget: _Budget, stepper: Stepper):
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


class Stepper:
    """The stepping loop: events located on each step's interpolant, samples taken as it goes."""

    def __init__(self, events, grid, y0):
        self.events, self.grid = events, grid
        self.hits: list[list] = [[] for _ in events]
        self.samples = unreached(grid, y0)
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

    def events_of(self, role: str) -> list:
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


def _stepped_run(status: str, method: str, rtol: float, stepper: Stepper, nfev: int, seconds: float) -> Run:
    """The Run of what `stepper` sampled and recorded, ended with `status`."""
    return run_from(
        status,
        method,
        rtol,
        stepper.grid,
        stepper.samples,
        stepper.last,
        stepper.events_of("max"),
        stepper.events_of("min"),
        stepper.events_of("speed"),
        nfev,
        seconds,
    )
