"""I3: the work of a spring (conservative) and of drag (not) from A to B, along the chord or an arc.

Closed forms give every readout: W_spring = U(A) - U(B) on any path, W_drag = -|F| L_path. The line
integral by Gauss-Legendre quadrature (`line_integral_work`, n = 32 per smooth piece, optionally
halved adaptively) is the independent second method the tests hold the closed forms to. The model also computes the vertices of its figure's moving shapes
(paths, force arrows), because a page only looks values up.
"""
from __future__ import annotations

import numpy as np

from ...physics.base import Model, Output, Param
from ...physics.numerics import Measurement, Numerics
from ...physics.structure import ChoiceOf, Choose, Coord, Poly, param

G = 9.81  # m/s², the book's value (physics.md §0.1)
HALF_CHORD = 1.0  # A = (-1, 0), B = (1, 0): both on the line y = 0
CHORD = 2.0 * HALF_CHORD
H_MAX = 2.0 * CHORD  # beyond this the arc nearly closes (sin θ -> 0); physics.md clamps h <= 2c
SPRING, DRAG = 0, 1
DIRECT, ARC = 0, 1
LINEAR, QUADRATIC = 0, 1
CONSERVATIVE, PATH_DEPENDENT = 0, 1
GAUSS_NODES = 32  # per smooth piece; 16 is not enough near the rest-length singularity (physics.md I3)
CLOSED_FORM = "closed-form"  # the only method: every readout is exact


def arc_half_angle(h):
    """θ = 2 arctan(2h/c), the half-angle the arc subtends at its centre (0 for the flat arc)."""
    return 2.0 * np.arctan(2.0 * np.asarray(h, float) / CHORD)


def arc_length(h):
    """c θ / sin θ, written as c / sinc(θ/π) so that it is exactly c at h = 0 (no 0/0)."""
    return CHORD / np.sinc(arc_half_angle(h) / np.pi)


# The figure's moving shapes, in metres. Field arrows sit on a 15 x 9 grid whose spacing (0.3 m) is a
# whole number of anchor-slider steps (0.05 m), so table rows for different anchors repeat (compress).
GRID_X = np.round(-2.1 + 0.3 * np.arange(15), 10)
GRID_Y = np.round(-0.45 + 0.3 * np.arange(9), 10)
ARROW_MAX = 0.27  # the longest field arrow, just under the grid spacing
ARROW_PER_UNIT = ARROW_MAX / 2.5  # length ∝ |F|/k (metres of stretch); above 2.5 m drawn as 2.5 m
ARROW_WIDTH = 0.07  # base of a wedge-shaped arrow (narrower for short arrows)
DRAG_SPACING = 0.3  # one drag arrow per this much path: the longer path carries more of them
DRAG_ARROW, DRAG_WIDTH = 0.2, 0.09
MOST_DRAG_ARROWS = int(np.rint(arc_length(H_MAX) / DRAG_SPACING))
ARC_POINTS = 33  # at h = 2 the polygon strays 3 mm (a quarter pixel) from the circle
HEAD_LENGTH, HEAD_WIDTH = 0.17, 0.13  # the arrowhead at B that shows the direction of travel
HEAD_ROOM = HEAD_LENGTH + 0.05  # the drag arrows keep this much path clear before B
WEDGE_VERTICES = 6  # per arrow drawn by `wedges`
JOIN_Y = GRID_Y.min() - 2.0 * ARROW_MAX  # below every arrow and below the figure's axes: joins run here


# --- exact forms for the page (physics.md I3 "structure"), for the base law without effects --------
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
        Param.choice("path", "path A → B", ("direct", "arc"), "direct", description="the chord or the arc over the top"),
        Param("k", "k", "N/m", 1.0, lo=0.0, lo_open=True, description="spring constant"),
        Param("x_c", "x<sub>c</sub>", "m", 0.0, description="anchor of the spring, on the line through A and B"),
        Param("h", "h", "m", 1.0, lo=0.0, hi=H_MAX, description="height of the arc above the chord (sagitta)"),
        Param("s", "s", "m/s", 1.0, lo=0.0, description="traversal speed"),
        Param("b", "b", "N·s/m", 1.0, lo=0.0, description="linear drag coefficient"),
        Param("ell0", "ℓ<sub>0</sub>", "m", 0.0, lo=0.0, description="rest length of the spring").with_effect("spring_rest_length"),
        Param.choice("drag_law", "drag law", ("linear", "quadratic"), "linear", description="F = −bv or F = −c_q|v|v").with_effect("drag_law"),
        Param("c_q", "c<sub>q</sub>", "kg/m", 1.0, lo=0.0, description="quadratic drag coefficient").with_effect("drag_law"),
        Param("m_g", "m", "kg", 0.1, lo=0.0, description="mass pulled down by gravity").with_effect("gravity"),
    )
    _spring = ("k", "x_c", "ell0")
    _drag = ("s", "b", "drag_law", "c_q")
    _field = ("force", "k", "x_c", "ell0", "m_g")
    _field_size = WEDGE_VERTICES * GRID_X.size * GRID_Y.size
    _drag_size = WEDGE_VERTICES * MOST_DRAG_ARROWS
    outputs = (
        Output("W", "W along path", "J", ("force", "path", "h", *_spring, *_drag), structure=_by_force(_SPRING_WORK, _DRAG_WORK)),
        # U of the conservative forces acting (spring, gravity). Drag has no potential at all, so with
        # drag alone there is no U to speak of: NaN, shown as "—".
        Output("dU", "U(A) − U(B)", "J", ("force", *_spring), special="—", why="this force has no potential energy: its work depends on the path"),
        Output("W_drag", "W by drag", "J", ("force", "path", "h", *_drag), structure=_by_force(Poly(lambda c: 0.0, ()), _DRAG_WORK)),
        Output("verdict", "path-independent?", "", ("force",), labels=("yes — conservative", "no — depends on the path")),
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
        Output("rest_x", "rest-length circle, x", "m", ("force", "x_c", "ell0"), decimals=2, size=ARC_POINTS, ragged=True, effect="spring_rest_length"),
        Output("rest_y", "rest-length circle, y", "m", ("force", "ell0"), decimals=2, size=ARC_POINTS, ragged=True, effect="spring_rest_length"),
    )
    effects = ("spring_rest_length", "drag_law", "gravity")
    # The readouts are closed forms (exact, and bitwise the same on both paths): no numerical method
    # computes them. The build still checks them against the line integral by Gauss–Legendre,
    # n = 32 per smooth piece (physics.md I3), so that a wrong closed form cannot reach a page.
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
        return Measurement(abs(reference - closed), 0, "closed form", f"Gauss–Legendre n = {GAUSS_NODES}, halved to 1e-15 J")

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
            "head_x": lambda: shape("head", lambda: _arrowhead_at_b(arc, x["h"]), 0),
            "head_y": lambda: shape("head", lambda: _arrowhead_at_b(arc, x["h"]), 1),
            "field_x": lambda: shape("field", lambda: _field_arrows(spring, x["k"], x["x_c"], ell0, mass), 0),
            "field_y": lambda: shape("field", lambda: _field_arrows(spring, x["k"], x["x_c"], ell0, mass), 1),
            "drag_x": lambda: shape("drag", lambda: _drag_arrows(spring, arc, x["h"]), 0),
            "drag_y": lambda: shape("drag", lambda: _drag_arrows(spring, arc, x["h"]), 1),
            "anchor_x": lambda: np.where(spring, x["x_c"], np.nan)[..., None],
            "rest_x": lambda: _rest_circle(spring, x["x_c"], x["ell0"], np.cos),
            "rest_y": lambda: _rest_circle(spring, 0.0, x["ell0"], np.sin),
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


def path_length(arc, h):
    """Length of the chosen path: the arc's c / sinc(θ/π), or the chord c."""
    return np.where(arc, arc_length(h), CHORD)


# --- path geometry and the line integral ---------------------------------------------------------------


def arc_points(h, lam=None):
    """Points of the arc at parameters λ in [0, 1] (A at 0, B at 1), at constant speed in λ.

    With ψ = θ(1 - 2λ): x = -(c/2) sin ψ / sin θ and y = c sin(θλ) sin(θ(1 - λ)) / sin θ, written with
    sinc so that every factor stays finite as θ -> 0, where the arc becomes the chord.
    """
    lam = np.linspace(0.0, 1.0, ARC_POINTS) if lam is None else np.asarray(lam, float)
    theta = arc_half_angle(h)[..., None]
    sinc = lambda angle: np.sinc(angle / np.pi)  # noqa: E731
    x = HALF_CHORD * (2.0 * lam - 1.0) * sinc(theta * (1.0 - 2.0 * lam)) / sinc(theta)
    y = CHORD * theta * lam * (1.0 - lam) * sinc(theta * lam) * sinc(theta * (1.0 - lam)) / sinc(theta)
    return x, y


def arc_velocity(h, lam):
    """dr/dλ on the arc: length L along the direction (cos ψ, sin ψ), ψ = θ(1 - 2λ)."""
    theta = arc_half_angle(h)[..., None]
    psi = theta * (1.0 - 2.0 * np.asarray(lam, float))
    length = CHORD / np.sinc(theta / np.pi)
    return length * np.cos(psi), length * np.sin(psi)


def path_points(arc, h, lam):
    """Points r(λ) of the chosen path (the chord or the arc) at parameters λ (last axis)."""
    lam = np.asarray(lam, float)
    arc_x, arc_y = arc_points(h, lam)
    arc = np.asarray(arc)[..., None]
    return np.where(arc, arc_x, HALF_CHORD * (2.0 * lam - 1.0)), np.where(arc, arc_y, 0.0)


def path_velocity(arc, h, lam):
    """dr/dλ of the chosen path at parameters λ (last axis)."""
    arc_vx, arc_vy = arc_velocity(h, lam)
    arc = np.asarray(arc)[..., None]
    return np.where(arc, arc_vx, CHORD), np.where(arc, arc_vy, 0.0)


def spring_force(px, py, k, x_c, ell0=None):
    """F = -k (1 - l0/|r - C|)(r - C) at points (px, py); the zero-rest-length spring when l0 is None."""
    dx, dy = px - x_c, py
    if ell0 is None:
        return -k * dx, -k * dy
    distance = np.hypot(dx, dy)
    # (1 - l0/|d|) d = d - l0 d/|d|. At the anchor itself the direction is undefined; take 0 there.
    ux = np.divide(dx, distance, out=np.zeros_like(distance), where=distance > 0)
    uy = np.divide(dy, distance, out=np.zeros_like(distance), where=distance > 0)
    return -k * (dx - ell0 * ux), -k * (dy - ell0 * uy)


def nearest_to_anchor(arc: bool, h: float, x_c: float) -> float | None:
    """λ of the path's point nearest the anchor, if strictly between A and B, else None.

    On the chord (and the flat arc) that is where the path passes through the anchor, and a
    rest-length spring's force flips direction: the integrand has a jump. On the arc it is where
    the integrand's complex singularity (|r - C| = 0) comes nearest the real λ axis.
    """
    theta = float(arc_half_angle(h)) if arc else 0.0
    if theta == 0.0:
        return (x_c + HALF_CHORD) / CHORD if -HALF_CHORD < x_c < HALF_CHORD else None
    psi = np.arctan2(-x_c * np.sin(theta), np.cos(theta))  # the arc point in the direction of C from the centre
    return 0.5 * (1.0 - psi / theta) if abs(psi) < theta else None


def line_integral_work(force, path, h, *, k=1.0, x_c=0.0, ell0=None, drag=1.0, mass=None, n=GAUSS_NODES, split=True, tol=None):
    """W = ∫ F · dr from A to B by n-point Gauss–Legendre on each smooth piece (one scalar case).

    `force` is SPRING (with an optional rest length, and gravity when `mass` is given) or DRAG of
    magnitude `drag` against the motion. With `split` and a rest length, the path is cut at its
    point nearest the anchor. With `tol`, each piece is halved until halving changes it by <= tol.
    """
    arc = path == ARC

    def integrand(lam):
        px, py = path_points(arc, h, lam)
        vx, vy = path_velocity(arc, h, lam)
        if force != SPRING:
            return -drag * np.hypot(vx, vy)
        fx, fy = spring_force(px, py, k, x_c, ell0)
        return fx * vx + (fy - (0.0 if mass is None else mass * G)) * vy

    cut = nearest_to_anchor(arc, h, x_c) if split and ell0 else None
    edges = (0.0, 1.0) if cut is None else (0.0, cut, 1.0)
    nodes, weights = np.polynomial.legendre.leggauss(n)
    return sum(_gauss_piece(integrand, lo, hi, nodes, weights, tol) for lo, hi in zip(edges[:-1], edges[1:]))


def _adaptive_work(x, effects) -> float:
    """The line integral at one point (scalar inputs) by adaptive Gauss–Legendre, to 1e-15 J per piece."""
    force, path, h = int(x["force"]), int(x["path"]), float(x["h"])
    drag = float(_drag_force(x, effects))
    ell0 = float(x["ell0"]) if "spring_rest_length" in effects else None
    mass = float(x["m_g"]) if "gravity" in effects else None
    if force == SPRING:
        return line_integral_work(SPRING, path, h, k=float(x["k"]), x_c=float(x["x_c"]), ell0=ell0, mass=mass, tol=1e-15)
    gravity = 0.0 if mass is None else line_integral_work(SPRING, path, h, k=0.0, mass=mass, tol=1e-15)
    return line_integral_work(DRAG, path, h, drag=drag, tol=1e-15) + gravity


def _gauss_piece(integrand, lo, hi, nodes, weights, tol, depth=0):
    """Gauss–Legendre over [lo, hi]; with `tol`, halved recursively until the halves agree with the whole."""
    def rule(a, b):
        return (b - a) / 2.0 * float(np.dot(weights, integrand(a + (b - a) * (nodes + 1.0) / 2.0)))

    whole = rule(lo, hi)
    if tol is None:
        return whole
    mid = 0.5 * (lo + hi)
    halves = rule(lo, mid) + rule(mid, hi)
    if abs(halves - whole) <= tol or depth >= 40:
        return halves
    return _gauss_piece(integrand, lo, mid, nodes, weights, tol, depth + 1) + _gauss_piece(integrand, mid, hi, nodes, weights, tol, depth + 1)


# --- the figure's moving shapes --------------------------------------------------------------------------


def wedges(px, py, vx, vy, width, count=None):
    """Arrows along (vx, vy), centred on the points (px, py), drawn as ONE fill-only polygon.

    Each arrow is a thin triangle (left corner, tip, right corner). The outline reaches it by a
    vertical drop from JOIN_Y, below the figure, and goes back the same way, so the joins enclose no
    area; the moves from one drop to the next run along JOIN_Y, outside the axes, where the layer
    is clipped. (Joins between arrows inside the axes leave anti-aliasing hairlines in Chromium;
    vertical ones traversed out and back do not.) Inputs end in an arrow axis; `count` per point
    keeps the first arrows only. The result ends in a vertex axis of 6n, padded with NaN.
    """
    length = np.hypot(vx, vy)
    half = 0.5 * np.minimum(width, 0.6 * length)
    nx = np.divide(-vy, length, out=np.zeros_like(length), where=length > 0) * half
    ny = np.divide(vx, length, out=np.zeros_like(length), where=length > 0) * half
    tail_x, tail_y = px - 0.5 * vx, py - 0.5 * vy
    left_x, left_y = tail_x + nx, tail_y + ny
    drop_y = np.full(left_y.shape, JOIN_Y)
    xs = np.stack([left_x, left_x, tail_x + vx, tail_x - nx, left_x, left_x], axis=-1)
    ys = np.stack([drop_y, left_y, tail_y + vy, tail_y - ny, left_y, drop_y], axis=-1)
    xs, ys = (v.reshape(*v.shape[:-2], -1) for v in (xs, ys))
    used = length.shape[-1] if count is None else np.asarray(count)[..., None]
    valid = np.arange(xs.shape[-1]) < WEDGE_VERTICES * used
    return np.where(valid, xs, np.nan), np.where(valid, ys, np.nan)


def _field_arrows(spring, k, x_c, ell0, mass):
    """The grid of field arrows along the spring force (plus gravity), length ∝ |F|/k, capped.

    Divided by k the spring's field is its stretch vector, the same for every k; so is its picture,
    and the table needs no k axis unless gravity (whose share grows as 1/k) is on. Drag is no field
    (it depends on the motion, not on the place): for drag alone the grid is empty; with gravity it
    shows gravity alone, scaled as if k were 1 N/m.
    """
    gx, gy = (g.ravel() for g in np.meshgrid(GRID_X, GRID_Y))
    sprung = spring[..., None]
    fx, fy = spring_force(gx, gy, 1.0, x_c[..., None], None if ell0 is None else ell0[..., None])
    fx, fy = np.where(sprung, fx, 0.0), np.where(sprung, fy, 0.0)
    if mass is not None:
        fy = fy - mass[..., None] * G / np.where(sprung, k[..., None], 1.0)
    magnitude = np.hypot(fx, fy)
    drawn = np.minimum(ARROW_PER_UNIT * magnitude, ARROW_MAX)
    scale = np.divide(drawn, magnitude, out=np.zeros_like(magnitude), where=magnitude > 0)
    count = np.where(spring if mass is None else True, gx.size, 0)
    return wedges(gx + 0.0 * fx, gy + 0.0 * fy, scale * fx, scale * fy, ARROW_WIDTH, count)


def _drag_arrows(spring, arc, h):
    """Drag arrows on the chosen path, against the motion: one per DRAG_SPACING of its length,
    spread evenly over the path short of the arrowhead at B."""
    length = path_length(arc, h)
    count = np.where(spring, 0, np.rint(length / DRAG_SPACING).astype(int))
    slot = np.arange(MOST_DRAG_ARROWS)
    lam = (slot + 0.5) / np.maximum(count, 1)[..., None] * (1.0 - HEAD_ROOM / length)[..., None]
    px, py = path_points(arc, h, lam)
    vx, vy = path_velocity(arc, h, lam)
    speed = np.hypot(vx, vy)
    return wedges(px, py, -DRAG_ARROW * vx / speed, -DRAG_ARROW * vy / speed, DRAG_WIDTH, count)


def _arrowhead_at_b(arc, h):
    """A triangle with its tip at B, pointing along the chosen path where it arrives."""
    vx, vy = (v[..., 0] for v in path_velocity(arc, h, np.array([1.0])))
    speed = np.hypot(vx, vy)
    ux, uy = vx / speed, vy / speed
    base_x, base_y = HALF_CHORD - HEAD_LENGTH * ux, -HEAD_LENGTH * uy
    half = 0.5 * HEAD_WIDTH
    xs = np.stack([base_x - half * uy, HALF_CHORD + 0.0 * ux, base_x + half * uy], axis=-1)
    ys = np.stack([base_y + half * ux, 0.0 * uy, base_y - half * ux], axis=-1)
    return xs, ys


def _rest_circle(spring, centre, ell0, trig):
    """One coordinate of the circle |r - C| = l0 (empty for drag or l0 = 0): centre + l0 trig(angle)."""
    angle = np.linspace(0.0, 2.0 * np.pi, ARC_POINTS)
    values = np.asarray(centre)[..., None] + ell0[..., None] * trig(angle)
    empty = (~spring | (ell0 == 0))[..., None]
    return np.where(empty, np.nan, values)
