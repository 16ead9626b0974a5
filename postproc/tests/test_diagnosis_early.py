"""A ramp's first collapse may be early or late (diagnosis/early.py, likelihood.py): the
bracket's term against a Monte Carlo of its story, the rule against a hand-worked scan, the
kernel against another code on where ramps fall early, and the constants against the rule
on LMGC90's fine scans (bench/lmgc90/collapse_scan.py, stored) sorted by the kernel's."""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.special import ndtr

from collapse_windows import early_rule
from conftest import bin_dir
from independent_campaigns import ARCHES
from voussoir_post.diagnosis import early as E
from voussoir_post.diagnosis import likelihood as L
from voussoir_post.diagnosis import next_test as N
from voussoir_post.diagnosis.early import early_fractions, early_key, ramp_depths
from voussoir_post.diagnosis.settings import DiagnosisSettings

SCANS = Path(__file__).parent / "data" / "lmgc90" / "collapse_scan.json"
BANK_SCANS = Path(__file__).parent / "data" / "replay" / "bank_scans.json"
PROB = (E.EARLY_PROB_ROUGH, E.LATE_PROB_ROUGH)  #: a rough pair's
CENTRE = L.SHIFTS.size // 2  #: the column of SHIFTS at no shift


# ---------------------------------------------------------------- the bracket's term


def _story_probability(lo, hi, m, s, rng, n=400_000):
    """P(the ramp's first collapse lies in (lo, hi]) by drawing the story, written here from
    the docstrings: an outlier (log t uniform within a factor OUTLIER_FACTOR of m) or
    log t ~ N(m, s^2); then the first collapse is early with probability PROB[0] (at
    log t - u, u uniform on (0, EARLY_SPAN)), late with PROB[1] (at log t + u, u uniform on
    (0, LATE_SPAN)), else at log t."""
    half = math.log(L.OUTLIER_FACTOR)
    out = rng.random(n) < L.OUTLIER_PROB
    logt = np.where(out, m + rng.uniform(-half, half, n), m + s * rng.standard_normal(n))
    story = rng.random(n)
    first = np.where(story < PROB[0], logt - rng.uniform(0.0, E.EARLY_SPAN, n),
                     np.where(story < PROB[0] + PROB[1], logt + rng.uniform(0.0, E.LATE_SPAN, n), logt))
    return float(np.mean((first > lo) & (first <= hi)))


@pytest.mark.parametrize("shift,s,width", [(0.0, 0.05, 0.04), (0.10, 0.03, 0.04), (0.25, 0.03, 0.04),
                                           (-0.08, 0.04, 0.06), (-0.15, 0.03, 0.04), (0.12, 0.05, 0.30)])
def test_a_brackets_term_is_the_probability_its_story_gives(shift, s, width):
    """specimen_log_tables for one two-sided bracket (lo, hi] at a rough pair, a model at
    hi + shift: the probability a Monte Carlo of the story gives, within 4 standard errors.
    A model whose threshold lies 10 % above the ramp's collapse, or 15 % below it, keeps the
    early or late story's share instead of the normal tail alone."""
    rng = np.random.default_rng(7)
    hi = math.log(0.012)
    lo = hi - width
    m = hi + shift
    term = L.bracket_terms(SimpleNamespace(low_m=math.exp(lo), high_m=math.exp(hi)), stands_unreported=False)
    outlier = [L._log_outlier(term[0][0], term[0][1], m + L.SHIFTS[None, :])]
    table = L.specimen_log_tables([SimpleNamespace(specimen_id="A")], [term], np.array([[m]]), np.array([[s * s]]),
                                  outlier, tau_pair=0.0, early_prob=[PROB])["A"]
    p = _story_probability(lo, hi, m, s, rng)
    se = math.sqrt(p * (1 - p) / 400_000)
    assert math.exp(float(table[0, CENTRE])) == pytest.approx(p, abs=4 * se + 1e-6)
    if 0.05 < shift < 0.15 and width < E.EARLY_SPAN:
        assert p > 0.3 * PROB[0] * width / E.EARLY_SPAN
    if -0.2 < shift < -0.1:
        assert p > 0.3 * PROB[1] * width / E.LATE_SPAN


@pytest.mark.parametrize("shift,s", [(0.10, 0.03), (-0.05, 0.06), (0.30, 0.04)])
def test_a_pair_of_collapse_rows_only_mixes_the_story_over_its_unreported_steps(shift, s):
    """A pair whose stands went unreported: its term is the weighted sum, over the ramp
    steps bracket_terms gives, of each bracket's story (drawn here) with the outlier's, within
    4 standard errors of that Monte Carlo."""
    rng = np.random.default_rng(8)
    hi = math.log(0.012)
    m = hi + shift
    terms = L.bracket_terms(SimpleNamespace(low_m=0.0, high_m=math.exp(hi)), stands_unreported=True)
    assert len(terms) > 1
    table = L.specimen_log_tables([SimpleNamespace(specimen_id="A")], [terms], np.array([[m]]), np.array([[s * s]]),
                                  [None], tau_pair=0.0, early_prob=[PROB])["A"]
    ps = [_story_probability(lo, hi, m, s, rng) for lo, _, _ in terms]
    want = sum(math.exp(w) * p for (_, _, w), p in zip(terms, ps))
    se = math.sqrt(sum(math.exp(2 * w) * p * (1 - p) / 400_000 for (_, _, w), p in zip(terms, ps)))
    assert math.exp(float(table[0, CENTRE])) == pytest.approx(want, abs=4 * se + 1e-6)


def test_shifted_masses_over_a_ramps_steps_add_to_one():
    """An early (or late) collapse falls in some step of the ramp: the masses of steps that
    tile the line add to 1, wherever the threshold lies (at every column of the shifts)."""
    edges = np.log(0.012) + 0.03 * np.arange(-70, 71)
    for m, s in [(np.log(0.012), 0.02), (np.log(0.013), 0.08)]:
        base, sd = np.array([[m]]), np.array([[s]])
        for prob in ((1.0, 0.0), (0.0, 1.0)):
            total = sum(L._shifted_term(a, L._end_ramps(b, base, sd, prob), base, sd, prob)
                        for a, b in zip(edges[:-1], edges[1:]))
            assert np.allclose(total, 1.0, atol=1e-9)


def test_the_advices_outcome_law_is_the_storys(rng=np.random.default_rng(11)):
    """next_test's law of a ramp's first collapse (_ramp_cdf) against a Monte Carlo of the
    same story as the likelihood's, drawn here: at x from a span below the threshold to a
    span above, within 4 standard errors; without early or late collapses, the normal CDF."""
    m, s, n = math.log(0.012), 0.04, 400_000
    logt = m + s * rng.standard_normal(n)
    story = rng.random(n)
    first = np.where(story < PROB[0], logt - rng.uniform(0.0, E.EARLY_SPAN, n),
                     np.where(story < PROB[0] + PROB[1], logt + rng.uniform(0.0, E.LATE_SPAN, n), logt))
    xs = m + np.linspace(-E.EARLY_SPAN - 2 * s, E.LATE_SPAN + 2 * s, 15)
    got = N._ramp_cdf(xs, np.array(m), np.array(s), PROB)
    want = np.array([np.mean(first <= x) for x in xs])
    assert np.all(np.abs(got - want) <= 4 * np.sqrt(want * (1 - want) / n) + 1e-6), (got, want)
    assert N._ramp_cdf(np.array([-np.inf, np.inf]), np.array(m), np.array(s), PROB).tolist() == [0.0, 1.0]
    assert np.allclose(N._ramp_cdf(xs, np.array(m), np.array(s), (0.0, 0.0)), ndtr((xs - m) / s), atol=1e-15)


def test_a_ramp_at_a_rough_pair_is_expected_to_tell_less():
    """Two rivals 10 % apart: a ramp where first collapses may be early or late is a noisier
    reading of the same threshold, so its expected information is smaller (and a ramp's
    outcome law still sums to 1)."""
    args = ([0.5, 0.5], [math.log(0.030), math.log(0.033)], [0.02, 0.02])
    smooth = N.expected_gain_bits(*args)
    rough = N.expected_gain_bits(*args, early=PROB)
    assert 0.0 < rough < 0.9 * smooth
    _, py_m = N._outcome_laws(*args, N.RAMP_STEP, None, PROB)
    assert np.allclose(py_m.sum(axis=1), 1.0, atol=1e-6)


# ---------------------------------------------------------------- the rule and the scans


def test_the_rule_on_a_scan_worked_by_hand():
    """A scan that stands to index 9, falls at 10 (a window one amplitude wide), stands to
    19 and falls from 20 on. By hand: the search finds 10 from the one phase of four that
    lands on it (2, 6, 10) and 20 from the other three (bisection from 16, 17 or 19 up to
    20, 21 or 23 ends at 20); the nine ramps (steps 2, 3, 4 at every phase) first fall at 10
    (step 2 phase 0, step 3 phase 1, step 4 phase 2), 20 (step 3 phase 2, step 4 phase 0),
    21 (step 2 phase 1, step 3 phase 0, step 4 phase 1) or 23 (step 4 phase 3). Early: the
    three at 10 against each search that found 20, 9 of 36, each 10 grid steps deep. Late
    against the search that found 10, the six that stepped over it by a step or more: 20,
    20, 21, 21, 21, 23, of steps 3, 4, 2, 3, 4, 4, all a step or more above 10; against the
    searches at 20, the one at 23 (step 4, phase 3) is under a step above: none. A monotone
    scan has neither; a scan that does not bracket is not read."""
    scan = [False] * 10 + [True] + [False] * 9 + [True] * 10
    n, early, late = ramp_depths(scan, 0.015)
    assert n == 36
    assert early == pytest.approx([10 * math.log(1.015)] * 9)
    assert sorted(late) == pytest.approx(sorted(k * math.log(1.015) for k in (10, 10, 11, 11, 11, 13)))
    assert ramp_depths([False] * 20 + [True] * 10, 0.015) == (36, [], [])
    assert ramp_depths([True] * 30, 0.015) == (0, [], [])
    assert ramp_depths([False] * 30, 0.015) == (0, [], [])


@pytest.fixture(scope="module")
def kernel_scans(tmp_path_factory):
    """The kernel's scans (early.early_fractions, the diagnosis's own path) of the nominal
    test arches at the pairs LMGC90 scanned, about the same reference thresholds."""
    scan = json.loads(SCANS.read_text())
    settings = DiagnosisSettings(bin_dir=bin_dir(), n_ranks=2, log=lambda m: None)
    work = tmp_path_factory.mktemp("early")
    refs = {}
    for r in scan["rows"]:
        refs.setdefault(r["specimen_id"], {})[r["frequency_hz"]] = r["reference_m"]
    out = {}
    for a in ARCHES:
        if a.specimen_id not in refs:
            continue
        spec = a.specimen()
        freqs = sorted(refs[a.specimen_id])
        found = early_fractions(spec, freqs, [refs[a.specimen_id][f] for f in freqs], (1, 1, 1), settings,
                                work / "cache", work / "runs")
        out.update({early_key(a.specimen_id, f): d for f, d in found.items()})
    return out


def test_the_kernels_scans_bracket_their_thresholds_and_sort_the_stored_banks_pairs_alike(kernel_scans):
    """Every scan of the nominal arch stands at 0.7 of its threshold and falls at 1.35; the
    stored bank's scans (tests/data/replay/bank_scans.json, which the replay tests read)
    sort its six pairs as the live scans do."""
    assert len(kernel_scans) == 10
    for d in kernel_scans.values():
        assert not d["collapsed"][0] and d["collapsed"][-1], d
        assert d["fraction"] is not None
    stored = json.loads(BANK_SCANS.read_text())["rows"]
    assert len(stored) == 6
    for r in stored:
        live = kernel_scans[early_key(r["specimen_id"], r["frequency_hz"])]["fraction"]
        assert (r["fraction"] > 0) == (live > 0), r


def test_the_kernel_sees_where_lmgc90s_ramps_fall_early_and_the_constants_are_the_rule(kernel_scans):
    """Where the kernel's own scan of the nominal arch has an early ramp, LMGC90's ramps on
    eight truths (effects and faults of their own) fall early ten times as often as where it
    has none, on at least 60 scans that bracket, with windows in at least 10: a kernel that
    saw no windows, or saw them at other pairs, fails. The constants of early.py are the
    rule's, the rates rounded to 0.01 and the spans up to a step of the likelihood's shifts."""
    scan = json.loads(SCANS.read_text())
    assert scan["made_by"].startswith("bench/lmgc90/collapse_scan.py")
    rule = early_rule(scan, {k: d["fraction"] for k, d in kernel_scans.items()})
    assert sum(rule["pairs"].values()) >= 60 and rule["unusable"] <= 0.2 * len(scan["rows"])
    assert rule["with_early"]["rough"] >= 10 and rule["pairs"]["smooth"] >= 20
    assert rule["early"]["rough"] > 10 * rule["early"]["smooth"]
    r2 = lambda x: round(x, 2)  # noqa: E731
    assert (E.EARLY_PROB_ROUGH, E.EARLY_PROB_SMOOTH, E.EARLY_PROB_UNKNOWN) == tuple(
        r2(rule["early"][c]) for c in ("rough", "smooth", "unknown"))
    assert (E.LATE_PROB_ROUGH, E.LATE_PROB_SMOOTH, E.LATE_PROB_UNKNOWN) == tuple(
        r2(rule["late"][c]) for c in ("rough", "smooth", "unknown"))
    up = lambda x: round(math.ceil(x / E.SPAN_STEP - 1e-9) * E.SPAN_STEP, 9)  # noqa: E731
    assert (E.EARLY_SPAN, E.LATE_SPAN) == (up(rule["early_span"]), up(rule["late_span"]))
    assert E.SPAN_STEP == pytest.approx(L.SHIFTS[1] - L.SHIFTS[0], abs=1e-12)


def test_the_advice_reads_each_tested_pairs_ramp_by_its_class(monkeypatch, tmp_path):
    """A replayed campaign on the stored bank (its kernel scans read as the replay tests read
    them): next_test scores the repeat of each tested pair with that pair's class, the rough
    rates where the stored scan of the pair has early ramps and the smooth ones where not;
    an advice blind to the class scores every pair alike."""
    from replay_maps import draw_observations, load_map
    from test_diagnosis import DATA, stored_bank
    from voussoir_post.diagnosis.posterior import infer
    from voussoir_post.readers.campaign import TableLimits

    bank = stored_bank()
    rough = {k for k, x in bank.early.items() if x}
    assert rough and len(rough) < len(bank.early), "the stored scans should hold rough and smooth pairs"
    obs = draw_observations(load_map(DATA / "maps" / "chamfer_3mm.json"), np.random.default_rng(5))
    post = infer(bank, obs)
    seen = {}
    laws = N._outcome_laws

    def spy(probabilities, means, sds, step, within, early=(0.0, 0.0)):
        if within is not None:
            seen[round(math.exp(within[1]), 9)] = tuple(early)
        return laws(probabilities, means, sds, step, within, early)

    monkeypatch.setattr(N, "_outcome_laws", spy)
    settings = DiagnosisSettings(bin_dir=bin_dir(), n_ranks=1, log=lambda m: None, probe_frequencies_hz=())
    rivals = sorted(post.probabilities, key=lambda m: -post.probabilities[m])[:3]
    N.next_test(post, obs, rivals, settings, tmp_path, TableLimits(), holds=False)
    want = {round(p.high_m, 9): (E.EARLY_PROB_ROUGH, E.LATE_PROB_ROUGH)
            if early_key(p.specimen_id, p.frequency_hz) in rough else (E.EARLY_PROB_SMOOTH, E.LATE_PROB_SMOOTH)
            for p in post.pairs if math.isfinite(p.high_m)}
    assert want and seen == want
