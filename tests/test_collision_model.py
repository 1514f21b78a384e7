"""I2 (1-D collision with restitution): exact rationals, the cancellation hard cases and the energy ledger."""
from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from sitegen.compute.quantize import fmt
from sitegen.physics.collision import COLLISION, SEPARATING, Collision

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
    ids=["m1=0", "m1<0", "m2=0", "m2<0", "e<0", "e>1", "m1=nan", "m2=nan", "v1i=nan", "v2i=nan", "e=nan",
         "e-array-just-above-1"],
)
def test_invalid_input_raises_naming_the_parameter(inputs):
    """m ≤ 0, e outside [0, 1] or NaN raise ValueError whose message names the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        Collision().evaluate(inputs)
