"""Collapse envelopes of a sweep, with measured points of a campaign overlaid.

Threshold mode: threshold amplitude [mm] and the peak table acceleration of the
commanded motion at the threshold [m/s², g] (the true peak of the afd motion, about 1.05
times the full-cycle A (2 pi f)^2, see :mod:`..analysis.afd`) against frequency [Hz],
one curve per parameter set; points where the search met a
stand above a collapse (non_monotonic) are ringed. Grid mode: stand/collapse map over
(frequency, amplitude) per parameter set, with the envelope (smallest collapsing
amplitude at each frequency).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.lines import Line2D

from ..analysis.afd import afd_peak_accel_per_m, full_cycle_accel_m_s2
from ..errors import InputError
from ..readers.campaign import Campaign, MeasuredThreshold, measured_thresholds
from ..readers.results import SweepResult
from ..tables import ReportTable
from .drawing import (COLLAPSE_COLOUR, COLORS, G_M_S2, MARKERS, add_g_axis, arch_caption, legend_pad, new_figure,
                      provenance, save_figure, wrap_text)

__all__ = ["ThresholdCurve", "GridMap", "MeasuredOverlay", "EnvelopeData", "threshold_curves",
           "grid_maps", "measured_overlays", "plot_envelope"]


@dataclass
class ThresholdCurve:
    """Threshold-mode results of one parameter set, sorted by frequency."""

    param_set: int
    label: str
    frequency_hz: np.ndarray
    threshold_m: np.ndarray  #: NaN where no collapse was found up to amp_max_m
    peak_accel_m_s2: np.ndarray  #: true peak of the commanded afd motion at threshold_m
    full_cycle_accel_m_s2: np.ndarray  #: A (2 pi f)^2 at threshold_m
    non_monotonic: np.ndarray  #: bool
    n_runs: np.ndarray


@dataclass
class GridMap:
    """Grid-mode results of one parameter set and its envelope."""

    param_set: int
    label: str
    frequency_hz: np.ndarray  #: one entry per grid run
    amplitude_m: np.ndarray
    collapsed: np.ndarray  #: bool
    envelope_frequency_hz: np.ndarray  #: the distinct frequencies, increasing
    envelope_amplitude_m: np.ndarray  #: smallest collapsing amplitude there (NaN if none)


@dataclass
class MeasuredOverlay:
    """Measured points of one specimen."""

    specimen_id: str
    frequency_hz: np.ndarray  #: per test with frequency and amplitude
    amplitude_m: np.ndarray
    collapsed: np.ndarray  #: bool
    peak_accel_m_s2: np.ndarray  #: measured peak acceleration (NaN when not given)
    thresholds: list[MeasuredThreshold]
    #: true peak acceleration of each test's commanded motion per metre of amplitude
    peak_per_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: the same for each threshold (its tests' cycles)
    threshold_peak_per_m: np.ndarray = field(default_factory=lambda: np.zeros(0))


@dataclass
class EnvelopeData:
    """What :func:`plot_envelope` drew."""

    mode: str
    curves: list[ThresholdCurve] = field(default_factory=list)
    maps: list[GridMap] = field(default_factory=list)
    measured: list[MeasuredOverlay] = field(default_factory=list)
    png_path: str | None = None
    table: ReportTable = field(default_factory=lambda: ReportTable([]))


def _sweep_cycles(sweep: SweepResult) -> tuple[int, int, int]:
    motion = sweep.config.get("motion", {})
    return tuple(int(motion.get(k, 1)) for k in ("n_attack", "n_full", "n_decay"))


def threshold_curves(sweep: SweepResult) -> list[ThresholdCurve]:
    """One :class:`ThresholdCurve` per parameter set of a threshold-mode sweep. A file of
    an older version has no peak column (its A (2 pi f)^2 is read as the full-cycle
    acceleration): the peak is then computed from the threshold and the sweep's cycles."""
    if sweep.mode != "threshold":
        raise InputError(f"{sweep.path}: a '{sweep.mode}' sweep has no thresholds")
    res = dict(sweep.results)
    if "peak_accel_m_s2" not in res:
        cycles = _sweep_cycles(sweep)
        res["peak_accel_m_s2"] = res["threshold_m"] * np.array(
            [afd_peak_accel_per_m(float(f), *cycles) for f in res["frequency_hz"]])
    curves = []
    for ps in range(sweep.n_sets):
        rows = np.nonzero(res["param_set"] == ps)[0]
        rows = rows[np.argsort(res["frequency_hz"][rows], kind="stable")]
        curves.append(ThresholdCurve(
            param_set=ps,
            label=sweep.set_label(ps),
            frequency_hz=res["frequency_hz"][rows],
            threshold_m=res["threshold_m"][rows],
            peak_accel_m_s2=res["peak_accel_m_s2"][rows],
            full_cycle_accel_m_s2=res["full_cycle_accel_m_s2"][rows],
            non_monotonic=res["non_monotonic"][rows].astype(bool),
            n_runs=res["n_runs"][rows],
        ))
    return curves


def grid_maps(sweep: SweepResult) -> list[GridMap]:
    """One :class:`GridMap` per parameter set of a grid-mode sweep."""
    if sweep.mode != "grid":
        raise InputError(f"{sweep.path}: a '{sweep.mode}' sweep has no grid")
    res = sweep.results
    maps = []
    for ps in range(sweep.n_sets):
        rows = np.nonzero(res["param_set"] == ps)[0]
        f, a = res["frequency_hz"][rows], res["amplitude_m"][rows]
        collapsed = res["collapsed"][rows].astype(bool)
        freqs = np.unique(f)
        env = np.array([a[(f == fr) & collapsed].min() if np.any((f == fr) & collapsed) else math.nan
                        for fr in freqs])
        maps.append(GridMap(ps, sweep.set_label(ps), f, a, collapsed, freqs, env))
    return maps


def measured_overlays(campaign: Campaign, specimen_ids: list[str] | None = None) -> list[MeasuredOverlay]:
    """Measured tests and thresholds of the chosen specimens (default: all)."""
    ids = list(campaign.specimens) if not specimen_ids else specimen_ids
    out = []
    for sid in ids:
        if sid not in campaign.specimens:
            raise InputError(f"{campaign.path}: no specimen '{sid}' (has: {', '.join(campaign.specimens)})")
        tests = [t for t in campaign.tests_of(sid) if t.frequency_hz is not None and t.amplitude_m is not None]
        thresholds = measured_thresholds(campaign, sid)
        out.append(MeasuredOverlay(
            specimen_id=sid,
            frequency_hz=np.array([t.frequency_hz for t in tests], dtype=float),
            amplitude_m=np.array([t.amplitude_m for t in tests], dtype=float),
            collapsed=np.array([t.collapsed for t in tests], dtype=bool),
            peak_accel_m_s2=np.array([math.nan if t.peak_accel_m_s2 is None else t.peak_accel_m_s2
                                      for t in tests], dtype=float),
            thresholds=thresholds,
            peak_per_m=np.array([_test_peak_per_m(t) for t in tests], dtype=float),
            threshold_peak_per_m=np.array([_test_peak_per_m(campaign.tests[m.test_ids[0]]) for m in thresholds],
                                          dtype=float),
        ))
    return out


def _test_peak_per_m(test) -> float:
    """True peak acceleration per metre of a test's commanded afd motion."""
    return afd_peak_accel_per_m(float(test.frequency_hz), test.n_attack, test.n_full, test.n_decay)


def _draw_measured(ax, overlays: list[MeasuredOverlay], accel: bool = False) -> None:
    """Measured collapse (filled) and stand (open) rows, one marker per specimen, drawn
    over the measured threshold (a larger gold marker behind them: the threshold is often
    a tested amplitude itself). On the acceleration panel the tests are the peaks of
    their commanded motions, as the curve is, and the table's measured peaks (grey rings)
    say what the table did."""
    for k, ov in enumerate(overlays):
        marker = MARKERS[k % len(MARKERS)]
        scale = ov.peak_per_m if accel else 1e3
        y = ov.amplitude_m * scale
        c, s = ov.collapsed, ~ov.collapsed
        th = [(m, per_m) for m, per_m in zip(ov.thresholds, ov.threshold_peak_per_m) if m.has_collapse]
        if th:
            f = np.array([m.frequency_hz for m, _ in th])
            a = np.array([m.threshold_m for m, _ in th])
            yt = a * (np.array([per_m for _, per_m in th]) if accel else 1e3)
            ax.plot(f, yt, marker, color="gold", markeredgecolor="black", markersize=13, linestyle="none",
                    zorder=5)
        ax.plot(ov.frequency_hz[c], y[c], marker, color="black", markersize=5, linestyle="none", zorder=6)
        ax.plot(ov.frequency_hz[s], y[s], marker, color="black", markerfacecolor="white", markersize=5,
                linestyle="none", zorder=6)
        if accel and np.any(np.isfinite(ov.peak_accel_m_s2)):
            ax.plot(ov.frequency_hz, ov.peak_accel_m_s2, marker, color="tab:gray", markerfacecolor="none",
                    markersize=19, markeredgewidth=1.5, linestyle="none", zorder=7)


def _measured_legend(overlays: list[MeasuredOverlay], accel: bool = False) -> list[Line2D]:
    handles = []
    what = "\n(right: the peak of its commanded motion, as the curve)" if accel else ""
    for k, ov in enumerate(overlays):
        handles.append(Line2D([], [], marker=MARKERS[k % len(MARKERS)], color="black", linestyle="none",
                              markersize=5, label=f"{ov.specimen_id}: a test that collapsed{what}"))
    if overlays:
        m = MARKERS[0]
        if any(np.any(~ov.collapsed) for ov in overlays):
            handles.append(Line2D([], [], marker=m, color="black", markerfacecolor="white", linestyle="none",
                                  markersize=5, label="a test that stood"))
        handles.append(Line2D([], [], marker=m, color="gold", markeredgecolor="black", markersize=11,
                              linestyle="none", label="measured threshold (behind the test that set it)"))
        if accel and any(np.any(np.isfinite(ov.peak_accel_m_s2)) for ov in overlays):
            handles.append(Line2D([], [], marker=m, color="tab:gray", markerfacecolor="none", markersize=12,
                                  markeredgewidth=1.5, linestyle="none",
                                  label="right: the table's measured peak acceleration in that\n"
                                        "test (what the table did, not the command)"))
    return handles


def _frequency_axis(ax, frequencies_hz) -> None:
    """A log frequency axis (0.5-4 Hz gets equal room per octave) ticked in plain Hz."""
    f = np.asarray([v for v in frequencies_hz if np.isfinite(v) and v > 0], dtype=float)
    if f.size == 0:
        return
    ax.set_xscale("log")
    lo, hi = f.min() / 1.12, f.max() * 1.12
    ax.set_xlim(lo, hi)
    ticks = [t for t in (0.1, 0.2, 0.25, 0.5, 0.75, 1, 1.5, 2, 3, 4, 5, 6, 8, 10, 15, 20, 30, 50) if lo <= t <= hi]
    if len(ticks) < 3:  # a narrow band: tick the frequencies themselves
        ticks = sorted(set(float(v) for v in f))[:8]
    ax.set_xticks(ticks, [f"{t:g}" for t in ticks])
    ax.set_xticks([], minor=True)


def _plot_threshold(sweep: SweepResult, overlays, out_png, capacity_m_s2: float | None = None,
                    capacity_source: str = "") -> EnvelopeData:
    curves = threshold_curves(sweep)
    fig = new_figure(11.0, 6.0)
    ax_a, ax_g = fig.subplots(1, 2)
    handles = []
    for k, cv in enumerate(curves):
        colour = COLORS[k % len(COLORS)]
        for ax, y in ((ax_a, 1e3 * cv.threshold_m), (ax_g, cv.peak_accel_m_s2)):
            ax.plot(cv.frequency_hz, y, "-o", color=colour, markersize=4)
            nm = cv.non_monotonic & np.isfinite(y)
            ax.plot(cv.frequency_hz[nm], y[nm], "o", markersize=11, markerfacecolor="none",
                    markeredgecolor="black", markeredgewidth=1.0)
            missing = ~np.isfinite(y)
            ax.plot(cv.frequency_hz[missing], np.full(missing.sum(), 0.97), "^", color=colour,
                    transform=ax.get_xaxis_transform(), markersize=7)
        handles.append(Line2D([], [], color=colour, marker="o", markersize=4,
                              label=f"simulated threshold: {cv.label}" if len(curves) > 1 else "simulated threshold"))
    if any(np.any(cv.non_monotonic) for cv in curves):
        handles.append(Line2D([], [], marker="o", markersize=11, markerfacecolor="none", linestyle="none",
                              markeredgecolor="black", markeredgewidth=1.0,
                              label="non-monotonic search\n(a stand met above a collapse)"))
    if any(np.any(~np.isfinite(cv.threshold_m)) for cv in curves):
        handles.append(Line2D([], [], marker="^", color="gray", linestyle="none",
                              label="no collapse up to the max. amplitude"))
    freqs = np.concatenate([cv.frequency_hz for cv in curves] + [ov.frequency_hz for ov in overlays])
    if capacity_m_s2 is not None and math.isfinite(capacity_m_s2) and capacity_m_s2 > 0:
        src = f", {capacity_source}" if capacity_source else ""
        ax_g.axhline(capacity_m_s2, color="0.3", linestyle="--", linewidth=1.2, zorder=1)
        fine = np.geomspace(max(freqs[freqs > 0].min() / 1.12, 1e-3), freqs.max() * 1.12, 60)
        cycles = _sweep_cycles(sweep)
        onset_mm = 1e3 * capacity_m_s2 / np.array([afd_peak_accel_per_m(float(f), *cycles) for f in fine])
        ax_a.plot(fine, onset_mm, "--", color="0.3", linewidth=1.2, zorder=1)
        handles.append(Line2D([], [], color="0.3", linestyle="--", linewidth=1.2,
                              label=f"static capacity λg = {capacity_m_s2:.2f} m/s² = {capacity_m_s2 / G_M_S2:.3f} g "
                                    f"(limit analysis{src});\nleft: the amplitude whose peak reaches it"))
    _draw_measured(ax_a, overlays)
    _draw_measured(ax_g, overlays, accel=True)
    for ax in (ax_a, ax_g):
        _frequency_axis(ax, freqs)
        ax.set_xlabel("frequency [Hz] (log scale)")
        ax.grid(True, alpha=0.3, which="both")
    ax_g.set_ylim(bottom=0)
    ax_a.set_ylabel("threshold amplitude [mm] (log scale)")
    ax_a.set_yscale("log")  # with the log frequency: a constant acceleration is a straight line
    lo_mm, hi_mm = ax_a.get_ylim()
    ticks = [t for t in (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000) if lo_mm <= t <= hi_mm]
    ax_a.set_yticks(ticks, [f"{t:g}" for t in ticks])
    ax_a.set_yticks([], minor=True)
    ax_a.set_title("Collapse threshold: commanded displacement amplitude", fontsize=10)
    ax_g.set_ylabel("peak table acceleration [m/s²]")
    add_g_axis(ax_g, "peak table acceleration [g]")
    ax_g.set_title("The same as the peak acceleration of the commanded motion", fontsize=10)
    fig.legend(handles=handles + _measured_legend(overlays, accel=True), fontsize=8, loc="outside lower center",
               borderaxespad=legend_pad(8), ncols=2)
    fig.suptitle(f"Collapse envelope under sinusoidal shaking: {arch_caption(sweep.config.get('arch', {}))}",
                 fontsize=11)
    rows = []
    for cv in curves:
        for f, a, g, fc, nm, n in zip(cv.frequency_hz, cv.threshold_m, cv.peak_accel_m_s2, cv.full_cycle_accel_m_s2,
                                      cv.non_monotonic, cv.n_runs):
            rows.append((cv.param_set, cv.label, float(f), 1e3 * float(a), float(g), float(fc), bool(nm), int(n)))
    table = ReportTable(["param_set", "parameters", "frequency_hz", "threshold_mm", "peak_accel_m_s2",
                         "full_cycle_accel_m_s2", "non_monotonic", "n_runs"], rows,
                        title=f"Thresholds of {sweep.path}")
    return EnvelopeData("threshold", curves=curves, measured=overlays,
                        png_path=save_figure(fig, out_png, note=_note(sweep)), table=table)


def _plot_grid(sweep: SweepResult, overlays, out_png) -> EnvelopeData:
    maps = grid_maps(sweep)
    ncols = min(len(maps), 3)
    nrows = math.ceil(len(maps) / ncols)
    fig = new_figure(5.5 * ncols + 2.6, 4.6 * nrows)
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False)).reshape(-1)
    for ax, gm in zip(axes, maps):
        c = gm.collapsed
        ax.plot(gm.frequency_hz[~c], 1e3 * gm.amplitude_m[~c], "o", color="tab:green",
                markerfacecolor="none", label="stand (simulated)")
        ax.plot(gm.frequency_hz[c], 1e3 * gm.amplitude_m[c], "x", color=COLLAPSE_COLOUR, label="collapse (simulated)")
        ax.plot(gm.envelope_frequency_hz, 1e3 * gm.envelope_amplitude_m, "-", color=COLLAPSE_COLOUR, linewidth=1.5,
                label="envelope: smallest collapsing amplitude")
        _draw_measured(ax, overlays)
        _frequency_axis(ax, gm.frequency_hz)
        ax.set_xlabel("frequency [Hz] (log scale)")
        ax.set_ylabel("amplitude [mm]")
        ax.set_title(gm.label, fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(handles=ax.get_legend_handles_labels()[0] + _measured_legend(overlays), fontsize=7,
                  loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside the map, over no run
    for ax in axes[len(maps):]:
        ax.set_visible(False)
    fig.suptitle(wrap_text(f"Stand or collapse under sinusoidal shaking, frequency by amplitude: "
                           f"{arch_caption(sweep.config.get('arch', {}))}", fig.get_figwidth() - 0.3, 11), fontsize=11)
    rows = []
    cycles = _sweep_cycles(sweep)
    for gm in maps:
        for f, a in zip(gm.envelope_frequency_hz, gm.envelope_amplitude_m):
            sel = gm.frequency_hz == f
            rows.append((gm.param_set, gm.label, float(f), int(sel.sum()), int(gm.collapsed[sel].sum()),
                         1e3 * float(a), float(a * afd_peak_accel_per_m(float(f), *cycles)),
                         float(full_cycle_accel_m_s2(a, f))))
    table = ReportTable(["param_set", "parameters", "frequency_hz", "n_runs", "n_collapse", "envelope_mm",
                         "envelope_peak_accel_m_s2", "envelope_full_cycle_accel_m_s2"], rows, title=f"Grid envelope of {sweep.path}")
    return EnvelopeData("grid", maps=maps, measured=overlays, png_path=save_figure(fig, out_png, note=_note(sweep)),
                        table=table)


def _note(sweep: SweepResult) -> str:
    inp = str(sweep.config.get("output", {}).get("file", ""))
    return provenance(sweep.code_version, os.path.basename(sweep.path) if not inp else os.path.basename(inp))


def plot_envelope(sweep: SweepResult, out_png: str | os.PathLike, campaign: Campaign | None = None,
                  specimen_ids: list[str] | None = None, capacity_m_s2: float | None = None,
                  capacity_source: str = "") -> EnvelopeData:
    """Plot the envelope of a threshold or grid sweep; with ``campaign``, overlay the
    measured points of ``specimen_ids`` (default all specimens); with ``capacity_m_s2``
    (the limit analysis's lambda g, e.g. of voussoir-limit's JSON named by
    ``capacity_source``), draw the static capacity. Returns the drawn data."""
    overlays = measured_overlays(campaign, specimen_ids) if campaign is not None else []
    if sweep.mode == "threshold":
        return _plot_threshold(sweep, overlays, out_png, capacity_m_s2, capacity_source)
    return _plot_grid(sweep, overlays, out_png)
