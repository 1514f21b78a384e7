"""The report views of the models whose bench results the accuracy page shows, by model name (as FIGURES
holds the figure views): each draws the parts its model declares in `Model.reports`."""
from __future__ import annotations

from .bubble import BubbleReport
from .chain import ChainReport

REPORT_VIEWS = {
    "chain": ChainReport(),
    "bubble": BubbleReport(),
}
