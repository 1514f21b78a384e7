"""I1: the impulse of a force pulse on a mass m; by default a symmetric triangle, J = F_pk tau / 2 (closed form).

Effects (physics.md I1): `shape` picks the pulse (triangle, Hann, half-sine or rectangle, each with
its closed-form J); `initial_velocity` adds v0 and the velocity v(t) of the mass; and
`contact_from_collision` replaces the pulse by the force of a spring–dashpot contact (contact.py):
a body of mass m_hit runs into m at the approach speed Δ, and J = μ(1 + e)Δ.
"""
from __future__ import annotations

import numpy as np

from ...physics import contact
from ...physics.base import Model, Output, Param
from ...physics.structure import ChoiceOf, Choose, Coord, Poly, param

SHAPES = ("triangle", "hann", "half_sine", "rectangle")
TRIANGLE = 0
# The drawn pulse: SAMPLES + 1 even times over the pulse (t = τ/2 among them: SAMPLES is even), the
# apex once more, and the polygon's corners (0, 0) and (end, 0) around them.
SAMPLES = 48
CURVE_SIZE = SAMPLES + 4
CONTACT = "contact_from_collision"
_CONTACT_DEPS = ("m", "m_hit", "v_rel", "k_c", "c_d")
_CONTACT_TIME_DEPS = ("m", "m_hit", "k_c", "c_d")


def _triangle(s):
    return np.maximum(0.0, 1.0 - np.abs(2.0 * s - 1.0))


def _hann(s):
    return np.sin(np.pi * s) ** 2


def _half_sine(s):
    return np.sin(np.pi * s)


def _rectangle(s):
    return np.ones_like(s)


def _triangle_rise(s):
    return np.where(s <= 0.5, s * s, 0.5 - (1.0 - s) ** 2)


def _hann_rise(s):
    return s / 2.0 - np.sin(2.0 * np.pi * s) / (4.0 * np.pi)


def _half_sine_rise(s):
    return 2.0 * np.sin(0.5 * np.pi * s) ** 2 / np.pi  # (1 − cos πs)/π without the cancellation at small s


def _rectangle_rise(s):
    return np.asarray(s, float)


# Each shape on 0 <= s = t/τ <= 1 with unit peak: its force F/F_pk, its running integral ∫₀^s F/F_pk ds'
# (so v(t) = v0 + F_pk τ · rise(t/τ)/m) and its area J/(F_pk τ).
SHAPE_FORCE = {"triangle": _triangle, "hann": _hann, "half_sine": _half_sine, "rectangle": _rectangle}
SHAPE_RISE = {"triangle": _triangle_rise, "hann": _hann_rise, "half_sine": _half_sine_rise, "rectangle": _rectangle_rise}
SHAPE_AREA = {"triangle": 0.5, "hann": 0.5, "half_sine": 2.0 / np.pi, "rectangle": 1.0}


def _with_effects(base: tuple[str, ...], shape: bool = True, contact_deps: tuple[str, ...] = _CONTACT_DEPS):
    """deps_with: the shape choice, and the contact's parameters in place of F_pk and τ."""
    return ((("shape", ("shape",)),) if shape else ()) + ((CONTACT, contact_deps),)


# --- exact forms for the page (physics.md I1 "structure"), for the pulse shapes (not the contact) ----
# J = area F_pk τ is trilinear in (F_pk, τ, area of the shape), Δv = J (1/m) adds the axis 1/m, and the
# drawn pulse scales with F_pk (forces) and τ (times): a handful of nodes reproduce every stop.
_FRACTIONS = np.sort(np.concatenate([np.arange(SAMPLES + 1) / SAMPLES, [0.5]]))  # as ShapedPulse samples
_F, _TAU, _V0 = param("F_pk"), param("tau"), param("v0")
_AREA = Coord("shape_area", ("shape",), lambda shape: np.array([SHAPE_AREA[s] for s in SHAPES])[np.rint(shape).astype(int)])
_INV_M = Coord("inv_m", ("m",), lambda m: 1.0 / m)
_PULSE = ((_F, 1), (_TAU, 1), (_AREA, 1))


def _impulse(c):
    return c["shape_area"] * c["F_pk"] * c["tau"]


def _column(value):
    return np.asarray(value, float)[..., None]


def _per_shape(make) -> Choose:
    """One polynomial per pulse shape, chosen by the shape parameter."""
    return Choose(ChoiceOf("shape"), tuple(make(name) for name in SHAPES))


def _unless_contact(form):
    """The exact form for the shaped pulses; the contact's outputs are tabulated per stop."""
    return lambda effects: None if CONTACT in effects else form


def _drawn_forces(name):
    return Poly(lambda c: _polygon_forces(_column(c["F_pk"]) * SHAPE_FORCE[name](_FRACTIONS)), ((_F, 1),), size=CURVE_SIZE)


def _drawn_velocities(name):
    def kernel(c):
        gains = _column(c["F_pk"] * c["tau"] * c["inv_m"]) * SHAPE_RISE[name](_FRACTIONS)
        return _column(c["v0"]) + _polygon_times(gains)
    return Poly(kernel, ((_V0, 1), (_F, 1), (_TAU, 1), (_INV_M, 1)), size=CURVE_SIZE)


class Impulse(Model):
    """A force pulse F(t) acting for a time τ on a mass m (or, with the contact, the force of an impact)."""

    name = "impulse"
    title = "Impulse of a force pulse"
    params = (
        Param("F_pk", "F<sub>pk</sub>", "N", 12.0, lo=0.0, description="peak force").replaced_by(CONTACT),
        Param("tau", "τ", "s", 0.20, lo=0.0, lo_open=True, description="pulse duration").replaced_by(CONTACT),
        Param("m", "m", "kg", 2.0, lo=0.0, lo_open=True, description="mass"),
        Param.choice("shape", "shape", SHAPES, "triangle", description="shape of the pulse").with_effect("shape"),
        Param("v0", "v<sub>0</sub>", "m/s", 0.0, description="velocity before the pulse").with_effect("initial_velocity"),
        Param("m_hit", "m<sub>1</sub>", "kg", 1.0, lo=0.0, lo_open=True, description="mass of the body that strikes m").with_effect(CONTACT),
        Param("v_rel", "Δ", "m/s", 4.0, lo=0.0, description="speed at which the bodies approach").with_effect(CONTACT),
        Param("k_c", "k<sub>c</sub>", "kN/m", 10.0, lo=0.0, lo_open=True, description="contact stiffness").with_effect(CONTACT),
        Param("c_d", "c<sub>d</sub>", "N·s/m", 0.0, lo=0.0, description="contact damping").with_effect(CONTACT),
    )
    _pulse = ("F_pk", "tau")
    _motion = ("F_pk", "tau", "m", "v0")
    outputs = (
        Output("J", "impulse J", "N·s", _pulse, deps_with=_with_effects(_pulse), structure=_unless_contact(Poly(_impulse, _PULSE))),
        Output("dp", "Δp = J", "kg·m/s", _pulse, deps_with=_with_effects(_pulse), structure=_unless_contact(Poly(_impulse, _PULSE))),
        Output("dv", "Δv = J/m", "m/s", ("F_pk", "tau", "m"), deps_with=_with_effects(_pulse),
               structure=_unless_contact(Poly(lambda c: _impulse(c) * c["inv_m"], _PULSE + ((_INV_M, 1),)))),
        # The apex time of the pulse, a vertex of the F(t) figure (exact: tau is on a 0.01 grid); with
        # the contact, the time of its largest force.
        Output("t_apex", "apex time τ/2", "s", ("tau",), decimals=4, deps_with=_with_effects((), False, _CONTACT_TIME_DEPS),
               structure=_unless_contact(Poly(lambda c: 0.5 * c["tau"], ((_TAU, 1),)))),
        Output("F_max", "peak force", "N", ("F_pk",), decimals=2, deps_with=_with_effects((), False),
               structure=_unless_contact(Poly(lambda c: c["F_pk"], ((_F, 1),)))),
        Output("t_contact", "contact time", "s", _CONTACT_TIME_DEPS, decimals=4, special="∞ (overdamped: the bodies never separate)", effect=CONTACT),
        Output("e_contact", "e of the contact", "", _CONTACT_TIME_DEPS, decimals=3, effect=CONTACT),
        Output("v_after", "v after the pulse", "m/s", _motion, deps_with=_with_effects(_motion), effect="initial_velocity",
               structure=_unless_contact(Poly(lambda c: c["v0"] + _impulse(c) * c["inv_m"], ((_V0, 1),) + _PULSE + ((_INV_M, 1),)))),
        # Figure geometry: the drawn pulse as a polygon (t, F), its end, and v(t) at the same times.
        Output("pulse_t", "figure: t of the drawn pulse", "s", ("tau",), decimals=4, size=CURVE_SIZE,
               deps_with=_with_effects((), False, _CONTACT_TIME_DEPS),
               structure=_unless_contact(Poly(lambda c: _polygon_times(_column(c["tau"]) * _FRACTIONS), ((_TAU, 1),), size=CURVE_SIZE))),
        Output("pulse_F", "figure: F of the drawn pulse", "N", ("F_pk",), decimals=2, size=CURVE_SIZE, deps_with=_with_effects(()),
               structure=_unless_contact(_per_shape(_drawn_forces))),
        Output("t_end", "figure: end of the drawn pulse", "s", ("tau",), decimals=4, deps_with=_with_effects((), False, _CONTACT_TIME_DEPS),
               structure=_unless_contact(Poly(lambda c: c["tau"], ((_TAU, 1),)))),
        Output("v_curve", "figure: v at the times of the drawn pulse", "m/s", _motion, size=CURVE_SIZE,
               deps_with=_with_effects(_motion), effect="initial_velocity", structure=_unless_contact(_per_shape(_drawn_velocities))),
    )
    effects = ("shape", "initial_velocity", CONTACT)

    def _evaluate(self, x, wanted, effects):
        if "shape" in effects and CONTACT in effects:
            raise ValueError("effects `shape` and `contact_from_collision` exclude each other: the contact sets the pulse's shape")
        pulse = ContactPulse(x) if CONTACT in effects else ShapedPulse(x, "shape" in effects)
        v0 = x["v0"] if "initial_velocity" in effects else np.zeros_like(x["m"])
        formulas = {
            "J": pulse.impulse,
            "dp": pulse.impulse,  # Newton's second law, integrated: the momentum change is J
            "dv": lambda: pulse.impulse() / x["m"],
            "t_apex": pulse.apex_time,
            "F_max": pulse.peak,
            "t_contact": lambda: pulse.duration(),
            "e_contact": lambda: pulse.restitution(),
            "v_after": lambda: v0 + pulse.impulse() / x["m"],
            "pulse_t": lambda: _polygon_times(pulse.times()),
            "pulse_F": lambda: _polygon_forces(pulse.forces()),
            "t_end": lambda: pulse.times()[..., -1],
            "v_curve": lambda: v0[..., None] + _polygon_times(pulse.gains()) / x["m"][..., None],
        }
        return {name: formulas[name]() for name in wanted}


class ShapedPulse:
    """A pulse of one of SHAPES at each point (the triangle unless the `shape` effect is on)."""

    def __init__(self, x, shaped: bool):
        self.F_pk, self.tau = x["F_pk"], x["tau"]
        self.codes = np.rint(x["shape"]).astype(int) if shaped else np.full(self.F_pk.shape, TRIANGLE)
        self.fractions = np.sort(np.concatenate([np.arange(SAMPLES + 1) / SAMPLES, [0.5]]))  # the apex τ/2 twice

    def _unit_curves(self, table) -> np.ndarray:
        """table[shape](fractions) at every point; each shape present is evaluated once, the others never."""
        out = np.empty(self.codes.shape + self.fractions.shape)
        for code in np.unique(self.codes):
            out[self.codes == code] = table[SHAPES[code]](self.fractions)
        return out

    def impulse(self):
        """J = F_pk τ × the shape's area (F_pk τ/2 for the triangle)."""
        area = np.array([SHAPE_AREA[name] for name in SHAPES])[self.codes]
        return area * self.F_pk * self.tau

    def apex_time(self):
        """τ/2, where every shape has its peak."""
        return 0.5 * self.tau

    def peak(self):
        """The largest force, F_pk."""
        return np.array(self.F_pk, float)

    def duration(self):
        """How long the force acts, τ."""
        return np.array(self.tau, float)

    def restitution(self):
        """A pulse without a contact has no restitution (NaN; the output exists only with the contact)."""
        return np.full(self.tau.shape, np.nan)

    def times(self):
        """The sample times s τ (last axis)."""
        return self.tau[..., None] * self.fractions

    def forces(self):
        """F at the sample times."""
        return self.F_pk[..., None] * self._unit_curves(SHAPE_FORCE)

    def gains(self):
        """∫₀^t F dt' at the sample times (m times the velocity gained)."""
        return (self.F_pk * self.tau)[..., None] * self._unit_curves(SHAPE_RISE)


class ContactPulse:
    """The force of a spring–dashpot contact: m_hit strikes m at speed Δ (contact.py)."""

    def __init__(self, x):
        m, m_hit = x["m"], x["m_hit"]
        self.mu = m_hit * (m / (m_hit + m))
        self.k, self.c, self.approach = 1e3 * x["k_c"], x["c_d"], x["v_rel"]

    def _zeta(self):
        return contact.damping_ratio(self.mu, self.k, self.c)

    def restitution(self):
        """e = exp(−ζπ/√(1 − ζ²)) of the contact."""
        return contact.restitution(self._zeta())

    def impulse(self):
        """J = μ(1 + e)Δ."""
        return self.mu * (1.0 + self.restitution()) * self.approach

    def apex_time(self):
        """The time of the largest force."""
        return contact.peak_time(self.mu, self.k, self.c)

    def peak(self):
        """The largest force."""
        return contact.peak_force(self.mu, self.k, self.c, self.approach)

    def duration(self):
        """The contact time t_c (∞ when overdamped)."""
        return contact.contact_time(self.mu, self.k, self.c)

    def times(self):
        """The sample times over the drawn contact, its peak among them (last axis)."""
        return contact.sample_times(self.mu, self.k, self.c, SAMPLES)

    def _column(self, value):
        return np.asarray(value, float)[..., None]

    def forces(self):
        """F at the sample times."""
        return contact.force(self.times(), *(self._column(v) for v in (self.mu, self.k, self.c, self.approach)))

    def gains(self):
        """∫₀^t F dt' = μ(Δ − δ'(t))."""
        mu, k, c, approach = (self._column(v) for v in (self.mu, self.k, self.c, self.approach))
        return mu * (approach - contact.overlap_rate(self.times(), mu, k, c, approach))


def _polygon_times(samples):
    """Samples along the last axis, with the first and last repeated: the corners (0, 0) and (end, 0)."""
    return np.concatenate([samples[..., :1], samples, samples[..., -1:]], axis=-1)


def _polygon_forces(samples):
    """Forces along the last axis between the zero corners of the polygon."""
    zero = np.zeros(samples.shape[:-1] + (1,))
    return np.concatenate([zero, samples, zero], axis=-1)


def force(t: np.ndarray, F_pk: float, tau: float) -> np.ndarray:
    """The force of the triangular pulse at times `t` (zero outside 0 <= t <= tau)."""
    return F_pk * np.maximum(0.0, 1.0 - np.abs(2.0 * np.asarray(t) / tau - 1.0))


def shaped_force(t: np.ndarray, F_pk: float, tau: float, shape: str) -> np.ndarray:
    """The force of a pulse of the given shape at times `t` (zero outside 0 <= t <= tau)."""
    s = np.asarray(t, float) / tau
    inside = (s >= 0.0) & (s <= 1.0)
    return np.where(inside, F_pk * SHAPE_FORCE[shape](np.clip(s, 0.0, 1.0)), 0.0)


def velocity(t: np.ndarray, F_pk: float, tau: float, m: float, v0: float = 0.0) -> np.ndarray:
    """The velocity of the mass during and after the pulse (piecewise quadratic in t)."""
    t = np.clip(np.asarray(t, float), 0.0, tau)
    rising = F_pk * t**2 / (m * tau)
    falling = (0.5 * F_pk * tau - F_pk * (tau - t) ** 2 / tau) / m
    return v0 + np.where(t <= 0.5 * tau, rising, falling)
