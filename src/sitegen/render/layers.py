"""Moving layers: shapes whose vertices are looked up from tables or read from sliders."""
from __future__ import annotations

from dataclasses import dataclass, field

Ref = float | str  # a number, "out:NAME" (a tabulated output) or "in:NAME" (a parameter's value)


@dataclass(frozen=True)
class Layer:
    """One moving shape drawn over axes `axes` with vertices given as references."""

    name: str
    kind: str  # "polyline" | "polygon"
    axes: int
    points: tuple[tuple[Ref, Ref], ...]
    style: dict[str, str] = field(default_factory=dict)

    def outputs(self) -> set[str]:
        """The tabulated outputs this layer reads."""
        return {r[4:] for xy in self.points for r in xy if isinstance(r, str) and r.startswith("out:")}
