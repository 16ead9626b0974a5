"""Stage 6 of the diagnosis: report.md, its figures, and the plain-words notes."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..plots.drawing import new_figure, provenance, save_png
from ..analysis.afd import afd_command
from .decision import NAME_AT, Decision
from .likelihood import GAIN_SCATTER_DEFAULT, OUTLIER_FACTOR, OUTLIER_PROB, TAU0
from .models import CANDIDATES, members
from .posterior import ADEQUATE_P, Posterior

__all__ = ["write_report", "notes", "METHOD_CHECK"]

#: How the probabilities were checked (docs/diagnosis.md has the table).
METHOD_CHECK = ("The probabilities were checked by a calibration study (bench/diagnosis_calibration.sh, "
                "docs/diagnosis.md): campaigns written by an independent generator (chamfered polygon blocks, "
                "a finer time step, an actuator played as a record, effects outside the catalogue), each in "
                "many noise draws, diagnosed by this method; it reports how often a cause named at 0.9 is right "
                "and how often the truth lies in the 90 % set of rivals.")

PRIOR_TEXT = ("Prior: `none` 1/4; each of the five single effects 1/10; each of the ten pairs 1/40. Parameters "
              "uniform: contact inset 0 to 10 mm (0 to 8 mm in a pair), friction nominal -0.25 to +0.25 (within "
              "0.15 to 0.9; -0.2 to +0.1 in a pair), thickness factor 0.76 to 1.12 (0.82 to 1.06 in a pair), "
              "restraint left, right or both alike, table gain 0.7 to 1.4 (with records: each pair's gain as "
              "they measure it).")


def _pct(x) -> str:
    return "-" if x is None or not math.isfinite(x) else f"{100 * x:.1f} %"


def _md_table(headers, rows) -> str:
    out = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    out += ["| " + " | ".join(str(x) for x in r) + " |" for r in rows]
    return "\n".join(out)


def _param_text(params: dict) -> str:
    def one(k, v):
        if isinstance(v["value"], list):
            return f"{k} = {', '.join(v['value'])}"
        scale, unit, fmt = {"m": (1e3, " mm", ".2f"), "s": (1e3, " ms", ".1f")}.get(v["unit"], (1.0, "", ".3f"))
        return (f"{k} = {scale * v['value']:{fmt}}{unit} (90 %: {scale * v['low']:{fmt}} to "
                f"{scale * v['high']:{fmt}})")
    return "; ".join(one(k, v) for k, v in params.items())


def notes(decision: Decision, post: Posterior, result: dict, info: dict) -> str:
    """The one plain-words paragraph of diagnosis.json."""
    p = post.probabilities
    top = decision.top
    base = result["baseline"]["threshold_error_pct"]
    ext = result["extended"]
    ranked = ", ".join(f"{m} {p[m]:.2f}" for m in post.ranked()[:4])
    if not decision.adequate:
        text = (f"The nominal model misses the measured thresholds by {base:.1f} % on average. No model of the "
                f"catalogue explains the campaign: even the most probable, {top} ({p[top]:.2f}), fails the "
                f"posterior predictive check (p = {decision.p_value:.3f} < {ADEQUATE_P}); the cause is likely "
                f"outside the catalogue or several at once.")
    elif decision.verdict == "none":
        text = (f"The nominal model explains the data: probability {p['none']:.2f} (the nominal model misses the "
                f"measured thresholds by {base:.1f} % on average, within their uncertainty).")
    elif decision.verdict != "inconclusive":
        text = (f"Named with probability {p[top]:.2f}: {top} ({_param_text(result['parameters'])}). The nominal "
                f"model misses the thresholds by {base:.1f} %; the named model, fitted without each specimen it "
                f"predicts, by {ext['threshold_error_pct']:.1f} %"
                + (f" (standard error {ext['threshold_error_se_pct']:.1f} %)" if ext["threshold_error_se_pct"]
                   is not None else "") + f". Most probable models: {ranked}.")
    else:
        text = (f"The data cannot tell these models apart: {', '.join(decision.rivals)} hold {NAME_AT:g} of the "
                f"probability together ({ranked}); none reaches {NAME_AT:g}.")
        common = set(members(decision.rivals[0])).intersection(*(set(members(m)) for m in decision.rivals[1:]))
        if common:
            text += f" Every rival includes {' and '.join(sorted(common))}: that part is established."
        nt = info.get("next_test")
        if nt:
            text += (f" The test whose outcome would best separate them: specimen {nt['specimen_id']} at "
                     f"{nt['frequency_hz']:g} Hz"
                     + (" (a frequency not tested yet), where the rivals predict thresholds of "
                        + ", ".join(f"{m} {1e3 * v:.1f} mm" for m, v in nt["predicted_m"].items())
                        if nt["new"] else ", ramped again in finer steps") + ".")
    for s in info.get("screen", []):
        text += " " + s["sentence"]
    return text


def _figure_thresholds(out: Path, obs, post: Posterior, decision: Decision, info: dict, note: str) -> str:
    pairs = obs.pairs
    fig = new_figure(max(6.5, 1.1 * len(pairs) + 2.5), 4.4)
    ax = fig.subplots()
    x = np.arange(len(pairs))
    closed = np.array([p.low_m > 0 for p in pairs])
    meas = np.array([1e3 * p.threshold_m for p in pairs])
    low = np.array([1e3 * p.low_m for p in pairs])
    high = np.array([1e3 * p.high_m for p in pairs])
    if closed.any():
        ax.errorbar(x[closed], meas[closed], yerr=[(meas - low)[closed], (high - meas)[closed]], fmt="o", color="k",
                    capsize=4, label="measured: midpoint, bar from the last stand to the first collapse")
    # A pair with no stand below its collapse is a bound, not a value: the threshold is at
    # most the first collapse (a cap there and an arrow down, as in the compare figure).
    for k in np.flatnonzero(~closed):
        ax.plot([x[k] - 0.08, x[k] + 0.08], [high[k], high[k]], color="k", linewidth=2.5)
        ax.annotate("", (x[k], 0.85 * high[k]), (x[k], high[k]),
                    arrowprops=dict(arrowstyle="-|>", color="k", linewidth=1.3, mutation_scale=12))
    if (~closed).any():
        ax.plot([], [], color="k", linewidth=2.5, marker="v", markersize=6,
                label="measured: at most the first collapse (no test stood below it)")
    ax.plot(x - 0.15, 1e3 * info["baseline_pred"], "s", color="0.45", label="nominal model")
    shown = decision.shown
    if shown:
        pred = info["held"][shown][0]
        ax.plot(x + 0.15, 1e3 * pred, "D", color="tab:blue",
                label=f"{shown} (probability {post.probabilities[shown]:.2f}), fitted without the specimen")
    ax.set_xticks(x)
    ax.set_xticklabels([f"{p.specimen_id}\n{p.frequency_hz:g} Hz" for p in pairs], fontsize=8)
    ax.set_ylabel("collapse threshold, table displacement amplitude [mm]")
    ax.set_title("Collapse thresholds: measured brackets against the models")
    ax.legend(fontsize=7)
    save_png(fig, out / "thresholds.png", note=note)
    return "thresholds.png"


def _figure_probabilities(out: Path, post: Posterior, note: str) -> str:
    ranked = post.ranked()
    shown = [m for m in ranked if post.probabilities[m] >= 0.005][:10] or ranked[:1]
    fig = new_figure(7.5, 0.35 * len(shown) + 1.9)
    ax = fig.subplots()
    y = np.arange(len(shown))[::-1]
    ax.barh(y, [post.probabilities[m] for m in shown], color="tab:blue")
    ax.axvline(NAME_AT, color="k", lw=0.8, ls="--", label=f"a cause is named at {NAME_AT:g}")
    ax.set_yticks(y)
    ax.set_yticklabels(shown, fontsize=8)
    ax.set_xlim(0, 1)
    ax.set_xlabel("posterior probability")
    ax.set_title("Posterior probability of each model (those above 0.005)")
    ax.legend(fontsize=8, loc="lower right")
    save_png(fig, out / "probabilities.png", note=note)
    return "probabilities.png"


def _figure_table(out: Path, campaign, table, note: str) -> str | None:
    if table.source != "records" or not table.per_test:
        return None
    tid = max(table.per_test, key=lambda r: campaign.tests[r[0]].amplitude_m)[0]
    rec, test = campaign.records[tid], campaign.tests[tid]
    t = rec.t_s - rec.t_s[0]
    fig = new_figure(11.0, 3.6)
    axes = fig.subplots(1, 2)
    axes[0].plot(t, 1e3 * afd_command(t, test.frequency_hz, test.amplitude_m, test.n_attack, test.n_full,
                                      test.n_decay), label="command")
    axes[0].plot(t, 1e3 * (rec.table_x_m - rec.table_x_m[0]), lw=0.8, label="measured")
    axes[0].set_xlabel("time [s]")
    axes[0].set_ylabel("table displacement [mm]")
    axes[0].set_title(f"Commanded and measured table motion, test {tid}", fontsize=9)
    axes[0].legend(fontsize=8)
    axes[1].plot([1e3 * r[2] for r in table.per_test], [r[1] for r in table.per_test], "o",
                 label="one record: gain x command(t - delay)")
    axes[1].axhline(1.0, color="k", lw=0.6, label="the command (gain 1)")
    axes[1].set_xlabel("fitted delay [ms]")
    axes[1].set_ylabel("fitted gain (measured / commanded)")
    axes[1].set_title("Actuator fit of every record", fontsize=9)
    axes[1].legend(fontsize=8)
    save_png(fig, out / "table_records.png", note=note)
    return "table_records.png"


def _model_rows(post: Posterior, info: dict, result: dict) -> list:
    by_model = dict(zip(CANDIDATES, result["candidates"]))
    rows = []
    for m in post.ranked():
        err, se = (info["held"][m][1], info["held"][m][2])
        params = by_model[m]["parameters"] if m in by_model else {}
        rows.append((f"`{m}`", f"{info['prior'][m]:.3f}", f"{post.probabilities[m]:.3f}",
                     _pct(err) + ("" if not math.isfinite(se) else f" ± {_pct(se)}"), _param_text(params) or "-"))
    return rows


def write_report(out: Path, campaign, obs, post: Posterior, decision: Decision, result: dict, info: dict) -> str:
    """Write report.md and its figures; return the notes paragraph."""
    bank = info["bank"]
    note = provenance(f"voussoir-diagnose, executables {bank.code}", f"campaign {campaign.name}")
    text = notes(decision, post, result, info)
    figs = [_figure_thresholds(out, obs, post, decision, info, note), _figure_probabilities(out, post, note)]
    tfig = _figure_table(out, campaign, info["table"], note)
    sc = post.scales
    lines = [f"# Diagnosis of campaign `{campaign.name}`", "", f"**Verdict: `{result['verdict']}`.** {text}", "",
             f"![probabilities]({figs[1]})", "", "## Thresholds", "",
             f"Mean absolute error of the nominal model: {result['baseline']['threshold_error_pct']:.1f} %. "
             + (f"Of `{decision.shown}`, fitted without the specimen it predicts: "
                f"{result['extended']['threshold_error_pct']:.1f} %." if decision.shown else ""), "",
             f"![thresholds]({figs[0]})", "",
             _md_table(["specimen", "f [Hz]", "last stand [mm]", "first collapse [mm]", "nominal [mm]"],
                       [(p.specimen_id, f"{p.frequency_hz:g}", "-" if p.low_m <= 0 else f"{1e3 * p.low_m:.1f}",
                         f"{1e3 * p.high_m:.1f}", f"{1e3 * b:.1f}")
                        for p, b in zip(obs.pairs, info["baseline_pred"])]),
             "", "## Every model", "",
             "Prior and posterior probability, held-out error (fitted without the specimen it predicts, with "
             "its standard error over the pairs) and the posterior mean and 90 % credible interval of the "
             "parameters.", "", _md_table(["model", "prior", "posterior", "held-out error", "parameters"],
                                          _model_rows(post, info, result)),
             "", "## How the probabilities are made", "",
             "Each pair's rows bracket its threshold; the likelihood is the probability that the threshold lies "
             "in the bracket, under each model over a grid of its parameters, with: the simulator's own spread "
             f"({_pct(float(np.min(sc.sigma_sim)))} to {_pct(float(np.max(sc.sigma_sim)))} by pair: the replicas "
             "of the nominal model at dt x 0.97 and x 1.03 and with scan steps of 3 and 7 %, and the jitter of "
             "every model's simulated thresholds about its smooth fit), the "
             f"test-to-test table gain scatter ({_pct(sc.sigma_gain)}"
             + {"records": ", measured by the records",
                "peak_accel": ", from the measured peak accelerations, at least 3 % (a noisy peak overstates)",
                "none": f", assumed {_pct(GAIN_SCATTER_DEFAULT)} without records"}[obs.gain_source]
             + "), a discrepancy shared by a "
             f"specimen's pairs (integrated over {', '.join(_pct(t) for t in TAU0)}, plus the change of its "
             "thresholds from dt to dt / 2: "
             + ", ".join(f"{sid} {_pct(v)}" for sid, v in sc.d_fine.items())
             + f") and an outlier mixture (probability {OUTLIER_PROB:g}, within a factor {OUTLIER_FACTOR:g}). "
             + ("Each test's measured gain (records, or measured over commanded peak acceleration) is weighed "
                "too: 1 if the table followed the command, the pair's own gain under `table_motion`."
                if obs.gain_source != "none" else ""), "", PRIOR_TEXT, "",
             f"Posterior predictive check of `{decision.top}`: p = {decision.p_value:.3f} "
             f"({'adequate' if decision.adequate else 'not adequate'}; the threshold is {ADEQUATE_P}).", "",
             METHOD_CHECK, ""]
    lines += ["## The table", ""]
    lines.append({"records": "Records of the table's motion were fitted as gain x command(t - delay); each "
                             "test's gain enters the probabilities.",
                  "peak_accel": "No records; the measured peak accelerations over the commanded motion's own "
                                "peak (1.049 A (2 pi f)^2 for 1-1-1 cycles: the envelopes add to it) stand for "
                                "the gains (a noisy record overstates a peak).",
                  "none": "No records and no measured peak accelerations: the table's motion is unknown."
                  }[obs.gain_source])
    if tfig:
        lines += ["", f"![table]({tfig})"]
    lines += ["", "## Hinges and crown motion (reported, not in the probabilities)", ""]
    if result["baseline"]["hinge_match"] is None:
        lines.append("No hinges were observed (no hinges/ files).")
    else:
        lines.append(f"Fraction of observed hinges (joint and side) that the model opens in the same test, up to "
                     f"the collapse: nominal {_pct(result['baseline']['hinge_match'])}"
                     + (f", `{decision.shown}` {_pct(result['extended']['hinge_match'])}" if decision.shown else "")
                     + ".")
    crown = info.get("crown") or {}
    if crown.get("models"):
        lines += ["", f"Peak horizontal crown displacement of {len(crown['tests'])} recorded tests that stood, "
                      "against the simulation of the same test: mean |ln(simulated / measured)| (0 is perfect, "
                      "0.69 a factor of 2; peaks below 0.5 mm count as 0.5 mm).", "",
                  _md_table(["model", "mean abs log ratio of peaks"],
                            [(k, f"{v['mean']:.2f}") for k, v in crown["models"].items()])]
    if obs.apart:
        lines += ["", "## Specimens with an uncertain set-up", "",
                  "Declared `setup_certain = 0`: simulated with their declared set-up, not used in the "
                  "probabilities.", "",
                  _md_table(["specimen", "f [Hz]", "measured [mm]", "nominal [mm]", "nominal error"],
                            [(p.specimen_id, f"{p.frequency_hz:g}", f"{1e3 * p.threshold_m:.1f}",
                              f"{1e3 * t:.1f}", f"{100 * (t - p.threshold_m) / p.threshold_m:+.1f} %")
                             for p in obs.apart
                             for t in [bank.specimens[p.specimen_id].threshold("nominal", p.frequency_hz)]])]
    if info.get("samples"):
        lines += ["", "## The calibrated model, for the fragility", "",
                  f"{info['settings'].posterior_samples} samples of the arch's model drawn from the posterior (a "
                  "model by its probability, its parameters by their weights), written as &arch values of each "
                  "specimen (table gains and restraints, the laboratory's, are not carried): "
                  + ", ".join(f"`{p.name}`" for p in info["samples"])
                  + ". An IDA reads one with `&sweep model_samples_file` (docs/earthquakes.md)."]
    s = info["settings"]
    lines += ["", "## How this was made", "",
              f"voussoir-diagnose on `{campaign.path}`: simulation bank of {len(bank.specimens)} specimen(s) "
              f"({bank.searches} threshold searches made now, {bank.reused} specimens from the cache; executables "
              f"{bank.code}), {info['runs']} single runs, dt = {s.dt_s:g} s, {s.n_ranks} MPI ranks, "
              f"{info['elapsed_s']:.0f} s. The machine-readable result is `diagnosis.json` (contract version 3).", ""]
    (out / "report.md").write_text("\n".join(lines))
    return text

