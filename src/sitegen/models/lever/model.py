"""I4: torques on a bar with a mass at each end, resting on a pivot (closed form).

Sign convention (docs/physics/lever.md): a torque is positive when it turns the bar counter-clockwise,
i.e. when it pushes the left end down. The mechanics (torques, balance, the rotation to the stop) are
in mechanics.py; this module declares the outputs, their exact forms and the figure's geometry.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from ...physics.base import Model, Output, Param
from ...physics.numerics import Measurement, Numerics
from ...physics.structure import Choose, Coord, Poly, Threshold, param
from .mechanics import (
    BALANCE_SLACK,
    BALANCED,
    LENGTH,
    STATES,
    TIPS_LEFT,
    TIPS_RIGHT,
    G,
    angular_velocity_at_stop,
    balance_point,
    mechanical_advantage,
    moment_of_inertia,
    moving_torque,
    time_to_stop,
    tip_state,
    torque_per_g,
)

# Geometry of the figure, in metres in the bar's own frame (the pivot is at height 0). The page
# script only looks values up, so every moving vertex that needs arithmetic is an output.
DRAWN_SLOPE = math.tan(math.radians(5.0))  # how far the drawn bar leans when it tips
BLOCK_SIDE_PER_CUBE_ROOT_KG = 0.16  # block side ∝ m^(1/3): the blocks' volume grows with mass
FULCRUM_HALF_WIDTH = 0.11
MARKER_HALF_WIDTH = 0.05

_POSITION = ("m_L", "m_R", "x_p")
_TILT = _POSITION + ("balance_tolerance",)
_WITH_BAR = ("m_L", "m_R", "x_p", "m_b")
_TILT_WITH_BAR = _WITH_BAR + ("balance_tolerance",)
_ROTATION = _POSITION + ("theta_s",)
_BAR_TURNS_TOO = (("bar_mass", ("m_b",)),)  # with bar_mass the rotation feels the bar's weight and inertia


# --- exact forms for the page (docs/physics/lever.md) ----------------------------------------
# Torques are multilinear in (m_L, m_R, x_p). With s = 1/(m_L + m_R) as a coordinate (one table
# along m_L + m_R) the balance point x* = ℓ m_R s is bilinear, and the state is a threshold on
# (x_p − x*)/tolerance. The drawn tilt is one of three polynomials chosen by that state.
_X_P, _M_L, _M_R = param("x_p"), param("m_L"), param("m_R")
INV_TOTAL = Coord("inv_total_mass", ("m_L", "m_R"), lambda m_L, m_R: 1.0 / (m_L + m_R))
INV_TOLERANCE = Coord(
    "inv_tolerance", ("balance_tolerance",), lambda balance_tolerance: 1.0 / (balance_tolerance * (1.0 + BALANCE_SLACK))
)
SIDE = {
    side: Coord(f"side_{side}", (f"m_{side}",), lambda **m: _block_side(next(iter(m.values())))) for side in ("L", "R")
}


def _offset_in_tolerances(c):
    """(x_p − x*) in units of the (slackened) balance tolerance."""
    return (c["x_p"] - LENGTH * c["m_R"] * c["inv_total_mass"]) * c["inv_tolerance"]


_STATE = Threshold(
    Poly(_offset_in_tolerances, ((_X_P, 1), (_M_R, 1), (INV_TOTAL, 1), (INV_TOLERANCE, 1))),
    (-1.0, 1.0),
    (TIPS_RIGHT, BALANCED, TIPS_LEFT),
)
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
    names = [
        ("y_left", "height of the bar's left end", _tilted_height(0.0)),
        ("y_right", "height of the bar's right end", _tilted_height(LENGTH)),
    ]
    for block, side, centre in (("left", "L", 0.0), ("right", "R", LENGTH)):
        for edge, where, sign in (("0", "left", -0.5), ("1", "right", 0.5)):
            names.append(
                (
                    f"{block}_block_bottom{edge}",
                    f"height of the {block} block's bottom {where} corner",
                    _tilted_height(centre, side, sign),
                )
            )
            names.append(
                (
                    f"{block}_block_top{edge}",
                    f"height of the {block} block's top {where} corner",
                    _tilted_height(centre, side, sign, top=True),
                )
            )
    return tuple(
        Output(
            f"{name}{suffix}",
            f"{label} (as drawn{described})",
            "m",
            deps,
            decimals=3,
            effect=effect,
            structure=None if effect else form,
        )
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
            "balance_tolerance",
            "Δx<sub>p</sub>/2",
            "m",
            0.005,
            lo=0.0,
            hi=0.25 * LENGTH,
            description="how far the pivot may sit from the balance point and "
            "still count as balanced: half the pivot slider's step",
        ),
        Param("m_b", "m<sub>b</sub>", "kg", 1.0, lo=0.0, description="mass of the bar (uniform)").with_effect(
            "bar_mass"
        ),
        Param(
            "theta_s",
            "θ<sub>s</sub>",
            "°",
            15.0,
            lo=0.0,
            hi=90.0,
            lo_open=True,
            description="angle at which the tipping bar hits its stop",
        ).with_effect("rotation_dynamics"),
    )
    outputs = (
        Output(
            "tau_L",
            "τ<sub>L</sub>",
            "N·m",
            ("m_L", "x_p"),
            decimals=2,
            structure=Poly(lambda c: c["m_L"] * G * c["x_p"], ((_M_L, 1), (_X_P, 1))),
        ),
        Output(
            "tau_R",
            "τ<sub>R</sub>",
            "N·m",
            ("m_R", "x_p"),
            decimals=2,
            structure=Poly(lambda c: c["m_R"] * G * (LENGTH - c["x_p"]), ((_M_R, 1), (_X_P, 1))),
        ),
        Output(
            "tau_net",
            "net τ",
            "N·m",
            _POSITION,
            decimals=2,
            structure=Poly(
                lambda c: G * (c["m_L"] * c["x_p"] - c["m_R"] * (LENGTH - c["x_p"])), ((_M_L, 1), (_M_R, 1), (_X_P, 1))
            ),
        ),
        Output(
            "MA",
            "MA = L<sub>L</sub>/L<sub>R</sub>",
            "×",
            ("x_p",),
            decimals=2,
            digits=3,
            special="∞ (pivot at the end)",
        ),
        Output("state", "the bar", "", _TILT, labels=STATES, structure=_STATE),
        Output("x_star", "balance point x*", "m", ("m_L", "m_R"), decimals=3, structure=_shifted_balance_point(0.0)),
        # Figure geometry: the fulcrum, the blocks' sides and the balance-point marker.
        Output(
            "fulcrum_x0",
            "left foot of the fulcrum (as drawn)",
            "m",
            ("x_p",),
            decimals=3,
            structure=Poly(lambda c: c["x_p"] - FULCRUM_HALF_WIDTH, ((_X_P, 1),)),
        ),
        Output(
            "fulcrum_x1",
            "right foot of the fulcrum (as drawn)",
            "m",
            ("x_p",),
            decimals=3,
            structure=Poly(lambda c: c["x_p"] + FULCRUM_HALF_WIDTH, ((_X_P, 1),)),
        ),
        Output("left_block_x0", "left side of the left block (as drawn)", "m", ("m_L",), decimals=3),
        Output("left_block_x1", "right side of the left block (as drawn)", "m", ("m_L",), decimals=3),
        Output("right_block_x0", "left side of the right block (as drawn)", "m", ("m_R",), decimals=3),
        Output("right_block_x1", "right side of the right block (as drawn)", "m", ("m_R",), decimals=3),
        Output(
            "marker_x0",
            "left foot of the balance-point marker (as drawn)",
            "m",
            ("m_L", "m_R"),
            decimals=3,
            structure=_shifted_balance_point(-MARKER_HALF_WIDTH),
        ),
        Output(
            "marker_x1",
            "right foot of the balance-point marker (as drawn)",
            "m",
            ("m_L", "m_R"),
            decimals=3,
            structure=_shifted_balance_point(MARKER_HALF_WIDTH),
        ),
        *_tilt_outputs("", _TILT),
        # bar_mass: the same picture with the bar's own weight acting at its middle.
        Output("tau_b", "τ<sub>b</sub> (bar)", "N·m", ("x_p", "m_b"), decimals=2, effect="bar_mass"),
        Output("tau_net_bar", "net τ (with bar)", "N·m", _WITH_BAR, decimals=2, effect="bar_mass"),
        Output("state_bar", "the bar (with its mass)", "", _TILT_WITH_BAR, labels=STATES, effect="bar_mass"),
        Output("x_star_bar", "balance point x* (with bar)", "m", ("m_L", "m_R", "m_b"), decimals=3, effect="bar_mass"),
        Output(
            "marker_x0_bar",
            "left foot of the balance-point marker (as drawn, with the bar)",
            "m",
            ("m_L", "m_R", "m_b"),
            decimals=3,
            effect="bar_mass",
        ),
        Output(
            "marker_x1_bar",
            "right foot of the balance-point marker (as drawn, with the bar)",
            "m",
            ("m_L", "m_R", "m_b"),
            decimals=3,
            effect="bar_mass",
        ),
        *_tilt_outputs("_bar", _TILT_WITH_BAR, "bar_mass"),
        # rotation_dynamics: released from rest, horizontal, the bar turns until it hits the stop.
        Output(
            "inertia",
            "I (about the pivot)",
            "kg·m²",
            _POSITION,
            decimals=3,
            effect="rotation_dynamics",
            deps_with=_BAR_TURNS_TOO,
        ),
        Output(
            "t_stop",
            "time to hit the stop",
            "s",
            _ROTATION,
            decimals=3,
            special="∞ (no net torque)",
            effect="rotation_dynamics",
            deps_with=_BAR_TURNS_TOO,
        ),
        Output(
            "omega_stop",
            "ω at the stop",
            "rad/s",
            _ROTATION,
            decimals=3,
            effect="rotation_dynamics",
            deps_with=_BAR_TURNS_TOO,
        ),
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
        elliptic = float(time_to_stop(x))
        torque, inertia, stop = (
            abs(float(moving_torque(x))),
            float(moment_of_inertia(x)),
            math.radians(float(x["theta_s"])),
        )
        if torque == 0.0:  # the bar never moves: both say ∞
            return Measurement(
                0.0 if math.isinf(elliptic) else math.inf, 0, "elliptic integral", "DOP853 at rtol 1e-12"
            )
        hit = lambda t, y: y[0] - stop  # noqa: E731
        hit.terminal, hit.direction = True, 1
        horizon = 4.0 * elliptic + 1.0
        run = solve_ivp(
            lambda t, y: (y[1], torque * math.cos(y[0]) / inertia),
            (0.0, horizon),
            (0.0, 0.0),
            method="DOP853",
            rtol=1e-12,
            atol=1e-14 * stop,
            events=hit,
        )
        reference = float(run.t_events[0][0]) if len(run.t_events[0]) else math.inf
        return Measurement(abs(elliptic - reference) / reference, 0, "elliptic integral", "DOP853 at rtol 1e-12")

    def _evaluate(self, x, wanted, effects):
        bar = "bar_mass" in effects  # the rotation includes the bar's weight and inertia only then
        x_p, m_L, m_R = x["x_p"], x["m_L"], x["m_R"]
        side_L, side_R = _block_side(m_L), _block_side(m_R)
        formulas = {
            "tau_L": lambda: m_L * G * x_p,
            "tau_R": lambda: m_R * G * (LENGTH - x_p),
            "tau_net": lambda: G * torque_per_g(x),
            "MA": lambda: mechanical_advantage(x_p),
            "state": lambda: tip_state(x, with_bar=False),
            "x_star": lambda: balance_point(x, with_bar=False),
            "fulcrum_x0": lambda: x_p - FULCRUM_HALF_WIDTH,
            "fulcrum_x1": lambda: x_p + FULCRUM_HALF_WIDTH,
            "left_block_x0": lambda: -0.5 * side_L,
            "left_block_x1": lambda: 0.5 * side_L,
            "right_block_x0": lambda: LENGTH - 0.5 * side_R,
            "right_block_x1": lambda: LENGTH + 0.5 * side_R,
            "marker_x0": lambda: balance_point(x, with_bar=False) - MARKER_HALF_WIDTH,
            "marker_x1": lambda: balance_point(x, with_bar=False) + MARKER_HALF_WIDTH,
            "tau_b": lambda: x["m_b"] * G * (x_p - 0.5 * LENGTH),
            "tau_net_bar": lambda: G * torque_per_g(x, with_bar=True),
            "state_bar": lambda: tip_state(x, with_bar=True),
            "x_star_bar": lambda: balance_point(x, with_bar=True),
            "marker_x0_bar": lambda: balance_point(x, with_bar=True) - MARKER_HALF_WIDTH,
            "marker_x1_bar": lambda: balance_point(x, with_bar=True) + MARKER_HALF_WIDTH,
            "inertia": lambda: moment_of_inertia(x, bar),
            "t_stop": lambda: time_to_stop(x, bar),
            "omega_stop": lambda: angular_velocity_at_stop(x, bar),
        }
        for suffix, with_bar in (("", False), ("_bar", True)):
            formulas.update(_tilt_formulas(x, suffix, with_bar, side_L, side_R))
        return {name: formulas[name]() for name in wanted}


def _block_side(mass):
    return BLOCK_SIDE_PER_CUBE_ROOT_KG * np.cbrt(mass)


def _tilt_formulas(x, suffix: str, with_bar: bool, side_L, side_R) -> dict:
    """Heights of the drawn bar and of the blocks standing on its ends, leaning towards the side that wins."""

    def slope():
        state = tip_state(x, with_bar)
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
