"""I2: a 1-D collision with restitution, in the cancellation-safe centre-of-mass form.

Effects (docs/physics/collision.md): `restitution_law`, the instantaneous law v2f − v1f = −e(v2i − v1i), is the
default; `contact_spring_dashpot` replaces it by a finite contact (contact.py: a spring k_c and a
dashpot c_d, ending when the overlap closes) whose restitution e = exp(−ζπ/√(1 − ζ²)) then enters
the same centre-of-mass formulas in place of the `e` slider; `explosive` allows e > 1 (the bodies
separate faster than they met: energy is released at the contact).
"""

from __future__ import annotations

import numpy as np

from ...physics import contact
from ...physics.base import Model, Output, Param
from ...physics.structure import Choose, Coord, Poly, Ratio, Threshold, param

COLLISION, SEPARATING = 0, 1
CONTACT = "contact_spring_dashpot"
CURVE_SAMPLES = 48  # the drawn contact force: this many even steps over the contact, plus its peak
CURVE_SIZE = CURVE_SAMPLES + 4  # ... and the polygon's corners (0, 0) and (t_c, 0)
_WITH_CONTACT = ((CONTACT, ("k_c", "c_d")),)  # the contact's restitution depends on k_c and c_d


def _law(form):
    """An exact form of the instantaneous law; with the contact, e is a function of four sliders:
    the output is then tabulated per stop."""
    return lambda effects: None if CONTACT in effects else form


# --- exact forms for the page (docs/physics/collision.md) -------------------------------------
# With s = 1/(m1 + m2) as a coordinate every output is a polynomial of low degree in
# (m1, m2, v1i, v2i, e, s): v_f = s (m1 v1i + m2 v2i ∓ e m2,1 Δ) is multilinear. s depends on the
# masses only through their sum, so its table is one row along m1 + m2.
INV_TOTAL = Coord("inv_total_mass", ("m1", "m2"), lambda m1, m2: 1.0 / (m1 + m2))
_M1, _M2, _V1, _V2, _E = (param(n) for n in ("m1", "m2", "v1i", "v2i", "e"))


def _v1f_colliding(c):
    return c["inv_total_mass"] * (c["m1"] * c["v1i"] + c["m2"] * c["v2i"] - c["e"] * c["m2"] * (c["v1i"] - c["v2i"]))


def _v2f_colliding(c):
    return c["inv_total_mass"] * (c["m1"] * c["v1i"] + c["m2"] * c["v2i"] + c["e"] * c["m1"] * (c["v1i"] - c["v2i"]))


def _kinetic_before(c):
    return 0.5 * c["m1"] * c["v1i"] ** 2 + 0.5 * c["m2"] * c["v2i"] ** 2


def _kinetic_lost(c):
    return 0.5 * c["m1"] * c["m2"] * c["inv_total_mass"] * (1 - c["e"]) * (1 + c["e"]) * (c["v1i"] - c["v2i"]) ** 2


def _momentum_after(c):
    return c["m1"] * _v1f_colliding(c) + c["m2"] * _v2f_colliding(c)


_MULTILINEAR = ((_M1, 1), (_M2, 1), (_V1, 1), (_V2, 1), (_E, 1), (INV_TOTAL, 1))
_QUADRATIC_IN_V_AND_E = ((_M1, 1), (_M2, 1), (INV_TOTAL, 1), (_V1, 2), (_V2, 2), (_E, 2))
# Interpolating v1i − v2i may leave ±1e−16 where the two are equal; on any slider grid a true
# approach speed is many orders larger, so "approaching" is v1i − v2i > 1e−9 m/s (verified per scene).
_STATUS = Threshold(Poly(lambda c: c["v1i"] - c["v2i"], ((_V1, 1), (_V2, 1))), (1e-9,), (SEPARATING, COLLISION))
_K_BEFORE = Poly(_kinetic_before, ((_M1, 1), (_M2, 1), (_V1, 2), (_V2, 2)))
_K_AFTER = Choose(_STATUS, (Poly(lambda c: _kinetic_before(c) - _kinetic_lost(c), _QUADRATIC_IN_V_AND_E), _K_BEFORE))


def _passing(name: str) -> Poly:
    return Poly(lambda c: c[name], ((param(name), 1),))


class Collision(Model):
    """Body 1 starts left of body 2; they collide only if v1i > v2i (approaching)."""

    name = "collision"
    title = "Collision with restitution"
    params = (
        Param("m1", "m<sub>1</sub>", "kg", 1.0, lo=0.0, lo_open=True, description="mass of body 1"),
        Param("m2", "m<sub>2</sub>", "kg", 2.0, lo=0.0, lo_open=True, description="mass of body 2"),
        Param("v1i", "v<sub>1i</sub>", "m/s", 3.0, description="initial velocity of body 1"),
        Param("v2i", "v<sub>2i</sub>", "m/s", -1.0, description="initial velocity of body 2"),
        Param("e", "e", "", 1.0, lo=0.0, hi=1.0, description="coefficient of restitution")
        .widened_by("explosive", np.inf)
        .replaced_by(CONTACT),
        Param("k_c", "k<sub>c</sub>", "kN/m", 10.0, lo=0.0, lo_open=True, description="contact stiffness").with_effect(
            CONTACT
        ),
        Param("c_d", "c<sub>d</sub>", "N·s/m", 0.0, lo=0.0, description="contact damping").with_effect(CONTACT),
    )
    _all = ("m1", "m2", "v1i", "v2i", "e")
    _initial = ("m1", "m2", "v1i", "v2i")
    _contact = ("m1", "m2", "k_c", "c_d")
    outputs = (
        Output(
            "v1f",
            "v<sub>1f</sub>",
            "m/s",
            _all,
            deps_with=_WITH_CONTACT,
            structure=_law(Choose(_STATUS, (Poly(_v1f_colliding, _MULTILINEAR), _passing("v1i")))),
        ),
        Output(
            "v2f",
            "v<sub>2f</sub>",
            "m/s",
            _all,
            deps_with=_WITH_CONTACT,
            structure=_law(Choose(_STATUS, (Poly(_v2f_colliding, _MULTILINEAR), _passing("v2i")))),
        ),
        Output(
            "v_cm",
            "V (centre of mass)",
            "m/s",
            _initial,
            structure=Poly(
                lambda c: c["inv_total_mass"] * (c["m1"] * c["v1i"] + c["m2"] * c["v2i"]),
                _MULTILINEAR[:4] + _MULTILINEAR[5:],
            ),
        ),
        Output(
            "p_before",
            "p before",
            "kg·m/s",
            _initial,
            decimals=2,
            structure=Poly(lambda c: c["m1"] * c["v1i"] + c["m2"] * c["v2i"], _MULTILINEAR[:4]),
        ),
        Output(
            "p_after",
            "p after",
            "kg·m/s",
            _all,
            decimals=2,
            deps_with=_WITH_CONTACT,
            structure=_law(
                Choose(
                    _STATUS,
                    (
                        Poly(_momentum_after, ((_M1, 2), (_M2, 2)) + _MULTILINEAR[2:]),
                        Poly(lambda c: c["m1"] * c["v1i"] + c["m2"] * c["v2i"], _MULTILINEAR[:4]),
                    ),
                )
            ),
        ),
        Output("K_before", "K before", "J", _initial, decimals=2, structure=_K_BEFORE),
        Output("K_after", "K after", "J", _all, decimals=2, deps_with=_WITH_CONTACT, structure=_law(_K_AFTER)),
        Output(
            "K_lost",
            "K lost",
            "J",
            _all,
            decimals=2,
            deps_with=_WITH_CONTACT,
            structure=_law(Choose(_STATUS, (Poly(_kinetic_lost, _QUADRATIC_IN_V_AND_E), Poly(lambda c: 0.0, ())))),
        ),
        Output(
            "K_kept_pct",
            "K kept",
            "%",
            _all,
            decimals=1,
            deps_with=_WITH_CONTACT,
            structure=_law(Ratio(_K_AFTER, _K_BEFORE, scale=100.0, when_zero=100.0)),
        ),
        Output(
            "status",
            "status",
            "",
            ("v1i", "v2i"),
            labels=("collision", "no collision — bodies separating (or at rest relative to each other)"),
            structure=_STATUS,
        ),
        # contact_spring_dashpot: the contact's duration, restitution and force.
        Output(
            "t_contact",
            "contact time t<sub>c</sub>",
            "ms",
            _contact,
            decimals=2,
            special="∞ (overdamped: the bodies never separate)",
            effect=CONTACT,
        ),
        Output("zeta", "damping ratio ζ", "", _contact, decimals=3, effect=CONTACT),
        Output("e_contact", "e of the contact", "", _contact, decimals=3, effect=CONTACT),
        Output("J", "impulse J on body 2", "N·s", _all, decimals=3, deps_with=_WITH_CONTACT, effect=CONTACT),
        Output("F_max", "peak contact force", "N", _all, decimals=1, deps_with=_WITH_CONTACT, effect=CONTACT),
        Output(
            "contact_t",
            "figure: t of the drawn contact force",
            "ms",
            _contact,
            decimals=3,
            size=CURVE_SIZE,
            effect=CONTACT,
        ),
        Output(
            "contact_F",
            "figure: the drawn contact force",
            "N",
            _all,
            decimals=1,
            size=CURVE_SIZE,
            deps_with=_WITH_CONTACT,
            effect=CONTACT,
        ),
    )
    effects = ("restitution_law", CONTACT, "explosive")

    def _evaluate(self, x, wanted, effects):
        if CONTACT in effects and ({"restitution_law", "explosive"} & effects):
            raise ValueError(
                f"effect `{CONTACT}` replaces the instantaneous restitution law: it excludes "
                "`restitution_law` and `explosive`"
            )
        m1, m2, v1i, v2i = (x[k] for k in self._initial)
        total = m1 + m2
        w1, w2 = m1 / total, m2 / total  # w2 directly, never 1 - w1 (cancellation at extreme ratios)
        delta = v1i - v2i
        approaching = delta > 0
        com = w1 * v1i + w2 * v2i
        impact = Impact(m1 * w2, x, np.where(approaching, delta, 0.0)) if CONTACT in effects else None
        e = impact.restitution() if impact else x["e"]
        # Separating or equal velocities: no contact, so no impulse (v_f is v_i bitwise).
        v1f = np.where(approaching, com - e * w2 * delta, v1i)
        v2f = np.where(approaching, com + e * w1 * delta, v2i)
        formulas = {
            "v1f": lambda: v1f,
            "v2f": lambda: v2f,
            "v_cm": lambda: com,
            "p_before": lambda: m1 * v1i + m2 * v2i,
            "p_after": lambda: m1 * v1f + m2 * v2f,  # computed from v_f: shows conservation
            "K_before": lambda: 0.5 * m1 * v1i**2 + 0.5 * m2 * v2i**2,
            "K_after": lambda: 0.5 * m1 * v1f**2 + 0.5 * m2 * v2f**2,
            # Closed form, not K_before - K_after, which loses all digits when the loss is tiny.
            "K_lost": lambda: np.where(approaching, 0.5 * (m1 * w2) * (1 - e) * (1 + e) * delta**2, 0.0),
            "K_kept_pct": lambda: _kept_percent(m1, m2, v1i, v2i, e, w2, delta, approaching),
            "status": lambda: np.where(approaching, COLLISION, SEPARATING),
            "t_contact": lambda: 1e3 * impact.duration(),
            "zeta": lambda: impact.zeta(),
            "e_contact": lambda: e,
            "J": lambda: (m1 * w2) * (1.0 + e) * np.where(approaching, delta, 0.0),  # μ(1 + e)Δ
            "F_max": lambda: impact.peak(),
            "contact_t": lambda: 1e3 * impact.times(),
            "contact_F": lambda: impact.forces(),
        }
        if impact is None:  # the contact's own outputs do not exist without it (NaN; never evaluated)
            formulas.update({o.name: _absent(o, m1) for o in self.outputs if o.effect == CONTACT})
        return {name: formulas[name]() for name in wanted}


def _absent(output: Output, like):
    """NaN of the output's shape: what an output of an effect the scene did not enable is."""
    return lambda: np.full(np.shape(like) + ((output.size,) if output.size else ()), np.nan)


class Impact:
    """The spring–dashpot contact of reduced mass μ at the approach speed Δ (0 when the bodies separate)."""

    def __init__(self, mu, x, approach):
        self.mu, self.k, self.c, self.approach = mu, 1e3 * x["k_c"], x["c_d"], approach  # k_c is in kN/m

    def zeta(self):
        """The damping ratio ζ = c_d/(2√(k_c μ))."""
        return contact.damping_ratio(self.mu, self.k, self.c)

    def restitution(self):
        """e = exp(−ζπ/√(1 − ζ²)), 0 when ζ ≥ 1."""
        return contact.restitution(self.zeta())

    def duration(self):
        """The contact time (s); it does not depend on how fast the bodies meet."""
        return contact.contact_time(self.mu, self.k, self.c)

    def peak(self):
        """The largest force of the contact (0 when the bodies do not meet)."""
        return contact.peak_force(self.mu, self.k, self.c, self.approach)

    def _samples(self):
        return contact.sample_times(self.mu, self.k, self.c, CURVE_SAMPLES)

    def times(self):
        """The polygon's times: the corner (0, 0), the samples with the peak among them, the corner (end, 0)."""
        samples = self._samples()
        return np.concatenate([samples[..., :1], samples, samples[..., -1:]], axis=-1)

    def forces(self):
        """F at the samples, between the polygon's zero corners."""
        columns = (np.asarray(v, float)[..., None] for v in (self.mu, self.k, self.c, self.approach))
        samples = contact.force(self._samples(), *columns)
        zero = np.zeros(samples.shape[:-1] + (1,))
        return np.concatenate([zero, samples, zero], axis=-1)


def _kept_percent(m1, m2, v1i, v2i, e, w2, delta, approaching):
    """Percentage of the kinetic energy that survives; 100 when nothing moves (nothing is lost)."""
    before = 0.5 * m1 * v1i**2 + 0.5 * m2 * v2i**2
    lost = np.where(approaching, 0.5 * (m1 * w2) * (1 - e) * (1 + e) * delta**2, 0.0)
    fraction_lost = np.divide(lost, before, out=np.zeros_like(before), where=before > 0)
    return 100.0 * (1.0 - fraction_lost)
