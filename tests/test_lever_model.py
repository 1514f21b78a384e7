"""I4 (lever): exact integer references on the whole slider grid, the hard cases, and the effects."""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest
from helpers import resolved_scene
from scipy.integrate import quad, solve_ivp

from sitegen.build import needed_outputs
from sitegen.compute.quantize import SPECIAL, fmt, quantize
from sitegen.compute.tabulate import tabulate_scene
from sitegen.models.lever.mechanics import BALANCED, LENGTH, TIPS_LEFT, TIPS_RIGHT, tipping_integral
from sitegen.models.lever.model import BLOCK_SIDE_PER_CUBE_ROOT_KG, DRAWN_SLOPE, Lever
from sitegen.registry import builtin_registry
from sitegen.render.layers import layer_points
from sitegen.review.decode import listed
from sitegen.site.assemble import readout_text
from sitegen.site.payload import scene_payload
from sitegen.site.sizes import gzip_bytes

FIGURES = builtin_registry().figures

EPS = np.finfo(float).eps
G = Fraction(981, 100)
BUDGET_GZIP = 60_000  # bytes of the scene's inline JSON, gzip as a host sends it

SCENE = """\
model: lever
id: lever
slider m_L: 0.5..10 step 0.5 default 2
slider m_R: 0.5..10 step 0.5 default 2
slider x_p: 0..2 step 0.01 default 1
fix balance_tolerance: 0.005
readouts: tau_L tau_R tau_net MA state
"""
BAR_SCENE = """\
model: lever
id: lever-bar
slider m_b: 0..10 step 0.5 default 2
slider x_p: 0..2 step 0.01 default 1
fix m_L: 1
fix m_R: 3
effects: bar_mass
readouts: tau_L tau_R tau_b tau_net_bar x_star_bar state_bar
"""


def _evaluate(wanted=None, effects=(), **inputs):
    """The model's outputs at one point or over broadcast arrays."""
    return Lever().evaluate(inputs, wanted=wanted, effects=effects)


def _integer_grid(mass_step_tenths: int = 1):
    """Slider stops as integers: m_L = a/10, m_R = b/10 (0.1..10 kg), x_p = k/100 (0..2 m), shape (A, B, 201)."""
    tenths = np.arange(mass_step_tenths, 101, mass_step_tenths, dtype=np.int64)
    return np.meshgrid(tenths, tenths, np.arange(201, dtype=np.int64), indexing="ij")


def _floats(a, b, k):
    """The floats a slider hands the model (a/10 and k/100 are correctly rounded, like the author's literals)."""
    return {"m_L": a / 10, "m_R": b / 10, "x_p": k / 100}


def _exact_state(a, b, k, c=0):
    """The rule in integers: with n = 1000 τ/g, balanced iff |x_p − x*| ≤ 0.005 m iff |2n| ≤ a + b (+ c)."""
    n = a * k - b * (200 - k) + c * (k - 100)
    balanced = np.abs(2 * n) <= a + b + c
    return np.where(balanced, BALANCED, np.where(n > 0, TIPS_LEFT, TIPS_RIGHT))


@pytest.fixture(scope="module")
def full_grid():
    """Every stop of docs/physics/lever.md's slider grid (0.1 kg × 0.1 kg × 0.01 m: 2.01 million) with the model's
    outputs."""
    a, b, k = _integer_grid()
    wanted = ["tau_L", "tau_R", "tau_net", "MA", "state", "x_star"]
    return a, b, k, _evaluate(wanted, **_floats(a, b, k))


@pytest.fixture(scope="module")
def built_scene():
    """The recommended scene resolved, tabulated and serialised as the page ships it."""
    scene = resolved_scene(SCENE)
    tables = tabulate_scene(scene, needed_outputs(scene))
    layers = FIGURES["lever"].layers(scene)
    return scene, tables, layers, scene_payload(scene, tables, tuple(layers))


def _stops(scene, **values) -> tuple[int, ...]:
    """Slider indices for the given values (the default elsewhere)."""
    stops = list(scene.default_stops)
    for name, value in values.items():
        i = scene.axis_index(name)
        stops[i] = [float(s) for s in scene.axes[i].stops].index(value)
    return tuple(stops)


# --- the seed's readouts at the defaults -----------------------------------------------------------------


@pytest.mark.parametrize(
    "output, expected",
    [("tau_L", "19.62 N·m"), ("tau_R", "19.62 N·m"), ("tau_net", "0.00 N·m"), ("MA", "1.00×"), ("state", "balanced")],
    ids=["tau_L", "tau_R", "tau_net", "MA", "state"],
)
def test_defaults_show_the_seed_readouts(built_scene, output, expected):
    """At x_p = 1 m and 2 kg on each end the page shows τL = τR = 19.62 N·m, net 0.00 N·m, MA 1.00, balanced."""
    scene, tables, _, _ = built_scene
    assert readout_text(tables[output], Lever.output(output).unit, scene.default_stops) == expected


def test_g_is_the_seed_value_not_standard_gravity():
    """docs/physics/README.md: g = 9.81, so 2 kg on a 1 m arm is 19.62 N·m (9.80665 would show 19.61)."""
    assert float(_evaluate(["tau_L"], m_L=2.0, x_p=1.0)["tau_L"]) == 2.0 * 9.81


# --- every displayed digit at every stop of the full-resolution grid ---------------------------------------

# Each check: |10^d · shown − exact| ≤ ½ unit, written in integers (exact = 981·(...)/1000 for the torques).
DISPLAY_CHECKS = {
    "tau_L": lambda q, a, b, k: np.abs(1000 * q - 981 * a * k) <= 500,
    "tau_R": lambda q, a, b, k: np.abs(1000 * q - 981 * b * (200 - k)) <= 500,
    "tau_net": lambda q, a, b, k: np.abs(1000 * q - 981 * (a * k - b * (200 - k))) <= 500,
    "MA": lambda q, a, b, k: np.where(k < 200, 2 * np.abs(q * (200 - k) - 100 * k) <= 200 - k, q == SPECIAL),
    "x_star": lambda q, a, b, k: 2 * np.abs(q * (a + b) - 2000 * b) <= a + b,
}


@pytest.mark.parametrize("output", DISPLAY_CHECKS, ids=list(DISPLAY_CHECKS))
def test_display_is_correctly_rounded_at_every_stop(full_grid, output):
    """At all 2.01 million stops (0.1 kg, 0.1 kg, 0.01 m) the shown value is within ½ unit of the exact rational."""
    a, b, k, out = full_grid
    q = quantize(out[output], Lever.output(output).decimals, special=bool(Lever.output(output).special))
    ok = DISPLAY_CHECKS[output](q, a, b, k)
    assert np.all(ok), f"{np.count_nonzero(~ok)} stops wrong, first at (a, b, k) = {np.argwhere(~ok)[0]}"


def test_net_torque_error_is_bounded_by_the_roundoff_of_its_terms(full_grid):
    """net τ against the exact decimal stops: |error| ≤ 5ε·g(m_L + m_R)ℓ at every stop, however small net τ is.

    The bound is the rounding of the inputs and of the terms, so it holds only for a direct form: no loss
    to cancellation beyond what the inputs already carry."""
    a, b, k, out = full_grid
    exact = 981.0 * (a * k - b * (200 - k)) / 1e5  # an exact integer over 10⁵: correctly rounded
    scale = 9.81 * (a + b) / 10 * LENGTH
    worst = np.max(np.abs(out["tau_net"] - exact) / (5 * EPS * scale))
    assert worst <= 1.0, f"worst case {worst:.3g} × the tolerance"


# --- hard case: pivot at the end (x_p = ℓ) ------------------------------------------------------------------

PIVOT_AT_THE_END = {
    "MA-is-+inf-never-nan": lambda scene, tables, payload: float(_evaluate(["MA"], x_p=LENGTH)["MA"]) == math.inf,
    "scene-data-is-strict-json": lambda scene, tables, payload: (
        json.dumps(json.loads(payload), allow_nan=False) is not None
        and listed(json.loads(payload)["tables"]["MA"])[-1] is None
    ),
    "readout-renders-infinity-phrase": lambda scene, tables, payload: (
        readout_text(tables["MA"], "×", _stops(scene, x_p=2.0)) == "∞ (pivot at the end)"
    ),
    "tau_R-is-0": lambda scene, tables, payload: (
        np.all(_evaluate(["tau_R"], m_R=np.arange(1, 101) / 10, x_p=LENGTH)["tau_R"] == 0.0)
        and readout_text(tables["tau_R"], "N·m", _stops(scene, x_p=2.0)) == "0.00 N·m"
    ),
    "MA-at-x_p=0-is-0": lambda scene, tables, payload: readout_text(tables["MA"], "×", _stops(scene, x_p=0.0)) == "0×",
}


@pytest.mark.parametrize("check", PIVOT_AT_THE_END, ids=list(PIVOT_AT_THE_END))
def test_pivot_at_the_end(built_scene, check):
    """x_p = ℓ: MA = ∞ as a sentinel (null in strict JSON, shown as a phrase), τR = 0; and MA(0) = 0 (shown to
    significant digits: "0×")."""
    scene, tables, _, payload = built_scene
    assert PIVOT_AT_THE_END[check](scene, tables, payload)


# --- hard case: balance point off the pivot grid -----------------------------------------------------------


def test_off_grid_balance_point_is_four_thirds():
    """m_L = 1, m_R = 2: x* = ℓ m_R/(m_L + m_R) = 4/3 within 1 ulp."""
    value = float(_evaluate(["x_star"], m_L=1.0, m_R=2.0)["x_star"])
    assert abs(Fraction(value) - Fraction(4, 3)) <= Fraction(EPS) * Fraction(4, 3)


def test_off_grid_nearest_stop_shows_a_small_net_torque():
    """At the nearest stop x_p = 1.33: net τ = −0.0981 N·m within 1e−14, displayed "−0.10"."""
    value = float(_evaluate(["tau_net"], m_L=1.0, m_R=2.0, x_p=1.33)["tau_net"])
    assert abs(value - (-0.0981)) <= 1e-14
    assert fmt(value, 2) == "\u22120.10"


def test_off_grid_balance_point_balances_exactly_the_nearest_stop():
    """m_L = 1, m_R = 2: of the 201 pivot stops only 1.33 is "balanced"; left of it the bar tips right."""
    x_p = np.arange(201) / 100
    state = _evaluate(["state"], m_L=1.0, m_R=2.0, x_p=x_p)["state"]
    assert list(x_p[state == BALANCED]) == [1.33]
    assert np.all(state[x_p < 1.33] == TIPS_RIGHT) and np.all(state[x_p > 1.33] == TIPS_LEFT)


def test_balance_point_midway_between_stops_balances_both():
    """m_L = 7.9, m_R = 0.1: x* = 0.025 exactly midway, so 0.02 and 0.03 are both balanced (the rule's ≤)."""
    x_p = np.arange(201) / 100
    state = _evaluate(["state"], m_L=7.9, m_R=0.1, x_p=x_p)["state"]
    assert list(x_p[state == BALANCED]) == [0.02, 0.03]


def test_off_grid_balance_marker_is_shown(built_scene):
    """At m_L = 1, m_R = 2 the figure's balance marker points at x* = 1.333 (display resolution 1 mm)."""
    scene, tables, layers, _ = built_scene
    stops = _stops(scene, m_L=1.0, m_R=2.0, x_p=1.33)
    points = dict(zip((layer.name for layer in layers), layer_points(layers, scene, tables, stops)))
    assert points["balance-marker"][1][0] == pytest.approx(1.333, abs=1e-12)
    assert points["balance-line"][0][0] == pytest.approx(1.333, abs=1e-12)


def test_state_matches_the_exact_rule_at_every_stop(full_grid):
    """balanced iff |x_p − x*| ≤ Δx_p/2, else tips towards the centre of mass: equal to integer arithmetic at all
    stops."""
    a, b, k, out = full_grid
    wrong = out["state"] != _exact_state(a, b, k)
    assert not np.any(wrong), f"{np.count_nonzero(wrong)} stops wrong, first at (a, b, k) = {np.argwhere(wrong)[0]}"


@pytest.mark.parametrize("step_tenths", [1, 5], ids=["every-pair-0.1kg-grid", "every-pair-0.5kg-scene-grid"])
def test_every_mass_pair_has_one_or_two_balanced_stops(full_grid, step_tenths):
    """For every (m_L, m_R) on the slider grid exactly one or two pivot stops are "balanced"."""
    a, b, k, out = full_grid
    picked = a[:, 0, 0] % step_tenths == 0
    counts = np.count_nonzero(out["state"][picked][:, picked] == BALANCED, axis=-1)
    assert counts.min() == 1 and counts.max() == 2, (counts.min(), counts.max())


# --- hard case: net τ near balance ---------------------------------------------------------------------------


def test_net_torque_at_the_default_is_exactly_zero():
    """net τ = g(m_L x_p − m_R(ℓ − x_p)) directly: at the defaults it is 0.0 exactly, not a roundoff residue."""
    assert float(_evaluate(["tau_net"])["tau_net"]) == 0.0


@pytest.mark.parametrize(
    "m_L, m_R, x_p",
    [(1.0, 1.0, 1.0), (3.0, 1.0, 0.5), (1.5, 0.5, 0.5), (0.5, 1.5, 1.5)],
    ids=["1|1@1", "3|1@0.5", "1.5|0.5@0.5", "0.5|1.5@1.5"],
)
def test_net_torque_is_exactly_zero_at_exact_balances_with_binary_values(m_L, m_R, x_p):
    """Where every product is exact in binary the direct form gives 0.0 and the state is balanced."""
    out = _evaluate(["tau_net", "state"], m_L=m_L, m_R=m_R, x_p=x_p)
    assert float(out["tau_net"]) == 0.0 and int(out["state"]) == BALANCED


# --- the figure's moving parts ---------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def geometry():
    """The drawn bar and blocks over the 0.5 kg grid of masses and every pivot stop."""
    a, b, k = _integer_grid(5)
    x = _floats(a, b, k)
    names = [o.name for o in Lever.outputs if not o.effect and o.unit == "m"] + ["state"]
    return x, _evaluate(names, **x)


def test_bar_leans_towards_the_winning_side(geometry):
    """Tips left: the left end is drawn low (y_left < y_right); tips right: the reverse; balanced: level at 0."""
    x, out = geometry
    state, left, right = out["state"], out["y_left"], out["y_right"]
    assert np.all(left[state == TIPS_LEFT] < right[state == TIPS_LEFT])
    assert np.all(left[state == TIPS_RIGHT] > right[state == TIPS_RIGHT])
    assert np.all((left[state == BALANCED] == 0.0) & (right[state == BALANCED] == 0.0))


def test_bar_is_drawn_through_the_pivot_at_the_fixed_slope(geometry):
    """The drawn bar passes through (x_p, 0) with slope ±tan 5° (0 when balanced), to 1e−15."""
    x, out = geometry
    slope = (out["y_right"] - out["y_left"]) / LENGTH
    expected = np.select([out["state"] == TIPS_LEFT, out["state"] == TIPS_RIGHT], [DRAWN_SLOPE, -DRAWN_SLOPE], 0.0)
    assert np.max(np.abs(slope - expected)) <= 1e-15
    assert np.max(np.abs(out["y_left"] + slope * x["x_p"])) <= 1e-15


@pytest.mark.parametrize("block", ["left", "right"])
def test_blocks_stand_on_the_bar_ends(geometry, block):
    """Each block's bottom corners lie on the drawn bar, its top is one side higher, and it is centred on the end."""
    x, out = geometry
    mass = x["m_L"] if block == "left" else x["m_R"]
    side = BLOCK_SIDE_PER_CUBE_ROOT_KG * np.cbrt(mass)
    centre = 0.0 if block == "left" else LENGTH
    slope = (out["y_right"] - out["y_left"]) / LENGTH
    for edge in "01":
        at = out[f"{block}_block_x{edge}"]
        on_bar = out["y_left"] + slope * at
        assert np.max(np.abs(out[f"{block}_block_bottom{edge}"] - on_bar)) <= 1e-15
        assert np.max(np.abs(out[f"{block}_block_top{edge}"] - out[f"{block}_block_bottom{edge}"] - side)) <= 1e-15
    assert np.max(np.abs(0.5 * (out[f"{block}_block_x0"] + out[f"{block}_block_x1"]) - centre)) <= 1e-15


def test_block_volume_grows_in_proportion_to_mass():
    """Block side ∝ m^(1/3): side³/m is the same for every mass, within 4ε rel."""
    m = np.arange(1, 101) / 10
    out = _evaluate(["left_block_x0", "left_block_x1"], m_L=m)
    ratio = (out["left_block_x1"] - out["left_block_x0"]) ** 3 / m
    assert np.max(np.abs(ratio / BLOCK_SIDE_PER_CUBE_ROOT_KG**3 - 1)) <= 4 * EPS * 4


def test_scene_layers_read_declared_outputs_and_level_bar_at_defaults(built_scene):
    """Every layer reads outputs of the model; at the defaults the bar is drawn level and the fulcrum's apex is at
    x_p."""
    scene, tables, layers, _ = built_scene
    declared = {o.name for o in Lever.outputs}
    assert set().union(*(layer.outputs() for layer in layers)) <= declared
    points = dict(zip((layer.name for layer in layers), layer_points(layers, scene, tables, scene.default_stops)))
    assert points["bar"] == [(0.0, 0.0), (2.0, 0.0)]
    assert points["fulcrum"][1] == (1.0, 0.0)


def test_bar_mass_scene_layers_follow_the_bar_inclusive_balance():
    """With bar_mass enabled the figure's tilt and balance marker read the outputs that include the bar."""
    scene = resolved_scene(BAR_SCENE)
    reads = set().union(*(layer.outputs() for layer in FIGURES["lever"].layers(scene)))
    assert {"x_star_bar", "y_left_bar", "y_right_bar", "left_block_top0_bar"} <= reads
    assert not reads & {"x_star", "y_left", "y_right", "left_block_top0"}


# --- the scene's size ---------------------------------------------------------------------------------------------


def test_scene_data_fits_the_budget(built_scene):
    """The recommended scene's inline JSON is at most 60 kB gzip-compressed."""
    size = gzip_bytes(built_scene[3].encode())
    assert size <= BUDGET_GZIP, f"{size} bytes"


# --- effect bar_mass ----------------------------------------------------------------------------------------------


@pytest.mark.parametrize("x_p", [0.0, 0.37, 1.0, 1.5, 2.0], ids=["x_p=0", "x_p=0.37", "x_p=1", "x_p=1.5", "x_p=2"])
def test_bar_torque_sign_and_value(x_p):
    """τ_b = m_b g (x_p − ℓ/2) within 2ε of the exact value; positive (left end down) when the middle is left of the
    pivot."""
    value = float(_evaluate(["tau_b"], effects=["bar_mass"], m_b=3.7, x_p=x_p)["tau_b"])
    exact = Fraction(3.7) * G * (Fraction(x_p) - 1)
    assert abs(Fraction(value) - exact) <= Fraction(2 * EPS) * abs(exact)
    assert np.sign(value) == np.sign(x_p - 1.0)


@pytest.mark.parametrize("m_b", [0.5, 3.0, 10.0], ids=["m_b=0.5", "m_b=3", "m_b=10"])
def test_bar_acts_like_half_its_mass_at_each_end(m_b):
    """Second method: the uniform bar's torque about any pivot equals m_b/2 at each end (net τ within 8ε·g·Σ m·arm)."""
    a, b, k = _integer_grid(5)
    x = _floats(a, b, k)
    with_bar = _evaluate(["tau_net_bar", "x_star_bar"], effects=["bar_mass"], m_b=m_b, **x)
    halves = _evaluate(["tau_net", "x_star"], m_L=x["m_L"] + m_b / 2, m_R=x["m_R"] + m_b / 2, x_p=x["x_p"])
    scale = 9.81 * ((x["m_L"] + m_b) * x["x_p"] + (x["m_R"] + m_b) * (LENGTH - x["x_p"]))
    assert np.max(np.abs(with_bar["tau_net_bar"] - halves["tau_net"]) / scale) <= 8 * EPS
    assert np.max(np.abs(with_bar["x_star_bar"] - halves["x_star"])) <= 4 * EPS * LENGTH


@pytest.mark.parametrize("m_b", [0.5, 3.0, 10.0], ids=["m_b=0.5", "m_b=3", "m_b=10"])
def test_bar_mass_state_matches_the_exact_rule_with_one_or_two_balanced_stops(m_b):
    """With the bar: state equals the integer rule at every stop of the 0.5 kg grid, 1 or 2 balanced stops per pair."""
    a, b, k = _integer_grid(5)
    state = _evaluate(["state_bar"], effects=["bar_mass"], m_b=m_b, **_floats(a, b, k))["state_bar"]
    assert np.array_equal(state, _exact_state(a, b, k, c=round(10 * m_b)))
    counts = np.count_nonzero(state == BALANCED, axis=-1)
    assert counts.min() == 1 and counts.max() == 2


BAR_PAIRS = [
    ("tau_net_bar", "tau_net"),
    ("x_star_bar", "x_star"),
    ("state_bar", "state"),
    ("y_left_bar", "y_left"),
    ("right_block_top1_bar", "right_block_top1"),
]


@pytest.fixture(scope="module")
def massless_bar(full_grid):
    """Over the full grid, the bar-mass outputs at m_b = 0 and the massless-bar outputs (each model run once)."""
    a, b, k, _ = full_grid
    x = _floats(a, b, k)
    with_bar = _evaluate([w for w, _ in BAR_PAIRS], effects=["bar_mass"], m_b=0.0, **x)
    return with_bar, _evaluate([w for _, w in BAR_PAIRS], **x)


@pytest.mark.parametrize("with_bar, without", BAR_PAIRS, ids=[p[0] for p in BAR_PAIRS])
def test_massless_bar_reproduces_the_base_model_exactly(massless_bar, with_bar, without):
    """Vanishing limit at m_b = 0: every bar-mass output equals the massless-bar output at all 2.01 million stops."""
    got, base = massless_bar
    assert np.array_equal(got[with_bar], base[without])


@pytest.mark.parametrize("m_b", [1e-3, 1e-6, 1e-9], ids=["m_b=1e-3", "m_b=1e-6", "m_b=1e-9"])
def test_bar_mass_vanishing_limit(m_b):
    """m_b → 0: |Δ net τ| ≤ m_b g ℓ/2 and |Δx*| ≤ m_b ℓ/(2 M) (+ roundoff), so the massless bar is the limit."""
    a, b, k = _integer_grid(5)
    x = _floats(a, b, k)
    bar = _evaluate(["tau_net_bar", "x_star_bar"], effects=["bar_mass"], m_b=m_b, **x)
    base = _evaluate(["tau_net", "x_star"], **x)
    roundoff = 8 * EPS * 9.81 * 20 * LENGTH
    assert np.max(np.abs(bar["tau_net_bar"] - base["tau_net"])) <= m_b * 9.81 * LENGTH / 2 + roundoff
    bound = m_b * LENGTH / (2 * (x["m_L"] + x["m_R"])) + 4 * EPS * LENGTH
    assert np.all(np.abs(bar["x_star_bar"] - base["x_star"]) <= bound)


# --- effect rotation_dynamics ----------------------------------------------------------------------------------

ROTATION_CASES = [
    pytest.param(2.0, 2.0, 1.2, 15.0, id="tips-left-x_p=1.2"),
    pytest.param(1.0, 6.5, 0.9, 15.0, id="tips-right-heavy-right"),
    pytest.param(0.1, 10.0, 0.0, 30.0, id="pivot-at-left-end-x_p=0"),
    pytest.param(7.3, 0.1, 2.0, 30.0, id="pivot-at-right-end-x_p=2"),
    pytest.param(1.0, 2.0, 1.33, 10.0, id="nearly-balanced-1|2@1.33"),
    pytest.param(3.0, 1.0, 1.7, 90.0, id="stop-at-90deg"),
    pytest.param(3.0, 1.0, 1.7, 1.0, id="stop-at-1deg"),
]


def _integrate_to_the_stop(m_L, m_R, x_p, theta_s, m_b=0.0):
    """Second method: I θ'' = τ cos θ from rest by DOP853 (rtol 1e−12), stopped by a terminal event at ±θ_s;
    with m_b > 0, I and τ include the uniform bar."""
    torque = 9.81 * (m_L * x_p - m_R * (LENGTH - x_p) + m_b * (x_p - LENGTH / 2))
    inertia = m_L * x_p**2 + m_R * (LENGTH - x_p) ** 2 + m_b * (LENGTH**2 / 12 + (LENGTH / 2 - x_p) ** 2)
    stop = math.copysign(math.radians(theta_s), torque)

    def hits_stop(t, y):
        return y[0] - stop

    hits_stop.terminal = True
    solution = solve_ivp(
        lambda t, y: (y[1], torque * math.cos(y[0]) / inertia),
        (0.0, 1e3),
        (0.0, 0.0),
        method="DOP853",
        rtol=1e-12,
        atol=1e-14 * abs(stop),
        events=hits_stop,
        dense_output=True,
    )
    assert solution.status == 1, solution.message  # ended at the event, not at the time cap
    return solution, torque, inertia


@pytest.mark.parametrize("m_L, m_R, x_p, theta_s", ROTATION_CASES)
def test_time_and_speed_at_the_stop_match_the_integrated_motion(m_L, m_R, x_p, theta_s):
    """The closed-form t_stop and ω_stop agree with the event time and speed of the integrated ODE within 1e−9 rel."""
    solution, _, _ = _integrate_to_the_stop(m_L, m_R, x_p, theta_s)
    t_event, (_, omega_event) = solution.t_events[0][0], solution.y_events[0][0]
    out = _evaluate(["t_stop", "omega_stop"], effects=["rotation_dynamics"], m_L=m_L, m_R=m_R, x_p=x_p, theta_s=theta_s)
    assert abs(float(out["t_stop"]) / t_event - 1) <= 1e-9
    assert abs(float(out["omega_stop"]) / omega_event - 1) <= 1e-9


@pytest.mark.parametrize("m_L, m_R, x_p, theta_s", ROTATION_CASES)
def test_integrated_motion_conserves_energy(m_L, m_R, x_p, theta_s):
    """Energy check: ½ I θ'² = τ(0) sin θ along the integrated motion within 1e−9 of τ(0) sin θ_s."""
    solution, torque, inertia = _integrate_to_the_stop(m_L, m_R, x_p, theta_s)
    theta, omega = solution.sol(np.linspace(0.0, solution.t_events[0][0], 400))
    scale = abs(torque) * math.sin(math.radians(theta_s))
    assert np.max(np.abs(0.5 * inertia * omega**2 - torque * np.sin(theta))) <= 1e-9 * scale


@pytest.mark.parametrize(
    "theta", [1e-3, 0.01, 0.2618, 1.0, math.pi / 2], ids=["1e-3", "0.01", "15deg", "1rad", "90deg"]
)
def test_tipping_integral_closed_form_matches_quadrature(theta):
    """∫₀^θ dφ/√(sin φ) in elliptic closed form equals adaptive quadrature with the √φ singularity as a weight, 1e−13
    rel."""
    reference = quad(
        lambda p: math.sqrt(p / math.sin(p)) if p else 1.0,
        0.0,
        theta,
        weight="alg",
        wvar=(-0.5, 0.0),
        epsabs=0,
        epsrel=1e-13,
    )[0]
    assert abs(float(tipping_integral(theta)) / reference - 1) <= 1e-13


def test_small_stop_angle_is_uniform_angular_acceleration():
    """θ_s → 0: t_stop → √(2 I θ_s / τ), the constant-acceleration time, within θ_s² rel."""
    theta_s = 0.05
    out = _evaluate(
        ["t_stop", "inertia", "tau_net"], effects=["rotation_dynamics"], m_L=3.0, m_R=1.0, x_p=1.7, theta_s=theta_s
    )
    expected = math.sqrt(2 * float(out["inertia"]) * math.radians(theta_s) / float(out["tau_net"]))
    assert abs(float(out["t_stop"]) / expected - 1) <= math.radians(theta_s) ** 2


def test_bar_never_moves_exactly_where_there_is_no_net_torque(full_grid):
    """t_stop = ∞ (shown as a phrase) and ω = 0 exactly at the stops where m_L x_p = m_R (ℓ − x_p) in exact
    arithmetic."""
    a, b, k, _ = full_grid
    out = _evaluate(["t_stop", "omega_stop"], effects=["rotation_dynamics"], theta_s=15.0, **_floats(a, b, k))
    still = a * k == b * (200 - k)
    assert np.array_equal(np.isinf(out["t_stop"]), still) and np.all(out["omega_stop"][still] == 0.0)
    assert np.all(np.isfinite(out["t_stop"][~still]) & (out["omega_stop"][~still] != 0.0))


@pytest.mark.parametrize("x_p", [0.0, 2.0], ids=["pivot-at-left-end", "pivot-at-right-end"])
def test_moment_of_inertia_is_positive_with_the_pivot_at_an_end(x_p):
    """I = m_L x_p² + m_R(ℓ − x_p)² > 0 at x_p = 0 and ℓ with the lightest masses (0.1 kg): 0.4 kg·m²."""
    value = float(_evaluate(["inertia"], effects=["rotation_dynamics"], m_L=0.1, m_R=0.1, x_p=x_p)["inertia"])
    assert value == pytest.approx(0.4, rel=4 * EPS)


BAR_ROTATION_CASES = [
    pytest.param(2.0, 2.0, 1.2, 1.0, 15.0, id="tips-left-x_p=1.2-m_b=1"),
    pytest.param(1.0, 6.5, 0.9, 3.0, 15.0, id="tips-right-heavy-right-m_b=3"),
    pytest.param(0.1, 0.1, 0.0, 10.0, 30.0, id="bar-outweighs-the-blocks-x_p=0"),
    pytest.param(3.0, 1.0, 1.7, 0.5, 90.0, id="stop-at-90deg"),
]


@pytest.mark.parametrize("m_L, m_R, x_p, m_b, theta_s", BAR_ROTATION_CASES)
def test_rotation_with_the_bar_matches_the_integrated_motion(m_L, m_R, x_p, m_b, theta_s):
    """bar_mass with rotation_dynamics: I includes m_b(ℓ²/12 + (ℓ/2 − x_p)²) and the torque m_b g (x_p − ℓ/2);
    t_stop and ω_stop agree with the integrated ODE within 1e−9 rel."""
    solution, _, inertia = _integrate_to_the_stop(m_L, m_R, x_p, theta_s, m_b)
    t_event, omega_event = solution.t_events[0][0], solution.y_events[0][0][1]
    out = _evaluate(
        ["t_stop", "omega_stop", "inertia"],
        effects=["bar_mass", "rotation_dynamics"],
        m_L=m_L,
        m_R=m_R,
        x_p=x_p,
        m_b=m_b,
        theta_s=theta_s,
    )
    assert abs(float(out["inertia"]) / inertia - 1) <= 4 * EPS
    assert abs(float(out["t_stop"]) / t_event - 1) <= 1e-9
    assert abs(float(out["omega_stop"]) / omega_event - 1) <= 1e-9


def test_rotation_ignores_the_bar_unless_bar_mass_is_on():
    """Without bar_mass the rotation outputs are those of the massless bar, whatever m_b is given (bitwise)."""
    names = ["inertia", "t_stop", "omega_stop"]
    heavy = _evaluate(names, effects=["rotation_dynamics"], m_L=1.0, m_R=6.5, x_p=0.9, m_b=3.0)
    plain = _evaluate(names, effects=["rotation_dynamics"], m_L=1.0, m_R=6.5, x_p=0.9)
    assert all(float(heavy[n]) == float(plain[n]) for n in names)


@pytest.mark.parametrize("m_b", [0.0, 1e-12, 1e-6, 1e-3], ids=lambda m: f"m_b={m}")
def test_rotation_with_a_vanishing_bar_is_the_massless_rotation(m_b):
    """m_b → 0 with both effects on: t_stop and ω_stop tend to the massless bar's, within a relative change
    of O(m_b/M) (bound: m_b(ℓ²/3 + ℓ/2)/min(I, |τ|/g) + 16ε); m_b = 0 gives them bitwise."""
    names = ["t_stop", "omega_stop"]
    inputs = dict(m_L=1.0, m_R=6.5, x_p=0.9, theta_s=15.0)
    with_bar = _evaluate(names, effects=["bar_mass", "rotation_dynamics"], m_b=m_b, **inputs)
    massless = _evaluate(names, effects=["rotation_dynamics"], **inputs)
    inertia = 1.0 * 0.9**2 + 6.5 * 1.1**2
    arms = abs(1.0 * 0.9 - 6.5 * 1.1)
    bound = m_b * (LENGTH**2 / 3 + LENGTH / 2) / min(inertia, arms) + (16 * EPS if m_b else 0.0)
    for name in names:
        assert abs(float(with_bar[name]) / float(massless[name]) - 1) <= bound, name


# --- invalid input -----------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "inputs",
    [
        {"x_p": -0.01},
        {"x_p": 2.01},
        {"m_L": 0.0},
        {"m_R": -1.0},
        {"balance_tolerance": -1e-3},
        {"m_b": -0.1},
        {"theta_s": 0.0},
        {"theta_s": 90.5},
        {"x_p": float("nan")},
        {"m_L": float("inf")},
    ],
    ids=["x_p<0", "x_p>l", "m_L=0", "m_R<0", "tolerance<0", "m_b<0", "theta_s=0", "theta_s>90", "x_p=nan", "m_L=inf"],
)
def test_invalid_input_raises_naming_the_parameter(inputs):
    """Values outside the domain raise ValueError whose message names the parameter."""
    (name,) = inputs
    with pytest.raises(ValueError, match=f"`{name}`"):
        Lever().evaluate(inputs)
