"""K4: the bubble radius against time, in one of three views chosen by the scene's effects:
the Rayleigh collapse (step), the driven bubble (drive) or the nucleus under a ramp (ramp)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from matplotlib.lines import Line2D

from ...render import style as s
from ...render.figures.base import param_range, table_range
from ...render.layers import Layer
from .point import DRIVE_PERIODS
from .run import CURVE_POINTS
from .terms import rayleigh_radius

# Inline style: matplotlib's SVG sheet sets * {stroke-linecap: butt}, which would hide zero-length dots.
_DOT = {"fill": "none", "style": "stroke-linecap: round"}
_LINE = {"fill": "none", "stroke": s.BLUE, "stroke-width": "2.2"}


def _view(scene) -> str:
    """The scene's pressure history, which names its outputs: "collapse", "driven" or "ramp"."""
    if "drive" in scene.effects:
        return "driven"
    return "ramp" if "ramp" in scene.effects else "collapse"


def _x_end(scene) -> float:
    """The right end of the time axis in the view's unit: 2 T, t_ramp + t_hold (µs), or 2 t_c."""
    if _view(scene) == "ramp":
        values = scene.base_values()
        return values["t_ramp"] + values["t_hold"]
    return float(DRIVE_PERIODS) if _view(scene) == "driven" else 2.0


class BubbleFigure:
    """R(t) from the model with its event markers; beneath the driven bubble, the drive p∞(t)."""

    label = (
        "Bubble radius against time. For the collapse, R/R0 against t/tc with the analytic Rayleigh curve and a dot "
        "where the run stopped; for the driven bubble, R/R0 against t/T with dots at the event-detected maximum and "
        "minimum and the liquid pressure beneath; for the nucleus under tension, R/R_B on a log scale against time."
    )

    def layers(self, scene):
        out = f"out:{_view(scene)}_"
        layers = [
            Layer("radius", "polyline", 0, xs=out + "curve_x", ys=out + "curve_y", style=_LINE),
            Layer(
                "stop",
                "dots",
                0,
                xs=out + "stop_x",
                ys=out + "stop_y",
                style={**_DOT, "stroke": s.ORANGE, "stroke-width": "8"},
            ),
        ]
        if _view(scene) != "ramp":
            layers.insert(
                1,
                Layer(
                    "extrema",
                    "dots",
                    0,
                    xs=out + "mark_x",
                    ys=out + "mark_y",
                    style={**_DOT, "stroke": s.INK, "stroke-width": "6"},
                ),
            )
        if _view(scene) == "driven":
            xs = tuple(float(v) for v in np.round(np.linspace(0.0, _x_end(scene), CURVE_POINTS), 6))
            layers.append(
                Layer(
                    "drive",
                    "polyline",
                    1,
                    xs=xs,
                    ys="out:driven_p_far",
                    style={**_LINE, "stroke": s.ORANGE, "stroke-width": "1.8"},
                )
            )
        if _view(scene) == "collapse":  # R/R0 against t/t_c is universal: the note gives the scale R0 sets
            layers.append(Layer.note("scale", "scaled to R₀ = ", "in:R0", " and the collapse time ", "out:t_c"))
        return layers

    def draw(self, scene, tables, narrow=False):
        view = _view(scene)
        if view == "driven":
            fig, (ax, ax_p) = s.new_rows(
                4.2 if narrow else 3.4, 2, narrow, sharex=True, gridspec_kw={"height_ratios": [3, 1]}
            )
            handles = _draw_driven(ax, ax_p, scene, tables)
        else:
            fig, (ax,) = s.new_figure(3.2 if narrow else 2.7, narrow=narrow)
            handles = (_draw_ramp if view == "ramp" else _draw_collapse)(ax, scene, tables)
        # Above the axes: the curve and its dots can reach any corner inside them.
        ax.legend(
            handles=handles,
            loc="lower center",
            bbox_to_anchor=(0.5, 1.0),
            ncols=2 if narrow else len(handles),
            frameon=False,
            fontsize=9,
            handlelength=1.6,
            columnspacing=1.0,
            handletextpad=0.5,
        )
        fig.tight_layout(pad=0.4, h_pad=0.6)
        return fig


class BubbleEventsFigure(BubbleFigure):
    """The driven bubble's events without its R(t) curve: a scene over more stops than curves can ship.

    Each curve costs about 170 bytes gzip; the events cost a few. Over every (R0, p_a, f) stop the
    dots still show when, and how far, the bubble grows and collapses in the drive's cycle.
    """

    label = (
        "Radius against time for a bubble driven by a sound wave: a dot at the event-detected largest radius "
        "and one at the smallest, R/R0 on a log scale against t/T, with the liquid pressure p∞(t)/p0 beneath."
    )

    def layers(self, scene):
        # Without the curve to lead the eye to them, the event dots are drawn larger.
        layers = [layer for layer in super().layers(scene) if layer.name != "radius"]
        return [
            replace(layer, style={**layer.style, "stroke-width": "11"}) if layer.name == "extrema" else layer
            for layer in layers
        ]


def _model_handles(stop_label: str, extrema_label: str | None = None, curve: bool = True) -> list:
    """The legend of the model's layers; without the curve (bubble_events) its event dots are drawn larger."""
    handles = [Line2D([], [], color=s.BLUE, lw=2.2, label="model R(t)")] if curve else []
    if extrema_label:
        handles.append(Line2D([], [], color=s.INK, marker="o", ls="none", ms=5 if curve else 8, label=extrema_label))
    handles.append(Line2D([], [], color=s.ORANGE, marker="o", ls="none", ms=6, label=stop_label))
    return handles


def _draw_collapse(ax, scene, tables) -> list:
    """R/R0 against t/t_c with the exact Rayleigh curve (static: it is universal in these units)."""
    fraction = np.linspace(0.0, 1.0, 801)
    ax.plot(fraction, rayleigh_radius(fraction), color=s.FILL_BLUE, lw=6, solid_capstyle="round", zorder=1)
    ax.set_xlim(0.0, 2.0)
    ax.set_ylim(0.0, 1.08)
    ax.axvline(1.0, color=s.MUTED, lw=0.6, ls=(0, (2, 3)))
    ax.set_xlabel("time t / t$_c$ (Rayleigh collapse time)")
    ax.set_ylabel("radius R / R$_0$")
    handles = [Line2D([], [], color=s.FILL_BLUE, lw=6, label="Rayleigh, exact")]
    return handles + _model_handles("stopped: |Ṙ| = c", "R$_{min}$ (event)")


def _draw_driven(ax, ax_p, scene, tables) -> list:
    """log10(R/R0) against t/T above the drive p∞(t)/p0."""
    low, high = _y_range(tables, "driven")
    ax.set_xlim(0.0, float(DRIVE_PERIODS))
    ax.set_ylim(min(low, -0.1) - 0.06, max(high, 0.1) + 0.08)
    _log_ticks(ax)
    ax.axhline(0.0, color=s.MUTED, lw=0.8)
    ax.set_ylabel("radius R / R$_0$ (log scale)")
    curve = "driven_curve_y" in tables  # the bubble_events view does not tabulate the curve
    handles = _model_handles("stopped by an event", "R$_{max}$, R$_{min}$ (events)", curve)
    amplitude = max(param_range(scene, "p_a")[1], 0.1)
    ax_p.set_ylim(1.0 - 1.15 * amplitude, 1.0 + 1.15 * amplitude)
    ax_p.axhline(0.0, color=s.MUTED, lw=0.8)
    ax_p.set_xticks(np.arange(0, DRIVE_PERIODS + 0.5, 0.5))
    ax_p.set_xlabel("time t / T (acoustic periods)")
    ax_p.set_ylabel("p$_∞$ / p$_0$")
    return handles


_LOG_TICKS = (0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100)


def _log_ticks(ax) -> None:
    """Tick marks at 1-2-5 values on an axis whose data are log10 of a ratio."""
    low, high = ax.get_ylim()
    ticks = [t for t in _LOG_TICKS if low <= np.log10(t) <= high]
    ax.set_yticks(np.log10(ticks), [f"{t:g}" for t in ticks])


def _y_range(tables, view: str) -> tuple[float, float]:
    """The smallest and largest radius coordinate of the curve and its event dots over every stop."""
    ranges = [
        table_range(tables[f"{view}_{name}"]) for name in ("curve_y", "mark_y", "stop_y") if f"{view}_{name}" in tables
    ]
    return min(r[0] for r in ranges), max(r[1] for r in ranges)


def _draw_ramp(ax, scene, tables) -> list:
    """log10(R/R_B) against time, with the Blake radius and the 10 R_B stop as reference lines."""
    low, high = _y_range(tables, "ramp")
    ax.set_xlim(0.0, _x_end(scene))
    ax.set_ylim(min(low, -0.2) - 0.08, max(high, 1.0) + 0.1)
    _log_ticks(ax)
    ax.axhline(0.0, color=s.INK, lw=1.0, ls=(0, (5, 3)))
    ax.axhline(1.0, color=s.MUTED, lw=0.8, ls=(0, (2, 3)))
    ramp = scene.base_values()["t_ramp"]
    ax.axvline(ramp, color=s.MUTED, lw=0.8, ls=(0, (2, 3)))
    ax.text(ramp, ax.get_ylim()[0] + 0.03, "ramp ends ", color=s.MUTED, fontsize=8, ha="right", va="bottom")
    ax.text(0.01 * _x_end(scene), 0.03, "Blake radius R$_B$", color=s.INK, fontsize=8, va="bottom")
    ax.text(0.01 * _x_end(scene), 1.03, "10 R$_B$: unbounded", color=s.MUTED, fontsize=8, va="bottom")
    ax.set_xlabel("time t (µs)")
    ax.set_ylabel("radius R / R$_B$ (log scale)")
    return _model_handles("reached 10 R$_B$")
