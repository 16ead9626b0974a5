"""The LP's collapse mechanism drawn on any assembly (``voussoir-limit --json``): a load
case of ``&load`` (live point loads, an axle group, a path's critical position), a wall,
a polygon file, a restrained arch, a bridge.

Drawn from the JSON's ``blocks`` (free blocks buff, driven ones grey and hatched), the
LP's ``mechanism`` (hinges where they turn, interfaces that slide), its ``contact_forces``
(each interface's resultant at its centre of pressure, to scale; for an arch the centres
of pressure joined are the line of thrust) and the placed ``point_loads`` (live ones
times the load factor). One panel for the live load as given, and one towards -x where
the live load is the horizontal acceleration and the JSON has that direction. An arch is
drawn with y = 0 at its springings and x from midspan, as the four-hinge figure is;
any other assembly in the input's own coordinates.
"""

from __future__ import annotations

import math
import os
import textwrap
from dataclasses import dataclass

import numpy as np
from matplotlib.patches import Polygon

from ..readers.limit_results import LimitResult, LpInterfaceForce, LpInterfaceMode
from ..tables import ReportTable
from .drawing import HINGE_COLOURS, legend_pad, new_figure, provenance, save_figure, vehicle_words

__all__ = ["LpPanel", "interface_resultants", "plot_lp_mechanism"]

FORCE_COLOUR = "#444444"   #: as the four-hinge figure's LP forces
LIVE_COLOUR = "tab:red"    #: the live load, times lambda
DEAD_COLOUR = "tab:brown"  #: dead point loads
HINGE_COLOUR = "tab:olive"  #: a hinge between blocks that are not arch joints (no intrados or extrados)
FILL_COLOUR = "tab:brown"  #: the fill's surface
BACKING_COLOUR = "#c8b8a6"  #: a bridge's masonry backing (greyer than the ring's buff)


@dataclass
class LpPanel:
    """One direction of the LP drawn."""

    direction: str  #: '+x' (the live load as given) or '-x' (the acceleration turned round)
    load_factor: float
    hinges: list[LpInterfaceMode]  #: the interfaces that hinge, with the point they turn about
    sliding: list[LpInterfaceMode]  #: the interfaces that slide
    force_point_m: np.ndarray  #: (n_interfaces, 2) centres of pressure (NaN where no force)
    force_n: np.ndarray  #: (n_interfaces, 2) resultant on the second block of each interface
    forces: list[LpInterfaceForce]  #: the JSON's entries, in its order


def interface_resultants(forces: list[LpInterfaceForce]) -> tuple[np.ndarray, np.ndarray]:
    """Centre of pressure (N1 e1 + N2 e2) / (N1 + N2) and resultant (N1 + N2) n + S t on
    the second block, of every interface of the LP's static field."""
    point = np.full((len(forces), 2), np.nan)
    force = np.zeros((len(forces), 2))
    for k, f in enumerate(forces):
        total = float(f.normal_n.sum())
        tangent = np.array([-f.normal[1], f.normal[0]])
        force[k] = total * f.normal + f.shear_n * tangent
        if total > 0.0:
            point[k] = (f.normal_n[0] * f.ends_xy_m[0] + f.normal_n[1] * f.ends_xy_m[1]) / total
    return point, force


def _panel(direction: str, lam: float, modes: list[LpInterfaceMode], forces: list[LpInterfaceForce]) -> LpPanel:
    point, force = interface_resultants(forces)
    return LpPanel(direction, lam, [m for m in modes if m.mode == "hinge" and m.hinge_xy_m is not None],
                   [m for m in modes if m.mode == "sliding"], point, force, forces)


def _top_y(blocks: list[np.ndarray], x: float) -> float:
    """The top surface of the drawn blocks at x: the highest point of any block's boundary."""
    best = -math.inf
    for poly in blocks:
        for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, axis=0)):
            if min(x0, x1) - 1e-9 <= x <= max(x0, x1) + 1e-9:
                y = max(y0, y1) if abs(x1 - x0) <= 1e-12 else y0 + (x - x0) / (x1 - x0) * (y1 - y0)
                best = max(best, float(y))
    return best


def _strips(limit: LimitResult) -> list:
    """Each surface load's Boussinesq strips (edges, loads, retained), or None where it spreads at an angle."""
    return limit.surface_strips or [None] * len(limit.surface_loads)


def _peak_pressure(limit: LimitResult) -> float:
    """The greatest Boussinesq pressure on the blocks' top of any surface load [N/m per the width]."""
    return max((float(np.max(s[1] / np.diff(s[0]))) for s in _strips(limit) if s is not None), default=0.0)


def pressure_m_per_n_m(limit: LimitResult, blocks: list[np.ndarray], shift: np.ndarray) -> float:
    """The drawing's scale of the Boussinesq pressure [m of drawing per N/m]: the peak at 0.8 of
    the fill's least depth beneath a surface load."""
    level = float(limit.surface_loads[0].xy_m[1]) - shift[1]
    depth = min(level - _top_y(blocks, float(p.xy_m[0]) - shift[0]) for p in limit.surface_loads)
    peak = _peak_pressure(limit)
    return 0.8 * depth / peak if peak > 0 else 0.0


def _newtons(value_n: float) -> str:
    return f"{value_n / 1e3:.4g} kN" if abs(value_n) >= 1e3 else f"{value_n:.4g} N"


def _live_loads(limit: LimitResult) -> list:
    """The live loads as given: on the fill's surface where there is a fill, else as placed
    (a patch at its centre)."""
    return limit.surface_loads or [p for p in limit.point_loads if p.live] + limit.patch_loads


def _live_words(limit: LimitResult) -> str:
    """'1 kN down at x = -0.2 m' for the live point loads (their resultant's x on a path)."""
    live = _live_loads(limit)
    if not live:
        return ""
    total = sum(float(np.hypot(*p.force_n)) for p in live)
    down = all(p.force_n[0] == 0.0 and p.force_n[1] < 0.0 for p in live)
    where = (f"vehicle at x = {limit.critical_x_m:.3g} m (critical position of its path)"
             if math.isfinite(limit.critical_x_m) else
             "at x = " + ", ".join(f"{p.xy_m[0]:.3g}" for p in live) + " m")
    return f"{len(live)} live load{'s' if len(live) > 1 else ''} of {_newtons(total)} in all" \
           f"{' (down)' if down else ''}, {where}"


def _title(limit: LimitResult, panel: LpPanel) -> str:
    if math.isnan(panel.load_factor):
        return f"towards {panel.direction}: no load factor"
    lam = panel.load_factor
    if limit.live_is_acceleration:
        return (f"towards {panel.direction}: collapse load factor λ = {lam:.4g}\n"
                f"(horizontal acceleration {lam * limit.g_m_s2:.3g} m/s² = {lam:.3g} g)")
    total = sum(float(np.hypot(*p.force_n)) for p in _live_loads(limit))
    return (f"collapse load factor λ = {lam:.4g} on the live load:\n"
            f"the live loads times λ, {_newtons(lam * total)} in all, bring it down")


def _frame(limit: LimitResult) -> tuple[np.ndarray, str, str]:
    """The shift that the drawing subtracts from the JSON's coordinates, and the axis labels."""
    if limit.has_arch:
        y0 = float(min(limit.joint_intrados_xy_m[0, 1], limit.joint_intrados_xy_m[-1, 1]))
        return np.array([0.0, y0]), "x [m] from midspan", "y [m] above the springings"
    if limit.assembly == "bridge":   # its own frame (docs/bridges.md)
        return np.zeros(2), "x [m] from the left springing of span 1", "y [m] above the springings"
    return np.zeros(2), "x [m]", "y [m]"


def plot_lp_mechanism(limit: LimitResult, out_png: str | os.PathLike):
    """The LP's mechanism and static field on the assembly's blocks; returns what
    :func:`voussoir_post.plots.mechanism.plot_mechanism` returns (a MechanismData)."""
    from .mechanism import MechanismData   # (its module imports this one)

    if not limit.blocks:
        raise ValueError(f"{limit.path}: no 'blocks' in the JSON (written before voussoir-limit listed the "
                         "assembly's blocks): run voussoir-limit --json again")
    panels = [_panel("+x", limit.load_factor, limit.mechanism, limit.contact_forces)]
    if limit.live_is_acceleration and limit.contact_forces_neg:
        panels.append(_panel("-x", limit.load_factor_neg, limit.mechanism_neg, limit.contact_forces_neg))
    shift, xlabel, ylabel = _frame(limit)
    blocks = [b.vertices_xy_m - shift for b in limit.blocks]
    pts = np.vstack(blocks)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    size = float(max(hi - lo))
    width_in = 11.0
    panel_w = width_in / len(panels)
    axes_height_in = min(7.0, max(2.2, panel_w * (hi[1] - lo[1] + 0.35 * size) / (hi[0] - lo[0] + 0.2 * size)))
    fig = new_figure(width_in, axes_height_in + 2.5)
    axes = np.atleast_1d(fig.subplots(1, len(panels)))
    largest = max((float(np.max(np.hypot(*p.force_n.T))) for p in panels if p.force_n.size), default=0.0)
    scale = size / 10.0 / largest if largest > 0 else math.nan
    key_n = _key_force(largest)
    live_total = sum(float(np.hypot(*p.force_n)) for p in _live_loads(limit))
    load_len_m = size / 8.0
    has_thrust = limit.has_arch and all(f.joint is not None for f in limit.contact_forces)
    # The fill's pressures on their own scale: the largest a fifteenth of the drawing.
    largest_p = max((abs(float(p.force_n[0])) for p in limit.fill_pressures if np.isfinite(p.force_n[0])), default=0.0)
    pressure_scale = size / 15.0 / largest_p if largest_p > 0 else 0.0
    for ax, panel in zip(axes, panels):
        for poly, block in zip(blocks, limit.blocks):
            ax.add_patch(Polygon(poly, closed=True, facecolor="#9e9e9e" if block.driven else
                                 BACKING_COLOUR if _is_backing(block) else "#e8c99b",
                                 edgecolor="#333333", linewidth=0.6, hatch="//" if block.driven else None))
        at = panel.force_point_m - shift
        if has_thrust:
            order = np.argsort([f.joint for f in panel.forces])
            ax.plot(at[order, 0], at[order, 1], "-", color="black", linewidth=1.1, zorder=4)
        if math.isfinite(scale):
            ok = np.all(np.isfinite(at), axis=1)
            arrows = ax.quiver(at[ok, 0], at[ok, 1], panel.force_n[ok, 0], panel.force_n[ok, 1], angles="xy",
                               scale_units="xy", scale=1.0 / scale, color=FORCE_COLOUR, width=0.004,
                               pivot="middle", zorder=6)
            ax.quiverkey(arrows, 0.12, 0.93, key_n, _newtons(key_n), labelpos="E", coordinates="axes",
                         fontproperties={"size": 8})
        for m in panel.sliding:
            f = next((c for c in panel.forces if c.blocks == m.blocks), None)
            if f is not None:
                ends = f.ends_xy_m - shift
                ax.plot(ends[:, 0], ends[:, 1], "-", color=HINGE_COLOURS["separated"], linewidth=3, zorder=5)
        for m in panel.hinges:
            colour = HINGE_COLOURS.get(m.hinge_side or "", HINGE_COLOUR)
            x, y = m.hinge_xy_m - shift
            ax.plot(x, y, "o", color=colour, markersize=7, markeredgecolor="white", zorder=7)
            if m.joint is not None and limit.has_arch:
                # Outward (extrados) or inward (intrados) along the radius from the circle's centre.
                radial = m.hinge_xy_m / max(float(np.hypot(*m.hinge_xy_m)), 1e-12)
                offset = (radial if m.hinge_side == "extrados" else -radial) * 14
                ax.annotate(f"{m.joint}{(m.hinge_side or ' ')[0]}", (x, y), textcoords="offset points",
                            xytext=tuple(offset), ha="center", va="center", fontsize=9, color=colour,
                            fontweight="bold")
        if limit.surface_loads:
            level = float(limit.surface_loads[0].xy_m[1]) - shift[1]
            ax.plot([lo[0], hi[0]], [level, level], "--", color=FILL_COLOUR, linewidth=1.2, zorder=3)
            for p, (x_lo, x_hi), strips in zip(limit.surface_loads, limit.surface_spread_x_m, _strips(limit)):
                x0 = float(p.xy_m[0]) - shift[0]
                if strips is None:
                    ax.plot([x_lo - shift[0], x0, x_hi - shift[0]], [_top_y(blocks, x_lo - shift[0]), level,
                            _top_y(blocks, x_hi - shift[0])], ":", color=LIVE_COLOUR, linewidth=1.2, zorder=8)
                    continue
                # Boussinesq: no lines bound the spread; its pressure on the extrados, drawn up
                # from it, the peak of all the loads at 0.8 of the fill's depth beneath the load.
                edges, loads, _ = strips
                x = edges - shift[0]
                base = np.array([_top_y(blocks, float(v)) for v in x])
                height = np.repeat(loads / np.diff(edges) * pressure_m_per_n_m(limit, blocks, shift), 2)
                xs = np.repeat(x, 2)[1:-1]
                ys = np.repeat(base, 2)[1:-1]
                ax.fill_between(xs, ys, ys + height, color=LIVE_COLOUR, alpha=0.25, linewidth=0, zorder=3,
                                gid="boussinesq_pressure")
                ax.plot(xs, ys + height, "-", color=LIVE_COLOUR, linewidth=0.8, zorder=8)
        if pressure_scale > 0 and panel.direction == "+x":
            at_p = np.array([p.xy_m for p in limit.fill_pressures]) - shift
            force_p = np.array([p.force_n for p in limit.fill_pressures])
            ax.quiver(at_p[:, 0], at_p[:, 1], force_p[:, 0], force_p[:, 1], angles="xy", scale_units="xy",
                      scale=1.0 / pressure_scale, color=FILL_COLOUR, width=0.004, pivot="tip", zorder=6)
        if panel.direction == "+x":
            for p in _live_loads(limit) if limit.surface_loads else limit.point_loads + limit.patch_loads:
                u = p.force_n / max(float(np.hypot(*p.force_n)), 1e-300)
                tip = p.xy_m - shift
                ax.annotate("", xy=tuple(tip), xytext=tuple(tip - load_len_m * u),
                            arrowprops=dict(arrowstyle="-|>", color=LIVE_COLOUR if p.live else DEAD_COLOUR,
                                            linewidth=1.6), zorder=8)
        if limit.live_is_acceleration:
            ax.annotate("", xy=(0.95, 0.90), xytext=(0.70, 0.90), xycoords="axes fraction",
                        arrowprops=dict(arrowstyle="->" if panel.direction == "+x" else "<-", color="black"))
            ax.text(0.825, 0.93, "inertial load λ × weight", transform=ax.transAxes, ha="center", fontsize=8)
        ax.set_xlim(lo[0] - 0.1 * size, hi[0] + 0.1 * size)
        ax.set_ylim(lo[1] - 0.1 * size, hi[1] + 0.25 * size)
        ax.set_aspect("equal")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title(_title(limit, panel), fontsize=10)
        ax.grid(True, alpha=0.2)
    handles = _legend_handles(axes[0], limit, panels, has_thrust, key_n, scale, live_total, load_len_m,
                              pressure_scale)
    for h in handles:
        h.set_label(textwrap.fill(h.get_label(), 125))
    fig.legend(handles=handles, loc="outside lower center", borderaxespad=legend_pad(8), ncols=1, fontsize=8)
    legend_lines = sum(h.get_label().count("\n") + 1 for h in handles)
    fig.set_size_inches(width_in, axes_height_in + 1.6 + 0.16 * legend_lines)
    fig.suptitle("\n".join(textwrap.fill(line, 140) for line in _suptitle(limit).split("\n")), fontsize=10)
    png = save_figure(fig, out_png, note=provenance(limit.code_version, limit.input_file,
                                                 os.path.basename(limit.path)))
    rows = []
    for panel in panels:
        for m in panel.hinges + panel.sliding:
            xy = m.hinge_xy_m - shift if m.hinge_xy_m is not None else (math.nan, math.nan)
            names = [limit.blocks[b - 1].name for b in m.blocks]
            between = " / ".join(names) if all(names) else f"{m.blocks[0]}-{m.blocks[1]}"
            rows.append((panel.direction, panel.load_factor, between,
                         "" if m.joint is None else m.joint, m.mode, m.hinge_side or "", float(xy[0]), float(xy[1])))
    table = ReportTable(["direction", "load_factor", "blocks", "joint", "mode", "side", "x_m",
                         "y_above_springings_m" if limit.has_arch or limit.assembly == "bridge" else "y_m"], rows,
                        title=f"LP mechanism of {limit.path}")
    return MechanismData(blocks, panels, png, table, float(shift[1]), scale, key_n)


def _key_force(largest_n: float) -> float:
    """A round force near `largest_n` for the key arrow: 1, 2 or 5 times a power of ten."""
    if not largest_n > 0:
        return 1.0
    power = 10.0 ** math.floor(math.log10(largest_n))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= largest_n)


def _suptitle(limit: LimitResult) -> str:
    what = {"arch": "arch", "restrained arch": "arch with restraint brackets", "wall": "wall",
            "polygon file": f"assembly of {len(limit.blocks)} blocks (polygon file)",
            "bridge": f"bridge of {len(limit.blocks)} blocks (&bridge)"}.get(limit.assembly, limit.assembly)
    if limit.has_arch:
        what += (f": {limit.embrace_deg:g}° of {limit.n_voussoirs} voussoirs, t = {limit.thickness_m * 1e3:.4g} mm, "
                 f"R_ext = {limit.r_ext_m * 1e3:.4g} mm")
    vehicle = limit.config.get("vehicle") if limit.config_nml else None
    case = ("horizontal acceleration" if limit.live_is_acceleration else
            (f"the {vehicle_words(vehicle)} of &vehicle: " if vehicle else "the live load of &load: ") +
            _live_words(limit))
    return f"Collapse mechanism by linear programming (associative friction) under {case}:\n{what}"


def _is_backing(block) -> bool:
    """A block of a bridge's masonry backing (&bridge backing_level_m: named 'backing k')."""
    return block.name.startswith("backing ")


def _legend_handles(ax, limit, panels, has_thrust, key_n, scale, live_total, load_len_m, pressure_scale=0.0):
    handles = []
    backing = [b for b in limit.blocks if _is_backing(b)]
    if backing:
        top = max(float(np.max(np.asarray(b.vertices_xy_m)[:, 1])) for b in backing)
        handles.append(ax.fill([], [], facecolor=BACKING_COLOUR, edgecolor="#333333", linewidth=0.6,
                               label=f"masonry backing over the haunches, up to y = {top:.3g} m: {len(backing)} free "
                                     "blocks in horizontal courses (rigid, no tension, Coulomb friction)")[0])
    sides = {m.hinge_side for p in panels for m in p.hinges}
    for side in ("intrados", "extrados"):
        if side in sides:
            handles.append(ax.plot([], [], "o", color=HINGE_COLOURS[side],
                                   label=f"hinge pivoting on the {side} ({side[0]}; joints numbered from the "
                                         "left springing)")[0])
    if None in sides:
        handles.append(ax.plot([], [], "o", color=HINGE_COLOUR, label="hinge: the point a block turns about "
                                                                       "on its neighbour")[0])
    if any(p.sliding for p in panels):
        handles.append(ax.plot([], [], "-", color=HINGE_COLOURS["separated"], linewidth=3,
                               label=f"interface that slides in the mechanism (friction {limit.friction:g})")[0])
    if has_thrust:
        handles.append(ax.plot([], [], "-", color="black", linewidth=1.1,
                               label="line of thrust at collapse: the centres of pressure of the LP's joint forces")[0])
    if math.isfinite(scale):
        handles.append(ax.plot([], [], linestyle="none", marker=r"$\rightarrow$", markersize=14, color=FORCE_COLOUR,
                               label="force across each interface in the LP's static field at collapse, on its "
                                     "centre of pressure; to scale: "
                                     f"{_newtons(key_n)} = {key_n * scale * 1e3:.0f} mm")[0])
    if limit.surface_loads:
        level = float(limit.surface_loads[0].xy_m[1])
        fill_n = sum(-float(f.force_n[1]) for f in limit.fill_loads)
        handles.append(ax.plot([], [], "--", color=FILL_COLOUR, linewidth=1.2,
                               label=f"fill surface, y = {level:.3g} m: the fill's weight ({_newtons(fill_n)} over the "
                                     "free blocks) a dead load on the blocks beneath")[0])
        if any(s is None for s in _strips(limit)):
            handles.append(ax.plot([], [], ":", color=LIVE_COLOUR, linewidth=1.2,
                                   label="spread of each live load through the fill onto the blocks (uniform along x "
                                         "between the dotted lines' feet)")[0])
        if any(s is not None for s in _strips(limit)):
            retained = [s[2] for s in _strips(limit) if s is not None]
            handles.append(ax.fill_between([], [], [], color=LIVE_COLOUR, alpha=0.25,
                                           label="Boussinesq: Flamant's vertical pressure of each live load on the "
                                                 "blocks' top at the fill's depth there, drawn up from it (peak "
                                                 f"{_newtons(_peak_pressure(limit))}/m at λ = 1; scaled to the load, "
                                                 "the stress's integral over the strips being "
                                                 + ", ".join(f"{r:.3g}" for r in retained)
                                                 + " × the load before scaling); no lines bound this spread"))
    if pressure_scale > 0:
        total = sum(abs(float(p.force_n[0])) for p in limit.fill_pressures)
        largest = max(abs(float(p.force_n[0])) for p in limit.fill_pressures)
        handles.append(ax.plot([], [], linestyle="none", marker=r"$\rightarrow$", markersize=14, color=FILL_COLOUR,
                               label="the fill's horizontal pressure on each extrados face at collapse, into the ring "
                                     f"(between active and mobilised passive, as the LP chose; {_newtons(total)} "
                                     f"in all); its own scale: the largest, {_newtons(largest)}, "
                                     f"{largest * pressure_scale * 1e3:.0f} mm")[0])
    if _live_loads(limit):
        lam = panels[0].load_factor
        handles.append(ax.plot([], [], linestyle="none", marker=r"$\downarrow$", markersize=12, color=LIVE_COLOUR,
                               label=f"live load (arrow not to scale, {load_len_m:.2g} m): "
                                     f"{_newtons(live_total)} at factor 1, λ × that = {_newtons(lam * live_total)} "
                                     "at collapse")[0])
    if any(not p.live for p in limit.point_loads):
        handles.append(ax.plot([], [], linestyle="none", marker=r"$\downarrow$", markersize=12, color=DEAD_COLOUR,
                               label="dead point load (fixed, with the weights; arrow not to scale)")[0])
    if not math.isnan(limit.load_factor_nonassociative) and not math.isclose(
            limit.load_factor_nonassociative, limit.load_factor, rel_tol=1e-6):
        handles.append(ax.plot([], [], linestyle="none",
                               label=f"without dilatancy (non-associative) the load factor is "
                                     f"{limit.load_factor_nonassociative:.4g}")[0])
    return handles
