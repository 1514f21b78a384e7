"""I4: torques on a bar with a mass at each end, resting on a pivot (closed form).

Sign convention (physics.md I4): a torque is positive when it turns the bar counter-clockwise,
i.e. when it pushes the left end down.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.special import ellipk, ellipkinc

from ...physics.base import Model, Output, Param
from ...physics.numerics import Measurement, Numerics
from ...physics.structure import Choose, Coord, Poly, Threshold, param

G = 9.81  # physics.md §0.1 requires 9.81: the seed's 2 kg · 9.81 m/s² · 1 m = 19.62 N·m (9.80665 shows 19.61)
LENGTH = 2.0  # ℓ, the bar's length (m)
BALANCED, TIPS_LEFT, TIPS_RIGHT = 0, 1, 2
STATES = ("balanced", "tips left", "tips right")
# Relative slack on the balance test, so that a balance point exactly midway between two pivot
# stops counts for both (the rule is |x_p − x*| ≤ Δx_p/2) whatever the last-bit rounding of the
# floats. On the 0.01 m × 0.1 kg grids a true |x_p − x*| that is not exactly Δx_p/2 differs from it
# by at least 0.5 % of Δx_p/2, so the slack changes no other verdict.
BALANCE_SLACK = 1e-9

# Geometry of the figure, in metres in the bar's own frame (the pivot is at height 0). The page
# script only looks values up, so every moving vertex that needs arithmetic is an output.
DRAWN_SLOPE = math.tan(math.radians(5.0))  # how far the drawn bar leans when it tips
BLOCK_SIDE_PER_CUBE_ROOT_KG = 0.16  # block side ∝ m^(1/3): the blocks' volume grows with mass
FULCRUM_HALF_WIDTH = 0.11
MARKER_HALF_WIDTH = 0.05
EPS = np.finfo(float).eps

_POSITION = ("m_L", "m_R", "x_p")
_TILT = _POSITION + ("balance_tolerance",)
_WITH_BAR = ("m_L", "m_R", "x_p", "m_b")
_TILT_WITH_BAR = _WITH_BAR + ("balance_tolerance",)
_ROTATION = _POSITION + ("theta_s",)
_BAR_TURNS_TOO = (("bar_mass", ("m_b",)),)  # with bar_mass the rotation feels the bar's weight and inertia


# --- exact forms for the page (physics.md I4 "structure") -----------------------------------
# Torques are multilinear in (m_L, m_R, x_p). With s = 1/(m_L + m_R) as a coordinate (one table
# along m_L + m_R) the balance point x* = ℓ m_R s is bilinear, and the state is a threshold on
# (x_p − x*)/tolerance. The drawn tilt is one of three polynomials chosen by that state.
_X_P, _M_L, _M_R = param("x_p"), param("m_L"), param("m_R")
INV_TOTAL = Coord("inv_total_mass", ("m_L", "m_R"), lambda m_L, m_R: 1.0 / (m_L + m_R))
INV_TOLERANCE = Coord("inv_tolerance", ("balance_tolerance",),
                      lambda balance_tolerance: 1.0 / (balance_tolerance * (1.0 + BALANCE_SLACK)))
SIDE = {side: Coord(f"side_{side}", (f"m_{side}",), lambda **m: _block_side(next(iter(m.values()))))
        for side in ("L", "R")}


def _offset_in_tolerances(c):
    """(x_p − x*) in units of the (slackened) balance tolerance."""
    return (c["x_p"] - LENGTH * c["m_R"] * c["inv_total_mass"]) * c["inv_tolerance"]


_STATE = Threshold(Poly(_offset_in_tolerances, ((_X_P, 1), (_M_R, 1), (INV_TOTAL, 1), (INV_TOLERANCE, 1))),
                   (-1.0, 1.0), (TIPS_RIGHT, BALANCED, TIPS_LEFT))
_BALANCE_POINT = ((_M_R, 1), (INV_TOTAL, 1))


def _shifted_balance_point(shift: float) -> Poly:
    return Poly(lambda c: LENGTH * c["m_R"] * c["inv_total_mass"] + shift, _BALANCE_POINT)


def _tilted_height(at: float, block: str = "", edge: float = 0.0, top: bool = False) -> Choose:
    """A drawn height slope·(x − x_p) (+ the block's side for its top), x = at + edge·side."""
    coords = ((_X_P, 1),) + (((SIDE[block], 1),) if block else ())

    def kernel(slope):
        def height(c):
            side = c[f"side_{block}"] if block else 0.0
            return slope * (at + edge * side - c["x_p"]) + (side if top else 0.0)
        return Poly(height, coords)

    by_state = {BALANCED: kernel(0.0), TIPS_LEFT: kernel(DRAWN_SLOPE), TIPS_RIGHT: kernel(-DRAWN_SLOPE)}
    return Choose(_STATE, tuple(by_state[k] for k in range(3)))


def _tilt_outputs(suffix: str, deps: tuple[str, ...], effect: str = "") -> tuple[Output, ...]:
    """The heights of the drawn bar's ends and of the blocks' corners, which follow the tilt."""
    described = ", with the bar's mass" if effect else ""
    names = [("y_left", "height of the bar's left end", _tilted_height(0.0)),
             ("y_right", "height of the bar's right end", _tilted_height(LENGTH))]
    for block, side, centre in (("left", "L", 0.0), ("right", "R", LENGTH)):
        for edge, where, sign in (("0", "left", -0.5), ("1", "right", 0.5)):
            names.append((f"{block}_block_bottom{edge}", f"height of the {block} block's bottom {where} corner",
                          _tilted_height(centre, side, sign)))
            names.append((f"{block}_block_top{edge}", f"height of the {block} block's top {where} corner",
                          _tilted_height(centre, side, sign, top=True)))
    return tuple(
        Output(f"{name}{suffix}", f"{label} (as drawn{described})", "m", deps, decimals=3, effect=effect,
               structure=None if effect else form)
        for name, label, form in names
    )


class Lever(Model):
    """A rigid bar of length ℓ with masses m_L and m_R at its ends, on a pivot at x_p from the left end."""

    name = "lever"
    title = "Torque and the lever principle"
    params = (
        Param("x_p", "x<sub>p</sub>", "m", 1.0, lo=0.0, hi=LENGTH, description="pivot position, from the left end"),
        Param("m_L", "m<sub>L</sub>", "kg", 2.0, lo=0.0, lo_open=True, description="mass at the left end"),
        Param("m_R", "m<sub>R</sub>", "kg", 2.0, lo=0.0, lo_open=True, description="mass at the right end"),
        Param(
            "balance_tolerance", "Δx<sub>p</sub>/2", "m", 0.005, lo=0.0, hi=0.25 * LENGTH,
            description="how far the pivot may sit from the balance point and still count as balanced: half the pivot slider's step",
        ),
        Param("m_b", "m<sub>b</sub>", "kg", 1.0, lo=0.0, description="mass of the bar (uniform)").with_effect("bar_mass"),
        Param(
            "theta_s", "θ<sub>s</sub>", "°", 15.0, lo=0.0, hi=90.0, lo_open=True,
            description="angle at which the tipping bar hits its stop",
        ).with_effect("rotation_dynamics"),
    )
    outputs = (
        Output("tau_L", "τ<sub>L</sub>", "N·m", ("m_L", "x_p"), decimals=2,
               structure=Poly(lambda c: c["m_L"] * G * c["x_p"], ((_M_L, 1), (_X_P, 1)))),
        Output("tau_R", "τ<sub>R</sub>", "N·m", ("m_R", "x_p"), decimals=2,
               structure=Poly(lambda c: c["m_R"] * G * (LENGTH - c["x_p"]), ((_M_R, 1), (_X_P, 1)))),
        Output("tau_net", "net τ", "N·m", _POSITION, decimals=2,
               structure=Poly(lambda c: G * (c["m_L"] * c["x_p"] - c["m_R"] * (LENGTH - c["x_p"])), ((_M_L, 1), (_M_R, 1), (_X_P, 1)))),
        Output("MA", "MA = L<sub>L</sub>/L<sub>R</sub>", "×", ("x_p",), decimals=2, digits=3, special="∞ (pivot at the end)"),
        Output("state", "the bar", "", _TILT, labels=STATES, structure=_STATE),
        Output("x_star", "balance point x*", "m", ("m_L", "m_R"), decimals=3, structure=_shifted_balance_point(0.0)),
        # Figure geometry: the fulcrum, the blocks' sides and the balance-point marker.
        Output("fulcrum_x0", "left foot of the fulcrum (as drawn)", "m", ("x_p",), decimals=3,
               structure=Poly(lambda c: c["x_p"] - FULCRUM_HALF_WIDTH, ((_X_P, 1),))),
        Output("fulcrum_x1", "right foot of the fulcrum (as drawn)", "m", ("x_p",), decimals=3,
               structure=Poly(lambda c: c["x_p"] + FULCRUM_HALF_WIDTH, ((_X_P, 1),))),
        Output("left_block_x0", "left side of the left block (as drawn)", "m", ("m_L",), decimals=3),
        Output("left_block_x1", "right side of the left block (as drawn)", "m", ("m_L",), decimals=3),
        Output("right_block_x0", "left side of the right block (as drawn)", "m", ("m_R",), decimals=3),
        Output("right_block_x1", "right side of the right block (as drawn)", "m", ("m_R",), decimals=3),
        Output("marker_x0", "left foot of the balance-point marker (as drawn)", "m", ("m_L", "m_R"), decimals=3,
               structure=_shifted_balance_point(-MARKER_HALF_WIDTH)),
        Output("marker_x1", "right foot of the balance-point marker (as drawn)", "m", ("m_L", "m_R"), decimals=3,
               structure=_shifted_balance_point(MARKER_HALF_WIDTH)),
        *_tilt_outputs("", _TILT),
        # bar_mass: the same picture with the bar's own weight acting at its middle.
        Output("tau_b", "τ<sub>b</sub> (bar)", "N·m", ("x_p", "m_b"), decimals=2, effect="bar_mass"),
        Output("tau_net_bar", "net τ (with bar)", "N·m", _WITH_BAR, decimals=2, effect="bar_mass"),
        Output("state_bar", "the bar (with its mass)", "", _TILT_WITH_BAR, labels=STATES, effect="bar_mass"),
        Output("x_star_bar", "balance point x* (with bar)", "m", ("m_L", "m_R", "m_b"), decimals=3, effect="bar_mass"),
        Output("marker_x0_bar", "left foot of the balance-point marker (as drawn, with the bar)", "m", ("m_L", "m_R", "m_b"), decimals=3, effect="bar_mass"),
        Output("marker_x1_bar", "right foot of the balance-point marker (as drawn, with the bar)", "m", ("m_L", "m_R", "m_b"), decimals=3, effect="bar_mass"),
        *_tilt_outputs("_bar", _TILT_WITH_BAR, "bar_mass"),
        # rotation_dynamics: released from rest, horizontal, the bar turns until it hits the stop.
        Output("inertia", "I (about the pivot)", "kg·m²", _POSITION, decimals=3, effect="rotation_dynamics",
               deps_with=_BAR_TURNS_TOO),
        Output("t_stop", "time to hit the stop", "s", _ROTATION, decimals=3, special="∞ (no net torque)", effect="rotation_dynamics",
               deps_with=_BAR_TURNS_TOO),
        Output("omega_stop", "ω at the stop", "rad/s", _ROTATION, decimals=3, effect="rotation_dynamics",
               deps_with=_BAR_TURNS_TOO),
    )
    effects = ("bar_mass", "rotation_dynamics")
    # The tipping bar's time to the stop is an incomplete elliptic integral F(ψ | ½) (scipy's ellipkinc),
    # checked against a tight numerical solution of I θ'' = τ cos θ.
    numerics = Numerics("elliptic", tolerance=1e-9)
    methods = {"elliptic": {}}
    error_metric = "relative error of the time to the stop"

    def is_numerical(self, effects) -> bool:
        """Only the rotation to the stop is computed by a special function; the statics are closed forms."""
        return "rotation_dynamics" in effects

    def measure_error(self, values, effects) -> Measurement:
        """t_stop by the elliptic integral against DOP853 at rtol 1e-12 with a terminal event at θ_s."""
        x = {k: np.asarray(v, float) for k, v in {**self.defaults(), **values}.items()}
        elliptic = float(_time_to_stop(x))
        torque, inertia, stop = abs(float(_moving_torque(x))), float(_inertia(x)), math.radians(float(x["theta_s"]))
        if torque == 0.0:  # the bar never moves: both say ∞
            return Measurement(0.0 if math.isinf(elliptic) else math.inf, 0, "elliptic integral", "DOP853 at rtol 1e-12")
        hit = lambda t, y: y[0] - stop  # noqa: E731
        hit.terminal, hit.direction = True, 1
        horizon = 4.0 * elliptic + 1.0
        run = solve_ivp(lambda t, y: (y[1], torque * math.cos(y[0]) / inertia), (0.0, horizon), (0.0, 0.0),
                        method="DOP853", rtol=1e-12, atol=1e-14 * stop, events=hit)
        reference = float(run.t_events[0][0]) if len(run.t_events[0]) else math.inf
        return Measurement(abs(elliptic - reference) / reference, 0, "elliptic integral", "DOP853 at rtol 1e-12")

    def _evaluate(self, x, wanted, effects):
        bar = "bar_mass" in effects  # the rotation includes the bar's weight and inertia only then
        x_p, m_L, m_R = x["x_p"], x["m_L"], x["m_R"]
        side_L, side_R = _block_side(m_L), _block_side(m_R)
        formulas = {
            "tau_L": lambda: m_L * G * x_p,
            "tau_R": lambda: m_R * G * (LENGTH - x_p),
            "tau_net": lambda: G * _torque_per_g(x),
            "MA": lambda: _mechanical_advantage(x_p),
            "state": lambda: _state(x, with_bar=False),
            "x_star": lambda: _balance_point(x, with_bar=False),
            "fulcrum_x0": lambda: x_p - FULCRUM_HALF_WIDTH,
            "fulcrum_x1": lambda: x_p + FULCRUM_HALF_WIDTH,
            "left_block_x0": lambda: -0.5 * side_L,
            "left_block_x1": lambda: 0.5 * side_L,
            "right_block_x0": lambda: LENGTH - 0.5 * side_R,
            "right_block_x1": lambda: LENGTH + 0.5 * side_R,
            "marker_x0": lambda: _balance_point(x, with_bar=False) - MARKER_HALF_WIDTH,
            "marker_x1": lambda: _balance_point(x, with_bar=False) + MARKER_HALF_WIDTH,
            "tau_b": lambda: x["m_b"] * G * (x_p - 0.5 * LENGTH),
            "tau_net_bar": lambda: G * _torque_per_g(x, with_bar=True),
            "state_bar": lambda: _state(x, with_bar=True),
            "x_star_bar": lambda: _balance_point(x, with_bar=True),
            "marker_x0_bar": lambda: _balance_point(x, with_bar=True) - MARKER_HALF_WIDTH,
            "marker_x1_bar": lambda: _balance_point(x, with_bar=True) + MARKER_HALF_WIDTH,
            "inertia": lambda: _inertia(x, bar),
            "t_stop": lambda: _time_to_stop(x, bar),
            "omega_stop": lambda: _angular_velocity_at_stop(x, bar),
        }
        for suffix, with_bar in (("", False), ("_bar", True)):
            formulas.update(_tilt_formulas(x, suffix, with_bar, side_L, side_R))
        return {name: formulas[name]() for name in wanted}


def _torque_per_g(x, with_bar: bool = False):
    """Net torque over g, m_L x_p − m_R (ℓ − x_p) [+ m_b (x_p − ℓ/2)], computed directly (0.0 at balance)."""
    x_p = x["x_p"]
    masses = x["m_L"] * x_p - x["m_R"] * (LENGTH - x_p)
    return masses + x["m_b"] * (x_p - 0.5 * LENGTH) if with_bar else masses


def _total_mass(x, with_bar: bool):
    return x["m_L"] + x["m_R"] + x["m_b"] if with_bar else x["m_L"] + x["m_R"]


def _balance_point(x, with_bar: bool):
    """x* = ℓ m_R / (m_L + m_R): the centre of mass; the bar adds m_b at ℓ/2."""
    heavy_right = x["m_R"] + 0.5 * x["m_b"] if with_bar else x["m_R"]
    return LENGTH * heavy_right / _total_mass(x, with_bar)


def _state(x, with_bar: bool):
    """Balanced iff |x_p − x*| ≤ tolerance; else the bar tips towards the side of the centre of mass."""
    # |x_p − x*| = |τ/g| / M: compare torques, no subtraction of nearly equal positions.
    torque = _torque_per_g(x, with_bar)
    allowed = x["balance_tolerance"] * (1.0 + BALANCE_SLACK) * _total_mass(x, with_bar)
    return np.where(np.abs(torque) <= allowed, BALANCED, np.where(torque > 0, TIPS_LEFT, TIPS_RIGHT))


def _mechanical_advantage(x_p):
    """MA = x_p / (ℓ − x_p): +∞ with the pivot at the right end, never NaN."""
    right_arm = LENGTH - x_p  # exact for x_p in [ℓ/2, ℓ] (Sterbenz), so 0 only at x_p = ℓ
    return np.divide(x_p, right_arm, out=np.full(np.shape(x_p), np.inf), where=right_arm > 0)


def _block_side(mass):
    return BLOCK_SIDE_PER_CUBE_ROOT_KG * np.cbrt(mass)


def _tilt_formulas(x, suffix: str, with_bar: bool, side_L, side_R) -> dict:
    """Heights of the drawn bar and of the blocks standing on its ends, leaning towards the side that wins."""

    def slope():
        state = _state(x, with_bar)
        # Tipping left turns the bar counter-clockwise: it rises to the right.
        return np.select([state == TIPS_LEFT, state == TIPS_RIGHT], [DRAWN_SLOPE, -DRAWN_SLOPE], 0.0)

    # The tilt is drawn as a small-angle shear of the level picture about the pivot: the ends stay at
    # x = 0 and ℓ and the blocks' sides stay vertical (a rotation by 5° would move the ends in by
    # under 8 mm, about a pixel), so every block corner keeps its x and only its height changes.
    def height(at):
        return lambda: slope() * (at - x["x_p"])

    def above(at, side):
        return lambda: slope() * (at - x["x_p"]) + side

    formulas = {f"y_left{suffix}": height(0.0), f"y_right{suffix}": height(LENGTH)}
    for block, centre, side in (("left", 0.0, side_L), ("right", LENGTH, side_R)):
        for edge, at in (("0", centre - 0.5 * side), ("1", centre + 0.5 * side)):
            formulas[f"{block}_block_bottom{edge}{suffix}"] = height(at)
            formulas[f"{block}_block_top{edge}{suffix}"] = above(at, side)
    return formulas


def _inertia(x, with_bar: bool = False):
    """Moment of inertia about the pivot: the two point masses [+ the uniform bar, m_b(ℓ²/12 + (ℓ/2 − x_p)²)]."""
    masses = x["m_L"] * x["x_p"] ** 2 + x["m_R"] * (LENGTH - x["x_p"]) ** 2
    return masses + x["m_b"] * (LENGTH**2 / 12.0 + (0.5 * LENGTH - x["x_p"]) ** 2) if with_bar else masses


def _tipping_integral(theta):
    """∫₀^θ dφ/√(sin φ) for 0 < θ ≤ π/2, in closed form: √2 F(ψ | ½) with tan ψ = √(2 sin θ/(1 − sin θ)).

    This is Legendre's complement of √2 (K(½) − F(arccos √(sin θ) | ½)), which cancels as θ → 0.
    """
    sine = np.sin(theta)
    psi = np.where(sine < 1.0, np.arctan(np.sqrt(2.0 * sine / np.maximum(1.0 - sine, np.finfo(float).tiny))), np.pi / 2)
    return math.sqrt(2.0) * ellipkinc(psi, 0.5)


def _moving_torque(x, with_bar: bool = False):
    """The net torque that sets the bar turning, with the roundoff of an exact balance set to 0.

    m_L x_p − m_R (ℓ − x_p) carries at most about 3ε (m_L x_p + m_R (ℓ − x_p)) of rounding; a
    residue that small is a balance (e.g. 0.3 kg · 0.5 m against 0.1 kg · 1.5 m), not a slow tip
    that would take 10⁷ s. On the slider grids a true imbalance is at least 0.001 kg·m. The bar's
    own weight acts at its middle: m_b (x_p − ℓ/2), a torque that also scales with cos θ.
    """
    per_g = _torque_per_g(x, with_bar)
    arms = x["m_L"] * x["x_p"] + x["m_R"] * (LENGTH - x["x_p"])
    roundoff = 4.0 * EPS * (arms + x["m_b"] * np.abs(x["x_p"] - 0.5 * LENGTH) if with_bar else arms)
    return np.where(np.abs(per_g) <= roundoff, 0.0, G * per_g)


def _time_to_stop(x, with_bar: bool = False):
    """Time from rest to the stop: I θ'' = τ cos θ has the first integral ½ I θ'² = τ sin θ, so
    t = √(I / 2|τ|) ∫₀^θs dφ/√(sin φ); ∞ when there is no net torque (the bar never moves)."""
    torque = np.abs(_moving_torque(x, with_bar))
    scale = np.divide(_inertia(x, with_bar), 2.0 * torque, out=np.full(np.shape(torque), np.inf), where=torque > 0)
    # θ_s takes a handful of values over a whole grid: evaluate the elliptic integral once for each.
    angles, where = np.unique(np.radians(x["theta_s"]), return_inverse=True)
    return np.sqrt(scale) * _tipping_integral(angles)[where].reshape(scale.shape)


def _angular_velocity_at_stop(x, with_bar: bool = False):
    """ω at the stop from ½ I ω² = τ sin θs; positive when the bar turns counter-clockwise (left end down)."""
    torque = _moving_torque(x, with_bar)
    speed = np.sqrt(2.0 * np.abs(torque) * np.sin(np.radians(x["theta_s"])) / _inertia(x, with_bar))
    return np.copysign(speed, torque) + 0.0  # + 0.0: no signed zero when the bar stays put
