"""I1: the force pulse F(t) with the impulse shaded underneath; with `initial_velocity`, v(t) below it."""

from __future__ import annotations

from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ...render import style as s
from ...render.figures.base import param_range, table_range
from ...render.layers import Layer
from .model import CONTACT

FAR = 1e3  # s: the velocity after the pulse is drawn flat to here (clipped at the panel's edge)
SHAPE_WORDS = {
    "triangle": "a triangular",
    "hann": "a Hann (sine-squared)",
    "half_sine": "a half-sine",
    "rectangle": "a rectangular",
}


class ImpulseFigure:
    """F(t) of the pulse with the impulse shaded underneath (and, with v0, the velocity it produces)."""

    label = "Force against time for a triangular pulse; the shaded area under the curve is the impulse J."

    def describe(self, scene) -> str:
        """The label, naming the pulse the scene's effects choose and the velocity panel when there is one."""
        if CONTACT in scene.effects:
            pulse = "Force against time during the contact of two colliding bodies (a spring and a dashpot)"
        elif "shape" in scene.effects:
            pulse = "Force against time for a force pulse of the chosen shape"
        else:
            return self.label if "initial_velocity" not in scene.effects else self.label[:-1] + self._velocity_words()
        text = pulse + "; the shaded area under the curve is the impulse J."
        return text[:-1] + self._velocity_words() if "initial_velocity" in scene.effects else text

    @staticmethod
    def _velocity_words() -> str:
        return ". Below: the velocity of the mass against time, rising by J/m during the pulse."

    def layers(self, scene):
        area = {"fill": s.FILL_BLUE, "fill-opacity": "0.75", "stroke": "none"}
        curve = {"fill": "none", "stroke": s.BLUE, "stroke-width": "2.2"}
        if _sampled(scene):
            pulse = [
                Layer("area", "polygon", 0, xs="out:pulse_t", ys="out:pulse_F", style=area),
                Layer("pulse", "polyline", 0, xs="out:pulse_t", ys="out:pulse_F", style=curve),
            ]
        else:
            apex = ("out:t_apex", "in:F_pk")
            vertices = ((0.0, 0.0), apex, ("in:tau", 0.0))
            pulse = [
                Layer("area", "polygon", 0, vertices, style=area),
                Layer("pulse", "polyline", 0, vertices, style=curve),
            ]
        if "initial_velocity" not in scene.effects:
            return pulse
        velocity = {"fill": "none", "stroke": s.ORANGE, "stroke-width": "2.2"}
        return pulse + [
            Layer("velocity", "polyline", 1, xs="out:pulse_t", ys="out:v_curve", style=velocity),
            Layer(
                "velocity-after", "polyline", 1, (("out:t_end", "out:v_after"), (FAR, "out:v_after")), style=velocity
            ),
        ]

    def draw(self, scene, tables, narrow=False):
        with_velocity = "initial_velocity" in scene.effects
        if with_velocity:
            fig, named = s.new_mosaic(
                4.6 if narrow else 4.3,
                [["F"], ["v"]],
                narrow=narrow,
                sharex=True,
                gridspec_kw={"height_ratios": [3, 2]},
            )
            ax, ax_v = named["F"], named["v"]
        else:
            fig, (ax,) = s.new_figure(2.7 if narrow else 2.5, narrow=narrow)
        t_max, f_lo, f_hi = _extent(scene, tables)
        ax.set_xlim(0, t_max * 1.04)
        ax.set_ylim(f_lo * 1.08, f_hi * 1.08)
        ax.set_ylabel("force F (N)")
        if f_lo < 0:
            ax.axhline(0, color=s.MUTED, lw=0.6)
        ax.legend(
            handles=[
                Line2D([], [], color=s.BLUE, lw=2.2, label="F(t)"),
                Patch(color=s.FILL_BLUE, label="area = impulse J"),
            ],
            loc="lower right",  # above the axes: the pulse can reach any corner of them
            bbox_to_anchor=(1.0, 1.0),
            ncols=2,
            frameon=False,
            fontsize=9,
        )
        if with_velocity:
            _draw_velocity_axes(ax_v, tables)
            ax_v.set_xlabel("time t (s)")
            fig.tight_layout(pad=0.4, h_pad=0.6)
        else:
            ax.set_xlabel("time t (s)")
            fig.tight_layout(pad=0.4)
        return fig


def _sampled(scene) -> bool:
    """Whether the pulse is drawn from its samples (any shape, or the contact) rather than three vertices."""
    return "shape" in scene.effects or CONTACT in scene.effects


def _extent(scene, tables) -> tuple[float, float, float]:
    """The largest time and the force range over every stop (the contact's force turns briefly negative)."""
    if CONTACT in scene.effects:
        f_lo, f_hi = table_range(tables["pulse_F"])
        return table_range(tables["pulse_t"])[1], min(f_lo, 0.0), max(f_hi, 1e-9)
    return param_range(scene, "tau")[1], 0.0, max(param_range(scene, "F_pk")[1], 1e-9)


def _draw_velocity_axes(ax, tables) -> None:
    """Velocity limits that fit every stop, with the zero line."""
    low, high = table_range(tables["v_curve"])
    pad = 0.08 * (high - low or 1.0)
    ax.set_ylim(min(low, 0.0) - pad, max(high, 0.0) + pad)
    ax.axhline(0, color=s.MUTED, lw=0.6)
    ax.set_ylabel("velocity v (m/s)")
    ax.legend(
        handles=[Line2D([], [], color=s.ORANGE, lw=2.2, label="v(t)")],
        loc="lower right",
        bbox_to_anchor=(1.0, 1.0),
        frameon=False,
        fontsize=9,
        borderaxespad=0.1,
    )
