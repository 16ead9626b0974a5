"""Baker's binomial fit of MSA stripes (voussoir_post.earthquake.stripes_fit): a known
lognormal recovered from synthetic stripes over many seeds (the rate at which the
asymptotic 90 % interval, from the Fisher information at the true values, holds the
estimate), the closed form of two stripes, the refusals, and the MSA reader."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import norm

from voussoir_post.cli.post import main
from voussoir_post.earthquake.fragility import FitError
from voussoir_post.earthquake.msa import is_msa, read_msa
from voussoir_post.earthquake.stripes_fit import binomial_log_likelihood, fit_runs, fit_stripes, stripes_band
from voussoir_post.errors import ResultsError

THETA_G, BETA = 0.4, 0.4
LEVELS_G = np.array([0.15, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0])
RUNS = np.full(LEVELS_G.size, 20)


def fisher_sd() -> tuple[float, float]:
    """Asymptotic standard deviations of (ln median, beta) for the stripes above:
    the inverse of the binomial Fisher information sum_j n_j phi^2 / (Phi (1 - Phi))
    g g^T at the true values, g = du/d(mu, beta) = (-1/beta, -u/beta)."""
    u = np.log(LEVELS_G / THETA_G) / BETA
    w = RUNS * norm.pdf(u) ** 2 / (norm.cdf(u) * norm.sf(u))
    g = np.stack([-np.ones_like(u) / BETA, -u / BETA])
    cov = np.linalg.inv((g * w) @ g.T)
    return math.sqrt(cov[0, 0]), math.sqrt(cov[1, 1])


def test_a_known_lognormal_is_recovered_over_many_seeds():
    sd_mu, sd_beta = fisher_sd()
    p_true = norm.cdf(np.log(LEVELS_G / THETA_G) / BETA)
    ln_medians, betas = [], []
    n_seeds = 600
    for seed in range(n_seeds):
        collapsed = np.random.default_rng(seed).binomial(RUNS, p_true)
        fit = fit_stripes(LEVELS_G, RUNS, collapsed)
        ln_medians.append(math.log(fit.median))
        betas.append(fit.beta)
    ln_medians, betas = np.array(ln_medians), np.array(betas)
    # 90 % asymptotic intervals: the rate over 600 seeds has a sampling sd of 0.012, and
    # 160 runs leave a small finite-sample shortfall; 0.85 to 0.95 holds both.
    rate_mu = np.mean(np.abs(ln_medians - math.log(THETA_G)) <= 1.645 * sd_mu)
    rate_beta = np.mean(np.abs(betas - BETA) <= 1.645 * sd_beta)
    assert 0.85 <= rate_mu <= 0.95, rate_mu
    assert 0.85 <= rate_beta <= 0.95, rate_beta
    # no bias in ln median beyond 4.5 standard errors of the mean (sd_mu / sqrt(600))
    assert abs(ln_medians.mean() - math.log(THETA_G)) <= 4.5 * sd_mu / math.sqrt(n_seeds)


@pytest.mark.parametrize("x, n, z", [((0.2, 0.5), (10, 10), (3, 7)), ((0.1, 0.3), (8, 12), (1, 11)),
                                     ((0.3, 0.35), (40, 40), (18, 21))])
def test_two_stripes_closed_form(x, n, z):
    # With two stripes the two parameters can match both fractions f_j = z_j / n_j (each
    # binomial's own maximum): ln x_j = ln median + beta Phi^-1(f_j), so
    # beta = ln(x2 / x1) / (Phi^-1(f2) - Phi^-1(f1)), median = x1 exp(-beta Phi^-1(f1)).
    q1, q2 = norm.ppf(z[0] / n[0]), norm.ppf(z[1] / n[1])
    beta = math.log(x[1] / x[0]) / (q2 - q1)
    median = x[0] * math.exp(-beta * q1)
    fit = fit_stripes(x, n, z)
    assert fit.median == pytest.approx(median, rel=1e-6)
    assert fit.beta == pytest.approx(beta, rel=1e-6)
    # Baker's likelihood, the binomial coefficients included, at the fractions themselves
    expected = sum(math.log(math.comb(nj, zj)) + zj * math.log(zj / nj) + (nj - zj) * math.log(1 - zj / nj)
                   for nj, zj in zip(n, z))
    assert fit.log_likelihood == pytest.approx(expected, rel=1e-9)
    assert binomial_log_likelihood(math.log(median), beta, x, n, z) == pytest.approx(expected, rel=1e-9)


def test_single_runs_are_their_stripes():
    levels = [0.5, 0.2, 0.5, 0.2, 0.2, 0.5]
    collapsed = [True, False, False, True, False, True]
    a = fit_runs(levels, collapsed)
    b = fit_stripes([0.2, 0.5], [3, 3], [1, 2])
    assert (a.median, a.beta) == pytest.approx((b.median, b.beta), rel=1e-9)


@pytest.mark.parametrize("z, words", [
    ((0, 0, 0), "no run collapsed at any of the 3 levels (up to 0.5 g)"),
    ((5, 5, 5), "every run collapsed, at each of the 3 levels (from 0.2 g)"),
    ((0, 2, 5), "the stripes are separated: every run stood at or below 0.3 g and every one collapsed at or "
                "above 0.3 g"),
    ((0, 0, 5), "every run stood at or below 0.3 g and every one collapsed at or above 0.5 g"),
])
def test_stripes_without_a_fragility_are_refused(z, words):
    with pytest.raises(FitError, match=words.replace("(", r"\(").replace(")", r"\)")):
        fit_stripes([0.2, 0.3, 0.5], [5, 5, 5], z)


def test_a_fraction_falling_with_the_level_is_refused():
    with pytest.raises(FitError, match="the fraction collapsed does not grow with the level"):
        fit_stripes([0.2, 0.3, 0.5], [10, 10, 10], [8, 5, 2])


def test_the_band_draws_records_and_holds_the_fit():
    rng = np.random.default_rng(4)
    records = np.repeat([f"r{k}" for k in range(10)], LEVELS_G.size)
    levels = np.tile(LEVELS_G, 10)
    collapsed = rng.random(levels.size) < norm.cdf(np.log(levels / THETA_G) / BETA)
    fit = fit_runs(levels, collapsed)
    band = stripes_band(levels, collapsed, np.linspace(0.01, 1.2, 60), records, None, "record", n_resamples=80)
    assert band.cluster_by == "record" and band.n_clusters == 10 and band.n_resamples + band.n_unfitted == 80
    assert band.median_low <= fit.median <= band.median_high


def write_csv(path, rows):
    path.write_text("record,param_set,level_g,scale,collapsed,failed,event\n" + "".join(rows))


def test_the_reader_refuses_a_bad_flag(tmp_path):
    write_csv(tmp_path / "bad.csv", ["a.csv,0,0.2,1.5,2,0,\n"])
    assert is_msa(tmp_path / "bad.csv")
    with pytest.raises(ResultsError, match=r"line 2, column collapsed: '2' is not 0 or 1"):
        read_msa(tmp_path / "bad.csv")


def test_compare_refuses_an_msa_file(tmp_path, capsys):
    write_csv(tmp_path / "a.csv", ["a.csv,0,0.2,1.5,0,0,\n"])
    assert main(["fragility", str(tmp_path / "a.csv"), "--compare", str(tmp_path / "a.csv")]) == 2
    assert "an MSA file (&sweep mode = 'msa') is fitted alone" in capsys.readouterr().err
