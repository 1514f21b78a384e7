"""K4 helpers: one point of a slider grid, composed into a nondimensional Problem and read back.

`compose` turns parameter values and the enabled effects into a Problem with only those terms
(and the initial state consistent with them); `read_run` turns a solved Run into every dynamic
output in display units, with inf where a value does not exist (the page shows "—").
"""
from __future__ import annotations

import math

import numpy as np

from . import terms
from .solve import (
    ANALYTIC, CAP_NFEV, CORE, CURVE_POINTS, EXPLICIT, EXPLICIT_RTOL, FAILED, IMPLICIT, IMPLICIT_RTOL, KM_STOP, MACH,
    POINT, STIFF, UNBOUNDED_GROWTH, Run,
)
from .terms import P0, T0, Problem

DRIVE_PERIODS = 2  # the driven bubble runs two acoustic periods from rest at R0
CURVE_EXTREMA = 200  # event-detected extrema merged into the drawn curve (the deepest, if more)
CURVE_SIZE = CURVE_POINTS + CURVE_EXTREMA + 1  # samples, extrema and the stop
CURVE_GAP = 1e-3  # the drawn curve's resolution in y (its 3 decimals): extrema closer to the chord add nothing

NEEDS = {"vdw_hard_core": "gas", "thermal_damping": "gas", "radiation": "gas"}
PROTOCOLS = ("step", "drive", "ramp")  # what is done to the liquid pressure: one per scene

FLAGS = (
    "valid",
    "incompressible model invalid: max |Ṙ|/c > 0.2 (needs keller_miksis)",
    "incompressible model invalid: the wall reaches |Ṙ| = c, where the curve ends",
    "stopped at |Ṙ| = 0.9c: outside Keller–Miksis validity",
    "stopped at R = 0.01 R₀: the empty cavity collapses to a point",
    "tolerance too loose: the solution reached the van der Waals hard core",
    "stopped at R = 10 R_B: unbounded growth",
    "evaluation cap hit: solve abandoned",
    "solver failed: step size underflow",
)
# Why a dynamic output has no value at a point (0: it has one): how the run ended (FLAGS from 2 on), or
# what the bubble lacks for that quantity.
MISSING = FLAGS + ("no gas in the bubble: nothing is compressed", "no van der Waals hard core (h = 0)",
                   "not reached before the run ended")
_NO_GAS, _NO_CORE, _NOT_REACHED = range(len(FLAGS), len(FLAGS) + 3)
_FLAG_OF_STATUS = {MACH: 2, KM_STOP: 3, POINT: 4, CORE: 5, UNBOUNDED_GROWTH: 6, CAP_NFEV: 7, FAILED: 8}
def _power(rtol: float) -> str:
    """An rtol as a label writes it: 1e−6."""
    return f"{rtol:.0e}".replace("e-0", "e−").replace("e-", "e−")


# The default settings' three choices, then any method at the rtol a scene's `numerics:` line sets.
SCENE_METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA", EXPLICIT, IMPLICIT)
SOLVER_LABELS = ("analytic (betaincinv)", f"DOP853 (compiled), rtol {_power(EXPLICIT_RTOL)}",
                 f"Radau IIA (compiled; stiff: 4µT/ρR₀² > 10³), rtol {_power(IMPLICIT_RTOL)}", "other") + tuple(
    f"{method}, at the scene's rtol" for method in SCENE_METHODS)
BLAKE_LABELS = (
    "settles: it stays below the Blake radius, at a size in equilibrium",
    "passed the Blake radius, then fell back below it",
    "keeps growing: past the Blake radius and still growing",
    "keeps growing, slowly: still below the Blake radius, but past the threshold no size is in equilibrium",
    "unbounded: reached 10 Blake radii",
)

GUARDS = (MACH, KM_STOP, POINT, CORE)  # terminal events that end a run before its window does
TERMINAL = GUARDS + (UNBOUNDED_GROWTH,)
ABANDONED = (CAP_NFEV, FAILED)


def check_effects(effects) -> None:
    """Raise ValueError for an effect set that is not a model: a missing companion or two rivals."""
    for effect, needed in NEEDS.items():
        if effect in effects and needed not in effects:
            raise ValueError(f"effect `{effect}` needs `{needed}`")
    if "radiation" in effects and "keller_miksis" in effects:
        raise ValueError("effects `radiation` and `keller_miksis` exclude each other (Keller–Miksis includes radiation)")
    protocols = [p for p in PROTOCOLS if p in effects]
    if len(protocols) > 1:
        raise ValueError(f"effects {' and '.join(f'`{p}`' for p in protocols)} exclude each other: one pressure history per scene")


class Scales:
    """The SI scales of one point: R_i, t_ref = R_i/U, and the seconds per unit of the figure's x."""

    def __init__(self, point: dict, effects, pb: Problem):
        self.radius = point["R0"] * 1e-6
        self.t_ref = self.radius / math.sqrt(P0 / point["rho"])
        if "drive" in effects:
            self.x_unit, self.x_name = 1.0 / (point["f"] * 1e3), "T"
        elif "ramp" in effects:
            self.x_unit, self.x_name = 1e-6, "µs"
        else:
            self.x_unit, self.x_name = terms.rayleigh_tau(_collapse_dp(pb)) * self.t_ref, "t_c"

    def x(self, tau):
        """Nondimensional time in the figure's unit."""
        return np.asarray(tau, float) * self.t_ref / self.x_unit


def _collapse_dp(pb: Problem) -> float:
    """ΔP = P∞ − P_v of the collapse; its size when negative, 1 when it vanishes (a time scale only)."""
    delta = pb.p_inf - pb.vapour
    return abs(delta) if delta else 1.0


def compose(point: dict, effects) -> tuple[Problem, Scales]:
    """The nondimensional problem of one point with only the enabled terms, and its scales."""
    radius, rho = point["R0"] * 1e-6, point["rho"]
    t_ref = radius / math.sqrt(P0 / rho)
    on = set(effects)
    vapour = point["p_v"] / P0 if "vapour" in on else 0.0
    sigma = point["sigma"] / (P0 * radius) if "surface_tension" in on else 0.0
    visc = point["mu"] / (radius * math.sqrt(rho * P0)) if "viscosity" in on else 0.0
    p_inf = point["p_inf"] if "step" in on else 1.0  # p_inf is in atm and p0 is 1 atm
    fields = dict(p_inf=p_inf, vapour=vapour, sigma=sigma, visc=visc, sound=point["c"] * t_ref / radius)
    if "gas" in on:  # equilibrium at R0 with exactly the enabled terms, unless the step sets the content
        gas = point["gas_content"] * p_inf if "step" in on else 1.0 - vapour + 2.0 * sigma
        fields.update(gas=gas, kappa=point["kappa"], eta=point["h_frac"] if "vdw_hard_core" in on else 0.0)
    if "drive" in on:
        fields.update(drive=point["p_a"], omega=2e3 * math.pi * point["f"] * t_ref)
    if "thermal_damping" in on:
        fields.update(_thermal(point, fields, radius, rho))
    if "keller_miksis" in on or "radiation" in on:
        fields["compressible"] = terms.KELLER_MIKSIS if "keller_miksis" in on else terms.RADIATION
    if "ramp" in on:
        r_b, p_blake = terms.blake_nucleus(sigma, vapour)
        # The depth x = (p0 − p_target)/(p0 − p_Blake): the share of the way from p0 down to the threshold,
        # so x > 1 lies beyond it for every nucleus (p_Blake > 0 for large ones, where p_target/p_Blake
        # would run the wrong way).
        fields.update(ramp_to=1.0 - point["depth"] * (1.0 - float(p_blake)), ramp_time=point["t_ramp"] * 1e-6 / t_ref,
                      r_unbounded=terms.UNBOUNDED * float(r_b))
    pb = Problem(**fields, tau_end=_window(point, on, Problem(**fields), t_ref))
    return pb, Scales(point, on, pb)


def _window(point: dict, on: set, pb: Problem, t_ref: float) -> float:
    """The run's length: two acoustic periods, the ramp and hold, or two Rayleigh times."""
    if "drive" in on:
        return DRIVE_PERIODS * 2.0 * math.pi / pb.omega
    if "ramp" in on:
        return (point["t_ramp"] + point["t_hold"]) * 1e-6 / t_ref
    return 2.0 * terms.rayleigh_tau(_collapse_dp(pb))


def _thermal(point: dict, fields: dict, radius: float, rho: float) -> dict:
    """Prosperetti's effective polytropic exponent and thermal viscosity at the drive frequency
    (or, undriven, at the adiabatic natural frequency)."""
    gamma = point["kappa"]
    if "omega" in fields:
        omega = fields["omega"]
    else:
        omega = terms.natural_omega(Problem(gas=fields["gas"], kappa=gamma, eta=fields["eta"], sigma=fields["sigma"]))
    if omega <= 0.0:  # no gas, or no restoring force: nothing oscillates, the gas law is left as it is
        return {}
    omega_si = omega * math.sqrt(P0 / rho) / radius
    phi = terms.thermal_phi(gamma, point["D_g"] * 1e-6 / (omega_si * radius**2))
    mu_thermal = fields["gas"] * P0 * phi.imag / (4.0 * omega_si)
    return {"kappa": phi.real / 3.0, "visc": fields["visc"] + mu_thermal / (radius * math.sqrt(rho * P0))}


# --- reading one run -------------------------------------------------------------------------------------


def read_run(run: Run, pb: Problem, scales: Scales, effects) -> dict:
    """Every dynamic output of one run, in display units (inf where there is no value)."""
    part = pb.tau_end / DRIVE_PERIODS if "drive" in effects else pb.tau_end
    first, second = _extremes(run, pb, 0.0, part), _extremes(run, pb, part, pb.tau_end)
    to_y = _y_transform(pb, effects)
    out = {
        "R_max": first["r_max"][1], "t_Rmax": scales.x(first["r_max"][0]),
        "R_min": first["r_min"][1], "t_Rmin": scales.x(first["r_min"][0]),
        "mach": first["speed"] / pb.sound,
        "R_max2": second["r_max"][1], "R_min2": second["r_min"][1],
        "flag": _flag(run, pb), "solver": _solver_label(run, pb), "growth": _blake_state(run, pb),
    }
    out.update(_gas_peaks(pb, first["r_min"][1]))
    out.update(_figure_marks(run, scales, to_y, first))
    out.update(_why_missing(out, pb))
    return out


def _why_missing(out: dict, pb: Problem) -> dict:
    """For each number ("<key>_why"): 0 where it has a value, else why not, as an index into MISSING."""
    ended = out["flag"] if out["flag"] >= 2 else _NOT_REACHED
    whys = {}
    for key in ("R_max", "t_Rmax", "R_min", "t_Rmin", "mach", "pg_peak", "Tg_peak", "Rmin_h", "R_max2", "R_min2"):
        reason = 0 if math.isfinite(out[key]) else ended
        if reason and math.isfinite(out["R_min"]):  # the minimum exists: the quantity needs what is missing
            reason = _NO_CORE if key == "Rmin_h" else _NO_GAS if key in ("pg_peak", "Tg_peak") else reason
        whys[f"{key}_why"] = reason
    return whys


def _extremes(run: Run, pb: Problem, a: float, b: float) -> dict:
    """R_max, R_min (τ, r) and max |ṙ| over [a, b] from events, plus the ends of [a, b] if reached.

    A run stopped by a guard inside [a, b] has no R_min there (the collapse it was heading into is
    not computed, e.g. the empty collapse stopped at |Ṙ| = c); an abandoned run has no value at all.
    Ties go to the earliest candidate (events first, then the window's ends).
    """
    missing = (np.inf, np.inf)
    if run.status in ABANDONED:
        return {"r_max": missing, "r_min": missing, "speed": np.inf, "events": (_NONE, _NONE)}
    inside = lambda rows: rows[(rows[:, 0] >= a) & (rows[:, 0] <= b)]  # noqa: E731
    maxima, minima, speeds = inside(run.maxima), inside(run.minima), inside(run.speeds)
    events = maxima, minima
    index = [int(round(t / pb.tau_end * (len(run.tau) - 1))) for t in (a, b)]
    if not math.isnan(run.r[index[1]]):  # the run covered [a, b]: its ends are candidates too
        ends = np.array([(run.tau[k], run.r[k]) for k in index])
        maxima, minima = np.concatenate([maxima, ends]), np.concatenate([minima, ends])
        speeds = np.concatenate([speeds, [(run.tau[k], run.v[k]) for k in index]])
    stop_t, stop_r, stop_v = run.end
    if a <= stop_t <= b and run.status == UNBOUNDED_GROWTH:
        maxima = np.concatenate([maxima, [(stop_t, stop_r)]])
    if a <= stop_t <= b and run.status in (MACH, KM_STOP):
        speeds = np.concatenate([speeds, [(stop_t, stop_v)]])
    if a <= stop_t <= b and run.status in GUARDS:  # the minimum of [a, b] lies beyond the stop: unknown
        minima = _NONE
    return {
        "r_max": tuple(maxima[np.argmax(maxima[:, 1])]) if len(maxima) else missing,
        "r_min": tuple(minima[np.argmin(minima[:, 1])]) if len(minima) else missing,
        "speed": float(np.max(np.abs(speeds[:, 1]))) if len(speeds) else np.inf,
        "events": events,
    }


_NONE = np.empty((0, 2))


def _gas_peaks(pb: Problem, r_min: float) -> dict:
    """Peak gas pressure (GPa), adiabatic temperature (K) and R_min/h at the minimum radius."""
    found = math.isfinite(r_min)
    out = {"pg_peak": np.inf, "Tg_peak": np.inf, "Rmin_h": r_min / pb.eta if found and pb.eta else np.inf}
    if found and pb.gas:
        e3 = pb.eta**3
        compression = (1.0 - e3) / (r_min**3 - e3)
        out.update(pg_peak=pb.gas * compression**pb.kappa * P0 * 1e-9, Tg_peak=T0 * compression ** (pb.kappa - 1.0))
    return out


def _y_transform(pb: Problem, effects):
    """The figure's radius coordinate: log10(R/R0) driven, log10(R/R_B) under a ramp, else R/R0.

    Logarithms because the driven and ramped radii span decades across the sliders' stops.
    """
    if "drive" in effects:
        return lambda r: np.log10(np.asarray(r, float))
    r_b = pb.r_unbounded / terms.UNBOUNDED
    if "ramp" in effects and math.isfinite(r_b):  # without surface tension there is no Blake radius
        return lambda r: np.log10(np.asarray(r, float) / r_b)
    return lambda r: np.asarray(r, float)


def _figure_marks(run: Run, scales: Scales, to_y, first: dict) -> dict:
    """The drawn curve (samples with the extrema and the stop merged in), the stop and the R_max, R_min dots.

    Grid samples alone miss a violent collapse: in preset B they bottom out near 0.5 R0 while the
    event-detected minimum is 0.176 R0 (physics.md §0.3), so the curve passes through the events.
    """
    curve = _curve_points(run, to_y)
    pad = CURVE_SIZE - len(curve)
    out = {
        "curve_x": np.concatenate([scales.x(curve[:, 0]), np.full(pad, np.nan)]),
        "curve_y": np.concatenate([curve[:, 1], np.full(pad, np.nan)]),
        "stop_x": np.full(1, np.nan), "stop_y": np.full(1, np.nan),
    }
    if run.status in TERMINAL:
        out.update(stop_x=scales.x([run.end[0]]), stop_y=to_y([run.end[1]]))
    marked = [row for row in (first["r_max"], first["r_min"])
              if row[0] > 0 and any(np.any(np.all(group == row, axis=1)) for group in first["events"])]
    xs, ys = np.full(2, np.nan), np.full(2, np.nan)
    for k, (t, r) in enumerate(marked):
        xs[k], ys[k] = scales.x(t), to_y(r)
    out.update(mark_x=xs, mark_y=ys)
    return out


def _curve_points(run: Run, to_y) -> np.ndarray:
    """(τ, y) of the grid samples, the visible extrema (the deepest CURVE_EXTREMA) and a terminal stop, in time order.

    An extremum joins the curve only where the line through the grid samples would miss it by more
    than the drawing's resolution (CURVE_GAP in y). That keeps the curve well defined: where R(t) is
    quasi-static, ringing far below the resolution makes tiny extrema (about 1e-10 R0) whose number and
    times differ between any two solvers, and merging them would shift every later point of the curve.
    """
    reached = np.isfinite(run.r)
    tau, y = run.tau[reached], to_y(run.r[reached])
    extrema = np.concatenate([run.maxima, run.minima])
    extrema = extrema[extrema[:, 0] <= run.end[0]]
    extrema = np.stack([extrema[:, 0], to_y(extrema[:, 1])], axis=1)
    extrema = extrema[_visible(extrema, tau, y, run.tau[1] - run.tau[0])]
    if len(extrema) > CURVE_EXTREMA:
        depth = np.abs(extrema[:, 1] - y[0])
        extrema = extrema[np.sort(np.argsort(-depth, kind="stable")[:CURVE_EXTREMA])]
    stop = [(run.end[0], float(to_y(run.end[1])))] if run.status in TERMINAL else []
    points = np.concatenate([np.stack([tau, y], axis=1), extrema, np.reshape(stop, (-1, 2))])
    points = points[np.argsort(points[:, 0], kind="stable")]
    keep = np.concatenate([[True], np.diff(points[:, 0]) > 0])  # one point per time (t = 0 is both)
    return points[keep]


def _visible(extrema: np.ndarray, tau: np.ndarray, y: np.ndarray, spacing: float) -> np.ndarray:
    """Which extrema (τ, y) lie farther than CURVE_GAP from the chord between the grid samples around them
    (all of those past the last sample, where there is no chord)."""
    left = np.floor(extrema[:, 0] / spacing).astype(int)
    inside = left + 1 < len(tau)
    k = np.where(inside, left, 0)
    chord = y[k] + (y[np.minimum(k + 1, len(y) - 1)] - y[k]) * (extrema[:, 0] - tau[k]) / spacing
    return ~inside | (np.abs(extrema[:, 1] - chord) > CURVE_GAP)


def _flag(run: Run, pb: Problem) -> int:
    """Index into FLAGS: how the run ended, or invalid if the incompressible wall passed 0.2c."""
    if run.status in _FLAG_OF_STATUS and run.status != UNBOUNDED_GROWTH:
        return _FLAG_OF_STATUS[run.status]
    fastest = max([abs(v) for v in run.speeds[:, 1]] + [float(np.nanmax(np.abs(run.v)))])
    if pb.compressible == terms.NONE and fastest > terms.INVALID_MACH * pb.sound:
        return 1
    return _FLAG_OF_STATUS.get(run.status, 0)


def _solver_label(run: Run, pb: Problem) -> int:
    """Index into SOLVER_LABELS (the stiff label only where the terms are stiff)."""
    choices = {(ANALYTIC, 0.0): 0, (EXPLICIT, EXPLICIT_RTOL): 1}
    if pb.stiffness > STIFF:
        choices[(IMPLICIT, IMPLICIT_RTOL)] = 2
    if (run.method, run.rtol) in choices:
        return choices[(run.method, run.rtol)]
    return 4 + SCENE_METHODS.index(run.method) if run.method in SCENE_METHODS else 3


def _blake_state(run: Run, pb: Problem) -> int:
    """Index into BLAKE_LABELS: the verdict on the nucleus at the end of the ramp and hold.

    A large nucleus grows slowly: within the hold it may not reach R_B even beyond the threshold, so the
    verdict reads the end of the run too (R > R_B and Ṙ > 0: past the unstable size, it goes on growing)
    and, below R_B, whether any size is in equilibrium at the final pressure (beyond the threshold, none
    is: a pressure below p_Blake pulls every nucleus open, however slowly).
    """
    if run.status == UNBOUNDED_GROWTH:
        return 4
    r_b, p_blake = terms.blake_nucleus(pb.sigma, pb.vapour)
    _, r_end, v_end = run.end
    if r_end > r_b and v_end > 0.0:
        return 2
    if pb.ramp_to < float(p_blake):
        return 3
    largest = max([float(np.nanmax(run.r))] + list(run.maxima[:, 1]))
    return 1 if largest > r_b else 0
