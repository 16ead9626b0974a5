"""The load-position curve of a path of ``&load`` (``voussoir-limit --json``'s
``load_factor_curve``): the load factor against the vehicle's position, the grid's points
and the positions refined at the joints marked apart, the critical one labelled. One
curve per case (e.g. the bridge with and without the fill's passive pressure), each in
its colour; a right-hand axis reads the load factor as the collapse live load in kN
(lambda times the vehicle's live loads, the same in every case).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.ticker import FuncFormatter

from ..tables import ReportTable
from .drawing import COLORS, legend_pad, new_figure, save_figure, wrap_text

__all__ = ["CurveCase", "LoadPositionData", "plot_load_position"]


@dataclass(frozen=True)
class CurveCase:
    """One case's curve, as the JSON gives it."""

    label: str  #: e.g. 'with passive pressure (m = 0.33)'
    x_m: np.ndarray  #: the vehicle's positions [m]
    load_factor: np.ndarray  #: lambda at each (NaN where the LP had none)
    at_joint: np.ndarray  #: bool: refined over a joint's end, not a grid point
    critical_x_m: float
    critical_load_factor: float


@dataclass
class LoadPositionData:
    """What :func:`plot_load_position` drew."""

    png_path: str
    table: ReportTable = field(default_factory=lambda: ReportTable([]))


def plot_load_position(cases: list[CurveCase], live_total_n: float, out_png: str | os.PathLike, title: str,
                       note: str = "") -> LoadPositionData:
    """The curves of ``cases`` in one axes; ``live_total_n`` the vehicle's live loads at
    load factor 1 (for the kN axis); ``title`` says what bridge and vehicle."""
    fig = new_figure(9.0, 5.6)
    ax = fig.subplots()
    handles = []
    rows = []
    for k, case in enumerate(cases):
        colour = COLORS[k % len(COLORS)]
        order = np.argsort(case.x_m, kind="stable")
        x, lam, joint = case.x_m[order], case.load_factor[order], case.at_joint[order]
        ax.plot(x, lam, "-", color=colour, linewidth=1.2, zorder=3)
        ax.plot(x[~joint], lam[~joint], "o", color=colour, markersize=5, zorder=4)
        ax.plot(x[joint], lam[joint], "^", color=colour, markerfacecolor="white", markersize=6, zorder=4)
        none = ~np.isfinite(lam)
        if none.any():   # the LP found no collapse there (e.g. a load standing on a pier)
            ax.plot(x[none], np.full(none.sum(), 0.015), "x", color=colour, markersize=6, zorder=4,
                    transform=ax.get_xaxis_transform(), clip_on=False)
        ax.plot([case.critical_x_m], [case.critical_load_factor], "*", color="tab:red", markersize=15,
                markeredgecolor="black", zorder=6)
        # The labels stacked in the band kept free below the curves, each joined to its star.
        ax.annotate(f"critical: x = {case.critical_x_m:.3f} m, λ = {case.critical_load_factor:.4g} "
                    f"({case.critical_load_factor * live_total_n / 1e3:.4g} kN)",
                    (case.critical_x_m, case.critical_load_factor), textcoords="axes fraction",
                    xytext=(0.5, 0.06 + 0.07 * (len(cases) - 1 - k)), fontsize=8, color=colour, ha="center",
                    va="bottom", bbox=dict(boxstyle="round,pad=0.2", facecolor="white", edgecolor=colour,
                                           alpha=0.9),
                    arrowprops=dict(arrowstyle="-", color=colour, linewidth=0.6), zorder=7)
        handles.append(Line2D([], [], color=colour, linewidth=1.2, label=case.label))
        for xi, li, ji in zip(x, lam, joint):
            rows.append((case.label, float(xi), float(li), bool(ji),
                         bool(xi == case.critical_x_m and li == case.critical_load_factor)))
    grey = "#555555"
    handles += [Line2D([], [], linestyle="none", marker="o", color=grey, markersize=5,
                       label="grid point of the path (path_x0_m .. path_x1_m)"),
                Line2D([], [], linestyle="none", marker="^", color=grey, markerfacecolor="white", markersize=6,
                       label="refined: a live load a micrometre to either side of a joint's extrados end"),
                Line2D([], [], linestyle="none", marker="*", color="tab:red", markeredgecolor="black",
                       markersize=12, label="critical position (the least load factor)")]
    if any((~np.isfinite(c.load_factor)).any() for c in cases):
        handles.append(Line2D([], [], linestyle="none", marker="x", color=grey, markersize=6,
                              label="no load factor there (the LP found no collapse)"))
    finite = np.concatenate([c.load_factor[np.isfinite(c.load_factor)] for c in cases])
    if finite.size:
        lo, hi = float(finite.min()), float(finite.max())
        pad = 0.08 * (hi - lo if hi > lo else max(abs(hi), 1.0))
        ax.set_ylim(lo - (2.5 + 1.0 * len(cases)) * pad, hi + pad)
    # The band below the curves holds the labels: no negative load factor or load is read there.
    blank_negative = FuncFormatter(lambda v, _pos: "" if v < -1e-9 else f"{v:g}")
    ax.yaxis.set_major_formatter(blank_negative)
    ax.set_xlabel("vehicle position x [m] from the left springing of span 1 (the resultant of its live loads)")
    ax.set_ylabel("collapse load factor λ on the live load")
    if math.isfinite(live_total_n) and live_total_n > 0:
        right = ax.secondary_yaxis("right", functions=(lambda a: a * live_total_n / 1e3,
                                                       lambda kn: kn * 1e3 / live_total_n))
        right.set_ylabel(f"collapse live load λ × {live_total_n / 1e3:.4g} kN [kN]")
        right.yaxis.set_major_formatter(blank_negative)
    ax.grid(True, alpha=0.3)
    ax.set_title("\n".join(wrap_text(line, 8.6, 10) for line in title.split("\n")), fontsize=10)
    fig.legend(handles=handles, loc="outside lower center", borderaxespad=legend_pad(8), ncols=2, fontsize=8)
    png = save_figure(fig, out_png, note=note or None)
    table = ReportTable(["case", "x_m", "load_factor", "at_joint", "critical"], rows,
                        title="load factor against the vehicle's position")
    return LoadPositionData(png, table)
