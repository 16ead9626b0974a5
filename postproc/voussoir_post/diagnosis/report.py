"""report.md and its figures for a diagnosis (see diagnosis.py)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..plots.drawing import new_figure, provenance, save_png
from .actuator import afd_command
from .effects import EFFECTS_BY_ID, Variant
from .selection import loss, mean_error

__all__ = ["write_report"]


def _pct(x: float | None) -> str:
    return "-" if x is None or not math.isfinite(x) else f"{100 * x:.1f} %"


def _md_table(headers, rows) -> str:
    out = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    out += ["| " + " | ".join(str(x) for x in r) + " |" for r in rows]
    return "\n".join(out)


def _figure_thresholds(out: Path, pairs, cands, decision, nested, note: str) -> str:
    fig = new_figure(max(6.0, 1.1 * len(pairs) + 2), 4.2)
    ax = fig.subplots()
    x = np.arange(len(pairs))
    meas = np.array([1e3 * p.measured.threshold_m for p in pairs])
    low = np.array([1e3 * (p.measured.low_m if math.isfinite(p.measured.low_m) else p.measured.high_m) for p in pairs])
    high = np.array([1e3 * p.measured.high_m for p in pairs])
    ax.errorbar(x, meas, yerr=[meas - low, high - meas], fmt="o", color="k", capsize=4,
                label="measured (bracket: last stand, first collapse)")
    base = [1e3 * p.simulated.get(Variant(), math.nan) for p in pairs]
    ax.plot(x - 0.15, base, "s", color="tab:red", label="nominal model")
    shown = decision.chosen or decision.best_rival
    if shown is not None and nested:
        ax.plot(x + 0.15, [1e3 * h for h in nested], "D", color="tab:blue",
                label=f"extended ({shown.effect}" + ("" if decision.chosen else ", best of the rivals")
                + "), nested held out")
    ax.set_xticks(x)
    ax.set_xticklabels([f"{p.spec.specimen_id}\n{p.measured.frequency_hz:g} Hz" for p in pairs], fontsize=8)
    ax.set_ylabel("collapse threshold amplitude [mm]")
    ax.set_title("Measured and simulated collapse thresholds")
    ax.legend(fontsize=8)
    name = "thresholds.png"
    save_png(fig, out / name, note=note)
    return name


def _figure_candidates(out: Path, pairs, cands, settings, table, note: str) -> str:
    drawn = sorted((e for e in EFFECTS_BY_ID.values() if e.figure_axis is not None), key=lambda e: e.figure_axis[0])
    fig = new_figure(4.0 * len(drawn), 3.6)
    axes = fig.subplots(1, len(drawn))
    for ax, e in zip(axes, drawn):
        effect, (_, scale, label) = e.id, e.figure_axis
        values = e.candidate_values(pairs, settings)
        err = [100 * mean_error(pairs, e, v) for v in values]
        x = np.array(values, float) * scale
        ax.plot(x, err, "-", color="tab:blue", label="mean threshold error")
        nll = ax.twinx()
        nll.plot(x, [loss(pairs, e, v) for v in values], ":", color="tab:orange")
        nll.set_ylabel("-log likelihood (fit criterion)", color="tab:orange", fontsize=8)
        ax.plot([], [], ":", color="tab:orange", label="-log likelihood (right axis)")
        c = cands[effect]
        measured = e.fixed_value(table) is not None
        ax.axvline(float(c.value) * scale, color="tab:green", ls="--",
                   label="measured on the table records (not fitted)" if measured
                   else "fitted: least -log likelihood\n(the change nearest nominal among ties)")
        ax.set_xlabel(label)
        ax.set_ylabel("mean threshold error [%]")
        ax.set_title(f"{effect}: held-out {100 * c.cv_error:.1f} %" + ("" if c.admissible else " (excluded)"),
                     fontsize=9)
        ax.legend(fontsize=8)
    fig.suptitle("Each candidate cause: mean error of the simulated collapse thresholds against its parameter "
                 "(all pairs with a certain set-up)", fontsize=10)
    name = "candidates.png"
    save_png(fig, out / name, note=note)
    return name


def _figure_table(out: Path, campaign, table, note: str) -> str | None:
    if table.source != "records" or not table.per_test:
        return None
    tid = max(table.per_test, key=lambda r: campaign.tests[r[0]].amplitude_m)[0]
    rec = campaign.records[tid]
    test = campaign.tests[tid]
    t = rec.t_s - rec.t_s[0]
    fig = new_figure(11.0, 3.6)
    axes = fig.subplots(1, 2)
    axes[0].plot(t, 1e3 * afd_command(t, test.frequency_hz, test.amplitude_m, test.n_attack, test.n_full,
                                      test.n_decay), label="command")
    axes[0].plot(t, 1e3 * (rec.table_x_m - rec.table_x_m[0]), lw=0.8, label="measured")
    axes[0].set_xlabel("time [s]")
    axes[0].set_ylabel("table displacement [mm]")
    axes[0].set_title(f"{tid}", fontsize=9)
    axes[0].legend(fontsize=8)
    gains = [r[1] for r in table.per_test]
    delays = [1e3 * r[2] for r in table.per_test]
    axes[1].plot(delays, gains, "o")
    axes[1].axhline(1.0, color="k", lw=0.6)
    axes[1].set_xlabel("fitted delay [ms]")
    axes[1].set_ylabel("fitted gain")
    axes[1].set_title("Actuator fit of every record", fontsize=9)
    name = "table_records.png"
    save_png(fig, out / name, note=note)
    return name


def write_report(out: Path, campaign, pairs, cands, decision, table, baseline_error, resolution, result, info
                 ) -> None:
    note = provenance(info.get("code_version", ""), f"voussoir-diagnose on {campaign.path}")
    nested = info.get("nested") or []
    figs = [_figure_thresholds(out, pairs, cands, decision, nested, note),
            _figure_candidates(out, pairs, cands, info["settings"], table, note)]
    tfig = _figure_table(out, campaign, table, note)
    lines = [f"# Diagnosis of campaign `{campaign.name}`", "",
             f"**Verdict: `{result['verdict']}`.** {result['notes']}", ""]
    if result["parameters"]:
        lines.append("Fitted parameters: " + "; ".join(
            f"{k} = {v['value']} (interval {v['low']} to {v['high']}{' ' + v['unit'] if v['unit'] else ''})"
            for k, v in result["parameters"].items()) + ".")
        lines.append("")
    lines += ["## Thresholds", "",
              f"Mean absolute error of the nominal model: {_pct(baseline_error)}; of the extended model, held out: "
              f"{result['extended']['threshold_error_pct']:.1f} % (nested cross-validation: the choice of the cause "
              f"itself redone without each specimen it then predicts). Measurement resolution (half the amplitude "
              f"steps, plus the search tolerance): {_pct(resolution)}.", "", f"![thresholds]({figs[0]})", ""]
    rows = []
    for k, p in enumerate(pairs):
        base = p.simulated.get(Variant(), math.nan)
        shown = decision.chosen or decision.best_rival
        ext = nested[k] if shown and nested else math.nan
        rows.append((p.spec.specimen_id, f"{p.measured.frequency_hz:g}",
                     "-" if not math.isfinite(p.measured.low_m) else f"{1e3 * p.measured.low_m:.1f}",
                     f"{1e3 * p.measured.high_m:.1f}", f"{1e3 * p.measured.threshold_m:.1f}",
                     f"{1e3 * base:.1f}", _pct((base - p.measured.threshold_m) / p.measured.threshold_m),
                     "-" if not math.isfinite(ext) else f"{1e3 * ext:.1f}"))
    lines.append(_md_table(["specimen", "f [Hz]", "last stand [mm]", "first collapse [mm]", "measured [mm]",
                            "nominal [mm]", "nominal error", "extended, nested held out [mm]"], rows))
    lines += ["", "## Candidate causes", "",
              "Each effect's parameter is fitted on all specimens but one and judged on the one left out "
              "(leave-one-specimen-out; leave-one-pair-out with a single specimen). A pair of effects "
              "(`a+b`) is listed when the additive screen (combined.py) found it promising; it was then "
              "simulated about its fit.", "",
              _md_table(["effect", "held-out error", "in-sample error", "fitted", "hinge match (recall)",
                         "hinge F1 (false hinges count)", "status"],
                        [(e, _pct(c.cv_error), _pct(c.in_sample_error), c.eff.value_text(c),
                          _pct(c.hinge_match) if c.hinge_match is not None else "-",
                          f"{c.hinge_score:.2f}" if c.hinge_score is not None else "-",
                          "admissible" if c.admissible else f"excluded: {c.reason}") for e, c in cands.items()]),
              "", f"![candidates]({figs[1]})", ""]
    lines += ["## The table", ""]
    if table.source == "records":
        lines.append(f"{table.n} records of afd tests fitted as gain x command(t - delay): gain {table.gain:.3f} "
                     f"(scatter {table.gain_sd:.3f}), delay {1e3 * table.delay_s:.1f} ms. "
                     + ("The table did not follow the command." if table.deviates
                        else "The table followed the command within the scatter."))
    elif table.source == "peak_accel":
        lines.append(f"No records; the measured peak accelerations are {table.gain:.3f} times the commanded "
                     f"A (2 pi f)^2 (median of {table.n} tests; a noisy record overstates a peak).")
    else:
        lines.append("No records and no measured peak accelerations: the table's motion is unknown.")
    if tfig:
        lines += ["", f"![table]({tfig})"]
    lines += ["", "## Hinges", ""]
    if result["baseline"]["hinge_match"] is None:
        lines.append("No hinges were observed (no hinges/ files).")
    else:
        lines.append(f"Fraction of observed hinges (joint and side) that the model reproduces in the same test: "
                     f"nominal {_pct(result['baseline']['hinge_match'])}, extended "
                     f"{_pct(result['extended']['hinge_match'])}.")
    suggestion = info.get("next_test")
    if suggestion:
        lines += ["", "## The test to run next", "",
                  f"The rivals ({', '.join(decision.rivals)}) each at its fitted value, on every specimen with a "
                  f"certain set-up at its tested frequencies and at new ones: the largest relative difference of "
                  f"their predicted thresholds is at **{suggestion['specimen']}, {suggestion['frequency_hz']:g} Hz**"
                  + (" (not tested yet)" if suggestion["new_frequency"] else "") + ": "
                  + ", ".join(f"{e} {1e3 * v:.1f} mm" for e, v in suggestion["predicted_threshold_m"].items())
                  + ". A ramp of that test with amplitude steps finer than that difference tells them apart."]
    uncertain = info.get("uncertain") or []
    if uncertain:
        lines += ["", "## Specimens with an uncertain set-up", "",
                  "Declared `setup_certain = 0` in specimens.csv: simulated with their declared set-up, but "
                  "they neither fit a parameter nor count in the errors above.", "",
                  _md_table(["specimen", "f [Hz]", "measured [mm]", "nominal [mm]", "named cause [mm]",
                             "reproduced alone by (within 5 %)"],
                            [(u["specimen"], f"{u['frequency_hz']:g}", f"{1e3 * u['measured_m']:.1f}",
                              f"{1e3 * u['nominal_m']:.1f}",
                              "-" if not math.isfinite(u["extended_m"]) else f"{1e3 * u['extended_m']:.1f}",
                              ", ".join(u["explained_by"]) or "no single effect") for u in uncertain])]
    alone = info.get("restrained_alone") or []
    if alone:
        lines += ["", "## A specimen restrained on its own", "",
                  "Brackets on one specimen only cannot be judged leaving that specimen out (nothing else "
                  "predicts them); each specimen with two or more frequencies is therefore also screened on its "
                  "own data: the restraint fitted on its other frequencies predicts each one held out, and must "
                  "beat by strong evidence the nominal model, the campaign's model and each other effect fitted "
                  "to that specimen alone the same way. Where it does:", "",
                  _md_table(["specimen", "restraint", "its held-out error"]
                            + list(alone[0]["other_errors"]),
                            [(r["specimen"], r["restraint"], _pct(r["held_out_error"]))
                             + tuple(_pct(x) for x in r["other_errors"].values()) for r in alone]),
                  "", *[r["sentence"] for r in alone]]
    crown = info.get("crown") or {}
    lines += ["", "## Crown motion", ""]
    if crown.get("models"):
        lines.append(f"Peak horizontal crown displacement of {len(crown['tests'])} recorded tests that stood (the "
                     "largest amplitudes, where the arch rocks most) against the simulation of the same test; "
                     "peaks below 0.5 mm count as 0.5 mm (sensor noise), a simulated collapse as 1 m. The figure "
                     "is the mean of |ln(simulated / measured)|: 0 is perfect, 0.69 a factor of 2.")
        lines.append("")
        lines.append(_md_table(["model", "mean abs log ratio of peaks"],
                               [(k, f"{v['mean']:.2f}") for k, v in crown["models"].items()]))
    else:
        lines.append("No record has the crown's motion.")
    s = info["settings"]
    lines += ["", "## How this was made", "",
              f"voussoir-diagnose run on `{campaign.path}`: {info['sweeps']} sweeps with voussoir-sweep on "
              f"{s.n_ranks} ranks and {info['runs']} single runs with voussoir-run, dt = {s.dt_s:g} s, threshold "
              f"tolerance {100 * s.amp_tol_fraction:g} % of the threshold, in {info['elapsed_s']:.0f} s. "
              f"Executables from `{s.bin_dir}` ({info.get('code_version') or 'version unknown'}). The "
              f"machine-readable result is `diagnosis.json`.", ""]
    (out / "report.md").write_text("\n".join(lines))
