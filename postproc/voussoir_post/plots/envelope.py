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
from .drawing import COLORS, MARKERS, add_g_axis, arch_caption, legend_pad, new_figure, provenance, save_png

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
    """Measured collapse (filled) and stand (open) rows, and thresholds (black star
    edge), one marker per specimen."""
    for k, ov in enumerate(overlays):
        marker = MARKERS[k % len(MARKERS)]
        scale = ov.peak_per_m if accel else 1e3
        y = ov.amplitude_m * scale
        c, s = ov.collapsed, ~ov.collapsed
        ax.plot(ov.frequency_hz[c], y[c], marker, color="black", markersize=6, linestyle="none")
        ax.plot(ov.frequency_hz[s], y[s], marker, color="black", markerfacecolor="none", markersize=6,
                linestyle="none")
        th = [(m, per_m) for m, per_m in zip(ov.thresholds, ov.threshold_peak_per_m) if m.has_collapse]
        if th:
            f = np.array([m.frequency_hz for m, _ in th])
            a = np.array([m.threshold_m for m, _ in th])
            y = a * (np.array([per_m for _, per_m in th]) if accel else 1e3)
            ax.plot(f, y, marker, color="gold", markeredgecolor="black", markersize=10, linestyle="none",
                    zorder=5)
        if accel and np.any(np.isfinite(ov.peak_accel_m_s2)):
            ax.plot(ov.frequency_hz, ov.peak_accel_m_s2, marker, color="tab:gray", markerfacecolor="none",
                    markersize=8, linestyle="none")


def _measured_legend(overlays: list[MeasuredOverlay], accel: bool = False) -> list[Line2D]:
    handles = []
    for k, ov in enumerate(overlays):
        handles.append(Line2D([], [], marker=MARKERS[k % len(MARKERS)], color="black", linestyle="none",
                              label=f"{ov.specimen_id}: measured collapse"))
    if overlays:
        m = MARKERS[0]
        if any(np.any(~ov.collapsed) for ov in overlays):
            handles.append(Line2D([], [], marker=m, color="black", markerfacecolor="none", linestyle="none",
                                  label="measured stand"))
        handles.append(Line2D([], [], marker=m, color="gold", markeredgecolor="black", markersize=10,
                              linestyle="none", label="measured threshold"))
        if accel and any(np.any(np.isfinite(ov.peak_accel_m_s2)) for ov in overlays):
            handles.append(Line2D([], [], marker=m, color="tab:gray", markerfacecolor="none", markersize=8,
                                  linestyle="none", label="measured peak accel."))
    return handles


def _plot_threshold(sweep: SweepResult, overlays, out_png) -> EnvelopeData:
    curves = threshold_curves(sweep)
    fig = new_figure(11.0, 5.6)
    ax_a, ax_g = fig.subplots(1, 2)
    handles = []
    for k, cv in enumerate(curves):
        colour = COLORS[k % len(COLORS)]
        for ax, y in ((ax_a, 1e3 * cv.threshold_m), (ax_g, cv.peak_accel_m_s2)):
            ax.plot(cv.frequency_hz, y, "-o", color=colour, markersize=4)
            nm = cv.non_monotonic & np.isfinite(y)
            ax.plot(cv.frequency_hz[nm], y[nm], "o", markersize=11, markerfacecolor="none",
                    markeredgecolor="tab:red", markeredgewidth=1.5)
            missing = ~np.isfinite(y)
            ax.plot(cv.frequency_hz[missing], np.full(missing.sum(), 0.97), "^", color=colour,
                    transform=ax.get_xaxis_transform(), markersize=7)
        handles.append(Line2D([], [], color=colour, marker="o", markersize=4, label=cv.label))
    if any(np.any(cv.non_monotonic) for cv in curves):
        handles.append(Line2D([], [], marker="o", markersize=11, markerfacecolor="none", linestyle="none",
                              markeredgecolor="tab:red", markeredgewidth=1.5, label="non-monotonic search"))
    if any(np.any(~np.isfinite(cv.threshold_m)) for cv in curves):
        handles.append(Line2D([], [], marker="^", color="gray", linestyle="none",
                              label="no collapse up to the max. amplitude"))
    _draw_measured(ax_a, overlays)
    _draw_measured(ax_g, overlays, accel=True)
    ax_a.set_xlabel("frequency [Hz]")
    ax_a.set_ylabel("threshold amplitude [mm]")
    ax_a.set_title("Collapse threshold (commanded displacement amplitude)", fontsize=10)
    ax_g.set_xlabel("frequency [Hz]")
    ax_g.set_ylabel("peak table acceleration [m/s²]")
    add_g_axis(ax_g, "peak table acceleration [g]")
    ax_g.set_title("Peak acceleration of the commanded motion at threshold", fontsize=10)
    for ax in (ax_a, ax_g):
        ax.grid(True, alpha=0.3)
        ax.set_ylim(bottom=0)
    fig.legend(handles=handles + _measured_legend(overlays, accel=True), fontsize=8, loc="outside lower center", borderaxespad=legend_pad(8),
               ncols=3)
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
                        png_path=save_png(fig, out_png, note=_note(sweep)), table=table)


def _plot_grid(sweep: SweepResult, overlays, out_png) -> EnvelopeData:
    maps = grid_maps(sweep)
    ncols = min(len(maps), 3)
    nrows = math.ceil(len(maps) / ncols)
    fig = new_figure(5.5 * ncols, 4.6 * nrows)
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False)).reshape(-1)
    for ax, gm in zip(axes, maps):
        c = gm.collapsed
        ax.plot(gm.frequency_hz[~c], 1e3 * gm.amplitude_m[~c], "o", color="tab:green",
                markerfacecolor="none", label="stand (simulated)")
        ax.plot(gm.frequency_hz[c], 1e3 * gm.amplitude_m[c], "x", color="tab:red", label="collapse (simulated)")
        ax.plot(gm.envelope_frequency_hz, 1e3 * gm.envelope_amplitude_m, "-", color="tab:red", linewidth=1.5,
                label="envelope: smallest collapsing amplitude")
        _draw_measured(ax, overlays)
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel("amplitude [mm]")
        ax.set_title(gm.label, fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(handles=ax.get_legend_handles_labels()[0] + _measured_legend(overlays), fontsize=7,
                  loc="upper right")
    for ax in axes[len(maps):]:
        ax.set_visible(False)
    fig.suptitle(f"Stand or collapse under sinusoidal shaking, frequency by amplitude: "
                 f"{arch_caption(sweep.config.get('arch', {}))}", fontsize=11)
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
    return EnvelopeData("grid", maps=maps, measured=overlays, png_path=save_png(fig, out_png, note=_note(sweep)),
                        table=table)


def _note(sweep: SweepResult) -> str:
    inp = str(sweep.config.get("output", {}).get("file", ""))
    return provenance(sweep.code_version, os.path.basename(sweep.path) if not inp else os.path.basename(inp))


def plot_envelope(sweep: SweepResult, out_png: str | os.PathLike, campaign: Campaign | None = None,
                  specimen_ids: list[str] | None = None) -> EnvelopeData:
    """Plot the envelope of a threshold or grid sweep; with ``campaign``, overlay the
    measured points of ``specimen_ids`` (default all specimens). Returns the drawn data."""
    overlays = measured_overlays(campaign, specimen_ids) if campaign is not None else []
    if sweep.mode == "threshold":
        return _plot_threshold(sweep, overlays, out_png)
    return _plot_grid(sweep, overlays, out_png)
