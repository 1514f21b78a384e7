"""K4: Rayleigh–Plesset bubble dynamics, composed from the effects a scene names.

Three presets (presets.py) are three scenes of this one model (docs/physics/bubble.md), one per pressure history:
A `step`, the Rayleigh collapse (analytic when only inertia and vapour act); B `drive`, a driven
bubble with Keller–Miksis compressibility; C `ramp`, a nucleus under a ramped tension (Blake
threshold). The dynamic outputs of each history carry its prefix (collapse_, driven_, ramp_) and
depend only on its own parameters. Each grid point is solved in nondimensional variables with
terminal events and caps (solve.py; what a run is: run.py); points that are one nondimensional problem are solved once.
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.base import Model, Output, Param
from ...physics.numerics import Measurement, Numerics
from . import terms
from .bench import Regime
from .compare import run_difference, shown_difference
from .point import (
    ALL,
    BLAKE_LABELS,
    CURVE_SIZE,
    DRIVE_PERIODS,
    FLAGS,
    HISTORY_PARAMS,
    LIQUID_AND_GAS,
    MISSING,
    PREFIX,
    ROW_OF,
    SOLVER_LABELS,
    check_effects,
    compose,
    read_row,
    read_run,
)
from .run import CURVE_POINTS, REFERENCE_CAPS
from .scipy_path import SOLVERS
from .solve import AUTO, COMPILED, STIFF, method_for, reference_for, solve
from .sweep import DigitSweep
from .terms import P0, WATER

EFFECTS = (
    "inertia",
    "gas",
    "vdw_hard_core",
    "vapour",
    "surface_tension",
    "viscosity",
    "thermal_damping",
    "step",
    "drive",
    "ramp",
    "radiation",
    "keller_miksis",
)

# The dynamic outputs of each pressure history: (key of read_run, label, unit, decimals or labels).
_T = "t/T at "
DYNAMIC = {
    "step": (
        ("R_min", "R<sub>min</sub>/R<sub>0</sub> (first collapse)", "", 5),
        ("t_Rmin", "t/t<sub>c</sub> at R<sub>min</sub>", "", 5),
        ("mach", "max |Ṙ|/c", "", 4),
    ),
    "drive": (
        ("R_max", "R<sub>max</sub>/R<sub>0</sub>", "", 4),
        ("t_Rmax", _T + "R<sub>max</sub>", "", 5),
        ("R_min", "R<sub>min</sub>/R<sub>0</sub>", "", 5),
        ("t_Rmin", _T + "R<sub>min</sub>", "", 5),
        ("mach", "max |Ṙ|/c (1st period)", "", 4),
        ("pg_peak", "peak gas pressure p<sub>g</sub>", "GPa", 2),
        ("Tg_peak", "adiabatic T<sub>g</sub> at R<sub>min</sub>", "K", 0),
        ("Rmin_h", "R<sub>min</sub>/h", "", 2),
        ("R_max2", "2nd cycle R<sub>max</sub>/R<sub>0</sub>", "", 4),
        ("R_min2", "2nd cycle R<sub>min</sub>/R<sub>0</sub>", "", 5),
    ),
    "ramp": (("growth", "the nucleus", "", BLAKE_LABELS), ("R_max", "R<sub>max</sub>/R<sub>0</sub>", "", 4)),
}
# Spanning decades over a drive's amplitudes: significant digits, as many as the solve's tolerance (1e-5
# in R/R0, amplified about fivefold in p_g ∝ R^-3κ) keeps exact.
SIGNIFICANT = {"mach": {"digits": 3}, "pg_peak": {"digits": 3}}
COMMON = (("flag", "model check", "", FLAGS), ("solver", "solver", "", SOLVER_LABELS))
# Figure geometry: x in the history's time unit (t/t_c, t/T, µs); y = R/R0, log10(R/R0), log10(R/R_B).
GEOMETRY = (
    ("curve_x", 3, CURVE_SIZE),
    ("curve_y", 3, CURVE_SIZE),
    ("stop_x", 5, 1),
    ("stop_y", 3, 1),
    ("mark_x", 5, 2),
    ("mark_y", 3, 2),
)


# The solver is chosen from the stiffness 4µT/ρR0² (µ with its thermal part) and from whether only
# inertia acts; c and the quantities the choice never reads are not its dependencies.
SOLVER_DEPS = {
    "step": ("R0", "rho", "kappa", "h_frac", "p_v", "sigma", "mu", "D_g", "p_inf", "gas_content"),
    "drive": ("R0", "rho", "kappa", "p_v", "sigma", "mu", "D_g", "p_a", "f"),
    "ramp": ("R0", "rho", "kappa", "h_frac", "p_v", "sigma", "mu", "D_g", "t_ramp", "t_hold"),
}


def _history_outputs() -> tuple[Output, ...]:
    """Every dynamic output, per pressure history, each depending on the liquid, the gas and that history."""
    outputs = []
    for history, prefix in PREFIX.items():
        deps = LIQUID_AND_GAS + HISTORY_PARAMS[history]
        for key, label, unit, shown in DYNAMIC[history] + COMMON:
            extra = (
                {"labels": shown}
                if isinstance(shown, tuple)
                else {"decimals": shown, "special": "—", "why_from": f"{prefix}_{key}_why"}
            )
            extra.update(SIGNIFICANT.get(key, {}))
            output_deps = SOLVER_DEPS[history] if key == "solver" else deps
            outputs.append(Output(f"{prefix}_{key}", label, unit, output_deps, effect=history, **extra))
            if "why_from" in extra:  # why it has no value where it shows "—"
                outputs.append(
                    Output(f"{prefix}_{key}_why", f"why {label} has no value", "", deps, labels=MISSING, effect=history)
                )
        for key, decimals, size in GEOMETRY:
            if key.startswith("mark") and history == "ramp":  # the ramp's growth has no extremum to mark
                continue
            outputs.append(
                Output(
                    f"{prefix}_{key}",
                    f"figure: {key}",
                    "",
                    deps,
                    decimals=decimals,
                    size=size,
                    ragged=True,
                    effect=history,
                )
            )
    return tuple(outputs)


class Bubble(Model):
    """A spherical bubble in water: inertia plus the pressure terms of the enabled effects."""

    name = "bubble"
    title = "Rayleigh–Plesset bubble dynamics"
    params = (
        Param("R0", "R<sub>0</sub>", "µm", 4.5, lo=0.0, lo_open=True, description="radius at rest at t = 0"),
        Param("rho", "ρ", "kg/m³", WATER["rho"], lo=0.0, lo_open=True, description="liquid density"),
        Param("c", "c", "m/s", WATER["c"], lo=0.0, lo_open=True, description="speed of sound in the liquid"),
        Param(
            "kappa", "κ", "", 5 / 3, lo=1.0, hi=3.0, description="polytropic exponent (γ with thermal damping)"
        ).with_effect("gas"),
        Param(
            "h_frac", "h/R<sub>0</sub>", "", 1 / 8.86, lo=0.0, hi=0.9, description="van der Waals hard-core radius"
        ).with_effect("vdw_hard_core"),
        Param("p_v", "p<sub>v</sub>", "Pa", WATER["p_v"], lo=0.0, hi=5e4, description="vapour pressure").with_effect(
            "vapour"
        ),
        Param("sigma", "σ", "N/m", WATER["sigma"], lo=0.0, hi=1.0, description="surface tension").with_effect(
            "surface_tension"
        ),
        Param("mu", "µ", "Pa·s", WATER["mu"], lo=0.0, hi=100.0, description="liquid viscosity").with_effect(
            "viscosity"
        ),
        Param(
            "D_g", "D<sub>g</sub>", "mm²/s", 20.5, lo=0.0, description="thermal diffusivity of the gas (argon)"
        ).with_effect("thermal_damping"),
        Param(
            "p_a", "p<sub>a</sub>/p<sub>0</sub>", "", 1.3, lo=0.0, hi=10.0, description="drive amplitude"
        ).with_effect("drive"),
        Param("f", "f", "kHz", 26.5, lo=0.0, hi=1e4, lo_open=True, description="drive frequency").with_effect("drive"),
        Param(
            "p_inf", "p<sub>∞</sub>", "atm", 1.0, lo=0.0, hi=1e3, lo_open=True, description="liquid pressure from t = 0"
        ).with_effect("step"),
        Param(
            "gas_content", "p<sub>gi</sub>/p<sub>∞</sub>", "", 0.0, lo=0.0, hi=1.0, description="initial gas pressure"
        ).with_effect("step"),
        Param(
            "depth",
            "depth x",
            "",
            0.99,
            description="how far the ramp goes from p0 towards the Blake threshold: "
            "x = (p0 − p_target)/(p0 − p_Blake), 1 at the threshold",
        ).with_effect("ramp"),
        Param(
            "t_ramp", "t<sub>ramp</sub>", "µs", 200.0, lo=0.0, hi=1e3, lo_open=True, description="ramp duration"
        ).with_effect("ramp"),
        Param("t_hold", "t<sub>hold</sub>", "µs", 100.0, lo=0.0, hi=1e3, description="hold after the ramp").with_effect(
            "ramp"
        ),
    )
    outputs = (
        Output(
            "t_c",
            "Rayleigh collapse time t<sub>c</sub>",
            "µs",
            ("R0", "rho", "p_inf", "p_v"),
            decimals=3,
            special="∞ (no collapse: p∞ ≤ p_v)",
            effect="step",
        ),
        Output(
            "R_mach",
            "R/R<sub>0</sub> where |Ṙ| = c (incompressible)",
            "",
            ("rho", "c", "p_inf", "p_v"),
            decimals=4,
            effect="step",
        ),
        Output("t_mach", "t/t<sub>c</sub> where |Ṙ| = c", "", ("rho", "c", "p_inf", "p_v"), decimals=5, effect="step"),
        Output(
            "f0",
            "linear f<sub>0</sub>",
            "kHz",
            ("R0", "rho", "kappa", "h_frac", "p_v", "sigma", "D_g", "f"),
            decimals=1,
            effect="gas",
        ),
        Output(
            "beta",
            "viscous damping β = 2µ/ρR<sub>0</sub><sup>2</sup>",
            "1/ms",
            ("R0", "rho", "mu"),
            decimals=1,
            effect="viscosity",
        ),
        # Closed forms over nuclei of 0.1–100 µm: four significant digits.
        Output(
            "two_sigma_R0", "2σ/R<sub>0</sub>", "kPa", ("R0", "sigma"), decimals=1, digits=4, effect="surface_tension"
        ),
        Output(
            "R_B",
            "Blake radius R<sub>B</sub>",
            "µm",
            ("R0", "sigma", "p_v"),
            decimals=4,
            digits=4,
            special="—",
            why="no surface tension, so no Blake radius",
            effect="surface_tension",
        ),
        Output(
            "p_blake",
            "Blake threshold p<sub>Blake</sub>",
            "kPa",
            ("R0", "sigma", "p_v"),
            decimals=1,
            digits=4,
            effect="surface_tension",
        ),
        Output(
            "p_end",
            "p<sub>∞</sub> after the ramp",
            "kPa",
            ("R0", "sigma", "p_v", "depth"),
            decimals=1,
            digits=4,
            effect="ramp",
        ),
        Output(
            "driven_p_far",
            "figure: p∞(t)/p0 over two periods",
            "",
            ("p_a",),
            decimals=3,
            size=CURVE_POINTS,
            effect="drive",
        ),
    ) + _history_outputs()
    effects = EFFECTS
    # `auto`: the analytic collapse when only inertia (+ vapour) acts, the compiled DOP853 otherwise, the
    # compiled Radau where the viscous terms are stiff, each at the rtol at which every readout of the
    # book's bubble scenes shows the tight reference's digits (solve.EXPLICIT_RTOL, IMPLICIT_RTOL).
    # A scene's `rtol` replaces both. The tolerance bounds max |ΔR|/R0 (4.2e-6 measured, a violent collapse).
    numerics = Numerics(AUTO, tolerance=1e-5)
    methods = {
        AUTO: {"rtol": None, "atol": None},
        **{name: {"rtol": 1e-6, "atol": None} for name in (*SOLVERS, *COMPILED)},
    }
    error_metric = "max |ΔR|/R₀ over R(t) and its extrema"
    accuracy_stops = 16  # each costs a solve and a tight reference solve (compiled: 1–50 ms)
    compares_digits = True
    # An ODE solve per stop (1–50 ms compiled): blocks spread a scene over the executor's workers and pace its
    # progress lines, and hold enough stops to pay for their trip to a worker.
    chunk_stops = 64
    # The bench at the scenes' stops: `auto` at its own rule, the compiled solvers over rtol 1e-6 … 1e-10 (a scipy
    # solver costs 20–200 times as much, and an explicit one seconds a stop where the terms are stiff: those are
    # compared on the three regimes of docs/physics/bubble.md instead, and the sweep puts every stop's digits
    # against time).
    ladders = {"rtol": (1e-6, 1e-7, 1e-8, 1e-9, 1e-10), AUTO: {"rtol": ()}, **{name: {"rtol": ()} for name in SOLVERS}}
    experiments = {**{f"bubble-{case}": Regime(case) for case in "ABC"}, "settings": DigitSweep()}

    def _evaluate(self, x, wanted, effects):
        check_effects(effects)
        results = {name: CLOSED_FORMS[name](x, effects) for name in wanted if name in CLOSED_FORMS}
        dynamic = [name for name in wanted if name not in CLOSED_FORMS]
        for name in dynamic:
            if self.output(name).effect not in effects:
                raise ValueError(f"output `{name}` needs effect `{self.output(name).effect}`")
        if dynamic:
            results.update(_solve_points(x, dynamic, effects, self.settings))
        return results

    def is_numerical(self, effects) -> bool:
        """Only a pressure history is solved: the closed forms alone need no check."""
        return bool(set(effects) & set(HISTORY_PARAMS))

    def measure_error(self, values, effects) -> Measurement:
        """The point solved with the scene's settings against the tight solution `reference_for` names."""
        check_effects(effects)
        pb, scales = compose({**self.defaults(), **values}, effects)
        method, rtol, atol = method_for(pb, self.settings)
        run = solve(pb, method, rtol, atol=atol)
        ref_method, ref_rtol, ref_atol = reference_for(pb, method)
        reference = solve(pb, ref_method, ref_rtol, REFERENCE_CAPS, atol=ref_atol)
        error = run_difference(run, reference, pb, scales, effects)
        where = " where stiff" if pb.stiffness > STIFF else ""
        wrong, near = shown_difference(
            read_run(run, pb, scales, effects),
            read_run(reference, pb, scales, effects),
            PREFIX[_history(effects)],
            error,
            self.outputs,
        )
        return Measurement(error, run.nfev, method, f"{ref_method} at rtol {ref_rtol:g}{where}", wrong, near)


# --- closed forms (vectorised) ---------------------------------------------------------------------------


def _delta_p(x, effects):
    """p∞ − p_v of the collapse, Pa (p0 without the step, no p_v without vapour)."""
    p_inf = x["p_inf"] * P0 if "step" in effects else np.full_like(x["R0"], P0)
    return p_inf - (x["p_v"] if "vapour" in effects else 0.0)


def _t_c(x, effects):
    """Rayleigh's collapse time in µs (R0 is in µm); infinite when p∞ ≤ p_v (no collapse)."""
    delta = _delta_p(x, effects)
    safe = np.where(delta > 0, delta, 1.0)
    return np.where(delta > 0, terms.RAYLEIGH_B * x["R0"] * np.sqrt(x["rho"] / (6.0 * safe)), np.inf)


def _mach_radius(x, effects):
    """R/R0 where the incompressible collapse reaches |Ṙ| = c."""
    delta = np.maximum(_delta_p(x, effects), 1e-300)
    return terms.mach_one_radius(delta / (x["rho"] * x["c"] ** 2), 1.0)


def _f0(x, effects):
    """Linear natural frequency (kHz) of the bubble in equilibrium at R0 under p0, with the enabled terms."""

    def one(*values):
        equilibrium = set(effects) - {"step", "ramp"}
        pb, scales = compose(dict(zip(ALL, values)), equilibrium)
        return terms.natural_omega(pb) / scales.t_ref / (2e3 * math.pi)

    return np.vectorize(one, otypes=[float])(*(x[name] for name in ALL))


def _blake(x, effects):
    """(R_B in µm, p_Blake in kPa) of the nucleus in equilibrium at p0 (isothermal, quasi-static)."""
    zero = np.zeros_like(x["R0"])
    sigma = x["sigma"] / (P0 * x["R0"] * 1e-6) if "surface_tension" in effects else zero
    vapour = x["p_v"] / P0 if "vapour" in effects else zero
    r_b, p_blake = terms.blake_nucleus(sigma, vapour)
    return r_b * x["R0"], p_blake * P0 * 1e-3


CLOSED_FORMS = {
    "t_c": _t_c,  # R0 in µm gives µs
    "R_mach": lambda x, e: _mach_radius(x, e),
    "t_mach": lambda x, e: terms.rayleigh_fraction(_mach_radius(x, e)),
    "f0": _f0,
    "beta": lambda x, e: 2.0 * x["mu"] / (x["rho"] * (x["R0"] * 1e-6) ** 2) * 1e-3,
    "two_sigma_R0": lambda x, e: 2.0 * x["sigma"] / (x["R0"] * 1e-6) * 1e-3,
    "R_B": lambda x, e: _blake(x, e)[0],
    "p_blake": lambda x, e: _blake(x, e)[1],
    "p_end": lambda x, e: P0 * 1e-3 - x["depth"] * (P0 * 1e-3 - _blake(x, e)[1]),
    "driven_p_far": lambda x, e: (
        1.0 - x["p_a"][..., None] * np.sin(2.0 * np.pi * DRIVE_PERIODS * np.linspace(0.0, 1.0, CURVE_POINTS))
    ),
}


# --- solving the grid -----------------------------------------------------------------------------------


def _solve_points(x, names, effects, settings: Numerics) -> dict[str, np.ndarray]:
    """Solve every point (each distinct nondimensional problem once) and read the named outputs.

    Each point's result depends on that point alone, so the tables do not depend on how the grid is split.
    """
    shape = np.shape(x["R0"])
    flat = {name: np.ravel(x[name]).astype(float).tolist() for name in ALL}  # Python floats, read faster
    count = int(np.prod(shape, dtype=int))

    def one(i: int) -> np.ndarray:
        pb, scales = compose({name: flat[name][i] for name in ALL}, effects)
        method, rtol, atol = method_for(pb, settings)
        return read_row(solve(pb, method, rtol, atol=atol), pb, scales, effects)

    rows = np.array([one(i) for i in range(count)])
    sizes = {name: (Bubble.output(name).size,) if Bubble.output(name).size else () for name in names}
    return {name: rows[:, ROW_OF[name.split("_", 1)[1]]].reshape(shape + sizes[name]) for name in names}


def _history(effects) -> str:
    return next(name for name in HISTORY_PARAMS if name in effects)
