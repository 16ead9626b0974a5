"""Collapse sequence of a run: frames of the block polygons with open hinges marked."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.animation import FuncAnimation, PillowWriter
from matplotlib.patches import Polygon

from ..analysis.kinematics import (ROLE_BACKING, ROLE_FOUNDATION, ROLE_RESTRAINT, JointState, block_polygons,
                                   default_open_tol_m, joint_openings, joint_states)
from ..readers.results import RunResult
from ..tables import ReportTable
from .drawing import HINGE_COLOURS, legend_pad, new_figure, provenance, run_caption, save_figure, wrap_text

__all__ = ["SequenceFrame", "SequenceData", "default_frame_times", "first_opening_time", "sequence_frames",
           "plot_sequence", "write_sequence_gif"]

_FILL = {1: "#e8c99b", ROLE_FOUNDATION: "#9e9e9e", ROLE_RESTRAINT: "#5f5f5f", ROLE_BACKING: "#c8b8a6"}
_SIDE_LABEL = {"intrados": "i", "extrados": "e", "separated": "s"}


@dataclass
class SequenceFrame:
    """One drawn frame: the sample, its time, the polygons and the open joints."""

    sample: int
    time_s: float
    polygons_m: list[np.ndarray]  #: (nv, 2) per body, amplified
    open_joints: list[JointState]
    amplify: float = 1.0  #: the exaggeration drawn (1 after a collapse: the true fall)

    def hinge_labels(self) -> str:
        """'4i 9e ...': joint index and side letter of every open joint."""
        return " ".join(f"{s.joint}{_SIDE_LABEL[s.state]}" for s in self.open_joints)


@dataclass
class SequenceData:
    """What :func:`plot_sequence` drew."""

    amplify: float
    open_tol_m: float
    frames: list[SequenceFrame]
    png_path: str | None = None
    gif_path: str | None = None
    table: ReportTable = field(default_factory=lambda: ReportTable([]))


def first_opening_time(run: RunResult, open_tol_m: float | None = None) -> float | None:
    """Time [s] of the first sample at which a joint of an arch opens by more than
    ``open_tol_m`` (default :func:`.kinematics.default_open_tol_m`); None when none does
    (or the run is not of an arch)."""
    if run.arch is None:
        return None
    tol = default_open_tol_m(run) if open_tol_m is None else open_tol_m
    for k in range(run.n_samples):
        if float(joint_openings(run, k).max()) > tol:
            return float(run.time_s[k])
    return None


def default_frame_times(run: RunResult, n_frames: int, open_tol_m: float | None = None) -> np.ndarray:
    """``n_frames`` times [s] up to the collapse time plus 15 % (or the end of the run
    when it did not collapse), capped at the last sample: the first at the start (the
    reference), the others evenly spread from the first opening of a joint
    (:func:`first_opening_time`), so that no two frames show the same still arch; evenly
    spread from the start when no joint opens."""
    t_first, t_last = float(run.time_s[0]), float(run.time_s[-1])
    if run.collapsed and math.isfinite(run.collapse_time_s):
        t_end = min(t_last, 1.15 * run.collapse_time_s)
    else:
        t_end = t_last
    n = max(n_frames, 1)
    t_open = first_opening_time(run, open_tol_m) if n >= 3 else None
    if t_open is None or not t_first < t_open < t_end:
        return np.linspace(t_first, t_end, n)
    return np.concatenate([[t_first], np.linspace(t_open, t_end, n - 1)])


def _nearest_samples(run: RunResult, times_s) -> list[int]:
    return [int(np.argmin(np.abs(run.time_s - t))) for t in times_s]


def sequence_frames(run: RunResult, times_s, amplify: float = 1.0,
                    open_tol_m: float | None = None) -> list[SequenceFrame]:
    """Frames at the samples nearest to ``times_s``. Displacements are exaggerated by
    ``amplify`` until the collapse only: a falling block is drawn where it really is."""
    frames = []
    for k in _nearest_samples(run, times_s):
        fallen = run.collapsed and math.isfinite(run.collapse_time_s) and run.time_s[k] >= run.collapse_time_s
        gain = 1.0 if fallen else amplify
        states = joint_states(run, k, open_tol_m, gain) if run.arch is not None else []
        frames.append(SequenceFrame(k, float(run.time_s[k]), block_polygons(run, k, gain), states, gain))
    return frames


def _view_limits(run: RunResult) -> tuple[tuple[float, float], tuple[float, float]]:
    """Axis limits: the reference assembly plus a margin of a quarter of its span."""
    pts = np.vstack(block_polygons(run, 0))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = float(max(hi - lo))
    margin = 0.25 * span
    x_shift = float(np.max(np.abs(run.table_x_m)))
    return ((lo[0] - margin - x_shift, hi[0] + margin + x_shift), (lo[1] - 0.05 * span, hi[1] + margin))


def _draw_frame(ax, run: RunResult, frame: SequenceFrame, limits, label_hinges: bool = True,
                amplify: float = 1.0):
    for b, poly in enumerate(frame.polygons_m):
        ax.add_patch(Polygon(poly, closed=True, facecolor=_FILL.get(int(run.body_role[b]), "#cccccc"),
                             edgecolor="#333333", linewidth=0.6))
    for s in frame.open_joints:
        colour = HINGE_COLOURS[s.state]
        ax.plot(*s.pivot_xy_m, "o", color=colour, markersize=5, markeredgecolor="white", markeredgewidth=0.6)
        if label_hinges:
            ax.annotate(f"{s.joint}{_SIDE_LABEL[s.state]}", s.pivot_xy_m, textcoords="offset points",
                        xytext=(3, 3), fontsize=7, color=colour)
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_aspect("equal")
    scale = "" if frame.amplify == 1.0 else f", displacements x{frame.amplify:g}"
    fallen = run.collapsed and frame.time_s >= run.collapse_time_s
    after = (" (collapsed: true scale)" if amplify != 1.0 else " (collapsed)") if fallen else scale
    ax.set_title(f"t = {frame.time_s:.3f} s{after}", fontsize=9)
    ax.tick_params(labelsize=7)


def plot_sequence(run: RunResult, out_png: str | os.PathLike, times_s=None, n_frames: int = 6,
                  amplify: float = 1.0, open_tol_m: float | None = None) -> SequenceData:
    """Draw a strip of frames of every block polygon, open hinges marked and labelled
    ``<joint>i`` / ``<joint>e`` (``s`` for a separated joint); returns the drawn data."""
    tol = default_open_tol_m(run) if open_tol_m is None else open_tol_m
    chosen = times_s is None
    if chosen:
        times_s = default_frame_times(run, n_frames, tol)
    frames = sequence_frames(run, times_s, amplify, tol)
    limits = _view_limits(run)
    ncols = min(len(frames), 3)
    nrows = math.ceil(len(frames) / ncols)
    width_m = limits[0][1] - limits[0][0]
    height_m = limits[1][1] - limits[1][0]
    panel_w = 4.2
    # Equal-aspect panels: each row needs room for its title, ticks and label beyond the
    # drawing itself (about 0.6 in), the figure for its title and legend (below). A
    # strip of one or two frames is widened so that the title and legend fit.
    fig_w = max(panel_w * ncols, 8.4)
    panel_w = fig_w / ncols
    legend_cols = 2 if fig_w >= 12.0 else 1
    status = (f"collapsed at {run.collapse_time_s:.3f} s" if run.collapsed else "did not collapse")
    scale = ("true scale" if amplify == 1.0 else
             f"displacements exaggerated x{amplify:g} until the collapse, true after it")
    t_open = first_opening_time(run, tol) if chosen and len(frames) >= 3 else None
    frames_words = (f"; frames: the start, then from the first opening of a joint ({t_open:.3f} s)"
                    if t_open is not None and frames[1].time_s > frames[0].time_s else "")
    title = wrap_text(f"Collapse sequence: {run_caption(run)}; {status}; {scale}{frames_words}", fig_w - 0.3, 9)
    legend_in = 0.17 * (3 if legend_cols == 1 else 2) + 0.15 if run.arch is not None else 0.0
    extra_in = 0.2 * (title.count("\n") + 1) + legend_in + 0.25
    fig = new_figure(fig_w, panel_w * height_m / width_m * nrows + 0.6 * nrows + extra_in)
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False)).reshape(-1)
    for ax, frame in zip(axes, frames):
        _draw_frame(ax, run, frame, limits, amplify=amplify)
    for ax in axes[len(frames):]:
        ax.set_visible(False)
    for ax in axes[::ncols]:
        ax.set_ylabel("y [m]", fontsize=8)
    for ax in axes[(nrows - 1) * ncols:]:
        ax.set_xlabel("x [m]", fontsize=8)
    fig.suptitle(title, fontsize=9)
    if run.arch is not None:
        opens = f"the joint opens (more than {tol * 1e3:.2g} mm) and pivots on its"
        handles = [axes[0].plot([], [], "o", color=HINGE_COLOURS["intrados"], markeredgecolor="white",
                                label=f"hinge (i): {opens} intrados edge")[0],
                   axes[0].plot([], [], "o", color=HINGE_COLOURS["extrados"], markeredgecolor="white",
                                label=f"hinge (e): {opens} extrados edge")[0],
                   axes[0].plot([], [], "o", color=HINGE_COLOURS["separated"], markeredgecolor="white",
                                label="separated joint (s): both edges open, the blocks part or slide")[0]]
        fig.legend(handles=handles, loc="outside lower center", borderaxespad=legend_pad(7), ncols=legend_cols,
                   fontsize=7)
    png = save_figure(fig, out_png, note=provenance(run.code_version, run.input_file, os.path.basename(run.path)))
    table = ReportTable(["frame", "sample", "time_s", "crown_dx_mm", "crown_dy_mm", "open_joints"],
                        [(i + 1, f.sample, f.time_s, 1e3 * float(run.crown_dx_m[f.sample]),
                          1e3 * float(run.crown_dy_m[f.sample]), f.hinge_labels() or "-")
                         for i, f in enumerate(frames)],
                        title=f"Sequence frames of {run.path}")
    return SequenceData(amplify, tol, frames, png_path=png, table=table)


def write_sequence_gif(run: RunResult, out_gif: str | os.PathLike, t_end_s: float | None = None,
                       amplify: float = 1.0, open_tol_m: float | None = None,
                       max_frames: int = 120, fps: int = 15) -> tuple[str, list[int]]:
    """Animated GIF (matplotlib PillowWriter) of the samples from 0 to ``t_end_s``
    (default: the end of :func:`default_frame_times`), at most ``max_frames`` frames.
    Returns the path and the drawn sample indices."""
    if t_end_s is None:
        t_end_s = float(default_frame_times(run, 2)[-1])
    samples = np.nonzero(run.time_s <= t_end_s + 1e-12)[0]
    if samples.size > max_frames:
        samples = samples[np.linspace(0, samples.size - 1, max_frames).round().astype(int)]
    tol = default_open_tol_m(run) if open_tol_m is None else open_tol_m
    limits = _view_limits(run)
    width_m = limits[0][1] - limits[0][0]
    height_m = limits[1][1] - limits[1][0]
    fig = new_figure(6.0, 6.0 * height_m / width_m + 0.5)
    ax = fig.add_subplot()

    def draw(i):
        ax.clear()
        k = int(samples[i])
        frame = sequence_frames(run, [run.time_s[k]], amplify, tol)[0]
        _draw_frame(ax, run, frame, limits, amplify=amplify)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title(f"{os.path.basename(run.path)}  t = {frame.time_s:.3f} s  (x{amplify:g})", fontsize=9)
        return []

    anim = FuncAnimation(fig, draw, frames=len(samples), blit=False)
    out_gif = os.fspath(out_gif)
    os.makedirs(os.path.dirname(os.path.abspath(out_gif)), exist_ok=True)
    anim.save(out_gif, writer=PillowWriter(fps=fps), dpi=80)
    return out_gif, [int(k) for k in samples]
