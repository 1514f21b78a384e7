"""K4: Rayleigh–Plesset bubble dynamics, composed from the effects a scene names.

Three presets are three scenes of this one model (physics.md K4): A the Rayleigh collapse
(`step`, analytic when only inertia and vapour act), B a driven bubble with Keller–Miksis
compressibility, C a nucleus under a ramped tension (Blake threshold). Each point of a slider grid
is solved in nondimensional variables with terminal events and caps (bubble_solve.py); points
that are the same nondimensional problem are solved once.
"""
from __future__ import annotations

import math
import time

import numpy as np

from . import bubble_terms as terms
from .base import Model, Output, Param
from .bubble_point import (
    BLAKE_LABELS, CURVE_SIZE, DRIVE_PERIODS, FLAGS, SOLVER_LABELS, Scales, check_effects, compose, read_run,
)
from .bubble_solve import CURVE_POINTS, Run, solve
from .bubble_terms import P0, WATER, Problem

EFFECTS = ("inertia", "gas", "vdw_hard_core", "vapour", "surface_tension", "viscosity", "thermal_damping",
           "drive", "step", "ramp", "radiation", "keller_miksis")
ALL = ("R0", "rho", "c", "kappa", "h_frac", "p_v", "sigma", "mu", "D_g", "p_a", "f", "p_inf", "gas_content",
       "p_target", "t_ramp", "t_hold")
FAR_FIELD = ("p_a", "p_inf", "p_target", "R0", "sigma", "p_v", "t_ramp", "t_hold")
EQUILIBRIUM = ("R0", "rho", "kappa", "h_frac", "p_v", "sigma", "D_g", "f")


class Bubble(Model):
    """A spherical bubble in water: inertia plus the pressure terms of the enabled effects."""

    name = "bubble"
    title = "Rayleigh–Plesset bubble dynamics"
    params = (
        Param("R0", "R<sub>0</sub>", "µm", 4.5, lo=0.0, lo_open=True, description="radius at rest at t = 0"),
        Param("rho", "ρ", "kg/m³", WATER["rho"], lo=0.0, lo_open=True, description="liquid density"),
        Param("c", "c", "m/s", WATER["c"], lo=0.0, lo_open=True, description="speed of sound in the liquid"),
        Param("kappa", "κ", "", 5 / 3, lo=1.0, hi=3.0, description="polytropic exponent (γ with thermal damping)").with_effect("gas"),
        Param("h_frac", "h/R<sub>0</sub>", "", 1 / 8.86, lo=0.0, hi=0.9, description="van der Waals hard-core radius").with_effect("vdw_hard_core"),
        Param("p_v", "p<sub>v</sub>", "Pa", WATER["p_v"], lo=0.0, description="vapour pressure").with_effect("vapour"),
        Param("sigma", "σ", "N/m", WATER["sigma"], lo=0.0, description="surface tension").with_effect("surface_tension"),
        Param("mu", "µ", "Pa·s", WATER["mu"], lo=0.0, description="liquid viscosity").with_effect("viscosity"),
        Param("D_g", "D<sub>g</sub>", "mm²/s", 20.5, lo=0.0, description="thermal diffusivity of the gas (argon)").with_effect("thermal_damping"),
        Param("p_a", "p<sub>a</sub>/p<sub>0</sub>", "", 1.3, lo=0.0, description="drive amplitude").with_effect("drive"),
        Param("f", "f", "kHz", 26.5, lo=0.0, lo_open=True, description="drive frequency").with_effect("drive"),
        Param("p_inf", "p<sub>∞</sub>", "atm", 1.0, lo=0.0, lo_open=True, description="liquid pressure from t = 0").with_effect("step"),
        Param("gas_content", "p<sub>gi</sub>/p<sub>∞</sub>", "", 0.0, lo=0.0, description="initial gas pressure").with_effect("step"),
        Param("p_target", "p<sub>target</sub>/p<sub>Blake</sub>", "", 0.99, description="end of the pressure ramp").with_effect("ramp"),
        Param("t_ramp", "t<sub>ramp</sub>", "µs", 200.0, lo=0.0, lo_open=True, description="ramp duration").with_effect("ramp"),
        Param("t_hold", "t<sub>hold</sub>", "µs", 100.0, lo=0.0, description="hold after the ramp").with_effect("ramp"),
    )
    outputs = (
        Output("t_c", "Rayleigh collapse time t<sub>c</sub>", "µs", ("R0", "rho", "p_inf", "p_v"), decimals=3, special="∞ (no collapse: p∞ ≤ p_v)", effect="step"),
        Output("R_mach", "R/R<sub>0</sub> where |Ṙ| = c (incompressible)", "", ("rho", "c", "p_inf", "p_v"), decimals=4, effect="step"),
        Output("t_mach", "t/t<sub>c</sub> where |Ṙ| = c", "", ("rho", "c", "p_inf", "p_v"), decimals=5, effect="step"),
        Output("R_max", "R<sub>max</sub>/R<sub>0</sub>", "", ALL, decimals=4, special="—"),
        Output("t_Rmax", "t/T at R<sub>max</sub>", "", ALL, decimals=5, special="—", effect="drive"),
        Output("R_min", "R<sub>min</sub>/R<sub>0</sub>", "", ALL, decimals=5, special="—"),
        Output("t_Rmin", "t/T at R<sub>min</sub>", "", ALL, decimals=5, special="—", effect="drive"),
        Output("t_collapse", "t/t<sub>c</sub> at R<sub>min</sub>", "", ALL, decimals=5, special="—", effect="step"),
        Output("mach_max", "max |Ṙ|/c", "", ALL, decimals=4, special="—"),
        Output("pg_peak", "peak gas pressure p<sub>g</sub>", "GPa", ALL, decimals=2, special="—", effect="gas"),
        Output("Tg_peak", "adiabatic T<sub>g</sub> at R<sub>min</sub>", "K", ALL, decimals=0, special="—", effect="gas"),
        Output("Rmin_h", "R<sub>min</sub>/h", "", ALL, decimals=2, special="—", effect="vdw_hard_core"),
        Output("R_max2", "2nd cycle R<sub>max</sub>/R<sub>0</sub>", "", ALL, decimals=4, special="—", effect="drive"),
        Output("R_min2", "2nd cycle R<sub>min</sub>/R<sub>0</sub>", "", ALL, decimals=5, special="—", effect="drive"),
        Output("f0", "linear f<sub>0</sub>", "kHz", EQUILIBRIUM, decimals=1, effect="gas"),
        Output("beta", "viscous damping β = 2µ/ρR<sub>0</sub><sup>2</sup>", "1/ms", ("R0", "rho", "mu"), decimals=1, effect="viscosity"),
        Output("two_sigma_R0", "2σ/R<sub>0</sub>", "kPa", ("R0", "sigma"), decimals=1, effect="surface_tension"),
        Output("R_B", "Blake radius R<sub>B</sub>", "µm", ("R0", "sigma", "p_v"), decimals=4, special="—", effect="surface_tension"),
        Output("p_blake", "Blake threshold p<sub>Blake</sub>", "kPa", ("R0", "sigma", "p_v"), decimals=1, special="—", effect="surface_tension"),
        Output("p_end", "p<sub>∞</sub> after the ramp", "kPa", ("R0", "sigma", "p_v", "p_target"), decimals=1, effect="ramp"),
        Output("blake", "the nucleus", "", ALL, labels=BLAKE_LABELS, effect="ramp"),
        Output("flag", "model check", "", ALL, labels=FLAGS),
        Output("solver", "solver", "", ALL, labels=SOLVER_LABELS),
        # Figure geometry. x is in the run's time unit (t/T driven, µs ramped, t/t_c otherwise);
        # y is log10(R/R0) driven, log10(R/R_B) ramped, R/R0 otherwise.
        Output("curve_x", "R(t): sample times, extrema and stop (x)", "", ALL, decimals=3, size=CURVE_SIZE, ragged=True),
        Output("curve_y", "R(t): sample times, extrema and stop (y)", "", ALL, decimals=3, size=CURVE_SIZE, ragged=True),
        Output("stop_x", "where a terminal event stopped the run (x)", "", ALL, decimals=5, size=1, ragged=True),
        Output("stop_y", "where a terminal event stopped the run (y)", "", ALL, decimals=3, size=1, ragged=True),
        Output("mark_x", "event-detected R_max and R_min (x)", "", ALL, decimals=5, size=2, ragged=True),
        Output("mark_y", "event-detected R_max and R_min (y)", "", ALL, decimals=3, size=2, ragged=True),
        Output("p_far", "p∞(t)/p0 on the sample grid", "", FAR_FIELD, decimals=3, size=CURVE_POINTS),
    )
    effects = EFFECTS

    def _evaluate(self, x, wanted, effects):
        check_effects(effects)
        closed = [name for name in wanted if name in CLOSED_FORMS]
        results = {name: CLOSED_FORMS[name](x, effects) for name in closed}
        dynamic = [name for name in wanted if name not in CLOSED_FORMS]
        if dynamic:
            results.update(_solve_points(x, dynamic, effects))
        return results


# --- closed forms (vectorised) ---------------------------------------------------------------------------


def _delta_p(x, effects):
    p_inf = x["p_inf"] * P0 if "step" in effects else np.full_like(x["R0"], P0)
    return p_inf - (x["p_v"] if "vapour" in effects else 0.0)


def _t_c(x, effects):
    delta = _delta_p(x, effects)
    safe = np.where(delta > 0, delta, 1.0)
    return np.where(delta > 0, terms.RAYLEIGH_B * x["R0"] * np.sqrt(x["rho"] / (6.0 * safe)), np.inf)


def _mach_radius(x, effects):
    delta = np.maximum(_delta_p(x, effects), 1e-300)
    return terms.mach_one_radius(delta / (x["rho"] * x["c"] ** 2), 1.0)


def _equilibrium_gas(x, effects):
    """p_g0/p0 at R0 with the enabled terms (0 without gas)."""
    sigma = x["sigma"] / (P0 * x["R0"] * 1e-6) if "surface_tension" in effects else 0.0 * x["R0"]
    vapour = x["p_v"] / P0 if "vapour" in effects else 0.0
    return (1.0 - vapour + 2.0 * sigma) if "gas" in effects else 0.0 * x["R0"], sigma, vapour


def _f0(x, effects):
    def one(*values):
        point = dict(zip(ALL, values))
        pb, scales = compose({**point, "p_inf": 1.0, "gas_content": 0.0}, set(effects) - {"step", "ramp"})
        return terms.natural_omega(pb) / scales.t_ref / (2e3 * math.pi)

    return np.vectorize(one, otypes=[float])(*(x[name] for name in ALL))


def _blake(x, effects, which):
    gas, sigma, vapour = _equilibrium_gas(x, effects)
    with np.errstate(divide="ignore", invalid="ignore"):
        r_b, p_blake = terms.blake(gas, sigma, vapour)
    valid = (gas > 0) & (sigma > 0)
    if which == "R_B":
        return np.where(valid, r_b * x["R0"], np.inf)
    return np.where(valid, p_blake * P0 * 1e-3, np.inf)


CLOSED_FORMS = {
    "t_c": _t_c,  # R0 in µm gives µs
    "R_mach": lambda x, e: _mach_radius(x, e),
    "t_mach": lambda x, e: terms.rayleigh_fraction(_mach_radius(x, e)),
    "f0": _f0,
    "beta": lambda x, e: 2.0 * x["mu"] / (x["rho"] * (x["R0"] * 1e-6) ** 2) * 1e-3,
    "two_sigma_R0": lambda x, e: 2.0 * x["sigma"] / (x["R0"] * 1e-6) * 1e-3,
    "R_B": lambda x, e: _blake(x, e, "R_B"),
    "p_blake": lambda x, e: _blake(x, e, "p_blake"),
    "p_end": lambda x, e: x["p_target"] * _blake(x, e, "p_blake"),
    "p_far": lambda x, e: _far_field_curves(x, e),
}


def _far_field_curves(x, effects):
    """p∞(t)/p0 on the sample grid, in closed form in the figure's time unit (so f never enters
    the driven curve through rounding)."""
    share = np.linspace(0.0, 1.0, CURVE_POINTS)
    shape = np.shape(x["R0"]) + (1,)
    base = (x["p_inf"] if "step" in effects else np.ones_like(x["R0"])).reshape(shape)
    curve = np.broadcast_to(base, shape[:-1] + (CURVE_POINTS,)).copy()
    if "ramp" in effects:
        seconds = _run_seconds(x, effects).reshape(shape) * share
        rise = (x["p_target"] * _blake(x, effects, "p_blake") * 1e3 / P0).reshape(shape) - base
        curve += rise * np.minimum(seconds / (x["t_ramp"].reshape(shape) * 1e-6), 1.0)
    if "drive" in effects:
        curve -= x["p_a"].reshape(shape) * np.sin(2.0 * np.pi * DRIVE_PERIODS * share)
    return curve


def _run_seconds(x, effects):
    """The run's length in seconds for a ramp (with a drive: its two periods)."""
    if "drive" in effects:
        return DRIVE_PERIODS / (x["f"] * 1e3)
    return (x["t_ramp"] + x["t_hold"]) * 1e-6


# --- solving the grid -----------------------------------------------------------------------------------


def _solve_points(x, names, effects) -> dict[str, np.ndarray]:
    """Solve every point (each distinct nondimensional problem once) and read the named outputs."""
    shape = np.shape(x["R0"])
    flat = {name: np.ravel(x[name]) for name in ALL}
    rows = []
    for i in range(int(np.prod(shape, dtype=int))):
        point = {name: float(flat[name][i]) for name in ALL}
        pb, scales = compose(point, effects)
        rows.append(read_run(solve(pb), pb, scales, effects))
    out = {}
    for name in names:
        size = Bubble.output(name).size
        out[name] = np.array([row[name] for row in rows], float).reshape(shape + ((size,) if size else ()))
    return out


# --- presets, for the accuracy report ---------------------------------------------------------------------

PRESETS = {
    "A": (("inertia", "vapour", "step"), {"R0": 1000.0, "p_inf": 1.0}),
    "B": (("gas", "vdw_hard_core", "surface_tension", "viscosity", "drive", "keller_miksis"), {"R0": 4.5, "p_a": 1.3, "f": 26.5}),
    "C": (("gas", "vapour", "surface_tension", "viscosity", "ramp"), {"R0": 1.0, "kappa": 1.0, "p_target": 0.99}),
}


def preset_problem(preset: str, **changes) -> tuple[Problem, Scales]:
    """The nondimensional problem of a preset at its defaults (or with some parameters changed)."""
    effects, values = PRESETS[preset]
    return compose({**Bubble.defaults(), **values, **changes}, effects)


def run_preset(preset: str, method: str, rtol: float, **changes) -> tuple[Run, int, float]:
    """One preset solved with a given method and rtol: (run, nfev, wall seconds), uncached."""
    pb, _ = preset_problem(preset, **changes)
    start = time.perf_counter()
    run = solve.__wrapped__(pb, method, rtol)
    return run, run.nfev, time.perf_counter() - start
