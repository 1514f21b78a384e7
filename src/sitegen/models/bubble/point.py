"""K4 helpers: one point of a slider grid, composed into a nondimensional Problem and read back.

`compose` turns parameter values and the enabled effects into a Problem with only those terms
(and the initial state consistent with them); `read_run` turns a solved Run into every dynamic
output in display units, with inf where a value does not exist (the page shows "—").
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from . import kernel_read, terms
from .run import CURVE_POINTS, STATUS_CODES, Run
from .solve import ANALYTIC, EXPLICIT, EXPLICIT_RTOL, IMPLICIT, IMPLICIT_RTOL, STIFF
from .terms import P0, T0, Problem

# The parameters: the liquid's and the gas's, and each pressure history's (with the prefix of its outputs).
LIQUID_AND_GAS = ("R0", "rho", "c", "kappa", "h_frac", "p_v", "sigma", "mu", "D_g")
HISTORY_PARAMS = {"step": ("p_inf", "gas_content"), "drive": ("p_a", "f"), "ramp": ("depth", "t_ramp", "t_hold")}
PREFIX = {"step": "collapse", "drive": "driven", "ramp": "ramp"}
ALL = LIQUID_AND_GAS + tuple(p for names in HISTORY_PARAMS.values() for p in names)

DRIVE_PERIODS = 2  # the driven bubble runs two acoustic periods from rest at R0
CURVE_SIZE = CURVE_POINTS + kernel_read.CURVE_EXTREMA + 1  # samples, extrema and the stop

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
MISSING = FLAGS + (
    "no gas in the bubble: nothing is compressed",
    "no van der Waals hard core (h = 0)",
    "not reached before the run ended",
)
# Where each output of a run (read_run's keys) lies in kernel_read's row: an index, or a slice for an array.
_LABELS = ("flag", "growth", "solver")  # indices into FLAGS, BLAKE_LABELS, SOLVER_LABELS
ROW_OF = {
    **{key: index for index, key in enumerate(kernel_read.SCALARS)},
    **{f"{kernel_read.SCALARS[key]}_why": kernel_read.WHY + i for i, key in enumerate(kernel_read.WHY_OF)},
    "mark_x": slice(kernel_read.MARK_X, kernel_read.MARK_X + 2),
    "mark_y": slice(kernel_read.MARK_Y, kernel_read.MARK_Y + 2),
    "stop_x": slice(kernel_read.STOP_X, kernel_read.STOP_X + 1),
    "stop_y": slice(kernel_read.STOP_Y, kernel_read.STOP_Y + 1),
    "curve_x": slice(kernel_read.CURVE_X, kernel_read.CURVE_X + CURVE_SIZE),
    "curve_y": slice(kernel_read.CURVE_X + CURVE_SIZE, kernel_read.CURVE_X + 2 * CURVE_SIZE),
}


def _power(rtol: float) -> str:
    """An rtol as a label writes it: 1e−6."""
    return f"{rtol:.0e}".replace("e-0", "e−").replace("e-", "e−")


# The default settings' three choices, then any method at the rtol a scene's `numerics:` line sets.
SCENE_METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA", EXPLICIT, IMPLICIT)
SOLVER_LABELS = (
    "analytic (betaincinv)",
    f"DOP853 (compiled), rtol {_power(EXPLICIT_RTOL)}",
    f"Radau IIA (compiled; stiff: 4µT/ρR₀² > 10³), rtol {_power(IMPLICIT_RTOL)}",
    "other",
) + tuple(f"{method}, at the scene's rtol" for method in SCENE_METHODS)
BLAKE_LABELS = (
    "settles: it stays below the Blake radius, at a size in equilibrium",
    "passed the Blake radius, then fell back below it",
    "keeps growing: past the Blake radius and still growing",
    "keeps growing, slowly: still below the Blake radius, but past the threshold no size is in equilibrium",
    "unbounded: reached 10 Blake radii",
)


def check_effects(effects) -> None:
    """Raise ValueError for an effect set that is not a model: a missing companion or two rivals."""
    for effect, needed in NEEDS.items():
        if effect in effects and needed not in effects:
            raise ValueError(f"effect `{effect}` needs `{needed}`")
    if "radiation" in effects and "keller_miksis" in effects:
        raise ValueError(
            "effects `radiation` and `keller_miksis` exclude each other (Keller–Miksis includes radiation)"
        )
    protocols = [p for p in PROTOCOLS if p in effects]
    if len(protocols) > 1:
        raise ValueError(
            f"effects {' and '.join(f'`{p}`' for p in protocols)} exclude each other: one pressure history per scene"
        )


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
        r_b, p_blake = blake_point(sigma, vapour)
        # The depth x = (p0 − p_target)/(p0 − p_Blake): the share of the way from p0 down to the threshold,
        # so x > 1 lies beyond it for every nucleus (p_Blake > 0 for large ones, where p_target/p_Blake
        # would run the wrong way).
        fields.update(
            ramp_to=1.0 - point["depth"] * (1.0 - p_blake),
            ramp_time=point["t_ramp"] * 1e-6 / t_ref,
            r_unbounded=terms.UNBOUNDED * r_b,
        )
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
    row, out = read_row(run, pb, scales, effects), {}
    for key, where in ROW_OF.items():
        if isinstance(where, slice):
            out[key] = row[where]
        else:  # labels and reasons are indices
            out[key] = int(row[where]) if key in _LABELS or key.endswith("_why") else float(row[where])
    return out


def read_row(run: Run, pb: Problem, scales: Scales, effects) -> np.ndarray:
    """Every dynamic output of one run as kernel_read lays out a row (`read_run` names its entries)."""
    row = kernel_read.read(
        reading(pb, scales, effects),
        run.tau,
        run.r,
        run.v,
        run.end,
        STATUS_CODES[run.status],
        run.maxima,
        run.minima,
        run.speeds,
    )
    row[kernel_read.SOLVER] = _solver_label(run, pb)
    return row


def reading(pb: Problem, scales: Scales, effects) -> np.ndarray:
    """What the reading of a run needs to know of its point (kernel_read's Q_ entries, in their order)."""
    r_b, p_blake = blake_point(pb.sigma, pb.vapour)
    y_kind, y_scale = kernel_read.Y_PLAIN, 1.0  # the figure's y: logarithms where radii span decades
    if "drive" in effects:
        y_kind = kernel_read.Y_LOG
    elif "ramp" in effects and math.isfinite(pb.r_unbounded):  # without surface tension there is no Blake radius
        y_kind, y_scale = kernel_read.Y_LOG_BLAKE, pb.r_unbounded / terms.UNBOUNDED
    part = pb.tau_end / DRIVE_PERIODS if "drive" in effects else pb.tau_end
    # the wall speed past which the incompressible model is flagged invalid (a compressible one has no such limit)
    invalid = terms.INVALID_MACH * pb.sound if pb.compressible == terms.NONE else math.inf
    return np.array(
        (
            pb.tau_end,
            part,
            pb.sound,
            invalid,
            pb.eta,
            pb.eta**3,
            pb.gas,
            pb.kappa,
            pb.ramp_to,
            y_kind,
            y_scale,
            scales.t_ref,
            scales.x_unit,
            r_b,
            p_blake,
            P0,
            T0,
        )
    )


@lru_cache(maxsize=4096)
def blake_point(sigma: float, vapour: float) -> tuple[float, float]:
    """terms.blake_nucleus at one point, as floats (remembered: a scene has few distinct nuclei)."""
    r_b, p_blake = terms.blake_nucleus(sigma, vapour)
    return float(r_b), float(p_blake)


def _solver_label(run: Run, pb: Problem) -> int:
    """Index into SOLVER_LABELS (the stiff label only where the terms are stiff)."""
    choices = {(ANALYTIC, 0.0): 0, (EXPLICIT, EXPLICIT_RTOL): 1}
    if pb.stiffness > STIFF:
        choices[(IMPLICIT, IMPLICIT_RTOL)] = 2
    if (run.method, run.rtol) in choices:
        return choices[(run.method, run.rtol)]
    return 4 + SCENE_METHODS.index(run.method) if run.method in SCENE_METHODS else 3
