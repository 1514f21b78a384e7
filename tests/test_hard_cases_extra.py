"""Hard cases of docs/physics/ that no model test covered: K4 resonance foldover, and K2's quantile default
never touching NumPy's random streams. Tolerances are those of docs/physics/ (README.md for the foldover)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers import resolved_scene

from sitegen.build import needed_outputs
from sitegen.compute.quantize import quantize
from sitegen.compute.tabulate import tabulate_scene
from sitegen.models.bubble.model import Bubble
from sitegen.models.bubble.point import compose
from sitegen.models.bubble.solve import integrate
from sitegen.models.kinetic.model import Kinetic
from sitegen.models.kinetic.walls import QUANTILE, RANDOM, molecules

# --- K4 resonance foldover (docs/physics/bubble.md, hard cases) ----------------------------------
#
# Near its linear resonance a weakly driven bubble's steady response is not a smooth function of f: R_max/R0
# jumps between adjacent points of a fine log-f grid (docs/physics/README.md: 0.168 at 328 kHz; here, with the
# model's argon bubble, vdW core and Keller–Miksis, f0 = 378.9 kHz and the jump is 0.092 at 362–365 kHz).
# Interpolating across it does not converge, so the rule is: tabulate at slider stops only, never interpolate.

FOLD_EFFECTS = ("gas", "vdw_hard_core", "surface_tension", "viscosity", "drive", "keller_miksis")
FOLD_POINT = {"R0": 10.0, "p_a": 0.05}  # 10 µm, p_a = 0.05 p0
CYCLES = 40  # from rest, as docs/physics/README.md ran it
# Three adjacent points of a 129-point log grid over 200–500 kHz, 200·2.5^(i/128) for i = 83, 84, 85.
FINE = [200.0 * 2.5 ** (i / 128) for i in (83, 84, 85)]
DISPLAY_RESOLUTION = 0.5e-4  # R_max/R0 is shown with 4 decimals


def _steady_r_max(f_khz: float, rtol: float) -> float:
    """R_max/R0 over 40 drive cycles from rest at R0 (DOP853 with the model's terms and terminal events)."""
    pb, _ = compose({**Bubble.defaults(), **FOLD_POINT, "f": f_khz}, FOLD_EFFECTS)
    pb = dataclasses.replace(pb, tau_end=CYCLES * 2.0 * math.pi / pb.omega)
    run = integrate(pb, (1.0, 0.0), "DOP853", rtol)
    assert run.status == "ok", run.status
    return max([r for _, r in run.maxima] + [1.0])


@pytest.mark.slow
def test_resonance_response_jumps_between_adjacent_frequencies_so_interpolation_fails():
    """The hazard: across 362.3, 364.9, 367.5 kHz (one 129-point log-f step apart) R_max/R0 = 1.1564, 1.2489,
    1.2711: a jump of 0.092 (> 0.05), and the middle one interpolated from its neighbours misses by 0.035,
    700× the display resolution. Both are physics, not solver noise: rtol 1e−9 and 1e−10 agree to 1e−6."""
    low, middle, high = (_steady_r_max(f, 1e-9) for f in FINE)
    assert abs(_steady_r_max(FINE[1], 1e-10) - middle) <= 1e-6
    assert middle - low > 0.05, f"jump {middle - low:.4f}"
    interpolated = low + (high - low) * (math.log(FINE[1] / FINE[0]) / math.log(FINE[2] / FINE[0]))
    assert abs(interpolated - middle) > 100 * DISPLAY_RESOLUTION, (
        f"interpolation error {abs(interpolated - middle):.4f}"
    )


FOLD_SCENE = """\
model: bubble
id: foldover
effects: {effects}
fix R0: 10
fix p_a: 0.05
slider f: 355, 360, 362.3, 364.9, 367.5, 370, 375, 379 default 364.9
readouts: driven_R_max
"""


def _scene():
    return resolved_scene(FOLD_SCENE.format(effects=" ".join(FOLD_EFFECTS)))


def test_resonance_readout_is_tabulated_at_every_stop_never_interpolated():
    """The stable rule: the build evaluates R_max at every f stop near resonance (one table entry per stop,
    no coarser nodes), and each entry is the model's own value at that stop, quantized to its 4 decimals."""
    scene = _scene()
    table = tabulate_scene(scene, ["driven_R_max"])["driven_R_max"]
    axis = scene.axes[scene.axis_index("f")]
    stops = np.array([float(s) for s in axis.stops])
    assert table.shape == (len(stops),) and len(stops) == 8
    direct = Bubble().evaluate({**FOLD_POINT, "f": stops}, wanted=["driven_R_max"], effects=FOLD_EFFECTS)[
        "driven_R_max"
    ]
    expected = quantize(direct, Bubble.output("driven_R_max").decimals, special=True)
    assert [table.at((k,)) for k in range(len(stops))] == expected.tolist()
    assert "driven_R_max" in needed_outputs(scene)


# --- K2 RNG streams: the quantile default is deterministic and independent of NumPy's generators -----------------


def test_quantile_default_never_draws_from_numpys_generators(monkeypatch):
    """docs/physics/kinetic.md: generator streams are not stable across NumPy versions, so the default sampling is the
    quantile sample. With np.random.default_rng made to raise, every readout at the defaults still evaluates
    (bitwise as before), while random mode does reach the generator (so the patch is not vacuous)."""
    assert Kinetic.param("sampling").default == QUANTILE
    names = [o.name for o in Kinetic.outputs if not o.effect]
    before = Kinetic().evaluate(Kinetic.defaults(), wanted=names)
    molecules.cache_clear()

    def forbidden(*args, **kwargs):
        raise AssertionError("the quantile sample drew from np.random")

    monkeypatch.setattr(np.random, "default_rng", forbidden)
    after = Kinetic().evaluate(Kinetic.defaults(), wanted=names)
    for name in names:
        assert np.array_equal(before[name], after[name], equal_nan=True), name
    molecules.cache_clear()
    with pytest.raises(AssertionError, match="np.random"):
        Kinetic().evaluate({**Kinetic.defaults(), "sampling": float(RANDOM)}, wanted=["ratio"])
    molecules.cache_clear()
