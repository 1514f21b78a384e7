"""K1: the middle ear as an ideal lossless transformer: area ratio × lever ratio (closed form).

    G = p_OW/p_TM = ℓ·A_r,  A_r = A_TM/A_FP,  G_dB = 20 log₁₀ G            (a pressure gain)
    T(Z₁, Z₂) = 4Z₁Z₂/(Z₁ + Z₂)²,  T₀ = T(Z_a, Z_c),  T₁ = T(Z_a, Z_c/(ℓ²A_r))  (power transmission)

G_dB is a ratio of pressures (20 log) and 10 log T a ratio of powers: the two are reported side by side
and never added. Effects: `lever` (ℓ; off means ℓ = 1), `area_ratio` (off means the eardrum acts with
the footplate's area, A_r = 1) and `load_model` (off means the water half-space).
"""

from __future__ import annotations

import numpy as np

from ...physics.base import Model, Output, Param
from ...physics.structure import Coord, Log10, Poly, Ratio, param

P_REF = 20e-6  # Pa rms, the reference of SPL
Z_AIR = 1.204 * 343.2  # ρ_a c_a at 20 °C: 413.2 Pa·s/m
Z_WATER = 998.2 * 1482.0  # ρ_w c_w at 20 °C: 1.479e6 Pa·s/m
Z_COCHLEA_ACOUSTIC = 21.1e9  # Pa·s/m³, the measured cochlear input impedance (Aibara et al. 2001), flat 0.1–5 kHz
MM2 = 1e-6  # m² per mm²
FULCRUM_HALF_WIDTH = 0.05  # of the drawn fulcrum, in lengths of the whole bar (malleus + incus arm)
LOADS = ("water", "cochlea")
WATER, COCHLEA = 0, 1


# --- exact forms for the page (docs/physics/ossicles.md: three separable 1-D dB tables)----------------
# With all three effects on, every output over more than two sliders is a low-degree polynomial in
# small one- or two-slider coordinate tables: decibels add, and the load referred to the eardrum is
# a product u Z_a with u = (Z_c A_FP / Z_a) (1/ℓ²) (1/A_TM), so T₁ = 4u/(1 + u)² is a ratio of two
# polynomials in those three coordinates.
ALL_EFFECTS = frozenset({"lever", "area_ratio", "load_model"})
_ELL, _A_TM = param("ell"), param("A_TM")
_INV_A_FP = Coord("inv_A_FP", ("A_FP",), lambda A_FP: 1.0 / A_FP)
_P_TM = Coord("p_TM", ("SPL",), lambda SPL: _pressure(SPL))
_DB = {
    name: Coord(f"dB_{name}", (name,), lambda **v: 20.0 * np.log10(next(iter(v.values()))))
    for name in ("ell", "A_TM", "A_FP")
}
_LOAD_PER_Z_AIR = Coord(
    "load_per_Z_air", ("load", "A_FP"), lambda load, A_FP: load_impedance(load, A_FP) * A_FP / Z_AIR
)
_INV_ELL_SQUARED = Coord("inv_ell_squared", ("ell",), lambda ell: 1.0 / ell**2)
_INV_A_TM = Coord("inv_A_TM", ("A_TM",), lambda A_TM: 1.0 / A_TM)
_SQRT_LOAD = Coord(
    "sqrt_load_per_Z_air", ("load", "A_FP"), lambda load, A_FP: np.sqrt(load_impedance(load, A_FP) * A_FP / Z_AIR)
)
_INV_SQRT_A_TM = Coord("inv_sqrt_A_TM", ("A_TM",), lambda A_TM: 1.0 / np.sqrt(A_TM))
_REFERRED = ((_LOAD_PER_Z_AIR, 1), (_INV_ELL_SQUARED, 1), (_INV_A_TM, 1))
_REFERRED_SQUARED = ((_LOAD_PER_Z_AIR, 2), (_INV_ELL_SQUARED, 2), (_INV_A_TM, 2))


def _referred(c):
    """u = Z_ref / Z_a."""
    return c["load_per_Z_air"] * c["inv_ell_squared"] * c["inv_A_TM"]


def _with_every_effect(form):
    """The exact form, for a scene with the lever, the area ratio and the load model on (else per stop)."""
    return lambda effects: form if effects == ALL_EFFECTS else None


_T1 = Ratio(Poly(lambda c: 4.0 * _referred(c), _REFERRED), Poly(lambda c: (1.0 + _referred(c)) ** 2, _REFERRED_SQUARED))


class Ossicles(Model):
    """Eardrum → malleus/incus lever → stapes footplate, loaded by water or by the measured cochlea."""

    name = "ossicles"
    title = "The middle-ear ossicle lever"
    params = (
        Param(
            "A_TM", "A<sub>TM</sub>", "mm²", 55.0, lo=0.0, lo_open=True, description="effective eardrum area"
        ).with_effect("area_ratio"),
        Param("A_FP", "A<sub>FP</sub>", "mm²", 3.2, lo=0.0, lo_open=True, description="stapes footplate area"),
        Param(
            "ell", "ℓ", "", 1.3, lo=0.0, lo_open=True, description="lever ratio: malleus arm over incus arm"
        ).with_effect("lever"),
        Param("SPL", "input SPL", "dB", 60.0, description="sound pressure level at the eardrum (rms re 20 µPa)"),
        Param.choice(
            "load", "load on the footplate", LOADS, "water", description="water half-space, or the measured cochlea"
        ).with_effect("load_model"),
    )
    _gain = ("ell", "A_TM", "A_FP")
    _load = ("load", "ell", "A_TM", "A_FP")
    outputs = (
        Output(
            "A_r",
            "area ratio A<sub>r</sub>",
            "",
            ("A_TM", "A_FP"),
            decimals=2,
            structure=_with_every_effect(Poly(lambda c: c["A_TM"] * c["inv_A_FP"], ((_A_TM, 1), (_INV_A_FP, 1)))),
        ),
        Output(
            "G",
            "pressure gain G = ℓA<sub>r</sub>",
            "×",
            _gain,
            decimals=2,
            structure=_with_every_effect(
                Poly(lambda c: c["ell"] * c["A_TM"] * c["inv_A_FP"], ((_ELL, 1), (_A_TM, 1), (_INV_A_FP, 1)))
            ),
        ),
        Output(
            "G_dB",
            "pressure gain 20 log₁₀ G",
            "dB",
            _gain,
            decimals=2,
            structure=_with_every_effect(
                Poly(lambda c: c["dB_ell"] + c["dB_A_TM"] - c["dB_A_FP"], tuple((d, 1) for d in _DB.values()))
            ),
        ),
        Output("p_TM", "p at the eardrum", "Pa rms", ("SPL",), decimals=4, digits=4),
        Output(
            "p_OW",
            "p at the oval window",
            "Pa rms",
            ("SPL", *_gain),
            decimals=3,
            digits=4,
            structure=_with_every_effect(
                Poly(
                    lambda c: c["ell"] * c["A_TM"] * c["inv_A_FP"] * c["p_TM"],
                    ((_ELL, 1), (_A_TM, 1), (_INV_A_FP, 1), (_P_TM, 1)),
                )
            ),
        ),
        Output(
            "L_OW",
            "level at the oval window L<sub>p</sub> + 20 log₁₀ G",
            "dB",
            ("SPL", *_gain),
            decimals=2,
            structure=_with_every_effect(
                Poly(
                    lambda c: c["SPL"] + c["dB_ell"] + c["dB_A_TM"] - c["dB_A_FP"],
                    ((param("SPL"), 1), *((d, 1) for d in _DB.values())),
                )
            ),
        ),
        Output("Z_c", "load Z<sub>c</sub> at the footplate", "Pa·s/m", ("load", "A_FP"), decimals=0),
        Output(
            "Z_ref",
            "load seen at the eardrum Z<sub>c</sub>/(ℓ²A<sub>r</sub>)",
            "Pa·s/m",
            _load,
            decimals=0,
            structure=_with_every_effect(Poly(lambda c: Z_AIR * _referred(c), _REFERRED)),
        ),
        Output("T0", "power in, no transformer T<sub>0</sub>", "%", ("load", "A_FP"), decimals=4),
        Output("T0_dB", "10 log₁₀ T<sub>0</sub>", "dB", ("load", "A_FP"), decimals=2),
        Output(
            "T1",
            "power in, with transformer T<sub>1</sub>",
            "%",
            _load,
            decimals=2,
            structure=_with_every_effect(Ratio(_T1.numerator, _T1.denominator, scale=100.0)),
        ),
        Output(
            "T1_dB", "10 log₁₀ T<sub>1</sub>", "dB", _load, decimals=2, structure=_with_every_effect(Log10(_T1, 10.0))
        ),
        Output(
            "ell_match",
            "ℓ for a perfect match",
            "",
            ("load", "A_TM", "A_FP"),
            decimals=2,
            structure=_with_every_effect(
                Poly(lambda c: c["sqrt_load_per_Z_air"] * c["inv_sqrt_A_TM"], ((_SQRT_LOAD, 1), (_INV_SQRT_A_TM, 1)))
            ),
        ),
        # Figure geometry: where the pivot sits on a bar of unit length, and the pistons' effective diameters.
        Output("pivot", "malleus arm / (malleus + incus arm)", "", ("ell",), decimals=3),
        Output("fulcrum_x0", "left foot of the fulcrum (as drawn)", "", ("ell",), decimals=3),
        Output("fulcrum_x1", "right foot of the fulcrum (as drawn)", "", ("ell",), decimals=3),
        Output("span_TM", "eardrum edge, ±√(A<sub>TM</sub>/π)", "mm", ("A_TM",), decimals=2, size=2),
        Output("span_FP", "footplate edge, ±√(A<sub>FP</sub>/π)", "mm", ("A_FP",), decimals=2, size=2),
    )
    effects = ("lever", "area_ratio", "load_model")

    def _evaluate(self, x, wanted, effects):
        ell = x["ell"] if "lever" in effects else np.ones_like(x["ell"])
        # Without the area ratio the eardrum pushes with the footplate's own area.
        A_TM = x["A_TM"] if "area_ratio" in effects else x["A_FP"]
        A_FP = x["A_FP"]
        load = x["load"] if "load_model" in effects else np.full_like(x["load"], WATER)
        area_ratio = A_TM / A_FP
        gain = ell * area_ratio
        Z_c = load_impedance(load, A_FP)
        Z_ref = Z_c / (ell**2 * area_ratio)  # the footplate load referred to the eardrum: /G² in p/U terms
        formulas = {
            "A_r": lambda: area_ratio,
            "G": lambda: gain,
            "G_dB": lambda: 20.0 * np.log10(gain),
            "p_TM": lambda: _pressure(x["SPL"]),
            "p_OW": lambda: gain * _pressure(x["SPL"]),
            "L_OW": lambda: x["SPL"] + 20.0 * np.log10(gain),
            "Z_c": lambda: Z_c,
            "Z_ref": lambda: Z_ref,
            "T0": lambda: 100.0 * transmission(Z_AIR, Z_c),
            "T0_dB": lambda: 10.0 * np.log10(transmission(Z_AIR, Z_c)),
            "T1": lambda: 100.0 * transmission(Z_AIR, Z_ref),
            "T1_dB": lambda: 10.0 * np.log10(transmission(Z_AIR, Z_ref)),
            "ell_match": lambda: np.sqrt(Z_c / (Z_AIR * area_ratio)),
            "pivot": lambda: ell / (ell + 1.0),
            "fulcrum_x0": lambda: ell / (ell + 1.0) - FULCRUM_HALF_WIDTH,
            "fulcrum_x1": lambda: ell / (ell + 1.0) + FULCRUM_HALF_WIDTH,
            "span_TM": lambda: _span(x["A_TM"]),  # as slid; without the area ratio the figure draws span_FP
            "span_FP": lambda: _span(A_FP),
        }
        return {name: formulas[name]() for name in wanted}


def transmission(Z1, Z2):
    """Power transmission 4Z₁Z₂/(Z₁ + Z₂)² between resistive loads; exactly 1 when Z₁ = Z₂."""
    total = Z1 + Z2
    return 4.0 * Z1 * Z2 / (total * total)


def load_impedance(load, A_FP):
    """Specific impedance at the footplate (Pa·s/m): ρ_w c_w, or 21.1 GΩ (acoustic) × A_FP."""
    return np.where(load == COCHLEA, Z_COCHLEA_ACOUSTIC * A_FP * MM2, Z_WATER)


def _pressure(spl):
    """The rms pressure 20 µPa · 10^(SPL/20)."""
    return P_REF * 10.0 ** (np.asarray(spl, float) / 20.0)


def _span(area):
    """(−r, r) with r = √(A/π), the effective radius in mm of a piston of area A (mm²)."""
    radius = np.sqrt(area / np.pi)
    return np.stack([-radius, radius], axis=-1)
