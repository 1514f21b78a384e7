"""I1: the impulse of a force pulse on a mass m; by default a symmetric triangle, J = F_pk tau / 2 (closed form).

Effects (docs/physics/impulse.md): `shape` picks the pulse (triangle, Hann, half-sine or rectangle, each with
its closed-form J); `initial_velocity` adds v0 and the velocity v(t) of the mass; and
`contact_from_collision` replaces the pulse by the force of a spring–dashpot contact (contact.py):
a body of mass m_hit runs into m at the approach speed Δ, and J = μ(1 + e)Δ. The pulses themselves
are in pulses.py; this module declares the outputs and their exact forms.
"""

from __future__ import annotations

import numpy as np

from ...physics.base import Model, Output, Param
from ...physics.structure import ChoiceOf, Choose, Coord, Poly, param
from .pulses import SAMPLES, SHAPE_AREA, SHAPE_FORCE, SHAPE_RISE, SHAPES, ContactPulse, ShapedPulse

CURVE_SIZE = SAMPLES + 4  # the drawn pulse's samples and the polygon's two corners
CONTACT = "contact_from_collision"
_CONTACT_DEPS = ("m", "m_hit", "v_rel", "k_c", "c_d")
_CONTACT_TIME_DEPS = ("m", "m_hit", "k_c", "c_d")


def _with_effects(base: tuple[str, ...], shape: bool = True, contact_deps: tuple[str, ...] = _CONTACT_DEPS):
    """deps_with: the shape choice, and the contact's parameters in place of F_pk and τ."""
    return ((("shape", ("shape",)),) if shape else ()) + ((CONTACT, contact_deps),)


# --- exact forms for the page (docs/physics/impulse.md), for the pulse shapes (not the contact) ----
# J = area F_pk τ is trilinear in (F_pk, τ, area of the shape), Δv = J (1/m) adds the axis 1/m, and the
# drawn pulse scales with F_pk (forces) and τ (times): a handful of nodes reproduce every stop.
_FRACTIONS = np.sort(np.concatenate([np.arange(SAMPLES + 1) / SAMPLES, [0.5]]))  # as ShapedPulse samples
_F, _TAU, _V0 = param("F_pk"), param("tau"), param("v0")
_AREA = Coord(
    "shape_area", ("shape",), lambda shape: np.array([SHAPE_AREA[s] for s in SHAPES])[np.rint(shape).astype(int)]
)
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
    return Poly(
        lambda c: _polygon_forces(_column(c["F_pk"]) * SHAPE_FORCE[name](_FRACTIONS)), ((_F, 1),), size=CURVE_SIZE
    )


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
        Param("v0", "v<sub>0</sub>", "m/s", 0.0, description="velocity before the pulse").with_effect(
            "initial_velocity"
        ),
        Param(
            "m_hit", "m<sub>1</sub>", "kg", 1.0, lo=0.0, lo_open=True, description="mass of the body that strikes m"
        ).with_effect(CONTACT),
        Param("v_rel", "Δ", "m/s", 4.0, lo=0.0, description="speed at which the bodies approach").with_effect(CONTACT),
        Param("k_c", "k<sub>c</sub>", "kN/m", 10.0, lo=0.0, lo_open=True, description="contact stiffness").with_effect(
            CONTACT
        ),
        Param("c_d", "c<sub>d</sub>", "N·s/m", 0.0, lo=0.0, description="contact damping").with_effect(CONTACT),
    )
    _pulse = ("F_pk", "tau")
    _motion = ("F_pk", "tau", "m", "v0")
    outputs = (
        Output(
            "J",
            "impulse J",
            "N·s",
            _pulse,
            deps_with=_with_effects(_pulse),
            structure=_unless_contact(Poly(_impulse, _PULSE)),
        ),
        Output(
            "dp",
            "Δp = J",
            "kg·m/s",
            _pulse,
            deps_with=_with_effects(_pulse),
            structure=_unless_contact(Poly(_impulse, _PULSE)),
        ),
        Output(
            "dv",
            "Δv = J/m",
            "m/s",
            ("F_pk", "tau", "m"),
            deps_with=_with_effects(_pulse),
            structure=_unless_contact(Poly(lambda c: _impulse(c) * c["inv_m"], _PULSE + ((_INV_M, 1),))),
        ),
        # The apex time of the pulse, a vertex of the F(t) figure (exact: tau is on a 0.01 grid); with
        # the contact, the time of its largest force.
        Output(
            "t_apex",
            "apex time τ/2",
            "s",
            ("tau",),
            decimals=4,
            deps_with=_with_effects((), False, _CONTACT_TIME_DEPS),
            structure=_unless_contact(Poly(lambda c: 0.5 * c["tau"], ((_TAU, 1),))),
        ),
        Output(
            "F_max",
            "peak force",
            "N",
            ("F_pk",),
            decimals=2,
            deps_with=_with_effects((), False),
            structure=_unless_contact(Poly(lambda c: c["F_pk"], ((_F, 1),))),
        ),
        Output(
            "t_contact",
            "contact time",
            "s",
            _CONTACT_TIME_DEPS,
            decimals=4,
            special="∞ (overdamped: the bodies never separate)",
            effect=CONTACT,
        ),
        Output("e_contact", "e of the contact", "", _CONTACT_TIME_DEPS, decimals=3, effect=CONTACT),
        Output(
            "v_after",
            "v after the pulse",
            "m/s",
            _motion,
            deps_with=_with_effects(_motion),
            effect="initial_velocity",
            structure=_unless_contact(
                Poly(lambda c: c["v0"] + _impulse(c) * c["inv_m"], ((_V0, 1),) + _PULSE + ((_INV_M, 1),))
            ),
        ),
        # Figure geometry: the drawn pulse as a polygon (t, F), its end, and v(t) at the same times.
        Output(
            "pulse_t",
            "figure: t of the drawn pulse",
            "s",
            ("tau",),
            decimals=4,
            size=CURVE_SIZE,
            deps_with=_with_effects((), False, _CONTACT_TIME_DEPS),
            structure=_unless_contact(
                Poly(lambda c: _polygon_times(_column(c["tau"]) * _FRACTIONS), ((_TAU, 1),), size=CURVE_SIZE)
            ),
        ),
        Output(
            "pulse_F",
            "figure: F of the drawn pulse",
            "N",
            ("F_pk",),
            decimals=2,
            size=CURVE_SIZE,
            deps_with=_with_effects(()),
            structure=_unless_contact(_per_shape(_drawn_forces)),
        ),
        Output(
            "t_end",
            "figure: end of the drawn pulse",
            "s",
            ("tau",),
            decimals=4,
            deps_with=_with_effects((), False, _CONTACT_TIME_DEPS),
            structure=_unless_contact(Poly(lambda c: c["tau"], ((_TAU, 1),))),
        ),
        Output(
            "v_curve",
            "figure: v at the times of the drawn pulse",
            "m/s",
            _motion,
            size=CURVE_SIZE,
            deps_with=_with_effects(_motion),
            effect="initial_velocity",
            structure=_unless_contact(_per_shape(_drawn_velocities)),
        ),
    )
    effects = ("shape", "initial_velocity", CONTACT)

    def _evaluate(self, x, wanted, effects):
        if "shape" in effects and CONTACT in effects:
            raise ValueError(
                "effects `shape` and `contact_from_collision` exclude each other: the contact sets the pulse's shape"
            )
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


def _polygon_times(samples):
    """Samples along the last axis, with the first and last repeated: the corners (0, 0) and (end, 0)."""
    return np.concatenate([samples[..., :1], samples, samples[..., -1:]], axis=-1)


def _polygon_forces(samples):
    """Forces along the last axis between the zero corners of the polygon."""
    zero = np.zeros(samples.shape[:-1] + (1,))
    return np.concatenate([zero, samples, zero], axis=-1)
