"""The vertices of I3's figure's moving shapes, in metres: the field arrows, the drag arrows on the
path, the arrowhead at B and the rest-length circle."""

from __future__ import annotations

import numpy as np

from .paths import ARC_POINTS, H_MAX, HALF_CHORD, G, arc_length, path_length, path_points, path_velocity, spring_force

# Field arrows sit on a 15 x 9 grid whose spacing (0.3 m) is a
# whole number of anchor-slider steps (0.05 m), so table rows for different anchors repeat (compress).
GRID_X = np.round(-2.1 + 0.3 * np.arange(15), 10)
GRID_Y = np.round(-0.45 + 0.3 * np.arange(9), 10)
ARROW_MAX = 0.27  # the longest field arrow, just under the grid spacing
ARROW_PER_UNIT = ARROW_MAX / 2.5  # length ∝ |F|/k (metres of stretch); above 2.5 m drawn as 2.5 m
ARROW_WIDTH = 0.07  # base of a wedge-shaped arrow (narrower for short arrows)
DRAG_SPACING = 0.3  # one drag arrow per this much path: the longer path carries more of them
DRAG_ARROW, DRAG_WIDTH = 0.2, 0.09
MOST_DRAG_ARROWS = int(np.rint(arc_length(H_MAX) / DRAG_SPACING))
HEAD_LENGTH, HEAD_WIDTH = 0.17, 0.13  # the arrowhead at B that shows the direction of travel
HEAD_ROOM = HEAD_LENGTH + 0.05  # the drag arrows keep this much path clear before B
WEDGE_VERTICES = 6  # per arrow drawn by `wedges`
JOIN_Y = GRID_Y.min() - 2.0 * ARROW_MAX  # below every arrow and below the figure's axes: joins run here


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


def field_arrows(spring, k, x_c, ell0, mass):
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


def drag_arrows(spring, arc, h):
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


def arrowhead_at_b(arc, h):
    """A triangle with its tip at B, pointing along the chosen path where it arrives."""
    vx, vy = (v[..., 0] for v in path_velocity(arc, h, np.array([1.0])))
    speed = np.hypot(vx, vy)
    ux, uy = vx / speed, vy / speed
    base_x, base_y = HALF_CHORD - HEAD_LENGTH * ux, -HEAD_LENGTH * uy
    half = 0.5 * HEAD_WIDTH
    xs = np.stack([base_x - half * uy, HALF_CHORD + 0.0 * ux, base_x + half * uy], axis=-1)
    ys = np.stack([base_y + half * ux, 0.0 * uy, base_y - half * ux], axis=-1)
    return xs, ys


def rest_circle(spring, centre, ell0, trig):
    """One coordinate of the circle |r - C| = l0 (empty for drag or l0 = 0): centre + l0 trig(angle)."""
    angle = np.linspace(0.0, 2.0 * np.pi, ARC_POINTS)
    values = np.asarray(centre)[..., None] + ell0[..., None] * trig(angle)
    empty = (~spring | (ell0 == 0))[..., None]
    return np.where(empty, np.nan, values)
