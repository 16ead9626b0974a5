"""Collapse mechanisms of the limit analysis (``voussoir-limit --json``), drawn on the arch."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.patches import Polygon

from ..readers.results import LimitResult
from ..tables import ReportTable
from .drawing import legend_pad, new_figure, provenance, save_png

__all__ = ["G_M_S2", "MechanismPanel", "MechanismData", "voussoir_polygons", "foundation_polygons",
           "plot_mechanism"]

G_M_S2 = 9.81  #: gravity [m/s2] of the Fortran kernel (voussoir_kinds), when the JSON has no g_m_s2


def voussoir_polygons(intrados_xy_m: np.ndarray, extrados_xy_m: np.ndarray) -> list[np.ndarray]:
    """Voussoir k (1..n) as the quadrilateral of joints k-1 and k (counter-clockwise)."""
    n = intrados_xy_m.shape[0] - 1
    return [np.array([intrados_xy_m[k - 1], intrados_xy_m[k], extrados_xy_m[k], extrados_xy_m[k - 1]])
            for k in range(1, n + 1)]


def foundation_polygons(intrados_xy_m: np.ndarray, extrados_xy_m: np.ndarray,
                        depth_m: float) -> list[np.ndarray]:
    """The two foundation blocks under the springing joints, as the arch builder makes them
    (the joint on top, vertical sides, a flat bottom ``depth_m`` below its lower end)."""
    def block(left_top, right_top):
        y_bottom = min(left_top[1], right_top[1]) - depth_m
        return np.array([[left_top[0], y_bottom], [right_top[0], y_bottom], right_top, left_top])
    return [block(extrados_xy_m[0], intrados_xy_m[0]), block(intrados_xy_m[-1], extrados_xy_m[-1])]


@dataclass
class MechanismPanel:
    """One direction of the limit analysis."""

    direction: str  #: '+x' or '-x'
    load_factor: float  #: lambda: collapse acceleration / g
    hinges: list[tuple[int, str]]
    hinge_xy_m: np.ndarray  #: (n_hinges, 2) drawn points
    sliding_joints: list[int]  #: joints where friction does not carry the collapse thrust
    g_m_s2: float = G_M_S2
    thrust_xy_m: np.ndarray | None = None  #: (n+1, 2) where the collapse thrust crosses each joint

    @property
    def accel_m_s2(self) -> float:
        return self.load_factor * self.g_m_s2


@dataclass
class MechanismData:
    """What :func:`plot_mechanism` drew."""

    voussoirs_m: list[np.ndarray]
    panels: list[MechanismPanel]
    png_path: str | None = None
    table: ReportTable = field(default_factory=lambda: ReportTable([]))


def _capacity_text(panel: MechanismPanel) -> str:
    """λ and λg, or why there is none (null lambda in the JSON, or a negative one)."""
    if math.isnan(panel.load_factor):
        return "no admissible mechanism"
    if panel.load_factor < 0:
        return f"λ = {panel.load_factor:.4g}: the arch cannot carry its own weight"
    return f"collapses at {panel.load_factor:.3g} g (λ; a = {panel.accel_m_s2:.3g} m/s²)"


def thrust_points(limit: LimitResult, fraction: np.ndarray | None) -> np.ndarray | None:
    """Where the thrust crosses each joint [m]: between the joint's two pivots (its ends,
    moved in by the contact inset), at `fraction` from the intrados one."""
    if fraction is None or not np.all(np.isfinite(fraction)):
        return None
    intr, extr = limit.joint_intrados_xy_m, limit.joint_extrados_xy_m
    along = (extr - intr) / np.linalg.norm(extr - intr, axis=1)[:, None]
    pivot_i = intr + limit.contact_inset_m * along
    pivot_e = extr - limit.contact_inset_m * along
    return pivot_i + fraction[:, None] * (pivot_e - pivot_i)


def plot_mechanism(limit: LimitResult, out_png: str | os.PathLike) -> MechanismData:
    """Two panels (towards +x and -x): the arch's voussoirs with the hinges of the
    mechanism marked at the joint end they pivot on and labelled ``<joint><i|e>``."""
    intr, extr = limit.joint_intrados_xy_m, limit.joint_extrados_xy_m
    voussoirs = voussoir_polygons(intr, extr)
    foundations = foundation_polygons(intr, extr, limit.thickness_m)
    panels = []
    for direction, lam, hinges, sliding, fraction in (
            ("+x", limit.lambda_pos, limit.hinges_pos, limit.sliding_pos, limit.thrust_fraction_pos),
            ("-x", limit.lambda_neg, limit.hinges_neg, limit.sliding_neg, limit.thrust_fraction_neg)):
        xy = np.array([intr[j] if side == "intrados" else extr[j] for j, side in hinges]).reshape(-1, 2)
        sliding = limit.sliding if sliding is None else sliding
        panels.append(MechanismPanel(direction, lam, list(hinges), xy,
                                     [int(j) for j in sliding if isinstance(j, (int, float))], limit.g_m_s2,
                                     thrust_points(limit, fraction)))

    pts = np.vstack(voussoirs + foundations)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = float(max(hi - lo))
    fig = new_figure(11.0, 0.5 * 11.0 * (hi[1] - lo[1] + 0.3 * span) / (hi[0] - lo[0] + 0.2 * span) + 1.4)
    axes = fig.subplots(1, 2)
    for ax, panel in zip(axes, panels):
        for poly in voussoirs:
            ax.add_patch(Polygon(poly, closed=True, facecolor="#e8c99b", edgecolor="#333333", linewidth=0.7))
        for poly in foundations:
            ax.add_patch(Polygon(poly, closed=True, facecolor="#9e9e9e", edgecolor="#333333", linewidth=0.7,
                                 hatch="//"))
        for (j, side), (x, y) in zip(panel.hinges, panel.hinge_xy_m):
            colour = "tab:red" if side == "intrados" else "tab:blue"
            ax.plot(x, y, "o", color=colour, markersize=8, markeredgecolor="white", zorder=5)
            # Label outward (extrados) or inward (intrados) along the radius.
            radial = np.array([x, y]) / max(math.hypot(x, y), 1e-12)
            offset = (radial if side == "extrados" else -radial) * 14
            ax.annotate(f"{j}{side[0]}", (x, y), textcoords="offset points", xytext=tuple(offset),
                        ha="center", va="center", fontsize=9, color=colour, fontweight="bold")
        if panel.thrust_xy_m is not None:
            ax.plot(*panel.thrust_xy_m.T, "-", color="black", linewidth=1.2, zorder=4)
        for j in panel.sliding_joints:
            if 0 <= j < intr.shape[0]:
                ax.plot(*np.array([intr[j], extr[j]]).T, "-", color="tab:purple", linewidth=3, zorder=4)
        ax.annotate("", xy=(0.62, 0.06), xytext=(0.38, 0.06), xycoords="axes fraction",
                    arrowprops=dict(arrowstyle="->" if panel.direction == "+x" else "<-", color="black"))
        ax.text(0.5, 0.09, "inertial load", transform=ax.transAxes, ha="center", fontsize=8)
        ax.set_xlim(lo[0] - 0.1 * span, hi[0] + 0.1 * span)
        ax.set_ylim(lo[1] - 0.12 * span, hi[1] + 0.15 * span)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title(f"towards {panel.direction}: {_capacity_text(panel)}", fontsize=10)
        ax.grid(True, alpha=0.2)
    handles = [axes[0].plot([], [], "o", color=c, label=f"hinge pivoting on the {s} ({s[0]})")[0]
               for c, s in (("tab:red", "intrados"), ("tab:blue", "extrados"))]
    if any(p.thrust_xy_m is not None for p in panels):
        handles.append(axes[0].plot([], [], "-", color="black", linewidth=1.2,
                                    label="line of thrust at collapse (its crossing of each joint): it must "
                                          "touch the four hinges and stay in the ring")[0])
    if any(p.sliding_joints for p in panels):
        friction = "" if math.isnan(limit.friction) else f" (friction {limit.friction:g})"
        handles.append(axes[0].plot([], [], "-", color="tab:purple", linewidth=3,
                                    label=f"joint that would slide: |T|/N above the friction{friction}")[0])
    fig.legend(handles=handles, loc="outside lower center", borderaxespad=legend_pad(8), ncols=2, fontsize=8)
    sliding = f"; sliding governs at joints {', '.join(map(str, limit.sliding))}" if limit.sliding else ""
    fig.suptitle(f"Static collapse mechanisms under horizontal acceleration (limit analysis): "
                 f"{limit.embrace_deg:g}° arch of {limit.n_voussoirs} voussoirs, t = {limit.thickness_m * 1e3:.4g} mm, "
                 f"R_ext = {limit.r_ext_m * 1e3:.4g} mm{sliding}", fontsize=10)
    png = save_png(fig, out_png, note=provenance(limit.code_version, limit.input_file,
                                                 os.path.basename(limit.path)))
    rows = []
    for panel in panels:
        for (j, side), (x, y) in zip(panel.hinges, panel.hinge_xy_m):
            rows.append((panel.direction, panel.load_factor, panel.accel_m_s2, j, side, float(x), float(y),
                         j in panel.sliding_joints))
    table = ReportTable(["direction", "lambda", "accel_m_s2", "joint", "side", "x_m", "y_m", "slides"], rows,
                        title=f"Mechanisms of {limit.path}")
    return MechanismData(voussoirs, panels, png, table)
