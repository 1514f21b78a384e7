"""The book's pendulum against references: the small-swing limit, the series in the amplitude, and
the period measured by integrating the equation of motion (a second method); then the checks every
build makes, asked for by name (sitegen.testing). Run with `pytest` (`pip install "sitegen[test]"`)."""
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from sitegen.testing import book_model, deps_problems, scene_problems

BOOK = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def pendulum():
    """The model as a build finds it: from the book's models/ folder."""
    return book_model("pendulum", BOOK)


def test_small_swings_have_the_textbook_period(pendulum):
    """T0 = 2π √(L/g), and T tends to it as the amplitude goes to zero."""
    out = pendulum.evaluate({"theta0": 0.01, "L": 2.0, "g": 9.81})
    assert out["T0"] == pytest.approx(2 * np.pi * np.sqrt(2.0 / 9.81), rel=1e-14)
    assert out["T"] == pytest.approx(out["T0"], rel=1e-8)


@pytest.mark.parametrize("degrees", [5, 10, 20], ids=lambda d: f"{d}deg")
def test_moderate_swings_follow_the_series(pendulum, degrees):
    """T/T0 = 1 + θ²/16 + 11θ⁴/3072 + 173θ⁶/737280 + O(θ⁸)."""
    theta = np.radians(degrees)
    series = 1 + theta**2 / 16 + 11 * theta**4 / 3072 + 173 * theta**6 / 737280
    assert pendulum.evaluate({"theta0": degrees}, ["ratio"])["ratio"] == pytest.approx(series, rel=theta**8)


def _integrated_period(theta0: float, length: float, gravity: float) -> float:
    """Four times the time from release at rest to the bottom, by integrating θ'' = -(g/L) sin θ."""
    bottom = lambda t, y: y[0]  # noqa: E731 - solve_ivp's event function
    bottom.terminal, bottom.direction = True, -1
    run = solve_ivp(lambda t, y: (y[1], -gravity / length * np.sin(y[0])), (0, 100), (theta0, 0.0),
                    method="DOP853", rtol=1e-12, atol=1e-12, events=bottom)
    return 4 * run.t_events[0][0]


@pytest.mark.parametrize("degrees", [30, 90, 150, 175], ids=lambda d: f"{d}deg")
def test_the_period_is_what_the_equation_of_motion_gives(pendulum, degrees):
    """The elliptic-integral period equals the period found by integrating the motion."""
    expected = _integrated_period(np.radians(degrees), 1.5, 9.81)
    assert pendulum.evaluate({"theta0": degrees, "L": 1.5, "g": 9.81}, ["T"])["T"] == pytest.approx(expected, rel=1e-9)


def test_the_bob_stays_on_its_circle(pendulum):
    """Every drawn point is at distance L from the pivot, and the bob ends the arc."""
    out = pendulum.evaluate({"theta0": np.array([10.0, 120.0]), "L": np.array([0.5, 2.0])})
    assert np.hypot(out["arc_x"], out["arc_y"]) == pytest.approx(np.array([[0.5], [2.0]]) * np.ones((1, out["arc_x"].shape[1])))
    assert out["arc_x"][:, -1] == pytest.approx(out["bob_x"]) and out["arc_y"][:, -1] == pytest.approx(out["bob_y"])


def test_each_output_declares_exactly_what_it_depends_on(pendulum):
    """Moving a parameter an output's deps leave out never changes it; moving one they name does, somewhere."""
    assert deps_problems(pendulum, book=BOOK) == []


def test_the_scenes_fit_their_model_and_figure():
    """Every page reads, every scene resolves (the figure's layers name outputs and parameters the model has),
    and each scene's outputs change only with what their deps name: what `sitegen build` checks first."""
    assert scene_problems(BOOK) == []
