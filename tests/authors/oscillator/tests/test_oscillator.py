"""The author's tests of the book's oscillator: against a second method (the equation of motion
integrated from rest), and the contract every build checks (deps, the figure's references)."""

from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from sitegen.testing import book_model, deps_problems, scene_problems

BOOK = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def oscillator():
    return book_model("oscillator", BOOK)


def _integrated(f0, zeta, f, x_st, t):
    """x(t) from rest, by integrating x'' = -2ζω₀x' - ω₀²(x - x_st cos ωt) (DOP853, rtol 1e-11)."""
    w0, w = 2 * np.pi * f0, 2 * np.pi * f
    run = solve_ivp(lambda s, y: (y[1], -2 * zeta * w0 * y[1] - w0**2 * (y[0] - x_st * np.cos(w * s))),
                    (0, t), (0.0, 0.0), method="DOP853", rtol=1e-11, atol=1e-11, t_eval=[t])
    return run.y[0, -1]


@pytest.mark.parametrize("zeta, f, t", [(0.1, 1.0, 5.0), (0.4, 0.7, 2.5), (0.8, 2.3, 12.0)], ids=["resonant", "below", "above"])
def test_the_motion_from_rest_is_what_the_equation_of_motion_gives(oscillator, zeta, f, t):
    out = oscillator.evaluate({"zeta": zeta, "f": f, "t": t, "x_st": 25.0}, ["x_now"])
    assert out["x_now"] == pytest.approx(_integrated(1.0, zeta, f, 25.0, t), abs=1e-6)


def test_at_resonance_the_amplitude_is_x_st_over_two_zeta_a_quarter_period_behind(oscillator):
    out = oscillator.evaluate({"zeta": np.array([0.1, 0.4, 0.8]), "f": 1.0, "x_st": 25.0}, ["X", "phase"])
    assert out["X"] == pytest.approx([125.0, 31.25, 15.625], rel=1e-12)
    assert out["phase"] == pytest.approx([90.0] * 3, rel=1e-12)


def test_each_output_declares_what_it_depends_on(oscillator):
    assert deps_problems(oscillator, book=BOOK) == []


def test_the_scenes_fit_their_model_and_figure():
    assert scene_problems(BOOK) == []
