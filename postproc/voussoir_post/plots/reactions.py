"""The reactions of a run's supports over time (from its contact forces)."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np

from ..analysis.contact_forces import Reactions, reactions, reactions_table
from ..analysis.kinematics import ROLE_BACKING, ROLE_FILL, ROLE_FOUNDATION, ROLE_VOUSSOIR
from ..readers.results import RunResult
from ..tables import ReportTable
from .drawing import (G_M_S2, add_g_axis, legend_pad, new_figure, provenance, run_caption, save_figure,
                      wrap_text)

__all__ = ["ReactionsData", "plot_reactions", "free_weight_n", "support_names"]


@dataclass
class ReactionsData:
    """What :func:`plot_reactions` drew."""

    reactions: Reactions
    names: list[str]  #: one per support, as in the legend
    weight_n: float  #: the weight of the free blocks (NaN when the file lacks density or width)
    png_path: str | None = None
    summary: ReportTable = field(default_factory=lambda: ReportTable([]))

    def samples_table(self) -> ReportTable:
        """One row per output sample: each support's Fx, Fy [N] (for --csv)."""
        return reactions_table(self.reactions)


def free_weight_n(run: RunResult) -> float:
    """The weight of the free blocks [N]: density x width x polygon area x g, from the
    run's &arch density_kg_m3 and width_m and the blocks' shapes (NaN without them)."""
    arch = run.config.get("arch", {})
    density, width = arch.get("density_kg_m3"), arch.get("width_m")
    if not isinstance(density, (int, float)) or not isinstance(width, (int, float)):
        return math.nan
    free = np.nonzero(run.body_role == ROLE_VOUSSOIR)[0]
    densities = np.full(len(free), float(density))
    bridge = run.config.get("bridge")
    if bridge:
        # A bridge's free blocks: the voussoirs of every span, then the piers (their own density).
        n_ring = int(bridge.get("n_voussoirs", 0)) * sum(
            1 for k, v in bridge.items() if k.startswith("span_m(") and float(v) > 0)
        densities[n_ring:] = float(bridge.get("pier_density_kg_m3", density))
        # A fill of particles (role 4, after the ring and the piers): their own density.
        particles = np.nonzero(run.body_role == ROLE_FILL)[0]
        free = np.concatenate([free, particles])
        densities = np.concatenate([densities, np.full(len(particles), float(bridge.get("fill_density_kg_m3", 0.0)))])
        # The masonry backing (role 5): its own density.
        backing = np.nonzero(run.body_role == ROLE_BACKING)[0]
        free = np.concatenate([free, backing])
        densities = np.concatenate([densities, np.full(len(backing), float(bridge.get("backing_density_kg_m3", 2000.0)))])
    weight = 0.0
    for b, rho in zip(free, densities):
        x, y = run.vertices_local_m[b, : run.n_vertices[b]].T
        weight += rho * 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    return weight * float(width) * G_M_S2


def carries_constant_forces(run: RunResult) -> bool:
    """Whether the run's blocks carry forces besides their own weight: loads of &load, a
    vehicle (constant forces), a bridge's fill (its weight: the mass the blocks carry;
    its pressure: constant forces)."""
    load = run.config.get("load", {})
    bridge = run.config.get("bridge", {})
    return bool(run.config.get("vehicle")) or any(k.startswith("point_load_n(") for k in load) or \
        float(load.get("dead_load_n_per_m", 0.0) or 0.0) > 0 or float(bridge.get("fill_density_kg_m3", 0.0) or 0.0) > 0


def support_names(r: Reactions) -> list[str]:
    """'left springing' and 'right springing' for the two foundations of an arch, else
    'support k'; each with its body number (1-based, as in the file)."""
    foundations = [k for k, role in enumerate(r.role) if role == ROLE_FOUNDATION]
    names = []
    for k, (body, role) in enumerate(zip(r.bodies, r.role)):
        if len(foundations) == 2 and k in foundations:
            name = "left springing" if k == foundations[0] else "right springing"
        elif role == ROLE_FOUNDATION:
            name = f"support {k + 1}"
        else:
            name = f"restraint bracket {k + 1}"
        names.append(f"{name} (body {body + 1})")
    return names


def plot_reactions(run: RunResult, out_png: str | os.PathLike) -> ReactionsData:
    """Three panels against time [s]: the table's acceleration, the horizontal and the
    vertical reaction of every support [N] (the force it exerts on the blocks it carries:
    the mean force over the step that ends at each output sample), the sum of the vertical
    ones against the weight of the free blocks. Returns what was drawn."""
    r = reactions(run)
    data = ReactionsData(r, support_names(r), free_weight_n(run))
    fig = new_figure(8.0, 8.5)
    axes = fig.subplots(3, 1, sharex=True)
    axes[0].plot(r.time_s, run.table_a_m_s2, color="tab:blue")
    axes[0].set_ylabel("table a [m/s²]")
    add_g_axis(axes[0], "table a [g]")
    colours = ["tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink", "tab:olive"]
    for k, name in enumerate(data.names):
        colour = colours[k % len(colours)]
        axes[1].plot(r.time_s, r.force_n[:, k, 0], color=colour, linewidth=0.9, label=name)
        axes[2].plot(r.time_s, r.force_n[:, k, 1], color=colour, linewidth=0.9, label=name)
    axes[1].plot(r.time_s, r.total_n[:, 0], color="black", linewidth=0.9, linestyle=":")
    axes[2].plot(r.time_s, r.total_n[:, 1], color="black", linewidth=0.9, linestyle=":",
                 label="sum over the supports")
    if math.isfinite(data.weight_n):
        axes[1].plot(r.time_s, data.weight_n / G_M_S2 * run.table_a_m_s2, color="grey", linestyle="--",
                     linewidth=0.9)
        axes[2].axhline(data.weight_n, color="grey", linestyle="--", linewidth=0.9,
                        label=f"Fy: the weight of the free blocks, {data.weight_n:.4g} N;\nFx: their mass times "
                              "the table's acceleration\n(the sum while they move with the table" +
                              (";\nthe constant forces of &load, a vehicle, the fill's pressure\n"
                               "and the fill's weight, mass the blocks carry, come on top)"
                               if carries_constant_forces(run) else ")"))
    axes[1].set_ylabel("horizontal reaction Fx [N]\n(+: towards +x)")
    axes[2].set_ylabel("vertical reaction Fy [N]\n(+: upwards)")
    axes[2].set_xlabel("time [s]")
    fig.legend(handles=axes[2].get_lines(), loc="outside lower center", borderaxespad=legend_pad(8), ncols=2,
               fontsize=8)
    collapse = run.collapse_time_s if run.collapsed else math.nan
    for ax in axes:
        ax.grid(True, alpha=0.3)
        if math.isfinite(collapse):
            ax.axvline(collapse, color="tab:red", linestyle="--", linewidth=1.0)
    if math.isfinite(collapse):
        axes[0].annotate(f"collapse {collapse:.3f} s", (collapse, 1.0), xycoords=("data", "axes fraction"),
                         xytext=(0, 2), textcoords="offset points", ha="center", va="bottom", color="tab:red",
                         fontsize=8)
    # the run's caption a line for the structure and one for the shaking (on one line it is wider than
    # 8 inches at 9 pt), each wrapped to the figure's width
    fig.suptitle("\n".join(wrap_text(line, 8.0 - 0.3, 9.0) for line in (
        "Reactions of the supports over time: the force each exerts on the blocks it carries",
        "(mean over the time step that ends at each output sample)", *run_caption(run, "\n").split("\n"))),
        fontsize=9)
    data.png_path = save_figure(fig, out_png, note=provenance(run.code_version, run.input_file,
                                                           os.path.basename(run.path)))
    rows = []
    for k, name in enumerate(data.names):
        fx, fy = r.force_n[:, k, 0], r.force_n[:, k, 1]
        rows.append((name, float(fx.min()), float(fx.max()), float(fx[-1]), float(fy.min()), float(fy.max()),
                     float(fy[-1])))
    rows.append(("sum", float(r.total_n[:, 0].min()), float(r.total_n[:, 0].max()), float(r.total_n[-1, 0]),
                 float(r.total_n[:, 1].min()), float(r.total_n[:, 1].max()), float(r.total_n[-1, 1])))
    data.summary = ReportTable(["support", "fx_min_n", "fx_max_n", "fx_final_n", "fy_min_n", "fy_max_n",
                                "fy_final_n"], rows,
                               title=f"Reactions of {run.path} (weight of the free blocks {data.weight_n:.6g} N)")
    return data
