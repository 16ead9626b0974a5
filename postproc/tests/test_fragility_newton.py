"""The maximiser of the interval-censored lognormal likelihood
(voussoir_post.earthquake.fragility.max_likelihood_intervals): damped Newton on the
analytic Hessian, with BFGS as its fallback.

Its maximum is checked against Nelder-Mead at tight tolerance on a likelihood written
here from scipy.stats.norm alone, on rows drawn here of all four kinds (exact,
bracketed, right-censored, left-censored), by Newton alone (BFGS unreachable) and by
the fallback alone; the analytic score and Hessian against central differences of the
value and of the score.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize, stats

from voussoir_post.earthquake import fragility
from voussoir_post.earthquake.fragility import fit_intervals, interval_log_likelihood


def mixed_rows(seed: int, n: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """(low, high] of n collapse intensities drawn from a lognormal: a quarter exact, a
    quarter bracketed, a quarter right-censored (low < x, inf), a quarter
    left-censored (0, high >= x)."""
    rng = np.random.default_rng(seed)
    x = np.exp(rng.normal(math.log(0.4), 0.35, n))
    kind = np.arange(n) % 4
    below, above = x * np.exp(-rng.uniform(0.02, 0.6, n)), x * np.exp(rng.uniform(0.02, 0.6, n))
    low = np.select([kind == 0, kind == 3], [x, 0.0], below)
    high = np.select([kind == 0, kind == 2], [x, math.inf], above)
    return low, high


def independent_log_likelihood(mu: float, beta: float, low: np.ndarray, high: np.ndarray) -> float:
    """The log-likelihood of the rows, from scipy.stats.norm alone: ln pdf of ln x for
    an exact row (the constant -ln x left out, as in the module), ln(Phi(z_high) -
    Phi(z_low)) for the others."""
    exact = low == high
    with np.errstate(divide="ignore"):
        ln_low, ln_high = np.log(low), np.log(high)
    value = np.sum(stats.norm.logpdf(ln_low[exact], mu, beta))
    p = stats.norm.cdf(ln_high[~exact], mu, beta) - stats.norm.cdf(ln_low[~exact], mu, beta)
    return float(value + np.sum(np.log(p)))


def nelder_mead_maximum(low: np.ndarray, high: np.ndarray) -> tuple[float, float]:
    """(mu, beta) maximising :func:`independent_log_likelihood`, by Nelder-Mead on
    (mu, ln beta) at tight tolerance from a deliberately poor start."""
    result = optimize.minimize(lambda p: -independent_log_likelihood(p[0], math.exp(p[1]), low, high),
                               [0.0, 0.0], method="Nelder-Mead",
                               options={"xatol": 1e-11, "fatol": 1e-13, "maxiter": 20000, "maxfev": 40000})
    assert result.success, result.message
    return float(result.x[0]), math.exp(result.x[1])


@pytest.mark.parametrize("seed", [11, 12, 13, 14, 15, 16])
@pytest.mark.parametrize("tol", [1e-12, 1e-9])
def test_newton_alone_reaches_the_maximum_of_mixed_rows(seed, tol, monkeypatch):
    low, high = mixed_rows(seed)
    mu_ref, beta_ref = nelder_mead_maximum(low, high)

    def no_bfgs(*args, **kwargs):
        raise AssertionError("Newton failed and fell back to BFGS")

    monkeypatch.setattr(fragility.optimize, "minimize", no_bfgs)
    fit = fit_intervals(low, high, tol=tol)
    assert math.log(fit.median) == pytest.approx(mu_ref, abs=1e-6)
    assert fit.beta == pytest.approx(beta_ref, abs=1e-6)
    assert fit.log_likelihood == pytest.approx(independent_log_likelihood(mu_ref, beta_ref, low, high), abs=1e-9)
    # The check has teeth: a midpoint summary of the rows is far from the maximum.
    with np.errstate(divide="ignore"):
        point = np.where(np.isfinite(high) & (low > 0.0), np.sqrt(low * high), np.where(low > 0.0, low, high))
    assert abs(np.mean(np.log(point)) - mu_ref) > 1e-3 or abs(np.std(np.log(point)) - beta_ref) > 1e-3


@pytest.mark.parametrize("seed", [17, 18])
def test_the_bfgs_fallback_reaches_the_same_maximum(seed, monkeypatch):
    """Newton made to fail everywhere: BFGS's answer stands, still the maximum."""
    low, high = mixed_rows(seed)
    mu_ref, beta_ref = nelder_mead_maximum(low, high)
    monkeypatch.setattr(fragility, "_newton", lambda p, rows, tol: None)
    fit = fit_intervals(low, high, tol=1e-9)
    assert math.log(fit.median) == pytest.approx(mu_ref, abs=1e-6)
    assert fit.beta == pytest.approx(beta_ref, abs=1e-6)


@pytest.mark.parametrize("seed", [21, 22, 23])
@pytest.mark.parametrize("mu_beta", [(math.log(0.4), 0.35), (math.log(0.25), 0.2), (math.log(0.7), 0.8)])
def test_analytic_score_and_hessian_match_central_differences(seed, mu_beta):
    """At points on and off the maximum, in (mu, s = ln beta): the score against central
    differences of interval_log_likelihood, the Hessian against central differences of
    the score."""
    low, high = mixed_rows(seed)
    with np.errstate(divide="ignore"):
        ln_low, ln_high = np.log(low), np.log(high)
    exact = ln_low == ln_high
    rows = (ln_low[exact], ln_low[~exact], ln_high[~exact])

    def value(p):
        return interval_log_likelihood(p[0], math.exp(p[1]), ln_low, ln_high)

    def score(p):
        return fragility._derivatives(p[0], math.exp(p[1]), *rows)[1]

    p = np.array([mu_beta[0], math.log(mu_beta[1])])
    ll, g, hess = fragility._derivatives(p[0], math.exp(p[1]), *rows)
    # rel 1e-9: scipy's difference of two cdfs loses digits in a tail
    assert ll == pytest.approx(independent_log_likelihood(p[0], math.exp(p[1]), low, high), rel=1e-9)
    h = 1e-6
    g_fd = np.array([(value(p + e) - value(p - e)) / (2 * h) for e in np.eye(2) * h])
    hess_fd = np.column_stack([(score(p + e) - score(p - e)) / (2 * h) for e in np.eye(2) * h])
    scale = np.max(np.abs(hess))
    assert np.max(np.abs(g - g_fd)) < 1e-6 * scale
    assert np.max(np.abs(hess - hess_fd)) < 1e-6 * scale
    assert hess[0, 1] == hess[1, 0]
