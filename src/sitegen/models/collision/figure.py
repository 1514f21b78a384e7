"""I2: velocities before and after contact, and the kinetic-energy ledger; with the spring–dashpot
contact, also the contact force F(t) with the impulse shaded under it (the impulse picture of I1)."""

from __future__ import annotations

from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ...render import style as s
from ...render.figures.base import param_range, table_range
from ...render.layers import Layer
from .model import CONTACT


class CollisionFigure:
    """Velocities before and after contact, and the kinetic-energy ledger."""

    label = (
        "Left: velocity of each body against time, with the contact at t = 0 and the centre-of-mass velocity dashed. "
        "Right: kinetic energy after the impact as a percentage of the energy before; the grey part is the energy lost."
    )

    def describe(self, scene) -> str:
        """The label, with the contact-force panel when the scene has the spring–dashpot contact."""
        if CONTACT not in scene.effects:
            return self.label
        return self.label + (
            " Bottom: the force between the bodies during the contact against time; "
            "the shaded area under it is the impulse J given to body 2."
        )

    def layers(self, scene):
        def step(body):
            return ((-1.0, f"in:v{body}i"), (0.0, f"in:v{body}i"), (0.0, f"out:v{body}f"), (1.0, f"out:v{body}f"))

        def bar(x, low, high):
            return ((x - 0.32, low), (x - 0.32, high), (x + 0.32, high), (x + 0.32, low))

        line = {"fill": "none", "stroke-width": "2.4"}
        return [
            Layer(
                "centre-of-mass",
                "polyline",
                0,
                ((-1.0, "out:v_cm"), (1.0, "out:v_cm")),
                style={**line, "stroke": s.MUTED, "stroke-width": "1.6", "stroke-dasharray": "5 4"},
            ),
            Layer("body-1", "polyline", 0, step(1), style={**line, "stroke": s.BLUE}),
            Layer("body-2", "polyline", 0, step(2), style={**line, "stroke": s.ORANGE}),
            Layer(
                "K-after",
                "polygon",
                1,
                bar(1.0, 0.0, "out:K_kept_pct"),
                style={"fill": s.FILL_BLUE, "stroke": s.BLUE, "stroke-width": "1.2"},
            ),
            Layer(
                "K-lost",
                "polygon",
                1,
                bar(1.0, "out:K_kept_pct", 100.0),
                style={
                    "fill": s.LOST,
                    "fill-opacity": "0.6",
                    "stroke": s.MUTED,
                    "stroke-width": "1",
                    "stroke-dasharray": "3 2",
                },
            ),
        ] + (_contact_layers() if CONTACT in scene.effects else [])

    def draw(self, scene, tables, narrow=False):
        if CONTACT in scene.effects:
            if narrow:  # three rows, in the wide figure's order of axes
                fig, named = s.new_mosaic(
                    7.4, [["v"], ["K"], ["F"]], narrow=True, gridspec_kw={"height_ratios": [3, 2.2, 2]}
                )
            else:
                fig, named = s.new_mosaic(
                    4.9, [["v", "K"], ["F", "F"]], gridspec_kw={"width_ratios": [3, 2], "height_ratios": [3, 1.9]}
                )
            ax_v, ax_k = named["v"], named["K"]
            _draw_force_axes(named["F"], tables)
        else:
            shape = {"height_ratios": [3, 2.2]} if narrow else {"width_ratios": [3, 2]}
            fig, (ax_v, ax_k) = s.new_figure(5.4 if narrow else 3.0, ncols=2, narrow=narrow, gridspec_kw=shape)
        lows, highs = zip(
            *(table_range(tables[n]) for n in ("v1f", "v2f", "v_cm")),
            param_range(scene, "v1i"),
            param_range(scene, "v2i"),
        )
        v_lo, v_hi = min(lows), max(highs)
        pad = 0.06 * (v_hi - v_lo or 1.0)
        ax_v.set_xlim(-1, 1)
        ax_v.set_ylim(v_lo - pad, v_hi + pad)
        ax_v.axvline(0, color=s.MUTED, lw=0.8)
        ax_v.axhline(0, color=s.MUTED, lw=0.6)
        ax_v.set_xticks([-1, 0, 1], ["before", "contact", "after"])
        ax_v.set_xlabel("time")
        ax_v.set_ylabel("velocity v (m/s)")
        ax_v.legend(
            handles=[
                Line2D([], [], color=s.BLUE, lw=2.4, label="body 1"),
                Line2D([], [], color=s.ORANGE, lw=2.4, label="body 2"),
                Line2D([], [], color=s.MUTED, lw=1.6, ls=(0, (5, 4)), label="centre of mass"),
            ],
            loc="lower center",
            bbox_to_anchor=(0.5, 1.0),
            ncols=2 if narrow else 3,
            frameon=False,
            fontsize=9,
        )
        ax_k.bar([0], [100.0], width=0.64, color=s.FILL_BLUE, edgecolor=s.BLUE, linewidth=1.2)
        ax_k.set_xlim(-0.6, 1.6)
        ax_k.set_ylim(0, 112)
        ax_k.set_yticks([0, 25, 50, 75, 100])
        ax_k.set_xticks([0, 1], ["before", "after"])
        ax_k.grid(axis="x", visible=False)
        ax_k.set_ylabel("kinetic energy (% of before)")
        ax_k.legend(
            handles=[Patch(facecolor=s.LOST, edgecolor=s.MUTED, ls="--", label="lost")],
            loc="lower right",
            bbox_to_anchor=(1.0, 1.0),
            frameon=False,
            fontsize=9,
        )  # above the bars, never over them
        fig.tight_layout(pad=0.4, w_pad=1.2)
        return fig


def _contact_layers() -> list[Layer]:
    """The contact force F(t) and the impulse under it, drawn over the third axes."""
    return [
        Layer(
            "contact-area",
            "polygon",
            2,
            xs="out:contact_t",
            ys="out:contact_F",
            style={"fill": s.FILL_ORANGE, "fill-opacity": "0.8", "stroke": "none"},
        ),
        Layer(
            "contact-force",
            "polyline",
            2,
            xs="out:contact_t",
            ys="out:contact_F",
            style={"fill": "none", "stroke": s.ORANGE, "stroke-width": "2.2"},
        ),
    ]


def _draw_force_axes(ax, tables) -> None:
    """Time and force limits that fit the contact at every stop (its force ends briefly negative: tension)."""
    t_hi = table_range(tables["contact_t"])[1]
    f_lo, f_hi = table_range(tables["contact_F"])
    span = (f_hi - min(f_lo, 0.0)) or 1.0
    ax.set_xlim(0, 1.02 * (t_hi or 1.0))
    ax.set_ylim(min(f_lo, 0.0) - 0.06 * span, f_hi + 0.12 * span)
    ax.axhline(0, color=s.MUTED, lw=0.6)
    ax.set_xlabel("time since first touch (ms)")
    ax.set_ylabel("force on body 2 (N)", fontsize=9)
    ax.legend(
        handles=[
            Line2D([], [], color=s.ORANGE, lw=2.2, label="contact force F(t)"),
            Patch(color=s.FILL_ORANGE, label="area = impulse J"),
        ],
        loc="lower right",
        bbox_to_anchor=(1.0, 1.0),
        ncols=2,
        frameon=False,
        fontsize=9,  # above: clear of the curve
    )
