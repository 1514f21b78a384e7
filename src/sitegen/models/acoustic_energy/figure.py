"""K5: kinetic and potential energy density and intensity along one wavelength, and the local balance."""

from __future__ import annotations

from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle

from ...render import style as s
from ...render.layers import Layer
from .model import X_OVER_LAMBDA

XS = tuple(float(v) for v in X_OVER_LAMBDA)
ENERGY_LIMITS = (-2.25, 4.35)  # e_k, e_p ≤ (1 + R)² ≤ 4; I/c between −2R² and 2 (units ⟨e⟩ᵢ)
# Inline CSS: the static SVG's stylesheet sets `stroke-linecap: butt`, which would make the dots zero-length.
DOTS = {"fill": "none", "stroke": s.ORANGE, "stroke-width": "4.5", "style": "stroke-linecap: round"}
RATE_LIMITS = (-4.4, 4.4)  # ∂e/∂t = 2ω⟨e⟩ᵢ(sin 2a − R² sin 2b): at most 2(1 + R²) ≤ 4; a margin for the stroke


class AcousticEnergyFigure:
    """Energy densities and I/c along x at one instant, with their time averages; below, ∂e/∂t and −∂I/∂x."""

    label = (
        "Top: kinetic and potential energy density and the intensity divided by c along one wavelength in front "
        "of the reflector, at the chosen instant, with their time averages dotted; in units of the incident wave's "
        "mean energy density. Bottom: the rate of change of the energy density and the convergence of the "
        "intensity, which coincide everywhere."
    )

    def layers(self, scene):
        line = {"fill": "none", "stroke-width": "2.2"}
        average = {"fill": "none", "stroke-width": "1.3", "stroke-dasharray": "2 3"}
        probe = {"fill": "none", "stroke": s.MUTED, "stroke-width": "1.2"}
        layers = [
            Layer("ek-average", "polyline", 0, xs=XS, ys="out:ek_avg_x", style={**average, "stroke": s.BLUE}),
            Layer("ep-average", "polyline", 0, xs=XS, ys="out:ep_avg_x", style={**average, "stroke": s.ORANGE}),
            Layer(
                "I-average",
                "polyline",
                0,
                ((-1.0, "out:I_avg_n"), (0.0, "out:I_avg_n")),
                style={**average, "stroke": s.INK},
            ),
            Layer(
                "I",
                "polyline",
                0,
                xs=XS,
                ys="out:Ic_x",
                style={**line, "stroke": s.INK, "stroke-width": "1.6", "stroke-dasharray": "6 3"},
            ),
            # e_p wide under a narrower e_k: where they coincide (a travelling wave) both stay visible.
            Layer("ep", "polyline", 0, xs=XS, ys="out:ep_x", style={**line, "stroke": s.ORANGE, "stroke-width": "3.6"}),
            Layer("ek", "polyline", 0, xs=XS, ys="out:ek_x", style={**line, "stroke": s.BLUE, "stroke-width": "1.8"}),
            Layer(
                "rate", "polyline", 1, xs=XS, ys="out:dedt_x", style={**line, "stroke": s.BLUE, "stroke-width": "1.8"}
            ),
            Layer("convergence", "dots", 1, xs=XS, ys="out:neg_dIdx_x", style=DOTS),
        ]
        # The axes are in units of ⟨e⟩ᵢ and λ: the note gives them, so SPL and f visibly change the figure.
        layers.append(Layer.note("scale", "⟨e⟩ᵢ = ", "out:e_inc", " · λ = ", "out:wavelength"))
        if scene.axis_index("x_probe") is not None:
            layers.insert(
                0,
                Layer(
                    "probe",
                    "polyline",
                    0,
                    (("in:x_probe", ENERGY_LIMITS[0]), ("in:x_probe", ENERGY_LIMITS[1])),
                    style=probe,
                ),
            )
        return layers

    def draw(self, scene, tables, narrow=False):
        fig, (ax_e, ax_r) = s.new_rows(
            5.4 if narrow else 4.3, 2, narrow, sharex=True, gridspec_kw={"height_ratios": [3, 2]}
        )
        for ax, limits in ((ax_e, ENERGY_LIMITS), (ax_r, RATE_LIMITS)):
            ax.set_xlim(-1.0, 0.06)
            ax.set_ylim(*limits)
            ax.axhline(0, color=s.MUTED, lw=0.6)
            _reflector(ax, limits)
        ax_e.set_yticks([-2, 0, 1, 2, 4])
        ax_e.set_ylabel("energy density\n(units of ⟨e⟩ᵢ)")
        ax_r.set_yticks([-4, -2, 0, 2, 4])
        ax_r.set_ylabel("rate (units\nof ω⟨e⟩ᵢ)")
        ax_r.set_xticks([-1, -0.75, -0.5, -0.25, 0], ["−1", "−¾", "−½", "−¼", "0"])
        ax_r.set_xlabel("position x/λ (reflector at x = 0)")
        ax_e.legend(
            handles=_energy_legend(),
            loc="lower center",
            bbox_to_anchor=(0.47, 1.0),
            ncols=2 if narrow else 4,
            frameon=False,
            fontsize=9,
            handlelength=1.8,
            columnspacing=1.1,
        )
        ax_r.legend(
            handles=_rate_legend(), loc="lower left", bbox_to_anchor=(0.0, 0.98), ncols=2, frameon=False, fontsize=9
        )
        fig.tight_layout(pad=0.4, h_pad=1.4)
        return fig


def _reflector(ax, limits) -> None:
    """The reflector at x = 0 as a hatched wall to the right of the wave."""
    low, high = limits
    ax.add_patch(
        Rectangle((0.0, low), 0.06, high - low, facecolor=s.LOST, edgecolor=s.MUTED, hatch="///", lw=0.8, zorder=3)
    )


def _energy_legend():
    return [
        Line2D([], [], color=s.BLUE, lw=1.8, label="e$_k$"),
        Line2D([], [], color=s.ORANGE, lw=3.6, label="e$_p$"),
        Line2D([], [], color=s.INK, lw=1.6, ls=(0, (6, 3)), label="I/c"),
        Line2D([], [], color=s.MUTED, lw=1.3, ls=(0, (2, 3)), label="time averages"),
    ]


def _rate_legend():
    return [
        Line2D([], [], color=s.BLUE, lw=1.8, label="∂e/∂t"),
        Line2D([], [], color=s.ORANGE, lw=0, marker="o", markersize=4.5, label="−∂I/∂x"),
    ]
