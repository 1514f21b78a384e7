"""I1 (impulse of a triangular force pulse): closed forms against exact rationals, hard cases, helpers."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from scipy.integrate import quad

from sitegen.compute.quantize import fmt
from sitegen.models.impulse.model import Impulse
from sitegen.models.impulse.pulses import force, velocity

EPS = np.finfo(float).eps

# (F_pk, tau, m) stops: the seed's defaults, the other seed-compatible pairs, the slider corners and odd stops.
STOPS = [
    pytest.param(12.0, 0.20, 2.0, id="defaults-12N-0.20s-2kg"),
    pytest.param(24.0, 0.10, 2.0, id="seed-alt-24N-0.10s"),
    pytest.param(6.0, 0.40, 2.0, id="seed-alt-6N-0.40s"),
    pytest.param(0.5, 0.01, 10.0, id="smallest-pulse-heaviest-mass"),
    pytest.param(50.0, 1.00, 0.1, id="largest-pulse-lightest-mass"),
    pytest.param(50.0, 0.01, 0.1, id="narrow-tall-pulse"),
    pytest.param(37.5, 0.73, 3.3, id="odd-stop-37.5N-0.73s-3.3kg"),
    pytest.param(49.5, 0.99, 0.7, id="odd-stop-49.5N-0.99s-0.7kg"),
    pytest.param(0.0, 0.37, 4.1, id="zero-force"),
]


def _evaluate(F_pk, tau, m):
    """All outputs of the model at one stop, as Python floats."""
    scalars = [o.name for o in Impulse.outputs if not o.size and not o.effect]
    out = Impulse().evaluate({"F_pk": F_pk, "tau": tau, "m": m}, wanted=scalars)
    return {name: float(value) for name, value in out.items()}


def _err_in_eps(value: float, exact: Fraction) -> float:
    """|value − exact| in units of ε·|exact| (an exact zero must be reproduced exactly)."""
    if exact == 0:
        return 0.0 if value == 0 else np.inf
    return float(abs(Fraction(value) - exact) / abs(exact)) / EPS


def _exact_impulse(F_pk, tau) -> Fraction:
    return Fraction(F_pk) * Fraction(tau) / 2


@pytest.mark.parametrize("F_pk, tau, m", STOPS)
def test_impulse_is_half_peak_times_duration(F_pk, tau, m):
    """J = F_pk·τ/2 to one rounding (≤ ε/2 rel) of the exact rational product of the float inputs."""
    assert _err_in_eps(_evaluate(F_pk, tau, m)["J"], _exact_impulse(F_pk, tau)) <= 0.5


@pytest.mark.parametrize("F_pk, tau, m", STOPS)
def test_momentum_change_equals_impulse(F_pk, tau, m):
    """Δp = J to one rounding of the exact rational."""
    assert _err_in_eps(_evaluate(F_pk, tau, m)["dp"], _exact_impulse(F_pk, tau)) <= 0.5


@pytest.mark.parametrize("F_pk, tau, m", STOPS)
def test_velocity_change_is_impulse_over_mass(F_pk, tau, m):
    """Δv = J/m within two roundings (≤ ε rel) of the exact rational."""
    exact = _exact_impulse(F_pk, tau) / Fraction(m)
    assert _err_in_eps(_evaluate(F_pk, tau, m)["dv"], exact) <= 1.0


@pytest.mark.parametrize("F_pk, tau, m", STOPS)
def test_apex_time_is_half_the_duration(F_pk, tau, m):
    """t_apex = τ/2 exactly (halving a float is exact)."""
    assert Fraction(_evaluate(F_pk, tau, m)["t_apex"]) == Fraction(tau) / 2


@pytest.mark.parametrize(
    "output, expected",
    [("J", "1.200"), ("dp", "1.200"), ("dv", "0.600")],
    ids=["J", "dp", "dv"],
)
def test_defaults_display_the_seed_readouts(output, expected):
    """At the defaults (12 N, 0.20 s, 2 kg) the page shows the seed's J 1.200, Δp 1.200, Δv 0.600."""
    value = Impulse().evaluate(Impulse.defaults(), wanted=[output])[output]
    assert fmt(float(value), Impulse.output(output).decimals) == expected


@pytest.mark.parametrize("output", ["J", "dp", "dv"])
def test_zero_peak_force_prints_unsigned_zero(output):
    """F_pk = 0 gives J = Δp = Δv = 0, printed "0.000"."""
    value = Impulse().evaluate({"F_pk": 0.0, "tau": 0.2, "m": 2.0}, wanted=[output])[output]
    assert fmt(float(value), Impulse.output(output).decimals) == "0.000"


@pytest.mark.parametrize(
    "output, expected",
    [("J", "25.000"), ("dv", "250.000")],
    ids=["J", "dv"],
)
def test_light_mass_large_impulse_fits_the_field(output, expected):
    """m = 0.1 kg with J = 25 N·s (50 N, 1 s) shows Δv "250.000" in full."""
    value = Impulse().evaluate({"F_pk": 50.0, "tau": 1.0, "m": 0.1}, wanted=[output])[output]
    assert fmt(float(value), Impulse.output(output).decimals) == expected


def _slider_grid():
    """Every (F_pk, τ) slider stop: F_pk 0.5..50 step 0.5, τ 0.01..1 step 0.01, as 2-D arrays."""
    F_pk = np.arange(1, 101) * 0.5
    tau = np.arange(1, 101) / 100  # the float nearest k/100, as the slider holds it
    return np.meshgrid(F_pk, tau, indexing="ij")


def test_pulse_vertices_are_exact_at_every_stop():
    """force() is 0 at t = 0 and t = τ and exactly F_pk at the apex t_apex, at every (F_pk, τ) stop."""
    F_pk, tau = _slider_grid()
    apex = Impulse().evaluate({"F_pk": F_pk, "tau": tau}, wanted=["t_apex"])["t_apex"]
    vertices = force(np.stack([np.zeros_like(tau), apex, tau]), F_pk, tau)
    assert np.array_equal(vertices, np.stack([np.zeros_like(F_pk), F_pk, np.zeros_like(F_pk)]))


def test_trapezoid_area_of_pulse_polyline_equals_impulse_at_every_stop():
    """The trapezoid area of the polyline (0,0),(τ/2,F_pk),(τ,0) equals J within 1e−14 rel at every stop."""
    F_pk, tau = _slider_grid()
    out = Impulse().evaluate({"F_pk": F_pk, "tau": tau}, wanted=["J", "t_apex"])
    t = np.stack([np.zeros_like(tau), out["t_apex"], tau])
    area = np.trapezoid(force(t, F_pk, tau), t, axis=0)
    worst = np.max(np.abs(area - out["J"]) / out["J"])
    assert worst <= 1e-14, f"worst relative error {worst:.3g}"


@pytest.mark.parametrize("F_pk, tau, m", [s for s in STOPS if s.values[0] > 0])
def test_quadrature_of_force_agrees_with_impulse(F_pk, tau, m):
    """scipy.integrate.quad of force() over [0, τ] (break point τ/2) agrees with J to ≤ 1e−12 rel."""
    area, _ = quad(force, 0.0, tau, args=(F_pk, tau), points=[tau / 2])
    J = _evaluate(F_pk, tau, m)["J"]
    assert abs(area - J) <= 1e-12 * J


@pytest.mark.parametrize("F_pk, tau, m", STOPS)
@pytest.mark.parametrize("v0", [0.0, -3.7, 5.0], ids=["v0=0", "v0=-3.7", "v0=5"])
def test_velocity_gain_over_pulse_is_impulse_over_mass(F_pk, tau, m, v0):
    """velocity(τ) − v0 = J/m (and velocity(0) = v0) within a few ε of the scale of the velocities."""
    exact_gain = float(_exact_impulse(F_pk, tau) / Fraction(m))
    scale = abs(v0) + exact_gain
    assert float(velocity(0.0, F_pk, tau, m, v0)) == v0
    assert abs(float(velocity(tau, F_pk, tau, m, v0)) - v0 - exact_gain) <= 4 * EPS * max(scale, EPS)


@pytest.mark.parametrize("F_pk, tau, m", STOPS)
def test_velocity_is_continuous_at_the_apex(F_pk, tau, m):
    """The rising and falling branches of v(t) meet at τ/2: both equal F_pk·τ/(4m) within 4ε rel."""
    half = 0.5 * tau
    expected = float(Fraction(F_pk) * Fraction(tau) / (4 * Fraction(m)))
    at_apex = float(velocity(half, F_pk, tau, m))
    just_after = float(velocity(np.nextafter(half, np.inf), F_pk, tau, m))
    just_before = float(velocity(np.nextafter(half, -np.inf), F_pk, tau, m))
    for value in (just_before, at_apex, just_after):
        assert abs(value - expected) <= 4 * EPS * max(expected, EPS)


@pytest.mark.parametrize("F_pk, tau, m", STOPS)
def test_velocity_is_constant_after_the_pulse(F_pk, tau, m):
    """After the pulse ends (t > τ) the velocity stays at v(τ); before it starts (t < 0) it is v0."""
    after = velocity(np.array([tau, 1.5 * tau, 10.0]), F_pk, tau, m, 1.0)
    assert np.all(after == after[0])
    assert float(velocity(-1.0, F_pk, tau, m, 1.0)) == 1.0


@pytest.mark.parametrize(
    "inputs",
    [
        {"tau": 0.0},
        {"tau": -0.2},
        {"m": 0.0},
        {"m": -2.0},
        {"F_pk": -1.0},
        {"tau": float("nan")},
        {"m": float("nan")},
        {"F_pk": float("nan")},
        {"m": np.array([2.0, 0.0, 1.0])},
    ],
    ids=["tau=0", "tau<0", "m=0", "m<0", "F_pk<0", "tau=nan", "m=nan", "F_pk=nan", "m-array-with-0"],
)
def test_out_of_domain_input_raises_naming_the_parameter(inputs):
    """τ ≤ 0, m ≤ 0, F_pk < 0 or NaN raise ValueError whose message names the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        Impulse().evaluate(inputs)


# --- effect `shape`: the four pulses of docs/physics/impulse.md
# -------------------------------------------------------------

from sitegen.models.collision.model import Collision  # noqa: E402
from sitegen.models.impulse.pulses import SHAPES, shaped_force  # noqa: E402

# The closed-form J of each shape, as an exact multiple of F_pk·τ (the half-sine's 2/π in floating point).
SHAPE_J = {"triangle": 0.5, "hann": 0.5, "half_sine": 2.0 / np.pi, "rectangle": 1.0}
POSITIVE = [s for s in STOPS if s.values[0] > 0]


def _shaped(shape: str, wanted, effects=("shape",), **inputs):
    """Outputs of the model with the shape effect on and `shape` chosen."""
    return Impulse().evaluate({**inputs, "shape": float(SHAPES.index(shape))}, wanted=wanted, effects=effects)


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("F_pk, tau, m", POSITIVE)
def test_quadrature_of_each_shape_agrees_with_its_closed_form_impulse(F_pk, tau, m, shape):
    """scipy.integrate.quad of the shape's F(t) over [0, τ] equals the model's closed-form J to ≤ 1e−12 rel."""
    area, _ = quad(shaped_force, 0.0, tau, args=(F_pk, tau, shape), points=[tau / 2], epsabs=0.0, epsrel=1e-13)
    J = float(_shaped(shape, ["J"], F_pk=F_pk, tau=tau, m=m)["J"])
    assert abs(area - J) <= 1e-12 * J
    assert J == pytest.approx(SHAPE_J[shape] * F_pk * tau, rel=2 * EPS)


@pytest.mark.parametrize("shape", SHAPES)
def test_each_shape_has_the_same_peak_at_half_the_duration(shape):
    """The drawn samples include t = τ/2 exactly, where the force is F_pk (every shape is symmetric with its peak
    there)."""
    out = _shaped(shape, ["pulse_t", "pulse_F", "t_apex", "F_max"], F_pk=37.5, tau=0.73)
    at_half = out["pulse_t"] == 0.5 * 0.73
    assert np.any(at_half) and np.all(out["pulse_F"][at_half] == 37.5)
    assert float(out["t_apex"]) == 0.5 * 0.73 and float(out["F_max"]) == 37.5


@pytest.mark.parametrize(
    "shape, tolerance",
    [("triangle", 1e-14), ("hann", 1e-14), ("rectangle", 1e-14), ("half_sine", 4e-4)],
    ids=["triangle", "hann", "rectangle", "half_sine"],
)
def test_area_of_the_drawn_pulse_is_the_impulse(shape, tolerance):
    """The trapezoid area of the drawn polygon equals J: exactly (1e−14) for the triangle, the rectangle and the
    Hann pulse (a full period of sin² on even samples), and within π²/12·(1/48)² < 4e−4 for the half-sine."""
    out = _shaped(shape, ["pulse_t", "pulse_F", "J"], F_pk=12.0, tau=0.2)
    area = np.trapezoid(out["pulse_F"], out["pulse_t"])
    assert abs(area - float(out["J"])) <= tolerance * float(out["J"])


def test_triangle_under_the_shape_effect_is_the_base_model_bitwise():
    """shape = triangle reproduces every output of the model without the effect bit for bit (its vanishing limit)."""
    names = ["J", "dp", "dv", "t_apex", "F_max", "pulse_t", "pulse_F", "t_end"]
    inputs = {"F_pk": np.array([0.0, 12.0, 49.5]), "tau": np.array([0.01, 0.2, 0.99]), "m": np.array([0.1, 2.0, 10.0])}
    plain = Impulse().evaluate(inputs, wanted=names)
    shaped = Impulse().evaluate({**inputs, "shape": 0.0}, wanted=names, effects=("shape",))
    for name in names:
        assert np.array_equal(plain[name], shaped[name]), name


# --- effect `initial_velocity`: v(t) ---------------------------------------------------------------------------


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("v0", [0.0, -3.7, 5.0], ids=["v0=0", "v0=-3.7", "v0=5"])
def test_velocity_curve_is_the_running_integral_of_the_force(shape, v0):
    """v(t) at every drawn time is v0 + (1/m)∫₀ᵗ F dt' (quad of the shape's force) within 1e−12 of |v0| + J/m."""
    F_pk, tau, m = 37.5, 0.73, 3.3
    out = _shaped(
        shape,
        ["pulse_t", "v_curve", "v_after", "J"],
        effects=("shape", "initial_velocity"),
        F_pk=F_pk,
        tau=tau,
        m=m,
        v0=v0,
    )
    scale = abs(v0) + float(out["J"]) / m
    for t, v in zip(out["pulse_t"], out["v_curve"]):
        gained, _ = quad(
            shaped_force,
            0.0,
            t,
            args=(F_pk, tau, shape),
            points=[tau / 2] if t > tau / 2 else None,
            epsabs=0.0,
            epsrel=1e-13,
        )
        assert abs(v - (v0 + gained / m)) <= 1e-12 * scale, f"t = {t}"
    assert abs(float(out["v_after"]) - (v0 + float(out["J"]) / m)) <= 2 * EPS * scale


@pytest.mark.parametrize("F_pk, tau, m", STOPS)
def test_velocity_curve_of_the_triangle_is_the_piecewise_quadratic(F_pk, tau, m):
    """For the default triangle the v(t) layer is docs/physics/impulse.md's piecewise quadratic (`velocity`) within 4ε
    of its scale."""
    out = Impulse().evaluate(
        {"F_pk": F_pk, "tau": tau, "m": m, "v0": 1.5}, wanted=["pulse_t", "v_curve"], effects=("initial_velocity",)
    )
    expected = velocity(out["pulse_t"], F_pk, tau, m, 1.5)
    scale = 1.5 + float(_exact_impulse(F_pk, tau) / Fraction(m))
    assert np.max(np.abs(out["v_curve"] - expected)) <= 4 * EPS * scale


def test_initial_velocity_leaves_the_readouts_alone():
    """Adding v0 changes no readout of the base model: J, Δp, Δv are the seed's 1.200, 1.200, 0.600 for any v0."""
    out = Impulse().evaluate({"v0": -4.3}, wanted=["J", "dp", "dv"], effects=("initial_velocity",))
    shown = {name: fmt(float(out[name]), Impulse.output(name).decimals) for name in out}
    assert shown == {"J": "1.200", "dp": "1.200", "dv": "0.600"}


# --- effect `contact_from_collision`: the force of an I2 contact drives the impulse picture -----------------------

CONTACTS = [
    pytest.param(1.0, 2.0, 4.0, 10.0, 0.0, id="elastic-defaults"),
    pytest.param(1.0, 2.0, 4.0, 10.0, 20.0, id="damped-zeta-0.12"),
    pytest.param(0.3, 7.0, 2.5, 40.0, 90.0, id="damped-zeta-0.42"),
    pytest.param(5.0, 0.5, 6.0, 5.0, 60.0, id="zeta-0.63-peak-at-start"),
    pytest.param(2.0, 2.0, 1.0, 2.0, 200.0, id="overdamped"),
]


@pytest.mark.parametrize("m_hit, m, v_rel, k_c, c_d", CONTACTS)
def test_contact_impulse_is_that_of_the_collision(m_hit, m, v_rel, k_c, c_d):
    """J = μ(1 + e)Δ, and the impulse picture's F(t) is the collision's contact force (same curve, t in s vs ms)."""
    out = Impulse().evaluate(
        {"m_hit": m_hit, "m": m, "v_rel": v_rel, "k_c": k_c, "c_d": c_d},
        wanted=["J", "dv", "pulse_t", "pulse_F", "e_contact"],
        effects=("contact_from_collision",),
    )
    hit = Collision().evaluate(
        {"m1": m_hit, "m2": m, "v1i": v_rel, "v2i": 0.0, "k_c": k_c, "c_d": c_d},
        wanted=["J", "v2f", "contact_t", "contact_F", "e_contact"],
        effects=("contact_spring_dashpot",),
    )
    mu = m_hit * m / (m_hit + m)
    assert float(out["J"]) == pytest.approx(mu * (1 + float(out["e_contact"])) * v_rel, rel=4 * EPS)
    assert float(out["J"]) == pytest.approx(float(hit["J"]), rel=4 * EPS)
    assert float(out["dv"]) == pytest.approx(float(hit["v2f"]), rel=1e-14)  # body 2 starts at rest
    assert np.allclose(1e3 * out["pulse_t"], hit["contact_t"], rtol=1e-14, atol=0.0)
    assert np.allclose(out["pulse_F"], hit["contact_F"], rtol=1e-13, atol=1e-13 * float(np.max(hit["contact_F"])))


@pytest.mark.parametrize("m_hit, m, v_rel, k_c, c_d", CONTACTS)
def test_contact_velocity_is_the_running_integral_of_the_contact_force(m_hit, m, v_rel, k_c, c_d):
    """With initial_velocity, v(t) = v0 + (1/m)∫₀ᵗ F dt' (quad of the contact force) within 1e−12 of its scale."""
    from sitegen.physics import contact

    mu, v0 = m_hit * m / (m_hit + m), -0.8
    out = Impulse().evaluate(
        {"m_hit": m_hit, "m": m, "v_rel": v_rel, "k_c": k_c, "c_d": c_d, "v0": v0},
        wanted=["pulse_t", "v_curve", "v_after", "J"],
        effects=("contact_from_collision", "initial_velocity"),
    )
    scale = abs(v0) + float(out["J"]) / m
    for t, v in zip(out["pulse_t"], out["v_curve"]):
        gained, _ = quad(lambda s: float(contact.force(s, mu, 1e3 * k_c, c_d, v_rel)), 0.0, t, epsabs=0.0, epsrel=1e-13)
        assert abs(v - (v0 + gained / m)) <= 1e-12 * scale, f"t = {t}"


def test_shape_and_contact_exclude_each_other():
    """The contact sets the pulse's shape: enabling both is refused by name."""
    with pytest.raises(ValueError, match="exclude each other"):
        Impulse().evaluate({}, wanted=["J"], effects=("shape", "contact_from_collision"))
