"""The diagnosis must say how sure it is, and be right as often as it says.

Rates, not seeds. Each hard case is a truth hidden in campaigns by an independent
generator (independent_campaigns.py: chamfered polygon blocks, a thinner ring of
polygons, brackets with play, an actuator played as a record, dt 5e-4 s against the
diagnosis's 1e-3 s). Its runs are stored as an outcome map (replay_maps.py: collapse or
not against the amplitude the table really made), and each of 20 noise draws replays the
generator's ramp over it with its own table-gain noise. The diagnosis's own simulations
are stored too, as the simulation bank of those arches (data/replay/bank, made by
bench/diagnosis_replay_bank.sh with the executables of this tree). The tests then run the
inference on every draw in milliseconds and assert rates: the truth in the 90 % set of
rivals in at least 15 of 20 draws, and no wrong cause named at 0.9 or more.

A change of the kernel's last bits is judged by the same draws on a remade bank: a paired
McNemar test, better or no worse, not "the same seed passes" (bench/diagnosis_replay_bank.sh).
One end-to-end diagnosis checks the format of the output and that the truth keeps a
probability of at least 0.02.
"""

from __future__ import annotations

import dataclasses
import json
import math
import shutil
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import binomtest, multivariate_normal, norm

from voussoir_post.diagnosis.actuator import peak_gain
import voussoir_post.diagnosis.bank as bank_module
from voussoir_post.diagnosis.bank import Bank, build_bank, key_variant, load_banks, variant_key
from voussoir_post.diagnosis.decision import NAME_AT, Decision, credible_set, to_separate
from voussoir_post.diagnosis.emulator import emulate
from voussoir_post.diagnosis.early import early_key
from voussoir_post.diagnosis.likelihood import ONE_SIDED_STEPS, _log_bracket, bracket_terms, records_log_factor, scales
from voussoir_post.diagnosis.models import MODEL_IDS, model_prior, nominal_log, sim_spread
from voussoir_post.diagnosis.observations import Observations, PairObservation, from_campaign
from voussoir_post.diagnosis.pipeline import DiagnosisSettings, diagnose
from voussoir_post.diagnosis.posterior import ADEQUATE_P, adequacy, infer
from voussoir_post.diagnosis.rates import draw_outcomes, mcnemar
from voussoir_post.diagnosis.effects import COMBINED, Variant
from voussoir_post.diagnosis.models import ModelGrid
from voussoir_post.diagnosis.next_test import (expected_gain_bits, gain_jackknife_se_bits, gain_spread_bits,
                                               posterior_draws, within_limits)
from voussoir_post.diagnosis.report import _next_test_lines
from voussoir_post.diagnosis.posterior import ModelPosterior
from voussoir_post.readers.campaign import CampaignError, Specimen, TableLimits, Test as CampaignTest, read_campaign

from conftest import SEED_CAMPAIGN, VERDICTS, bin_dir, executable
from independent_campaigns import Arch, Truth, write_campaign
from replay_maps import draw_observations, load_map

DATA = Path(__file__).parent / "data" / "replay"
BANK_SCANS = DATA / "bank_scans.json"
DRAWS = 20


@lru_cache(maxsize=1)
def stored_bank() -> Bank:
    """The stored bank of the test arches, with the kernel's scan of each pair's nominal
    arch that sorts its pairs for early collapses (early.early_fractions, stored beside it:
    test_diagnosis_early.py checks its classes against the kernel's live scans)."""
    bank = load_banks(DATA / "bank")
    assert bank.specimens, f"no stored simulation bank in {DATA / 'bank'} (bench/diagnosis_replay_bank.sh makes it)"
    for r in json.loads(BANK_SCANS.read_text())["rows"]:
        bank.early[early_key(r["specimen_id"], r["frequency_hz"])] = r["fraction"]
    return bank


def case_outcomes(slug: str, bank: Bank | None = None) -> list[dict]:
    omap = load_map(DATA / "maps" / f"{slug}.json")
    return draw_outcomes(bank or stored_bank(), omap, DRAWS, draw_observations)


HARD_CASES = sorted(p.stem for p in (DATA / "maps").glob("*.json"))


@pytest.mark.parametrize("slug", HARD_CASES)
def test_replayed_draws_hold_the_truth_and_name_nothing_wrong(slug):
    outcomes = case_outcomes(slug)
    truth = outcomes[0]["truth"]
    tops = {}
    for o in outcomes:
        tops[o["top"]] = tops.get(o["top"], 0) + 1
    line = (f"[{slug}] truth {truth}: in the 90 % set {sum(o['in_set'] for o in outcomes)}/{DRAWS}, named "
            f"wrongly {sum(o['wrong_named'] for o in outcomes)}/{DRAWS}, named rightly "
            f"{sum(o['right_named'] for o in outcomes)}/{DRAWS}, mean P(truth) "
            f"{np.mean([o['p_truth'] for o in outcomes]):.2f}; most probable: "
            + ", ".join(f"{m} x{n}" for m, n in sorted(tops.items(), key=lambda kv: -kv[1])))
    print("\n" + line + "\n" + ", ".join(f"{o['verdict']}:{o['top']} {o['p_top']:.2f}" for o in outcomes))
    VERDICTS.append(line)
    assert sum(o["wrong_named"] for o in outcomes) == 0, line
    if truth == "outside":
        assert all(not o["named"] for o in outcomes), line
    else:
        assert sum(o["in_set"] for o in outcomes) >= 15, line


@pytest.mark.parametrize("slug", ["friction_0.43", "chamfer_4mm_friction_0.42"])
def test_a_tenth_of_the_uncertainty_moves_no_probability_by_more_than_005(slug):
    """Moving any one measured threshold by a tenth of its uncertainty, up or down, changes
    no model's probability by more than 0.05. The uncertainty of a measured threshold
    (the midpoint of its bracket, docs/measured_data.md) is half its bracket; with no
    stand row below, half the campaign's median relative bracket."""
    bank = stored_bank()
    omap = load_map(DATA / "maps" / f"{slug}.json")
    rng = np.random.default_rng(7)
    for _ in range(3):
        obs = draw_observations(omap, rng)
        base = infer(bank, obs).probabilities
        median = float(np.median([(p.high_m - p.low_m) / p.high_m for p in obs.pairs if p.low_m > 0]))
        for j, p in enumerate(obs.pairs):
            half = 0.5 * (p.high_m - p.low_m) if p.low_m > 0 else 0.5 * median * p.high_m
            for sign in (-1.0, 1.0):
                shift = sign * 0.1 * half
                moved = list(obs.pairs)
                moved[j] = PairObservation(p.specimen_id, p.frequency_hz, p.low_m + shift if p.low_m > 0 else 0.0,
                                           p.high_m + shift, p.gains, p.test_ids)
                other = infer(bank, dataclasses.replace(obs, pairs=moved)).probabilities
                worst = max(abs(base[m] - other[m]) for m in base)
                assert worst <= 0.05, (slug, p.specimen_id, p.frequency_hz, sign, worst)


# ------------------------------------------------------------------ the pieces, against closed forms


def test_bracket_probability_is_the_normal_mass_between_its_ends():
    lo = np.array([-np.inf, -1.0, 2.0, 30.0])
    hi = np.array([0.3, 1.5, 2.5, 31.0])
    m, s = np.array([0.0, 0.2, -1.0, 0.0]), np.array([1.0, 0.5, 1.0, 2.0])
    expect = norm.cdf(hi, m, s) - norm.cdf(lo, m, s)
    got = np.exp(_log_bracket(lo, hi, m, s))
    assert np.allclose(got[:3], expect[:3], rtol=1e-9, atol=0)
    # Far in a tail the difference of two CDFs underflows; the log form does not.
    assert math.isfinite(_log_bracket(lo[3:], hi[3:], m[3:], s[3:])[0])
    assert abs(_log_bracket(lo[3:], hi[3:], m[3:], s[3:])[0] - norm.logsf(15.0) - math.log1p(-math.exp(norm.logsf(15.5) - norm.logsf(15.0)))) < 1e-6


def test_a_campaign_of_collapse_rows_only_reads_each_as_a_ramps_first_collapse():
    """Given the threshold t, a ramp of step r whose phase is arbitrary puts its first
    collapse h uniformly in log on (log t, log t + log(1 + r)); over r the pair's term,
    as a function of log h, must therefore be a probability density (integral 1) for any
    t, and where the campaign reports stands elsewhere the pair stays an upper bound."""
    pair = PairObservation("S", 1.0, 0.0, 0.05)
    assert bracket_terms(pair, stands_unreported=False) == [(-math.inf, math.log(0.05), 0.0)]
    assert bracket_terms(dataclasses.replace(pair, low_m=0.04), True) == [(math.log(0.04), math.log(0.05), 0.0)]
    log_t = math.log(0.037)
    grid = np.linspace(log_t - 0.5, log_t + 2.0, 20001)  # h from below t to 300 % above
    density = [sum(math.exp(w) for lo, hi, w in bracket_terms(dataclasses.replace(pair, high_m=math.exp(h)), True)
                   if lo < log_t <= hi) for h in grid]
    total = float(np.sum(density) * (grid[1] - grid[0]))
    assert abs(total - 1.0) < 0.01, total
    # Exactly, by the nodes: the mean over r of (1 / log(1 + r)) x log(1 + r) is 1.
    widths = np.log1p(ONE_SIDED_STEPS)
    assert sum(w * math.exp(lw) for w, (_, _, lw) in zip(widths, bracket_terms(pair, True))) == pytest.approx(1.0)
    # The density falls with how far below the collapse the threshold lies.
    near, far = (sum(math.exp(w) for lo, hi, w in bracket_terms(pair, True) if lo < math.log(x) <= hi)
                 for x in (0.0495, 0.03))
    assert near > 10 * far > 0


def test_a_campaign_says_whether_it_reports_stands():
    camp = read_campaign(SEED_CAMPAIGN)
    obs, _ = from_campaign(camp)
    assert obs.stand_rows is False and obs.stands_unreported  # the seed paper: collapse rows only
    assert all(p.low_m == 0 for p in obs.pairs)
    with_stand = dataclasses.replace(obs, stand_rows=True)
    assert not with_stand.stands_unreported


def test_a_test_driven_by_a_record_alone_is_named_as_not_read(tmp_path):
    """A campaign may hold tests driven by a record (an earthquake, a pulse) with no afd
    frequency and amplitude: they fall in no (specimen, frequency) pair, and the notes and
    the log say which tests the probabilities leave out instead of passing over them."""
    from voussoir_post.diagnosis.report import unread_text
    folder = tmp_path / "campaign"
    shutil.copytree(SEED_CAMPAIGN, folder)
    with open(folder / "tests.csv", "a") as f:
        f.write("E1,A156,record,,,,,,collapse,\n")
    (folder / "records").mkdir(exist_ok=True)
    (folder / "records" / "E1.csv").write_text("t_s,table_x_m\n0.0,0.0\n0.01,0.001\n0.02,0.003\n")
    plain, _ = from_campaign(read_campaign(SEED_CAMPAIGN))
    obs, _ = from_campaign(read_campaign(folder))
    assert plain.unread == () and unread_text(plain) == ""
    assert obs.unread == ("E1",)
    assert [(p.specimen_id, p.frequency_hz, p.high_m) for p in obs.pairs] == \
        [(p.specimen_id, p.frequency_hz, p.high_m) for p in plain.pairs]
    text = unread_text(obs)
    assert "1 test driven by a record (E1)" in text and "none of these probabilities" in text


def _obs(gains_per_pair, source="records"):
    pairs = [PairObservation("S", 1.0 + k, 0.01, 0.011, tuple(g)) for k, g in enumerate(gains_per_pair)]
    return Observations("t", {}, pairs, {}, source)


def test_records_factor_weighs_a_table_that_followed_the_command_against_one_that_did_not():
    rng = np.random.default_rng(1)
    followed = _obs([1.0 + 0.01 * rng.standard_normal(8) for _ in range(4)])
    off = _obs([1.15 + 0.01 * rng.standard_normal(8) for _ in range(4)])
    for obs, favoured in ((followed, False), (off, True)):
        sc = scales(Bank({}, ""), obs, obs.pairs)
        diff = records_log_factor(True, obs, obs.pairs, sc) - records_log_factor(False, obs, obs.pairs, sc)
        assert (diff > 5.0) if favoured else (diff < -5.0), diff
    # In closed form: the gains N(1 + b, s^2) with the transducer's common bias b ~ N(0, 1 %^2)
    # integrated out are jointly normal, covariance s^2 I + 0.01^2 1 1^T (s floored at 0.003).
    one = _obs([(1.0, 1.004), (0.998, 1.001, 1.003)])
    sc = scales(Bank({}, ""), one, one.pairs)
    g = np.array([1.0, 1.004, 0.998, 1.001, 1.003])
    s2 = max(0.003, sc.sigma_gain) ** 2
    cov = s2 * np.eye(5) + 0.01 ** 2 * np.ones((5, 5))
    assert abs(records_log_factor(False, one, one.pairs, sc) - multivariate_normal(np.ones(5), cov).logpdf(g)) < 1e-9


def test_a_common_gain_offset_within_the_calibration_favours_a_table_that_followed():
    """A transducer reading 1.5 % high on every test (within 1.5 calibrations of 1 %) is a
    sensor bias: the table that followed the command stays far more probable than a
    table whose every pair had its own gain."""
    rng = np.random.default_rng(4)
    biased = _obs([1.015 * (1.0 + 0.003 * rng.standard_normal(6)) for _ in range(6)])
    sc = scales(Bank({}, ""), biased, biased.pairs)
    assert records_log_factor(False, biased, biased.pairs, sc) - records_log_factor(True, biased, biased.pairs, sc) > 10.0
    # Without the bias term (a calibration known to 0.1 %), the same gains would name the table.
    sc_exact = dataclasses.replace(sc, gain_bias_sd=0.001)
    assert records_log_factor(False, biased, biased.pairs, sc_exact) < records_log_factor(True, biased, biased.pairs,
                                                                                         sc_exact)


def test_the_emulator_passes_through_its_nodes_and_knows_where_it_does_not():
    """At a node without noise the GP returns the node's value with no variance; between
    nodes of a step it has variance; a steep step (a friction at which the arch starts to
    slide) is followed where a cubic least-squares fit misses it by more than 5 %."""
    x = np.linspace(0.0, 1.0, 11)
    y = np.where(x < 0.45, np.log(0.03), np.log(0.05)) + 0.02 * x
    em = emulate(x[:, None], y, np.full(x.size, 1e-8), x[:, None])
    assert np.max(np.abs(em.mean - y)) < 1e-3 and np.max(em.var) < 1e-6
    mid = emulate(x[:, None], y, np.full(x.size, 1e-8), np.array([[0.45]]))
    assert mid.var[0] > 1e-4
    cubic = np.polyval(np.polyfit(x, y, 3), x)
    assert np.max(np.abs(cubic - y)) > 0.05
    # With noise, the nodes are followed to within it, and the leave-one-out residuals
    # of a smooth curve are of order one.
    rng = np.random.default_rng(2)
    xs = np.linspace(0.0, 1.0, 15)
    noisy = np.log(0.04) - 0.3 * xs + 0.01 * rng.standard_normal(xs.size)
    em = emulate(xs[:, None], noisy, np.full(xs.size, 1e-4), xs[:, None])
    assert np.max(np.abs(em.mean - noisy)) < 0.03
    assert 0.3 < float(np.sqrt(np.mean(em.loo_z ** 2))) < 2.0


def _nominal_campaign(bank, rng, shift=None):
    """Brackets drawn from the nominal model's own predictive on the stored bank (the
    check's null), ramps of 5 %; `shift` moves one specimen's thresholds (its power)."""
    pairs = []
    specimens = {}
    deltas = {sid: 0.03 * rng.standard_normal() for sid in bank.specimens}
    common = 0.01 * rng.standard_normal()
    for sid, sb in sorted(bank.specimens.items()):
        for f in sb.frequencies_hz:
            mu = nominal_log(sb, f) + deltas[sid] + common + sim_spread(sb, f) * rng.standard_normal()
            mu += 0.01 * rng.standard_normal() + (shift.get(sid, 0.0) if shift else 0.0)
            step = 0.05 * math.exp(nominal_log(sb, f))
            start = 0.6 * math.exp(nominal_log(sb, f)) + step * rng.random()
            k = math.ceil((math.exp(mu) - start) / step)
            high = start + k * step
            pairs.append(PairObservation(sid, f, high - step, high))
        specimens[sid] = Specimen(sid, *{"W156": (156.0, 13), "W132": (132.0, 11), "W118": (118.0, 10)}[sid],
                                  0.508, 0.071, 0.145, 700.0, 0.5)
    return Observations("null", specimens, pairs, {sid: (1, 1, 1) for sid in specimens})


def test_the_adequacy_check_holds_its_size_under_its_null_and_fails_a_specimen_off_by_25_percent():
    bank = stored_bank()
    rng = np.random.default_rng(11)
    null = [adequacy(infer(bank, obs, model_ids=("none",)), "none") for obs in
            (_nominal_campaign(bank, rng) for _ in range(60))]
    # Its level is 0.01; Sidak's bound is conservative, so at most a few of 60 may fall below.
    assert sum(p < ADEQUATE_P for p in null) <= 3, sorted(null)[:5]
    off = [adequacy(infer(bank, obs, model_ids=("none",)), "none") for obs in
           (_nominal_campaign(bank, rng, {"W132": math.log(1.25)}) for _ in range(20))]
    assert sum(p < ADEQUATE_P for p in off) >= 15, sorted(off)


def test_expected_gain_is_the_mutual_information_of_the_ramps_bin():
    """Two rivals equally likely whose thresholds lie far apart: the outcome says which,
    one bit; the same prediction: nothing; a 9:1 split, far apart: H(0.1) bits."""
    assert abs(expected_gain_bits([0.5, 0.5], [math.log(0.03), math.log(0.06)], [0.01, 0.01]) - 1.0) < 1e-6
    assert expected_gain_bits([0.5, 0.5], [math.log(0.03)] * 2, [0.02, 0.02]) < 1e-9
    h = -(0.9 * math.log2(0.9) + 0.1 * math.log2(0.1))
    assert abs(expected_gain_bits([0.9, 0.1], [math.log(0.03), math.log(0.06)], [0.01, 0.01]) - h) < 1e-6
    # Half-overlapping predictions tell less than one bit but more than none.
    mid = expected_gain_bits([0.5, 0.5], [math.log(0.03), math.log(0.0309)], [0.02, 0.02])
    assert 0.05 < mid < 0.9


def test_a_rival_whose_parameters_spread_at_a_new_frequency_tells_less():
    """A rival is a mixture over its parameters' draws. Rival A predicts x1; rival B half
    x1 and half x2, far apart: the outcome is near x2 with probability 1/4 overall, so
    I = H(3/4) - (1/2) H(1/2) = 0.3113 bits (against 1 bit were B's draws all at x2); a
    mixture of equal components is the normal law itself; equal mixtures tell nothing."""
    x1, x2 = math.log(0.03), math.log(0.06)
    h = lambda q: -(q * math.log2(q) + (1 - q) * math.log2(1 - q))
    assert abs(expected_gain_bits([0.5, 0.5], [x1, [x1, x2]], [0.01, 0.01]) - (h(0.75) - 0.5)) < 1e-4
    assert abs(expected_gain_bits([0.5, 0.5], [[x1] * 3, [x2] * 3], [0.01, 0.01]) - 1.0) < 1e-6
    assert expected_gain_bits([0.5, 0.5], [[x1, x2], [x2, x1]], [0.01, 0.01]) < 1e-9


def test_what_one_run_of_a_test_delivers_spreads_about_its_expected_gain():
    """Rival A predicts x1; rival B half x1, half x2, far apart; 1:1. An outcome near x2
    (probability 1/4) leaves B alone: 1 bit. One near x1 (3/4) leaves A at 2/3: 1 - H(2/3)
    bits. Their mean is the expected gain H(3/4) - 1/2, their standard deviation the
    spread. Far-apart rivals always deliver the same (no spread); so do identical ones."""
    x1, x2 = math.log(0.03), math.log(0.06)
    h = lambda q: -(q * math.log2(q) + (1 - q) * math.log2(1 - q))
    near_x2, near_x1 = 1.0, 1.0 - h(2 / 3)
    mean = 0.25 * near_x2 + 0.75 * near_x1
    sd = math.sqrt(0.25 * (near_x2 - mean) ** 2 + 0.75 * (near_x1 - mean) ** 2)
    assert abs(mean - (h(0.75) - 0.5)) < 1e-12  # (the identity the mean rests on)
    assert abs(gain_spread_bits([0.5, 0.5], [x1, [x1, x2]], [0.01, 0.01]) - sd) < 1e-4
    assert gain_spread_bits([0.9, 0.1], [x1, x2], [0.01, 0.01]) < 1e-6
    assert gain_spread_bits([0.5, 0.5], [x1, x1], [0.02, 0.02]) < 1e-9


def test_the_monte_carlo_error_of_a_gain_is_the_jackknife_over_the_draws():
    """Rival A's three draws at x1; B's at x2, x2, x1; far apart, 1:1. Leaving out one of
    B's x2 draws leaves B half at x1: H(3/4) - 1/2 bits (twice); leaving out its x1 draw
    separates them: 1 bit. The jackknife: sqrt(2/3 sum (g_i - mean)^2). Draws that agree
    have no Monte Carlo error."""
    x1, x2 = math.log(0.03), math.log(0.06)
    h = lambda q: -(q * math.log2(q) + (1 - q) * math.log2(1 - q))
    g = np.array([h(0.75) - 0.5, h(0.75) - 0.5, 1.0])
    se = math.sqrt(2 / 3 * float(np.sum((g - g.mean()) ** 2)))
    assert abs(gain_jackknife_se_bits([0.5, 0.5], [[x1] * 3, [x2, x2, x1]], [0.01, 0.01]) - se) < 1e-4
    assert gain_jackknife_se_bits([0.5, 0.5], [[x1] * 3, [x2] * 3], [0.01, 0.01]) < 1e-9


def test_the_report_ranks_the_best_tests_and_calls_a_near_tie_one():
    """The section lists every test with each rival's prediction; a lead smaller than
    twice its standard error is called a near tie, a larger one is not."""
    def test(sid, gain, se):
        return {"specimen_id": sid, "frequency_hz": 2.0, "new": True, "amplitudes_m": [0.02, 0.03, 0.0005],
                "expected_gain_bits": gain, "gain_se_bits": se, "gain_spread_bits": 0.4,
                "predicted_m": {"geometry": 0.025, "contact_edges": 0.027}}
    best = dict(test("W156", 0.40, 0.05), alternatives=[test("W132", 0.35, 0.05), test("W118", 0.10, 0.0)])
    text = "\n".join(_next_test_lines(best))
    assert "near tie" in text
    assert "| 3 | W118 |" in text and "25.0 | 27.0 |" in text
    # A test held below the threshold: its amplitude, and each rival's predicted crown peak.
    hold = dict(test("W118", 0.05, 0.01), kind="hold_crown", amplitudes_m=[0.0215],
                predicted_crown_m={"geometry": 0.0031, "contact_edges": 0.0008})
    best["alternatives"].append(hold)
    text = "\n".join(_next_test_lines(best))
    assert "| 4 | W118 | 2 (new) | hold at 21.5, record the crown |" in text and "crown 3.10 | crown 0.80 |" in text
    best["alternatives"][0]["expected_gain_bits"] = 0.10
    assert "near tie" not in "\n".join(_next_test_lines(best))
    assert _next_test_lines(None) == []


def test_the_notes_say_when_no_test_tells_much_and_how_to_part_a_thinner_ring_from_pivots():
    """Below LITTLE_BITS the notes say that no test is expected to tell much, and where
    the two leading rivals differ only by a thinner ring against pivots set in (alone or
    beside the same other effect) they say to measure the specimens; neither at a larger
    gain, and no caliper where the leading rivals differ otherwise."""
    from voussoir_post.diagnosis.report import LITTLE_BITS, _advice_text

    def advice(gain, rivals):
        return _advice_text({"specimen_id": "W132", "frequency_hz": 3.0, "new": False, "kind": "afd_ramp",
                             "amplitudes_m": [0.015, 0.023, 0.0005], "expected_gain_bits": gain,
                             "predicted_m": {m: 0.018 for m in rivals}}, "The next test")

    little = "No test within the table's limits is expected to tell much: the best 0.04 bits"
    caliper = "Measuring the ring's thickness and the voussoirs' edges"
    for rivals in (["geometry", "contact_edges", "contact_edges+geometry"],
                   ["contact_edges+table_motion", "geometry+table_motion"]):
        text = advice(0.04, rivals)
        assert text.startswith(" The next test (0.04 bits): specimen W132 at 3 Hz")
        assert little in text and caliper in text
    text = advice(0.04, ["base_restraint", "base_restraint+contact_edges", "geometry"])
    assert little in text and caliper not in text
    text = advice(LITTLE_BITS, ["geometry", "contact_edges"])
    assert "tell much" not in text and caliper not in text
    assert _advice_text(None, "The next test") == ""


def test_posterior_draws_are_the_posteriors_stratified_quantiles():
    """Three draws of a uniform posterior over friction 0.30, 0.31, ..., 0.70 (41 points):
    the first grid points whose cumulative mass reaches 1/6, 1/2 and 5/6, i.e. the
    7th, 21st and 35th: 0.36, 0.50 and 0.64; a pair's draws carry both parameters (a
    restraint's side as text); `none` is the nominal variant."""
    def posterior(model_id, names, values):
        n = values[0].size
        grid = ModelGrid(model_id, names, values, np.full(n, -math.log(n)), np.zeros((n, 1)), False)
        return ModelPosterior(model_id, grid, 0.0, np.full(n, 1.0 / n))
    friction = np.round(np.linspace(0.30, 0.70, 41), 6)
    draws = posterior_draws(posterior("friction", ("friction",), [friction]))
    assert draws == [Variant("friction", 0.36), Variant("friction", 0.5), Variant("friction", 0.64)]
    sides = np.array(["left", "right"], dtype=object).repeat(2)
    pair = posterior("base_restraint+friction", ("base_restraint", "friction"), [sides, np.array([0.4, 0.6] * 2)])
    # cumulative mass 1/4, 1/2, 3/4, 1: the first points reaching 1/4 and 3/4
    assert posterior_draws(pair, 2) == [Variant(COMBINED, (("base_restraint", "left"), ("friction", 0.4))),
                                        Variant(COMBINED, (("base_restraint", "right"), ("friction", 0.4)))]
    nominal = posterior("none", (), [np.zeros(1)])
    assert posterior_draws(nominal, 2) == [Variant(), Variant()]


def test_a_repeat_is_scored_within_the_bracket_the_pair_already_has():
    """A repeat's rows join the pair's bracket: its outcome is a bin of that bracket, each
    rival's law truncated to it. A bracket narrower than the ramp's bin: nothing left to
    learn; a one-sided bracket above both rivals: the full bit; two bins: the mutual
    information of the truncated laws, computed apart."""
    means, sds = [math.log(0.03), math.log(0.0309)], [0.02, 0.02]
    assert expected_gain_bits([0.5, 0.5], means, sds) > 0.05  # as if untested
    assert expected_gain_bits([0.5, 0.5], means, sds, within=(math.log(0.0300), math.log(0.0306))) < 1e-12
    far = expected_gain_bits([0.5, 0.5], [math.log(0.03), math.log(0.06)], [0.01, 0.01],
                             within=(-math.inf, math.log(0.08)))
    assert abs(far - 1.0) < 1e-6
    lo, hi, step = math.log(0.0295), math.log(0.0295) + 2 * math.log1p(0.025), 0.025
    edges = [lo, lo + math.log1p(step), hi]
    rows = []
    for m, s_ in zip(means, sds):
        c = norm.cdf(edges, m, s_)
        rows.append(np.diff(c) / (c[-1] - c[0]))
    rows = np.array(rows)
    mix = rows.mean(axis=0)
    h = lambda q: -float(np.sum(q * np.log2(q)))
    assert abs(expected_gain_bits([0.5, 0.5], means, sds, step, within=(lo, hi))
               - (h(mix) - 0.5 * (h(rows[0]) + h(rows[1])))) < 1e-9


def test_a_pair_whose_tests_all_stood_is_a_lower_bound(tmp_path):
    """A ramp that ends without a collapse says that the threshold lies above its largest
    stand: the pair is read (not dropped, as it was), its term is the normal mass above
    the stand, and a repeat of it ramps on upward, where a rival below the stand has no
    bin left and two rivals above it part by the mutual information of their laws
    truncated to (stand, inf), computed apart."""
    folder = tmp_path / "campaign"
    shutil.copytree(SEED_CAMPAIGN, folder)
    with open(folder / "tests.csv", "a") as f:
        for k, a in enumerate((0.004, 0.006, 0.008)):
            f.write(f"A156_2Hz_{k},A156,afd,2.0,{a},1,1,1,stand,\n")
    obs, _ = from_campaign(read_campaign(folder))
    lower = [p for p in obs.pairs if p.frequency_hz == 2.0]
    assert len(lower) == 1 and lower[0].low_m == 0.008 and lower[0].high_m == math.inf
    assert not lower[0].collapsed and not lower[0].closed and obs.stand_rows and not obs.stands_unreported
    (lo, hi, w), = bracket_terms(lower[0], obs.stands_unreported)
    assert (lo, hi, w) == (math.log(0.008), math.inf, 0.0)
    m, s_ = np.array([math.log(0.007), math.log(0.009)]), np.array([0.1, 0.1])
    assert np.allclose(np.exp(_log_bracket(np.full(2, lo), np.full(2, hi), m, s_)), norm.sf(lo, m, s_), rtol=1e-12)
    # The repeat's outcome: bins of RAMP_STEP above the stand, the last one open.
    means, sds = [math.log(0.0095), math.log(0.0120)], [0.03, 0.03]
    step = 0.025
    got = expected_gain_bits([0.5, 0.5], means, sds, step, within=(lo, math.inf))
    edges = lo + math.log1p(step) * np.arange(0, 200)
    edges = np.append(edges[edges < max(means) + 6 * 0.03 + math.log1p(step)], np.inf)
    rows = np.array([np.diff(norm.cdf(edges, mu, s)) / norm.sf(lo, mu, s) for mu, s in zip(means, sds)])
    mix = rows.mean(axis=0)
    h = lambda q: -float(np.sum(q[q > 0] * np.log2(q[q > 0])))
    assert got == pytest.approx(h(mix) - 0.5 * (h(rows[0]) + h(rows[1])), abs=0.02)
    assert got > 0.9  # the two rivals lie 23 % apart, far beyond their spread
    assert expected_gain_bits([0.5, 0.5], [math.log(0.002), math.log(0.003)], [0.01, 0.01], step,
                              within=(lo, math.inf)) < 1e-9


def test_an_advised_ramp_stays_within_the_tables_limits():
    table = TableLimits(stroke_m=0.1, max_velocity_m_s=0.5, max_accel_m_s2=10.0)
    assert within_limits(0.05, 1.0, table)  # 0.31 m/s, 2.0 m/s2
    assert not within_limits(0.12, 0.5, table)  # stroke
    assert not within_limits(0.09, 1.0, table)  # 0.57 m/s
    assert not within_limits(0.03, 3.0, table)  # 10.7 m/s2


def test_table_csv_is_read_with_its_defaults_and_refused_when_off(tmp_path):
    folder = tmp_path / "c"
    shutil.copytree(SEED_CAMPAIGN, folder)
    assert read_campaign(folder).table == TableLimits()
    (folder / "table.csv").write_text("stroke_m,displacement_gain_sd\n0.1,0.02\n")
    t = read_campaign(folder).table
    assert (t.stroke_m, t.displacement_gain_sd, t.max_velocity_m_s, t.from_file) == (0.1, 0.02, 1.0, True)
    (folder / "table.csv").write_text("stroke_m\n-0.1\n")
    with pytest.raises(CampaignError, match="stroke_m"):
        read_campaign(folder)
    (folder / "table.csv").write_text("stroke_m\n0.1\n0.2\n")
    with pytest.raises(CampaignError, match="one data row"):
        read_campaign(folder)


def test_credible_set_is_the_smallest_set_reaching_the_mass_best_first():
    p = {"none": 0.05, "friction": 0.6, "geometry": 0.3, "contact_edges": 0.05}
    assert credible_set(p) == ["friction", "geometry"]
    assert credible_set({"friction": 0.95, "none": 0.05}) == ["friction"]


def test_model_priors_sum_to_one_over_the_models():
    assert abs(sum(model_prior(m) for m in MODEL_IDS) - 1.0) < 1e-12
    assert len(MODEL_IDS) == 16


def test_variant_keys_round_trip():
    for key in ("nominal", "friction=0.45", "contact_edges=0.002+friction=0.45", "base_restraint=left+geometry=0.88"):
        assert variant_key(key_variant(key)) == key


def test_a_table_that_follows_the_command_has_gain_one_from_its_peak():
    """Without records the gain is the measured peak over the command's own peak, not
    over A (2 pi f)^2: the attack and decay envelopes add their derivatives to the full
    cycles (here the command's peak by second differences of docs/measured_data.md's
    displacement, sampled densely)."""
    f, amp = 1.25, 0.046
    t = np.linspace(0.0, 3.0 / f, 300001)
    h = t[1] - t[0]
    T = 1.0 / f
    env = np.where(t < T, np.sin(np.pi * t / (2 * T)) ** 2,
                   np.where(t < 2 * T, 1.0, np.cos(np.pi * (t - 2 * T) / (2 * T)) ** 2))
    x = amp * env * np.sin(2 * np.pi * f * t)
    peak = float(np.abs(np.diff(x, 2)).max() / h ** 2)
    assert peak > 1.04 * amp * (2 * np.pi * f) ** 2  # the envelopes add about 5 %
    for gain in (1.0, 1.1):
        test = CampaignTest("t", "A", "afd", "collapse", frequency_hz=f, amplitude_m=amp, peak_accel_m_s2=gain * peak)
        assert abs(peak_gain(test) - gain) < 1e-5


def test_mcnemar_is_the_exact_binomial_test_of_the_discordant_draws():
    a = [True] * 10 + [False] * 10
    b = [True] * 4 + [False] * 6 + [True] * 1 + [False] * 9
    # Discordant: a right b wrong 6, a wrong b right 1.
    assert abs(mcnemar(a, b)["p_value"] - binomtest(1, 7, 0.5).pvalue) < 1e-12
    assert mcnemar(a, b)["worse"] == 6 and mcnemar(a, b)["better"] == 1


# ------------------------------------------------------------------ end to end, on a campaign folder


# Small grids, one tested frequency and one new one for the next test, brackets in
# contact only, no refined nodes: the end-to-end test checks the plumbing and the format
# (the rates, and the brackets with play, are the replay tests', on the stored bank's full
# grids; the refinement is test_bank_refines_where_the_response_is_steep's).
SMALL_GRIDS = dict(inset_grid_m=(0.002, 0.005), friction_steps=(0.05, 0.1, 0.2), thickness_factors=(0.85, 0.94),
                   pair_inset_m=(0.002,), pair_friction_steps=(-0.1,), pair_thickness_factors=(0.88,),
                   probe_frequencies_hz=(3.0,), bracket_gaps_m=(0.0,), refine_rounds=0)
ONE_ARCH = (Arch("W156", 156.0, 13, (1.25,)),)


def test_end_to_end_diagnosis_follows_the_contract_and_keeps_the_truth(tmp_path, voussoir_run_exe):
    if executable("voussoir-sweep") is None or executable("voussoir-limit") is None:
        pytest.fail(f"voussoir-sweep and voussoir-limit are needed in {bin_dir()}")
    folder = tmp_path / "campaign"
    write_campaign(folder, Truth(friction=0.43), bin_dir(), arches=ONE_ARCH, seed=23)
    campaign = read_campaign(folder)
    words = ("inset", "chamfer", "restrain", "bracket", "gain", "truth", "hidden", "effect", "actuator", "gap")
    for path in folder.rglob("*"):
        if path.is_file():
            assert not any(w in path.read_text().lower() for w in words), f"{path} gives the truth away"
    assert all(s.friction == 0.5 for s in campaign.specimens.values())
    logs: list[str] = []
    settings = DiagnosisSettings(bin_dir=bin_dir(), n_ranks=2, log=logs.append, bank_dir=tmp_path / "bank",
                                 crown_records=True, **SMALL_GRIDS)
    result = diagnose(folder, tmp_path / "first", settings)
    questions = sorted(p.name for p in (tmp_path / "bank" / "next-test").glob("*"))
    again_logs: list[str] = []
    again = diagnose(folder, tmp_path / "second",
                     DiagnosisSettings(bin_dir=bin_dir(), n_ranks=2, log=again_logs.append,
                                       bank_dir=tmp_path / "bank", crown_records=True, **SMALL_GRIDS))
    VERDICTS.append(f"[end to end, friction 0.43 on W156] verdict {result['verdict']} rivals {result['rivals']} "
                    f"P(friction) {result['probabilities']['friction']:.2f}")
    # The contract, version 4.
    keys = {"campaign", "contract_version", "verdict", "effects", "rivals", "probabilities", "adequate",
            "parameters", "baseline", "extended", "candidates", "next_test", "flags", "adequacy_p_value", "notes"}
    assert set(result) == keys
    on_disk = json.loads((tmp_path / "first" / "diagnosis.json").read_text())
    assert on_disk == json.loads(json.dumps(result))
    assert result["contract_version"] == 4
    assert 0.0 <= result["adequacy_p_value"] <= 1.0 and result["adequate"] == (result["adequacy_p_value"] >= 0.01)
    known = {"one_sided", "sensor_bias", "inadequate"}
    assert all(f in known or f.startswith("prior_bound:") for f in result["flags"]), result["flags"]
    assert ("inadequate" in result["flags"]) == (not result["adequate"])
    assert [c["effect"] for c in result["candidates"]] == list(MODEL_IDS[1:])
    nt = result["next_test"]
    if nt is not None:
        assert {"specimen_id", "frequency_hz", "kind", "amplitudes_m", "expected_gain_bits", "predictions",
                "alternatives"} <= set(nt)
        if nt["kind"] == "hold_crown":   # one amplitude, at or below the pair's largest stand
            (amp,) = nt["amplitudes_m"]
            stands = [t.amplitude_m for t in campaign.tests.values() if not t.collapsed
                      and t.specimen_id == nt["specimen_id"] and abs(t.frequency_hz - nt["frequency_hz"]) < 1e-9]
            assert 0 < amp <= max(stands) + 1e-9 and set(nt["predicted_crown_m"]) == set(nt["predictions"])
        else:
            assert nt["kind"] == "afd_ramp", nt["kind"]
            a_from, a_to, a_by = nt["amplitudes_m"]
            assert 0 < a_by < a_from < a_to and within_limits(a_to, nt["frequency_hz"], TableLimits())
        assert set(nt["predictions"]) == set(result["rivals"] if result["adequate"]
                                             else credible_set(result["probabilities"]))
        assert nt["expected_gain_bits"] >= 0
    assert abs(sum(result["probabilities"].values()) - 1.0) < 1e-4
    assert set(result["probabilities"]) == set(MODEL_IDS)
    assert set(result["extended"]) == {"threshold_error_pct", "threshold_error_se_pct", "hinge_match"}
    for c in result["candidates"]:
        assert 0.0 <= c["probability"] <= 1.0 and c["cv_error_pct"] >= 0.0
    p = result["probabilities"]
    if result["verdict"] == "inconclusive":
        assert result["effects"] == [] and (result["rivals"] or not result["adequate"])
        if result["rivals"]:
            assert sum(p[m] for m in result["rivals"]) >= NAME_AT - 1e-9
    else:
        assert max(p.values()) >= NAME_AT and result["adequate"]
    assert p["friction"] >= 0.02, p
    report = (tmp_path / "first" / "report.md").read_text()
    assert report.count("Prior:") == 1
    # The generator's crown records of the tests that stood near the threshold entered the
    # probabilities, and the report says which and what they did.
    assert any("crown records of" in line for line in logs), logs
    assert "## Crown records in the probabilities" in report
    for png in ("thresholds.png", "probabilities.png"):
        assert (tmp_path / "first" / png).stat().st_size > 10_000
    # The posterior as model samples of the arch: as many as asked, parameters inside the
    # prior, and each model drawn about as often as its probability says (binomial, 4 sigma).
    rows = [line.split(",") for line in (tmp_path / "first" / "posterior_samples_W156.csv").read_text().splitlines()
            if not line.startswith("#")]
    assert rows[0] == ["sample", "model", "friction", "contact_inset_m", "thickness_m", "r_ext_m"]
    body = rows[1:]
    assert len(body) == settings.posterior_samples
    for r in body:
        friction, inset, t, r_ext = map(float, r[2:])
        assert 0.25 - 1e-9 <= friction <= 0.75 + 1e-9 and 0.0 <= inset <= 0.005 + 1e-9
        assert 0.85 * 0.071 - 1e-9 <= t <= 0.071 * 1.0 + 1e-9 or abs(t - 0.071) < 1e-9
        assert abs((r_ext - t / 2) - (0.508 - 0.071 / 2)) < 1e-6  # about the mean radius
    top = max(p, key=p.get)
    n_top = sum(r[1] == top for r in body)
    n = len(body)
    assert abs(n_top - n * p[top]) <= 4 * math.sqrt(n * p[top] * (1 - p[top])) + 1, (n_top, p[top])
    # Diagnosed twice: the same probabilities, nothing simulated again.
    assert any("0 threshold searches made" in line for line in again_logs), again_logs
    # ... and the next test's sweeps are the first run's (the same questions, not new ones).
    assert sorted(p.name for p in (tmp_path / "bank" / "next-test").glob("*")) == questions
    assert max(abs(p[m] - again["probabilities"][m]) for m in p) <= 0.01
    # The bank the diagnosis made is the one build_bank reads back: asked again, nothing is
    # simulated (a new frequency: test_a_new_frequency_simulates_that_frequency_only).
    spec = campaign.specimens["W156"]
    first = build_bank({"W156": spec}, {"W156": [1.25]}, {"W156": (1, 1, 1)}, settings, tmp_path / "bank",
                       tmp_path / "work")
    assert first.searches == 0 and first.specimens["W156"].frequencies_hz == [1.25]
    # One window for hinges, for the generator and the model: a model that names the
    # truth reproduces most of what the generator saw.
    assert result["baseline"]["hinge_match"] is not None


def test_a_new_frequency_simulates_that_frequency_only(tmp_path, monkeypatch):
    """The bank's cache holds one file per specimen and frequency: asked again, a bank is
    read, not made; asked at one more frequency, only that frequency is simulated; the
    merged bank holds both, the first frequency's thresholds to the bit, and a node refined
    at one frequency only holds MISSING at the other. The kernel is replaced here by a
    stand-in that records what it is asked to simulate (the end-to-end test makes and reads
    back a real bank), so the count of simulations is exact."""
    asked = []

    def stand_in(spec, freqs, cycles, settings, work):
        asked.append(list(freqs))
        f = freqs[0]
        made = bank_module.SpecimenBank(spec.specimen_id, list(freqs), tuple(cycles), [0.01 * f], 0.5, 1e-4,
                                        settings.dt_s)
        made.thresholds = {"nominal": [0.0123456789123 * f], f"node@{f:g}": [0.02 * f]}
        made.searches = 2
        return made

    monkeypatch.setattr(bank_module, "_simulate", stand_in)
    spec = Specimen("W156", 156.0, 13, 0.508, 0.071, 0.1, 1900.0, 0.5)
    settings = DiagnosisSettings(bin_dir=bin_dir(), log=lambda *_: None)

    def bank_at(freqs):
        return build_bank({"W156": spec}, {"W156": freqs}, {"W156": (1, 1, 1)}, settings, tmp_path / "bank",
                          tmp_path / "work")
    first, again, grown = bank_at([1.25]), bank_at([1.25]), bank_at([1.25, 2.5])
    assert asked == [[1.25], [2.5]]
    assert (first.searches, again.searches, grown.searches) == (2, 0, 2)
    merged, one = grown.specimens["W156"], first.specimens["W156"]
    assert merged.frequencies_hz == [1.25, 2.5]
    assert merged.thresholds["nominal"][0] == one.thresholds["nominal"][0] == float(f"{0.0123456789123 * 1.25:.9g}")
    assert merged.thresholds["node@1.25"] == [one.thresholds["node@1.25"][0], bank_module.MISSING]
    assert merged.thresholds["node@2.5"] == [bank_module.MISSING, 0.05]


def test_bank_refines_where_the_response_is_steep(tmp_path, monkeypatch):
    """Between neighbouring values of a single effect whose thresholds differ by more than
    REFINE_SPREADS x max(spread, 1 %), the bank simulates the midpoint, for
    settings.refine_rounds rounds. The kernel is replaced by a response known by hand: the
    threshold falls from 20 to 15 mm where the inset passes 3.5 mm, flat in every other
    effect, the same in every replica (spread 0, so the limit is 3 x 1 %). On the inset
    grid 0 (nominal), 2 and 5 mm, round 1 adds 3.5 mm (2 -> 5 mm differs by log(20/15) =
    0.29) and round 2 adds 2.75 mm (2 -> 3.5 mm); 3.5 -> 5 mm is flat. No rounds: no node."""
    def response(self, spec, freqs, cycles, variants, amp_max, amp_tol):
        out = {}
        for v in variants:
            inset = dict(v.parts()).get("contact_edges", 0.0)
            for f in freqs:
                out[(v, f)] = 0.015 if inset >= 0.0035 else 0.020
        return out

    monkeypatch.setattr(bank_module.Simulator, "thresholds_at", response)
    monkeypatch.setattr(bank_module, "onset_amplitudes", lambda runner, spec, freqs: [0.01 for _ in freqs])
    spec = Specimen("W156", 156.0, 13, 0.508, 0.071, 0.1, 1900.0, 0.5)
    grids = dict(inset_grid_m=(0.002, 0.005), friction_steps=(0.1,), thickness_factors=(0.94,),
                 pair_inset_m=(0.002,), pair_friction_steps=(-0.1,), pair_thickness_factors=(0.94,),
                 bracket_gaps_m=(0.0,))
    made = {}
    for rounds in (0, 1, 2):
        settings = DiagnosisSettings(bin_dir=bin_dir(), log=lambda *_: None, refine_rounds=rounds, **grids)
        b = bank_module._simulate(spec, [1.25], (1, 1, 1), settings, tmp_path / f"work{rounds}")
        made[rounds] = sorted(float(k.split("=")[1]) for k in b.thresholds
                              if k.startswith("contact_edges=") and "+" not in k)
    assert made[0] == [0.002, 0.005]
    assert made[1] == [0.002, 0.0035, 0.005]
    assert made[2] == [0.002, 0.00275, 0.0035, 0.005]
    # Below REFINE_MIN_STEP x 2 apart no midpoint, however steep; a value whose search found
    # no collapse beside one that did is steep.
    assert bank_module.refine_values("contact_edges", [0.0, 0.0004], {0.0: [0.02], 0.0004: [0.01]}, 0.0) == []
    assert bank_module.refine_values("contact_edges", [0.0, 0.002], {0.0: [0.02], 0.002: [math.nan]}, 0.0) == [0.001]
    assert bank_module.refine_values("friction", [0.4, 0.5], {0.4: [0.02], 0.5: [0.0203]}, 0.0) == []


def test_the_reports_figures_are_written_in_the_format_asked(tmp_path):
    """voussoir-diagnose run --format: report.md's figures as PDF or SVG, not only PNG."""
    from voussoir_post.diagnosis.figures import probabilities_figure
    probs = {"none": 0.6, "friction": 0.3, "geometry": 0.1}
    assert probabilities_figure(tmp_path, probs, "note", "pdf") == "probabilities.pdf"
    assert (tmp_path / "probabilities.pdf").read_bytes()[:4] == b"%PDF"
    assert probabilities_figure(tmp_path, probs, "note", "svg") == "probabilities.svg"
    assert b"<svg" in (tmp_path / "probabilities.svg").read_bytes()[:2000]
    assert probabilities_figure(tmp_path, probs, "note") == "probabilities.png"
    assert (tmp_path / "probabilities.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"



# ------------------------------------------------------------------ the build tolerance and what counts as a cause


def _power_law_bank(exponent: float, factors=(0.76, 0.82, 0.88, 0.94, 0.97, 0.985, 1.015, 1.03, 1.06, 1.12)):
    """A bank of one specimen at one frequency whose threshold is t0 f^exponent in the
    ring's thickness factor f (a smooth response, no replicas)."""
    from voussoir_post.diagnosis.bank import SpecimenBank
    t0 = 0.06
    sb = SpecimenBank("A156", [1.25], (1, 1, 1), [0.01], 1.0, 1e-4, 1e-3)
    sb.thresholds["nominal"] = [t0]
    for f in factors:
        sb.thresholds[f"geometry={f}"] = [t0 * f ** exponent]
    return sb


def test_the_tolerance_spread_and_the_material_threshold_follow_a_smooth_response():
    """On a threshold t0 f^b, a thickness factor 1 + e with e ~ N(0, s^2) moves log t by
    b log(1 + e): its root mean square (by quadrature of the normal law, apart from the
    code's Gauss-Hermite rule) is the tolerance spread; the material threshold is the
    larger of 5 % and twice it; and a ring of factor 0.9 moves log t by |b log 0.9|."""
    from scipy.integrate import quad
    from voussoir_post.diagnosis.bank import Bank
    from voussoir_post.diagnosis.models import effect_sizes, material_threshold, tolerance_spread
    from voussoir_post.readers.campaign import Specimen
    spec = Specimen("A156", 156.0, 13, 0.508, 0.071, 0.145, 700.0, 0.5)
    for b, s in ((1.5, 0.015), (4.0, 0.015), (4.0, 0.03)):
        sb = _power_law_bank(b)
        expect = math.sqrt(quad(lambda z: (b * math.log1p(s * z)) ** 2 * norm.pdf(z), -8, 8)[0])
        got = tolerance_spread(sb, spec, 1.25, s)
        assert got == pytest.approx(expect, rel=0.03), (b, s, got, expect)
        assert tolerance_spread(sb, spec, 1.25, 0.0) == 0.0
        obs = Observations("t", {"A156": spec}, [PairObservation("A156", 1.25, 0.05, 0.06)], {}, build_tolerance=s)
        bank = Bank({"A156": sb}, "synthetic")
        least = material_threshold(bank, obs, obs.pairs[0])
        assert least == pytest.approx(max(0.05, 2.0 * expect), rel=0.03)
        size = effect_sizes(bank, obs, ("geometry",), [np.array([0.9])])[0, 0]
        assert size == pytest.approx(abs(b * math.log(0.9)) / least, rel=0.03)


def test_an_advised_ramp_is_written_in_whole_half_millimetres():
    """The amplitudes a laboratory is told to command are multiples of 0.5 mm, printed
    without float noise (0.051, not 0.051000000000000004), whatever the rivals' spread."""
    from voussoir_post.diagnosis.next_test import ramp
    rng = np.random.default_rng(3)
    for _ in range(200):
        amps = ramp(list(np.log(rng.uniform(0.01, 0.2, 3))), list(rng.uniform(0.01, 0.2, 3)))
        for a in amps:
            assert a >= 5e-4 and repr(a) == repr(round(a, 4)), amps
            assert abs(a / 5e-4 - round(a / 5e-4)) < 1e-9, amps


def test_a_failed_check_still_asks_for_the_test_that_separates_the_most_probable_models():
    """No rivals when the catalogue explains nothing, but the laboratory still gets advice:
    the test that separates the models the rivals would have been (0.5 + 0.3 + 0.15
    first reach 0.9); none when a cause is named."""
    probs = {"none": 0.05, "friction": 0.5, "geometry": 0.3, "contact_edges": 0.15}
    failed = Decision("inconclusive", [], [], False, 0.001, "friction", probs)
    assert to_separate(failed) == ["friction", "geometry", "contact_edges"]
    passed = Decision("inconclusive", [], ["friction", "geometry"], True, 0.4, "friction", probs)
    assert to_separate(passed) == ["friction", "geometry"]
    named = Decision("friction", ["friction"], [], True, 0.4, "friction", {"friction": 0.95, "none": 0.05})
    assert to_separate(named) == []
