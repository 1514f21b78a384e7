"""I3's plane: the points A and B, the chord and the arc between them, the spring's force, and the
work along a path by Gauss-Legendre quadrature (the independent second method the closed forms are held to)."""

from __future__ import annotations

import numpy as np

G = 9.81  # m/s², the book's value (docs/physics/README.md)
HALF_CHORD = 1.0  # A = (-1, 0), B = (1, 0): both on the line y = 0
CHORD = 2.0 * HALF_CHORD
H_MAX = 2.0 * CHORD  # beyond this the arc nearly closes (sin θ -> 0); so h is kept <= 2c
SPRING, DRAG = 0, 1
DIRECT, ARC = 0, 1
GAUSS_NODES = 32  # per smooth piece; 16 is not enough near the rest-length singularity (docs/physics/work.md)
ARC_POINTS = 33  # at h = 2 the polygon strays 3 mm (a quarter pixel) from the circle


def arc_half_angle(h):
    """θ = 2 arctan(2h/c), the half-angle the arc subtends at its centre (0 for the flat arc)."""
    return 2.0 * np.arctan(2.0 * np.asarray(h, float) / CHORD)


def arc_length(h):
    """c θ / sin θ, written as c / sinc(θ/π) so that it is exactly c at h = 0 (no 0/0)."""
    return CHORD / np.sinc(arc_half_angle(h) / np.pi)


def path_length(arc, h):
    """Length of the chosen path: the arc's c / sinc(θ/π), or the chord c."""
    return np.where(arc, arc_length(h), CHORD)


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


def line_integral_work(
    force, path, h, *, k=1.0, x_c=0.0, ell0=None, drag=1.0, mass=None, n=GAUSS_NODES, split=True, tol=None
):
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
    return _gauss_piece(integrand, lo, mid, nodes, weights, tol, depth + 1) + _gauss_piece(
        integrand, mid, hi, nodes, weights, tol, depth + 1
    )
