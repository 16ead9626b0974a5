"""The diagnosis's figures, drawn from plain data so that a test can draw each from a few
numbers: the measured thresholds against the models and the posterior probabilities
(report.md), the actuator fit of the table records, and the reliability of the stated
probabilities (bench/diagnosis_calibration.sh, docs/figures/diagnosis_reliability.png).

Each function writes one PNG into ``out`` and returns its file name."""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

import numpy as np

from ..analysis.afd import afd_command
from ..plots.drawing import COLORS, new_figure, save_figure, save_png
from .decision import NAME_AT
from .observations import PairObservation

__all__ = ["thresholds_figure", "probabilities_figure", "table_figure", "reliability_figure", "ReliabilityBin"]

#: The colour of a model's prediction (the nominal model grey), of the line where a cause is named.
_MODEL_COLOUR, _NOMINAL_COLOUR, _NAMED_AT_STYLE = COLORS[0], "0.45", dict(color="k", lw=0.8, ls="--")


def thresholds_figure(out: Path, pairs: Sequence[PairObservation], nominal_m: Sequence[float],
                      shown: str | None, shown_probability: float, shown_m: Sequence[float] | None,
                      note: str, fmt: str = "png") -> str:
    """Each pair's measured bracket (a bound where no test stood below the collapse), the
    nominal model's threshold and the shown model's, fitted without the specimen."""
    fig = new_figure(max(6.5, 1.1 * len(pairs) + 2.5), 4.6)
    ax = fig.subplots()
    x = np.arange(len(pairs))
    closed = np.array([p.closed for p in pairs])
    above = np.array([not p.collapsed for p in pairs])  # every test stood: a bound from below
    meas = np.array([1e3 * p.threshold_m if p.closed else np.nan for p in pairs])
    low = np.array([1e3 * p.low_m for p in pairs])
    high = np.array([1e3 * p.high_m for p in pairs])
    if closed.any():
        ax.errorbar(x[closed], meas[closed], yerr=[(meas - low)[closed], (high - meas)[closed]], fmt="o", color="k",
                    capsize=4, label="measured: midpoint, bar from the last stand to the first collapse")
    ax.plot(x - 0.15, 1e3 * np.asarray(nominal_m), "s", color=_NOMINAL_COLOUR, label="nominal model")
    if shown and shown_m is not None:
        ax.plot(x + 0.15, 1e3 * np.asarray(shown_m), "D", color=_MODEL_COLOUR,
                label=f"{shown} (probability {shown_probability:.2f}), fitted without the specimen")
    # A bound is not a value: a cap at the first collapse with an arrow down where no stand
    # lies below it (as in the compare figure), a cap at the last stand with an arrow up
    # where every test stood; the arrows a tenth of the points' span long, and the axes
    # widened to hold their tips (annotations do not widen them).
    ends = np.concatenate([high[np.isfinite(high)], low[low > 0], 1e3 * np.asarray(nominal_m, float)])
    length = 0.1 * max(float(np.ptp(ends)), 0.2 * float(np.max(ends)))
    tips = []
    for k in np.flatnonzero(~closed):
        up = bool(above[k])
        at = low[k] if up else high[k]
        tip = at + length if up else at - length
        tips.append(tip)
        ax.plot([x[k] - 0.08, x[k] + 0.08], [at, at], color="k", linewidth=2.5)
        ax.annotate("", (x[k], tip), (x[k], at), arrowprops=dict(arrowstyle="-|>", color="k", linewidth=1.3,
                                                                   mutation_scale=12))
    if (~closed & ~above).any():
        ax.plot([], [], color="k", linewidth=2.5, marker="v", markersize=6,
                label="measured: at most the first collapse (no stand row below it)")
    if above.any():
        ax.plot([], [], color="k", linewidth=2.5, marker="^", markersize=6,
                label="measured: above the last stand (every test stood)")
    if tips:
        bottom, top = ax.get_ylim()
        new_bottom, new_top = min(bottom, min(tips)), max(top, max(tips))
        pad = 0.05 * (new_top - new_bottom)
        ax.set_ylim(new_bottom - (pad if new_bottom < bottom else 0.0), new_top + (pad if new_top > top else 0.0))
    ax.set_xticks(x)
    ax.set_xticklabels([f"{p.specimen_id}\n{p.frequency_hz:g} Hz" for p in pairs], fontsize=8)
    ax.set_xlim(-0.6, len(pairs) - 0.4)
    ax.set_ylabel("collapse threshold:\ntable displacement amplitude [mm]")
    ax.set_title("Collapse thresholds: measured brackets against the models")
    # Below the axes, where no point can hide under it.
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=1, frameon=False)
    save_figure(fig, out / f"thresholds.{fmt}", note=note)
    return f"thresholds.{fmt}"


def probabilities_figure(out: Path, probabilities: dict[str, float], note: str, fmt: str = "png") -> str:
    """The posterior probability of the models above 0.005 (at most ten), most probable on top."""
    ranked = sorted(probabilities, key=lambda m: -probabilities[m])
    shown = [m for m in ranked if probabilities[m] >= 0.005][:10] or ranked[:1]
    fig = new_figure(7.5, 0.35 * len(shown) + 1.9)
    ax = fig.subplots()
    y = np.arange(len(shown))[::-1]
    ax.barh(y, [probabilities[m] for m in shown], color=_MODEL_COLOUR)
    ax.axvline(NAME_AT, label=f"a cause is named at {NAME_AT:g}", **_NAMED_AT_STYLE)
    ax.set_yticks(y)
    ax.set_yticklabels(shown, fontsize=8)
    ax.set_xlim(0, 1)
    ax.set_xlabel("posterior probability")
    ax.set_title("Posterior probability of each model (those above 0.005)")
    ax.legend(fontsize=8, loc="lower right")
    save_figure(fig, out / f"probabilities.{fmt}", note=note)
    return f"probabilities.{fmt}"


def table_figure(out: Path, campaign, table, note: str, fmt: str = "png") -> str | None:
    """The commanded and measured table motion of the largest recorded test, and the
    actuator fit (gain, delay) of every record; None without records."""
    if table.source != "records" or not table.per_test:
        return None
    tid = max(table.per_test, key=lambda r: campaign.tests[r[0]].amplitude_m)[0]
    rec, test = campaign.records[tid], campaign.tests[tid]
    t = rec.t_s - rec.t_s[0]
    fig = new_figure(11.0, 3.8)
    axes = fig.subplots(1, 2)
    axes[0].plot(t, 1e3 * afd_command(t, test.frequency_hz, test.amplitude_m, test.n_attack, test.n_full,
                                      test.n_decay), color=COLORS[0], label="command")
    axes[0].plot(t, 1e3 * (rec.table_x_m - rec.table_x_m[0]), lw=0.8, color=COLORS[1], label="measured")
    axes[0].set_xlabel("time [s]")
    axes[0].set_ylabel("table displacement [mm]")
    axes[0].set_title(f"Commanded and measured table motion, test {tid}", fontsize=9)
    axes[0].legend(fontsize=8)
    axes[1].plot([1e3 * r[2] for r in table.per_test], [r[1] for r in table.per_test], "o", color=COLORS[0],
                 label="one record: gain x command(t - delay)")
    axes[1].axhline(1.0, color="k", lw=0.6, label="the command (gain 1)")
    axes[1].set_xlabel("fitted delay [ms]")
    axes[1].set_ylabel("fitted gain (measured / commanded)")
    axes[1].set_title("Actuator fit of every record", fontsize=9)
    axes[1].legend(fontsize=8)
    save_figure(fig, out / f"table_records.{fmt}", note=note)
    return f"table_records.{fmt}"


#: One bin of the reliability figure: stated probabilities in [low, high), their number
#: of draws, mean stated probability, fraction right and its 95 % interval.
ReliabilityBin = tuple[float, float, int, float, float, float, float]


def reliability_figure(out: Path, bins: Sequence[ReliabilityBin], note: str | None = None) -> str:
    """Stated probability of the most probable model against how often it is the truth."""
    fig = new_figure(6.6, 5.0)  # wide enough for the provenance line of the bench
    ax = fig.subplots()
    ax.plot([0, 1], [0, 1], color="0.45", lw=0.8, label="perfectly calibrated")
    for _, _, n, stated, right, ci_low, ci_high in bins:
        ax.errorbar(stated, right, yerr=[[right - ci_low], [ci_high - right]], fmt="o", color=_MODEL_COLOUR,
                    capsize=3)
        # The count under the bar, centred: clear of the line at 0.9 and of the diagonal.
        # (above the bar where it reaches the axis)
        low_end = ci_low > 0.06
        ax.annotate(f"{n}", (stated, ci_low if low_end else ci_high), textcoords="offset points",
                    xytext=(0, -3 if low_end else 3), ha="center", va="top" if low_end else "bottom", fontsize=7)
    ax.axvline(NAME_AT, label=f"a cause is named at {NAME_AT:g}", **_NAMED_AT_STYLE)
    ax.plot([], [], "o", color=_MODEL_COLOUR, label="campaigns binned by stated probability\n(bar: 95 % interval, "
                                                    "bootstrap over the truths;\nnumber: campaigns)")
    ax.set_xlim(0, 1.02)
    ax.set_ylim(0, 1.02)
    ax.set_xlabel("stated probability of the most probable model")
    ax.set_ylabel("observed frequency that it is the truth")
    ax.set_title("Reliability of the diagnosis's probabilities\n(campaigns made by LMGC90, truths in the catalogue)",
                 fontsize=10)
    ax.legend(fontsize=7, loc="upper left")
    save_png(fig, out / "diagnosis_reliability.png", note=note)
    return "diagnosis_reliability.png"
