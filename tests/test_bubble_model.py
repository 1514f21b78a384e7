"""K4 (Rayleigh–Plesset bubble): analytic references, the presets' readouts, effect composition and
the vanishing limit of every effect. The hard cases are in test_bubble_hard_cases.py."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq, minimize_scalar
from scipy.special import betainc, betaincinv

from sitegen.compute.quantize import fmt
from sitegen.models.bubble import kernel_read
from sitegen.models.bubble.model import Bubble
from sitegen.models.bubble.point import BLAKE_LABELS, FLAGS, MISSING, SOLVER_LABELS, compose, read_run
from sitegen.models.bubble.presets import PRESETS, preset_problem, run_preset
from sitegen.models.bubble.run import CAP_NFEV, CORE, FAILED, KM_STOP, MACH, OK, POINT, STATUS_CODES, UNBOUNDED_GROWTH
from sitegen.models.bubble.solve import ANALYTIC, EXPLICIT, IMPLICIT, choose_method, integrate, solve
from sitegen.models.bubble.terms import (
    P0,
    WATER,
    Problem,
    blake,
    energy,
    mach_one_radius,
    rayleigh_fraction,
    rayleigh_radius,
    rayleigh_tau,
)


def _evaluate(preset: str, wanted, effects=None, **changes) -> dict:
    """The model's outputs for a preset (its effects unless given), with some parameters changed."""
    preset_effects, values = PRESETS[preset]
    out = Bubble().evaluate(
        {**values, **changes}, wanted=wanted, effects=preset_effects if effects is None else effects
    )
    return {name: float(value) for name, value in out.items()}


def _shown(preset: str, name: str, **changes) -> str:
    """A readout as the page shows it."""
    value = _evaluate(preset, [name], **changes)[name]
    output = Bubble.output(name)
    return output.labels[int(value)] if output.labels else fmt(value, output.decimals)


def _point(preset: str, **changes) -> dict:
    return {**Bubble.defaults(), **PRESETS[preset][1], **changes}


# --- reference 1: the Rayleigh collapse ----------------------------------------------------------------------


def _rayleigh_time_by_quadrature(r: float, delta_p: float = 1.0) -> float:
    """τ(r) = ∫_r^1 dr'/|ṙ| with ṙ² = (2ΔP/3)(1/r'³ − 1), by adaptive quadrature (a second method).

    r' = 1 − s² removes the inverse-square-root singularity at the start, where ṙ = 0.
    """

    def integrand(s):
        x = 1.0 - s * s
        return 2.0 * s / math.sqrt(2.0 * delta_p / 3.0 * (1.0 - x**3) / x**3) if s else 2.0 / math.sqrt(2.0 * delta_p)

    value, _ = quad(integrand, 0.0, math.sqrt(1.0 - r), epsabs=0.0, epsrel=1e-13, limit=200)
    return value


def test_rayleigh_collapse_time_is_0_914681_R0_sqrt_rho_over_dp():
    """t_c = R0 sqrt(ρ/6Δp) B(5/6, 1/2) = 0.914681 R0 sqrt(ρ/Δp) (6 digits) and equals the quadrature to 1e-10 rel."""
    assert rayleigh_tau(1.0) == pytest.approx(0.914681, abs=5e-7)
    assert rayleigh_tau(1.0) == pytest.approx(_rayleigh_time_by_quadrature(0.0), rel=1e-10)


@pytest.mark.parametrize("r", [0.9, 0.5, 0.1, 0.01, 1e-4], ids=["r=0.9", "r=0.5", "r=0.1", "r=0.01", "r=1e-4"])
def test_rayleigh_time_of_radius_matches_quadrature(r):
    """t(R) = t_c[1 − I_{r³}(5/6, 1/2)] agrees with the quadrature of dR/|Ṙ| to 1e-10 rel."""
    assert rayleigh_tau(1.0) * float(rayleigh_fraction(r)) == pytest.approx(_rayleigh_time_by_quadrature(r), rel=1e-10)


def test_betaincinv_curve_round_trips_through_betainc():
    """betainc(betaincinv(q)) = q to 1e-14 over the collapse (measured 3.2e-16)."""
    q = np.linspace(0.0, 1.0, 1001)
    assert np.max(np.abs(betainc(5 / 6, 1 / 2, betaincinv(5 / 6, 1 / 2, q)) - q)) <= 1e-14


@pytest.mark.parametrize("gap, tolerance", [(1e-3, 1e-4), (1e-9, 1e-7)], ids=["tc-t=1e-3:1e-4", "tc-t=1e-9:1e-7"])
def test_rayleigh_radius_near_collapse_follows_the_two_fifths_law(gap, tolerance):
    """R ≃ (5/2)^(2/5)(2Δp/3ρ)^(1/5) R0^(3/5) (t_c − t)^(2/5): ratio within 1e-4 at 1e-3, 1e-7 at 1e-9 (measured 5e-5,
    4e-9)."""
    tau_c = rayleigh_tau(1.0)
    exact = float(rayleigh_radius(1.0 - gap / tau_c))
    asymptote = 2.5**0.4 * (2.0 / 3.0) ** 0.2 * gap**0.4
    assert abs(exact / asymptote - 1.0) <= tolerance


def test_mach_one_radius_is_where_the_rayleigh_speed_equals_c():
    """At R_M/R0 = (1 + 3ρc²/2Δp)^(−1/3) the exact speed sqrt(2Δp/3ρ (R0³/R³ − 1)) equals c to 1e-12 rel."""
    pb, _ = preset_problem("A")
    delta = pb.p_inf - pb.vapour
    r_m = float(mach_one_radius(delta, pb.sound))
    assert math.sqrt(2.0 * delta / 3.0 * (r_m**-3 - 1.0)) == pytest.approx(pb.sound, rel=1e-12)


def test_dop853_collapse_matches_the_analytic_curve():
    """DOP853 at rtol 1e-9 on the empty collapse: max |ΔR|/R0 ≤ 1e-6 against betaincinv (measured 2.1e-8)."""
    run, _, _ = run_preset("A", "DOP853", 1e-9)
    pb, _ = preset_problem("A")
    reached = np.isfinite(run.r)
    exact = rayleigh_radius(run.tau[reached] / rayleigh_tau(pb.p_inf - pb.vapour))
    assert run.status == MACH
    assert np.max(np.abs(run.r[reached] - exact)) <= 1e-6


@pytest.mark.parametrize(
    "output, shown",
    [
        ("t_c", "91.853"),
        ("R_mach", "0.0311"),
        ("t_mach", "0.99991"),
        ("collapse_mach", "1.0000"),
        ("collapse_R_min", "—"),
        ("collapse_flag", "incompressible model invalid: the wall reaches |Ṙ| = c, where the curve ends"),
        ("collapse_solver", "analytic (betaincinv)"),
    ],
    ids=["t_c", "R_mach", "t_mach", "mach_max", "R_min", "flag", "solver"],
)
def test_preset_A_defaults_show_the_reference_readouts(output, shown):
    """Preset A (R_max 1 mm, p∞ 1 atm, Δp = 98 986 Pa): t_c = 91.853 µs, |Ṙ| = c at 0.0311 R0, t = 0.99991 t_c."""
    value = _evaluate("A", [output])[output]
    out = Bubble.output(output)
    text = out.labels[int(value)] if out.labels else (out.special if math.isinf(value) else fmt(value, out.decimals))
    assert text == shown


# --- reference 2: the energy ledger ----------------------------------------------------------------------------


def _conservative_collapse(content: float, sigma: float) -> Problem:
    """A gas-filled inviscid collapse (κ = 1.4) under p∞ = p0, incompressible and without a Mach stop."""
    pb = Problem(p_inf=1.0, gas=content, kappa=1.4, sigma=sigma)
    return dataclasses.replace(pb, tau_end=1.2 * rayleigh_tau(1.0))


@pytest.mark.parametrize("sigma", [0.0, 0.01], ids=["sigma*=0", "sigma*=0.01"])
@pytest.mark.parametrize("content", [1e-1, 1e-2, 1e-3], ids=["pgi=1e-1", "pgi=1e-2", "pgi=1e-3"])
def test_conservative_collapse_minimum_is_the_energy_root(content, sigma):
    """R_min (DOP853 rtol 1e-11) = root of E(R, 0) = E(R_i, 0) to 1e-9 rel (measured ≤ 4.4e-12)."""
    pb = _conservative_collapse(content, sigma)
    run = integrate(pb, (1.0, 0.0), "DOP853", 1e-11)
    start = float(energy(pb, 1.0, 0.0))
    root = brentq(lambda r: float(energy(pb, r, 0.0)) - start, 1e-6, 0.999, xtol=1e-16, rtol=1e-15)
    assert run.minima[0, 1] == pytest.approx(root, rel=1e-9)


@pytest.mark.parametrize("rtol", [1e-6, 1e-9], ids=["rtol=1e-6", "rtol=1e-9"])
def test_energy_drift_is_within_100_rtol(rtol):
    """Along the conservative collapse (p_gi/p∞ = 1e-2, σ* = 0.01) |E − E0|/E0 ≤ 100 rtol at every sample."""
    pb = _conservative_collapse(1e-2, 0.01)
    run = integrate(pb, (1.0, 0.0), "DOP853", rtol)
    reached = np.isfinite(run.r)
    start = float(energy(pb, 1.0, 0.0))
    assert np.max(np.abs(energy(pb, run.r[reached], run.v[reached]) / start - 1.0)) <= 100 * rtol


# --- reference 3: linear oscillation ------------------------------------------------------------------------


def test_minnaert_frequency_times_radius_is_3_29_m_per_s():
    """Gas only (κ = 1.4): f0 R0 = sqrt(3κp0/ρ)/2π = 3.29 m/s, and the model's f0 equals it to 1e-12 rel."""
    f0 = _evaluate("B", ["f0"], effects=("gas",), kappa=1.4, R0=1000.0)["f0"] * 1e3
    minnaert = math.sqrt(3 * 1.4 * P0 / WATER["rho"]) / (2 * math.pi)
    assert fmt(minnaert, 2) == "3.29"
    assert f0 * 1000e-6 == pytest.approx(minnaert, rel=1e-12)


def _linear_problem(effects, x0: float, periods: float):
    """A bubble of R0 = 10 µm (gas κ = 1.4) released at rest from R0(1 + x0) for a few natural periods."""
    pb, scales = compose({**Bubble.defaults(), "R0": 10.0, "kappa": 1.4}, effects)
    k = 3 * pb.kappa * pb.gas - 2 * pb.sigma
    return dataclasses.replace(pb, tau_end=periods * 2 * math.pi / math.sqrt(k)), k


def test_rayleigh_plesset_small_oscillation_follows_linear_theory():
    """RP, x0 = 1e-4: max |x − x_lin|/x0 ≤ 1e-3 over 5 periods (measured 1.9e-4), x_lin the damped oscillator."""
    x0 = 1e-4
    pb, k = _linear_problem(("gas", "surface_tension", "viscosity"), x0, periods=5)
    run = integrate(pb, (1.0 + x0, 0.0), "DOP853", 1e-11)
    damping = 2 * pb.visc  # ẍ + 4M ẋ + K x = 0 with ρ = R0 = 1
    omega = math.sqrt(k - damping**2)
    lin = x0 * np.exp(-damping * run.tau) * (np.cos(omega * run.tau) + damping / omega * np.sin(omega * run.tau))
    assert np.max(np.abs(run.r - 1.0 - lin)) / x0 <= 1e-3


def test_keller_miksis_small_oscillation_decays_at_the_linear_rate():
    """KM, x0 = 1e-5: the decay rate fitted to successive maxima matches b/2a of the linear KM oscillator to 1e-4
    rel."""
    x0 = 1e-5
    pb, k = _linear_problem(("gas", "surface_tension", "viscosity", "keller_miksis"), x0, periods=12)
    run = integrate(pb, (1.0 + x0, 0.0), "DOP853", 1e-12)
    a = 1.0 + 4 * pb.visc / pb.sound  # (R0² + 4µR0/ρc) ẍ + (4µ/ρ + KR0/ρc) ẋ + (K/ρ) x = 0
    b = 4 * pb.visc + k / pb.sound
    peaks = run.maxima[run.maxima[:, 0] > 0]
    fitted = math.log((peaks[1, 1] - 1.0) / (peaks[-1, 1] - 1.0)) / (peaks[-1, 0] - peaks[1, 0])
    assert fitted == pytest.approx(b / (2 * a), rel=1e-4)


# --- reference 4: the Blake threshold --------------------------------------------------------------------------


def test_blake_threshold_is_the_minimum_of_the_quasi_static_pressure():
    """p_Blake = min over R of p_v + K/R³ − 2σ/R (K = p_g0 R0³), at R = R_B, to 1e-9 rel (R0 = 1 µm)."""
    pb, _ = preset_problem("C")
    r_b, p_blake = blake(pb.gas, pb.sigma, pb.vapour)
    best = minimize_scalar(
        lambda r: pb.vapour + pb.gas / r**3 - 2 * pb.sigma / r,
        bounds=(1.0, 10.0),
        method="bounded",
        options={"xatol": 1e-12},
    )
    assert float(p_blake) == pytest.approx(best.fun, rel=1e-9)
    assert float(r_b) == pytest.approx(best.x, rel=1e-5)


@pytest.mark.parametrize(
    "output, shown",
    [
        ("two_sigma_R0", "145.6"),
        ("R_B", "2.2449"),
        ("p_blake", "\u221240.9"),
        ("ramp_growth", BLAKE_LABELS[0]),
        ("ramp_solver", SOLVER_LABELS[2]),
    ],
    ids=["2sigma/R0", "R_B", "p_Blake", "settles", "solver"],
)
def test_preset_C_defaults_show_the_reference_readouts(output, shown):
    """Preset C (R0 = 1 µm, depth 0.99): 2σ/R0 = 1.456e5 Pa, R_B = 2.2449 µm, p_Blake = −40 900 Pa, it settles."""
    assert _shown("C", output) == shown


@pytest.mark.parametrize(
    "depth, status", [(0.99, OK), (1.01, UNBOUNDED_GROWTH)], ids=["0.99:bounded", "1.01:unbounded"]
)
def test_ramp_across_the_blake_threshold(depth, status):
    """R0 = 1 µm: bounded (R < R_B throughout) at depth 0.99; R reaches 10 R_B at depth 1.01."""
    pb, _ = preset_problem("C", depth=depth)
    run = solve(pb)
    assert run.status == status
    assert (np.nanmax(run.r) < pb.r_unbounded / 10) == (status == OK)


def test_depth_one_puts_the_far_field_at_the_blake_threshold():
    """The depth x = (p0 − p_target)/(p0 − p_Blake): x = 1 ends the ramp at p_Blake, x = 0 at p0, for a large
    nucleus (p_Blake > 0) as for a small one (p_Blake < 0)."""
    for r0 in (1.0, 100.0):
        blake_kpa = float(Bubble().evaluate({"R0": r0}, wanted=["p_blake"], effects=PRESETS["C"][0])["p_blake"])
        for depth, expected in ((0.0, P0 * 1e-3), (1.0, blake_kpa), (0.5, (P0 * 1e-3 + blake_kpa) / 2)):
            pb, _ = preset_problem("C", R0=r0, depth=depth)
            assert pb.ramp_to * P0 * 1e-3 == pytest.approx(expected, rel=1e-12, abs=1e-12)


# --- reference 5 and the presets' readouts -------------------------------------------------------------------


@pytest.mark.parametrize(
    "output, shown",
    [
        ("driven_R_max", "6.8115"),
        ("driven_t_Rmax", "0.42824"),
        ("driven_R_min", "0.17624"),
        ("driven_t_Rmin", "0.51661"),
        ("driven_mach", "0.4578"),
        ("driven_pg_peak", "1.30"),
        ("driven_Tg_peak", "11553"),
        ("driven_Rmin_h", "1.56"),
        ("driven_R_max2", "6.8389"),
        ("driven_R_min2", "0.17587"),
        ("driven_flag", "valid"),
        ("driven_solver", SOLVER_LABELS[1]),
        ("f0", "893.5"),
    ],
    ids=[
        "R_max",
        "t_Rmax",
        "R_min",
        "t_Rmin",
        "mach",
        "p_g",
        "T_g",
        "R_min/h",
        "R_max2",
        "R_min2",
        "flag",
        "solver",
        "f0",
    ],
)
def test_preset_B_defaults_show_the_reference_readouts(output, shown):
    """Preset B (4.5 µm, p_a = 1.30 p0, 26.5 kHz, KM, argon): the reference digits of docs/physics/bubble.md (T_g
    1.16e4 K, f0 893.5 kHz)."""
    assert _shown("B", output) == shown


# --- effects: composition, solver choice, vanishing limits --------------------------------------------------


@pytest.mark.parametrize(
    "effects, gas",
    [
        (("gas",), 1.0),
        (("gas", "surface_tension"), "1+2S"),
        (("gas", "vapour"), "1-Pv"),
        (("gas", "vapour", "surface_tension"), "1-Pv+2S"),
    ],
    ids=["gas", "gas+sigma", "gas+vapour", "gas+vapour+sigma"],
)
def test_equilibrium_gas_pressure_includes_only_enabled_terms(effects, gas):
    """p_g0 = p0 − p_v + 2σ/R0 with each term present only when its effect is enabled (docs/physics/README.md, effects,
    rule 1)."""
    pb, _ = compose(_point("C"), effects)
    sigma, vapour = 0.0728 / (P0 * 1e-6), 2339.0 / P0
    expected = {1.0: 1.0, "1+2S": 1.0 + 2 * sigma, "1-Pv": 1.0 - vapour, "1-Pv+2S": 1.0 - vapour + 2 * sigma}[gas]
    assert pb.gas == pytest.approx(expected, rel=1e-15)
    assert (pb.sigma > 0) == ("surface_tension" in effects) and (pb.vapour > 0) == ("vapour" in effects)


@pytest.mark.parametrize(
    "param, value",
    [("sigma", 0.5), ("mu", 0.3), ("kappa", 1.2), ("h_frac", 0.3), ("p_a", 0.4), ("D_g", 1.0), ("depth", 0.5)],
    ids=["sigma", "mu", "kappa", "h", "p_a", "D_g", "depth"],
)
def test_parameters_of_disabled_effects_are_never_used(param, value):
    """Preset A (vapour, step only): changing a parameter of an effect it does not name leaves every output bitwise
    equal."""
    names = ["t_c", "R_mach", "collapse_R_min", "collapse_mach", "collapse_flag", "collapse_curve_y"]
    base = Bubble().evaluate(PRESETS["A"][1], wanted=names, effects=PRESETS["A"][0])
    moved = Bubble().evaluate({**PRESETS["A"][1], param: value}, wanted=names, effects=PRESETS["A"][0])
    for name in names:
        assert np.array_equal(base[name], moved[name], equal_nan=True), name


@pytest.mark.parametrize(
    "preset, changes, effects, method",
    [
        ("A", {}, None, ANALYTIC),
        ("A", {}, ("vapour", "step", "gas"), ANALYTIC),
        ("A", {"gas_content": 0.01}, ("vapour", "step", "gas"), EXPLICIT),
        ("A", {}, ("vapour", "step", "keller_miksis"), EXPLICIT),
        ("B", {}, None, EXPLICIT),
        ("C", {}, None, IMPLICIT),
        ("C", {"R0": 10.0}, None, EXPLICIT),
    ],
    ids=[
        "A:inertia+vapour->analytic",
        "A:gas-content-0->analytic",
        "A:gas->DOP853",
        "A:KM->DOP853",
        "B->DOP853",
        "C-1um:stiff->Radau",
        "C-10um->DOP853",
    ],
)
def test_solver_follows_from_the_composed_terms(preset, changes, effects, method):
    """Analytic when only inertia (+ vapour) act, the compiled Radau when 4µT/ρR0² > 1e3, the compiled DOP853
    otherwise."""
    pb, _ = compose(_point(preset, **changes), PRESETS[preset][0] if effects is None else effects)
    assert choose_method(pb)[0] == method


@pytest.mark.parametrize(
    "effects, message",
    [
        (("step", "drive"), "one pressure history"),
        (("gas", "radiation", "keller_miksis"), "exclude each other"),
        (("gas", "surface_tension", "step", "ramp"), "one pressure history"),
        (("vdw_hard_core",), "needs `gas`"),
        (("thermal_damping",), "needs `gas`"),
    ],
    ids=["step+drive", "radiation+KM", "step+ramp", "core-without-gas", "thermal-without-gas"],
)
def test_incompatible_effect_sets_raise(effects, message):
    """An effect without its companion, or two rival effects (two pressure histories), raise ValueError naming them."""
    with pytest.raises(ValueError, match=message):
        Bubble().evaluate({}, wanted=["t_c"], effects=effects)


@pytest.mark.parametrize(
    "inputs",
    [{"R0": 0.0}, {"kappa": 0.9}, {"h_frac": 1.0}, {"f": 0.0}, {"R0": float("nan")}],
    ids=["R0=0", "kappa<1", "h=R0", "f=0", "R0=nan"],
)
def test_invalid_parameters_raise_naming_the_parameter(inputs):
    """Values outside the domain raise ValueError naming the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        Bubble().evaluate(inputs, wanted=["t_c"], effects=("step",))


_MILD_B = {"p_a": 0.9, "f": 50.0}  # a non-violent driven bubble: the reduced models stay well conditioned
_B_EFFECTS = ("gas", "vdw_hard_core", "surface_tension", "viscosity", "drive", "keller_miksis")
_C_EFFECTS = PRESETS["C"][0]
VANISHING = [
    pytest.param("B", _MILD_B, _B_EFFECTS, {"sigma": 1e-12}, ("surface_tension",), id="sigma->0"),
    pytest.param("B", _MILD_B, _B_EFFECTS, {"mu": 1e-12}, ("viscosity",), id="mu->0"),
    pytest.param("B", _MILD_B, _B_EFFECTS, {"h_frac": 1e-4}, ("vdw_hard_core",), id="h->0"),
    pytest.param("B", {"f": 50.0}, _B_EFFECTS, {"p_a": 1e-13}, ("drive",), id="p_a->0"),
    pytest.param("B", _MILD_B, _B_EFFECTS, {"c": 1e12}, ("keller_miksis",), id="KM:c->inf"),
    pytest.param(
        "B",
        _MILD_B,
        ("gas", "surface_tension", "viscosity", "drive", "radiation"),
        {"c": 1e12},
        ("radiation",),
        id="radiation:c->inf",
    ),
    pytest.param(
        "B",
        _MILD_B,
        ("gas", "surface_tension", "viscosity", "thermal_damping", "drive"),
        {"D_g": 1e-20},
        ("thermal_damping",),
        id="thermal:D->0",
    ),
    pytest.param(
        "B",
        _MILD_B,
        ("gas", "surface_tension", "drive", "step"),
        {"p_inf": 1.0, "gas_content": 1.0 + 2 * 0.0728 / (P0 * 4.5e-6)},
        ("step",),
        id="step:p_inf->p0",
    ),
    pytest.param("C", {"R0": 5.0, "depth": 0.9}, _C_EFFECTS, {"p_v": 1e-9}, ("vapour",), id="C:p_v->0"),
    pytest.param("C", {"R0": 5.0, "depth": 0.9}, _C_EFFECTS, {"mu": 1e-12}, ("viscosity",), id="C:mu->0"),
    pytest.param(
        "A", {}, ("vapour", "step", "surface_tension"), {"sigma": 1e-12}, ("surface_tension",), id="A:sigma->0"
    ),
    pytest.param("A", {}, ("vapour", "step", "viscosity"), {"mu": 1e-12}, ("viscosity",), id="A:mu->0"),
]


@pytest.mark.parametrize("preset, base, effects, tiny, removed", VANISHING)
@pytest.mark.slow
def test_effect_vanishing_limit_reproduces_the_reduced_model(preset, base, effects, tiny, removed):
    """With the effect's parameter → 0 the run matches the run without the effect to 1e-6 rel (samples and extrema)."""
    point = _point(preset, **base, **tiny)
    with_effect, _ = compose(point, effects)
    reduced, _ = compose(point, tuple(e for e in effects if e not in removed))
    runs = [
        solve(pb) if pb.is_rayleigh else integrate(pb, (1.0, 0.0), "DOP853", 1e-10) for pb in (with_effect, reduced)
    ]
    if preset == "A":  # the collapse is compared up to where both stop (|Ṙ| = c)
        assert runs[0].status == runs[1].status == MACH
    reached = np.isfinite(runs[0].r) & np.isfinite(runs[1].r)
    assert reached.sum() > 100
    assert np.max(np.abs(runs[0].r[reached] / runs[1].r[reached] - 1.0)) <= 1e-6
    for kind in ("maxima", "minima"):
        a, b = getattr(runs[0], kind), getattr(runs[1], kind)
        count = min(len(a), len(b), 3)
        assert np.allclose(a[:count, 1], b[:count, 1], rtol=1e-6, atol=0.0), kind


def test_thermal_damping_limits_are_adiabatic_and_isothermal():
    """Prosperetti's Φ/3: κ_eff → γ as D → 0 (to 1e-8; the approach is ∝ sqrt D) and → 1 as D → ∞ (to 1e-6)."""
    low = compose(_point("B", D_g=1e-20), ("gas", "thermal_damping", "drive"))[0]
    high = compose(_point("B", D_g=1e9), ("gas", "thermal_damping", "drive"))[0]
    middle = compose(_point("B"), ("gas", "thermal_damping", "drive"))[0]
    assert low.kappa == pytest.approx(5 / 3, rel=1e-8) and high.kappa == pytest.approx(1.0, rel=1e-6)
    assert 1.0 < middle.kappa < 5 / 3 and middle.visc > 0


def test_scale_free_collapse_is_solved_once_per_nondimensional_problem():
    """Preset A without σ and µ: R0 does not enter the problem, so the 210 stops are 30 distinct problems."""
    stops = [
        (r0, p, g)
        for r0 in (100, 200, 500, 1000, 2000, 5000, 10000)
        for p in (0.25, 0.5, 1, 2, 5, 10)
        for g in (0, 1e-4, 1e-3, 1e-2, 1e-1)
    ]
    problems = {
        compose(_point("A", R0=r0, p_inf=p, gas_content=g, kappa=1.4), ("vapour", "step", "gas"))[0]
        for r0, p, g in stops
    }
    assert len(problems) == 30


def test_drawn_curve_passes_through_the_event_detected_minimum():
    """Preset B: the lowest vertex of the drawn R(t) is the event-detected minimum (0.17587 R0, 2nd cycle); samples
    alone stay above 0.35 R0."""
    out = _evaluate("B", ["driven_R_min", "driven_R_min2"])
    curve = Bubble().evaluate(PRESETS["B"][1], wanted=["driven_curve_y"], effects=PRESETS["B"][0])["driven_curve_y"]
    pb, _ = preset_problem("B")
    assert 10 ** np.nanmin(curve) == pytest.approx(min(out.values()), rel=1e-12)
    assert np.nanmin(solve(pb).r) > 2 * min(out.values())


def test_read_run_never_returns_nan_outside_the_curve_padding():
    """Every scalar output of a run is finite or +inf (shown as "—"), never NaN, for each preset."""
    for preset in ("A", "B", "C"):
        pb, scales = preset_problem(preset)
        values = read_run(solve(pb), pb, scales, PRESETS[preset][0])
        assert not any(np.isnan(v) for name, v in values.items() if np.ndim(v) == 0), preset


@pytest.mark.parametrize(
    "status, phrase",
    [
        (OK, "valid"),
        (MACH, "the wall reaches |Ṙ| = c"),
        (KM_STOP, "stopped at |Ṙ| = 0.9c"),
        (POINT, "collapses to a point"),
        (CORE, "van der Waals hard core"),
        (UNBOUNDED_GROWTH, "unbounded growth"),
        (CAP_NFEV, "evaluation cap hit"),
        (FAILED, "solver failed"),
    ],
)
def test_the_compiled_reading_flags_each_end_of_a_run_by_its_phrase(status, phrase):
    """The compiled reading's flag for a run's status indexes the phrase that names it."""
    assert phrase in FLAGS[kernel_read.flag_of_code(STATUS_CODES[status])]


@pytest.mark.parametrize(
    "reason, phrase",
    [
        (kernel_read.NO_GAS, "no gas"),
        (kernel_read.NO_CORE, "no van der Waals hard core"),
        (kernel_read.NOT_REACHED, "not reached"),
    ],
)
def test_the_compiled_reading_says_why_a_value_is_missing_by_its_phrase(reason, phrase):
    """The reasons the compiled reading gives beyond how the run ended index the phrases that say them."""
    assert MISSING[reason].startswith(phrase)
