"""Figure helpers: Agg figures without pyplot (no global figure state), PNG output."""

from __future__ import annotations

import os

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

__all__ = ["new_figure", "save_png", "MARKERS", "COLORS"]

#: Marker style per specimen or parameter set, in order.
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "<", ">", "h")
#: Colour cycle (matplotlib's tab10).
COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
          "tab:pink", "tab:gray", "tab:olive", "tab:cyan")


def new_figure(width_in: float, height_in: float) -> Figure:
    """A figure drawn by the Agg canvas (independent of pyplot and its global state)."""
    fig = Figure(figsize=(width_in, height_in), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def save_png(fig: Figure, path: str | os.PathLike, dpi: int = 120) -> str:
    """Save ``fig`` as PNG at ``path`` (parent folders created); returns the path."""
    path = os.fspath(path)
    parent = os.path.dirname(os.path.abspath(path))
    os.makedirs(parent, exist_ok=True)
    fig.savefig(path, dpi=dpi, format="png")
    return path
