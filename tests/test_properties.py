"""Property-based tests (hypothesis) of the invariants of docs/physics/ over the whole parameter domain,
far beyond the sliders: conservation in every collision at mass ratios 1e−15…1e15, the chain's exact
energy, the path independence of a conservative force, the shape independence of an impulse, the
lever's mirror antisymmetry, and the vanishing limit of every effect of every model (docs/physics/README.md, effects,
rule 2).

Every property runs with fixed settings (`derandomize=True`, no example database, no deadline), so a
run is reproducible; a failure prints the falsifying example. The models are driven through their
public `evaluate(inputs, wanted, effects)`; a quadrature helper of the work model serves as the
independent second method where the model's readout is a closed form.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import pytest
from examples import examples as share_of
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.special import cosdg

from sitegen.models.acoustic_energy.model import C as C_AIR
from sitegen.models.bubble import model as bubble_module
from sitegen.models.bubble.terms import P0
from sitegen.models.impulse.model import Impulse
from sitegen.models.impulse.pulses import force
from sitegen.models.lever.mechanics import TIPS_LEFT, TIPS_RIGHT
from sitegen.models.work.paths import ARC, DIRECT, SPRING, line_integral_work
from sitegen.registry import builtin_registry

MODELS = builtin_registry().models

EPS = np.finfo(float).eps
G = 9.81


def _settings(examples: int):
    """Deterministic hypothesis settings: the same examples on every run, no database, no deadline."""
    return settings(
        max_examples=share_of(examples),
        derandomize=True,
        database=None,
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
    )


def _log_uniform(lo_exp: float, hi_exp: float) -> st.SearchStrategy[float]:
    """10**u for u uniform in [lo_exp, hi_exp]: a positive value spread over decades."""
    return st.floats(lo_exp, hi_exp).map(lambda u: 10.0**u)


def _signed(magnitudes: st.SearchStrategy[float]) -> st.SearchStrategy[float]:
    return st.builds(lambda sign, value: sign * value, st.sampled_from([-1.0, 1.0]), magnitudes)


def _small(hi_exp: float, lo_exp: float = -300.0, zero: bool = True, signed: bool = False) -> st.SearchStrategy[float]:
    """A departure δ from a neutral value: exactly 0 (unless `zero` is False), or ±10**u with u in
    [lo_exp, hi_exp] (the sign only when `signed`)."""
    magnitudes = _log_uniform(lo_exp, hi_exp)
    if signed:
        magnitudes = _signed(magnitudes)
    return st.one_of(st.just(0.0), magnitudes) if zero else magnitudes


# ================================================================================================
# I2 collisions: conservation and exactness at any mass ratio 1e−15 … 1e15
# ================================================================================================

COLLISION = MODELS["collision"]()
# Any velocity from 1e−100 to 1e100 m/s in size, or 0 (smaller sizes only test the underflow of v²).
_VELOCITY = st.one_of(
    st.just(0.0),
    st.floats(-1e3, 1e3).filter(lambda v: v == 0.0 or abs(v) >= 1e-100),
    _signed(_log_uniform(-100.0, 100.0)),
)
# m1 anywhere in 1e−30 … 1e30 kg, m2/m1 in 1e−15 … 1e15.
_MASSES = st.builds(lambda a, r: (10.0**a, 10.0 ** (a + r)), st.floats(-30.0, 30.0), st.floats(-15.0, 15.0))
_RESTITUTION = st.one_of(st.sampled_from([0.0, 0.5, 1.0]), st.floats(0.0, 1.0))


@st.composite
def _approaching(draw, e=_RESTITUTION):
    """(m1, m2, v1i, v2i, e) with v1i > v2i: the bodies collide."""
    m1, m2 = draw(_MASSES)
    a, b = draw(_VELOCITY), draw(_VELOCITY)
    if a == b:
        b = a - max(abs(a), 1.0)
    v1i, v2i = max(a, b), min(a, b)
    return m1, m2, v1i, v2i, draw(e)


def _collide(m1, m2, v1i, v2i, e, wanted=None) -> dict[str, float]:
    out = COLLISION.evaluate({"m1": m1, "m2": m2, "v1i": v1i, "v2i": v2i, "e": e}, wanted=wanted)
    return {name: float(value) for name, value in out.items()}


def _exact_collision(m1, m2, v1i, v2i, e) -> dict[str, Fraction]:
    """The final velocities and the energy lost in exact rationals on the float inputs (docs/physics/collision.md)."""
    m1, m2, v1i, v2i, e = (Fraction(x) for x in (m1, m2, v1i, v2i, e))
    M = m1 + m2
    delta = v1i - v2i
    V = (m1 * v1i + m2 * v2i) / M
    if delta <= 0:
        return {"v1f": v1i, "v2f": v2i, "K_lost": Fraction(0)}
    return {
        "v1f": V - e * m2 / M * delta,
        "v2f": V + e * m1 / M * delta,
        "K_lost": m1 * m2 / M * (1 - e) * (1 + e) * delta**2 / 2,
    }


@_settings(500)
@given(_approaching())
def test_collision_conserves_momentum_at_any_mass_ratio(case):
    """|p_after − p_before| ≤ 4ε(m1|v1i| + m2|v2i|) for mass ratios 1e−15…1e15 and any velocities."""
    m1, m2, v1i, v2i, _ = case
    out = _collide(*case, wanted=["p_before", "p_after"])
    error = abs(Fraction(out["p_after"]) - Fraction(out["p_before"]))
    assert error <= 4 * Fraction(EPS) * (Fraction(m1) * abs(Fraction(v1i)) + Fraction(m2) * abs(Fraction(v2i))), (
        f"error {float(error) / (EPS * (m1 * abs(v1i) + m2 * abs(v2i))):.3g} ε·Σm|v|"
    )


@_settings(500)
@given(_approaching(e=st.just(1.0)))
def test_elastic_collision_conserves_kinetic_energy_at_any_mass_ratio(case):
    """e = 1: |K_after − K_before| ≤ 8ε K_before for mass ratios 1e−15…1e15 and any velocities."""
    out = _collide(*case, wanted=["K_before", "K_after"])
    error = abs(Fraction(out["K_after"]) - Fraction(out["K_before"]))
    assert error <= 8 * Fraction(EPS) * Fraction(out["K_before"]), (
        f"error {float(error) / (EPS * out['K_before']):.3g} ε·K"
    )


@_settings(500)
@given(_approaching())
def test_collision_final_velocities_are_the_exact_rationals(case):
    """|v − v_exact| ≤ 4ε max(|v1i|, |v2i|) against exact rational arithmetic on the float inputs."""
    _, _, v1i, v2i, _ = case
    out, exact = _collide(*case, wanted=["v1f", "v2f"]), _exact_collision(*case)
    scale = max(abs(Fraction(v1i)), abs(Fraction(v2i)))
    for name in ("v1f", "v2f"):
        error = abs(Fraction(out[name]) - exact[name])
        assert error <= 4 * Fraction(EPS) * scale, f"{name}: error {float(error / scale) / EPS:.3g} ε·max|v|"


@_settings(500)
@given(_approaching())
def test_collision_energy_lost_is_the_exact_closed_form(case):
    """K_lost within 8ε rel of the exact ½μ(1−e)(1+e)Δ² (never K_before − K_after), at any mass ratio."""
    out, exact = _collide(*case, wanted=["K_lost"]), _exact_collision(*case)["K_lost"]
    if exact == 0:
        assert out["K_lost"] == 0.0
    else:
        rel = abs(Fraction(out["K_lost"]) - exact) / exact
        assert rel <= 8 * Fraction(EPS), f"rel error {float(rel) / EPS:.3g} ε"


@_settings(300)
@given(_MASSES, _VELOCITY, _VELOCITY, _RESTITUTION, st.booleans())
def test_bodies_that_do_not_approach_keep_their_velocities_bitwise(masses, a, b, e, equal):
    """v1i ≤ v2i (separating or equal): v_f is v_i bitwise, nothing is lost, K kept is 100 %."""
    v1i, v2i = (a, a) if equal else (min(a, b), max(a, b))
    out = _collide(*masses, v1i, v2i, e, wanted=["v1f", "v2f", "K_lost", "K_kept_pct"])
    assert np.float64(out["v1f"]).tobytes() == np.float64(v1i).tobytes()
    assert np.float64(out["v2f"]).tobytes() == np.float64(v2i).tobytes()
    assert out["K_lost"] == 0.0 and out["K_kept_pct"] == 100.0


# ================================================================================================
# I5 chain: the exact (DST) solution conserves energy for any N, σ, launch, ends, ω0 and time
# ================================================================================================

CHAIN = MODELS["chain"]()
_CHAIN_POINT = st.fixed_dictionaries(
    {
        "N": st.integers(1, 256).map(float),
        "sigma": st.floats(-3.0, math.log10(0.05)).map(lambda u: min(10.0**u, 0.05)),
        "t": st.one_of(st.floats(0.0, 2.0), st.floats(0.0, 1e4)),
        "launch": st.sampled_from([0.0, 1.0]),
        "ends": st.sampled_from([0.0, 1.0, 2.0]),
        "omega0": st.one_of(st.just(0.0), st.floats(0.0, 50.0)),
    }
)


def _chain_energies(point) -> tuple[float, float, float]:
    """E(0), E(t) and ω_max of the exact solution: E(t) is the engine's energy of the exact state at t (the
    `onsite_damping` readout at γ = 0), E(0) the conserved readout."""
    out = CHAIN.evaluate(
        {**point, "gamma": 0.0},
        wanted=["E_chain", "E_now", "omega_max"],
        effects=("boundary", "onsite_damping", "onsite_spring"),
    )
    return float(out["E_chain"]), float(out["E_now"]), float(out["omega_max"])


@_settings(300)
@given(_CHAIN_POINT)
def test_exact_chain_conserves_energy_at_any_time(point):
    """Undamped: |E(t)/E(0) − 1| ≤ 1e−12 + 4ε·ω_max·t for any N, σ, launch, ends, ω0 and t ≤ 1e4
    (docs/physics/chain.md: 1e−12, with the ε·ωt rounding of the phase it allows at huge t); the absolute floor
    1e−290 only covers sums that fall into subnormals."""
    e0, et, omega_max = _chain_energies(point)
    tolerance = 1e-12 + 4 * EPS * omega_max * point["t"]
    assert math.isfinite(et) and abs(et - e0) <= tolerance * e0 + 1e-290, f"E(t)/E(0) − 1 = {et / e0 - 1:.3g}"


@example({"N": 24.0, "sigma": 0.01, "t": 1115.0, "launch": 0.0, "ends": 0.0, "omega0": 0.0})
@_settings(100)
@given(_CHAIN_POINT.filter(lambda p: p["t"] >= 100.0))
def test_exact_chain_energy_does_not_drift_with_the_phase(point):
    """Each mode's (ωû)² + v̂² does not depend on its phase, so the exact solution should keep E(t)/E(0) − 1
    within 1e−12 however long it runs (t = 1e2 … 1e4), not only up to ε·ωt. Free ends and a ring are the
    exception: no wall holds them, so their free translation (total momentum × t) rides in every u_j and
    its rounding enters the stretches; they are held to the ε·ω_max·t bound of the test above (measured
    1.6e−12 for a ring at N = 163, σ = 0.001, t = 1611)."""
    e0, et, omega_max = _chain_energies(point)
    drifting = 4 * EPS * omega_max * point["t"] if point["ends"] != 0.0 else 0.0  # 0: fixed ends
    assert abs(et - e0) <= (1e-12 + drifting) * e0 + 1e-290, f"E(t)/E(0) − 1 = {et / e0 - 1:.3g}"


# ================================================================================================
# I3 work: a conservative force does the same work on every path
# ================================================================================================

WORK = MODELS["work"]()
_SPRING_CASE = st.fixed_dictionaries(
    {
        "k": _log_uniform(-3.0, 3.0),
        "x_c": st.floats(-5.0, 5.0),
        "ell0": st.one_of(st.just(0.0), st.floats(0.0, 3.0)),
        "h": st.one_of(st.sampled_from([0.0, 1e-12, 1.0, 4.0]), st.floats(0.0, 4.0)),
    }
)


def _exact_potential_drop(k, x_c, ell0) -> Fraction:
    """U(A) − U(B) = ½k[(|A − C| − ℓ0)² − (|B − C| − ℓ0)²] in exact rationals."""
    k, x_c, ell0 = (Fraction(v) for v in (k, x_c, ell0))
    d_a, d_b = abs(-1 - x_c), abs(1 - x_c)
    return k * ((d_a - ell0) ** 2 - (d_b - ell0) ** 2) / 2


def _energy_scale(case) -> float:
    """k R² with R the farthest the spring is stretched on either path: the natural size of W."""
    return case["k"] * (1.0 + abs(case["x_c"]) + case["h"] + case["ell0"]) ** 2


@_settings(300)
@given(_SPRING_CASE)
def test_spring_work_is_path_independent_by_quadrature(case):
    """|W_arc − W_direct| ≤ 1e−12·kR² by adaptive Gauss–Legendre line integrals, for any anchor, rest
    length and sagitta, and both equal the exact U(A) − U(B) to the same tolerance (docs/physics/work.md:
    1e−12 J at k R² ~ 1)."""
    args = dict(k=case["k"], x_c=case["x_c"], ell0=case["ell0"] or None)
    scale = _energy_scale(case)
    arc = line_integral_work(SPRING, ARC, case["h"], tol=1e-15 * scale, **args)
    direct = line_integral_work(SPRING, DIRECT, case["h"], tol=1e-15 * scale, **args)
    exact = _exact_potential_drop(case["k"], case["x_c"], case["ell0"])
    assert abs(arc - direct) <= 1e-12 * scale, f"|W_arc − W_dir| = {abs(arc - direct) / scale:.3g} kR²"
    for name, work in (("arc", arc), ("direct", direct)):
        error = abs(Fraction(work) - exact)
        assert error <= Fraction(1e-12 * scale), f"{name}: {float(error) / scale:.3g} kR²"


@_settings(300)
@given(_SPRING_CASE, st.sets(st.sampled_from(["drag_law", "gravity"])))
def test_spring_work_readout_is_the_same_on_both_paths(case, others):
    """The readout W is bitwise the same on the chord and the arc, with the verdict "conservative", and
    within 4ε·k·max(1, |x_c|)² of the exact U(A) − U(B) (any anchor, rest length, sagitta, other effects)."""
    effects = ("spring_rest_length", *others)
    out = WORK.evaluate(
        {**case, "force": float(SPRING), "path": np.array([float(DIRECT), float(ARC)])},
        wanted=["W", "verdict"],
        effects=effects,
    )
    assert out["W"][0] == out["W"][1] and np.all(out["verdict"] == 0)
    error = abs(Fraction(float(out["W"][0])) - _exact_potential_drop(case["k"], case["x_c"], case["ell0"]))
    assert error <= Fraction(4 * EPS * case["k"] * max(1.0, abs(case["x_c"])) ** 2)


# ================================================================================================
# I1 impulse: J does not depend on how the pulse is shaped when docs/physics/ says so
# ================================================================================================

_PULSE = st.fixed_dictionaries(
    {
        "F_pk": st.one_of(st.just(0.0), _log_uniform(-6.0, 6.0)),
        "tau": _log_uniform(-6.0, 6.0),
        "m": _log_uniform(-6.0, 6.0),
    }
)


@_settings(200)
@given(_PULSE)
def test_impulse_is_the_same_for_the_triangle_and_the_hann_pulse(pulse):
    """J = F_pk τ/2 (the model) equals ∫F dt of the triangle and of the Hann pulse F_pk sin²(πt/τ) by
    adaptive quadrature within 1e−12 rel (docs/physics/impulse.md: the shape-independence demo), at any
    F_pk, τ, m far beyond the sliders; Δp = J bitwise and Δv = J/m."""
    F_pk, tau = pulse["F_pk"], pulse["tau"]
    out = {k: float(v) for k, v in Impulse().evaluate(pulse, wanted=["J", "dp", "dv"]).items()}
    J = out["J"]
    triangle, _ = quad(lambda t: float(force(t, F_pk, tau)), 0.0, tau, points=[tau / 2], epsabs=0.0, epsrel=1e-13)
    hann, _ = quad(lambda t: F_pk * math.sin(math.pi * t / tau) ** 2, 0.0, tau, epsabs=0.0, epsrel=1e-13)
    for name, value in (("triangle", triangle), ("Hann", hann)):
        assert abs(value - J) <= 1e-12 * abs(J), f"{name}: rel {abs(value - J) / J:.3g}"
    assert out["dp"] == J and abs(out["dv"] - J / pulse["m"]) <= EPS * abs(J / pulse["m"])


# ================================================================================================
# I4 lever: mirroring the bar negates the net torque exactly
# ================================================================================================

LEVER = MODELS["lever"]()
_LEVER_CASE = st.fixed_dictionaries(
    {
        "m_L": _log_uniform(-100.0, 100.0),
        "m_R": _log_uniform(-100.0, 100.0),
        "x_p": st.one_of(st.sampled_from([1.0, 4 / 3, 2.0]), st.floats(1.0, 2.0)),  # ℓ − x_p is then exact
        "balance_tolerance": st.floats(0.0, 0.5),
        "m_b": st.one_of(st.just(0.0), _log_uniform(-100.0, 100.0)),
    }
)
_MIRRORED_STATE = {0: 0, TIPS_LEFT: TIPS_RIGHT, TIPS_RIGHT: TIPS_LEFT}


@_settings(500)
@given(_LEVER_CASE)
def test_lever_mirror_negates_the_net_torque_exactly(case):
    """Swapping the masses and putting the pivot at ℓ − x_p gives −net τ exactly (with and without the
    bar's mass), τL and τR swap bitwise, the state mirrors, x* → ℓ − x* and MA → 1/MA (to rounding).

    x_p is drawn in [ℓ/2, ℓ], where ℓ − x_p is exact (Sterbenz), so the mirrored pivot is exactly the
    mirror image and both pivots are exact floats; each call covers a pivot in [0, ℓ/2] too.
    """
    mirror = {**case, "m_L": case["m_R"], "m_R": case["m_L"], "x_p": 2.0 - case["x_p"]}
    wanted = ["tau_L", "tau_R", "tau_net", "state", "x_star", "MA", "tau_net_bar", "state_bar"]
    a = {k: float(v) for k, v in LEVER.evaluate(case, wanted=wanted, effects=("bar_mass",)).items()}
    b = {k: float(v) for k, v in LEVER.evaluate(mirror, wanted=wanted, effects=("bar_mass",)).items()}
    assert b["tau_net"] == -a["tau_net"] and b["tau_net_bar"] == -a["tau_net_bar"]
    assert b["tau_L"] == a["tau_R"] and b["tau_R"] == a["tau_L"]
    assert b["state"] == _MIRRORED_STATE[int(a["state"])] and b["state_bar"] == _MIRRORED_STATE[int(a["state_bar"])]
    assert abs(b["x_star"] - (2.0 - a["x_star"])) <= 4 * EPS * 2.0
    if math.isinf(a["MA"]) or math.isinf(b["MA"]):
        assert {a["MA"], b["MA"]} == {0.0, math.inf}
    else:
        assert abs(a["MA"] * b["MA"] - 1.0) <= 4 * EPS


def _arms(x):
    return x["m_L"] * x["x_p"] + x["m_R"] * (2.0 - x["x_p"])


def _stop_time_reference(x, off):
    """√(2Iθs/|τ|): uniform angular acceleration, the θs → 0 limit; ∞ where the engine sees a balance
    (|m_L x_p − m_R(ℓ − x_p)| within the 4ε roundoff of its terms, lever/mechanics.py `moving_torque`)."""
    per_g = x["m_L"] * x["x_p"] - x["m_R"] * (2.0 - x["x_p"])
    if abs(per_g) <= 4 * EPS * _arms(x):
        return math.inf
    inertia = x["m_L"] * x["x_p"] ** 2 + x["m_R"] * (2.0 - x["x_p"]) ** 2
    return math.sqrt(2 * inertia * math.radians(x["theta_s"]) / (G * abs(per_g)))


def _stop_speed_bound(d, x, ref):
    """ω at the stop, √(2|τ| sin θs/I) ≤ √(2|τ|θs/I): it vanishes with θs."""
    inertia = x["m_L"] * x["x_p"] ** 2 + x["m_R"] * (2.0 - x["x_p"]) ** 2
    torque = G * abs(x["m_L"] * x["x_p"] - x["m_R"] * (2.0 - x["x_p"]))
    return math.sqrt(2 * torque * math.radians(d) / inertia) * (1 + 1e-12)


def _tipping_series(degrees):
    """t_stop/√(2Iθs/|τ|) − 1 = θs²/60 + O(θs⁴): the departure from uniform acceleration (≤ θs²)."""
    return math.radians(degrees) ** 2


def _tipping_cancellation(degrees):
    """The closed form K(½) − F(arccos√sin θ | ½) cancels as θ → 0: ~ε·K(½)/√θ relative, plus 8ε
    (test_lever_stop_time_stays_accurate_as_the_stop_angle_vanishes: the cancellation-free form keeps 8ε)."""
    return 8 * EPS + 4 * EPS * math.sqrt(2) * 1.8540746773013719 / (2 * math.sqrt(math.radians(degrees)))


@example(degrees=1e-12, case={"m_L": 1.0, "m_R": 3.0, "x_p": 1.0})
@_settings(100)
@given(
    degrees=_log_uniform(-12.0, -3.0),
    case=st.fixed_dictionaries(
        {"m_L": _log_uniform(-3.0, 3.0), "m_R": _log_uniform(-3.0, 3.0), "x_p": st.floats(0.0, 2.0)}
    ),
)
def test_lever_stop_time_stays_accurate_as_the_stop_angle_vanishes(degrees, case):
    """t_stop = √(2Iθs/|τ|)(1 + θs²/60) to 16ε as θs → 0 (the series of ∫₀^θ dφ/√sin φ = 2√θ + θ^{5/2}/30)."""
    out = LEVER.evaluate({**case, "theta_s": degrees}, wanted=["t_stop"], effects=("rotation_dynamics",))
    reference = _stop_time_reference({**case, "theta_s": degrees}, None) * (1 + math.radians(degrees) ** 2 / 60)
    if math.isinf(reference):
        assert math.isinf(float(out["t_stop"]))
    else:
        rel = abs(float(out["t_stop"]) / reference - 1)
        assert rel <= 16 * EPS, f"rel {rel:.3g}"


# ================================================================================================
# docs/physics/README.md, effects, rule 2: the vanishing limit of every effect of every model
# ================================================================================================


@dataclass(frozen=True)
class Compare:
    """An output with the effect on, held to its counterpart without the effect.

    `off` names an output of the evaluation without the effect, or gives the reference value from
    (inputs, outputs without the effect). `bound(δ, inputs, reference)` is the largest allowed
    |on − reference|; 0 demands equality and inf skips the comparison at that δ.
    """

    on: str
    off: str | Callable[[dict, dict], object]
    bound: Callable[[float, dict, np.ndarray], object]


@dataclass(frozen=True)
class Limit:
    """The vanishing limit of one parameter of one effect: the parameter → its neutral value."""

    model: str
    effect: str
    param: str  # the parameter that is taken to its neutral value ("" when the effect has none)
    label: str  # how the limit reads in the test id, e.g. "ell0->0"
    inputs: st.SearchStrategy | None = None  # the other parameters
    delta: st.SearchStrategy | None = None  # the departure δ from neutral; None: the neutral value itself
    value: Callable[[float, dict], float] = lambda delta, x: delta  # the parameter at δ
    compare: tuple[Compare, ...] = ()
    companions: tuple[str, ...] = ()  # effects on in both evaluations: any subset, or all of them
    optional: bool = True  # False: every companion is always on
    strict: bool = True  # every other output without an effect must be bitwise unchanged
    common: Callable | None = None  # bound for every scalar output present with and without the effect
    common_skip: tuple[str, ...] = ()  # ... except outputs ending in these (a readout that → ∞ in the limit)
    examples: int = 100
    skip: str = ""  # why this parameter has no vanishing limit to test

    @property
    def id(self) -> str:
        head = f"{self.model}.{self.effect}" + (f".{self.label}" if self.label else "")
        return f"{head}-SKIPPED({self.skip})" if self.skip else head


def _rel(factor: float, roundoff: float = 8 * EPS):
    """|Δ| ≤ factor·|δ|·|reference|, plus `roundoff`·|reference| once δ ≠ 0 (equality at δ = 0)."""
    return lambda d, x, ref: (factor * abs(d) + (roundoff if d else 0.0)) * np.abs(ref)


def _equal_at_neutral(d, x, ref):
    """Equal at δ = 0, not compared elsewhere (a discrete output that may flip for δ > 0)."""
    return 0.0 if d == 0 else np.inf


# --- I3 work ---------------------------------------------------------------------------------------

_WORK_INPUTS = st.fixed_dictionaries(
    {
        "force": st.sampled_from([0.0, 1.0]),
        "path": st.sampled_from([0.0, 1.0]),
        "k": _log_uniform(-3.0, 3.0),
        "x_c": st.floats(-5.0, 5.0),
        "h": st.floats(0.0, 4.0),
        "s": st.floats(0.0, 10.0),
        "b": st.floats(0.0, 10.0),
        "ell0": st.floats(0.0, 3.0),
        "drag_law": st.sampled_from([0.0, 1.0]),
        "c_q": st.floats(0.0, 10.0),
        "m_g": st.floats(0.0, 10.0),
    }
)


def _rest_length_work_bound(d, x, ref):
    """W(ℓ0) − W(0) = −2k·clip(x_c)·ℓ0 exactly: |Δ| ≤ 2kδ, plus the roundoff of the two closed forms."""
    return 2.0 * x["k"] * d * (1 + 1e-12) + (8 * EPS * x["k"] * max(1.0, abs(x["x_c"])) ** 2 if d else 0.0)


def _spring_field_bound(scale):
    """Field-arrow vertices move by at most `scale(δ, x)` metres (0 at δ = 0); only for the spring's field.

    A change η in F/k moves each drawn vector by ≤ 0.108η (a radial clip, then the 0.108 m/m scale) and
    each vertex by ≤ 1.5× that (the tip; the corners' half-width map is 0.3-Lipschitz): 0.162η.
    """
    return lambda d, x, ref: np.inf if x["force"] != SPRING else scale(d, x) + (1e-13 if d else 0.0)


_WORK_LIMITS = [
    Limit(
        "work",
        "spring_rest_length",
        "ell0",
        "ell0->0",
        _WORK_INPUTS,
        _small(-6.0),
        compare=(
            Compare("W", "W", _rest_length_work_bound),
            Compare("dU", "dU", _rest_length_work_bound),
            Compare("field_x", "field_x", _spring_field_bound(lambda d, x: 0.2 * d)),
            Compare("field_y", "field_y", _spring_field_bound(lambda d, x: 0.2 * d)),
        ),
        companions=("drag_law", "gravity"),
    ),
    Limit(
        "work",
        "drag_law",
        "drag_law",
        "drag_law=linear",
        _WORK_INPUTS,
        None,
        value=lambda d, x: 0.0,
        companions=("spring_rest_length", "gravity"),
    ),
    Limit(
        "work",
        "drag_law",
        "c_q",
        "c_q",
        skip="c_q acts only under the quadratic law; the effect vanishes "
        "by the law choice (drag_law=linear, tested), while c_q->0 removes the drag altogether",
    ),
    # Gravity does no net work between A and B (same height): the readouts must not move at all.
    Limit(
        "work",
        "gravity",
        "m_g",
        "m_g->0",
        _WORK_INPUTS,
        _small(-6.0),
        # Under drag alone there is no potential at all (U(A) − U(B) shows "—"); gravity, being
        # conservative, brings one (its drop A → B is 0), so only the spring's dU must stay equal.
        compare=(
            Compare("dU", "dU", lambda d, x, ref: np.inf if x["force"] != SPRING else 0.0),
            Compare("field_x", "field_x", _spring_field_bound(lambda d, x: 0.2 * d * G / x["k"])),
            Compare("field_y", "field_y", _spring_field_bound(lambda d, x: 0.2 * d * G / x["k"])),
        ),
        companions=("spring_rest_length", "drag_law"),
    ),
]

# --- I4 lever --------------------------------------------------------------------------------------

_LEVER_INPUTS = st.fixed_dictionaries(
    {
        "x_p": st.floats(0.0, 2.0),
        "m_L": _log_uniform(-6.0, 6.0),
        "m_R": _log_uniform(-6.0, 6.0),
        "balance_tolerance": st.floats(0.0, 0.5),
        "m_b": st.floats(0.0, 10.0),
        "theta_s": st.floats(1.0, 90.0),
    }
)


_TILT = ["y_left", "y_right"] + [
    f"{block}_block_{side}{edge}" for block in ("left", "right") for edge in "01" for side in ("bottom", "top")
]
_LEVER_LIMITS = [
    Limit(
        "lever",
        "bar_mass",
        "m_b",
        "m_b->0",
        _LEVER_INPUTS,
        _small(-3.0),
        compare=(
            Compare("tau_net_bar", "tau_net", lambda d, x, ref: G * d + (16 * EPS * G * (_arms(x) + d) if d else 0.0)),
            Compare("tau_b", lambda x, off: 0.0, lambda d, x, ref: G * d),
            Compare("x_star_bar", "x_star", lambda d, x, ref: d / (x["m_L"] + x["m_R"]) + (8 * EPS if d else 0.0)),
            Compare(
                "marker_x0_bar", "marker_x0", lambda d, x, ref: d / (x["m_L"] + x["m_R"]) + (8 * EPS if d else 0.0)
            ),
            Compare(
                "marker_x1_bar", "marker_x1", lambda d, x, ref: d / (x["m_L"] + x["m_R"]) + (8 * EPS if d else 0.0)
            ),
            Compare("state_bar", "state", _equal_at_neutral),
            *(Compare(f"{name}_bar", name, _equal_at_neutral) for name in _TILT),
        ),
        companions=("rotation_dynamics",),
    ),
    # The rotation outputs have no counterpart without the effect; θs → 0 is the uniform-acceleration limit.
    Limit(
        "lever",
        "rotation_dynamics",
        "theta_s",
        "theta_s->0",
        _LEVER_INPUTS,
        _small(-2.0, lo_exp=-12.0, zero=False),
        compare=(
            Compare(
                "t_stop", _stop_time_reference, lambda d, x, ref: (_tipping_series(d) + _tipping_cancellation(d)) * ref
            ),
            Compare("omega_stop", lambda x, off: 0.0, _stop_speed_bound),
        ),
    ),
]


# --- I1 impulse ------------------------------------------------------------------------------------

_IMPULSE_INPUTS = st.fixed_dictionaries(
    {
        "F_pk": st.one_of(st.just(0.0), _log_uniform(-3.0, 3.0)),
        "tau": _log_uniform(-3.0, 1.0),
        "m": _log_uniform(-2.0, 2.0),
        "shape": st.sampled_from([0.0, 1.0, 2.0, 3.0]),
        "v0": st.floats(-10.0, 10.0),
        "m_hit": _log_uniform(-2.0, 2.0),
        "v_rel": st.floats(0.0, 10.0),
        "k_c": _log_uniform(-1.0, 2.0),
        "c_d": st.floats(0.0, 100.0),
    }
)


def _reduced_mass(x, first: str, second: str) -> float:
    return x[first] * x[second] / (x[first] + x[second])


def _damping_loss(d, x, first: str, second: str) -> float:
    """1 − e ≤ πζ/√(1 − ζ²) for the contact damping c_d = δ (ζ = δ/2√(k_c μ), k_c in kN/m)."""
    zeta = d / (2.0 * math.sqrt(1e3 * x["k_c"] * _reduced_mass(x, first, second)))
    return math.pi * zeta / math.sqrt((1 - zeta) * (1 + zeta)) if zeta < 1 else 1.0


_IMPULSE_LIMITS = [
    # The triangle is the base model's pulse: choosing it under `shape` changes no bit of any output.
    Limit(
        "impulse",
        "shape",
        "shape",
        "shape=triangle",
        _IMPULSE_INPUTS,
        None,
        value=lambda d, x: 0.0,
        companions=("initial_velocity",),
    ),
    # v0 → 0: the velocity curve and the velocity after the pulse become those gained from rest, J/m.
    Limit(
        "impulse",
        "initial_velocity",
        "v0",
        "v0->0",
        _IMPULSE_INPUTS,
        _small(1.0, signed=True),
        compare=(
            Compare(
                "v_curve", "v_curve", lambda d, x, ref: abs(d) * (1 + 1e-15) + (4 * EPS * np.abs(ref) if d else 0.0)
            ),
            Compare("v_after", "dv", lambda d, x, ref: abs(d) * (1 + 1e-15) + (4 * EPS * abs(ref) if d else 0.0)),
        ),
        companions=("shape",),
    ),
    # The contact's force: damping → 0 makes it elastic, J → 2μΔ; the approach speed → 0 makes it vanish.
    Limit(
        "impulse",
        "contact_from_collision",
        "c_d",
        "c_d->0(J->2muDelta)",
        _IMPULSE_INPUTS,
        _small(-3.0),
        compare=(
            Compare(
                "J",
                lambda x, off: 2.0 * _reduced_mass(x, "m_hit", "m") * x["v_rel"],
                lambda d, x, ref: ref * (_damping_loss(d, x, "m_hit", "m") / 2 + 4 * EPS),
            ),
        ),
        companions=("initial_velocity",),
        strict=False,
    ),
    Limit(
        "impulse",
        "contact_from_collision",
        "v_rel",
        "v_rel->0",
        _IMPULSE_INPUTS,
        _small(-3.0),
        compare=(
            Compare(
                "J", lambda x, off: 0.0, lambda d, x, ref: 2.0 * _reduced_mass(x, "m_hit", "m") * d * (1 + 4 * EPS)
            ),
            Compare(
                "F_max",
                lambda x, off: 0.0,
                lambda d, x, ref: (
                    d * (math.sqrt(1e3 * x["k_c"] * _reduced_mass(x, "m_hit", "m")) + x["c_d"]) * (1 + 1e-12)
                ),
            ),
        ),
        companions=("initial_velocity",),
        strict=False,
    ),
    Limit(
        "impulse",
        "contact_from_collision",
        "k_c",
        "k_c",
        skip="the stiffness sets the contact's duration and height, not "
        "its strength: J depends on k_c only through e, and the contact vanishes with c_d->0 (elastic) or v_rel->0",
    ),
    Limit(
        "impulse",
        "contact_from_collision",
        "m_hit",
        "m_hit",
        skip="the striking mass describes the collision that makes "
        "the force (no neutral value); the contact's limits are c_d->0 and v_rel->0",
    ),
]

# --- I2 collision ---------------------------------------------------------------------------------

_CONTACT_INPUTS = st.fixed_dictionaries(
    {
        "m1": _log_uniform(-2.0, 2.0),
        "m2": _log_uniform(-2.0, 2.0),
        "v1i": st.floats(-10.0, 10.0),
        "v2i": st.floats(-10.0, 10.0),
        "e": st.just(1.0),
        "k_c": _log_uniform(-1.0, 2.0),
        "c_d": st.floats(0.0, 100.0),
    }
)


def _contact_bound(weight: str):
    """|Δv| ≤ w Δ (1 − e) against the elastic law, plus the roundoff of the two evaluations."""

    def bound(d, x, ref):
        total = x["m1"] + x["m2"]
        approach = max(x["v1i"] - x["v2i"], 0.0)
        return x[weight] / total * approach * _damping_loss(d, x, "m1", "m2") + 8 * EPS * max(
            abs(x["v1i"]), abs(x["v2i"])
        )

    return bound


def _contact_energy_bound(d, x, ref):
    """K lost ≤ μΔ²(1 − e), plus roundoff of the energies."""
    approach = max(x["v1i"] - x["v2i"], 0.0)
    before = 0.5 * x["m1"] * x["v1i"] ** 2 + 0.5 * x["m2"] * x["v2i"] ** 2
    return _reduced_mass(x, "m1", "m2") * approach**2 * _damping_loss(d, x, "m1", "m2") + 16 * EPS * before


_COLLISION_LIMITS = [
    # docs/physics/README.md: ζ → 0 ⇒ e → 1, and the contact's velocities and ledger become the elastic law's.
    Limit(
        "collision",
        "contact_spring_dashpot",
        "c_d",
        "c_d->0(zeta->0)",
        _CONTACT_INPUTS,
        _small(-3.0),
        compare=(
            Compare("e_contact", lambda x, off: 1.0, lambda d, x, ref: _damping_loss(d, x, "m1", "m2") + 2 * EPS),
            Compare("v1f", "v1f", _contact_bound("m2")),
            Compare("v2f", "v2f", _contact_bound("m1")),
            Compare(
                "p_after", "p_after", lambda d, x, ref: 16 * EPS * (x["m1"] * abs(x["v1i"]) + x["m2"] * abs(x["v2i"]))
            ),
            Compare("K_after", "K_after", _contact_energy_bound),
            Compare("K_lost", "K_lost", _contact_energy_bound),
            Compare(
                "K_kept_pct",
                "K_kept_pct",
                lambda d, x, ref: (
                    100
                    * _contact_energy_bound(d, x, ref)
                    / max(0.5 * x["m1"] * x["v1i"] ** 2 + 0.5 * x["m2"] * x["v2i"] ** 2, 1e-300)
                    + 1e-12
                ),
            ),
        ),
    ),
    Limit(
        "collision",
        "contact_spring_dashpot",
        "k_c",
        "k_c",
        skip="the stiffness alone sets the contact's duration, not "
        "its outcome: at c_d = 0 every k_c gives the elastic law bitwise "
        "(test_collision_model); the contact vanishes with c_d->0",
    ),
]

# --- I5 chain --------------------------------------------------------------------------------------

_CHAIN_INPUTS = st.fixed_dictionaries(
    {
        "N": st.integers(1, 256).map(float),
        "sigma": st.floats(-2.5, math.log10(0.05)).map(lambda u: min(10.0**u, 0.05)),
        "t": st.floats(0.0, 100.0),
        "launch": st.sampled_from([0.0, 1.0]),
        "ends": st.sampled_from([0.0, 1.0, 2.0]),
        "gamma": st.floats(0.0, 10.0),
        "omega0": st.floats(0.0, 50.0),
    }
)


def _lowest_bare_mode(x) -> float:
    """ω1 of the bare fixed-end chain, 2(c/a) sin(π/2(N+1)) (L = c = 1): the discrete Poincaré constant."""
    n = round(x["N"])
    return 2.0 * (n + 1) * math.sin(math.pi / (2 * (n + 1)))


def _damping_shift(d, x, ref, off=None):
    """max_j|u_γ − u_0| ≤ γt√(2E0) (A = 1): the difference w obeys mẅ + κLw = −mγu̇_γ, whose forcing has
    ‖F‖/√m ≤ γ√(2E0), so √(2E_w) ≤ γt√(2E0), and |w_j| ≤ √(2E_w L/μc²) between fixed walls."""
    return d * x["t"] * math.sqrt(2 * x["_E"]) * (1 + 1e-9) + (1e-13 * np.nanmax(np.abs(ref)) if d else 0.0)


def _onsite_energy_bound(d, x, ref):
    """The on-site spring adds ½mω0²Σu0² ≤ (ω0/ω1)² E0 to the energy at release."""
    return (d / _lowest_bare_mode(x)) ** 2 * ref + (4 * EPS * ref if d else 0.0)


def _spring_shift(d, x, ref):
    """max_j|u_ω0 − u_0| ≤ ω0² t √(2E)/ω1: the forcing −mω0²u has ‖F‖/√m ≤ ω0²√(2E)/ω1 (Poincaré)."""
    return d**2 * x["t"] * math.sqrt(2 * x["_E"]) / _lowest_bare_mode(x) * (1 + 1e-9) + (
        1e-13 * np.nanmax(np.abs(ref)) if d else 0.0
    )


_CHAIN_LIMITS = [
    Limit(
        "chain",
        "boundary",
        "ends",
        "ends=fixed",
        _CHAIN_INPUTS,
        None,
        value=lambda d, x: 0.0,
        companions=("onsite_damping", "onsite_spring"),
        examples=60,
    ),
    Limit(
        "chain",
        "onsite_damping",
        "gamma",
        "gamma->0",
        _CHAIN_INPUTS,
        _small(-3.0),
        compare=(
            # E(t) with damping lies in [E0 e^{−2γt}, E0] (dE/dt = −mγΣu̇² ≥ −2γE).
            Compare("E_now", "E_chain", lambda d, x, ref: ref * (-math.expm1(-2 * d * x["t"]) + 1e-12)),
            Compare("u_dots", "u_dots", _damping_shift),
            Compare("dev", "dev", lambda d, x, ref: _damping_shift(d, x, ref) + (1e-13 if d else 0.0)),
        ),
        companions=("onsite_spring",),
        examples=60,
    ),
    Limit(
        "chain",
        "onsite_spring",
        "omega0",
        "omega0->0",
        _CHAIN_INPUTS,
        _small(-2.0),
        compare=(
            Compare("u_dots", "u_dots", _spring_shift),
            Compare("dev", "dev", lambda d, x, ref: _spring_shift(d, x, ref) + (1e-13 if d else 0.0)),
            # ½mω0²Σu0² ≤ (ω0/ω1)² E0.
            Compare("E_chain", "E_chain", _onsite_energy_bound),
            Compare("E_chain_mJ", "E_chain_mJ", _onsite_energy_bound),
            # hypot(ω, ω0) − ω ≤ ω0²/2ω.
            Compare("omega_max", "omega_max", lambda d, x, ref: d**2 / (2 * ref) + (2 * EPS * ref if d else 0.0)),
            Compare(
                "log_omega",
                "log_omega",
                lambda d, x, ref: (d / _lowest_bare_mode(x)) ** 2 / (2 * math.log(10)) + (1e-15 if d else 0.0),
            ),
        ),
        companions=("onsite_damping",),
        examples=60,
    ),
]

# --- K1 ossicles -----------------------------------------------------------------------------------

_OSSICLE_INPUTS = st.fixed_dictionaries(
    {
        "A_TM": _log_uniform(-2.0, 4.0),
        "A_FP": _log_uniform(-2.0, 3.0),
        "ell": _log_uniform(-1.0, 1.0),
        "SPL": st.floats(-20.0, 200.0),
        "load": st.sampled_from([0.0, 1.0]),
    }
)
_DB = lambda d, x, ref: 9.0 * abs(d) + (1e-13 * (1.0 + np.abs(ref)) if d else 0.0)  # noqa: E731  20 log10(1 + δ) ≤ 8.7|δ|
_GAIN_COMPARE = (
    Compare("G", "G", _rel(3.0)),
    Compare("G_dB", "G_dB", _DB),
    Compare("L_OW", "L_OW", _DB),  # SPL + G_dB: moves with the gain, within the same decibel bound
    Compare("p_OW", "p_OW", _rel(3.0)),
    Compare("Z_ref", "Z_ref", _rel(3.0)),
    Compare("T1", "T1", _rel(3.0)),
    Compare("T1_dB", "T1_dB", _DB),
)
_OSSICLE_LIMITS = [
    Limit(
        "ossicles",
        "lever",
        "ell",
        "ell->1",
        _OSSICLE_INPUTS,
        _small(-6.0, signed=True),
        value=lambda d, x: 1.0 + d,
        compare=(
            *_GAIN_COMPARE,
            *(
                Compare(n, n, lambda d, x, ref: abs(d) / 3 + (2 * EPS if d else 0.0))
                for n in ("pivot", "fulcrum_x0", "fulcrum_x1")
            ),
        ),
        companions=("area_ratio", "load_model"),
    ),
    Limit(
        "ossicles",
        "area_ratio",
        "A_TM",
        "A_TM->A_FP",
        _OSSICLE_INPUTS,
        _small(-6.0, signed=True),
        value=lambda d, x: x["A_FP"] * (1.0 + d),
        compare=(*_GAIN_COMPARE, Compare("A_r", "A_r", _rel(3.0)), Compare("ell_match", "ell_match", _rel(3.0))),
        companions=("lever", "load_model"),
    ),
    Limit(
        "ossicles",
        "load_model",
        "load",
        "load=water",
        _OSSICLE_INPUTS,
        None,
        value=lambda d, x: 0.0,
        companions=("lever", "area_ratio"),
    ),
]

# --- K2 kinetic ------------------------------------------------------------------------------------

_KINETIC_INPUTS = st.fixed_dictionaries(
    {
        "N": st.sampled_from([1.0, 2.0, 10.0, 30.0, 100.0, 300.0, 1000.0]),
        "T": _log_uniform(0.0, 4.0),
        "species": st.integers(0, 5).map(float),
        "t_w": st.one_of(st.sampled_from([1.0, 100.0]), st.floats(0.01, 300.0)),
        "sampling": st.sampled_from([0.0, 1.0]),
        "dim": st.sampled_from([0.0, 1.0, 2.0]),
        "tau_c": st.floats(0.0, 5.0),
        "alpha": st.floats(0.0, 1.0),
    }
)
_KINETIC_LIMITS = [
    Limit(
        "kinetic",
        "dimension",
        "dim",
        "dim=3D",
        _KINETIC_INPUTS,
        None,
        value=lambda d, x: 2.0,
        compare=(
            Compare("v_rms_d", "v_rms", lambda d, x, ref: 0.0),
            Compare("E_k", lambda x, off: 1.5 * 1.380649e-23 * x["T"] * 1e21, lambda d, x, ref: 4 * EPS * ref),
        ),
        examples=40,
    ),
    # docs/physics/ states no tolerance for it; the pulses straddling a bin edge move at most their impulse.
    Limit(
        "kinetic",
        "contact_duration",
        "tau_c",
        "tau_c->0",
        _KINETIC_INPUTS,
        _small(-9.0),
        compare=(
            Compare("train_soft", "train", lambda d, x, ref: 1e-6 * np.max(np.abs(ref)) if d else 0.0),
            Compare("running_soft", "running", lambda d, x, ref: 1e-6 * np.max(np.abs(ref)) if d else 0.0),
        ),
        companions=("dimension",),
        examples=40,
    ),
    Limit(
        "kinetic",
        "wall_law",
        "alpha",
        "alpha->0",
        _KINETIC_INPUTS,
        _small(-12.0),
        compare=(
            Compare("ratio_wall", "ratio", _rel(0.0, 1e-12)),
            Compare("hits_wall", "hits", lambda d, x, ref: 0.0),
            Compare("train_wall", "train", lambda d, x, ref: 1e-12 * np.max(np.abs(ref)) if d else 0.0),
            Compare("running_wall", "running", lambda d, x, ref: 1e-12 * np.max(np.abs(ref)) if d else 0.0),
        ),
        companions=("dimension",),
        examples=40,
    ),
]

# --- K5 acoustic energy ----------------------------------------------------------------------------

_ACOUSTIC_INPUTS = st.fixed_dictionaries(
    {
        "SPL": st.floats(-50.0, 200.0),
        "f": _log_uniform(0.0, 6.0),
        "R_r": st.floats(0.0, 1.0),
        "wt": st.floats(-720.0, 720.0),
        "x_probe": st.floats(-3.0, 3.0),
        "alpha": st.floats(0.0, 100.0),
        "d": st.floats(0.0, 1e4),
        "r": _log_uniform(-3.0, 4.0),
    }
)
_TEN_LOG10_E = 10.0 / math.log(10.0)


def _share_bound(d, x, ref):
    """e_k/(e_k + e_p) moves by ≈ 100 δ|cos b/cos a| %; not compared within 1e−3 of a node of the
    travelling wave, where it is undefined at δ = 0 ("—") and 50 % for any δ > 0."""
    if d == 0:
        return 0.0
    near = abs(cosdg(360.0 * x["x_probe"] - x["wt"]))
    return 200.0 * d / near + 1e-12 if near >= 1e-3 else np.inf


_CURVES = ("ek_x", "ep_x", "Ic_x", "ek_avg_x", "ep_avg_x", "dedt_x", "neg_dIdx_x")
_ACOUSTIC_LIMITS = [
    Limit(
        "acoustic_energy",
        "reflection",
        "R_r",
        "R_r->0",
        _ACOUSTIC_INPUTS,
        _small(-6.0),
        compare=(
            Compare("e_avg", "e_avg", lambda d, x, ref: (1.01 * d * d + (4 * EPS if d else 0)) * ref),
            Compare("I_avg", "I_avg", lambda d, x, ref: (1.01 * d * d + (4 * EPS if d else 0)) * ref),
            Compare("I_avg_n", "I_avg_n", lambda d, x, ref: (1.01 * d * d + (4 * EPS if d else 0)) * ref),
            Compare("transport", "transport", lambda d, x, ref: (2.02 * d * d + (4 * EPS if d else 0)) * ref),
            Compare("L_I", "L_I", lambda d, x, ref: _TEN_LOG10_E * 1.01 * d * d + (8 * EPS * abs(ref) if d else 0)),
            Compare("ek_share", "ek_share", _share_bound),
            *(Compare(n, n, lambda d, x, ref: 4 * d + 4 * d * d + (1e-14 if d else 0.0)) for n in _CURVES),
        ),
        companions=("absorption", "spherical_spreading"),
    ),
    Limit(
        "acoustic_energy",
        "absorption",
        "alpha",
        "alpha->0",
        _ACOUSTIC_INPUTS,
        _small(-9.0),
        compare=(
            Compare("I_abs", "I_avg", lambda d, x, ref: (2.02 * d * x["d"] + (4 * EPS if d else 0)) * ref),
            Compare(
                "L_abs", "L_I", lambda d, x, ref: _TEN_LOG10_E * 2.02 * d * x["d"] + (8 * EPS * abs(ref) if d else 0)
            ),
            Compare("absorbed", lambda x, off: 0.0, lambda d, x, ref: 202.0 * d * x["d"]),
        ),
        companions=("spherical_spreading",),
    ),
    Limit(
        "acoustic_energy",
        "absorption",
        "d",
        "d->0",
        _ACOUSTIC_INPUTS,
        _small(-6.0),
        compare=(
            Compare("I_abs", "I_avg", lambda d, x, ref: (2.02 * d * x["alpha"] + (4 * EPS if d else 0)) * ref),
            Compare(
                "L_abs",
                "L_I",
                lambda d, x, ref: _TEN_LOG10_E * 2.02 * d * x["alpha"] + (8 * EPS * abs(ref) if d else 0),
            ),
            Compare("absorbed", lambda x, off: 0.0, lambda d, x, ref: 202.0 * d * x["alpha"]),
        ),
        companions=("spherical_spreading",),
    ),
    # The SPL slider gives the level at r0 = 1 m: there the spherical wave carries the plane wave's intensity.
    Limit(
        "acoustic_energy",
        "spherical_spreading",
        "r",
        "r->r0",
        _ACOUSTIC_INPUTS,
        _small(-6.0, signed=True),
        value=lambda d, x: 1.0 + d,
        compare=(
            Compare("I_r", "I_avg", _rel(3.0)),
            Compare("L_I_r", "L_I", lambda d, x, ref: 9.0 * abs(d) + (8 * EPS * abs(ref) if d else 0)),
        ),
        companions=("absorption",),
    ),
    # Far from the source the near-field terms vanish as 1/(kr)²: e_k = e_p and ⟨I⟩ = c⟨e⟩, the plane wave.
    Limit(
        "acoustic_energy",
        "spherical_spreading",
        "r",
        "1/r->0",
        _ACOUSTIC_INPUTS,
        _small(-3.0, lo_exp=-100.0, zero=False),
        value=lambda d, x: 1.0 / d,
        compare=(
            Compare(
                "ek_ep_r",
                lambda x, off: 1.0,
                lambda d, x, ref: 1.01 / (2 * math.pi * x["f"] / C_AIR / d) ** 2 + 4 * EPS,
            ),
            Compare(
                "transport_r", "transport", lambda d, x, ref: 0.51 / (2 * math.pi * x["f"] / C_AIR / d) ** 2 + 4 * EPS
            ),
        ),
        companions=("absorption",),
    ),
]

# --- K4 bubble ---------------------------------------------------------------------------------------
# The dynamic readouts belong to one pressure history (step, drive or ramp: one per scene) and carry its
# prefix. A compressibility or liquid term is compared readout by readout with the same history on; a
# history itself is compared with the bubble left at rest (R ≡ R0), which is what the model without it is.

_HISTORY_PREFIX = getattr(bubble_module, "PREFIX", {"step": "collapse", "drive": "driven", "ramp": "ramp"})
_B_EFFECTS = ("gas", "vdw_hard_core", "surface_tension", "viscosity", "drive", "keller_miksis")
_C_EFFECTS = ("gas", "vapour", "surface_tension", "viscosity", "ramp")
_A_EFFECTS = ("vapour", "step")
# A driven bubble that stays mild (no violent collapse), where the reduced models are well conditioned.
_MILD_BUBBLE = st.fixed_dictionaries(
    {
        "R0": _log_uniform(math.log10(3.0), math.log10(20.0)),
        "p_a": st.floats(0.2, 0.9),
        "f": st.floats(20.0, 80.0),
    }
)
_NUCLEUS = st.fixed_dictionaries({"R0": _log_uniform(0.0, 1.0), "kappa": st.just(1.0), "depth": st.floats(0.5, 0.95)})
_CAVITY = st.fixed_dictionaries({"R0": _log_uniform(2.0, 4.0), "p_inf": st.floats(0.25, 10.0)})


def _bubble_rel(d, x, ref):
    """docs/physics/README.md (K4): the reduced model is reproduced to 1e−6 rel (text readouts: the same phrase)."""
    return 1e-6 * np.abs(ref) + 1e-12


def _bubble(
    effect,
    param,
    label,
    delta,
    *,
    effects=_B_EFFECTS,
    inputs=_MILD_BUBBLE,
    value=lambda d, x: d,
    compare=(),
    skip_suffixes=(),
):
    others = tuple(e for e in effects if e != effect)
    return Limit(
        "bubble",
        effect,
        param,
        label,
        inputs,
        delta,
        value=value,
        compare=compare,
        companions=others,
        optional=False,
        strict=False,
        examples=6,
        common=None if compare else _bubble_rel,
        common_skip=skip_suffixes,
    )


def _at_rest(history, radii, speed="mach"):
    """The history's readouts against the bubble at rest: radii → 1 (1e−6 rel), wall speed → 0 (1e−6)."""
    prefix = _HISTORY_PREFIX[history]
    return (
        *(Compare(f"{prefix}_{name}", lambda x, off: 1.0, _bubble_rel) for name in radii),
        Compare(f"{prefix}_{speed}", lambda x, off: 0.0, lambda d, x, ref: 1e-6),
    )


def _step_neutral(d, x):
    """p∞ = (1 + δ) atm with the gas content at its equilibrium, p_gi = p0: the step vanishes at δ = 0.

    (Without surface tension: with it the equilibrium content 1 + 2σ/R0p0 lies above the domain's 1.)
    """
    x["gas_content"] = 1.0 / (1.0 + d)
    return 1.0 + d


def _ramp_neutral(d, x):
    """The depth with p_end = p0(1 + δ): the ramp is flat at δ = 0 (p_Blake from the model's closed form)."""
    p_blake = float(MODELS["bubble"]().evaluate({"R0": x["R0"]}, wanted=["p_blake"], effects=_C_EFFECTS)["p_blake"])
    return -d * P0 * 1e-3 / (P0 * 1e-3 - p_blake)


_BUBBLE_LIMITS = [
    Limit("bubble", "inertia", "", "no-parameter", skip="inertia is the base law, always on"),
    Limit(
        "bubble",
        "gas",
        "kappa",
        "kappa",
        skip="kappa is the polytropic exponent, not the gas amount; "
        "gas->0 is singular (the Rayleigh collapse), tested via K4 reference 1 (docs/physics/README.md)",
    ),
    _bubble("vdw_hard_core", "h_frac", "h_frac->0(driven)", _small(-4.0), skip_suffixes=("Rmin_h", "Rmin_h_why")),
    _bubble("vapour", "p_v", "p_v->0(driven)", _small(-6.0), effects=(*_B_EFFECTS, "vapour")),
    _bubble("vapour", "p_v", "p_v->0(ramp)", _small(-6.0), effects=_C_EFFECTS, inputs=_NUCLEUS),
    _bubble("surface_tension", "sigma", "sigma->0(driven)", _small(-10.0)),
    _bubble(
        "surface_tension",
        "sigma",
        "sigma->0(collapse)",
        _small(-10.0),
        effects=(*_A_EFFECTS, "surface_tension"),
        inputs=_CAVITY,
    ),
    _bubble("viscosity", "mu", "mu->0(driven)", _small(-10.0)),
    _bubble("viscosity", "mu", "mu->0(ramp)", _small(-10.0), effects=_C_EFFECTS, inputs=_NUCLEUS),
    _bubble("viscosity", "mu", "mu->0(collapse)", _small(-10.0), effects=(*_A_EFFECTS, "viscosity"), inputs=_CAVITY),
    _bubble(
        "thermal_damping",
        "D_g",
        "D_g->0(driven)",
        _small(-20.0),
        effects=("gas", "surface_tension", "viscosity", "thermal_damping", "drive"),
    ),
    # Neither compressibility term has a parameter of its own; c -> ∞ (base parameter) removes it (KM -> RP).
    _bubble(
        "keller_miksis",
        "c",
        "c->inf(base-param,driven)",
        _small(-12.0, lo_exp=-15.0, zero=False),
        value=lambda d, x: 1.0 / d,
    ),
    _bubble(
        "radiation",
        "c",
        "c->inf(base-param,driven)",
        _small(-12.0, lo_exp=-15.0, zero=False),
        value=lambda d, x: 1.0 / d,
        effects=("gas", "surface_tension", "viscosity", "drive", "radiation"),
    ),
    # The pressure histories: without one the bubble stays at rest at R0.
    _bubble("drive", "p_a", "p_a->0", _small(-12.0), compare=_at_rest("drive", ("R_max", "R_min", "R_max2", "R_min2"))),
    Limit(
        "bubble", "drive", "f", "f", skip="f is the drive's frequency, not its strength: the drive vanishes with p_a"
    ),
    _bubble(
        "step",
        "p_inf",
        "p_inf->p0",
        _small(-9.0),
        value=_step_neutral,
        effects=("gas", "step"),
        compare=_at_rest("step", ("R_min",)),
    ),
    Limit(
        "bubble",
        "step",
        "gas_content",
        "gas_content",
        skip="gas_content is tied to p_inf: the step's neutral "
        "point is p_inf = p0 with the gas at its equilibrium p_g0, tested as p_inf->p0",
    ),
    _bubble(
        "ramp",
        "depth",
        "p_end->p0",
        _small(-9.0, signed=True),
        effects=_C_EFFECTS,
        inputs=_NUCLEUS,
        value=_ramp_neutral,
        compare=(
            *_at_rest("ramp", ("R_max",))[:-1],
            Compare(f"{_HISTORY_PREFIX['ramp']}_growth", lambda x, off: 0.0, lambda d, x, ref: 0.0),
        ),
    ),
    Limit("bubble", "ramp", "t_ramp", "t_ramp", skip="a duration, not a strength: the ramp vanishes with p_end->p0"),
    Limit("bubble", "ramp", "t_hold", "t_hold", skip="a duration, not a strength: the ramp vanishes with p_end->p0"),
]

# --- effects without a parameter -------------------------------------------------------------------

_NO_PARAMETER = {
    ("collision", "restitution_law"): "it is the base law, the default",
    ("collision", "explosive"): "it widens e beyond 1; with 0 <= e <= 1 it is the base law",
    ("euler_slab", "convective_term"): "a readout of a term the linear balance leaves out",
    ("euler_slab", "gravity"): "a readout of a term the linear balance leaves out",
    ("euler_slab", "absorption"): "a readout of a term the linear balance leaves out",
}

LIMITS = [
    *_IMPULSE_LIMITS,
    *_COLLISION_LIMITS,
    *_WORK_LIMITS,
    *_LEVER_LIMITS,
    *_CHAIN_LIMITS,
    *_OSSICLE_LIMITS,
    *_KINETIC_LIMITS,
    *_ACOUSTIC_LIMITS,
    *_BUBBLE_LIMITS,
    *(Limit(m, e, "", "no-parameter", skip=f"no parameter: {why}") for (m, e), why in _NO_PARAMETER.items()),
    *(
        Limit(name, "(none)", "", "", skip="the model declares no effects")
        for name, model in MODELS.items()
        if not model.effects
    ),
]


def _evaluate_pair(limit: Limit, x: dict, delta: float, others) -> tuple[dict, dict, dict]:
    """The outputs with the effect on (its parameter at δ from neutral) and off, at the same inputs."""
    model = MODELS[limit.model]()
    x = dict(x)
    if limit.param:
        x[limit.param] = limit.value(delta, x)  # may also set a tied parameter (the step's gas content)
    names_on = [c.on for c in limit.compare]
    names_off = [c.off for c in limit.compare if isinstance(c.off, str)]
    if limit.strict:
        plain = [o.name for o in model.outputs if not o.effect]
        names_on, names_off = list(dict.fromkeys(names_on + plain)), list(dict.fromkeys(names_off + plain))
    if limit.common:
        shared = [
            o.name
            for o in model.outputs
            if not o.size
            and (not o.effect or o.effect in others)
            and not o.name.endswith(("_solver", *limit.common_skip))
        ]  # the method label may change
        names_on, names_off = list(dict.fromkeys(names_on + shared)), list(dict.fromkeys(names_off + shared))
    on = model.evaluate(x, wanted=names_on, effects=(*others, limit.effect))
    off = model.evaluate(x, wanted=names_off, effects=others)
    return x, on, off


def _check_limit(limit: Limit, x: dict, delta: float, others) -> None:
    x, on, off = _evaluate_pair(limit, x, delta, others)
    if "E_chain" in on:  # the chain's bounds need its energy at release (per μc²A²), with the effect on
        x["_E"] = float(on["E_chain"])
    compared = set()
    shared = [Compare(name, name, limit.common) for name in off if limit.common and name in on]
    for c in (*limit.compare, *shared):
        value = np.asarray(on[c.on], float)
        ref = np.asarray(off[c.off] if isinstance(c.off, str) else c.off(x, off), float)
        bound = np.asarray(c.bound(delta, x, ref), float)
        same = (value == ref) | (np.isnan(value) & np.isnan(ref))
        with np.errstate(invalid="ignore"):
            ok = same | (np.abs(value - ref) <= bound) | np.isinf(bound)
            excess = np.nanmax(np.where(ok, 0.0, np.abs(value - ref)))
        assert np.all(ok), (
            f"{c.on} vs {c.off if isinstance(c.off, str) else 'reference'} at δ = {delta!r}: "
            f"|Δ| = {excess:.3g} > bound {np.nanmin(np.where(ok, np.inf, bound)):.3g}"
        )
        compared.add(c.on)
    if limit.strict:
        for name in off:
            if name in compared or name not in on:
                continue
            assert np.array_equal(np.asarray(on[name]), np.asarray(off[name]), equal_nan=True), (
                f"{name} changed although the effect cannot touch it (δ = {delta!r})"
            )


# the bubble's limits solve its ODE on both sides of each limit, seconds apiece: left to `make test`
@pytest.mark.parametrize(
    "limit", [pytest.param(x, id=x.id, marks=pytest.mark.slow if x.model == "bubble" else ()) for x in LIMITS]
)
def test_effect_vanishes_in_its_limit(limit):
    """Effects rule 2 (docs/physics/README.md): as an effect's parameter goes to its neutral value the outputs go to
    those of the model
    without the effect, within the bound docs/physics/ gives (or one derived from the physics), at random
    points of the whole domain; every output the effect cannot touch is bitwise unchanged."""
    if limit.skip:
        pytest.skip(limit.skip)
    deltas = st.just(0.0) if limit.delta is None else limit.delta
    if not limit.companions:
        companions = st.just(set())
    elif limit.optional:
        companions = st.sets(st.sampled_from(limit.companions))
    else:
        companions = st.just(set(limit.companions))

    @_settings(limit.examples)
    @given(x=limit.inputs, delta=deltas, others=companions)
    def check(x, delta, others):
        _check_limit(limit, x, delta, tuple(sorted(others)))

    check()


def test_every_effect_parameter_has_a_vanishing_limit_case():
    """Each (model, effect, parameter) declared by a model has a case above, tested or skipped with a reason,
    and each effect without a parameter is listed; a new effect or parameter makes this fail by name."""
    declared = {(name, p.effect, p.name) for name, model in MODELS.items() for p in model.params if p.effect}
    bare = {
        (name, effect)
        for name, model in MODELS.items()
        for effect in model.effects
        if not any(p.effect == effect for p in model.params)
    }
    covered = {(limit.model, limit.effect, limit.param) for limit in LIMITS}
    missing = sorted(declared - covered)
    assert not missing, f"no vanishing-limit case for {missing}"
    effects_covered = {(limit.model, limit.effect) for limit in LIMITS}
    assert not sorted(bare - effects_covered), (
        f"effects without a parameter and without a case: {sorted(bare - effects_covered)}"
    )
    stale = sorted((m, e) for m, e, _ in covered if e != "(none)" and e not in MODELS[m].effects)
    assert not stale, f"cases for effects the models no longer declare: {stale}"


_NO_PARAMETER_INPUTS = {
    "collision": st.fixed_dictionaries(
        {
            "m1": _log_uniform(-15.0, 15.0),
            "m2": _log_uniform(-15.0, 15.0),
            "v1i": _VELOCITY,
            "v2i": _VELOCITY,
            "e": _RESTITUTION,
        }
    ),
    "euler_slab": st.fixed_dictionaries(
        {
            "spl": st.floats(-50.0, 200.0),
            "f": _log_uniform(0.0, 6.0),
            "dx_l": _log_uniform(-10.0, 0.0),
            "phi": st.floats(-720.0, 720.0),
        }
    ),
}


@pytest.mark.parametrize("model, effect", sorted(_NO_PARAMETER), ids=[f"{m}.{e}" for m, e in sorted(_NO_PARAMETER)])
def test_effect_without_a_parameter_changes_no_base_output(model, effect):
    """An effect with no parameter (the base law itself, or a readout of a neglected term) leaves every
    output of the model without it bitwise unchanged, anywhere in the domain."""

    @_settings(100)
    @given(x=_NO_PARAMETER_INPUTS[model])
    def check(x):
        plain = [o.name for o in MODELS[model].outputs if not o.effect]
        on = MODELS[model]().evaluate(x, wanted=plain, effects=(effect,))
        off = MODELS[model]().evaluate(x, wanted=plain)
        for name in plain:
            assert np.array_equal(np.asarray(on[name]), np.asarray(off[name]), equal_nan=True), name

    check()
