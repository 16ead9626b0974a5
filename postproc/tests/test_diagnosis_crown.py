"""Crown records in the probabilities (diagnosis/crown.py) and the test held for them
(next_test.py, kind hold_crown): the law against closed forms, the evidence against
records made by another code (LMGC90, stored by bench/lmgc90/crown_records.py), the
factor with a stand-in simulator, and the hold's expected information against the
mutual information's closed forms."""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.integrate import quad

from conftest import bin_dir
from voussoir_post.diagnosis import crown
from voussoir_post.diagnosis.crown import FLOOR_M, SCALE_KNOTS, crown_log_factors, crown_scale, crown_tests, log_terms
from voussoir_post.diagnosis.effects import Variant
from voussoir_post.diagnosis.next_test import hold_gain_bits
from voussoir_post.diagnosis.observations import PairObservation
from voussoir_post.diagnosis.settings import DiagnosisSettings
from voussoir_post.diagnosis.simulator import FALLEN_PEAK_M, Simulator
from voussoir_post.readers.campaign import Campaign, Record, Specimen
from voussoir_post.readers.campaign import Test as CampaignTest

STORED = Path(__file__).parent / "data" / "lmgc90" / "crown_records.json"
#: The same truths at the campaigns' pairs, LMGC90 held at fractions of a laboratory ramp's
#: bracket (crown_records.py --ramp-brackets), as the diagnosis reads a record's fraction.
STORED_RAMP = Path(__file__).parent / "data" / "lmgc90" / "crown_records_ramp.json"


def t3_pdf(z):
    """Student t of 3 degrees of freedom, by hand."""
    return 2.0 / (math.pi * math.sqrt(3.0) * (1.0 + z * z / 3.0) ** 2)


#: The t's 95th percentile at 3 degrees of freedom (tables).
t3_ppf_95 = 2.353363


def t3_cdf(z):
    return 0.5 + (z / (math.sqrt(3.0) * (1.0 + z * z / 3.0)) + math.atan(z / math.sqrt(3.0))) / math.pi


# ---------------------------------------------------------------- the law


def test_the_law_above_the_floor_is_a_student_t_of_the_log_peak():
    for measured, simulated, s in ((2e-3, 3e-3, 0.1), (5e-3, 1e-3, 0.31), (1e-3, 2e-4, 0.5)):
        z = (math.log(measured) - math.log(max(simulated, FLOOR_M))) / s
        assert log_terms(measured, [simulated], s)[0] == pytest.approx(math.log(t3_pdf(z) / s), rel=1e-10)


def test_a_peak_below_the_floor_is_censored_and_the_law_sums_to_one():
    s, sim = 0.2, 8e-4
    censored = math.exp(log_terms(1e-4, [sim], s)[0])
    assert censored == pytest.approx(t3_cdf((math.log(FLOOR_M) - math.log(sim)) / s), rel=1e-10)
    # Every measured peak below the floor has the same likelihood: the transducer cannot tell them apart.
    assert log_terms(4e-4, [sim], s)[0] == log_terms(1e-5, [sim], s)[0]
    # The censored mass and the density above the floor (in log peak) make one law.
    above, _ = quad(lambda y: math.exp(log_terms(math.exp(y), [sim], s)[0]), math.log(FLOOR_M), math.log(FLOOR_M) + 60)
    assert censored + above == pytest.approx(1.0, abs=1e-6)


def test_the_scale_widens_towards_the_threshold():
    assert crown_scale(0.5) == SCALE_KNOTS[0][1]
    assert crown_scale(0.925) == pytest.approx(0.5 * (SCALE_KNOTS[0][1] + SCALE_KNOTS[1][1]))
    assert crown_scale(1.0) == SCALE_KNOTS[-1][1]


# ---------------------------------------------------------------- against another code


def _stored_rows():
    return json.loads(STORED.read_text())["rows"]


def _log_err(r, which="own"):
    sim = max(np.mean(r[f"{which}_peaks_mm"]) * 1e-3, FLOOR_M)
    return math.log(max(r["lmgc90_peak_mm"] * 1e-3, FLOOR_M) / sim)


def _usable(rows, fraction, rival=True):
    """The records of truths inside the catalogue at `fraction` where LMGC90 and the own
    model stood (and the rival too, unless rival=False)."""
    return [r for r in rows if r["model"] != "outside" and abs(r["fraction"] - fraction) < 1e-9
            and not (r["lmgc90_collapsed"] or r["own_collapsed"] or (rival and r["rival_collapsed"]))]


def _robust(x):
    x = np.asarray(x, float)
    return 1.4826 * float(np.median(np.abs(x - np.median(x))))


def _records_llr(rows, law, scale):
    """log p(LMGC90's records | the own model) - log p(... | the rival) over `rows`, each
    record's simulated peak the mean of its runs, under `law` of scale `scale`."""
    return sum(float(law(1e-3 * r["lmgc90_peak_mm"], [1e-3 * np.mean(r["own_peaks_mm"])], scale)[0]
                     - law(1e-3 * r["lmgc90_peak_mm"], [1e-3 * np.mean(r["rival_peaks_mm"])], scale)[0])
               for r in rows)


def _llr(rows, fraction, law=log_terms):
    """Per truth: log p(LMGC90's records | its own model) - log p(... | the closest rival by
    thresholds), the law's scale calibrated (as SCALE_KNOTS) to the coverage of the OTHER
    truths' cross-code errors."""
    use = _usable(rows, fraction)
    out = {}
    for slug in sorted({r["slug"] for r in use}):
        mine = [r for r in use if r["slug"] == slug]
        scale = max(float(np.quantile(np.abs([_log_err(r) for r in use if r["slug"] != slug]), 0.9, method="higher"))
                    / t3_ppf_95,
                    0.02)
        out[slug] = _records_llr(mine, law, scale)
    return out


def _parts(rows, fraction):
    """The truths whose records can part their own model from its rival: the median over
    the truth's records of |log rival / own| exceeds the median of |log LMGC90 / own|
    (the rivals differ by more than the codes do; worked from the records alone)."""
    use = _usable(rows, fraction)
    out = set()
    for slug in {r["slug"] for r in use}:
        mine = [r for r in use if r["slug"] == slug]
        err = np.median([abs(_log_err(r)) for r in mine])
        diff = np.median([abs(_log_err(r, "rival") - _log_err(r)) for r in mine])
        if diff > err:
            out.add(slug)
    return out


def test_another_codes_records_favour_the_truths_own_model_and_none_is_confidently_wrong():
    """LMGC90's crown records of twenty-one truths inside the catalogue (three nominal
    arches, four rings, two frictions, and twelve with pivots set in, brackets or a second
    effect: eight of them with pivots), held at 0.9 of each threshold, judged between the
    truth's own model and the catalogue model closest to it by thresholds (what the
    thresholds cannot part), the scale from the other truths' records: wherever the
    records can part the two (`_parts`: the rivals' records differ by more than the codes'
    do), the law must favour the truth; and it must exclude no truth's own model at odds
    beyond e^5. (Where they cannot part them, the rival is nearly the same arch, t06's,
    t07's and t153's among them, and the sign of a log ratio near 0 is not a verdict; a
    first version asked for all but one of nine truths, on records made at the
    campaign's offset rather than at each model's own threshold at the pair. The own
    model of a truth with brackets is on the truth's side: t158's mirror, brackets on the
    left, fits its thresholds as well and sat at -10.9.)"""
    rows = _stored_rows()
    llr = _llr(rows, 0.9)
    parted = _parts(rows, 0.9)
    assert len(llr) >= 20 and len(parted) >= 12, (sorted(llr), sorted(parted))
    assert all(llr[s] > 0 for s in parted), {s: llr[s] for s in parted}
    assert min(llr.values()) > -5.0, llr


def _normal_law(measured, simulated, s):
    """The mutation of log_terms the floor tests must catch: a normal law of scale s."""
    loc = np.log(np.maximum(np.asarray(simulated, float), FLOOR_M))
    return -0.5 * ((math.log(max(measured, FLOOR_M)) - loc) / s) ** 2 - math.log(s)


def _llr_at_knots(rows, law=log_terms, knots=SCALE_KNOTS):
    """Per knot, per truth: log p(LMGC90's records | own) - log p(... | the closest rival),
    under `law` at the knot's scale."""
    out = {}
    for fraction, scale in knots:
        use = _usable(rows, fraction)
        out[fraction] = {slug: _records_llr([r for r in use if r["slug"] == slug], law, scale)
                         for slug in sorted({r["slug"] for r in use})}
    return out


def test_records_held_at_a_ramps_bracket_exclude_no_truths_own_model():
    """The diagnosis reads a record's fraction from the bracket of the laboratory's ramp,
    not from a bisection's first collapse; a ramp can step over a window where the arch
    stands above its first collapse, and its bracket is some per cent wide. On LMGC90's
    records held that way (the stored ramp file: the twenty-one truths at the campaigns'
    pairs, 2 mm ramps), the law as calibrated, at each knot's own scale, must exclude no
    truth's own model at odds beyond e^5, as on the records held at the bisection's
    threshold. At the knots of 0.9 and 0.95: at 0.98 a 2 mm bracket (3 to 8 % of these
    thresholds) spans the cliff, which the law integrates over (its nodes) and this point
    comparison does not (there the nominal t03 rocked 24 and 36 mm at two pairs where its
    own model, at 0.98 of its own threshold, rocked 0.7 and 1.6: -5.3; docs/diagnosis.md)."""
    rows = json.loads(STORED_RAMP.read_text())["rows"]
    assert all(r["campaign_pair"] for r in rows) and len({r["slug"] for r in rows}) >= 20
    llr = _llr_at_knots(rows, knots=SCALE_KNOTS[:2])
    assert all(len(v) >= 20 for v in llr.values()), {f: len(v) for f, v in llr.items()}
    assert min(min(v.values()) for v in llr.values()) > -5.0, llr


def test_a_normal_law_in_its_place_is_confidently_wrong_on_the_ramps_records():
    """The mutation the previous test must catch: a normal law of the same scales. (A t
    law four times narrower is not: its tails cap what one record costs, -4.8 at most.)"""
    rows = json.loads(STORED_RAMP.read_text())["rows"]
    llr = _llr_at_knots(rows, _normal_law, SCALE_KNOTS[:2])
    assert min(min(v.values()) for v in llr.values()) < -5.0


def test_a_normal_law_in_its_place_is_confidently_wrong_on_the_same_records():
    """The mutation the previous test must catch: the same records under a normal law of
    the same scale exclude a truth's own model at odds beyond e^5."""
    assert min(_llr(_stored_rows(), 0.9, _normal_law).values()) < -5.0


def test_the_laws_90_percent_interval_holds_90_percent_of_the_codes_disagreements():
    """At each knot, the law's central 90 % interval (the t's 95th percentile, 2.353, times
    the scale) holds at least 90 % of the cross-code errors of the stored records, in
    every leave-one-truth-out set (the law must not claim more agreement between codes
    than the records show). The records are those where LMGC90 and the own model both
    stood (the rival has no part in the cross-code error)."""
    rows = _stored_rows()
    for fraction, scale in SCALE_KNOTS:
        use = _usable(rows, fraction, rival=False)
        for slug in sorted({r["slug"] for r in use}):
            errors = np.abs([_log_err(r) for r in use if r["slug"] != slug])
            assert np.mean(errors <= t3_ppf_95 * scale + 1e-12) >= 0.9, (fraction, slug, scale)


def _cliff_shifts(rows):
    """(slug, |log(f' / f)|) of every stored record of a truth inside the catalogue: f' is
    the fraction of its own threshold at which Voussoir's own model reaches the peak
    LMGC90 reached at f. Voussoir's curve: the geometric mean of its three runs at 0.9,
    0.95 and 0.98 (floored at 0.5 mm, a fall 100 mm), kept non-decreasing, from the floor
    at 0.8 to a fall at 1.0, linear in log peak between. No shift where the two peaks lie
    within 0.3 in log (the log law's business); a record at the floor where Voussoir
    already rocks shifts to the last fraction Voussoir spends at the floor."""
    floor, fall = math.log(0.5), math.log(100.0)
    by_pair = {}
    for r in rows:
        if r["model"] != "outside":
            by_pair.setdefault((r["slug"], r["specimen_id"], r["frequency_hz"]), {})[r["fraction"]] = r
    out = []
    for (slug, _, _), at in by_pair.items():
        fs = sorted(at)
        own = np.maximum.accumulate([
            fall if at[f]["own_collapsed"] else
            max(float(np.mean(np.log(np.maximum(at[f]["own_peaks_mm"], 0.5)))), floor) for f in fs])
        xs, ys = [0.8, *fs, 1.0], [floor, *own, fall]
        for f, mine in zip(fs, own):
            lab = fall if at[f]["lmgc90_collapsed"] else math.log(max(at[f]["lmgc90_peak_mm"], 0.5))
            if abs(mine - lab) < 0.3:
                shift = f
            elif lab <= floor:
                shift = max(x for x, y in zip(xs, ys) if y <= floor)
            else:
                shift = float(np.interp(lab, ys, xs))
            out.append((slug, abs(math.log(shift / f))))
    return out


def test_the_cliff_spread_holds_90_percent_of_the_codes_shifts_and_no_more_than_it_must():
    """CLIFF_SPREAD against the stored records (worked here from the records, not from
    crown.py): a normal of that spread holds (1.645 spreads) the 90th percentile of the
    cross-code shift of the fraction in every leave-one-truth-out set, and the largest of
    those percentiles is at least 0.9 of it (a spread twice too wide fails)."""
    shifts = _cliff_shifts(_stored_rows())
    slugs = sorted({s for s, _ in shifts})
    assert len(slugs) >= 8 and len(shifts) >= 150
    q90 = [float(np.quantile([x for s, x in shifts if s != out], 0.9)) for out in slugs]
    assert max(q90) <= 1.645 * crown.CLIFF_SPREAD, q90
    assert max(q90) >= 0.9 * 1.645 * crown.CLIFF_SPREAD, q90


# ---------------------------------------------------------------- which records enter


def _campaign(tests: list[CampaignTest], peaks: dict[str, float]) -> Campaign:
    spec = Specimen("A", 180.0, 9, 0.5, 0.05, 0.1, 2000.0)
    t = np.linspace(0.0, 2.0, 201)
    records = {tid: Record(tid, "", t, np.zeros_like(t), crown_dx_m=p * np.cos(7 * t)) for tid, p in peaks.items()}
    return Campaign("c", {"A": spec}, {x.test_id: x for x in tests}, records)


def _test(tid, f, amp, outcome="stand"):
    return CampaignTest(tid, "A", "afd", outcome, frequency_hz=f, amplitude_m=amp)


def test_the_records_that_enter_are_one_per_pair_that_stood_near_a_two_sided_threshold():
    pairs = [PairObservation("A", 2.0, 0.040, 0.042), PairObservation("A", 3.0, 0.0, 0.030),
             PairObservation("A", 4.0, 0.020, 0.021)]
    tests = [_test("near", 2.0, 0.036), _test("lower", 2.0, 0.035), _test("low", 2.0, 0.020),
             _test("fell", 2.0, 0.042, "collapse"), _test("one_sided", 3.0, 0.027), _test("top", 2.0, 0.040),
             _test("other", 4.0, 0.020)]
    c = _campaign(tests, {t.test_id: 2e-3 for t in tests})
    chosen = crown_tests(c, pairs)
    # 2 Hz: "near" and "lower" (0.878 and 0.854 of the bracket's midpoint) have the same,
    # narrowest law, "near" the higher fraction;
    # "top" stood at 0.976 of it (a wider law); 3 Hz has no stand below its
    # collapse; 4 Hz's only record (0.976) enters after the narrower law.
    assert [x.test.test_id for x in chosen] == ["near", "other"]
    near = chosen[0]
    assert near.fraction == pytest.approx(0.036 / 0.041)
    assert near.scale == pytest.approx(crown_scale(0.036 / 0.041)) == SCALE_KNOTS[0][1]
    assert near.peak_m == pytest.approx(2e-3, rel=1e-3)
    # The bracket: its geometric centre and its width in log.
    assert near.centre == pytest.approx(0.036 / math.sqrt(0.040 * 0.042))
    assert near.width == pytest.approx(math.log(0.042 / 0.040))


# ---------------------------------------------------------------- the factor, with a stand-in simulator


class StandIn:
    """Returns, for each job, the crown peak a variant's value sets [m], and keeps the
    jobs it was asked."""

    def __init__(self, peak_of):
        self.peak_of, self.jobs = peak_of, []

    def peaks(self, jobs, cache=None):
        self.jobs += jobs
        return [self.peak_of(v) for _, _, v, _ in jobs]


def _post(models):
    """A posterior of one pair: each model a grid of thickness factors with its weights
    and log thresholds."""
    out = {}
    for m, (values, weights, mu, prob) in models.items():
        grid = SimpleNamespace(names=("geometry",), values=[np.array(values, float)], mu=np.array(mu, float)[:, None])
        out[m] = SimpleNamespace(grid=grid, weights=np.array(weights, float), log_evidence=0.0, log_lik=None,
                                 probability=prob)
    # The pair's simulator and build-tolerance spreads: 0.03 and 0.04, 0.05 together.
    scales = SimpleNamespace(sigma_sim=np.array([0.03]), sigma_tol=np.array([0.04]))
    return SimpleNamespace(models=out, probabilities={m: v[3] for m, v in models.items()}, scales=scales)


def _draws(mp, k):
    return [int(np.argmax(mp.weights))] * k


def test_the_factor_favours_the_model_whose_draws_rock_as_measured():
    pair = PairObservation("A", 2.0, 0.040, 0.042)
    held = _test("held", 2.0, 0.037)
    c = _campaign([held], {"held": 3e-3})
    tests = crown_tests(c, [pair])
    post = _post({"ring": ([0.9], [1.0], [math.log(0.050)], 0.5), "pivots": ([0.95], [1.0], [math.log(0.060)], 0.4999),
                  "rare": ([1.1], [1.0], [math.log(0.040)], 1e-6)})
    sim = StandIn(lambda v: {0.9: 3e-3, 0.95: 8e-4}[dict(v.parts())["geometry"]])
    obs = SimpleNamespace(specimens={"A": c.specimens["A"]})
    f = crown_log_factors(post, obs, tests, sim, _draws)
    # Each model's runs at the test's amplitude times its threshold over the specimen's,
    # at the nodes of that ratio's law (its threshold known to 0.05 in log, joined to the
    # codes' CLIFF_SPREAD; the specimen's anywhere in the 40 to 42 mm bracket;
    # threshold_nodes is tested below), and no run of the rare one.
    amps = sorted({round(job[1].amplitude_m, 7) for job in sim.jobs})
    nodes = crown.threshold_nodes(math.hypot(0.05, crown.CLIFF_SPREAD), math.log(0.042 / 0.040))
    expected = sorted(0.037 / math.sqrt(0.040 * 0.042) * t * math.exp(x) for t in (0.050, 0.060) for x in nodes)
    assert amps == pytest.approx(expected, abs=1e-7)  # in 0.1 um
    assert all(dict(job[2].parts())["geometry"] != 1.1 for job in sim.jobs)
    s = tests[0].scale
    assert f["ring"] - f["pivots"] == pytest.approx(math.log(t3_pdf(0.0) / t3_pdf(math.log(3e-3 / 8e-4) / s)), rel=1e-9)
    assert f["rare"] == min(f["ring"], f["pivots"])


def test_with_crown_multiplies_the_odds_by_the_factors():
    post = _post({"a": ([1.0], [1.0], [0.0], 0.6), "b": ([1.0], [1.0], [0.0], 0.4)})
    crown.with_crown(post, {"a": 0.0, "b": math.log(3.0)})
    assert post.probabilities["b"] / post.probabilities["a"] == pytest.approx(3 * 0.4 / 0.6)
    assert sum(post.probabilities.values()) == pytest.approx(1.0)


# ---------------------------------------------------------------- the hold's expected information


def _h(p):
    return -sum(x * math.log2(x) for x in p if x > 0)


def test_a_hold_whose_rivals_predict_the_same_crown_gives_nothing():
    assert hold_gain_bits([0.5, 0.5], [[2e-3] * 3, [2e-3] * 3], 0.1)[0] == pytest.approx(0.0, abs=1e-12)
    # Below the floor every prediction is the same outcome: nothing to learn either.
    assert hold_gain_bits([0.5, 0.5], [[1e-4] * 3, [3e-4] * 3], 0.1)[0] == pytest.approx(0.0, abs=1e-12)


def test_a_hold_that_parts_two_even_rivals_gives_one_bit():
    gain, spread, se = hold_gain_bits([0.5, 0.5], [[2e-3] * 3, [40e-3] * 3], 0.1)
    assert gain == pytest.approx(1.0, abs=0.01)
    assert spread == pytest.approx(0.0, abs=0.05)
    assert se == pytest.approx(0.0, abs=1e-9)


def test_a_rival_whose_draws_split_gives_half_the_entropy_of_a_third():
    """Rival A's three draws all rock at 2 mm; rival B's at 2 mm once and at 40 mm twice:
    P(Y = 2 mm) = 1/2 + 1/6, and I(M; Y) = H(1/3) - H(1/3) / 2."""
    gain, _, se = hold_gain_bits([0.5, 0.5], [[2e-3] * 3, [2e-3, 40e-3, 40e-3]], 0.1)
    assert gain == pytest.approx(0.5 * _h([1 / 3, 2 / 3]), abs=0.01)
    assert se > 0.0


def test_single_runs_are_kept_so_a_second_diagnosis_runs_none_again(tmp_path, monkeypatch):
    """Simulator.peaks: each run's peak (a fall counts as FALLEN_PEAK_M), kept under the
    hash of its input; asked again, nothing runs, and a changed amplitude runs alone."""
    sim = Simulator(DiagnosisSettings(bin_dir=bin_dir(), log=lambda *_: None), tmp_path / "work")
    ran = []

    def stand_in(jobs):
        ran.extend(jobs)
        t = np.linspace(0.0, 1.0, 11)
        return [{"collapsed": test.amplitude_m > 0.05, "crown_dx_m": test.amplitude_m * 0.1 * np.cos(t)}
                for _, test, _, _ in jobs]
    monkeypatch.setattr(sim, "run_tests", stand_in)
    spec = Specimen("A", 180.0, 9, 0.5, 0.05, 0.1, 2000.0)
    jobs = [(spec, _test(f"t{k}", 2.0, a), Variant("friction", 0.4), {}) for k, a in enumerate((0.02, 0.06, 0.02))]
    first = sim.peaks(jobs, tmp_path / "cache")
    assert first == pytest.approx([0.002, FALLEN_PEAK_M, 0.002]) and len(ran) == 2  # the repeat ran once
    assert sim.peaks(jobs, tmp_path / "cache") == first and len(ran) == 2
    sim.peaks([(spec, _test("t", 2.0, 0.03), Variant("friction", 0.4), {})], tmp_path / "cache")
    assert len(ran) == 3


def test_the_nodes_are_the_quantiles_of_a_normal_plus_a_uniform():
    """threshold_nodes against independent answers: the normal's quantiles (no bracket),
    the uniform's (no spread), and a large seeded sample of the sum for both."""
    q = (np.arange(5) + 0.5) / 5
    assert crown.threshold_nodes(0.05, 0.0) == pytest.approx(0.05 * np.array([-1.2815516, -0.5244005, 0.0,
                                                                               0.5244005, 1.2815516]), abs=1e-7)
    assert crown.threshold_nodes(0.0, 0.1) == pytest.approx([-0.04, -0.02, 0.0, 0.02, 0.04], abs=1e-12)
    rng = np.random.default_rng(7)
    sample = rng.normal(0.0, 0.03, 2_000_000) + rng.uniform(-0.05, 0.05, 2_000_000)
    assert crown.threshold_nodes(0.03, 0.1) == pytest.approx(np.quantile(sample, q), abs=3e-4)


def test_a_threshold_known_to_a_few_per_cent_widens_a_steep_crown():
    """Near the threshold the crown can grow tenfold within a few per cent of amplitude:
    a model whose central node barely rocks (1 mm) but whose upper node (its threshold a
    spread lower for the specimen as built) rocks as measured (25 mm) keeps that node's
    weight, 1/5 of the t's density, instead of the t's far tail."""
    measured, s = 0.025, 0.31
    central = math.log(t3_pdf(math.log(measured / 0.001) / s) / s)
    mixed = crown.mixture_log_term(measured, [0.0004, 0.001, 0.001, 0.001, 0.025], s)
    by_hand = math.log(3 / 5 * t3_pdf(math.log(measured / 0.001) / s) / s
                       + 1 / 5 * t3_pdf(math.log(measured / FLOOR_M) / s) / s + 1 / 5 * t3_pdf(0.0) / s)
    assert mixed == pytest.approx(by_hand, rel=1e-12) and mixed > central + 3.0
    assert crown.amplitudes(0.9, math.log(0.04), 0.0) == [0.036] * 5


def test_a_wide_bracket_keeps_the_specimen_whose_threshold_is_at_its_largest_stand(monkeypatch):
    """W118 at 3 Hz in the loop against LMGC90: held at 32.5 mm below a 34 to 38 mm
    bracket, the specimen rocked 30 mm. A model (its threshold 36 mm, known exactly) that
    rocks 25 mm above 0.94 of its threshold and 1 mm below: of the five equal quantiles of
    the specimen's threshold (log-uniform in the bracket), only the lowest (34.38 mm) puts
    the test above 0.94 of it, so the factor is the mixture of one node at 25 mm and four
    at 1 mm, not the 1 mm alone the bracket's midpoint would give (the codes' cliff
    spread set aside: the bracket alone)."""
    monkeypatch.setattr(crown, "CLIFF_SPREAD", 0.0)
    pair = PairObservation("A", 3.0, 0.034, 0.038)
    held = _test("held", 3.0, 0.0325)
    c = _campaign([held], {"held": 0.030})
    tests = crown_tests(c, [pair])
    post = _post({"m": ([1.0], [1.0], [math.log(0.036)], 1.0)})
    post.scales = SimpleNamespace(sigma_sim=np.array([0.0]), sigma_tol=np.array([0.0]))
    sim = StandIn(None)
    sim.peaks = lambda jobs, cache=None: [0.025 if job[1].amplitude_m / 0.036 > 0.94 else 0.001 for job in jobs]
    lab = [0.034 * (0.038 / 0.034) ** ((i + 0.5) / 5) for i in range(5)]
    assert sum(0.0325 / t > 0.94 for t in lab) == 1 and 0.0325 / 0.036 < 0.94
    f = crown_log_factors(post, SimpleNamespace(specimens={"A": c.specimens["A"]}), tests, sim, _draws)
    s = crown_scale(0.0325 / 0.036)
    assert f["m"] == pytest.approx(math.log((t3_pdf(math.log(0.030 / 0.025) / s) + 4 * t3_pdf(math.log(30.0) / s))
                                            / (5 * s)), rel=1e-9)
