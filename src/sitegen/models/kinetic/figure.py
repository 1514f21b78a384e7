"""K2: the impulse train on the wall, the running mean of the pressure, and the v_x histogram."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ...render import style as s
from ...render.layers import Layer
from .model import HIST_SPAN
from .walls import TRAIN_BINS

TRAIN_TOP = 3.0  # force axis: 0 .. 3 × the mean force; taller kicks (few molecules) are clipped
PULSE_TOP = 6.0  # with contact_duration: room for the pulses of a few molecules
RUNNING_SPAN = (0.5, 1.5)  # running-mean axis, in units of p_ideal
DENSITY_TOP = 0.6
MAXWELL_Z = np.linspace(-HIST_SPAN, HIST_SPAN, 97)  # vertices of the Maxwellian curve


class KineticFigure:
    """Force on the wall in time bins, its running mean, and the sample's v_x against the Maxwellian."""

    label = (
        "Top left: force on the wall x = L in time bins across the window t_w, in units of the ideal mean force; "
        "the dashed line is the ideal mean. Bottom left: the pressure averaged from 0 to t, in units of n k_B T, "
        "with the sample's long-time value dashed. Right: histogram of the molecules' v_x in units of v_th "
        "against the Maxwellian (a normal distribution)."
    )

    def layers(self, scene):
        edges = np.arange(TRAIN_BINS + 1) / TRAIN_BINS
        train, running = _time_outputs(scene.effects)
        sample = (
            []
            if "wall_law" in scene.effects
            else [  # diffuse walls re-thermalise: no fixed sample limit
                Layer(
                    "sample-pressure",
                    "polyline",
                    1,
                    ((0.0, "out:ratio_sample"), (1.0, "out:ratio_sample")),
                    style={"fill": "none", "stroke": s.ORANGE, "stroke-width": "1.6", "stroke-dasharray": "5 4"},
                ),
            ]
        )
        return [
            Layer(
                "impulse-train",
                "polygon",
                0,
                xs=_fixed(np.repeat(edges, 2)),
                ys=f"out:{train}",
                style={"fill": s.FILL_BLUE, "stroke": s.BLUE, "stroke-width": "1"},
            ),
            *sample,
            # Forces, pressures and speeds are drawn in units of p_ideal and v_th, which T and the gas set.
            Layer.note("scale", "scales: ideal-gas pressure ", "out:p_ideal", " · thermal speed ", "out:v_th"),
            Layer(
                "running-mean",
                "polyline",
                1,
                xs=_fixed(edges[1:]),
                ys=f"out:{running}",
                style={"fill": "none", "stroke": s.BLUE, "stroke-width": "2"},
            ),
            Layer(
                "velocity-histogram",
                "polygon",
                2,
                xs="out:hist_x",
                ys="out:hist_y",
                style={"fill": s.FILL_BLUE, "fill-opacity": "0.8", "stroke": s.BLUE, "stroke-width": "1.2"},
            ),
            # Static, but a layer so that it is drawn over the histogram.
            Layer(
                "maxwellian",
                "polyline",
                2,
                xs=_fixed(MAXWELL_Z),
                ys=_fixed(np.round(_normal(MAXWELL_Z), 4)),
                style={"fill": "none", "stroke": s.ORANGE, "stroke-width": "2"},
            ),
        ]

    def draw(self, scene, tables, narrow=False):
        fig, (ax_train, ax_run, ax_hist) = _axes(narrow)
        _draw_train(ax_train, PULSE_TOP if "contact_duration" in scene.effects else TRAIN_TOP)
        _draw_running(ax_run, sample_limit="wall_law" not in scene.effects)
        _draw_histogram(ax_hist, legend_columns=2 if narrow else 1)
        fig.tight_layout(pad=0.4, h_pad=0.6, w_pad=1.4)
        return fig


def _time_outputs(effects) -> tuple[str, str]:
    """The outputs the time panels show: the force train and running mean of the walls the scene models."""
    if "wall_law" in effects:
        return "train_wall", "running_wall"
    if "contact_duration" in effects:
        return "train_soft", "running_soft"
    return "train", "running"


def _axes(narrow: bool):
    """Two stacked time panels on the left, the velocity histogram on the right (fig.axes in that order);
    narrow, the histogram goes under them."""
    with plt.rc_context(s.RC):
        fig = plt.figure(figsize=(s.width(narrow), 7.4 if narrow else 4.0))
        grid = (
            fig.add_gridspec(3, 1, height_ratios=[1, 1, 1.5])
            if narrow
            else fig.add_gridspec(2, 2, width_ratios=[1.45, 1.0])
        )
        ax_train = fig.add_subplot(grid[0, 0])
        ax_run = fig.add_subplot(grid[1, 0], sharex=ax_train)
        ax_hist = fig.add_subplot(grid[2, 0] if narrow else grid[:, 1])
    return fig, (ax_train, ax_run, ax_hist)


def _draw_train(ax, top: float):
    ax.set_xlim(0, 1)
    ax.set_ylim(0, top)
    ax.set_yticks(np.arange(0, top + 0.5, 1 if top <= 3 else 2))
    ax.axhline(1.0, color=s.INK, lw=1.0, ls=(0, (4, 3)))
    ax.set_ylabel(r"$F\,/\,p_\mathrm{ideal}L^2$")
    ax.set_title("force on the wall x = L", fontsize=10, loc="left", color=s.INK)
    ax.tick_params(labelbottom=False)


def _draw_running(ax, sample_limit: bool):
    ax.set_ylim(*RUNNING_SPAN)
    ax.set_yticks([0.5, 1.0, 1.5])
    ax.axhline(1.0, color=s.INK, lw=1.0, ls=(0, (4, 3)))
    ax.set_xticks([0, 0.25, 0.5, 0.75, 1], ["0", "", "", "", r"$t_\mathrm{w}$"])
    ax.set_xlabel("time t", labelpad=-9)
    ax.set_ylabel(r"$\bar p\,/\,p_\mathrm{ideal}$")
    ax.set_title("pressure averaged from 0 to t", fontsize=10, loc="left", color=s.INK)
    ax.legend(
        handles=[
            Line2D([], [], color=s.BLUE, lw=2, label="running mean"),
            *(
                [Line2D([], [], color=s.ORANGE, lw=1.6, ls=(0, (5, 4)), label=r"sample, $t\to\infty$")]
                if sample_limit
                else []
            ),
            Line2D([], [], color=s.INK, lw=1.0, ls=(0, (4, 3)), label="ideal gas"),
        ],
        loc="upper center",
        bbox_to_anchor=(0.45, -0.2),
        ncols=2,
        frameon=False,
        fontsize=9,
        handlelength=1.6,
        columnspacing=1.0,
        handletextpad=0.5,
    )


def _draw_histogram(ax, legend_columns: int):
    ax.set_xlim(-HIST_SPAN, HIST_SPAN)
    ax.set_ylim(0, DENSITY_TOP)
    ax.set_xticks([-4, -2, 0, 2, 4])
    ax.set_xlabel(r"$v_x\,/\,v_\mathrm{th}$")
    ax.set_ylabel("probability density")
    # The legend between the axes and the title: a few molecules' histogram can reach any height.
    ax.set_title("velocities along x at t = 0", fontsize=10, loc="left", color=s.INK, pad=6 + 15 * (3 - legend_columns))
    ax.legend(
        handles=[
            Patch(facecolor=s.FILL_BLUE, edgecolor=s.BLUE, label="molecules"),
            Line2D([], [], color=s.ORANGE, lw=1.8, label="Maxwellian"),
        ],
        loc="lower left",
        bbox_to_anchor=(0.0, 1.0),
        ncols=legend_columns,
        frameon=False,
        fontsize=9,
        handlelength=1.4,
        borderaxespad=0.1,
        columnspacing=1.0,
    )


def _normal(z):
    """The Maxwellian of v_x/v_th: the standard normal density."""
    return np.exp(-0.5 * z * z) / np.sqrt(2.0 * np.pi)


def _fixed(values) -> tuple[float, ...]:
    return tuple(float(v) for v in values)
