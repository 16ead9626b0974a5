"""Diagnosis of a measured campaign: what the simulation gets wrong, and why.

The method (docs/diagnosis.md explains it with its reasons):

1. Measured thresholds and brackets of every (specimen, frequency) pair, as
   shared/MEASURED_DATA.md defines them, and the measurement resolution: the relative
   half-width of the brackets (the amplitude steps), plus the tolerance of the
   simulated threshold search.
2. Direct evidence of the table (actuator.py): the records fitted as
   gain x command(t - delay), or the measured peak accelerations.
3. Simulated thresholds of the nominal model and of each candidate effect over a grid
   of its parameter (effects.py, one class per effect), with the MPI sweep driver
   (simulator.py, through the one runner).
4. Each candidate's parameter fitted by leave-one-specimen-out cross-validation
   (selection.py): the error that counts is the error on the specimens held out.
5. The decision (decision.py), and the report (diagnosis_report.py).

This module ties them together: `diagnose` runs the whole and writes report.md,
its figures and diagnosis.json.
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..readers.campaign import Campaign, MeasuredThreshold, Specimen, measured_thresholds, read_campaign
from .actuator import TableEvidence, afd_command, fit_actuator, table_evidence
from .combined import all_pairs, screen_pairs
from .decision import Decision, decide, hinge_match, hinge_score
from .effects import EFFECTS, Variant, effect
from .nested import admissibility, mean_relative_error, nested_held_out
from .selection import CandidateResult, PairData, evaluate_candidate, held_out_loss, mean_error
from .settings import DiagnosisSettings
from .setup_screen import specimen_restraints
from .simulator import Simulator

__all__ = ["DiagnosisSettings", "diagnose", "fit_actuator", "afd_command", "EFFECTS", "CandidateResult",
           "PairData", "TableEvidence", "Decision", "decide", "Variant", "variants", "parameters"]


def variants(spec: Specimen, settings: DiagnosisSettings) -> list[Variant]:
    """Every model simulated for one specimen: the nominal one and each effect's grid."""
    return [Variant()] + [v for e in EFFECTS for v in effect(e).simulated(spec, settings)]


def parameters(c: CandidateResult | None, table: TableEvidence) -> dict:
    """The `parameters` object of diagnosis.json for a candidate (empty for none)."""
    return {} if c is None else c.eff.parameters(c, table)


def candidate_entry(c: CandidateResult, table: TableEvidence) -> dict:
    """One entry of diagnosis.json's `candidates`; a pair is `combined` with its `effects`."""
    entry = {"effect": c.effect if len(c.members) == 1 else "combined"}
    if len(c.members) > 1:
        entry["effects"] = list(c.members)
    entry.update({"cv_error_pct": 100 * c.cv_error, "parameters": parameters(c, table)})
    return entry


def _store(ps: list[PairData], thr: dict) -> None:
    """File simulated thresholds {(variant, frequency): m} with their pairs."""
    for p in ps:
        for (v, f), t in thr.items():
            if abs(f - p.measured.frequency_hz) < 1e-9:
                p.simulated[v] = t


def simulate_pairs(pairs: list[PairData], groups: dict, singles: dict, sim: Simulator, settings: DiagnosisSettings,
                   table: TableEvidence) -> dict:
    """The pairs of effects worth simulating (combined.py: screened by the additive rule),
    simulated about their fits and judged with the simulated correction. Two rounds at
    most: a refit that leaves the simulated grid is simulated again."""
    out = {}
    combos = all_pairs(singles, settings, table)
    for (sid, cycles), ps in groups.items():
        variants = [v for ce in combos
                    for v in ce.calibration(ps[0].spec, tuple(singles[m].value for m in ce.member_ids))]
        if variants:
            settings.log(f"[diagnose] simulating {len(variants)} pairs of effects on {sid}, each at its fits alone")
            _store(ps, sim.thresholds(ps[0].spec, [p.measured for p in ps], cycles, variants))
    for ce, screened in screen_pairs(pairs, singles, combos, settings, table):
        c = screened
        for _ in range(2):
            fits = [c.value] + list(c.fold_values)
            needed = 0
            for (sid, cycles), ps in groups.items():
                variants = [v for v in ce.variants_to_simulate(ps[0].spec, fits) if v not in ps[0].simulated]
                if not variants:
                    continue
                needed += len(variants)
                settings.log(f"[diagnose] simulating {ce.id} on {sid}: {len(variants)} combinations")
                _store(ps, sim.thresholds(ps[0].spec, [p.measured for p in ps], cycles, variants))
            if not needed:
                break
            c = evaluate_candidate(pairs, ce, settings, table)
        settings.log(f"[diagnose] pair {ce.id}: screened held-out {100 * screened.cv_error:.1f} %, "
                     f"simulated {100 * c.cv_error:.1f} %")
        out[ce.id] = c
    return out


def _cycles(campaign: Campaign, m: MeasuredThreshold) -> tuple[int, int, int]:
    t = campaign.tests[m.test_ids[0]]
    return (t.n_attack, t.n_full, t.n_decay)


def diagnose(campaign_dir: str | os.PathLike, out_dir: str | os.PathLike, settings: DiagnosisSettings) -> dict:
    """Run the whole diagnosis; write report.md, its figures and diagnosis.json into
    `out_dir`; return the JSON object."""
    t0 = time.time()
    log = settings.log
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    campaign = read_campaign(campaign_dir)
    measured = [m for m in measured_thresholds(campaign) if m.has_collapse]
    if not measured:
        raise InputError(f"{campaign.path}: no (specimen, frequency) pair has a collapse: no threshold to compare")
    all_pairs = []
    for m in measured:
        res = (m.high_m - m.low_m) / 2.0 / m.threshold_m if math.isfinite(m.low_m) else settings.default_resolution
        all_pairs.append(PairData(m, campaign.specimens[m.specimen_id], res,
                                  math.hypot(res + settings.amp_tol_fraction, settings.model_floor)))
    # Specimens whose set-up is not known are simulated and reported apart: they neither
    # fit a parameter nor count in the errors that decide (shared/MEASURED_DATA.md).
    pairs = [p for p in all_pairs if p.spec.setup_certain]
    apart = [p for p in all_pairs if not p.spec.setup_certain]
    if not pairs:
        raise InputError(f"{campaign.path}: every specimen with a collapse has setup_certain = 0: "
                         "nothing can fit or judge a cause")
    resolution = float(np.mean([p.resolution for p in pairs])) + settings.amp_tol_fraction
    table = table_evidence(campaign)
    if table.source == "records":
        gains = {tid: g for tid, g, _, _ in table.per_test}
        for p in all_pairs:
            own = [gains[t] for t in p.measured.test_ids if t in gains]
            if own:
                p.gain_shape = float(np.mean(own)) / table.gain
    log(f"[diagnose] {campaign.name}: {len(campaign.specimens)} specimens, {len(campaign.tests)} tests, "
        f"{len(pairs)} pairs with a collapse and a certain set-up ({len(apart)} apart); resolution {100 * resolution:.1f} %; table evidence: {table.source}"
        + (f" gain {table.gain:.3f}" if table.source != "none" else ""))

    sim = Simulator(settings, out_dir / "work")
    groups: dict[tuple[str, tuple[int, int, int]], list[PairData]] = {}
    for p in all_pairs:
        groups.setdefault((p.spec.specimen_id, _cycles(campaign, p.measured)), []).append(p)
    for (sid, cycles), ps in groups.items():
        log(f"[diagnose] simulating thresholds of {sid} ({len(ps)} frequencies, {len(variants(ps[0].spec, settings))} models)")
        _store(ps, sim.thresholds(ps[0].spec, [p.measured for p in ps], cycles, variants(ps[0].spec, settings)))

    baseline_error = mean_error(pairs, None, None)
    cands = {e: evaluate_candidate(pairs, effect(e), settings, table) for e in EFFECTS}
    admissibility(cands, table)
    cands.update(simulate_pairs(pairs, groups, cands, sim, settings, table))

    # Hinges: every test with observed hinges, simulated with the nominal model and with
    # each candidate's fitted model.
    hinge_tests = [campaign.tests[tid] for tid, h in campaign.hinges.items()
                   if h and campaign.tests[tid].waveform == "afd" and campaign.tests[tid].amplitude_m is not None]
    observed = {t.test_id: {(h.joint, h.side) for h in campaign.hinges[t.test_id]} for t in hinge_tests}
    baseline_hinges = None
    if hinge_tests:
        log(f"[diagnose] simulating {len(hinge_tests)} tests with observed hinges, {1 + len(cands)} models")
        models = [(None, Variant(), {})] + [(e, *c.eff.model(c.value, table)) for e, c in cands.items()]
        for name, variant, motion in models:
            runs = sim.run_tests([(campaign.specimens[t.specimen_id], t, variant, motion) for t in hinge_tests])
            simulated = {t.test_id: r["hinges"] for t, r in zip(hinge_tests, runs)}
            if name is None:
                baseline_hinges = hinge_match(observed, simulated)
            else:
                cands[name].hinge_match = hinge_match(observed, simulated)
                cands[name].hinge_score = hinge_score(observed, simulated)

    decision = decide(pairs, resolution, cands, table)
    chosen = decision.chosen
    suggestion = None
    if decision.verdict == "inconclusive" and len(decision.rival_results) > 1:
        log(f"[diagnose] looking for the test that separates {', '.join(c.effect for c in decision.rival_results)}")
        suggestion = separating_test(pairs, decision.rival_results, sim, campaign, settings, table)
        decision.notes += " " + suggestion["sentence"]
    # The extended model: the named cause, or for `inconclusive` the best rival; its error
    # by nested cross-validation (nested.py), never on the data that chose it.
    shown = chosen or decision.best_rival
    log("[diagnose] nested cross-validation of the whole choice")
    nested, fold_verdicts = nested_held_out(pairs, [c.eff for c in cands.values()], settings, table)
    extended_error = mean_relative_error(nested, pairs) if shown else baseline_error
    extended_hinges = shown.hinge_match if shown else baseline_hinges
    notes = decision.notes or notes_named(chosen, baseline_error, resolution, cands, table, pairs,
                                          decision.separation)
    if shown:
        notes += (f" Measured by nested cross-validation (the choice itself redone without each specimen), the "
                  f"extended model's error on the specimens held out is {100 * extended_error:.1f} %"
                  + (f" (the folds chose {', '.join(fold_verdicts)})." if fold_verdicts else "."))
    uncertain = uncertain_specimens(apart, chosen, settings)
    if uncertain:
        notes += " " + " ".join(u["sentence"] for u in uncertain)
    restrained_alone = specimen_restraints(pairs, shown, settings, table)
    if restrained_alone:
        notes += " " + " ".join(r["sentence"] for r in restrained_alone)
    crown = crown_comparison(campaign, sim, [("nominal", Variant(), {})]
                             + ([(chosen.effect, *chosen.eff.model(chosen.value, table))] if chosen else []))
    elapsed = time.time() - t0
    result = {
        "campaign": campaign.name,
        "verdict": decision.verdict,
        "effects": list(chosen.members) if chosen else [],
        "rivals": list(decision.rivals),
        "parameters": parameters(chosen, table),
        "baseline": {"threshold_error_pct": 100 * baseline_error, "hinge_match": baseline_hinges},
        "extended": {"threshold_error_pct": 100 * extended_error, "hinge_match": extended_hinges},
        "candidates": [candidate_entry(c, table) for c in cands.values()],
        "notes": notes,
    }
    (out_dir / "diagnosis.json").write_text(json.dumps(result, indent=2) + "\n")
    from .report import write_report
    write_report(out_dir, campaign, pairs, cands, decision, table, baseline_error, resolution, result,
                 {"elapsed_s": elapsed, "sweeps": sim.n_sweeps, "runs": sim.n_runs, "settings": settings,
                  "code_version": sim.code_version,
                  "crown": crown, "uncertain": uncertain, "next_test": suggestion, "restrained_alone": restrained_alone,
                  "nested": nested, "fold_verdicts": fold_verdicts})
    log(f"[diagnose] verdict: {decision.verdict} ({elapsed:.0f} s, {sim.n_sweeps} sweeps, {sim.n_runs} single runs)")
    return result


def crown_comparison(campaign: Campaign, sim: Simulator, models: list, max_tests: int = 24) -> dict:
    """Measured crown motion against the simulated one, per model, on the tests that
    stood and whose records have crown_dx_m (at most `max_tests`, the largest amplitudes
    first: near the threshold the arch rocks most). The compared feature is the peak
    horizontal crown displacement relative to the table, floored at 0.5 mm (the noise of
    a displacement sensor): a peak is robust where a time series near collapse is
    chaotic. Returns, per model, the mean of |log(simulated peak / measured peak)| and
    the per-test values."""
    floor_m = 5e-4
    tests = [campaign.tests[tid] for tid, r in campaign.records.items()
             if r.crown_dx_m is not None and campaign.tests[tid].waveform == "afd"
             and campaign.tests[tid].amplitude_m is not None and not campaign.tests[tid].collapsed]
    if not tests:
        return {}
    tests.sort(key=lambda t: -t.amplitude_m)
    tests = tests[:max_tests]
    out = {"tests": [t.test_id for t in tests], "models": {}}
    for name, variant, motion in models:
        runs = sim.run_tests([(campaign.specimens[t.specimen_id], t, variant, motion) for t in tests])
        errors = []
        for t, r in zip(tests, runs):
            measured = max(floor_m, float(np.abs(campaign.records[t.test_id].crown_dx_m).max()))
            simulated = max(floor_m, float(np.abs(r["crown_dx_m"]).max())) if not r["collapsed"] else 1.0
            errors.append(abs(math.log(simulated / measured)))
        out["models"][name] = {"mean": float(np.mean(errors)), "per_test": errors}
    return out


def notes_named(c: CandidateResult, baseline_error: float, resolution: float, cands: dict, table: TableEvidence,
                pairs: list[PairData], separation: str = "") -> str:
    """The plain-words paragraph of a named cause. The others are ranked as the decision
    ranks them (held-out likelihood), so a smaller mean error of a weaker rival is said
    as it is; `separation` is what told the cause from rivals that the thresholds did not
    (Decision.separation), said instead of a strong evidence it did not have."""
    pct = lambda x: f"{100 * x:.1f} %"
    what = c.eff.sentence(c, table)
    others = sorted((x for e, x in cands.items() if e != c.effect), key=lambda x: held_out_loss(x, pairs))
    listed = ", ".join(f"{x.effect} {pct(x.cv_error)}" + ("" if x.admissible else f" (excluded: {x.reason})")
                       for x in others)
    return (f"The nominal model misses the measured collapse thresholds by {pct(baseline_error)} on average "
            f"(resolution {pct(resolution)}). The data are best explained if {what}: with that one change, "
            f"fitted without the specimen it predicts, the error falls to {pct(c.cv_error)}. "
            + (f"{separation} Mean held-out errors of all the other causes: {listed}." if separation else
               f"The other causes explain the held-out thresholds less well by strong evidence (likelihood of "
               f"the held-out predictions; their mean held-out errors: {listed})."))


def separating_test(pairs: list[PairData], rivals: list[CandidateResult], sim: Simulator, campaign: Campaign,
                    settings: DiagnosisSettings, table: TableEvidence) -> dict:
    """The test (a specimen with a certain set-up, at a frequency it was tested at or a new
    one) whose thresholds predicted by the rivals, each at its fitted value, differ most
    relative to the smallest: what the laboratory should run next. New frequencies are
    simulated here with each rival's model."""
    options = []  # (spread, specimen, frequency, {effect: threshold_m}, new)
    for p in pairs:
        preds = {c.effect: c.eff.predict(p, c.value) for c in rivals}
        options.append((p.spec, p.measured.frequency_hz, preds, False))
    by_specimen: dict[str, list[PairData]] = {}
    for p in pairs:
        by_specimen.setdefault(p.spec.specimen_id, []).append(p)
    for sid, ps in by_specimen.items():
        spec = ps[0].spec
        tested = {p.measured.frequency_hz for p in ps}
        new = [f for f in settings.probe_frequencies_hz if min(abs(f - t) for t in tested) > 0.05]
        if not new:
            continue
        # Constant peak acceleration sets the scale of the amplitudes at other frequencies.
        accel = max(p.measured.threshold_accel_m_s2 for p in ps)
        amp_max = max(4.0 * accel / (2 * math.pi * f) ** 2 for f in new)
        amp_tol = max(1e-5, settings.amp_tol_fraction * min(0.25 * accel / (2 * math.pi * f) ** 2 for f in new))
        models = {c.effect: c.eff.model(c.value, table) for c in rivals}
        variants_needed = [Variant()] + [v for v, motion in models.values() if v != Variant()]
        thr = sim.thresholds_at(spec, new, _cycles(campaign, ps[0].measured), variants_needed, amp_max, amp_tol)
        for f in new:
            preds = {}
            for c in rivals:
                variant, motion = models[c.effect]
                base = thr.get((variant, min(new, key=lambda x: abs(x - f))), math.nan)
                preds[c.effect] = base / motion.get("table_gain", 1.0)
            options.append((spec, f, preds, True))
    def spread(preds):
        vals = [v for v in preds.values() if math.isfinite(v)]
        return (max(vals) - min(vals)) / min(vals) if len(vals) > 1 else -1.0
    spec, f, preds, new = max(options, key=lambda o: spread(o[2]))
    listed = ", ".join(f"{e} {1e3 * v:.1f} mm" for e, v in preds.items())
    sentence = (f"The test that would best separate them: specimen {spec.specimen_id} at {f:g} Hz"
                + (" (a frequency not tested yet)" if new else "")
                + f", where the rivals predict collapse thresholds of {listed} "
                  f"({100 * spread(preds):.0f} % apart).")
    return {"specimen": spec.specimen_id, "frequency_hz": f, "new_frequency": new,
            "predicted_threshold_m": preds, "spread": spread(preds), "sentence": sentence}


def uncertain_specimens(apart: list[PairData], chosen: CandidateResult | None, settings: DiagnosisSettings
                        ) -> list[dict]:
    """How far off each pair of a specimen with an uncertain set-up is, under the nominal
    model and the named cause, and which single effect value would reproduce it alone."""
    out = []
    for p in apart:
        meas = p.measured.threshold_m
        nominal = p.simulated.get(Variant(), math.nan)
        extended = chosen.eff.predict(p, chosen.value) if chosen else math.nan
        explain = []
        for e in EFFECTS:
            eff = effect(e)
            best = min(eff.candidate_values([p], settings), key=lambda v: abs(eff.predict(p, v) - meas)
                       if math.isfinite(eff.predict(p, v)) else math.inf)
            err = (eff.predict(p, best) - meas) / meas
            if math.isfinite(err) and abs(err) <= 0.05:
                explain.append(eff.label(best))
        pct = lambda x: "n/a" if not math.isfinite(x) else f"{100 * x:+.0f} %"
        sentence = (f"{p.spec.specimen_id} at {p.measured.frequency_hz:g} Hz (set-up not certain, not used): the "
                    f"nominal model is {pct((nominal - meas) / meas)} off"
                    + (f", the named cause {pct((extended - meas) / meas)}" if chosen else "")
                    + ("; it would be reproduced alone by " + " or ".join(explain) if explain
                       else "; no single effect of the catalogue reproduces it") + ".")
        out.append({"specimen": p.spec.specimen_id, "frequency_hz": p.measured.frequency_hz, "measured_m": meas,
                    "nominal_m": nominal, "extended_m": extended, "explained_by": explain, "sentence": sentence})
    return out
