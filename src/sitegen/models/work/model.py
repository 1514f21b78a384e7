"""I3: the work of a spring (conservative) and of drag (not) from A to B, along the chord or an arc.

Closed forms give every readout: W_spring = U(A) - U(B) on any path, W_drag = -|F| L_path. The line
integral by Gauss-Legendre quadrature (`line_integral_work` in paths.py, n = 32 per smooth piece,
optionally halved adaptively) is the independent second method the tests hold the closed forms to. The
model also tabulates the vertices of its figure's moving shapes (shapes.py), because a page only looks
values up.
"""

from __future__ import annotations

import numpy as np

from ...physics.base import Model, Output, Param
from ...physics.numerics import Measurement, Numerics
from ...physics.structure import ChoiceOf, Choose, Coord, Poly, param
from .paths import (
    ARC,
    ARC_POINTS,
    DRAG,
    GAUSS_NODES,
    H_MAX,
    HALF_CHORD,
    SPRING,
    G,
    arc_points,
    line_integral_work,
    path_length,
)
from .shapes import (
    GRID_X,
    GRID_Y,
    MOST_DRAG_ARROWS,
    WEDGE_VERTICES,
    arrowhead_at_b,
    drag_arrows,
    field_arrows,
    rest_circle,
)

LINEAR, QUADRATIC = 0, 1
CONSERVATIVE, PATH_DEPENDENT = 0, 1
CLOSED_FORM = "closed-form"  # the only method: every readout is exact


# --- exact forms for the page (docs/physics/work.md), for the base law without effects --------
# The spring's work 2 k x_c is bilinear (|x_c| <= c/2 on the slider); drag's is -b s L, bilinear in s
# and the path length L, which one small table over (path, h) provides.
PATH_LENGTH = Coord("path_length", ("path", "h"), lambda path, h: path_length(path == ARC, h))


def _spring_work(c):
    return 2.0 * c["k"] * c["x_c"]


def _drag_work(c):
    return -c["b"] * c["s"] * c["path_length"]


def _by_force(spring: Poly, drag: Poly):
    """The output as one polynomial per force, for a scene without effects (else per stop)."""
    form = Choose(ChoiceOf("force"), (spring, drag))
    return lambda effects: None if effects else form


_SPRING_WORK = Poly(_spring_work, ((param("k"), 1), (param("x_c"), 1)))
_DRAG_WORK = Poly(_drag_work, ((param("s"), 1), (param("b"), 1), (PATH_LENGTH, 1)))


class Work(Model):
    """A point moved from A to B at constant speed s, pulled by a spring to C = (x_c, 0) or slowed by drag."""

    name = "work"
    title = "Work, energy and conservation"
    params = (
        Param.choice("force", "force", ("spring", "drag"), "spring", description="the force doing the work"),
        Param.choice(
            "path", "path A → B", ("direct", "arc"), "direct", description="the chord or the arc over the top"
        ),
        Param("k", "k", "N/m", 1.0, lo=0.0, lo_open=True, description="spring constant"),
        Param("x_c", "x<sub>c</sub>", "m", 0.0, description="anchor of the spring, on the line through A and B"),
        Param("h", "h", "m", 1.0, lo=0.0, hi=H_MAX, description="height of the arc above the chord (sagitta)"),
        Param("s", "s", "m/s", 1.0, lo=0.0, description="traversal speed"),
        Param("b", "b", "N·s/m", 1.0, lo=0.0, description="linear drag coefficient"),
        Param("ell0", "ℓ<sub>0</sub>", "m", 0.0, lo=0.0, description="rest length of the spring").with_effect(
            "spring_rest_length"
        ),
        Param.choice(
            "drag_law", "drag law", ("linear", "quadratic"), "linear", description="F = −bv or F = −c_q|v|v"
        ).with_effect("drag_law"),
        Param("c_q", "c<sub>q</sub>", "kg/m", 1.0, lo=0.0, description="quadratic drag coefficient").with_effect(
            "drag_law"
        ),
        Param("m_g", "m", "kg", 0.1, lo=0.0, description="mass pulled down by gravity").with_effect("gravity"),
    )
    _spring = ("k", "x_c", "ell0")
    _drag = ("s", "b", "drag_law", "c_q")
    _field = ("force", "k", "x_c", "ell0", "m_g")
    _field_size = WEDGE_VERTICES * GRID_X.size * GRID_Y.size
    _drag_size = WEDGE_VERTICES * MOST_DRAG_ARROWS
    outputs = (
        Output(
            "W",
            "W along path",
            "J",
            ("force", "path", "h", *_spring, *_drag),
            structure=_by_force(_SPRING_WORK, _DRAG_WORK),
        ),
        # U of the conservative forces acting (spring, gravity). Drag has no potential at all, so with
        # drag alone there is no U to speak of: NaN, shown as "—".
        Output(
            "dU",
            "U(A) − U(B)",
            "J",
            ("force", *_spring),
            special="—",
            why="this force has no potential energy: its work depends on the path",
        ),
        Output(
            "W_drag",
            "W by drag",
            "J",
            ("force", "path", "h", *_drag),
            structure=_by_force(Poly(lambda c: 0.0, ()), _DRAG_WORK),
        ),
        Output(
            "verdict", "path-independent?", "", ("force",), labels=("yes — conservative", "no — depends on the path")
        ),
        Output("L", "path length", "m", ("path", "h")),
        Output("W_g", "W by gravity", "J", (), effect="gravity"),
        # Vertices of the figure's moving shapes: mm for the smooth path (2 decimals make a shallow arc
        # visibly stepped), cm (1/450 of the figure's width) for the arrows.
        Output("arc_x", "arc, x", "m", ("h",), decimals=3, size=ARC_POINTS),
        Output("arc_y", "arc, y", "m", ("h",), decimals=3, size=ARC_POINTS),
        # The chosen path drawn solid: the arc's y (with arc_x) when it is the arc, A and B when it is the chord.
        Output("chosen_arc_y", "chosen arc, y", "m", ("path", "h"), decimals=3, size=ARC_POINTS, ragged=True),
        Output("chord_x", "chosen chord, x", "m", ("path",), decimals=3, size=2, ragged=True),
        Output("head_x", "arrowhead at B, x", "m", ("path", "h"), decimals=3, size=3),
        Output("head_y", "arrowhead at B, y", "m", ("path", "h"), decimals=3, size=3),
        Output("field_x", "field arrows, x", "m", _field, decimals=2, size=_field_size, ragged=True),
        Output("field_y", "field arrows, y", "m", _field, decimals=2, size=_field_size, ragged=True),
        Output("drag_x", "drag arrows, x", "m", ("force", "path", "h"), decimals=2, size=_drag_size, ragged=True),
        Output("drag_y", "drag arrows, y", "m", ("force", "path", "h"), decimals=2, size=_drag_size, ragged=True),
        Output("anchor_x", "anchor, x", "m", ("force", "x_c"), decimals=2, size=1, ragged=True),
        Output(
            "rest_x",
            "rest-length circle, x",
            "m",
            ("force", "x_c", "ell0"),
            decimals=2,
            size=ARC_POINTS,
            ragged=True,
            effect="spring_rest_length",
        ),
        Output(
            "rest_y",
            "rest-length circle, y",
            "m",
            ("force", "ell0"),
            decimals=2,
            size=ARC_POINTS,
            ragged=True,
            effect="spring_rest_length",
        ),
    )
    effects = ("spring_rest_length", "drag_law", "gravity")
    # The readouts are closed forms (exact, and bitwise the same on both paths): no numerical method
    # computes them. The build still checks them against the line integral by Gauss–Legendre,
    # n = 32 per smooth piece (docs/physics/work.md), so that a wrong closed form cannot reach a page.
    numerics = Numerics(CLOSED_FORM, tolerance=1e-12)
    methods = {CLOSED_FORM: {}}
    error_metric = "|ΔW| in J"

    def measure_error(self, values, effects) -> Measurement:
        """The closed-form W at one point against the adaptive line integral.

        Gauss–Legendre n = 32 with pieces halved until they agree to 1e-15 J: a fixed n = 32 is not
        enough on a shallow arc passing close to a rest-length spring's anchor (6e-5 J at
        h = 0.05 m, x_c = -0.95 m, measured).
        """
        x = {k: np.asarray(v, float) for k, v in {**self.defaults(), **values}.items()}
        closed = float(self.evaluate(x, ["W"], effects)["W"])
        reference = _adaptive_work(x, frozenset(effects))
        return Measurement(
            abs(reference - closed), 0, "closed form", f"Gauss–Legendre n = {GAUSS_NODES}, halved to 1e-15 J"
        )

    def _evaluate(self, x, wanted, effects):
        spring = x["force"] == SPRING
        arc = x["path"] == ARC
        ell0 = x["ell0"] if "spring_rest_length" in effects else None
        mass = x["m_g"] if "gravity" in effects else None
        shapes: dict[str, tuple] = {}  # each pair of vertex vectors is computed once for its x and y

        def shape(name, compute, axis):
            return (shapes[name] if name in shapes else shapes.setdefault(name, compute()))[axis]

        def drag():
            return np.where(spring, 0.0, drag_work(_drag_force(x, effects), path_length(arc, x["h"])))

        def released():  # U(A) - U(B) of the conservative forces; for a conservative force it is its work
            return np.where(spring, potential_drop(x["k"], x["x_c"], ell0), 0.0) + gravity_work(mass)

        formulas = {
            "W": lambda: released() + drag(),
            "dU": lambda: np.where(spring | (mass is not None), released(), np.nan),
            "W_drag": drag,
            "verdict": lambda: np.where(spring, CONSERVATIVE, PATH_DEPENDENT),  # the field's kind, never a comparison
            "L": lambda: path_length(arc, x["h"]),
            "W_g": lambda: gravity_work(np.asarray(x["m_g"])),
            "arc_x": lambda: shape("arc", lambda: arc_points(x["h"]), 0),
            "arc_y": lambda: shape("arc", lambda: arc_points(x["h"]), 1),
            "chosen_arc_y": lambda: np.where(arc[..., None], shape("arc", lambda: arc_points(x["h"]), 1), np.nan),
            "chord_x": lambda: np.where(arc[..., None], np.nan, np.array([-HALF_CHORD, HALF_CHORD])),
            "head_x": lambda: shape("head", lambda: arrowhead_at_b(arc, x["h"]), 0),
            "head_y": lambda: shape("head", lambda: arrowhead_at_b(arc, x["h"]), 1),
            "field_x": lambda: shape("field", lambda: field_arrows(spring, x["k"], x["x_c"], ell0, mass), 0),
            "field_y": lambda: shape("field", lambda: field_arrows(spring, x["k"], x["x_c"], ell0, mass), 1),
            "drag_x": lambda: shape("drag", lambda: drag_arrows(spring, arc, x["h"]), 0),
            "drag_y": lambda: shape("drag", lambda: drag_arrows(spring, arc, x["h"]), 1),
            "anchor_x": lambda: np.where(spring, x["x_c"], np.nan)[..., None],
            "rest_x": lambda: rest_circle(spring, x["x_c"], x["ell0"], np.cos),
            "rest_y": lambda: rest_circle(spring, 0.0, x["ell0"], np.sin),
        }
        return {name: formulas[name]() for name in wanted}


# --- closed forms -------------------------------------------------------------------------------------


def potential_drop(k, x_c, ell0=None):
    """U(A) - U(B) of the spring, which is its work on every path from A to B.

    With d_A = |1 + x_c| and d_B = |1 - x_c|: U(A) - U(B) = k (d_A - d_B)(d_A + d_B - 2 l0) / 2, where
    d_A - d_B = 2 clip(x_c, -1, 1) and d_A + d_B = 2 max(1, |x_c|), so nothing cancels.
    """
    reach = np.maximum(HALF_CHORD, np.abs(x_c))
    return 2.0 * k * np.clip(x_c, -HALF_CHORD, HALF_CHORD) * (reach if ell0 is None else reach - ell0)


def gravity_work(mass):
    """-m g (y_B - y_A): gravity's work on any path from A to B; exactly 0 here, and 0.0 without gravity."""
    return 0.0 if mass is None else -mass * G * (0.0 - 0.0)


def _drag_force(x, effects):
    """|F| of the drag at speed s: b s, or c_q s² when the quadratic law is chosen."""
    if "drag_law" not in effects:
        return x["b"] * x["s"]
    return np.where(x["drag_law"] == QUADRATIC, x["c_q"] * x["s"] ** 2, x["b"] * x["s"])


def drag_work(force, length):
    """Work of a drag of constant magnitude `force`, always against the motion, over a path of `length`."""
    return -force * length


def _adaptive_work(x, effects) -> float:
    """The line integral at one point (scalar inputs) by adaptive Gauss–Legendre, to 1e-15 J per piece."""
    force, path, h = int(x["force"]), int(x["path"]), float(x["h"])
    drag = float(_drag_force(x, effects))
    ell0 = float(x["ell0"]) if "spring_rest_length" in effects else None
    mass = float(x["m_g"]) if "gravity" in effects else None
    if force == SPRING:
        return line_integral_work(
            SPRING, path, h, k=float(x["k"]), x_c=float(x["x_c"]), ell0=ell0, mass=mass, tol=1e-15
        )
    gravity = 0.0 if mass is None else line_integral_work(SPRING, path, h, k=0.0, mass=mass, tol=1e-15)
    return line_integral_work(DRAG, path, h, drag=drag, tol=1e-15) + gravity
