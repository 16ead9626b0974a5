"""Diagnosis of a measured campaign: what the simulation gets wrong, why, and how sure.

The stages, each handing its result to the next (docs/diagnosis.md explains them):

1. observations.py: the campaign's brackets and the table's measured gains;
2. bank.py: the simulated thresholds of every model, independent of the data, cached;
3. models.py, likelihood.py: each model's predictions over its parameter prior and the
   likelihood of the brackets, with the simulator's own spread and a specimen
   discrepancy;
4. posterior.py: the models' posterior probabilities, their parameters, the check of the
   most probable model, the prior sensitivity and the held-out errors; next_test.py the
   next test;
5. decision.py: the verdict of docs/measured_data.md version 4 and its flags;
6. report.py: report.md, its figures and diagnosis.json; samples.py: the posterior as
   model samples of each arch (posterior_samples_<specimen>.csv), for the fragility.

With DiagnosisSettings.crown_records (off by default), the crown records of tests held
below the threshold enter the probabilities (crown.py: each model's draws simulated at the
same fraction of their own thresholds). Hinges and the crown comparison of the report's
single runs (the nominal model and the reported one) do not.
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..readers.campaign import read_campaign
from .bank import Bank, build_bank
from .crown import crown_log_factors, crown_tests, with_crown
from .decision import Decision, decide, flags, to_separate
from .effects import BRACKET_GAPS_M, Variant, restraint_parts, restraint_value
from .models import CANDIDATES, MODEL_IDS, members, model_prior
from .observations import Observations, from_campaign
from .next_test import draw_indices, next_test
from .early import add_early_scans
from .pulses import add_pulse_banks, unit_pulse
from .posterior import (SENSITIVITY_FACTORS, Posterior, held_out, infer, prior_sensitivity, relative_errors,
                        weighted_summary)
from .report import unread_text, write_report
from .samples import write_samples
from .screen import specimen_screen
from .settings import DiagnosisSettings
from .simulator import Simulator
from .single_runs import crown_comparison, hinge_matches

__all__ = ["DiagnosisSettings", "diagnose", "infer_campaign", "parameters", "model_run", "CONTRACT_VERSION"]

CONTRACT_VERSION = 4
#: The pulse of a pulse_pair advice, of unit travel (table_x_m from -0.5 to +0.5 m): the
#: laboratory plays it scaled by each amplitude of the ramp, and reversed.
PULSE_RECORD = "next_test_pulse.csv"


def parameters(post: Posterior, model_id: str | None, obs: Observations) -> dict:
    """The `parameters` object of diagnosis.json for a model (empty for none)."""
    if model_id is None or model_id == "none":
        return {}
    mp = post.models[model_id]
    out = {}
    names = {"contact_edges": ("inset_m", "m"), "friction": ("friction", ""), "geometry": ("thickness_factor", "")}
    for e in mp.grid.names:
        value, low, high = mp.summary(e)
        if e == "base_restraint":
            side, _ = restraint_parts(value)
            sides = ["left", "right"] if side == "both" else [side]
            out["restrained_springings"] = {"value": sides, "low": sides, "high": sides, "unit": ""}
            # The play of the brackets on that side: its posterior mean and 5-95 % range.
            v = mp.grid.values[mp.grid.names.index(e)]
            on = np.array([restraint_parts(x)[0] == side for x in v])
            gaps = np.array([restraint_parts(x)[1] for x in v[on]])
            mean, low, high = weighted_summary(gaps, mp.weights[on] / mp.weights[on].sum())
            out["bracket_gap_m"] = {"value": mean, "low": low, "high": high, "unit": "m"}
        elif e == "table_motion":
            out["accel_gain"] = {"value": value, "low": low, "high": high, "unit": ""}
        else:
            name, unit = names[e]
            out[name] = {"value": value, "low": low, "high": high, "unit": unit}
    if "table_motion" in members(model_id) and mp.grid.gain_per_pair:
        # The campaign's mean gain over its pairs, with the 90 % interval of that mean: the
        # tests' scatter over their number and the transducer's calibration, which no
        # number of tests removes (each pair's own gain is in the report).
        g = post.scales.gain_mean
        n_tests = max(1, sum(len(p.gains) for p in post.pairs))
        se = math.sqrt(post.scales.sigma_gain ** 2 / n_tests + post.scales.gain_bias_sd ** 2) * float(np.mean(g))
        out["accel_gain"] = {"value": float(np.mean(g)), "low": float(np.mean(g) - 1.645 * se),
                             "high": float(np.mean(g) + 1.645 * se), "unit": ""}
        if obs.gain_source == "records":  # peak accelerations say nothing of a delay
            se_d = obs.delay_se_s if math.isfinite(obs.delay_se_s) else 0.0
            out["delay_s"] = {"value": obs.delay_s, "low": obs.delay_s - 1.645 * se_d,
                              "high": obs.delay_s + 1.645 * se_d, "unit": "s"}
    return out


def model_run(model_id: str | None, params: dict, obs: Observations) -> tuple[Variant, dict]:
    """The (variant, extra &motion settings) of a model at its reported parameters, for
    single runs."""
    parts, motion = [], {}
    for e in members(model_id or "none"):
        if e == "contact_edges":
            parts.append((e, params["inset_m"]["value"]))
        elif e == "friction":
            parts.append((e, params["friction"]["value"]))
        elif e == "geometry":
            parts.append((e, params["thickness_factor"]["value"]))
        elif e == "base_restraint":
            sides = params["restrained_springings"]["value"]
            gap = params.get("bracket_gap_m", {"value": 0.0})["value"]
            # The simulated play nearest the reported one (single runs use the bank's nodes).
            gap = min(BRACKET_GAPS_M, key=lambda g: abs(g - gap))
            parts.append((e, restraint_value("both" if len(sides) == 2 else sides[0], gap)))
        elif e == "table_motion":
            motion = {"table_gain": params["accel_gain"]["value"],
                      "table_delay_s": max(0.0, params.get("delay_s", {"value": 0.0})["value"])}
    return Variant.of(parts), motion


def infer_campaign(bank: Bank, obs: Observations) -> tuple[Posterior, Decision]:
    """Stages 4 and 5 on stored inputs: what the replay tests and the calibration run."""
    post = infer(bank, obs)
    return post, decide(post)


def diagnose(campaign_dir: str | os.PathLike, out_dir: str | os.PathLike, settings: DiagnosisSettings) -> dict:
    """Run the whole diagnosis; write report.md, its figures and diagnosis.json into
    `out_dir`; return the JSON object."""
    t0 = time.time()
    log = settings.log
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    campaign = read_campaign(campaign_dir)
    obs, table = from_campaign(campaign)
    obs.build_tolerance = settings.build_tolerance
    if not any(p.collapsed for p in obs.pairs + obs.apart):
        raise InputError(f"{campaign.path}: no (specimen, frequency) pair has a collapse: no threshold to compare")
    if not any(p.collapsed for p in obs.pairs):
        raise InputError(f"{campaign.path}: every specimen with a collapse has setup_certain = 0: "
                         "nothing can fit or judge a cause")
    stood = sum(not p.collapsed for p in obs.pairs)
    log(f"[diagnose] {campaign.name}: {len(campaign.specimens)} specimens, {len(campaign.tests)} tests, "
        f"{len(obs.pairs) - stood} pairs with a collapse and a certain set-up"
        + (f" and {stood} whose tests all stood (lower bounds)" if stood else "")
        + f" ({len(obs.apart)} apart); table evidence: {obs.gain_source}")
    if obs.unread:
        log(f"[diagnose]{unread_text(obs)}")
    cache = Path(settings.bank_dir) if settings.bank_dir else out_dir.resolve().parent / "voussoir-bank"
    bank = build_bank(obs.specimens, {sid: obs.frequencies(sid) for sid in obs.specimens}, obs.cycles, settings,
                      cache, out_dir / "work")
    log(f"[diagnose] simulation bank: {bank.searches} threshold searches made, {bank.reused} specimens cached "
        f"({cache})")
    add_early_scans(bank, obs, settings, cache / "scans", out_dir / "work" / "scans")
    if obs.pulse_pairs:
        n = add_pulse_banks(bank, obs, settings, cache / "pulses", out_dir / "work" / "pulses")
        log(f"[diagnose] {len(obs.pulse_pairs)} pulse pairs (record tests one way and the other): {n} models' "
            "thresholds both ways, simulated or read from the cache; their ratio enters the probabilities")
    post = infer(bank, obs)
    crown_available = crown_tests(campaign, obs.pairs)
    crown_tests_ = crown_available if settings.crown_records else []
    if crown_tests_:
        log(f"[diagnose] crown records of {len(crown_tests_)} tests held below their threshold: each model's "
            "draws simulated at the same fractions of their own thresholds")
        crown_sim = Simulator(settings, out_dir / "work" / "crown")
        factors = crown_log_factors(post, obs, crown_tests_, crown_sim, draw_indices, cache / "crown-runs")
        post = with_crown(post, factors)
        log(f"[diagnose] crown records weighed: {crown_sim.n_runs} single runs made now (the rest from "
            f"{cache / 'crown-runs'})")
    decision = decide(post)
    log("[diagnose] most probable: " + ", ".join(f"{m} {post.probabilities[m]:.3f}" for m in post.ranked()[:4]))
    samples = write_samples(out_dir, post, obs, settings.posterior_samples, campaign.name)
    held = {m: held_out(bank, obs, m) for m in MODEL_IDS}
    baseline_pred = np.array([bank.specimens[p.specimen_id].threshold("nominal", p.frequency_hz) for p in obs.pairs])
    # Over the pairs with a collapse (diagnose refuses a campaign without one).
    baseline_error = float(np.mean(relative_errors(baseline_pred, obs.pairs)))
    shown = decision.shown
    shown_params = parameters(post, shown, obs)
    flag_list = flags(post, decision, shown)
    sensitivity = {f: prior_sensitivity(post, f) for f in SENSITIVITY_FACTORS}
    rivals = decision.rivals
    asked = to_separate(decision)
    suggestion = None
    if len(asked) > 1:
        log(f"[diagnose] looking for the test that separates {', '.join(asked)} (tested and new frequencies)")
        # The next test's simulations beside the bank: a rerun reuses them.
        suggestion = next_test(post, obs, asked, settings, cache / "next-test", campaign.table, crown_tests_,
                               settings.crown_records)
    sim = Simulator(settings, out_dir / "work")
    runs = {"nominal": (Variant(), {})}
    if shown:
        runs[shown] = model_run(shown, shown_params, obs)
    log("[diagnose] hinges and crown records of the nominal model" + (f" and of {shown}" if shown else ""))
    hinge = hinge_matches(campaign, sim, runs)
    crown = crown_comparison(campaign, sim, runs)
    screen = specimen_screen(bank, obs, decision)
    _, ext_error, ext_se = held[shown] if shown else (None, baseline_error, math.nan)
    result = {
        "campaign": campaign.name,
        "contract_version": CONTRACT_VERSION,
        "verdict": decision.verdict,
        "effects": decision.effects,
        "rivals": rivals,
        "probabilities": {m: round(p, 6) for m, p in post.probabilities.items()},
        "adequate": decision.adequate,
        "parameters": shown_params,
        "baseline": {"threshold_error_pct": 100 * baseline_error, "hinge_match": hinge["nominal"]},
        "extended": {"threshold_error_pct": 100 * ext_error,
                     "threshold_error_se_pct": None if not math.isfinite(ext_se) else 100 * ext_se,
                     "hinge_match": hinge[shown] if shown else hinge["nominal"]},
        "candidates": [candidate_entry(m, post, held[m], obs) for m in CANDIDATES],
        "next_test": None if suggestion is None else {
            "specimen_id": suggestion["specimen_id"], "frequency_hz": suggestion["frequency_hz"],
            "kind": suggestion["kind"], "amplitudes_m": suggestion["amplitudes_m"],
            "expected_gain_bits": suggestion["expected_gain_bits"], "predictions": suggestion["predicted_m"],
            "gain_spread_bits": suggestion["gain_spread_bits"], "gain_se_bits": suggestion["gain_se_bits"],
            **({"predicted_crown_m": suggestion["predicted_crown_m"]} if "predicted_crown_m" in suggestion else {}),
            **({"predicted_ratio": suggestion["predicted_ratio"], "record": PULSE_RECORD}
               if suggestion["kind"] == "pulse_pair" else {}),
            "alternatives": [{("predictions" if k == "predicted_m" else k): v for k, v in a.items() if k != "new"}
                             for a in suggestion["alternatives"]]},
        "flags": flag_list,
        "adequacy_p_value": decision.p_value,
        "notes": "",
    }
    info = {"elapsed_s": time.time() - t0, "bank": bank, "settings": settings, "table": table, "crown": crown, "screen": screen,
            "crown_evidence": (crown_available, post.crown, settings.crown_records),
            "held": held, "baseline_pred": baseline_pred, "samples": samples, "next_test": suggestion, "runs": sim.n_runs,
            "prior": {m: model_prior(m) for m in MODEL_IDS}, "sensitivity": sensitivity}
    if suggestion is not None and "pulse_pair" in [suggestion["kind"]] + [a["kind"] for a in suggestion["alternatives"]]:
        t, x, _ = unit_pulse()
        (out_dir / PULSE_RECORD).write_text("t_s,table_x_m\n" + "".join(f"{a:.4f},{b:.7f}\n" for a, b in zip(t, x)))
    result["notes"] = write_report(out_dir, campaign, obs, post, decision, result, info)
    (out_dir / "diagnosis.json").write_text(json.dumps(result, indent=2) + "\n")
    log(f"[diagnose] verdict: {decision.verdict} ({info['elapsed_s']:.0f} s, {bank.searches} threshold searches, "
        f"{sim.n_runs} single runs)")
    return result


def candidate_entry(model_id: str, post: Posterior, held: tuple, obs: Observations) -> dict:
    """One entry of diagnosis.json's `candidates`: its model id (a pair's ids joined by
    `+`), with its `effects`."""
    entry = {"effect": model_id, "effects": list(members(model_id))}
    entry.update({"cv_error_pct": 100 * held[1], "probability": post.probabilities[model_id],
                  "parameters": parameters(post, model_id, obs)})
    return entry
