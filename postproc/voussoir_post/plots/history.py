"""Time histories of a run: table motion, crown displacement, solver effort, contacts."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np

from ..readers.results import RunResult
from ..tables import ReportTable
from .drawing import add_g_axis, new_figure, provenance, run_caption, save_figure

__all__ = ["HistoryData", "plot_history"]


@dataclass
class HistoryData:
    """The series :func:`plot_history` drew (samples and steps), in plotted units."""

    time_s: np.ndarray
    table_x_mm: np.ndarray
    table_v_m_s: np.ndarray
    table_a_m_s2: np.ndarray
    crown_dx_mm: np.ndarray
    crown_dy_mm: np.ndarray
    contact_count: np.ndarray
    step_time_s: np.ndarray
    step_iterations: np.ndarray
    collapse_time_s: float
    png_path: str | None = None
    summary: ReportTable = field(default_factory=lambda: ReportTable([]))

    def samples_table(self) -> ReportTable:
        """One row per output sample (for --csv)."""
        return ReportTable(["time_s", "table_x_mm", "table_v_m_s", "table_a_m_s2", "crown_dx_mm",
                            "crown_dy_mm", "contact_count"],
                           [tuple(float(v) for v in row[:-1]) + (int(row[-1]),) for row in zip(
                               self.time_s, self.table_x_mm, self.table_v_m_s, self.table_a_m_s2,
                               self.crown_dx_mm, self.crown_dy_mm, self.contact_count)])

    def steps_table(self) -> ReportTable:
        """One row per time step (for --csv)."""
        return ReportTable(["step_time_s", "iterations"],
                           [(float(t), int(i)) for t, i in zip(self.step_time_s, self.step_iterations)])


def _summary(data: HistoryData) -> ReportTable:
    rows = []
    for name, t, values in (
        ("table_x_mm", data.time_s, data.table_x_mm),
        ("table_v_m_s", data.time_s, data.table_v_m_s),
        ("table_a_m_s2", data.time_s, data.table_a_m_s2),
        ("crown_dx_mm", data.time_s, data.crown_dx_mm),
        ("crown_dy_mm", data.time_s, data.crown_dy_mm),
        ("nlgs_iterations", data.step_time_s, data.step_iterations),
        ("contact_count", data.time_s, data.contact_count),
    ):
        if values.size == 0:
            rows.append((name, math.nan, math.nan, math.nan, math.nan, math.nan))
            continue
        k_min, k_max = int(np.argmin(values)), int(np.argmax(values))
        rows.append((name, float(values[k_min]), float(t[k_min]), float(values[k_max]), float(t[k_max]),
                     float(values[-1])))
    return ReportTable(["series", "min", "t_min_s", "max", "t_max_s", "final"], rows)


def plot_history(run: RunResult, out_png: str | os.PathLike) -> HistoryData:
    """Stacked panels against time [s]: table displacement, velocity, acceleration, crown
    dx/dy [mm], NLGS iterations per step and active contact points; the collapse time
    is drawn as a dashed line. Returns the plotted series."""
    data = HistoryData(
        time_s=run.time_s,
        table_x_mm=1e3 * run.table_x_m,
        table_v_m_s=run.table_v_m_s,
        table_a_m_s2=run.table_a_m_s2,
        crown_dx_mm=1e3 * run.crown_dx_m,
        crown_dy_mm=1e3 * run.crown_dy_m,
        contact_count=run.contact_count,
        step_time_s=run.step_time_s,
        step_iterations=run.step_iterations,
        collapse_time_s=run.collapse_time_s if run.collapsed else math.nan,
    )
    fig = new_figure(8.0, 11.0)
    axes = fig.subplots(6, 1, sharex=True)
    axes[0].plot(data.time_s, data.table_x_mm, color="tab:blue")
    axes[0].set_ylabel("table x [mm]")
    axes[1].plot(data.time_s, data.table_v_m_s, color="tab:blue")
    axes[1].set_ylabel("table v [m/s]")
    axes[2].plot(data.time_s, data.table_a_m_s2, color="tab:blue")
    axes[2].set_ylabel("table a [m/s²]")
    add_g_axis(axes[2], "table a [g]")
    axes[3].plot(data.time_s, data.crown_dx_mm, label="dx (horizontal)", color="tab:orange")
    axes[3].plot(data.time_s, data.crown_dy_mm, label="dy (vertical)", color="tab:green")
    axes[3].set_ylabel("crown rel. table [mm]")
    if math.isfinite(data.collapse_time_s):
        # The rocking before the collapse is what an engineer reads; the fall after it
        # runs to metres and would flatten it: the panel is scaled on the motion before.
        before = data.time_s <= data.collapse_time_s
        peak = max(1.0, float(np.abs(np.concatenate([data.crown_dx_mm[before], data.crown_dy_mm[before]])).max()))
        axes[3].set_ylim(-1.5 * peak, 1.5 * peak)
        axes[3].text(0.99, 0.04, "after the collapse the crown falls off this scale", transform=axes[3].transAxes,
                     ha="right", fontsize=7, color="tab:red")
    axes[3].legend(loc="upper left", fontsize=8)
    axes[4].plot(data.step_time_s, data.step_iterations, color="tab:purple", linewidth=0.7)
    axes[4].set_ylabel("NLGS iterations")
    axes[5].step(data.time_s, data.contact_count, where="post", color="tab:brown")
    axes[5].set_ylabel("contact points")
    axes[5].set_xlabel("time [s]")
    if math.isfinite(data.collapse_time_s):
        for ax in axes:
            ax.axvline(data.collapse_time_s, color="tab:red", linestyle="--", linewidth=1.0)
        axes[0].annotate(f"collapse {data.collapse_time_s:.3f} s", (data.collapse_time_s, 1.0),
                         xycoords=("data", "axes fraction"), xytext=(4, -12),
                         textcoords="offset points", color="tab:red", fontsize=8)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    status = f"collapsed at {run.collapse_time_s:.3f} s" if run.collapsed else "stood"
    fig.suptitle(f"Time histories: {run_caption(run, sep=chr(10))}\n{status}; mean {run.mean_iterations:.1f} "
                 f"NLGS iterations/step, {run.nonconverged_steps} non-converged steps", fontsize=9)
    data.png_path = save_figure(fig, out_png, note=provenance(run.code_version, run.input_file,
                                                           os.path.basename(run.path)))
    data.summary = _summary(data)
    data.summary.title = f"History of {run.path}"
    return data
