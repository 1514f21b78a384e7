"""K3: the pressure wave sweeping past a slab of air, and the slab's acceleration against Euler's."""

from __future__ import annotations

from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ...render import style as s
from ...render.layers import Layer
from .model import MIN_DRAWN_WIDTH, WAVE_X

SLAB_TOP = 1.08  # the shaded slab spans the wave's height (p′/P in ±1); notes sit above and below it
Y_LIMIT = 1.38
BAR_HALF_WIDTH = 0.32
TEXT_SIZE, NOTE_SIZE = 11, 10
# Inline CSS: the static SVG's own stylesheet sets `* {stroke-linecap: butt}`, which beats the
# stroke-linecap attribute the dots rely on and would leave them zero-length, i.e. invisible.
FACE_DOTS = {"stroke": s.ORANGE, "stroke-width": "8", "style": "stroke-linecap: round"}


class EulerSlabFigure:
    """The wave p′(x)/P with the slab and its face pressures; bars of ā and a_m in units of Pk/ρₐ."""

    label = (
        "Left: the pressure of the sound wave, in units of its amplitude P, over two wavelengths around a slab "
        "of air (shaded, centred on x_m; drawn at least λ/40 wide), with dots at the pressures on its two faces. "
        "Right: the slab's mean acceleration and Euler's point acceleration at its centre, both in units of Pk/ρₐ."
    )

    def layers(self, scene):
        def bar(x, top):
            return (
                (x - BAR_HALF_WIDTH, 0.0),
                (x - BAR_HALF_WIDTH, top),
                (x + BAR_HALF_WIDTH, top),
                (x + BAR_HALF_WIDTH, 0.0),
            )

        slab = (
            ("out:drawn_lo", -SLAB_TOP),
            ("out:drawn_lo", SLAB_TOP),
            ("out:drawn_hi", SLAB_TOP),
            ("out:drawn_hi", -SLAB_TOP),
        )
        faces = (("out:face_lo", "out:p_left"), ("out:face_hi", "out:p_right"))
        return [
            Layer(
                "slab",
                "polygon",
                0,
                slab,
                style={"fill": s.ORANGE, "fill-opacity": "0.22", "stroke": s.ORANGE, "stroke-width": "1.2"},
            ),
            Layer(
                "wave",
                "polyline",
                0,
                xs=WAVE_X,
                ys="out:wave",
                style={"fill": "none", "stroke": s.BLUE, "stroke-width": "2.2"},
            ),
            Layer("faces", "dots", 0, faces, style=FACE_DOTS),
            Layer(
                "a-slab",
                "polygon",
                1,
                bar(0.0, "out:bar_slab"),
                style={"fill": s.ORANGE, "fill-opacity": "0.55", "stroke": s.ORANGE, "stroke-width": "1.2"},
            ),
            Layer(
                "a-point",
                "polygon",
                1,
                bar(1.0, "out:bar_point"),
                style={"fill": s.FILL_BLUE, "stroke": s.BLUE, "stroke-width": "1.2"},
            ),
            # The axes are in units of P, λ and Pk/ρₐ: the note gives P and λ, which L_p and f set.
            Layer.note("scale", "P = ", "out:P", " · λ = ", "out:wavelength"),
        ]

    def draw(self, scene, tables, narrow=False):
        shape = {"height_ratios": [3, 2]} if narrow else {"width_ratios": [3.2, 1]}
        fig, (ax_w, ax_a) = s.new_figure(5.6 if narrow else 3.1, ncols=2, narrow=narrow, gridspec_kw=shape)
        _draw_wave_axes(ax_w, legend_columns=2 if narrow else 3)
        _draw_bar_axes(ax_a)
        for ax in (ax_w, ax_a):  # larger than the house default: the figure is read down to phone width
            ax.tick_params(labelsize=TEXT_SIZE)
        fig.tight_layout(pad=0.4, w_pad=1.0)
        return fig


def _draw_wave_axes(ax, legend_columns: int = 3):
    """Fixed frame of the wave panel: x in wavelengths about the slab centre, p′ in units of P."""
    ax.set_xlim(WAVE_X[0], WAVE_X[-1])
    ax.set_ylim(-Y_LIMIT, Y_LIMIT)
    ax.set_xticks([-1, -0.5, 0, 0.5, 1], ["−λ", "−λ/2", "x$_m$", "λ/2", "λ"])
    ax.set_yticks([-1, 0, 1], ["−P", "0", "P"])
    ax.axhline(0, color=s.MUTED, lw=0.6)
    ax.plot([0, 0], [-SLAB_TOP, SLAB_TOP], color=s.MUTED, lw=0.8, ls=(0, (4, 3)))  # the centre x_m
    ax.set_xlabel("position along the wave", fontsize=TEXT_SIZE)
    ax.set_ylabel("sound pressure p′", fontsize=TEXT_SIZE)
    row = 0.5 * (SLAB_TOP + Y_LIMIT)
    ax.annotate("", xy=(-0.98, row), xytext=(-0.64, row), arrowprops={"arrowstyle": "->", "color": s.MUTED, "lw": 1.2})
    ax.text(-0.6, row, "wave travels", color=s.MUTED, fontsize=NOTE_SIZE, va="center")
    ax.text(
        0.99,
        -row,
        f"slab drawn ≥ λ/{round(1 / MIN_DRAWN_WIDTH)} wide",
        color=s.MUTED,
        fontsize=NOTE_SIZE - 1,
        ha="right",
        va="center",
    )
    ax.legend(
        handles=[
            Line2D([], [], color=s.BLUE, lw=2.2, label="p′(x)"),
            Patch(facecolor=s.ORANGE, alpha=0.3, edgecolor=s.ORANGE, label="slab Δx"),
            Line2D([], [], color=s.ORANGE, lw=0, marker="o", ms=7, label="face pressures"),
        ],
        loc="lower center",
        bbox_to_anchor=(0.6 if legend_columns == 3 else 0.5, 1.0),
        ncols=legend_columns,
        frameon=False,
        fontsize=NOTE_SIZE,
        handlelength=1.6,
        columnspacing=1.2,
    )


def _draw_bar_axes(ax):
    """Fixed frame of the acceleration panel: two bars in units of Euler's amplitude Pk/ρₐ."""
    ax.set_xlim(-0.6, 1.6)
    ax.set_ylim(-1.1, 1.1)
    ax.set_xticks([0, 1], ["slab\nā", "point\na$_m$"])
    for label in ax.get_xticklabels():
        label.set_linespacing(1.35)  # room for the subscript
    ax.set_yticks([-1, 0, 1])
    ax.grid(axis="x", visible=False)
    ax.axhline(0, color=s.MUTED, lw=0.8)
    ax.set_ylabel("acceleration ÷ Pk/ρ$_a$", fontsize=TEXT_SIZE)
