"""The diagnosis on campaigns made by another code, with the faults real laboratories have.

The truths are LMGC90's (lmgc90_campaigns.py; made by bench/lmgc90/truths.sh and stored
in data/lmgc90): drawn from the diagnosis's own prior, values off every grid, pairs of
effects and truths outside the catalogue, each specimen built a little off. Each is
replayed as DRAWS laboratory campaigns (ramps of 1 to 5 mm, a transducer off by up to
2 %, a campaign-wide offset, some campaigns with collapse rows only) and diagnosed on the
stored simulation bank of the test arches (data/replay/bank, Voussoir's).

What is asserted (`judge`) must fail when the method ignores the data or its bank is off:
power (the mean of log P(truth) - log prior(truth), an information gain in nats, above
POWER_MARGIN), the nominal truths recognised (mean P(none) at least NOMINAL_P_NONE),
causes named at 0.9 wrong no more often than their stated probabilities allow (by truth,
p >= 0.01), truths outside the catalogue never named, the truth in the 90 % set at least 70 % of the time, the truth's parameter inside
its 90 % interval at least 70 % of the time, and the posterior CDFs at the true values
centred on 1/2 (a simulation-based calibration). These are floors against blindness and
bias; the goals of issue 33 (0.9, 0.85, ...) are measured by
bench/diagnosis_calibration.sh and reported in docs/diagnosis.md. The mutation tests run
the same judgement on a posterior equal to the prior and on banks whose thresholds are
all 5 % high or low, and require it to fail.
"""

from __future__ import annotations

import dataclasses
import math
from functools import lru_cache

import numpy as np
import pytest

from voussoir_post.diagnosis import posterior as posterior_module
from voussoir_post.diagnosis.bank import Bank
from voussoir_post.diagnosis.observations import Observations
from voussoir_post.diagnosis.rates import outcome, power

from conftest import VERDICTS
from lmgc90_campaigns import LabFaults, draw_campaign, stored_truths, truth_model, truth_values
from test_diagnosis import stored_bank

DRAWS = 3
POWER_MARGIN = 0.2  #: nats of information about the truth, on average over the draws (a diagnosis blind to the data: 0)
#: Mean probability of `none` on the nominal truths (its prior is 0.25). With campaigns of
#: collapse rows only read as ramps whose stands went unreported (likelihood.bracket_terms),
#: the stored bank gives 0.81 on the stored truths and banks 5 % off 0.62 (x 1.05) and
#: 0.52 (x 0.95); read as bare upper bounds, 0.59, 0.43 and 0.47 (the floor was 0.5).
NOMINAL_P_NONE = 0.7
NAMED_LEVEL = 0.01  #: p-value below which the named causes are wrong more often than they say
IN_SET = 0.7
PARAMETER_COVERAGE = 0.7

def outcomes(bank: Bank, truths: list[dict], draws: int = DRAWS, faults: LabFaults = LabFaults()) -> list[dict]:
    out = []
    for t in truths:
        for k in range(draws):
            obs, drawn = draw_campaign(t, np.random.default_rng([2026, t["truth"]["index"], k]), faults)
            if not obs.pairs:
                continue
            o = outcome(bank, obs, truth_model(t, bank, obs), truth_values(t))
            o.update(slug=t["slug"], faults=drawn)
            out.append(o)
    return out


def wrong_namings(named: list[dict]) -> tuple[int, float]:
    """Are the causes named at 0.9 right as often as they say? By truth (a truth's
    campaigns are not independent draws): a truth counts as named wrongly when most of its
    named campaigns name a wrong model, and each truth's chance of that is the mean of
    1 - P(named) over them; the number named wrongly is then a Poisson-binomial variable,
    and the p-value is the chance of as many or more."""
    by = {}
    for o in named:
        by.setdefault(o["slug"], []).append(o)
    chances = [float(np.mean([1.0 - o["p_top"] for o in v])) for v in by.values()]
    wrong = sum(sum(o["wrong_named"] for o in v) > len(v) / 2 for v in by.values())
    dist = np.array([1.0])
    for c in chances:
        dist = np.convolve(dist, [1.0 - c, c])
    return wrong, float(dist[wrong:].sum())


def judge(outs: list[dict]) -> list[str]:
    """The criteria the outcomes fail (empty: every one holds)."""
    failed = []
    inside = [o for o in outs if o["truth"] != "outside"]
    named = [o for o in inside if o["named"]]
    gain = power(inside)
    if not gain > POWER_MARGIN:
        failed.append(f"power {gain:.2f} nats <= {POWER_MARGIN}")
    nominal = [o["p_truth"] for o in inside if o["truth"] == "none"]
    if nominal and not np.mean(nominal) >= NOMINAL_P_NONE:
        failed.append(f"P(none) on the nominal truths {np.mean(nominal):.2f} < {NOMINAL_P_NONE}")
    wrong, p_named = wrong_namings(named)
    if p_named < NAMED_LEVEL:
        failed.append(f"{wrong} truths named wrongly, more than their stated probabilities allow (p {p_named:.4f})")
    if any(o["named"] for o in outs if o["truth"] == "outside"):
        failed.append("a truth outside the catalogue was named")
    if sum(o["in_set"] for o in inside) < IN_SET * len(inside):
        failed.append(f"truth in the 90 % set {sum(o['in_set'] for o in inside)}/{len(inside)} < {IN_SET}")
    cdfs = np.array([c for o in inside for c in o["cdf"].values()])
    covered = int(np.sum((cdfs >= 0.05) & (cdfs <= 0.95)))
    if cdfs.size and covered < PARAMETER_COVERAGE * cdfs.size:
        failed.append(f"truth's parameter in its 90 % interval {covered}/{cdfs.size} < {PARAMETER_COVERAGE}")
    # Simulation-based calibration: the posterior CDF at the true value is uniform when the
    # posteriors are right, so its mean over the truths (each truth's campaigns averaged:
    # they are not independent) is 1/2 within 3 standard errors (at most 1 / sqrt(12 n)); a
    # bank that predicts every threshold a few percent off shifts every parameter one way.
    per_truth = {}
    for o in inside:
        for name, c in o["cdf"].items():
            per_truth.setdefault((o["slug"], name), []).append(c)
    means = np.array([np.mean(v) for v in per_truth.values()])
    if means.size >= 5 and abs(float(means.mean()) - 0.5) > 3.0 / math.sqrt(12.0 * means.size):
        failed.append(f"the truth's posterior CDF averages {means.mean():.2f} over {means.size} truths' parameters, "
                      "not 1/2")
    return failed


def summary(outs: list[dict]) -> str:
    inside = [o for o in outs if o["truth"] != "outside"]
    named = [o for o in inside if o["named"]]
    outside = [o for o in outs if o["truth"] == "outside"]
    return (f"{len(outs)} campaigns of {len({o['slug'] for o in outs})} LMGC90 truths: power "
            f"{power(inside):.2f} nats, named {len(named)}/{len(inside)} (right {sum(o['right_named'] for o in named)}), "
            f"truth in the 90 % set {sum(o['in_set'] for o in inside)}/{len(inside)}, outside truths named "
            f"{sum(o['named'] for o in outside)}/{len(outside)} and flagged inadequate "
            f"{sum(not o['adequate'] for o in outside)}/{len(outside)}")


@lru_cache(maxsize=1)
def truths() -> list[dict]:
    found = stored_truths()
    assert len(found) >= 10, "fewer than 10 LMGC90 truths in data/lmgc90 (bench/lmgc90/truths.sh makes them)"
    return found


@lru_cache(maxsize=1)
def real_outcomes() -> list[dict]:
    return outcomes(stored_bank(), truths())


def test_lmgc90_truths_are_named_with_power_and_never_wrongly():
    outs = real_outcomes()
    line = "[LMGC90 truths] " + summary(outs)
    print("\n" + line)
    for o in outs:
        print(f"  {o['slug']}: {o['verdict']} top {o['top']} {o['p_top']:.2f} P(truth) {o['p_truth']:.2f} "
              f"p {o['p_value']:.3f} {o['flags']}")
    VERDICTS.append(line)
    assert judge(outs) == [], line


def test_a_posterior_equal_to_the_prior_fails_the_judgement(monkeypatch):
    """Mutation: the likelihood and the records' factor set to zero."""
    monkeypatch.setattr(posterior_module, "log_likelihood", lambda grid, *a, **k: np.zeros(grid.n))
    monkeypatch.setattr(posterior_module, "records_log_factor", lambda *a, **k: 0.0)
    failed = judge(outcomes(stored_bank(), truths(), draws=1))
    assert any(f.startswith("power") for f in failed), failed


def _biased(bank: Bank, factor: float) -> Bank:
    scale = lambda d: {k: [factor * x for x in v] for k, v in d.items()}
    return Bank({sid: dataclasses.replace(sb, thresholds=scale(sb.thresholds), replicas=scale(sb.replicas),
                                          node_replicas={k: scale(r) for k, r in sb.node_replicas.items()})
                 for sid, sb in bank.specimens.items()}, bank.code + "-biased")


@pytest.mark.parametrize("factor", [1.05, 0.95])
def test_a_bank_biased_by_5_percent_fails_the_judgement(factor):
    """One draw a truth, as for the prior's mutation (with one draw the stored bank gives
    P(none) 0.83 on the nominal truths and passes; these banks 0.59 and 0.56)."""
    failed = judge(outcomes(_biased(stored_bank(), factor), truths(), draws=1))
    assert failed, f"a bank whose thresholds are all x {factor} passed every criterion"


def test_a_transducer_off_by_1_5_percent_names_no_cause_and_is_flagged():
    nominal = [t for t in truths() if truth_model(t) == "none"]
    assert nominal, "no nominal truth among the LMGC90 truths"
    faults = LabFaults(transducer_bias=0.0, offset_sd=0.0, collapses_only_p=0.0)
    outs = []
    for t in nominal:
        for k in range(4):
            obs, _ = draw_campaign(t, np.random.default_rng([7, t["truth"]["index"], k]), faults)
            biased = [dataclasses.replace(p, gains=tuple(1.015 * g for g in p.gains)) for p in obs.pairs]
            outs.append(outcome(stored_bank(), dataclasses.replace(obs, pairs=biased), "none"))
    assert not any(o["wrong_named"] for o in outs), [(o["verdict"], o["top"], o["p_top"]) for o in outs]
    assert sum("sensor_bias" in o["flags"] for o in outs) >= 0.75 * len(outs), [o["flags"] for o in outs]


def test_collapse_rows_only_are_flagged_one_sided():
    t = truths()[0]
    obs, drawn = draw_campaign(t, np.random.default_rng(3), LabFaults(collapses_only_p=1.0))
    assert drawn["collapses_only"] and all(p.low_m == 0 for p in obs.pairs)
    assert "one_sided" in outcome(stored_bank(), obs, truth_model(t))["flags"]
    obs, drawn = draw_campaign(t, np.random.default_rng(3), LabFaults(collapses_only_p=0.0, step_mm=(1.0, 1.0)))
    assert "one_sided" not in outcome(stored_bank(), obs, truth_model(t))["flags"] or any(
        p.low_m == 0 for p in obs.pairs)


def _collapse_rows_only(bank: Bank) -> list[dict]:
    """One campaign of collapse rows only for every stored truth inside the catalogue."""
    out = []
    for t in truths():
        obs, _ = draw_campaign(t, np.random.default_rng([7, t["truth"]["index"], 0]), LabFaults(collapses_only_p=1.0))
        model = truth_model(t, bank, obs) if obs.pairs else "outside"
        if model != "outside":
            out.append(outcome(bank, obs, model, truth_values(t)))
    return out


ONE_SIDED_IN_SET = 0.8  #: a 90 % set, over a truth per draw: 0.9 within about two standard errors


def _one_sided_failures(outs: list[dict]) -> list[str]:
    failed = []
    held = float(np.mean([o["in_set"] for o in outs]))
    if held < ONE_SIDED_IN_SET:
        failed.append(f"truth in the 90 % set {held:.2f} < {ONE_SIDED_IN_SET}")
    if not power(outs) > POWER_MARGIN:
        failed.append(f"power {power(outs):.2f} nats <= {POWER_MARGIN}")
    return failed


def test_campaigns_of_collapse_rows_only_hold_the_truth_and_say_something():
    """A campaign that reports only the collapse of each ramp (like the seed paper's) still
    says where the thresholds are: its 90 % sets hold the truth about 90 % of the time and
    the truth gains probability on average. Read as bare upper bounds they favour every
    model that predicts lower thresholds: 0.74 in the set and -0.28 nats over 68 such
    draws (docs/diagnosis.md)."""
    outs = _collapse_rows_only(stored_bank())
    assert len(outs) >= 25, len(outs)
    failed = _one_sided_failures(outs)
    assert failed == [], (failed, [(o["top"], round(o["p_truth"], 2)) for o in outs])


def test_collapse_rows_read_as_bare_upper_bounds_fail_the_one_sided_check(monkeypatch):
    """Mutation: the campaign's unreported stands ignored (every pair an upper bound)."""
    monkeypatch.setattr(Observations, "stands_unreported", property(lambda self: False))
    assert _one_sided_failures(_collapse_rows_only(stored_bank()))


def _with_counterfactual(t: dict, effect: str, factor: float) -> dict:
    """A truth with a made-up counterfactual without `effect`: its thresholds x factor."""
    cf = {"pairs": [dict(p, threshold_m=None if p["threshold_m"] is None else p["threshold_m"] * factor)
                    for p in t["pairs"]]}
    return dict(t, counterfactuals={effect: cf})


@pytest.mark.parametrize("effect", ["base_restraint", "outside"])
def test_an_effect_is_a_cause_by_the_generators_counterfactual(effect):
    """The label's rule, by the generator: an effect whose counterfactual moves no tested
    threshold by more than 1 % is no cause (every material threshold is at least
    MATERIAL_EFFECT, 5 %); one that moves them by 50 % (0.41 in log, above any pair's twice
    build-tolerance spread) is; without a counterfactual the label is the emulators'."""
    bank = stored_bank()
    model = "outside" if effect == "outside" else None
    found = [t for t in truths() if (t["truth"]["model"] == "outside" if model else effect in t["truth"]["model"])]
    assert found, f"no stored truth with {effect}"
    t = dict(found[0], counterfactuals={})
    obs, _ = draw_campaign(t, np.random.default_rng(1), LabFaults(collapses_only_p=0.0))
    plain = truth_model(t, bank, obs)
    assert plain == ("outside" if model else plain)
    small = truth_model(_with_counterfactual(t, effect, 1.01), bank, obs)
    large = truth_model(_with_counterfactual(t, effect, 1.5), bank, obs)
    if model:
        assert (small, large) == ("none", "outside")
    else:
        assert effect in plain.split("+"), f"{t['slug']}: the rigid brackets' emulator calls them no cause ({plain})"
        assert effect not in small.split("+"), f"an effect that moves nothing by 1 % kept: {small}"
        assert large == plain, f"a 50 % effect dropped: {large} against {plain}"
