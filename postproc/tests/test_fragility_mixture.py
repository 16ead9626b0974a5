"""The calibrated fragility as a mixture of stratified model samples (issue 36, item 2),
each part against an answer derived apart from the code:

- the mixture's median against a root of the closed-form mixture of lognormal CDFs
  (scipy.stats.lognorm, brentq here), its percentile curves against the order statistics
  of the samples' curves, each model's curve against its own lognormal;
- the two-stage bootstrap: drawing the samples as well as the events widens the band of a
  mixture whose samples disagree, and its spread of the ln median is close to the events' part
  and the samples' own bootstrap (computed here from the fits) added in quadrature;
- the calibrated goodness-of-fit p-value: roughly uniform over data sets drawn from the
  null (samples of lognormal medians, rows clustered by event and record, bracketed as an
  IDA's rows; the KS table's p-value on the same sets is not), and small for two models of
  well-separated lognormals, and for thirty samples of lognormal medians not;
- the commands: the fragility's JSON gives the weights of a stratified file written by hand
  and the mixture's median (a root found here), and the risk of the mixture on a power-law
  hazard is the weighted sum of the samples' closed forms (Cornell et al. 2002), for the
  point and for each two-stage bootstrap resample.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy import optimize, stats

from voussoir_post.earthquake.mixture import (calibrated_fit_check, cluster_correlations, fit_samples,
                                              mixture_band, mixture_quantile, model_curves, percentile_curves)



# ------------------------------------------------------------------ the mixture

def _exact_rows(median, beta, k=12):
    """k exact intensities whose maximum-likelihood lognormal is (median, beta) exactly."""
    u = stats.norm.ppf((np.arange(k) + 0.5) / k)
    u = (u - u.mean()) / u.std()
    return np.exp(math.log(median) + beta * u)


def _rows(samples):
    low, sets = [], []
    for s, (m, b) in enumerate(samples):
        x = _exact_rows(m, b)
        low.append(x)
        sets.append(np.full(x.size, s))
    low = np.concatenate(low)
    return low, low.copy(), np.concatenate(sets)


def test_the_mixtures_median_is_the_root_of_the_closed_form_mixture():
    low, high, sets = _rows([(0.20, 0.30), (0.40, 0.20)])
    fits = fit_samples(low, high, sets, weights={0: 0.3, 1: 0.7}, models={0: "a", 1: "b"})
    assert fits.medians == pytest.approx([0.20, 0.40], rel=1e-10) and fits.betas == pytest.approx([0.30, 0.20])

    def cdf(x):  # the mixture of the two lognormals, by scipy's lognorm
        return 0.3 * stats.lognorm.cdf(x, 0.30, scale=0.20) + 0.7 * stats.lognorm.cdf(x, 0.20, scale=0.40)

    median = optimize.brentq(lambda x: cdf(x) - 0.5, 0.01, 5.0, xtol=1e-14)
    assert fits.median() == pytest.approx(median, rel=1e-9)
    assert mixture_quantile(0.16, fits.medians, fits.betas, fits.weights) == pytest.approx(
        optimize.brentq(lambda x: cdf(x) - 0.16, 0.01, 5.0, xtol=1e-14), rel=1e-9)
    im = np.linspace(0.05, 1.0, 40)
    assert fits.cdf(im) == pytest.approx(cdf(im), abs=1e-12)
    curves = model_curves(im, fits)
    assert curves["a"] == pytest.approx(stats.lognorm.cdf(im, 0.30, scale=0.20), abs=1e-12)
    assert curves["b"] == pytest.approx(stats.lognorm.cdf(im, 0.20, scale=0.40), abs=1e-12)


def test_the_percentile_curves_are_the_weighted_order_statistics():
    samples = [(0.2, 0.3), (0.3, 0.2), (0.45, 0.25)]
    low, high, sets = _rows(samples)
    im = np.linspace(0.05, 1.0, 30)
    own = np.array([stats.lognorm.cdf(im, b, scale=m) for m, b in samples])
    # equal weights (1/3 each): the 16 % is the smallest curve, the 84 % the largest
    curves = percentile_curves(im, fit_samples(low, high, sets))
    assert curves[0.16] == pytest.approx(own.min(axis=0), abs=1e-12)
    assert curves[0.84] == pytest.approx(own.max(axis=0), abs=1e-12)
    # weights 0.1, 0.2, 0.7 (cumulated from the smallest value): the 16 % is the middle value
    # wherever the 0.1-sample's curve is the smallest, which it is below the crossing points
    fits = fit_samples(low, high, sets, weights={0: 0.2, 1: 0.1, 2: 0.7})
    got = percentile_curves(im, fits)[0.16]
    order = np.argsort(own, axis=0)
    w = np.array([0.2, 0.1, 0.7])
    want = [own[order[0, k], k] if w[order[0, k]] >= 0.16 else own[order[1, k], k] for k in range(im.size)]
    assert got == pytest.approx(want, abs=1e-12)


def _ida_like(rng, medians, betas, n_events=7, per_event=2, ratio=1.05, rho_e=0.0, rho_r=0.0, models=None):
    """Rows of a synthetic IDA: every sample plays every record; sample s's ln IM_c = ln m_s +
    beta_s (record effect + own noise), bracketed (x / ratio^u', x ratio^u] as a search is."""
    n_records = n_events * per_event
    events = np.repeat(np.arange(n_events), per_event)
    a_event = rng.standard_normal(n_events)[events]
    a_record = rng.standard_normal(n_records)
    low, high, sets, rec, ev = [], [], [], [], []
    for s, (m, b) in enumerate(zip(medians, betas)):
        z = math.sqrt(rho_e) * a_event + math.sqrt(rho_r - rho_e) * a_record + math.sqrt(1 - rho_r) * \
            rng.standard_normal(n_records)
        x = np.exp(math.log(m) + b * z)
        top = x * ratio ** rng.uniform(0, 1, n_records)
        low.append(top / ratio)
        high.append(top)
        sets.append(np.full(n_records, s))
        rec.append([f"r{k}" for k in range(n_records)])
        ev.append([f"e{e}" for e in events])
    return (np.concatenate(low), np.concatenate(high), np.concatenate(sets), sum(rec, []), sum(ev, []))


def test_the_two_stage_band_carries_the_samples_spread():
    rng = np.random.default_rng(7)
    # 8 samples in one stratum whose medians spread by beta_m = 0.25 in ln, records adding 0.15
    ln_m = math.log(0.3) + 0.25 * stats.norm.ppf((np.arange(8) + 0.5) / 8)
    low, high, sets, rec, ev = _ida_like(rng, np.exp(ln_m), np.full(8, 0.15), rho_e=0.3, rho_r=0.6)
    fits = fit_samples(low, high, sets)
    im = np.linspace(0.05, 1.0, 20)
    both = mixture_band(low, high, sets, fits, im, rec, ev, "event", n_resamples=200, seed=3)
    events_only = mixture_band(low, high, sets, fits, im, rec, ev, "event", n_resamples=200, seed=3,
                               resample_samples=False)
    assert both.ln_median_sd > 1.5 * events_only.ln_median_sd
    # the samples' own part: the bootstrap standard error of the mixture's ln median over the 8
    # samples alone (records fixed), computed here from the fits
    rng2 = np.random.default_rng(11)
    alone = [math.log(mixture_quantile(0.5, fits.medians[k], fits.betas[k], np.ones(8)))
             for k in (rng2.integers(0, 8, 8) for _ in range(400))]
    expected = math.hypot(float(np.std(alone, ddof=1)), events_only.ln_median_sd)
    assert both.ln_median_sd == pytest.approx(expected, rel=0.25)


# ------------------------------------------------------------------ the calibrated goodness of fit

def test_the_correlations_of_a_clustered_sample_are_found():
    rng = np.random.default_rng(5)
    n_events, per_event, n_samples = 40, 3, 6
    events = np.repeat(np.arange(n_events), per_event)
    z = (math.sqrt(0.2) * rng.standard_normal(n_events)[events][None, :]
         + math.sqrt(0.3) * rng.standard_normal(n_events * per_event)[None, :]
         + math.sqrt(0.25) * rng.standard_normal(n_samples)[:, None]
         + math.sqrt(0.25) * rng.standard_normal((n_samples, n_events * per_event)))
    records = np.tile(np.arange(n_events * per_event), n_samples)
    rho_r, rho_e, rho_s = cluster_correlations(z.reshape(-1), records, np.tile(events, n_samples),
                                               np.repeat(np.arange(n_samples), n_events * per_event))
    # planted shares of the variance: record (event included) 0.5, event 0.2, sample 0.25
    assert rho_r == pytest.approx(0.5, abs=0.1) and rho_e == pytest.approx(0.2, abs=0.1)
    assert rho_s == pytest.approx(0.25, abs=0.15)


def test_the_calibrated_p_value_is_uniform_under_the_null():
    p_values, p_table = [], []
    for k in range(40):
        rng = np.random.default_rng(100 + k)
        # the null: 4 samples whose ln medians are normal about ln 0.3 (a pooled lognormal holds),
        # 7 events x 2 records, every sample on every record
        medians = np.exp(math.log(0.3) + 0.12 * rng.standard_normal(4))
        low, high, sets, rec, ev = _ida_like(rng, medians, np.full(4, 0.2), rho_e=0.2, rho_r=0.4)
        check = calibrated_fit_check(low, high, clusters=rec, events=ev, samples=sets, n_simulations=49,
                                     seed=k)
        p_values.append(check.p_value)
        p_table.append(check.p_table)
    p_values = np.array(p_values)
    assert stats.kstest(p_values, "uniform").pvalue > 0.05
    assert 0.0 <= np.mean(p_values < 0.1) <= 0.25 and 0.35 <= p_values.mean() <= 0.65
    # the KS table's p-value on the same data sets is not uniform (fitted parameters: too large)
    assert stats.kstest(p_table, "uniform").pvalue < 0.01 and np.mean(p_table) > 0.65


def test_the_calibrated_p_value_is_small_for_two_separated_lognormals():
    rng = np.random.default_rng(2)
    # ten samples of each of two models, medians 0.2 g and 0.45 g, each sample's rows within 0.08
    medians = np.r_[np.full(10, 0.2), np.full(10, 0.45)] * np.exp(0.03 * rng.standard_normal(20))
    low, high, sets, rec, ev = _ida_like(rng, medians, np.full(20, 0.08), rho_e=0.1, rho_r=0.3)
    check = calibrated_fit_check(low, high, clusters=rec, events=ev, samples=sets, n_simulations=199, seed=1)
    assert check.p_value < 0.05 and not check.holds
    # the same rows without their samples: rows clustered by record only
    flat = calibrated_fit_check(low, high, clusters=rec, events=ev, n_simulations=199, seed=1)
    assert flat.p_value <= 0.01
    # thirty samples whose ln medians are normal (spread 0.2): the pooled lognormal holds
    rng = np.random.default_rng(10)
    medians = np.exp(math.log(0.3) + 0.2 * rng.standard_normal(30))
    low, high, sets, rec, ev = _ida_like(rng, medians, np.full(30, 0.15), n_events=14, rho_e=0.2, rho_r=0.5)
    check = calibrated_fit_check(low, high, clusters=rec, events=ev, samples=sets, n_simulations=99, seed=1)
    assert check.holds


# ------------------------------------------------------------------ the commands

def _ida_csv(path, rng):
    """An IDA CSV of 8 model samples of two models (a: medians 0.2 g, b: 0.45 g) x 10 records of 5 events."""
    g = 9.81
    rows = ["record,param_set,friction,scale_stood,scale_threshold,pga_threshold_m_s2,pgv_threshold_m_s,censored,"
            "event,pga_m_s2"]
    record_effect = 0.6 * rng.standard_normal(10)
    for s, median in enumerate([0.2, 0.21, 0.19, 0.205, 0.45, 0.44, 0.47, 0.46]):
        for r in range(10):
            pga = median * g * math.exp(0.08 * (record_effect[r] + 0.8 * rng.standard_normal()))
            unit = 2.0 + 0.3 * r  # the record's own PGA [m/s2]
            high = pga * 1.05 ** rng.uniform()
            rows.append(f"rec{r},{s},{0.3 + 0.01 * s},{high / 1.05 / unit!r},{high / unit!r},{high!r},{0.1 * high!r},0,"
                        f"event{r // 2},{unit!r}")
    path.write_text("\n".join(rows) + "\n")


def _strata_csv(path):
    """A stratified samples file written by hand: a share 0.4 over 4 samples, b 0.6 over 4."""
    lines = ["# format: voussoir posterior samples 1",
             "# stratum: model = a, probability = 0.3, share = 0.4, samples = 4, weight = 0.1",
             "# stratum: model = b, probability = 0.45, share = 0.6, samples = 4, weight = 0.15",
             "sample,model,friction"] + [f"{s},{'a' if s < 4 else 'b'},{0.3 + 0.01 * s!r}" for s in range(8)]
    path.write_text("\n".join(lines) + "\n")


def test_fragility_and_risk_commands_use_the_mixture_when_the_pooled_fit_fails(tmp_path, capsys):
    from voussoir_post.cli.post import main

    _ida_csv(tmp_path / "ida.csv", np.random.default_rng(4))
    _strata_csv(tmp_path / "strata.csv")
    assert main(["fragility", str(tmp_path / "ida.csv"), "--strata", str(tmp_path / "strata.csv"), "--json",
                 "--bootstrap", "60", "--out", str(tmp_path)]) == 0
    out = json.loads(capsys.readouterr().out)
    mix = out["mixture"]
    assert mix["sample_weight"] == pytest.approx([0.1] * 4 + [0.15] * 4, rel=1e-6)
    assert mix["sample_model"] == ["a"] * 4 + ["b"] * 4
    assert not mix["pooled_holds"] and mix["to_use"] == "mixture" and mix["pooled_gof_p_calibrated"] < 0.05
    m, b, w = (np.array(mix[k]) for k in ("sample_median_pga_g", "sample_beta_pga", "sample_weight"))
    root = optimize.brentq(lambda x: float(np.sum(w * stats.norm.cdf(np.log(x / m) / b))) - 0.5, 0.05, 2.0,
                           xtol=1e-12)
    assert mix["median_pga_g"] == pytest.approx(root, rel=1e-8)
    assert mix["model_median_pga_g"]["a"] < 0.25 < 0.4 < mix["model_median_pga_g"]["b"]
    assert len(mix["bootstrap_draws"]) + mix["n_bootstrap_unfitted"] == 60
    assert (tmp_path / "ida_fragility_mixture.png").exists() and (tmp_path / "ida_fragility_mixture.csv").exists()
    frag = tmp_path / "frag.json"
    frag.write_text(json.dumps(out))
    # the risk on a power-law hazard: the mixture's rate is the weighted sum of the samples' closed forms
    k0, k = 1e-4, 2.5
    xs = np.geomspace(0.01, 5.0, 40)
    (tmp_path / "site.csv").write_text("pga_g,annual_rate\n" + "\n".join(f"{x:.17g},{k0 * x ** -k:.17g}" for x in xs)
                                         + "\n")
    assert main(["risk", str(tmp_path / "site.csv"), "--fragility-json", str(frag), "--mce-g", "0.5", "--json",
                 "--out", str(tmp_path / "risk.png")]) == 0
    risk = json.loads(capsys.readouterr().out)
    closed = lambda mm, bb: k0 * mm ** -k * np.exp(0.5 * (k * bb) ** 2)
    assert risk["annual_rate_of_collapse"] == pytest.approx(float(np.sum(w * closed(m, b))), rel=1e-2)
    assert risk["collapse_margin_ratio"] == pytest.approx(root / 0.5, rel=1e-6)
    draws = mix["bootstrap_draws"]
    each = [float(np.sum(np.array(d["weight"]) * closed(np.array(d["median_pga_g"]), np.array(d["beta_pga"]))))
            for d in draws]
    assert risk["fragility_bands"]["mixture bootstrap"]["mean_annual_rate"] == pytest.approx(np.mean(each), rel=1e-2)
    assert risk["fragility_bands"]["model samples"]["mean_annual_rate"] == pytest.approx(
        risk["annual_rate_of_collapse"], rel=1e-2)
