"""I2 (1-D collision with restitution): exact rationals, the cancellation hard cases and the energy ledger."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from sitegen.compute.quantize import fmt
from sitegen.models.collision.model import COLLISION, SEPARATING, Collision

EPS = np.finfo(float).eps
NAMES = ("m1", "m2", "v1i", "v2i", "e")


def _evaluate(m1, m2, v1i, v2i, e, wanted=None):
    """The model's outputs at one point (or broadcast arrays of points)."""
    return Collision().evaluate(dict(zip(NAMES, (m1, m2, v1i, v2i, e))), wanted=wanted)


def _exact(m1, m2, v1i, v2i, e) -> dict[str, Fraction]:
    """Every numeric output in exact rational arithmetic on the float inputs (the spec's reference)."""
    m1, m2, v1i, v2i, e = (Fraction(float(x)) for x in (m1, m2, v1i, v2i, e))
    M = m1 + m2
    w1, w2 = m1 / M, m2 / M
    delta = v1i - v2i
    V = w1 * v1i + w2 * v2i
    hit = delta > 0
    v1f = V - e * w2 * delta if hit else v1i
    v2f = V + e * w1 * delta if hit else v2i
    K_before = (m1 * v1i**2 + m2 * v2i**2) / 2
    K_lost = m1 * w2 * (1 - e) * (1 + e) * delta**2 / 2 if hit else Fraction(0)
    return {
        "v1f": v1f,
        "v2f": v2f,
        "v_cm": V,
        "p_before": m1 * v1i + m2 * v2i,
        "K_before": K_before,
        "K_after": (m1 * v1f**2 + m2 * v2f**2) / 2,
        "K_lost": K_lost,
        "K_kept_pct": 100 * (1 - K_lost / K_before) if K_before else Fraction(100),
    }


def _random_approaching(seed: int, n: int = 2000, e=None):
    """Random approaching collisions: masses 10^[−7.5, 7.5] (ratios up to 1e±15), |v| ≤ 5, e in [0, 1]."""
    rng = np.random.default_rng(seed)
    m1, m2 = 10.0 ** rng.uniform(-7.5, 7.5, size=(2, n))
    v = np.sort(rng.uniform(-5.0, 5.0, size=(2, n)), axis=0)
    v2i, v1i = v[0], v[1]  # v1i > v2i: the collision branch
    e = rng.uniform(0.0, 1.0, size=n) if e is None else np.full(n, float(e))
    return m1, m2, v1i, v2i, e


# --- extreme mass ratios ---------------------------------------------------------------------------------

RATIOS = [1e-15, 1e-9, 1.0, 1e9, 1e15]
RATIO_IDS = ["m2/m1=1e-15", "m2/m1=1e-9", "m2/m1=1", "m2/m1=1e9", "m2/m1=1e15"]


@pytest.mark.parametrize("output", ["v1f", "v2f"])
@pytest.mark.parametrize("e", [0.0, 0.5, 0.83, 1.0], ids=["e=0", "e=0.5", "e=0.83", "e=1"])
@pytest.mark.parametrize("v1i, v2i", [(3.0, -1.0), (2.9, -1.7), (0.3, 0.1)], ids=["3|-1", "2.9|-1.7", "0.3|0.1"])
@pytest.mark.parametrize("ratio", RATIOS, ids=RATIO_IDS)
def test_final_velocity_at_extreme_mass_ratio(ratio, v1i, v2i, e, output):
    """|v − v_exact| ≤ 4ε·max(|v1i|, |v2i|) for mass ratios m2/m1 from 1e−15 to 1e15."""
    m1 = 1.3
    m2 = m1 * ratio
    value = float(_evaluate(m1, m2, v1i, v2i, e, wanted=[output])[output])
    error = abs(Fraction(value) - _exact(m1, m2, v1i, v2i, e)[output])
    assert error <= Fraction(4 * EPS) * Fraction(max(abs(v1i), abs(v2i))), f"error {float(error) / EPS:.3g} ε"


# --- the energy lost when it is tiny compared with K ---------------------------------------------------------


@pytest.mark.parametrize(
    "m1, m2",
    [(1e9, 1.0), (1e15, 1.0), (1.0, 1e9), (1.0, 1e15)],
    ids=["m1/m2=1e9", "m1/m2=1e15", "m1/m2=1e-9", "m1/m2=1e-15"],
)
def test_kinetic_energy_lost_when_much_smaller_than_K(m1, m2):
    """ΔK ≪ K (v1i = 3, v2i = 2.9, e = 0.5): K_lost within 8ε rel of ½μ(1−e)(1+e)Δ² in exact rationals."""
    value = float(_evaluate(m1, m2, 3.0, 2.9, 0.5, wanted=["K_lost"])["K_lost"])
    exact = _exact(m1, m2, 3.0, 2.9, 0.5)["K_lost"]
    rel = abs(Fraction(value) - exact) / exact
    assert rel <= Fraction(8 * EPS), f"rel error {float(rel) / EPS:.3g} ε"


@pytest.mark.parametrize("seed", [1, 2], ids=["seed-1", "seed-2"])
def test_kinetic_energy_lost_matches_closed_form_over_random_sample(seed):
    """K_lost is within 8ε rel of the exact ½μ(1−e)(1+e)Δ² over random collisions with ratios up to 1e±15."""
    m1, m2, v1i, v2i, e = _random_approaching(seed, n=500)
    values = _evaluate(m1, m2, v1i, v2i, e, wanted=["K_lost"])["K_lost"]
    worst = max(
        abs(Fraction(float(k)) - ex) / ex
        for k, ex in ((values[i], _exact(m1[i], m2[i], v1i[i], v2i[i], e[i])["K_lost"]) for i in range(len(m1)))
        if ex > 0
    )
    assert worst <= Fraction(8 * EPS), f"worst rel error {float(worst) / EPS:.3g} ε"


# --- separating or equal velocities: no contact ---------------------------------------------------------------


def _no_contact_grid(relation: str):
    """Every stop with v1i < v2i (or v1i == v2i) on v in −5..5 step 0.5, for a few masses and e values."""
    v = np.arange(-10, 11) * 0.5
    m1, m2, v1i, v2i, e = (
        a.ravel() for a in np.meshgrid([0.1, 1.0, 7.3], [0.1, 2.0, 10.0], v, v, [0.0, 0.37, 1.0], indexing="ij")
    )
    keep = v1i < v2i if relation == "separating" else v1i == v2i
    return m1[keep], m2[keep], v1i[keep], v2i[keep], e[keep]


def _bits(array) -> np.ndarray:
    return np.asarray(array, dtype=float).view(np.int64)


NO_CONTACT_CHECKS = {
    "v1f-is-v1i-bitwise": lambda out, v1i, v2i: np.array_equal(_bits(out["v1f"]), _bits(v1i)),
    "v2f-is-v2i-bitwise": lambda out, v1i, v2i: np.array_equal(_bits(out["v2f"]), _bits(v2i)),
    "K_lost-is-0": lambda out, v1i, v2i: np.all(out["K_lost"] == 0.0),
    "K_kept_pct-is-100": lambda out, v1i, v2i: np.all(out["K_kept_pct"] == 100.0),
    "status-is-SEPARATING": lambda out, v1i, v2i: np.all(out["status"] == SEPARATING),
}


@pytest.mark.parametrize("check", NO_CONTACT_CHECKS, ids=list(NO_CONTACT_CHECKS))
@pytest.mark.parametrize("relation", ["separating", "equal"])
def test_no_contact_when_not_approaching(relation, check):
    """For every grid stop with v1i ≤ v2i: v_f == v_i bitwise, nothing is lost, status SEPARATING."""
    m1, m2, v1i, v2i, e = _no_contact_grid(relation)
    assert len(m1) > 0
    out = _evaluate(m1, m2, v1i, v2i, e)
    assert NO_CONTACT_CHECKS[check](out, v1i, v2i)


def test_approaching_bodies_report_a_collision():
    """Every approaching pair (v1i > v2i) has status COLLISION."""
    m1, m2, v1i, v2i, e = _random_approaching(seed=3)
    assert np.all(_evaluate(m1, m2, v1i, v2i, e, wanted=["status"])["status"] == COLLISION)


# --- e = 0 and e = 1 ----------------------------------------------------------------------------------------


def test_perfectly_inelastic_bodies_move_together_bitwise():
    """e = 0: v1f == v2f bitwise over random collisions with mass ratios up to 1e±15."""
    m1, m2, v1i, v2i, e = _random_approaching(seed=4, e=0.0)
    out = _evaluate(m1, m2, v1i, v2i, e, wanted=["v1f", "v2f"])
    assert np.array_equal(_bits(out["v1f"]), _bits(out["v2f"]))


@pytest.mark.parametrize("output, takes", [("v1f", "v2i"), ("v2f", "v1i")], ids=["v1f=v2i", "v2f=v1i"])
@pytest.mark.parametrize(
    "m, v1i, v2i",
    [(1.0, 3.0, -1.0), (0.1, 5.0, -5.0), (7.3, 0.3, 0.1), (2.0, -0.5, -4.9), (1e-15, 4.4, 1.7), (1e15, 1.1, -0.3)],
    ids=["1kg-3|-1", "0.1kg-5|-5", "7.3kg-0.3|0.1", "2kg--0.5|-4.9", "1e-15kg-4.4|1.7", "1e15kg-1.1|-0.3"],
)
def test_elastic_equal_masses_exchange_velocities(m, v1i, v2i, output, takes):
    """e = 1 and m1 = m2: the bodies swap velocities within 2ε·max|v|."""
    value = float(_evaluate(m, m, v1i, v2i, 1.0, wanted=[output])[output])
    expected = {"v1i": v1i, "v2i": v2i}[takes]
    assert abs(value - expected) <= 2 * EPS * max(abs(v1i), abs(v2i))


# --- conservation readouts -------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", [5, 6], ids=["seed-5", "seed-6"])
def test_momentum_is_conserved_over_random_sample(seed):
    """|p_after − p_before| ≤ 4ε(m1|v1i| + m2|v2i|) over random collisions with ratios up to 1e±15."""
    m1, m2, v1i, v2i, e = _random_approaching(seed)
    out = _evaluate(m1, m2, v1i, v2i, e, wanted=["p_before", "p_after"])
    scaled = np.abs(out["p_after"] - out["p_before"]) / (4 * EPS * (m1 * np.abs(v1i) + m2 * np.abs(v2i)))
    assert np.max(scaled) <= 1.0, f"worst case {np.max(scaled):.3g} × the tolerance"


@pytest.mark.parametrize("seed", [7, 8], ids=["seed-7", "seed-8"])
def test_elastic_collision_conserves_kinetic_energy_over_random_sample(seed):
    """e = 1: |K_after − K_before| ≤ 8ε·K_before over random collisions with ratios up to 1e±15."""
    m1, m2, v1i, v2i, e = _random_approaching(seed, e=1.0)
    out = _evaluate(m1, m2, v1i, v2i, e, wanted=["K_before", "K_after"])
    scaled = np.abs(out["K_after"] - out["K_before"]) / (8 * EPS * out["K_before"])
    assert np.max(scaled) <= 1.0, f"worst case {np.max(scaled):.3g} × the tolerance"


# --- other outputs against exact rationals ----------------------------------------------------------------------

POINTS = [
    pytest.param(1.0, 2.0, 3.0, -1.0, 1.0, id="defaults"),
    pytest.param(1.0, 2.0, 3.0, -1.0, 0.5, id="defaults-e=0.5"),
    pytest.param(1.0, 2.0, 3.0, -1.0, 0.0, id="defaults-e=0"),
    pytest.param(0.1, 10.0, 4.7, -2.2, 0.37, id="light-hits-heavy"),
    pytest.param(10.0, 0.1, -0.4, -4.9, 0.91, id="heavy-catches-light"),
    pytest.param(1e9, 1.0, 3.0, 2.9, 0.5, id="ratio-1e9-tiny-loss"),
    pytest.param(1.3, 1.3e-15, 2.9, -1.7, 0.83, id="ratio-1e-15"),
    pytest.param(2.0, 3.0, -1.0, 2.5, 0.6, id="separating"),
    pytest.param(2.0, 3.0, 1.5, 1.5, 0.6, id="equal-velocities"),
]


@pytest.mark.parametrize("m1, m2, v1i, v2i, e", POINTS)
def test_centre_of_mass_velocity(m1, m2, v1i, v2i, e):
    """v_cm = (m1 v1i + m2 v2i)/(m1 + m2) within 4ε·max(|v1i|, |v2i|)."""
    value = float(_evaluate(m1, m2, v1i, v2i, e, wanted=["v_cm"])["v_cm"])
    exact = (Fraction(m1) * Fraction(v1i) + Fraction(m2) * Fraction(v2i)) / (Fraction(m1) + Fraction(m2))
    assert abs(Fraction(value) - exact) <= Fraction(4 * EPS) * Fraction(max(abs(v1i), abs(v2i)))


@pytest.mark.parametrize("output", ["p_before", "K_before", "K_after"])
@pytest.mark.parametrize("m1, m2, v1i, v2i, e", POINTS)
def test_momentum_and_energy_readouts(m1, m2, v1i, v2i, e, output):
    """p_before, K_before and K_after within 8ε of the exact value, scaled by Σ m|v| or Σ ½mv² respectively."""
    value = float(_evaluate(m1, m2, v1i, v2i, e, wanted=[output])[output])
    exact = _exact(m1, m2, v1i, v2i, e)
    if output == "p_before":
        scale = abs(Fraction(m1) * Fraction(v1i)) + abs(Fraction(m2) * Fraction(v2i))
    else:
        scale = exact["K_before"]
    assert abs(Fraction(value) - exact[output]) <= Fraction(8 * EPS) * scale


@pytest.mark.parametrize("m1, m2, v1i, v2i, e", POINTS)
def test_kinetic_energy_kept_percentage(m1, m2, v1i, v2i, e):
    """K_kept_pct = 100·(1 − K_lost/K_before) within 8ε·100 (exactly 100 when nothing is lost)."""
    value = float(_evaluate(m1, m2, v1i, v2i, e, wanted=["K_kept_pct"])["K_kept_pct"])
    exact = _exact(m1, m2, v1i, v2i, e)
    if exact["K_lost"] == 0:
        assert value == 100.0
    else:
        assert abs(Fraction(value) - exact["K_kept_pct"]) <= Fraction(8 * EPS) * 100


@pytest.mark.parametrize(
    "v1i, v2i, e",
    [(3.0, -1.0, 1.0), (-2.0, 4.0, 0.3), (0.0, 0.0, 0.0), (1.5, 1.5, 0.2)],
    ids=["elastic", "separating", "both-at-rest", "equal-velocities"],
)
def test_kinetic_energy_kept_is_exactly_100_when_nothing_is_lost(v1i, v2i, e):
    """K_kept_pct is exactly 100 for an elastic collision, no contact, or bodies at rest (no 0/0)."""
    assert float(_evaluate(1.0, 2.0, v1i, v2i, e, wanted=["K_kept_pct"])["K_kept_pct"]) == 100.0


def test_kinetic_energy_kept_is_zero_when_everything_is_lost():
    """Equal masses meeting head-on at equal speeds with e = 0 keep 0 % of K."""
    assert float(_evaluate(1.0, 1.0, 2.0, -2.0, 0.0, wanted=["K_kept_pct"])["K_kept_pct"]) == 0.0


# --- the seed's readouts ---------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "output, expected",
    [
        ("v1f", "\u22122.333"),
        ("v2f", "1.667"),
        ("p_before", "1.00"),
        ("p_after", "1.00"),
        ("K_before", "5.50"),
        ("K_after", "5.50"),
        ("K_lost", "0.00"),
        ("K_kept_pct", "100.0"),
    ],
    ids=["v1f", "v2f", "p_before", "p_after", "K_before", "K_after", "K_lost", "K_kept_pct"],
)
def test_defaults_display_the_seed_readouts(output, expected):
    """At the defaults (1, 2, 3, −1, 1) the page shows the seed's readouts (U+2212 minus)."""
    value = Collision().evaluate(Collision.defaults(), wanted=[output])[output]
    assert fmt(float(value), Collision.output(output).decimals) == expected


def test_defaults_report_a_collision():
    """At the defaults the status is COLLISION (body 1 at 3 m/s catches body 2 at −1 m/s)."""
    assert int(Collision().evaluate(Collision.defaults(), wanted=["status"])["status"]) == COLLISION


# --- invalid input -----------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "inputs",
    [
        {"m1": 0.0},
        {"m1": -1.0},
        {"m2": 0.0},
        {"m2": -1e-300},
        {"e": -0.01},
        {"e": 1.01},
        {"m1": float("nan")},
        {"m2": float("nan")},
        {"v1i": float("nan")},
        {"v2i": float("nan")},
        {"e": float("nan")},
        {"e": np.array([0.5, 1.0 + 1e-15])},
    ],
    ids=[
        "m1=0",
        "m1<0",
        "m2=0",
        "m2<0",
        "e<0",
        "e>1",
        "m1=nan",
        "m2=nan",
        "v1i=nan",
        "v2i=nan",
        "e=nan",
        "e-array-just-above-1",
    ],
)
def test_invalid_input_raises_naming_the_parameter(inputs):
    """m ≤ 0, e outside [0, 1] or NaN raise ValueError whose message names the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        Collision().evaluate(inputs)


# --- effect `contact_spring_dashpot`: a finite contact, μδ'' + c_d δ' + k_c δ = 0 ----------------------------------

from scipy.integrate import quad, solve_ivp  # noqa: E402

from sitegen.physics import contact  # noqa: E402

CONTACT = ("contact_spring_dashpot",)
# (m1, m2, v1i, v2i, k_c kN/m, c_d N·s/m): ζ from 0 to 0.9, mass ratios 1e−3 … 1e3, bodies moving either way.
CONTACT_CASES = [
    pytest.param(1.0, 2.0, 3.0, -1.0, 10.0, 0.0, id="defaults-elastic"),
    pytest.param(1.0, 2.0, 3.0, -1.0, 10.0, 20.0, id="defaults-zeta-0.12"),
    pytest.param(0.1, 10.0, 4.7, -2.2, 40.0, 30.0, id="light-hits-heavy-zeta-0.24"),
    pytest.param(10.0, 0.1, -0.4, -4.9, 5.0, 25.0, id="heavy-catches-light-zeta-0.56"),
    pytest.param(2.0, 3.0, 1.2, 0.4, 2.0, 88.0, id="zeta-0.90"),
    pytest.param(1e3, 1.0, 0.5, -0.5, 50.0, 100.0, id="ratio-1e-3-zeta-0.22"),
    pytest.param(1.0, 1e3, 5.0, 4.9, 1.0, 1.0, id="ratio-1e3-slow-zeta-0.016"),
]


def _contact_inputs(m1, m2, v1i, v2i, k_c, c_d) -> dict:
    return {"m1": m1, "m2": m2, "v1i": v1i, "v2i": v2i, "k_c": k_c, "c_d": c_d}


def _integrate_contact(m1, m2, v1i, v2i, k_c, c_d):
    """Second method: both bodies' positions and velocities by DOP853 (rtol 1e−12) while they overlap;
    the force k_c δ + c_d δ' pushes them apart; a terminal event ends the contact where δ returns to 0."""
    k = 1e3 * k_c

    def rhs(t, y):
        x1, x2, u1, u2 = y
        force = k * (x1 - x2) + c_d * (u1 - u2)  # on body 2, compressive > 0
        return (u1, u2, -force / m1, force / m2)

    def separated(t, y):
        return y[0] - y[1]

    separated.terminal, separated.direction = True, -1
    period = 2 * np.pi * np.sqrt(m1 * m2 / (m1 + m2) / k)
    solution = solve_ivp(
        rhs,
        (0.0, 10 * period),
        (0.0, 0.0, v1i, v2i),
        method="DOP853",
        rtol=1e-12,
        atol=1e-15 * max(abs(v1i), abs(v2i)) * period,
        events=separated,
        first_step=period * 1e-6,
    )
    assert solution.status == 1, solution.message
    return solution.t_events[0][0], solution.y_events[0][0]


@pytest.mark.parametrize("m1, m2, v1i, v2i, k_c, c_d", CONTACT_CASES)
def test_integrated_contact_reproduces_the_restitution_law_with_its_e(m1, m2, v1i, v2i, k_c, c_d):
    """The ODE-integrated contact ends with the velocities of the restitution law at the model's e_contact,
    within 1e−9 of max(|v1i|, |v2i|), and after the model's contact time within 1e−9 rel."""
    t_end, (_, _, u1, u2) = _integrate_contact(m1, m2, v1i, v2i, k_c, c_d)
    out = Collision().evaluate(
        _contact_inputs(m1, m2, v1i, v2i, k_c, c_d), wanted=["v1f", "v2f", "e_contact", "t_contact"], effects=CONTACT
    )
    law = _evaluate(m1, m2, v1i, v2i, float(out["e_contact"]), wanted=["v1f", "v2f"])
    scale = max(abs(v1i), abs(v2i))
    assert abs(u1 - float(law["v1f"])) <= 1e-9 * scale and abs(u2 - float(law["v2f"])) <= 1e-9 * scale
    assert float(out["v1f"]) == float(law["v1f"]) and float(out["v2f"]) == float(law["v2f"])
    assert abs(1e-3 * float(out["t_contact"]) / t_end - 1) <= 1e-9


@pytest.mark.parametrize("zeta", [0.0, 1e-12, 1e-6, 0.1, 0.5, 0.9, 0.999], ids=lambda z: f"zeta={z}")
def test_restitution_of_the_contact_is_its_closed_form(zeta):
    """e = exp(−x), x = ζπ/√(1 − ζ²) with 1 − ζ² taken exactly: within 4ε(1 + x) rel (the exponent's own
    rounding is amplified by x), so the root formed as √((1 − ζ)(1 + ζ)) keeps its digits as ζ → 1."""
    import math

    exponent = math.pi * zeta / math.sqrt(float(1 - Fraction(zeta) ** 2))
    expected = math.exp(-exponent)
    assert abs(float(contact.restitution(zeta)) - expected) <= 4 * EPS * (1 + exponent) * expected


@pytest.mark.parametrize("zeta", [1e-12, 1e-9, 1e-6, 1e-3, 1e-2], ids=lambda z: f"zeta={z}")
def test_restitution_tends_to_one_as_damping_vanishes(zeta):
    """Vanishing limit (ζ → 0 ⇒ e → 1): 0 ≤ 1 − e ≤ πζ/√(1 − ζ²), and the final velocities approach
    the elastic law's within w·Δ·(1 − e)."""
    mu, k = 2.0 / 3.0, 1e4
    c = zeta * 2 * np.sqrt(k * mu)
    e = float(contact.restitution(contact.damping_ratio(mu, k, c)))
    assert 0.0 <= 1.0 - e <= np.pi * zeta / np.sqrt(1 - zeta**2) * (1 + 1e-12) + 2 * EPS
    out = Collision().evaluate({"k_c": 10.0, "c_d": c}, wanted=["v1f", "v2f"], effects=CONTACT)
    elastic = _evaluate(1.0, 2.0, 3.0, -1.0, 1.0, wanted=["v1f", "v2f"])
    assert abs(float(out["v1f"]) - float(elastic["v1f"])) <= (2 / 3) * 4 * (1 - e) + 4 * EPS * 3
    assert abs(float(out["v2f"]) - float(elastic["v2f"])) <= (1 / 3) * 4 * (1 - e) + 4 * EPS * 3


def test_undamped_contact_is_the_elastic_law_bitwise():
    """c_d = 0 gives e = 1 exactly and every readout of the elastic collision bit for bit (the seed's values)."""
    names = ["v1f", "v2f", "p_after", "K_after", "K_lost", "K_kept_pct", "status"]
    m1, m2, v1i, v2i, e = _random_approaching(11, n=200, e=1.0)
    law = _evaluate(m1, m2, v1i, v2i, e, wanted=names)
    spring = Collision().evaluate(
        {"m1": m1, "m2": m2, "v1i": v1i, "v2i": v2i, "k_c": 7.0, "c_d": 0.0}, wanted=names, effects=CONTACT
    )
    assert all(np.array_equal(law[n], spring[n]) for n in names)


@pytest.mark.parametrize("m1, m2, v1i, v2i, k_c, c_d", CONTACT_CASES)
def test_impulse_of_the_contact_is_the_area_under_its_force(m1, m2, v1i, v2i, k_c, c_d):
    """J = μ(1 + e)Δ equals quad of F(t) over the contact (1e−12 rel) and m2(v2f − v2i) (1e−13 rel)."""
    mu = m1 * m2 / (m1 + m2)
    out = Collision().evaluate(
        _contact_inputs(m1, m2, v1i, v2i, k_c, c_d), wanted=["J", "t_contact", "v2f"], effects=CONTACT
    )
    area, _ = quad(
        lambda t: float(contact.force(t, mu, 1e3 * k_c, c_d, v1i - v2i)),
        0.0,
        1e-3 * float(out["t_contact"]),
        epsabs=0.0,
        epsrel=1e-13,
        limit=200,
    )
    J = float(out["J"])
    assert abs(area - J) <= 1e-12 * J
    assert abs(m2 * (float(out["v2f"]) - v2i) - J) <= 1e-13 * (J + m2 * abs(v2i))


@pytest.mark.parametrize("m1, m2, v1i, v2i, k_c, c_d", CONTACT_CASES)
def test_contact_ends_where_the_overlap_closes_with_the_dashpot_pulling(m1, m2, v1i, v2i, k_c, c_d):
    """The stated criterion: at t_c the overlap is 0 (to 1e−12 of its largest value) and the force is the
    dashpot's pull, F(t_c) = −c_d e Δ (tensile when damped)."""
    mu, k, delta = m1 * m2 / (m1 + m2), 1e3 * k_c, v1i - v2i
    out = Collision().evaluate(
        _contact_inputs(m1, m2, v1i, v2i, k_c, c_d), wanted=["t_contact", "e_contact"], effects=CONTACT
    )
    t_c, e = 1e-3 * float(out["t_contact"]), float(out["e_contact"])
    samples = np.linspace(0.0, t_c, 2001)
    assert abs(float(contact.overlap(t_c, mu, k, c_d, delta))) <= 1e-12 * np.max(
        contact.overlap(samples, mu, k, c_d, delta)
    )
    assert float(contact.force(t_c, mu, k, c_d, delta)) == pytest.approx(
        -c_d * e * delta, rel=1e-9, abs=1e-9 * k * delta / np.sqrt(k / mu)
    )


@pytest.mark.parametrize("m1, m2, v1i, v2i, k_c, c_d", CONTACT_CASES)
def test_peak_contact_force_is_the_maximum_of_the_force(m1, m2, v1i, v2i, k_c, c_d):
    """F_max is the largest force: no sample of F over the contact exceeds it (1e−12), and a bounded
    minimiser started anywhere finds the same value within 1e−9 rel."""
    from scipy.optimize import minimize_scalar

    mu, k, delta = m1 * m2 / (m1 + m2), 1e3 * k_c, v1i - v2i
    out = Collision().evaluate(
        _contact_inputs(m1, m2, v1i, v2i, k_c, c_d), wanted=["t_contact", "F_max"], effects=CONTACT
    )
    t_c, peak = 1e-3 * float(out["t_contact"]), float(out["F_max"])
    forces = contact.force(np.linspace(0.0, t_c, 20001), mu, k, c_d, delta)
    assert np.max(forces) <= peak * (1 + 1e-12)
    best = minimize_scalar(
        lambda t: -float(contact.force(t, mu, k, c_d, delta)),
        bounds=(0.0, t_c),
        method="bounded",
        options={"xatol": 1e-14 * t_c},
    )
    assert max(-best.fun, float(forces[0])) == pytest.approx(peak, rel=1e-9)


@pytest.mark.parametrize("c_d", [2 * np.sqrt(1e4 * 2 / 3), 100.0, 1e4], ids=["critical", "zeta-0.61", "zeta-61"])
def test_overdamped_contact_never_ends_and_the_bodies_move_together(c_d):
    """ζ ≥ 1: the overlap never closes, so t_c = ∞ (shown as a phrase), e = 0 and v1f == v2f bitwise;
    just below critical damping e is continuous with 0."""
    out = Collision().evaluate(
        {"k_c": 10.0, "c_d": c_d}, wanted=["t_contact", "e_contact", "v1f", "v2f", "contact_F"], effects=CONTACT
    )
    zeta = float(contact.damping_ratio(2 / 3, 1e4, c_d))
    if zeta >= 1:
        assert np.isinf(out["t_contact"]) and float(out["e_contact"]) == 0.0
        assert float(out["v1f"]) == float(out["v2f"])
    assert np.all(np.isfinite(out["contact_F"]))
    assert float(contact.restitution(np.nextafter(1.0, 0.0))) < 1e-6


def test_contact_time_does_not_depend_on_the_approach_speed():
    """A linear contact lasts π/ω_d whatever the speed: t_contact is the same for Δ = 0.1 and 10 m/s (bitwise)."""
    slow = Collision().evaluate({"v1i": 0.1, "v2i": 0.0, "c_d": 30.0}, wanted=["t_contact"], effects=CONTACT)
    fast = Collision().evaluate({"v1i": 5.0, "v2i": -5.0, "c_d": 30.0}, wanted=["t_contact"], effects=CONTACT)
    assert float(slow["t_contact"]) == float(fast["t_contact"])


def test_separating_bodies_feel_no_contact_force():
    """v1i ≤ v2i: no impulse, no force, the velocities unchanged bitwise (the contact never starts)."""
    out = Collision().evaluate(
        {"v1i": -1.0, "v2i": 2.0, "c_d": 30.0}, wanted=["J", "F_max", "contact_F", "v1f", "v2f"], effects=CONTACT
    )
    assert float(out["J"]) == 0.0 and float(out["F_max"]) == 0.0 and np.all(out["contact_F"] == 0.0)
    assert (float(out["v1f"]), float(out["v2f"])) == (-1.0, 2.0)


def test_contact_defaults_display_the_seed_readouts():
    """With the contact and c_d = 0 the defaults show the elastic seed readouts −2.333, 1.667 and K lost 0.00."""
    out = Collision().evaluate(Collision.defaults(), wanted=["v1f", "v2f", "K_lost"], effects=CONTACT)
    assert [fmt(float(out[n]), Collision.output(n).decimals) for n in ("v1f", "v2f", "K_lost")] == [
        "\u22122.333",
        "1.667",
        "0.00",
    ]


# --- effect `explosive`: e > 1 only when the scene asks for it -----------------------------------------------------


@pytest.mark.parametrize("e", [1.01, 1.5, 3.0], ids=["e=1.01", "e=1.5", "e=3"])
def test_restitution_above_one_needs_the_explosive_effect(e):
    """e > 1 is rejected (naming `e` and the effect that would allow it) unless `explosive` is on."""
    with pytest.raises(ValueError, match="`e`.*explosive"):
        Collision().evaluate({"e": e})
    Collision().evaluate({"e": e}, effects=("explosive",))


@pytest.mark.parametrize("e", [1.25, 2.0], ids=["e=1.25", "e=2"])
def test_explosive_collision_gains_energy_and_keeps_momentum(e):
    """e > 1: momentum conserved (4ε), K_lost = −½μ(e² − 1)Δ² < 0 (8ε rel), velocities from the same law (exact
    rationals)."""
    m1, m2, v1i, v2i, _ = _random_approaching(12, n=300, e=0.0)
    out = Collision().evaluate(
        {"m1": m1, "m2": m2, "v1i": v1i, "v2i": v2i, "e": e},
        effects=("explosive",),
        wanted=["v1f", "p_before", "p_after", "K_lost"],
    )
    scaled = np.abs(out["p_after"] - out["p_before"]) / (4 * EPS * (m1 * np.abs(v1i) + m2 * np.abs(v2i)))
    assert np.max(scaled) <= 1.0
    assert np.all(out["K_lost"] < 0)
    for i in range(0, 300, 37):
        exact = _exact(m1[i], m2[i], v1i[i], v2i[i], e)
        assert abs(Fraction(float(out["K_lost"][i])) - exact["K_lost"]) <= 8 * EPS * abs(exact["K_lost"])
        assert abs(Fraction(float(out["v1f"][i])) - exact["v1f"]) <= Fraction(4 * EPS) * Fraction(
            max(abs(v1i[i]), abs(v2i[i]))
        ) * Fraction(e)


def test_explosive_within_the_usual_range_is_the_base_law_bitwise():
    """With e ≤ 1 the explosive effect changes nothing (its vanishing limit)."""
    m1, m2, v1i, v2i, e = _random_approaching(13, n=300)
    names = [o.name for o in Collision.outputs if not o.effect]
    plain = _evaluate(m1, m2, v1i, v2i, e, wanted=names)
    explosive = Collision().evaluate(dict(zip(NAMES, (m1, m2, v1i, v2i, e))), wanted=names, effects=("explosive",))
    assert all(np.array_equal(plain[n], explosive[n]) for n in names)


@pytest.mark.parametrize("other", ["restitution_law", "explosive"])
def test_contact_excludes_the_instantaneous_laws(other):
    """The contact replaces the restitution law: naming it with restitution_law or explosive is refused."""
    with pytest.raises(ValueError, match="excludes"):
        Collision().evaluate({}, wanted=["v1f"], effects=("contact_spring_dashpot", other))
