"""Simulated against measured collapse thresholds, per (specimen, frequency).

Matching a sweep to the campaign's specimens (kept simple on purpose):

1. With ``specimen_id`` given (``--specimen``), every parameter set of the sweep is
   compared with that specimen.
2. Otherwise the arch of each parameter set is the ``&arch`` group of the sweep's
   ``config_nml`` with the swept parameters that are ``&arch`` variables put in (a
   parameter named ``thickness_m`` or ``arch.thickness_m`` / ``arch%thickness_m``
   overrides ``&arch thickness_m``). A specimen matches when its ``embrace_deg``,
   ``n_voussoirs`` and ``r_ext_m`` equal the set's (relative tolerance 1e-6): these
   say which arch was built, while thickness, friction and the like are what a sweep
   calibrates. When several specimens match, those whose thickness_m also equals the
   set's are kept if there are any; all the remaining ones are compared.
3. No match at all is an error that asks for ``--specimen``.

Frequencies match within a relative 1e-6. The simulated threshold is ``threshold_m`` in
threshold mode and, in grid mode, the smallest collapsing amplitude at that frequency.
The relative error is (simulated - measured) / measured in percent. A measured pair
that the sweep did not simulate is listed with an empty simulated value.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np
from matplotlib.lines import Line2D

from ..errors import MatchError
from ..readers.campaign import Campaign, measured_thresholds
from ..readers.results import SweepResult
from ..tables import ReportTable
from .drawing import COLORS, new_figure, parameters_in_words, provenance, save_figure, wrap_text
from .envelope import grid_maps

__all__ = ["MatchError", "ComparisonRow", "CompareData", "arch_of_set", "match_specimens",
           "compare_thresholds", "plot_compare", "mean_error_lines"]

_ARCH_KEYS = ("embrace_deg", "n_voussoirs", "r_ext_m")
_REL_TOL = 1e-6


def _same(a: float, b: float) -> bool:
    return abs(float(a) - float(b)) <= _REL_TOL * max(abs(float(a)), abs(float(b)), 1e-30)


_ARCH_VARIABLES = ("embrace_deg", "n_voussoirs", "r_ext_m", "thickness_m", "width_m", "density_kg_m3",
                   "friction", "contact_inset_m")


def arch_of_set(sweep: SweepResult, param_set: int) -> dict[str, object]:
    """The ``&arch`` variables of one parameter set (config_nml with swept values put in)."""
    arch = dict(sweep.config.get("arch", {}))
    for name, value in sweep.set_parameters(param_set).items():
        parts = name.replace("%", ".").lower().split(".")
        group, variable = (parts[0], parts[-1]) if len(parts) > 1 else (None, parts[0])
        if group == "arch" or (group is None and (variable in arch or variable in _ARCH_VARIABLES)):
            arch[variable.strip()] = value
    return arch


def match_specimens(sweep: SweepResult, campaign: Campaign,
                    specimen_id: str | None = None) -> dict[int, list[str]]:
    """Specimens compared with each parameter set (see the module docstring)."""
    if specimen_id is not None:
        if specimen_id not in campaign.specimens:
            raise MatchError(f"{campaign.path}: no specimen '{specimen_id}' "
                             f"(has: {', '.join(campaign.specimens)})")
        return {ps: [specimen_id] for ps in range(sweep.n_sets)}
    matches: dict[int, list[str]] = {}
    for ps in range(sweep.n_sets):
        arch = arch_of_set(sweep, ps)
        missing = [k for k in _ARCH_KEYS if not isinstance(arch.get(k), (int, float))]
        if missing:
            raise MatchError(f"{sweep.path}: config_nml has no &arch {', '.join(missing)}, so the sweep "
                             "cannot be matched to a specimen; give --specimen ID")
        found = [s.specimen_id for s in campaign.specimens.values()
                 if all(_same(getattr(s, k), arch[k]) for k in _ARCH_KEYS)]
        if len(found) > 1 and isinstance(arch.get("thickness_m"), (int, float)):
            same_t = [sid for sid in found if _same(campaign.specimens[sid].thickness_m, arch["thickness_m"])]
            found = same_t or found
        matches[ps] = found
    if not any(matches.values()):
        arch = arch_of_set(sweep, 0)
        raise MatchError(
            f"{sweep.path}: no specimen of {campaign.path} has the sweep's arch (embrace_deg="
            f"{arch.get('embrace_deg')}, n_voussoirs={arch.get('n_voussoirs')}, r_ext_m={arch.get('r_ext_m')}); "
            "give --specimen ID")
    return matches


@dataclass
class ComparisonRow:
    """One (parameter set, specimen, frequency) comparison."""

    param_set: int
    label: str
    specimen_id: str
    frequency_hz: float
    simulated_m: float  #: NaN when not simulated or no collapse found
    measured_m: float
    low_m: float  #: measured bracket (NaN when unknown)
    high_m: float
    error_pct: float  #: (simulated - measured) / measured * 100

    @property
    def simulated_full_cycle_accel_m_s2(self) -> float:
        """A (2 pi f)^2 at the simulated threshold (not the peak of the afd motion)."""
        return self.simulated_m * (2 * math.pi * self.frequency_hz) ** 2

    @property
    def measured_full_cycle_accel_m_s2(self) -> float:
        """A (2 pi f)^2 at the measured threshold."""
        return self.measured_m * (2 * math.pi * self.frequency_hz) ** 2


@dataclass
class CompareData:
    """What :func:`plot_compare` drew."""

    rows: list[ComparisonRow]
    mean_abs_error_pct: dict[int, float]  #: per parameter set, over rows with both values
    png_path: str | None = None
    table: ReportTable = field(default_factory=lambda: ReportTable([]))
    notes: list[str] = field(default_factory=list)


def mean_error_lines(data: CompareData, sweep: SweepResult) -> list[str]:
    """The mean |error| of each parameter set, in words, with its number of pairs."""
    lines = []
    counts = _error_counts(data.rows)
    for ps, err in data.mean_abs_error_pct.items():
        n = counts.get(ps, 0)
        text = "n/a (no pair)" if math.isnan(err) else f"{err:.2f} % over {n} pair{'s' if n != 1 else ''}"
        lines.append(f"mean |error| of parameter set {ps} ({sweep.set_label(ps)}): {text}")
    return lines


def _simulated_thresholds(sweep: SweepResult) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """Per parameter set: (frequency_hz, simulated threshold_m)."""
    out = {}
    if sweep.mode == "threshold":
        res = sweep.results
        for ps in range(sweep.n_sets):
            sel = res["param_set"] == ps
            out[ps] = (res["frequency_hz"][sel], res["threshold_m"][sel])
    else:
        for gm in grid_maps(sweep):
            out[gm.param_set] = (gm.envelope_frequency_hz, gm.envelope_amplitude_m)
    return out


def compare_thresholds(sweep: SweepResult, campaign: Campaign,
                       specimen_id: str | None = None) -> tuple[list[ComparisonRow], list[str]]:
    """Comparison rows (parameter set, then specimen order, then frequency) and notes."""
    matches = match_specimens(sweep, campaign, specimen_id)
    simulated = _simulated_thresholds(sweep)
    notes = []
    if specimen_id is not None:
        spec = campaign.specimens[specimen_id]
        arch = sweep.config.get("arch", {})
        for key in _ARCH_KEYS:
            if isinstance(arch.get(key), (int, float)) and not _same(arch[key], getattr(spec, key)):
                notes.append(f"note: sweep &arch {key}={arch[key]} but specimen {specimen_id} has "
                             f"{getattr(spec, key)}")
    rows = []
    for ps in range(sweep.n_sets):
        freqs, thresholds = simulated[ps]
        for sid in matches[ps]:
            for m in measured_thresholds(campaign, sid):
                if not m.has_collapse:
                    notes.append(f"note: {sid} at {m.frequency_hz:g} Hz never collapsed; no measured threshold")
                    continue
                hit = [k for k, f in enumerate(freqs) if _same(f, m.frequency_hz)]
                sim = float(thresholds[hit[0]]) if hit else math.nan
                if not hit:
                    notes.append(f"note: the sweep has no run at {m.frequency_hz:g} Hz ({sid}, set {ps})")
                err = 100.0 * (sim - m.threshold_m) / m.threshold_m if math.isfinite(sim) else math.nan
                rows.append(ComparisonRow(ps, sweep.set_label(ps), sid, m.frequency_hz, sim, m.threshold_m,
                                          m.low_m, m.high_m, err))
    return rows, notes


def _error_counts(rows: list[ComparisonRow]) -> dict[int, int]:
    """Per parameter set, the pairs with both a measured and a simulated threshold."""
    counts: dict[int, int] = {}
    for r in rows:
        counts[r.param_set] = counts.get(r.param_set, 0) + int(math.isfinite(r.error_pct))
    return counts


def _mean_error_words(err: float, n: int) -> str:
    """'|error| 40.0 % (one pair)' or 'mean |error| 12.3 % over 4 pairs'."""
    if n == 0 or math.isnan(err):
        return "no pair to compare"
    return f"|error| {err:.1f} % (one pair)" if n == 1 else f"mean |error| {err:.1f} % over {n} pairs"


def plot_compare(sweep: SweepResult, campaign: Campaign, out_png: str | os.PathLike,
                 specimen_id: str | None = None) -> CompareData:
    """Grouped bars of measured and simulated thresholds per (specimen, frequency) and the
    relative error [%] per parameter set (as Fig. 10 of the seed paper). A measured
    bracket closed below (a test stood below the first collapse) is drawn as a bracket
    about the bar of its midpoint; a bracket open below (no test stood below the
    collapse) is a one-sided bound: the threshold is at most the first collapse, drawn
    as a cap with an arrow pointing down, and its relative error is a lower bound (>=).
    Returns the compared numbers."""
    rows, notes = compare_thresholds(sweep, campaign, specimen_id)
    pairs = list(dict.fromkeys((r.specimen_id, r.frequency_hz) for r in rows))
    sets = sorted({r.param_set for r in rows})
    mean_err = {}
    for ps in sets:
        errs = [abs(r.error_pct) for r in rows if r.param_set == ps and math.isfinite(r.error_pct)]
        mean_err[ps] = float(np.mean(errs)) if errs else math.nan
    counts = _error_counts(rows)

    fig = new_figure(max(10.0, 1.6 * len(pairs) + 6.0), 8.0)
    ax_a, ax_e = fig.subplots(2, 1, sharex=True)
    x = np.arange(len(pairs))
    # Each (specimen, frequency) gets the measured slot and a bar for each parameter set
    # simulated there only (the seed arches are one set each: no empty slots).
    present = {p: [ps for ps in sets if any(r.param_set == ps and (r.specimen_id, r.frequency_hz) == p
                                            for r in rows)] for p in pairs}
    width = 0.8 / (1 + max(len(v) for v in present.values()))
    measured = {(r.specimen_id, r.frequency_hz): r for r in rows}
    starts = np.array([x[i] - 0.5 * width * (1 + len(present[p])) for i, p in enumerate(pairs)])
    open_below = {p: not math.isfinite(measured[p].low_m) for p in pairs}
    drawn_closed = drawn_open = False
    for i, p in enumerate(pairs):
        xm, row = starts[i] + 0.5 * width, measured[p]
        if open_below[p]:
            # At most the first collapse: a cap there and an arrow down (no bar: there is
            # no value below it that a test has shown).
            top = 1e3 * row.high_m
            ax_a.plot([xm - 0.4 * width, xm + 0.4 * width], [top, top], color="0.2", linewidth=2.5)
            ax_a.annotate("", (xm, 0.55 * top), (xm, top), arrowprops=dict(arrowstyle="-|>", color="0.2",
                                                                             linewidth=1.5, mutation_scale=14))
            drawn_open = True
        else:
            ax_a.bar(xm, 1e3 * row.measured_m, width, color="0.55")
            ax_a.errorbar(xm, 1e3 * row.measured_m, yerr=[[1e3 * (row.measured_m - row.low_m)],
                                                          [1e3 * (row.high_m - row.measured_m)]],
                          color="black", capsize=4, linewidth=1.2)
            drawn_closed = True
    handles = []
    if drawn_open:
        handles.append(ax_a.plot([], [], color="0.2", linewidth=2.5, marker="v", markersize=6,
                                 label="measured: the first collapse; no test stood below it, so the\n"
                                       "threshold is at most this (a one-sided bound)")[0])
    if drawn_closed:
        handles.append(ax_a.errorbar([], [], yerr=[], color="black", capsize=4,
                                     label="measured bracket (last stand, first collapse) about its midpoint"))
    for k, ps in enumerate(sets):
        sel = {(r.specimen_id, r.frequency_hz): r for r in rows if r.param_set == ps}
        where = [i for i, p in enumerate(pairs) if p in sel]
        xs = np.array([starts[i] + (1.5 + present[pairs[i]].index(ps)) * width for i in where])
        sim = np.array([1e3 * sel[pairs[i]].simulated_m for i in where])
        err = np.array([sel[pairs[i]].error_pct for i in where])
        colour = COLORS[k % len(COLORS)]
        words = parameters_in_words(sweep.set_parameters(ps)) or "the sweep's arch"
        ax_a.bar(xs, np.nan_to_num(sim), width, color=colour, label=f"simulated: {words}")
        ax_e.bar(xs, np.nan_to_num(err), width, color=colour,
                 label=f"{words}: {_mean_error_words(mean_err[ps], counts.get(ps, 0))}")
        for xi, e, i in zip(xs, err, where):
            if math.isfinite(e):
                bound = "≥ " if open_below[pairs[i]] else ""
                ax_e.annotate(f"{bound}{e:+.0f} %", (xi, e), textcoords="offset points",
                              xytext=(0, 3 if e >= 0 else -10), ha="center", fontsize=7)
            else:
                ax_e.annotate("no collapse\nsimulated", (xi, 0), textcoords="offset points", xytext=(0, 3),
                              ha="center", fontsize=7)
    ax_e.axhline(0.0, color="black", linewidth=0.8)
    ax_e.margins(y=0.15)
    ax_e.set_xlim(-0.5 - 0.3 * (len(pairs) < 3), len(pairs) - 0.5 + 0.3 * (len(pairs) < 3))
    ax_a.set_ylabel("threshold amplitude [mm]")
    ax_a.set_title("Collapse threshold: measured and simulated", fontsize=10)
    ax_a.margins(y=0.1)
    ax_e.set_ylabel("relative error [%]")
    ax_e.set_title("(simulated − measured) / measured", fontsize=10)
    ax_e.set_xticks(x, [f"{sid}\n{f:g} Hz" for sid, f in pairs])
    ax_e.set_xlabel("specimen, frequency")
    for ax in (ax_a, ax_e):
        ax.grid(True, axis="y", alpha=0.3)
    ax_a.legend(handles=handles + [h for h in ax_a.get_legend_handles_labels()[0] if h not in handles],
                fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside, over no bar
    bound = ([Line2D([], [], linestyle="none", marker="$≥$", markersize=8, color="black",
                     label="a lower bound of the error: the measured\nthreshold is at most its value")]
             if drawn_open else [])
    ax_e.legend(handles=ax_e.get_legend_handles_labels()[0] + bound, fontsize=7.5, loc="upper left",
                bbox_to_anchor=(1.01, 1.0))
    fig.suptitle(wrap_text(f"Collapse thresholds under sinusoidal shaking: simulation against the shaking-table "
                           f"tests of {campaign.name}", fig.get_figwidth() - 0.3, 11), fontsize=11)
    png = save_figure(fig, out_png, note=provenance(sweep.code_version, os.path.basename(sweep.path), campaign.path))
    table = ReportTable(["param_set", "parameters", "specimen_id", "frequency_hz", "measured_mm", "low_mm",
                         "high_mm", "simulated_mm", "error_pct", "measured_full_cycle_accel_m_s2",
                         "simulated_full_cycle_accel_m_s2"],
                        [(r.param_set, r.label, r.specimen_id, r.frequency_hz, 1e3 * r.measured_m, 1e3 * r.low_m,
                          1e3 * r.high_m, 1e3 * r.simulated_m, r.error_pct, r.measured_full_cycle_accel_m_s2,
                          r.simulated_full_cycle_accel_m_s2) for r in rows],
                        title=f"Simulated vs measured thresholds ({sweep.path} / {campaign.path})")
    return CompareData(rows, mean_err, png, table, notes)
