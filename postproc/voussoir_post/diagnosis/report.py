"""Stage 6 of the diagnosis: report.md, its figures, and the plain-words notes."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..plots.drawing import provenance
from .decision import NAME_AT, Decision
from .figures import probabilities_figure, table_figure, thresholds_figure
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
    shown = decision.shown
    figs = [thresholds_figure(out, obs.pairs, info["baseline_pred"], shown,
                              post.probabilities[shown] if shown else float("nan"),
                              info["held"][shown][0] if shown else None, note),
            probabilities_figure(out, post.probabilities, note)]
    tfig = table_figure(out, campaign, info["table"], note)
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

