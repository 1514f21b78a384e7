"""What the build measured about one scene's numerics, as the accuracy page and captions show it."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class SceneAccuracy:
    """One numerically computed scene: its settings, the reference it was checked against, and the result.

    Every field is deterministic (no wall-clock times): the built site must be byte-identical
    from build to build. Times come from `make bench`, which records them separately.
    """

    page: str  # slug of the page the scene is on, e.g. "newtons-laws"
    scene: str  # the scene's id; its row on the accuracy page has the HTML id f"acc-{page}-{scene}"
    model: str
    method: str  # e.g. "DOP853", "exact DST", "Gauss–Legendre n = 32", "analytic"
    settings: str  # e.g. "rtol 1e-6, atol 1e-9" (as an author would write them)
    tolerance: float  # the declared tolerance the measured error must not exceed
    error: float  # the largest error measured against the reference over the sampled stops
    metric: str  # what `error` is, e.g. "max |ΔR|/R₀ over one period"
    reference: str  # e.g. "Radau rtol 1e-12", "closed form"
    stops_measured: int
    evaluations: int  # function evaluations (nfev) summed over the checked stops
    # Displayed values checked against the reference's at the sampled stops: the wrong ones and those
    # where the reference lies within the tolerance of a rounding boundary ("stop: output", listed).
    digits_compared: bool = False  # whether the model compares displayed digits at all
    digits_wrong: tuple[str, ...] = ()
    near_boundary: tuple[str, ...] = ()

    @property
    def anchor(self) -> str:
        """The id of this scene's row on the accuracy page."""
        return f"acc-{self.page}-{self.scene}"

    @property
    def methods_anchor(self) -> str:
        """The id of its model's part on the accuracy page: what each method costs at this scene's stops."""
        return methods_anchor(self.model)


def methods_anchor(model: str) -> str:
    """The id of a model's part on the accuracy page (what the captions of its scenes link to)."""
    return f"methods-{model}"
