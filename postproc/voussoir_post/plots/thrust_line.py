"""The thrust line of an arch over a run: where each joint's force crosses it, in time."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.colors import LinearSegmentedColormap

from ..analysis.contact_forces import ThrustLine, thrust_line
from ..readers.results import RunResult
from ..tables import ReportTable
from .drawing import HINGE_COLOURS, add_g_axis, new_figure, provenance, run_caption, save_figure

__all__ = ["ThrustLineData", "plot_thrust_line", "EDGE_FRACTION"]

#: A centre of pressure within this fraction of the joint from an edge counts as "at the edge".
EDGE_FRACTION = 0.05


@dataclass
class ThrustLineData:
    """What :func:`plot_thrust_line` drew."""

    thrust: ThrustLine
    png_path: str | None = None
    summary: ReportTable = field(default_factory=lambda: ReportTable([]))

    def samples_table(self) -> ReportTable:
        """One row per output sample: every joint's place of the centre of pressure (0
        intrados, 1 extrados; NaN open) and its normal force [N] (for --csv)."""
        nj = self.thrust.fraction.shape[1]
        columns = ["time_s"] + [f"joint{j}_fraction" for j in range(nj)] + [f"joint{j}_normal_n" for j in range(nj)]
        rows = [tuple([float(t)] + [float(v) for v in f] + [float(v) for v in n])
                for t, f, n in zip(self.thrust.time_s, self.thrust.fraction, self.thrust.normal_n)]
        return ReportTable(columns, rows)


def plot_thrust_line(run: RunResult, out_png: str | os.PathLike) -> ThrustLineData:
    """Two panels against time [s]: the table's acceleration, and for every joint (rows,
    0 at the left springing) the place of the centre of pressure of its contact forces
    across the joint, coloured from the intrados (0, green) to the extrados (1, blue), the
    colours of hinges on those sides in every figure; grey
    where the joint carries nothing (fully open)."""
    t = thrust_line(run)
    data = ThrustLineData(t)
    nj = t.fraction.shape[1]
    fig = new_figure(9.0, 7.0)
    axes = fig.subplots(2, 1, sharex=True, height_ratios=[1, 2.6])
    axes[0].plot(t.time_s, run.table_a_m_s2, color="tab:blue")
    axes[0].set_ylabel("table a [m/s²]")
    add_g_axis(axes[0], "table a [g]")
    axes[0].grid(True, alpha=0.3)
    cmap = LinearSegmentedColormap.from_list(
        "intrados_extrados", [HINGE_COLOURS["intrados"], "white", HINGE_COLOURS["extrados"]]).with_extremes(bad="#c8c8c8")
    # Cell edges: samples at their times, joints at integers.
    edges_t = np.concatenate([t.time_s, [t.time_s[-1] + (t.time_s[-1] - t.time_s[-2] if t.time_s.size > 1 else 1.0)]])
    mesh = axes[1].pcolormesh(edges_t, np.arange(nj + 1) - 0.5, np.ma.masked_invalid(t.fraction.T), cmap=cmap,
                              vmin=0.0, vmax=1.0, shading="flat")
    bar = fig.colorbar(mesh, ax=axes[1], location="right", fraction=0.05, pad=0.02)
    bar.set_label("centre of pressure across the joint\n0 intrados (green) … 1 extrados (blue)\ngrey: the joint "
                  "carries nothing")
    axes[1].set_ylabel("joint (0: left springing)")
    axes[1].set_yticks(range(nj))
    axes[1].set_xlabel("time [s]")
    collapse = run.collapse_time_s if run.collapsed else math.nan
    if math.isfinite(collapse):
        for ax in axes:
            ax.axvline(collapse, color="black", linestyle="--", linewidth=1.0)
        axes[0].annotate(f"collapse {collapse:.3f} s", (collapse, 1.0), xycoords=("data", "axes fraction"),
                         xytext=(0, 2), textcoords="offset points", ha="center", va="bottom", fontsize=8)
    fig.suptitle(f"Thrust line over time: where each joint's contact force crosses it (mean over the time step "
                 f"ending at each output sample)\n{run_caption(run)}", fontsize=9)
    data.png_path = save_figure(fig, out_png, note=provenance(run.code_version, run.input_file,
                                                           os.path.basename(run.path)))
    rows = []
    first = 1 if run.contact_count[0] == 0 else 0  # t = 0 before any step: no forces yet
    for j in range(nj):
        f = t.fraction[first:, j]
        carried = np.isfinite(f)
        rows.append((j, float(np.nanmin(f)) if carried.any() else math.nan,
                     float(np.nanmax(f)) if carried.any() else math.nan,
                     int(np.count_nonzero(carried & (f <= EDGE_FRACTION))),
                     int(np.count_nonzero(carried & (f >= 1.0 - EDGE_FRACTION))),
                     int(np.count_nonzero(~carried)), float(np.max(t.normal_n[first:, j]))))
    data.summary = ReportTable(["joint", "fraction_min", "fraction_max", "samples_at_intrados",
                                "samples_at_extrados", "samples_open", "max_normal_n"], rows,
                               title=f"Thrust line of {run.path}: the centre of pressure across each joint "
                                     f"(0 intrados, 1 extrados; at an edge: within {EDGE_FRACTION:g} of it), "
                                     f"over the samples after t = 0")
    return data
