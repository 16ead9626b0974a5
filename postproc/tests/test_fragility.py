"""The lognormal fragility fit (voussoir_post.earthquake.fragility).

The fit is checked against the closed form (uncensored data), against known lognormal
populations sampled here (with and without censoring, and bracketed as an IDA brackets
them, within the sampling error that the observed information of a likelihood written
here gives), the clustered bootstrap against constructions whose answer is known and by
its coverage of the true median of clustered rows drawn here, and the goodness of fit
on data from the fitted law and from another, and the split of beta into
record-to-record and model parts on model samples drawn here with known medians and a
known common beta. The IDA files and the command: test_fragility_ida.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from voussoir_post.earthquake.fragility import (FitError, bootstrap_band, clustered_band, confidence_curve,
                                                empirical_collapse_fraction, fit_intervals, fit_lognormal, fragility,
                                                goodness_of_fit, log_likelihood, max_likelihood, resample_clusters,
                                                split_beta)

G = 9.81


def hessian(f, p0, h=1e-4):
    """Central-difference Hessian of f at p0 (2 parameters)."""
    p0 = np.asarray(p0, float)
    hess = np.zeros((2, 2))
    for i in range(2):
        for j in range(2):
            e_i, e_j = np.eye(2)[i] * h, np.eye(2)[j] * h
            hess[i, j] = (f(p0 + e_i + e_j) - f(p0 + e_i - e_j) - f(p0 - e_i + e_j) + f(p0 - e_i - e_j)) / (4 * h * h)
    return hess


def standard_errors(ln_x, censored, mu, beta):
    """Standard errors of (mu, beta) from the observed information: the inverse of the
    negative Hessian of the log-likelihood at the fit (central differences)."""
    hess = hessian(lambda p: log_likelihood(p[0], p[1], ln_x, censored), [mu, beta])
    return np.sqrt(np.diag(np.linalg.inv(-hess)))


def bracket_log_likelihood(mu, beta, low, high):
    """The log-likelihood of intensities known to lie in (low, high], written here from
    scipy.stats.norm alone (independent of the module's tail-safe version)."""
    return float(np.sum(np.log(stats.norm.cdf((np.log(high) - mu) / beta) - stats.norm.cdf((np.log(low) - mu) / beta))))


def ida_brackets(x, rng, step):
    """Bracket each collapse intensity x as an IDA search does: on a geometric ladder of
    intensities step**(k + offset) (an offset per row, as each record starts the ladder
    from its own PGA), between the last rung below x and the first at or above."""
    offset = rng.uniform(0.0, 1.0, x.size)
    k = np.floor(np.log(x) / math.log(step) - offset)
    low, high = step ** (k + offset), step ** (k + 1 + offset)
    assert np.all((low < x) & (x <= high))
    return low, high


def test_uncensored_fit_is_the_closed_form():
    im = np.array([2.1, 3.7, 2.9, 5.2, 1.8, 4.4, 3.3])
    fit = fit_lognormal(im)
    assert fit.median == math.exp(np.mean(np.log(im)))
    assert fit.beta == np.std(np.log(im), ddof=0)
    assert fit.n == 7 and fit.n_censored == 0
    # The numerical maximiser used with censoring finds the same maximum.
    mu, beta, _ = max_likelihood(np.log(im), np.zeros(im.size, bool))
    assert math.exp(mu) == pytest.approx(fit.median, rel=1e-7)
    assert beta == pytest.approx(fit.beta, rel=1e-7)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_fit_recovers_a_known_lognormal(seed):
    median, beta, n = 3.5, 0.45, 400
    im = np.exp(np.random.default_rng(seed).normal(math.log(median), beta, n))
    fit = fit_lognormal(im)
    # Sampling error of the maximum-likelihood estimates of a normal sample.
    assert abs(math.log(fit.median) - math.log(median)) < 3.5 * beta / math.sqrt(n)
    assert abs(fit.beta - beta) < 3.5 * beta / math.sqrt(2 * n)


@pytest.mark.parametrize("seed", [4, 5, 6])
def test_fit_with_censoring_recovers_a_known_lognormal(seed):
    median, beta, n = 0.35 * G, 0.4, 400
    capacity = np.exp(np.random.default_rng(seed).normal(math.log(median), beta, n))
    # Records scaled only up to a bound: capacities above it are not seen (30 % of them).
    bound = median * math.exp(beta * 0.5244)  # the 70th percentile
    censored = capacity > bound
    im = np.where(censored, bound, capacity)
    assert 0.2 < censored.mean() < 0.4
    fit = fit_lognormal(im, censored)
    se_mu, se_beta = standard_errors(np.log(im), censored, math.log(fit.median), fit.beta)
    assert abs(math.log(fit.median) - math.log(median)) < 3.5 * se_mu
    assert abs(fit.beta - beta) < 3.5 * se_beta
    # Treating the lower bounds as collapses is biased beyond that error: the censoring
    # is what makes the fit right.
    naive = fit_lognormal(im)
    assert abs(naive.beta - beta) > 3.5 * se_beta


@pytest.mark.parametrize("seed", [8, 9, 10])
def test_interval_censored_fit_recovers_a_known_lognormal(seed):
    """Collapse intensities drawn here from a known lognormal and bracketed on a 25 %
    ladder: the interval-censored fit finds median and beta within 3.5 standard errors
    (observed information of the likelihood written in this file), its maximum is that
    likelihood's (zero gradient there), and taking the top of each bracket as the
    intensity misses the median by about half a rung, ln(1.25) / 2 = 0.11, more than
    that error (0.3 / sqrt(400) = 0.015)."""
    median, beta, n = 5.4, 0.3, 400
    rng = np.random.default_rng(seed)
    x = np.exp(rng.normal(math.log(median), beta, n))
    low, high = ida_brackets(x, rng, 1.25)
    fit = fit_intervals(low, high)
    assert fit.n == n and fit.n_interval == n and fit.n_censored == 0

    def ll(p):
        return bracket_log_likelihood(p[0], p[1], low, high)

    p_hat = np.array([math.log(fit.median), fit.beta])
    se_mu, se_beta = np.sqrt(np.diag(np.linalg.inv(-hessian(ll, p_hat))))
    assert 0.9 * beta / math.sqrt(n) < se_mu < 1.3 * beta / math.sqrt(n)  # a little above the exact-data error
    assert abs(math.log(fit.median) - math.log(median)) < 3.5 * se_mu
    assert abs(fit.beta - beta) < 3.5 * se_beta
    h = 1e-5
    gradient = [(ll(p_hat + e) - ll(p_hat - e)) / (2 * h) for e in np.eye(2) * h]
    assert np.max(np.abs(gradient)) < 1e-3, gradient  # against n / beta ~ 1000 per unit of mu
    top = fit_lognormal(high)
    assert math.log(top.median) - math.log(median) > 3.5 * se_mu


def test_a_failed_search_censored_at_its_last_stand_moves_the_fit_up():
    """A search that failed after a stand at s says only IM_c > s. (1) When every row
    says IM_c > x the median is above x: at the maximum, the score in mu makes mu the
    mean over the rows of E[ln IM_c | its bracket], each above ln x. (2) Added to
    bracketed rows, a row censored at s raises the median, the more the higher s; far
    below all of them it tells nothing and the fit is the fit without it."""
    x = 4.0
    low = np.array([x, 1.1 * x, 1.05 * x, 1.3 * x, x, 1.2 * x])
    high = np.array([1.2 * x, 1.3 * x, np.inf, 1.6 * x, np.inf, 1.5 * x])
    assert fit_intervals(low, high).median > x
    # (2)
    rng = np.random.default_rng(12)
    x_c = np.exp(rng.normal(math.log(5.0), 0.3, 20))
    low, high = ida_brackets(x_c, rng, 1.1)
    without = fit_intervals(low, high).median
    medians = [fit_intervals(np.append(low, s), np.append(high, np.inf)).median for s in (3.0, 5.0, 8.0, 12.0)]
    assert without < medians[0] < medians[1] < medians[2] < medians[3]
    far_below = fit_intervals(np.append(low, 1e-3), np.append(high, np.inf))
    assert far_below.median == pytest.approx(without, rel=1e-7)


def test_clustered_band_is_wider_when_rows_within_a_record_are_identical():
    """12 records whose 4 model samples each give the same bracket: the rows add nothing
    to the records. Drawing records, a resample of the 48 rows is a resample of the 12
    brackets repeated 4 times, whose fit is the fit of the 12: the band is the row
    bootstrap of the 12 brackets (same seed, same draws). Drawing rows treats them as
    48 independent ones: its band is narrower by sqrt(48 / 12) = 2."""
    k, r = 12, 4
    rng = np.random.default_rng(13)
    x = np.exp(rng.normal(math.log(5.0), 0.3, k))
    low, high = ida_brackets(x, rng, 1.05)
    rows_low, rows_high = np.repeat(low, r), np.repeat(high, r)
    records = np.repeat([f"rec{i:02d}.AT2" for i in range(k)], r)
    grid = np.linspace(1.0, 10.0, 40)
    by_record = clustered_band(rows_low, rows_high, grid, records, cluster_by="record", seed=5)
    by_row = clustered_band(rows_low, rows_high, grid, None, seed=5)
    of_records = clustered_band(low, high, grid, None, seed=5)
    assert by_record.cluster_by == "record" and by_record.n_clusters == k
    assert by_row.cluster_by == "row" and by_row.n_clusters == k * r
    np.testing.assert_allclose(by_record.low, of_records.low, atol=1e-9)
    np.testing.assert_allclose(by_record.high, of_records.high, atol=1e-9)
    assert by_record.median_low == pytest.approx(of_records.median_low, rel=1e-9)
    width = {name: math.log(band.median_high / band.median_low) for name, band in
             (("record", by_record), ("row", by_row))}
    assert 1.6 < width["record"] / width["row"] < 2.5, width
    assert by_record.ln_median_sd > 1.6 * by_row.ln_median_sd


def test_two_stage_resample_draws_events_then_whole_records():
    """With events, a resample holds whole records (all their rows), only records of the
    events drawn, and as many records from a drawn event as it has."""
    events = np.array(["Imperial Valley"] * 4 + ["Loma Prieta"] * 4 + ["San Fernando"] * 2)
    records = np.array(["ELC180", "ELC180", "ELC270", "ELC270", "CLS000", "CLS000", "CLS090", "CLS090",
                        "PUL164", "PUL164"])
    rng = np.random.default_rng(14)
    for _ in range(50):
        pick = resample_clusters(rng, records, events)
        drawn = records[pick]
        for name in set(drawn.tolist()):
            assert np.sum(drawn == name) % 2 == 0  # whole records of two rows
        per_event = {e: np.sum(events[pick] == e) for e in set(events.tolist())}
        assert per_event["Imperial Valley"] % 4 == 0 and per_event["Loma Prieta"] % 4 == 0
        assert pick.size == sum(per_event.values())
    with pytest.raises(FitError, match="belongs to two events"):
        clustered_band(np.ones(2), np.full(2, 2.0), [1.5], ["a", "a"], ["e1", "e2"])


def test_goodness_of_fit_accepts_the_fitted_law_and_rejects_another():
    """The PIT of rows drawn from a lognormal, fitted, is uniform: out of 40 draws the KS
    test rejects at 5 % at most a few (it is conservative with fitted parameters: fewer
    than 2 expected; 7 or more has probability < 1 %). Rows from two well separated
    lognormals (medians 2 and 8) are not lognormal: p < 0.01 every time. The PIT lies
    within F of its bracket, and a seed gives it again."""
    p_same = []
    for seed in range(40):
        rng = np.random.default_rng(100 + seed)
        low, high = ida_brackets(np.exp(rng.normal(math.log(5.4), 0.3, 200)), rng, 1.05)
        fit = fit_intervals(low, high)
        check = goodness_of_fit(low, high, fit.median, fit.beta, seed=seed)
        assert np.all((fragility(low, fit.median, fit.beta) <= check.pit)
                      & (check.pit <= fragility(high, fit.median, fit.beta)))
        p_same.append(check.p_value)
    assert sum(p < 0.05 for p in p_same) <= 6, p_same
    for seed in range(5):
        rng = np.random.default_rng(200 + seed)
        two = np.where(rng.uniform(size=200) < 0.5, rng.normal(math.log(2.0), 0.1, 200),
                       rng.normal(math.log(8.0), 0.1, 200))
        low, high = ida_brackets(np.exp(two), rng, 1.05)
        fit = fit_intervals(low, high)
        assert goodness_of_fit(low, high, fit.median, fit.beta, seed=seed).p_value < 0.01
    again = goodness_of_fit(low, high, fit.median, fit.beta, seed=4)
    np.testing.assert_array_equal(again.pit, goodness_of_fit(low, high, fit.median, fit.beta, seed=4).pit)


def test_bootstrap_band_holds_the_fit_and_narrows_as_one_over_root_n():
    population = np.exp(np.random.default_rng(7).normal(math.log(3.0), 0.4, 480))
    widths = {}
    for n in (120, 480):
        im = np.minimum(population[:n], 5.0)
        censored = population[:n] > 5.0
        fit = fit_lognormal(im, censored)
        grid = np.linspace(0.5, 8.0, 60)
        band = bootstrap_band(im, censored, grid, n_resamples=200)
        p = fragility(grid, fit.median, fit.beta)
        inside = (p > 0.02) & (p < 0.98)
        assert np.all(band.low[inside] <= p[inside]) and np.all(p[inside] <= band.high[inside])
        assert band.median_low < fit.median < band.median_high and band.n_resamples == 200
        widths[n] = math.log(band.median_high / band.median_low)
    # Four times the rows: half the width (the sampling error of a median), give or take.
    assert 1.5 < widths[120] / widths[480] < 2.7, widths


def test_kaplan_meier_fraction_by_hand():
    # 4 records: collapse at 1, censored at 2, collapses at 3 and 4. At 1: 1 - 3/4; the
    # censored record leaves the risk set; at 3: 1 - (3/4)(1/2); at 4: everyone.
    x, p = empirical_collapse_fraction([3.0, 2.0, 1.0, 4.0], [False, True, False, False])
    np.testing.assert_allclose(x, [1.0, 3.0, 4.0])
    np.testing.assert_allclose(p, [0.25, 0.625, 1.0])


def test_no_fit_without_two_collapses():
    with pytest.raises(FitError, match="at least two"):
        fit_lognormal([1.0, 2.0, 3.0], [True, True, False])


def test_beta_split_of_exact_crossed_rows_is_the_analysis_of_variance():
    """Every model sample sees the same records, as in an IDA: ln IM_c(r, s) = mu + a_r +
    b_s, exact rows. Each sample's fit is the closed form, so each beta_s = std(a)
    (divisor n) and beta_RTR = std(a); each ln median is mu + mean(a) + b_s, so
    beta_model = std(b) (divisor m - 1): the record effect, common to the samples,
    drops out. The pooled beta^2 is then, exactly, beta_RTR^2 + (m - 1)/m beta_model^2
    (the within and between sums of squares), so sqrt(beta_RTR^2 + beta_model^2) is a
    little above beta_total, by the divisor."""
    rng = np.random.default_rng(21)
    a, b = rng.normal(0.0, 0.35, 8), np.array([-0.12, 0.03, 0.1, -0.05])
    ln_x = math.log(3.6) + a[None, :] + b[:, None]  # (model sample, record)
    x = np.exp(ln_x).reshape(-1)
    samples = np.repeat(np.arange(4), 8)
    split = split_beta(x, x, samples)
    assert split.samples == [0, 1, 2, 3] and split.n_samples == 4 and list(split.n_rows) == [8] * 4
    np.testing.assert_allclose(split.betas, np.std(a), rtol=1e-12)
    np.testing.assert_allclose(np.log(split.medians), math.log(3.6) + np.mean(a) + b, rtol=1e-12)
    assert split.beta_rtr == pytest.approx(np.std(a), rel=1e-12)
    assert split.beta_model == pytest.approx(np.std(b, ddof=1), rel=1e-12)
    assert split.beta_total == pytest.approx(fit_intervals(x, x).beta, rel=1e-15)
    assert split.beta_total ** 2 == pytest.approx(split.beta_rtr ** 2 + 0.75 * split.beta_model ** 2, rel=1e-12)
    assert split.beta_srss == pytest.approx(math.hypot(np.std(a), np.std(b, ddof=1)), rel=1e-12)


def test_beta_split_recovers_a_known_record_spread_and_spread_of_medians():
    """5 model samples, each 200 collapse intensities drawn here from a lognormal of
    known median (ln medians spread with standard deviation 0.2, divisor m - 1) and the
    common beta 0.3, bracketed on a 10 % ladder; 40 such draws. Sampling errors from
    the draw sizes: a beta from n rows has standard deviation ~ beta / sqrt(2n), so
    beta_RTR (the root mean square of m of them) ~ beta / sqrt(2nm) = 0.0067; each
    ln median carries an error e_s of standard deviation se = beta / sqrt(n) = 0.021,
    so beta_model^2 = sd^2(ln m_s + e_s) has the mean 0.2^2 + se^2 (the estimator is
    biased up by the medians' own error) and beta_model the standard deviation
    ~ se / sqrt(m - 1) = 0.011. Each draw is within 4 of these errors (x 1.2 for the
    brackets), the spread of the 40 draws agrees with them within a factor 1.6 (so they
    are the right tolerances), and the means of the 40 are within 3.5 of their own
    standard errors of beta and of 0.2^2 + se^2."""
    m, n, beta, spread = 5, 200, 0.3, 0.2
    d = np.arange(m) - 2.0
    ln_medians = math.log(4.0) + spread * d / np.std(d, ddof=1)
    samples = np.repeat(np.arange(m), n)
    sd_rtr, se = beta / math.sqrt(2 * n * m), beta / math.sqrt(n)
    sd_model = se / math.sqrt(m - 1)
    rtr, model = [], []
    for seed in range(40):
        rng = np.random.default_rng(300 + seed)
        x = np.exp(rng.normal(np.repeat(ln_medians, n), beta))
        low, high = ida_brackets(x, rng, 1.1)
        split = split_beta(low, high, samples)
        assert np.all(np.abs(np.log(split.medians) - ln_medians) < 4 * 1.2 * se)
        assert abs(split.beta_rtr - beta) < 4 * 1.2 * sd_rtr
        assert abs(split.beta_model - spread) < 4 * 1.2 * sd_model
        # The pooled beta holds both parts: sqrt(0.3^2 + 0.8 x 0.2^2) = 0.35.
        assert split.beta_total == pytest.approx(math.sqrt(beta ** 2 + (m - 1) / m * spread ** 2), abs=0.03)
        rtr.append(split.beta_rtr)
        model.append(split.beta_model)
    rtr, model = np.array(rtr), np.array(model)
    assert 1 / 1.6 < np.std(rtr, ddof=1) / sd_rtr < 1.6
    assert 1 / 1.6 < np.std(model, ddof=1) / sd_model < 1.6
    assert abs(np.mean(rtr) - beta) < 3.5 * np.std(rtr, ddof=1) / math.sqrt(rtr.size)
    squares = model ** 2
    assert abs(np.mean(squares) - (spread ** 2 + se ** 2)) < 3.5 * np.std(squares, ddof=1) / math.sqrt(squares.size)


def test_beta_split_with_one_model_sample_has_no_model_part():
    rng = np.random.default_rng(22)
    low, high = ida_brackets(np.exp(rng.normal(math.log(5.0), 0.3, 30)), rng, 1.05)
    split = split_beta(low, high, np.zeros(30, int))
    assert split.beta_model is None and split.beta_srss is None and split.n_samples == 1
    assert split.beta_rtr == pytest.approx(split.beta_total, rel=1e-12)  # the same rows, the same fit


def test_beta_split_names_a_sample_that_cannot_be_fitted_alone():
    low = np.array([1.0, 2.0, 3.0, 1.5, 2.5, 3.5])
    high = np.array([1.1, 2.2, 3.3, np.inf, np.inf, np.inf])  # sample 7: every row censored
    with pytest.raises(FitError, match="model sample 7 alone \\(3 rows\\)"):
        split_beta(low, high, [3, 3, 3, 7, 7, 7])
    with pytest.raises(FitError, match="one model sample label per row"):
        split_beta(low, high, [3, 3, 7])


def test_confidence_curve_is_the_fit_moved_to_the_lower_bound_of_the_median():
    """The same beta, the median at the band's lower percentile: the curve reaches 1/2
    there, lies above the fit everywhere, and the bound is the 5th percentile of the
    bootstrap medians (below the fit's median)."""
    rng = np.random.default_rng(23)
    low, high = ida_brackets(np.exp(rng.normal(math.log(5.0), 0.3, 40)), rng, 1.05)
    fit = fit_intervals(low, high)
    grid = np.linspace(1.0, 12.0, 50)
    band = clustered_band(low, high, grid, n_resamples=100, seed=3)
    curve = confidence_curve(grid, fit, band)
    assert band.median_low < fit.median
    assert confidence_curve([band.median_low], fit, band)[0] == pytest.approx(0.5, abs=1e-12)
    np.testing.assert_allclose(curve, fragility(grid, band.median_low, fit.beta), rtol=1e-15)
    assert np.all(curve >= fragility(grid, fit.median, fit.beta))


def test_clustered_band_covers_the_true_median_of_clustered_rows():
    """Coverage of the 90 % band of the median on synthetic rows clustered as an IDA's
    are: E = 14 events (as the FEMA P695 far-field set), R = 2 records (components) in
    each, M = 4 model samples on each record, ln IM_c = ln 4 + a_event + b_record +
    c_row with standard deviations s_a = 0.25, s_b = 0.3, s_c = 0.1; exact rows (the
    closed-form fit, mu_hat = the mean of ln IM_c, balanced), 200 independent draws.

    The expected coverage, derived here, not measured: with V_E = s_a^2 + (s_b^2 +
    s_c^2 / M) / R the variance of an event's mean, mu_hat has the variance V_E / E. The
    two-stage resample (events, then records within them) has on average the variance
    [(E - 1) / E V_E + (R - 1) / R^2 (s_b^2 + s_c^2 / M)] / E, rho^2 times the true one;
    its spread is estimated from E events, so (mu_hat - mu) / sd* is roughly t with
    E - 1 degrees of freedom, and the percentiles of B resamples (numpy's interpolation
    at 0.05 (B - 1)) span about the fraction L_B = 1 - 2 (1 + 0.05 (B - 1)) / (B + 1) of
    the resamples' law. Expected coverage p = 2 F_t(z_B rho) - 1, z_B the normal
    quantile of (1 + L_B) / 2: about 0.86 for B = 40 (the nominal 0.90 less the few
    events and the few resamples; rho = 1.07, the second stage adds a little). The row bootstrap draws 112 rows as independent:
    its variance is on average (s^2 - V_E / E) / N, N = 112, s^2 = s_a^2 + s_b^2 +
    s_c^2, so rho_row = 0.42 and it covers about 2 Phi(z_B rho_row) - 1 = 0.46 of the
    time: it under-covers, which is why the band is clustered.

    Tolerance: a coverage count over n = 200 draws is binomial, standard deviation
    sqrt(p (1 - p) / n) (0.025 at p = 0.86, 0.035 at 0.46); each rate is asserted within
    3.5 of them of its expectation (a false alarm below 1 in 2000), and the clustered
    band's rate is also asserted above the row band's expectation + 3.5 of its own. The
    seeds are fixed; B = 40 resamples per band keep it near 10 s of CPU (16 000 fits)."""
    n_events, n_records, n_models = 14, 2, 4
    s_a, s_b, s_c = 0.25, 0.3, 0.1
    median, n_draws, n_boot = 4.0, 200, 40
    n_rows = n_events * n_records * n_models
    events = np.repeat([f"event{e:02d}" for e in range(n_events)], n_records * n_models)
    records = np.repeat([f"record{k:02d}" for k in range(n_events * n_records)], n_models)
    covered = {"event": 0, "row": 0}
    for draw in range(n_draws):
        rng = np.random.default_rng(4000 + draw)
        ln_x = (math.log(median) + np.repeat(rng.normal(0.0, s_a, n_events), n_records * n_models)
                + np.repeat(rng.normal(0.0, s_b, n_events * n_records), n_models) + rng.normal(0.0, s_c, n_rows))
        x = np.exp(ln_x)
        bands = {"event": clustered_band(x, x, [median], records, events, cluster_by="event", n_resamples=n_boot,
                                         seed=draw),
                 "row": clustered_band(x, x, [median], None, n_resamples=n_boot, seed=draw)}
        for name, band in bands.items():
            covered[name] += band.median_low <= median <= band.median_high
    assert bands["event"].cluster_by == "event" and bands["event"].n_clusters == n_events
    assert bands["event"].n_resamples == n_boot and bands["row"].n_clusters == n_rows
    rate = {name: count / n_draws for name, count in covered.items()}

    level_b = 1.0 - 2.0 * (1.0 + 0.05 * (n_boot - 1)) / (n_boot + 1)
    z_b = stats.norm.ppf(0.5 * (1.0 + level_b))
    var_event = s_a ** 2 + (s_b ** 2 + s_c ** 2 / n_models) / n_records
    true_var = var_event / n_events
    two_stage = ((n_events - 1) / n_events * var_event
                 + (n_records - 1) / n_records ** 2 * (s_b ** 2 + s_c ** 2 / n_models)) / n_events
    rows_var = (s_a ** 2 + s_b ** 2 + s_c ** 2 - true_var) / n_rows
    expected = {"event": 2.0 * stats.t.cdf(z_b * math.sqrt(two_stage / true_var), n_events - 1) - 1.0,
                "row": 2.0 * stats.norm.cdf(z_b * math.sqrt(rows_var / true_var)) - 1.0}
    assert 0.82 < expected["event"] < 0.90 and 0.40 < expected["row"] < 0.60, expected  # the derivation's numbers
    sd = {name: math.sqrt(p * (1.0 - p) / n_draws) for name, p in expected.items()}
    for name in ("event", "row"):
        assert abs(rate[name] - expected[name]) < 3.5 * sd[name], (name, rate, expected)
    assert rate["event"] > expected["row"] + 3.5 * sd["row"], (rate, expected)
