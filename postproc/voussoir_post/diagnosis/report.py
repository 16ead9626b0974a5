"""Stage 6 of the diagnosis: report.md, its figures, and the plain-words notes."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import numpy as np

from ..plots.drawing import provenance
from .crown import FLOOR_M, NODES, T_DOF
from .decision import NAME_AT, Decision
from .figures import probabilities_figure, table_figure, thresholds_figure
from .early import EARLY_PROB_ROUGH, EARLY_PROB_SMOOTH, EARLY_PROB_UNKNOWN, EARLY_SPAN
from .likelihood import (GAIN_SCATTER_DEFAULT, ONE_SIDED_STEPS, OUTLIER_FACTOR, OUTLIER_PROB,
                         TAU_CAMPAIGN, TAU_PAIR, TAU_SPECIMEN)
from .models import CANDIDATES, MATERIAL, MATERIAL_EFFECT, members, model_prior
from .posterior import ADEQUATE_P, SENSITIVITY_FACTORS, Posterior
from .pulses import RATIO_SCALE, grid_log_ratio

__all__ = ["write_report", "notes", "METHOD_CHECK", "prior_text", "FLAG_TEXT"]

#: How the probabilities were checked (docs/diagnosis.md has the table).
METHOD_CHECK = ("The probabilities were checked by a calibration study (bench/diagnosis_calibration.sh, "
                "docs/diagnosis.md): campaigns made by another code (LMGC90) on truths drawn from this prior, "
                "with the faults of real laboratories (specimens built a little off, a transducer's calibration, "
                "ramps of 1 to 5 mm, collapse rows only, a campaign-wide offset) and truths outside the "
                "catalogue, each in many noise draws, diagnosed by this method; it reports how often a cause "
                "named at 0.9 is right, how often the truth lies in the 90 % set, and the reliability of the "
                "stated probabilities.")

#: What each flag of diagnosis.json means, for the report.
FLAG_TEXT = {"sensor_bias": "the records' common gain offset is within what the transducer's calibration allows "
                            "(table.csv `displacement_gain_sd`); it was taken as a possible sensor bias, not as a "
                            "cause",
             "inadequate": "the check of the most probable model failed: no model of the catalogue explains the "
                           "campaign, and no cause is named"}


def prior_text(settings, friction: float | None = None) -> str:
    """The prior, from the settings' grids (the ranges the bank simulates), never a fixed
    text; `friction` the specimens' nominal coefficient (its range is relative to it)."""
    inset = [e for e in settings.inset_grid_m]
    step, pair = max(settings.friction_steps), settings.pair_friction_steps
    f_text = (f"nominal - {step:g} to nominal + {step:g}" if friction is None else
              f"{max(settings.min_friction, friction - step):.3g} to {min(settings.max_friction, friction + step):.3g}")
    f_pair = (f"nominal {min(pair):+g} to {max(pair):+g}" if friction is None else
              f"{max(settings.min_friction, friction + min(pair)):.3g} to {min(settings.max_friction, friction + max(pair)):.3g}")
    t, tp = settings.thickness_factors, settings.pair_thickness_factors
    frac = lambda m: str(Fraction(model_prior(m)).limit_denominator(1000))
    return (f"Prior: `none` {frac('none')}, each of the five single effects {frac('friction')}, each of the ten "
            f"pairs {frac('friction+geometry')}. "
            f"Parameters uniform on the ranges the simulation bank covers: contact inset 0 to "
            f"{1e3 * max(inset):.3g} mm (0 to {1e3 * max(settings.pair_inset_m):.3g} mm in a pair; at most 0.45 of "
            f"the ring's thickness), friction {f_text} (within {settings.min_friction:g} to "
            f"{settings.max_friction:g}; {f_pair} in a pair), thickness factor {min(min(t), 1.0):g} to "
            f"{max(max(t), 1.0):g} ({min(min(tp), 1.0):g} to {max(max(tp), 1.0):g} in a pair); restraint left, "
            f"right or both alike, each {' or '.join('in contact' if g == 0 else f'{1e3 * g:g} mm off' for g in settings.bracket_gaps_m)} "
            "alike; table gain 0.7 to 1.4 for the campaign without records, each pair's gain as "
            "its records measure it with them. Only material points: a parameter at least "
            f"{1e3 * MATERIAL['contact_edges']:g} mm of inset, {MATERIAL['friction']:g} of friction or "
            f"{MATERIAL['geometry']:g} of thickness factor from nominal, whose effect moves at least one tested "
            f"threshold by {_pct(MATERIAL_EFFECT)} and by twice the build tolerance's spread at that pair "
            "(smaller effects are the nominal model: these tests could not tell them from it).")


def _early_text(obs, sc) -> str:
    """Which pairs the likelihood gives an early first collapse, and how probable (early.py)."""
    rough = [f"{p.specimen_id} {p.frequency_hz:g} Hz" for p, e in zip(obs.pairs, sc.early_prob)
             if e[0] == EARLY_PROB_ROUGH]
    return (f"probability {EARLY_PROB_ROUGH:g} where the kernel's own fine scan of the nominal arch falls early ("
            + (", ".join(rough) if rough else "no pair of this campaign")
            + f"), {EARLY_PROB_SMOOTH:g} where it does not, {EARLY_PROB_UNKNOWN:g} without a scan (rates from "
            "another code's fine scans).")


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


#: An advised test expected to tell less than this [bits] tells little: a test that surely
#: parts two even rivals tells 1 bit.
LITTLE_BITS = 0.1


def _little_to_tell(nt: dict) -> str:
    """The sentences of the notes when even the best test is expected to tell little
    (below LITTLE_BITS), and why, where the two leading rivals differ only by a thinner
    ring against pivots set in (empty otherwise)."""
    best = nt["expected_gain_bits"]
    if best >= LITTLE_BITS:
        return ""
    text = (f" No test within the table's limits is expected to tell much: the best {best:.2f} bits, where a test "
            "that surely parts two even rivals tells 1 bit.")
    lead = [set(members(m)) for m in list(nt["predicted_m"])[:2]]
    if len(lead) == 2 and lead[0] ^ lead[1] == {"geometry", "contact_edges"}:
        text += (" The two leading rivals differ by a thinner ring against pivots set in, which thin the arch's "
                 "line of thrust alike: on a shaking table their thresholds at every frequency, crown records, "
                 "pulses and static capacities differ by a few per cent at most, less than two codes differ "
                 "(docs/diagnosis.md, \"Why a thinner ring and pivots set in stay unnamed\"). Measuring the "
                 "ring's thickness and the voussoirs' edges on the specimens parts them where the table cannot.")
    return text


def _advice_text(nt: dict | None, what: str) -> str:
    """The sentence of the notes that gives the advised test (empty without one), and
    what to do instead when even it is expected to tell little (_little_to_tell)."""
    if not nt:
        return ""
    return _advised(nt, what) + _little_to_tell(nt)


def _advised(nt: dict, what: str) -> str:
    """The sentence of the notes that gives the advised test."""
    a = nt["amplitudes_m"]
    if nt.get("kind") == "hold_crown":
        return (f" {what} ({nt['expected_gain_bits']:.2f} bits): specimen {nt['specimen_id']} at "
                f"{nt['frequency_hz']:g} Hz, one afd test held at {1e3 * a[0]:.1f} mm (below the measured "
                "threshold) with the crown's horizontal displacement recorded, where the models predict peaks of "
                + ", ".join(f"{m} {1e3 * v:.2f} mm" for m, v in nt["predicted_crown_m"].items()) + ".")
    if nt.get("kind") == "pulse_pair":
        return (f" {what} ({nt['expected_gain_bits']:.2f} bits): specimen {nt['specimen_id']}, a pulse one way and "
                f"the other (next_test_pulse.csv, a table travel of 1 m: scaled from {1e3 * a[0]:.1f} to "
                f"{1e3 * a[1]:.1f} mm of travel by {1e3 * a[2]:.1f} mm, each way, to the first collapse), where the "
                "models predict ratios of the two ways' thresholds (the other way over its own) of "
                + ", ".join(f"{m} {v:.3f}" for m, v in nt["predicted_ratio"].items()) + ".")
    return (f" {what} ({nt['expected_gain_bits']:.2f} bits): specimen {nt['specimen_id']} at "
            f"{nt['frequency_hz']:g} Hz" + (" (a frequency not tested yet)" if nt["new"] else "")
            + f", an afd ramp from {1e3 * a[0]:.1f} to {1e3 * a[1]:.1f} mm by {1e3 * a[2]:.1f} mm, where "
            "the models predict thresholds of "
            + ", ".join(f"{m} {1e3 * v:.1f} mm" for m, v in nt["predicted_m"].items()) + ".")


def _next_test_lines(nt: dict | None) -> list[str]:
    """The section on the advised test: the best tests (at most four), each with its
    ramp, the information it is expected to give (with the Monte Carlo standard error of
    that expectation at a new frequency and the spread of what one run may give) and each
    rival's predicted threshold."""
    if not nt:
        return []
    tests = [nt] + list(nt.get("alternatives", []))
    rivals = list(nt["predicted_m"])

    def gain(t):
        se = t.get("gain_se_bits", 0.0)
        return f"{t['expected_gain_bits']:.2f}" + (f" ± {se:.2f}" if se > 0 else "")

    def what(t):
        a = t["amplitudes_m"]
        if t.get("kind") == "hold_crown":
            return f"hold at {1e3 * a[0]:.1f}, record the crown"
        if t.get("kind") == "pulse_pair":
            return f"pulse each way, travel {1e3 * a[0]:.1f} to {1e3 * a[1]:.1f} by {1e3 * a[2]:.1f}"
        return f"ramp {1e3 * a[0]:.1f} to {1e3 * a[1]:.1f} by {1e3 * a[2]:.1f}"

    def predicted(t, m):
        if t.get("kind") == "hold_crown":
            return f"crown {1e3 * t['predicted_crown_m'][m]:.2f}" if m in t.get("predicted_crown_m", {}) else "-"
        if t.get("kind") == "pulse_pair":
            return f"ratio {t['predicted_ratio'][m]:.3f}" if m in t.get("predicted_ratio", {}) else "-"
        return f"{1e3 * t['predicted_m'][m]:.1f}" if m in t.get("predicted_m", {}) else "-"

    rows = [(str(i + 1), t["specimen_id"], "(a pulse)" if t.get("kind") == "pulse_pair" else
             f"{t['frequency_hz']:g}" + (" (new)" if t.get("new") else ""),
             what(t), gain(t), f"{t.get('gain_spread_bits', float('nan')):.2f}", *[predicted(t, m) for m in rivals])
            for i, t in enumerate(tests)]
    gap = ""
    if len(tests) > 1:
        d = tests[0]["expected_gain_bits"] - tests[1]["expected_gain_bits"]
        se = math.hypot(tests[0].get("gain_se_bits", 0.0), tests[1].get("gain_se_bits", 0.0))
        gap = (f" The first leads the second by {d:.2f} bits" + (f" (standard error {se:.2f})" if se > 0 else "")
               + (": a near tie, either serves." if se > 0 and d < 2 * se else "."))
    return ["## The next test", "",
            "Afd ramps (from, to, by, in mm), afd tests held below a measured threshold with the crown "
            "recorded and pulse pairs (a pulse ramped in travel one way and the other), ranked by the expected "
            "information of their outcome (the bracket the ramp gives; the peak crown displacement of the held "
            "test; the ratio of the pulse's two ways) about which rival is the cause, in bits. `±`: the Monte Carlo "
            "standard error of that expectation where each rival's prediction is a mixture over a few simulated "
            "draws of its parameters (a jackknife over the draws). `spread`: the standard deviation, over the "
            "test's possible outcomes, of the information one run delivers (the rivals' entropy before less "
            "after): a single run often gives much less or much more than the expectation. The rivals' columns: "
            "each one's predicted threshold amplitude [mm] there, or for a held test its predicted peak crown "
            "displacement [mm], or for a pulse pair (a pulse one way and the other, next_test_pulse.csv scaled to "
            "the travel of the ramp) its predicted ratio of the two ways' thresholds, the other way over its own "
            "(1 for a mirror-symmetric arch)." + gap, "",
            _md_table(["rank", "specimen", "f [Hz]", "test [mm]", "expected [bits]", "spread [bits]",
                       *[f"{m} [mm]" for m in rivals]], rows), ""]


def _crown_lines(evidence, post: Posterior) -> list[str]:
    """The section on the crown records that entered the probabilities (crown.py)."""
    if not evidence or not evidence[0]:
        return []
    tests, factors, weighed = evidence
    if not weighed:
        return ["## Crown records", "",
                f"{len(tests)} tests that stood near their pair's threshold carry a crown record. They are not in "
                "the probabilities: `voussoir-diagnose run --crown-records` weighs them (docs/diagnosis.md says how, "
                "and why it is not yet the default).", ""]
    shown = post.ranked()[:4]
    rows = [(c.test.test_id, c.test.specimen_id, f"{c.test.frequency_hz:g}", f"{1e3 * c.test.amplitude_m:.1f}",
             f"{c.fraction:.3f}", f"{1e3 * c.peak_m:.2f}" + (" (below the floor)" if c.peak_m < FLOOR_M else ""),
             f"{c.scale:.2f}") for c in tests]
    best = max(factors[m] for m in shown)
    return ["## Crown records in the probabilities", "",
            f"{len(tests)} tests that stood below their pair's measured threshold carry a crown record. Each model "
            "is simulated at the same fraction of its own threshold, for a few draws of its parameters, at "
            f"{NODES} amplitudes that cover where in its bracket the specimen's threshold lies, how well the model "
            "knows its own for the specimen as built, and how far the codes differ in where the crown starts to "
            "grow; the measured peak |crown dx| against the simulated ones is a Student t of "
            f"{T_DOF} degrees of freedom in log, of the scale measured across codes at the test's fraction "
            f"(censored below {1e3 * FLOOR_M:g} mm, a transducer's noise).", "",
            _md_table(["test", "specimen", "f [Hz]", "amplitude [mm]", "fraction of threshold", "peak [mm]",
                       "scale (log)"], rows), "",
            "What the records did to the most probable models (log factor relative to the best of them, and the "
            "odds it multiplies): " + ", ".join(f"{m} {factors[m] - best:+.2f} (x {math.exp(factors[m] - best):.3g})"
                                                for m in shown) + ".", ""]


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
                f"check on the specimens it was not fitted to (p = {decision.p_value:.3f} < {ADEQUATE_P}); the cause is likely "
                f"outside the catalogue or several at once.")
        text += _advice_text(info.get("next_test"), "The test whose outcome is expected to tell most about which of "
                             "the catalogue's most probable models comes nearest, and whether the misfit repeats")
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
        text += _advice_text(info.get("next_test"), "The test whose outcome is expected to tell most about the cause")
    for s in info.get("screen", []):
        text += " " + s["sentence"]
    return text


def unread_text(obs) -> str:
    """The sentence of the notes on the tests the diagnosis does not read (none: '')."""
    if not obs.unread:
        return ""
    ids = ", ".join(obs.unread[:5]) + (", ..." if len(obs.unread) > 5 else "")
    n = len(obs.unread)
    return (f" {n} test{'s' if n > 1 else ''} driven by a record ({ids}) {'are' if n > 1 else 'is'} in none of "
            f"these probabilities: the diagnosis reads afd ramps (a frequency and an amplitude per test) and pulses "
            f"of one shape ramped one way and the other on a specimen with afd pairs, not other motions given by "
            f"a record alone.")


def _pulse_lines(obs, post: Posterior) -> list[str]:
    """The section on the pulse pairs that entered the probabilities (pulses.py): each
    way's bracket, the measured ratio, and each leading model's predicted ratio."""
    if not obs.pulse_pairs or post.bank is None:
        return []
    shown = post.ranked()[:4]
    rows = []
    for pp in obs.pulse_pairs:
        ratios = post.bank.pulses.get(pp.bank_key, {})
        own, other = pp.ramps[1], pp.ramps[-1]
        fmt = lambda r: (f"{1e3 * r.low:.1f}" if r.low > 0 else "0") + " to " + (
            f"{1e3 * r.high:.1f}" if math.isfinite(r.high) else "(stood)")
        centre = lambda r: math.sqrt(r.low * r.high) if r.closed else (r.high if r.low <= 0 else r.low)
        predicted = []
        for m in shown:
            mp = post.models[m]
            rho = grid_log_ratio(mp.grid, ratios, obs.specimens[pp.specimen_id])
            predicted.append(f"{float(mp.weights @ np.exp(rho)):.3f}")
        rows.append((pp.specimen_id, str(len(own.test_ids) + len(other.test_ids)), fmt(own), fmt(other),
                     f"{centre(other) / centre(own):.3f}", *predicted))
    return ["## Pulses one way and the other", "",
            "Record tests of one pulse shape, ramped its own way and reversed, read as a pair (pulses.py): each way's "
            "bracket of the collapse in mm of the table's travel (from the records), and the ratio of the two ways' "
            "thresholds (the other way over its own; 1 for an arch that is its own mirror image, away from 1 with "
            "brackets on one side). Only the ratio enters the probabilities, with the two codes' disagreement on it "
            f"(RMS {100 * RATIO_SCALE:.0f} %, bench/lmgc90/pulse.py) as its scale. The models' columns: each one's "
            "posterior mean ratio.", "",
            _md_table(["specimen", "tests", "own way [mm]", "other way [mm]", "measured ratio",
                       *[f"{m}" for m in shown]], rows), ""]


def _common_friction(obs) -> float | None:
    values = {float(obs.specimens[p.specimen_id].friction) for p in obs.pairs}
    return values.pop() if len(values) == 1 else None


def _one_sided_text(obs) -> str:
    """What `one_sided` means for this campaign (likelihood.bracket_terms)."""
    if obs.stands_unreported:
        return (f"every row is a collapse: each pair's smallest collapse is read as the first collapse of a ramp "
                f"whose stands were not reported, of an unknown step ({_pct(float(ONE_SIDED_STEPS[0]))} to "
                f"{_pct(float(ONE_SIDED_STEPS[-1]))} of the collapse amplitude, log-uniform), so a threshold is "
                "known only to within that step below it; stand rows below each collapse would say how far")
    return ("some pairs have collapse rows only (their ramps fell at the first test, since the campaign reports "
            "stands elsewhere): their brackets are upper bounds, and a parameter they bound is bounded from one "
            "side only")


def _flag_lines(result: dict, obs) -> list[str]:
    if not result["flags"]:
        return ["Flags: none (no one-sided brackets, no parameter against its prior's edge, no sensor bias, "
                "the check passed).", ""]
    lines = ["Flags (what to know before trusting the numbers):", ""]
    for f in result["flags"]:
        if f.startswith("prior_bound:"):
            lines.append(f"- `{f}`: the posterior of {f.split(':', 1)[1]} lies against an edge of its prior: the "
                         "data do not bound it from that side, and its interval is the prior's as much as the "
                         "data's.")
        else:
            lines.append(f"- `{f}`: {_one_sided_text(obs) if f == 'one_sided' else FLAG_TEXT[f]}.")
    return lines + [""]


def _sensitivity_lines(info: dict) -> list[str]:
    sens = info.get("sensitivity")
    if not sens:
        return []
    base = sens[1.0]
    top = sorted(base, key=lambda m: -base[m])[:5]
    rows = [(f"`{m}`", *(f"{sens[f][m]:.3f}" for f in SENSITIVITY_FACTORS)) for m in top]
    return ["Prior sensitivity: the probabilities of the most probable models with every continuous "
            "parameter's prior range scaled about its nominal value (a wider range dilutes the prior over "
            "values the bank did not simulate, whose likelihood is taken as nil). Where they move much, the "
            "prior, not the data, decides.", "",
            _md_table(["model"] + [f"ranges x {f:g}" for f in SENSITIVITY_FACTORS], rows), ""]


def _emulator_lines(post: Posterior) -> list[str]:
    """The emulators' lack of fit, apart from the noise: RMS of the standardised
    leave-one-node-out residuals over every model's nodes, per pair."""
    rows = []
    for j, p in enumerate(post.pairs):
        z = np.concatenate([np.asarray(mp.grid.loo_z[j]) for mp in post.models.values()
                            if mp.grid.loo_z is not None and len(mp.grid.loo_z[j])])
        if z.size:
            rows.append((p.specimen_id, f"{p.frequency_hz:g}", f"{z.size}", f"{float(np.sqrt(np.mean(z * z))):.2f}",
                         f"{float(np.max(np.abs(z))):.1f}"))
    if not rows:
        return []
    return ["The emulators' lack of fit, measured apart (never taken for noise): each node predicted by the "
            "emulator without it, standardised by its predictive spread (about 1 when the emulator is as good "
            "as it says).", "", _md_table(["specimen", "f [Hz]", "nodes", "RMS z", "largest |z|"], rows), ""]


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
    text = notes(decision, post, result, info) + unread_text(obs)
    shown = decision.shown
    fmt = info["settings"].figure_format
    figs = [thresholds_figure(out, obs.pairs, info["baseline_pred"], shown,
                              post.probabilities[shown] if shown else float("nan"),
                              info["held"][shown][0] if shown else None, note, fmt),
            probabilities_figure(out, post.probabilities, note, fmt)]
    tfig = table_figure(out, campaign, info["table"], note, fmt)
    sc = post.scales
    lines = [f"# Diagnosis of campaign `{campaign.name}`", "", f"**Verdict: `{result['verdict']}`.** {text}", "",
             f"![probabilities]({figs[1]})", "", "## Thresholds", "",
             f"Mean absolute error of the nominal model: {result['baseline']['threshold_error_pct']:.1f} %. "
             + (f"Of `{decision.shown}`, fitted without the specimen it predicts: "
                f"{result['extended']['threshold_error_pct']:.1f} %." if decision.shown else ""), "",
             f"![thresholds]({figs[0]})", "",
             _md_table(["specimen", "f [Hz]", "last stand [mm]", "first collapse [mm]", "nominal [mm]"],
                       [(p.specimen_id, f"{p.frequency_hz:g}", "-" if p.low_m <= 0 else f"{1e3 * p.low_m:.1f}",
                         f"{1e3 * p.high_m:.1f}" if p.collapsed else "none (every test stood)", f"{1e3 * b:.1f}")
                        for p, b in zip(obs.pairs, info["baseline_pred"])]),
             "", "## Every model", "",
             "Prior and posterior probability, held-out error (fitted without the specimen it predicts, with "
             "its standard error over the pairs) and the posterior mean and 90 % credible interval of the "
             "parameters.", "", _md_table(["model", "prior", "posterior", "held-out error", "parameters"],
                                          _model_rows(post, info, result)),
             "", "## How the probabilities are made", "",
             "Each pair's rows bracket its threshold; the likelihood is the probability that the threshold lies "
             "in the bracket, under each model over a grid of its parameters"
             + (" (the campaign reports collapses only: each pair's bracket is that of a ramp whose stands went "
                "unreported, averaged over the ramp's unknown step; see the flag below)" if obs.stands_unreported
                else "") + ". Between the simulated nodes the "
             "threshold is emulated (a Gaussian process through the bank's nodes, whose nugget is the "
             "simulator's own spread and, where the nodes follow no smooth curve, their roughness), and the "
             "emulator's variance goes with it. The spreads: the simulator's "
             f"own ({_pct(float(np.min(sc.sigma_sim)))} to {_pct(float(np.max(sc.sigma_sim)))} by pair: the "
             "replicas of the bank's models at dt x 0.97 and x 1.03 and other scan steps), what the "
             f"specimens' build tolerance (ring thickness {_pct(obs.build_tolerance)}) moves each threshold by ("
             + (f"{_pct(float(np.min(sc.sigma_tol)))} to {_pct(float(np.max(sc.sigma_tol)))} by pair"
                if sc.sigma_tol.size else "none known")
             + f"), a discrepancy of each pair (integrated over {', '.join(_pct(t) for t in TAU_PAIR)}), the "
             f"test-to-test table gain scatter ({_pct(sc.sigma_gain)}"
             + {"records": ", measured by the records",
                "peak_accel": ", from the measured peak accelerations, at least 3 % (a noisy peak overstates)",
                "none": f", assumed {_pct(GAIN_SCATTER_DEFAULT)} without records"}[obs.gain_source]
             + "), a discrepancy shared by a specimen's pairs (its build and set-up; integrated over "
             f"{', '.join(_pct(t) for t in TAU_SPECIMEN)}, plus the change of its thresholds from dt to dt / 2: "
             + ", ".join(f"{sid} {_pct(v)}" for sid, v in sc.d_fine.items())
             + "), a discrepancy shared by the whole campaign (what two codes, or a code and a laboratory, differ "
             f"by; integrated over {', '.join(_pct(t) for t in TAU_CAMPAIGN)}) and an outlier mixture "
             f"(probability {OUTLIER_PROB:g}, within a factor {OUTLIER_FACTOR:g}). A ramp's first collapse "
             "may be an early one (rocking is not monotone in amplitude: a finer ramp can fall in a window "
             f"below the threshold a search finds), anywhere up to {_pct(-math.expm1(-EARLY_SPAN))} below it: "
             + _early_text(obs, sc) + " "
             + ("Each test's measured gain (records, or measured over commanded peak acceleration) is weighed "
                "too: 1 if the table followed the command, read through a transducer whose calibration may be "
                f"off by a common factor (standard deviation {_pct(sc.gain_bias_sd)}, "
                + ("table.csv" if campaign.table.from_file else "the default without table.csv")
                + "), or the pair's own gain under `table_motion`."
                if obs.gain_source != "none" else ""), "",
             prior_text(info["settings"], _common_friction(obs)), "",
             f"Check of `{decision.top}`: p = {decision.p_value:.3f} "
             f"({'adequate' if decision.adequate else 'not adequate'}; the threshold is {ADEQUATE_P}). Each "
             "specimen's brackets are predicted by the model fitted without that specimen; the probability "
             "integral transform of each measured threshold under that prediction is uniform when the model is "
             "right, and the largest |Phi^-1(PIT)| over the pairs is compared with its null distribution "
             "(Sidak's, exact for independent pairs, conservative for dependent ones). No outlier process "
             "enters the check.", "",
             ] + _flag_lines(result, obs) + _sensitivity_lines(info) + _emulator_lines(post) + [
             METHOD_CHECK, ""]
    lines += _crown_lines(info.get("crown_evidence"), post)
    lines += _pulse_lines(obs, post)
    lines += _next_test_lines(info.get("next_test"))
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
    lines += ["", "## Hinges and crown motion of the reported model (reported, not in the probabilities)", ""]
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
                            [(p.specimen_id, f"{p.frequency_hz:g}",
                              f"{1e3 * p.threshold_m:.1f}" if p.collapsed else f"> {1e3 * p.low_m:.1f}",
                              f"{1e3 * t:.1f}",
                              f"{100 * (t - p.threshold_m) / p.threshold_m:+.1f} %" if p.collapsed else "-")
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
              f"{info['elapsed_s']:.0f} s. The machine-readable result is `diagnosis.json` (contract version 4).", ""]
    (out / "report.md").write_text("\n".join(lines))
    return text

