"""Collapse mechanisms of the limit analysis (``voussoir-limit --json``), drawn on the arch.

Drawn with y = 0 at the springings (the intrados ends of joints 0 and n) and x = 0 at
midspan; the JSON's coordinates have their origin at the circle's centre. Towards +x the
line of thrust is the LP's: the centre of pressure of each joint's contact forces, with
the joint's resultant drawn as an arrow there (scaled in N, the key says how); towards -x,
where the LP is not solved, it is that of the four-hinge analysis.
"""

from __future__ import annotations

import math
import os
import textwrap
from dataclasses import dataclass, field

import numpy as np
from matplotlib.patches import Polygon

from ..analysis.contact_forces import LpJointResultants, lp_joint_resultants
from ..readers.results import LimitResult
from ..tables import ReportTable
from ..units import G_M_S2
from .drawing import HINGE_COLOURS, legend_pad, new_figure, provenance, save_figure

#: The LP's joint forces: dark grey, a colour that no hinge, joint or collapse uses.
FORCE_COLOUR = "#444444"

__all__ = ["G_M_S2", "MechanismPanel", "MechanismData", "voussoir_polygons", "foundation_polygons",
           "plot_mechanism"]



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
    #: The LP's joint forces at collapse (towards +x only), whose centres of pressure are thrust_xy_m.
    lp_forces: LpJointResultants | None = None

    @property
    def accel_m_s2(self) -> float:
        return self.load_factor * self.g_m_s2


@dataclass
class MechanismData:
    """What :func:`plot_mechanism` drew."""

    voussoirs_m: list[np.ndarray]  #: in the JSON's frame
    panels: list[MechanismPanel]  #: in the JSON's frame
    png_path: str | None = None
    table: ReportTable = field(default_factory=lambda: ReportTable([]))
    springing_y_m: float = 0.0  #: the JSON's y of the springings, drawn as y = 0
    force_scale_m_per_n: float = math.nan  #: arrow length per newton of the joint forces
    force_key_n: float = math.nan  #: the force of the key arrow [N]


def _capacity_text(panel: MechanismPanel) -> str:
    """λ and λg, or why there is none (null lambda in the JSON, or a negative one)."""
    if math.isnan(panel.load_factor):
        return "no admissible mechanism"
    if panel.load_factor < 0:
        return f"load factor λ = {panel.load_factor:.4g}: the arch cannot carry its own weight"
    return (f"collapse load factor λ = {panel.load_factor:.3f}\n(horizontal acceleration "
            f"{panel.accel_m_s2:.3g} m/s² = {panel.load_factor:.3f} g)")


def _nice_force_n(largest_n: float) -> float:
    """A round force near `largest_n` for the key arrow: 1, 2 or 5 times a power of ten."""
    if not largest_n > 0:
        return 1.0
    power = 10.0 ** math.floor(math.log10(largest_n))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= largest_n)


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
    mechanism marked at the joint end they pivot on and labelled ``<joint><i|e>``.
    A load case of ``&load`` (live point loads) and any assembly other than the arch
    builder's (a wall, a polygon file, a restrained arch, a bridge) are drawn from the
    LP's own mechanism and forces instead (:mod:`.mechanism_lp`): the four-hinge analysis
    is of the arch's weights under horizontal acceleration alone."""
    if limit.assembly != "arch" or not limit.has_arch or not limit.live_is_acceleration:
        from .mechanism_lp import plot_lp_mechanism
        return plot_lp_mechanism(limit, out_png)
    intr, extr = limit.joint_intrados_xy_m, limit.joint_extrados_xy_m
    voussoirs = voussoir_polygons(intr, extr)
    foundations = foundation_polygons(intr, extr, limit.thickness_m)
    lp = lp_joint_resultants(limit)
    panels = []
    for direction, lam, hinges, sliding, fraction in (
            ("+x", limit.lambda_pos, limit.hinges_pos, limit.sliding_pos, limit.thrust_fraction_pos),
            ("-x", limit.lambda_neg, limit.hinges_neg, limit.sliding_neg, limit.thrust_fraction_neg)):
        xy = np.array([intr[j] if side == "intrados" else extr[j] for j, side in hinges]).reshape(-1, 2)
        sliding = limit.sliding if sliding is None else sliding
        forces = lp if direction == "+x" else None
        thrust = forces.point_m if forces is not None else thrust_points(limit, fraction)
        panels.append(MechanismPanel(direction, lam, list(hinges), xy,
                                     [int(j) for j in sliding if isinstance(j, (int, float))], limit.g_m_s2,
                                     thrust, forces))
    # Drawn with y = 0 at the springings (the JSON's origin is the circle's centre).
    y0 = float(min(intr[0, 1], intr[-1, 1]))
    up = np.array([0.0, y0])
    voussoirs_drawn = [p - up for p in voussoirs]
    foundations = [p - up for p in foundations]

    pts = np.vstack(voussoirs_drawn + foundations)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = float(max(hi - lo))
    axes_height_in = 0.5 * 11.0 * (hi[1] - lo[1] + 0.3 * span) / (hi[0] - lo[0] + 0.2 * span)
    fig = new_figure(11.0, axes_height_in + 2.0)
    axes = fig.subplots(1, 2)
    # Joint forces: the largest arrow a tenth of the span long.
    largest = float(np.max(np.hypot(*lp.force_n.T))) if lp is not None else math.nan
    scale = span / 10.0 / largest if largest > 0 else math.nan
    key_n = _nice_force_n(largest) if largest > 0 else math.nan
    for ax, panel in zip(axes, panels):
        for poly in voussoirs_drawn:
            ax.add_patch(Polygon(poly, closed=True, facecolor="#e8c99b", edgecolor="#333333", linewidth=0.7))
        for poly in foundations:
            ax.add_patch(Polygon(poly, closed=True, facecolor="#9e9e9e", edgecolor="#333333", linewidth=0.7,
                                 hatch="//"))
        for (j, side), (x, y) in zip(panel.hinges, panel.hinge_xy_m):
            colour = HINGE_COLOURS[side]
            ax.plot(x, y - y0, "o", color=colour, markersize=8, markeredgecolor="white", zorder=5)
            # Label outward (extrados) or inward (intrados) along the radius from the circle's centre.
            radial = np.array([x, y]) / max(math.hypot(x, y), 1e-12)
            offset = (radial if side == "extrados" else -radial) * 14
            ax.annotate(f"{j}{side[0]}", (x, y - y0), textcoords="offset points", xytext=tuple(offset),
                        ha="center", va="center", fontsize=9, color=colour, fontweight="bold")
        if panel.thrust_xy_m is not None:
            ax.plot(panel.thrust_xy_m[:, 0], panel.thrust_xy_m[:, 1] - y0, "-", color="black", linewidth=1.2,
                    zorder=4)
        if panel.lp_forces is not None and scale > 0:
            at = panel.lp_forces.point_m - up
            arrows = ax.quiver(at[:, 0], at[:, 1], panel.lp_forces.force_n[:, 0], panel.lp_forces.force_n[:, 1],
                               angles="xy", scale_units="xy", scale=1.0 / scale, color=FORCE_COLOUR, width=0.005,
                               pivot="middle", zorder=6)
            ax.quiverkey(arrows, 0.12, 0.93, key_n, f"{key_n:g} N", labelpos="E", coordinates="axes",
                         fontproperties={"size": 8})
        for j in panel.sliding_joints:
            if 0 <= j < intr.shape[0]:
                ax.plot(*(np.array([intr[j], extr[j]]) - up).T, "-", color=HINGE_COLOURS["separated"], linewidth=3,
                        zorder=4)
        ax.annotate("", xy=(0.62, 0.06), xytext=(0.38, 0.06), xycoords="axes fraction",
                    arrowprops=dict(arrowstyle="->" if panel.direction == "+x" else "<-", color="black"))
        ax.text(0.5, 0.09, "inertial load", transform=ax.transAxes, ha="center", fontsize=8)
        ax.set_xlim(lo[0] - 0.1 * span, hi[0] + 0.1 * span)
        ax.set_ylim(lo[1] - 0.12 * span, hi[1] + 0.15 * span)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m] from midspan")
        ax.set_ylabel("y [m] above the springings")
        ax.set_title(f"towards {panel.direction}: {_capacity_text(panel)}", fontsize=10)
        ax.grid(True, alpha=0.2)
    handles = [axes[0].plot([], [], "o", color=c, label=f"hinge pivoting on the {s} ({s[0]})")[0]
               for c, s in ((HINGE_COLOURS["intrados"], "intrados"), (HINGE_COLOURS["extrados"], "extrados"))]
    if any(p.thrust_xy_m is not None for p in panels):
        source = ("+x: the centres of pressure of the LP's contact forces; -x: the four-hinge analysis"
                  if lp is not None else "its crossing of each joint")
        handles.append(axes[0].plot([], [], "-", color="black", linewidth=1.2,
                                    label=f"line of thrust at collapse ({source}): it touches the hinges "
                                          "and stays in the ring")[0])
    if lp is not None:
        lp_note = ""
        # Only where the LP is below the four-hinge analysis of the same load (sliding).
        if limit.load_factor < limit.lambda_pos * (1.0 - 1e-6):
            lp_note = f": with sliding, below the four-hinge {limit.lambda_pos:.3f}"
        handles.append(axes[0].plot([], [], linestyle="none", marker=r"$\rightarrow$", markersize=14,
                                    color=FORCE_COLOUR,
                                    label=f"force across each joint in the LP's static field at collapse (λ = {limit.load_factor:.3f}{lp_note}, "
                                          f"load towards +x), from the "
                                          f"part on its left onto the part on its right, centred on its centre of pressure; "
                                          f"arrows to scale: {key_n:g} N = {key_n * scale * 1e3:.0f} mm")[0])
    if any(p.sliding_joints for p in panels):
        friction = "" if math.isnan(limit.friction) else f" (friction {limit.friction:g})"
        handles.append(axes[0].plot([], [], "-", color=HINGE_COLOURS["separated"], linewidth=3,
                                    label=f"joint that would slide: |T|/N above the friction{friction}")[0])
    for h in handles:  # long entries on two lines, so that the legend fits the figure's width
        h.set_label(textwrap.fill(h.get_label(), 120))
    fig.legend(handles=handles, loc="outside lower center", borderaxespad=legend_pad(8), ncols=1 if lp else 2,
               fontsize=8)
    # Room for the axes, two lines of suptitle, two of panel titles, the x label and the legend.
    legend_lines = sum(h.get_label().count("\n") + 1 for h in handles)
    if not lp:
        legend_lines = (legend_lines + 1) // 2
    fig.set_size_inches(11.0, axes_height_in + 1.4 + 0.15 * legend_lines)
    sliding = f"; sliding governs at joints {', '.join(map(str, limit.sliding))}" if limit.sliding else ""
    fig.suptitle(f"Static collapse mechanisms under horizontal acceleration (limit analysis):\n"
                 f"{limit.embrace_deg:g}° arch of {limit.n_voussoirs} voussoirs, t = {limit.thickness_m * 1e3:.4g} mm, "
                 f"R_ext = {limit.r_ext_m * 1e3:.4g} mm{sliding}", fontsize=10)
    png = save_figure(fig, out_png, note=provenance(limit.code_version, limit.input_file,
                                                 os.path.basename(limit.path)))
    rows = []
    for panel in panels:
        for (j, side), (x, y) in zip(panel.hinges, panel.hinge_xy_m):
            rows.append((panel.direction, panel.load_factor, panel.accel_m_s2, j, side, float(x), float(y - y0),
                         j in panel.sliding_joints))
    table = ReportTable(["direction", "lambda", "accel_m_s2", "joint", "side", "x_m", "y_above_springings_m",
                         "slides"], rows, title=f"Mechanisms of {limit.path}")
    return MechanismData(voussoirs, panels, png, table, y0, scale, key_n)
